//! The failure route (paper §7) of a [`Simulation`](crate::model::Simulation): one driver loop
//! (`driver.rs`) runs a dynamics model (`dynamics.rs`) — the paper's (`paper/`), the rigid
//! body's on its three-point frame (`rigid/`, with what the two share of the frame in
//! `three_point.rs`) or the block's on its base (`body/`) — from its start, increment by
//! increment, until the route ends for a stated reason (`termination.rs`), recording rows in a
//! logbook (`row.rs`, `logbook.rs`). Every model meets its events through one layer
//! (`events.rs`) and rests through another (`rest.rs`). `models.rs` is the one place that picks
//! the model from the settings and knows what each reports; `simulate.rs` runs it and says how
//! the computation went.

mod body;
mod driver;
mod dynamics;
mod energy;
mod events;
pub mod integrator;
mod logbook;
pub(crate) mod models;
pub mod paper;
pub mod pose_finder;
mod rest;
mod rigid;
mod row;
mod simulate;
pub mod termination;
pub(crate) mod three_point;

pub use energy::EnergyBalance;
pub use models::Report;
pub use pose_finder::PoseMethod;
pub use row::Row;
pub use simulate::{KEPT_ROWS, Runner, simulate};
pub use termination::{Reason, Termination};

use crate::mechanics::static_friction::{FactorOfSafety, YieldAcceleration};
use crate::model::{DynamicsModel, Integrator, Intensity, Mode};
use serde::Serialize;

/// A computed route: the recorded rows, how it ended and what it came to. Two routes of one
/// simulation are equal, whatever the computation cost: how it went is kept apart
/// ([`Diagnostics`], beside the route in a [`Computed`]).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Route {
    /// The scene's name.
    pub scene: String,
    /// The pose system.
    pub mode: Mode,
    /// How each increment was taken.
    pub integrator: Integrator,
    /// The paper's dynamics or the rigid body's.
    pub dynamics: DynamicsModel,
    /// How the pose was found at each increment.
    pub pose_method: PoseMethod,
    /// The recorded rows (every row, or those a streamed run keeps), the last always among
    /// them.
    #[serde(skip)]
    pub rows: Vec<Row>,
    /// How and when it ended.
    pub termination: Termination,
    /// The factor of safety at the start, whatever the dynamics: the largest multiple of the
    /// driving loads static friction within the three cones can hold; absent only if its cone
    /// program failed.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub factor_of_safety: Option<FactorOfSafety>,
    /// What limits the factor of safety where it is a number: the loads' multiple makes the
    /// block slide, or tips it onto two contacts.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub factor_of_safety_limit: Option<crate::mechanics::static_friction::Limit>,
    /// Length of the CM path (m).
    pub travel_m: f64,
    /// Increments taken.
    pub increments: usize,
    /// What the dynamics model adds to its route: the paper's onset ratio, an energy balance,
    /// where a base rested… ([`Report`]; read through `Route::energy`, `Route::paper_ratio`,
    /// `Route::base`, `Route::steps`). Its numbers stand among the route's in summary.json.
    #[serde(flatten)]
    pub report: Report,
    /// With a ground-motion record, Newmark's permanent displacement: the horizontal distance
    /// of the CM at the route's end from its start, relative to the foundation (m).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub permanent_displacement_m: Option<f64>,
    /// With a ground-motion record, the permanent rotation: the yaw at the route's end
    /// (degrees; the tilts are the foundation's).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub permanent_rotation_deg: Option<f64>,
    /// With a ground-motion record, the permanent displacement as a signed vector, its X and
    /// Z (m): the CM's at the route's end less its start's, relative to the foundation.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub permanent_displacement_xz_m: Option<[f64; 2]>,
    /// With a ground-motion record, what its shaking measures (`model::Intensity`): PGA, PGV,
    /// Arias intensity, D5–95, along X, Y, Z.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub record_intensity: Option<Intensity>,
    /// With a ground-motion record on the three-point frame, the yield acceleration k_y at the
    /// start and the direction it pushes the block (`static_friction::yield_acceleration`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub yield_acceleration: Option<YieldAcceleration>,
    /// With `seismic.polarity = "both"`: the permanent displacement under the record as it is
    /// and reversed; the route is the one of the longer.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub polarities: Option<Polarities>,
    /// The anchors' tendons that broke at their capacity, in the order they broke.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub anchors_broken: Vec<AnchorBreak>,
}

/// An anchor's tendon broken at its capacity: which (`[[anchor]]`'s order, from 0) and when.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct AnchorBreak {
    /// The anchor, from 0.
    pub anchor: usize,
    /// When (s).
    pub t_s: f64,
}

/// The permanent displacements (X, Z, m) of a record run as it is and reversed
/// (`seismic.polarity = "both"`), and which the route reports: the longer (the first on a tie).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Polarities {
    /// "normal" or "reversed": the route's.
    pub reported: &'static str,
    /// Under the record as it is.
    pub normal_xz_m: [f64; 2],
    /// Under the record reversed.
    pub reversed_xz_m: [f64; 2],
}

