//! The energy balance of a route whose model follows the block's energy (the rigid body on its
//! three-point frame, the block on its base): the works of the loads and of friction against the
//! change of kinetic and potential energy since the start (`derivations/08-rigid-body.md` §3).

use serde::Serialize;

/// Energy bookkeeping of a rigid-body route (J), from the start to its last state.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize)]
pub struct EnergyBalance {
    /// Work of the applied loads other than gravity's pull: the water's force and its couples,
    /// the pseudo-static and a record's inertial forces, the anchors' tendons.
    pub work_hydraulic_j: f64,
    /// Work of friction (≤ 0).
    pub work_friction_j: f64,
    /// Kinetic energy at the end.
    pub kinetic_j: f64,
    /// Kinetic energy at the start (0 unless the scene's `[initial]` sets the block moving).
    pub kinetic_initial_j: f64,
    /// Change of potential energy m g ΔY_cm.
    pub potential_change_j: f64,
    /// W_h + W_f − (kinetic − initial kinetic + potential change): zero up to the integrator's
    /// error.
    pub residual_j: f64,
}

impl EnergyBalance {
    /// The balance of works `(applied, friction)` (J) against the kinetic energy `(at the start,
    /// now)` (J) and the change of potential energy m g ΔY (J), the residual what they leave.
    pub fn of(
        (work_applied, work_friction): (f64, f64),
        (kinetic_initial, kinetic): (f64, f64),
        potential_change: f64,
    ) -> Self {
        EnergyBalance {
            work_hydraulic_j: work_applied,
            work_friction_j: work_friction,
            kinetic_j: kinetic,
            kinetic_initial_j: kinetic_initial,
            potential_change_j: potential_change,
            residual_j: work_applied + work_friction
                - (kinetic - kinetic_initial)
                - potential_change,
        }
    }
}
