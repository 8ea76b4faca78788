//! All roots of two polynomials of bidegree (2, 2) by eigenvalues.
//!
//! Hidden variable x: as quadratics in y, p = P0(x) + P1(x) y + P2(x) y² and likewise q. They
//! share a root y exactly when the 4×4 Sylvester matrix S(x) = S0 + x S1 + x² S2 is singular
//! (S(x)·[y³, y², y, 1]ᵀ = 0). The quadratic matrix polynomial is linearised by the companion
//! pencil A − x B, A = [[0, I], [−S0, −S1]], B = [[I, 0], [0, S2]] (8×8). S2 may be singular
//! (roots at infinity), so instead of inverting B we shift and invert: the eigenvalues μ of
//! (A − σB)⁻¹B give x = σ + 1/μ, and μ ≈ 0 is a root at x = ∞.
//!
//! y is recovered for each x as the common root of the two quadratics p(x, ·), q(x, ·) — the
//! candidate with the smallest relative residual, never by dividing by a quantity that can
//! vanish — and each (x, y) is refined by Newton's method on the pair (p, q) itself.

use crate::numeric::poly_mul;
use nalgebra::{SMatrix, SVector};
use num_complex::Complex64 as C;

/// `p[i][j]` multiplies x^i y^j.
pub type Coeffs = [[f64; 3]; 3];

/// A finite root (x, y), after refinement, with its relative residual.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RawRoot {
    /// The first unknown.
    pub x: C,
    /// The second.
    pub y: C,
    /// max(|p|/Σ|p terms|, |q|/Σ|q terms|) at the root.
    pub residual: f64,
}

/// All finite roots (up to 8) and the number of eigenvalues at infinity.
#[derive(Debug, Clone, PartialEq)]
pub struct RawRoots {
    /// The finite roots.
    pub roots: Vec<RawRoot>,
    /// Eigenvalues of the pencil at x = ∞, plus finite x whose y is at infinity.
    pub at_infinity: usize,
}

/// Up to 8 finite roots and the count at infinity, without allocation: what [`RawRoots`] holds.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FixedRoots {
    roots: [RawRoot; 8],
    len: usize,
    /// As [`RawRoots::at_infinity`].
    pub at_infinity: usize,
}

impl FixedRoots {
    /// None yet, `at_infinity` at infinity.
    pub(crate) fn new(at_infinity: usize) -> Self {
        let zero = C::new(0.0, 0.0);
        let none = RawRoot {
            x: zero,
            y: zero,
            residual: 0.0,
        };
        FixedRoots {
            roots: [none; 8],
            len: 0,
            at_infinity,
        }
    }

    /// The finite roots.
    pub fn roots(&self) -> &[RawRoot] {
        &self.roots[..self.len]
    }

    fn push(&mut self, r: RawRoot) {
        self.roots[self.len] = r;
        self.len += 1;
    }
}

impl From<&RawRoots> for FixedRoots {
    fn from(r: &RawRoots) -> Self {
        let mut fixed = FixedRoots::new(r.at_infinity);
        r.roots.iter().for_each(|&root| fixed.push(root));
        fixed
    }
}

impl From<FixedRoots> for RawRoots {
    fn from(r: FixedRoots) -> Self {
        RawRoots {
            roots: r.roots().to_vec(),
            at_infinity: r.at_infinity,
        }
    }
}

/// |re| + |im|: a norm within √2 of the modulus, without a square root.
#[inline]
fn l1(z: C) -> f64 {
    z.re.abs() + z.im.abs()
}

/// The modulus without `hypot`'s overflow guard (these values are far from overflow), which
/// is several times faster.
#[inline]
fn modulus(z: C) -> f64 {
    (z.re * z.re + z.im * z.im).sqrt()
}

/// Value (Horner) and Σ|terms| (in real arithmetic from |x|, |y|).
#[inline]
fn eval(c: &Coeffs, x: C, y: C) -> (C, f64) {
    let (ax, ay) = (modulus(x), modulus(y));
    let mut v = C::new(0.0, 0.0);
    let mut mag = 0.0;
    for row in c.iter().rev() {
        let r = (C::new(row[2], 0.0) * y + row[1]) * y + row[0];
        let m = (row[2].abs() * ay + row[1].abs()) * ay + row[0].abs();
        v = v * x + r;
        mag = mag * ax + m;
    }
    (v, mag)
}

