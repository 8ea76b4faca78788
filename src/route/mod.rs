//! The failure route (paper §7) of a [`Simulation`](crate::model::Simulation): one driver loop
//! (`driver.rs`) runs a dynamics model (`dynamics.rs`) — the paper's (`paper/`) or the rigid
//! body's (`rigid/`) — from its start, increment by increment, until the route ends for a
//! stated reason (`termination.rs`), recording rows in a logbook (`row.rs`, `logbook.rs`); `simulate.rs` picks
//! the model and says how the computation went.

mod body;
mod driver;
mod dynamics;
pub mod integrator;
mod logbook;
pub mod paper;
pub mod pose_finder;
mod rigid;
mod row;
mod simulate;
pub mod termination;

pub use body::{BaseReport, Carrying, OVERTURN_DEG, Resting, pose_of_row};
pub use logbook::EnergyBalance;
pub use pose_finder::PoseMethod;
pub use row::{Row, faces_of};
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
    /// The paper's dynamics only: its resisting capacity over driving force along x' at the start
    /// (`mechanics::onset`), a different quantity (absent where nothing drives the block along x').
    #[serde(skip_serializing_if = "Option::is_none")]
    pub paper_ratio: Option<f64>,
    /// Length of the CM path (m).
    pub travel_m: f64,
    /// Increments taken.
    pub increments: usize,
    /// Energy balance (rigid-body dynamics only).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub energy: Option<EnergyBalance>,
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
    /// A block on its base (`contacts = "base"`): where it rested before any load, what carried
    /// it, and the deepest its base went into the ground.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub base: Option<BaseReport>,
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
/// keeps one flat object), compared apart.
#[derive(Debug, Clone, Serialize)]
pub struct Computed {
    /// The route.
    #[serde(flatten)]
    pub route: Route,
    /// How it was computed.
    #[serde(flatten)]
    pub diagnostics: Diagnostics,
}

/// How one computation of a route went: its cost and the pose method's statistics. They vary
/// from run to run (the time) or with the method, not with the physics.
#[derive(Debug, Clone, PartialEq, Default, Serialize)]
pub struct Diagnostics {
    /// How often the followed friction solution was lost and chosen afresh by the rule (the
    /// paper's dynamics).
    pub friction_switches: usize,
    /// Continuation statistics: accepted and rejected steps, Newton iterations (continuation
    /// method only).
    pub tracker: Option<crate::roots::TrackStats>,
    /// Condition number of the tracked equations' Jacobian at the last pose (continuation only):
    /// large near a turning point or where roots merge.
    pub end_jacobian_condition: Option<f64>,
    /// Wall-clock time of the computation (s).
    pub wall_s: f64,
    /// The integration steps taken (each chosen against the tolerance), and those tried and
    /// taken again shorter: the rigid body's, and the paper's dynamics' RK4 substeps; none for
    /// the paper's own update and the block on its base, whose steps are the increments.
    pub steps: Option<Steps>,
}

/// The integration steps of a route chosen against the tolerance (`Diagnostics::steps`).
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
