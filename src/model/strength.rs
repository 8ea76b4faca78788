//! What two surfaces carry in shear where they touch: a face of the rock and a body, or two
//! bodies across their joint. [`Strengths`] holds every surface's friction criterion and
//! cohesion and answers for a pair ([`Strengths::between`], a [`PairStrength`]); a contact takes
//! its pair's criterion and the share of its cohesion it stands for ([`ContactStrength`]). The
//! contacts of a contact model are a slice of them ([`ContactStrengths`]), with the one fixed
//! point of stress-dependent coefficients ([`ContactStrengths::settle`]).

use super::error::{ModelError, non_negative};
use super::friction::Friction;

/// A surface a contact is on.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Surface {
    /// A face of the rock, numbered as route.csv's `face` columns (the paper's planes 0, 1, 2;
    /// a list of planes or a surface's triangles in their order).
    Rock(u32),
    /// A body of the simulation, by its place in the list of bodies.
    Body(usize),
}

/// What a pair of surfaces carries where they touch: a friction criterion, and the cohesion of
/// the joint between them while it is bonded.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PairStrength {
    /// The pair's friction criterion.
    pub criterion: Friction,
    /// The joint's cohesion (Pa).
    pub cohesion_pa: f64,
}

impl PairStrength {
    /// What a contact standing for `area_m2` of the joint carries: the pair's criterion, and its
    /// share c·A of the cohesion when `bonded` (at rest and never yet slid;
    /// `derivations/11-dam-loads.md` §8).
    pub fn contact(&self, area_m2: f64, bonded: bool) -> ContactStrength {
        ContactStrength {
            criterion: self.criterion,
            cohesion_n: if bonded {
                self.cohesion_pa * area_m2
            } else {
                0.0
            },
        }
    }
}

/// What one contact carries in shear at one state: its pair's friction criterion and its share
/// of the joint's cohesion, held while the joint is bonded and lost once it slides.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactStrength {
    /// The friction criterion of the pair of surfaces the contact is between.
    pub criterion: Friction,
    /// The contact's share of the cohesion c·A (N); zero once the joint has slid.
    pub cohesion_n: f64,
}

impl From<Friction> for ContactStrength {
    /// The criterion, no cohesion.
    fn from(criterion: Friction) -> ContactStrength {
        ContactStrength {
            criterion,
            cohesion_n: 0.0,
        }
    }
}

impl ContactStrength {
    /// |S| / |N| at normal force `normal` (0 for none): friction only.
    pub fn coefficient(&self, normal: f64) -> f64 {
        self.criterion.coefficient(normal)
    }

    /// |S| (N) carried by friction at normal force `normal`.
    pub fn shear(&self, normal: f64) -> f64 {
        self.criterion.shear(normal)
    }

    /// The same contact without cohesion: the joint once it has slid.
    pub fn sliding(self) -> ContactStrength {
        ContactStrength {
            cohesion_n: 0.0,
            ..self
        }
    }
}

/// What the contacts of a contact model carry, each its own [`ContactStrength`], in the
/// contacts' order. A contact past the end of the slice carries nothing.
pub trait ContactStrengths {
    /// |S| / |N| of contact i at normal force `normal` (0 for none): friction only.
    fn coefficient(&self, i: usize, normal: f64) -> f64;

    /// |S| (N) contact i carries by friction at normal force `normal`.
    fn shear(&self, i: usize, normal: f64) -> f64;

    /// True when no contact has friction (no friction solve is needed).
    fn is_frictionless(&self) -> bool;

    /// True when some contact's |S| / |N| depends on |N| (the coefficients must be settled with
    /// the normals).
    fn is_stress_dependent(&self) -> bool;

    /// The first N contacts' coefficients at their normal forces (negative ones taken as zero).
    fn coefficients<const N: usize>(&self, normals: &[f64; N]) -> [f64; N] {
        std::array::from_fn(|i| self.coefficient(i, normals[i].max(0.0)))
    }

    /// The first N contacts' shares of the cohesion (N).
    fn cohesions<const N: usize>(&self) -> [f64; N];

