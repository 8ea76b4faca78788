//! The pose equations of each mode in the form the solvers need.
//!
//! * [`Equations`]: the *unsquared* equations of the chosen mode and their Jacobian, for the
//!   tracker. Small-angle: E = A + B·Q (sin h ≥ 0) in u = (α, β). Exact: (13), (14) in
//!   u = (α, ψ). Building one evaluates only that mode's coefficients.
//! * [`biquadratic`]: the polynomial system of bidegree (2, 2) for the all-roots solver, in
//!   scaled unknowns x, y (small-angle: α = tan ξ·x, β = tan ζ·y; exact: tan(α/2) = tan(ξ/2)·x,
//!   tan(ψ/2) = tan(max(ξ, ζ)/2)·y), each equation divided by its largest coefficient.

use super::eigen::Coeffs;
use crate::coeffs::{
    CoeffInputs, Exact, GeneralExact, GeneralSmallAngle, Inputs, SMALL_ANGLE_MONOMIALS,
    SMALL_ANGLE_UNSQUARED_A13, SMALL_ANGLE_UNSQUARED_A14, SMALL_ANGLE_UNSQUARED_SPLIT, SmallAngle,
    SmallAngleUnsquared,
};
use crate::geometry::Displacement;
use crate::geometry::Site;
use crate::model::Mode;

/// The unsquared equations of one mode at one displacement: the paper's on the paper's site,
/// the general system's (in u = (α, ψ) for both modes) on any other.
#[derive(Debug, Clone, Copy)]
pub enum Equations {
    /// The paper's small-angle (13), (14) before squaring.
    SmallAngle(SmallAngleUnsquared),
    /// The paper's exact (13), (14).
    Exact(Exact),
    /// The general system with small angles.
    GeneralSmallAngle(GeneralSmallAngle),
    /// The general system, exact.
    GeneralExact(GeneralExact),
}

/// Residual, Jacobian and the size of each equation's terms (for round-off judgements).
pub struct Evaluated {
    /// The residuals (m).
    pub r: [f64; 2],
    /// ∂r/∂u.
    pub j: [[f64; 2]; 2],
    /// Σ|terms| of each equation.
    pub scale: [f64; 2],
}

impl Equations {
    /// `mode`'s equations of `site` at displacement `d`.
    pub fn new(site: &Site, d: Displacement, mode: Mode) -> Self {
        Self::from_inputs(&Inputs::new(site, d), mode)
    }

    /// From the generator's inputs at one displacement.
    pub fn from_inputs(inputs: &Inputs, mode: Mode) -> Self {
        match (inputs, mode) {
            (Inputs::Paper(p), Mode::SmallAngle) => {
                Equations::SmallAngle(SmallAngleUnsquared::new(p))
            }
            (Inputs::Paper(p), Mode::Exact) => Equations::Exact(Exact::new(p)),
            (Inputs::General(g), Mode::SmallAngle) => {
                Equations::GeneralSmallAngle(GeneralSmallAngle::new(g))
            }
            (Inputs::General(g), Mode::Exact) => Equations::GeneralExact(GeneralExact::new(g)),
        }
    }

    /// At u = (α, β) (small-angle) or (α, ψ) (exact); `None` where the small-angle Q is not real.
    #[inline]
    pub fn eval(&self, u: [f64; 2]) -> Option<Evaluated> {
        match self {
            Equations::SmallAngle(s) => {
                let [e13, e14] = s.eval(u[0], u[1])?;
                Some(Evaluated {
                    r: [e13.value, e14.value],
                    j: [e13.grad, e14.grad],
                    scale: [e13.scale, e14.scale],
                })
            }
            Equations::Exact(e) => {
                let (r, j) = e.residual_jacobian(u[0], u[1]);
                let s: f64 = e.g.iter().map(|c| c.abs()).sum();
                Some(Evaluated {
                    r,
                    j,
                    scale: [s, s],
                })
            }
            Equations::GeneralExact(e) => {
                let (r, j) = e.residual_jacobian(u[0], u[1]);
                let s: f64 = e.g.iter().map(|c| c.abs()).sum();
                Some(Evaluated {
                    r,
                    j,
                    scale: [s, s],
                })
            }
            Equations::GeneralSmallAngle(e) => {
                let (r, j, scale) = e.eval(u[0], u[1]);
                Some(Evaluated { r, j, scale })
            }
        }
    }
}

/// The scales of the all-roots solver's two unknowns: each physical unknown (α or tan α/2, and
/// β, ψ or tan ψ/2) is the solver's times its scale, so that the physical roots are of order one.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct UnknownScales {
    /// The first unknown's scale.
    pub x: f64,
    /// The second unknown's scale.
    pub y: f64,
}

