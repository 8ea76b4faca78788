//! The route of a block on its whole base (`[solver] contacts = "base"`;
//! `derivations/13-base-contact.md`).
//!
//! The block is a rigid body in six degrees of freedom. It is first set down on the ground
//! under its own weight (`geometry::settle`): the lowest pose of its base with nothing below the
//! ground. Then, step by step, the loads at the pose give the free velocities; the base's
//! touches with the ground within the step's reach (`geometry::touch`: corners on faces, the
//! ground's vertices under the base, ground edges across its edges) give the contacts; the
//! contact impulses (`mechanics::impulses`: no contact pulls, no gap closes past zero, Coulomb
//! friction exactly) give the velocities at the step's end, and the pose moves by them
//! (`step.rs`). A contact is made where a gap closes (an inelastic impact, the energy it takes
//! booked with friction's) and released where its impulse falls to zero, so the block rocks,
//! hops, drops off a step and lands as the physics says. Where the whole base lies flush on one
//! face, its slide is an ordinary differential equation integrated to the tolerance, under a
//! record too, its onsets and stops located (`flush.rs`, `sliding.rs`); where every touch is on
//! one face otherwise and no record shakes it, the steps are extrapolated and held to the
//! tolerance, a stop or a reversal located (`extrapolate.rs`, `stepping.rs`). We deliberately
//! differ from the three-point model elsewhere: on two faces or more, and under a record off a
//! flush face, the step is time-stepped alone (first order, every contact change inside a step,
//! not located to round-off), because the contacts of a base on real rock change by the dozen.
//!
//! The route ends only where the physics does: the block stops and static friction holds it
//! (no ground motion), it overturns (its base tilts beyond [`OVERTURN_DEG`]), its base goes
//! over no ground, or the time limit; at rest it ends in the rest layer's words
//! (`route/rest.rs`), and it reports its tilts and its factor of safety at the start through the
//! three-point frame's points (`route/three_point.rs`).

mod dense;
mod extrapolate;
mod flush;
pub(super) mod report;
mod sliding;
mod state;
mod step;
mod stepping;

pub use report::{BaseReport, Carrying, Resting, pose_of_row};

use super::dynamics::{Dynamics, Flow, Start};
use super::energy::EnergyBalance;
use super::logbook::Logbook;
use super::pose_finder::PoseFinder;
use super::rest::{self, AtRest};
use super::row::Row;
use super::termination::Reason;
use super::three_point::factor_of_safety_at_start;
use super::{AnchorBreak, Steps};
use crate::geometry::contact::Quadrature;
use crate::geometry::penetration::{deepest_of, samples};
use crate::geometry::{
    BodyPose, CastError, Footprint, Ground, Pose, Relief, Rest, SettleError, cast, set_down,
};
use crate::model::{Base, Body, Simulation, Tendon};
use flush::Flush;
use nalgebra::{Matrix3, Vector3};
use serde::Serialize;
use state::BodyState;
use std::cell::Cell;
use std::sync::Arc;
use step::{Ctx, HELD_SOLVE, STEP_SOLVE, Stepped};

/// What the block on its base adds to its route.
#[derive(Debug, Clone, PartialEq, Default, Serialize)]
pub struct OnBaseReport {
    /// The energy balance from the start to the route's last state.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub energy: Option<EnergyBalance>,
    /// Where it rested before any load, what carried it, and the deepest its base went into the
    /// ground (none where it could not be set down).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub base: Option<BaseReport>,
    /// The steps chosen against the tolerance (`derivations/13-base-contact.md` §12).
    #[serde(skip)]
    pub steps: Steps,
    /// Where the tolerance was not met: steps still over it at the shortest length, taken as
    /// they were (none where every step met it).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub tolerance_unmet: Option<Unmet>,
    /// The phases stepped by the time-stepping scheme alone, first order at the rows' interval
    /// (the base on more than one plane of the rock): none where every step was held to the
    /// tolerance.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub first_order: Option<FirstOrder>,
}