    /// Settles the coefficients μ of a stress-dependent criterion with the normal forces they
    /// give (the one fixed point of the paper's §8 for every solve that needs it): solve at μ
    /// and take μ' at the solution's normals, until μ' differs from μ by less than
    /// [`Settling::tol`] (at most [`Settling::max_solves`] solves). Returns the last solution —
    /// the one at the μ its own normals reproduce to `tol` — and whether it settled; μ is left
    /// at μ'. `normals` answering `None` (a solution without finite normals) stops the
    /// iteration unsettled.
    fn settle<const N: usize, S, E>(
        &self,
        mu: &mut [f64; N],
        settling: Settling,
        mut solve: impl FnMut(&[f64; N]) -> Result<S, E>,
        normals: impl Fn(&S) -> Option<[f64; N]>,
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
            let change = (0..N).map(|j| (new[j] - mu[j]).abs()).fold(0.0, f64::max);
            *mu = new;
            if change < tol {
                return Ok((sol, true));
            }
        }
        Ok((sol, false))
    }
}

impl ContactStrengths for [ContactStrength] {
    fn coefficient(&self, i: usize, normal: f64) -> f64 {
        self.get(i).map_or(0.0, |c| c.coefficient(normal))
    }

    fn shear(&self, i: usize, normal: f64) -> f64 {
        self.get(i).map_or(0.0, |c| c.shear(normal))
    }

    fn is_frictionless(&self) -> bool {
        self.iter().all(|c| c.criterion.is_frictionless())
    }

    fn is_stress_dependent(&self) -> bool {
        self.iter().any(|c| c.criterion.is_stress_dependent())
    }

    fn cohesions<const N: usize>(&self) -> [f64; N] {
        std::array::from_fn(|i| self.get(i).map_or(0.0, |c| c.cohesion_n))
    }
}

/// When [`ContactStrengths::settle`] stops: μ changed by less than `tol` in the last solve, or
/// after `max_solves` solves (unsettled).
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

/// What every surface carries: the rock's criterion and cohesion for faces without their own,
/// the faces with their own (`[friction]` and `[[friction.face]]`), and the joints between
/// bodies (the simulation's, taken by its builder).
#[derive(Debug, Clone, PartialEq)]
pub struct Strengths {
    /// The criterion of faces without their own.
    pub friction: Friction,
    /// The cohesion (Pa) of faces without their own.
    pub cohesion_pa: f64,
    /// Faces with their own criterion and cohesion, in the file's order (the first that names
    /// a face is its).
    pub faces: Vec<FaceStrength>,
    /// Each joint's pair of bodies and strength, from the simulation's joints.
    joints: Vec<([usize; 2], PairStrength)>,
}

impl Strengths {
    /// `friction` on every face, no cohesion, no face of its own.
    pub fn new(friction: Friction) -> Strengths {
        Strengths {
            friction,
            cohesion_pa: 0.0,
            faces: Vec::new(),
            joints: Vec::new(),
        }
    }

    /// The same strengths with the joints between bodies `joints` (pairs of bodies and their
    /// strength), replacing any before.
    pub(crate) fn with_joints(self, joints: Vec<([usize; 2], PairStrength)>) -> Strengths {
        Strengths { joints, ..self }
    }

    /// What face `face` of the rock carries against a body: its own entry's, or the default.
    pub fn face(&self, face: u32) -> PairStrength {
        match self.faces.iter().find(|f| f.faces.contains(&face)) {
            Some(s) => PairStrength {
                criterion: s.friction,
                cohesion_pa: s.cohesion_pa,
            },
            None => PairStrength {
                criterion: self.friction,
                cohesion_pa: self.cohesion_pa,
            },
        }
    }

    /// What surfaces `a` and `b` carry where they touch: a face of the rock and a body, the
    /// face's ([`Strengths::face`]); two bodies, their joint's (without one, the rock's default
    /// criterion and no cohesion).
    pub fn between(&self, a: Surface, b: Surface) -> PairStrength {
        match (a, b) {
            (Surface::Rock(face), _) | (_, Surface::Rock(face)) => self.face(face),
            (Surface::Body(i), Surface::Body(j)) => self
                .joints
                .iter()
                .find(|(pair, _)| *pair == [i, j] || *pair == [j, i])
                .map_or(
                    PairStrength {
                        criterion: self.friction,
                        cohesion_pa: 0.0,
                    },
                    |(_, s)| *s,
                ),
        }
    }

    /// True when some face has cohesion.
    pub fn has_cohesion(&self) -> bool {
        self.cohesion_pa > 0.0 || self.faces.iter().any(|f| f.cohesion_pa > 0.0)
    }

