//! At poses found by the independent direct pose solver (Newton on the three contact
//! constraints, no polynomials), the paper's exact relations and our exact polynomial system
//! vanish to round-off, and the paper's geometry (eqs. 1, 2, 21) rebuilds the same frame.

use crate::common::{relations, scene};
use proptest::prelude::*;
use slideroute::Scene;
use slideroute::internals::geometry::{Displacement, Pose, direct};
use slideroute::poses::{CoeffInputs, Exact};

prop_compose! {
    fn scene_and_reachable_pose()(
        l in 1.0..100.0f64,
        l2x in 0.1..0.9f64,
        l1z in 0.05..0.95f64,
        xi in 1.0..70.0f64,
        zeta in 1.0..70.0f64,
        kappa in -80.0..80.0f64,
        x in 0.0..0.4f64,
        z in -0.15..0.15f64,
        theta in -15.0..15.0f64,
    ) -> (Scene, Displacement) {
        (scene(l, l2x, l1z, xi, zeta, kappa), Displacement::new(x * l, z * l, theta.to_radians()))
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(600))]

    #[test]
    fn exact_relations_hold_at_direct_poses((s, d) in scene_and_reachable_pose()) {
        let l = s.l();
        let p = direct::solve(s.site(), d);
        prop_assume!(p.is_ok());
        let p = p.unwrap();
        let (alpha, beta) = (p.alpha(l), p.beta(l));
        // Only physically placed frames (vertex 2 on the −z' side, tilts below 80°).
        let pose = Pose::from_tilts(s.site().as_paper().unwrap(), d, alpha, beta);
        prop_assume!(pose.is_ok() && alpha.abs() < 1.4 && beta.abs() < 1.4);
        let pose = pose.unwrap();
        prop_assume!((pose.vertices[2] - p.vertices[2]).norm() < 1e-6 * l);

        // (13), (14) as printed (with √2), h from (2).
        let r = relations::law_of_sines(s.site().as_paper().unwrap(), d, alpha, beta).unwrap();
        prop_assert!(r[0].abs() <= 1e-12 * l && r[1].abs() <= 1e-12 * l, "(13), (14): {:?}", r);

        // Our exact polynomial system, generated at build time, in (α, ψ).
        let e = Exact::new(&CoeffInputs::new(s.site().as_paper().unwrap(), d));
        let psi = pose.psi;
        let r = e.residual(alpha.sin(), alpha.cos(), psi.sin(), psi.cos());
        prop_assert!(r[0].abs() <= 1e-12 * l && r[1].abs() <= 1e-12 * l, "exact: {:?}", r);

        // Eq. (21) and the rebuilt frame.
        prop_assert!((pose.cm.y - p.cm_y).abs() <= 1e-12 * l);
        for (a, b) in pose.vertices.iter().zip(&p.vertices) {
            prop_assert!((a - b).norm() <= 1e-11 * l, "vertex {} vs {}", a, b);
        }
        prop_assert!((pose.gamma - p.gamma(l)).abs() <= 1e-11);
        let (fa, fb) = (pose.frame, p.frame(l));
        prop_assert!((fa.r() - fb.r()).norm() <= 1e-11);
        let r = fa.r();
        prop_assert!((r * r.transpose() - nalgebra::Matrix3::identity()).norm() <= 1e-13);
    }
}

#[test]
fn most_sampled_poses_are_reached_by_the_direct_solver() {
    // Guards the property test above against silently assuming everything away.
    let mut ok = 0;
    let n = 200;
    for k in 0..n {
        let t = k as f64 / n as f64;
        let s = scene(
            10.0,
            0.2 + 0.6 * t,
            0.5,
            10.0 + 50.0 * t,
            15.0 + 40.0 * t,
            -60.0 + 120.0 * t,
        );
        let d = Displacement::new(3.0 * t, 1.0 - 2.0 * t, (10.0 - 20.0 * t).to_radians());
        if direct::solve(s.site(), d).is_ok() {
            ok += 1;
        }
    }
    assert!(ok >= 190, "only {ok} of {n} poses solved");
}

#[test]
fn small_angle_residual_falls_at_second_order_in_the_dips() {
    // Derivation (`derivations/03-small-angle.md`, "Accuracy"): with dips scaled by ε at a
    // fixed displacement, α, β = O(ε), cot = O(1/ε), the leading terms of (15) are O(1) and
    // the approximations sin α ≈ α, cos α ≈ 1 leave O(ε²). Halving ε divides it by 4.
    let d = Displacement::new(1.3, 0.4, 4f64.to_radians());
    let mut prev: Option<f64> = None;
    for k in 0..5 {
        let eps = 0.5f64.powi(k);
        let s = scene(10.0, 0.4, 0.5, 20.0 * eps, 25.0 * eps, 30.0);
        let p = direct::solve(s.site(), d).unwrap();
        let l = s.l();
        let f = slideroute::internals::coeffs::SmallAngle::new(&CoeffInputs::new(
            s.site().as_paper().unwrap(),
            d,
        ));
        let r = f.residual(p.alpha(l), p.beta(l));
        let size = r[0].abs().max(r[1].abs()) / (l * l);
        if let Some(q) = prev {
            let order = (q / size).log2();
            eprintln!("observed order {order:.4} at ε = {eps}");
            assert!((1.8..2.2).contains(&order), "order {order} at ε = {eps}");
        }
        prev = Some(size);
    }
}

#[test]
fn exact_system_vanishes_where_the_small_angle_one_does_not() {
    // At 20–25° dips the small-angle system is off by O(ε²); the exact one is at round-off.
    let s = Scene::default_scene();
    let d = Displacement::new(2.0, 0.3, (-3f64).to_radians());
    let p = direct::solve(s.site(), d).unwrap();
    let l = s.l();
    let inputs = CoeffInputs::new(s.site().as_paper().unwrap(), d);
    let pose = Pose::from_tilts(s.site().as_paper().unwrap(), d, p.alpha(l), p.beta(l)).unwrap();
    let e = Exact::new(&inputs).residual(
        pose.alpha.sin(),
        pose.alpha.cos(),
        pose.psi.sin(),
        pose.psi.cos(),
    );
    let sa =
        slideroute::internals::coeffs::SmallAngle::new(&inputs).residual(p.alpha(l), p.beta(l));
    assert!(e[0].abs().max(e[1].abs()) < 1e-13 * l);
    assert!(sa[0].abs().max(sa[1].abs()) > 1e-4 * l * l);
}
