//! What the foundation's faces carry in shear: the friction criteria with proportional
//! stresses (paper §8) and the joint's cohesion. [`Friction`] is one criterion; [`Strengths`]
//! is every face's, with the cohesion shared among the contacts; [`Strength`] is what the three
//! contacts carry at one state, with the one fixed point of stress-dependent coefficients
//! ([`Strength::settle`]). A new criterion is a new variant of [`Friction`] and its arms in
//! [`Friction::shear`], [`Friction::is_frictionless`], [`Friction::is_stress_dependent`] and
//! [`Friction::check`].

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

/// What the three contacts can carry in shear at one state: each contact's friction criterion —
/// the one of the face it rests on — and its share of the joint's cohesion, held while the joint
/// is bonded (the block at rest and never yet slid) and lost once it slides
/// (`derivations/11-dam-loads.md` §8).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Strength {
    /// The friction criterion of the face under each contact.
    pub criteria: [Friction; 3],
    /// Each contact's share of the cohesion c·A (N); zero once the joint has slid.
    pub cohesion_n: [f64; 3],
}

impl From<Friction> for Strength {
    /// One criterion at every contact, no cohesion.
    fn from(f: Friction) -> Strength {
        Strength {
            criteria: [f; 3],
            cohesion_n: [0.0; 3],
        }
    }
}

impl Strength {
    /// |S| / |N| of contact i at normal force `normal` (0 for none): friction only.
    pub fn coefficient(&self, i: usize, normal: f64) -> f64 {
        self.criteria[i].coefficient(normal)
    }

    /// The three contacts' coefficients at their normal forces (negative ones taken as zero).
    pub fn coefficients(&self, normals: &[f64; 3]) -> [f64; 3] {
        std::array::from_fn(|i| self.coefficient(i, normals[i].max(0.0)))
    }

    /// |S| (N) contact i carries by friction at normal force `normal`.
    pub fn shear(&self, i: usize, normal: f64) -> f64 {
        self.criteria[i].shear(normal)
    }

    /// True when no contact has friction (no friction solve is needed).
    pub fn is_frictionless(&self) -> bool {
        self.criteria.iter().all(Friction::is_frictionless)
    }

    /// True when some contact's |S| / |N| depends on |N| (the coefficients must be settled with
    /// the normals).
    pub fn is_stress_dependent(&self) -> bool {
        self.criteria.iter().any(Friction::is_stress_dependent)
    }

    /// The same strength without cohesion: the joint once it has slid.
    pub fn sliding(&self) -> Strength {
        Strength {
            cohesion_n: [0.0; 3],
            ..*self
        }
    }

    /// Settles the coefficients μ of a stress-dependent criterion with the normal forces they
    /// give (the one fixed point of the paper's §8 for every solve that needs it): solve at μ
    /// and take μ' at the solution's normals, until μ' differs from μ by less than
    /// [`Settling::tol`] (at most [`Settling::max_solves`] solves). Returns the last solution — the one at the μ its own normals
    /// reproduce to `tol` — and whether it settled; μ is left at μ'. `normals` answering
    /// `None` (a solution without finite normals) stops the iteration unsettled.
    pub fn settle<S, E>(
        &self,
        mu: &mut [f64; 3],
        settling: Settling,
        mut solve: impl FnMut(&[f64; 3]) -> Result<S, E>,
        normals: impl Fn(&S) -> Option<[f64; 3]>,
    ) -> Result<(S, bool), E> {
        let Settling { tol, max_solves } = settling;
        let mut sol = solve(mu)?;
        for k in 0..max_solves.max(1) {
            if k > 0 {
                sol = solve(mu)?;
            }
            let Some(n) = normals(&sol) else {
                return Ok((sol, false));
            };
            let new = self.coefficients(&n);
            let change = (0..3).map(|j| (new[j] - mu[j]).abs()).fold(0.0, f64::max);
            *mu = new;
            if change < tol {
                return Ok((sol, true));
            }
        }
        Ok((sol, false))
    }
}

/// When [`Strength::settle`] stops: μ changed by less than `tol` in the last solve, or after
/// `max_solves` solves (unsettled).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Settling {
    /// The largest change of any μ that counts as settled.
    pub tol: f64,
    /// The most solves tried.
    pub max_solves: usize,
}

/// Faces with their own criterion and cohesion (`[[friction.face]]`).
#[derive(Debug, Clone, PartialEq)]
pub struct FaceStrength {
    /// Face numbers as in route.csv's `face` columns (the paper's planes 0, 1, 2; a list of
    /// planes or a surface's triangles in their order).
    pub faces: Vec<u32>,
    /// Their criterion.
    pub friction: Friction,
    /// Their cohesion (Pa).
    pub cohesion_pa: f64,
}

