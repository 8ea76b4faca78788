//! The friction criteria, with proportional stresses (paper §8): [`Friction`] is one criterion,
//! what a pair of surfaces takes (`strength.rs` says which pair takes which). A new criterion is
//! a new variant of [`Friction`] and its arms in [`Friction::shear`],
//! [`Friction::is_frictionless`], [`Friction::is_stress_dependent`] and [`Friction::check`].

use super::error::{ModelError, finite, non_negative, positive};
use crate::numeric::degrees;

/// Upper limit of the Barton–Choubey friction angle JRC·log10(JCS/σ) + φ_r (Barton's
/// recommended cap, reached only at very low normal stress).
pub const BARTON_MAX_ANGLE_DEG: f64 = 70.0;

/// A friction criterion at the contacts (paper eqs. (24b) and (43)).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Friction {
    /// |S| = μ_k |N| (eq. 24b).
    #[non_exhaustive]
    Coulomb {
        /// μ_k.
        mu_k: f64,
    },
    /// Barton–Choubey, normalised per contact (eq. 43): τ = σ tan(JRC log10(JCS/σ) + φ_r),
    /// with σ = |N| / contact area.
    #[non_exhaustive]
    BartonChoubey {
        /// The joint roughness coefficient.
        jrc: f64,
        /// The joint wall's compressive strength (Pa).
        jcs_pa: f64,
        /// The residual friction angle (rad).
        phi_r: f64,
        /// The area each contact stands for (m²).
        contact_area_m2: f64,
    },
}

impl Friction {
    /// The models' names in a scene file (`[friction] model`), in the order of the variants.
    pub const MODELS: [&'static str; 2] = ["coulomb", "barton-choubey"];

    /// Coulomb's criterion with coefficient μ_k.
    pub fn coulomb(mu_k: f64) -> Friction {
        Friction::Coulomb { mu_k }
    }

    /// Barton–Choubey's criterion: JRC, JCS (Pa), φ_r (rad) and the area each contact stands
    /// for (m²).
    pub fn barton_choubey(jrc: f64, jcs_pa: f64, phi_r: f64, contact_area_m2: f64) -> Friction {
        Friction::BartonChoubey {
            jrc,
            jcs_pa,
            phi_r,
            contact_area_m2,
        }
    }

    /// The model's name in a scene file.
    pub fn model(&self) -> &'static str {
        match self {
            Friction::Coulomb { .. } => Friction::MODELS[0],
            Friction::BartonChoubey { .. } => Friction::MODELS[1],
        }
    }

    /// |S| (N) a contact carries at a normal force |N| (N) ≥ 0.
    pub fn shear(&self, normal: f64) -> f64 {
        if normal <= 0.0 {
            return 0.0;
        }
        match *self {
            // (24b)
            Friction::Coulomb { mu_k } => mu_k * normal,
            // (43) normalised per contact: σ = |N| / A, τ = σ tan(JRC log10(JCS/σ) + φ_r),
            // |S| = τ A. log10(JCS/σ) is taken ≥ 0 (the criterion is for σ ≤ JCS) and the angle
            // is capped at 70°.
            Friction::BartonChoubey {
                jrc,
                jcs_pa,
                phi_r,
                contact_area_m2,
            } => {
                let sigma = normal / contact_area_m2;
                let angle = (jrc * (jcs_pa / sigma).log10().max(0.0)).to_radians() + phi_r;
                normal * angle.min(BARTON_MAX_ANGLE_DEG.to_radians()).tan()
            }
        }
    }

    /// The same criterion for a contact standing for `area_m2` of the joint: Barton–Choubey's
    /// σ taken over that area (its share of the pressure, `derivations/13-base-contact.md`
    /// §11); Coulomb's unchanged. An area not positive and finite leaves the criterion as given.
    pub fn over(self, area_m2: f64) -> Friction {
        match self {
            Friction::BartonChoubey {
                jrc, jcs_pa, phi_r, ..
            } if area_m2 > 0.0 && area_m2.is_finite() => {
                Friction::barton_choubey(jrc, jcs_pa, phi_r, area_m2)
            }
            other => other,
        }
    }

    /// |S| / |N| at this normal force (0 for no normal force).
    pub fn coefficient(&self, normal: f64) -> f64 {
        if normal > 0.0 {
            self.shear(normal) / normal
        } else {
            0.0
        }
    }

    /// True when the criterion gives no shear at all (no friction solve is needed).
    pub fn is_frictionless(&self) -> bool {
        match *self {
            Friction::Coulomb { mu_k } => mu_k == 0.0,
            Friction::BartonChoubey { .. } => false,
        }
    }

