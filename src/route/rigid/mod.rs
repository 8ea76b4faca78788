//! The route under rigid-body dynamics (`[solver] dynamics = "rigid-body"`;
//! `derivations/08-rigid-body.md`).
//!
//! The state (`state.rs`) is the three degrees of freedom (X, Z, θ), their rates, the work done
//! so far by the applied loads (the water, the pseudo-static and the record's inertial forces)
//! and by friction, integrated with the motion by classic RK4 so that the energy balance
//! (`energy.rs`) can be checked to the integrator's order, and the time, on which a
//! ground-motion record's loads depend. Constraint drift stays at round-off by construction: the
//! pose is recomputed from (X, Z, θ) by the tracker at every evaluation (`evaluate.rs`) and the
//! six-component twist is the projection of (Ẋ, Ż, θ̇) onto the constraints
//! (`mechanics::rigid_body::twist`).
//!
//! Stick and slip at the block level: at rest (the start, or when the motion stops), the block
//! stays put when static friction within the three cones can hold it (`at_rest.rs`, on the rest
//! layer, `route/rest.rs`); otherwise it slips from rest in the direction that reproduces
//! itself. While sliding, an increment is taken in substeps (`substep.rs`), each checked for
//! events — a stop (the twist reverses), a pivot (a contact's slip reverses), a release (a
//! sticking contact's cone no longer holds it) or a failure (a state off the model) —
//! recognised in `heading.rs` and found by the event layer's bisection on the step length
//! (`route/events.rs`), and shortened where the energy balance says RK4 does not resolve the
//! motion (`derivations/08-rigid-body.md` §3). The events of the rock's faces — a contact
//! meeting a face, running over a ridge, let go by a crease — and their impacts are in
//! `faces.rs`. At a stop the velocity is set to exactly zero. A sticking contact is held where
//! it stuck, and a contact in a crease on its second face (`hold.rs`), their slip projected out
//! as an impulse would (the energy that takes booked as friction work), so that they stay put
//! whatever dt.

mod at_rest;
mod energy;
mod evaluate;
mod faces;
mod heading;
mod held_region;
mod hold;
mod rows;
mod state;
mod substep;
mod tendons;

use super::Steps;
use super::dynamics::{Dynamics, Flow, Start};
use super::energy::EnergyBalance;
use super::logbook::Logbook;
use super::pose_finder::PoseFinder;
use super::rest::{self, AtRest};
use super::row::Row;
use super::termination::{Reason, Stop};
use super::three_point::{faces_of, factor_of_safety_at_start, yield_acceleration_at_start};
use crate::geometry::Pose;
use crate::mechanics::ContactGeometry;
use crate::mechanics::static_friction::{HoldingRange, Limit};
use crate::model::{Body, ContactStrength, Foundation, RunSettings, Simulation};
use at_rest::{rest_eval, rest_row, static_check};
use energy::EnergyOrigin;
use evaluate::{Eval, Hold, cm_y, evaluate};
use hold::Anchor;
use serde::Serialize;
use state::RigidState;
use std::rc::Rc;

/// What the rigid body adds to its route.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize)]
pub struct RigidBodyReport {
    /// The energy balance from the start to the route's last state.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub energy: Option<EnergyBalance>,
    /// Its steps, chosen against the tolerance (written with the computation's numbers in
    /// summary.json, `Report::steps`).
    #[serde(skip)]
    pub steps: Steps,
}

/// The rigid body's logbook.
pub(super) type Log<'s> = Logbook<'s, RigidBodyReport>;

/// What a route follows: the simulation (its foundation, strengths and settings) and its one
/// body as the route has it — the one given, or the route's own once the route has changed it:
/// its anchors' tendons fixed in the rock where it starts, one of them broken
/// (`derivations/11-dam-loads.md` §10). Cloned for nothing either way.
#[derive(Clone)]
pub(super) struct Model<'a> {
    sim: &'a Simulation,
    body: Followed<'a>,
}

/// The body a route follows: the simulation's, or the route's own copy.
#[derive(Clone)]
enum Followed<'a> {
    Given(&'a Body),
    Own(Rc<Body>),
}

