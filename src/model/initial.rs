//! The motion at the start of the route.

use super::error::{ModelError, finite};

/// The motion at t = 0: the CM velocity (Ẋ, Ż) (m/s) and the yaw rate θ̇ (rad/s). Default: at
/// rest. A block set moving — by a transient such as an earthquake pulse, as in Newmark's
/// sliding block — under loads that static friction can hold decelerates and stops.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
#[non_exhaustive]
pub struct Initial {
    /// Ẋ (m/s).
    pub vx: f64,
    /// Ż (m/s).
    pub vz: f64,
    /// θ̇ (rad/s).
    pub omega: f64,
}

impl Initial {
    /// Moving at (Ẋ, Ż) (m/s) and turning at θ̇ (rad/s).
    pub fn new(vx: f64, vz: f64, omega: f64) -> Initial {
        Initial { vx, vz, omega }
    }

    /// Whether the block starts at rest.
    pub fn at_rest(&self) -> bool {
        self.vx == 0.0 && self.vz == 0.0 && self.omega == 0.0
    }

    /// Every rate finite.
    pub fn check(&self) -> Result<(), ModelError> {
        finite("initial.vx_m_s", self.vx)?;
        finite("initial.vz_m_s", self.vz)?;
        finite("initial.omega_deg_s", self.omega)?;
        Ok(())
    }
}
