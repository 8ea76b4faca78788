//! Scene model: the frame (contact triangle), the foundation (three planes), and, for commands
//! that simulate, the block, loads, friction and solver settings.
//!
//! A scene is read from TOML ([`Scene::from_toml`], [`Scene::from_file`]) and validated: every
//! bad input is a [`SceneError`] naming the key and the reason. Angles are degrees in the file
//! and radians in these types. Coordinates follow `docs/conventions.md` (README, "Coordinates").

mod echo;
mod error;
pub mod input;
mod raw;

pub use error::SceneError;

use serde::Deserialize;
use std::path::Path;

/// The scene compiled into the binary: the paper-like scene of `scenes/paper-like.toml`.
pub const DEFAULT_SCENE_TOML: &str = include_str!("../../scenes/paper-like.toml");
/// The origin named in errors about the embedded default scene.
pub const DEFAULT_ORIGIN: &str = "<embedded default scene>";

pub use crate::geometry::site::{Foundation, Frame, Site};

/// Mass properties of the monolith.
#[derive(Debug, Clone, Copy, PartialEq)]
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
}

impl Block {
    /// The inertia tensor about the CM in the block's axes (x', y', z') (kg·m²).
    pub fn tensor(&self) -> nalgebra::Matrix3<f64> {
        nalgebra::Matrix3::new(
            self.inertia_x,
            0.0,
            -self.inertia_xz,
            0.0,
            self.inertia,
            0.0,
            -self.inertia_xz,
            0.0,
            self.inertia_z,
        )
    }
}

/// Which dynamics moves the block.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Deserialize, serde::Serialize)]
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
    pub fn as_str(self) -> &'static str {
        match self {
            DynamicsModel::Paper => "paper",
            DynamicsModel::RigidBody => "rigid-body",
        }
    }
}

/// The driving loads.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Loads {
    /// |F| (N), acting along x'.
    pub hydraulic_force: f64,
    /// c (m): F's line misses the CM by c; c > 0 turns the block so that θ grows.
    pub eccentricity: f64,
    /// g (m/s²).
    pub gravity: f64,
}

/// Friction criterion at the contacts (paper eqs. (24b) and (43)).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Friction {
    /// |S| = μ_k |N| (eq. 24b).
    Coulomb { mu_k: f64 },
    /// Barton–Choubey, normalised per contact (eq. 43): τ = σ tan(JRC log10(JCS/σ) + φ_r),
    /// with σ = |N| / contact area. `phi_r` in radians.
    BartonChoubey {
        jrc: f64,
        jcs_pa: f64,
        phi_r: f64,
        contact_area_m2: f64,
    },
}

/// Which polynomial system gives the pose.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize, serde::Serialize)]
#[cfg_attr(feature = "cli", derive(clap::ValueEnum))]
#[serde(rename_all = "kebab-case")]
pub enum Mode {
    /// The exact relations (13), (14) (see `derivations/04-exact.md`).
    Exact,
    /// The paper's small-angle system (15) (see `derivations/03-small-angle.md`).
    SmallAngle,
}

impl Mode {
    pub fn as_str(self) -> &'static str {
        match self {
            Mode::Exact => "exact",
            Mode::SmallAngle => "small-angle",
        }
    }
}

/// How the state is advanced over one increment.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Deserialize, serde::Serialize)]
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

/// Time stepping.
#[derive(Debug, Clone, Copy, PartialEq)]
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

/// A validated scene. `frame` and `foundation` are always present; the other sections are
/// needed only by commands that simulate ([`Simulation::new`]).
#[derive(Debug, Clone, PartialEq)]
pub struct Scene {
    pub name: String,
    /// Where the scene came from (file path or [`DEFAULT_ORIGIN`]), used in error messages.
    pub origin: String,
    /// The contact frame and the foundation: all that geometry, the coefficients and the roots
    /// take of a scene.
    pub site: Site,
    pub block: Option<Block>,
    pub loads: Option<Loads>,
    pub friction: Option<Friction>,
    pub solver: Option<Solver>,
    /// `[initial]`: the motion at t = 0 (absent: at rest).
    pub initial: Initial,
}

