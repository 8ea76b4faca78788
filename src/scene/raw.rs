//! The scene file as written: TOML, degrees, the documented keys. Every key is optional here and
//! every name (mode, model, …) a string, so that serde reports only values of the wrong type;
//! a missing key, an unknown key or an unknown name is found by [`super::validate`] and
//! [`read`], which know which key it is, without reading serde's message text.
//! [`super::Scene`] is the validated, typed form, in radians.

use serde::Deserialize;
use serde::de::{self, Deserializer, Visitor};

#[derive(Debug, Default, Deserialize)]
#[serde(expecting = "a scene: tables [frame], [foundation], …")]
pub struct RawScene {
    pub name: Option<String>,
    pub frame: Option<RawFrame>,
    pub foundation: Option<RawFoundation>,
    pub block: Option<RawBlock>,
    pub loads: Option<RawLoads>,
    pub friction: Option<RawFriction>,
    pub solver: Option<RawSolver>,
    pub initial: Option<RawInitial>,
    pub monolith: Option<RawMonolith>,
    pub water: Option<RawWater>,
    pub silt: Option<RawSilt>,
    pub ice: Option<RawIce>,
    pub seismic: Option<RawSeismic>,
    pub check: Option<RawCheck>,
    pub base: Option<RawBase>,
    pub case: Option<Vec<RawCase>>,
    pub anchor: Option<Vec<RawAnchor>>,
    /// `[uncertain]`: `"section.key" = "name:p1:p2…"`, the distributions of a probabilistic
    /// analysis.
    pub uncertain: Option<std::collections::BTreeMap<String, String>>,
}

/// `[check]`: the guideline table the load cases' required factors of safety come from.
#[derive(Debug, Default, Deserialize)]
#[serde(expecting = "the table [check]")]
pub struct RawCheck {
    pub structure: Option<String>,
    pub site_information: Option<String>,
    pub allowable_bearing_pa: Option<f64>,
}

/// One `[[case]]`: a load combination, its levels and seismic inputs, and its requirement.
#[derive(Debug, Default, Deserialize)]
#[serde(expecting = "a table [[case]]")]
pub struct RawCase {
    pub name: Option<String>,
    pub category: Option<String>,
    pub headwater_m: Option<f64>,
    pub tailwater_m: Option<f64>,
    pub kh: Option<f64>,
    pub kv: Option<f64>,
    pub drain_efficiency: Option<f64>,
    pub silt_depth_m: Option<f64>,
    pub ice_force_n_m: Option<f64>,
    pub required_fs: Option<f64>,
}

/// `[monolith]`: the block from its section (beside `[block]`, which gives mass and inertia
/// directly).
#[derive(Debug, Default, Deserialize)]
#[serde(expecting = "the table [monolith]")]
pub struct RawMonolith {
    pub base_length_m: Option<f64>,
    pub width_m: Option<f64>,
    pub height_m: Option<f64>,
    pub crest_length_m: Option<f64>,
    pub density_kg_m3: Option<f64>,
}

/// `[water]`: the water's loads from levels (needs `[monolith]`).
#[derive(Debug, Default, Deserialize)]
#[serde(expecting = "the table [water]")]
pub struct RawWater {
    pub headwater_m: Option<f64>,
    pub tailwater_m: Option<f64>,
    pub density_kg_m3: Option<f64>,
    pub drain_efficiency: Option<f64>,
    pub drain_position_m: Option<f64>,
    pub crack: Option<bool>,
}

/// `[silt]`: the reservoir's sediment against the upstream face (needs `[water]`).
#[derive(Debug, Default, Deserialize)]
#[serde(expecting = "the table [silt]")]
pub struct RawSilt {
    pub depth_m: Option<f64>,
    pub unit_weight_n_m3: Option<f64>,
    pub friction_angle_deg: Option<f64>,
}

/// `[ice]`: an ice sheet's thrust on the upstream face (needs `[water]`).
#[derive(Debug, Default, Deserialize)]
#[serde(expecting = "the table [ice]")]
pub struct RawIce {
    pub force_n_m: Option<f64>,
    pub elevation_m: Option<f64>,
}

