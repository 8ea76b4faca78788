//! One route from a scene: the scene's simulation (`Scene::simulation`, the only step that
//! can fail), run (`route::Runner`).

use crate::route::{Route, Runner};
use crate::scene::{Scene, SceneError};
use std::ops::ControlFlow;

/// The route of a scene, which needs its `[block]` (or `[monolith]`), `[loads]`, `[friction]`
/// and `[solver]` sections.
///
/// ```
/// let scene = slideroute::Scene::from_file("scenes/turning.toml".as_ref())?;
/// let route = slideroute::run(&scene)?;
/// println!("{} at t = {} s after {:.3} m", route.termination.reason, route.termination.t_s, route.travel_m);
/// # assert!(route.travel_m > 0.0);
/// # Ok::<(), slideroute::SceneError>(())
/// ```
pub fn run(scene: &Scene) -> Result<Route, SceneError> {
    Ok(crate::route::simulate(&scene.simulation()?))
}

/// [`run`], calling `progress(t / t_end)` after every increment; when it answers
/// `ControlFlow::Break` the route stops there as interrupted (see [`Runner::progress`]).
pub fn run_observed(
    scene: &Scene,
    progress: impl FnMut(f64) -> ControlFlow<()>,
) -> Result<Route, SceneError> {
    let sim = scene.simulation()?;
    Ok(Runner::new(&sim).progress(progress).run().route)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::Friction;
    use crate::route::Reason;

    #[test]
    fn a_scene_is_checked_once_and_its_simulation_then_runs_without_failing() {
        // A geometry-only scene has no simulation: the missing section is named.
        let geometry_only = Scene::from_toml(
            "[frame]\nl1x = 6.0\nl2x = 4.0\nl1z = 5.0\nl2z = 5.0\n\
             [foundation]\nxi_deg = 20.0\nzeta_deg = 25.0\nkappa_deg = 30.0\n",
            "test",
        )
        .unwrap();
        assert_eq!(run(&geometry_only).unwrap_err().key, "block");
        // A scene changed by key is checked as a file would be.
        let default = Scene::default_scene();
        assert_eq!(
            default.with("block.mass_kg", -1.0).unwrap_err().key,
            "block.mass_kg"
        );
        assert_eq!(
            default.with("foundation.xi_deg", 100.0).unwrap_err().key,
            "foundation.xi_deg"
        );
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
        let sim = other.simulation().unwrap();
        assert!(matches!(
            sim.strengths().friction,
            Friction::BartonChoubey { jrc: 10.0, .. }
        ));
        assert_eq!(sim.first_body().initial().vx, 0.5);
        // A full one runs, infallibly, to the same route as `run`.
        let sim = default.simulation().unwrap();
        assert_eq!(crate::route::simulate(&sim), run(&default).unwrap());
    }

    #[test]
    fn a_route_told_to_stop_ends_interrupted_at_once() {
        let scene = Scene::default_scene();
        let r = run_observed(&scene, |_| ControlFlow::Break(())).unwrap();
        assert_eq!(r.termination.reason, Reason::Interrupted);
        assert_eq!(r.increments, 1);
    }
}