/// |value| / Σ|terms| of one polynomial.
#[inline]
fn rel(c: &Coeffs, x: C, y: C) -> f64 {
    let (v, m) = eval(c, x, y);
    if m > 0.0 { modulus(v) / m } else { modulus(v) }
}

/// Value and partial derivatives (∂/∂x, ∂/∂y).
fn eval_grad(c: &Coeffs, x: C, y: C) -> (C, C, C) {
    let xs = [C::new(1.0, 0.0), x, x * x];
    let ys = [C::new(1.0, 0.0), y, y * y];
    let mut v = C::new(0.0, 0.0);
    let mut dx = C::new(0.0, 0.0);
    let mut dy = C::new(0.0, 0.0);
    for i in 0..3 {
        for j in 0..3 {
            let k = c[i][j];
            v += xs[i] * ys[j] * k;
            if i > 0 {
                dx += xs[i - 1] * ys[j] * (k * i as f64);
            }
            if j > 0 {
                dy += xs[i] * ys[j - 1] * (k * j as f64);
            }
        }
    }
    (v, dx, dy)
}

fn rel_residual(p: &Coeffs, q: &Coeffs, x: C, y: C) -> f64 {
    rel(p, x, y).max(rel(q, x, y))
}

/// Principal square root by the algebraic formula (no `atan2`, no `hypot`).
#[inline]
fn csqrt(z: C) -> C {
    let m = modulus(z);
    let re = (0.5 * (m + z.re)).max(0.0).sqrt();
    let im = (0.5 * (m - z.re)).max(0.0).sqrt();
    C::new(re, if z.im < 0.0 { -im } else { im })
}

/// Roots of a + b y + c y² (complex coefficients), stably; a root at infinity is omitted.
/// Returns the roots and how many there are.
fn quadratic_roots(a: C, b: C, c: C) -> ([C; 2], usize) {
    let zero = C::new(0.0, 0.0);
    let scale = l1(a).max(l1(b)).max(l1(c));
    if scale == 0.0 {
        return ([zero; 2], 0);
    }
    let tiny = 1e-14 * scale;
    if l1(c) <= tiny {
        return if l1(b) > tiny {
            ([-a / b, zero], 1)
        } else {
            ([zero; 2], 0)
        };
    }
    let disc = csqrt(b * b - c * a * 4.0);
    // q = −(b + s√disc)/2 with the sign that avoids cancellation.
    let qq = if (b.conj() * disc).re >= 0.0 {
        -(b + disc) * 0.5
    } else {
        -(b - disc) * 0.5
    };
    if l1(qq) > tiny {
        ([qq / c, a / qq], 2)
    } else {
        ([qq / c, zero], 1)
    }
}

/// Newton on (p, q) from (x, y), until the step is at round-off (the eigenvalues are already
/// accurate, so this takes one or two steps at a simple root); stops rather than wander if a
/// step is large. The relative residual is evaluated once, at the end.
fn polish(p: &Coeffs, q: &Coeffs, mut x: C, mut y: C) -> RawRoot {
    for _ in 0..5 {
        let (vp, px, py) = eval_grad(p, x, y);
        let (vq, qx, qy) = eval_grad(q, x, y);
        let det = px * qy - py * qx;
        if det == C::new(0.0, 0.0) || !det.is_finite() {
            break;
        }
        let dx = (vp * qy - vq * py) / det;
        let dy = (px * vq - qx * vp) / det;
        let size = 1.0 + l1(x).max(l1(y));
        let step = l1(dx).max(l1(dy));
        if !step.is_finite() || step > 0.1 * size {
            break;
        }
        x -= dx;
        y -= dy;
        if step <= 1e-15 * size {
            break;
        }
    }
    RawRoot {
        x,
        y,
        residual: rel_residual(p, q, x, y),
    }
}

type M4 = SMatrix<f64, 4, 4>;
type M8 = SMatrix<f64, 8, 8>;