/// One `[[anchor]]`: a post-tensioned anchor through the monolith into the rock (needs
/// `[monolith]`).
#[derive(Debug, Default, Deserialize)]
#[serde(expecting = "a table [[anchor]]")]
pub struct RawAnchor {
    pub x_m: Option<f64>,
    pub y_m: Option<f64>,
    pub z_m: Option<f64>,
    pub plunge_deg: Option<f64>,
    pub trend_deg: Option<f64>,
    pub prestress_n: Option<f64>,
    pub capacity_n: Option<f64>,
    pub free_length_m: Option<f64>,
    pub steel_area_m2: Option<f64>,
    pub modulus_pa: Option<f64>,
}

/// `[seismic]`: pseudo-static coefficients, and a ground-motion record.
#[derive(Debug, Default, Deserialize)]
#[serde(expecting = "the table [seismic]")]
pub struct RawSeismic {
    pub kh: Option<f64>,
    pub kv: Option<f64>,
    pub record: Option<String>,
    pub record_x: Option<String>,
    pub record_y: Option<String>,
    pub record_z: Option<String>,
    pub units: Option<String>,
    pub dt_s: Option<f64>,
    pub scale: Option<f64>,
    pub target_pga_g: Option<f64>,
    pub polarity: Option<String>,
}

/// The motion at t = 0 (default: at rest).
#[derive(Debug, Default, Deserialize)]
#[serde(expecting = "the table [initial]")]
pub struct RawInitial {
    pub vx_m_s: Option<f64>,
    pub vz_m_s: Option<f64>,
    pub omega_deg_s: Option<f64>,
}

/// `[frame]`: the paper's right isosceles frame (`l1x` … `l2z`), or any triangle
/// (`contacts_m`).
#[derive(Debug, Default, Deserialize)]
#[serde(expecting = "the table [frame]")]
pub struct RawFrame {
    pub l1x: Option<f64>,
    pub l2x: Option<f64>,
    pub l1z: Option<f64>,
    pub l2z: Option<f64>,
    /// The three contacts' (x', z') about the CM (m).
    pub contacts_m: Option<Vec<Vec<f64>>>,
}

/// `[foundation]`: the paper's three planes (`xi_deg`, `zeta_deg`, `kappa_deg`), or a list of
/// faces (`[[foundation.plane]]`).
#[derive(Debug, Default, Deserialize)]
#[serde(expecting = "the table [foundation]")]
pub struct RawFoundation {
    pub xi_deg: Option<f64>,
    pub zeta_deg: Option<f64>,
    pub kappa_deg: Option<f64>,
    pub plane: Option<Vec<RawPlane>>,
    /// A triangulated surface: a Wavefront OBJ file (Y up, scene coordinates), relative to the
    /// scene file's folder.
    pub surface: Option<String>,
}

/// One `[[foundation.plane]]`.
#[derive(Debug, Default, Deserialize)]
#[serde(expecting = "a table [[foundation.plane]]")]
pub struct RawPlane {
    pub dip_deg: Option<f64>,
    pub dip_direction_deg: Option<f64>,
    pub point_m: Option<Vec<f64>>,
}

#[derive(Debug, Default, Deserialize)]
#[serde(expecting = "the table [block]")]
pub struct RawBlock {
    pub mass_kg: Option<f64>,
    pub inertia_kg_m2: Option<f64>,
    /// Rigid-body mode: moments about x' and z' and the product ∫x'z' dm (default: a thin
    /// plate, half of `inertia_kg_m2` each, product 0).
    pub inertia_x_kg_m2: Option<f64>,
    pub inertia_z_kg_m2: Option<f64>,
    pub inertia_xz_kg_m2: Option<f64>,
}

#[derive(Debug, Default, Deserialize)]
#[serde(expecting = "the table [loads]")]
pub struct RawLoads {
    pub hydraulic_force_n: Option<f64>,
    pub eccentricity_m: Option<f64>,
    pub gravity_m_s2: Option<f64>,
}

