//! What the samples come to: the probability of sliding (factor of safety below 1; under a
//! ground-motion record, a permanent displacement) with its 95 % interval, the probabilities that
//! travel, rotation and a record's permanent displacement exceed the limits given,
//! percentiles, and each input's rank correlations — `probabilistic.json`.

use super::{Design, Sample, Sampling, Sensitivity, proportion, sensitivities};
use crate::analysis::runner::{Outcome, RouteResult};

/// A probability with its 95 % Wilson interval, over the samples whose route ran.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct Probability {
    /// The proportion.
    pub value: f64,
    /// Its 95 % Wilson score interval.
    pub ci95: [f64; 2],
}

/// `0.9400 (95 % interval 0.9235 to 0.9531)`, or `none (no route ran)`.
impl std::fmt::Display for Probability {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        if self.value.is_nan() {
            return f.write_str("none (no route ran)");
        }
        write!(
            f,
            "{:.4} (95 % interval {:.4} to {:.4})",
            self.value, self.ci95[0], self.ci95[1]
        )
    }
}

fn probability(k: usize, n: usize) -> Probability {
    let (value, (lo, hi)) = proportion(k, n);
    Probability {
        value,
        ci95: [lo, hi],
    }
}

/// Percentiles 5, 50, 95 of some values (linear between order statistics; infinite values
/// count, as the largest or smallest). Written as numbers, an infinite one as the factor of
/// safety's words (`"unbounded"`, `"not-holdable"`): a file holds no infinity.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct Percentiles {
    /// The 5th percentile.
    #[serde(serialize_with = "word_or_number")]
    pub p5: f64,
    /// The median.
    #[serde(serialize_with = "word_or_number")]
    pub p50: f64,
    /// The 95th percentile.
    #[serde(serialize_with = "word_or_number")]
    pub p95: f64,
}

/// A finite value as a number; +∞ as `"unbounded"` and −∞ as `"not-holdable"`, the words of a
/// factor of safety no multiple of the loads reaches or that the weight alone defeats (the
/// only percentiles that can be infinite); NaN, which percentiles leave out, as null.
fn word_or_number<S: serde::Serializer>(v: &f64, s: S) -> Result<S::Ok, S::Error> {
    if v.is_finite() {
        s.serialize_f64(*v)
    } else if *v == f64::INFINITY {
        s.serialize_str("unbounded")
    } else if *v == f64::NEG_INFINITY {
        s.serialize_str("not-holdable")
    } else {
        s.serialize_none()
    }
}

/// The percentiles of `v`, NaN left out; `None` if nothing is left.
pub fn percentiles(mut v: Vec<f64>) -> Option<Percentiles> {
    v.retain(|x| !x.is_nan());
    if v.is_empty() {
        return None;
    }
    v.sort_by(f64::total_cmp);
    let at = |q: f64| {
        let pos = q * (v.len() - 1) as f64;
        let (i, f) = (pos.floor() as usize, pos.fract());
        let j = (i + 1).min(v.len() - 1);
        if f == 0.0 || v[i] == v[j] {
            v[i]
        } else if v[i].is_infinite() || v[j].is_infinite() {
            // No line between them: the nearer order statistic.
            if f < 0.5 { v[i] } else { v[j] }
        } else {
            v[i] + f * (v[j] - v[i])
        }
    };
    Some(Percentiles {
        p5: at(0.05),
        p50: at(0.5),
        p95: at(0.95),
    })
}

/// One uncertain key as it was given.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct Given {
    /// The scene key.
    pub key: String,
    /// Its distribution, as written (`normal:0.4:0.05`).
    pub distribution: String,
}

/// Travel and rotation limits whose exceedance is asked for.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Limits {
    /// Travel (m).
    pub travel_m: Option<f64>,
    /// Size of the final yaw (degrees).
    pub rotation_deg: Option<f64>,
    /// The permanent displacement's length under a ground-motion record (m).
    pub displacement_m: Option<f64>,
}

