//! The one classic fourth-order Runge–Kutta step both dynamics integrate with.

/// One classic RK4 step of length `h` from `y`, whose derivative `k1` is known:
/// y + h/6 (k1 + 2 k2 + 2 k3 + k4) with the stages at y + h/2 k1, y + h/2 k2 and y + h k3.
/// `f(stage)` gives the derivative at a stage (or an error, which ends the step). The one RK4
/// of both dynamics: the paper's on (X, Z, θ, Ẋ, Ż, θ̇), the rigid body's on that state and
/// the two works. It also gives its last stage k4 (the derivative at y + h k3), with which and
/// the derivative k5 at the step's end the embedded third-order solution
/// y + h/6 (k1 + 2 k2 + 2 k3 + k5) estimates the step's error as h/6 (k4 − k5)
/// (`derivations/08-rigid-body.md` §4a): both dynamics choose their steps by it.
pub fn rk4_stages<const N: usize, E>(
    y: &[f64; N],
    k1: &[f64; N],
    h: f64,
    mut f: impl FnMut(&[f64; N]) -> Result<[f64; N], E>,
) -> Result<([f64; N], [f64; N]), E> {
    let axpy = |k: &[f64; N], c: f64| -> [f64; N] { std::array::from_fn(|i| y[i] + c * k[i]) };
    let k2 = f(&axpy(k1, 0.5 * h))?;
    let k3 = f(&axpy(&k2, 0.5 * h))?;
    let k4 = f(&axpy(&k3, h))?;
    let next =
        std::array::from_fn(|i| y[i] + h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]));
    Ok((next, k4))
}

/// A step's error over the tolerance: the largest weighted component of the difference between
/// RK4's solution and the embedded third-order one, h/6 (k4 − k5), where k5 is the derivative
/// at the step's end (`derivations/08-rigid-body.md` §4a); `weights` each value's 1 / (tolerance
/// × its scale), 0 for a value not weighed. At most 1 where the step is within the tolerance.
/// Both dynamics choose their steps by it.
pub fn error_ratio<const N: usize>(
    weights: &[f64; N],
    h: f64,
    k4: &[f64; N],
    k5: &[f64; N],
) -> f64 {
    (0..N)
        .map(|i| (h / 6.0 * (k4[i] - k5[i])).abs() * weights[i])
        .fold(0.0, f64::max)
}

/// The cubic Hermite interpolant between (y0, f0) at the start of a step of length `h` and
/// (y1, f1) at its end, at the fraction `s` ∈ [0, 1] of it: the dense output of the step,
/// within O(h⁴) of the motion where the step is.
pub fn hermite<const N: usize>(
    (y0, f0): (&[f64; N], &[f64; N]),
    (y1, f1): (&[f64; N], &[f64; N]),
    h: f64,
    s: f64,
) -> [f64; N] {
    let (s2, s3) = (s * s, s * s * s);
    let h00 = 2.0 * s3 - 3.0 * s2 + 1.0;
    let h10 = s3 - 2.0 * s2 + s;
    let h01 = -2.0 * s3 + 3.0 * s2;
    let h11 = s3 - s2;
    std::array::from_fn(|i| h00 * y0[i] + h10 * h * f0[i] + h01 * y1[i] + h11 * h * f1[i])
}

#[cfg(test)]
mod tests {
    use super::*;

    /// y' = y from y(0) = 1: the step's error estimate against the true error, and the
    /// interpolant's order.
    #[test]
    fn the_error_estimate_falls_as_h_to_the_fourth_and_bounds_the_step_error() {
        let f = |y: &[f64; 1]| -> Result<[f64; 1], ()> { Ok([y[0]]) };
        let mut last = None;
        for h in [0.2, 0.1, 0.05] {
            let (next, k4) = rk4_stages(&[1.0], &[1.0], h, f).unwrap();
            let k5 = next;
            let estimate = (h / 6.0 * (k4[0] - k5[0])).abs();
            let error = (next[0] - f64::exp(h)).abs();
            // The estimate is the third-order solution's error: above the fourth-order step's.
            assert!(estimate > error, "{h}: {estimate} ≤ {error}");
            if let Some(prev) = last {
                let ratio: f64 = prev / estimate;
                assert!((ratio.log2() - 4.0).abs() < 0.2, "order {}", ratio.log2());
            }
            last = Some(estimate);
        }
    }

    #[test]
    fn the_dense_output_matches_ends_and_is_fourth_order_between() {
        let mut last = None;
        for h in [0.4, 0.2, 0.1] {
            let y = |t: f64| [f64::exp(t)];
            let d = |t: f64| [f64::exp(t)];
            let at = |s| hermite((&y(0.0), &d(0.0)), (&y(h), &d(h)), h, s);
            assert_eq!(at(0.0), y(0.0));
            assert!((at(1.0)[0] - y(h)[0]).abs() < 1e-15);
            let err = (at(0.5)[0] - y(0.5 * h)[0]).abs();
            if let Some(prev) = last {
                let ratio: f64 = prev / err;
                assert!((ratio.log2() - 4.0).abs() < 0.2, "order {}", ratio.log2());
            }
            last = Some(err);
        }
    }
}
