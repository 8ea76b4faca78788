//! The route under rigid-body dynamics (`[solver] dynamics = "rigid-body"`, issue #7;
//! `derivations/08-rigid-body.md`).
//!
//! State y = (X, Z, θ, Ẋ, Ż, θ̇, W_h, W_f): the three degrees of freedom, their rates, and the
//! work done so far by the hydraulic force and couple (W_h) and by friction (W_f), integrated
//! with the motion by classic RK4 so that the energy balance can be checked to the
//! integrator's order. Constraint drift stays at round-off by construction: the pose is
//! recomputed from (X, Z, θ) by the tracker at every evaluation and the six-component twist is
//! the projection of (Ẋ, Ż, θ̇) onto the constraints (`mechanics::rigid_body::twist`).
//!
//! Stick and slip at the block level: at rest (the start, or when the motion stops), the block
//! stays put when static friction within the three cones can hold it
//! (`mechanics::static_friction`); otherwise it slips from rest in the direction that
//! reproduces itself. While sliding, each step is checked for events — a stop (the twist
//! reverses), a pivot (a contact's slip reverses), a release (a sticking contact's cone no
//! longer holds it) or a failure (a state off the model) — found by bisection on the step
//! length, and taken in shorter substeps where the energy balance says RK4 does not resolve the
//! motion (`derivations/08-rigid-body.md` §3). At a stop the velocity is set to exactly zero.
//! A sticking contact is held where it stuck (`hold`), its slip projected out as an impulse
//! would (`accept` books the energy that takes as friction work), so that it stays on its plane
//! whatever dt (issue #12).

use super::dynamics::{Dynamics, Flow, Start};
use super::outcome::{EnergyBalance, Outcome};
use super::pose_finder::PoseFinder;
use super::rhs::{Stop, pose_at};
use super::state::Row;
use super::termination::Reason;
use crate::geometry::{Displacement, Pose};
use crate::mechanics::ContactGeometry;
use crate::mechanics::loads::Applied;
use crate::mechanics::rigid_body::{self, Motion, RigidError};
use crate::mechanics::static_friction::{self, StaticCheck};
use crate::scene::{Scene, Simulation};
use nalgebra::Vector3;

type Y = [f64; 8];

/// One evaluation of the rigid-body right-hand side.
#[derive(Debug, Clone, Copy)]
struct Eval {
    pose: Pose,
    motion: Motion,
    /// The rates the motion was evaluated with (those of the state, with a sticking contact's
    /// slip projected out).
    rates: [f64; 3],
    /// The kinetic energy that projection removed (J, ≤ 0): friction work, booked when the
    /// state is taken (`accept`).
    removed: f64,
}

/// The state `y` as the route takes it at evaluation `e`: its rates those the motion was
/// evaluated with, and the kinetic energy their projection removed booked as friction work.
fn accept(y: &Y, e: &Eval) -> Y {
    let mut z = with_rates(y, e.rates);
    z[7] += e.removed;
    z
}

fn displacement(y: &Y) -> Displacement {
    Displacement::new(y[0], y[1], y[2])
}

fn stop_of(e: RigidError) -> Stop {
    let reason = match e {
        RigidError::LiftOff { .. } => Reason::ContactLiftedOff,
        RigidError::Singular(_)
        | RigidError::SlipFromRest
        | RigidError::SlipStart { .. }
        | RigidError::StickSingular { .. } => Reason::ContactForcesUndetermined,
    };
    Stop {
        reason,
        detail: e.to_string(),
    }
}

