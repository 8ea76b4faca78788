//! The scene reader: a scene file (TOML, degrees, the documented keys) read, validated and
//! turned into the model (`model/`) and the site (`geometry/`), every bad input a
//! [`SceneError`] naming its key, its line and the reason; the scene as used echoed back in the
//! file's own keys; and a scene changed by key ([`Scene::with`]), validated as a file with that
//! line would be. Angles are degrees in the file and radians in the model. Coordinates follow
//! `docs/conventions.md`.

mod echo;
mod error;
mod files;
pub mod input;
mod obj;
mod raw;
mod read;
mod record_files;
mod simulation;
mod validate;

pub use echo::LoadsUsed;
pub use error::{SceneError, SceneErrorKind};
pub(crate) use raw::keys_of;

use crate::geometry::Site;
use crate::model::{
    Block, Contacts, DynamicsModel, Friction, Guideline, Initial, LoadCase, Loads, Record,
    RunSettings, Strengths,
};
use std::path::Path;

/// A validated scene: read from a file or text ([`Scene::from_file`], [`Scene::from_toml`]) or
/// made from one by changing keys ([`Scene::with`]), and in no other way, so that every scene
/// is one a file could give. `frame` and `foundation` are always present; the other sections
/// are needed only by commands that simulate ([`Scene::simulation`]).
#[derive(Debug, Clone)]
pub struct Scene {
    pub(crate) name: String,
    /// Where the scene came from (file path or [`Scene::DEFAULT_ORIGIN`]), used in error
    /// messages.
    pub(crate) origin: String,
    /// The contact frame and the foundation: all that geometry, the coefficients and the roots
    /// take of a scene.
    pub(crate) site: Site,
    pub(crate) block: Option<Block>,
    pub(crate) loads: Option<Loads>,
    pub(crate) settings: Option<RunSettings>,
    /// `[initial]`: the motion at t = 0 (absent: at rest).
    pub(crate) initial: Initial,
    /// The document as read, in the file's keys and units: what [`Scene::with`] edits.
    pub(crate) source: toml::Table,
    /// The folder the files the scene names (a surface) are found from.
    pub(crate) folder: std::path::PathBuf,
    /// `[check]`: the guideline the load cases' requirements come from.
    pub(crate) guideline: Guideline,
    /// `[[case]]`: the load combinations `check` runs.
    pub(crate) cases: Vec<LoadCase>,
    /// `seismic.record`: the foundation's acceleration in time.
    pub(crate) record: Option<std::sync::Arc<Record>>,
    /// `seismic.polarity = "both"`: the record run as it is and reversed, the larger
    /// permanent displacement reported.
    pub(crate) both_polarities: bool,
    /// `[friction]`: the default criterion and cohesion, and `[[friction.face]]`.
    pub(crate) strengths: Option<Strengths>,
    /// The bonded area each of the frame's contacts stands for (m²; `friction.cohesion_area_m2`
    /// or the monolith's base, shared among the contacts).
    pub(crate) shares_m2: [f64; 3],
    /// `[uncertain]`: the distributions of a probabilistic analysis, by key name.
    pub(crate) uncertain: Vec<crate::numeric::Uncertain>,
    /// `[base]`, or a monolith's base rectangle: the footprint under `contacts = "base"`.
    pub(crate) base: Option<crate::model::Base>,
    /// `[monolith]`: the section the block's mass and the water's loads come from.
    pub(crate) monolith: Option<crate::model::Monolith>,
    /// `[[anchor]]`: post-tensioned anchors through the monolith.
    pub(crate) anchors: Vec<crate::model::RockAnchor>,
}

/// Two scenes are equal when their values are (the documents may differ in how they wrote
/// them).
impl PartialEq for Scene {
    fn eq(&self, other: &Scene) -> bool {
        (
            &self.name,
            &self.origin,
            &self.site,
            &self.block,
            &self.loads,
            &self.settings,
            &self.initial,
            (&self.strengths, &self.shares_m2),
            (self.record.as_deref(), self.both_polarities),
            &self.uncertain,
            &self.base,
        ) == (
            &other.name,
            &other.origin,
            &other.site,
            &other.block,
            &other.loads,
            &other.settings,
            &other.initial,
            (&other.strengths, &other.shares_m2),
            (other.record.as_deref(), other.both_polarities),
            &other.uncertain,
            &other.base,
        ) && self.monolith == other.monolith
            && self.anchors == other.anchors
    }
}