/// The steps of a route on its base taken by the time-stepping scheme alone (first order, at
/// the rows' interval): how many, how long in all, the first one's start and the last one's
/// end.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct FirstOrder {
    /// Steps taken.
    pub steps: usize,
    /// Their time in all (s).
    pub duration_s: f64,
    /// The first one's start (s).
    pub from_s: f64,
    /// The last one's end (s).
    pub to_s: f64,
}

impl FirstOrder {
    /// A step from `t` of `h` booked in `first`.
    fn book(first: &mut Option<FirstOrder>, t: f64, h: f64) {
        let f = first.get_or_insert(FirstOrder {
            steps: 0,
            duration_s: 0.0,
            from_s: t,
            to_s: t + h,
        });
        f.steps += 1;
        f.duration_s += h;
        f.to_s = t + h;
    }
}

/// The steps of a route on its base that could not meet the tolerance at the shortest length
/// (a contact changing faster than a step can resolve): how many, from when to when, and the
/// largest error among them over the tolerance.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Unmet {
    /// Steps taken over the tolerance.
    pub steps: usize,
    /// The first one's start (s).
    pub from_s: f64,
    /// The last one's end (s).
    pub to_s: f64,
    /// The largest error over the tolerance among them.
    pub worst_ratio: f64,
}

impl Unmet {
    /// A step from `t` of `h` taken with its error `ratio` times the tolerance, booked in
    /// `unmet`.
    fn book(unmet: &mut Option<Unmet>, t: f64, h: f64, ratio: f64) {
        let u = unmet.get_or_insert(Unmet {
            steps: 0,
            from_s: t,
            to_s: t + h,
            worst_ratio: ratio,
        });
        u.steps += 1;
        u.to_s = t + h;
        u.worst_ratio = u.worst_ratio.max(ratio);
    }
}

/// The block on its base's logbook.
type Log<'s> = Logbook<'s, OnBaseReport>;

/// The tilt of the base from level beyond which the block has overturned (degrees).
pub const OVERTURN_DEG: f64 = 60.0;

/// The speed, as a fraction of g h, under which a step leaves a block held where a rigid
/// equilibrium exists (`derivations/13-base-contact.md` §6): a thousandth of what its weight
/// gives it in a step, above what a step's unconverged sweeps leave a held block with, below
/// a block that the loads move on.
const SLOW: f64 = 1e-3;

/// Samples along each side of the base in the independent check of its penetration.
const PENETRATION_SAMPLES: usize = 6;

/// Samples along each side of a cast base's triangles in the same check (its vertices, the
/// middles of its triangles' sides and their thirds: a relief has hundreds of triangles).
const RELIEF_SAMPLES: usize = 3;

