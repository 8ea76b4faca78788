//! Stiff and extreme cases (`extreme_cases` in `extreme.rs`): each agrees with the direct pose solver
//! and converges, or ends with its typed reason — never NaN, a panic, a hang or a branch jump.
//! And the work–precision report's own claims.

use super::extreme::{extreme, extreme_cases};
use super::ladder::{point_count, work_precision};
use crate::{DynamicsModel, Integrator, Mode, Scene};
use crate::{PoseMethod, Reason};

#[test]
fn every_extreme_case_is_a_valid_scene() {
    // Each case is the default scene with keys changed, validated as a file is; it carries
    // its own name and differs from the base it was made from.
    let base = Scene::default_scene()
        .with_dynamics(DynamicsModel::Paper)
        .unwrap();
    let cases = extreme_cases().unwrap();
    assert_eq!(cases.len(), 18);
    for c in &cases {
        assert_eq!(c.scene.name(), c.name);
        assert_ne!(
            c.scene.with("name", base.name()).unwrap(),
            base,
            "{}",
            c.name
        );
    }
    let kicked = cases.last().unwrap();
    assert_eq!(
        kicked.scene.settings().unwrap().dynamics,
        DynamicsModel::RigidBody
    );
    assert_eq!(kicked.scene.settings().unwrap().integrator, Integrator::Rk4);
}

#[test]
fn every_extreme_case_agrees_with_the_direct_solver_or_ends_with_its_reason() {
    for row in extreme(50).unwrap() {
        assert_ne!(row.reason, "invalid scene", "{}: {}", row.case, row.detail);
        assert!(
            row.t_s.is_finite() && row.travel_m.is_finite(),
            "{}",
            row.case
        );
        assert!(!row.detail.is_empty(), "{}", row.case);
        if let Some(e) = row.max_tilt_error_rad {
            assert!(
                e <= 1e-9,
                "{}: tilts off the direct solver by {e} rad",
                row.case
            );
        }
        if let Some(c) = row.end_jacobian_condition {
            assert!(c.is_finite(), "{}", row.case);
        }
    }
}

#[test]
fn extreme_cases_that_slide_converge_as_dt_halves() {
    for case in extreme_cases().unwrap() {
        let run = |dt: f64| {
            let keys: [(&str, toml::Value); 3] = [
                ("solver.dt_s", dt.into()),
                ("solver.t_end_s", 0.4.into()),
                ("solver.integrator", "rk4".into()),
            ];
            let s = case.scene.with_keys(keys).unwrap();
            crate::run(&s).unwrap()
        };
        let (a, b) = (run(2e-3), run(1e-3));
        if a.termination.reason != Reason::TimeLimit || b.termination.reason != Reason::TimeLimit {
            continue;
        }
        let (p, q) = (a.rows.last().unwrap(), b.rows.last().unwrap());
        let d = (p.x_m - q.x_m).hypot(p.z_m - q.z_m);
        assert!(d < 1e-8, "{}: end points differ by {d} m", case.name);
    }
}

#[test]
fn quick_report_establishes_its_references_and_shows_the_orders() {
    let (points, references) =
        work_precision(true, || std::ops::ControlFlow::Continue(())).unwrap();
    assert_eq!(points.len(), point_count(true));
    for r in &references {
        assert!(
            r.change_m < r.bound_m,
            "{}: reference moves by {} m at dt/2",
            r.scene,
            r.change_m
        );
    }
    let series =
        |scene: &str, method: PoseMethod, mode: Mode, integrator: Integrator| -> Vec<f64> {
            points
                .iter()
                .filter(|p| {
                    p.scene == scene
                        && p.dynamics == DynamicsModel::Paper
                        && p.tolerance.is_none()
                        && p.method == method
                        && p.mode == mode
                        && p.integrator == integrator
                })
                .map(|p| p.error_m)
                .collect()
        };
    for scene in ["paper-like", "shallow"] {
        for (integrator, order) in [(Integrator::Paper, 1.0), (Integrator::Rk4, 4.0)] {
            let e = series(scene, PoseMethod::Continuation, Mode::Exact, integrator);
            for w in e.windows(2) {
                let o = (w[0] / w[1]).log2();
                assert!((o - order).abs() < 0.3, "{scene} {integrator:?}: order {o}");
            }
            // Both pose methods give the same route, so the same errors.
            let a = series(scene, PoseMethod::AllRoots, Mode::Exact, integrator);
            for (x, y) in e.iter().zip(&a) {
                assert!((x - y).abs() <= 1e-9 + 1e-6 * x, "{scene}: {x} vs {y}");
            }
        }
        // Small-angle against the exact reference: the model error remains as dt falls.
        let s = series(
            scene,
            PoseMethod::Continuation,
            Mode::SmallAngle,
            Integrator::Rk4,
        );
        assert!(s.iter().all(|&e| e > 1e-8), "{scene}: {s:?}");
        // The rigid body, the default dynamics, against its own reference: a series of its
        // own over a ladder of tolerances, its error falling with the tolerance (by more than
        // 300× over the four decades) and within it (the tolerance of the block's size L).
        let rigid: Vec<(f64, f64)> = points
            .iter()
            .filter(|p| p.scene == scene && p.dynamics == DynamicsModel::RigidBody)
            .map(|p| (p.tolerance.unwrap(), p.error_m))
            .collect();
        assert_eq!(rigid.len(), 3, "{scene}: {rigid:?}");
        assert!(
            rigid.windows(2).all(|w| w[1].1 < w[0].1) && rigid[2].1 * 300.0 < rigid[0].1,
            "{scene}: {rigid:?}"
        );
        // Both scenes' frames are 10 m across.
        let l = 10.0;
        assert!(
            rigid.iter().all(|&(tol, e)| e < tol * l),
            "{scene}: {rigid:?}"
        );
        // The paper's dynamics over tolerances (RK4, rows every 0.02 s): its error never rises
        // as the tolerance falls, keeps within it, and falls where the tolerance is below what
        // one step an increment gives (10⁻¹⁰ of L), the increments then cut into substeps.
        let paper: Vec<(f64, f64, usize, usize)> = points
            .iter()
            .filter(|p| {
                p.scene == scene && p.dynamics == DynamicsModel::Paper && p.tolerance.is_some()
            })
            .map(|p| (p.tolerance.unwrap(), p.error_m, p.steps, p.increments))
            .collect();
        assert_eq!(paper.len(), 3, "{scene}: {paper:?}");
        assert!(
            paper.windows(2).all(|w| w[1].1 <= w[0].1) && paper[2].1 * 10.0 < paper[0].1,
            "{scene}: {paper:?}"
        );
        assert!(
            paper.iter().all(|&(tol, e, _, _)| e < tol * l),
            "{scene}: {paper:?}"
        );
        assert!(paper[2].2 > paper[2].3, "{scene}: {paper:?}");
    }
    assert!(
        references
            .iter()
            .any(|r| r.dynamics == DynamicsModel::RigidBody)
    );
}
