//! Uncertain scene values (issue #17): distributions on any numeric scene key
//! (`numeric/distribution.rs`, so that a scene can name them), designs of samples drawn whole from a seed (`sampling.rs`), each
//! sample's scene and route (here), every sample of a design run in order (`analysis.rs`), the
//! rank correlations of inputs with results (`sensitivity.rs`), and what the samples come to
//! (`summary.rs`).

mod analysis;
mod sampling;
mod sensitivity;
mod summary;

pub use crate::numeric::{Distribution, FORMS, Uncertain};
pub use analysis::{Design, NOT_RUN, Outcome, Sample, run_values};
pub use sampling::{Sampling, design};
pub use sensitivity::{Sensitivity, sensitivities, spearman};
pub use summary::{Given, Limits, Percentiles, Probability, Summary, percentiles, summarise};

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

/// The most points of a sample's CM path kept ([`SampleResult::cm_path_m`]): enough to draw it
/// in a route fan, little enough that ten thousand samples keep ten megabytes.
pub const PATH_POINTS: usize = 64;

use crate::mechanics::static_friction::FactorOfSafety;
use crate::route::{Reason, run};
use crate::scene::{Scene, SceneError};

/// What one sample's route came to (its number and values are its [`Sample`]'s).
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct SampleResult {
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
    /// The CM path in plan, (X, Z) in m, thinned evenly to at most [`PATH_POINTS`] points (the
    /// first and last kept).
    #[serde(skip)]
    pub cm_path_m: Vec<[f64; 2]>,
}

/// At most `n` of `k` items, evenly spread, the first and last kept.
fn thin<T: Copy>(items: &[T], n: usize) -> Vec<T> {
    if items.len() <= n || n < 2 {
        return items.to_vec();
    }
    (0..n)
        .map(|i| items[(i * (items.len() - 1)).div_ceil(n - 1).min(items.len() - 1)])
        .collect()
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

/// The route of the sample with `values`.
pub fn run_sample(
    scene: &Scene,
    uncertain: &[Uncertain],
    values: &[f64],
) -> Result<SampleResult, SceneError> {
    route_result(&sample_scene(scene, uncertain, values)?)
}

/// What the route of `scene` comes to, as a sample's row has it (a sweep's combination too).
pub fn route_result(scene: &Scene) -> Result<SampleResult, SceneError> {
    let r = run(scene)?;
    let last = r.rows.last();
    Ok(SampleResult {
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
        cm_path_m: thin(
            &r.rows.iter().map(|r| [r.x_m, r.z_m]).collect::<Vec<_>>(),
            PATH_POINTS,
        ),
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
    fn a_thinned_path_keeps_its_ends_and_at_most_its_count() {
        let v: Vec<usize> = (0..1000).collect();
        let t = thin(&v, PATH_POINTS);
        assert_eq!(t.len(), PATH_POINTS);
        assert_eq!((t[0], *t.last().unwrap()), (0, 999));
        assert!(t.windows(2).all(|w| w[0] < w[1]));
        assert_eq!(thin(&v[..10], PATH_POINTS), v[..10].to_vec());
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
