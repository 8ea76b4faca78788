//! Designs of uniforms in (0, 1)ⁿ: plain Monte Carlo, or a Latin hypercube (each
//! value's range cut into as many equally likely strata as there are samples, one sample in
//! each, the strata paired at random across values). A fixed function of the seed — drawn a row
//! at a time ([`Draws`]) as if drawn whole before any route runs —, so that the samples are the
//! same for a seed whatever the number of threads or machines that run them.

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

/// `samples` rows of `dims` uniforms in (0, 1), from `seed` ([`Draws`] collected).
#[cfg(test)]
pub fn design(samples: usize, dims: usize, seed: u64, sampling: Sampling) -> Vec<Vec<f64>> {
    Draws::new(samples, dims, seed, sampling).collect()
}

/// A uniform strictly inside (0, 1).
fn open(rng: &mut ChaCha8Rng) -> f64 {
    loop {
        let u: f64 = rng.random();
        if u > 0.0 {
            return u;
        }
    }
}

/// The rows of a design one at a time, the same as `design`'s, holding no row: plain Monte
/// Carlo holds only its generator; a Latin hypercube holds each value's pairing of the strata
/// (4 bytes a sample per value) and a generator per value, set where that value's points are
/// drawn, so that the values come out as the whole design draws them (every pairing first,
/// then each value's points in sample order, value after value).
pub struct Draws {
    samples: usize,
    next: usize,
    how: How,
}

enum How {
    MonteCarlo {
        rng: Box<ChaCha8Rng>,
        dims: usize,
    },
    /// Per value: its strata in sample order and the generator of its points.
    LatinHypercube(Vec<(Vec<u32>, ChaCha8Rng)>),
}

impl Draws {
    /// The design of `samples` rows of `dims` uniforms from `seed`. A Latin hypercube of more
    /// than 2³² samples is not drawn (no design may have that many: `MAX_SAMPLES`).
    pub fn new(samples: usize, dims: usize, seed: u64, sampling: Sampling) -> Draws {
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        let how = match sampling {
            Sampling::MonteCarlo => How::MonteCarlo {
                rng: Box::new(rng),
                dims,
            },
            Sampling::LatinHypercube => {
                let n = u32::try_from(samples).unwrap_or(u32::MAX);
                let values = (0..dims)
                    .map(|_| {
                        // A random pairing of the strata (Fisher–Yates), a random point in
                        // each: the pairing drawn, the generator kept where the points start,
                        // then moved past them to where the next value's pairing starts.
                        let mut strata: Vec<u32> = (0..n).collect();
                        for i in (1..strata.len()).rev() {
                            let j = rng.random_range(0..=i);
                            strata.swap(i, j);
                        }
                        let points = rng.clone();
                        for _ in 0..strata.len() {
                            open(&mut rng);
                        }
                        (strata, points)
                    })
                    .collect();
                How::LatinHypercube(values)
            }
        };
        Draws {
            samples,
            next: 0,
            how,
        }
    }
}

impl Iterator for Draws {
    type Item = Vec<f64>;

    fn next(&mut self) -> Option<Vec<f64>> {
        if self.next >= self.samples {
            return None;
        }
        let k = self.next;
        self.next += 1;
        let n = self.samples as f64;
        Some(match &mut self.how {
            How::MonteCarlo { rng, dims } => (0..*dims).map(|_| open(rng)).collect(),
            How::LatinHypercube(values) => values
                .iter_mut()
                .map(|(strata, rng)| {
                    ((f64::from(strata[k]) + open(rng)) / n).min(1.0 - f64::EPSILON)
                })
                .collect(),
        })
    }

    fn size_hint(&self) -> (usize, Option<usize>) {
        let left = self.samples - self.next;
        (left, Some(left))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The design as it was drawn whole (rows of every sample held) before [`Draws`].
    fn drawn_whole(samples: usize, dims: usize, seed: u64, sampling: Sampling) -> Vec<Vec<f64>> {
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        match sampling {
            Sampling::MonteCarlo => (0..samples)
                .map(|_| (0..dims).map(|_| open(&mut rng)).collect())
                .collect(),
            Sampling::LatinHypercube => {
                let mut rows = vec![vec![0.0; dims]; samples];
                for d in 0..dims {
                    let mut strata: Vec<usize> = (0..samples).collect();
                    for i in (1..samples).rev() {
                        let j = rng.random_range(0..=i);
                        strata.swap(i, j);
                    }
                    for (row, s) in rows.iter_mut().zip(strata) {
                        row[d] =
                            ((s as f64 + open(&mut rng)) / samples as f64).min(1.0 - f64::EPSILON);
                    }
                }
                rows
            }
        }
    }

    #[test]
    fn drawn_one_row_at_a_time_a_design_is_the_one_drawn_whole_bit_for_bit() {
        for sampling in [Sampling::MonteCarlo, Sampling::LatinHypercube] {
            for (samples, dims, seed) in
                [(0, 2, 1), (1, 3, 2), (97, 3, 7), (1000, 1, 42), (5, 0, 3)]
            {
                let whole = drawn_whole(samples, dims, seed, sampling);
                let drawn: Vec<Vec<f64>> = Draws::new(samples, dims, seed, sampling).collect();
                let bits = |v: &Vec<Vec<f64>>| -> Vec<Vec<u64>> {
                    v.iter()
                        .map(|r| r.iter().map(|x| x.to_bits()).collect())
                        .collect()
                };
                assert_eq!(
                    bits(&drawn),
                    bits(&whole),
                    "{sampling:?} {samples} {dims} {seed}"
                );
            }
        }
    }

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
