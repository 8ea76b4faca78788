//! Branch continuation: follow the physical pose from increment to increment.
//!
//! The tracker works on the *unsquared* equations of the chosen mode (small-angle: A + B·Q with
//! sin h ≥ 0 in (α, β); exact: (13), (14) in (α, ψ)). On these the start of sliding is a
//! regular point, shown by analysis in `derivations/06-roots-and-tracking.md`: at X = Z = θ = 0
//! the Jacobian of the exact system at α = ψ = 0 is [[L cot ξ, 0], [−L cot ζ, L cot ζ]], which is
//! invertible, and the small-angle one is [[L cot ξ, 0], [0, −√2 L cot ζ]]. The double roots of
//! the *squared* system (15) at θ = 0, where the spurious branch meets the physical one, are not
//! roots of multiplicity two here, so Newton's method starts there without help.
//!
//! Each step: a secant predictor (after the first step), a Newton corrector with Deuflhard's
//! contraction test (each correction must shrink by a factor ≤ 1/2, the second by ≤ 1/4 of the
//! first), and a jump guard (the correction must be small against the step). A step that fails
//! is halved; a branch that cannot be followed below a minimal step ends with a diagnosis.

use super::classify::{
    Inadmissible, REGION_TOL, check_pose_within, exact_mirrored, pose, roll_is_unknown,
};
use super::system::Equations;
use crate::coeffs::{Inputs, SiteTrig};
use crate::geometry::Site;
use crate::geometry::{Displacement, Pose};
use crate::model::Mode;
use crate::numeric::fixed;
use std::borrow::Cow;

/// A point on the followed branch: displacement and u = (α, β) (small-angle) or (α, ψ) (exact).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BranchPoint {
    /// The displacement.
    pub d: Displacement,
    /// The unknowns there (rad).
    pub u: [f64; 2],
}

/// Why the branch cannot be followed further.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum TrackError {
    /// A displacement that is not finite.
    #[error("non-finite displacement {0:?}")]
    NonFinite(Displacement),
    /// The corrector failed at every step size down to the minimum: a turning point, roots
    /// merging, or the equations losing a real solution.
    #[error(
        "the branch ends near X = {} m, Z = {} m, θ = {}°: {diagnosis}",
        fixed(*x, 6), fixed(*z, 6), fixed(*theta_deg, 6)
    )]
    BranchEnded {
        /// Where: X (m).
        x: f64,
        /// Z (m).
        z: f64,
        /// θ (degrees).
        theta_deg: f64,
        /// What the equations show there, for people.
        diagnosis: String,
    },
    /// The branch continues but the pose is no longer admissible.
    #[error(
        "at X = {} m, Z = {} m, θ = {}°: {reason}",
        fixed(*x, 6), fixed(*z, 6), fixed(*theta_deg, 6)
    )]
    Inadmissible {
        /// Where: X (m).
        x: f64,
        /// Z (m).
        z: f64,
        /// θ (degrees).
        theta_deg: f64,
        /// Why the pose is not admissible.
        reason: Inadmissible,
    },
}

/// Counters for reports and benchmarks.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, serde::Serialize)]
pub struct TrackStats {
    /// Accepted steps.
    pub steps: usize,
    /// Steps refused and retried shorter.
    pub rejected: usize,
    /// Newton iterations of the corrector, in all.
    pub newton_iterations: usize,
}

/// Follows the physical branch of the chosen mode.
#[derive(Debug, Clone)]
pub struct Tracker<'s> {
    /// The site followed: the scene's, or one the route changed to (a contact onto another
    /// face, [`Tracker::on_site`]).
    site: Cow<'s, Site>,
    /// The foundation's trigonometric functions, computed once.
    trig: SiteTrig,
    mode: Mode,
    current: BranchPoint,
    /// The placed frame at `current`, built by the admissibility check.
    current_pose: Option<Pose>,
    previous: Option<BranchPoint>,
    /// Fraction of the next segment to try first (grows after successes).
    h: f64,
    /// The regions' tolerance of the admissibility check (a fraction of L; see
    /// [`super::classify::check_pose_within`]).
    region_tol: f64,
    /// What following the branch has cost so far.
    pub stats: TrackStats,
}

const MAX_ITERATIONS: usize = 8;
const MIN_FRACTION: f64 = 1e-10;

