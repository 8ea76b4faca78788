//! `[friction]` and `[[friction.face]]`: the criterion of every face without its own, the faces
//! with their own, and the joint's cohesion shared among the contacts
//! (`derivations/11-dam-loads.md` §8).

use super::Reader;
use crate::geometry::Site;
use crate::model::{self, FaceStrength, Friction, Monolith, Strengths, barycentric};
use crate::scene::SceneError;
use crate::scene::error::SceneErrorKind;
use crate::scene::raw::{RawFaceFriction, RawFriction};

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
    fn of(f: &RawFriction) -> CriterionKeys<'_> {
        CriterionKeys {
            model: f.model.as_deref(),
            mu_k: f.mu_k,
            jrc: f.jrc,
            jcs_pa: f.jcs_pa,
            phi_r_deg: f.phi_r_deg,
            contact_area_m2: f.contact_area_m2,
        }
    }

    fn of_face(f: &RawFaceFriction) -> CriterionKeys<'_> {
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

impl Reader<'_> {
    /// The friction criterion of `[friction]`.
    pub(super) fn friction(&self, f: &RawFriction) -> Result<Friction, SceneError> {
        self.criterion("friction", &CriterionKeys::of(f))
    }

    /// The friction criterion under `prefix`: `model` says which keys belong; a key of the
    /// other model is refused as unknown rather than ignored.
    fn criterion(&self, prefix: &str, f: &CriterionKeys<'_>) -> Result<Friction, SceneError> {
        let key = |name: &str| format!("{prefix}.{name}");
        let [coulomb, barton] = Friction::MODELS;
        let model = self.need(&key("model"), f.model)?;
        if !Friction::MODELS.contains(&model) {
            return Err(self.invalid(
                key("model"),
                format!(
                    "unknown friction model \"{model}\"; expected one of \"{coulomb}\", \
                     \"{barton}\""
                ),
            ));
        }
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
            return Err(self.fault(
                SceneErrorKind::UnknownKey,
                key(name),
                format!(
                    "unknown key for model = \"{model}\" (its keys: model, {})",
                    own.join(", ")
                ),
            ));
        }
        let criterion = if model == coulomb {
            Friction::coulomb(self.need(&key("mu_k"), f.mu_k)?)
        } else {
            Friction::barton_choubey(
                self.need(&key("jrc"), f.jrc)?,
                self.need(&key("jcs_pa"), f.jcs_pa)?,
                self.need(&key("phi_r_deg"), f.phi_r_deg)?.to_radians(),
                self.need(&key("contact_area_m2"), f.contact_area_m2)?,
            )
        };
        criterion.check(prefix).map_err(|e| self.model(e))?;
        Ok(criterion)
    }

    /// `[friction]`: the default criterion and cohesion and `[[friction.face]]`, each face's
    /// criterion and cohesion; and each of the frame's contacts' share of the bonded area.
    pub(super) fn strengths(
        &self,
        f: &RawFriction,
        site: &Site,
        monolith: Option<&Monolith>,
    ) -> Result<(Strengths, [f64; 3]), SceneError> {
        let mut out = Strengths::new(self.friction(f)?);
        out.cohesion_pa = f.cohesion_pa.unwrap_or(0.0);
        for (k, face) in f.face.as_deref().unwrap_or(&[]).iter().enumerate() {
            let prefix = format!("friction.face[{k}]");
            let listed = self.need(&format!("{prefix}.faces"), face.faces.clone())?;
            let keys = CriterionKeys::of_face(face);
            let friction = if keys.any() {
                let model = keys.model.or(f.model.as_deref());
                self.criterion(&prefix, &CriterionKeys { model, ..keys })?
            } else {
                out.friction
            };
            out.faces.push(FaceStrength {
                faces: listed,
                friction,
                cohesion_pa: face.cohesion_pa.unwrap_or(out.cohesion_pa),
            });
        }
        out.check(model::face_count(site))
            .map_err(|e| self.model(e))?;
        if out.has_cohesion() {
            Ok((out, self.shares(f, site, monolith)?))
        } else if f.cohesion_area_m2.is_some() {
            Err(self.invalid(
                "friction.cohesion_area_m2",
                "an area without cohesion: give friction.cohesion_pa too",
            ))
        } else {
            Ok((out, [0.0; 3]))
        }
    }

    /// The bonded area each contact stands for: the area (given, or the monolith's base) times
    /// the contact's barycentric weight of the area's centroid (the base's centre, or the
    /// contact triangle's), so that a uniform cohesion's resultant acts there.
    fn shares(
        &self,
        f: &RawFriction,
        site: &Site,
        monolith: Option<&Monolith>,
    ) -> Result<[f64; 3], SceneError> {
        let (area, centre) = match (f.cohesion_area_m2, monolith) {
            (Some(a), m) => (
                self.positive("friction.cohesion_area_m2", a)?,
                m.map(Monolith::base_centre),
            ),
            (None, Some(m)) => (
                m.section.base_length * m.section.width,
                Some(m.base_centre()),
            ),
            (None, None) => {
                return Err(self.invalid(
                    "friction.cohesion_area_m2",
                    "cohesion needs the bonded area of the joint (m²): give \
                     friction.cohesion_area_m2, or [monolith] for its base",
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
            return Err(self.invalid(
                "friction.cohesion_pa",
                format!(
                    "the base's centre (x', z') = ({:.6}, {:.6}) m is outside the contact \
                     triangle: its cohesion cannot be shared among the three contacts with its \
                     resultant there; place the contacts around it",
                    centre[0], centre[1]
                ),
            ));
        };
        Ok(weights.map(|w| w.max(0.0) * area))
    }
}
