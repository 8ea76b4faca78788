//! The scene as used, in its file's own keys and units (degrees, SI), every default filled in:
//! what `summary.json` echoes so that anyone holding an output folder can tell what produced
//! it.

use super::Scene;
use crate::model::Friction;
use toml::{Table, Value};

fn table(entries: &[(&str, Value)]) -> Value {
    Value::Table(
        entries
            .iter()
            .map(|(k, v)| (k.to_string(), v.clone()))
            .collect(),
    )
}

impl Scene {
    /// Every section present, every key with its value as used (defaults filled in), in the
    /// scene file's keys and units.
    pub fn as_used(&self) -> Table {
        let mut t = Table::new();
        t.insert("name".into(), Value::String(self.name.clone()));
        // The frame and the foundation have no defaults: as the file gave them (the paper's
        // lengths and angles, or contacts and faces).
        self.as_given(&mut t, &["frame", "foundation"]);
        self.block_as_used(&mut t);
        self.loads_as_used(&mut t);
        if let Some(fr) = self.friction() {
            t.insert("friction".into(), self.friction_as_used(fr));
        }
        if let Some(s) = &self.settings {
            t.insert(
                "solver".into(),
                table(&[
                    ("mode", Value::String(s.mode.as_str().into())),
                    ("dt_s", Value::Float(s.dt)),
                    ("t_end_s", Value::Float(s.t_end)),
                    ("dynamics", Value::String(s.dynamics.as_str().into())),
                    ("integrator", Value::String(s.integrator.as_str().into())),
                    ("stride", Value::Integer(s.stride as i64)),
                    ("contacts", Value::String(s.contacts.as_str().into())),
                    ("tolerance", Value::Float(s.tolerance)),
                ]),
            );
        }
        // The footprint as the file gave it (a monolith's follows from its section).
        self.as_given(&mut t, &["base"]);
        // The guideline and the load cases, as the file gave them.
        self.as_given(&mut t, &["check", "case"]);
        let i = &self.initial;
        t.insert(
            "initial".into(),
            table(&[
                ("vx_m_s", Value::Float(i.vx)),
                ("vz_m_s", Value::Float(i.vz)),
                ("omega_deg_s", Value::Float(i.omega.to_degrees())),
            ]),
        );
        t
    }

    /// The `sections` the file gives, as it gives them.
    fn as_given(&self, t: &mut Table, sections: &[&str]) {
        for &section in sections {
            if let Some(v) = self.source.get(section) {
                t.insert(section.into(), v.clone());
            }
        }
    }

    /// `[monolith]` as given (its mass properties follow from it), or `[block]` with the
    /// rigid-body inertia's defaults.
    fn block_as_used(&self, t: &mut Table) {
        let f = Value::Float;
        if let Some(m) = self.source.get("monolith") {
            t.insert("monolith".into(), m.clone());
            if !self.anchors.is_empty() {
                // As the file wrote each (its degrees as written), with the defaults it left out.
                let given = self.source.get("anchor").and_then(Value::as_array);
                let f = Value::Float;
                let anchors = self.anchors.iter().enumerate().map(|(k, a)| {
                    let mut one = given
                        .and_then(|g| g.get(k))
                        .and_then(Value::as_table)
                        .cloned()
                        .unwrap_or_default();
                    for (key, v) in [
                        ("y_m", f(a.head[1])),
                        ("z_m", f(a.head[2])),
                        ("plunge_deg", f(a.plunge.to_degrees())),
                        ("trend_deg", f(a.trend.to_degrees())),
                        ("modulus_pa", f(a.modulus)),
                    ] {
                        one.entry(key).or_insert(v);
                    }
                    Value::Table(one)
                });
                t.insert("anchor".into(), Value::Array(anchors.collect()));
            }
        } else if let Some(b) = &self.block {
            t.insert(
                "block".into(),
                table(&[
                    ("mass_kg", f(b.mass)),
                    ("inertia_kg_m2", f(b.inertia)),
                    ("inertia_x_kg_m2", f(b.inertia_x)),
                    ("inertia_z_kg_m2", f(b.inertia_z)),
                    ("inertia_xz_kg_m2", f(b.inertia_xz)),
                ]),
            );
        }
    }