/// The right-hand side at state `y`. `stuck`: the contact that stuck at the start of the step;
/// the integrator's drift of its slip is projected out (as an impulse would, the energy it
/// takes in `Eval::removed`) so that it stays stuck while its cone allows.
fn evaluate(
    scene: &Scene,
    dynamics: &Simulation,
    finder: &mut PoseFinder<'_>,
    y: &Y,
    stuck: Option<usize>,
) -> Result<Eval, Stop> {
    let pose = pose_at(scene, finder, displacement(y))?;
    let geom = ContactGeometry::with_normals(dynamics.normals(), &pose);
    let applied = Applied::new(dynamics.loads(), dynamics.block(), &geom.frame);
    let mut rates = [y[3], y[4], y[5]];
    let mut removed = 0.0;
    if let Some(i) = stuck {
        // Always: a contact that stuck at the start of the step can only start to slip by its
        // cone no longer holding it (the release, which `accelerations` sees after this
        // projection), never by the integrator's drift, however long the step.
        (rates, removed) =
            rigid_body::pivot_rates(&geom, dynamics.block(), rates, i).map_err(stop_of)?;
    }
    let motion = rigid_body::accelerations_slaved(
        &geom,
        &applied,
        dynamics.block(),
        dynamics.friction(),
        rates,
        dynamics.solver().dt,
    )
    .map_err(stop_of)?;
    Ok(Eval {
        pose,
        motion,
        rates,
        removed,
    })
}

/// Puts the sticking contact `i` back on the point `at` where it stuck (issue #12). The
/// integrator keeps its velocity at zero only to its order, so without this its position
/// creeps by a little every step and a contact that sticks on a strike line (where contacts 1
/// and 2 start) drifts off its plane's region after a time that depends on dt. The correction
/// is the least change of (X, Z, L θ) that returns the contact's horizontal position to `at`
/// (Gauss–Newton with the contact's velocity map as the Jacobian; the contact stays on its
/// plane through the pose), a move of the size of the integrator's error.
fn hold(
    scene: &Scene,
    dynamics: &Simulation,
    finder: &mut PoseFinder<'_>,
    y: &Y,
    ev: Eval,
    i: usize,
    at: Vector3<f64>,
) -> Result<(Y, Eval), Stop> {
    let l = scene.l();
    let (mut y, mut ev) = (*y, ev);
    for _ in 0..4 {
        let p = ev.pose.vertices[i];
        let r = [at.x - p.x, at.z - p.z];
        if r[0].hypot(r[1]) <= 1e-14 * l || ev.motion.stuck != Some(i) {
            break;
        }
        let geom = ContactGeometry::with_normals(dynamics.normals(), &ev.pose);
        // The contact's horizontal velocity for unit (Ẋ, Ż, L θ̇): rows X and Z.
        let v = rigid_body::contact_velocity_map(&geom, l, i).map_err(stop_of)?;
        let j = [v.map(|c| c.x), v.map(|c| c.z)];
        let dot = |a: &[f64; 3], b: &[f64; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
        let (a, b, d) = (dot(&j[0], &j[0]), dot(&j[0], &j[1]), dot(&j[1], &j[1]));
        let det = a * d - b * b;
        if det.abs() <= 1e-12 * a.max(d).powi(2) || !det.is_finite() {
            break;
        }
        let m = [(d * r[0] - b * r[1]) / det, (a * r[1] - b * r[0]) / det];
        let delta: [f64; 3] = std::array::from_fn(|c| j[0][c] * m[0] + j[1][c] * m[1]);
        y[0] += delta[0];
        y[1] += delta[1];
        y[2] += delta[2] / l;
        ev = evaluate(scene, dynamics, finder, &y, Some(i))?;
        y = accept(&y, &ev);
    }
    Ok((y, ev))
}

/// The fraction of the largest kinetic energy of the route below which the block counts as at
/// rest when a contact's slip passes through zero (see the event handling in `slide`).
const REST: f64 = 1e-9;

/// A substep is halved when the energy balance W_h + W_f − ΔK − ΔU moves over it by more than
/// this fraction of the route's energy scale (the largest of its kinetic energy and of the
/// works so far), prorated to the substep. Where the motion is resolved RK4 moves it by about
/// 1e-18 a step; it is exceeded where friction makes the motion stiff — near a stop the friction
/// moments damp the rotation at a rate ∝ μ N r² / (I |v|) — or a slip swings round near zero.
const ENERGY_TOLERANCE: f64 = 1e-9;

/// The most events (stops that restart, pivots) resolved within one increment.
const MAX_EVENTS: usize = 16;

/// The shortest substep, as a fraction of dt (then the step is taken as it is).
const MIN_SUBSTEP: f64 = 1e-3;

fn derivative(y: &Y, m: &Motion) -> Y {
    [
        y[3],
        y[4],
        y[5],
        m.acc[0],
        m.acc[1],
        m.acc[2],
        m.power_hydraulic,
        m.power_friction,
    ]
}

/// `y` with its rates replaced.
fn with_rates(y: &Y, rates: [f64; 3]) -> Y {
    let mut z = *y;
    z[3..6].copy_from_slice(&rates);
    z
}

/// The motion at the start of a step, against which the events of the step are recognised:
/// a stop — a later twist t has reversed, ⟨t, before⟩ ≤ 0 in the kinetic-energy inner
/// product —, a release — the contact that stuck no longer does — or a pivot — the slip of a
/// slipping contact no longer runs the way its friction at the start opposed, i.e. it passed
/// through zero.
#[derive(Clone, Copy)]
struct Heading<'a> {
    before: &'a Motion,
    mass: f64,
}

