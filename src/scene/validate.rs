//! From the file's keys to the typed, checked scene: every value finite and in its range, every
//! name one the option has, the sections consistent with each other. Each fault is one
//! [`SceneError`] naming its key.

use super::checks::{check, named, need, non_negative, positive, section};
use super::dam;
use super::error::SceneErrorKind;
use super::files::Files;
use super::raw::{self, RawScene};
use super::strengths::{FaceStrength, Strengths, barycentric};
use super::{
    Block, DynamicsModel, Foundation, Frame, Friction, Initial, Integrator, Loads, Mode, Scene,
    SceneError, Site, Solver,
};
use crate::geometry::{Ground, Plane};
use std::path::Path;
use std::sync::Arc;

/// The most increments one run may take (t_end / dt).
pub const MAX_INCREMENTS: f64 = 1e8;

/// Relative tolerance on L1X + L2X = L1Z + L2Z.
const FRAME_TOLERANCE: f64 = 1e-9;

/// The block, with the rigid-body inertia defaults (a thin plate in the x'z' plane) and the
/// checks a rigid body's inertia must pass (positive definite, triangle inequalities).
fn block(o: &str, b: &raw::RawBlock) -> Result<Block, SceneError> {
    let mass = need(o, "block.mass_kg", b.mass_kg)?;
    let inertia = need(o, "block.inertia_kg_m2", b.inertia_kg_m2)?;
    let inertia = positive(o, "block.inertia_kg_m2", inertia)?;
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
        mass: positive(o, "block.mass_kg", mass)?,
        inertia,
        inertia_x,
        inertia_z,
        inertia_xz,
        inertia_xy: 0.0,
    };
    let key = if b.inertia_xz_kg_m2.is_some() {
        "block.inertia_xz_kg_m2"
    } else {
        "block"
    };
    rigid(o, key, block)
}

/// The checks a rigid body's inertia must pass: positive definite, triangle inequalities.
pub(super) fn rigid(o: &str, key: &str, block: Block) -> Result<Block, SceneError> {
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
    scale: f64,
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
    let ml2 = b.mass * scale * scale;
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

/// A criterion's keys as a section or a `[[friction.face]]` gives them.
struct CriterionKeys<'a> {
    model: Option<&'a str>,
    mu_k: Option<f64>,
    jrc: Option<f64>,
    jcs_pa: Option<f64>,
    phi_r_deg: Option<f64>,
    contact_area_m2: Option<f64>,
}

impl CriterionKeys<'_> {
    fn of(f: &raw::RawFriction) -> CriterionKeys<'_> {
        CriterionKeys {
            model: f.model.as_deref(),
            mu_k: f.mu_k,
            jrc: f.jrc,
            jcs_pa: f.jcs_pa,
            phi_r_deg: f.phi_r_deg,
            contact_area_m2: f.contact_area_m2,
        }
    }

    fn of_face(f: &raw::RawFaceFriction) -> CriterionKeys<'_> {
        CriterionKeys {
            model: f.model.as_deref(),
            mu_k: f.mu_k,
            jrc: f.jrc,
            jcs_pa: f.jcs_pa,
            phi_r_deg: f.phi_r_deg,
            contact_area_m2: f.contact_area_m2,
        }
    }

    fn any(&self) -> bool {
        self.model.is_some()
            || self.mu_k.is_some()
            || self.jrc.is_some()
            || self.jcs_pa.is_some()
            || self.phi_r_deg.is_some()
            || self.contact_area_m2.is_some()
    }
}

/// The friction criterion of `[friction]`.
fn friction(o: &str, f: &raw::RawFriction) -> Result<Friction, SceneError> {
    criterion(o, "friction", &CriterionKeys::of(f))
}