/// What every face carries: the default cohesion, the faces with their own criterion and
/// cohesion, and the share of the bonded area each contact stands for.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Strengths {
    /// The cohesion (Pa) of faces without their own.
    pub cohesion_pa: f64,
    /// The bonded area (m²) each contact stands for: the area times the contact's barycentric
    /// weight of the area's centroid, so that a uniform cohesion's resultant acts there.
    pub shares_m2: [f64; 3],
    /// Faces with their own criterion and cohesion, in the file's order (the first that names
    /// a face is its).
    pub faces: Vec<FaceStrength>,
}

impl Strengths {
    /// The strength of the contacts on `faces` with the default criterion `friction`; with
    /// cohesion when `bonded` (the block at rest and never yet slid).
    pub fn at(&self, friction: &Friction, faces: [u32; 3], bonded: bool) -> Strength {
        let own = |face: u32| self.faces.iter().find(|f| f.faces.contains(&face));
        let criteria = faces.map(|f| own(f).map_or(*friction, |s| s.friction));
        let cohesion_n = std::array::from_fn(|i| {
            let c = own(faces[i]).map_or(self.cohesion_pa, |s| s.cohesion_pa);
            if bonded { c * self.shares_m2[i] } else { 0.0 }
        });
        Strength {
            criteria,
            cohesion_n,
        }
    }

    /// True when some face has cohesion.
    pub fn has_cohesion(&self) -> bool {
        self.cohesion_pa > 0.0 || self.faces.iter().any(|f| f.cohesion_pa > 0.0)
    }

    /// Cohesions and shares zero or more, each face's criterion in its range, and every face
    /// named one of the foundation's `face_count` (numbered from 0).
    pub fn check(&self, face_count: usize) -> Result<(), ModelError> {
        non_negative("friction.cohesion_pa", self.cohesion_pa)?;
        for (k, s) in self.shares_m2.iter().enumerate() {
            non_negative(
                &format!("friction.cohesion_area_m2 (contact {k}'s share)"),
                *s,
            )?;
        }
        let mut seen = Vec::new();
        for (k, face) in self.faces.iter().enumerate() {
            let prefix = format!("friction.face[{k}]");
            if face.faces.is_empty() {
                return Err(ModelError::new(
                    format!("{prefix}.faces"),
                    "an empty list: name the faces (as route.csv's face columns) this entry is \
                     for",
                ));
            }
            if let Some(bad) = face.faces.iter().find(|&&n| n as usize >= face_count) {
                return Err(ModelError::new(
                    format!("{prefix}.faces"),
                    format!(
                        "face {bad} does not exist: the foundation's faces are 0 to {}",
                        face_count.saturating_sub(1)
                    ),
                ));
            }
            // A face named twice (in one entry or two) would take the first entry's criterion
            // silently: refused, naming both.
            for &n in &face.faces {
                if let Some(&(_, j)) = seen.iter().find(|(m, _)| *m == n) {
                    return Err(ModelError::new(
                        format!("{prefix}.faces"),
                        format!(
                            "face {n} is named twice (also in friction.face[{j}]): a face \
                             takes one criterion"
                        ),
                    ));
                }
                seen.push((n, k));
            }
            face.friction.check(&prefix)?;
            non_negative(&format!("{prefix}.cohesion_pa"), face.cohesion_pa)?;
        }
        Ok(())
    }
}