/// Why a corrector attempt was refused.
#[derive(Debug, Clone, Copy)]
pub(crate) enum Refusal {
    NoRealQ,
    Singular,
    NotContracting,
    NoConvergence,
    Jump,
}

impl Refusal {
    fn diagnosis(self) -> &'static str {
        match self {
            Refusal::NoRealQ => "the small-angle relations have no real sin h here",
            Refusal::Singular => "the Jacobian is singular (turning point or merging roots)",
            Refusal::NotContracting => "Newton's method does not contract (roots close together)",
            Refusal::NoConvergence => "Newton's method does not converge",
            Refusal::Jump => "the corrector would jump to another branch",
        }
    }
}

fn norm(v: [f64; 2]) -> f64 {
    v[0].abs().max(v[1].abs())
}

/// One Newton update of the unsquared equations at `u`.
#[inline]
fn update(eqs: &Equations, u: [f64; 2], iterations: &mut usize) -> Result<[f64; 2], Refusal> {
    let e = eqs.eval(u).ok_or(Refusal::NoRealQ)?;
    *iterations += 1;
    let [[a, b], [c, d]] = e.j;
    let det = a * d - b * c;
    let jmax = a.abs().max(b.abs()).max(c.abs()).max(d.abs());
    if det.is_nan() || det.abs() <= 1e-13 * jmax * jmax {
        return Err(Refusal::Singular);
    }
    let du = [
        -(d * e.r[0] - b * e.r[1]) / det,
        -(a * e.r[1] - c * e.r[0]) / det,
    ];
    if !norm(du).is_finite() {
        return Err(Refusal::NoConvergence);
    }
    Ok(du)
}

/// Newton on the unsquared equations from `u0`, with the contraction test.
#[inline]
pub(crate) fn correct(
    eqs: &Equations,
    u0: [f64; 2],
    iterations: &mut usize,
) -> Result<[f64; 2], Refusal> {
    let mut u = u0;
    let mut last = f64::INFINITY;
    for k in 0..MAX_ITERATIONS {
        let du = update(eqs, u, iterations)?;
        let n = norm(du);
        let limit = if k == 1 { 0.25 } else { 0.5 };
        if k >= 1 && n > limit * last && n > 1e-13 {
            return Err(Refusal::NotContracting);
        }
        u = [u[0] + du[0], u[1] + du[1]];
        // Converged: the update is at round-off, or below 1e-9 rad — Newton's error after it is
        // of order its square (the Jacobian is checked well away from singular above), so a
        // further iteration would only confirm it.
        if n <= 1e-9 {
            return Ok(u);
        }
        last = n;
    }
    Err(Refusal::NoConvergence)
}

fn distance(site: &Site, a: Displacement, b: Displacement) -> f64 {
    let l = site.l();
    (a.x - b.x)
        .abs()
        .max((a.z - b.z).abs())
        .max(l * (a.theta - b.theta).abs())
}

fn lerp(a: Displacement, b: Displacement, s: f64) -> Displacement {
    Displacement::new(
        a.x + s * (b.x - a.x),
        a.z + s * (b.z - a.z),
        a.theta + s * (b.theta - a.theta),
    )
}

impl<'s> Tracker<'s> {
    /// At the start of sliding: X = Z = θ = 0, the flat frame (α = β = ψ = 0).
    pub fn new(site: &'s Site, mode: Mode) -> Self {
        Tracker {
            site: Cow::Borrowed(site),
            trig: SiteTrig::new(site),
            mode,
            current: BranchPoint {
                d: Displacement::default(),
                u: [0.0, 0.0],
            },
            current_pose: pose(site, Displacement::default(), mode, [0.0, 0.0]),
            previous: None,
            h: 1.0,
            region_tol: REGION_TOL,
            stats: TrackStats::default(),
        }
    }

    /// The pose system followed.
    pub fn mode(&self) -> Mode {
        self.mode
    }

    /// A copy that does not check the contacts' regions (only the tilts' upper bounds), for the
    /// intermediate stages of an integrator.
    pub fn without_regions(&self) -> Self {
        Tracker {
            region_tol: f64::INFINITY,
            ..self.clone()
        }
    }

