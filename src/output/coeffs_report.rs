//! The `coeffs` report: both coefficient sets at one displacement.

use super::Ordered;
use crate::poses::{CoeffInputs, Exact, SmallAngle};
use crate::{Displacement, Scene};
use serde::Serialize;
use std::fmt;

/// The exact form's coefficients, by basis monomial, plus its tangent half-angle matrices.
#[derive(Debug, Clone, PartialEq, Serialize)]
struct ExactReport {
    /// The unknowns' names as used in the basis names: sa = sin α, ca = cos α, sp = sin ψ,
    /// cp = cos ψ (ψ: roll about side 01).
    unknowns: [&'static str; 4],
    eq13: Ordered<f64>,
    eq14: Ordered<f64>,
    /// `half_angle_eq13[i][j]` multiplies tan(α/2)^i tan(ψ/2)^j (times (1+ta²)(1+tp²)).
    half_angle_eq13: [[f64; 3]; 3],
    half_angle_eq14: [[f64; 3]; 3],
}

/// Coefficients of the paper's small-angle system (15) and of the exact form (13), (14) at one
/// displacement: what `slideroute coeffs` prints (its `Display`) and writes as JSON (its
/// `Serialize`: f1 … f12 in order, and each exact equation by basis monomial).
///
/// ```
/// use slideroute::output::CoeffReport;
/// use slideroute::{Displacement, Scene};
/// let report = CoeffReport::new(&Scene::default_scene(), Displacement::new(0.5, 0.1, 0.02)).unwrap();
/// assert_eq!(report.not_finite(), None);
/// assert!(report.to_string().contains("small-angle system (15):"));
/// ```
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct CoeffReport {
    /// The scene's name.
    pub scene: String,
    /// X: the CM's displacement along X (m).
    pub x_m: f64,
    /// Z: the CM's displacement along Z (m).
    pub z_m: f64,
    /// θ: the yaw (degrees).
    pub theta_deg: f64,
    small_angle: Ordered<f64>,
    exact: ExactReport,
}

impl CoeffReport {
    /// The paper's coefficients at `d`; `None` on a site that is not the paper's (its pose
    /// comes from the general system, `derivations/09-general-pose.md`).
    pub fn new(scene: &Scene, d: Displacement) -> Option<Self> {
        let inputs = CoeffInputs::new(scene.site().as_paper()?, d);
        let small = SmallAngle::new(&inputs);
        let exact = Exact::new(&inputs);
        let half = exact.half_angle();
        let named = |names: &[&str], vals: &[f64]| {
            Ordered(
                names
                    .iter()
                    .zip(vals)
                    .map(|(n, v)| (n.to_string(), *v))
                    .collect(),
            )
        };
        Some(CoeffReport {
            scene: scene.name().to_string(),
            x_m: d.x,
            z_m: d.z,
            theta_deg: d.theta.to_degrees(),
            small_angle: named(&SmallAngle::NAMES, &small.f),
            exact: ExactReport {
                unknowns: ["sa = sin α", "ca = cos α", "sp = sin ψ", "cp = cos ψ"],
                eq13: named(&Exact::NAMES_13, exact.eq13()),
                eq14: named(&Exact::NAMES_14, exact.eq14()),
                half_angle_eq13: half[0],
                half_angle_eq14: half[1],
            },
        })
    }
}

impl CoeffReport {
    /// The name of the first coefficient that is not a finite number (a displacement so far
    /// that the system overflows), if any.
    pub fn not_finite(&self) -> Option<String> {
        let half = |eq: &str, h: &[[f64; 3]; 3]| {
            (0..9)
                .find(|k| !h[k / 3][k % 3].is_finite())
                .map(|k| format!("{eq} in half-angles, ta^{} tp^{}", k / 3, k % 3))
        };
        [&self.small_angle, &self.exact.eq13, &self.exact.eq14]
            .into_iter()
            .find_map(|o| o.0.iter().find(|(_, v)| !v.is_finite()))
            .map(|(name, _)| name.clone())
            .or_else(|| half("(13)", &self.exact.half_angle_eq13))
            .or_else(|| half("(14)", &self.exact.half_angle_eq14))
    }
}

impl fmt::Display for CoeffReport {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let g = crate::numeric::given;
        writeln!(
            f,
            "scene {}: X = {} m, Z = {} m, θ = {}°",
            self.scene,
            g(self.x_m),
            g(self.z_m),
            g(self.theta_deg)
        )?;
        writeln!(f, "small-angle system (15):")?;
        for (k, v) in &self.small_angle.0 {
            writeln!(f, "  {k:>4} = {v:>+.12e}")?;
        }
        writeln!(
            f,
            "exact (13), (14) in sa = sin α, ca = cos α, sp = sin ψ, cp = cos ψ:"
        )?;
        for (name, eq) in [("(13)", &self.exact.eq13), ("(14)", &self.exact.eq14)] {
            let terms: Vec<String> = eq.0.iter().map(|(k, v)| format!("{v:+.6e}·{k}")).collect();
            writeln!(f, "  {name} {} = 0", terms.join(" "))?;
        }
        Ok(())
    }
}
