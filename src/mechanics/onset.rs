//! Whether the paper's dynamics starts the block: its resisting-over-driving ratio at onset
//! (reported as `paper_ratio`; the factor of safety of every route, whatever the dynamics, is
//! the friction cones' of `super::static_friction`).
//!
//! Driving force D = (F + W + Σ N_i^S)·i': the hydraulic force and the components along the
//! sliding direction x' of the weight and of the frictionless normal reactions (25)–(27) — at
//! the start these include the resistance of the inclined planes 1 and 2, whose normals lean
//! against +X. Resisting capacity R = Σ |S_i|max, the largest shear each contact can carry at
//! its normal force by the scene's criterion. FS = R / D; FS ≥ 1 means friction can hold the
//! block (it does not slide); with D ≤ 0 nothing drives it and FS is infinite.

use super::ContactGeometry;
use super::loads::Applied;
use crate::model::{ContactStrength, ContactStrengths};

/// (FS, D, R); FS is `f64::INFINITY` when D ≤ 0.
pub fn factor_of_safety(
    geom: &ContactGeometry,
    applied: &Applied,
    c: &[f64; 3],
    friction: &[ContactStrength],
) -> (f64, f64, f64) {
    let i = &geom.frame.i;
    let mut driving = applied.total_force().dot(i);
    let mut resisting = 0.0;
    for (k, (n, &ck)) in geom.n.iter().zip(c).enumerate() {
        driving += n.dot(i) * ck;
        resisting += friction.shear(k, ck.max(0.0));
    }
    let fs = if driving > 0.0 {
        resisting / driving
    } else {
        f64::INFINITY
    };
    (fs, driving, resisting)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::Pose;
    use crate::mechanics::statics::frictionless_normals;
    use crate::scene::Scene;

    #[test]
    fn factor_of_safety_at_the_flat_start_matches_the_hand_formula() {
        // Flat frame: i' = X, so N0·i' = 0, N1·i' = −c1 sin ξ, N2·i' = −c2 sin ζ cos κ, W·i' = 0:
        // FS = μ (c0 + c1 + c2) / (F − c1 sin ξ − c2 sin ζ cos κ).
        let s = Scene::default_scene();
        let d = s.simulation().unwrap();
        let pose =
            Pose::from_tilts(s.site.as_paper().unwrap(), Default::default(), 0.0, 0.0).unwrap();
        let geom = ContactGeometry::new(&s.site().normals(), &pose);
        let applied = Applied::new(d.first_body().loads(), d.first_body().block(), &geom.frame);
        let c = frictionless_normals(&geom, &applied).unwrap();
        let g = &s.site.as_paper().unwrap().foundation;
        let driving = d.first_body().loads().hydraulic_force
            - c[1] * g.xi.sin()
            - c[2] * g.zeta.sin() * g.kappa.cos();
        let want = 0.4 * (c[0] + c[1] + c[2]) / driving;
        let (fs, dd, _) = factor_of_safety(
            &geom,
            &applied,
            &c,
            &d.first_body()
                .frame_strength(d.strengths(), [0, 1, 2], false),
        );
        assert!((fs - want).abs() < 1e-12 * want, "{fs} vs {want}");
        assert!((dd - driving).abs() < 1e-6);
    }
}
