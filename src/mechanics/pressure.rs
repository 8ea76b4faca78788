//! The pressure under a base lying flush on its rock (`derivations/13-base-contact.md` §9): the
//! linear distribution, with no tension, of a rigid base on a uniform bed — the gravity-dam
//! engineer's base pressure, σ = N/A ± M·y/I while the resultant is within the kern, and the
//! cracked base (a triangle of pressure over part of the base) beyond it.
//!
//! A rigid base on a bed of equal springs presses p(ξ) = k·max(0, δ(ξ)) with δ linear over the
//! base, the bed's deflection; the resultant fixes δ, whatever k. Which linear δ is the
//! minimum of the convex function
//!
//! Φ(d, a) = Σ_k w_k · ½ max(0, d + a·ξ_k)² − N (d + a·c),
//!
//! (its gradient is the resultant's misfit: Σ p_k − N and Σ p_k ξ_k − N c), found by Newton's
//! method on its piecewise-quadratic form with a line search. It exists exactly when the
//! centre of pressure c is inside the quadrature points' convex hull. Points on one line (an
//! edge of the base lying on a face) take a pressure linear along it.

use nalgebra::{Matrix3, Vector3};

/// The share of `total` (N or N·s) each quadrature point carries when the resultant acts at
/// `centre`: `points` and `weights` the base's quadrature (m, m²), the result in `out` (the same
/// units as `total`, adding up to it). False, and `out` untouched, where no linear pressure
/// without tension has that resultant (the centre off the points' hull, or a total not above
/// zero).
#[cfg_attr(not(feature = "internals"), allow(dead_code))]
pub fn spread(
    points: &[[f64; 2]],
    weights: &[f64],
    total: f64,
    centre: [f64; 2],
    out: &mut Vec<f64>,
) -> bool {
    Bed::new(points, weights).is_some_and(|mut bed| bed.spread(total, centre, out))
}

/// The quadrature points of a base with what [`spread`] needs of them worked out once: their
/// coordinates about their centroid, scaled, and the all-pressed solve (the shares of many
/// resultants on one base, as the sweeps of a step ask, each from the last one's δ).
#[derive(Debug, Clone)]
pub struct Bed {
    /// (1, ξ, ζ) of each point about the centroid over the scale (ζ = 0 on a line).
    xi: Vec<Vector3<f64>>,
    /// Each weight over the total.
    w: Vec<f64>,
    mid: [f64; 2],
    scale: f64,
    /// The line's direction, where the points are on one.
    along: Option<nalgebra::Vector2<f64>>,
    /// The inverse of Σ w (1, ξ)(1, ξ)ᵀ: δ when every point presses.
    all_pressed: Matrix3<f64>,
    /// The last δ found.
    last: Vector3<f64>,
}

impl Bed {
    /// The bed of `points` with `weights` (m²), or None where they have no area, no extent, or
    /// are not as many as the weights.
    pub fn new(points: &[[f64; 2]], weights: &[f64]) -> Option<Bed> {
        let area: f64 = weights.iter().sum();
        if !(area > 0.0 && area.is_finite()) || points.len() != weights.len() {
            return None;
        }
        // Coordinates about the points' centroid, scaled to their spread, for a well-conditioned
        // Newton step.
        let mut mid = [0.0; 2];
        for (p, w) in points.iter().zip(weights) {
            mid[0] += w * p[0] / area;
            mid[1] += w * p[1] / area;
        }
        let scale = points
            .iter()
            .map(|p| (p[0] - mid[0]).hypot(p[1] - mid[1]))
            .fold(0.0, f64::max);
        if scale.is_nan() || scale <= 0.0 {
            return None;
        }
        // Points on one line (a base's edge lying on a face): the pressure is linear along it,
        // and the cross-line coordinate is dropped (the resultant is on the line too).
        let mut cov = nalgebra::Matrix2::zeros();
        for (p, w) in points.iter().zip(weights) {
            let d = nalgebra::Vector2::new(p[0] - mid[0], p[1] - mid[1]) / scale;
            cov += d * d.transpose() * (w / area);
        }
        // Its eigenvalues, the larger first.
        let (lam, q) = crate::numeric::symmetric_eigen2(&cov);
        let line = lam[1] <= 1e-12 * lam[0].max(1e-300);
        let mut bed = Bed {
            xi: Vec::with_capacity(points.len()),
            w: weights.iter().map(|w| w / area).collect(),
            mid,
            scale,
            along: line.then(|| q.column(0).into_owned()),
            all_pressed: Matrix3::identity(),
            last: Vector3::new(1.0, 0.0, 0.0),
        };
        bed.xi = points.iter().map(|p| bed.coords(*p)).collect();
        let mut hess = bed.hessian(|_| true);
        if line {
            hess[(2, 2)] = 1.0;
        }
        bed.all_pressed = hess.try_inverse()?;
        Some(bed)
    }