/// The barycentric weights of `p` in the triangle `c` (x′, z′), or `None` for a degenerate
/// triangle.
pub fn barycentric(c: &[[f64; 2]; 3], p: [f64; 2]) -> Option<[f64; 3]> {
    let (a, b) = (
        [c[1][0] - c[0][0], c[1][1] - c[0][1]],
        [c[2][0] - c[0][0], c[2][1] - c[0][1]],
    );
    let d = a[0] * b[1] - a[1] * b[0];
    if d.abs() < 1e-12 * (a[0].hypot(a[1]) * b[0].hypot(b[1])) {
        return None;
    }
    let q = [p[0] - c[0][0], p[1] - c[0][1]];
    let w1 = (q[0] * b[1] - q[1] * b[0]) / d;
    let w2 = (a[0] * q[1] - a[1] * q[0]) / d;
    Some([1.0 - w1 - w2, w1, w2])
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

    #[test]
    fn each_contact_takes_its_own_faces_criterion() {
        let s = Strength {
            criteria: [Friction::coulomb(0.3), Friction::coulomb(0.0), barton()],
            cohesion_n: [1.0, 2.0, 3.0],
        };
        assert_eq!(s.coefficient(0, 5.0), 0.3);
        assert_eq!(s.shear(1, 5.0), 0.0);
        assert_eq!(s.shear(2, 2e6), barton().shear(2e6));
        assert_eq!(s.coefficients(&[-1.0, 1.0, 1.0])[0], 0.0);
        assert!(!s.is_frictionless() && s.is_stress_dependent());
        assert_eq!(s.sliding().cohesion_n, [0.0; 3]);
        let none = Strength::from(Friction::coulomb(0.0));
        assert!(none.is_frictionless() && !none.is_stress_dependent());
    }

    /// Settled to round-off, well within the solves it may take.
    const SETTLING: Settling = Settling {
        tol: 1e-13,
        max_solves: 100,
    };

    #[test]
    fn settling_reaches_the_coefficients_its_normals_give() {
        // A toy solve: the normal force falls as the coefficient grows, N = 1 MN / (1 + μ).
        let s = Strength::from(barton());
        let solve = |mu: &[f64; 3]| -> Result<[f64; 3], ()> { Ok(mu.map(|m| 1e6 / (1.0 + m))) };
        let mut mu = [0.5; 3];
        let (n, settled) = s.settle(&mut mu, SETTLING, solve, |n| Some(*n)).unwrap();
        assert!(settled);
        for j in 0..3 {
            assert!((barton().coefficient(n[j]) - mu[j]).abs() < 1e-12);
            assert!((n[j] - 1e6 / (1.0 + mu[j])).abs() < 1e-6);
        }
        // Normals that cannot be had stop it, unsettled.
        let mut mu = [0.5; 3];
        let (_, settled) = s.settle(&mut mu, SETTLING, solve, |_| None).unwrap();
        assert!(!settled && mu == [0.5; 3]);
    }

    #[test]
    fn the_weights_rebuild_the_point_and_the_faces_their_strength() {
        let c = [[-6.0, 5.0], [4.0, 5.0], [4.0, -5.0]];
        // The monolith's base centre, 3 m downstream of its centre of mass (README).
        let w = barycentric(&c, [3.0, 0.0]).unwrap();
        for (got, want) in w.iter().zip([0.1, 0.4, 0.5]) {
            assert!((got - want).abs() < 1e-12, "{w:?}");
        }
        assert!(barycentric(&[[0.0, 0.0], [1.0, 0.0], [2.0, 0.0]], [0.0, 0.0]).is_none());
        let s = Strengths {
            cohesion_pa: 100.0,
            shares_m2: [1.0, 2.0, 3.0],
            faces: vec![FaceStrength {
                faces: vec![2, 7],
                friction: Friction::coulomb(0.9),
                cohesion_pa: 0.0,
            }],
        };
        let base = Friction::coulomb(0.4);
        let st = s.at(&base, [0, 7, 1], true);
        assert_eq!(st.criteria, [base, Friction::coulomb(0.9), base]);
        assert_eq!(st.cohesion_n, [100.0, 0.0, 300.0]);
        assert_eq!(s.at(&base, [0, 7, 1], false).cohesion_n, [0.0; 3]);
        assert!(s.has_cohesion() && s.check(8).is_ok());
        assert_eq!(s.check(7).unwrap_err().key, "friction.face[0].faces");
    }

    #[test]
    fn a_face_named_twice_is_refused_naming_both_entries() {
        let entry = |faces: Vec<u32>, mu| FaceStrength {
            faces,
            friction: Friction::coulomb(mu),
            cohesion_pa: 0.0,
        };
        let with = |faces| Strengths {
            cohesion_pa: 0.0,
            shares_m2: [0.0; 3],
            faces,
        };
        // In two entries: the second is named, with the first.
        let e = with(vec![entry(vec![1], 0.8), entry(vec![2, 1], 0.3)])
            .check(3)
            .unwrap_err();
        assert_eq!(e.key, "friction.face[1].faces");
        assert!(
            e.reason.contains("face 1") && e.reason.contains("friction.face[0]"),
            "{e}"
        );
        // In one entry.
        let e = with(vec![entry(vec![0, 0], 0.8)]).check(3).unwrap_err();
        assert_eq!(e.key, "friction.face[0].faces");
        // Each once: fine.
        assert!(
            with(vec![entry(vec![0], 0.8), entry(vec![1, 2], 0.3)])
                .check(3)
                .is_ok()
        );
    }
}
