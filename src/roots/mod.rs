//! All roots of the pose system, which of them is physical, and how to follow it.
//!
//! * [`solve_all`]: every root of the chosen mode's polynomial system by eigenvalues
//!   ([`eigen`]): small-angle (15) has bidegree (2, 2) in (α, β), so at most 8 finite roots of
//!   the 16 that Bézout counts in the projective plane (the rest lie at infinity); the exact form
//!   has bidegree (2, 2) in (tan α/2, tan ψ/2), at most 8 in P¹ × P¹. Each root is classified
//!   ([`classify`]): real or complex, spurious, admissible.
//! * [`solve_all_batch`]: the same at many displacements, each pose's eigenvalues continued
//!   from the pose before and certified, else found by QR ([`batch`]).
//! * [`select`]: the physical pose — the root reached by continuation from the start of sliding
//!   along the straight segment to (X, Z, θ) ([`Tracker`]).
//!
//! ```
//! use slideroute::poses::{Tracker, solve_all};
//! use slideroute::{Displacement, Mode, Scene};
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

pub mod batch;
pub mod classify;
pub mod eigen;
pub mod follower;
pub mod system;
pub mod tracker;

pub use batch::BatchSolver;
pub use classify::Inadmissible;
pub use follower::EigenFollower;
pub use tracker::{BranchPoint, TrackError, TrackStats, Tracker};

use crate::coeffs::{CoeffInputs, Inputs, SmallAngleUnsquared};
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
fn merge(raw: &[eigen::RawRoot]) -> Vec<(eigen::RawRoot, usize)> {
    let mut out: Vec<(eigen::RawRoot, usize)> = Vec::new();
    for &r in raw {
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
    let raw = eigen::solve(&p, &q);
    let scales = system::unknown_scales(site, mode);
    Ok(classified(site, d, mode, scales, &raw.roots))
}

/// [`solve_all`] at each of `ds`, in order, each system's eigenvalues continued from the one
/// before by `solver` and certified, else found by QR (`roots/batch.rs`): the roots of one
/// displacement at a time to within their certified disks (10⁻⁶ relative at most; 10⁻⁹ measured
/// on the default scene, where the counts, classification and selection were the same).
pub fn solve_all_batch(
    site: &Site,
    ds: &[Displacement],
    mode: Mode,
    solver: &mut BatchSolver,
) -> Vec<Result<AllRoots, TrackError>> {
    let scales = system::unknown_scales(site, mode);
    let systems: Vec<(eigen::Coeffs, eigen::Coeffs)> = ds
        .iter()
        .map(|&d| match d.is_finite() {
            true => system::biquadratic_from(site, &Inputs::new(site, d), scales, d, mode),
            false => ([[0.0; 3]; 3], [[0.0; 3]; 3]),
        })
        .collect();
    let mut raw = Vec::with_capacity(ds.len());
    solver.solve(&systems, &mut raw);
    ds.iter()
        .zip(&raw)
        .map(|(&d, r)| match d.is_finite() {
            true => Ok(classified(site, d, mode, scales, r.roots())),
            false => Err(TrackError::NonFinite(d)),
        })
        .collect()
}

/// The roots `raw` of the system at `d` (in the unknowns scaled by `scales`), merged,
/// classified and sorted, with the physical one selected.
fn classified(
    site: &Site,
    d: Displacement,
    mode: Mode,
    scales: system::UnknownScales,
    raw: &[eigen::RawRoot],
) -> AllRoots {
    let g = structural_multiplicity(site, d, mode);
    let merged: Vec<(eigen::RawRoot, usize)> =
        merge(raw).into_iter().map(|(r, k)| (r, k * g)).collect();
    let finite: usize = merged.iter().map(|(_, k)| k).sum();
    let classifier = Classifier::new(site, d, mode, scales);
    let mut roots: Vec<Root> = merged
        .into_iter()
        .map(|(r, multiplicity)| classifier.root(&r, multiplicity))
        .collect();
    roots.sort_by(|a, b| {
        (!a.admissible, !a.real, a.alpha.re, a.beta.re)
            .partial_cmp(&(!b.admissible, !b.real, b.alpha.re, b.beta.re))
            .unwrap_or(std::cmp::Ordering::Equal)
    });
    let (selected, selection_error) = match select(site, d, mode) {
        Ok(p) => match select_among(site, d, mode, &p, &mut roots) {
            Ok(k) => (Some(k), None),
            Err(e) => (None, Some(e)),
        },
        Err(e) => (None, Some(e)),
    };
    AllRoots {
        mode,
        displacement: d,
        roots,
        finite_roots: finite,
        roots_at_infinity: bezout_count(mode).saturating_sub(finite),
        selected,
        selection_error,
    }
}

/// What classifying one root of the solved system needs: the site, displacement and mode, and
/// the scales and unsquared relations they give.
struct Classifier<'a> {
    site: &'a Site,
    d: Displacement,
    mode: Mode,
    /// The solver's unknowns are the physical ones divided by these ([`system::unknown_scales`]).
    scales: system::UnknownScales,
    /// The unsquared small-angle relations, on the paper's site only.
    unsquared: Option<SmallAngleUnsquared>,
    /// A site other than the paper's: the unknowns are (α, ψ) in both modes.
    general: bool,
}