/// What happened within a step.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Event {
    /// The whole motion reversed: the block stopped.
    Stop,
    /// The slip of this contact passed through zero while the block moved on.
    Pivot(usize),
    /// The contact that stuck at the start of the step can no longer be held by its friction
    /// cone: it starts to slip.
    Release(usize),
}

impl Heading<'_> {
    fn event(&self, m: &Motion) -> Option<Event> {
        let b = self.before;
        if b.twist.is_zero() {
            return None;
        }
        if m.twist.energy_dot(&b.twist, self.mass, &b.inertia) <= 0.0 {
            return Some(Event::Stop);
        }
        if let Some(i) = b.stuck.filter(|&i| m.stuck != Some(i)) {
            return Some(Event::Release(i));
        }
        // The slip's direction at the step's start is the one its friction opposes (for a slip
        // just started, the direction it starts in, which its velocity, still of round-off's
        // size, does not yet show).
        (0..3)
            .filter(|&i| b.stuck != Some(i) && b.shear[i].norm() > 0.0)
            .find(|&i| m.slip[i].dot(&b.shear[i]) >= 0.0)
            .map(Event::Pivot)
    }
}

/// One classic RK4 step of length h from y, whose derivative k1 is known; stages evaluated on
/// clones of `finder`. Also says whether a stage met an event of `heading`: then the step
/// passed through a stop or a pivot, where Coulomb friction jumps and the step's result means
/// nothing (its later stages push on with friction turned round).
fn rk4(
    scene: &Scene,
    dynamics: &Simulation,
    finder: &PoseFinder<'_>,
    y: &Y,
    k1: &Y,
    h: f64,
    heading: &Heading<'_>,
) -> Result<(Y, Option<Event>), Stop> {
    let mut crossed = None;
    let stuck = heading.before.stuck;
    let mut stage = |y: &Y| {
        let mut f = finder.for_stages();
        evaluate(scene, dynamics, &mut f, y, stuck).map(|e| {
            crossed = crossed.or(heading.event(&e.motion));
            derivative(&with_rates(y, e.rates), &e.motion)
        })
    };
    let next = super::integrator::rk4(y, k1, h, &mut stage)?;
    Ok((next, crossed))
}

fn row(t: f64, y: &Y, e: &Eval) -> Row {
    Row {
        t_s: t,
        x_m: y[0],
        y_m: e.pose.cm.y,
        z_m: y[1],
        theta_deg: y[2].to_degrees(),
        alpha_deg: e.pose.alpha.to_degrees(),
        beta_deg: e.pose.beta.to_degrees(),
        gamma_deg: e.pose.gamma.to_degrees(),
        vx_m_s: y[3],
        vz_m_s: y[4],
        omega_deg_s: y[5].to_degrees(),
        n_n: Some(e.motion.normal),
        s_n: Some(e.motion.shear.map(|s| s.norm())),
    }
}

