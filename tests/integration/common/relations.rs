//! The paper's law-of-sines relations (13) and (14), evaluated as printed (with √2 for 1.41
//! and 1/√2 for cos 45), in the unknowns α, β, with h from eq. (2) on 0 ≤ h ≤ 180°.
//!
//! An independent statement of the relations the generated coefficients come from, written here
//! from the paper and not from the library, so that the tests compare the two.

use slideroute::Displacement;
use slideroute::internals::geometry::PaperSite;
use slideroute::internals::geometry::pose::cos_h;
use std::f64::consts::SQRT_2;

/// LHS − RHS of (13) and (14) (m) at tilts α, β (rad).
pub fn law_of_sines(
    site: &PaperSite,
    d: Displacement,
    alpha: f64,
    beta: f64,
) -> Result<[f64; 2], String> {
    let ch = cos_h(alpha, beta);
    if !(-1.0..=1.0).contains(&ch) {
        return Err(format!(
            "no real frame: cos h = {ch} at α = {alpha}, β = {beta}"
        ));
    }
    let h = ch.acos();
    let f = &site.frame;
    let g = &site.foundation;
    let l = f.l();
    let (sa, ca) = alpha.sin_cos();
    let (sb, cb) = beta.sin_cos();
    let th = d.theta;
    // (13)
    let lhs13 = SQRT_2 * f.l1z * cb * (h - th).cos();
    let rhs13 =
        d.x - f.l2x - (f.l1x - f.l1z) * ca * th.cos() + l * th.cos() * ca - l / g.xi.tan() * sa;
    // (14), with R (4), S (5), t (6)
    let r = f.l2x * g.kappa.cos() + f.l2z * g.kappa.sin();
    let s = d.x * g.kappa.cos() - d.z * g.kappa.sin();
    let t = (f.l1x - f.l1z) * ca * (std::f64::consts::FRAC_PI_2 - th - g.kappa).sin();
    let lhs14 = SQRT_2 * f.l2z * cb * (h - (g.kappa + th)).cos();
    let rhs14 = SQRT_2 * l * sb / g.zeta.tan() + r + t - s;
    Ok([lhs13 - rhs13, lhs14 - rhs14])
}
