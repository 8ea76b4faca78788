//! The rigid body at rest, on the rest layer (`route/rest.rs`): the static check of the friction
//! cones (`mechanics::static_friction`), what a stop comes to ([`RigidBody::come_to_rest`]), and
//! an increment held at rest while a ground-motion record shakes the foundation
//! ([`RigidBody::rest`]): the record's samples walked, the onset of slip, the slip from rest
//! there, the end once the record is over.

use super::Model;
use super::RigidBody;
use super::evaluate::{Eval, Hold, body_geometry, cm_y, evaluate, stop_of};
use super::held_region::{self, HeldRegion};
use super::hold::Anchor;
use super::state::RigidState;
use super::{Log, RigidBodyReport};
use crate::geometry::Pose;
use crate::mechanics::ContactGeometry;
use crate::mechanics::loads::Applied;
use crate::mechanics::rigid_body::{self, Creases, Motion};
use crate::mechanics::static_friction::{self, HoldingRange, StaticError};
use crate::route::dynamics::Flow;
use crate::route::pose_finder::PoseFinder;
use crate::route::rest::{self, AtRest, row_at_rest};
use crate::route::row::Row;
use crate::route::termination::{Reason, Stop};
use crate::route::three_point::{faces_of, frame_row};
use nalgebra::Vector3;

/// How far below 1 the factor of safety of a block at rest may be and the block still be
/// taken as held when no consistent start of slip is found (`mechanics::rigid_body`'s search
/// for it resolves accelerations down to about this fraction of g; below it the block would
/// creep at a rate no route could show).
pub(super) const BARELY: f64 = 1e-4;

/// Whether the loads exceed the friction cones of `check` by less than [`BARELY`].
pub(super) fn barely_exceeded(check: &HoldingRange) -> bool {
    check.lowest <= 1.0 && check.factor_of_safety >= 1.0 - BARELY
}

/// The static check at a pose at time t (the loads of a ground-motion record then), the
/// contacts on `faces`, with the joint's cohesion when `bonded` (never yet slid).
pub(super) fn static_check(
    sim: &Model<'_>,
    geom: &ContactGeometry,
    t: f64,
    faces: [u32; 3],
    bonded: bool,
) -> Result<HoldingRange, Stop> {
    let applied = Applied::of(sim.body(), geom, sim.foundation().acceleration(t));
    let strength = sim.frame_strength(faces, bonded);
    static_friction::at_rest(geom, &applied, &strength).map_err(static_stop)
}

/// A static check without an answer: the route ends there.
fn static_stop(err: StaticError) -> Stop {
    Stop {
        contact: None,
        reason: Reason::ContactForcesUndetermined,
        detail: err.to_string(),
    }
}

/// A row at rest (the rest layer's: velocities zero; reactions not computed, static friction is
/// indeterminate).
pub(super) fn rest_row(t: f64, y: &RigidState, pose: &Pose, faces: [u32; 3]) -> Row {
    row_at_rest(frame_row(
        t,
        y.frame_state(),
        pose,
        (faces, [None; 3]),
        None,
    ))
}

/// The evaluation of the block held at rest at `pose` (no motion; the normal reactions of a
/// holding state of `check`).
pub(super) fn rest_eval(
    sim: &Model<'_>,
    finder: &PoseFinder<'_>,
    pose: Pose,
    check: &HoldingRange,
) -> Result<Eval, Stop> {
    let geom = body_geometry(sim, &finder.site().normals(), &pose);
    let inertia = rigid_body::Inertia::new(sim.body().block(), &geom).map_err(stop_of)?;
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
            regime: 0,
        },
        rates: [0.0; 3],
        removed: 0.0,
        faces: faces_of(finder.site()),
    })
}

/// What a stop comes to (see [`RigidBody::come_to_rest`]).
pub(super) enum Rest {
    /// Not held: the block slips again from rest, from this evaluation.
    Slips(Box<Eval>),
    /// Held where it stopped while a ground-motion record still shakes the foundation: it
    /// rests from this evaluation at this time, checked again as the record's loads change.
    Rests(Box<Eval>, f64),
    /// The route ends: held where it stopped, or the slip from rest cannot be had.
    Ended(Reason, f64, String),
    /// The state at rest is off the model (as a failed step).
    Failed(Stop),
}

