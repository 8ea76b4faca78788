//! The local coordinate system at the CM, built from the vertex positions.
//!
//! We deliberately differ from the paper's (16)–(18) and R, which are misprinted (k' as printed
//! is not orthogonal to i'; R's first row has cos α sin α for cos α sin θ; R is not symmetric):
//! i' = (P1 − P0)/L, k' = (P1 − P2)/L, j' = k' × i', and R has rows i', j', k' (R_ij = e'_i·e_j,
//! eq. (19)), so v_local = R v_global and R⁻¹ = Rᵀ.

use nalgebra::{Matrix3, Vector3};

/// Orthonormal local axes (i', j', k') and R.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LocalFrame {
    /// i': along side 01, from vertex 0 to vertex 1.
    pub i: Vector3<f64>,
    /// j': the frame's upward normal.
    pub j: Vector3<f64>,
    /// k' = i' × j'.
    pub k: Vector3<f64>,
}

impl LocalFrame {
    /// From the three vertex positions and the side length L.
    pub fn from_vertices(p: &[Vector3<f64>; 3], l: f64) -> Self {
        let i = (p[1] - p[0]) / l;
        let k = (p[1] - p[2]) / l;
        let j = k.cross(&i);
        LocalFrame { i, j, k }
    }

    /// From the unit axes i' and k' (orthonormal): j' = k' × i'.
    pub fn from_axes(i: Vector3<f64>, k: Vector3<f64>) -> Self {
        LocalFrame {
            i,
            j: k.cross(&i),
            k,
        }
    }

    /// R with R_ij = e'_i · e_j: rows i', j', k' (eq. (19); v_local = R v_global).
    pub fn r(&self) -> Matrix3<f64> {
        Matrix3::from_rows(&[self.i.transpose(), self.j.transpose(), self.k.transpose()])
    }
}