/// A block on its base under way.
pub(super) struct OnBase<'a> {
    sim: &'a Simulation,
    /// The body it follows.
    body: &'a Body,
    base: &'a Base,
    ground: Arc<Ground>,
    inertia: Matrix3<f64>,
    size: f64,
    /// The base's quadrature over its area and along its edges.
    quadrature: Quadrature,
    /// A base cast onto its rock: its underside, found where it rests.
    relief: Option<Relief>,
    /// The base's samples for the independent check of its penetration (body axes, m).
    samples: Vec<Vector3<f64>>,
    s: BodyState,
    t: f64,
    /// What the last step found (the touches carrying the block).
    last: Stepped,
    /// The CM's height at the start and the kinetic energy there.
    origin: (f64, f64),
    /// The deepest the base went into the ground in any recorded row (m).
    deepest: Cell<f64>,
    /// At rest under a ground-motion record: each increment is a step from rest, kept only if
    /// it moves the block (`derivations/13-base-contact.md` §6).
    resting: bool,
    /// The anchors' tendons: fixed in the rock where the block rests, each let go when it
    /// reaches its capacity at the end of a step (`derivations/11-dam-loads.md` §10).
    tendons: Vec<Tendon>,
    /// The joint is bonded: the block has cohesion with its rock, is at rest and has never
    /// slid (`derivations/13-base-contact.md` §11). A bond once broken does not form again.
    bonded: bool,
    /// The next step's length (s), as the last step's error asked.
    h: f64,
    /// The mean accelerations over the last step taken (m/s², rad/s²): where a slip stops
    /// within the next, how soon.
    slowing: Option<(Vector3<f64>, Vector3<f64>)>,
    /// The driver's time: a row asked for is the row at it, within the last step where that
    /// went past it.
    shown_t: f64,
    /// The recorded rows within the last step (`stepping.rs`), in time order.
    within: Vec<Row>,
    /// The base lying flush on one face, alone: its slide (`sliding.rs`).
    flush: Option<Flush>,
    /// When the base last left its slide: it is not taken up again before a step of the
    /// time-stepping scheme.
    left_flush_at: Option<f64>,
    /// No record shakes the block, or one shakes it along one horizontal line (its X or its
    /// Z component alone, with or without its vertical one): where the slide may be taken.
    along_one_line: bool,
    /// Under a record, the slide stalled (`sliding.rs`): the time-stepping scheme takes the
    /// block until it rests again.
    stalled: bool,
}

impl<'a> OnBase<'a> {
    /// The block on `base` not yet set down: flat, its base's lowest point at the origin's
    /// height, at rest, nothing carrying it.
    fn unset(sim: &'a Simulation, body: &'a Body, base: &'a Base) -> Self {
        let size = (0..base.outline().len())
            .map(|k| footprint(base).corner(k).norm())
            .fold(base.depth(), f64::max);
        let flat = BodyPose {
            cm: Vector3::new(0.0, base.depth(), 0.0),
            rotation: Matrix3::identity(),
        };
        let ground = Arc::clone(sim.foundation().ground());
        let along_one_line = sim
            .foundation()
            .record()
            .is_none_or(|r| !(r.moves()[0] && r.moves()[2]));
        OnBase {
            sim,
            body,
            base,
            ground,
            inertia: body.block().tensor(),
            size,
            quadrature: Quadrature::of(base),
            relief: None,
            samples: samples(base.outline(), base.depth(), PENETRATION_SAMPLES),
            s: BodyState::at_rest(flat),
            t: 0.0,
            last: Stepped::default(),
            origin: (flat.cm.y, 0.0),
            deepest: Cell::new(f64::NEG_INFINITY),
            resting: false,
            tendons: Vec::new(),
            bonded: false,
            h: sim.settings().reference_step(),
            slowing: None,
            shown_t: 0.0,
            within: Vec::new(),
            flush: None,
            left_flush_at: None,
            along_one_line,
            stalled: false,
        }
    }

    /// The block set down on its rock under its own weight (`geometry::settle`), its anchors'
    /// tendons fixed in the rock where it rests, a cast base cast onto the rock there
    /// (`geometry::relief`): where it rests, or why it cannot (the reason and the words).
    fn rest_on_the_rock(&mut self) -> Result<Rest, (Reason, String)> {
        let (base, flat) = (self.base, self.s.pose);
        let rest =
            set_down(&self.ground, footprint(base), flat, 1e-10 * self.size).map_err(|e| {
                let reason = match e {
                    SettleError::OffGround(_) => Reason::BaseOffGround,
                    SettleError::Tips(_) => Reason::Overturned,
                    SettleError::Solver(_) | SettleError::NotSettled(_) => {
                        Reason::ContactForcesUndetermined
                    }
                };
                (reason, format!("the block cannot be set down: {e}"))
            })?;
        self.s = BodyState::at_rest(rest.pose);
        // Anchors: each tendon's bond fixed in the rock where the block rests.
        let frame = rest.pose.frame();
        self.tendons = self
            .body
            .tendons()
            .iter()
            .map(|t| t.fixed_at(&self.under_cm(), &frame))
            .collect();
        if base.is_cast() {
            let relief = cast(&self.ground, &base.triangles(), &rest.pose).map_err(|e| {
                let reason = match e {
                    CastError::OffGround { .. } => Reason::BaseOffGround,
                    CastError::Steep(_) => Reason::ContactForcesUndetermined,
                };
                (
                    reason,
                    format!("the base cannot be cast onto its rock: {e}"),
                )
            })?;
            self.size = self.size.max(relief.reach());
            self.samples = relief.samples(RELIEF_SAMPLES);
            self.quadrature = Quadrature::of_relief(&relief);
            self.relief = Some(relief);
        }
        Ok(rest)
    }

