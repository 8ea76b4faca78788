//! Coefficients of the pose polynomials, generated at build time by `codegen/` from the paper's
//! law-of-sines relations (eqs. (2), (3), (8)–(14)) and included from `OUT_DIR`.
//!
//! * [`SmallAngle`]: f1–f12 of system (15), re-derived (the paper's printed f1, f2, f7, f11 are
//!   misprints; see `derivations/05-paper-differences.md`).
//! * [`Exact`]: (13) and (14) without approximation, in the unknowns (sin α, cos α, sin ψ, cos ψ)
//!   where ψ is the roll of the frame about side 01 (`derivations/04-exact.md`). Bilinear, so
//!   no squaring is needed and no spurious roots arise; ψ and β are related by
//!   √2 sin β = sin α − cos α sin ψ.
//!
//! Evaluating one mode never evaluates the other's coefficients.

mod general;

pub use general::{GeneralExact, GeneralSmallAngle, Inputs, SiteTrig};

use crate::geometry::Displacement;
use crate::geometry::PaperSite;

#[allow(clippy::all)]
mod generated {
    include!(concat!(env!("OUT_DIR"), "/coeffs.rs"));
}

pub use generated::{CoeffInputs, GeneralInputs};
pub use generated::{
    EXACT_BASIS_13, EXACT_BASIS_14, EXACT_TERMS, SMALL_ANGLE_MONOMIALS, SMALL_ANGLE_UNSQUARED_A13,
    SMALL_ANGLE_UNSQUARED_A14, SMALL_ANGLE_UNSQUARED_SPLIT,
};

/// Number of trig-basis terms of exact (13) plus (14).
pub const EXACT_LEN: usize = EXACT_TERMS[0] + EXACT_TERMS[1];

/// The trigonometric functions of the foundation that [`CoeffInputs`] needs (sin κ, cos κ,
/// cot ξ, cot ζ): fixed by the site, so a solver that evaluates the coefficients at many
/// displacements computes them once.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FoundationTrig {
    sk: f64,
    ck: f64,
    cot_xi: f64,
    cot_zeta: f64,
}

impl FoundationTrig {
    /// tan ξ and tan ζ (for the admissibility check's tilt bounds).
    pub fn tan_dips(&self) -> (f64, f64) {
        (1.0 / self.cot_xi, 1.0 / self.cot_zeta)
    }

    /// (sin κ, cos κ): the strike of plane 2 (`geometry::paper_planes`), computed once.
    pub fn kappa_sin_cos(&self) -> (f64, f64) {
        (self.sk, self.ck)
    }

    /// The functions of `site`'s foundation.
    pub fn new(site: &PaperSite) -> Self {
        let g = site.foundation;
        let (sk, ck) = g.kappa.sin_cos();
        FoundationTrig {
            sk,
            ck,
            cot_xi: 1.0 / g.xi.tan(),
            cot_zeta: 1.0 / g.zeta.tan(),
        }
    }
}

impl CoeffInputs {
    /// The generator's inputs for a site at displacement `d`. Differences of cosines are
    /// computed from products of sines, so small displacements lose no precision.
    pub fn new(site: &PaperSite, d: Displacement) -> Self {
        Self::with_trig(site, &FoundationTrig::new(site), d)
    }

    /// As [`CoeffInputs::new`], with the foundation's trigonometric functions computed before
    /// (`trig` must come from the same site). One `sin_cos` per call: with s = sin(θ/2),
    /// c = cos(θ/2): sin θ = 2sc, 1 − cos θ = 2s², cos κ − cos(θ + κ) = 2s·sin(θ/2 + κ) and
    /// sin(θ + κ) − sin κ = 2s·cos(θ/2 + κ), the half-angle sums expanded by κ's sine and cosine.
    pub fn with_trig(site: &PaperSite, trig: &FoundationTrig, d: Displacement) -> Self {
        let f = site.frame;
        let (s_half, c_half) = (0.5 * d.theta).sin_cos();
        let FoundationTrig {
            sk,
            ck,
            cot_xi,
            cot_zeta,
        } = *trig;
        let s_hk = s_half * ck + c_half * sk;
        let c_hk = c_half * ck - s_half * sk;
        CoeffInputs {
            x: d.x,
            z: d.z,
            l2x: f.l2x,
            l1z: f.l1z,
            l2z: f.l2z,
            omc: 2.0 * s_half * s_half,
            st: 2.0 * s_half * c_half,
            ck,
            sk,
            dck: 2.0 * s_half * s_hk,
            dsk: 2.0 * s_half * c_hk,
            cot_xi,
            cot_zeta,
        }
    }
}

