//! The route under rigid-body dynamics (`[solver] dynamics = "rigid-body"`, issue #7;
//! `derivations/08-rigid-body.md`).
//!
//! State y = (X, Z, θ, Ẋ, Ż, θ̇, W_h, W_f, t): the three degrees of freedom, their rates, the
//! work done so far by the applied loads (W_h: the water, the pseudo-static and the record's
//! inertial forces) and by friction (W_f), integrated with the motion by classic RK4 so that the
//! energy balance can be checked to the integrator's order, and the time, on which a
//! ground-motion record's loads depend. Constraint drift stays at round-off by construction: the pose is
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
use super::state::{Row, faces_of};
use super::termination::Reason;
use crate::geometry::{Displacement, Pose};
use crate::mechanics::ContactGeometry;
use crate::mechanics::loads::Applied;
use crate::mechanics::rigid_body::{self, Creases, Motion, RigidError};
use crate::mechanics::static_friction::{self, StaticCheck};
use crate::scene::{Scene, Simulation};
use nalgebra::Vector3;

mod events;
mod substep;

use events::{Event, Heading};

type Y = [f64; 9];

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
    /// The face each contact rests on (`Row::faces`).
    faces: [u32; 3],
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
    let (reason, contact) = match e {
        RigidError::LiftOff { contact, .. } | RigidError::ImpactLifts { contact, .. } => {
            (Reason::ContactLiftedOff, Some(contact))
        }
        // Events of a crease (`substep.rs` handles them where it finds them).
        RigidError::CreaseLetsGo { contact, .. } => (Reason::CreaseLetsGo, Some(contact)),
        RigidError::CreaseTakesOver { contact, .. } => (Reason::CreaseTakesOver, Some(contact)),
        RigidError::Wedged => (Reason::Wedged, None),
        RigidError::Singular(_)
        | RigidError::SlipFromRest
        | RigidError::SlipStart { .. }
        | RigidError::StickSingular { .. } => (Reason::ContactForcesUndetermined, None),
    };
    Stop {
        reason,
        detail: e.to_string(),
        contact,
    }
}

/// What the step holds contacts to: a contact that stuck at the start of the step, and the
/// contacts riding creases (`derivations/10-faces.md` §4).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
struct Hold {
    stuck: Option<usize>,
    creases: Creases,
}

impl Hold {
    /// What the motion `m` was evaluated holding.
    fn of(m: &Motion) -> Hold {
        Hold {
            stuck: m.stuck,
            creases: m.creases,
        }
    }

    /// The same creases, with `stuck` sticking.
    fn sticking(self, stuck: Option<usize>) -> Hold {
        Hold { stuck, ..self }
    }
}

