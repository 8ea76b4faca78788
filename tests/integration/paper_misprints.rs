//! The paper's printed f1, f2, f7 and f11 are misprints: at true poses (from the direct pose
//! solver) they leave system (15) far from zero, while our re-derived coefficients leave only
//! the small-angle error. These tests exist so that nobody "fixes" our coefficients back.
//! See `derivations/05-paper-differences.md`.

use crate::common::{printed_f1_f2_f7_f11, scene};
use slideroute::Scene;
use slideroute::internals::geometry::{Displacement, direct};
use slideroute::poses::{CoeffInputs, SmallAngle};

/// (15) residuals with our coefficients, and with one printed coefficient swapped in.
fn residuals_with_printed(index: usize, s: &Scene, d: Displacement) -> (f64, f64) {
    let p = direct::solve(s.site(), d).expect("direct pose");
    let l = s.l();
    let (a, b) = (p.alpha(l), p.beta(l));
    let ours = SmallAngle::new(&CoeffInputs::new(s.site().as_paper().unwrap(), d));
    let printed = printed_f1_f2_f7_f11(s, d);
    let mut theirs = ours;
    let slot = [0, 1, 6, 10][index];
    theirs.f[slot] = printed[index];
    // Only the equation that holds the coefficient: (15a) for f1, f2; (15b) for f7, f11.
    let eq = slot / 6;
    let size = |r: [f64; 2]| r[eq].abs() / (l * l);
    (size(ours.residual(a, b)), size(theirs.residual(a, b)))
}

/// Shallow dips keep the small-angle error small; θ ≠ 0 (f1's misprint is sin²θ-sized).
fn shallow() -> (Scene, Displacement) {
    (
        scene(10.0, 0.4, 0.35, 4.0, 5.0, 30.0),
        Displacement::new(0.6, 0.15, 5f64.to_radians()),
    )
}

fn assert_misprint(index: usize, name: &str, (s, d): (Scene, Displacement)) {
    let (ours, printed) = residuals_with_printed(index, &s, d);
    assert!(
        ours < 1e-5,
        "our (15) should nearly vanish at the true pose: {ours:e}"
    );
    assert!(
        printed > 100.0 * ours,
        "the printed {name} should not vanish at the true pose: {printed:e} vs ours {ours:e}"
    );
}

#[test]
fn paper_f1_misprint_does_not_vanish_at_true_pose() {
    // Printed: X² + 2L2X(cos θ − 1)X + (L2X² − L1Z²) sin²θ; ours: B² − L1Z² sin²θ with
    // B = X − L2X(1 − cos θ). They differ by L2X²(sin²θ − (1 − cos θ)²).
    assert_misprint(0, "f1", shallow());
}

#[test]
fn paper_f2_misprint_does_not_vanish_at_true_pose() {
    // Printed: 2L cot ξ (L2X − X − cos θ [L2X + L1Z]); ours: −2L cot ξ B. They differ by
    // 2 L L1Z cos θ cot ξ — the printed f2 has an extra L1Z.
    assert_misprint(1, "f2", shallow());
}

#[test]
fn paper_f7_misprint_does_not_vanish_at_true_pose() {
    // Printed: … + cos²(θ+κ)(−L2X + 2L2Z)² …; ours: (D − L2X cos(θ+κ))² − L2Z² sin²(θ+κ).
    assert_misprint(2, "f7", shallow());
}

#[test]
fn paper_f11_misprint_does_not_vanish_at_true_pose() {
    // Printed: 4 L L1Z cos(θ+κ) cot ζ; ours: 4 L L2Z cos(θ+κ) cot ζ (invisible when L1Z = L2Z).
    // f11 multiplies α β², a term of the same (second) order in the dips as the small-angle
    // error itself, so at shallow dips the misprint hides behind it. It shows where L1Z and
    // L2Z differ strongly and the slide turns (θ = 5°) with κ = 0: there our residual is
    // about 1/1400 of the printed one.
    let s = scene(10.0, 0.4, 0.8, 20.0, 24.0, 0.0);
    let d = Displacement::new(1.0, 0.1, 5f64.to_radians());
    assert_misprint(3, "f11", (s, d));
}

#[test]
fn printed_f3_to_f6_f8_to_f10_and_f12_agree_with_ours() {
    // The rest of the printed coefficients are right; typed as printed (1.41 → √2).
    let s = scene(10.0, 0.4, 0.35, 20.0, 25.0, 30.0);
    let d = Displacement::new(0.6, 0.15, 5f64.to_radians());
    let (f, g) = (
        s.site().as_paper().unwrap().frame,
        s.site().as_paper().unwrap().foundation,
    );
    let l = s.l();
    let r2 = std::f64::consts::SQRT_2;
    let (st, ct) = d.theta.sin_cos();
    let _ = st;
    let cp = (d.theta + g.kappa).cos();
    let (cx, cz) = (1.0 / g.xi.tan(), 1.0 / g.zeta.tan());
    let dd = g.kappa.cos() * (f.l2x - d.x) + g.kappa.sin() * (f.l2z + d.z);
    let printed = [
        (
            2,
            2.0 * r2 * f.l1z * (ct * ct * (f.l1z + f.l2x) - ct * (f.l2x - d.x) - f.l1z),
        ),
        (3, l * l * cx * cx),
        (4, -2.0 * r2 * l * f.l1z * ct * cx),
        (5, 2.0 * f.l1z * f.l1z),
        (7, 2.0 * r2 * l * cz * (dd - f.l2x * cp)),
        (
            8,
            2.0 * r2 * f.l2z * (cp * cp * (f.l1x - f.l1z) + dd * cp - f.l2z),
        ),
        (9, 2.0 * l * l * cz * cz),
        (11, 2.0 * f.l2z * f.l2z),
    ];
    let ours = SmallAngle::new(&CoeffInputs::new(s.site().as_paper().unwrap(), d)).f;
    for (k, v) in printed {
        assert!(
            (ours[k] - v).abs() < 1e-12 * v.abs().max(l * l),
            "f{}: {} vs {}",
            k + 1,
            ours[k],
            v
        );
    }
}
