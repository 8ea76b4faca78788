//! From the file's keys to the typed, checked scene: every value finite and in its range, every
//! name one the option has, the sections consistent with each other. Each fault is one
//! [`SceneError`] naming its key. A [`Reader`] holds what every check needs — where the scene
//! came from, the folder its files are found from, the files already read — and reads one
//! group of sections per file: the site (`site.rs`), the block (`body.rs`), the loads
//! (`loads.rs`), the friction (`friction.rs`), the run settings and the start (`solver.rs`),
//! the load cases and the uncertain values (`cases.rs`).

mod body;
mod cases;
mod friction;
mod loads;
mod site;
mod solver;

#[cfg(test)]
pub(super) use solver::{DEFAULT_DT_S, DEFAULT_T_END_S};

use super::error::SceneErrorKind;
use super::files::{Files, Sources};
use super::raw::RawScene;
use super::{Scene, SceneError};
use crate::model::{self, Contacts, ModelError, Strengths, UnknownName};
use std::path::Path;

/// What reading one document needs: where it came from (named in every error), the folder the
/// files it names are found from, and the files read before under their names.
pub(super) struct Reader<'a> {
    origin: &'a str,
    folder: &'a Path,
    files: &'a Files,
}

/// The typed scene of a document, or its first fault. `source` is kept as the scene's own
/// file ([`Scene::with`] edits it).
pub(super) fn validate(
    raw: RawScene,
    origin: &str,
    source: toml::Table,
    sources: Sources,
) -> Result<Scene, SceneError> {
    let Sources { folder, files } = sources;
    Reader {
        origin,
        folder,
        files,
    }
    .scene(raw, source)
}

