//! Why a route ends: one typed reason each.

use crate::roots::{Inadmissible, TrackError};
use serde::Serialize;
use std::fmt;

/// The reason a route ended.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Reason {
    /// The driving force does not exceed the resistance at the start (factor of safety ≥ 1).
    DoesNotSlide,
    /// The paper's frictional system (23), (24), (28) has no solution with N0 > 0.
    NoFrictionSolution,
    /// The speed reached zero and friction holds the block.
    Stopped,
    /// A frictionless normal reaction (25)–(27) became non-positive.
    ContactLiftedOff,
    /// Contact 0 reached an inclined plane.
    Contact0ReachedInclinedPlane,
    /// Contact 1 or 2 left its plane.
    ContactLeftPlane,
    /// A tilt reached its dip (α → ξ or β → ζ).
    TiltReachedDip,
    /// On a foundation of faces: a contact reached a face other than its own (a crease).
    ContactReachedAnotherFace,
    /// On a surface: the ground fell away under a contact (a ridge): a three-point model ends.
    ContactOverRidge,
    /// On a surface: a contact left the surveyed surface.
    ContactOffSurface,
    /// A contact riding a crease is let go by the crease's second face (an event the rigid body
    /// handles; an end only where it cannot).
    CreaseLetsGo,
    /// A contact riding a crease leaves its own face for the crease's other one (an end until
    /// a contact can change its face).
    CreaseTakesOver,
    /// Every contact rides a crease: the block is held in all six degrees of freedom.
    Wedged,
    /// The pose equations have no admissible root to follow (the tracker's diagnosis).
    NoAdmissibleRoot,
    /// t reached t_end.
    TimeLimit,
    /// Rigid-body mode: the contact forces are not determined by the state (a singular
    /// contact system, Painlevé's paradox, or slip from rest with no consistent direction).
    ContactForcesUndetermined,
    /// The caller asked the route to stop (Ctrl-C, SIGTERM): what was computed stands.
    Interrupted,
    /// A base touching the ground: it turned over (its base tilted beyond the stated limit).
    Overturned,
    /// A base touching the ground: part of it went over no ground (off the surveyed surface).
    BaseOffGround,
    /// Several bodies: their dynamics together is not computed yet (the route ends at t = 0).
    SeveralBodies,
}

impl Reason {
    /// Every reason, in the order declared.
    pub const ALL: [Reason; 20] = [
        Reason::DoesNotSlide,
        Reason::NoFrictionSolution,
        Reason::Stopped,
        Reason::ContactLiftedOff,
        Reason::Contact0ReachedInclinedPlane,
        Reason::ContactLeftPlane,
        Reason::TiltReachedDip,
        Reason::ContactReachedAnotherFace,
        Reason::ContactOverRidge,
        Reason::ContactOffSurface,
        Reason::CreaseLetsGo,
        Reason::CreaseTakesOver,
        Reason::Wedged,
        Reason::NoAdmissibleRoot,
        Reason::TimeLimit,
        Reason::ContactForcesUndetermined,
        Reason::Interrupted,
        Reason::Overturned,
        Reason::BaseOffGround,
        Reason::SeveralBodies,
    ];

    /// The reason written `text` ([`Reason::as_str`]), if any.
    pub fn parse(text: &str) -> Option<Reason> {
        Reason::ALL.into_iter().find(|r| r.as_str() == text)
    }

    /// The reason in words, as route.csv's readers and the summaries write it.
    pub const fn as_str(self) -> &'static str {
        match self {
            Reason::DoesNotSlide => "does not slide",
            Reason::NoFrictionSolution => "the paper's frictional system has no solution",
            Reason::Stopped => "stopped",
            Reason::ContactLiftedOff => "contact lifted off",
            Reason::Contact0ReachedInclinedPlane => "contact 0 reached an inclined plane",
            Reason::ContactLeftPlane => "a contact left its plane",
            Reason::TiltReachedDip => "a tilt reached its dip",
            Reason::ContactReachedAnotherFace => "a contact reached another face",
            Reason::ContactOverRidge => "a contact ran over a ridge",
            Reason::ContactOffSurface => "a contact ran off the surveyed surface",
            Reason::CreaseLetsGo => "a crease let go of its contact",
            Reason::CreaseTakesOver => "a contact left its face for a crease's other face",
            Reason::Wedged => "the block is wedged (every contact in a crease)",
            Reason::NoAdmissibleRoot => "no admissible root",
            Reason::TimeLimit => "time limit",
            Reason::ContactForcesUndetermined => "the contact forces are not determined",
            Reason::Interrupted => "interrupted",
            Reason::Overturned => "the block overturned",
            Reason::BaseOffGround => "the base left the surveyed ground",
            Reason::SeveralBodies => "several bodies (not computed yet)",
        }
    }
}

