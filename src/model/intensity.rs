//! What a ground-motion record's shaking measures, as a Newmark engineer reports it
//! (`derivations/11-dam-loads.md` §7): the peak ground acceleration and velocity, the Arias
//! intensity and the significant duration D5–95, per component along the scene's X, Y, Z.
//!
//! All exact for the record as the route takes it, linear between samples: over a sample
//! interval Δt from a₀ to a₁ the velocity gains Δt (a₀ + a₁)/2, and ∫a² dt is
//! Δt (a₀² + a₀a₁ + a₁²)/3, a cubic in time within the interval, inverted there for the times
//! at 5 % and 95 % of the whole. The velocity is the acceleration's integral from rest at the
//! first sample, without a baseline correction (a processed record, such as the NGA database's,
//! ends near rest).

use super::Record;
use serde::Serialize;

/// Per component along X, Y, Z.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Intensity {
    /// Peak ground acceleration, the largest |a| at a sample (g).
    pub pga_g: [f64; 3],
    /// Peak ground velocity, the largest |v| (m/s).
    pub pgv_m_s: [f64; 3],
    /// Arias intensity, π/(2g) ∫ a² dt (m/s).
    pub arias_m_s: [f64; 3],
    /// Significant duration: from 5 % to 95 % of the Arias intensity (s; zero without shaking).
    pub d5_95_s: [f64; 3],
}

impl Intensity {
    /// The measures of `record` with gravity `g` (m/s²).
    pub fn of(record: &Record, g: f64) -> Intensity {
        let (t, a) = record.samples();
        let mut out = Intensity {
            pga_g: [0.0; 3],
            pgv_m_s: [0.0; 3],
            arias_m_s: [0.0; 3],
            d5_95_s: [0.0; 3],
        };
        for c in 0..3 {
            let a: Vec<f64> = a.iter().map(|s| s[c] * g).collect();
            out.pga_g[c] = a.iter().fold(0.0, |m: f64, v| m.max(v.abs())) / g;
            let mut v: f64 = 0.0;
            // Cumulative ∫a² dt at each sample.
            let mut cumulative = vec![0.0; t.len()];
            for k in 1..t.len() {
                let (dt, a0, a1) = (t[k] - t[k - 1], a[k - 1], a[k]);
                // Within the interval v is a quadratic; its peak where a crosses zero.
                if a0 * a1 < 0.0 {
                    let s = a0 / (a0 - a1);
                    let at_zero = v + dt * s * a0 / 2.0;
                    out.pgv_m_s[c] = out.pgv_m_s[c].max(at_zero.abs());
                }
                v += dt * (a0 + a1) / 2.0;
                out.pgv_m_s[c] = out.pgv_m_s[c].max(v.abs());
                cumulative[k] = cumulative[k - 1] + dt * (a0 * a0 + a0 * a1 + a1 * a1) / 3.0;
            }
            let total = cumulative[t.len() - 1];
            out.arias_m_s[c] = std::f64::consts::PI / (2.0 * g) * total;
            if total > 0.0 {
                let when = |f: f64| time_at(t, &a, &cumulative, f * total);
                out.d5_95_s[c] = when(0.95) - when(0.05);
            }
        }
        out
    }
}

/// The time at which ∫a² dt reaches `level` (≤ the whole): in the interval where the
/// cumulative passes it, the cubic a₀²s + a₀(a₁ − a₀)s² + (a₁ − a₀)²s³/3 (times Δt) solved by
/// bisection, which it is monotone for.
fn time_at(t: &[f64], a: &[f64], cumulative: &[f64], level: f64) -> f64 {
    let k = cumulative
        .partition_point(|&c| c < level)
        .clamp(1, t.len() - 1);
    let (dt, a0, a1) = (t[k] - t[k - 1], a[k - 1], a[k]);
    let d = a1 - a0;
    let within = |s: f64| dt * (a0 * a0 * s + a0 * d * s * s + d * d * s * s * s / 3.0);
    let need = level - cumulative[k - 1];
    let (mut lo, mut hi) = (0.0, 1.0);
    for _ in 0..60 {
        let mid = 0.5 * (lo + hi);
        if within(mid) < need {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    t[k - 1] + 0.5 * (lo + hi) * dt
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A triangle along X: 0 at t = 0, `peak` g at T, 0 at 2T; a constant `lift` g along Y.
    fn triangle(peak: f64, half: f64, lift: f64) -> Record {
        Record::new(vec![
            (0.0, [0.0, lift, 0.0]),
            (half, [peak, lift, 0.0]),
            (2.0 * half, [0.0, lift, 0.0]),
        ])
        .unwrap()
    }

    #[test]
    fn a_triangle_of_acceleration_has_the_closed_form_velocity_arias_intensity_and_duration() {
        let (peak, half, g) = (0.4, 0.5, 9.81);
        let m = Intensity::of(&triangle(peak, half, 0.0), g);
        let a = peak * g;
        assert_eq!(m.pga_g, [peak, 0.0, 0.0]);
        // The velocity at the end is the triangle's area, A g T.
        assert!((m.pgv_m_s[0] - a * half).abs() < 1e-12, "{:?}", m.pgv_m_s);
        // π/(2g) (A g)² 2T/3.
        let arias = std::f64::consts::PI / (2.0 * g) * a * a * 2.0 * half / 3.0;
        assert!((m.arias_m_s[0] - arias).abs() < 1e-12 * arias);
        // ∫₀ᵗ (A g s/T)² ds = (A g)² t³/(3T²) reaches 5 % of the whole at t = 0.1^(1/3) T, and
        // 95 % as far before 2T: D5–95 = 2T (1 − 0.1^(1/3)).
        let d = 2.0 * half * (1.0 - 0.1f64.cbrt());
        assert!(
            (m.d5_95_s[0] - d).abs() < 1e-12,
            "{} against {d}",
            m.d5_95_s[0]
        );
        assert_eq!(
            (m.pgv_m_s[2], m.arias_m_s[2], m.d5_95_s[2]),
            (0.0, 0.0, 0.0)
        );
    }

    #[test]
    fn a_constant_acceleration_spreads_its_intensity_evenly_and_a_sign_change_peaks_the_velocity() {
        let (g, half) = (9.81, 0.5);
        let m = Intensity::of(&triangle(0.0, half, -0.2), g);
        // Constant over 2T: v = a t, D5–95 = 0.9 · 2T.
        assert!((m.pgv_m_s[1] - 0.2 * g * 2.0 * half).abs() < 1e-12);
        assert!((m.d5_95_s[1] - 0.9 * 2.0 * half).abs() < 1e-12);
        // +a for 1 s then −a for 1 s, linear between: v peaks where a crosses zero, at
        // a·1 s + a·(crossing half-interval)/2.
        let r = Record::new(vec![
            (0.0, [0.1, 0.0, 0.0]),
            (1.0, [0.1, 0.0, 0.0]),
            (1.2, [-0.1, 0.0, 0.0]),
            (2.2, [-0.1, 0.0, 0.0]),
        ])
        .unwrap();
        let m = Intensity::of(&r, g);
        let peak = 0.1 * g * (1.0 + 0.1 / 2.0);
        assert!(
            (m.pgv_m_s[0] - peak).abs() < 1e-12,
            "{} {peak}",
            m.pgv_m_s[0]
        );
    }
}
