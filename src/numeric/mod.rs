//! Small numerical kernels shared by the stages: eigenvalues of small Hessenberg matrices and
//! dense polynomial products.

pub mod hessenberg;

/// An angle folded into (−π, π] by arithmetic (no trigonometric calls).
#[inline]
pub fn wrap_angle(a: f64) -> f64 {
    use std::f64::consts::{PI, TAU};
    let w = a - TAU * (a / TAU).round();
    if w <= -PI { w + TAU } else { w }
}

/// Solves the 4×4 system a·x = b by Gaussian elimination with partial pivoting; `None` if a
/// pivot vanishes. (Several times cheaper than a general LU at this size.) Written with indices,
/// as elimination is usually read.
#[inline]
#[allow(clippy::needless_range_loop)]
pub fn solve4(mut a: [[f64; 4]; 4], mut b: [f64; 4]) -> Option<[f64; 4]> {
    for col in 0..4 {
        let mut piv = col;
        for r in col + 1..4 {
            if a[r][col].abs() > a[piv][col].abs() {
                piv = r;
            }
        }
        if a[piv][col] == 0.0 || !a[piv][col].is_finite() {
            return None;
        }
        a.swap(col, piv);
        b.swap(col, piv);
        for r in col + 1..4 {
            let f = a[r][col] / a[col][col];
            for c in col..4 {
                a[r][c] -= f * a[col][c];
            }
            b[r] -= f * b[col];
        }
    }
    let mut x = [0.0; 4];
    for r in (0..4).rev() {
        let s: f64 = (r + 1..4).map(|c| a[r][c] * x[c]).sum();
        x[r] = (b[r] - s) / a[r][r];
    }
    Some(x)
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
    fn solve4_matches_nalgebra_and_pivots() {
        let a = [
            [0.0, 2.0, 1.0, 3.0],
            [1.0, 1.0, 0.0, 0.0],
            [4.0, 0.0, 2.0, 1.0],
            [1.0, 5.0, 1.0, 2.0],
        ];
        let b = [1.0, 2.0, 3.0, 4.0];
        let x = solve4(a, b).unwrap();
        let m = nalgebra::Matrix4::from_fn(|r, c| a[r][c]);
        let y = m.lu().solve(&nalgebra::Vector4::from(b)).unwrap();
        for k in 0..4 {
            assert!((x[k] - y[k]).abs() < 1e-12);
        }
        assert!(
            solve4(
                [
                    [1.0, 2.0, 0.0, 0.0],
                    [2.0, 4.0, 0.0, 0.0],
                    [0.0, 0.0, 1.0, 0.0],
                    [0.0, 0.0, 0.0, 1.0]
                ],
                b
            )
            .is_none()
        );
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
