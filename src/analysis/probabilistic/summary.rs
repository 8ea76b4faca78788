//! What the samples come to: the probability of sliding (factor of safety below 1; under a
//! ground-motion record, a permanent displacement) with its 95 % interval, the probabilities that
//! travel, rotation and a record's permanent displacement exceed the limits given,
//! percentiles, and each input's rank correlations — `probabilistic.json`.

use super::{Columns, Design, Sample, Sampling, Sensitivity, proportion};
use crate::analysis::runner::Outcome;

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

/// What `samples` of `design` came to (a [`Tally`] of them, held in memory).
pub fn summarise(design: &Design, limits: Limits, samples: &[Sample]) -> Summary {
    let mut tally = Tally::new(design, limits, None).with_in_memory_rows(samples.len());
    // Held in memory, the tally has no file to fail on.
    samples
        .iter()
        .try_for_each(|s| tally.add(s))
        .and_then(|()| tally.finish())
        .expect("a tally held in memory does not fail")
}

/// What the samples of a design come to, taken one at a time in the design's order
/// ([`Tally::add`]) and summed up by [`Tally::finish`]: the counts as the samples come, and each
/// route's values (the sample's values, factor of safety, travel, yaw, permanent displacement)
/// in [`Columns`], which hold a bounded number in memory and the rest in a temporary file, so
/// that the percentiles and rank correlations are exact for any number of samples in a few tens
/// of MB.
pub struct Tally {
    head: Summary,
    limits: Limits,
    keys: usize,
    /// Sliding, over the displacement, travel and rotation limits.
    counts: [usize; 4],
    columns: Columns,
}

impl Tally {
    /// An empty tally of `design`'s samples; a temporary file, if needed, made in `spill_in`
    /// (else the system's temporary folder).
    pub fn new(design: &Design, limits: Limits, spill_in: Option<std::path::PathBuf>) -> Tally {
        let keys = design.uncertain.len();
        let shaken = design.scene.record().is_some();
        let head = Summary {
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
            routes: 0,
            invalid_samples: 0,
            not_run: 0,
            shaken,
            probability_of_sliding: probability(0, 0),
            displacement_limit_m: limits.displacement_m.filter(|_| shaken),
            probability_displacement_exceeds_limit: None,
            permanent_displacement_m: None,
            travel_limit_m: limits.travel_m,
            probability_travel_exceeds_limit: None,
            rotation_limit_deg: limits.rotation_deg,
            probability_rotation_exceeds_limit: None,
            factor_of_safety: None,
            travel_m: None,
            rotation_deg: None,
            rank_correlations: design
                .uncertain
                .iter()
                .map(|u| Sensitivity {
                    key: u.key.clone(),
                    with_factor_of_safety: None,
                    with_travel: None,
                })
                .collect(),
        };
        Tally {
            head,
            limits,
            keys,
            counts: [0; 4],
            columns: Columns::new(keys + 4, spill_in),
        }
    }

    /// The same tally holding up to `rows` routes in memory.
    pub fn with_in_memory_rows(self, rows: usize) -> Tally {
        Tally {
            columns: self.columns.with_in_memory_rows(rows),
            ..self
        }
    }

    /// Its summing up asks `stop` every 65 536 routes and ends with an error of kind
    /// `Interrupted` when it says so ([`Columns::stop_when`]).
    pub fn stop_when(&mut self, stop: fn() -> bool) {
        self.columns.stop_when(stop);
    }

    /// Takes the next sample.
    pub fn add(&mut self, sample: &Sample) -> std::io::Result<()> {
        let r = match &sample.outcome {
            Outcome::Route(r) => r,
            Outcome::Invalid { .. } => {
                self.head.invalid_samples += 1;
                return Ok(());
            }
            Outcome::NotRun => {
                self.head.not_run += 1;
                return Ok(());
            }
        };
        self.head.routes += 1;
        // A failed cone program counts as not sliding (its row says so).
        let fs = r.factor_of_safety_value().unwrap_or(f64::NAN);
        let displaced = r.permanent_m().unwrap_or(0.0);
        let sliding = if self.head.shaken {
            displaced > 0.0
        } else {
            fs < 1.0
        };
        let over = [
            sliding,
            self.head.shaken && self.limits.displacement_m.is_some_and(|l| displaced > l),
            self.limits.travel_m.is_some_and(|l| r.travel_m > l),
            self.limits
                .rotation_deg
                .is_some_and(|l| r.yaw_deg.abs() > l),
        ];
        for (c, o) in self.counts.iter_mut().zip(over) {
            *c += usize::from(o);
        }
        let mut row = Vec::with_capacity(self.keys + 4);
        row.extend(sample.values.iter().take(self.keys));
        row.resize(self.keys, f64::NAN);
        row.extend([fs, r.travel_m, r.yaw_deg.abs(), displaced]);
        self.columns.push(&row)
    }

    /// The samples' factor of safety, in order, of each route that ran (NaN where its cone
    /// program failed): `each` called with every one.
    pub fn factors_of_safety(&self, mut each: impl FnMut(f64)) -> std::io::Result<()> {
        let c = self.keys;
        self.columns.scan(|row| each(row[c]))
    }