/// The friction criterion under `prefix`: `model` says which keys belong; a key of the other
/// model is refused as unknown rather than ignored.
fn criterion(o: &str, prefix: &str, f: &CriterionKeys<'_>) -> Result<Friction, SceneError> {
    let key = |name: &str| format!("{prefix}.{name}");
    let [coulomb, barton] = Friction::MODELS;
    let model = need(o, &key("model"), f.model)?;
    let model = named(
        o,
        &key("model"),
        "friction model",
        model,
        &[coulomb, barton],
        |m| m,
    )?;
    let given = [
        ("mu_k", f.mu_k.is_some(), coulomb),
        ("jrc", f.jrc.is_some(), barton),
        ("jcs_pa", f.jcs_pa.is_some(), barton),
        ("phi_r_deg", f.phi_r_deg.is_some(), barton),
        ("contact_area_m2", f.contact_area_m2.is_some(), barton),
    ];
    if let Some((name, _, _)) = given
        .iter()
        .find(|(_, present, of)| *present && *of != model)
    {
        let own: Vec<_> = given.iter().filter(|g| g.2 == model).map(|g| g.0).collect();
        return Err(SceneError::of(
            SceneErrorKind::UnknownKey,
            o,
            key(name),
            format!(
                "unknown key for model = \"{model}\" (its keys: model, {})",
                own.join(", ")
            ),
        ));
    }
    Ok(if model == coulomb {
        Friction::Coulomb {
            mu_k: non_negative(o, &key("mu_k"), need(o, &key("mu_k"), f.mu_k)?)?,
        }
    } else {
        let phi_r_deg = need(o, &key("phi_r_deg"), f.phi_r_deg)?;
        Friction::BartonChoubey {
            jrc: non_negative(o, &key("jrc"), need(o, &key("jrc"), f.jrc)?)?,
            jcs_pa: positive(o, &key("jcs_pa"), need(o, &key("jcs_pa"), f.jcs_pa)?)?,
            phi_r: check(
                o,
                &key("phi_r_deg"),
                phi_r_deg,
                (0.0..90.0).contains(&phi_r_deg),
                "an angle from 0° up to (not including) 90°",
            )?
            .to_radians(),
            contact_area_m2: positive(
                o,
                &key("contact_area_m2"),
                need(o, &key("contact_area_m2"), f.contact_area_m2)?,
            )?,
        }
    })
}

