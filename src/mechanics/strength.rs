//! What the three contacts can carry in shear at one state ([`Strength`], issue #16,
//! `derivations/11-dam-loads.md` §8): the arms of each contact's criterion, and the fixed point
//! of stress-dependent coefficients. A new criterion is a new `Friction` variant
//! (`super::friction`).

use crate::scene::{Friction, Strength};

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
    /// and take μ' at the solution's normals, until μ' differs from μ by less than `tol` (at
    /// most `max` solves). Returns the last solution — the one at the μ its own normals
    /// reproduce to `tol` — and whether it settled; μ is left at μ'. `normals` answering
    /// `None` (a solution without finite normals) stops the iteration unsettled.
    pub fn settle<S, E>(
        &self,
        mu: &mut [f64; 3],
        (tol, max): (f64, usize),
        mut solve: impl FnMut(&[f64; 3]) -> Result<S, E>,
        normals: impl Fn(&S) -> Option<[f64; 3]>,
    ) -> Result<(S, bool), E> {
        let mut sol = solve(mu)?;
        for k in 0..max.max(1) {
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

#[cfg(test)]
mod tests {
    use super::*;

    fn barton() -> Friction {
        Friction::BartonChoubey {
            jrc: 10.0,
            jcs_pa: 50e6,
            phi_r: 30f64.to_radians(),
            contact_area_m2: 2.0,
        }
    }

    #[test]
    fn each_contact_takes_its_own_faces_criterion() {
        let s = Strength {
            criteria: [
                Friction::Coulomb { mu_k: 0.3 },
                Friction::Coulomb { mu_k: 0.0 },
                barton(),
            ],
            cohesion_n: [1.0, 2.0, 3.0],
        };
        assert_eq!(s.coefficient(0, 5.0), 0.3);
        assert_eq!(s.shear(1, 5.0), 0.0);
        assert_eq!(s.shear(2, 2e6), barton().shear(2e6));
        assert_eq!(s.coefficients(&[-1.0, 1.0, 1.0])[0], 0.0);
        assert!(!s.is_frictionless() && s.is_stress_dependent());
        assert_eq!(s.sliding().cohesion_n, [0.0; 3]);
        let none = Strength::from(Friction::Coulomb { mu_k: 0.0 });
        assert!(none.is_frictionless() && !none.is_stress_dependent());
    }

    #[test]
    fn settling_reaches_the_coefficients_its_normals_give() {
        // A toy solve: the normal force falls as the coefficient grows, N = 1 MN / (1 + μ).
        let s = Strength::from(barton());
        let solve = |mu: &[f64; 3]| -> Result<[f64; 3], ()> { Ok(mu.map(|m| 1e6 / (1.0 + m))) };
        let mut mu = [0.5; 3];
        let (n, settled) = s
            .settle(&mut mu, (1e-13, 100), solve, |n| Some(*n))
            .unwrap();
        assert!(settled);
        for j in 0..3 {
            assert!((barton().coefficient(n[j]) - mu[j]).abs() < 1e-12);
            assert!((n[j] - 1e6 / (1.0 + mu[j])).abs() < 1e-6);
        }
        // Normals that cannot be had stop it, unsettled.
        let mut mu = [0.5; 3];
        let (_, settled) = s.settle(&mut mu, (1e-13, 100), solve, |_| None).unwrap();
        assert!(!settled && mu == [0.5; 3]);
    }
}