/// f1–f12 of system (15) at one displacement: (15a) is
/// f1 + f2 α + f3 αβ + f4 α² + f5 α²β + f6 α²β² = 0 and (15b) is
/// f7 + f8 β + f9 αβ + f10 β² + f11 αβ² + f12 α²β² = 0 (SI units, unscaled).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SmallAngle {
    /// `f[0]` is f1, …, `f[11]` is f12.
    pub f: [f64; 12],
}

impl SmallAngle {
    /// The coefficients' names, f1–f12, in the order of [`SmallAngle::f`].
    pub const NAMES: [&'static str; 12] = [
        "f1", "f2", "f3", "f4", "f5", "f6", "f7", "f8", "f9", "f10", "f11", "f12",
    ];

    /// The coefficients at the displacement and site of `inputs`.
    pub fn new(inputs: &CoeffInputs) -> Self {
        SmallAngle {
            f: generated::small_angle(inputs),
        }
    }

    /// Residuals of (15a), (15b) at (α, β) in radians (m²).
    pub fn residual(&self, alpha: f64, beta: f64) -> [f64; 2] {
        let mut r = [0.0; 2];
        for (eq, mons) in SMALL_ANGLE_MONOMIALS.iter().enumerate() {
            r[eq] = mons
                .iter()
                .zip(&self.f[6 * eq..6 * eq + 6])
                .map(|(&(i, j), c)| c * alpha.powi(i as i32) * beta.powi(j as i32))
                .sum();
        }
        r
    }
}

/// The small-angle relations before squaring: (13)·cos α and (14)·cos α under the small-angle
/// substitutions, E = A(α, β) + B·Q with Q = √(1 − (1/√2 − αβ)²) ≥ 0 (0 ≤ h ≤ 180°). Their
/// roots are the non-spurious roots of (15); the tracker follows these, not (15).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SmallAngleUnsquared {
    /// A13 terms ([`SMALL_ANGLE_UNSQUARED_A13`]), B13, A14 terms, B14.
    pub c: [f64; SMALL_ANGLE_UNSQUARED_A13.len() + SMALL_ANGLE_UNSQUARED_A14.len() + 2],
}

/// Value, gradient and the sum of term magnitudes of A(α, β) = Σ c_k α^i β^j.
fn poly_ab(c: &[f64], exps: &[(u32, u32)], a: f64, b: f64) -> (f64, [f64; 2], f64) {
    let (mut v, mut da, mut db, mut mag) = (0.0, 0.0, 0.0, 0.0);
    for (&(i, j), &k) in exps.iter().zip(c) {
        let t = k * a.powi(i as i32) * b.powi(j as i32);
        v += t;
        mag += t.abs();
        if i > 0 {
            da += k * i as f64 * a.powi(i as i32 - 1) * b.powi(j as i32);
        }
        if j > 0 {
            db += k * j as f64 * a.powi(i as i32) * b.powi(j as i32 - 1);
        }
    }
    (v, [da, db], mag)
}

/// One unsquared small-angle equation evaluated at (α, β).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct UnsquaredValue {
    /// A + B·Q (the physical sign, sin h ≥ 0).
    pub value: f64,
    /// A − B·Q (the other sign; zero at a spurious root of (15)).
    pub mirror: f64,
    /// ∂(A + BQ)/∂(α, β).
    pub grad: [f64; 2],
    /// Σ|terms|: the size against which round-off is judged.
    pub scale: f64,
}

impl SmallAngleUnsquared {
    /// The relations at `inputs`.
    pub fn new(inputs: &CoeffInputs) -> Self {
        SmallAngleUnsquared {
            c: generated::small_angle_unsquared(inputs),
        }
    }