/// `[friction]`'s cohesion and `[[friction.face]]`: each face's criterion and cohesion, and each
/// contact's share of the bonded area (`derivations/11-dam-loads.md` §8).
fn strengths(
    o: &str,
    f: &raw::RawFriction,
    site: &Site,
    monolith: Option<&dam::Monolith>,
) -> Result<Strengths, SceneError> {
    let cohesion = |key: &str, v: Option<f64>| non_negative(o, key, v.unwrap_or(0.0));
    let cohesion_pa = cohesion("friction.cohesion_pa", f.cohesion_pa)?;
    let count = site.ground().map_or(3, |(g, _)| g.faces().len());
    let mut faces = Vec::new();
    for (k, face) in f.face.as_deref().unwrap_or(&[]).iter().enumerate() {
        let prefix = format!("friction.face[{k}]");
        let listed = need(o, &format!("{prefix}.faces"), face.faces.clone())?;
        if listed.is_empty() {
            return Err(SceneError::new(
                o,
                format!("{prefix}.faces"),
                "an empty list: name the faces (as route.csv's face columns) this entry is for"
                    .to_string(),
            ));
        }
        if let Some(bad) = listed.iter().find(|&&n| n as usize >= count) {
            return Err(SceneError::new(
                o,
                format!("{prefix}.faces"),
                format!(
                    "face {bad} does not exist: the foundation's faces are 0 to {}",
                    count - 1
                ),
            ));
        }
        let keys = CriterionKeys::of_face(face);
        let friction = if keys.any() {
            let model = keys.model.or(f.model.as_deref());
            criterion(o, &prefix, &CriterionKeys { model, ..keys })?
        } else {
            friction(o, f)?
        };
        faces.push(FaceStrength {
            faces: listed,
            friction,
            cohesion_pa: match face.cohesion_pa {
                Some(c) => cohesion(&format!("{prefix}.cohesion_pa"), Some(c))?,
                None => cohesion_pa,
            },
        });
    }
    let mut out = Strengths {
        cohesion_pa,
        shares_m2: [0.0; 3],
        faces,
    };
    if !out.has_cohesion() {
        if f.cohesion_area_m2.is_some() {
            return Err(SceneError::new(
                o,
                "friction.cohesion_area_m2",
                "an area without cohesion: give friction.cohesion_pa too".to_string(),
            ));
        }
        return Ok(out);
    }
    // The bonded area: given, or the monolith's base; its centroid: the base's centre, or the
    // contact triangle's.
    let (area, centre) = match (f.cohesion_area_m2, monolith) {
        (Some(a), m) => (
            positive(o, "friction.cohesion_area_m2", a)?,
            m.map(dam::base_centre),
        ),
        (None, Some(m)) => (
            m.section.base_length * m.section.width,
            Some(dam::base_centre(m)),
        ),
        (None, None) => {
            return Err(SceneError::new(
                o,
                "friction.cohesion_area_m2",
                "cohesion needs the bonded area of the joint (m²): give \
                 friction.cohesion_area_m2, or [monolith] for its base"
                    .to_string(),
            ));
        }
    };
    let c = site.contacts();
    let centre = centre.unwrap_or([
        (c[0][0] + c[1][0] + c[2][0]) / 3.0,
        (c[0][1] + c[1][1] + c[2][1]) / 3.0,
    ]);
    let weights = barycentric(c, centre).filter(|w| w.iter().all(|&x| x >= -1e-12));
    let Some(weights) = weights else {
        return Err(SceneError::new(
            o,
            "friction.cohesion_pa",
            format!(
                "the base's centre (x', z') = ({:.6}, {:.6}) m is outside the contact triangle: \
                 its cohesion cannot be shared among the three contacts with its resultant \
                 there; place the contacts around it",
                centre[0], centre[1]
            ),
        ));
    };
    out.shares_m2 = weights.map(|w| w.max(0.0) * area);
    Ok(out)
}