/// A scene that can be run (issue #14): its physical model — the frame and foundation, the
/// block, the loads, the friction — and its run settings (`[solver]`), every section present and
/// their combination valid, settled once when it is built ([`Simulation::new`]). Its fields are
/// private: a `Simulation` exists only as validated, and running one checks nothing again.
#[derive(Debug, Clone, PartialEq)]
pub struct Simulation {
    scene: Scene,
    block: Block,
    loads: Loads,
    friction: Friction,
    settings: Solver,
    /// The upward unit normals of the planes under vertices 0, 1, 2 (horizontal, plane 1,
    /// plane 2), computed once.
    normals: [nalgebra::Vector3<f64>; 3],
}

impl Simulation {
    /// The scene's simulation, or an error naming the first missing section or the setting that
    /// cannot be run as written.
    pub fn new(scene: &Scene) -> Result<Simulation, SceneError> {
        let missing = |section: &str| {
            SceneError::new(
                &scene.origin,
                section,
                format!("missing section [{section}] (needed to simulate)"),
            )
        };
        let block = scene.block.ok_or_else(|| missing("block"))?;
        // The values too, as a file's would be: a scene's fields are public, and one built by
        // hand has not been through [`Scene::from_toml`]. Its echo in the file's own keys
        // (`echo.rs`) is validated; the simulation keeps the scene's own numbers.
        let echo = toml::Value::Table(scene.as_used());
        let raw: raw::RawScene = echo.try_into().map_err(|e: toml::de::Error| {
            SceneError::new(&scene.origin, "", e.message().to_string())
        })?;
        validate(raw, &scene.origin)?;
        let loads = scene.loads.ok_or_else(|| missing("loads"))?;
        let friction = scene.friction.ok_or_else(|| missing("friction"))?;
        let settings = scene.solver.ok_or_else(|| missing("solver"))?;
        if settings.dynamics == DynamicsModel::RigidBody && settings.mode == Mode::SmallAngle {
            return Err(SceneError::new(
                &scene.origin,
                "solver.mode",
                "the rigid-body dynamics needs mode = \"exact\": small-angle poses (the paper's \
                 approximation (15)) leave the contacts off their planes (about 1 % in α at \
                 20–25° dips), which the rigid body's contact constraints cannot follow (the \
                 tracker then takes about a thousand steps an increment); use \"exact\", or \
                 dynamics = \"paper\" (--dynamics paper) for the small-angle system",
            ));
        }
        Ok(Simulation {
            scene: scene.clone(),
            block,
            loads,
            friction,
            settings,
            normals: scene.site.foundation.normals(),
        })
    }

    /// The scene it was built from (name, frame, foundation, initial motion).
    pub fn scene(&self) -> &Scene {
        &self.scene
    }

    pub fn block(&self) -> &Block {
        &self.block
    }

    pub fn loads(&self) -> &Loads {
        &self.loads
    }

    pub fn friction(&self) -> &Friction {
        &self.friction
    }

    /// The run settings: mode, dynamics, integrator, dt, t_end, stride.
    pub fn solver(&self) -> &Solver {
        &self.settings
    }

    /// The upward unit normals of the planes under vertices 0, 1, 2.
    pub fn normals(&self) -> &[nalgebra::Vector3<f64>; 3] {
        &self.normals
    }
}

/// The most increments one run may take (t_end / dt).
pub const MAX_INCREMENTS: f64 = 1e8;

