//! `slideroute probabilistic` (issue #17): uncertain scene values sampled from their
//! distributions, every sample's route run in parallel, and what they come to — the probability
//! of sliding with its 95 % interval, the probabilities of exceeding travel and rotation limits,
//! percentiles. The samples are drawn whole from the seed before any route runs and the rows are
//! kept in sample order, so the results are the same for a seed whatever the number of threads.

use rayon::prelude::*;
use serde::Serialize;
use slideroute::stages::scene::Scene;
use slideroute::stages::uncertainty::{
    SampleResult, Sampling, Uncertain, proportion, run_sample, sample_values,
};

/// What one sample came to: its route, or why it has none.
#[derive(Debug, Clone, PartialEq)]
pub enum Outcome {
    Route(SampleResult),
    /// The sampled values make no valid scene (the reason names the key).
    Invalid(String),
    /// Not run: the analysis was interrupted first.
    NotRun,
}

/// The reason of a sample an interrupted analysis did not start.
pub const NOT_RUN: &str = "not run (interrupted)";

/// Every sample, in order: (values, outcome). `tick` is called after each; `stop` is asked
/// before each.
pub fn run(
    base: &Scene,
    uncertain: &[Uncertain],
    (samples, seed, sampling): (usize, u64, Sampling),
    tick: impl Fn() + Sync,
    stop: impl Fn() -> bool + Sync,
) -> Vec<(Vec<f64>, Outcome)> {
    let values = sample_values(uncertain, samples, seed, sampling);
    values
        .into_par_iter()
        .enumerate()
        .map(|(k, v)| {
            let outcome = if stop() {
                Outcome::NotRun
            } else {
                match run_sample(base, uncertain, k, &v) {
                    Ok(r) => Outcome::Route(r),
                    Err(e) => Outcome::Invalid(e.to_string()),
                }
            };
            tick();
            (v, outcome)
        })
        .collect()
}

/// A probability with its 95 % Wilson interval, over the samples that ran.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Probability {
    pub value: f64,
    pub ci95: [f64; 2],
}

fn probability(k: usize, n: usize) -> Probability {
    let (value, (lo, hi)) = proportion(k, n);
    Probability {
        value,
        ci95: [lo, hi],
    }
}

/// Percentiles 5, 50, 95 of some values (linear between order statistics).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Percentiles {
    pub p5: f64,
    pub p50: f64,
    pub p95: f64,
}

fn percentiles(mut v: Vec<f64>) -> Option<Percentiles> {
    v.retain(|x| x.is_finite());
    if v.is_empty() {
        return None;
    }
    v.sort_by(f64::total_cmp);
    let at = |q: f64| {
        let pos = q * (v.len() - 1) as f64;
        let (i, f) = (pos.floor() as usize, pos.fract());
        let j = (i + 1).min(v.len() - 1);
        v[i] + f * (v[j] - v[i])
    };
    Some(Percentiles {
        p5: at(0.05),
        p50: at(0.5),
        p95: at(0.95),
    })
}

/// One uncertain key as it was given.
#[derive(Debug, Clone, Serialize)]
pub struct Given {
    pub key: String,
    pub distribution: String,
}

/// `probabilistic.json`.
#[derive(Debug, Clone, Serialize)]
pub struct Summary {
    pub scene: String,
    pub samples: usize,
    pub seed: u64,
    pub sampling: Sampling,
    pub distributions: Vec<Given>,
    /// Samples whose route ran, whose values made no valid scene, and that were not run.
    pub routes: usize,
    pub invalid_samples: usize,
    pub not_run: usize,
    /// Factor of safety below 1, over the samples whose route ran.
    pub probability_of_sliding: Probability,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub travel_limit_m: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub probability_travel_exceeds_limit: Option<Probability>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub rotation_limit_deg: Option<f64>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub probability_rotation_exceeds_limit: Option<Probability>,
    pub factor_of_safety: Option<Percentiles>,
    pub travel_m: Option<Percentiles>,
    /// Of the final yaw's size.
    pub rotation_deg: Option<Percentiles>,
}

