//! Designs of uniforms in (0, 1)ⁿ: plain Monte Carlo, or a Latin hypercube (each
//! value's range cut into as many equally likely strata as there are samples, one sample in
//! each, the strata paired at random across values). Drawn whole from the seed before any route
//! runs, so that the samples are the same for a seed whatever the number of threads or machines
//! that run them.

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// How the samples are drawn.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Sampling {
    /// Independent uniforms.
    #[serde(rename = "mc")]
    MonteCarlo,
    /// A Latin hypercube.
    #[default]
    #[serde(rename = "lhs")]
    LatinHypercube,
}

crate::model::names::named!(Sampling, "sampling", [LatinHypercube => "lhs", MonteCarlo => "mc"]);

/// `samples` rows of `dims` uniforms in (0, 1), from `seed`.
pub fn design(samples: usize, dims: usize, seed: u64, sampling: Sampling) -> Vec<Vec<f64>> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    // A uniform strictly inside (0, 1).
    let open = |rng: &mut ChaCha8Rng| loop {
        let u: f64 = rng.random();
        if u > 0.0 {
            return u;
        }
    };
    match sampling {
        Sampling::MonteCarlo => (0..samples)
            .map(|_| (0..dims).map(|_| open(&mut rng)).collect())
            .collect(),
        Sampling::LatinHypercube => {
            let mut rows = vec![vec![0.0; dims]; samples];
            for d in 0..dims {
                // A random pairing of the strata (Fisher–Yates), a random point in each.
                let mut strata: Vec<usize> = (0..samples).collect();
                for i in (1..samples).rev() {
                    let j = rng.random_range(0..=i);
                    strata.swap(i, j);
                }
                for (row, s) in rows.iter_mut().zip(strata) {
                    row[d] = ((s as f64 + open(&mut rng)) / samples as f64).min(1.0 - f64::EPSILON);
                }
            }
            rows
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_latin_hypercube_has_one_sample_in_each_stratum_of_each_value() {
        let n = 97;
        let rows = design(n, 3, 7, Sampling::LatinHypercube);
        for d in 0..3 {
            let mut seen = vec![false; n];
            for r in &rows {
                assert!(r[d] > 0.0 && r[d] < 1.0);
                let s = (r[d] * n as f64) as usize;
                assert!(!seen[s], "stratum {s} twice");
                seen[s] = true;
            }
        }
    }

    #[test]
    fn a_design_is_the_same_for_a_seed_and_differs_between_seeds() {
        for sampling in [Sampling::MonteCarlo, Sampling::LatinHypercube] {
            let a = design(50, 2, 7, sampling);
            assert_eq!(a, design(50, 2, 7, sampling));
            assert_ne!(a, design(50, 2, 8, sampling));
            assert!(a.iter().flatten().all(|&u| u > 0.0 && u < 1.0));
        }
        // Plain Monte Carlo: the mean of many uniforms is ½ to within a few standard errors.
        let m = design(10_000, 1, 1, Sampling::MonteCarlo);
        let mean = m.iter().map(|r| r[0]).sum::<f64>() / 1e4;
        assert!(
            (mean - 0.5).abs() < 4.0 * (1.0 / 12.0f64 / 1e4).sqrt(),
            "{mean}"
        );
    }
}