/// A row at rest (velocities zero; reactions not computed: static friction is indeterminate).
fn rest_row(t: f64, y: &Y, pose: &Pose) -> Row {
    Row {
        t_s: t,
        x_m: y[0],
        y_m: pose.cm.y,
        z_m: y[1],
        theta_deg: y[2].to_degrees(),
        alpha_deg: pose.alpha.to_degrees(),
        beta_deg: pose.beta.to_degrees(),
        gamma_deg: pose.gamma.to_degrees(),
        vx_m_s: 0.0,
        vz_m_s: 0.0,
        omega_deg_s: 0.0,
        n_n: None,
        s_n: None,
    }
}

/// The static check at a pose.
fn static_check(dynamics: &Simulation, geom: &ContactGeometry) -> Result<StaticCheck, Stop> {
    let applied = Applied::new(dynamics.loads(), dynamics.block(), &geom.frame);
    static_friction::at_rest(geom, &applied, dynamics.friction()).map_err(|err| Stop {
        reason: Reason::ContactForcesUndetermined,
        detail: err.to_string(),
    })
}

/// Substep control: whether a substep of length `len` (of an increment `dt`) moved the energy
/// balance's residual from `before` to `after` by more than the tolerance — a fraction
/// `ENERGY_TOLERANCE` of the route's energy `scale`, prorated to the substep, and never below
/// the balance's own round-off — and may still be halved (it is longer than `MIN_SUBSTEP`·dt).
fn unresolved_substep(
    (before, after): (f64, f64),
    scale: f64,
    (len, dt): (f64, f64),
    round_off: f64,
) -> bool {
    (after - before).abs() > (ENERGY_TOLERANCE * scale * (len / dt)).max(round_off)
        && len > MIN_SUBSTEP * dt
}

/// Where within a step an event lies: the longest step length `lo` known not to reach it (its
/// state `y_lo`), the shortest `hi` known to (its state `y_hi`), and the event, if one was seen.
struct Bracket {
    lo: f64,
    hi: f64,
    y_lo: Y,
    y_hi: Y,
    found: Option<Event>,
}

/// Event location: bisection on the length of the step from `y` (derivative `k1`) between 0
/// and `h` (whose end state is `end`), down to 1e-12·dt, for the longest step that neither
/// meets an event of `heading` (at its end or at one of its stages) nor fails.
fn bracket_event(
    scene: &Scene,
    sections: &Simulation,
    finder: &PoseFinder<'_>,
    (y, k1): (&Y, &Y),
    (h, end): (f64, Y),
    heading: &Heading<'_>,
) -> Bracket {
    let stuck = heading.before.stuck;
    let reaches = |len: f64| -> Result<(Option<Event>, Y), Stop> {
        let (yh, crossed) = rk4(scene, sections, finder, y, k1, len, heading)?;
        let mut f = finder.clone();
        let e = evaluate(scene, sections, &mut f, &yh, stuck)?;
        Ok((heading.event(&e.motion).or(crossed), yh))
    };
    let mut b = Bracket {
        lo: 0.0,
        hi: h,
        y_lo: *y,
        y_hi: end,
        found: None,
    };
    for _ in 0..60 {
        if b.hi - b.lo <= 1e-12 * sections.solver().dt {
            break;
        }
        let mid = 0.5 * (b.lo + b.hi);
        match reaches(mid) {
            Ok((None, ym)) => {
                b.lo = mid;
                b.y_lo = ym;
            }
            Ok((event, ym)) => {
                b.hi = mid;
                b.y_hi = ym;
                b.found = event;
            }
            Err(_) => b.hi = mid,
        }
    }
    b
}

/// What a stop comes to (see [`come_to_rest`]).
enum Rest {
    /// Not held: the block slips again from rest, from this evaluation.
    Slips(Box<Eval>),
    /// The route ends: held where it stopped, or the slip from rest cannot be had.
    Ended(Reason, f64, String),
    /// The state at rest is off the model (as a failed step).
    Failed(Stop),
}

