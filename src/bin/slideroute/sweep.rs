//! Parameter sweeps: every combination of the varied scene keys, run in parallel.
//!
//! A key is named as in the scene file, `section.key` (e.g. `friction.mu_k`,
//! `foundation.xi_deg`). Each combination is the base scene with its keys set
//! ([`Scene::with_keys`]) and validated again, so every key of the schema can be varied and every
//! value is checked exactly as in a scene file; a combination that is invalid or whose route
//! fails becomes a row with its reason, never an abort.

use rayon::prelude::*;
use serde::Serialize;
use slideroute::stages::route::{self, Route};
use slideroute::stages::scene::{DynamicsModel, Friction, Integrator, Mode, Scene};
use std::ops::ControlFlow;

/// One varied key and its values.
#[derive(Debug, Clone, PartialEq)]
pub struct Vary {
    /// `section.key`.
    pub key: String,
    /// The numbers, or for a list of words the indices 0, 1, … into [`Vary::words`].
    pub values: Vec<f64>,
    /// For a key that takes words (`solver.dynamics=paper,rigid-body`): the words.
    pub words: Option<Vec<String>>,
}

impl Vary {
    /// Value `x` of this key as a table cell: the number, or the word it stands for.
    pub fn cell(&self, x: f64) -> String {
        match &self.words {
            Some(w) => w.get(x as usize).cloned().unwrap_or_default(),
            None => x.to_string(),
        }
    }

    /// Value `x` as a TOML value for a key whose base value (if any) is `base`.
    fn toml_value(&self, x: f64, base: Option<&toml::Value>) -> toml::Value {
        match (&self.words, base) {
            (Some(w), _) => toml::Value::String(w.get(x as usize).cloned().unwrap_or_default()),
            (None, Some(toml::Value::Integer(_))) => toml::Value::Integer(x as i64),
            (None, None) if INTEGER_KEYS.contains(&self.key.as_str()) => {
                toml::Value::Integer(x as i64)
            }
            _ => toml::Value::Float(x),
        }
    }
}

/// Optional scene keys that a sweep may vary although the base scene leaves them out (their
/// default then stands in the base).
const OPTIONAL_KEYS: [&str; 9] = [
    "solver.dynamics",
    "solver.integrator",
    "solver.stride",
    "block.inertia_x_kg_m2",
    "block.inertia_z_kg_m2",
    "block.inertia_xz_kg_m2",
    "initial.vx_m_s",
    "initial.vz_m_s",
    "initial.omega_deg_s",
];

/// The base scene's own value of `key` (`section.key`), if its file gives one.
fn document_value<'a>(base: &'a Scene, key: &str) -> Option<&'a toml::Value> {
    let (section, name) = key.split_once('.')?;
    base.document().get(section)?.as_table()?.get(name)
}

/// Keys that take whole numbers.
const INTEGER_KEYS: [&str; 1] = ["solver.stride"];

/// Keys that take words, and their words.
/// The words a key takes, for a key that takes words: the names the scene itself accepts.
fn words_of(key: &str) -> Option<Vec<&'static str>> {
    Some(match key {
        "solver.dynamics" => DynamicsModel::ALL.map(DynamicsModel::as_str).to_vec(),
        "solver.integrator" => Integrator::ALL.map(Integrator::as_str).to_vec(),
        "solver.mode" => Mode::ALL.map(Mode::as_str).to_vec(),
        "friction.model" => Friction::MODELS.to_vec(),
        _ => return None,
    })
}

fn takes_words(key: &str) -> bool {
    words_of(key).is_some()
}

