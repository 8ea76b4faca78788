//! Small numerical kernels shared by the stages: eigenvalues of small Hessenberg matrices, the
//! roots of a polynomial continued from a nearby one's quadratic factors,
//! dense polynomial products, the resultant of two quadratics, the eigen-decomposition of a
//! symmetric 2 × 2 matrix, small square systems solved on fixed arrays, and interpolation
//! through a few nodes.

pub mod bairstow;
pub mod barycentric;
mod distribution;
pub mod hessenberg;
mod shown;
pub mod small_solve;
mod symmetric2;

pub use distribution::{Distribution, FORMS, Uncertain};
pub use shown::{degrees, fixed, given, seconds};
pub use symmetric2::symmetric_eigen2;

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

/// The resultant in y of two quadratics p = a0 + a1 y + a2 y² and q = b0 + b1 y + b2 y² whose
/// coefficients are polynomials in x (lowest degree first; the resultant's degree at most 8):
/// R = (a2 b0 − a0 b2)² − (a2 b1 − a1 b2)(a1 b0 − a0 b1) (the determinant of the Bézout
/// matrix). Returns R and the magnitudes of its two terms — the same products with every
/// coefficient and difference taken in absolute value and summed — for a bound on its rounding.
/// One kernel for the pose system's x-roots (`roots::eigen`) and the paper's reactions
/// (`mechanics::reactions_paper`).
pub fn quadratic_resultant(a: [&[f64]; 3], b: [&[f64]; 3]) -> ([f64; 9], [f64; 9], [f64; 9]) {
    // Every coefficient quadratic in x (the pose system's case): fixed-size arithmetic.
    fn fixed(c: [&[f64]; 3]) -> Option<[&[f64; 3]; 3]> {
        Some([
            c[0].try_into().ok()?,
            c[1].try_into().ok()?,
            c[2].try_into().ok()?,
        ])
    }
    match (fixed(a), fixed(b)) {
        (Some(a), Some(b)) => quadratic_resultant_3(a, b),
        _ => quadratic_resultant_any(a, b),
    }
}

/// [`quadratic_resultant`] for coefficients of any number of terms.
fn quadratic_resultant_any(a: [&[f64]; 3], b: [&[f64]; 3]) -> ([f64; 9], [f64; 9], [f64; 9]) {
    // u·v − w·z (degree ≤ 8) and |u|·|v| + |w|·|z|.
    let cross = |u: &[f64], v: &[f64], w: &[f64], z: &[f64]| {
        let (mut l, mut r, mut la, mut ra) = ([0.0; 9], [0.0; 9], [0.0; 9], [0.0; 9]);
        let abs = |c: &[f64]| {
            let mut out = [0.0; 9];
            out[..c.len()]
                .iter_mut()
                .zip(c)
                .for_each(|(o, x)| *o = x.abs());
            out
        };
        poly_mul(u, v, &mut l[..u.len() + v.len() - 1]);
        poly_mul(w, z, &mut r[..w.len() + z.len() - 1]);
        poly_mul(
            &abs(u)[..u.len()],
            &abs(v)[..v.len()],
            &mut la[..u.len() + v.len() - 1],
        );
        poly_mul(
            &abs(w)[..w.len()],
            &abs(z)[..z.len()],
            &mut ra[..w.len() + z.len() - 1],
        );
        let len = (u.len() + v.len()).max(w.len() + z.len()) - 1;
        let (mut val, mut mag) = ([0.0; 9], [0.0; 9]);
        for k in 0..len {
            val[k] = l[k] - r[k];
            mag[k] = la[k] + ra[k];
        }
        (val, mag, len)
    };
    let (c20, m20, n20) = cross(a[2], b[0], a[0], b[2]);
    let (c21, m21, n21) = cross(a[2], b[1], a[1], b[2]);
    let (c10, m10, n10) = cross(a[1], b[0], a[0], b[1]);
    let (mut sq, mut pr, mut msq, mut mpr) = ([0.0; 17], [0.0; 17], [0.0; 17], [0.0; 17]);
    poly_mul(&c20[..n20], &c20[..n20], &mut sq[..2 * n20 - 1]);
    poly_mul(&c21[..n21], &c10[..n10], &mut pr[..n21 + n10 - 1]);
    poly_mul(&m20[..n20], &m20[..n20], &mut msq[..2 * n20 - 1]);
    poly_mul(&m21[..n21], &m10[..n10], &mut mpr[..n21 + n10 - 1]);
    debug_assert!(sq[9..].iter().chain(&pr[9..]).all(|&v| v == 0.0));
    let mut res = [0.0; 9];
    for k in 0..9 {
        res[k] = sq[k] - pr[k];
    }
    (
        res,
        msq[..9].try_into().unwrap_or([0.0; 9]),
        mpr[..9].try_into().unwrap_or([0.0; 9]),
    )
}

