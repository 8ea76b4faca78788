//! Scene model: the frame (contact triangle), the foundation (three planes), and, for commands
//! that simulate, the block, loads, friction and solver settings.
//!
//! A scene is read from TOML ([`Scene::from_toml`], [`Scene::from_file`]) and validated: every
//! bad input is a [`SceneError`] naming the key and the reason. Angles are degrees in the file
//! and radians in these types. Coordinates follow `docs/conventions.md` (README, "Coordinates").

pub mod cases;
mod checks;
mod dam;
mod echo;
mod error;
mod files;
pub mod input;
mod raw;
mod read;
pub mod record;
mod simulation;
mod strengths;
mod validate;
pub mod water;

pub use echo::LoadsUsed;
pub use error::{SceneError, SceneErrorKind};
pub use simulation::Simulation;
pub use strengths::{FaceStrength, Strength, Strengths};
pub use validate::MAX_INCREMENTS;

use std::path::Path;

/// The scene compiled into the binary: the paper-like scene of `scenes/paper-like.toml`.
pub const DEFAULT_SCENE_TOML: &str = include_str!("../../scenes/paper-like.toml");
/// The origin named in errors about the embedded default scene.
pub const DEFAULT_ORIGIN: &str = "<embedded default scene>";

pub use crate::geometry::site::{Foundation, Frame, Site};

/// Mass properties of the monolith. Read from a scene ([`Scene::block`]); built only by its
/// validation.
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub struct Block {
    /// m (kg).
    pub mass: f64,
    /// I_m about the frame normal y' (kg·m²): the paper's only moment of inertia.
    pub inertia: f64,
    /// Moment about x' (kg·m²; rigid-body mode). Default: `inertia / 2` (thin plate).
    pub inertia_x: f64,
    /// Moment about z' (kg·m²; rigid-body mode). Default: `inertia / 2` (thin plate).
    pub inertia_z: f64,
    /// Product of inertia ∫ x' z' dm (kg·m²; rigid-body mode), entering the tensor as −I_xz.
    /// Default 0.
    pub inertia_xz: f64,
    /// Product of inertia ∫ x' y' dm (kg·m²; rigid-body mode), entering the tensor as −I_xy:
    /// a monolith's section is not symmetric about its centre's height (`[monolith]`).
    /// 0 for `[block]`.
    pub inertia_xy: f64,
}

impl Block {
    /// The inertia tensor about the CM in the block's axes (x', y', z') (kg·m²).
    pub fn tensor(&self) -> nalgebra::Matrix3<f64> {
        nalgebra::Matrix3::new(
            self.inertia_x,
            -self.inertia_xy,
            -self.inertia_xz,
            -self.inertia_xy,
            self.inertia,
            0.0,
            -self.inertia_xz,
            0.0,
            self.inertia_z,
        )
    }
}

/// Which dynamics moves the block.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Serialize)]
#[cfg_attr(feature = "cli", derive(clap::ValueEnum))]
#[serde(rename_all = "kebab-case")]
pub enum DynamicsModel {
    /// The paper's (§5–7): translation along x' and rotation about y', shear directions
    /// chosen so that this holds (`mechanics::reactions_paper`).
    Paper,
    /// A rigid body with the three contacts held on their planes and Coulomb-type friction
    /// opposing each contact's slip (`mechanics::rigid_body`, `derivations/08-rigid-body.md`).
    /// The default (issue #12): it moves every scene the paper's dynamics moves, and many it
    /// cannot start or continue.
    #[default]
    RigidBody,
}

impl DynamicsModel {
    /// Every model, in the order the documentation lists them.
    pub const ALL: [DynamicsModel; 2] = [DynamicsModel::Paper, DynamicsModel::RigidBody];

    pub fn as_str(self) -> &'static str {
        match self {
            DynamicsModel::Paper => "paper",
            DynamicsModel::RigidBody => "rigid-body",
        }
    }
}