    /// (1, ξ, ζ) of plan point `p`.
    fn coords(&self, p: [f64; 2]) -> Vector3<f64> {
        let d = nalgebra::Vector2::new(p[0] - self.mid[0], p[1] - self.mid[1]) / self.scale;
        match self.along {
            Some(a) => Vector3::new(1.0, d.dot(&a), 0.0),
            None => Vector3::new(1.0, d[0], d[1]),
        }
    }

    /// Σ w (1, ξ)(1, ξ)ᵀ over the points `pressed` says.
    fn hessian(&self, pressed: impl Fn(usize) -> bool) -> Matrix3<f64> {
        let mut hess = Matrix3::zeros();
        for (k, (q, w)) in self.xi.iter().zip(&self.w).enumerate() {
            if pressed(k) {
                hess += q * q.transpose() * *w;
            }
        }
        hess
    }

    /// Φ at δ = x over the resultant `target`.
    fn phi(&self, x: &Vector3<f64>, target: &Vector3<f64>) -> f64 {
        self.xi
            .iter()
            .zip(&self.w)
            .map(|(q, w)| 0.5 * w * q.dot(x).max(0.0).powi(2))
            .sum::<f64>()
            - x.dot(target)
    }

    /// [`spread`] on this bed.
    pub fn spread(&mut self, total: f64, centre: [f64; 2], out: &mut Vec<f64>) -> bool {
        if !(total > 0.0 && total.is_finite()) {
            return false;
        }
        // The resultant per unit area, so that d is a pressure of order one.
        let target = self.coords(centre);
        // Every point pressed: one linear solve.
        let x = self.all_pressed * target;
        if self.xi.iter().all(|q| q.dot(&x) >= 0.0) {
            return self.share(&x, total, out);
        }
        let mut x = if self.last.iter().all(|v| v.is_finite()) {
            self.last
        } else {
            Vector3::new(1.0, 0.0, 0.0)
        };
        for _ in 0..100 {
            let mut grad = -target;
            for (q, w) in self.xi.iter().zip(&self.w) {
                grad += q * (w * q.dot(&x).max(0.0));
            }
            if grad.norm() <= 1e-13 {
                self.last = x;
                return self.share(&x, total, out);
            }
            let mut hess = self.hessian(|k| self.xi[k].dot(&x) > 0.0);
            if self.along.is_some() {
                // The third unknown is idle along a line.
                hess[(2, 2)] = 1.0;
            }
            let Some(step) = hess.lu().solve(&-grad) else {
                return false;
            };
            // Backtracking on Φ (convex, piecewise quadratic): the full step once the set of
            // pressed points is right.
            let (f0, slope) = (self.phi(&x, &target), grad.dot(&step));
            let mut t = 1.0;
            while self.phi(&(x + step * t), &target) > f0 + 1e-4 * t * slope && t > 1e-12 {
                t *= 0.5;
            }
            if t <= 1e-12 {
                return false;
            }
            x += step * t;
        }
        false
    }