impl Limits {
    /// Limits each finite and zero or more; else the name of the first that is not
    /// (`travel_limit_m`, `rotation_limit_deg`) and its value.
    pub fn new(
        travel_m: Option<f64>,
        rotation_deg: Option<f64>,
    ) -> Result<Limits, (&'static str, f64)> {
        for (name, l) in [
            ("travel_limit_m", travel_m),
            ("rotation_limit_deg", rotation_deg),
        ] {
            if let Some(l) = l.filter(|l| !(l.is_finite() && *l >= 0.0)) {
                return Err((name, l));
            }
        }
        Ok(Limits {
            travel_m,
            rotation_deg,
            displacement_m: None,
        })
    }

    /// The same limits with one on the permanent displacement under a record (m): finite and
    /// zero or more, else `displacement_limit_m` and its value.
    pub fn with_displacement(self, limit: Option<f64>) -> Result<Limits, (&'static str, f64)> {
        match limit {
            Some(l) if !(l.is_finite() && l >= 0.0) => Err(("displacement_limit_m", l)),
            _ => Ok(Limits {
                displacement_m: limit,
                ..self
            }),
        }
    }
}

/// `probabilistic.json`.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct Summary {
    /// The scene's name.
    pub scene: String,
    /// How many samples the design has.
    pub samples: usize,
    /// The seed they were drawn from.
    pub seed: u64,
    /// How they were drawn.
    pub sampling: Sampling,
    /// The uncertain keys and their distributions.
    pub distributions: Vec<Given>,
    /// Samples whose route ran.
    pub routes: usize,
    /// Samples whose values made no valid scene.
    pub invalid_samples: usize,
    /// Samples not run (the analysis was stopped first).
    pub not_run: usize,
    /// Whether the scene is shaken by a ground-motion record: then the block slides when the
    /// record moves it, whatever its static factor of safety.
    pub shaken: bool,
    /// Unshaken, the factor of safety below 1; under a record, a permanent displacement (the
    /// block slid and stayed off where it was); over the samples whose route ran.
    pub probability_of_sliding: Probability,
    /// The permanent displacement limit asked about (m), under a record.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub displacement_limit_m: Option<f64>,
    /// The permanent displacement's length over it, over the samples whose route ran.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub probability_displacement_exceeds_limit: Option<Probability>,
    /// Of the permanent displacement's length (m), under a record.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub permanent_displacement_m: Option<Percentiles>,
    /// The travel limit asked about (m).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub travel_limit_m: Option<f64>,
    /// The travel over it, over the samples whose route ran.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub probability_travel_exceeds_limit: Option<Probability>,
    /// The rotation limit asked about (degrees, of the final yaw's size).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub rotation_limit_deg: Option<f64>,
    /// The final yaw over it in size, over the samples whose route ran.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub probability_rotation_exceeds_limit: Option<Probability>,
    /// Of the factor of safety.
    pub factor_of_safety: Option<Percentiles>,
    /// Of the travel (m).
    pub travel_m: Option<Percentiles>,
    /// Of the final yaw's size.
    pub rotation_deg: Option<Percentiles>,
    /// Spearman's rank correlation of each uncertain value with the factor of safety and with
    /// the travel.
    pub rank_correlations: Vec<Sensitivity>,
}