    /// Every criterion in its range, cohesions zero or more, and every face named one of the
    /// rock's `face_count` (numbered from 0).
    pub fn check(&self, face_count: usize) -> Result<(), ModelError> {
        self.friction.check("friction")?;
        non_negative("friction.cohesion_pa", self.cohesion_pa)?;
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
    fn each_contact_takes_its_own_pairs_criterion() {
        let s = [
            ContactStrength {
                criterion: Friction::coulomb(0.3),
                cohesion_n: 1.0,
            },
            ContactStrength {
                criterion: Friction::coulomb(0.0),
                cohesion_n: 2.0,
            },
            ContactStrength {
                criterion: barton(),
                cohesion_n: 3.0,
            },
        ];
        let s: &[ContactStrength] = &s;
        assert_eq!(s.coefficient(0, 5.0), 0.3);
        assert_eq!(s.shear(1, 5.0), 0.0);
        assert_eq!(s.shear(2, 2e6), barton().shear(2e6));
        assert_eq!(s.coefficients(&[-1.0, 1.0, 1.0])[0], 0.0);
        assert!(!s.is_frictionless() && s.is_stress_dependent());
        assert_eq!(s.cohesions(), [1.0, 2.0, 3.0]);
        let slid: Vec<ContactStrength> = s.iter().map(|c| c.sliding()).collect();
        assert_eq!(slid.cohesions(), [0.0; 3]);
        // Past the slice's end: nothing carried.
        assert_eq!(s.shear(3, 1e6), 0.0);
        assert_eq!(s[..1].cohesions(), [1.0, 0.0]);
        let none = [ContactStrength::from(Friction::coulomb(0.0)); 3];
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
        let s = [ContactStrength::from(barton()); 3];
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

    fn strengths() -> Strengths {
        Strengths {
            cohesion_pa: 100.0,
            faces: vec![FaceStrength {
                faces: vec![2, 7],
                friction: Friction::coulomb(0.9),
                cohesion_pa: 0.0,
            }],
            ..Strengths::new(Friction::coulomb(0.4))
        }
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
        let s = strengths();
        let base = Friction::coulomb(0.4);
        let shares = [1.0, 2.0, 3.0];
        let st: [ContactStrength; 3] =
            std::array::from_fn(|i| s.face([0, 7, 1][i]).contact(shares[i], true));
        assert_eq!(
            st.map(|c| c.criterion),
            [base, Friction::coulomb(0.9), base]
        );
        assert_eq!(st.cohesions(), [100.0, 0.0, 300.0]);
        assert_eq!(s.face(7).contact(2.0, false).cohesion_n, 0.0);
        assert!(s.has_cohesion() && s.check(8).is_ok());
        assert_eq!(s.check(7).unwrap_err().key, "friction.face[0].faces");
    }

    #[test]
    fn a_pair_takes_the_rock_faces_strength_or_its_joints() {
        let joint = PairStrength {
            criterion: barton(),
            cohesion_pa: 5e4,
        };
        let s = strengths().with_joints(vec![([0, 2], joint)]);
        // A rock face against a body, either way round: the face's own, or the default.
        assert_eq!(s.between(Surface::Rock(7), Surface::Body(1)), s.face(7));
        assert_eq!(s.between(Surface::Body(0), Surface::Rock(7)), s.face(7));
        assert_eq!(s.face(7).criterion, Friction::coulomb(0.9));
        assert_eq!(s.face(3).cohesion_pa, 100.0);
        // Two bodies: their joint's, either way round; without a joint, the default criterion
        // and no cohesion.
        assert_eq!(s.between(Surface::Body(2), Surface::Body(0)), joint);
        assert_eq!(s.between(Surface::Body(0), Surface::Body(2)), joint);
        let loose = s.between(Surface::Body(0), Surface::Body(1));
        assert_eq!(loose.criterion, Friction::coulomb(0.4));
        assert_eq!(loose.cohesion_pa, 0.0);
    }

    #[test]
    fn a_face_named_twice_is_refused_naming_both_entries() {
        let entry = |faces: Vec<u32>, mu| FaceStrength {
            faces,
            friction: Friction::coulomb(mu),
            cohesion_pa: 0.0,
        };
        let with = |faces| Strengths {
            faces,
            ..Strengths::new(Friction::coulomb(0.4))
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
        // The default criterion is checked too, under its own key.
        let e = Strengths::new(Friction::coulomb(-1.0))
            .check(3)
            .unwrap_err();
        assert_eq!(e.key, "friction.mu_k");
    }
}