impl<'a> Model<'a> {
    /// The simulation's one body, as given.
    fn new(sim: &'a Simulation) -> Self {
        Model {
            sim,
            body: Followed::Given(sim.first_body()),
        }
    }

    /// The same simulation with the route's own `body`.
    fn with_body(&self, body: Body) -> Self {
        Model {
            sim: self.sim,
            body: Followed::Own(Rc::new(body)),
        }
    }

    /// The body the route follows.
    pub(super) fn body(&self) -> &Body {
        match &self.body {
            Followed::Given(b) => b,
            Followed::Own(b) => b,
        }
    }

    /// The rock and its shaking.
    pub(super) fn foundation(&self) -> &'a Foundation {
        self.sim.foundation()
    }

    /// The run settings.
    pub(super) fn settings(&self) -> &'a RunSettings {
        self.sim.settings()
    }

    /// What the body's three contacts on the rock's faces `faces` carry, with the cohesion
    /// when `bonded` (never yet slid).
    pub(super) fn frame_strength(&self, faces: [u32; 3], bonded: bool) -> [ContactStrength; 3] {
        self.body()
            .frame_strength(self.sim.strengths(), faces, bonded)
    }
}

/// How a route ends within a substep.
enum Ending {
    /// A state off the model: the route ends at the state before the substep.
    Failed(Stop),
    /// An end decided where it happened (a stop held by friction, a failure located by
    /// bisection), its rows and energy balance already in the outcome.
    At(Reason, f64, String),
}

/// The rigid body under way: the state and the evaluation at it, the substep and what the
/// energy balance and the stick hold need. A [`Dynamics`] the driver (`driver.rs`) runs.
pub(super) struct RigidBody<'a> {
    sim: Model<'a>,
    y: RigidState,
    t: f64,
    ev: Eval,
    /// The sticking contact and where it stuck.
    anchor: Option<Anchor>,
    /// The largest kinetic energy so far (the energy balance's scale).
    ke_max: f64,
    /// The largest kinetic energy since the block last slipped from rest: the scale against
    /// which a slip is settling (`substep.rs`'s `SETTLED`).
    slip_peak: f64,
    /// The last event, when it was a pivot: the contact and the moment.
    pivoted: Option<(usize, f64)>,
    /// The next step passes through a moment where a contact's slip turns about zero faster
    /// than its events can be told apart (the same pivot met again at once, the block under
    /// way): taken plain, no event resolved, and of the shortest substep (`substep.rs`).
    through: bool,
    /// The next step's length: chosen by the error estimate against the tolerance
    /// (`substep.rs`), shortened where the energy balance says RK4 does not resolve the motion.
    h: f64,
    /// Each value's weight in the step's error: 1 / (tolerance × its scale), zero for the works
    /// and the time (`substep.rs`'s `error_weights`).
    weights: [f64; state::VALUES],
    /// The recorded rows at the times strictly inside the last step (its dense output, each
    /// evaluated at its state), for a step longer than the rows' interval.
    within: Vec<Row>,
    /// The recorded times inside the last step (a buffer kept from step to step).
    times: Vec<f64>,
    /// The time the driver last advanced to: the row it asks for is this one's.
    shown_t: f64,
    /// What the energy balance is measured from: the start.
    energy: EnergyOrigin,
    /// The balance's own round-off: its potential energy m g ΔY carries that of a height of the
    /// size of L. No substep can resolve it below that; near the start from rest, where the
    /// energies are tiny, the tolerance alone asked for it, and every increment was halved down
    /// to the shortest substep (36 000 halvings in the first 0.2 ms at dt = 10 µs).
    round_off: f64,
    /// Held at rest by static friction while a ground-motion record's loads change: each
    /// increment checks the friction cones again, and the block slips when they no longer hold
    /// it (`at_rest.rs`, on the rest layer, `route/rest.rs`).
    resting: bool,
    /// While resting: the ground accelerations it is certainly held under where it rests
    /// (`held_region.rs`), found at its first increment at rest.
    region: Option<held_region::HeldRegion>,
    /// Whether the next step locates a switch of friction's regime as an event
    /// (`route/events.rs`'s `Event::Switch`): not past `MAX_SWITCHES` in an increment, nor after a
    /// switch met again at the moment of the last.
    switching: bool,
    /// The moment of the last switch located.
    switched_at: f64,
}