/// Parses `KEY=START:STOP:COUNT` (COUNT ≥ 1 evenly spaced values, START and STOP included) or
/// `KEY=A,B,C` (a list: numbers, or words for a key that takes words, such as
/// `solver.dynamics=paper,rigid-body`).
pub fn parse_vary(s: &str) -> Result<Vary, String> {
    let bad = |why: &str| {
        format!(
            "--vary {s}: {why} (expected KEY=START:STOP:COUNT, e.g. friction.mu_k=0.2:0.6:5, \
             or KEY=A,B,…, e.g. solver.dynamics=paper,rigid-body)"
        )
    };
    let (key, range) = s.split_once('=').ok_or_else(|| bad("no `=`"))?;
    let key = key.trim();
    if key.split('.').count() != 2 || key.split('.').any(str::is_empty) {
        return Err(bad("KEY must be `section.key`"));
    }
    if range.contains(',') || takes_words(key) {
        let items: Vec<&str> = range.split(',').map(str::trim).collect();
        if items.iter().any(|i| i.is_empty()) {
            return Err(bad("the list has an empty item"));
        }
        if items.len() > 100_000 {
            return Err(bad("the list has more than 100000 items"));
        }
        if let Some(allowed) = words_of(key) {
            if let Some(w) = items.iter().find(|w| !allowed.contains(w)) {
                return Err(bad(&format!(
                    "`{w}` is not one of {} (the key takes words, as a list)",
                    allowed.join(", ")
                )));
            }
            return Ok(Vary {
                key: key.to_string(),
                values: (0..items.len()).map(|k| k as f64).collect(),
                words: Some(items.iter().map(|w| w.to_string()).collect()),
            });
        }
        let values = items
            .iter()
            .map(|t| match t.parse::<f64>() {
                Ok(v) if v.is_finite() => Ok(v),
                _ => Err(bad(&format!("`{t}` is not a finite number"))),
            })
            .collect::<Result<Vec<_>, _>>()?;
        return Ok(Vary {
            key: key.to_string(),
            values,
            words: None,
        });
    }
    let parts: Vec<&str> = range.split(':').collect();
    if parts.len() != 3 {
        return Err(bad("the range needs three parts"));
    }
    let num = |t: &str, what: &str| -> Result<f64, String> {
        let v: f64 = t
            .trim()
            .parse()
            .map_err(|_| bad(&format!("{what} `{t}` is not a number")))?;
        if v.is_finite() {
            Ok(v)
        } else {
            Err(bad(&format!("{what} must be finite")))
        }
    };
    let (a, b) = (num(parts[0], "START")?, num(parts[1], "STOP")?);
    let n: usize = parts[2]
        .trim()
        .parse()
        .map_err(|_| bad(&format!("COUNT `{}` is not a whole number", parts[2])))?;
    if n == 0 || n > 100_000 {
        return Err(bad("COUNT must be from 1 to 100000"));
    }
    let values = if n == 1 {
        vec![a]
    } else {
        // STOP itself as the last value, not START + (STOP − START) with its rounding.
        (0..n)
            .map(|k| {
                if k == n - 1 {
                    b
                } else {
                    a + (b - a) * k as f64 / (n - 1) as f64
                }
            })
            .collect()
    };
    Ok(Vary {
        key: key.to_string(),
        values,
        words: None,
    })
}

/// The outcome of one combination.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SweepRow {
    /// The varied values, in the order of the `--vary` flags.
    pub values: Vec<f64>,
    /// The termination reason, or "invalid scene".
    pub reason: String,
    pub t_end_s: Option<f64>,
    pub travel_m: Option<f64>,
    pub final_theta_deg: Option<f64>,
    pub max_alpha_deg: Option<f64>,
    pub max_beta_deg: Option<f64>,
    /// The factor of safety at the start (friction cones), whatever the dynamics.
    pub factor_of_safety: Option<slideroute::stages::mechanics::static_friction::FactorOfSafety>,
    pub detail: String,
}

impl SweepRow {
    /// The row of a combination that has no route (an invalid scene, a sweep stopped first).
    fn without_route(values: Vec<f64>, reason: &str, detail: String) -> SweepRow {
        SweepRow {
            values,
            reason: reason.into(),
            t_end_s: None,
            travel_m: None,
            final_theta_deg: None,
            max_alpha_deg: None,
            max_beta_deg: None,
            factor_of_safety: None,
            detail,
        }
    }
}

fn row_of(values: Vec<f64>, route: &Route) -> SweepRow {
    let max =
        |f: fn(&route::Row) -> f64| route.rows.iter().map(f).fold(f64::NEG_INFINITY, f64::max);
    SweepRow {
        values,
        reason: route.termination.reason.as_str().to_string(),
        t_end_s: Some(route.termination.t_s),
        travel_m: Some(route.travel_m),
        final_theta_deg: route.rows.last().map(|r| r.theta_deg),
        max_alpha_deg: Some(max(|r| r.alpha_deg)),
        max_beta_deg: Some(max(|r| r.beta_deg)),
        factor_of_safety: route.factor_of_safety,
        detail: route.termination.detail.clone(),
    }
}

/// The number of combinations (saturating).
pub fn count(varies: &[Vary]) -> usize {
    varies
        .iter()
        .fold(1usize, |n, v| n.saturating_mul(v.values.len()))
}

/// The most combinations one sweep may run.
pub const MAX_COMBINATIONS: usize = 1_000_000;

