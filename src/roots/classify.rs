//! Which roots are physical.
//!
//! * **spurious**: small-angle — introduced by squaring away sin h: the root satisfies
//!   A − B·Q = 0 rather than the unsquared A + B·Q = 0 with 0 ≤ h ≤ 180°. Exact — the mirrored
//!   frame, cos ψ < 0 (sin h < 0), which likewise fails (13), (14) with 0 ≤ h ≤ 180°.
//! * **admissible**: real, not spurious, 0 ≤ α < ξ, 0 ≤ β < ζ, and each contact over its own
//!   plane (vertex 0 over the horizontal part, vertex 1 over plane 1, vertex 2 over plane 2).

use crate::coeffs::{FoundationTrig, SiteTrig, SmallAngleUnsquared};
use crate::geometry::{Displacement, Pose};
use crate::geometry::{PaperSite, Site};
use crate::model::Mode;
use std::fmt;

/// Why a real pose is not admissible.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Inadmissible {
    /// Squaring artefact (small-angle) or mirrored frame (exact).
    Spurious,
    /// The tilts give no real frame.
    NoRealFrame,
    /// α < 0 or α ≥ ξ.
    AlphaOutOfRange,
    /// β < 0 or β ≥ ζ.
    BetaOutOfRange,
    /// Vertex 0 is over an inclined plane.
    Contact0ReachedInclinedPlane,
    /// Vertex 1 is off plane 1 (X1 < L2X).
    Contact1LeftPlane1,
    /// Vertex 2 is off plane 2 (n·P2 < R).
    Contact2LeftPlane2,
    /// On a general site: contact `.0` is under plane `.1` of another contact (it has left the
    /// part of the ground its own plane makes).
    ContactUnderAnotherPlane(usize, usize),
    /// On a ground of faces: contact `.0` is under face `.1` (it reached a crease).
    ContactUnderAnotherFace(usize, usize),
    /// On a surface: contact `.0` is above the ground, over face `.1` (it ran over a ridge).
    ContactOverRidge(usize, usize),
    /// On a surface: contact `.0` is off the surveyed surface.
    ContactOffSurface(usize),
}

impl fmt::Display for Inadmissible {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let text = match *self {
            Inadmissible::ContactUnderAnotherPlane(i, j) => {
                return write!(f, "contact {i} is under contact {j}'s plane");
            }
            Inadmissible::ContactUnderAnotherFace(i, j) => {
                return write!(f, "contact {i} reached face {j} (a crease)");
            }
            Inadmissible::ContactOverRidge(i, j) => {
                return write!(f, "contact {i} ran over a ridge onto face {j}");
            }
            Inadmissible::ContactOffSurface(i) => {
                return write!(f, "contact {i} ran off the surveyed surface");
            }
            Inadmissible::Spurious => "spurious root (wrong sign of sin h: the mirrored frame)",
            Inadmissible::NoRealFrame => "no real frame has these tilts",
            Inadmissible::AlphaOutOfRange => "tilt α outside [0, ξ)",
            Inadmissible::BetaOutOfRange => "tilt β outside [0, ζ)",
            Inadmissible::Contact0ReachedInclinedPlane => "contact 0 reached an inclined plane",
            Inadmissible::Contact1LeftPlane1 => "contact 1 left plane 1",
            Inadmissible::Contact2LeftPlane2 => "contact 2 left plane 2",
        };
        f.write_str(text)
    }
}

/// The one tolerance of the admissibility tests: how far (m, as a fraction of L) a contact may
/// stand beyond its plane's region — past plane 1's strike, short of plane 2's, over an inclined
/// plane for contact 0 — before the pose counts as off it.
///
/// Why this size: a contact that sticks on a strike line (where contacts 1 and 2 start) or rides
/// along one sits on the region's edge, and round-off, the tracker's Newton tolerance (updates
/// below 1e-9 rad, whose error is far smaller except at the double roots of (15) at θ = 0, where
/// convergence is linear) and the integrator put it a hair to either side. 1e-8·L (0.1 µm on a
/// 10 m frame) is well above all of these and far below anything surveyed on a foundation.
///
/// The lower tilt bounds are the same test in another form: with contact 0 on the horizontal
/// plane, sin α = (X1 − L2X)·tan ξ / L and sin β = (n·P2 − R)·tan ζ / (√2 L) (`derivations/01-geometry.md`),
/// so α < 0 exactly when contact 1 is short of plane 1's strike and β < 0 exactly when contact 2
/// is short of plane 2's. They take the tolerance through those relations (and a factor of two,
/// so that the region test, which names the contact, decides).
pub const REGION_TOL: f64 = 1e-8;

/// The placed frame for a point of the chosen mode: u = (α, β) or (α, ψ).
/// On a general site u = (α, ψ) in both modes.
pub fn pose(site: &Site, d: Displacement, mode: Mode, u: [f64; 2]) -> Option<Pose> {
    match (mode, site.as_paper()) {
        (Mode::SmallAngle, Some(p)) => Pose::from_tilts(p, d, u[0], u[1]).ok(),
        _ => Pose::from_tilt_roll(site, d, u[0], u[1]).ok(),
    }
}

impl super::AllRoots {
    /// The pose of the selected root (the physical one, by continuation), if a root is selected
    /// and its frame is real.
    pub fn selected_pose(&self, site: &Site) -> Option<Pose> {
        let r = &self.roots[self.selected?];
        pose(
            site,
            self.displacement,
            self.mode,
            [r.alpha.re, r.psi.unwrap_or(r.beta).re],
        )
    }
}