    /// The same point of the branch followed on another site: where a contact goes onto
    /// another face it is on both there, so the current (α, ψ) is a root of the new site's
    /// system too (`derivations/10-faces.md` §5). The predictor starts afresh.
    pub fn on_site(&self, site: Site) -> Tracker<'s> {
        let trig = SiteTrig::new(&site);
        let current_pose = pose(&site, self.current.d, self.mode, self.current.u);
        Tracker {
            site: Cow::Owned(site),
            trig,
            current_pose,
            previous: None,
            h: 1.0,
            ..self.clone()
        }
    }

    /// The site followed.
    pub fn site(&self) -> &Site {
        &self.site
    }

    /// The current point of the branch.
    pub fn point(&self) -> BranchPoint {
        self.current
    }

    /// The placed frame at the current point.
    pub fn pose(&self) -> Option<Pose> {
        self.current_pose
    }

    /// Follows the branch along the straight segment from the current displacement to
    /// `target`, in as many substeps as needed, and checks the pose there is admissible.
    pub fn advance(&mut self, target: Displacement) -> Result<BranchPoint, TrackError> {
        if !target.is_finite() {
            return Err(TrackError::NonFinite(target));
        }
        let from = self.current.d;
        if target == from {
            // Already there: no step (a zero-length one would spoil the secant predictor of
            // the next: every step after it was refused as a jump and halved some twenty
            // times), but the admissibility check all the same (the start may be inadmissible).
            self.check()?;
            return Ok(self.current);
        }
        let mut s = 0.0;
        let mut h = self.h;
        while s < 1.0 {
            let s_try = (s + h).min(1.0);
            let d = lerp(from, target, s_try);
            let u_pred = self.predict(d);
            let eqs =
                Equations::from_inputs(&Inputs::with_trig(&self.site, &self.trig, d), self.mode);
            let here = self.current.u;
            // Jump guard: with a first-order predictor the correction is second order in the
            // step.
            let guarded = |u: [f64; 2], pred: [f64; 2]| {
                let step = norm([u[0] - here[0], u[1] - here[1]]);
                let corr = norm([u[0] - pred[0], u[1] - pred[1]]);
                if corr > 0.5 * step + 1e-12 {
                    Err(Refusal::Jump)
                } else {
                    Ok(u)
                }
            };
            let iterations = &mut self.stats.newton_iterations;
            let mut result = correct(&eqs, u_pred, iterations).and_then(|u| match self.previous {
                Some(_) => guarded(u, u_pred),
                None => Ok(u),
            });
            if matches!(result, Err(Refusal::Jump)) {
                // The secant extrapolates along the last segment only: where the new one turns
                // away from it (a held contact projected back, an integrator's stages, a pivot),
                // its error is of the first order and halving the step does not help. Newton's
                // first update from the current point is a first-order predictor along any
                // segment (the tangent's, to first order); against it the correction is of the
                // second order again.
                result = update(&eqs, here, iterations).and_then(|du| {
                    let tangent = [here[0] + du[0], here[1] + du[1]];
                    correct(&eqs, tangent, iterations).and_then(|u| guarded(u, tangent))
                });
            }
            match result {
                Ok(u) => {
                    self.previous = Some(self.current);
                    self.current = BranchPoint { d, u };
                    self.stats.steps += 1;
                    s = s_try;
                    h = (2.0 * h).min(1.0);
                }
                Err(why) => {
                    self.stats.rejected += 1;
                    h *= 0.5;
                    if h < MIN_FRACTION {
                        return Err(TrackError::BranchEnded {
                            x: d.x,
                            z: d.z,
                            theta_deg: d.theta.to_degrees(),
                            diagnosis: why.diagnosis().to_string(),
                        });
                    }
                }
            }
        }
        self.h = h;
        self.current_pose = pose(&self.site, self.current.d, self.mode, self.current.u);
        self.check()?;
        Ok(self.current)
    }

    fn predict(&self, d: Displacement) -> [f64; 2] {
        let cur = self.current;
        match self.previous {
            Some(prev) => {
                let last = distance(&self.site, cur.d, prev.d);
                if last <= 0.0 {
                    return cur.u;
                }
                let f = (distance(&self.site, d, cur.d) / last).min(4.0);
                [
                    cur.u[0] + f * (cur.u[0] - prev.u[0]),
                    cur.u[1] + f * (cur.u[1] - prev.u[1]),
                ]
            }
            None => cur.u,
        }
    }

    /// Condition number (2-norm) of the Jacobian of the tracked equations at the current point:
    /// large near a turning point or where roots merge.
    pub fn jacobian_condition(&self) -> Option<f64> {
        let e = Equations::new(&self.site, self.current.d, self.mode).eval(self.current.u)?;
        let [[a, b], [c, d]] = e.j;
        // Singular values of a 2×2 matrix.
        let s = a * a + b * b + c * c + d * d;
        let det = (a * d - b * c).abs();
        let disc = (s * s - 4.0 * det * det).max(0.0).sqrt();
        let (smax, smin) = (
            ((s + disc) / 2.0).sqrt(),
            ((s - disc) / 2.0).max(0.0).sqrt(),
        );
        Some(if smin > 0.0 {
            smax / smin
        } else {
            f64::INFINITY
        })
    }

    fn check(&self) -> Result<(), TrackError> {
        let d = self.current.d;
        let fail = |reason| TrackError::Inadmissible {
            x: d.x,
            z: d.z,
            theta_deg: d.theta.to_degrees(),
            reason,
        };
        if roll_is_unknown(&self.site, self.mode) && exact_mirrored(self.current.u[1]) {
            return Err(fail(Inadmissible::Spurious));
        }
        let p = self
            .current_pose
            .ok_or_else(|| fail(Inadmissible::NoRealFrame))?;
        check_pose_within(&self.site, &self.trig, &p, self.region_tol).map_err(fail)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::Scene;

    #[test]
    fn advancing_to_where_it_is_keeps_the_predictor_and_takes_no_step() {
        // A route evaluates its start, where the tracker already is; that must not leave a
        // zero-length secant behind, after which every step was refused as a jump and halved
        // about twenty times.
        let scene = Scene::default_scene();
        let mut t = Tracker::new(&scene.site, Mode::Exact);
        t.advance(Displacement::default()).unwrap();
        assert_eq!(t.stats.steps, 0);
        for k in 1..=20 {
            let f = k as f64;
            t.advance(Displacement::new(0.02 * f, 0.001 * f, -0.002 * f))
                .unwrap();
        }
        assert_eq!(t.stats.rejected, 0, "{:?}", t.stats);
        assert_eq!(t.stats.steps, 20, "{:?}", t.stats);
    }

    #[test]
    fn a_path_that_turns_or_goes_back_is_followed_at_once_on_the_same_branch() {
        // A held contact projected back, an integrator's stages, a pivot: the displacement
        // turns away from the last segment, where the secant predicts wrong to first order and
        // every step was refused as a jump and halved some twenty times. Each is taken at once
        // (Newton's first update from the current point as the predictor), on the branch a
        // tracker going straight there from the start finds.
        let scene = Scene::default_scene();
        let mut t = Tracker::new(&scene.site, Mode::Exact);
        let path = [
            (0.02, 0.0, 0.0),
            (0.04, 0.0, 0.0),
            (0.04, 0.0, 0.002),
            (0.04, 0.003, 0.002),
            (0.03, 0.003, 0.002),
            (0.035, 0.001, 0.001),
            (0.05, 0.001, 0.001),
        ];
        for &(x, z, theta) in &path {
            let d = Displacement::new(x, z, theta);
            let got = t.advance(d).unwrap().u;
            let want = Tracker::new(&scene.site, Mode::Exact).advance(d).unwrap().u;
            let off = norm([got[0] - want[0], got[1] - want[1]]);
            assert!(off < 1e-12, "{d:?}: {got:?} against {want:?}");
        }
        assert_eq!(t.stats.rejected, 0, "{:?}", t.stats);
        assert_eq!(t.stats.steps, path.len(), "{:?}", t.stats);
    }

    #[test]
    fn jacobian_condition_is_the_ratio_of_singular_values() {
        let scene = Scene::default_scene();
        let mut t = Tracker::new(&scene.site, Mode::Exact);
        t.advance(Displacement::new(0.8, 0.1, 0.03)).unwrap();
        let e = Equations::new(&scene.site, t.point().d, Mode::Exact)
            .eval(t.point().u)
            .unwrap();
        let j = nalgebra::Matrix2::new(e.j[0][0], e.j[0][1], e.j[1][0], e.j[1][1]);
        let sv = j.singular_values();
        let want = sv.max() / sv.min();
        let got = t.jacobian_condition().unwrap();
        assert!((got - want).abs() < 1e-10 * want, "{got} vs {want}");
    }
}
