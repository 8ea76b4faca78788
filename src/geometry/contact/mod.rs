//! Contact in geometry: which features of which bodies touch what, and where they lie flush.
//!
//! The first stages of the contact pipeline (ARCHITECTURE.md, "The contact pipeline"):
//!
//! * [`narrow`]: the narrow phase — each body's underside (a flat base or a cast relief)
//!   against the rock, at the body's pose, as [`Touches`](crate::geometry::Touches); the shape
//!   of a touch between two bodies.
//! * [`patch`]: patch reduction — where an underside lies flush on its rock or rests on points
//!   of one plane, the quadrature points that press there, and the touches a flush face's hull
//!   implies left out (`derivations/13-base-contact.md` §9).
//! * [`hull`]: the plane across a normal: its tangents and a hull's corners seen along it.
//!
//! The pairs and rows built on these, with their strengths, are `src/contact/`'s.

pub mod hull;
pub mod narrow;
pub mod patch;

pub use hull::{hull_across, tangents};
pub use narrow::{BodyTouch, Placed, Underside};
pub use patch::{Bed, Patch, Quadrature, Reduced, Spot, reduce};
// The rest, for the tests and `internals`: the narrow phase of every body at once (the route
// follows one), a hull in the plane, a patch's point.
#[cfg_attr(not(feature = "internals"), allow(unused_imports))]
pub use {hull::hull_corners, narrow::all_on_rock, patch::PatchPoint};