    /// Both equations at (α, β); `None` where Q is not real (|1/√2 − αβ| > 1).
    pub fn eval(&self, alpha: f64, beta: f64) -> Option<[UnsquaredValue; 2]> {
        let p = std::f64::consts::FRAC_1_SQRT_2 - alpha * beta;
        let q2 = 1.0 - p * p;
        if q2.is_nan() || q2 <= 0.0 {
            return None;
        }
        let q = q2.sqrt();
        // dQ/dα = Pβ/Q, dQ/dβ = Pα/Q.
        let dq = [p * beta / q, p * alpha / q];
        let n13 = SMALL_ANGLE_UNSQUARED_SPLIT;
        let parts = [
            (&self.c[..n13], SMALL_ANGLE_UNSQUARED_A13, self.c[n13]),
            (
                &self.c[n13 + 1..self.c.len() - 1],
                SMALL_ANGLE_UNSQUARED_A14,
                self.c[self.c.len() - 1],
            ),
        ];
        Some(parts.map(|(c, exps, b)| {
            let (a, ga, mag) = poly_ab(c, exps, alpha, beta);
            UnsquaredValue {
                value: a + b * q,
                mirror: a - b * q,
                grad: [ga[0] + b * dq[0], ga[1] + b * dq[1]],
                scale: mag + (b * q).abs(),
            }
        }))
    }
}

/// The exact relations (13), (14) at one displacement, as coefficients of the trig basis
/// monomials of [`Exact::BASIS_13`] / [`Exact::BASIS_14`] (exponents of sin α, cos α, sin ψ,
/// cos ψ). Each equation reads LHS − RHS of the paper's (13) or (14), in metres.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Exact {
    /// Coefficients of (13), then of (14).
    pub g: [f64; EXACT_LEN],
}

