//! The narrow phase: which features of which bodies touch what, at their poses.
//!
//! A body meets the rock with its underside: a flat base, whose corners, the rock's vertices
//! under it and the rock's edges across its edges are where it can enter the rock
//! (`geometry/touch.rs`), or a base cast onto its rock, whose relief touches it at the same
//! three kinds of point (`geometry/relief/touches.rs`; `derivations/13-base-contact.md` §2,
//! §10). A body against another body is a [`BodyTouch`]: its shape is here for the pairs and
//! rows above (`src/contact/`), but no body's shape beyond its underside is in the model yet,
//! so nothing finds one.

use crate::geometry::{BodyPose, Feature, Footprint, Ground, Relief, Touches, relief_touches};
use nalgebra::Vector3;

/// What a body touches the rock with.
#[derive(Debug, Clone, Copy)]
pub enum Underside<'a> {
    /// A flat base.
    Flat(Footprint<'a>),
    /// A base cast onto its rock: its relief, which touches the rock in place of the flat
    /// footprint.
    Cast(&'a Relief),
}

/// One body as the narrow phase sees it: its number among the bodies, where it is, and what it
/// touches the rock with.
#[derive(Debug, Clone, Copy)]
pub struct Placed<'a> {
    /// Its number among the simulation's bodies.
    pub body: usize,
    /// Its centre of mass and rotation.
    pub pose: BodyPose,
    /// Its underside.
    pub underside: Underside<'a>,
}

impl Placed<'_> {
    /// The body's touches with `ground` whose gap is below `reach` (m), each point meeting the
    /// faces it may reach within a `drift` (m), and the points of its underside over no ground.
    pub fn on_rock(&self, ground: &Ground, reach: f64, drift: f64) -> Touches {
        match self.underside {
            Underside::Flat(base) => {
                crate::geometry::touches(ground, base, &self.pose, reach, drift)
            }
            Underside::Cast(relief) => relief_touches(ground, relief, &self.pose, reach, drift),
        }
    }
}

/// Every body's touches with `ground` whose gap is below `reach` (m), in the order of
/// `bodies`, at their poses as they stand (no drift).
#[cfg_attr(not(feature = "internals"), allow(dead_code))]
pub fn all_on_rock(ground: &Ground, bodies: &[Placed<'_>], reach: f64) -> Vec<Touches> {
    bodies
        .iter()
        .map(|b| b.on_rock(ground, reach, 0.0))
        .collect()
}

/// A place where two bodies touch or nearly do: body `bodies[0]`'s feature against body
/// `bodies[1]`'s.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(not(feature = "internals"), allow(dead_code))]
pub struct BodyTouch {
    /// The two bodies, by number (distinct).
    pub bodies: [usize; 2],
    /// The point of the first body (world, m).
    pub on_first: Vector3<f64>,
    /// Unit normal from the second body into the first.
    pub normal: Vector3<f64>,
    /// The gap along the normal (m; negative where they overlap).
    pub gap: f64,
    /// Which features touch, the first body's and the second's.
    pub features: [Feature; 2],
}
