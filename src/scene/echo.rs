//! The scene as used, in its file's own keys and units (degrees, SI), every default filled in:
//! what `summary.json` echoes so that anyone holding an output folder can tell what produced it
//! (issue #13).

use super::{Friction, Scene};
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
        let f = Value::Float;
        let mut t = Table::new();
        t.insert("name".into(), Value::String(self.name.clone()));
        // The frame and the foundation have no defaults: as the file gave them (the paper's
        // lengths and angles, or contacts and faces).
        for section in ["frame", "foundation"] {
            if let Some(v) = self.source.get(section) {
                t.insert(section.into(), v.clone());
            }
        }
        if let Some(b) = &self.block {
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
        if let Some(l) = &self.loads {
            t.insert(
                "loads".into(),
                table(&[
                    ("hydraulic_force_n", f(l.hydraulic_force)),
                    ("eccentricity_m", f(l.eccentricity)),
                    ("gravity_m_s2", f(l.gravity)),
                ]),
            );
        }
        if let Some(fr) = &self.friction {
            let v = match *fr {
                Friction::Coulomb { mu_k } => table(&[
                    ("model", Value::String("coulomb".into())),
                    ("mu_k", f(mu_k)),
                ]),
                Friction::BartonChoubey {
                    jrc,
                    jcs_pa,
                    phi_r,
                    contact_area_m2,
                } => table(&[
                    ("model", Value::String("barton-choubey".into())),
                    ("jrc", f(jrc)),
                    ("jcs_pa", f(jcs_pa)),
                    ("phi_r_deg", f(phi_r.to_degrees())),
                    ("contact_area_m2", f(contact_area_m2)),
                ]),
            };
            t.insert("friction".into(), v);
        }
        if let Some(s) = &self.solver {
            t.insert(
                "solver".into(),
                table(&[
                    ("mode", Value::String(s.mode.as_str().into())),
                    ("dt_s", f(s.dt)),
                    ("t_end_s", f(s.t_end)),
                    ("dynamics", Value::String(s.dynamics.as_str().into())),
                    ("integrator", Value::String(s.integrator.as_str().into())),
                    ("stride", Value::Integer(s.stride as i64)),
                ]),
            );
        }
        let i = &self.initial;
        t.insert(
            "initial".into(),
            table(&[
                ("vx_m_s", f(i.vx)),
                ("vz_m_s", f(i.vz)),
                ("omega_deg_s", f(i.omega.to_degrees())),
            ]),
        );
        t
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
        assert_eq!(back.solver, s.solver);
        let used = s.as_used();
        assert_eq!(used["solver"]["dynamics"].as_str(), Some("rigid-body"));
        assert_eq!(used["block"]["inertia_x_kg_m2"].as_float(), Some(5.5e6));
    }
}