/// What the samples came to.
pub fn summarise(
    base: &Scene,
    given: (&[Uncertain], &[String]),
    (samples, seed, sampling): (usize, u64, Sampling),
    (travel_limit, rotation_limit): (Option<f64>, Option<f64>),
    rows: &[(Vec<f64>, Outcome)],
) -> Summary {
    let routes: Vec<&SampleResult> = rows
        .iter()
        .filter_map(|(_, o)| match o {
            Outcome::Route(r) => Some(r),
            _ => None,
        })
        .collect();
    let n = routes.len();
    let count = |f: &dyn Fn(&SampleResult) -> bool| routes.iter().filter(|r| f(r)).count();
    // A failed cone program counts as not sliding (its row says so).
    let fs = |r: &SampleResult| r.factor_of_safety.unwrap_or(f64::NAN);
    Summary {
        scene: base.name().to_string(),
        samples,
        seed,
        sampling,
        distributions: given
            .0
            .iter()
            .zip(given.1)
            .map(|(u, text)| Given {
                key: u.key.clone(),
                distribution: text
                    .split_once('=')
                    .map_or(text.as_str(), |(_, d)| d)
                    .to_string(),
            })
            .collect(),
        routes: n,
        invalid_samples: rows
            .iter()
            .filter(|(_, o)| matches!(o, Outcome::Invalid(_)))
            .count(),
        not_run: rows
            .iter()
            .filter(|(_, o)| matches!(o, Outcome::NotRun))
            .count(),
        probability_of_sliding: probability(count(&|r| fs(r) < 1.0), n),
        travel_limit_m: travel_limit,
        probability_travel_exceeds_limit: travel_limit
            .map(|l| probability(count(&|r| r.travel_m > l), n)),
        rotation_limit_deg: rotation_limit,
        probability_rotation_exceeds_limit: rotation_limit
            .map(|l| probability(count(&|r| r.yaw_deg.abs() > l), n)),
        factor_of_safety: percentiles(routes.iter().map(|r| fs(r)).collect()),
        travel_m: percentiles(routes.iter().map(|r| r.travel_m).collect()),
        rotation_deg: percentiles(routes.iter().map(|r| r.yaw_deg.abs()).collect()),
    }
}

/// `samples.csv`: one row per sample, in order.
pub fn write_csv(
    out: impl std::io::Write,
    uncertain: &[Uncertain],
    rows: &[(Vec<f64>, Outcome)],
) -> Result<(), csv::Error> {
    let mut w = csv::Writer::from_writer(out);
    let mut header = vec!["sample".to_string()];
    header.extend(uncertain.iter().map(|u| u.key.clone()));
    header.extend(
        [
            "factor_of_safety",
            "reason",
            "t_end_s",
            "travel_m",
            "final_yaw_deg",
            "final_x_m",
            "final_z_m",
            "detail",
        ]
        .map(String::from),
    );
    w.write_record(&header)?;
    for (k, (values, outcome)) in rows.iter().enumerate() {
        let mut rec = vec![k.to_string()];
        rec.extend(values.iter().map(|v| v.to_string()));
        match outcome {
            Outcome::Route(r) => rec.extend([
                r.factor_of_safety.map_or(String::new(), |f| f.to_string()),
                r.reason.as_str().to_string(),
                r.t_s.to_string(),
                r.travel_m.to_string(),
                r.yaw_deg.to_string(),
                r.x_m.to_string(),
                r.z_m.to_string(),
                String::new(),
            ]),
            Outcome::Invalid(why) => {
                rec.extend(["", "invalid scene", "", "", "", "", ""].map(String::from));
                rec.push(why.clone());
            }
            Outcome::NotRun => {
                rec.extend(["", NOT_RUN, "", "", "", "", "", ""].map(String::from));
            }
        }
        w.write_record(&rec)?;
    }
    w.flush()?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn percentiles_interpolate_between_order_statistics() {
        let p = percentiles((0..=100).map(f64::from).rev().collect()).unwrap();
        assert_eq!((p.p5, p.p50, p.p95), (5.0, 50.0, 95.0));
        let p = percentiles(vec![1.0, 3.0]).unwrap();
        assert_eq!(p.p50, 2.0);
        assert!(percentiles(vec![f64::INFINITY]).is_none());
    }
}
