//! A joint between two bodies: where two monoliths meet, what it carries in shear and how far
//! open it is at the start. The simulation's builder checks each against the bodies it has.

use super::error::{ModelError, non_negative};
use super::friction::Friction;
use super::strength::PairStrength;

/// A contact between two distinct bodies of a simulation (by their places in its list of
/// bodies): its friction criterion, its cohesion while bonded, and its opening at the start.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Joint {
    /// The two bodies.
    pub bodies: [usize; 2],
    /// Its friction criterion.
    pub criterion: Friction,
    /// Its cohesion (Pa).
    pub cohesion_pa: f64,
    /// How far open it is at the start (m; zero: closed).
    pub opening_m: f64,
}

impl Joint {
    /// A closed joint between `bodies` under `criterion`, without cohesion.
    pub fn new(bodies: [usize; 2], criterion: Friction) -> Joint {
        Joint {
            bodies,
            criterion,
            cohesion_pa: 0.0,
            opening_m: 0.0,
        }
    }

    /// The same joint with cohesion `cohesion_pa` (Pa).
    pub fn with_cohesion(self, cohesion_pa: f64) -> Joint {
        Joint {
            cohesion_pa,
            ..self
        }
    }

    /// The same joint open by `opening_m` (m) at the start.
    pub fn with_opening(self, opening_m: f64) -> Joint {
        Joint { opening_m, ..self }
    }

    /// What it carries where its bodies touch.
    pub fn strength(&self) -> PairStrength {
        PairStrength {
            criterion: self.criterion,
            cohesion_pa: self.cohesion_pa,
        }
    }

    /// The `k`th joint of a simulation of `bodies` bodies: between two distinct bodies it has,
    /// its criterion in its range, its cohesion and opening zero or more. The errors name
    /// `joint[k].…`.
    pub fn check(&self, k: usize, bodies: usize) -> Result<(), ModelError> {
        let prefix = format!("joint[{k}]");
        let [a, b] = self.bodies;
        if let Some(bad) = [a, b].into_iter().find(|&i| i >= bodies) {
            return Err(ModelError::new(
                format!("{prefix}.bodies"),
                format!(
                    "body {bad} does not exist: the simulation's bodies are 0 to {}",
                    bodies.saturating_sub(1)
                ),
            ));
        }
        if a == b {
            return Err(ModelError::new(
                format!("{prefix}.bodies"),
                format!("body {a} twice: a joint is between two bodies"),
            ));
        }
        self.criterion.check(&prefix)?;
        non_negative(&format!("{prefix}.cohesion_pa"), self.cohesion_pa)?;
        non_negative(&format!("{prefix}.opening_m"), self.opening_m)?;
        Ok(())
    }
}

/// Every joint checked against `bodies` bodies, and no two between the same pair (the second
/// named, with the first).
pub(super) fn check_joints(joints: &[Joint], bodies: usize) -> Result<(), ModelError> {
    for (k, joint) in joints.iter().enumerate() {
        joint.check(k, bodies)?;
        let [a, b] = joint.bodies;
        let before = joints[..k]
            .iter()
            .position(|j| j.bodies == [a, b] || j.bodies == [b, a]);
        if let Some(j) = before {
            return Err(ModelError::new(
                format!("joint[{k}].bodies"),
                format!("bodies {a} and {b} already have joint[{j}]: a pair takes one joint"),
            ));
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_joint_is_between_two_distinct_existing_bodies_and_its_values_in_range() {
        let j = Joint::new([0, 1], Friction::coulomb(0.6))
            .with_cohesion(1e5)
            .with_opening(0.002);
        assert!(j.check(0, 2).is_ok());
        assert_eq!(j.strength().cohesion_pa, 1e5);
        let key = |j: Joint| j.check(3, 2).unwrap_err().key;
        assert_eq!(
            key(Joint::new([0, 2], Friction::coulomb(0.6))),
            "joint[3].bodies"
        );
        assert_eq!(
            key(Joint::new([1, 1], Friction::coulomb(0.6))),
            "joint[3].bodies"
        );
        assert_eq!(
            key(Joint::new([0, 1], Friction::coulomb(-1.0))),
            "joint[3].mu_k"
        );
        assert_eq!(key(j.with_cohesion(-1.0)), "joint[3].cohesion_pa");
        assert_eq!(key(j.with_opening(f64::NAN)), "joint[3].opening_m");
        let e = check_joints(&[j, Joint::new([1, 0], Friction::coulomb(0.3))], 2).unwrap_err();
        assert_eq!(e.key, "joint[1].bodies");
        assert!(e.reason.contains("joint[0]"), "{e}");
    }
}
