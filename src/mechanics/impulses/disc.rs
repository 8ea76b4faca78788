//! One contact's friction in a sweep: the least-energy impulse within its disc, Coulomb's law
//! exactly (`derivations/13-base-contact.md` §4).

use nalgebra::{Matrix2, Vector2};

/// A contact's tangential effective inverse mass W (2×2, symmetric positive definite) by its
/// eigenvectors and eigenvalues, W = Q diag(λ) Qᵀ, taken apart once a step.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Tangential {
    /// W itself.
    pub w: Matrix2<f64>,
    q: Matrix2<f64>,
    lam: Vector2<f64>,
}

impl Tangential {
    /// W taken apart.
    pub fn new(w: Matrix2<f64>) -> Tangential {
        let (lam, q) = crate::numeric::symmetric_eigen2(&w);
        Tangential { w, q, lam }
    }
}

/// The p of |p| ≤ `radius` that minimises ½ pᵀ W p + pᵀ u (W symmetric positive definite): the
/// friction impulse of one contact whose slip without it is `u`, W its tangential effective
/// inverse mass. Inside the disc, p = −W⁻¹u (it sticks); on its rim, p = −(W + ν I)⁻¹ u with
/// ν ≥ 0 making |p| the radius, so the slip W p + u = −ν p opposes p: Coulomb's maximal
/// dissipation. ν from the secular equation 1/|p(ν)| = 1/radius by Newton (Moré and
/// Sorensen's form, nearly linear in ν).
pub fn disc_minimum(w: &Tangential, u: &Vector2<f64>, radius: f64, nu: &mut f64) -> Vector2<f64> {
    if radius <= 0.0 || u.norm() == 0.0 {
        return Vector2::zeros();
    }
    let (q, lam) = (w.q, w.lam);
    let g = q.transpose() * u;
    let p_of = |nu: f64| -> Vector2<f64> {
        -(q * Vector2::new(g[0] / (lam[0] + nu), g[1] / (lam[1] + nu)))
    };
    if lam.min() > 0.0 && p_of(0.0).norm() <= radius {
        return p_of(0.0);
    }
    // |p(ν)| falls from above the radius (or from infinity) as ν grows; Newton from the last ν
    // this contact found (a slip that changes little needs a step or two).
    // A disc so small against the slip (a friction coefficient of 1e-300) that ν overflows:
    // p(ν) → −u/ν as ν grows, so the rim's point opposite the slip, to round-off.
    let opposite = || -u * (radius / u.norm());
    if !(*nu > 0.0 && p_of(*nu).norm() >= radius) {
        // |p(ν)| ≥ |u| / (λ_max + ν), so at this ν it is at least the radius: Newton on the
        // secular equation then climbs to the root without overshooting it.
        *nu = (u.norm() / radius - lam.max()).max(0.0);
        if !(*nu + lam.max()).powi(3).is_finite() {
            *nu = 0.0;
            return opposite();
        }
    }
    let mut nu_k = *nu;
    for _ in 0..50 {
        let nu = nu_k;
        let p = p_of(nu);
        let norm = p.norm();
        if (norm - radius).abs() <= 1e-13 * radius {
            break;
        }
        // d|p|/dν = −Σ g_k² / (λ_k + ν)³ / |p|.
        let d = -(g[0] * g[0] / (lam[0] + nu).powi(3) + g[1] * g[1] / (lam[1] + nu).powi(3)) / norm;
        // Newton on φ(ν) = 1/|p| − 1/radius: φ' = −d/|p|².
        let phi = 1.0 / norm - 1.0 / radius;
        let step = phi / (-d / (norm * norm));
        let next = (nu - step).max(0.1 * nu);
        nu_k = next;
        if (next - nu).abs() <= 1e-15 * (nu.abs() + lam.max()) {
            break;
        }
    }
    let p = p_of(nu_k);
    // On the rim exactly.
    let p = p * (radius / p.norm());
    if p.iter().all(|x| x.is_finite()) {
        *nu = nu_k;
        p
    } else {
        *nu = 0.0;
        opposite()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The minimum of ½ pᵀWp + pᵀu over the disc by brute force: a fine polar grid.
    fn brute(w: &Matrix2<f64>, u: &Vector2<f64>, radius: f64) -> Vector2<f64> {
        let f = |p: Vector2<f64>| 0.5 * p.dot(&(w * p)) + p.dot(u);
        let mut best = (f64::INFINITY, Vector2::zeros());
        for i in 0..=400 {
            for j in 0..720 {
                let r = radius * i as f64 / 400.0;
                let a = (j as f64).to_radians() / 2.0;
                let p = Vector2::new(r * a.cos(), r * a.sin());
                if f(p) < best.0 {
                    best = (f(p), p);
                }
            }
        }
        best.1
    }

    #[test]
    fn the_friction_of_one_contact_is_the_least_energy_in_its_disc_and_opposes_its_slip() {
        let w = Matrix2::new(2.0, 0.7, 0.7, 1.0);
        let t = Tangential::new(w);
        for (u, radius) in [
            (Vector2::new(3.0, -1.0), 0.5),
            (Vector2::new(0.2, 0.1), 5.0),
            (Vector2::new(-1.0, 4.0), 1.0),
        ] {
            let mut nu = 0.0;
            let p = disc_minimum(&t, &u, radius, &mut nu);
            let b = brute(&w, &u, radius);
            assert!((p - b).norm() < 0.02 * radius, "{p} against {b}");
            assert!(p.norm() <= radius * (1.0 + 1e-12));
            let slip = w * p + u;
            if p.norm() < radius * (1.0 - 1e-9) {
                // It sticks.
                assert!(slip.norm() < 1e-12, "{slip}");
            } else {
                // It slides against its friction.
                let cos = slip.dot(&p) / (slip.norm() * p.norm());
                assert!((cos + 1.0).abs() < 1e-12, "{cos}");
            }
        }
    }

    #[test]
    fn a_disc_too_small_for_its_slip_gives_the_rim_opposite_the_slip_not_a_nan() {
        // Before, ν = |u|/radius overflowed (a friction coefficient of 1e-300) and the impulse
        // was NaN, which hung the route in the rotation's renormalisation.
        let t = Tangential::new(Matrix2::new(2.0, 0.7, 0.7, 1.0));
        let u = Vector2::new(3.0, -4.0);
        for radius in [1e-300, 5e-324, 1e-310, 1e-200] {
            let mut nu = 0.0;
            let p = disc_minimum(&t, &u, radius, &mut nu);
            assert!(
                p.iter().all(|x| x.is_finite()) && nu.is_finite(),
                "{p} {nu}"
            );
            // Along −u (compared without squares, which underflow at these sizes).
            let along = p.x * u.x + p.y * u.y;
            let across = p.x * u.y - p.y * u.x;
            assert!(along <= 0.0 && across.abs() <= 1e-9 * along.abs(), "{p}");
            assert!(p.x.abs().max(p.y.abs()) <= radius, "{p}");
        }
    }
}