/// The right-hand side at state `y`. `hold.stuck`: the contact that stuck at the start of the
/// step; the integrator's drift of its slip is projected out (as an impulse would, the energy
/// it takes in `Eval::removed`) so that it stays stuck while its cone allows. `hold.creases`:
/// contacts riding creases; their velocities into their second faces are projected out likewise.
fn evaluate(
    scene: &Scene,
    dynamics: &Simulation,
    finder: &mut PoseFinder<'_>,
    y: &Y,
    hold: Hold,
) -> Result<Eval, Stop> {
    let stuck = hold.stuck;
    let pose = pose_at(scene, finder, displacement(y))?;
    let geom = body_geometry(dynamics, &finder.site().normals(), &pose);
    let applied = Applied::shaken(
        dynamics.loads(),
        dynamics.block(),
        &geom.frame,
        scene.ground(y[8]),
    )
    .about(&geom.cm_offset);
    let mut rates = [y[3], y[4], y[5]];
    let mut removed = 0.0;
    if let Some(i) = stuck {
        // Always: a contact that stuck at the start of the step can only start to slip by its
        // cone no longer holding it (the release, which `accelerations` sees after this
        // projection), never by the integrator's drift, however long the step.
        (rates, removed) =
            rigid_body::pivot_rates(&geom, dynamics.block(), rates, i).map_err(stop_of)?;
    }
    let riding = hold.creases.without(stuck);
    if !riding.is_empty() {
        let (r, into) =
            rigid_body::crease_rates(&geom, dynamics.block(), rates, &riding).map_err(stop_of)?;
        (rates, removed) = (r, removed + into);
    }
    let faces = faces_of(finder.site());
    let motion = rigid_body::accelerations_in_crease(
        &geom,
        &applied,
        dynamics.block(),
        &dynamics.strength(faces, false),
        rates,
        dynamics.solver().dt,
        hold.creases,
    )
    .map_err(stop_of)?;
    Ok(Eval {
        pose,
        motion,
        rates,
        removed,
        faces,
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
        let geom = body_geometry(dynamics, &finder.site().normals(), &ev.pose);
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
        ev = evaluate(
            scene,
            dynamics,
            finder,
            &y,
            Hold::of(&ev.motion).sticking(Some(i)),
        )?;
        y = accept(&y, &ev);
    }
    Ok((y, ev))
}

/// The contacts with their arms from the centre of mass, which a monolith has above the base
/// point the pose is of (`derivations/11-dam-loads.md` §1): Newton–Euler about the centre of
/// mass. The static checks keep the arms from the base point, with the loads' moments about it.
fn body_geometry(
    dynamics: &Simulation,
    normals: &[Vector3<f64>; 3],
    pose: &Pose,
) -> ContactGeometry {
    ContactGeometry::with_normals(normals, pose).centred(dynamics.loads().cm_height)
}

/// The height of the centre of mass (m) at `pose`: the base point's and the monolith's ȳ along
/// j′. Gravity's work is m g times its fall.
fn cm_y(dynamics: &Simulation, pose: &Pose) -> f64 {
    pose.cm.y + dynamics.loads().cm_height * pose.frame.j.y
}

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
        1.0,
    ]
}

