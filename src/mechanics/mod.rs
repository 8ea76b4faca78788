//! Forces on the block at one pose: loads, friction criteria, the frictionless normal
//! reactions (paper eqs. 25–27) and the paper's frictional reactions (eqs. 22–24, 28).
//!
//! Conventions (`docs/conventions.md`): F acts along i'; the hydraulic couple is −c·F about
//! j' (c > 0 turns the block so that θ grows); weight −m g along Y; each normal reaction lies
//! along the upward unit normal of its contact's plane and each shear reaction in that plane.

pub mod held;
pub mod impulses;
pub mod loads;
pub mod onset;
pub mod pressure;
pub mod reactions_paper;
pub mod rigid_body;
pub mod static_friction;
pub mod statics;

use crate::geometry::{LocalFrame, Pose};
use nalgebra::Vector3;

/// What the mechanics needs to know about a placed frame.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactGeometry {
    /// Local axes i', j', k' built from the vertices.
    pub frame: LocalFrame,
    /// From the CM to vertex i (global).
    pub r: [Vector3<f64>; 3],
    /// Upward unit normal of the plane carrying vertex i.
    pub n: [Vector3<f64>; 3],
    /// From the frame's origin (the base point under the centre of mass, where the pose puts
    /// it) to the point the arms `r` are from: zero, or the centre of mass itself
    /// ([`ContactGeometry::centred`]).
    pub cm_offset: Vector3<f64>,
    /// Where the frame's origin is (global): the pose's base point under the centre of mass,
    /// from which an anchor's head is placed.
    pub origin: Vector3<f64>,
}

impl ContactGeometry {
    /// The contacts of `pose` on the planes with upward unit normals `normals` (as
    /// [`crate::model::Body::normals`], computed once).
    pub fn new(normals: &[Vector3<f64>; 3], pose: &Pose) -> Self {
        ContactGeometry {
            frame: pose.frame,
            r: pose.vertices.map(|v| v - pose.cm),
            n: *normals,
            cm_offset: Vector3::zeros(),
            origin: pose.cm,
        }
    }

    /// The same contacts with their arms from the centre of mass at `height` above the frame's
    /// origin along j′ (a monolith's, `derivations/11-dam-loads.md` §1): what Newton–Euler
    /// about the centre of mass needs.
    pub fn centred(&self, height: f64) -> Self {
        let offset = self.frame.j * height;
        ContactGeometry {
            r: self.r.map(|r| r - offset),
            cm_offset: self.cm_offset + offset,
            ..*self
        }
    }

    /// A unit tangent of contact i along the projection of i' on its plane, and the second
    /// tangent n × t1; angle 0 of a shear force points along +i'.
    pub fn tangents(&self, i: usize) -> (Vector3<f64>, Vector3<f64>) {
        let n = self.n[i];
        let t1 = (self.frame.i - n * self.frame.i.dot(&n)).normalize();
        (t1, n.cross(&t1))
    }
}