/// `[friction]`: `model` says which of the criterion's keys belong (`coulomb`: `mu_k`;
/// `barton-choubey`: `jrc`, `jcs_pa`, `phi_r_deg`, `contact_area_m2`); `cohesion_pa` and
/// `cohesion_area_m2` the joint's cohesion; `[[friction.face]]` faces with their own.
#[derive(Debug, Default, Deserialize)]
#[serde(expecting = "the table [friction]")]
pub struct RawFriction {
    pub model: Option<String>,
    pub mu_k: Option<f64>,
    pub jrc: Option<f64>,
    pub jcs_pa: Option<f64>,
    pub phi_r_deg: Option<f64>,
    pub contact_area_m2: Option<f64>,
    pub cohesion_pa: Option<f64>,
    pub cohesion_area_m2: Option<f64>,
    pub face: Option<Vec<RawFaceFriction>>,
}

/// `[[friction.face]]`: the faces (numbers as in route.csv's `face` columns) and their own
/// criterion and cohesion.
#[derive(Debug, Default, Deserialize)]
#[serde(expecting = "a table [[friction.face]]")]
pub struct RawFaceFriction {
    pub faces: Option<Vec<u32>>,
    pub model: Option<String>,
    pub mu_k: Option<f64>,
    pub jrc: Option<f64>,
    pub jcs_pa: Option<f64>,
    pub phi_r_deg: Option<f64>,
    pub contact_area_m2: Option<f64>,
    pub cohesion_pa: Option<f64>,
}

#[derive(Debug, Default, Deserialize)]
#[serde(expecting = "the table [solver]")]
pub struct RawSolver {
    pub mode: Option<String>,
    pub dt_s: Option<f64>,
    pub t_end_s: Option<f64>,
    /// Default: "paper" for the paper's dynamics, "rk4" for the rigid body.
    pub integrator: Option<String>,
    /// Default: "rigid-body".
    pub dynamics: Option<String>,
    /// Record every `stride`-th increment (default 1: every one).
    pub stride: Option<i64>,
    /// Where the block touches the ground: "frame" (default) or "base".
    pub contacts: Option<String>,
    /// The error tolerance per step, the rigid body's and the paper's RK4 substeps' (default
    /// `model::DEFAULT_TOLERANCE`).
    pub tolerance: Option<f64>,
}

/// `[base]`: the block's footprint, where it touches the ground under `contacts = "base"`.
#[derive(Debug, Default, Deserialize)]
#[serde(expecting = "the table [base]")]
pub struct RawBase {
    /// The corners (x', z') (m): from the heel and the width's middle for a `[monolith]`,
    /// about the centre of mass for a `[block]`.
    pub outline_m: Option<Vec<Vec<f64>>>,
    /// Whether the base is cast onto its rock: its underside the foundation's own surface
    /// under the footprint where the block rests (default false: a flat base).
    pub cast: Option<bool>,
}

/// Why a document is not a [`RawScene`]: a key that is not a scene's, or a value of the wrong
/// type. Both carry the key's dotted path.
pub enum ReadError {
    /// Keys no scene has (each key once, in the file's order), and the scene read without them.
    Unknown {
        keys: Vec<String>,
        raw: Box<RawScene>,
    },
    WrongType {
        key: String,
        message: String,
        span: Option<std::ops::Range<usize>>,
    },
}

/// Reads a scene document from any deserializer (the TOML text's, or a table's), noting every
/// key no scene has.
pub fn read<'de, D>(document: D) -> Result<RawScene, ReadError>
where
    D: Deserializer<'de, Error = toml::de::Error>,
{
    let mut unknown: Vec<String> = Vec::new();
    let mut note = |path: serde_ignored::Path<'_>| {
        // `Option` sections appear as a `?` step and list items as their index: the key is
        // the rest, an item written `plane[1]`.
        unknown.push({
            let path = path.to_string();
            let mut key = String::new();
            for step in path.split('.').filter(|s| *s != "?") {
                if step.parse::<usize>().is_ok() {
                    key.push_str(&format!("[{step}]"));
                } else {
                    if !key.is_empty() {
                        key.push('.');
                    }
                    key.push_str(step);
                }
            }
            key
        });
    };
    let ignored = serde_ignored::Deserializer::new(document, &mut note);
    let raw = serde_path_to_error::deserialize(ignored).map_err(|e| {
        let path = e.path().to_string();
        let inner = e.into_inner();
        ReadError::WrongType {
            key: if path == "." { String::new() } else { path },
            message: inner.message().to_string(),
            span: inner.span(),
        }
    });
    match raw {
        Err(e) => Err(e),
        Ok(raw) if unknown.is_empty() => Ok(raw),
        Ok(raw) => Err(ReadError::Unknown {
            keys: unknown,
            raw: Box::new(raw),
        }),
    }
}