/// Sylvester blocks S0, S1, S2 of p, q as quadratics in y with coefficients quadratic in x.
fn sylvester(p: &Coeffs, q: &Coeffs) -> [M4; 3] {
    let mut s = [M4::zeros(); 3];
    for (k, sk) in s.iter_mut().enumerate() {
        // Row layout against [y³, y², y, 1]: (P2, P1, P0, 0), (0, P2, P1, P0), same for Q.
        for (r, c, shift) in [(p, 0usize, 0usize), (p, 1, 1), (q, 2, 0), (q, 3, 1)] {
            for j in 0..3 {
                sk[(c, shift + (2 - j))] = r[k][j];
            }
        }
    }
    s
}

/// x-values of the roots from the companion pencil of the Sylvester matrix (8×8, shift and
/// invert), and the number of eigenvalues at x = ∞. The reference method.
fn x_roots_pencil(p: &Coeffs, q: &Coeffs) -> (Vec<C>, usize) {
    let [s0, s1, s2] = sylvester(p, q);
    let mut a = M8::zeros();
    let mut b = M8::zeros();
    for i in 0..4 {
        a[(i, i + 4)] = 1.0;
        b[(i, i)] = 1.0;
        for j in 0..4 {
            a[(i + 4, j)] = -s0[(i, j)];
            a[(i + 4, j + 4)] = -s1[(i, j)];
            b[(i + 4, j + 4)] = s2[(i, j)];
        }
    }
    // Shifts away from the physical roots (which lie near 0 … 1 in the scaled unknowns).
    for sigma in [-0.618_033_988_749_895, 1.324_717_957_244_746, -2.5] {
        let lu = (a - b * sigma).lu();
        let Some(m) = lu.solve(&b) else { continue };
        if !m.iter().all(|v| v.is_finite()) {
            continue;
        }
        let mus: SVector<C, 8> = m.complex_eigenvalues();
        let mu_max = mus.iter().map(|m| m.norm()).fold(0.0, f64::max);
        let mut xs = Vec::with_capacity(8);
        let mut at_infinity = 0;
        for mu in mus.iter() {
            if mu.norm() <= 1e-10 * mu_max {
                at_infinity += 1;
            } else {
                xs.push(C::new(sigma, 0.0) + mu.inv());
            }
        }
        return (xs, at_infinity);
    }
    (Vec::new(), 8)
}

/// The resultant R(x) = det S(x) = (a2 b0 − a0 b2)² − (a2 b1 − a1 b2)(a1 b0 − a0 b1), where
/// p = Σ a_j(x) y^j and q = Σ b_j(x) y^j, made monic: its degree (a leading coefficient within
/// its rounding error is zero) and the roots at infinity that degree leaves.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Resultant {
    /// R / (its leading coefficient), lowest degree first, `deg` of them (the leading 1 omitted).
    pub(crate) monic: [f64; 8],
    /// The degree of R.
    pub(crate) deg: usize,
    /// 8 − `deg`.
    pub(crate) at_infinity: usize,
}