/// Checks that every varied key exists in the base scene (or is an optional key it may
/// have); the error names the key.
pub fn check_keys(base: &Scene, varies: &[Vary]) -> Result<(), String> {
    let table = base.document();
    for (k, v) in varies.iter().enumerate() {
        if varies[..k].iter().any(|w| w.key == v.key) {
            return Err(format!(
                "--vary {}: the key is given twice (each key varies once; put all its values \
                 in one range)",
                v.key
            ));
        }
        let (section, key) = v.key.split_once('.').unwrap_or(("", ""));
        let empty = toml::Table::new();
        let sec = table
            .get(section)
            .and_then(|t| t.as_table())
            .or_else(|| OPTIONAL_KEYS.contains(&v.key.as_str()).then_some(&empty))
            .ok_or_else(|| {
                let names: Vec<&String> = table
                    .iter()
                    .filter(|(_, v)| v.is_table())
                    .map(|(k, _)| k)
                    .collect();
                format!(
                    "--vary {}: the scene has no section [{section}] (sections: {})",
                    v.key,
                    names
                        .iter()
                        .map(|s| s.as_str())
                        .collect::<Vec<_>>()
                        .join(", ")
                )
            })?;
        let words_key = takes_words(&v.key);
        match sec.get(key) {
            None if OPTIONAL_KEYS.contains(&v.key.as_str()) => {
                if INTEGER_KEYS.contains(&v.key.as_str()) {
                    if let Some(x) = v.values.iter().find(|x| x.fract() != 0.0) {
                        return Err(format!(
                            "--vary {}: the key takes whole numbers, and the range gives {x}",
                            v.key
                        ));
                    }
                }
            }
            None => {
                let names: Vec<&str> = sec.keys().map(String::as_str).collect();
                return Err(format!(
                    "--vary {}: no key `{key}` in [{section}] (keys: {})",
                    v.key,
                    names.join(", ")
                ));
            }
            Some(_) if words_key != v.words.is_some() => {
                return Err(format!(
                    "--vary {}: the key takes {}",
                    v.key,
                    if words_key {
                        "words, as a list (KEY=A,B,…)"
                    } else {
                        "numbers"
                    }
                ));
            }
            Some(toml::Value::String(_)) => {}
            // A whole-number key (such as solver.stride) takes whole numbers only.
            Some(toml::Value::Integer(_)) => {
                if let Some(x) = v.values.iter().find(|x| x.fract() != 0.0) {
                    return Err(format!(
                        "--vary {}: the key takes whole numbers, and the range gives {x}",
                        v.key
                    ));
                }
            }
            Some(toml::Value::Float(_)) => {}
            Some(other) => {
                return Err(format!(
                    "--vary {}: the key is a {}, which a sweep cannot vary",
                    v.key,
                    other.type_str()
                ));
            }
        }
    }
    Ok(())
}

/// The reason of a combination a stopped sweep did not start.
pub const NOT_RUN: &str = "not run (interrupted)";

