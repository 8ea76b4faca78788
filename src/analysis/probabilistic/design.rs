//! Every sample of a design run: the samples a fixed function of the seed (drawn a row at a
//! time, the values of a design drawn whole before any route runs), each sample's route
//! independent of every other and run by the one runner (`analysis/runner.rs`), the results kept in sample order — so they are the same for a seed
//! whatever the number of threads, and a range of the design run anywhere (another process,
//! another machine) gives the rows the whole run gives for that range.

use super::{Sampling, Uncertain, sample_rows, sample_scene, sample_values};
use crate::analysis::runner::{Outcome, run_chunked, run_many};
use crate::analysis::sweep::{KeyError, check_key, given_twice};
use crate::scene::Scene;

/// The most samples one design may have.
pub const MAX_SAMPLES: usize = 10_000_000;

pub use crate::analysis::runner::CHUNK;

/// One sample: its number in the design, its values, what it came to.
#[derive(Debug, Clone, PartialEq)]
pub struct Sample {
    /// Its number in the design, from 0.
    pub index: usize,
    /// The value of each uncertain key, in their order.
    pub values: Vec<f64>,
    /// What its route came to.
    pub outcome: Outcome,
}

/// A probabilistic analysis: a scene, its uncertain keys, and the design.
#[derive(Debug, Clone)]
pub struct Design<'a> {
    /// The scene whose keys are uncertain.
    pub scene: &'a Scene,
    /// The uncertain keys and their distributions, in the order of the samples' values.
    pub uncertain: &'a [Uncertain],
    /// How many samples.
    pub samples: usize,
    /// The seed they are drawn from.
    pub seed: u64,
    /// How they are drawn.
    pub sampling: Sampling,
}

impl Design<'_> {
    /// Every sample's values, in order.
    pub fn values(&self) -> Vec<Vec<f64>> {
        sample_values(self.uncertain, self.samples, self.seed, self.sampling)
    }

    /// Every sample, in order, run on every core where the `parallel` feature is on. `tick` is
    /// called after each sample; `stop` is asked before each (those it stops are
    /// [`Outcome::NotRun`]) and by routes under way, which end at their next increment.
    pub fn run(&self, tick: impl Fn() + Sync, stop: impl Fn() -> bool + Sync) -> Vec<Sample> {
        run_values(self.scene, self.uncertain, 0, self.values(), tick, stop)
    }

    /// Every sample, in order, as [`Design::run`] runs them, each handed to `each` as soon as
    /// it and those before it have run, holding at most [`CHUNK`] samples at a time (their
    /// values drawn as they are needed, [`sample_rows`]): memory does not grow with the number
    /// of samples. The first error of `each` ends the run and is returned; so does `stop`, after
    /// which the samples not run are handed on as [`Outcome::NotRun`].
    pub fn run_each<E>(
        &self,
        tick: impl Fn() + Sync,
        stop: impl Fn() -> bool + Sync,
        each: impl FnMut(Sample) -> Result<(), E>,
    ) -> Result<(), E> {
        run_chunked(
            sample_rows(self.uncertain, self.samples, self.seed, self.sampling),
            |first, chunk| run_values(self.scene, self.uncertain, first, chunk, &tick, &stop),
            each,
        )
    }
}

/// Each uncertain key a number of `scene` (or an optional number it may have), given once.
pub fn check_uncertain(scene: &Scene, uncertain: &[Uncertain]) -> Result<(), KeyError> {
    if let Some(key) = given_twice(uncertain.iter().map(|u| u.key.as_str())) {
        return Err(KeyError {
            key: key.to_string(),
            reason: "given twice".to_string(),
        });
    }
    for u in uncertain {
        check_key(scene, &u.key, false, &[])?;
        // A whole-number key (solver.stride) refuses a fraction: a distribution draws fractions.
        if check_key(scene, &u.key, false, &[0.5]).is_err() {
            return Err(KeyError {
                key: u.key.clone(),
                reason: "the key takes whole numbers, and a distribution draws fractions"
                    .to_string(),
            });
        }
    }
    Ok(())
}

/// The samples numbered `first`, `first + 1`, … with `values` (a range of a design's
/// [`Design::values`], or values from anywhere), in order.
pub fn run_values(
    scene: &Scene,
    uncertain: &[Uncertain],
    first: usize,
    values: Vec<Vec<f64>>,
    tick: impl Fn() + Sync,
    stop: impl Fn() -> bool + Sync,
) -> Vec<Sample> {
    let outcomes = run_many(&values, |v| sample_scene(scene, uncertain, v), tick, stop);
    values
        .into_iter()
        .zip(outcomes)
        .enumerate()
        .map(|(k, (values, outcome))| Sample {
            index: first + k,
            values,
            outcome,
        })
        .collect()
}