/// The [`Resultant`] of p and q in y.
pub(crate) fn resultant(p: &Coeffs, q: &Coeffs) -> Resultant {
    let col = |c: &Coeffs, j: usize| [c[0][j], c[1][j], c[2][j]];
    let (a0, a1, a2) = (col(p, 0), col(p, 1), col(p, 2));
    let (b0, b1, b2) = (col(q, 0), col(q, 1), col(q, 2));
    // Each coefficient with a bound on its rounding error, carried through the products as
    // the same products of absolute values. When p or q is structurally linear in y (a
    // perfect square replaced by its root), the resultant of the true degrees is used: the
    // formal (2, 2) one would carry the extraneous factor b2(x) or a2(x).
    let linear = |c: &[f64; 3]| c.iter().all(|&v| v == 0.0);
    let (pl, ql) = (linear(&a2), linear(&b2));
    let prod = |u: &[f64; 3], v: &[f64; 3], w: &[f64; 3]| {
        let (mut uv, mut uvw) = ([0.0; 5], [0.0; 9]);
        poly_mul(u, v, &mut uv);
        poly_mul(&uv[..], w, &mut uvw[..7]);
        let (mut ua, mut uva) = ([0.0; 5], [0.0; 9]);
        poly_mul(&u.map(f64::abs), &v.map(f64::abs), &mut ua);
        poly_mul(&ua[..], &w.map(f64::abs), &mut uva[..7]);
        (uvw, uva)
    };
    let mut res = [0.0; 9];
    let mut bound = [0.0; 9];
    let mut accumulate = |sign: f64, (v, m): ([f64; 9], [f64; 9])| {
        for k in 0..9 {
            res[k] += sign * v[k];
            bound[k] += 32.0 * f64::EPSILON * m[k];
        }
    };
    match (pl, ql) {
        (true, true) => {
            // Res(a0 + a1 y, b0 + b1 y) = a0 b1 − a1 b0.
            let one = [1.0, 0.0, 0.0];
            accumulate(1.0, prod(&a0, &b1, &one));
            accumulate(-1.0, prod(&a1, &b0, &one));
        }
        (true, false) | (false, true) => {
            // Res(a0 + a1 y, b0 + b1 y + b2 y²) = b0 a1² − b1 a0 a1 + b2 a0².
            let ((l0, l1), (q0, q1, q2)) = if pl {
                ((a0, a1), (b0, b1, b2))
            } else {
                ((b0, b1), (a0, a1, a2))
            };
            accumulate(1.0, prod(&q0, &l1, &l1));
            accumulate(-1.0, prod(&q1, &l0, &l1));
            accumulate(1.0, prod(&q2, &l0, &l0));
        }
        (false, false) => {
            // (a2 b0 − a0 b2)² − (a2 b1 − a1 b2)(a1 b0 − a0 b1)
            let (r, msq, mpr) =
                crate::numeric::quadratic_resultant([&a0, &a1, &a2], [&b0, &b1, &b2]);
            for k in 0..9 {
                res[k] = r[k];
                bound[k] = 32.0 * f64::EPSILON * msq[k] + 32.0 * f64::EPSILON * mpr[k];
            }
        }
    }
    // Degree: a leading coefficient within its own rounding error is zero (a root at infinity).
    let mut deg = 8;
    while deg > 0 && res[deg].abs() <= bound[deg] {
        deg -= 1;
    }
    let mut monic = [0.0; 8];
    for k in 0..deg {
        monic[k] = res[k] / res[deg];
    }
    Resultant {
        monic,
        deg,
        at_infinity: 8 - deg,
    }
}

/// The eigenvalues of the companion matrix of the monic x^n + c[n−1] x^(n−1) + … + c[0]
/// (n ≥ 1) into `wr`, `wi`, by balancing and the Francis QR iteration: how many, or `None` if
/// the iteration does not converge.
pub(crate) fn companion_eigenvalues(
    c: &[f64],
    wr: &mut [f64; 8],
    wi: &mut [f64; 8],
) -> Option<usize> {
    let mut h = crate::numeric::hessenberg::Hessenberg::companion(c);
    h.balance();
    h.eigenvalues(wr, wi)
}

/// x-values of the roots as eigenvalues of the companion matrix of the [`resultant`]. The
/// companion matrix is already upper Hessenberg, so balancing and the Francis QR iteration
/// apply directly: no LU, no Hessenberg reduction, no allocation.
fn x_roots_resultant(p: &Coeffs, q: &Coeffs) -> Option<([C; 8], usize, usize)> {
    let Resultant {
        monic,
        deg,
        at_infinity,
    } = resultant(p, q);
    let mut xs = [C::new(0.0, 0.0); 8];
    if deg == 0 {
        return Some((xs, 0, at_infinity));
    }
    let (mut wr, mut wi) = ([0.0; 8], [0.0; 8]);
    let n = companion_eigenvalues(&monic[..deg], &mut wr, &mut wi)?;
    for k in 0..n {
        xs[k] = C::new(wr[k], wi[k]);
    }
    Some((xs, n, at_infinity))
}

/// All finite roots of p = q = 0 (each of bidegree ≤ (2, 2)), refined, and the count at ∞:
/// x from the eigenvalues of the resultant's companion matrix (falling back to the 8×8 pencil
/// if the QR iteration fails), then y and refinement as described in the module docs.
pub fn solve(p: &Coeffs, q: &Coeffs) -> RawRoots {
    match x_roots_resultant(p, q) {
        Some((xs, n, at_infinity)) => assign_y(p, q, &xs[..n], at_infinity, false),
        None => solve_pencil(p, q),
    }
}

