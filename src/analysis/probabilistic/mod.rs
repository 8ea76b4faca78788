//! The probabilistic analysis: distributions on any numeric scene key
//! (`numeric/distribution.rs`, below the scene so that a scene's `[uncertain]` table can name
//! them), designs of samples that are a fixed function of a seed (`sampling.rs`), each
//! sample's scene (here), every sample of a design run in order by the one runner
//! (`design.rs`), the rank correlations of inputs with results (`sensitivity.rs`), and what
//! the samples come to (`summary.rs`, from the bounded store of `columns.rs`).

mod columns;
mod design;
mod sampling;
mod sensitivity;
mod summary;

pub use crate::numeric::{Distribution, FORMS, Uncertain};
pub use columns::Columns;
pub use design::{CHUNK, Design, MAX_SAMPLES, Sample, check_uncertain, run_values};
pub use sampling::{Draws, Sampling};
pub use sensitivity::Sensitivity;
pub use summary::{Given, Limits, Percentiles, Probability, Summary, Tally, summarise};

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

/// The values of each sample, in the order of `uncertain`: the design's uniforms through each
/// key's quantile function, the design's dimensions taken by the keys in their sorted order
/// (by name), so that a seed gives each key the same values however the keys were given (a
/// scene's table, the command line, Python, Dask).
pub fn sample_values(
    uncertain: &[Uncertain],
    samples: usize,
    seed: u64,
    sampling: Sampling,
) -> Vec<Vec<f64>> {
    sample_rows(uncertain, samples, seed, sampling).collect()
}

/// [`sample_values`] one sample at a time, holding no sample's values but the one given (the
/// design drawn one row at a time).
pub fn sample_rows(
    uncertain: &[Uncertain],
    samples: usize,
    seed: u64,
    sampling: Sampling,
) -> impl Iterator<Item = Vec<f64>> + '_ {
    let mut sorted: Vec<usize> = (0..uncertain.len()).collect();
    sorted.sort_by(|&a, &b| uncertain[a].key.cmp(&uncertain[b].key));
    let mut dimension = vec![0; uncertain.len()];
    for (d, &k) in sorted.iter().enumerate() {
        dimension[k] = d;
    }
    Draws::new(samples, uncertain.len(), seed, sampling).map(move |row| {
        uncertain
            .iter()
            .zip(&dimension)
            .map(|(k, &d)| k.distribution.quantile(row[d]))
            .collect()
    })
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
    fn a_seed_gives_each_key_the_same_values_whatever_order_the_keys_come_in() {
        // The scene's table (sorted), --dist and Python (as given) must draw alike.
        let u = |key: &str, lo: f64| Uncertain {
            key: key.to_string(),
            distribution: Distribution::Uniform { lo, hi: lo + 1.0 },
        };
        let ab = [u("loads.eccentricity_m", 0.0), u("friction.mu_k", 0.2)];
        let ba = [ab[1].clone(), ab[0].clone()];
        for sampling in [Sampling::MonteCarlo, Sampling::LatinHypercube] {
            let x = sample_values(&ab, 50, 7, sampling);
            let y = sample_values(&ba, 50, 7, sampling);
            for (r, s) in x.iter().zip(&y) {
                assert_eq!((r[0], r[1]), (s[1], s[0]));
            }
        }
    }

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
    fn a_whole_number_key_is_refused_as_uncertain_before_any_sample_runs() {
        // `--dist solver.stride=uniform:1:5` ran every sample as an invalid scene and exited 0.
        let scene = crate::scene::Scene::default_scene();
        let u = |t: &str| t.parse::<Uncertain>().unwrap();
        let e = check_uncertain(&scene, &[u("solver.stride=uniform:1:5")]).unwrap_err();
        assert_eq!(e.key, "solver.stride");
        assert!(e.reason.contains("whole numbers"), "{}", e.reason);
        assert!(check_uncertain(&scene, &[u("friction.mu_k=uniform:0.3:0.5")]).is_ok());
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
