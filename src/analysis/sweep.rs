//! Parameter sweeps: every combination of the varied scene keys, each combination's route run
//! by the one runner (`runner.rs`).
//!
//! A key is named as in the scene file, `section.key` (e.g. `friction.mu_k`,
//! `foundation.xi_deg`). Each combination is the base scene with its keys set
//! ([`Scene::with_keys`]) and validated again, so every key of the schema can be varied and every
//! value is checked exactly as in a scene file; a combination that is invalid or whose route
//! fails becomes a row with its reason, never an abort.

use super::runner::{Outcome, run_chunked, run_many};
use crate::model::{Contacts, DynamicsModel, Friction, Integrator, Mode};
use crate::scene::{Scene, SceneError};

/// The most combinations one sweep may run.
pub const MAX_COMBINATIONS: usize = 1_000_000;

/// The most values one key may take in a sweep.
pub const MAX_VALUES: usize = 100_000;

/// A scene key that cannot be varied as asked, and why.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("{key}: {reason}")]
pub struct KeyError {
    /// The key as given (`section.key`), or the text that should have named one.
    pub key: String,
    /// Why, in one line.
    pub reason: String,
}

impl KeyError {
    fn new(key: &str, reason: impl Into<String>) -> KeyError {
        KeyError {
            key: key.to_string(),
            reason: reason.into(),
        }
    }
}

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
    /// `key` over the numbers `values`.
    pub fn numbers(key: &str, values: Vec<f64>) -> Vary {
        Vary {
            key: key.to_string(),
            values,
            words: None,
        }
    }

    /// For a key that names a file: each word that names a folder (from `folder`, the base
    /// scene's) replaced by the files in it, `word/name` in the order of their names (hidden
    /// files and sub-folders left out), so that `seismic.record_x=records/` runs every record
    /// of a folder. A folder without files is an error naming the key.
    fn with_folders_listed(self, folder: &std::path::Path) -> Result<Vary, KeyError> {
        let Some(words) = self
            .words
            .as_ref()
            .filter(|_| FILE_KEYS.contains(&self.key.as_str()))
        else {
            return Ok(self);
        };
        let mut listed = Vec::new();
        for w in words {
            let dir = folder.join(w);
            if !dir.is_dir() {
                listed.push(w.clone());
                continue;
            }
            let unreadable =
                |e: std::io::Error| KeyError::new(&self.key, format!("the folder `{w}`: {e}"));
            let mut names: Vec<String> = std::fs::read_dir(&dir)
                .map_err(unreadable)?
                .filter_map(Result::ok)
                .filter(|e| e.file_type().is_ok_and(|t| t.is_file()))
                .filter_map(|e| e.file_name().into_string().ok())
                .filter(|n| !n.starts_with('.'))
                .collect();
            if names.is_empty() {
                return Err(KeyError::new(
                    &self.key,
                    format!("the folder `{w}` has no files"),
                ));
            }
            names.sort();
            let stem = w.trim_end_matches(['/', '\\']);
            listed.extend(names.into_iter().map(|n| format!("{stem}/{n}")));
        }
        if listed.len() > MAX_VALUES {
            return Err(KeyError::new(
                &self.key,
                format!(
                    "{} files, more than the {MAX_VALUES} values one key may take",
                    listed.len()
                ),
            ));
        }
        Ok(Vary {
            key: self.key,
            values: (0..listed.len()).map(|k| k as f64).collect(),
            words: Some(listed),
        })
    }

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

/// `KEY=START:STOP:COUNT` (COUNT ≥ 1 evenly spaced values, START and STOP included) or
/// `KEY=A,B,C` (a list: numbers, or words for a key that takes words, such as
/// `solver.dynamics=paper,rigid-body`). The error's key is the whole text.
impl std::str::FromStr for Vary {
    type Err = KeyError;