/// What the energy balance is measured from: the start at `pose`, its kinetic energy `kinetic`.
fn start_origin(sim: &Model<'_>, pose: &Pose, kinetic: f64) -> EnergyOrigin {
    EnergyOrigin {
        kinetic,
        cm_y: cm_y(sim, pose),
        mass: sim.body().block().mass,
        gravity: sim.body().loads().gravity,
    }
}

impl<'a> RigidBody<'a> {
    /// At the start, in state `y` evaluated as `ev`, the energy measured from `energy`; resting
    /// while a record's loads change, or moving.
    fn new(sim: Model<'a>, y: RigidState, ev: Eval, energy: EnergyOrigin, resting: bool) -> Self {
        let mass = sim.body().block().mass;
        let (h, round_off) = (
            sim.settings().reference_step(),
            64.0 * f64::EPSILON * mass * sim.body().loads().gravity * sim.body().l(),
        );
        let weights = substep::error_weights(&sim);
        RigidBody {
            sim,
            y,
            t: 0.0,
            anchor: Anchor::after(&ev, None),
            ev,
            ke_max: 0.0,
            slip_peak: 0.0,
            pivoted: None,
            through: false,
            h,
            weights,
            within: Vec::new(),
            times: Vec::new(),
            shown_t: 0.0,
            energy,
            round_off,
            resting,
            region: None,
            switching: true,
            switched_at: f64::NAN,
        }
    }

    /// At rest at the start in state `y` at `pose` on `faces`, and held there by static friction
    /// (`check`): under a record that shakes the foundation it rests while the record's loads
    /// change; else the route ends, "does not slide".
    fn held_at_start<'s>(
        sim: Model<'a>,
        finder: &PoseFinder<'_>,
        (y, pose, faces): (RigidState, Pose, [u32; 3]),
        check: &HoldingRange,
        mut o: Log<'s>,
    ) -> Start<'s, Self, RigidBodyReport> {
        o.push(rest_row(0.0, &y, &pose, faces));
        if rest::shaking(sim.foundation(), 0.0) {
            // Held for now: it rests while the record's loads change.
            let ev = match rest_eval(&sim, finder, pose, check) {
                Ok(e) => e,
                Err(Stop { reason, detail, .. }) => {
                    return Start::Ended(o.end(reason, 0.0, detail));
                }
            };
            let origin = start_origin(&sim, &pose, 0.0);
            return Start::Moving(RigidBody::new(sim, y, ev, origin, true), o);
        }
        let why = format!(
            "static friction within the three cones holds the block: factor of safety {}",
            check.factor_of_safety()
        );
        let (reason, why) = AtRest::NeverSlid(why).words(sim.foundation());
        let mut done = o.end(reason, 0.0, why);
        done.report.energy = Some(EnergyBalance::default());
        Start::Ended(done)
    }

    /// Not held at the start (`check`), or set moving by `[initial]`: the block slips from rest,
    /// or moves on, from its evaluation in state `y` at `pose`. Where it has none the route
    /// ends there: "the block overturned" where it was at rest and its loads tip it onto two
    /// contacts, which the frame cannot follow (its base can).
    fn moving_at_start<'s>(
        sim: Model<'a>,
        finder: &mut PoseFinder<'_>,
        (y, pose, faces): (RigidState, Pose, [u32; 3]),
        check: &HoldingRange,
        mut o: Log<'s>,
    ) -> Start<'s, Self, RigidBodyReport> {
        let ev = match evaluate(&sim, finder, &y, Hold::default()) {
            Ok(e) => e,
            Err(Stop { reason, detail, .. }) => {
                o.push(rest_row(0.0, &y, &pose, faces));
                if sim.body().initial().at_rest() && check.limit() == Some(Limit::Tips) {
                    let detail = format!(
                        "the loads tip the block onto two contacts at the start (the load \
                         multiple {} is limited by tipping; on three contacts: {detail}); the \
                         block on its base follows it (solver.contacts = \"base\")",
                        check.factor_of_safety()
                    );
                    return Start::Ended(o.end(Reason::Overturned, 0.0, detail));
                }
                return Start::Ended(o.end(reason, 0.0, detail));
            }
        };
        o.push(ev.row(0.0, &y));
        let mass = sim.body().block().mass;
        let kinetic = ev.motion.twist.kinetic_energy(mass, &ev.motion.inertia);
        let origin = start_origin(&sim, &pose, kinetic);
        Start::Moving(RigidBody::new(sim, y, ev, origin, false), o)
    }

    /// The energy balance at state `y` evaluated as `e`.
    fn balance(&self, y: &RigidState, e: &Eval) -> EnergyBalance {
        let mass = self.sim.body().block().mass;
        self.energy.balance(
            y,
            e.motion.twist.kinetic_energy(mass, &e.motion.inertia),
            cm_y(&self.sim, &e.pose),
        )
    }

    /// The route ended by a failure at the current state.
    fn fail<'s>(&self, mut o: Log<'s>, s: Stop) -> Log<'s> {
        o.report.energy = Some(self.balance(&self.y, &self.ev));
        o.finish(self.ev.row(self.t, &self.y), s.reason, self.t, s.detail)
    }
}