    /// What the samples came to.
    pub fn finish(&self) -> std::io::Result<Summary> {
        let mut s = self.head.clone();
        let n = s.routes;
        let [sliding, over_displacement, over_travel, over_rotation] = self.counts;
        let (fs, travel, rotation, displaced) =
            (self.keys, self.keys + 1, self.keys + 2, self.keys + 3);
        s.probability_of_sliding = probability(sliding, n);
        s.probability_displacement_exceeds_limit = s
            .displacement_limit_m
            .map(|_| probability(over_displacement, n));
        s.probability_travel_exceeds_limit = s.travel_limit_m.map(|_| probability(over_travel, n));
        s.probability_rotation_exceeds_limit =
            s.rotation_limit_deg.map(|_| probability(over_rotation, n));
        if s.shaken {
            s.permanent_displacement_m = self.columns.percentiles(displaced)?;
        }
        s.factor_of_safety = self.columns.percentiles(fs)?;
        s.travel_m = self.columns.percentiles(travel)?;
        s.rotation_deg = self.columns.percentiles(rotation)?;
        for (k, c) in s.rank_correlations.iter_mut().enumerate() {
            c.with_factor_of_safety = self.columns.spearman(k, fs)?;
            c.with_travel = self.columns.spearman(k, travel)?;
        }
        Ok(s)
    }
}

#[cfg(test)]
mod tests {
    use super::super::columns::tests::uniforms;
    use super::super::sensitivity::sensitivities;
    use super::*;
    use crate::analysis::runner::RouteResult;
    use crate::mechanics::static_friction::FactorOfSafety;
    use crate::route::Reason;
    use crate::scene::Scene;

    /// Samples of every kind from a fixed sequence: routes with finite, infinite and failed
    /// factors of safety, ties in travel, invalid and not run.
    fn mixed(n: usize) -> Vec<Sample> {
        let mut next = uniforms(0x2545_f491_4f6c_dd1d);
        (0..n)
            .map(|index| {
                let (a, b) = (next(), next());
                let outcome = match index % 11 {
                    3 => Outcome::Invalid { reason: "x".into() },
                    7 => Outcome::NotRun,
                    k => Outcome::Route(RouteResult {
                        factor_of_safety: match k {
                            1 => Some(FactorOfSafety::Unbounded),
                            2 => Some(FactorOfSafety::NotHoldable),
                            5 => None,
                            _ => Some(FactorOfSafety::Finite {
                                value: 0.5 + a + 0.2 * b,
                            }),
                        },
                        reason: Reason::Stopped,
                        t_s: 1.0,
                        detail: String::new(),
                        // Ties: travel on a grid of 0.25 m.
                        travel_m: (8.0 * a * b).round() / 4.0,
                        x_m: 0.0,
                        z_m: 0.0,
                        yaw_deg: 10.0 * (b - 0.5),
                        max_alpha_deg: 0.0,
                        max_beta_deg: 0.0,
                        permanent_xz_m: Some([a, b]),
                        cm_path_m: Vec::new(),
                    }),
                };
                Sample {
                    index,
                    values: vec![a, b],
                    outcome,
                }
            })
            .collect()
    }

    #[test]
    fn a_tally_past_its_memory_comes_to_the_percentiles_and_correlations_of_every_value_held() {
        let scene = Scene::default_scene();
        let uncertain: Vec<crate::numeric::Uncertain> = [
            "friction.mu_k=uniform:0.3:0.5",
            "loads.eccentricity_m=uniform:0.5:1.5",
        ]
        .map(|u| u.parse().unwrap())
        .to_vec();
        let design = Design {
            scene: &scene,
            uncertain: &uncertain,
            samples: 700,
            seed: 1,
            sampling: Sampling::MonteCarlo,
        };
        let samples = mixed(700);
        let limits = Limits::new(Some(0.5), Some(2.0)).unwrap();
        // Held whole, the old way: every value in a list.
        let routes: Vec<&RouteResult> = samples.iter().filter_map(|s| s.outcome.route()).collect();
        let fs = |r: &&RouteResult| r.factor_of_safety_value().unwrap_or(f64::NAN);
        let want_fs = percentiles(routes.iter().map(fs).collect());
        let want_travel = percentiles(routes.iter().map(|r| r.travel_m).collect());
        let want_rotation = percentiles(routes.iter().map(|r| r.yaw_deg.abs()).collect());
        let keys = [
            "friction.mu_k".to_string(),
            "loads.eccentricity_m".to_string(),
        ];
        let want_rho = sensitivities(&keys, &samples);
        for rows in [1, 16, 100, 10_000] {
            let mut tally = Tally::new(&design, limits, None).with_in_memory_rows(rows);
            for s in &samples {
                tally.add(s).unwrap();
            }
            let got = tally.finish().unwrap();
            assert_eq!(got.routes, routes.len());
            assert_eq!((got.invalid_samples, got.not_run), (64, 63));
            assert_eq!(got.factor_of_safety, want_fs, "{rows}");
            assert_eq!(got.travel_m, want_travel, "{rows}");
            assert_eq!(got.rotation_deg, want_rotation, "{rows}");
            assert_eq!(
                got.probability_of_sliding,
                probability(routes.iter().filter(|r| fs(r) < 1.0).count(), routes.len())
            );
            assert_eq!(
                got.probability_travel_exceeds_limit,
                Some(probability(
                    routes.iter().filter(|r| r.travel_m > 0.5).count(),
                    routes.len()
                ))
            );
            for (g, w) in got.rank_correlations.iter().zip(&want_rho) {
                let near = |a: Option<f64>, b: Option<f64>| match (a, b) {
                    (Some(a), Some(b)) => (a - b).abs() < 1e-12,
                    (a, b) => a.is_none() && b.is_none(),
                };
                assert!(
                    near(g.with_factor_of_safety, w.with_factor_of_safety),
                    "{g:?} {w:?}"
                );
                assert!(near(g.with_travel, w.with_travel), "{g:?} {w:?}");
                assert!(g.with_travel.is_some() && g.with_factor_of_safety.is_some());
            }
        }
    }

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
