//! Uncertain scene values (issue #17, in progress): distributions on any numeric scene key
//! (`distribution.rs`), designs of samples drawn whole from a seed (`sampling.rs`), and each
//! sample's scene and route (here).

mod distribution;
mod sampling;

pub use distribution::{Distribution, FORMS, Uncertain};
pub use sampling::{Sampling, design};

use crate::mechanics::static_friction::FactorOfSafety;
use crate::route::{Reason, run};
use crate::scene::{Scene, SceneError};

/// What one sample's route came to.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct SampleResult {
    /// The sample's number in the design.
    pub index: usize,
    /// The sampled values, in the order of the uncertain keys.
    pub values: Vec<f64>,
    /// The factor of safety at the start: +∞ where no multiple of the driving loads starts the
    /// block, −∞ where the weight alone does; absent only where its cone program failed.
    pub factor_of_safety: Option<f64>,
    /// How the route ended, and when (s).
    pub reason: Reason,
    pub t_s: f64,
    /// Travel (m), and the final position (m) and yaw (degrees).
    pub travel_m: f64,
    pub x_m: f64,
    pub z_m: f64,
    pub yaw_deg: f64,
}

/// The values of each sample: the design's uniforms through each key's quantile function.
pub fn sample_values(
    uncertain: &[Uncertain],
    samples: usize,
    seed: u64,
    sampling: Sampling,
) -> Vec<Vec<f64>> {
    design(samples, uncertain.len(), seed, sampling)
        .into_iter()
        .map(|row| {
            row.iter()
                .zip(uncertain)
                .map(|(&u, k)| k.distribution.quantile(u))
                .collect()
        })
        .collect()
}

/// The scene of one sample: `scene` with each uncertain key set to its value, checked as a
/// file would be (the error names the key).
pub fn sample_scene(
    scene: &Scene,
    uncertain: &[Uncertain],
    values: &[f64],
) -> Result<Scene, SceneError> {
    scene.with_keys(
        uncertain
            .iter()
            .map(|u| u.key.as_str())
            .zip(values.iter().copied()),
    )
}

/// The route of sample `index` with `values`.
pub fn run_sample(
    scene: &Scene,
    uncertain: &[Uncertain],
    index: usize,
    values: &[f64],
) -> Result<SampleResult, SceneError> {
    let s = sample_scene(scene, uncertain, values)?;
    let r = run(&s)?;
    let last = r.rows.last();
    Ok(SampleResult {
        index,
        values: values.to_vec(),
        factor_of_safety: r.factor_of_safety.map(|f| match f {
            FactorOfSafety::Finite { value } => value,
            FactorOfSafety::Unbounded => f64::INFINITY,
            FactorOfSafety::NotHoldable => f64::NEG_INFINITY,
        }),
        reason: r.termination.reason,
        t_s: r.termination.t_s,
        travel_m: r.travel_m,
        x_m: last.map_or(0.0, |l| l.x_m),
        z_m: last.map_or(0.0, |l| l.z_m),
        yaw_deg: last.map_or(0.0, |l| l.theta_deg),
    })
}

/// A proportion `k` of `n` and its 95 % Wilson score interval.
pub fn proportion(k: usize, n: usize) -> (f64, (f64, f64)) {
    if n == 0 {
        return (f64::NAN, (0.0, 1.0));
    }
    let (k, n) = (k as f64, n as f64);
    let p = k / n;
    let z = 1.959_963_984_540_054_f64;
    let denom = 1.0 + z * z / n;
    let centre = (p + z * z / (2.0 * n)) / denom;
    let half = z * (p * (1.0 - p) / n + z * z / (4.0 * n * n)).sqrt() / denom;
    (p, ((centre - half).max(0.0), (centre + half).min(1.0)))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_wilson_interval_holds_its_proportion_and_stays_in_zero_one() {
        let (p, (lo, hi)) = proportion(30, 100);
        assert_eq!(p, 0.3);
        // By hand: centre (0.3 + 1.9208/100)/1.038415, half 1.96 √(0.0021 + 0.0000960)/1.038415.
        assert!(
            (lo - 0.2189).abs() < 1e-3 && (hi - 0.3958).abs() < 1e-3,
            "{lo} {hi}"
        );
        let (_, (lo, hi)) = proportion(0, 10);
        assert_eq!(lo, 0.0);
        assert!(hi > 0.2 && hi < 0.35);
    }
}