/// Where the motion stops, at `t_event`: the block at rest at `stopped` (the state just before
/// the stop, its rates zeroed; `from` the evaluation the step started from). Held there by
/// static friction, the route ends "stopped"; not held, it slips again from rest. The travel
/// to the rest point, the increment, the rest row and the energy balance go into `o`.
fn come_to_rest(
    (scene, sections, finder): (&Scene, &Simulation, &mut PoseFinder<'_>),
    (stopped, from): (&Y, &Eval),
    (k, t, t_event): (usize, f64, f64),
    origin: (f64, f64),
    o: &mut Outcome<'_>,
) -> Rest {
    let (mass, g) = (sections.block().mass, sections.loads().gravity);
    let stop_pose = match pose_at(scene, finder, displacement(stopped)) {
        Ok(p) => p,
        Err(e) => return Rest::Failed(e),
    };
    o.travel += (stop_pose.cm - from.pose.cm).norm();
    o.increments = k;
    let geom = ContactGeometry::with_normals(sections.normals(), &stop_pose);
    let check = match static_check(sections, &geom) {
        Ok(c) => c,
        Err(Stop { reason, detail }) => return Rest::Ended(reason, t, detail),
    };
    if check.holds() {
        o.push(rest_row(t_event, stopped, &stop_pose));
        o.energy = Some(energy(stopped, 0.0, stop_pose.cm.y, origin, mass, g));
        return Rest::Ended(
            Reason::Stopped,
            t_event,
            format!(
                "the motion stopped at t = {t_event:.6} s and static friction holds the block \
                 there (factor of safety {})",
                check.factor_of_safety()
            ),
        );
    }
    match evaluate(scene, sections, finder, stopped, None) {
        Ok(e) => Rest::Slips(Box::new(e)),
        Err(Stop { reason, detail }) => {
            o.energy = Some(energy(stopped, 0.0, stop_pose.cm.y, origin, mass, g));
            Rest::Ended(reason, t_event, detail)
        }
    }
}

/// The energy balance at a state with kinetic energy `kinetic` and CM height `cm_y`, from the
/// start's kinetic energy and CM height `(k0, y0)`.
fn energy(
    y: &Y,
    kinetic: f64,
    cm_y: f64,
    (k0, y0): (f64, f64),
    mass: f64,
    g: f64,
) -> EnergyBalance {
    let potential = mass * g * (cm_y - y0);
    EnergyBalance {
        work_hydraulic_j: y[6],
        work_friction_j: y[7],
        kinetic_j: kinetic,
        kinetic_initial_j: k0,
        potential_change_j: potential,
        residual_j: y[6] + y[7] - (kinetic - k0) - potential,
    }
}

/// The sticking contact and the point where it stuck (see [`hold`]), after evaluation `ev`.
fn anchor_of(ev: &Eval, anchor: Option<(usize, Vector3<f64>)>) -> Option<(usize, Vector3<f64>)> {
    match ev.motion.stuck {
        Some(i) if anchor.is_some_and(|a| a.0 == i) => anchor,
        Some(i) => Some((i, ev.pose.vertices[i])),
        None => None,
    }
}

/// The rigid body under way: the state y, the evaluation at it, the substep and what the
/// energy balance and the stick hold need. A [`Dynamics`] the driver (`driver.rs`) runs.
pub(super) struct RigidBody<'a> {
    scene: &'a Scene,
    sections: &'a Simulation,
    y: Y,
    t: f64,
    ev: Eval,
    /// The sticking contact and where it stuck.
    anchor: Option<(usize, Vector3<f64>)>,
    /// The largest kinetic energy so far (the energy balance's scale).
    ke_max: f64,
    /// The substep: dt, halved where the energy balance says RK4 does not resolve the motion
    /// (see `MIN_SUBSTEP`), grown back by doubling.
    h: f64,
    /// The reference of the energy balance: the start's kinetic energy and CM height.
    origin: (f64, f64),
    /// The balance's own round-off: its potential energy m g ΔY carries that of a height of the
    /// size of L. No substep can resolve it below that; near the start from rest, where the
    /// energies are tiny, the tolerance alone asked for it, and every increment was halved down
    /// to the shortest substep (36 000 halvings in the first 0.2 ms at dt = 10 µs).
    round_off: f64,
}