/// Checks tilt ranges and contact regions of a real, non-spurious pose, with [`REGION_TOL`].
pub fn check_pose(site: &Site, p: &Pose) -> Result<(), Inadmissible> {
    check_pose_within(site, &SiteTrig::new(site), p, REGION_TOL)
}

/// [`check_pose`] with the regions' tolerance `region_tol` (a fraction of L; infinite: the
/// regions are not checked, only the tilts' upper bounds, as for the intermediate stages of an
/// integrator, which are no states of the route: each contact's equations hold on its whole
/// plane, and only the states the route accepts must lie in the regions).
#[inline]
pub fn check_pose_within(
    site: &Site,
    trig: &SiteTrig,
    p: &Pose,
    region_tol: f64,
) -> Result<(), Inadmissible> {
    match (site.as_paper(), trig) {
        (Some(paper), SiteTrig::Paper(trig)) => check_paper_pose(paper, trig, p, region_tol),
        _ => check_general_pose(site, p, region_tol),
    }
}

/// On a general site without a ground, the paper's regions on any three planes: contact 0
/// where its plane is above both others, contacts 1 and 2 where theirs is above contact 0's (each
/// ignores the other's plane, as the paper's contact 2 ignores plane 1). On a ground of faces,
/// each contact where no face stands above its own. Both within `region_tol`·L.
fn check_general_pose(site: &Site, p: &Pose, region_tol: f64) -> Result<(), Inadmissible> {
    if !p.vertices.iter().all(|v| v.iter().all(|c| c.is_finite())) {
        return Err(Inadmissible::NoRealFrame);
    }
    let tol = region_tol * site.l();
    let planes = site.planes();
    for (i, v) in p.vertices.iter().enumerate() {
        let own = planes[i].height(v.x, v.z);
        match site.ground() {
            Some((ground, _)) => match ground.top(v.x, v.z) {
                None => return Err(Inadmissible::ContactOffSurface(i)),
                Some((top, h)) if h > own + tol => {
                    return Err(Inadmissible::ContactUnderAnotherFace(i, top));
                }
                // Only a surface falls away below a face's plane.
                Some((top, h)) if h < own - tol => {
                    return Err(Inadmissible::ContactOverRidge(i, top));
                }
                Some(_) => {}
            },
            None => {
                let others: &[usize] = if i == 0 { &[1, 2] } else { &[0] };
                if let Some(&j) = others
                    .iter()
                    .find(|&&j| planes[j].height(v.x, v.z) > own + tol)
                {
                    return Err(Inadmissible::ContactUnderAnotherPlane(i, j));
                }
            }
        }
    }
    Ok(())
}

/// The paper's admissibility: tilt ranges and the three regions.
fn check_paper_pose(
    site: &PaperSite,
    trig: &FoundationTrig,
    p: &Pose,
    region_tol: f64,
) -> Result<(), Inadmissible> {
    let g = site.foundation;
    let l = site.frame.l();
    let tol = region_tol * l;
    // sin α and α agree to round-off at these angles (about 1e-8 rad): no asin.
    let (tan_xi, tan_zeta) = trig.tan_dips();
    let alpha_min = -2.0 * region_tol * tan_xi;
    let beta_min = -2.0 * region_tol * tan_zeta / std::f64::consts::SQRT_2;
    // The tilts' upper bounds first: a tilt reaching its dip is its own end.
    if p.alpha.is_nan() || p.alpha >= g.xi {
        return Err(Inadmissible::AlphaOutOfRange);
    }
    if p.beta.is_nan() || p.beta >= g.zeta {
        return Err(Inadmissible::BetaOutOfRange);
    }
    // `paper_planes::r` and `along_dip_2` with κ's sine and cosine computed once (the same
    // values: a check is made at every pose the route takes).
    let (sk, ck) = trig.kappa_sin_cos();
    let along_dip_2 = |x: f64, z: f64| x * ck - z * sk;
    let (l2x, r2) = (site.frame.l2x, site.frame.l2x * ck + site.frame.l2z * sk);
    let [p0, p1, p2] = p.vertices;
    if p0.x > l2x + tol || along_dip_2(p0.x, p0.z) > r2 + tol {
        return Err(Inadmissible::Contact0ReachedInclinedPlane);
    }
    if p1.x < l2x - tol {
        return Err(Inadmissible::Contact1LeftPlane1);
    }
    if along_dip_2(p2.x, p2.z) < r2 - tol {
        return Err(Inadmissible::Contact2LeftPlane2);
    }
    if p.alpha < alpha_min {
        return Err(Inadmissible::AlphaOutOfRange);
    }
    if p.beta < beta_min {
        return Err(Inadmissible::BetaOutOfRange);
    }
    Ok(())
}

/// Whether a real root of (15) is spurious: it solves A − BQ = 0 but not A + BQ = 0.
pub fn small_angle_spurious(u: &SmallAngleUnsquared, alpha: f64, beta: f64) -> bool {
    match u.eval(alpha, beta) {
        None => true,
        Some(eqs) => eqs
            .iter()
            .any(|e| e.value.abs() > e.mirror.abs() && e.value.abs() > 1e-8 * e.scale),
    }
}

/// Whether the second unknown is the roll ψ (the exact form, and every mode on a general
/// site), so that a root with cos ψ < 0 is the mirrored frame.
pub fn roll_is_unknown(site: &Site, mode: Mode) -> bool {
    mode == Mode::Exact || site.as_paper().is_none()
}

/// Whether an exact-mode root is the mirrored frame (cos ψ < 0).
pub fn exact_mirrored(psi: f64) -> bool {
    psi.cos() < 0.0
}
