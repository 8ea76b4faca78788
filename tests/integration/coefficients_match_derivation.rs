//! The generated coefficients equal the formulas derived by hand in `derivations/`, at many
//! random scenes and displacements.
//!
//! Tolerance: relative error ≤ 1e-12 of the coefficient, or ≤ 1e-14 of the coefficient's
//! natural magnitude (for coefficients that pass through zero, where a relative error is not
//! meaningful: there both sides carry round-off of the size of their largest terms).

use crate::common::{hand_exact, hand_small_angle, scene};
use proptest::prelude::*;
use slideroute::Displacement;
use slideroute::internals::coeffs::{CoeffInputs, Exact, SmallAngle};

fn close(generated: f64, hand: f64, scale: f64) -> bool {
    (generated - hand).abs() <= 1e-12 * hand.abs() + 1e-14 * scale
}

prop_compose! {
    fn any_scene_and_pose()(
        l in 1.0..200.0f64,
        l2x in 0.05..0.95f64,
        l1z in 0.05..0.95f64,
        xi in 0.5..85.0f64,
        zeta in 0.5..85.0f64,
        kappa in -85.0..85.0f64,
        x in -0.5..1.0f64,
        z in -0.5..0.5f64,
        theta in -60.0..60.0f64,
    ) -> (slideroute::Scene, Displacement) {
        (scene(l, l2x, l1z, xi, zeta, kappa), Displacement::new(x * l, z * l, theta.to_radians()))
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(1000))]

    #[test]
    fn generated_f1_to_f12_equal_the_hand_derivation((s, d) in any_scene_and_pose()) {
        let f = SmallAngle::new(&CoeffInputs::new(s.site().as_paper().unwrap(), d)).f;
        for (k, h) in hand_small_angle(&s, d).iter().enumerate() {
            prop_assert!(close(f[k], h.value, h.scale),
                "f{}: generated {} vs hand {} (scale {})", k + 1, f[k], h.value, h.scale);
        }
    }

    #[test]
    fn generated_exact_coefficients_equal_the_hand_derivation((s, d) in any_scene_and_pose()) {
        let e = Exact::new(&CoeffInputs::new(s.site().as_paper().unwrap(), d));
        let hand = hand_exact(&s, d);
        let scale = s.l() + d.x.abs() + d.z.abs();
        let generated = [
            Exact::NAMES_13.iter().zip(e.eq13()).collect::<Vec<_>>(),
            Exact::NAMES_14.iter().zip(e.eq14()).collect::<Vec<_>>(),
        ];
        for (eq, (gen_eq, hand_eq)) in generated.iter().zip(&hand).enumerate() {
            prop_assert_eq!(gen_eq.len(), hand_eq.len(), "eq {} term count", eq);
            for (name, h) in hand_eq {
                let g = gen_eq.iter().find(|(n, _)| *n == name);
                prop_assert!(g.is_some(), "eq {}: no generated term {}", eq, name);
                let g = *g.unwrap().1;
                let sc = if name.starts_with("sa") || name == &"ca_sp" {
                    scale * (1.0 / s.site().as_paper().unwrap().foundation.xi.tan() + 1.0 / s.site().as_paper().unwrap().foundation.zeta.tan() + 1.0)
                } else { scale };
                prop_assert!(close(g, *h, sc), "eq {} {}: generated {} vs hand {}", eq, name, g, h);
            }
        }
    }

    #[test]
    fn half_angle_form_is_the_trig_form_times_its_weights(
        (s, d) in any_scene_and_pose(),
        alpha in -1.5..1.5f64,
        psi in -1.5..1.5f64,
    ) {
        let e = Exact::new(&CoeffInputs::new(s.site().as_paper().unwrap(), d));
        let h = e.half_angle();
        let (ta, tp) = ((alpha / 2.0).tan(), (psi / 2.0).tan());
        let w = (1.0 + ta * ta) * (1.0 + tp * tp);
        let trig = e.residual(alpha.sin(), alpha.cos(), psi.sin(), psi.cos());
        let mag: f64 = e.g.iter().map(|c| c.abs()).sum::<f64>() * w;
        for eq in 0..2 {
            let mut v = 0.0;
            for (i, row) in h[eq].iter().enumerate() {
                for (j, c) in row.iter().enumerate() {
                    v += c * ta.powi(i as i32) * tp.powi(j as i32);
                }
            }
            prop_assert!((v - w * trig[eq]).abs() <= 1e-13 * mag, "{} vs {}", v, w * trig[eq]);
        }
    }
}