/// Every finite eigenvalue with its best y, *without* the residual test that [`solve`] uses to
/// tell roots from misplaced eigenvalues at infinity: starting points for a caller that refines
/// them on other (e.g. unsquared) equations and judges them there. Near the start of sliding
/// the roots are nearly double and their coefficients tiny, so that test is not meaningful.
pub fn candidates(p: &Coeffs, q: &Coeffs) -> Vec<RawRoot> {
    match x_roots_resultant(p, q) {
        Some((xs, n, at_infinity)) => assign_y(p, q, &xs[..n], at_infinity, true).roots,
        None => {
            let (xs, at_infinity) = x_roots_pencil(p, q);
            assign_y(p, q, &xs, at_infinity, true).roots
        }
    }
}

/// The same by the 8×8 companion pencil of the Sylvester matrix (slower; better conditioned
/// for clustered roots). Kept as the reference the fast path is tested against.
pub fn solve_pencil(p: &Coeffs, q: &Coeffs) -> RawRoots {
    let (xs, at_infinity) = x_roots_pencil(p, q);
    assign_y(p, q, &xs, at_infinity, false)
}

/// For each x, the y that makes it a common root, then Newton refinement of (x, y).
fn assign_y(p: &Coeffs, q: &Coeffs, xs: &[C], at_infinity: usize, keep_all: bool) -> RawRoots {
    assign_y_fixed(p, q, xs, at_infinity, keep_all).into()
}

/// [`assign_y_fixed`] where no two x are within 10⁻⁶ of each other (as certified roots are):
/// y the common root of p(x, ·) and q(x, ·), y = −c20(x)/c21(x) with c20 = a2 b0 − a0 b2 and
/// c21 = a2 b1 − a1 b2 (q's y² times p less p's times q is linear in y; [`common_y`]), refined
/// by one Newton step on p(x, ·). Kept on [`assign_y_fixed`]'s terms: as it is where its
/// relative residual is at most 10⁻¹², else polished by Newton on (p, q) and kept if that
/// brings it below 10⁻⁶ onto no root already found. `None` as soon as a root is not so kept
/// (c21 near zero: both quadratics alike at x; y large; a root that does not polish), and the
/// caller takes [`assign_y_fixed`], which also decides what is at infinity.
pub(crate) fn assign_y_distinct(
    p: &Coeffs,
    q: &Coeffs,
    xs: &[C],
    at_infinity: usize,
) -> Option<FixedRoots> {
    let mut roots = FixedRoots::new(at_infinity);
    for (k, &x) in xs.iter().enumerate() {
        // The second of a conjugate pair: the first's root, conjugate (p and q are real; the
        // first may have been polished off its x).
        if k > 0 && x.im != 0.0 && x == xs[k - 1].conj() {
            let r = roots.roots[roots.len - 1];
            roots.push(RawRoot {
                x: r.x.conj(),
                y: r.y.conj(),
                residual: r.residual,
            });
            continue;
        }
        // A real x has a real y: real arithmetic.
        let (y, residual) = if x.im == 0.0 {
            let (y, r) = common_y(p, q, x.re);
            (C::new(y, 0.0), r)
        } else {
            common_y(p, q, x)
        };
        let r = if residual <= 1e-12 {
            RawRoot { x, y, residual }
        } else if residual < 1e-6 {
            // Not yet at round-off (x carries its eigenvalue's error): Newton on (p, q), as
            // `assign_y_fixed` polishes its best candidate.
            polish(p, q, x, y)
        } else {
            return None;
        };
        // Kept on `assign_y_fixed`'s terms.
        if r.residual.is_nan() || r.residual >= 1e-6 || lands_on(roots.roots(), &r) {
            return None;
        }
        roots.push(r);
    }
    Some(roots)
}

/// Whether the root `r` lands on one of `found`: within 10⁻⁶ of it in x and y, relative to
/// 1 + max(|x|, |y|) — a root found again from another x, extraneous. (A bound by |re| + |im|
/// first, which the moduli can only be below, spares most of the moduli.)
fn lands_on(found: &[RawRoot], r: &RawRoot) -> bool {
    let loose = std::f64::consts::SQRT_2 * 1e-6 * (1.0 + l1(r.x).max(l1(r.y)));
    found.iter().any(|o| {
        l1(o.x - r.x) < loose
            && l1(o.y - r.y) < loose
            && (o.x - r.x).norm().max((o.y - r.y).norm())
                < 1e-6 * (1.0 + r.x.norm().max(r.y.norm()))
    })
}

