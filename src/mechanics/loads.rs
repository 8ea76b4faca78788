//! The driving loads in global coordinates at one pose.

use crate::geometry::LocalFrame;
use crate::scene::{Block, Loads};
use nalgebra::Vector3;

/// Hydraulic force, hydraulic couple and weight (N, N·m).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Applied {
    /// F·i' (eq. 40).
    pub force: Vector3<f64>,
    /// −c·F·j' (eq. 41 with the sign of `docs/conventions.md`: c > 0 makes θ grow).
    pub moment: Vector3<f64>,
    /// −m g Y.
    pub weight: Vector3<f64>,
}

impl Applied {
    pub fn new(loads: &Loads, block: &Block, frame: &LocalFrame) -> Self {
        let f = loads.hydraulic_force;
        Applied {
            force: frame.i * f,
            moment: frame.j * (-loads.eccentricity * f),
            weight: Vector3::new(0.0, -block.mass * loads.gravity, 0.0),
        }
    }
}