    /// The block set going from where it rests (`rest`): the scene's initial motion, the energy
    /// balance's origin, and the first step's warm start — what carries it at rest, each touch
    /// with its share of the weight over a step of `h`.
    fn set_going(&mut self, rest: &Rest, h: f64) {
        let init = self.body.initial();
        self.s.v = Vector3::new(init.vx, 0.0, init.vz);
        self.s.w = Vector3::new(0.0, -init.omega, 0.0);
        self.origin = (
            rest.pose.cm.y,
            self.s.kinetic(self.body.block().mass, &self.inertia),
        );
        let weight = self.ctx().weight_impulse(h);
        let first = rest.carrying.first().map(|(t, _)| t.face);
        let one_face = first.is_some_and(|f| rest.carrying.iter().all(|(t, _)| t.face == f));
        self.last = Stepped {
            one_face,
            impulses: rest
                .carrying
                .iter()
                .map(|(t, share)| (*t, t.normal * (share * weight)))
                .collect(),
            h,
            ..Stepped::default()
        };
    }

    /// Where the step just taken leaves the model: part of the base over no ground, or the
    /// block overturned (its base tilted beyond [`OVERTURN_DEG`]); the reason and the words.
    fn off_the_model(&self) -> Option<(Reason, String)> {
        if let Some(&k) = self.last.off_ground.first() {
            let point = match self.relief {
                Some(_) => "vertex",
                None => "corner",
            };
            let detail = format!("{point} {k} of the base went over no ground");
            return Some((Reason::BaseOffGround, detail));
        }
        if self.tilt_deg() > OVERTURN_DEG {
            let tilt = self.tilt_deg();
            let detail = format!("the base tilted {tilt:.1}° from level, beyond {OVERTURN_DEG}°");
            return Some((Reason::Overturned, detail));
        }
        None
    }