/// A real or complex number, for [`common_y`].
trait Scalar:
    Copy
    + std::ops::Add<Output = Self>
    + std::ops::Sub<Output = Self>
    + std::ops::Mul<Output = Self>
    + std::ops::Div<Output = Self>
    + std::ops::Neg<Output = Self>
    + std::ops::Add<f64, Output = Self>
    + std::ops::Mul<f64, Output = Self>
{
    fn modulus(self) -> f64;
}

impl Scalar for f64 {
    #[inline]
    fn modulus(self) -> f64 {
        self.abs()
    }
}

impl Scalar for C {
    #[inline]
    fn modulus(self) -> f64 {
        modulus(self)
    }
}

/// The common root y of p(x, ·) and q(x, ·) at x and its relative residual (as [`rel_residual`]):
/// with P_j, Q_j the coefficients of y^j at x, y = −(P2 Q0 − P0 Q2)/(P2 Q1 − P1 Q2), then one
/// Newton step on p(x, ·).
#[inline]
fn common_y<T: Scalar>(p: &Coeffs, q: &Coeffs, x: T) -> (T, f64) {
    let ax = x.modulus();
    let at = |c: &Coeffs, j: usize| (x * c[2][j] + c[1][j]) * x + c[0][j];
    let (p0, p1, p2) = (at(p, 0), at(p, 1), at(p, 2));
    let (q0, q1, q2) = (at(q, 0), at(q, 1), at(q, 2));
    let y = -(p2 * q0 - p0 * q2) / (p2 * q1 - p1 * q2);
    let y = y - ((p2 * y + p1) * y + p0) / (p2 * y * 2.0 + p1);
    let ay = y.modulus();
    // |value| / Σ|terms| of c at (x, y), its terms' sizes from |x| and |y|.
    let rel = |c: &Coeffs, v: T| {
        let size = |j: usize| (c[2][j].abs() * ax + c[1][j].abs()) * ax + c[0][j].abs();
        let m = (size(2) * ay + size(1)) * ay + size(0);
        if m > 0.0 {
            v.modulus() / m
        } else {
            v.modulus()
        }
    };
    let vp = (p2 * y + p1) * y + p0;
    let vq = (q2 * y + q1) * y + q0;
    // A NaN on either side stays NaN (f64::max would drop it).
    let (rp, rq) = (rel(p, vp), rel(q, vq));
    (y, if rp >= rq || rp.is_nan() { rp } else { rq })
}