impl<'a> Dynamics<'a> for RigidBody<'a> {
    type Report = RigidBodyReport;

    fn start<'s>(
        sim: &'a Simulation,
        finder: &mut PoseFinder<'_>,
        mut o: Log<'s>,
    ) -> Start<'s, Self, RigidBodyReport> {
        let sim = Model::new(sim);
        let y = RigidState::start(sim.body().initial());
        let faces = faces_of(sim.body().site());
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
        // Anchors: each tendon's bond fixed in the rock where the block starts.
        let sim = if sim.body().tendons().is_empty() {
            sim
        } else {
            sim.with_body(
                sim.body()
                    .tendons_fixed_at(&start_pose.cm, &start_pose.frame),
            )
        };
        let geom = ContactGeometry::new(sim.body().normals(), &start_pose);
        let check = match static_check(&sim, &geom, 0.0, faces, true) {
            Ok(c) => c,
            Err(Stop { reason, detail, .. }) => {
                o.push(rest_row(0.0, &y, &start_pose, faces));
                return Start::Ended(o.end(reason, 0.0, detail));
            }
        };
        o.fs = Some(check.factor_of_safety());
        o.fs_limit = check.limit();
        let at = (y, start_pose, faces);
        if sim.body().initial().at_rest() && check.holds() {
            return RigidBody::held_at_start(sim, finder, at, &check, o);
        }
        RigidBody::moving_at_start(sim, finder, at, &check, o)
    }

    fn advance<'s>(
        &mut self,
        finder: &mut PoseFinder<'_>,
        k: usize,
        t_to: f64,
        o: Log<'s>,
    ) -> Flow<'s, RigidBodyReport> {
        self.shown_t = t_to;
        self.substeps(finder, k, t_to, o)
    }

    fn row(&self) -> Row {
        // A row inside the last step (the step went past the driver's time).
        if self.t > self.shown_t * (1.0 + 1e-15)
            && let Ok(k) = (self.within).binary_search_by(|r| r.t_s.total_cmp(&self.shown_t))
        {
            // The rows are in time order: found without a scan (up to 1024 a step).
            return self.within[k];
        }
        if self.resting {
            rest_row(self.t, &self.y, &self.ev.pose, self.ev.faces)
        } else {
            self.ev.row(self.t, &self.y)
        }
    }

    fn close(&self, o: &mut Log<'_>) {
        o.report.energy = Some(self.balance(&self.y, &self.ev));
    }

    /// The frame's factor of safety at the start where the start did not reach it (no start
    /// pose to check, or a start that ended before its static check) and, under a record, its
    /// yield acceleration.
    fn at_start(sim: &'a Simulation, start: Option<&Pose>, o: &mut Log<'_>) {
        factor_of_safety_at_start(sim, start, o);
        yield_acceleration_at_start(sim, start, o);
    }
}
