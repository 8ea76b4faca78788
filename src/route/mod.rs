//! The failure route (paper §7): one driver loop (`driver.rs`) runs a [`Dynamics`] model — the
//! paper's (`paper.rs`) or the rigid body's (`rigid/`) — from its start, increment by
//! increment, until the route ends for a stated reason; `run.rs` adds what the route is
//! computed with and how (the factor of safety at the start, the diagnostics).
//!
//! ```no_run
//! let scene = slideroute::Scene::default_scene();
//! let route = slideroute::run(&scene).unwrap();
//! println!("{} after {} s, {:.2} m", route.termination.reason, route.termination.t_s, route.travel_m);
//! ```

mod driver;
pub(crate) mod dynamics;
pub mod integrator;
mod outcome;
mod paper;
pub mod pose_finder;
pub mod rhs;
mod rigid;
mod run;
pub mod state;
pub mod termination;

pub use outcome::EnergyBalance;
pub use pose_finder::PoseMethod;
pub use run::{run, run_observed, run_streamed, run_with, simulate};
pub use state::{Row, State};
pub use termination::{Reason, Termination};

use crate::scene::{DynamicsModel, Integrator, Mode};
use serde::Serialize;

/// A computed route: the recorded rows, how it ended and what it came to. Two routes are
/// equal when these are: the [`Diagnostics`] (run time, the tracker's counts) are not
/// compared, so that two runs of one scene compare equal.
#[derive(Debug, Clone, Serialize)]
pub struct Route {
    pub scene: String,
    pub mode: Mode,
    pub integrator: Integrator,
    /// The paper's dynamics or the rigid body's.
    pub dynamics: DynamicsModel,
    /// How the pose was found at each increment.
    pub pose_method: PoseMethod,
    #[serde(skip)]
    pub rows: Vec<Row>,
    pub termination: Termination,
    /// The factor of safety at the start, whatever the dynamics: the largest multiple of the
    /// driving loads static friction within the three cones can hold
    /// (`mechanics::static_friction::FactorOfSafety`); absent only if its cone program failed.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub factor_of_safety: Option<crate::mechanics::static_friction::FactorOfSafety>,
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
    /// With a ground-motion record (`seismic.record`), Newmark's permanent displacement: the
    /// horizontal distance of the CM at the route's end from its start, relative to the
    /// foundation (m).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub permanent_displacement_m: Option<f64>,
    /// With a ground-motion record, the permanent rotation: the yaw at the route's end
    /// (degrees; the tilts are the foundation's).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub permanent_rotation_deg: Option<f64>,
    /// How the route was computed: written beside the results (summary.json keeps one flat
    /// object), never compared.
    #[serde(flatten)]
    pub diagnostics: Diagnostics,
}

impl PartialEq for Route {
    fn eq(&self, other: &Route) -> bool {
        self.scene == other.scene
            && self.mode == other.mode
            && self.integrator == other.integrator
            && self.dynamics == other.dynamics
            && self.pose_method == other.pose_method
            && self.rows == other.rows
            && self.termination == other.termination
            && self.factor_of_safety == other.factor_of_safety
            && self.paper_ratio == other.paper_ratio
            && self.travel_m == other.travel_m
            && self.increments == other.increments
            && self.energy == other.energy
            && self.permanent_displacement_m == other.permanent_displacement_m
            && self.permanent_rotation_deg == other.permanent_rotation_deg
    }
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
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn two_runs_of_one_scene_compare_equal_whatever_their_time() {
        let scene = crate::scene::Scene::default_scene();
        let a = run(&scene).unwrap();
        let mut b = run(&scene).unwrap();
        b.diagnostics.wall_s = a.diagnostics.wall_s + 1.0;
        assert_eq!(a, b);
        b.travel_m += 1e-9;
        assert_ne!(a, b, "a result that differs makes them differ");
    }

    #[test]
    fn a_simulation_is_checked_once_and_then_runs_without_failing() {
        // A geometry-only scene has no simulation: the missing section is named.
        let geometry_only = crate::scene::Scene::from_toml(
            "[frame]\nl1x = 6.0\nl2x = 4.0\nl1z = 5.0\nl2z = 5.0\n\
             [foundation]\nxi_deg = 20.0\nzeta_deg = 25.0\nkappa_deg = 30.0\n",
            "test",
        )
        .unwrap();
        let e = crate::scene::Simulation::new(&geometry_only).unwrap_err();
        assert_eq!(e.key, "block", "{e}");
        // A scene changed by key is checked as a file would be.
        let default = crate::scene::Scene::default_scene();
        let e = default.with("block.mass_kg", -1.0).unwrap_err();
        assert_eq!(e.key, "block.mass_kg", "{e}");
        let e = default.with("foundation.xi_deg", 100.0).unwrap_err();
        assert_eq!(e.key, "foundation.xi_deg", "{e}");
        // A stress-dependent friction criterion and an initial motion come through.
        let mut doc = toml::Table::new();
        for (k, v) in [
            ("model", toml::Value::from("barton-choubey")),
            ("jrc", 10.0.into()),
            ("jcs_pa", 50e6.into()),
            ("phi_r_deg", 30.0.into()),
            ("contact_area_m2", 2.0.into()),
        ] {
            doc.insert(k.into(), v);
        }
        let other = default
            .with("friction", doc)
            .and_then(|s| s.with("initial.vx_m_s", 0.5))
            .unwrap();
        let sim = crate::scene::Simulation::new(&other).unwrap();
        assert!(matches!(
            sim.friction(),
            crate::scene::Friction::BartonChoubey { jrc: 10.0, .. }
        ));
        assert_eq!(sim.scene().initial.vx, 0.5);
        // A full one runs, infallibly, to the same route as `run`.
        let scene = crate::scene::Scene::default_scene();
        let sim = crate::scene::Simulation::new(&scene).unwrap();
        assert_eq!(simulate(&sim), run(&scene).unwrap());
    }
}