/// [`assign_y`] into fixed storage (at most one root per x, and at most 8 x).
pub(crate) fn assign_y_fixed(
    p: &Coeffs,
    q: &Coeffs,
    xs: &[C],
    at_infinity: usize,
    keep_all: bool,
) -> FixedRoots {
    // Eigenvalues that coincide may belong to distinct roots sharing one x (then each takes a
    // different y) or to one multiple root (then they share y).
    let mut roots = FixedRoots::new(at_infinity);
    let mut used = [false; 8];
    for i in 0..xs.len() {
        if used[i] {
            continue;
        }
        let mut members = [0usize; 8];
        let mut nm = 0;
        for k in i..xs.len() {
            if !used[k] && l1(xs[k] - xs[i]) <= 1e-6 * (1.0 + l1(xs[i])) {
                members[nm] = k;
                nm += 1;
            }
        }
        let cluster = &members[..nm];
        let x = cluster.iter().map(|&k| xs[k]).sum::<C>() / cluster.len() as f64;
        // Candidate y from both quadratics at this x, best first, distinct ones only.
        let coef = |c: &Coeffs, j: usize| C::new(c[0][j], 0.0) + x * c[1][j] + x * x * c[2][j];
        // A root of p(x, ·) is judged by q, a root of q(x, ·) by p (its own equation holds by
        // construction). Fixed-size storage: no allocation per root.
        let mut cands = [(f64::INFINITY, C::new(0.0, 0.0)); 4];
        let mut nc = 0;
        for (own, other) in [(p, q), (q, p)] {
            let (ys, n) = quadratic_roots(coef(own, 0), coef(own, 1), coef(own, 2));
            for &y in &ys[..n] {
                if y.is_finite() {
                    cands[nc] = (rel(other, x, y), y);
                    nc += 1;
                }
            }
        }
        let cands = &mut cands[..nc];
        cands.sort_unstable_by(|a, b| a.0.total_cmp(&b.0));
        let mut distinct = [(f64::INFINITY, C::new(0.0, 0.0)); 4];
        let mut nd = 0;
        for &c in cands.iter() {
            if !distinct[..nd]
                .iter()
                .any(|d| l1(d.1 - c.1) <= 1e-6 * (1.0 + l1(c.1)))
            {
                distinct[nd] = c;
                nd += 1;
            }
        }
        let distinct = &distinct[..nd];
        let first_of_cluster = roots.len;
        for (m, &k) in cluster.iter().enumerate() {
            used[k] = true;
            // The m-th distinct candidate if it is itself nearly a root, else the best one.
            let pick = match distinct.get(m) {
                Some(&(r, y)) if m > 0 && r < 1e-6 => Some((r, y)),
                _ => distinct.first().copied(),
            };
            let xk = if cluster.len() > 1 { x } else { xs[k] };
            // Already near round-off (the usual case for a simple root): no Newton step needed.
            let refined = pick.map(|(r, y)| {
                // 1e-12: the tracker, not this report, gives the selected pose its last digits.
                let r = if r <= 1e-12 {
                    rel_residual(p, q, xk, y)
                } else {
                    r
                };
                if r <= 1e-12 && cluster.len() == 1 {
                    RawRoot {
                        x: xk,
                        y,
                        residual: r,
                    }
                } else {
                    polish(p, q, xk, y)
                }
            });
            match refined {
                // A root that does not polish is an eigenvalue at infinity that rounding moved
                // to a large finite value (or y at infinity); one that polishes onto a root
                // already found from another x is extraneous too.
                // (A multiple root polishes only to about the square root of round-off.)
                Some(r) if keep_all => roots.push(r),
                Some(r) if r.residual < 1e-6 && !lands_on(&roots.roots[..first_of_cluster], &r) => {
                    roots.push(r)
                }
                _ => roots.at_infinity += 1,
            }
        }
    }
    roots
}

#[cfg(test)]
mod tests {
    use super::*;

    /// (x − a)(y − b)-type systems with known roots.
    fn product(xr: [f64; 2], yr: [f64; 2]) -> Coeffs {
        // (x − x0)(x − x1)·1 + 0·y … as a bidegree (2,0) polynomial.
        let mut c = [[0.0; 3]; 3];
        c[0][0] = xr[0] * xr[1];
        c[1][0] = -(xr[0] + xr[1]);
        c[2][0] = 1.0;
        let _ = yr;
        c
    }

    #[test]
    fn four_real_roots_of_a_decoupled_system() {
        // p = (x − 1)(x − 2), q = (y + 1)(y − 3): roots {1, 2} × {−1, 3}.
        let p = product([1.0, 2.0], [0.0, 0.0]);
        let mut q = [[0.0; 3]; 3];
        q[0][0] = -3.0;
        q[0][1] = -2.0;
        q[0][2] = 1.0;
        let r = solve(&p, &q);
        assert_eq!(r.roots.len(), 4);
        for (xs, ys) in [(1.0, -1.0), (1.0, 3.0), (2.0, -1.0), (2.0, 3.0)] {
            assert!(
                r.roots
                    .iter()
                    .any(|t| (t.x - C::new(xs, 0.0)).norm() < 1e-12
                        && (t.y - C::new(ys, 0.0)).norm() < 1e-12),
                "missing ({xs}, {ys}) in {:?}",
                r.roots
            );
        }
        assert_eq!(r.at_infinity, 4);
    }

    #[test]
    fn full_bidegree_system_has_eight_roots_with_small_residuals() {
        let p = [[1.0, -2.0, 0.5], [0.3, 1.1, -0.7], [-1.2, 0.4, 0.9]];
        let q = [[-0.5, 0.8, 1.3], [1.7, -0.2, 0.6], [0.1, -1.4, 0.35]];
        let r = solve(&p, &q);
        assert_eq!(r.roots.len() + r.at_infinity, 8);
        assert_eq!(r.roots.len(), 8);
        for t in &r.roots {
            assert!(t.residual < 1e-13, "{t:?}");
        }
    }