/// Scales of the unknowns for the all-roots solver (see the module docs). On a general site,
/// the largest of the planes' dips stands for ξ and ζ (at least 0.01 rad, so that a foundation
/// of level faces still has a scale).
pub fn unknown_scales(site: &Site, mode: Mode) -> UnknownScales {
    let (xi, zeta) = match site.as_paper() {
        Some(p) => (p.foundation.xi, p.foundation.zeta),
        None => {
            let dip = site.planes().iter().map(|p| p.dip()).fold(0.01, f64::max);
            (dip, dip)
        }
    };
    let (x, y) = match mode {
        Mode::SmallAngle => (xi.tan(), zeta.tan()),
        Mode::Exact => ((xi / 2.0).tan(), (xi.max(zeta) / 2.0).tan()),
    };
    UnknownScales { x, y }
}

/// The coefficients of the polynomial in the scaled unknowns, normalised to a largest
/// coefficient of 1.
fn scaled(c: &Coeffs, scales: UnknownScales) -> Coeffs {
    let UnknownScales { x: sx, y: sy } = scales;
    let mut out = [[0.0; 3]; 3];
    let mut big = 0.0f64;
    for i in 0..3 {
        for j in 0..3 {
            out[i][j] = c[i][j] * sx.powi(i as i32) * sy.powi(j as i32);
            big = big.max(out[i][j].abs());
        }
    }
    if big > 0.0 {
        for row in &mut out {
            for v in row {
                *v /= big;
            }
        }
    }
    out
}

/// Which small-angle equations are perfect squares at `d`: (15a) when sin θ = 0, (15b) when
/// sin(θ + κ) = 0 (there B = 0 in A ± B·Q, so the squared equation is A²).
pub fn perfect_squares(site: &Site, d: Displacement, mode: Mode) -> [bool; 2] {
    match (mode, site.as_paper()) {
        (Mode::SmallAngle, Some(p)) => [
            d.theta.sin().abs() < 1e-12,
            (d.theta + p.foundation.kappa).sin().abs() < 1e-12,
        ],
        // The exact forms and the general small-angle form are not squared.
        _ => [false, false],
    }
}

/// The mode's polynomial system as two scaled (2, 2) coefficient arrays. A small-angle equation
/// that is a perfect square A² is replaced by A: its roots are the same, each of them simple
/// instead of double (see [`perfect_squares`]).
pub fn biquadratic(site: &Site, d: Displacement, mode: Mode) -> (Coeffs, Coeffs) {
    let scales = unknown_scales(site, mode);
    biquadratic_from(site, &Inputs::new(site, d), scales, d, mode)
}

/// As [`biquadratic`], from the generator's inputs at `d` and the [`unknown_scales`].
pub fn biquadratic_from(
    site: &Site,
    inputs: &Inputs,
    scales: UnknownScales,
    d: Displacement,
    mode: Mode,
) -> (Coeffs, Coeffs) {
    let raw: [Coeffs; 2] = match (inputs, mode) {
        (Inputs::Paper(inputs), Mode::SmallAngle) => {
            let inputs: &CoeffInputs = inputs;
            let square = perfect_squares(site, d, mode);
            let f = SmallAngle::new(inputs).f;
            let u = if square[0] || square[1] {
                Some(SmallAngleUnsquared::new(inputs).c)
            } else {
                None
            };
            let n13 = SMALL_ANGLE_UNSQUARED_SPLIT;
            let mut c = [[[0.0; 3]; 3]; 2];
            for (eq, mons) in SMALL_ANGLE_MONOMIALS.iter().enumerate() {
                match (square[eq], &u) {
                    (true, Some(u)) => {
                        let (exps, coef) = if eq == 0 {
                            (SMALL_ANGLE_UNSQUARED_A13, &u[..n13])
                        } else {
                            (SMALL_ANGLE_UNSQUARED_A14, &u[n13 + 1..u.len() - 1])
                        };
                        for (&(i, j), &k) in exps.iter().zip(coef) {
                            c[eq][i as usize][j as usize] = k;
                        }
                    }
                    _ => {
                        for (k, &(i, j)) in mons.iter().enumerate() {
                            c[eq][i as usize][j as usize] = f[6 * eq + k];
                        }
                    }
                }
            }
            c
        }
        (Inputs::Paper(inputs), Mode::Exact) => Exact::new(inputs).half_angle(),
        (Inputs::General(g), Mode::SmallAngle) => GeneralSmallAngle::new(g).coefficients(),
        (Inputs::General(g), Mode::Exact) => GeneralExact::new(g).half_angle(),
    };
    (scaled(&raw[0], scales), scaled(&raw[1], scales))
}