    fn from_str(s: &str) -> Result<Vary, KeyError> {
        let bad = |why: &str| {
            KeyError::new(
                s,
                format!(
                    "{why} (expected KEY=START:STOP:COUNT, e.g. friction.mu_k=0.2:0.6:5, or \
                     KEY=A,B,…, e.g. solver.dynamics=paper,rigid-body)"
                ),
            )
        };
        let (key, range) = s.split_once('=').ok_or_else(|| bad("no `=`"))?;
        let key = key.trim();
        if key.split('.').count() != 2 || key.split('.').any(str::is_empty) {
            return Err(bad("KEY must be `section.key`"));
        }
        if range.contains(',') || takes_words(key) {
            return list(key, range).map_err(|why| bad(&why));
        }
        let parts: Vec<&str> = range.split(':').collect();
        match parts.as_slice() {
            [one] => number(one, "the value").map(|v| Vary::numbers(key, vec![v])),
            [a, b, n] => evenly(a, b, n).map(|v| Vary::numbers(key, v)),
            _ => Err("the range needs three parts, START:STOP:COUNT".to_string()),
        }
        .map_err(|why| bad(&why))
    }
}

/// A finite number, or why `t` (`what`) is not one.
fn number(t: &str, what: &str) -> Result<f64, String> {
    match t.trim().parse::<f64>() {
        Ok(v) if v.is_finite() => Ok(v),
        Ok(_) => Err(format!("{what} must be finite")),
        Err(_) => Err(format!("{what} `{}` is not a number", t.trim())),
    }
}

/// COUNT values from START to STOP, evenly spaced, STOP itself the last (not START + (STOP −
/// START) with its rounding). Where STOP − START overflows (`1e308:-1e308:3`), each value is
/// START (1 − f) + STOP f instead, finite as both ends are.
fn evenly(a: &str, b: &str, n: &str) -> Result<Vec<f64>, String> {
    let (a, b) = (number(a, "START")?, number(b, "STOP")?);
    let n: usize = n
        .trim()
        .parse()
        .map_err(|_| format!("COUNT `{}` is not a whole number", n.trim()))?;
    if n == 0 || n > MAX_VALUES {
        return Err(format!("COUNT must be from 1 to {MAX_VALUES}"));
    }
    Ok(if n == 1 {
        vec![a]
    } else {
        (0..n)
            .map(|k| {
                if k == n - 1 {
                    b
                } else if (b - a).is_finite() {
                    a + (b - a) * k as f64 / (n - 1) as f64
                } else {
                    let f = k as f64 / (n - 1) as f64;
                    a * (1.0 - f) + b * f
                }
            })
            .collect()
    })
}

/// A list of numbers, or of words for a key that takes words.
fn list(key: &str, range: &str) -> Result<Vary, String> {
    let items: Vec<&str> = range.split(',').map(str::trim).collect();
    if items.iter().any(|i| i.is_empty()) {
        return Err("the list has an empty item".into());
    }
    if items.len() > MAX_VALUES {
        return Err(format!("the list has more than {MAX_VALUES} items"));
    }
    if takes_words(key) {
        let allowed = words_of(key);
        let stranger = allowed
            .as_ref()
            .and_then(|a| items.iter().find(|w| !a.contains(w)).map(|w| (w, a)));
        if let Some((w, allowed)) = stranger {
            return Err(format!(
                "`{w}` is not one of {} (the key takes words, as a list)",
                allowed.join(", ")
            ));
        }
        return Ok(Vary {
            key: key.to_string(),
            values: (0..items.len()).map(|k| k as f64).collect(),
            words: Some(items.iter().map(|w| w.to_string()).collect()),
        });
    }
    let values = items
        .iter()
        .map(|t| number(t, &format!("`{t}`")).map_err(|_| format!("`{t}` is not a finite number")))
        .collect::<Result<Vec<_>, _>>()?;
    Ok(Vary::numbers(key, values))
}

/// Optional scene keys that a sweep may vary although the base scene leaves them out (their
/// default then stands in the base).
const OPTIONAL_KEYS: [&str; 11] = [
    "solver.dynamics",
    "solver.integrator",
    "solver.stride",
    "solver.contacts",
    "solver.tolerance",
    "block.inertia_x_kg_m2",
    "block.inertia_z_kg_m2",
    "block.inertia_xz_kg_m2",
    "initial.vx_m_s",
    "initial.vz_m_s",
    "initial.omega_deg_s",
];

/// Keys that take whole numbers.
const INTEGER_KEYS: [&str; 1] = ["solver.stride"];

/// Keys that name a file beside the scene: any word is a value (the scene, read again, says
/// whether the file is there and what is in it).
const FILE_KEYS: [&str; 5] = [
    "foundation.surface",
    "seismic.record",
    "seismic.record_x",
    "seismic.record_y",
    "seismic.record_z",
];