/// The loads (`derivations/11-dam-loads.md`). The driving ones — the water's push and its
/// couples, the horizontal pseudo-static force — are those the factor of safety scales; the
/// weight, the uplift, the tailwater's weight and the vertical pseudo-static force stay.
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub struct Loads {
    /// |F| (N), acting along x': `loads.hydraulic_force_n`, or from `[water]` the reservoir's
    /// push less the tailwater's.
    pub hydraulic_force: f64,
    /// c (m): F's line misses the CM by c; c > 0 turns the block so that θ grows.
    pub eccentricity: f64,
    /// g (m/s²).
    pub gravity: f64,
    /// The moment of the water's pushes about the base point under the CM, along k' (N·m):
    /// −Σ H y over the pushes at heights y above the base. 0 for `loads.hydraulic_force_n`,
    /// which acts in the base plane (the paper's).
    pub hydraulic_pitch: f64,
    /// The loads that stay, other than the weight, in the block's axes: the uplift less the
    /// tailwater's weight on the downstream face, along y' (N), and their moment along k' about
    /// the base point under the CM (N·m).
    pub held_normal: f64,
    pub held_pitch: f64,
    /// Pseudo-static coefficients (fractions of g): horizontal along +X (downstream), vertical
    /// up.
    pub kh: f64,
    pub kv: f64,
    /// The CM's height above the base plane (m), where the weight and the pseudo-static forces
    /// act: from `[monolith]`; 0 for `[block]` (the paper's frame, CM in the base plane).
    pub cm_height: f64,
    /// The water's loads from levels, where the scene gives `[water]`.
    pub water: Option<crate::scene::water::WaterLoads>,
}

impl Loads {
    /// Loads of `[loads]` alone: a force F in the base plane with its couple −cF, gravity g.
    pub fn plain(hydraulic_force: f64, eccentricity: f64, gravity: f64) -> Loads {
        Loads {
            hydraulic_force,
            eccentricity,
            gravity,
            hydraulic_pitch: 0.0,
            held_normal: 0.0,
            held_pitch: 0.0,
            kh: 0.0,
            kv: 0.0,
            cm_height: 0.0,
            water: None,
        }
    }
}

/// Friction criterion at the contacts (paper eqs. (24b) and (43)).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Friction {
    /// |S| = μ_k |N| (eq. 24b).
    #[non_exhaustive]
    Coulomb { mu_k: f64 },
    /// Barton–Choubey, normalised per contact (eq. 43): τ = σ tan(JRC log10(JCS/σ) + φ_r),
    /// with σ = |N| / contact area. `phi_r` in radians.
    #[non_exhaustive]
    BartonChoubey {
        jrc: f64,
        jcs_pa: f64,
        phi_r: f64,
        contact_area_m2: f64,
    },
}

impl Friction {
    /// The models' names in a scene file (`[friction] model`), in the order of the variants.
    pub const MODELS: [&'static str; 2] = ["coulomb", "barton-choubey"];
}

/// Which polynomial system gives the pose.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[cfg_attr(feature = "cli", derive(clap::ValueEnum))]
#[serde(rename_all = "kebab-case")]
pub enum Mode {
    /// The exact relations (13), (14) (see `derivations/04-exact.md`).
    Exact,
    /// The paper's small-angle system (15) (see `derivations/03-small-angle.md`).
    SmallAngle,
}

impl Mode {
    pub const ALL: [Mode; 2] = [Mode::Exact, Mode::SmallAngle];

    pub fn as_str(self) -> &'static str {
        match self {
            Mode::Exact => "exact",
            Mode::SmallAngle => "small-angle",
        }
    }
}

/// How the state is advanced over one increment.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Integrator {
    /// The paper's update (30)–(41): accelerations at the start of the increment, then
    /// v += a·dt and x += v·dt + a·dt²/2. First order.
    #[default]
    Paper,
    /// Classic fourth-order Runge–Kutta on the same right-hand side.
    Rk4,
}