    /// The shares of `total` at δ = x.
    fn share(&self, x: &Vector3<f64>, total: f64, out: &mut Vec<f64>) -> bool {
        let sum: f64 = self
            .xi
            .iter()
            .zip(&self.w)
            .map(|(q, w)| w * q.dot(x).max(0.0))
            .sum();
        if sum.is_nan() || sum <= 0.0 {
            return false;
        }
        out.clear();
        out.extend(
            self.xi
                .iter()
                .zip(&self.w)
                .map(|(q, w)| w * q.dot(x).max(0.0) * total / sum),
        );
        true
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::Base;

    /// A base B = 6 m (along x′) by 2 m: its quadrature.
    fn strip() -> (Vec<[f64; 2]>, Vec<f64>) {
        let b = Base::rectangle([-3.0, 3.0], [-1.0, 1.0], 0.0).unwrap();
        b.quadrature(12).into_iter().unzip()
    }

    /// The pressure (N/m²) the shares give at x′ by least squares on the pressed points: a
    /// linear function of x′ alone here (the resultant on the axis).
    fn pressure_line(points: &[[f64; 2]], weights: &[f64], shares: &[f64]) -> (f64, f64) {
        let (mut sx, mut sxx, mut sy, mut sxy, mut n) = (0.0, 0.0, 0.0, 0.0, 0.0);
        for ((p, w), s) in points.iter().zip(weights).zip(shares) {
            if *s > 1e-9 {
                let y = s / w;
                sx += p[0];
                sxx += p[0] * p[0];
                sy += y;
                sxy += p[0] * y;
                n += 1.0;
            }
        }
        let slope = (n * sxy - sx * sy) / (n * sxx - sx * sx);
        (slope, (sy - slope * sx) / n)
    }

    #[test]
    fn a_centred_resultant_presses_the_base_evenly() {
        let (p, w) = strip();
        let mut out = Vec::new();
        assert!(spread(&p, &w, 1.2e6, [0.0, 0.0], &mut out));
        for (s, w) in out.iter().zip(&w) {
            assert!((s / w - 1.2e6 / 12.0).abs() < 1e-6, "{}", s / w);
        }
    }

    #[test]
    fn a_resultant_within_the_middle_third_gives_the_trapezoid_n_over_a_plus_m_y_over_i() {
        // e = 0.5 m on B = 6 m: σ = N/A (1 ± 6e/B), 1.5 and 0.5 of N/A at the toe and heel.
        let (p, w) = strip();
        let mut out = Vec::new();
        assert!(spread(&p, &w, 12.0, [0.5, 0.0], &mut out));
        let (slope, at0) = pressure_line(&p, &w, &out);
        assert!((at0 - 1.0).abs() < 1e-9, "{at0}");
        assert!((slope * 3.0 - 0.5).abs() < 1e-9, "{slope}");
        assert!(out.iter().all(|s| *s > 0.0));
    }

    #[test]
    fn a_resultant_beyond_the_kern_cracks_the_base_to_three_times_its_distance_from_the_toe() {
        // e = 2 m on B = 6 m: the resultant is 1 m from the toe; the pressure is a triangle over
        // 3 m from the toe, its peak 2N/(3 m × 2 m) (the cracked base of gravity-dam design).
        let (p, w) = strip();
        let mut out = Vec::new();
        assert!(spread(&p, &w, 12.0, [2.0, 0.0], &mut out));
        let (slope, at0) = pressure_line(&p, &w, &out);
        let zero_at = -at0 / slope;
        let peak = at0 + slope * 3.0;
        // The quadrature resolves the crack to within its points' spacing (0.5 m / 12).
        assert!((zero_at - 0.0).abs() < 0.05, "crack at {zero_at}");
        assert!((peak - 2.0 * 12.0 / 6.0).abs() < 0.05 * 4.0, "peak {peak}");
        let pressed: f64 = out.iter().sum();
        let moment: f64 = out.iter().zip(&p).map(|(s, q)| s * q[0]).sum();
        assert!((pressed - 12.0).abs() < 1e-9 && (moment / pressed - 2.0).abs() < 1e-9);
        assert!(p.iter().zip(&out).all(|(q, s)| q[0] > -0.1 || *s == 0.0));
    }

    #[test]
    fn a_resultant_off_the_base_or_a_pull_has_no_pressure() {
        let (p, w) = strip();
        let mut out = vec![7.0];
        assert!(!spread(&p, &w, 12.0, [3.5, 0.0], &mut out));
        assert!(!spread(&p, &w, -1.0, [0.0, 0.0], &mut out));
        assert!(!spread(&p, &w, f64::NAN, [0.0, 0.0], &mut out));
        assert_eq!(out, vec![7.0]);
    }

    #[test]
    fn an_edge_lying_on_a_face_carries_a_pressure_linear_along_it() {
        // Ten points along a 4 m edge from (0, 0) towards (√8, √8), the resultant 1.5 m along
        // it (e = −½ m from the middle, inside the middle third): σ = N/L + N e ξ / I, with I
        // = Σ w ξ² the points' own second moment.
        let (len, n) = (4.0, 10);
        let dir = [0.5f64.sqrt(), 0.5f64.sqrt()];
        let points: Vec<[f64; 2]> = (0..n)
            .map(|k| {
                let s = (k as f64 + 0.5) * len / n as f64;
                [dir[0] * s, dir[1] * s]
            })
            .collect();
        let weights = vec![len / n as f64; n];
        let mut out = Vec::new();
        assert!(spread(
            &points,
            &weights,
            8.0,
            [dir[0] * 1.5, dir[1] * 1.5],
            &mut out
        ));
        let xi = |k: usize| (k as f64 + 0.5) * len / n as f64 - 2.0;
        let second: f64 = (0..n).map(|k| weights[k] * xi(k).powi(2)).sum();
        for (k, share) in out.iter().enumerate() {
            let p = 8.0 / len + 8.0 * -0.5 * xi(k) / second;
            assert!(
                (share / weights[k] - p).abs() < 1e-9,
                "{k}: {} against {p}",
                share / weights[k]
            );
        }
    }
}
