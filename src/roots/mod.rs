//! All roots of the pose system, which of them is physical, and how to follow it.
//!
//! * [`solve_all`]: every root of the chosen mode's polynomial system by eigenvalues
//!   ([`eigen`]): small-angle (15) has bidegree (2, 2) in (α, β), so at most 8 finite roots of
//!   the 16 that Bézout counts in the projective plane (the rest lie at infinity); the exact form
//!   has bidegree (2, 2) in (tan α/2, tan ψ/2), at most 8 in P¹ × P¹. Each root is classified
//!   ([`classify`]): real or complex, spurious, admissible.
//! * [`select`]: the physical pose — the root reached by continuation from the start of sliding
//!   along the straight segment to (X, Z, θ) ([`Tracker`]).
//!
//! ```
//! use slideroute::{Displacement, Mode, Scene, Tracker, solve_all};
//! let site = Scene::default_scene().site().clone();
//! let d = Displacement::new(0.5, 0.1, 2f64.to_radians());
//! let all = solve_all(&site, d, Mode::Exact).unwrap();
//! let chosen = all.selected.map(|k| &all.roots[k]).unwrap();
//! assert!(chosen.admissible && chosen.alpha.im.abs() < 1e-12);
//!
//! // Following the branch over increments:
//! let mut tracker = Tracker::new(&site, Mode::Exact);
//! for k in 1..=10 {
//!     tracker.advance(d.scaled(k as f64 / 10.0)).unwrap();
//! }
//! assert!((tracker.point().u[0] - chosen.alpha.re).abs() < 1e-12);
//! ```

pub mod classify;
pub mod eigen;
pub mod follower;
pub mod system;
pub mod tracker;

pub use classify::Inadmissible;
pub use follower::EigenFollower;
pub use tracker::{BranchPoint, TrackError, TrackStats, Tracker};

use crate::coeffs::{CoeffInputs, SmallAngleUnsquared};
use crate::geometry::Displacement;
use crate::geometry::Site;
use crate::model::Mode;
use num_complex::Complex64;
use std::f64::consts::SQRT_2;

/// One root, in the physical unknowns.
#[derive(Debug, Clone, PartialEq)]
pub struct Root {
    /// α (rad).
    pub alpha: Complex64,
    /// β (rad).
    pub beta: Complex64,
    /// Roll about side 01 (exact mode only).
    pub psi: Option<Complex64>,
    /// How many eigenvalues coincide here (2 at the double roots of (15) at θ = 0).
    pub multiplicity: usize,
    /// Relative residual of the polynomial system after refinement.
    pub residual: f64,
    /// Whether it is real (to round-off).
    pub real: bool,
    /// Whether it is a root of the squared system (15) that the unsquared relations refuse.
    pub spurious: bool,
    /// Whether it is a pose the block can take: real, not spurious, its tilts in range and its
    /// contacts on their planes' regions.
    pub admissible: bool,
    /// For a real root that is not admissible: why.
    pub why_not: Option<Inadmissible>,
}

/// Every root of one mode's system at one displacement.
#[derive(Debug, Clone, PartialEq)]
pub struct AllRoots {
    /// The pose system solved.
    pub mode: Mode,
    /// The displacement it was solved at.
    pub displacement: Displacement,
    /// Finite roots; coinciding ones merged (see [`Root::multiplicity`]).
    pub roots: Vec<Root>,
    /// Number of finite roots counted with multiplicity.
    pub finite_roots: usize,
    /// The rest of the Bézout count: 16 for small-angle (total degree 4 × 4, the paper's count),
    /// 8 for exact (bidegree (2, 2) in P¹ × P¹).
    pub roots_at_infinity: usize,
    /// Index into `roots` of the physical pose (by continuation), if the branch reaches here.
    pub selected: Option<usize>,
    /// Why no root is selected, if none is.
    pub selection_error: Option<TrackError>,
}

/// The Bézout count each mode reports against.
pub fn bezout_count(mode: Mode) -> usize {
    match mode {
        Mode::SmallAngle => 16,
        Mode::Exact => 8,
    }
}

/// Roots closer than this (relative, in the solver's scaled unknowns) are one root.
const MERGE: f64 = 1e-6;

/// How many roots of (15) each root of the solved system stands for: 2 for each equation that
/// is a perfect square at `d` (solved as its root A instead, see [`system::perfect_squares`]).
fn structural_multiplicity(site: &Site, d: Displacement, mode: Mode) -> usize {
    let [a, b] = system::perfect_squares(site, d, mode);
    1 << (usize::from(a) + usize::from(b))
}

/// Merges roots closer than [`MERGE`]: returns (representative, count).
fn merge(raw: Vec<eigen::RawRoot>) -> Vec<(eigen::RawRoot, usize)> {
    let mut out: Vec<(eigen::RawRoot, usize)> = Vec::new();
    for r in raw {
        let size = 1.0 + r.x.norm().max(r.y.norm());
        match out
            .iter_mut()
            .find(|(m, _)| (m.x - r.x).norm().max((m.y - r.y).norm()) < MERGE * size)
        {
            Some((_, k)) => *k += 1,
            None => out.push((r, 1)),
        }
    }
    out
}