impl RigidBody<'_> {
    /// Whether static friction within the cones could hold the block at rest at state `y` (at
    /// its time, with the loads then; no cohesion): a contact's slip passing through zero there
    /// while the block settles is its stop.
    pub(super) fn holds_at(&self, finder: &PoseFinder<'_>, y: &RigidState) -> bool {
        let Ok(pose) = finder.clone().pose_at(y.displacement()) else {
            return false;
        };
        let geom = ContactGeometry::new(&finder.site().normals(), &pose);
        static_check(&self.sim, &geom, y.t, self.ev.faces, false).is_ok_and(|c| c.holds())
    }

    /// Where the motion stops, at `t_event` of increment `k`: the block at rest at `stopped`
    /// (the state just before the stop, its rates zeroed; the step started from the present
    /// evaluation). Held there by static friction, the route ends "stopped"; not held, it slips
    /// again from rest. The travel to the rest point, the increment, the rest row and the
    /// energy balance go into `o`.
    pub(super) fn come_to_rest(
        &self,
        finder: &mut PoseFinder<'_>,
        stopped: &RigidState,
        k: usize,
        t_event: f64,
        o: &mut Log<'_>,
    ) -> Rest {
        let model = self.sim.clone();
        let (sim, from): (&Model<'_>, _) = (&model, &self.ev);
        let stop_pose = match finder.pose_at(stopped.displacement()) {
            Ok(p) => p,
            Err(e) => return Rest::Failed(e),
        };
        o.travel += (stopped.travel - self.y.travel).max(0.0);
        o.increments = k;
        let geom = ContactGeometry::new(&finder.site().normals(), &stop_pose);
        let check = match static_check(sim, &geom, t_event, from.faces, false) {
            Ok(c) => c,
            Err(Stop { reason, detail, .. }) => return Rest::Ended(reason, self.t, detail),
        };
        // At rest there: its energy balance and its row; while a record shakes the foundation it
        // rests, else the route ends "stopped" for `why`.
        let balance = self.energy.balance(stopped, 0.0, cm_y(sim, &stop_pose));
        let held = |o: &mut Log<'_>, finder: &PoseFinder<'_>, why: String| {
            o.push(rest_row(t_event, stopped, &stop_pose, from.faces));
            o.report.energy = Some(balance);
            if rest::shaking(sim.foundation(), t_event) {
                match rest_eval(sim, finder, stop_pose, &check) {
                    Ok(e) => Rest::Rests(Box::new(e), t_event),
                    Err(stop) => Rest::Failed(stop),
                }
            } else {
                let (reason, why) = AtRest::Stopped(why).words(sim.foundation());
                Rest::Ended(reason, t_event, why)
            }
        };
        if check.holds() {
            return held(
                o,
                finder,
                format!(
                    "the motion stopped at t = {t_event:.6} s and static friction holds the \
                     block there (factor of safety {})",
                    check.factor_of_safety()
                ),
            );
        }
        match evaluate(sim, finder, stopped, Hold::of(&from.motion).sticking(None)) {
            Ok(e) => Rest::Slips(Box::new(e)),
            Err(Stop { reason, .. })
                if reason == Reason::ContactForcesUndetermined && barely_exceeded(&check) =>
            {
                held(
                    o,
                    finder,
                    format!(
                        "the motion stopped at t = {t_event:.6} s; the loads exceed the friction \
                         cones by {:.1e} of themselves there, too little for a consistent start \
                         of slip, and the block is taken as held (factor of safety {})",
                        1.0 - check.factor_of_safety,
                        check.factor_of_safety()
                    ),
                )
            }
            Err(Stop { reason, detail, .. }) => {
                o.report.energy = Some(balance);
                Rest::Ended(reason, t_event, detail)
            }
        }
    }

    /// An increment at rest, to `t_target`, while a ground-motion record shakes the
    /// foundation: the friction cones are checked with the loads then, at each of the record's
    /// samples (`rest::first_unheld`). Held, the block stays (and the route ends once the record
    /// is over); not held, it slips from rest at the moment the cones stop holding it
    /// (`rest::onset`; `self.resting` is then false and the increment goes on in substeps).
    pub(super) fn rest<'s>(
        &mut self,
        finder: &mut PoseFinder<'_>,
        t_target: f64,
        o: Log<'s>,
    ) -> Flow<'s, RigidBodyReport> {
        let model = self.sim.clone();
        let sim: &Model<'_> = &model;
        let foundation = sim.foundation();
        let geom = ContactGeometry::new(&finder.site().normals(), &self.ev.pose);
        // The joint's cohesion holds until the block first slides.
        let (faces, bonded) = (self.ev.faces, o.travel == 0.0);
        let check_at = |t: f64| static_check(sim, &geom, t, faces, bonded);
        let holds = |t: f64| check_at(t).map(|c| c.holds());
        if self.region.is_none() {
            // Where it came to rest: the ground accelerations it is certainly held under (a
            // failed cone program leaves every sample to the static check).
            let strength = sim.frame_strength(faces, bonded);
            self.region = HeldRegion::at(sim, &geom, &strength, foundation.acceleration(self.t))
                .ok()
                .flatten();
        }
        let region = self.region.as_ref();
        // Held at time t: inside the region, or by the static check.
        let held = |t: f64| match region {
            Some(r) if r.holds(foundation.acceleration(t)) => Ok(true),
            _ => holds(t),
        };
        let slips = match rest::first_unheld(foundation, (self.t, t_target), held) {
            Ok(s) => s,
            Err(s) => return Flow::Ended(self.fail(o, s)),
        };
        if let Some((lo, hi)) = slips {
            // Held at lo, not at hi, the record linear between: where the segment of its
            // accelerations leaves the held set, by one cone program (for a stress-dependent
            // criterion, by bisection to a millionth of the interval).
            let strength = sim.frame_strength(faces, bonded);
            let (a_lo, a_hi) = (foundation.acceleration(lo), foundation.acceleration(hi));
            let exit = held_region::exit(sim, &geom, &strength, a_lo, a_hi);
            let onset = match exit {
                Ok(exit) => rest::onset((lo, hi), exit, holds),
                Err(e) => Err(static_stop(e)),
            };
            return match onset {
                Ok(onset) => {
                    let barely = || check_at(t_target).is_ok_and(|c| barely_exceeded(&c));
                    self.slip_from_rest(finder, (onset, hi - lo), t_target, barely, o)
                }
                Err(s) => Flow::Ended(self.fail(o, s)),
            };
        }
        self.t = t_target;
        self.y.t = t_target;
        if rest::shaking(foundation, t_target) {
            return Flow::Go(o);
        }
        // Held through the record's end: the route ends, with the factor of safety there.
        match check_at(t_target) {
            Ok(check) => self.rested_through_the_record(check, o),
            Err(s) => Flow::Ended(self.fail(o, s)),
        }
    }

    /// The block slips from rest at `onset` (within the interval of `width` the onset was found
    /// in): just past the onset the loads exceed the cones by the cone program's tolerance, too
    /// little for a consistent direction of slip, so the start is sought a little later, at
    /// lengths doubling from a billionth of the interval, within the increment to `t_target`.
    /// At `t_target` still none: held for this increment if the loads exceed the cones there by
    /// too little (`barely`), else the route ends.
    fn slip_from_rest<'s>(
        &mut self,
        finder: &mut PoseFinder<'_>,
        (onset, width): (f64, f64),
        t_target: f64,
        barely: impl Fn() -> bool,
        o: Log<'s>,
    ) -> Flow<'s, RigidBodyReport> {
        let model = self.sim.clone();
        let sim: &Model<'_> = &model;
        let mut late = 1e-9 * width;
        let mut tried = onset;
        loop {
            let y = self.y.at(tried);
            match evaluate(sim, finder, &y, Hold::default()) {
                Ok(e) => {
                    self.y = y;
                    self.t = tried;
                    self.ev = e;
                    self.resting = false;
                    self.slip_peak = 0.0;
                    self.region = None;
                    self.anchor = Anchor::after(&self.ev, None);
                    self.h = sim.settings().reference_step();
                    return Flow::Go(o);
                }
                Err(s) if tried >= t_target => {
                    // Over the cones by too little for a consistent start of slip: held
                    // for this increment, checked again at the next.
                    if s.reason == Reason::ContactForcesUndetermined && barely() {
                        self.t = t_target;
                        self.y.t = t_target;
                        return Flow::Go(o);
                    }
                    return Flow::Ended(self.fail(o, s));
                }
                Err(_) => {
                    tried = (onset + late).min(t_target);
                    late *= 2.0;
                }
            }
        }
    }

    /// Held at rest through the record's end (`check` the static check there): the route ends,
    /// "stopped" if the block had moved, else "does not slide" (`rest::AtRest::RecordOver`).
    fn rested_through_the_record<'s>(
        &self,
        check: HoldingRange,
        mut o: Log<'s>,
    ) -> Flow<'s, RigidBodyReport> {
        let moved = o.travel > 0.0;
        o.push(rest_row(self.t, &self.y, &self.ev.pose, self.ev.faces));
        o.report.energy = Some(self.balance(&self.y, &self.ev));
        let (reason, detail) = AtRest::RecordOver {
            moved,
            on: "",
            holding: Some(check.factor_of_safety()),
        }
        .words(self.sim.foundation());
        Flow::Ended(o.end(reason, self.t, detail))
    }
}