/// [`quadratic_resultant`] where every coefficient has three terms: the same operations in the
/// same order on fixed arrays (the same bits; a test compares), without the slices' bounds and
/// zeroing.
fn quadratic_resultant_3(a: [&[f64; 3]; 3], b: [&[f64; 3]; 3]) -> ([f64; 9], [f64; 9], [f64; 9]) {
    fn mul<const U: usize, const V: usize, const W: usize>(u: &[f64; U], v: &[f64; V]) -> [f64; W] {
        let mut out = [0.0; W];
        for i in 0..U {
            for j in 0..V {
                out[i + j] += u[i] * v[j];
            }
        }
        out
    }
    let cross = |u: &[f64; 3], v: &[f64; 3], w: &[f64; 3], z: &[f64; 3]| {
        let (l, r): ([f64; 5], [f64; 5]) = (mul(u, v), mul(w, z));
        let abs = |c: &[f64; 3]| c.map(f64::abs);
        let (la, ra): ([f64; 5], [f64; 5]) = (mul(&abs(u), &abs(v)), mul(&abs(w), &abs(z)));
        let (mut val, mut mag) = ([0.0; 5], [0.0; 5]);
        for k in 0..5 {
            val[k] = l[k] - r[k];
            mag[k] = la[k] + ra[k];
        }
        (val, mag)
    };
    let (c20, m20) = cross(a[2], b[0], a[0], b[2]);
    let (c21, m21) = cross(a[2], b[1], a[1], b[2]);
    let (c10, m10) = cross(a[1], b[0], a[0], b[1]);
    let (sq, pr): ([f64; 9], [f64; 9]) = (mul(&c20, &c20), mul(&c21, &c10));
    let mut res = [0.0; 9];
    for k in 0..9 {
        res[k] = sq[k] - pr[k];
    }
    (res, mul(&m20, &m20), mul(&m21, &m10))
}

/// All roots of the polynomial Σ c\[k\] x^k (lowest degree first) as (re, im), by the eigenvalues
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
    fn the_resultant_of_quadratic_coefficients_is_that_of_any_to_the_last_bit() {
        let mut s = 5u64;
        let mut uniform = || {
            s = s
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (s >> 11) as f64 / (1u64 << 53) as f64 * 4.0 - 2.0
        };
        for _ in 0..1000 {
            let mut c = [[0.0; 3]; 6];
            c.iter_mut().flatten().for_each(|v| *v = uniform());
            // Some exact zeros (signed zeros must match too).
            c[1][2] = -0.0;
            c[4][0] = 0.0;
            let (a, b) = ([&c[0][..], &c[1], &c[2]], [&c[3][..], &c[4], &c[5]]);
            let bits =
                |r: ([f64; 9], [f64; 9], [f64; 9])| [r.0, r.1, r.2].map(|v| v.map(f64::to_bits));
            assert_eq!(
                bits(quadratic_resultant(a, b)),
                bits(quadratic_resultant_any(a, b))
            );
        }
    }

    #[test]
    fn the_resultant_of_two_quadratics_vanishes_where_they_share_a_root() {
        // p = y² − x and q = (y − 1)(y − 2) share a root where x = 1 or x = 4:
        // Res = ∏ p(y_i) over q's roots = (1 − x)(4 − x) = x² − 5x + 4.
        let (r, sq, pr) =
            quadratic_resultant([&[0.0, -1.0], &[0.0], &[1.0]], [&[2.0], &[-3.0], &[1.0]]);
        assert_eq!(&r[..3], &[4.0, -5.0, 1.0]);
        assert!(r[3..].iter().all(|&v| v == 0.0));
        // Magnitudes: (|a2 b0| + |a0 b2|)² = (2 + x)², |a2 b1|·|a0 b1| = 9x, all ≥ |R|.
        assert_eq!(&sq[..3], &[4.0, 4.0, 1.0]);
        assert_eq!(&pr[..3], &[0.0, 9.0, 0.0]);
    }

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