    /// After a step that left the block slow (its speed against a step of `h`'s): under
    /// a record it comes to rest (or is at rest for an instant as its motion turns) and rests
    /// from here; without one, where static friction holds it, the route ends "stopped". Else
    /// the route goes on.
    fn stopped_or_resting<'s>(&mut self, o: Log<'s>, h: f64) -> Flow<'s, OnBaseReport> {
        if !self.slow(&self.s, h) {
            return Flow::Go(o);
        }
        let shaken = self.sim.foundation().record().is_some();
        if !shaken && !self.held(self.t, h) {
            return Flow::Go(o);
        }
        self.come_to_rest(o)
    }

    /// The block at rest now, its last kinetic energy (under 1e-6 of the weight's over a step)
    /// booked with the contacts' work: under a record it rests on, its samples to say whether
    /// it stays; without one the route ends "stopped".
    fn come_to_rest<'s>(&mut self, o: Log<'s>) -> Flow<'s, OnBaseReport> {
        let shaken = self.sim.foundation().record().is_some();
        let mass = self.body.block().mass;
        self.s.work_contacts -= self.s.kinetic(mass, &self.inertia);
        self.s.v = Vector3::zeros();
        self.s.w = Vector3::zeros();
        if shaken {
            // The record's samples say whether it stays.
            self.resting = true;
            return Flow::Go(o);
        }
        let why = "the block stopped and static friction holds it on its base".into();
        let (reason, why) = AtRest::Stopped(why).words(self.sim.foundation());
        self.end(o, reason, why)
    }

    fn ctx(&self) -> Ctx<'_> {
        Ctx {
            sim: self.sim,
            body: self.body,
            ground: &self.ground,
            base: footprint(self.base),
            relief: self.relief.as_ref(),
            inertia: self.inertia,
            size: self.size,
            quadrature: &self.quadrature,
            solve: STEP_SOLVE,
            tendons: &self.tendons,
            bonded: self.bonded.then(|| self.body.shares_m2().iter().sum()),
            area: self.base.area().abs(),
        }
    }

    /// The joint's bond breaks now, as the block first slides: its cohesion is gone for good,
    /// and the time is booked in the report.
    fn break_bond(&mut self, o: &mut Log<'_>) {
        if self.bonded {
            self.bonded = false;
            if let Some(b) = o.report.base.as_mut() {
                b.bond_broken_s = Some(self.t);
            }
        }
    }

    /// The base point under the CM: where the three-point frame's rows put the block.
    fn under_cm(&self) -> Vector3<f64> {
        self.s
            .pose
            .point(&Vector3::new(0.0, -self.base.depth(), 0.0))
    }

    /// The energy balance and the deepest penetration, into the logbook.
    fn seal(&self, o: &mut Log<'_>) {
        let mass = self.body.block().mass;
        let kinetic = self.s.kinetic(mass, &self.inertia);
        let potential = mass * self.body.loads().gravity * (self.s.pose.cm.y - self.origin.0);
        let works = (self.s.work_applied, self.s.work_contacts);
        o.report.energy = Some(EnergyBalance::of(
            works,
            (self.origin.1, kinetic),
            potential,
        ));
        if let Some(b) = o.report.base.as_mut() {
            b.max_penetration_m = b.max_penetration_m.max(self.deepest.get());
        }
    }

    /// Whether the block in state `s` is slow: its speed, and its turning at its size, below
    /// [`SLOW`] of what its weight gives it in a step `h`.
    fn slow(&self, s: &BodyState, h: f64) -> bool {
        let g = self.body.loads().gravity;
        s.v.norm() + s.w.norm() * self.size <= SLOW * g * h
    }

    /// Whether static friction holds the block at rest where it is, at time `t`
    /// (`derivations/13-base-contact.md` §6): a rigid equilibrium exists (`Ctx::equilibrium`;
    /// a cone program that fails says no, and the steps go on), and a trial step of `h` from
    /// rest, its impulses solved to convergence, leaves it slow.
    fn held(&self, t: f64, h: f64) -> bool {
        if !self.ctx().equilibrium(&self.s.pose, t).unwrap_or(false) {
            return false;
        }
        // A static solution of the step's own law: the trial step would leave it at rest.
        self.ctx().held_by_its_law(&self.s.pose, t, h, &self.last) || self.settles(t, h)
    }

    /// Whether a trial step of `h` from rest at time `t`, its impulses solved to convergence,
    /// leaves the block slow (`derivations/13-base-contact.md` §6).
    fn settles(&self, t: f64, h: f64) -> bool {
        let mut trial = BodyState::at_rest(self.s.pose);
        let converged = Ctx {
            solve: HELD_SOLVE,
            ..self.ctx()
        };
        converged.step(&mut trial, t, h, &self.last);
        self.slow(&trial, h)
    }

    /// At rest under a record: the route goes on while the record does, and ends once it is
    /// over — "stopped" if the block moved, else it never slid.
    fn rest_until_the_record_ends<'s>(&self, o: Log<'s>) -> Flow<'s, OnBaseReport> {
        if rest::shaking(self.sim.foundation(), self.t) {
            return Flow::Go(o);
        }
        // Its holding is a rigid equilibrium on its touches and a step from rest that leaves
        // it slow (`held`): no multiple of the loads, so no factor of safety in the words.
        let (reason, detail) = AtRest::RecordOver {
            moved: o.travel > 0.0,
            on: " on its base",
            holding: None,
        }
        .words(self.sim.foundation());
        self.end(o, reason, detail)
    }

    /// Lets go every tendon whose force has reached its capacity at the present pose, each
    /// booked in the logbook (located to the step: the block on its base steps at dt).
    fn break_tendons(&mut self, o: &mut Log<'_>) {
        let frame = self.s.pose.frame();
        let origin = self.under_cm();
        for (k, t) in self.tendons.iter_mut().enumerate() {
            if t.past_capacity(&origin, &frame, 0.0) {
                t.broken = true;
                o.anchors_broken.push(AnchorBreak {
                    anchor: k,
                    t_s: self.t,
                });
            }
        }
    }

    /// The base's tilt from level (degrees).
    fn tilt_deg(&self) -> f64 {
        self.s.pose.up().y.clamp(-1.0, 1.0).acos().to_degrees()
    }

    /// The route ended before it began, at the pose the block has (`reason`, `detail`).
    fn refused<'s>(
        &self,
        o: Log<'s>,
        reason: Reason,
        detail: String,
    ) -> Start<'s, Self, OnBaseReport> {
        let row = self.row();
        Start::Ended(o.finish(row, reason, 0.0, detail))
    }

    /// The route ends at the block's state: the rows within its last step past the driver's
    /// time pushed first.
    fn end<'s>(&self, mut o: Log<'s>, reason: Reason, detail: String) -> Flow<'s, OnBaseReport> {
        for row in &self.within {
            if row.t_s > self.shown_t * (1.0 + 1e-15) && row.t_s < self.t {
                o.push(*row);
            }
        }
        let row = self.row_of(self.t, &self.s);
        self.seal(&mut o);
        Flow::Ended(o.finish(row, reason, self.t, detail))
    }
}