/// Relative tolerance on L1X + L2X = L1Z + L2Z.
const FRAME_TOLERANCE: f64 = 1e-9;

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
        Scene::from_toml(&text, &origin)
    }

    /// Parses and validates scene text; `origin` names the source in errors.
    pub fn from_toml(text: &str, origin: &str) -> Result<Scene, SceneError> {
        let raw = parse(text, origin)?;
        validate(raw, origin)
    }

    /// The same scene with the other dynamics model (when it has a `[solver]`). A change of
    /// model brings that model's own integrator, as a scene file without `integrator` would:
    /// "rk4" for the rigid body (its only one), "paper" for the paper's dynamics. The command
    /// line says so when it changes the scene's (`--dynamics`).
    pub fn with_dynamics(&self, model: DynamicsModel) -> Scene {
        let mut s = self.clone();
        if let Some(solver) = &mut s.solver {
            if solver.dynamics != model {
                solver.integrator = match model {
                    DynamicsModel::RigidBody => Integrator::Rk4,
                    DynamicsModel::Paper => Integrator::Paper,
                };
            }
            solver.dynamics = model;
        }
        s
    }

    /// Side length L (m).
    pub fn l(&self) -> f64 {
        self.site.frame.l()
    }

    /// Values that are valid but likely mistakes, one line each naming the key (issue #13): a
    /// dip under 1° (often radians typed as degrees) and a friction coefficient over 2.
    pub fn warnings(&self) -> Vec<String> {
        let mut w = Vec::new();
        for (key, dip) in [
            ("foundation.xi_deg", self.site.foundation.xi),
            ("foundation.zeta_deg", self.site.foundation.zeta),
        ] {
            let deg = dip.to_degrees();
            if deg < 1.0 {
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

fn line_col(text: &str, offset: usize) -> (usize, usize) {
    let mut end = offset.min(text.len());
    while !text.is_char_boundary(end) {
        end -= 1;
    }
    let before = &text[..end];
    let line = before.matches('\n').count() + 1;
    let col = before.rsplit('\n').next().map_or(0, |l| l.chars().count()) + 1;
    (line, col)
}

/// The first backquoted name in a serde message (`unknown field `foo`, …` → `foo`).
fn quoted_name(msg: &str) -> Option<&str> {
    let start = msg.find('`')? + 1;
    let len = msg[start..].find('`')?;
    Some(&msg[start..start + len])
}

fn parse(text: &str, origin: &str) -> Result<raw::RawScene, SceneError> {
    let de = toml::Deserializer::parse(text).map_err(|e| {
        let mut err = SceneError::new(origin, "", format!("not valid TOML: {}", e.message()));
        err.position = e.span().map(|s| line_col(text, s.start));
        err
    })?;
    serde_path_to_error::deserialize(de).map_err(|e| {
        let path = e.path().to_string();
        let inner = e.inner();
        let msg = inner.message().to_string();
        let parent = if path == "." { String::new() } else { path };
        // The path ends at the offending key for unknown fields and variants, and at the
        // enclosing table for missing fields.
        let join = |name: &str| {
            if parent.is_empty() {
                name.to_string()
            } else if parent == name || parent.ends_with(&format!(".{name}")) {
                parent.clone()
            } else {
                format!("{parent}.{name}")
            }
        };
        let (key, reason) = if msg.starts_with("unknown field") {
            let name = quoted_name(&msg).unwrap_or("?");
            (join(name), format!("unknown key; {msg}"))
        } else if msg.starts_with("missing field") {
            let name = quoted_name(&msg).unwrap_or("?");
            if parent.is_empty() {
                (name.to_string(), format!("missing section [{name}]"))
            } else {
                (join(name), format!("missing key `{name}`"))
            }
        } else if msg.starts_with("unknown variant") && parent.starts_with("friction") {
            (join("model"), format!("unknown friction model; {msg}"))
        } else if msg.starts_with("unknown variant") && parent.ends_with("integrator") {
            (parent.clone(), format!("unknown integrator; {msg}"))
        } else if msg.starts_with("unknown variant") && parent.ends_with("dynamics") {
            (parent.clone(), format!("unknown dynamics; {msg}"))
        } else if msg.starts_with("unknown variant") && parent.starts_with("solver") {
            (join("mode"), format!("unknown solver mode; {msg}"))
        } else {
            (parent.clone(), msg.clone())
        };
        let mut err = SceneError::new(origin, key, reason);
        err.position = inner.span().map(|s| line_col(text, s.start));
        err
    })
}

/// Checks one number: finite, and `ok(v)`; `what` says what was expected.
fn check(origin: &str, key: &str, v: f64, ok: bool, what: &str) -> Result<f64, SceneError> {
    if !v.is_finite() {
        return Err(SceneError::new(
            origin,
            key,
            format!("must be a finite number, got {v}"),
        ));
    }
    if !ok {
        return Err(SceneError::new(
            origin,
            key,
            format!("must be {what}, got {v}"),
        ));
    }
    Ok(v)
}

fn positive(origin: &str, key: &str, v: f64) -> Result<f64, SceneError> {
    check(origin, key, v, v > 0.0, "positive")
}

fn non_negative(origin: &str, key: &str, v: f64) -> Result<f64, SceneError> {
    check(origin, key, v, v >= 0.0, "zero or positive")
}

/// The block, with the rigid-body inertia defaults (a thin plate in the x'z' plane) and the
/// checks a rigid body's inertia must pass (positive definite, triangle inequalities).
fn block(o: &str, b: &raw::RawBlock) -> Result<Block, SceneError> {
    let inertia = positive(o, "block.inertia_kg_m2", b.inertia_kg_m2)?;
    let inertia_x = match b.inertia_x_kg_m2 {
        Some(v) => positive(o, "block.inertia_x_kg_m2", v)?,
        None => inertia / 2.0,
    };
    let inertia_z = match b.inertia_z_kg_m2 {
        Some(v) => positive(o, "block.inertia_z_kg_m2", v)?,
        None => inertia / 2.0,
    };
    let inertia_xz = match b.inertia_xz_kg_m2 {
        Some(v) => check(o, "block.inertia_xz_kg_m2", v, true, "finite")?,
        None => 0.0,
    };
    let block = Block {
        mass: positive(o, "block.mass_kg", b.mass_kg)?,
        inertia,
        inertia_x,
        inertia_z,
        inertia_xz,
    };
    let key = if b.inertia_xz_kg_m2.is_some() {
        "block.inertia_xz_kg_m2"
    } else {
        "block"
    };
    let p = block.tensor().symmetric_eigenvalues();
    let (lo, hi, sum) = (p.min(), p.max(), p.sum());
    if lo <= 0.0 {
        return Err(SceneError::new(
            o,
            key,
            format!(
                "the inertia tensor is not positive definite (principal moments {:.6e}, {:.6e}, \
                 {:.6e} kg·m²): |inertia_xz| must be below √(inertia_x · inertia_z)",
                p[0], p[1], p[2]
            ),
        ));
    }
    if hi > (sum - hi) * (1.0 + 1e-9) {
        return Err(SceneError::new(
            o,
            key,
            format!(
                "no rigid body has these moments of inertia: the largest principal moment \
                 {hi:.6e} kg·m² exceeds the sum of the other two, {:.6e} kg·m²",
                sum - hi
            ),
        ));
    }
    Ok(block)
}

/// The most a derived ratio may be, either way: the water load against the weight, and a
/// moment of inertia against m L². Each input is finite and positive on its own, but together
/// they can leave the mechanics nothing to compute with (issue #13: a mass of 1e308 kg made the
/// weight infinite and the contact problem "singular"; a water load of 1e308 N, the cone program
/// fail). A dam monolith's ratios are of order one.
const MAX_RATIO: f64 = 1e6;

/// Checks what follows from the inputs: the weight m g is a finite, normal number, the water
/// load is within [`MAX_RATIO`] of it, and each moment of inertia within [`MAX_RATIO`] of m L²
/// either way. The error names the key to change.
fn derived(
    o: &str,
    frame: &Frame,
    block: Option<&Block>,
    loads: Option<&Loads>,
) -> Result<(), SceneError> {
    let (Some(b), Some(l)) = (block, loads) else {
        return Ok(());
    };
    let weight = b.mass * l.gravity;
    if !weight.is_normal() {
        let key = if b.mass > l.gravity {
            "block.mass_kg"
        } else {
            "loads.gravity_m_s2"
        };
        return Err(SceneError::new(
            o,
            key,
            format!(
                "the weight m g = {weight:e} N is not a usable number (mass {:e} kg, gravity {:e} \
                 m/s²)",
                b.mass, l.gravity
            ),
        ));
    }
    if l.hydraulic_force > MAX_RATIO * weight {
        return Err(SceneError::new(
            o,
            "loads.hydraulic_force_n",
            format!(
                "{:e} N is more than {MAX_RATIO:e} times the weight ({weight:e} N, from a mass of \
                 {:e} kg)",
                l.hydraulic_force, b.mass
            ),
        ));
    }
    let ml2 = b.mass * frame.l() * frame.l();
    for (key, i) in [
        ("block.inertia_kg_m2", b.inertia),
        ("block.inertia_x_kg_m2", b.inertia_x),
        ("block.inertia_z_kg_m2", b.inertia_z),
    ] {
        let ratio = i / ml2;
        if !(ratio.is_finite() && (1.0 / MAX_RATIO..=MAX_RATIO).contains(&ratio)) {
            return Err(SceneError::new(
                o,
                key,
                format!(
                    "{i:e} kg·m² against m L² = {ml2:e} kg·m²: a ratio of {ratio:e}, outside \
                     1e-6 … 1e6 (a monolith's is of order 0.1)"
                ),
            ));
        }
    }
    Ok(())
}

fn validate(raw: raw::RawScene, o: &str) -> Result<Scene, SceneError> {
    let f = &raw.frame;
    let frame = Frame {
        l1x: positive(o, "frame.l1x", f.l1x)?,
        l2x: positive(o, "frame.l2x", f.l2x)?,
        l1z: positive(o, "frame.l1z", f.l1z)?,
        l2z: positive(o, "frame.l2z", f.l2z)?,
    };
    let (lx, lz) = (frame.l1x + frame.l2x, frame.l1z + frame.l2z);
    // Each length is finite, but their sum (L, on which every derived length and the pose's
    // coordinates rest) may not be (issue #13: 1.5e308 m each gave NaN tilts); nor may L²,
    // which the pose and the inertia scales use.
    if !(lx * lx).is_finite() || !(lz * lz).is_finite() {
        return Err(SceneError::new(
            o,
            "frame",
            format!(
                "l1x + l2x = {lx:e} m and l1z + l2z = {lz:e} m: the frame's side L (and L²) must \
                 be finite numbers"
            ),
        ));
    }
    if (lx - lz).abs() > FRAME_TOLERANCE * lx.max(lz) {
        return Err(SceneError::new(
            o,
            "frame",
            format!(
                "l1x + l2x = {lx} m but l1z + l2z = {lz} m; the frame is an isosceles right \
                 triangle, so the two sums must be equal"
            ),
        ));
    }

    let d = &raw.foundation;
    let dip = |key: &str, v: f64| {
        check(
            o,
            key,
            v,
            v > 0.0 && v < 90.0,
            "a dip strictly between 0° and 90°",
        )
        .map(f64::to_radians)
    };
    let foundation = Foundation {
        xi: dip("foundation.xi_deg", d.xi_deg)?,
        zeta: dip("foundation.zeta_deg", d.zeta_deg)?,
        kappa: check(
            o,
            "foundation.kappa_deg",
            d.kappa_deg,
            d.kappa_deg > -90.0 && d.kappa_deg < 90.0,
            "an azimuth strictly between -90° and 90°",
        )?
        .to_radians(),
    };

    let block = match &raw.block {
        None => None,
        Some(b) => Some(block(o, b)?),
    };
    let loads = match &raw.loads {
        None => None,
        Some(l) => Some(Loads {
            hydraulic_force: non_negative(o, "loads.hydraulic_force_n", l.hydraulic_force_n)?,
            eccentricity: check(o, "loads.eccentricity_m", l.eccentricity_m, true, "finite")?,
            gravity: positive(o, "loads.gravity_m_s2", l.gravity_m_s2)?,
        }),
    };
    let friction = match &raw.friction {
        None => None,
        Some(raw::RawFriction::Coulomb { mu_k }) => Some(Friction::Coulomb {
            mu_k: non_negative(o, "friction.mu_k", *mu_k)?,
        }),
        Some(raw::RawFriction::BartonChoubey {
            jrc,
            jcs_pa,
            phi_r_deg,
            contact_area_m2,
        }) => Some(Friction::BartonChoubey {
            jrc: non_negative(o, "friction.jrc", *jrc)?,
            jcs_pa: positive(o, "friction.jcs_pa", *jcs_pa)?,
            phi_r: check(
                o,
                "friction.phi_r_deg",
                *phi_r_deg,
                (0.0..90.0).contains(phi_r_deg),
                "an angle from 0° up to (not including) 90°",
            )?
            .to_radians(),
            contact_area_m2: positive(o, "friction.contact_area_m2", *contact_area_m2)?,
        }),
    };
    if let Some(s) = &raw.solver {
        if s.dt_s > s.t_end_s && s.t_end_s > 0.0 {
            return Err(SceneError::new(
                o,
                "solver.dt_s",
                format!(
                    "the increment ({} s) is longer than the whole route (t_end_s = {} s)",
                    s.dt_s, s.t_end_s
                ),
            ));
        }
        let n = s.t_end_s / s.dt_s;
        if s.dt_s > 0.0 && s.t_end_s > 0.0 && n > MAX_INCREMENTS {
            return Err(SceneError::new(
                o,
                "solver.dt_s",
                format!(
                    "t_end_s / dt_s = {n:.3e} increments, more than the {MAX_INCREMENTS:e} one run may take"
                ),
            ));
        }
    }
    let solver = match &raw.solver {
        None => None,
        Some(s) => Some(Solver {
            mode: s.mode,
            dt: positive(o, "solver.dt_s", s.dt_s)?,
            t_end: positive(o, "solver.t_end_s", s.t_end_s)?,
            integrator: match (s.dynamics, s.integrator) {
                (DynamicsModel::Paper, Some(i)) => i,
                (DynamicsModel::Paper, None) => Integrator::Paper,
                (DynamicsModel::RigidBody, Some(Integrator::Rk4) | None) => Integrator::Rk4,
                (DynamicsModel::RigidBody, Some(Integrator::Paper)) => {
                    return Err(SceneError::new(
                        o,
                        "solver.integrator",
                        "the rigid-body dynamics integrates with \"rk4\" only (the paper's \
                         update belongs to the paper's dynamics)",
                    ));
                }
            },
            dynamics: s.dynamics,
            stride: match s.stride {
                None => 1,
                Some(k) if k >= 1 => k as usize,
                Some(k) => {
                    return Err(SceneError::new(
                        o,
                        "solver.stride",
                        format!("must be a whole number of increments, 1 or more, got {k}"),
                    ));
                }
            },
        }),
    };
    let initial = match &raw.initial {
        None => Initial::default(),
        Some(i) => {
            let finite =
                |key: &str, v: Option<f64>| check(o, key, v.unwrap_or(0.0), true, "finite");
            Initial {
                vx: finite("initial.vx_m_s", i.vx_m_s)?,
                vz: finite("initial.vz_m_s", i.vz_m_s)?,
                omega: finite("initial.omega_deg_s", i.omega_deg_s)?.to_radians(),
            }
        }
    };
    derived(o, &frame, block.as_ref(), loads.as_ref())?;
    Ok(Scene {
        name: raw.name.unwrap_or_else(|| "unnamed".to_string()),
        origin: o.to_string(),
        site: Site { frame, foundation },
        block,
        loads,
        friction,
        solver,
        initial,
    })
}

#[cfg(test)]
mod tests;
