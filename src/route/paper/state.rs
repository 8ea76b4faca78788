//! The paper's state of the slide: the displacement (X, Z, θ) and its rates.

use crate::geometry::Displacement;

/// Position and velocity of the block: CM displacement (X, Z) (m), yaw θ (rad) and their
/// rates (m/s, rad/s), at time t (s).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct State {
    /// t (s).
    pub t: f64,
    /// X (m).
    pub x: f64,
    /// Z (m).
    pub z: f64,
    /// θ (rad).
    pub theta: f64,
    /// Ẋ (m/s).
    pub vx: f64,
    /// Ż (m/s).
    pub vz: f64,
    /// dθ/dt (rad/s).
    pub omega: f64,
}

impl State {
    /// Where the block is: (X, Z, θ).
    pub fn displacement(&self) -> Displacement {
        Displacement::new(self.x, self.z, self.theta)
    }

    /// Horizontal speed of the CM (m/s).
    pub fn speed(&self) -> f64 {
        self.vx.hypot(self.vz)
    }
}