/// What `samples` of `design` came to.
pub fn summarise(design: &Design, limits: Limits, samples: &[Sample]) -> Summary {
    let routes: Vec<&RouteResult> = samples.iter().filter_map(|s| s.outcome.route()).collect();
    let n = routes.len();
    let count = |f: &dyn Fn(&RouteResult) -> bool| routes.iter().filter(|r| f(r)).count();
    // A failed cone program counts as not sliding (its row says so).
    let fs = |r: &RouteResult| r.factor_of_safety_value().unwrap_or(f64::NAN);
    let keys: Vec<String> = design.uncertain.iter().map(|u| u.key.clone()).collect();
    let shaken = design.scene.record().is_some();
    let displaced = |r: &RouteResult| r.permanent_m().unwrap_or(0.0);
    Summary {
        scene: design.scene.name().to_string(),
        samples: design.samples,
        seed: design.seed,
        sampling: design.sampling,
        distributions: design
            .uncertain
            .iter()
            .map(|u| Given {
                key: u.key.clone(),
                distribution: u.distribution.to_string(),
            })
            .collect(),
        routes: n,
        invalid_samples: samples
            .iter()
            .filter(|s| matches!(s.outcome, Outcome::Invalid { .. }))
            .count(),
        not_run: samples
            .iter()
            .filter(|s| matches!(s.outcome, Outcome::NotRun))
            .count(),
        shaken,
        probability_of_sliding: if shaken {
            probability(count(&|r| displaced(r) > 0.0), n)
        } else {
            probability(count(&|r| fs(r) < 1.0), n)
        },
        displacement_limit_m: limits.displacement_m.filter(|_| shaken),
        probability_displacement_exceeds_limit: limits
            .displacement_m
            .filter(|_| shaken)
            .map(|l| probability(count(&|r| displaced(r) > l), n)),
        permanent_displacement_m: shaken
            .then(|| percentiles(routes.iter().map(|r| displaced(r)).collect()))
            .flatten(),
        travel_limit_m: limits.travel_m,
        probability_travel_exceeds_limit: limits
            .travel_m
            .map(|l| probability(count(&|r| r.travel_m > l), n)),
        rotation_limit_deg: limits.rotation_deg,
        probability_rotation_exceeds_limit: limits
            .rotation_deg
            .map(|l| probability(count(&|r| r.yaw_deg.abs() > l), n)),
        factor_of_safety: percentiles(routes.iter().map(|r| fs(r)).collect()),
        travel_m: percentiles(routes.iter().map(|r| r.travel_m).collect()),
        rotation_deg: percentiles(routes.iter().map(|r| r.yaw_deg.abs()).collect()),
        rank_correlations: sensitivities(&keys, samples),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_probability_says_its_interval_or_that_no_route_ran() {
        assert_eq!(
            probability(30, 100).to_string(),
            "0.3000 (95 % interval 0.2189 to 0.3958)"
        );
        assert_eq!(probability(0, 0).to_string(), "none (no route ran)");
    }

    #[test]
    fn a_limit_must_be_finite_and_zero_or_more() {
        assert!(Limits::new(Some(0.0), None).is_ok());
        assert_eq!(Limits::new(Some(-1.0), None), Err(("travel_limit_m", -1.0)));
        assert_eq!(
            Limits::new(Some(1.0), Some(f64::INFINITY)),
            Err(("rotation_limit_deg", f64::INFINITY))
        );
        assert!(Limits::new(None, Some(f64::NAN)).is_err());
    }

    #[test]
    fn percentiles_interpolate_between_order_statistics() {
        let p = percentiles((0..=100).map(f64::from).rev().collect()).unwrap();
        assert_eq!((p.p5, p.p50, p.p95), (5.0, 50.0, 95.0));
        let p = percentiles(vec![1.0, 3.0]).unwrap();
        assert_eq!(p.p50, 2.0);
        assert!(percentiles(vec![f64::NAN]).is_none());
        // An infinite factor of safety is the largest, not a hole.
        let p = percentiles(vec![1.0, 2.0, f64::INFINITY]).unwrap();
        assert_eq!((p.p50, p.p95), (2.0, f64::INFINITY));
        let p = percentiles(vec![f64::NEG_INFINITY, 1.0, 2.0]).unwrap();
        assert_eq!((p.p5, p.p50), (f64::NEG_INFINITY, 1.0));
        // Written with the factor of safety's words, never null or an infinity.
        let both = percentiles(vec![f64::NEG_INFINITY, 1.0, f64::INFINITY]).unwrap();
        assert_eq!(
            serde_json::to_string(&both).unwrap(),
            r#"{"p5":"not-holdable","p50":1.0,"p95":"unbounded"}"#
        );
    }
}