impl Integrator {
    pub const ALL: [Integrator; 2] = [Integrator::Paper, Integrator::Rk4];

    pub fn as_str(self) -> &'static str {
        match self {
            Integrator::Paper => "paper",
            Integrator::Rk4 => "rk4",
        }
    }
}

/// The motion at t = 0: the CM velocity (Ẋ, Ż) and the yaw rate θ̇ (rad/s). Default: at rest.
/// A block set moving — by a transient such as an earthquake pulse, as in Newmark's sliding
/// block — under loads that static friction can hold decelerates and stops.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
#[non_exhaustive]
pub struct Initial {
    pub vx: f64,
    pub vz: f64,
    pub omega: f64,
}

impl Initial {
    /// Whether the block starts at rest.
    pub fn at_rest(&self) -> bool {
        self.vx == 0.0 && self.vz == 0.0 && self.omega == 0.0
    }
}

/// Time stepping: the run settings of `[solver]`.
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub struct Solver {
    pub mode: Mode,
    /// Increment length (s).
    pub dt: f64,
    /// Time limit (s).
    pub t_end: f64,
    pub integrator: Integrator,
    /// Record every `stride`-th increment (≥ 1).
    pub stride: usize,
    pub dynamics: DynamicsModel,
}

/// A validated scene: read from a file or text ([`Scene::from_file`], [`Scene::from_toml`]) or
/// made from one by changing keys ([`Scene::with`]), and in no other way, so that every scene
/// is one a file could give. `frame` and `foundation` are always present; the other sections
/// are needed only by commands that simulate ([`Simulation::new`]).
#[derive(Debug, Clone)]
pub struct Scene {
    pub(crate) name: String,
    /// Where the scene came from (file path or [`DEFAULT_ORIGIN`]), used in error messages.
    pub(crate) origin: String,
    /// The contact frame and the foundation: all that geometry, the coefficients and the roots
    /// take of a scene.
    pub(crate) site: Site,
    pub(crate) block: Option<Block>,
    pub(crate) loads: Option<Loads>,
    pub(crate) friction: Option<Friction>,
    pub(crate) solver: Option<Solver>,
    /// `[initial]`: the motion at t = 0 (absent: at rest).
    pub(crate) initial: Initial,
    /// The document as read, in the file's keys and units: what [`Scene::with`] edits.
    pub(crate) source: toml::Table,
    /// The folder the files the scene names (a surface) are found from.
    pub(crate) folder: std::path::PathBuf,
    /// `[check]`: the guideline the load cases' requirements come from.
    pub(crate) guideline: cases::Guideline,
    /// `[[case]]`: the load combinations `check` runs.
    pub(crate) cases: Vec<cases::LoadCase>,
    /// `seismic.record`: the foundation's acceleration in time.
    pub(crate) record: Option<std::sync::Arc<record::Record>>,
    /// `[friction]`'s cohesion and `[[friction.face]]`.
    pub(crate) strengths: Strengths,
    /// `[uncertain]`: the distributions of a probabilistic analysis, by key name.
    pub(crate) uncertain: Vec<crate::numeric::Uncertain>,
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
            &self.friction,
            &self.solver,
            &self.initial,
            &self.strengths,
            self.record.as_deref(),
            &self.uncertain,
        ) == (
            &other.name,
            &other.origin,
            &other.site,
            &other.block,
            &other.loads,
            &other.friction,
            &other.solver,
            &other.initial,
            &other.strengths,
            other.record.as_deref(),
            &other.uncertain,
        )
    }
}