impl RigidBody<'_> {
    fn balance(&self, y: &Y, e: &Eval) -> EnergyBalance {
        let (mass, g) = (self.sections.block().mass, self.sections.loads().gravity);
        energy(
            y,
            e.motion.twist.kinetic_energy(mass, &e.motion.inertia),
            e.pose.cm.y,
            self.origin,
            mass,
            g,
        )
    }
}

impl<'a> Dynamics<'a> for RigidBody<'a> {
    fn start<'s>(
        scene: &'a Scene,
        sections: &'a Simulation,
        finder: &mut PoseFinder<'_>,
        mut o: Outcome<'s>,
    ) -> Start<'s, Self> {
        let mass = sections.block().mass;
        let init = scene.initial;
        let y: Y = [0.0, 0.0, 0.0, init.vx, init.vz, init.omega, 0.0, 0.0];
        // The start: at rest, held or not by static friction (decided before any acceleration
        // is sought: a held block has no consistent way to slip); or moving as `[initial]`
        // says, when it goes on until it stops (the factor of safety is reported all the same).
        let Some(start_pose) = finder.pose() else {
            return Start::Ended(o.end(
                Reason::NoAdmissibleRoot,
                0.0,
                "the flat start pose has no root to follow".into(),
            ));
        };
        let check = match static_check(sections, &ContactGeometry::new(scene, &start_pose)) {
            Ok(c) => c,
            Err(Stop { reason, detail }) => {
                o.push(rest_row(0.0, &y, &start_pose));
                return Start::Ended(o.end(reason, 0.0, detail));
            }
        };
        o.fs = Some(check.factor_of_safety());
        if init.at_rest() && check.holds() {
            o.push(rest_row(0.0, &y, &start_pose));
            let mut done = o.end(
                Reason::DoesNotSlide,
                0.0,
                format!(
                    "static friction within the three cones holds the block: factor of safety {}",
                    check.factor_of_safety()
                ),
            );
            done.energy = Some(EnergyBalance::default());
            return Start::Ended(done);
        }
        let ev = match evaluate(scene, sections, finder, &y, None) {
            Ok(e) => e,
            Err(Stop { reason, detail }) => {
                o.push(rest_row(0.0, &y, &start_pose));
                return Start::Ended(o.end(reason, 0.0, detail));
            }
        };
        o.push(row(0.0, &y, &ev));
        let origin = (
            ev.motion.twist.kinetic_energy(mass, &ev.motion.inertia),
            start_pose.cm.y,
        );
        let anchor = anchor_of(&ev, None);
        Start::Moving(
            RigidBody {
                scene,
                sections,
                y,
                t: 0.0,
                ev,
                anchor,
                ke_max: 0.0,
                h: sections.solver().dt,
                origin,
                round_off: 64.0 * f64::EPSILON * mass * sections.loads().gravity * scene.l(),
            },
            o,
        )
    }

    fn advance<'s>(
        &mut self,
        finder: &mut PoseFinder<'_>,
        k: usize,
        t_to: f64,
        o: Outcome<'s>,
    ) -> Flow<'s> {
        self.substeps(finder, k, t_to, o)
    }

    fn row(&self) -> Row {
        row(self.t, &self.y, &self.ev)
    }

    fn close(&self, o: &mut Outcome<'_>) {
        o.energy = Some(self.balance(&self.y, &self.ev));
    }
}

