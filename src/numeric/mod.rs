//! Small numerical kernels shared by the stages: eigenvalues of small Hessenberg matrices and
//! dense polynomial products.

pub mod hessenberg;
mod shown;

pub use shown::{Shown, fixed, seconds};

/// An angle folded into (−π, π] by arithmetic (no trigonometric calls).
#[inline]
pub fn wrap_angle(a: f64) -> f64 {
    use std::f64::consts::{PI, TAU};
    let w = a - TAU * (a / TAU).round();
    if w <= -PI { w + TAU } else { w }
}

/// Coefficients of the product of two polynomials (lowest degree first) into `out`, which must
/// have room for `a.len() + b.len() − 1` coefficients.
pub fn poly_mul(a: &[f64], b: &[f64], out: &mut [f64]) {
    out.iter_mut().for_each(|v| *v = 0.0);
    for (i, x) in a.iter().enumerate() {
        for (j, y) in b.iter().enumerate() {
            out[i + j] += x * y;
        }
    }
}

/// All roots of the polynomial Σ c[k] x^k (lowest degree first) as (re, im), by the eigenvalues
/// of its balanced companion matrix. Leading coefficients that are exactly zero are dropped;
/// degree at most [`hessenberg::N`]. `None` if the QR iteration fails to converge.
pub fn poly_roots(c: &[f64]) -> Option<Vec<(f64, f64)>> {
    let mut deg = c.len().saturating_sub(1);
    while deg > 0 && c[deg] == 0.0 {
        deg -= 1;
    }
    if deg == 0 {
        return Some(Vec::new());
    }
    let monic: Vec<f64> = c[..deg].iter().map(|v| v / c[deg]).collect();
    let mut h = hessenberg::Hessenberg::companion(&monic);
    h.balance();
    let (mut wr, mut wi) = ([0.0; hessenberg::N], [0.0; hessenberg::N]);
    let n = h.eigenvalues(&mut wr, &mut wi)?;
    Some((0..n).map(|k| (wr[k], wi[k])).collect())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn wrap_folds_into_the_half_open_circle() {
        use std::f64::consts::PI;
        for (a, w) in [
            (0.0, 0.0),
            (3.0 * PI, PI),
            (-PI, PI),
            (2.5, 2.5),
            (-7.0, -7.0 + 2.0 * PI),
        ] {
            assert!((wrap_angle(a) - w).abs() < 1e-12, "{a}: {}", wrap_angle(a));
        }
    }

    #[test]
    fn product_and_roots_round_trip() {
        let mut p = [0.0; 3];
        poly_mul(&[-2.0, 1.0], &[3.0, 1.0], &mut p); // (x − 2)(x + 3) = x² + x − 6
        assert_eq!(p, [-6.0, 1.0, 1.0]);
        let mut r = poly_roots(&p).unwrap();
        r.sort_by(|a, b| a.0.total_cmp(&b.0));
        assert!((r[0].0 + 3.0).abs() < 1e-14 && (r[1].0 - 2.0).abs() < 1e-14);
    }
}