    #[test]
    fn roots_at_distinct_x_are_the_general_recoverys_and_a_polished_pair_stays_conjugate() {
        let p = [[1.0, -2.0, 0.5], [0.3, 1.1, -0.7], [-1.2, 0.4, 0.9]];
        let q = [[-0.5, 0.8, 1.3], [1.7, -0.2, 0.6], [0.1, -1.4, 0.35]];
        let r = resultant(&p, &q);
        let (mut wr, mut wi) = ([0.0; 8], [0.0; 8]);
        let n = companion_eigenvalues(&r.monic[..r.deg], &mut wr, &mut wi).unwrap();
        let xs: Vec<C> = (0..n).map(|k| C::new(wr[k], wi[k])).collect();
        assert!(xs.iter().any(|x| x.im != 0.0), "no complex pair: {xs:?}");
        // At the eigenvalues: the roots of the general recovery, to round-off.
        let fast = assign_y_distinct(&p, &q, &xs, r.at_infinity).unwrap();
        let general = assign_y_fixed(&p, &q, &xs, r.at_infinity, false);
        assert_eq!(fast.at_infinity, general.at_infinity);
        assert_eq!(fast.roots().len(), general.roots().len());
        for (f, g) in fast.roots().iter().zip(general.roots()) {
            assert!(
                (f.x - g.x).norm() + (f.y - g.y).norm() < 1e-12,
                "{f:?} {g:?}"
            );
        }
        // Every x moved by 10⁻⁹ (pairs kept conjugate): each root is polished, the second of a
        // pair the conjugate of the first as polished, and each residual is the one at the
        // root reported.
        let moved: Vec<C> = xs.iter().map(|x| C::new(x.re + 1e-9, x.im)).collect();
        let fast = assign_y_distinct(&p, &q, &moved, r.at_infinity).unwrap();
        assert_eq!(fast.roots().len(), n);
        for (k, root) in fast.roots().iter().enumerate() {
            assert!(root.residual <= 1e-12, "{root:?}");
            let again = rel_residual(&p, &q, root.x, root.y);
            assert!(again <= 1e-12, "{root:?}: {again:e} where it is");
            if k > 0 && moved[k] == moved[k - 1].conj() {
                let first = fast.roots()[k - 1];
                assert_eq!((root.x, root.y), (first.x.conj(), first.y.conj()));
            }
        }
    }

    #[test]
    fn stable_quadratic_handles_vanishing_leading_coefficient() {
        let (r, n) = quadratic_roots(C::new(2.0, 0.0), C::new(-1.0, 0.0), C::new(0.0, 0.0));
        assert_eq!(n, 1);
        assert!((r[0] - C::new(2.0, 0.0)).norm() < 1e-15);
        // y² − 1e8 y + 1: roots 1e8 and 1e-8, both to full relative precision.
        let (r, n) = quadratic_roots(C::new(1.0, 0.0), C::new(-1e8, 0.0), C::new(1.0, 0.0));
        assert_eq!(n, 2);
        let small = r.iter().map(|v| v.norm()).fold(f64::INFINITY, f64::min);
        assert!((small - 1e-8).abs() < 1e-22);
    }
}

#[cfg(test)]
mod agreement {
    use super::*;
    use proptest::prelude::*;

    fn coeffs() -> impl Strategy<Value = Coeffs> {
        proptest::array::uniform3(proptest::array::uniform3(-2.0..2.0f64))
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(500))]

        /// The fast path (resultant companion + Hessenberg QR) and the reference (8×8 pencil)
        /// find the same roots.
        #[test]
        fn resultant_and_pencil_find_the_same_roots(p in coeffs(), q in coeffs()) {
            let fast = solve(&p, &q);
            let reference = solve_pencil(&p, &q);
            prop_assert_eq!(fast.roots.len() + fast.at_infinity, 8);
            let good = |r: &RawRoot| r.residual < 1e-12 && r.x.norm() < 1e4 && r.y.norm() < 1e4;
            for r in reference.roots.iter().filter(|r| good(r)) {
                prop_assert!(
                    fast.roots.iter().any(|f| (f.x - r.x).norm().max((f.y - r.y).norm())
                        < 1e-6 * (1.0 + r.x.norm().max(r.y.norm()))),
                    "reference root {:?} missing from {:?}", r, fast.roots
                );
            }
        }
    }
}