/// The impulse solve of a step under the route's `tolerance`: to the step's own fraction of the
/// largest impulse, or the tolerance where that is tighter (the solve's residual is an error in
/// the step's forces, which the extrapolation cannot remove).
fn step_solve(tolerance: f64) -> (f64, usize) {
    (STEP_SOLVE.0.min(tolerance), STEP_SOLVE.1)
}

/// What a step left not finite, if anything: the velocity, or the pose.
fn not_finite(s: &BodyState) -> Option<&'static str> {
    let finite = |m: &[f64]| m.iter().all(|x| x.is_finite());
    if !(finite(s.v.as_slice()) && finite(s.w.as_slice())) {
        return Some("velocity");
    }
    if !(finite(s.pose.cm.as_slice()) && finite(s.pose.rotation.as_slice())) {
        return Some("pose");
    }
    None
}

fn footprint(base: &Base) -> Footprint<'_> {
    Footprint {
        outline: base.outline(),
        depth: base.depth(),
    }
}

impl OnBase<'_> {
    /// The row of the block in state `s` at time `t`, what carries it as the last step found.
    fn row_of(&self, t: f64, s: &BodyState) -> Row {
        let pose = &s.pose;
        let depth = self.base.depth();
        let inside = deepest_of(&self.ground, &self.samples, pose);
        self.deepest.set(self.deepest.get().max(inside));
        let p0 = pose.point(&Vector3::new(0.0, -depth, 0.0));
        let v0 = s.v + s.w.cross(&(p0 - pose.cm));
        let frame = self
            .body
            .site()
            .contacts()
            .map(|[x, z]| pose.point(&Vector3::new(x, -depth, z)));
        let contacts = self.body.site().contacts();
        let elevation = |a: usize, b: usize| {
            let mut d = frame[b] - frame[a];
            if !(d.norm() > 0.0 && d.norm().is_finite()) {
                // A body so far away (a load of 1e30 flung it 1e22 m in a step) that its
                // contacts' places round to one: the side turned by the rotation alone, not a
                // NaN.
                let [(xa, za), (xb, zb)] = [a, b].map(|k| (contacts[k][0], contacts[k][1]));
                d = pose.rotation * Vector3::new(xb - xa, 0.0, zb - za);
            }
            (d.y / d.norm()).clamp(-1.0, 1.0).asin().to_degrees()
        };
        let faces = frame.map(|p| self.ground.top(p.x, p.z).map_or(0, |(f, _)| f as u32));
        let (corners, points) = self
            .last
            .carrying_summary(self.ctx().weight_impulse(self.last.h));
        Row {
            body: 0,
            t_s: t,
            x_m: p0.x,
            y_m: p0.y,
            z_m: p0.z,
            theta_deg: s.yaw().to_degrees(),
            alpha_deg: elevation(0, 1),
            beta_deg: elevation(0, 2),
            gamma_deg: elevation(1, 2),
            vx_m_s: v0.x,
            vz_m_s: v0.z,
            omega_deg_s: s.yaw_rate().to_degrees(),
            n_n: None,
            s_n: None,
            faces,
            crease: [None; 3],
            corners_carrying: Some(corners),
            points_carrying: Some(points),
        }
    }
}