/// Every root of the chosen mode's system at `d`, classified, with the physical one selected.
pub fn solve_all(site: &Site, d: Displacement, mode: Mode) -> Result<AllRoots, TrackError> {
    if !d.is_finite() {
        return Err(TrackError::NonFinite(d));
    }
    let (p, q) = system::biquadratic(site, d, mode);
    let g = structural_multiplicity(site, d, mode);
    let raw = eigen::solve(&p, &q);
    let merged: Vec<(eigen::RawRoot, usize)> = merge(raw.roots)
        .into_iter()
        .map(|(r, k)| (r, k * g))
        .collect();
    let finite: usize = merged.iter().map(|(_, k)| k).sum();
    let (sx, sy) = system::unknown_scales(site, mode);
    let unsquared = match (mode, site.as_paper()) {
        (Mode::SmallAngle, Some(p)) => Some(SmallAngleUnsquared::new(&CoeffInputs::new(p, d))),
        _ => None,
    };
    let general = site.as_paper().is_none();
    let mut roots: Vec<Root> = merged
        .into_iter()
        .map(|(r, multiplicity)| {
            let (alpha, beta, psi) = match mode {
                // A general site's small-angle unknowns are (α, ψ); β from the pose below.
                Mode::SmallAngle if general => {
                    (r.x * sx, Complex64::new(f64::NAN, f64::NAN), Some(r.y * sy))
                }
                Mode::SmallAngle => (r.x * sx, r.y * sy, None),
                Mode::Exact if general => {
                    let alpha = (r.x * sx).atan() * 2.0;
                    let psi = (r.y * sy).atan() * 2.0;
                    (alpha, Complex64::new(f64::NAN, f64::NAN), Some(psi))
                }
                Mode::Exact => {
                    let alpha = (r.x * sx).atan() * 2.0;
                    let psi = (r.y * sy).atan() * 2.0;
                    let beta = ((alpha.sin() - alpha.cos() * psi.sin()) / SQRT_2).asin();
                    (alpha, beta, Some(psi))
                }
            };
            let second = psi.unwrap_or(beta);
            let real = alpha.im.abs() <= 1e-9 && second.im.abs() <= 1e-9;
            let spurious = real
                && match (mode, &unsquared) {
                    (Mode::SmallAngle, Some(u)) => {
                        classify::small_angle_spurious(u, alpha.re, beta.re)
                    }
                    _ => classify::exact_mirrored(second.re),
                };
            let placed = real
                .then(|| classify::pose(site, d, mode, [alpha.re, second.re]))
                .flatten();
            let beta = match (general, &placed) {
                (true, Some(p)) => Complex64::new(p.beta, 0.0),
                _ => beta,
            };
            let why_not = if !real {
                None
            } else if spurious {
                Some(Inadmissible::Spurious)
            } else {
                match placed {
                    None => Some(Inadmissible::NoRealFrame),
                    Some(p) => classify::check_pose(site, &p).err(),
                }
            };
            Root {
                alpha,
                beta,
                psi,
                multiplicity,
                residual: r.residual,
                real,
                spurious,
                admissible: real && why_not.is_none(),
                why_not,
            }
        })
        .collect();
    roots.sort_by(|a, b| {
        (!a.admissible, !a.real, a.alpha.re, a.beta.re)
            .partial_cmp(&(!b.admissible, !b.real, b.alpha.re, b.beta.re))
            .unwrap_or(std::cmp::Ordering::Equal)
    });

    let (selected, selection_error) = match select(site, d, mode) {
        Ok(p) => {
            let k = roots
                .iter()
                .enumerate()
                .filter(|(_, r)| r.real)
                .map(|(k, r)| {
                    let s = r.psi.unwrap_or(r.beta).re;
                    (k, (r.alpha.re - p.u[0]).abs().max((s - p.u[1]).abs()))
                })
                .min_by(|a, b| a.1.total_cmp(&b.1));
            // The rest pose (X = Z = θ = 0, both inclined contacts on their strikes) is a
            // root where the eigenvalue solve of the resultant loses it (the system degenerates
            // there; issue #12): the tracked pose, when it satisfies the unsquared equations to
            // round-off, is then the selected root itself.
            let tracked = || {
                let e = system::Equations::new(site, d, mode).eval(p.u)?;
                let rel = (0..2)
                    .map(|i| e.r[i].abs() / e.scale[i].max(f64::MIN_POSITIVE))
                    .fold(0.0, f64::max);
                (rel < 1e-10).then_some(rel)
            };
            match k {
                Some((k, dist)) if dist < 1e-6 => (Some(k), None),
                _ if tracked().is_some() => {
                    let psi = (mode == Mode::Exact).then(|| Complex64::new(p.u[1], 0.0));
                    let beta = match mode {
                        Mode::SmallAngle => p.u[1],
                        Mode::Exact => {
                            ((p.u[0].sin() - p.u[0].cos() * p.u[1].sin()) / SQRT_2).asin()
                        }
                    };
                    roots.insert(
                        0,
                        Root {
                            alpha: Complex64::new(p.u[0], 0.0),
                            beta: Complex64::new(beta, 0.0),
                            psi,
                            multiplicity: 1,
                            residual: tracked().unwrap_or(0.0),
                            real: true,
                            spurious: false,
                            admissible: true,
                            why_not: None,
                        },
                    );
                    (Some(0), None)
                }
                _ => (
                    None,
                    Some(TrackError::BranchEnded {
                        x: d.x,
                        z: d.z,
                        theta_deg: d.theta.to_degrees(),
                        diagnosis: "the tracked pose matches none of the roots".into(),
                    }),
                ),
            }
        }
        Err(e) => (None, Some(e)),
    };
    Ok(AllRoots {
        mode,
        displacement: d,
        roots,
        finite_roots: finite,
        roots_at_infinity: bezout_count(mode).saturating_sub(finite),
        selected,
        selection_error,
    })
}

/// The physical pose at `d`: the branch followed from the start of sliding along the straight
/// segment to `d`. u = (α, β) in small-angle mode, (α, ψ) in exact mode.
pub fn select(site: &Site, d: Displacement, mode: Mode) -> Result<BranchPoint, TrackError> {
    let mut t = Tracker::new(site, mode);
    t.advance(d)
}