impl Scene {
    /// The scene compiled into the library: the paper-like scene of `scenes/paper-like.toml`.
    pub const DEFAULT_TOML: &'static str = include_str!("../../scenes/paper-like.toml");

    /// A commented gravity-dam scene to start from (`scenes/dam.toml`, `slideroute scene
    /// --template dam`): a monolith with its water, silt, ice, guideline and load cases.
    pub const DAM_TOML: &'static str = include_str!("../../scenes/dam.toml");

    /// The origin named in errors about the embedded default scene.
    pub const DEFAULT_ORIGIN: &'static str = "<embedded default scene>";

    /// The embedded default scene (paper-like).
    pub fn default_scene() -> Scene {
        Scene::from_toml(Scene::DEFAULT_TOML, Scene::DEFAULT_ORIGIN)
            .expect("the embedded default scene is valid (checked by a test)")
    }

    /// Reads and validates a scene file.
    pub fn from_file(path: &Path) -> Result<Scene, SceneError> {
        let origin = path.display().to_string();
        let text = input::read_bounded(path, input::MAX_SCENE_BYTES)
            .map_err(|e| SceneError::new(&origin, "", e))?;
        // Files the scene names (a surface) are found beside it.
        let folder = path.parent().map(Path::to_path_buf).unwrap_or_default();
        read::from_toml(&text, &origin, &folder)
    }

    /// Parses and validates scene text; `origin` names the source in errors, which give the
    /// line and column of the key they name. Files the scene names are found from the current
    /// folder.
    pub fn from_toml(text: &str, origin: &str) -> Result<Scene, SceneError> {
        read::from_toml(text, origin, Path::new(""))
    }

    /// A scene from a document already parsed (the tables and keys of a scene file: a Python
    /// dict, say), validated as a file is; files it names (a surface, a record) are found from
    /// `folder`.
    pub fn from_document(
        table: toml::Table,
        origin: &str,
        folder: &Path,
    ) -> Result<Scene, SceneError> {
        let files = files::Files::default();
        read::from_table(
            table,
            origin,
            files::Sources {
                folder,
                files: &files,
            },
        )
    }

    /// The same scene with one key set, in the file's own key and units
    /// (`with("friction.mu_k", 0.3)`, `with("foundation.xi_deg", 18.0)`,
    /// `with("solver.dynamics", "paper")`): the scene a file with that line would give, validated
    /// as a file is. A section not yet present is added.
    pub fn with(&self, key: &str, value: impl Into<toml::Value>) -> Result<Scene, SceneError> {
        self.with_keys([(key, value)])
    }

    /// The same scene with several keys set at once and then validated, as [`Scene::with`]
    /// does for one: keys that must agree (the frame's lengths) change together.
    pub fn with_keys<K, V>(
        &self,
        keys: impl IntoIterator<Item = (K, V)>,
    ) -> Result<Scene, SceneError>
    where
        K: AsRef<str>,
        V: Into<toml::Value>,
    {
        self.with_keys_of(self.source.clone(), keys)
    }