impl RigidBody<'_> {
    /// Increment `k` to `t_target` in substeps: each step checked for events — a stop, a
    /// pivot, a release, a failure — found by bisection on the step length, and halved where
    /// the energy balance says RK4 does not resolve the motion.
    fn substeps<'s>(
        &mut self,
        finder: &mut PoseFinder<'_>,
        k: usize,
        t_target: f64,
        mut o: Outcome<'s>,
    ) -> Flow<'s> {
        let (scene, sections) = (self.scene, self.sections);
        let dt = sections.solver().dt;
        let (mass, g) = (sections.block().mass, sections.loads().gravity);
        let (start, round_off) = (self.origin, self.round_off);
        let (mut y, mut t, mut ev) = (self.y, self.t, self.ev);
        let (mut anchor, mut ke_max, mut h) = (self.anchor, self.ke_max, self.h);
        let balance = |y: &Y, e: &Eval| {
            energy(
                y,
                e.motion.twist.kinetic_energy(mass, &e.motion.inertia),
                e.pose.cm.y,
                start,
                mass,
                g,
            )
        };
        // Substeps until the increment's end; events (a stop, a pivot) cut them.
        let mut events = 0usize;
        while t < t_target * (1.0 - 1e-15) {
            // Past MAX_EVENTS in one increment (a contact's slip chattering about zero), the
            // rest of the increment is taken in plain substeps: its error shows in the energy
            // balance.
            let resolve = events < MAX_EVENTS;
            let h_try = h.min(t_target - t);
            let k1 = derivative(&y, &ev.motion);
            ke_max = ke_max.max(ev.motion.twist.kinetic_energy(mass, &ev.motion.inertia));
            let heading = Heading {
                before: &ev.motion,
                mass,
            };
            let stuck = ev.motion.stuck;
            let fail = |o: Outcome<'s>, y: &Y, ev: &Eval, s: Stop| -> Outcome<'s> {
                let mut o = o;
                o.energy = Some(balance(y, ev));
                o.finish(row(t, y, ev), s.reason, t, s.detail)
            };
            // The step, and the state at its end. Where either fails (a stage or the end
            // state off the model: a contact lifting off, leaving its plane's region, …) the
            // failure is located like an event, by bisection, so that an event before it (a
            // pivot that would keep the contact on its plane) is handled first and a route that
            // ends does so at the moment it must, not at the next increment's end.
            let mut at_next = finder.clone();
            let step = rk4(scene, sections, finder, &y, &k1, h_try, &heading).and_then(|(n, c)| {
                let e = evaluate(scene, sections, &mut at_next, &n, stuck)?;
                Ok((n, c.filter(|_| resolve), e))
            });
            let (next, crossed, next_ev, failed) = match step {
                Ok((n, c, e)) => (accept(&n, &e), c, e, None),
                Err(stop) => (y, None, ev, Some(stop)),
            };
            // Whether a substep of length `len` from y to (y2, e2) moved the energy balance by
            // more than the tolerance (and may still be halved).
            let residual = balance(&y, &ev).residual_j;
            let unresolved = |len: f64, y2: &Y, e2: &Eval| {
                resolve
                    && unresolved_substep(
                        (residual, balance(y2, e2).residual_j),
                        ke_max.max(y[6].abs()).max(y[7].abs()).max(y2[6].abs()),
                        (len, dt),
                        round_off,
                    )
            };
            // A failure over a long substep may be the integrator's (a slip too young to be
            // watched for reversal, turned round within the step): retry in shorter substeps
            // down to the shortest, and only there locate it.
            if failed.is_some() && h_try > 2.0 * MIN_SUBSTEP * dt {
                h = 0.5 * h_try;
                continue;
            }
            let at_end = match failed {
                None => heading.event(&next_ev.motion).filter(|_| resolve),
                Some(_) => None,
            };
            if crossed.is_none() && at_end.is_none() && failed.is_none() {
                // No event: accept unless the energy balance moved by more than the tolerance
                // (then halve the substep and try again).
                if unresolved(h_try, &next, &next_ev) {
                    h = 0.5 * h_try;
                    continue;
                }
                *finder = at_next;
                let (next, next_ev) = match anchor {
                    Some((i, at)) if next_ev.motion.stuck == Some(i) => {
                        match hold(scene, sections, finder, &next, next_ev, i, at) {
                            Ok(held) => held,
                            Err(e) => return Flow::Ended(fail(o, &y, &ev, e)),
                        }
                    }
                    _ => (next, next_ev),
                };
                o.travel += (next_ev.pose.cm - ev.pose.cm).norm();
                y = next;
                ev = next_ev;
                anchor = anchor_of(&ev, anchor);
                t += h_try;
                if h_try >= h {
                    h = (2.0 * h).min(dt);
                }
                continue;
            }
            // An event inside the substep (at its end or at one of its stages): bisection on
            // the step length for the longest step that does not reach it, then the event's
            // own handling.
            let Bracket {
                lo,
                hi,
                y_lo,
                y_hi,
                found,
            } = bracket_event(scene, sections, finder, (&y, &k1), (h_try, next), &heading);
            if let (Some(stop), None) = (&failed, found) {
                // No event before the failure: the route ends where it fails, after the last
                // state that stands.
                if lo > 0.0 {
                    match evaluate(scene, sections, finder, &y_lo, stuck) {
                        Ok(e) => {
                            o.travel += (e.pose.cm - ev.pose.cm).norm();
                            y = accept(&y_lo, &e);
                            ev = e;
                        }
                        Err(e) => return Flow::Ended(fail(o, &y, &ev, e)),
                    }
                }
                let t_end = t + lo;
                o.push(row(t_end, &y, &ev));
                o.increments = k;
                o.energy = Some(balance(&y, &ev));
                return Flow::Ended(o.end(stop.reason, t_end, stop.detail.clone()));
            }
            // The substep up to the event must itself be resolved: else approach it in shorter
            // substeps.
            if lo > 0.0 {
                let mut f = finder.clone();
                match evaluate(scene, sections, &mut f, &y_lo, stuck) {
                    Ok(e) if unresolved(lo, &accept(&y_lo, &e), &e) => {
                        h = 0.5 * lo;
                        continue;
                    }
                    Ok(_) => {}
                    Err(e) => return Flow::Ended(fail(o, &y, &ev, e)),
                }
            }
            // Which event: what the shortest step that reaches it shows. A pivot with the
            // kinetic energy at REST of the largest it had is the stop itself: as a block comes
            // to rest its contacts' slips pass through zero one after another ever faster (the
            // Zeno behaviour of Coulomb friction), and the travel left is of order REST of the
            // stopping distance.
            let ke = ev.motion.twist.kinetic_energy(mass, &ev.motion.inertia);
            let event = match found.or(at_end).or(crossed).unwrap_or(Event::Stop) {
                Event::Pivot(_) if ke <= REST * ke_max => Event::Stop,
                e => e,
            };
            let t_event = t + hi;
            events += 1;
            // A release goes on from just past the moment (the contact then slips, in the
            // direction `rigid_body::accelerations` gives); a pivot from just before it, the
            // contact's remaining slip (of the bisection's size) projected out, stuck while its
            // cone allows.
            let resume = match event {
                Event::Release(_) => Some((y_hi, hi, None)),
                Event::Pivot(i) => Some((y_lo, lo, Some(i))),
                Event::Stop => None,
            };
            if let Some((y_at, len, stick)) = resume {
                let at = match evaluate(scene, sections, finder, &y_at, stick) {
                    Ok(e) => e,
                    Err(e) => return Flow::Ended(fail(o, &y, &ev, e)),
                };
                o.travel += (at.pose.cm - ev.pose.cm).norm();
                y = accept(&y_at, &at);
                ev = at;
                anchor = anchor_of(&ev, None);
                t += len;
                continue;
            }
            // The state just before the stop, at rest.
            let mut stopped = y_lo;
            stopped[3] = 0.0;
            stopped[4] = 0.0;
            stopped[5] = 0.0;
            match come_to_rest(
                (scene, sections, finder),
                (&stopped, &ev),
                (k, t, t_event),
                start,
                &mut o,
            ) {
                Rest::Failed(e) => return Flow::Ended(fail(o, &y, &ev, e)),
                Rest::Ended(reason, at, detail) => return Flow::Ended(o.end(reason, at, detail)),
                Rest::Slips(e) => {
                    ev = *e;
                    y = stopped;
                    anchor = anchor_of(&ev, None);
                    t = t_event;
                }
            }
        }
        self.t = t_target;
        (self.y, self.ev, self.anchor, self.ke_max, self.h) = (y, ev, anchor, ke_max, h);
        Flow::Go(o)
    }
}
