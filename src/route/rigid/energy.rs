//! The rigid body's energy balance: the work of the applied loads and of friction against the
//! change of kinetic and potential energy since the start (`derivations/08-rigid-body.md` §3).

use super::state::RigidState;
use crate::route::energy::EnergyBalance;

/// What the balance is measured from: the start's kinetic energy (J) and the CM's height there
/// (m), with the block's weight.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct EnergyOrigin {
    /// The kinetic energy at the start (J).
    pub kinetic: f64,
    /// The CM's height at the start (m).
    pub cm_y: f64,
    /// m (kg) and g (m/s²).
    pub mass: f64,
    pub gravity: f64,
}

impl EnergyOrigin {
    /// The balance at state `y`, where the kinetic energy is `kinetic` (J) and the CM's height
    /// `cm_y` (m).
    pub fn balance(&self, y: &RigidState, kinetic: f64, cm_y: f64) -> EnergyBalance {
        let potential = self.mass * self.gravity * (cm_y - self.cm_y);
        EnergyBalance::of(
            (y.work_applied, y.work_friction),
            (self.kinetic, kinetic),
            potential,
        )
    }
}