    /// [`Scene::with_keys`] on `doc`, this scene's document or a part of it.
    fn with_keys_of<K, V>(
        &self,
        mut doc: toml::Table,
        keys: impl IntoIterator<Item = (K, V)>,
    ) -> Result<Scene, SceneError>
    where
        K: AsRef<str>,
        V: Into<toml::Value>,
    {
        for (key, value) in keys {
            let key = key.as_ref();
            // `.mu_k`, `friction.`, `a..b`: no key of any section (the error would name none).
            if key.split('.').any(|part| part.trim().is_empty()) {
                return Err(SceneError::of(
                    SceneErrorKind::UnknownKey,
                    &self.origin,
                    key,
                    "not a key: a key is `section.key` (`friction.mu_k`), or `name`",
                ));
            }
            let (section, name) = match key.split_once('.') {
                Some((section, name)) => (Some(section), name),
                None => (None, key),
            };
            // A list item's section, `anchor[1]`: the item of that list the file gave.
            let item = section.and_then(|s| {
                let (list, rest) = s.split_once('[')?;
                Some((list, rest.strip_suffix(']')?.parse::<usize>().ok()?))
            });
            let not_table = |section: &str, what: &str| {
                SceneError::of(
                    SceneErrorKind::WrongType,
                    &self.origin,
                    section,
                    what.to_string(),
                )
            };
            let table = match (section, item) {
                (None, _) => &mut doc,
                (Some(section), Some((list, k))) => doc
                    .get_mut(list)
                    .and_then(toml::Value::as_array_mut)
                    .and_then(|a| a.get_mut(k))
                    .and_then(toml::Value::as_table_mut)
                    .ok_or_else(|| {
                        not_table(
                            section,
                            &format!("the scene has no [[{list}]] number {k} (from 0) to change"),
                        )
                    })?,
                (Some(section), None) => doc
                    .entry(section)
                    .or_insert_with(|| toml::Value::Table(toml::Table::new()))
                    .as_table_mut()
                    .ok_or_else(|| not_table(section, "is not a table of keys"))?,
            };
            table.insert(name.to_string(), value.into());
        }
        let files = files::Files::of(self);
        let sources = files::Sources {
            folder: &self.folder,
            files: &files,
        };
        read::from_table(doc, &self.origin, sources)
    }

    /// The same scene with the other dynamics model (when it has a `[solver]`). A change of
    /// model brings that model's own integrator, as a scene file without `integrator` would:
    /// "rk4" for the rigid body (its only one), "paper" for the paper's dynamics. The command
    /// line says so when it changes the scene's (`--dynamics`).
    pub fn with_dynamics(&self, model: DynamicsModel) -> Result<Scene, SceneError> {
        match self.settings {
            Some(s) if s.dynamics != model => {
                let mut doc = self.source.clone();
                if let Some(solver) = doc.get_mut("solver").and_then(|v| v.as_table_mut()) {
                    solver.remove("integrator");
                }
                let files = files::Files::of(self);
                let sources = files::Sources {
                    folder: &self.folder,
                    files: &files,
                };
                read::from_table(doc, &self.origin, sources)?
                    .with("solver.dynamics", model.as_str())
            }
            _ => Ok(self.clone()),
        }
    }

    /// The folder the files the scene names (a surface, a record) are found from.
    pub fn folder(&self) -> &Path {
        &self.folder
    }

    /// `[uncertain]`: the distributions a probabilistic analysis samples, by key name (none if
    /// the scene has no such table).
    pub fn uncertain(&self) -> &[crate::numeric::Uncertain] {
        &self.uncertain
    }

    /// The document as read, in the file's own keys and units (defaults not filled in; see
    /// [`Scene::as_used`] for those).
    pub fn document(&self) -> &toml::Table {
        &self.source
    }

    /// The scene's name (`name`; "unnamed" when the file gives none).
    pub fn name(&self) -> &str {
        &self.name
    }

    /// Where the scene came from: a file path or [`Scene::DEFAULT_ORIGIN`].
    pub fn origin(&self) -> &str {
        &self.origin
    }

    /// The frame and the foundation.
    pub fn site(&self) -> &Site {
        &self.site
    }

    /// `[check]`'s guideline (the default when absent).
    pub fn guideline(&self) -> &Guideline {
        &self.guideline
    }

    /// `[[case]]`: the load combinations, each with its requirement.
    pub fn cases(&self) -> &[LoadCase] {
        &self.cases
    }

    /// The same scene with load case `case`'s levels and coefficients set (its origin names
    /// the case).
    pub fn for_case(&self, case: &LoadCase) -> Result<Scene, SceneError> {
        // The case's scene without the `[[case]]` list: reading the others again for each would
        // make a check quadratic in its cases.
        let doc: toml::Table = self
            .source
            .iter()
            .filter(|(k, _)| k.as_str() != "case")
            .map(|(k, v)| (k.clone(), v.clone()))
            .collect();
        let mut s = self
            .with_keys_of(doc, case.keys.iter().map(|(k, v)| (k.as_str(), *v)))
            .map_err(|mut e| {
                if case.keys.iter().any(|(k, _)| *k == e.key) {
                    e.reason = format!("in case \"{}\": {}", case.name, e.reason);
                }
                e
            })?;
        s.name = format!("{}: {}", self.name, case.name);
        Ok(s)
    }