    /// `[loads]`, with `[water]`'s levels where the water's force comes from them, and
    /// `[seismic]`.
    fn loads_as_used(&self, t: &mut Table) {
        let f = Value::Float;
        let Some(l) = &self.loads else {
            return;
        };
        let mut loads = vec![
            ("eccentricity_m", f(l.eccentricity)),
            ("gravity_m_s2", f(l.gravity)),
        ];
        match &l.water {
            Some(w) => {
                let v = &w.levels;
                let mut water = vec![
                    ("headwater_m", f(v.headwater)),
                    ("tailwater_m", f(v.tailwater)),
                    ("density_kg_m3", f(v.density)),
                    ("drain_efficiency", f(v.drain_efficiency)),
                ];
                if v.drain_efficiency > 0.0 {
                    water.push(("drain_position_m", f(v.drain_position)));
                }
                water.push(("crack", Value::Boolean(v.crack)));
                t.insert("water".into(), table(&water));
                if let Some(s) = v.silt {
                    let silt = [
                        ("depth_m", f(s.depth)),
                        ("unit_weight_n_m3", f(s.unit_weight)),
                        ("friction_angle_deg", f(s.friction_angle.to_degrees())),
                    ];
                    t.insert("silt".into(), table(&silt));
                }
                if let Some(i) = v.ice {
                    let ice = [
                        ("force_n_m", f(i.force_per_m)),
                        ("elevation_m", f(i.elevation)),
                    ];
                    t.insert("ice".into(), table(&ice));
                }
            }
            None => loads.insert(0, ("hydraulic_force_n", f(l.hydraulic_force))),
        }
        t.insert("loads".into(), table(&loads));
        if let Some(given) = self.source.get("seismic") {
            let mut seismic = vec![("kh", f(l.kh)), ("kv", f(l.kv))];
            for key in [
                "record",
                "record_x",
                "record_y",
                "record_z",
                "units",
                "dt_s",
                "scale",
                "target_pga_g",
                "polarity",
            ] {
                if let Some(v) = given.get(key) {
                    seismic.push((key, v.clone()));
                }
            }
            t.insert("seismic".into(), table(&seismic));
        }
    }

    /// `[friction]`: the criterion `fr` with its own keys, the cohesion, the faces' own
    /// criteria as given.
    fn friction_as_used(&self, fr: &Friction) -> Value {
        let f = Value::Float;
        let mut v = match *fr {
            Friction::Coulomb { mu_k } => table(&[
                ("model", Value::String(fr.model().into())),
                ("mu_k", f(mu_k)),
            ]),
            Friction::BartonChoubey {
                jrc,
                jcs_pa,
                phi_r,
                contact_area_m2,
            } => table(&[
                ("model", Value::String(fr.model().into())),
                ("jrc", f(jrc)),
                ("jcs_pa", f(jcs_pa)),
                ("phi_r_deg", f(phi_r.to_degrees())),
                ("contact_area_m2", f(contact_area_m2)),
            ]),
        };
        if let Value::Table(table) = &mut v {
            if let Some(st) = self.strengths().filter(|s| s.has_cohesion()) {
                table.insert("cohesion_pa".into(), f(st.cohesion_pa));
                table.insert("cohesion_area_m2".into(), f(self.shares_m2.iter().sum()));
            }
            if let Some(faces) = self.source.get("friction").and_then(|f| f.get("face")) {
                table.insert("face".into(), faces.clone());
            }
        }
        v
    }
}

/// The loads a scene's route uses, in the engineer's terms (N, m, from the heel along x' and
/// above the base): what `summary.json` echoes.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct LoadsUsed {
    /// m g.
    pub weight_n: f64,
    /// The water's net push along x' (the reservoir's less the tailwater's).
    pub hydraulic_force_n: f64,
    /// The lateral offset of its line from the centre of mass.
    pub eccentricity_m: f64,
    /// Its moment about the base point under the centre of mass, along k' (N·m).
    pub hydraulic_pitch_n_m: f64,
    /// The uplift on the base (0 without `[water]`).
    pub uplift_n: f64,
    /// The centre of mass above the base.
    pub cm_height_m: f64,
    /// The horizontal pseudo-static coefficient (a fraction of g).
    pub kh: f64,
    /// The vertical one.
    pub kv: f64,
    /// The water's loads from levels, each with where it acts.
    pub water: Option<crate::model::WaterLoads>,
}

impl Scene {
    /// The loads the scene's route uses (`None` without `[block]` or `[monolith]` and
    /// `[loads]`).
    pub fn loads_used(&self) -> Option<LoadsUsed> {
        let (b, l) = (self.block.as_ref()?, self.loads.as_ref()?);
        Some(LoadsUsed {
            weight_n: b.mass * l.gravity,
            hydraulic_force_n: l.hydraulic_force,
            eccentricity_m: l.eccentricity,
            hydraulic_pitch_n_m: l.hydraulic_pitch,
            uplift_n: l.water.map_or(0.0, |w| w.uplift.force_n),
            cm_height_m: l.cm_height,
            kh: l.kh,
            kv: l.kv,
            water: l.water,
        })
    }
}

#[cfg(all(test, feature = "cli"))]
mod tests {
    use super::*;

    #[test]
    fn the_scene_as_used_reads_back_as_the_same_scene() {
        // Every value, defaults filled in, in the file's own keys: written out and read again
        // it is the same scene (to the round trip of degrees and radians).
        let s = Scene::default_scene();
        let text = toml::to_string(&s.as_used()).unwrap();
        let back = Scene::from_toml(&text, "echo").unwrap();
        assert_eq!(back.site, s.site);
        assert_eq!(back.block, s.block);
        assert_eq!(back.loads, s.loads);
        assert_eq!(back.settings, s.settings);
        let used = s.as_used();
        assert_eq!(used["solver"]["dynamics"].as_str(), Some("rigid-body"));
        assert_eq!(used["block"]["inertia_x_kg_m2"].as_float(), Some(5.5e6));
    }
}
