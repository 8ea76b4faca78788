//! What geometry needs of a scene: the contact frame and the foundation's planes
//! (`docs/conventions.md`, "The frame" and "The foundation"). The scene builds them from its
//! file and validates them; geometry takes nothing else.

use nalgebra::Vector3;

/// The contact triangle in the monolith base, in its own plane (x', z'), CM at the origin:
/// r0 = (−L1X, L1Z), r1 = (L2X, L1Z), r2 = (L2X, −L2Z) (paper eq. (20)); all lengths in m.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Frame {
    pub l1x: f64,
    pub l2x: f64,
    pub l1z: f64,
    pub l2z: f64,
}

impl Frame {
    /// Side length L = L1X + L2X = L1Z + L2Z (sides 01 and 12; side 02 is √2·L).
    pub fn l(&self) -> f64 {
        self.l1x + self.l2x
    }

    /// In-plane coordinates (x', z') of vertices 0, 1, 2 relative to the CM (eq. (20)).
    pub fn vertices(&self) -> [[f64; 2]; 3] {
        [
            [-self.l1x, self.l1z],
            [self.l2x, self.l1z],
            [self.l2x, -self.l2z],
        ]
    }
}

/// The three foundation planes: horizontal (vertex 0), plane 1 (vertex 1), plane 2 (vertex 2).
/// Angles in radians.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Foundation {
    /// ξ: true dip of plane 1, in (0, π/2).
    pub xi: f64,
    /// ζ: true dip of plane 2, in (0, π/2).
    pub zeta: f64,
    /// κ: azimuth of int. line 2/horiz, in (−π/2, π/2).
    pub kappa: f64,
}

impl Foundation {
    /// The upward unit normals of the horizontal plane, plane 1 and plane 2 (the planes under
    /// vertices 0, 1 and 2; `docs/conventions.md`, "The foundation").
    pub fn normals(&self) -> [Vector3<f64>; 3] {
        let (s1, c1) = self.xi.sin_cos();
        let (s2, c2) = self.zeta.sin_cos();
        [
            Vector3::y(),
            Vector3::new(-s1, c1, 0.0),
            Vector3::new(-s2 * self.kappa.cos(), c2, s2 * self.kappa.sin()),
        ]
    }
}

/// The frame and the foundation together.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Site {
    pub frame: Frame,
    pub foundation: Foundation,
}

impl Site {
    /// Side length L (m).
    pub fn l(&self) -> f64 {
        self.frame.l()
    }
}