    /// `seismic.record`, when given.
    pub fn record(&self) -> Option<&Record> {
        self.record.as_deref()
    }

    /// `[friction]` and `[[friction.face]]`, when given: every face's criterion and cohesion.
    pub fn strengths(&self) -> Option<&Strengths> {
        self.strengths.as_ref()
    }

    /// `[monolith]`, when given.
    pub fn monolith(&self) -> Option<&crate::model::Monolith> {
        self.monolith.as_ref()
    }

    /// The block's own footprint (`[base] outline_m`, or a monolith's base rectangle; a cast
    /// block's frame rectangle), when it has one; none for a flat block given only by its
    /// frame, whose base is its frame's bounding rectangle where a base is needed.
    pub fn base(&self) -> Option<&crate::model::Base> {
        self.base.as_ref()
    }

    /// `[[anchor]]`: the anchors through the monolith, as given.
    pub fn anchors(&self) -> &[crate::model::RockAnchor] {
        &self.anchors
    }

    /// `[block]`, or the monolith's mass properties.
    pub fn block(&self) -> Option<&Block> {
        self.block.as_ref()
    }

    /// `[loads]`, when given.
    pub fn loads(&self) -> Option<&Loads> {
        self.loads.as_ref()
    }

    /// `[friction]`'s criterion of faces without their own, when given.
    pub fn friction(&self) -> Option<&Friction> {
        self.strengths.as_ref().map(|s| &s.friction)
    }

    /// `[solver]`, the run settings, when given.
    pub fn settings(&self) -> Option<&RunSettings> {
        self.settings.as_ref()
    }

    /// `[initial]`: the motion at t = 0 (at rest when absent).
    pub fn initial(&self) -> &Initial {
        &self.initial
    }

    /// The frame's side L (m; for any triangle, its longest side over √2).
    pub fn l(&self) -> f64 {
        self.site.l()
    }

    /// Values that are valid but likely mistakes, one line each naming the key: a
    /// dip under 1° (often radians typed as degrees), a friction coefficient over 2, and a
    /// tolerance given to the block on its base, which holds it only on one face of the rock.
    pub fn warnings(&self) -> Vec<String> {
        let mut w = Vec::new();
        // The dips as written: the paper's two, or each face's (a level face, 0°, is meant).
        let foundation = self.source.get("foundation").and_then(|f| f.as_table());
        let number = |v: &toml::Value| v.as_float().or_else(|| v.as_integer().map(|i| i as f64));
        let mut dips: Vec<(String, f64)> = ["xi_deg", "zeta_deg"]
            .into_iter()
            .filter_map(|k| Some((format!("foundation.{k}"), number(foundation?.get(k)?)?)))
            .collect();
        if let Some(faces) = foundation.and_then(|f| f.get("plane")?.as_array()) {
            for (k, face) in faces.iter().enumerate() {
                if let Some(d) = face.get("dip_deg").and_then(number) {
                    dips.push((format!("foundation.plane[{k}].dip_deg"), d));
                }
            }
        }
        for (key, deg) in dips {
            if deg > 0.0 && deg < 1.0 {
                w.push(format!(
                    "{}: {key}: a dip of {deg}° is under 1° — degrees are meant (were radians \
                     typed?)",
                    self.origin
                ));
            }
        }
        if let Some(Friction::Coulomb { mu_k }) = self.friction().copied()
            && mu_k > 2.0
        {
            w.push(format!(
                "{}: friction.mu_k: μ = {mu_k} is over 2, far above any rock joint's (about \
                     0.3–1)",
                self.origin
            ));
        }
        let tolerance = self.source.get("solver").and_then(|t| t.get("tolerance"));
        if let (Some(_), Some(settings)) = (tolerance, &self.settings)
            && settings.contacts == Contacts::Base
        {
            w.push(format!(
                "{}: solver.tolerance: holds the block on its base (solver.contacts = \"base\") \
                 only while every touch is on one face of the rock; on two faces or more it steps \
                 by solver.dt_s (first order: halve dt_s to halve its error; summary.json's \
                 first_order says when)",
                self.origin
            ));
        }
        w
    }
}

#[cfg(test)]
mod tests;
