//! Exact geometry of the sliding frame.
//!
//! * [`site`]: the frame and the foundation, all that geometry takes of a scene.
//! * [`paper_planes`]: the paper's three foundation planes, their heights and regions.
//! * [`frame`]: the local frame (i', j', k') built from the actual vertex positions, and R.
//! * [`pose`]: the pose from (X, Z, θ, α, β) through the paper's relations (1), (2), (21), and
//!   from (X, Z, θ, α, ψ).
//! * [`direct`]: the independent pose solver (Newton on the three contact constraints) — the
//!   oracle every other stage is tested against.
//! * [`touch`], [`settle`], [`penetration`]: a flat base against the ground: where they touch,
//!   where it rests, how deep it went by an independent check.
//! * [`relief`]: a base cast onto its rock, its underside the ground's own surface.
//! * [`contact`]: the narrow phase of the bodies against the rock, and the patches where an
//!   underside lies flush on it.
//! * [`rock`]: the ground in the collision library's shapes (`parry3d-f64`), the independent
//!   check of the touches and of how deep the base went.

pub mod contact;
pub mod direct;
pub mod frame;
pub mod ground;
pub mod paper_planes;
pub mod penetration;
pub mod plan_tree;
pub mod plane;
pub mod pose;
pub mod relief;
pub mod rock;
pub mod settle;
pub mod site;
pub mod touch;
mod wedge;

#[cfg(test)]
pub(crate) mod fixtures;

pub use direct::DirectPose;
pub use frame::LocalFrame;
pub use ground::Ground;
pub use plane::Plane;
pub use pose::Pose;
pub use relief::{CastError, Relief, cast, relief_touches};
pub use settle::{Rest, SettleError, set_down};
pub use site::{Frame, PaperPlanes, PaperSite, Site};
pub use touch::{
    BodyPose, Feature, Footprint, Touch, Touches, in_outline, plan_box, signed_area, touches,
};

/// The horizontal displacement of the block: CM moved by (X, Z) (m), side 01 yawed by θ (rad,
/// from +X towards +Z). The start of sliding is the default, (0, 0, 0).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Displacement {
    /// X (m).
    pub x: f64,
    /// Z (m).
    pub z: f64,
    /// θ (rad).
    pub theta: f64,
}

impl Displacement {
    /// The displacement (X, Z) (m) and θ (rad).
    pub fn new(x: f64, z: f64, theta: f64) -> Self {
        Displacement { x, z, theta }
    }

    /// The point a fraction `s` of the way along the straight segment from the start.
    pub fn scaled(self, s: f64) -> Self {
        Displacement::new(self.x * s, self.z * s, self.theta * s)
    }

    /// Whether X, Z and θ are all finite.
    pub fn is_finite(&self) -> bool {
        self.x.is_finite() && self.z.is_finite() && self.theta.is_finite()
    }
}

/// Why a pose cannot be built or found.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum GeometryError {
    /// The tilts give |cos h| > 1 or |sin γ| > 1: no real frame has them.
    #[error("no real frame has these tilts: {0}")]
    NoRealFrame(String),
    /// The direct solver did not converge.
    #[error(
        "the direct pose solver did not converge at {at}: residual {residual:.3e} m after {iterations} iterations"
    )]
    NotConverged {
        /// The displacement it was at, for people.
        at: String,
        /// The largest constraint residual it reached (m).
        residual: f64,
        /// The iterations it took.
        iterations: usize,
    },
    /// A non-finite input.
    #[error("non-finite input: {0}")]
    NonFinite(String),
}