impl Exact {
    /// The basis monomials of (13): the exponents of (sin α, cos α, sin ψ, cos ψ) of each term,
    /// in the order of [`Exact::eq13`].
    pub const BASIS_13: [[u32; 4]; EXACT_TERMS[0]] = EXACT_BASIS_13;
    /// Those of (14), in the order of [`Exact::eq14`].
    pub const BASIS_14: [[u32; 4]; EXACT_TERMS[1]] = EXACT_BASIS_14;
    /// The names of (13)'s coefficients, its basis monomials, in the order of [`Exact::eq13`].
    pub const NAMES_13: [&'static str; EXACT_TERMS[0]] = generated::EXACT_NAMES_13;
    /// The names of (14)'s coefficients, in the order of [`Exact::eq14`].
    pub const NAMES_14: [&'static str; EXACT_TERMS[1]] = generated::EXACT_NAMES_14;

    /// The coefficients at the displacement and site of `inputs`.
    pub fn new(inputs: &CoeffInputs) -> Self {
        Exact {
            g: generated::exact_trig(inputs),
        }
    }

    /// Coefficients of (13).
    pub fn eq13(&self) -> &[f64] {
        &self.g[..EXACT_TERMS[0]]
    }

    /// Coefficients of (14).
    pub fn eq14(&self) -> &[f64] {
        &self.g[EXACT_TERMS[0]..]
    }

    /// Residuals of (13), (14) (m) at tilt α and roll ψ given by their sines and cosines.
    pub fn residual(&self, sa: f64, ca: f64, sp: f64, cp: f64) -> [f64; 2] {
        let val = [sa, ca, sp, cp];
        let term = |e: &[u32; 4]| -> f64 {
            e.iter()
                .zip(val)
                .map(|(&k, v)| if k == 0 { 1.0 } else { v })
                .product()
        };
        let r13 = EXACT_BASIS_13
            .iter()
            .zip(self.eq13())
            .map(|(e, c)| c * term(e))
            .sum();
        let r14 = EXACT_BASIS_14
            .iter()
            .zip(self.eq14())
            .map(|(e, c)| c * term(e))
            .sum();
        [r13, r14]
    }

    /// Residuals of (13), (14) (m) at (α, ψ) and their Jacobian ∂(r13, r14)/∂(α, ψ).
    #[inline]
    pub fn residual_jacobian(&self, alpha: f64, psi: f64) -> ([f64; 2], [[f64; 2]; 2]) {
        trig_residual_jacobian(
            [
                (&EXACT_BASIS_13, self.eq13()),
                (&EXACT_BASIS_14, self.eq14()),
            ],
            alpha,
            psi,
        )
    }

    /// The same equations in tangent half-angles ta = tan(α/2), tp = tan(ψ/2), multiplied by
    /// (1 + ta²)(1 + tp²): `h[eq][i][j]` multiplies ta^i tp^j. Bidegree (2, 2): at most 8 roots.
    pub fn half_angle(&self) -> [[[f64; 3]; 3]; 2] {
        unflatten(generated::exact_half_angle(&self.g))
    }
}

/// Residuals and their Jacobian ∂r/∂(α, ψ) of two equations given in a trig basis (exponents
/// of sin α, cos α, sin ψ, cos ψ, each pair of degree ≤ 1) with their coefficients.
#[inline(always)]
fn trig_residual_jacobian(
    parts: [(&[[u32; 4]], &[f64]); 2],
    alpha: f64,
    psi: f64,
) -> ([f64; 2], [[f64; 2]; 2]) {
    let (sa, ca) = alpha.sin_cos();
    let (sp, cp) = psi.sin_cos();
    let mut r = [0.0; 2];
    let mut j = [[0.0; 2]; 2];
    for (eq, (basis, coef)) in parts.into_iter().enumerate() {
        for (e, &c) in basis.iter().zip(coef) {
            // Each monomial is fa(α)·fp(ψ) with fa ∈ {1, sin α, cos α}, fp ∈ {1, sin ψ, cos ψ}.
            let (fa, dfa) = match (e[0], e[1]) {
                (1, _) => (sa, ca),
                (_, 1) => (ca, -sa),
                _ => (1.0, 0.0),
            };
            let (fp, dfp) = match (e[2], e[3]) {
                (1, _) => (sp, cp),
                (_, 1) => (cp, -sp),
                _ => (1.0, 0.0),
            };
            r[eq] += c * fa * fp;
            j[eq][0] += c * dfa * fp;
            j[eq][1] += c * fa * dfp;
        }
    }
    (r, j)
}

/// The (2, 2) coefficient array `h[eq][i][j]` of a flat generated half-angle form.
fn unflatten(flat: [f64; 18]) -> [[[f64; 3]; 3]; 2] {
    let mut h = [[[0.0; 3]; 3]; 2];
    for (k, v) in flat.into_iter().enumerate() {
        h[k / 9][(k / 3) % 3][k % 3] = v;
    }
    h
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::Scene;

    #[test]
    fn start_pose_is_a_root_of_both_systems() {
        // At X = Z = θ = 0 the flat frame (α = β = ψ = 0) is in contact with all three planes.
        let scene = Scene::default_scene();
        let inputs = CoeffInputs::new(scene.site().as_paper().unwrap(), Displacement::default());
        let small = SmallAngle::new(&inputs);
        let r = small.residual(0.0, 0.0);
        assert!(r[0].abs() < 1e-12 && r[1].abs() < 1e-12, "{r:?}");
        let exact = Exact::new(&inputs);
        let r = exact.residual(0.0, 1.0, 0.0, 1.0);
        assert!(r[0].abs() < 1e-12 && r[1].abs() < 1e-12, "{r:?}");
    }

    #[test]
    fn half_angle_form_equals_trig_form_times_weights() {
        let scene = Scene::default_scene();
        let d = Displacement {
            x: 1.2,
            z: -0.3,
            theta: 0.07,
        };
        let exact = Exact::new(&CoeffInputs::new(scene.site().as_paper().unwrap(), d));
        let h = exact.half_angle();
        for &(alpha, psi) in &[(0.1, -0.2), (0.4, 0.3), (-0.7, 1.1)] {
            let (ta, tp) = (f64::tan(alpha / 2.0), f64::tan(psi / 2.0));
            let w = (1.0 + ta * ta) * (1.0 + tp * tp);
            let trig = exact.residual(alpha.sin(), alpha.cos(), psi.sin(), psi.cos());
            for eq in 0..2 {
                let mut v = 0.0;
                for (i, row) in h[eq].iter().enumerate() {
                    for (j, c) in row.iter().enumerate() {
                        v += c * ta.powi(i as i32) * tp.powi(j as i32);
                    }
                }
                assert!(
                    (v - w * trig[eq]).abs() < 1e-12 * 10.0,
                    "{v} vs {}",
                    w * trig[eq]
                );
            }
        }
    }
}