/// Runs every combination in parallel; rows in the order of the combinations (the last
/// `--vary` varying fastest). `progress()` is called once per finished combination. Once
/// `stop()` answers true (Ctrl-C), routes under way end at their next increment as
/// "interrupted" and combinations not yet started are rows "not run (interrupted)": every
/// combination still has its row.
pub fn run(
    base: &Scene,
    varies: &[Vary],
    progress: impl Fn() + Sync,
    stop: impl Fn() -> bool + Sync,
) -> Result<Vec<SweepRow>, String> {
    check_keys(base, varies)?;
    let n = count(varies);
    if n > MAX_COMBINATIONS {
        return Err(format!(
            "--vary: {n} combinations, more than the {MAX_COMBINATIONS} one sweep may run"
        ));
    }
    Ok((0..n)
        .into_par_iter()
        .map(|index| {
            // Mixed-radix digits of the index, last key fastest.
            let mut rest = index;
            let mut values = vec![0.0; varies.len()];
            for (k, v) in varies.iter().enumerate().rev() {
                values[k] = v.values[rest % v.values.len()];
                rest /= v.values.len();
            }
            if stop() {
                progress();
                return SweepRow::without_route(
                    values,
                    NOT_RUN,
                    "the sweep was interrupted before this combination started".into(),
                );
            }
            let keys = varies.iter().zip(&values).map(|(v, &x)| {
                (
                    v.key.as_str(),
                    v.toml_value(x, document_value(base, &v.key)),
                )
            });
            // Each dynamics takes its own integrator when the dynamics varies.
            let dynamics = varies
                .iter()
                .zip(&values)
                .find(|(v, _)| v.key == "solver.dynamics")
                .filter(|_| !varies.iter().any(|w| w.key == "solver.integrator"))
                .and_then(|(v, &x)| {
                    let word = v.cell(x);
                    DynamicsModel::ALL.into_iter().find(|m| m.as_str() == word)
                });
            let scene = match dynamics {
                Some(model) => base.with_dynamics(model),
                None => Ok(base.clone()),
            }
            .and_then(|s| s.with_keys(keys));
            let row = match scene.map_err(|e| e.to_string()).and_then(|scene| {
                route::run_observed(&scene, |_| {
                    if stop() {
                        ControlFlow::Break(())
                    } else {
                        ControlFlow::Continue(())
                    }
                })
                .map_err(|e| e.to_string())
            }) {
                Ok(r) => row_of(values, &r),
                Err(e) => SweepRow::without_route(values, "invalid scene", e),
            };
            progress();
            row
        })
        .collect())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn vary_parses_ranges_and_rejects_bad_ones() {
        let v = parse_vary("friction.mu_k=0.2:0.6:5").unwrap();
        assert_eq!(v.key, "friction.mu_k");
        assert_eq!(v.values.len(), 5);
        assert!((v.values[4] - 0.6).abs() < 1e-15 && (v.values[2] - 0.4).abs() < 1e-15);
        assert_eq!(
            parse_vary("loads.eccentricity_m=1:1:1").unwrap().values,
            vec![1.0]
        );
        let list = parse_vary("friction.mu_k=0.3, 0.5,0.45").unwrap();
        assert_eq!((list.values, list.words), (vec![0.3, 0.5, 0.45], None));
        let words = parse_vary("solver.dynamics=paper,rigid-body").unwrap();
        assert_eq!(words.values, vec![0.0, 1.0]);
        assert_eq!(words.cell(1.0), "rigid-body");
        for bad in ["solver.dynamics=0:1:2", "solver.dynamics=paper,rigid"] {
            let e = parse_vary(bad).unwrap_err();
            assert!(e.contains("not one of paper, rigid-body"), "{e}");
        }
        for bad in [
            "mu=1:2:3",
            "friction.mu_k",
            "friction.mu_k=1:2",
            "friction.mu_k=a:2:3",
            "friction.mu_k=1:2:0",
            "friction.mu_k=1:inf:2",
            "friction.mu_k=0.3,,0.4",
            "friction.mu_k=0.3,abc",
        ] {
            let e = parse_vary(bad).unwrap_err();
            assert!(e.starts_with(&format!("--vary {bad}")), "{e}");
        }
    }

    #[test]
    fn unknown_keys_are_named() {
        let base = &Scene::default_scene();
        let e = check_keys(base, &[parse_vary("friction.mu=0:1:2").unwrap()]).unwrap_err();
        assert!(e.contains("friction.mu") && e.contains("mu_k"), "{e}");
        let e = check_keys(base, &[parse_vary("water.level=0:1:2").unwrap()]).unwrap_err();
        assert!(e.contains("no section [water]"), "{e}");
    }

    #[test]
    fn combinations_are_ordered_with_the_last_key_fastest_and_invalid_ones_are_rows() {
        let base = &Scene::default_scene();
        let varies = [
            parse_vary("foundation.xi_deg=20:95:2").unwrap(),
            parse_vary("loads.hydraulic_force_n=0:8e6:2").unwrap(),
        ];
        let rows = run(base, &varies, || (), || false).unwrap();
        assert_eq!(rows.len(), 4);
        assert_eq!(rows[1].values, vec![20.0, 8e6]);
        assert_eq!(rows[0].reason, "does not slide");
        assert_eq!(rows[2].reason, "invalid scene");
        assert!(
            rows[2].detail.contains("foundation.xi_deg"),
            "{}",
            rows[2].detail
        );
    }

    #[test]
    fn a_stopped_sweep_still_has_a_row_for_every_combination() {
        let varies = [parse_vary("friction.mu_k=0.2:0.6:5").unwrap()];
        let done = std::sync::atomic::AtomicUsize::new(0);
        let rows = run(
            &Scene::default_scene(),
            &varies,
            || {
                done.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
            },
            || true,
        )
        .unwrap();
        assert_eq!(rows.len(), 5);
        assert!(
            rows.iter()
                .all(|r| r.reason == NOT_RUN && r.travel_m.is_none())
        );
        assert_eq!(rows[4].values, vec![0.6]);
        assert_eq!(done.into_inner(), 5, "progress counts every combination");
    }
}