impl<'a> Dynamics<'a> for OnBase<'a> {
    type Report = OnBaseReport;

    fn start<'s>(
        sim: &'a Simulation,
        _finder: &mut PoseFinder<'_>,
        o: Log<'s>,
    ) -> Start<'s, Self, OnBaseReport> {
        let [body] = sim.bodies() else {
            let n = sim.bodies().len();
            let detail = format!("{n} bodies: their dynamics together is not computed yet");
            return Start::Ended(o.end(Reason::SeveralBodies, 0.0, detail));
        };
        let Some(base) = body.base() else {
            return Start::Ended(o.end(
                Reason::ContactForcesUndetermined,
                0.0,
                "the simulation has no base".into(),
            ));
        };
        let mut on = OnBase::unset(sim, body, base);
        let rest = match on.rest_on_the_rock() {
            Ok(r) => r,
            Err((reason, detail)) => return on.refused(o, reason, detail),
        };
        let mut o = o;
        o.report.base = Some(BaseReport {
            resting: Resting::of(&rest),
            max_penetration_m: f64::NEG_INFINITY,
            outline_m: base.outline().to_vec(),
            bond_broken_s: None,
        });
        let h = sim.settings().dt;
        on.set_going(&rest, h);
        // Cohesion bonds a block that starts at rest; one set going breaks it at once.
        on.bonded = sim.strengths().has_cohesion();
        if !body.initial().at_rest() {
            on.break_bond(&mut o);
        }
        o.push(on.row());
        let (init, shaken) = (body.initial(), rest::shaking(sim.foundation(), 0.0));
        if sim.foundation().record().is_some() {
            // What a Newmark user reports first: the yield acceleration where it rests.
            o.yield_acceleration = on.ctx().yield_acceleration(&rest.pose).ok().flatten();
        }
        if init.at_rest() && !shaken && on.held(0.0, h) {
            on.seal(&mut o);
            o.report.energy = Some(EnergyBalance::default());
            let why = "static friction holds the block where it rests on its base".into();
            let (reason, why) = AtRest::NeverSlid(why).words(sim.foundation());
            return Start::Ended(o.end(reason, 0.0, why));
        }
        // Shaken from rest: at rest until the record moves it (its bond holding till then).
        on.resting = init.at_rest() && shaken;
        if !on.resting {
            on.break_bond(&mut o);
        }
        Start::Moving(on, o)
    }

    fn advance<'s>(
        &mut self,
        _finder: &mut PoseFinder<'_>,
        _k: usize,
        t_to: f64,
        o: Log<'s>,
    ) -> Flow<'s, OnBaseReport> {
        self.go_to(t_to, o)
    }

    fn row(&self) -> Row {
        // A row inside the last step (the step went past the driver's time).
        if self.t > self.shown_t * (1.0 + 1e-15)
            && let Ok(k) = self
                .within
                .binary_search_by(|r| r.t_s.total_cmp(&self.shown_t))
        {
            return self.within[k];
        }
        self.row_of(self.t, &self.s)
    }
    fn close(&self, o: &mut Log<'_>) {
        self.seal(o);
    }

    /// The factor of safety at the start on the block's reporting triangle, the three-point
    /// frame's (one factor of safety whatever the model); its yield acceleration is its base's
    /// own, found where it rests (`start`).
    fn at_start(sim: &'a Simulation, start: Option<&Pose>, o: &mut Log<'_>) {
        factor_of_safety_at_start(sim, start, o);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::Scene;

    /// Whether the block of `scene` (TOML) at rest where it is set down is held, as the static
    /// check of its step's law says and as the converged trial step says.
    fn verdicts(scene: &str) -> (bool, bool) {
        let sim = Scene::from_toml(scene, "held")
            .unwrap()
            .simulation()
            .unwrap();
        let h = sim.settings().dt;
        let on = set_down(&sim, h);
        let law = on.ctx().held_by_its_law(&on.s.pose, 0.0, h, &on.last);
        (law, on.settles(0.0, h))
    }

    /// The first body of `sim` set down on its rock, going with the reference step `h`.
    pub(super) fn set_down(sim: &Simulation, h: f64) -> OnBase<'_> {
        let body = &sim.bodies()[0];
        let mut on = OnBase::unset(sim, body, body.base().unwrap());
        let rest = on.rest_on_the_rock().unwrap();
        on.set_going(&rest, h);
        on
    }

    /// A 4 m square block of 1000 t, its CM in its base, on level rock with μ = 0.4, pushed
    /// along X by `push` of its weight through a line `e` (m) off its CM.
    fn pushed(push: f64, e: f64) -> String {
        format!(
            "name = \"held\"\n[frame]\ncontacts_m = [[-2.0, 2.0], [2.0, 2.0], [2.0, -2.0]]\n\
             [foundation]\n[[foundation.plane]]\ndip_deg = 0.0\ndip_direction_deg = 0.0\n\
             point_m = [0.0, 0.0, 0.0]\n[block]\nmass_kg = 1.0e6\ninertia_kg_m2 = 2.6667e6\n\
             [loads]\nhydraulic_force_n = {}\neccentricity_m = {e}\ngravity_m_s2 = 9.81\n\
             [friction]\nmodel = \"coulomb\"\nmu_k = 0.4\n[solver]\nmode = \"exact\"\n\
             dt_s = 1.0e-3\nt_end_s = 1.0\ncontacts = \"base\"\n",
            push * 1e6 * 9.81
        )
    }

    #[test]
    fn the_static_check_of_the_steps_law_gives_the_converged_trial_steps_verdicts_around_the_limit()
    {
        // Pushed through its CM the even pressure holds up to μ W: both say held below it and
        // not above it.
        for push in [0.3, 0.39, 0.398, 0.402, 0.41, 0.5] {
            let (law, trial) = verdicts(&pushed(push, 0.0));
            assert_eq!((law, trial), (push < 0.4, push < 0.4), "push {push} W");
        }
        // Twisted too, a push of 0.05 W along a line e off its CM: the even pressure's friction
        // holds a couple of μ W a (√2 + ln(1 + √2))/3 = 0.612 W·m alone, the corners' μ W √2 a
        // = 1.13 W·m; around the bed's limit (e ≈ 12 m, less with the push's own friction) the
        // static check says what the converged step says, and says held wherever it holds.
        let mut held = 0;
        for e in [4.0, 8.0, 10.0, 11.0, 11.5, 12.5, 13.0, 14.0, 17.0, 22.0] {
            let (law, trial) = verdicts(&pushed(0.05, e));
            assert_eq!(law, trial, "a push of 0.05 W {e} m off its CM");
            held += usize::from(law);
        }
        assert!((4..10).contains(&held), "{held} held");
        assert!(
            !verdicts(&pushed(0.05, 17.0)).1,
            "beyond the bed's limit it turns"
        );
    }
}
