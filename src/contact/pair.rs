//! Contact pairs: which body touches what — a face of the rock or another body — where, along
//! which normal, how far apart, by which features, and with what strength.

use crate::geometry::contact::BodyTouch;
use crate::geometry::{BodyPose, Feature, Touch};
use crate::model::{Friction, PairStrength, Strengths, Surface};
use nalgebra::Vector3;

/// What a body touches.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Against {
    /// A face of the rock, by number.
    Rock {
        /// The face (for an edge or a vertex of the rock, one of the faces that meet there).
        face: usize,
    },
    /// Another body, by number.
    #[cfg_attr(not(feature = "internals"), allow(dead_code))]
    Body {
        /// The other body.
        body: usize,
        /// Its feature there.
        feature: Feature,
    },
}

/// One contact of one body: its frame (the point, the normal into the body, the gap), the
/// features that touch and the pair's strength.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactPair {
    /// The body, by number.
    pub body: usize,
    /// What it touches.
    pub against: Against,
    /// The body's point (world, m).
    pub point: Vector3<f64>,
    /// The same point in the body's axes about its centre of mass (m).
    pub on_body: Vector3<f64>,
    /// Unit normal from what it touches into the body.
    pub normal: Vector3<f64>,
    /// The gap along the normal (m; negative where they overlap).
    pub gap: f64,
    /// The body's feature.
    pub feature: Feature,
    /// The friction criterion between the two surfaces.
    pub criterion: Friction,
}

impl ContactPair {
    /// Body `body`'s touch `t` on the rock, with the criterion of the rock's face under it.
    pub fn on_rock(body: usize, t: &Touch, criterion: Friction) -> ContactPair {
        ContactPair {
            body,
            against: Against::Rock { face: t.face },
            point: t.on_base,
            on_body: t.body,
            normal: t.normal,
            gap: t.gap,
            feature: t.feature,
            criterion,
        }
    }

    /// The first body's side of a touch `t` between two bodies, the first at `pose`, with the
    /// criterion of their joint.
    #[cfg_attr(not(feature = "internals"), allow(dead_code))]
    pub fn between(t: &BodyTouch, pose: &BodyPose, criterion: Friction) -> ContactPair {
        ContactPair {
            body: t.bodies[0],
            against: Against::Body {
                body: t.bodies[1],
                feature: t.features[1],
            },
            point: t.on_first,
            on_body: pose.rotation.transpose() * (t.on_first - pose.cm),
            normal: t.normal,
            gap: t.gap,
            feature: t.features[0],
            criterion,
        }
    }

    /// The other body, if it touches one (None: the rock).
    pub fn other_body(&self) -> Option<usize> {
        match self.against {
            Against::Rock { .. } => None,
            Against::Body { body, .. } => Some(body),
        }
    }
}

/// The friction criterion between face `face` of the rock and body `body` (`Strengths::between`).
pub fn rock_criterion(strengths: &Strengths, face: usize, body: usize) -> Friction {
    rock_strength(strengths, face, body).criterion
}

/// What face `face` of the rock and body `body` carry where they touch: the criterion and the
/// cohesion (`Strengths::between`).
pub fn rock_strength(strengths: &Strengths, face: usize, body: usize) -> PairStrength {
    strengths.between(Surface::Rock(face as u32), Surface::Body(body))
}

/// Body `body`'s pairs on the rock from its `touches`, in their order, each with the criterion
/// between its face and the body.
pub fn on_rock(body: usize, touches: &[Touch], strengths: &Strengths) -> Vec<ContactPair> {
    touches
        .iter()
        .map(|t| ContactPair::on_rock(body, t, rock_criterion(strengths, t.face, body)))
        .collect()
}