    /// |S| / |N| where it is a constant (Coulomb's μ); None where it depends on |N|.
    pub fn constant_mu(&self) -> Option<f64> {
        match *self {
            Friction::Coulomb { mu_k } => Some(mu_k),
            Friction::BartonChoubey { .. } => None,
        }
    }

    /// True when |S| / |N| depends on |N| (the coefficients must be settled with the normals).
    pub fn is_stress_dependent(&self) -> bool {
        match *self {
            Friction::Coulomb { .. } => false,
            Friction::BartonChoubey { .. } => true,
        }
    }

    /// Each parameter in its range; `prefix` is the criterion's place in a scene file
    /// (`friction`, `friction.face[1]`), which its keys are named under.
    pub fn check(&self, prefix: &str) -> Result<(), ModelError> {
        let key = |name: &str| format!("{prefix}.{name}");
        match *self {
            Friction::Coulomb { mu_k } => {
                non_negative(&key("mu_k"), mu_k)?;
            }
            Friction::BartonChoubey {
                jrc,
                jcs_pa,
                phi_r,
                contact_area_m2,
            } => {
                non_negative(&key("jrc"), jrc)?;
                positive(&key("jcs_pa"), jcs_pa)?;
                finite(&key("phi_r_deg"), phi_r)?;
                if !(0.0..std::f64::consts::FRAC_PI_2).contains(&phi_r) {
                    return Err(ModelError::new(
                        key("phi_r_deg"),
                        format!(
                            "must be an angle from 0° up to (not including) 90°, got {}°",
                            degrees(phi_r.to_degrees())
                        ),
                    ));
                }
                positive(&key("contact_area_m2"), contact_area_m2)?;
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn barton() -> Friction {
        Friction::barton_choubey(10.0, 50e6, 30f64.to_radians(), 2.0)
    }

    #[test]
    fn coulomb_is_proportional() {
        let f = Friction::coulomb(0.4);
        assert_eq!(f.shear(1000.0), 400.0);
        assert_eq!(f.coefficient(1000.0), 0.4);
        assert!(!f.is_frictionless());
        assert!(Friction::coulomb(0.0).is_frictionless());
        assert!(!f.is_stress_dependent());
        // Its ratio is a constant, and the same as at any normal force.
        assert_eq!(f.constant_mu(), Some(f.coefficient(1.0)));
    }

    #[test]
    fn barton_choubey_matches_eq_43_by_hand() {
        // JRC 10, JCS 50 MPa, φr 30°, A = 2 m², N = 2 MN: σ = 1 MPa, log10(50) = 1.69897,
        // angle = 16.9897° + 30° = 46.9897°, τ = 1 MPa · tan(46.9897°).
        let f = barton();
        let want = 2e6 * (46.989_700_043_360_19f64).to_radians().tan();
        assert!((f.shear(2e6) - want).abs() < 1e-6 * want);
        // At σ ≥ JCS only φr remains; at tiny σ the angle is capped.
        assert!((f.coefficient(200e6) - 30f64.to_radians().tan()).abs() < 1e-12);
        assert!((f.coefficient(1.0) - 70f64.to_radians().tan()).abs() < 1e-12);
        assert!(f.is_stress_dependent() && !f.is_frictionless());
        assert_eq!(f.constant_mu(), None);
    }

    #[test]
    fn a_criterion_over_another_area_takes_its_stress_there() {
        // Over 4 m² a normal force of 4 MN is σ = 1 MPa: the shear of 2 MN over the 2 m² given.
        let f = barton().over(4.0);
        assert_eq!(f.shear(4e6), 2.0 * barton().shear(2e6));
        // An area that is none leaves it; Coulomb's is the same over any.
        assert_eq!(barton().over(0.0), barton());
        assert_eq!(barton().over(f64::NAN), barton());
        assert_eq!(Friction::coulomb(0.4).over(3.0), Friction::coulomb(0.4));
    }

    #[test]
    fn a_criterion_out_of_range_is_refused_naming_its_key() {
        assert!(barton().check("friction").is_ok());
        let e = Friction::coulomb(-0.1).check("friction").unwrap_err();
        assert_eq!(e.key, "friction.mu_k");
        let steep = Friction::barton_choubey(10.0, 50e6, 95f64.to_radians(), 2.0);
        let e = steep.check("friction.face[2]").unwrap_err();
        assert_eq!(e.key, "friction.face[2].phi_r_deg");
        assert!(e.reason.contains("95"), "{e}");
    }
}
