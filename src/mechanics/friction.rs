//! Friction criteria with proportional stresses (paper §8): the shear a contact can carry as a
//! function of its normal force. The criteria are the variants of one enum,
//! [`Friction`](crate::scene::Friction); a new criterion is a new variant and its arms here
//! (`shear`, `is_frictionless`, `is_stress_dependent`).

use crate::scene::Friction;

/// Upper limit of the Barton–Choubey friction angle JRC·log10(JCS/σ) + φ_r (Barton's
/// recommended cap, reached only at very low normal stress).
pub const BARTON_MAX_ANGLE_DEG: f64 = 70.0;

impl Friction {
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

    /// True when |S| / |N| depends on |N| (the coefficients must be settled with the normals).
    pub fn is_stress_dependent(&self) -> bool {
        match *self {
            Friction::Coulomb { .. } => false,
            Friction::BartonChoubey { .. } => true,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn coulomb_is_proportional() {
        let f = Friction::Coulomb { mu_k: 0.4 };
        assert_eq!(f.shear(1000.0), 400.0);
        assert_eq!(f.coefficient(1000.0), 0.4);
        assert!(!f.is_frictionless());
        assert!(Friction::Coulomb { mu_k: 0.0 }.is_frictionless());
        assert!(!f.is_stress_dependent());
    }

    #[test]
    fn barton_choubey_matches_eq_43_by_hand() {
        // JRC 10, JCS 50 MPa, φr 30°, A = 2 m², N = 2 MN: σ = 1 MPa, log10(50) = 1.69897,
        // angle = 16.9897° + 30° = 46.9897°, τ = 1 MPa · tan(46.9897°).
        let f = Friction::BartonChoubey {
            jrc: 10.0,
            jcs_pa: 50e6,
            phi_r: 30f64.to_radians(),
            contact_area_m2: 2.0,
        };
        let want = 2e6 * (46.989_700_043_360_19f64).to_radians().tan();
        assert!((f.shear(2e6) - want).abs() < 1e-6 * want);
        // At σ ≥ JCS only φr remains; at tiny σ the angle is capped.
        assert!((f.coefficient(200e6) - 30f64.to_radians().tan()).abs() < 1e-12);
        assert!((f.coefficient(1.0) - 70f64.to_radians().tan()).abs() < 1e-12);
        assert!(f.is_stress_dependent() && !f.is_frictionless());
    }
}
