//! The probabilistic analysis: distributions on any numeric scene key
//! (`numeric/distribution.rs`, below the scene so that a scene's `[uncertain]` table can name
//! them), designs of samples drawn whole from a seed (`sampling.rs`), each sample's scene (here),
//! every sample of a design run in order by the one runner (`design.rs`), the rank correlations
//! of inputs with results (`sensitivity.rs`), and what the samples come to (`summary.rs`).

mod design;
mod sampling;
mod sensitivity;
mod summary;

pub use crate::numeric::{Distribution, FORMS, Uncertain};
pub use design::{Design, MAX_SAMPLES, Sample, check_uncertain, run_values};
pub use sampling::{Sampling, design};
pub use sensitivity::{Sensitivity, sensitivities};
pub use summary::{Given, Limits, Percentiles, Probability, Summary, summarise};

use crate::scene::{Scene, SceneError};

/// The uncertain values of an analysis: a scene's `[uncertain]` table, then `given` (the
/// command line's, a caller's); a key of both takes `given`'s distribution.
pub fn merged(table: &[Uncertain], given: Vec<Uncertain>) -> Vec<Uncertain> {
    let mut all: Vec<Uncertain> = table
        .iter()
        .filter(|u| !given.iter().any(|g| g.key == u.key))
        .cloned()
        .collect();
    all.extend(given);
    all
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
    fn a_given_distribution_replaces_the_tables_and_the_others_follow_it() {
        let u = |t: &str| t.parse::<Uncertain>().unwrap();
        let table = [u("a.x=uniform:0:1"), u("b.y=uniform:0:1")];
        let all = merged(&table, vec![u("a.x=normal:0:1"), u("c.z=uniform:1:2")]);
        let keys: Vec<(&str, String)> = all
            .iter()
            .map(|v| (v.key.as_str(), v.distribution.to_string()))
            .collect();
        assert_eq!(
            keys,
            [
                ("b.y", "uniform:0:1".to_string()),
                ("a.x", "normal:0:1".to_string()),
                ("c.z", "uniform:1:2".to_string())
            ]
        );
        assert_eq!(merged(&table, vec![]), table.to_vec());
    }

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