/// The run settings, with each dynamics model's default integrator.
fn solver(o: &str, s: &raw::RawSolver) -> Result<Solver, SceneError> {
    let mode = need(o, "solver.mode", s.mode.as_deref())?;
    let mode = named(
        o,
        "solver.mode",
        "solver mode",
        mode,
        &Mode::ALL,
        Mode::as_str,
    )?;
    let dynamics = match s.dynamics.as_deref() {
        None => DynamicsModel::default(),
        Some(w) => named(
            o,
            "solver.dynamics",
            "dynamics",
            w,
            &DynamicsModel::ALL,
            DynamicsModel::as_str,
        )?,
    };
    let integrator = match s.integrator.as_deref() {
        None => None,
        Some(w) => Some(named(
            o,
            "solver.integrator",
            "integrator",
            w,
            &Integrator::ALL,
            Integrator::as_str,
        )?),
    };
    let dt = need(o, "solver.dt_s", s.dt_s)?;
    let t_end = need(o, "solver.t_end_s", s.t_end_s)?;
    if dt > t_end && t_end > 0.0 {
        return Err(SceneError::new(
            o,
            "solver.dt_s",
            format!("the increment ({dt} s) is longer than the whole route (t_end_s = {t_end} s)"),
        ));
    }
    let n = t_end / dt;
    if dt > 0.0 && t_end > 0.0 && n > MAX_INCREMENTS {
        return Err(SceneError::new(
            o,
            "solver.dt_s",
            format!(
                "t_end_s / dt_s = {n:.3e} increments, more than the {MAX_INCREMENTS:e} one run may take"
            ),
        ));
    }
    Ok(Solver {
        mode,
        dt: positive(o, "solver.dt_s", dt)?,
        t_end: positive(o, "solver.t_end_s", t_end)?,
        integrator: match (dynamics, integrator) {
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
        dynamics,
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
    })
}

/// The frame as given: the paper's lengths, or any triangle's contacts.
pub(super) enum FrameIn {
    Paper(Frame),
    Contacts([[f64; 2]; 3]),
}

/// The foundation as given: the paper's three planes, a list of faces, or a surface.
pub(super) enum FoundationIn {
    Paper(Foundation),
    Faces(Vec<Plane>),
    Surface(Arc<Ground>),
}

/// `[frame]`: either the paper's four lengths or `contacts_m`, not both.
fn frame(o: &str, f: &raw::RawFrame) -> Result<FrameIn, SceneError> {
    let paper_keys = [f.l1x, f.l2x, f.l1z, f.l2z];
    match &f.contacts_m {
        Some(_) if paper_keys.iter().any(Option::is_some) => Err(SceneError::new(
            o,
            "frame.contacts_m",
            "give either l1x, l2x, l1z, l2z (the paper's right isosceles frame) or contacts_m \
             (any triangle), not both",
        )),
        Some(c) => contacts(o, c).map(FrameIn::Contacts),
        None if paper_keys.iter().all(Option::is_none) => Err(SceneError::of(
            SceneErrorKind::MissingKey,
            o,
            "frame",
            "give l1x, l2x, l1z, l2z (the paper's right isosceles frame) or contacts_m (any \
             triangle)",
        )),
        None => paper_frame(o, f).map(FrameIn::Paper),
    }
}

/// `contacts_m`: three points (x', z') in metres, finite, about the CM, spanning a triangle.
fn contacts(o: &str, c: &[Vec<f64>]) -> Result<[[f64; 2]; 3], SceneError> {
    let key = "frame.contacts_m";
    if c.len() != 3 || c.iter().any(|p| p.len() != 2) {
        return Err(SceneError::new(
            o,
            key,
            format!(
                "must be three points [x, z] (m), e.g. [[-6.0, 5.0], [4.0, 5.0], [4.0, -5.0]]; \
                 got {} item(s)",
                c.len()
            ),
        ));
    }
    let pts: [[f64; 2]; 3] = std::array::from_fn(|k| [c[k][0], c[k][1]]);
    if let Some(v) = pts.iter().flatten().find(|v| !v.is_finite()) {
        return Err(SceneError::new(
            o,
            key,
            format!("must be finite numbers, got {v}"),
        ));
    }
    let side = |a: usize, b: usize| (pts[a][0] - pts[b][0]).hypot(pts[a][1] - pts[b][1]);
    let longest = side(0, 1).max(side(1, 2)).max(side(0, 2));
    let twice_area = (pts[1][0] - pts[0][0]) * (pts[2][1] - pts[0][1])
        - (pts[2][0] - pts[0][0]) * (pts[1][1] - pts[0][1]);
    let spans = twice_area.abs() > 1e-6 * longest * longest;
    if !(longest * longest).is_finite() || !spans {
        return Err(SceneError::new(
            o,
            key,
            format!(
                "the three contacts must span a triangle (finite sides, not on one line): \
                 longest side {longest:e} m, area {:e} m²",
                0.5 * twice_area.abs()
            ),
        ));
    }
    Ok(pts)
}

/// The paper's frame: positive lengths, a finite side, and the two legs of the right isosceles
/// triangle equal.
fn paper_frame(o: &str, f: &raw::RawFrame) -> Result<Frame, SceneError> {
    let length = |key: &str, v: Option<f64>| positive(o, key, need(o, key, v)?);
    let frame = Frame {
        l1x: length("frame.l1x", f.l1x)?,
        l2x: length("frame.l2x", f.l2x)?,
        l1z: length("frame.l1z", f.l1z)?,
        l2z: length("frame.l2z", f.l2z)?,
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
    Ok(frame)
}

/// `[foundation]`: exactly one of the paper's three angles, a list of faces, or a surface (not
/// read again when `files` already holds it under its name).
fn foundation(
    o: &str,
    d: &raw::RawFoundation,
    (folder, files): (&Path, &Files),
) -> Result<FoundationIn, SceneError> {
    let paper = [d.xi_deg, d.zeta_deg, d.kappa_deg]
        .iter()
        .any(Option::is_some);
    let forms = [
        (paper, "foundation.xi_deg"),
        (d.plane.is_some(), "foundation.plane"),
        (d.surface.is_some(), "foundation.surface"),
    ];
    let given: Vec<&str> = forms.iter().filter(|f| f.0).map(|f| f.1).collect();
    const FORMS: &str = "xi_deg, zeta_deg, kappa_deg (the paper's three planes), \
                         [[foundation.plane]] faces, or surface = \"rock.obj\" (a triangulated \
                         surface)";
    match given.as_slice() {
        [] => Err(SceneError::of(
            SceneErrorKind::MissingKey,
            o,
            "foundation",
            format!("give one of {FORMS}"),
        )),
        [_, second, ..] => Err(SceneError::new(
            o,
            *second,
            format!("give one of {FORMS}, not more"),
        )),
        ["foundation.plane"] => match d.plane.as_deref().unwrap_or_default() {
            [] => Err(SceneError::new(
                o,
                "foundation.plane",
                "a foundation of faces needs at least one [[foundation.plane]]",
            )),
            planes => planes
                .iter()
                .enumerate()
                .map(|(k, p)| face(o, k, p))
                .collect::<Result<Vec<_>, _>>()
                .map(FoundationIn::Faces),
        },
        ["foundation.surface"] => {
            let name = d.surface.as_deref().unwrap_or_default();
            match &files.surface {
                Some((read, ground)) if read == name => Ok(FoundationIn::Surface(ground.clone())),
                _ => surface(o, folder, name).map(|g| FoundationIn::Surface(Arc::new(g))),
            }
        }
        _ => paper_foundation(o, d).map(FoundationIn::Paper),
    }
}

/// The largest surface file (bytes): some two hundred thousand triangles.
pub const MAX_SURFACE_BYTES: u64 = 64 << 20;

/// `surface = "rock.obj"`: a Wavefront OBJ file of triangles (faces of more corners are split
/// into triangles), Y up, in scene coordinates, found from `folder`.
fn surface(o: &str, folder: &Path, name: &str) -> Result<Ground, SceneError> {
    let key = "foundation.surface";
    let path = folder.join(name);
    let bad = |why: String| SceneError::new(o, key, format!("{}: {why}", path.display()));
    let mut reader =
        std::io::BufReader::new(super::input::open_bounded(&path, MAX_SURFACE_BYTES).map_err(bad)?);
    let options = tobj::LoadOptions {
        triangulate: true,
        single_index: true,
        ..Default::default()
    };
    // A surface has no materials: a material library it names is not read.
    let (models, _) = tobj::load_obj_buf(&mut reader, &options, |_| {
        Err(tobj::LoadError::OpenFileFailed)
    })
    .map_err(|e| bad(format!("not a Wavefront OBJ surface: {e}")))?;
    let mut triangles = Vec::new();
    for m in &models {
        let p = &m.mesh.positions;
        for t in m.mesh.indices.chunks_exact(3) {
            let corner = |k: u32| -> Result<[f64; 3], SceneError> {
                let k = k as usize * 3;
                p.get(k..k + 3).map(|c| [c[0], c[1], c[2]]).ok_or_else(|| {
                    bad(format!(
                        "a face names vertex {} of {}",
                        k / 3 + 1,
                        p.len() / 3
                    ))
                })
            };
            triangles.push([corner(t[0])?, corner(t[1])?, corner(t[2])?]);
        }
    }
    Ground::surface(&triangles).map_err(|e| bad(e.to_string()))
}

/// The paper's three planes: dips strictly between 0° and 90°, κ strictly between −90° and 90°.
fn paper_foundation(o: &str, d: &raw::RawFoundation) -> Result<Foundation, SceneError> {
    let dip = |key: &str, v: Option<f64>| {
        let v = need(o, key, v)?;
        check(
            o,
            key,
            v,
            v > 0.0 && v < 90.0,
            "a dip strictly between 0° and 90°",
        )
        .map(f64::to_radians)
    };
    let kappa = need(o, "foundation.kappa_deg", d.kappa_deg)?;
    Ok(Foundation {
        xi: dip("foundation.xi_deg", d.xi_deg)?,
        zeta: dip("foundation.zeta_deg", d.zeta_deg)?,
        kappa: check(
            o,
            "foundation.kappa_deg",
            kappa,
            kappa > -90.0 && kappa < 90.0,
            "an azimuth strictly between -90° and 90°",
        )?
        .to_radians(),
    })
}

/// One `[[foundation.plane]]`: dip in [0°, 90°), any dip direction, a point of three finite
/// coordinates.
fn face(o: &str, k: usize, p: &raw::RawPlane) -> Result<Plane, SceneError> {
    let key = |name: &str| format!("foundation.plane[{k}].{name}");
    let dip = need(o, &key("dip_deg"), p.dip_deg)?;
    let dip = check(
        o,
        &key("dip_deg"),
        dip,
        (0.0..90.0).contains(&dip),
        "a dip from 0° up to (not including) 90°",
    )?;
    let dir = need(o, &key("dip_direction_deg"), p.dip_direction_deg)?;
    let dir = check(o, &key("dip_direction_deg"), dir, true, "finite")?;
    let point = need(o, &key("point_m"), p.point_m.as_ref())?;
    if point.len() != 3 || point.iter().any(|v| !v.is_finite()) {
        return Err(SceneError::new(
            o,
            key("point_m"),
            format!("must be a point [X, Y, Z] of three finite numbers (m), got {point:?}"),
        ));
    }
    Ok(Plane::from_dip(
        dip.to_radians(),
        dir.to_radians(),
        nalgebra::Vector3::new(point[0], point[1], point[2]),
    ))
}

/// How far (as a fraction of the frame's scale) a contact's start may lie off the ground.
pub const START_TOL: f64 = 1e-9;

/// The site: the paper's frame on the paper's planes keeps the paper's systems; any triangle on
/// the paper's planes (each through its contact's start, as the paper's are) takes the general
/// system; on a list of faces each contact starts on the face under it (the block starts flat at
/// Y = 0, so each contact must be on the ground there, neither under it nor above it).
fn site(o: &str, frame: FrameIn, foundation: FoundationIn) -> Result<Site, SceneError> {
    let contacts = match &frame {
        FrameIn::Paper(f) => f.vertices(),
        FrameIn::Contacts(c) => *c,
    };
    let start = |k: usize| nalgebra::Vector3::new(contacts[k][0], 0.0, contacts[k][1]);
    match (frame, foundation) {
        (FrameIn::Paper(f), FoundationIn::Paper(g)) => Ok(Site::paper(f, g)),
        (FrameIn::Contacts(c), FoundationIn::Paper(g)) => {
            let pi = std::f64::consts::PI;
            let planes = [
                Plane::from_dip(0.0, 0.0, start(0)),
                Plane::from_dip(g.xi, pi, start(1)),
                Plane::from_dip(g.zeta, pi - g.kappa, start(2)),
            ];
            Ok(Site::general(c, planes))
        }
        (_, FoundationIn::Faces(faces)) => on_ground(o, contacts, Arc::new(Ground::planes(faces))),
        (_, FoundationIn::Surface(ground)) => on_ground(o, contacts, ground),
    }
}

/// Contacts starting flat at Y = 0 on a ground of faces: each must be on the ground there,
/// neither under it nor above it, and takes the face under it.
fn on_ground(o: &str, contacts: [[f64; 2]; 3], ground: Arc<Ground>) -> Result<Site, SceneError> {
    let key = if ground.is_surface() {
        "foundation.surface"
    } else {
        "foundation.plane"
    };
    let scale = Site::general(contacts, [ground.faces()[0]; 3]).l();
    let tol = START_TOL * scale;
    let mut faces = [0; 3];
    for (k, &[x, z]) in contacts.iter().enumerate() {
        let at = format!("contact {k} starts at (X, Z) = ({x}, {z}) m");
        let Some((top, h)) = ground.top(x, z) else {
            return Err(SceneError::new(
                o,
                key,
                format!("{at}, off the surveyed surface"),
            ));
        };
        if h > tol {
            return Err(SceneError::new(
                o,
                key,
                format!(
                    "{at}, under the ground: face {top} stands {h:.6} m above it (the block \
                     starts flat at Y = 0 with every contact on the ground)"
                ),
            ));
        }
        if h < -tol {
            return Err(SceneError::new(
                o,
                key,
                format!(
                    "{at}, above the ground: the highest face there, face {top}, is {:.6} m \
                     below it (the block starts flat at Y = 0 with every contact on the ground)",
                    -h
                ),
            ));
        }
        // At a crease, the face that rises first along x' (the push of the water).
        faces[k] = ground
            .face_under(x, z, (1.0, 0.0), 1e-3 * scale, tol)
            .unwrap_or(top);
    }
    Ok(Site::on_ground(contacts, ground, faces))
}

/// The typed scene of a document, or its first fault. `source` is kept as the scene's own
/// file ([`Scene::with`] edits it).
pub(super) fn validate(
    raw: RawScene,
    o: &str,
    source: toml::Table,
    (folder, files): (&Path, &Files),
) -> Result<Scene, SceneError> {
    let frame = frame(o, section(o, "frame", &raw.frame)?)?;
    let foundation = foundation(
        o,
        section(o, "foundation", &raw.foundation)?,
        (folder, files),
    )?;
    let site = site(o, frame, foundation)?;
    let monolith = raw
        .monolith
        .as_ref()
        .map(|m| dam::monolith(o, m))
        .transpose()?;
    let block = match (&raw.block, &monolith) {
        (Some(_), Some(_)) => {
            return Err(SceneError::new(
                o,
                "monolith",
                "give the block's mass and inertia ([block]) or its section ([monolith]), not \
                 both"
                    .to_string(),
            ));
        }
        (Some(b), None) => Some(block(o, b)?),
        (None, Some(m)) => {
            dam::contacts_on_base(o, &site, m)?;
            Some(rigid(o, "monolith", m.block())?)
        }
        (None, None) => None,
    };
    let (kh, kv, record) = match &raw.seismic {
        Some(s) => dam::seismic(o, s, (folder, &files.record))?,
        None => (0.0, 0.0, None),
    };
    let loads = match &raw.loads {
        None => {
            for (present, name) in [
                (raw.water.is_some(), "water"),
                (raw.seismic.is_some(), "seismic"),
            ] {
                if present {
                    return Err(SceneError::new(
                        o,
                        name,
                        format!("[{name}] needs [loads] (gravity_m_s2, eccentricity_m)"),
                    ));
                }
            }
            None
        }
        Some(l) => {
            let eccentricity = check(
                o,
                "loads.eccentricity_m",
                need(o, "loads.eccentricity_m", l.eccentricity_m)?,
                true,
                "finite",
            )?;
            let gravity = positive(
                o,
                "loads.gravity_m_s2",
                need(o, "loads.gravity_m_s2", l.gravity_m_s2)?,
            )?;
            let mut loads = match &raw.water {
                Some(w) => {
                    if l.hydraulic_force_n.is_some() {
                        return Err(SceneError::new(
                            o,
                            "loads.hydraulic_force_n",
                            "[water] gives the water's force from its levels: remove \
                             loads.hydraulic_force_n"
                                .to_string(),
                        ));
                    }
                    let m = monolith.as_ref().ok_or_else(|| {
                        SceneError::new(
                            o,
                            "water",
                            "[water] needs [monolith]: the faces and the base the water acts \
                             on"
                            .to_string(),
                        )
                    })?;
                    dam::water(o, w, m, eccentricity, gravity)?
                }
                None => Loads::plain(
                    non_negative(
                        o,
                        "loads.hydraulic_force_n",
                        need(o, "loads.hydraulic_force_n", l.hydraulic_force_n)?,
                    )?,
                    eccentricity,
                    gravity,
                ),
            };
            loads.kh = kh;
            loads.kv = kv;
            loads.cm_height = monolith.as_ref().map_or(0.0, |m| m.props.cm_height);
            Some(loads)
        }
    };
    let friction = raw.friction.as_ref().map(|f| friction(o, f)).transpose()?;
    let strengths = match &raw.friction {
        Some(f) => strengths(o, f, &site, monolith.as_ref())?,
        None => Strengths::default(),
    };
    let solver = raw.solver.as_ref().map(|s| solver(o, s)).transpose()?;
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
    // What only the rigid body's dynamics follows.
    let rigid_only = [
        (
            record.is_some(),
            "seismic.record",
            "a ground-motion record moves the foundation under a rigid body",
        ),
        (
            strengths.has_cohesion(),
            "friction.cohesion_pa",
            "cohesion holds a block at rest and breaks when it slides, which the rigid body's \
             static check follows",
        ),
    ];
    let dynamics = solver.as_ref().map(|s| s.dynamics);
    if let Some((_, key, what)) = rigid_only.iter().find(|(given, _, _)| {
        *given && dynamics.is_some_and(|d| d != super::DynamicsModel::RigidBody)
    }) {
        return Err(SceneError::new(
            o,
            *key,
            format!("{what}: it needs solver.dynamics = \"rigid-body\""),
        ));
    }
    derived(o, site.l(), block.as_ref(), loads.as_ref())?;
    let guideline = match &raw.check {
        Some(c) => super::cases::guideline(o, c)?,
        None => Default::default(),
    };
    let cases = super::cases::cases(o, &guideline, raw.case.as_deref().unwrap_or(&[]))?;
    let uncertain = uncertain(o, raw.uncertain.as_ref())?;
    Ok(Scene {
        name: raw.name.unwrap_or_else(|| "unnamed".to_string()),
        origin: o.to_string(),
        site,
        block,
        loads,
        friction,
        solver,
        initial,
        source,
        folder: folder.to_path_buf(),
        guideline,
        cases,
        record,
        strengths,
        uncertain,
    })
}

/// `[uncertain]`: each `"section.key" = "name:p1:p2…"` read as a distribution, in the order of
/// the keys' names (so that a design's columns do not depend on how the file was written).
/// Whether each key is a number of the scene is asked where the samples are run.
fn uncertain(
    o: &str,
    table: Option<&std::collections::BTreeMap<String, String>>,
) -> Result<Vec<crate::numeric::Uncertain>, SceneError> {
    let Some(table) = table else {
        return Ok(vec![]);
    };
    table
        .iter()
        .map(|(key, spec)| {
            let at = format!("uncertain.\"{key}\"");
            if !key.contains('.') || key.starts_with("uncertain.") {
                return Err(SceneError::new(
                    o,
                    at,
                    "name a number of the scene as \"section.key\", e.g. \"friction.mu_k\"",
                ));
            }
            crate::numeric::Distribution::parse(spec)
                .map(|distribution| crate::numeric::Uncertain {
                    key: key.clone(),
                    distribution,
                })
                .map_err(|e| SceneError::new(o, at, e))
        })
        .collect()
}
