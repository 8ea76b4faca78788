//! How the route solves an increment's polynomial systems: continuation (the default) or all
//! roots by eigenvalues with the one continuing the previous chosen (for comparison in the
//! report). The method covers both systems: the pose here, and the paper's frictional reactions
//! in its right-hand side (`paper/rhs.rs`).

use super::termination::{Reason, Stop, from_track_error};
use crate::geometry::{Displacement, Pose, Site};
use crate::model::Mode;
use crate::roots::{BranchPoint, EigenFollower, TrackError, Tracker};
use serde::Serialize;

/// The method that gives the pose at each increment.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum PoseMethod {
    /// Predictor–corrector continuation of the physical branch (`roots::Tracker`); the
    /// reactions by Newton from the previous increment's solution.
    #[default]
    Continuation,
    /// All roots by eigenvalues at every increment, the admissible one nearest the previous
    /// pose chosen (`roots::EigenFollower`); likewise all solutions of the reactions, the one
    /// continuing the previous chosen by the stated rule.
    AllRoots,
}

impl PoseMethod {
    /// The method's name, as the report writes it.
    pub fn as_str(self) -> &'static str {
        match self {
            PoseMethod::Continuation => "continuation",
            PoseMethod::AllRoots => "all-roots",
        }
    }
}

/// Continuation is the common case and the larger variant; boxing it would cost an allocation
/// for every RK4 stage (the finder is cloned per stage), so the size difference is accepted.
#[allow(clippy::large_enum_variant)]
#[derive(Debug, Clone)]
pub enum PoseFinder<'s> {
    /// By continuation of the physical branch.
    Continuation(Tracker<'s>),
    /// By all roots at every increment.
    AllRoots(EigenFollower<'s>),
}

impl<'s> PoseFinder<'s> {
    /// A finder of the poses of `site` by `mode`'s system, at the start of sliding.
    pub fn new(site: &'s Site, mode: Mode, method: PoseMethod) -> Self {
        match method {
            PoseMethod::Continuation => PoseFinder::Continuation(Tracker::new(site, mode)),
            PoseMethod::AllRoots => PoseFinder::AllRoots(EigenFollower::new(site, mode)),
        }
    }

    /// A copy for the intermediate stages of an integrator, which are no states of the route:
    /// it does not check the contacts' regions (`roots::classify::check_pose_within`).
    pub fn for_stages(&self) -> Self {
        match self {
            PoseFinder::Continuation(t) => PoseFinder::Continuation(t.without_regions()),
            PoseFinder::AllRoots(f) => PoseFinder::AllRoots(f.without_regions()),
        }
    }

    /// The same point on another site (a contact gone onto another face).
    pub fn on_site(&self, site: crate::geometry::Site) -> Self {
        match self {
            PoseFinder::Continuation(t) => PoseFinder::Continuation(t.on_site(site)),
            PoseFinder::AllRoots(f) => PoseFinder::AllRoots(f.on_site(site)),
        }
    }

    /// The site followed: the scene's, or the one a contact's change of face made.
    pub fn site(&self) -> &crate::geometry::Site {
        match self {
            PoseFinder::Continuation(t) => t.site(),
            PoseFinder::AllRoots(f) => f.site(),
        }
    }

    /// Which method this finder is.
    pub fn method(&self) -> PoseMethod {
        match self {
            PoseFinder::Continuation(_) => PoseMethod::Continuation,
            PoseFinder::AllRoots(_) => PoseMethod::AllRoots,
        }
    }

    /// Moves to displacement `d` and returns the pose there, or the reason the route ends (the
    /// tracker's diagnosis as a termination reason).
    pub fn pose_at(&mut self, d: Displacement) -> Result<Pose, Stop> {
        self.advance(d).map_err(|e| {
            let at_dip = match (self.pose(), self.site().as_paper()) {
                (Some(p), Some(paper)) => {
                    p.alpha >= paper.foundation.xi || p.beta >= paper.foundation.zeta
                }
                _ => false,
            };
            Stop {
                contact: None,
                reason: from_track_error(&e, at_dip),
                detail: e.to_string(),
            }
        })?;
        self.pose().ok_or_else(|| Stop {
            contact: None,
            reason: Reason::NoAdmissibleRoot,
            detail: "the tracked point has no real frame".into(),
        })
    }

    /// Moves to displacement `d` along the branch.
    pub fn advance(&mut self, d: Displacement) -> Result<BranchPoint, TrackError> {
        match self {
            PoseFinder::Continuation(t) => t.advance(d),
            PoseFinder::AllRoots(f) => f.advance(d),
        }
    }

    /// The pose at the current point, if its frame is real.
    pub fn pose(&self) -> Option<Pose> {
        match self {
            PoseFinder::Continuation(t) => t.pose(),
            PoseFinder::AllRoots(f) => f.pose(),
        }
    }

    /// Jacobian condition number at the current point (continuation only).
    pub fn jacobian_condition(&self) -> Option<f64> {
        match self {
            PoseFinder::Continuation(t) => t.jacobian_condition(),
            PoseFinder::AllRoots(_) => None,
        }
    }

    /// Tracker statistics (continuation only).
    pub fn stats(&self) -> Option<crate::roots::TrackStats> {
        match self {
            PoseFinder::Continuation(t) => Some(t.stats),
            PoseFinder::AllRoots(_) => None,
        }
    }
}
