//! The alternative to continuation: at every increment, all roots by eigenvalues, then the
//! admissible root nearest the previous point. Used by the work–precision report to compare
//! the two methods; the [`super::Tracker`] is the default.

use super::classify::{self, Inadmissible};
use super::system::Equations;
use super::tracker::{BranchPoint, TrackError, correct};
use super::{eigen, system};
use crate::coeffs::{Inputs, SiteTrig};
use crate::geometry::Site;
use crate::geometry::{Displacement, Pose};
use crate::model::Mode;
use std::borrow::Cow;

/// Follows the physical pose by solving for all roots at every increment.
#[derive(Debug, Clone)]
pub struct EigenFollower<'s> {
    /// The site followed: the scene's, or one the route changed to (a contact onto another
    /// face, [`EigenFollower::on_site`]).
    site: Cow<'s, Site>,
    /// The foundation's trigonometric functions and the unknowns' scales, computed once.
    trig: SiteTrig,
    scales: system::UnknownScales,
    mode: Mode,
    current: BranchPoint,
    /// The regions' tolerance of the admissibility check (see [`classify::check_pose_within`]).
    region_tol: f64,
}

impl<'s> EigenFollower<'s> {
    /// At the start of sliding (the flat frame).
    pub fn new(site: &'s Site, mode: Mode) -> Self {
        EigenFollower {
            site: Cow::Borrowed(site),
            trig: SiteTrig::new(site),
            scales: system::unknown_scales(site, mode),
            mode,
            current: BranchPoint {
                d: Displacement::default(),
                u: [0.0, 0.0],
            },
            region_tol: classify::REGION_TOL,
        }
    }

    /// A copy that does not check the contacts' regions (only the tilts' upper bounds), for the
    /// intermediate stages of an integrator.
    pub fn without_regions(&self) -> Self {
        EigenFollower {
            region_tol: f64::INFINITY,
            ..self.clone()
        }
    }

    /// The same point followed on another site (see [`super::Tracker::on_site`]).
    pub fn on_site(&self, site: Site) -> EigenFollower<'s> {
        EigenFollower {
            trig: SiteTrig::new(&site),
            scales: system::unknown_scales(&site, self.mode),
            site: Cow::Owned(site),
            ..self.clone()
        }
    }

    /// The site followed.
    pub fn site(&self) -> &Site {
        &self.site
    }

    /// The pose at the current point, if its frame is real.
    pub fn pose(&self) -> Option<Pose> {
        classify::pose(&self.site, self.current.d, self.mode, self.current.u)
    }

    /// All roots at `target`; the admissible one nearest the current point becomes current.
    pub fn advance(&mut self, target: Displacement) -> Result<BranchPoint, TrackError> {
        if !target.is_finite() {
            return Err(TrackError::NonFinite(target));
        }
        if target == self.current.d {
            // Already there (in particular the start, the flat frame, known exactly).
            return Ok(self.current);
        }
        let fail = |reason| TrackError::Inadmissible {
            x: target.x,
            z: target.z,
            theta_deg: target.theta.to_degrees(),
            reason,
        };
        let inputs = Inputs::with_trig(&self.site, &self.trig, target);
        let system::UnknownScales { x: sx, y: sy } = self.scales;
        let (p, q) = system::biquadratic_from(&self.site, &inputs, self.scales, target, self.mode);
        let raw = eigen::candidates(&p, &q);
        let mut best: Option<([f64; 2], f64)> = None;
        let mut nearest_reason = None;
        let eqs = Equations::from_inputs(&inputs, self.mode);
        for r in &raw {
            let u = match self.mode {
                Mode::SmallAngle => [r.x * sx, r.y * sy],
                Mode::Exact => [(r.x * sx).atan() * 2.0, (r.y * sy).atan() * 2.0],
            };
            // (On a general site the small-angle unknowns are (α, ψ) themselves.)
            // Near θ = 0 the physical root of (15) and its spurious twin are nearly double and
            // may come out as a complex pair with small imaginary parts: every nearly real root
            // is a starting point for Newton on the unsquared equations, which are regular.
            if u[0].im.abs() > 1e-4 || u[1].im.abs() > 1e-4 {
                continue;
            }
            let mut iterations = 0;
            let Ok(u) = correct(&eqs, [u[0].re, u[1].re], &mut iterations) else {
                continue;
            };
            // A root of A + B·Q is never spurious; in exact mode the mirrored frame is.
            let spurious =
                classify::roll_is_unknown(&self.site, self.mode) && classify::exact_mirrored(u[1]);
            let dist = (u[0] - self.current.u[0])
                .abs()
                .max((u[1] - self.current.u[1]).abs());
            let verdict = if spurious {
                Err(Inadmissible::Spurious)
            } else {
                classify::pose(&self.site, target, self.mode, u)
                    .ok_or(Inadmissible::NoRealFrame)
                    .and_then(|pose| {
                        classify::check_pose_within(&self.site, &self.trig, &pose, self.region_tol)
                    })
            };
            match verdict {
                Ok(()) if best.is_none_or(|b| dist < b.1) => best = Some((u, dist)),
                Ok(()) => {}
                Err(why) if !spurious && nearest_reason.is_none_or(|(d, _)| dist < d) => {
                    nearest_reason = Some((dist, why))
                }
                Err(_) => {}
            }
        }
        match best {
            Some((u, _)) => {
                self.current = BranchPoint { d: target, u };
                Ok(self.current)
            }
            None => Err(match nearest_reason {
                Some((_, why)) => fail(why),
                None => TrackError::BranchEnded {
                    x: target.x,
                    z: target.z,
                    theta_deg: target.theta.to_degrees(),
                    diagnosis: "no real root is admissible".into(),
                },
            }),
        }
    }
}