/// The keys a section may have (the top level's: the section names), taken from the raw type
/// itself so that the list cannot drift from it.
pub fn keys_of(section: &str) -> &'static [&'static str] {
    // A list item's keys are those of its list (`foundation.plane[1]` → `foundation.plane`).
    let section = section.split('[').next().unwrap_or(section);
    match section {
        "" => fields::<RawScene>(),
        "frame" => fields::<RawFrame>(),
        "foundation" => fields::<RawFoundation>(),
        "block" => fields::<RawBlock>(),
        "loads" => fields::<RawLoads>(),
        "friction" => fields::<RawFriction>(),
        "solver" => fields::<RawSolver>(),
        "initial" => fields::<RawInitial>(),
        "monolith" => fields::<RawMonolith>(),
        "water" => fields::<RawWater>(),
        "silt" => fields::<RawSilt>(),
        "ice" => fields::<RawIce>(),
        "seismic" => fields::<RawSeismic>(),
        "check" => fields::<RawCheck>(),
        "base" => fields::<RawBase>(),
        "case" => fields::<RawCase>(),
        "anchor" => fields::<RawAnchor>(),
        "foundation.plane" => fields::<RawPlane>(),
        "friction.face" => fields::<RawFaceFriction>(),
        _ => &[],
    }
}

/// The field names serde's derive gives a struct: a deserializer that only listens for
/// `deserialize_struct` and records the names it is told.
fn fields<'de, T: Deserialize<'de>>() -> &'static [&'static str] {
    struct Probe<'a>(&'a mut &'static [&'static str]);
    impl<'de> Deserializer<'de> for Probe<'_> {
        type Error = de::value::Error;
        fn deserialize_any<V: Visitor<'de>>(self, _: V) -> Result<V::Value, Self::Error> {
            Err(de::Error::custom("probe"))
        }
        fn deserialize_struct<V: Visitor<'de>>(
            self,
            _name: &'static str,
            fields: &'static [&'static str],
            _visitor: V,
        ) -> Result<V::Value, Self::Error> {
            *self.0 = fields;
            Err(de::Error::custom("probe"))
        }
        serde::forward_to_deserialize_any! {
            bool i8 i16 i32 i64 i128 u8 u16 u32 u64 u128 f32 f64 char str string bytes
            byte_buf option unit unit_struct newtype_struct seq tuple tuple_struct map enum
            identifier ignored_any
        }
    }
    let mut names: &'static [&'static str] = &[];
    let _ = T::deserialize(Probe(&mut names));
    names
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_keys_of_each_section_are_the_raw_types_fields() {
        assert_eq!(keys_of("frame"), ["l1x", "l2x", "l1z", "l2z", "contacts_m"]);
        assert!(keys_of("").contains(&"foundation"));
        assert!(keys_of("solver").contains(&"stride"));
        assert!(keys_of("nothing").is_empty());
    }

    #[test]
    fn every_section_a_scene_may_have_names_its_keys() {
        // A section left out of `keys_of` would say "the keys of [base] are" and nothing.
        for section in keys_of("")
            .iter()
            .filter(|s| !["name", "uncertain"].contains(s))
        {
            assert!(
                !keys_of(section).is_empty(),
                "[{section}] has no keys listed"
            );
        }
        assert_eq!(keys_of("base"), ["outline_m", "cast"]);
    }
}