/// `y` with its rates replaced.
fn with_rates(y: &Y, rates: [f64; 3]) -> Y {
    let mut z = *y;
    z[3..6].copy_from_slice(&rates);
    z
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
    let hold = Hold::of(heading.before);
    let mut stage = |y: &Y| {
        let mut f = finder.for_stages();
        evaluate(scene, dynamics, &mut f, y, hold).map(|e| {
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
        faces: e.faces,
        crease: e.motion.creases.faces(),
    }
}

/// A row at rest (velocities zero; reactions not computed: static friction is indeterminate).
fn rest_row(t: f64, y: &Y, pose: &Pose, faces: [u32; 3]) -> Row {
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
        faces,
        crease: [None; 3],
    }
}

/// The evaluation of the block held at rest at `pose` (no motion; the normal reactions of a
/// holding state of `check`).
fn rest_eval(
    dynamics: &Simulation,
    finder: &PoseFinder<'_>,
    pose: Pose,
    check: &StaticCheck,
) -> Result<Eval, Stop> {
    let geom = body_geometry(dynamics, &finder.site().normals(), &pose);
    let inertia = rigid_body::Inertia::new(dynamics.block(), &geom).map_err(stop_of)?;
    let zero = Vector3::zeros();
    Ok(Eval {
        pose,
        motion: Motion {
            twist: rigid_body::Twist::default(),
            accel: zero,
            ang_accel: zero,
            normal: check.normal,
            shear: [zero; 3],
            slip: [zero; 3],
            acc: [0.0; 3],
            power_hydraulic: 0.0,
            power_friction: 0.0,
            inertia,
            stuck: None,
            crease_normal: [None; 3],
            creases: Creases::NONE,
        },
        rates: [0.0; 3],
        removed: 0.0,
        faces: faces_of(finder.site()),
    })
}

/// The static check at a pose at time t (the loads of a ground-motion record then), the
/// contacts on `faces`, with the joint's cohesion when `bonded` (never yet slid).
fn static_check(
    dynamics: &Simulation,
    geom: &ContactGeometry,
    (t, faces, bonded): (f64, [u32; 3], bool),
) -> Result<StaticCheck, Stop> {
    let applied = Applied::shaken(
        dynamics.loads(),
        dynamics.block(),
        &geom.frame,
        dynamics.scene().ground(t),
    );
    let strength = dynamics.strength(faces, bonded);
    static_friction::at_rest(geom, &applied, &strength).map_err(|err| Stop {
        contact: None,
        reason: Reason::ContactForcesUndetermined,
        detail: err.to_string(),
    })
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
    /// Held at rest by static friction while a ground-motion record's loads change: each
    /// increment checks the friction cones again, and the block slips when they no longer hold
    /// it (`rest`).
    resting: bool,
}

impl<'a> RigidBody<'a> {
    /// At the start, in state `y` evaluated as `ev`, with the kinetic energy and the CM height
    /// of the start (`origin`); resting while a record's loads change, or moving.
    fn new(
        scene: &'a Scene,
        sections: &'a Simulation,
        (y, ev): (Y, Eval),
        origin: (f64, f64),
        resting: bool,
    ) -> Self {
        let mass = sections.block().mass;
        RigidBody {
            scene,
            sections,
            y,
            t: 0.0,
            anchor: anchor_of(&ev, None),
            ev,
            ke_max: 0.0,
            h: sections.solver().dt,
            origin,
            round_off: 64.0 * f64::EPSILON * mass * sections.loads().gravity * scene.l(),
            resting,
        }
    }

    fn balance(&self, y: &Y, e: &Eval) -> EnergyBalance {
        let (mass, g) = (self.sections.block().mass, self.sections.loads().gravity);
        energy(
            y,
            e.motion.twist.kinetic_energy(mass, &e.motion.inertia),
            cm_y(self.sections, &e.pose),
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
        let y: Y = [0.0, 0.0, 0.0, init.vx, init.vz, init.omega, 0.0, 0.0, 0.0];
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
        let start = (0.0, faces_of(&scene.site), true);
        let check = match static_check(sections, &ContactGeometry::new(scene, &start_pose), start) {
            Ok(c) => c,
            Err(Stop { reason, detail, .. }) => {
                o.push(rest_row(0.0, &y, &start_pose, faces_of(&scene.site)));
                return Start::Ended(o.end(reason, 0.0, detail));
            }
        };
        o.fs = Some(check.factor_of_safety());
        let shaken = scene.record().is_some_and(|r| r.end() > 0.0);
        if init.at_rest() && check.holds() && shaken {
            // Held for now: it rests while the record's loads change.
            o.push(rest_row(0.0, &y, &start_pose, faces_of(&scene.site)));
            let ev = match rest_eval(sections, finder, start_pose, &check) {
                Ok(e) => e,
                Err(Stop { reason, detail, .. }) => {
                    return Start::Ended(o.end(reason, 0.0, detail));
                }
            };
            let origin = (0.0, cm_y(sections, &start_pose));
            return Start::Moving(RigidBody::new(scene, sections, (y, ev), origin, true), o);
        }
        if init.at_rest() && check.holds() {
            o.push(rest_row(0.0, &y, &start_pose, faces_of(&scene.site)));
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
        let ev = match evaluate(scene, sections, finder, &y, Hold::default()) {
            Ok(e) => e,
            Err(Stop { reason, detail, .. }) => {
                o.push(rest_row(0.0, &y, &start_pose, faces_of(&scene.site)));
                return Start::Ended(o.end(reason, 0.0, detail));
            }
        };
        o.push(row(0.0, &y, &ev));
        let origin = (
            ev.motion.twist.kinetic_energy(mass, &ev.motion.inertia),
            cm_y(sections, &start_pose),
        );
        Start::Moving(RigidBody::new(scene, sections, (y, ev), origin, false), o)
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
        if self.resting {
            rest_row(self.t, &self.y, &self.ev.pose, self.ev.faces)
        } else {
            row(self.t, &self.y, &self.ev)
        }
    }

    fn close(&self, o: &mut Outcome<'_>) {
        o.energy = Some(self.balance(&self.y, &self.ev));
    }
}