/// Whether `key` takes words: those of [`words_of`], or a file's name.
fn takes_words(key: &str) -> bool {
    words_of(key).is_some() || FILE_KEYS.contains(&key)
}

/// The words a key takes, for a key that takes words from a list: the names the scene itself
/// accepts.
fn words_of(key: &str) -> Option<Vec<&'static str>> {
    Some(match key {
        "solver.dynamics" => DynamicsModel::ALL.map(DynamicsModel::as_str).to_vec(),
        "solver.integrator" => Integrator::ALL.map(Integrator::as_str).to_vec(),
        "solver.contacts" => Contacts::ALL.map(Contacts::as_str).to_vec(),
        "solver.mode" => Mode::ALL.map(Mode::as_str).to_vec(),
        "friction.model" => Friction::MODELS.to_vec(),
        "seismic.units" => vec!["g", "m/s2", "cm/s2"],
        "seismic.polarity" => vec!["normal", "reversed", "both"],
        _ => return None,
    })
}

/// The base scene's own value of `key` (`section.key`), if its file gives one.
fn document_value<'a>(base: &'a Scene, key: &str) -> Option<&'a toml::Value> {
    let (section, name) = key.split_once('.')?;
    section_of(base.document(), section)?.get(name)
}

/// A section of the document: a table (`water`), or an item of a list of tables (`anchor[1]`,
/// from 0).
fn section_of<'a>(doc: &'a toml::Table, section: &str) -> Option<&'a toml::Table> {
    match section.split_once('[') {
        Some((list, rest)) => {
            let k: usize = rest.strip_suffix(']')?.parse().ok()?;
            doc.get(list)?.as_array()?.get(k)?.as_table()
        }
        None => doc.get(section)?.as_table(),
    }
}

/// Whether `key` can take `values` (numbers, or words where `words`) in `base`: a key the base
/// scene has, or an optional key it may have, of the kind the values are.
pub fn check_key(base: &Scene, key: &str, words: bool, values: &[f64]) -> Result<(), KeyError> {
    let table = base.document();
    let (section, name) = key.split_once('.').unwrap_or(("", ""));
    let empty = toml::Table::new();
    // An item of a list of tables takes any of its list's keys (those it leaves out have
    // defaults, or the scene's check names them).
    let list = section.split_once('[').map(|(list, _)| list);
    let optional = OPTIONAL_KEYS.contains(&key)
        || list.is_some_and(|l| crate::scene::keys_of(l).contains(&name));
    let sec = section_of(table, section)
        .or_else(|| (OPTIONAL_KEYS.contains(&key)).then_some(&empty))
        .ok_or_else(|| {
            if let Some(list) = list {
                let count = table
                    .get(list)
                    .and_then(toml::Value::as_array)
                    .map_or(0, Vec::len);
                return KeyError::new(
                    key,
                    format!("the scene has {count} [[{list}]] (numbered from 0)"),
                );
            }
            let names: Vec<&str> = table
                .iter()
                .filter(|(_, v)| v.is_table())
                .map(|(k, _)| k.as_str())
                .collect();
            KeyError::new(
                key,
                format!(
                    "the scene has no section [{section}] (sections: {})",
                    names.join(", ")
                ),
            )
        })?;
    let whole = |values: &[f64]| match values.iter().find(|x| x.fract() != 0.0) {
        Some(x) => Err(KeyError::new(
            key,
            format!("the key takes whole numbers, and the range gives {x}"),
        )),
        None => Ok(()),
    };
    let takes_words = takes_words(key);
    let kind = || {
        Err(KeyError::new(
            key,
            if takes_words {
                "the key takes words, as a list (KEY=A,B,…)"
            } else {
                "the key takes numbers"
            },
        ))
    };
    match sec.get(name) {
        // An optional key the scene leaves out takes values of its own kind all the same.
        None if optional && takes_words != words => kind(),
        None if optional && INTEGER_KEYS.contains(&key) => whole(values),
        None if optional => Ok(()),
        None => {
            let names: Vec<&str> = sec.keys().map(String::as_str).collect();
            Err(KeyError::new(
                key,
                format!(
                    "no key `{name}` in [{section}] (keys: {})",
                    names.join(", ")
                ),
            ))
        }
        Some(_) if takes_words != words => kind(),
        Some(toml::Value::String(_)) if takes_words => Ok(()),
        Some(toml::Value::Float(_)) => Ok(()),
        // A whole-number key (such as solver.stride) takes whole numbers only.
        Some(toml::Value::Integer(_)) => whole(values),
        Some(other) => Err(KeyError::new(
            key,
            format!("the key is a {}, which cannot be varied", other.type_str()),
        )),
    }
}

