//! Every sample of a design run (issue #17): the samples drawn whole from the seed before any
//! route runs, each sample's route independent of every other, and the results kept in sample
//! order — so they are the same for a seed whatever the number of threads, and a range of the
//! design run anywhere (another process, another machine) gives the rows the whole run gives
//! for that range.

use super::{SampleResult, Sampling, Uncertain, run_sample, sample_values};
use crate::scene::Scene;

/// What one sample came to: its route, or why it has none.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
#[serde(tag = "outcome", rename_all = "kebab-case")]
pub enum Outcome {
    Route(SampleResult),
    /// The sampled values make no valid scene (the reason names the key).
    Invalid {
        reason: String,
    },
    /// Not run: the analysis was interrupted first.
    NotRun,
}

/// The reason written for a sample an interrupted analysis did not start.
pub const NOT_RUN: &str = "not run (interrupted)";

/// One sample: its number in the design, its values, what it came to.
#[derive(Debug, Clone, PartialEq)]
pub struct Sample {
    pub index: usize,
    pub values: Vec<f64>,
    pub outcome: Outcome,
}

/// A probabilistic analysis: a scene, its uncertain keys, and the design.
#[derive(Debug, Clone)]
pub struct Design<'a> {
    pub scene: &'a Scene,
    pub uncertain: &'a [Uncertain],
    pub samples: usize,
    pub seed: u64,
    pub sampling: Sampling,
}

impl Design<'_> {
    /// Every sample's values, in order.
    pub fn values(&self) -> Vec<Vec<f64>> {
        sample_values(self.uncertain, self.samples, self.seed, self.sampling)
    }

    /// Every sample, in order, run on every core where the `parallel` feature is on. `tick` is
    /// called after each sample; `stop` is asked before each (those it stops are
    /// [`Outcome::NotRun`]).
    pub fn run(&self, tick: impl Fn() + Sync, stop: impl Fn() -> bool + Sync) -> Vec<Sample> {
        run_values(self.scene, self.uncertain, 0, self.values(), tick, stop)
    }
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
    let one = |(k, values): (usize, Vec<f64>)| {
        let index = first + k;
        let outcome = if stop() {
            Outcome::NotRun
        } else {
            match run_sample(scene, uncertain, &values) {
                Ok(r) => Outcome::Route(r),
                Err(e) => Outcome::Invalid {
                    reason: e.to_string(),
                },
            }
        };
        tick();
        Sample {
            index,
            values,
            outcome,
        }
    };
    #[cfg(feature = "parallel")]
    {
        use rayon::prelude::*;
        values.into_par_iter().enumerate().map(one).collect()
    }
    #[cfg(not(feature = "parallel"))]
    {
        values.into_iter().enumerate().map(one).collect()
    }
}