/// A route and how its computation went ([`Runner::run`]): written side by side (summary.json
/// keeps one flat object, [`Computed`]'s `Serialize`), compared apart.
#[derive(Debug, Clone)]
pub struct Computed {
    /// The route.
    pub route: Route,
    /// How it was computed.
    pub diagnostics: Diagnostics,
}

impl Serialize for Computed {
    /// summary.json: one flat object — the route's numbers, its model's report among them, then
    /// how it was computed — in the order the file has always had: the model's count of friction
    /// solutions chosen afresh first among the computation's numbers, its integration steps
    /// last (both asked of the report, whatever the model).
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        #[derive(Serialize)]
        struct Flat<'a> {
            #[serde(flatten)]
            route: &'a Route,
            friction_switches: usize,
            #[serde(flatten)]
            diagnostics: &'a Diagnostics,
            steps: Option<Steps>,
        }
        Flat {
            route: &self.route,
            friction_switches: self.route.report.friction_switches(),
            diagnostics: &self.diagnostics,
            steps: self.route.report.steps(),
        }
        .serialize(s)
    }
}

/// How one computation of a route went: its cost and the pose method's statistics. They vary
/// from run to run (the time) or with the method, not with the physics. (The model's own counts
/// — its steps, the paper's friction solutions chosen afresh — are in its [`Report`].)
#[derive(Debug, Clone, PartialEq, Default, Serialize)]
pub struct Diagnostics {
    /// Continuation statistics: accepted and rejected steps, Newton iterations (continuation
    /// method only).
    pub tracker: Option<crate::roots::TrackStats>,
    /// Condition number of the tracked equations' Jacobian at the last pose (continuation only):
    /// large near a turning point or where roots merge.
    pub end_jacobian_condition: Option<f64>,
    /// Wall-clock time of the computation (s).
    pub wall_s: f64,
}

/// The integration steps of a route chosen against the tolerance (`Report::steps`): the rigid
/// body's, and the paper's dynamics' RK4 substeps.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize)]
pub struct Steps {
    /// Steps taken.
    pub taken: usize,
    /// Steps tried and taken again shorter (the error over the tolerance, the energy balance
    /// unresolved, a failure to locate).
    pub retried: usize,
    /// Recorded rows within steps whose model values were interpolated between rows evaluated
    /// in the same step (`derivations/08-rigid-body.md` §4a), not evaluated.
    pub rows_interpolated: usize,
}

impl Steps {
    /// The steps, where any was taken or tried (none for a route that never stepped).
    pub fn if_any(self) -> Option<Steps> {
        ((self.taken, self.retried) != (0, 0)).then_some(self)
    }
}

impl Route {
    /// The energy balance, where the model keeps one (the rigid body's, the block on its base).
    pub fn energy(&self) -> Option<EnergyBalance> {
        self.report.energy()
    }

    /// The paper's resisting-over-driving ratio along x' at the start (`mechanics::onset`; the
    /// paper's dynamics only, absent where nothing drives the block along x').
    pub fn paper_ratio(&self) -> Option<f64> {
        self.report.paper_ratio()
    }

    /// The integration steps, where the model chose them against the tolerance and took any.
    pub fn steps(&self) -> Option<Steps> {
        self.report.steps()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn two_runs_of_one_scene_compare_equal_whatever_their_time() {
        let sim = crate::scene::Scene::default_scene().simulation().unwrap();
        let a = Runner::new(&sim).run();
        let b = Runner::new(&sim).run();
        assert_eq!(a.route, b.route);
        let mut c = b.route.clone();
        c.travel_m += 1e-9;
        assert_ne!(a.route, c, "a result that differs makes them differ");
        assert_eq!(simulate(&sim), a.route);
    }

    #[test]
    fn a_simulation_of_two_bodies_ends_at_the_start_saying_their_dynamics_is_not_computed_yet() {
        use crate::model::{Contacts, Simulation};
        let one = crate::scene::Scene::default_scene().simulation().unwrap();
        let body = one.first_body().clone();
        let sim = Simulation::builder()
            .body(body.clone())
            .body(body)
            .foundation(one.foundation().clone())
            .strengths(one.strengths().clone())
            .settings(one.settings().with_contacts(Contacts::Base))
            .build()
            .unwrap();
        let route = simulate(&sim);
        assert_eq!(route.termination.reason, Reason::SeveralBodies);
        assert_eq!(route.termination.t_s, 0.0);
        assert!(
            route.termination.detail.contains("not computed yet"),
            "{}",
            route.termination.detail
        );
        // No one body's frame speaks for both: no factor of safety at the start.
        assert!(route.rows.is_empty() && route.factor_of_safety.is_none());
    }
}