impl<'a> Classifier<'a> {
    fn new(site: &'a Site, d: Displacement, mode: Mode, scales: system::UnknownScales) -> Self {
        let unsquared = match (mode, site.as_paper()) {
            (Mode::SmallAngle, Some(p)) => Some(SmallAngleUnsquared::new(&CoeffInputs::new(p, d))),
            _ => None,
        };
        Classifier {
            site,
            d,
            mode,
            scales,
            unsquared,
            general: site.as_paper().is_none(),
        }
    }

    /// (α, β, ψ) of a root in the solver's scaled unknowns; β is NaN where it comes only from
    /// the pose (a general site).
    fn unknowns(&self, r: &eigen::RawRoot) -> (Complex64, Complex64, Option<Complex64>) {
        let (x, y) = (r.x * self.scales.x, r.y * self.scales.y);
        let unknown = Complex64::new(f64::NAN, f64::NAN);
        match self.mode {
            // A general site's small-angle unknowns are (α, ψ); β from the pose.
            Mode::SmallAngle if self.general => (x, unknown, Some(y)),
            Mode::SmallAngle => (x, y, None),
            Mode::Exact => {
                let alpha = x.atan() * 2.0;
                let psi = y.atan() * 2.0;
                let beta = if self.general {
                    unknown
                } else {
                    ((alpha.sin() - alpha.cos() * psi.sin()) / SQRT_2).asin()
                };
                (alpha, beta, Some(psi))
            }
        }
    }

    /// One root classified: real, spurious, admissible, and why not.
    fn root(&self, r: &eigen::RawRoot, multiplicity: usize) -> Root {
        let (alpha, beta, psi) = self.unknowns(r);
        let second = psi.unwrap_or(beta);
        let real = alpha.im.abs() <= 1e-9 && second.im.abs() <= 1e-9;
        let spurious = real
            && match (self.mode, &self.unsquared) {
                (Mode::SmallAngle, Some(u)) => classify::small_angle_spurious(u, alpha.re, beta.re),
                _ => classify::exact_mirrored(second.re),
            };
        let placed = real
            .then(|| classify::pose(self.site, self.d, self.mode, [alpha.re, second.re]))
            .flatten();
        let beta = match (self.general, &placed) {
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
                Some(p) => classify::check_pose(self.site, &p).err(),
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
    }
}

/// The index among `roots` of the branch's pose `p`: the nearest real root within 10⁻⁶ rad.
///
/// The rest pose (X = Z = θ = 0, both inclined contacts on their strikes) is a root the
/// eigenvalue solve of the resultant loses (the system degenerates there): the tracked pose,
/// when it satisfies the unsquared equations to round-off, is then inserted as the selected root
/// itself.
fn select_among(
    site: &Site,
    d: Displacement,
    mode: Mode,
    p: &BranchPoint,
    roots: &mut Vec<Root>,
) -> Result<usize, TrackError> {
    let nearest = roots
        .iter()
        .enumerate()
        .filter(|(_, r)| r.real)
        .map(|(k, r)| {
            let s = r.psi.unwrap_or(r.beta).re;
            (k, (r.alpha.re - p.u[0]).abs().max((s - p.u[1]).abs()))
        })
        .min_by(|a, b| a.1.total_cmp(&b.1));
    if let Some((k, dist)) = nearest
        && dist < 1e-6
    {
        return Ok(k);
    }
    let residual = system::Equations::new(site, d, mode)
        .eval(p.u)
        .map(|e| {
            (0..2)
                .map(|i| e.r[i].abs() / e.scale[i].max(f64::MIN_POSITIVE))
                .fold(0.0, f64::max)
        })
        .filter(|&rel| rel < 1e-10);
    match residual {
        Some(residual) => {
            roots.insert(0, tracked_root(p, mode, residual));
            Ok(0)
        }
        None => Err(TrackError::BranchEnded {
            x: d.x,
            z: d.z,
            theta_deg: d.theta.to_degrees(),
            diagnosis: "the tracked pose matches none of the roots".into(),
        }),
    }
}

/// The tracked pose `p` as a root (admissible, real, single).
fn tracked_root(p: &BranchPoint, mode: Mode, residual: f64) -> Root {
    let psi = (mode == Mode::Exact).then(|| Complex64::new(p.u[1], 0.0));
    let beta = match mode {
        Mode::SmallAngle => p.u[1],
        Mode::Exact => ((p.u[0].sin() - p.u[0].cos() * p.u[1].sin()) / SQRT_2).asin(),
    };
    Root {
        alpha: Complex64::new(p.u[0], 0.0),
        beta: Complex64::new(beta, 0.0),
        psi,
        multiplicity: 1,
        residual,
        real: true,
        spurious: false,
        admissible: true,
        why_not: None,
    }
}

/// The physical pose at `d`: the branch followed from the start of sliding along the straight
/// segment to `d`. u = (α, β) in small-angle mode, (α, ψ) in exact mode.
pub fn select(site: &Site, d: Displacement, mode: Mode) -> Result<BranchPoint, TrackError> {
    let mut t = Tracker::new(site, mode);
    t.advance(d)
}