impl Reader<'_> {
    /// The scene, or its faults: the first found, with the others its independent sections
    /// have ([`Reader::other_faults`]).
    fn scene(&self, raw: RawScene, source: toml::Table) -> Result<Scene, SceneError> {
        self.checked(&raw, source)
            .map_err(|first| first.with_also(self.other_faults(&raw)))
    }

    /// The faults of each section that does not need another to be right: the contacts, the
    /// site, the body, its loads, base, strengths and anchors where the site is right, the
    /// friction, the run settings, the start, the guideline and its cases, the uncertain
    /// values. (What sections must agree on is checked once each is right.)
    fn other_faults(&self, raw: &RawScene) -> Vec<SceneError> {
        let mut faults = Vec::new();
        let mut keep = |r: Result<(), SceneError>| {
            if let Err(e) = r {
                faults.push(e);
            }
        };
        let contacts = self.contacts_of(raw);
        if let Ok(contacts) = &contacts {
            keep(
                self.solver(
                    raw.solver.as_ref().unwrap_or(&Default::default()),
                    *contacts,
                )
                .map(drop),
            );
        }
        let site = (|| {
            let contacts = contacts?;
            self.site(
                self.section("frame", &raw.frame)?,
                self.section("foundation", &raw.foundation)?,
                contacts == Contacts::Base,
            )
        })();
        match site {
            Ok(site) => keep((|| {
                let (_, monolith) = self.body(raw, &site)?;
                let loads = self.loads(raw, monolith.as_ref()).map(|(l, _)| l);
                let cm_height = loads
                    .as_ref()
                    .ok()
                    .and_then(Option::as_ref)
                    .map_or(0.0, |l| l.cm_height);
                let others = [
                    loads.map(drop),
                    self.base(raw.base.as_ref(), monolith.as_ref(), &site, cm_height)
                        .map(drop),
                    raw.friction.as_ref().map_or(Ok(()), |f| {
                        self.strengths(f, &site, monolith.as_ref()).map(drop)
                    }),
                    self.anchors(raw.anchor.as_deref().unwrap_or(&[]), monolith.as_ref())
                        .map(drop),
                ];
                match others
                    .into_iter()
                    .filter_map(Result::err)
                    .reduce(|a, b| a.with_also([b]))
                {
                    Some(e) => Err(e),
                    None => Ok(()),
                }
            })()),
            Err(e) => keep(Err(e)),
        }
        keep(
            raw.friction
                .as_ref()
                .map_or(Ok(()), |f| self.friction(f).map(drop)),
        );
        keep(self.initial(raw.initial.as_ref()).map(drop));
        keep((|| {
            let guideline = match &raw.check {
                Some(c) => self.guideline(c)?,
                None => Default::default(),
            };
            self.cases(&guideline, raw.case.as_deref().unwrap_or(&[]))
                .map(drop)
        })());
        keep(self.uncertain(raw.uncertain.as_ref()).map(drop));
        faults
    }

    /// Every section in turn, then what they must agree on.
    fn checked(&self, raw: &RawScene, source: toml::Table) -> Result<Scene, SceneError> {
        let contacts = self.contacts_of(raw)?;
        let site = self.site(
            self.section("frame", &raw.frame)?,
            self.section("foundation", &raw.foundation)?,
            contacts == Contacts::Base,
        )?;
        let (block, monolith) = self.body(raw, &site)?;
        let (loads, record) = self.loads(raw, monolith.as_ref())?;
        let cm_height = loads.as_ref().map_or(0.0, |l| l.cm_height);
        let base = self.base(raw.base.as_ref(), monolith.as_ref(), &site, cm_height)?;
        let cast = raw.base.as_ref().and_then(|b| b.cast).unwrap_or(false);
        if cast && contacts == Contacts::Frame {
            return Err(self.invalid(
                "base.cast",
                "a base cast onto its rock touches it with its whole underside: set [solver] \
                 contacts = \"base\" (the three-point frame has no base)",
            ));
        }
        let (strengths, shares_m2) = match &raw.friction {
            Some(f) => {
                let (s, shares) = self.strengths(f, &site, monolith.as_ref())?;
                (Some(s), shares)
            }
            None => (None, [0.0; 3]),
        };
        // `[solver]` is optional: without it, or without a key of it, the defaults.
        let settings =
            Some(self.solver(raw.solver.as_ref().unwrap_or(&Default::default()), contacts)?);
        let initial = self.initial(raw.initial.as_ref())?;
        if let Some(s) = &settings {
            let cohesion = strengths.as_ref().is_some_and(Strengths::has_cohesion);
            model::check_rigid_only(s.dynamics, record.is_some(), cohesion)
                .map_err(|e| self.model(e))?;
        }
        if let (Some(b), Some(l)) = (&block, &loads) {
            model::check_ratios(site.l(), b, l).map_err(|e| self.model(e))?;
        }
        let guideline = match &raw.check {
            Some(c) => self.guideline(c)?,
            None => Default::default(),
        };
        let cases = self.cases(&guideline, raw.case.as_deref().unwrap_or(&[]))?;
        let anchors = self.anchors(raw.anchor.as_deref().unwrap_or(&[]), monolith.as_ref())?;
        if let Some(s) = &settings {
            model::check_anchored(s, !anchors.is_empty()).map_err(|e| self.model(e))?;
        }
        let uncertain = self.uncertain(raw.uncertain.as_ref())?;
        Ok(Scene {
            name: raw.name.clone().unwrap_or_else(|| "unnamed".to_string()),
            origin: self.origin.to_string(),
            site,
            block,
            loads,
            settings,
            initial,
            source,
            folder: self.folder.to_path_buf(),
            guideline,
            cases,
            both_polarities: record.is_some()
                && raw
                    .seismic
                    .as_ref()
                    .is_some_and(|s| s.polarity.as_deref() == Some("both")),
            record,
            strengths,
            shares_m2,
            uncertain,
            base,
            monolith,
            anchors,
        })
    }

    /// An invalid value of `key`.
    fn invalid(&self, key: impl Into<String>, reason: impl Into<String>) -> SceneError {
        SceneError::new(self.origin, key, reason)
    }

    /// A fault of `kind` at `key`.
    fn fault(
        &self,
        kind: SceneErrorKind,
        key: impl Into<String>,
        reason: impl Into<String>,
    ) -> SceneError {
        SceneError::of(kind, self.origin, key, reason)
    }

    /// A part of the model the values make that cannot be used, at the key it names.
    fn model(&self, e: ModelError) -> SceneError {
        self.invalid(e.key, e.reason)
    }

    /// The value of a key its section needs.
    fn need<T>(&self, key: &str, v: Option<T>) -> Result<T, SceneError> {
        v.ok_or_else(|| {
            let name = key.rsplit('.').next().unwrap_or(key);
            self.fault(
                SceneErrorKind::MissingKey,
                key,
                format!("missing key `{name}`"),
            )
        })
    }

    /// A section the scene needs.
    fn section<'s, T>(&self, name: &str, v: &'s Option<T>) -> Result<&'s T, SceneError> {
        v.as_ref().ok_or_else(|| {
            self.fault(
                SceneErrorKind::MissingSection,
                name,
                format!("missing section [{name}]"),
            )
        })
    }

    /// The option `word` names.
    fn named<T: std::str::FromStr<Err = UnknownName>>(
        &self,
        key: &str,
        word: &str,
    ) -> Result<T, SceneError> {
        word.parse()
            .map_err(|e: UnknownName| self.invalid(key, e.to_string()))
    }

    /// One number: finite, and `ok`; `what` says what was expected.
    fn check(&self, key: &str, v: f64, ok: bool, what: &str) -> Result<f64, SceneError> {
        model::check(key, v, ok, what).map_err(|e| self.model(e))
    }

    /// A finite number.
    fn finite(&self, key: &str, v: f64) -> Result<f64, SceneError> {
        model::finite(key, v).map_err(|e| self.model(e))
    }

    /// A positive number.
    fn positive(&self, key: &str, v: f64) -> Result<f64, SceneError> {
        model::positive(key, v).map_err(|e| self.model(e))
    }

    /// A number zero or more.
    fn non_negative(&self, key: &str, v: f64) -> Result<f64, SceneError> {
        model::non_negative(key, v).map_err(|e| self.model(e))
    }
}
