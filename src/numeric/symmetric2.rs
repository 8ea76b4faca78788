//! The eigenvalues and eigenvectors of a symmetric 2 × 2 matrix in closed form (a contact
//! step takes apart one for every touch and every point of a flush base).

use nalgebra::{Matrix2, Vector2};

/// The eigenvalues of the symmetric `m` (its off-diagonal taken as the mean of the two), the
/// larger first, and unit eigenvectors as the columns of a rotation in the same order:
/// λ = c ± d with c the mean of the diagonal and d = √(((a − b)/2)² + m₀₁²).
pub fn symmetric_eigen2(m: &Matrix2<f64>) -> (Vector2<f64>, Matrix2<f64>) {
    let (a, b, c) = (m[(0, 0)], 0.5 * (m[(0, 1)] + m[(1, 0)]), m[(1, 1)]);
    let (mean, half) = (0.5 * (a + c), 0.5 * (a - c));
    let d = half.hypot(b);
    let (l1, l2) = (mean + d, mean - d);
    // The eigenvector of l1 from whichever row of M − l1 I is the larger.
    let (u, v) = (Vector2::new(b, l1 - a), Vector2::new(l1 - c, b));
    let v1 = if u.norm() >= v.norm() { u } else { v };
    let v1 = if v1.norm() > 0.0 {
        v1.normalize()
    } else {
        Vector2::new(1.0, 0.0)
    };
    (Vector2::new(l1, l2), Matrix2::new(v1.x, -v1.y, v1.y, v1.x))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_symmetric_two_by_two_taken_apart_in_closed_form_puts_it_back_together() {
        for m in [
            Matrix2::new(2.0, 0.3, 0.3, 1.0),
            Matrix2::new(1.0, 0.0, 0.0, 3.0),
            Matrix2::new(1.0, 0.0, 0.0, 1.0),
            Matrix2::new(5e-7, -2e-7, -2e-7, 1e-7),
            Matrix2::new(0.0, 0.0, 0.0, 0.0),
        ] {
            let (lam, q) = symmetric_eigen2(&m);
            let back = q * Matrix2::from_diagonal(&lam) * q.transpose();
            assert!((back - m).norm() <= 1e-14 * m.norm(), "{m} against {back}");
            assert!((q.transpose() * q - Matrix2::identity()).norm() < 1e-14);
            assert!(lam[0] >= lam[1]);
            // Against nalgebra's general solver.
            let eig = m.symmetric_eigen();
            let (hi, lo) = (eig.eigenvalues.max(), eig.eigenvalues.min());
            assert!((lam[0] - hi).abs() <= 1e-14 * (1.0 + hi.abs()));
            assert!((lam[1] - lo).abs() <= 1e-14 * (1.0 + lo.abs()));
        }
    }
}
