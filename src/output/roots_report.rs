//! The `roots` report: every root at one displacement, and the selected one.

use crate::Displacement;
use crate::roots::{AllRoots, Inadmissible, Root, classify};
use crate::{model::Mode, scene::Scene};
use serde::Serialize;
use std::fmt;

/// The physical pose chosen by continuation.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub(crate) struct SelectedPose {
    pub alpha_deg: f64,
    pub beta_deg: f64,
    pub gamma_deg: f64,
    /// Roll about x' (side 01 of the paper's frame); absent for the paper's small-angle system.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub psi_deg: Option<f64>,
    /// CM height (eq. 21 on the paper's site), m.
    pub cm_y_m: f64,
}

/// One root, angles in degrees as [re, im].
#[derive(Debug, Clone, PartialEq, Serialize)]
pub(crate) struct RootRow {
    pub alpha_deg: [f64; 2],
    pub beta_deg: [f64; 2],
    #[serde(skip_serializing_if = "Option::is_none")]
    pub psi_deg: Option<[f64; 2]>,
    pub multiplicity: usize,
    pub residual: f64,
    pub real: bool,
    pub spurious: bool,
    pub admissible: bool,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub why_not: Option<Inadmissible>,
}

/// Every root of the pose system at one displacement, classified, and the physical one
/// selected: what `slideroute roots` prints (its `Display`) and writes as JSON (its
/// `Serialize`), angles in degrees.
///
/// ```
/// use slideroute::output::RootsReport;
/// use slideroute::{Displacement, Mode, Scene};
/// let scene = Scene::default_scene();
/// let all = slideroute::poses::solve_all(scene.site(), Displacement::new(0.5, 0.1, 0.02), Mode::Exact)?;
/// let report = RootsReport::new(&scene, &all);
/// assert!(report.to_string().contains("selected: α = "));
/// # Ok::<(), slideroute::poses::TrackError>(())
/// ```
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct RootsReport {
    scene: String,
    mode: Mode,
    x_m: f64,
    z_m: f64,
    theta_deg: f64,
    pub(crate) selected: Option<SelectedPose>,
    /// Why nothing is selected (the tracker's diagnosis), if so.
    pub(crate) selection_error: Option<String>,
    pub(crate) finite_roots: usize,
    pub(crate) roots_at_infinity: usize,
    pub(crate) roots: Vec<RootRow>,
}

fn deg(c: num_complex::Complex64) -> [f64; 2] {
    [c.re.to_degrees(), c.im.to_degrees()]
}

fn selected_pose(scene: &Scene, all: &AllRoots, r: &Root) -> Option<SelectedPose> {
    let (a, second) = (r.alpha.re, r.psi.unwrap_or(r.beta).re);
    let pose = classify::pose(scene.site(), all.displacement, all.mode, [a, second])?;
    Some(SelectedPose {
        alpha_deg: pose.alpha.to_degrees(),
        beta_deg: pose.beta.to_degrees(),
        gamma_deg: pose.gamma.to_degrees(),
        psi_deg: r.psi.map(|p| p.re.to_degrees()),
        cm_y_m: pose.cm.y,
    })
}

impl RootsReport {
    /// The report of `all`, the roots at one displacement of `scene`'s site.
    pub fn new(scene: &Scene, all: &AllRoots) -> Self {
        let d: Displacement = all.displacement;
        RootsReport {
            scene: scene.name().to_string(),
            mode: all.mode,
            x_m: d.x,
            z_m: d.z,
            theta_deg: d.theta.to_degrees(),
            selected: all
                .selected
                .and_then(|k| selected_pose(scene, all, &all.roots[k])),
            selection_error: all.selection_error.as_ref().map(|e| e.to_string()),
            finite_roots: all.finite_roots,
            roots_at_infinity: all.roots_at_infinity,
            roots: all
                .roots
                .iter()
                .map(|r| RootRow {
                    alpha_deg: deg(r.alpha),
                    beta_deg: deg(r.beta),
                    psi_deg: r.psi.map(deg),
                    multiplicity: r.multiplicity,
                    residual: r.residual,
                    real: r.real,
                    spurious: r.spurious,
                    admissible: r.admissible,
                    why_not: r.why_not,
                })
                .collect(),
        }
    }
}

fn cplx(v: [f64; 2]) -> String {
    if v[1].abs() < 1e-9 {
        format!("{:>12.6}", v[0])
    } else {
        format!("{:>12.6}{:+.3}i", v[0], v[1])
    }
}

impl fmt::Display for RootsReport {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        writeln!(
            f,
            "scene {} ({} mode): X = {} m, Z = {} m, θ = {}°",
            self.scene,
            self.mode.as_str(),
            crate::numeric::fixed(self.x_m, 6),
            crate::numeric::fixed(self.z_m, 6),
            crate::numeric::fixed(self.theta_deg, 6)
        )?;
        match (&self.selected, &self.selection_error) {
            (Some(s), _) => writeln!(
                f,
                "selected: α = {:.6}°, β = {:.6}°, γ = {:.6}°, CM height {:.6} m",
                s.alpha_deg, s.beta_deg, s.gamma_deg, s.cm_y_m
            )?,
            (None, Some(e)) => writeln!(f, "no pose selected: {e}")?,
            (None, None) => writeln!(f, "no pose selected")?,
        }
        writeln!(
            f,
            "{} finite roots (with multiplicity), {} at infinity:",
            self.finite_roots, self.roots_at_infinity
        )?;
        // The second column: β, or on a general site (where a complex root has no β) the roll ψ.
        let roll = self
            .roots
            .iter()
            .any(|r| r.beta_deg[0].is_nan() && r.psi_deg.is_some());
        writeln!(
            f,
            "  {:>24}  {:>24}  mult  status",
            "α (°)",
            if roll { "ψ (°)" } else { "β (°)" }
        )?;
        for r in &self.roots {
            let status = if r.admissible {
                "admissible".to_string()
            } else if !r.real {
                "complex".to_string()
            } else {
                r.why_not.map_or("real".to_string(), |w| w.to_string())
            };
            writeln!(
                f,
                "  {:>24}  {:>24}  {:>4}  {}",
                cplx(r.alpha_deg),
                cplx(match (roll, r.psi_deg) {
                    (true, Some(p)) => p,
                    _ => r.beta_deg,
                }),
                r.multiplicity,
                status
            )?;
        }
        Ok(())
    }
}