impl Scene {
    /// The embedded default scene (paper-like).
    pub fn default_scene() -> Scene {
        Scene::from_toml(DEFAULT_SCENE_TOML, DEFAULT_ORIGIN)
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
        read::from_table(table, origin, (folder, &files::Files::default()))
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
        let mut doc = self.source.clone();
        for (key, value) in keys {
            let key = key.as_ref();
            let (section, name) = match key.split_once('.') {
                Some((section, name)) => (Some(section), name),
                None => (None, key),
            };
            let table = match section {
                None => &mut doc,
                Some(section) => doc
                    .entry(section)
                    .or_insert_with(|| toml::Value::Table(toml::Table::new()))
                    .as_table_mut()
                    .ok_or_else(|| {
                        SceneError::of(
                            SceneErrorKind::WrongType,
                            &self.origin,
                            section,
                            "is not a table of keys",
                        )
                    })?,
            };
            table.insert(name.to_string(), value.into());
        }
        read::from_table(doc, &self.origin, (&self.folder, &files::Files::of(self)))
    }

    /// The same scene with the other dynamics model (when it has a `[solver]`). A change of
    /// model brings that model's own integrator, as a scene file without `integrator` would:
    /// "rk4" for the rigid body (its only one), "paper" for the paper's dynamics. The command
    /// line says so when it changes the scene's (`--dynamics`).
    pub fn with_dynamics(&self, model: DynamicsModel) -> Result<Scene, SceneError> {
        match self.solver {
            Some(s) if s.dynamics != model => {
                let mut doc = self.source.clone();
                if let Some(solver) = doc.get_mut("solver").and_then(|v| v.as_table_mut()) {
                    solver.remove("integrator");
                }
                read::from_table(doc, &self.origin, (&self.folder, &files::Files::of(self)))?
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

    /// Where the scene came from: a file path or [`DEFAULT_ORIGIN`].
    pub fn origin(&self) -> &str {
        &self.origin
    }

    /// The frame and the foundation.
    pub fn site(&self) -> &Site {
        &self.site
    }

    /// `[check]`'s guideline (the default when absent).
    pub fn guideline(&self) -> &cases::Guideline {
        &self.guideline
    }

    /// `[[case]]`: the load combinations, each with its requirement.
    pub fn cases(&self) -> &[cases::LoadCase] {
        &self.cases
    }

    /// The same scene with load case `case`'s levels and coefficients set (its origin names
    /// the case).
    pub fn for_case(&self, case: &cases::LoadCase) -> Result<Scene, SceneError> {
        let mut s = self.with_keys(case.keys.iter().map(|(k, v)| (k.as_str(), *v)))?;
        s.name = format!("{}: {}", self.name, case.name);
        Ok(s)
    }

    /// `seismic.record`, when given.
    pub fn record(&self) -> Option<&record::Record> {
        self.record.as_deref()
    }

    /// The foundation's acceleration (g, along X, Y, Z) at time t: the record's, or none.
    pub fn ground(&self, t: f64) -> [f64; 3] {
        self.record.as_ref().map_or([0.0; 3], |r| r.at(t))
    }

    /// `[block]`, when given.
    pub fn block(&self) -> Option<&Block> {
        self.block.as_ref()
    }

    /// `[loads]`, when given.
    pub fn loads(&self) -> Option<&Loads> {
        self.loads.as_ref()
    }

    /// `[friction]`, when given.
    pub fn friction(&self) -> Option<&Friction> {
        self.friction.as_ref()
    }

    /// `[solver]`, the run settings, when given.
    pub fn solver(&self) -> Option<&Solver> {
        self.solver.as_ref()
    }

    /// `[initial]`: the motion at t = 0 (at rest when absent).
    pub fn initial(&self) -> &Initial {
        &self.initial
    }

    /// The frame's side L (m; for any triangle, its longest side over √2).
    pub fn l(&self) -> f64 {
        self.site.l()
    }

    /// Values that are valid but likely mistakes, one line each naming the key (issue #13): a
    /// dip under 1° (often radians typed as degrees) and a friction coefficient over 2.
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
        if let Some(Friction::Coulomb { mu_k }) = self.friction {
            if mu_k > 2.0 {
                w.push(format!(
                    "{}: friction.mu_k: μ = {mu_k} is over 2, far above any rock joint's (about \
                     0.3–1)",
                    self.origin
                ));
            }
        }
        w
    }
}

#[cfg(test)]
mod tests;