impl fmt::Display for Reason {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.as_str())
    }
}

/// How and when a route ended.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Termination {
    /// Why it ended.
    pub reason: Reason,
    /// Time of the last state of the route (s).
    pub t_s: f64,
    /// What exactly happened, for people.
    pub detail: String,
}

/// Why a step of a route cannot go on, with the detail, before the route decides what it comes
/// to (an end, or an event it handles: a crease letting go of a contact, …).
#[derive(Debug, Clone, PartialEq)]
pub struct Stop {
    /// The reason the route would end for.
    pub reason: Reason,
    /// What exactly happened, for people.
    pub detail: String,
    /// The contact the reason is about, where it is about one (a crease letting go of it).
    pub contact: Option<usize>,
}

/// The reason for a failure of the tracker at the next increment.
pub fn from_track_error(e: &TrackError, alpha_at_dip: bool) -> Reason {
    match e {
        TrackError::Inadmissible { reason, .. } => match reason {
            Inadmissible::Contact0ReachedInclinedPlane => Reason::Contact0ReachedInclinedPlane,
            Inadmissible::Contact1LeftPlane1 | Inadmissible::Contact2LeftPlane2 => {
                Reason::ContactLeftPlane
            }
            Inadmissible::AlphaOutOfRange | Inadmissible::BetaOutOfRange if alpha_at_dip => {
                Reason::TiltReachedDip
            }
            Inadmissible::AlphaOutOfRange | Inadmissible::BetaOutOfRange => {
                Reason::ContactLeftPlane
            }
            // The paper's regions on any three planes: contact 0 under another contact's plane
            // has reached an inclined plane; contact 1 or 2 under contact 0's has left its own.
            Inadmissible::ContactUnderAnotherPlane(0, _) => Reason::Contact0ReachedInclinedPlane,
            Inadmissible::ContactUnderAnotherPlane(..) => Reason::ContactLeftPlane,
            Inadmissible::ContactUnderAnotherFace(..) => Reason::ContactReachedAnotherFace,
            Inadmissible::ContactOverRidge(..) => Reason::ContactOverRidge,
            Inadmissible::ContactOffSurface(..) => Reason::ContactOffSurface,
            Inadmissible::Spurious | Inadmissible::NoRealFrame => Reason::NoAdmissibleRoot,
        },
        TrackError::BranchEnded { .. } | TrackError::NonFinite(_) => Reason::NoAdmissibleRoot,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_reason_is_listed_once_and_read_back_from_its_words() {
        for (k, r) in Reason::ALL.into_iter().enumerate() {
            // Exhaustive: a new reason fails to compile here until it is listed.
            let listed = match r {
                Reason::DoesNotSlide
                | Reason::NoFrictionSolution
                | Reason::Stopped
                | Reason::ContactLiftedOff
                | Reason::Contact0ReachedInclinedPlane
                | Reason::ContactLeftPlane
                | Reason::TiltReachedDip
                | Reason::ContactReachedAnotherFace
                | Reason::ContactOverRidge
                | Reason::ContactOffSurface
                | Reason::CreaseLetsGo
                | Reason::CreaseTakesOver
                | Reason::Wedged
                | Reason::NoAdmissibleRoot
                | Reason::TimeLimit
                | Reason::ContactForcesUndetermined
                | Reason::Interrupted
                | Reason::Overturned
                | Reason::BaseOffGround
                | Reason::SeveralBodies => true,
            };
            assert!(listed);
            assert_eq!(Reason::parse(r.as_str()), Some(r));
            assert!(!Reason::ALL[..k].contains(&r), "{r:?} twice");
        }
        assert_eq!(Reason::parse("flew away"), None);
    }
}