/// Each key of `keys` once: the first given twice, if any.
pub fn given_twice<'k>(keys: impl IntoIterator<Item = &'k str>) -> Option<&'k str> {
    let mut seen = std::collections::BTreeSet::new();
    keys.into_iter().find(|k| !seen.insert(*k))
}

/// One combination of a sweep: its values, in the order of the varied keys, and what its route
/// came to.
#[derive(Debug, Clone, PartialEq)]
pub struct SweepRow {
    /// The varied values (for a key of words, the word's index).
    pub values: Vec<f64>,
    /// What its route came to.
    pub outcome: Outcome,
}

/// A sweep: a base scene and the keys it varies, each key checked and the number of
/// combinations bounded when it is made.
#[derive(Debug, Clone)]
pub struct Sweep<'a> {
    base: &'a Scene,
    varies: Vec<Vary>,
}

impl<'a> Sweep<'a> {
    /// The sweep of `varies` over `base`, or the first key that cannot be varied as asked.
    pub fn new(base: &'a Scene, varies: Vec<Vary>) -> Result<Sweep<'a>, KeyError> {
        if let Some(key) = given_twice(varies.iter().map(|v| v.key.as_str())) {
            return Err(KeyError::new(
                key,
                "the key is given twice (each key varies once; put all its values in one range)",
            ));
        }
        let varies = varies
            .into_iter()
            .map(|v| v.with_folders_listed(base.folder()))
            .collect::<Result<Vec<_>, _>>()?;
        for v in &varies {
            if v.values.is_empty() {
                return Err(KeyError::new(&v.key, "no values"));
            }
            check_key(base, &v.key, v.words.is_some(), &v.values)?;
        }
        let sweep = Sweep { base, varies };
        let n = sweep.count();
        if n > MAX_COMBINATIONS {
            let keys: Vec<&str> = sweep.varies.iter().map(|v| v.key.as_str()).collect();
            return Err(KeyError::new(
                &keys.join(", "),
                format!("{n} combinations, more than the {MAX_COMBINATIONS} one sweep may run"),
            ));
        }
        Ok(sweep)
    }

    /// The varied keys.
    pub fn varies(&self) -> &[Vary] {
        &self.varies
    }

    /// The number of combinations (saturating).
    pub fn count(&self) -> usize {
        self.varies
            .iter()
            .fold(1usize, |n, v| n.saturating_mul(v.values.len()))
    }

    /// The values of combination `index`: the mixed-radix digits of the index, the last key
    /// varying fastest.
    pub fn values(&self, index: usize) -> Vec<f64> {
        let mut rest = index;
        let mut values = vec![0.0; self.varies.len()];
        for (k, v) in self.varies.iter().enumerate().rev() {
            values[k] = v.values[rest % v.values.len()];
            rest /= v.values.len();
        }
        values
    }

    /// The scene of the combination with `values`. Each dynamics takes its own integrator when
    /// the dynamics varies (unless the integrator varies too).
    pub fn scene(&self, values: &[f64]) -> Result<Scene, SceneError> {
        let keys = self.varies.iter().zip(values).map(|(v, &x)| {
            (
                v.key.as_str(),
                v.toml_value(x, document_value(self.base, &v.key)),
            )
        });
        let dynamics = self
            .varies
            .iter()
            .zip(values)
            .find(|(v, _)| v.key == "solver.dynamics")
            .filter(|_| !self.varies.iter().any(|w| w.key == "solver.integrator"))
            .and_then(|(v, &x)| v.cell(x).parse::<DynamicsModel>().ok());
        match dynamics {
            Some(model) => self.base.with_dynamics(model),
            None => Ok(self.base.clone()),
        }
        .and_then(|s| s.with_keys(keys))
    }

    /// Every combination's route, in order (the last key varying fastest). `tick()` is called
    /// once per finished combination. Once `stop()` answers true, routes under way end at their
    /// next increment as interrupted and combinations not yet started are
    /// [`Outcome::NotRun`]: every combination still has its row.
    pub fn run(&self, tick: impl Fn() + Sync, stop: impl Fn() -> bool + Sync) -> Vec<SweepRow> {
        self.run_range(0..self.count(), tick, stop)
    }

    /// The combinations numbered `range`, in order, as [`Sweep::run`] runs them.
    fn run_range(
        &self,
        range: std::ops::Range<usize>,
        tick: impl Fn() + Sync,
        stop: impl Fn() -> bool + Sync,
    ) -> Vec<SweepRow> {
        let combinations: Vec<Vec<f64>> = range.map(|k| self.values(k)).collect();
        let outcomes = run_many(&combinations, |values| self.scene(values), tick, stop);
        combinations
            .into_iter()
            .zip(outcomes)
            .map(|(values, outcome)| SweepRow { values, outcome })
            .collect()
    }

    /// Every combination, in order, as [`Sweep::run`] runs them, each handed to `each` as soon
    /// as it and those before it have run, at most 4096 (`CHUNK`) at a time on every core: the
    /// sweep holds no row `each` does not keep. The first error of `each` ends the run and is
    /// returned.
    pub fn run_each<E>(
        &self,
        tick: impl Fn() + Sync,
        stop: impl Fn() -> bool + Sync,
        each: impl FnMut(SweepRow) -> Result<(), E>,
    ) -> Result<(), E> {
        run_chunked(
            0..self.count(),
            |first, chunk| self.run_range(first..first + chunk.len(), &tick, &stop),
            each,
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::analysis::runner::NOT_RUN;

    fn vary(s: &str) -> Vary {
        s.parse().unwrap()
    }

    #[test]
    fn a_range_wider_than_the_largest_number_gives_finite_values() {
        // Before, STOP − START overflowed and the middle value was NaN (written as such in
        // sweep.csv, the run exiting 0).
        let v = vary("solver.dt_s=1e308:-1e308:3");
        assert_eq!(v.values, vec![1e308, 0.0, -1e308]);
        let v = vary("friction.mu_k=-1.7976931348623157e308:1.7976931348623157e308:5");
        assert!(v.values.iter().all(|x| x.is_finite()), "{:?}", v.values);
        assert!(v.values.windows(2).all(|w| w[0] < w[1]), "{:?}", v.values);
        // An ordinary range keeps its values to the bit.
        assert_eq!(
            vary("friction.mu_k=0.2:0.6:3").values,
            vec![0.2, 0.2 + 0.4 * 0.5, 0.6]
        );
    }

    #[test]
    fn vary_parses_ranges_and_rejects_bad_ones() {
        let v = vary("friction.mu_k=0.2:0.6:5");
        assert_eq!(v.key, "friction.mu_k");
        assert_eq!(v.values.len(), 5);
        assert!((v.values[4] - 0.6).abs() < 1e-15 && (v.values[2] - 0.4).abs() < 1e-15);
        assert_eq!(vary("loads.eccentricity_m=1:1:1").values, vec![1.0]);
        assert_eq!(vary("solver.t_end_s=0.01").values, vec![0.01]);
        let list = vary("friction.mu_k=0.3, 0.5,0.45");
        assert_eq!((list.values, list.words), (vec![0.3, 0.5, 0.45], None));
        let words = vary("solver.dynamics=paper,rigid-body");
        assert_eq!(words.values, vec![0.0, 1.0]);
        assert_eq!(words.cell(1.0), "rigid-body");
        // A file's name is any word; a polarity one of two.
        let files = vary("seismic.record_x=RSN1_X.AT2,RSN2_X.AT2");
        assert_eq!(files.cell(1.0), "RSN2_X.AT2");
        assert_eq!(vary("seismic.record=motion.csv").words.unwrap().len(), 1);
        let e = "seismic.polarity=normal,up".parse::<Vary>().unwrap_err();
        assert!(e.reason.contains("not one of normal, reversed"), "{e}");
        for bad in ["solver.dynamics=0:1:2", "solver.dynamics=paper,rigid"] {
            let e = bad.parse::<Vary>().unwrap_err();
            assert!(e.reason.contains("not one of paper, rigid-body"), "{e}");
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
            "friction.mu_k=abc",
        ] {
            let e = bad.parse::<Vary>().unwrap_err();
            assert_eq!(e.key, bad, "{e}");
        }
    }

    #[test]
    fn unknown_keys_are_named() {
        let base = &Scene::default_scene();
        let e = Sweep::new(base, vec![vary("friction.mu=0:1:2")]).unwrap_err();
        assert!(e.key == "friction.mu" && e.reason.contains("mu_k"), "{e}");
        let e = Sweep::new(base, vec![vary("water.level=0:1:2")]).unwrap_err();
        assert!(e.reason.contains("no section [water]"), "{e}");
        let twice = vec![vary("friction.mu_k=0:1:2"), vary("friction.mu_k=3:4:2")];
        let e = Sweep::new(base, twice).unwrap_err();
        assert!(e.reason.contains("given twice"), "{e}");
        let e = Sweep::new(base, vec![vary("solver.stride=1:2:3")]).unwrap_err();
        assert!(e.reason.contains("whole numbers"), "{e}");
    }

    #[test]
    fn solver_keys_the_scene_leaves_out_can_be_varied_with_values_of_their_kind() {
        // The default scene writes neither solver.tolerance nor solver.contacts; a sweep over
        // them was refused ("no key", "`frame` is not a finite number").
        let base = &Scene::default_scene();
        assert!(document_value(base, "solver.tolerance").is_none());
        assert!(document_value(base, "solver.contacts").is_none());
        let tolerances = vec![vary("solver.tolerance=1e-3,1e-12")];
        let rows = Sweep::new(base, tolerances).unwrap().run(|| (), || false);
        let travel = |o: &Outcome| match o {
            Outcome::Route(r) => r.travel_m,
            other => panic!("{other:?}"),
        };
        let (coarse, fine) = (travel(&rows[0].outcome), travel(&rows[1].outcome));
        // Each tolerance is the one the route ran with: the coarse one's travel is off the
        // fine one's, by more than the fine one allows and less than the coarse one does.
        assert!(
            (coarse - fine).abs() > 1e-9 * fine && (coarse - fine).abs() < 1e-2 * fine,
            "{coarse} {fine}"
        );
        let contacts = vary("solver.contacts=frame,base");
        assert_eq!(contacts.cell(1.0), "base");
        Sweep::new(base, vec![contacts]).unwrap();
        // A key of words given numbers (a distribution's draws), and one of numbers given
        // words, are refused before any route runs, whether the scene writes the key or not.
        for key in [
            "solver.dynamics",
            "solver.integrator",
            "solver.contacts",
            "solver.mode",
        ] {
            let e = check_key(base, key, false, &[0.5]).unwrap_err();
            assert!(e.reason.contains("takes words"), "{key}: {e}");
        }
        for key in ["solver.tolerance", "solver.dt_s"] {
            let e = check_key(base, key, true, &[0.0]).unwrap_err();
            assert!(e.reason.contains("takes numbers"), "{key}: {e}");
        }
    }

    #[test]
    fn combinations_are_ordered_with_the_last_key_fastest_and_invalid_ones_are_rows() {
        let base = &Scene::default_scene();
        let varies = vec![
            vary("foundation.xi_deg=20:95:2"),
            vary("loads.hydraulic_force_n=0:8e6:2"),
        ];
        let rows = Sweep::new(base, varies).unwrap().run(|| (), || false);
        assert_eq!(rows.len(), 4);
        assert_eq!(rows[1].values, vec![20.0, 8e6]);
        assert_eq!(rows[0].outcome.reason(), "does not slide");
        match &rows[2].outcome {
            Outcome::Invalid { reason } => {
                assert!(reason.contains("foundation.xi_deg"), "{reason}")
            }
            other => panic!("{other:?}"),
        }
    }

    #[test]
    fn a_stopped_sweep_still_has_a_row_for_every_combination() {
        let base = Scene::default_scene();
        let sweep = Sweep::new(&base, vec![vary("friction.mu_k=0.2:0.6:5")]).unwrap();
        let done = std::sync::atomic::AtomicUsize::new(0);
        let rows = sweep.run(
            || {
                done.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
            },
            || true,
        );
        assert_eq!(rows.len(), 5);
        assert!(rows.iter().all(|r| r.outcome.reason() == NOT_RUN));
        assert_eq!(rows[4].values, vec![0.6]);
        assert_eq!(done.into_inner(), 5, "progress counts every combination");
    }
}
