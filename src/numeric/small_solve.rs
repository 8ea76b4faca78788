//! A small square system A x = b by Gaussian elimination with partial pivoting on fixed arrays:
//! the contact velocities' 4 × 4 and the normal reactions' N × N that every evaluation of the
//! rigid body solves. The arithmetic is nalgebra's LU and its solve, step for step (the pivot
//! the first of the largest magnitudes, the multipliers by the pivot's reciprocal, each update
//! b − l·u, the back substitution by division), so the solution is the same to the last bit, at
//! a fraction of the general code's cost (about 480 instructions a solve there).

/// x with A x = b (`a[i][j]` row i, column j), or None where a column has no pivot (A
/// singular); the caller checks that x is finite.
pub fn solve<const N: usize>(mut a: [[f64; N]; N], mut b: [f64; N]) -> Option<[f64; N]> {
    for k in 0..N {
        let mut p = k;
        let mut best = a[k][k].abs();
        for (i, row) in a.iter().enumerate().skip(k + 1) {
            if row[k].abs() > best {
                (p, best) = (i, row[k].abs());
            }
        }
        if best == 0.0 {
            return None;
        }
        a.swap(k, p);
        b.swap(k, p);
        let inv = 1.0 / a[k][k];
        let pivot = a[k];
        for i in k + 1..N {
            let l = a[i][k] * inv;
            for j in k + 1..N {
                a[i][j] -= pivot[j] * l;
            }
            b[i] -= b[k] * l;
        }
    }
    for i in (0..N).rev() {
        let x = b[i] / a[i][i];
        b[i] = x;
        for j in 0..i {
            b[j] -= x * a[j][i];
        }
    }
    Some(b)
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::{DMatrix, DVector};

    /// Random systems of sizes 1 to 6 (some with equal pivots, a zero column, rows swapped):
    /// the same solution as nalgebra's LU to the last bit, and None where it has none.
    #[test]
    fn solutions_equal_nalgebras_lu_to_the_last_bit() {
        fn check<const N: usize>(seed: &mut u64) {
            let mut next = || {
                *seed ^= *seed << 13;
                *seed ^= *seed >> 7;
                *seed ^= *seed << 17;
                (*seed >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
            };
            for case in 0..2000 {
                let mut a = [[0.0; N]; N];
                for row in a.iter_mut() {
                    for v in row.iter_mut() {
                        *v = next() * 10f64.powi((next() * 6.0) as i32);
                    }
                }
                match case % 7 {
                    // Ties between pivots' magnitudes: the first is taken.
                    1 if N > 1 => a[1][0] = -a[0][0],
                    // A column without a pivot: singular.
                    2 => a.iter_mut().for_each(|r| r[N / 2] = 0.0),
                    3 if N > 2 => a[2] = a[0],
                    _ => {}
                }
                let b: [f64; N] = std::array::from_fn(|_| next());
                let m = DMatrix::<f64>::from_fn(N, N, |i, j| a[i][j]);
                let want = m.lu().solve(&DVector::<f64>::from_column_slice(&b));
                let got = solve(a, b);
                match (want, got) {
                    (Some(w), Some(g)) => {
                        let w: Vec<u64> = w.iter().map(|v| v.to_bits()).collect();
                        let g: Vec<u64> = g.iter().map(|v| v.to_bits()).collect();
                        assert_eq!(g, w, "size {N}, case {case}");
                    }
                    (None, None) => {}
                    (w, g) => panic!("size {N}, case {case}: nalgebra {w:?}, ours {g:?}"),
                }
            }
        }
        let mut seed = 0x2545_f491_4f6c_dd1d;
        check::<1>(&mut seed);
        check::<2>(&mut seed);
        check::<3>(&mut seed);
        check::<4>(&mut seed);
        check::<5>(&mut seed);
        check::<6>(&mut seed);
    }
}
