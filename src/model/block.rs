//! The monolith's mass properties.

use super::error::{ModelError, finite, positive};

/// Mass properties of the monolith, about its centre of mass in its own axes (x′ along the
/// water's push, y′ up, z′ across): from `[block]` directly, or from a section
/// ([`Monolith::block`](super::Monolith::block)).
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub struct Block {
    /// m (kg).
    pub mass: f64,
    /// I_m about the frame normal y' (kg·m²): the paper's only moment of inertia.
    pub inertia: f64,
    /// Moment about x' (kg·m²; rigid-body dynamics). A thin plate's by default: `inertia / 2`.
    pub inertia_x: f64,
    /// Moment about z' (kg·m²; rigid-body dynamics). A thin plate's by default: `inertia / 2`.
    pub inertia_z: f64,
    /// Product of inertia ∫ x' z' dm (kg·m²; rigid-body dynamics), entering the tensor as
    /// −I_xz. 0 by default.
    pub inertia_xz: f64,
    /// Product of inertia ∫ x' y' dm (kg·m²; rigid-body dynamics), entering the tensor as
    /// −I_xy: a monolith's section is not symmetric about its centre's height. 0 for a plate.
    pub inertia_xy: f64,
}

impl Block {
    /// A thin plate in the x′z′ plane: mass m (kg) and moment I about y′ (kg·m²), the moments
    /// about x′ and z′ half of it each, no products of inertia.
    pub fn plate(mass: f64, inertia: f64) -> Block {
        Block {
            mass,
            inertia,
            inertia_x: inertia / 2.0,
            inertia_z: inertia / 2.0,
            inertia_xz: 0.0,
            inertia_xy: 0.0,
        }
    }

    /// The same block with its moments about x′ and z′ and the product ∫ x′z′ dm (kg·m²).
    #[must_use]
    pub fn with_axes(self, inertia_x: f64, inertia_z: f64, inertia_xz: f64) -> Block {
        Block {
            inertia_x,
            inertia_z,
            inertia_xz,
            ..self
        }
    }

    /// The same block with the product of inertia ∫ x′y′ dm (kg·m²).
    #[must_use]
    pub fn with_product_xy(self, inertia_xy: f64) -> Block {
        Block { inertia_xy, ..self }
    }

    /// The inertia tensor about the CM in the block's axes (x', y', z') (kg·m²).
    pub fn tensor(&self) -> nalgebra::Matrix3<f64> {
        nalgebra::Matrix3::new(
            self.inertia_x,
            -self.inertia_xy,
            -self.inertia_xz,
            -self.inertia_xy,
            self.inertia,
            0.0,
            -self.inertia_xz,
            0.0,
            self.inertia_z,
        )
    }

    /// The checks a rigid body passes: a positive mass and positive moments, finite products,
    /// and a tensor that is positive definite and whose principal moments obey the triangle
    /// inequality (no body has the largest above the sum of the other two).
    pub fn check(&self) -> Result<(), ModelError> {
        positive("block.mass_kg", self.mass)?;
        positive("block.inertia_kg_m2", self.inertia)?;
        positive("block.inertia_x_kg_m2", self.inertia_x)?;
        positive("block.inertia_z_kg_m2", self.inertia_z)?;
        finite("block.inertia_xz_kg_m2", self.inertia_xz)?;
        finite("block.inertia_xy_kg_m2", self.inertia_xy)?;
        let key = if self.inertia_xz != 0.0 {
            "block.inertia_xz_kg_m2"
        } else {
            "block"
        };
        let p = self.tensor().symmetric_eigenvalues();
        let (lo, hi, sum) = (p.min(), p.max(), p.sum());
        if lo <= 0.0 {
            return Err(ModelError::new(
                key,
                format!(
                    "the inertia tensor is not positive definite (principal moments {:.6e}, \
                     {:.6e}, {:.6e} kg·m²): |inertia_xz| must be below √(inertia_x · inertia_z)",
                    p[0], p[1], p[2]
                ),
            ));
        }
        if hi > (sum - hi) * (1.0 + 1e-9) {
            return Err(ModelError::new(
                key,
                format!(
                    "no rigid body has these moments of inertia: the largest principal moment \
                     {hi:.6e} kg·m² exceeds the sum of the other two, {:.6e} kg·m²",
                    sum - hi
                ),
            ));
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_plate_is_rigid_and_a_tensor_no_body_has_is_refused_naming_its_key() {
        let plate = Block::plate(1e6, 1.1e7);
        assert!(plate.check().is_ok());
        assert_eq!((plate.inertia_x, plate.inertia_z), (5.5e6, 5.5e6));
        // |I_xz| over √(I_x I_z): not positive definite.
        let e = plate.with_axes(5.5e6, 5.5e6, 6e6).check().unwrap_err();
        assert_eq!(e.key, "block.inertia_xz_kg_m2");
        assert!(e.reason.contains("positive definite"), "{e}");
        // A moment about y' above the sum of the others.
        let e = plate.with_axes(1e6, 1e6, 0.0).check().unwrap_err();
        assert_eq!(e.key, "block");
        assert!(e.reason.contains("exceeds the sum"), "{e}");
        let e = Block::plate(-1.0, 1.0).check().unwrap_err();
        assert_eq!(e.key, "block.mass_kg");
    }
}
