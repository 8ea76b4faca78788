//! The paper's frictional reactions: eqs. (22)–(24) with the frictionless proportions (28).
//!
//! Unknowns: the magnitude j of N0 and the directions φ0, φ1, φ2 of the three shear forces in
//! their contact planes (N_i = j m_i n̂_i, S_i = μ_i j m_i (cos φ_i t1_i + sin φ_i t2_i), with t1_i
//! along the projection of i' on plane i). Equations: the four "free" components of (23) — the
//! force along j' and k' and the moment about i' and k'; the force along i' and the moment about
//! j' then give the accelerations.
//!
//! Every contact term is proportional to j, so j drops out of the two moment equations and of
//! the ratio of the two force equations: three equations *affine* in (cos φ_i, sin φ_i), plus
//! the three unit circles. Fixing φ0 leaves a line in (cos φ1, sin φ1, cos φ2, sin φ2); meeting
//! the two circles is the resultant of two quadratics, a trigonometric polynomial of degree 4
//! in φ0 — a polynomial of degree 8 in t = tan((φ0 − δ)/2). Its real roots, from the eigenvalues
//! of the companion matrix, are *all* the solutions (at most 8); each is refined by Newton's
//! method on the four equations. `derivations/07-reactions-and-route.md` has the details and what we
//! measured; we choose among the solutions by the stated rule in [`select`].

// The three contacts are handled by index into parallel arrays (normals, tangents, arms).
#![allow(clippy::needless_range_loop)]

use super::ContactGeometry;
use super::loads::Applied;
use super::statics::ratios;
use crate::model::Block;
use crate::model::{ContactStrength, ContactStrengths};
use crate::numeric::{poly_mul, poly_roots, wrap_angle as wrap};
use nalgebra::{Matrix3, Matrix3x4, SMatrix, Vector3, Vector4};

/// One solution of the frictional system, with the accelerations it implies.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Reaction {
    /// The normal reactions (N), along each plane's upward normal.
    pub normal: [Vector3<f64>; 3],
    /// The shear reactions (N), in each plane.
    pub shear: [Vector3<f64>; 3],
    /// Direction of each shear force in its plane (rad): 0 along the projection of +i', π
    /// against it.
    pub angles: [f64; 3],
    /// CM acceleration along i' (m/s²), eq. (23).
    pub accel: f64,
    /// Angular acceleration about j' (rad/s²), eq. (23).
    pub ang_accel: f64,
}

/// Why the paper's reactions cannot be had.
#[derive(Debug, Clone, Copy, PartialEq, Eq, thiserror::Error)]
pub enum ReactionsError {
    /// A frictionless normal reaction (25)–(27) is not positive: that contact lifts off.
    #[error("contact {0} lifts off (its frictionless normal reaction is not positive)")]
    LiftOff(usize),
}

/// Offset of the half-angle parameter, so that no solution sits at t = ∞ except by accident.
const DELTA: f64 = std::f64::consts::FRAC_PI_4 + 0.1;

/// The 4-vector (v·j', v·k', (r×v)·i', (r×v)·k') of a force v applied at r.
fn g(geom: &ContactGeometry, r: &Vector3<f64>, v: &Vector3<f64>) -> Vector4<f64> {
    let f = &geom.frame;
    let m = r.cross(v);
    Vector4::new(v.dot(&f.j), v.dot(&f.k), m.dot(&f.i), m.dot(&f.k))
}

/// (sin x, cos x). For |x| ≤ 0.02 — the corrections of Newton's method once it is close —
/// by the Taylor series to x⁹ (truncation below 1e-20, i.e. exact in f64) instead of a libm call.
fn sin_cos_step(x: f64) -> (f64, f64) {
    if x.abs() <= 0.02 {
        let x2 = x * x;
        let s = x * (1.0 - x2 / 6.0 * (1.0 - x2 / 20.0 * (1.0 - x2 / 42.0 * (1.0 - x2 / 72.0))));
        let c = 1.0 - x2 / 2.0 * (1.0 - x2 / 12.0 * (1.0 - x2 / 30.0 * (1.0 - x2 / 56.0)));
        (s, c)
    } else {
        x.sin_cos()
    }
}

/// A point of the frictional system: N0 = j and the shear directions φ with their (sin, cos)
/// (kept alongside: Newton rotates them by its updates instead of recomputing them).
#[derive(Debug, Clone, Copy)]
struct Point {
    j: f64,
    phi: [f64; 3],
    sc: [(f64, f64); 3],
}

impl Point {
    fn new(j: f64, phi: [f64; 3]) -> Self {
        Point {
            j,
            phi,
            sc: phi.map(f64::sin_cos),
        }
    }
}

/// The frictional system at one pose, with per-contact friction coefficients μ_i.
struct System {
    g0: Vector4<f64>,
    a: [Vector4<f64>; 3],
    b: [Vector4<f64>; 3],
    /// Right-hand side of j·(G0 + Σ …) = w.
    w: Vector4<f64>,
    /// The tangents (t1, t2) of each contact ([`ContactGeometry::tangents`]).
    tangents: [(Vector3<f64>, Vector3<f64>); 3],
    /// The reduced system in φ alone (see [`Reduced`]).
    reduced: Reduced,
}

/// j·h(φ) = w says h(φ) ∥ w: with P (3×4) an orthonormal basis of w⊥ (rows 2–4 of the
/// Householder reflection that maps w onto the first axis), three equations P·h(φ) = 0 in the
/// three angles alone, and then j = |w| / (ŵ·h). Newton on these needs a 3×3 solve per
/// iteration instead of a 4×4 one.
#[derive(Debug, Clone, Copy)]
struct Reduced {
    g0: Vector3<f64>,
    a: [Vector3<f64>; 3],
    b: [Vector3<f64>; 3],
    /// ŵ·G0, ŵ·A_i, ŵ·B_i and |w|.
    wg0: f64,
    wa: [f64; 3],
    wb: [f64; 3],
    w_norm: f64,
}

impl Reduced {
    fn new(
        g0: &Vector4<f64>,
        a: &[Vector4<f64>; 3],
        b: &[Vector4<f64>; 3],
        w: &Vector4<f64>,
    ) -> Self {
        let w_norm = w.norm();
        let w_hat = if w_norm > 0.0 {
            w / w_norm
        } else {
            Vector4::x()
        };
        // Householder v = ŵ + sign(ŵ0) e0: H = I − 2vvᵀ/vᵀv maps ŵ to ∓e0; rows 1–3 of H span w⊥.
        let mut v = w_hat;
        v[0] += 1f64.copysign(w_hat[0]);
        let vv = v.norm_squared();
        let project = |x: &Vector4<f64>| {
            let f = 2.0 * v.dot(x) / vv;
            Vector3::new(x[1] - f * v[1], x[2] - f * v[2], x[3] - f * v[3])
        };
        Reduced {
            g0: project(g0),
            a: a.each_ref().map(project),
            b: b.each_ref().map(project),
            wg0: w_hat.dot(g0),
            wa: a.each_ref().map(|x| w_hat.dot(x)),
            wb: b.each_ref().map(|x| w_hat.dot(x)),
            w_norm,
        }
    }

    /// N0 = |w| / (ŵ·h(φ)) at the angles of `sc`.
    fn j(&self, sc: &[(f64, f64); 3]) -> f64 {
        let mut d = self.wg0;
        for i in 0..3 {
            d += self.wa[i] * sc[i].1 + self.wb[i] * sc[i].0;
        }
        self.w_norm / d
    }
}

impl System {
    fn new(geom: &ContactGeometry, applied: &Applied, m: &[f64; 3], mu: &[f64; 3]) -> Self {
        let mut g0 = Vector4::zeros();
        let mut a = [Vector4::zeros(); 3];
        let mut b = [Vector4::zeros(); 3];
        let tangents = [0, 1, 2].map(|i| geom.tangents(i));
        for i in 0..3 {
            let (t1, t2) = tangents[i];
            g0 += g(geom, &geom.r[i], &geom.n[i]) * m[i];
            a[i] = g(geom, &geom.r[i], &t1) * (mu[i] * m[i]);
            b[i] = g(geom, &geom.r[i], &t2) * (mu[i] * m[i]);
        }
        let f = &geom.frame;
        let loads = applied.total_force();
        let w = Vector4::new(
            -loads.dot(&f.j),
            -loads.dot(&f.k),
            -applied.total_moment().dot(&f.i),
            -applied.total_moment().dot(&f.k),
        );
        System {
            reduced: Reduced::new(&g0, &a, &b, &w),
            g0,
            a,
            b,
            w,
            tangents,
        }
    }

    /// h(φ) = G0 + Σ (cos φ_i A_i + sin φ_i B_i) from (sin φ_i, cos φ_i); the equations read
    /// j·h(φ) = w.
    fn h_sc(&self, sc: &[(f64, f64); 3]) -> Vector4<f64> {
        let mut h = self.g0;
        for i in 0..3 {
            h += self.a[i] * sc[i].1 + self.b[i] * sc[i].0;
        }
        h
    }

    /// Newton on the reduced equations P·h(φ) = 0 in (φ0, φ1, φ2) ([`Reduced`]), from the
    /// angles of `p` (its j is not used); then j = |w| / (ŵ·h). Stops when an update is at
    /// round-off, or below 1e-9 and ten times smaller than the one before (converging
    /// quadratically, so the error left is of order its square, 1e-18). Returns the point and
    /// the relative residual of the four equations j·h(φ) = w.
    fn polish(&self, mut p: Point) -> (Point, f64) {
        let r = &self.reduced;
        let mut last = f64::INFINITY;
        for _ in 0..8 {
            let mut f = r.g0;
            let mut cols = [Vector3::zeros(); 3];
            for i in 0..3 {
                let (s, c) = p.sc[i];
                f += r.a[i] * c + r.b[i] * s;
                cols[i] = r.b[i] * c - r.a[i] * s;
            }
            // Cramer's rule: dx = −J⁻¹ f.
            let det = cols[0].dot(&cols[1].cross(&cols[2]));
            if det == 0.0 || !det.is_finite() {
                break;
            }
            let dx = [
                -f.dot(&cols[1].cross(&cols[2])) / det,
                -cols[0].dot(&f.cross(&cols[2])) / det,
                -cols[0].dot(&cols[1].cross(&f)) / det,
            ];
            for i in 0..3 {
                p.phi[i] += dx[i];
                // Rotate (sin, cos) by the update rather than recompute them.
                let (s, c) = sin_cos_step(dx[i]);
                let (s0, c0) = p.sc[i];
                p.sc[i] = (s0 * c + c0 * s, c0 * c - s0 * s);
            }
            let step = dx[0].abs().max(dx[1].abs()).max(dx[2].abs());
            if step.is_nan() || step < 1e-13 || (step < 1e-9 && step < 0.1 * last) {
                break;
            }
            last = step;
        }
        p.j = r.j(&p.sc);
        let scale = self.w.amax().max(1e-300);
        let res = (self.h_sc(&p.sc) * p.j - self.w).amax() / scale;
        (p, res)
    }

    /// All solutions (j, φ) with j > 0: the affine equations in u = (c0, s0, c1, s1, c2, s2),
    /// solved along a line in u for φ0 = δ + 2 atan t ([`Parametrised`]); the two contact
    /// circles' resultant in t gives every candidate, each polished by Newton.
    fn solve(&self) -> Vec<Point> {
        let (m, rhs) = self.affine_rows();
        let Some(line) = Parametrised::new(&m, &rhs) else {
            return Vec::new();
        };
        let circles = [line.circle(0), line.circle(2)];
        // R = (a2 b0 − a0 b2)² − (a2 b1 − a1 b2)(a1 b0 − a0 b1).
        let [a, b] = &circles;
        let (res, _, _) =
            crate::numeric::quadratic_resultant([&a.c0, &a.c1, &[a.c2]], [&b.c0, &b.c1, &[b.c2]]);
        let Some(ts) = poly_roots(&res) else {
            return Vec::new();
        };
        let mut out: Vec<Point> = Vec::new();
        for (t, im) in ts {
            if im.abs() > 1e-6 * (1.0 + t.abs()) {
                continue;
            }
            let Some(p) = self.point_at(t, &line, &circles) else {
                continue;
            };
            if !out
                .iter()
                .any(|q| (0..3).all(|i| wrap(q.phi[i] - p.phi[i]).abs() < 1e-7))
            {
                out.push(p);
            }
        }
        out
    }

    /// The three affine equations M u = rhs in u = (c0, s0, c1, s1, c2, s2): the two of w's
    /// components 2 and 3, and the one that makes components 0 and 1 parallel to w's; each row
    /// scaled to a largest entry of 1.
    fn affine_rows(&self) -> (SMatrix<f64, 3, 6>, Vector3<f64>) {
        let (w0, w1) = (self.w[0], self.w[1]);
        let mut m = SMatrix::<f64, 3, 6>::zeros();
        let mut rhs = Vector3::zeros();
        for i in 0..3 {
            for (k, col) in [(2 * i, &self.a[i]), (2 * i + 1, &self.b[i])] {
                m[(0, k)] = col[2];
                m[(1, k)] = col[3];
                m[(2, k)] = col[0] * w1 - col[1] * w0;
            }
        }
        rhs[0] = -self.g0[2];
        rhs[1] = -self.g0[3];
        rhs[2] = self.g0[1] * w0 - self.g0[0] * w1;
        for r in 0..3 {
            let s = (0..6).map(|k| m[(r, k)].abs()).fold(0.0, f64::max);
            if s > 0.0 {
                for k in 0..6 {
                    m[(r, k)] /= s;
                }
                rhs[r] /= s;
            }
        }
        (m, rhs)
    }

    /// The point at a real root `t` of the circles' resultant: τ̂ from the first circle (the
    /// root that best satisfies the second), the angles from u, then Newton ([`Self::polish`]);
    /// `None` unless it converges to j > 0.
    fn point_at(&self, t: f64, line: &Parametrised, circles: &[Circle; 2]) -> Option<Point> {
        let ev = |c: &[f64]| c.iter().rev().fold(0.0, |acc, &k| acc * t + k);
        let [a, b] = circles;
        let w2 = 1.0 + t * t;
        let upt: [f64; 4] = line.up.map(|row| ev(&row));
        let (qa, qb, qc) = (a.c2, ev(&a.c1), ev(&a.c0));
        let disc = qb * qb - 4.0 * qa * qc;
        if disc < -1e-9 * (qb * qb + (4.0 * qa * qc).abs()) {
            return None;
        }
        let sq = disc.max(0.0).sqrt();
        let qq = -0.5 * (qb + sq.copysign(qb));
        let mut cands = vec![];
        if qa != 0.0 {
            cands.push(qq / qa);
        }
        if qq != 0.0 {
            cands.push(qc / qq);
        }
        let other = |tau: f64| (b.c2 * tau * tau + ev(&b.c1) * tau + ev(&b.c0)).abs();
        let tau = cands
            .into_iter()
            .min_by(|x, y| other(*x).total_cmp(&other(*y)))?;
        let u: [f64; 4] = [0, 1, 2, 3].map(|k| (upt[k] + tau * line.v[k]) / w2);
        let phi0 = DELTA + 2.0 * t.atan();
        let phi = [phi0, u[1].atan2(u[0]), u[3].atan2(u[2])];
        // Newton on the reduced equations, then j (N0) from the direction of w.
        let (mut p, residual) = self.polish(Point::new(0.0, phi));
        if !(residual < 1e-9 && p.j > 0.0) {
            return None;
        }
        p.phi = p.phi.map(wrap);
        Some(p)
    }
}

/// The solutions of the affine equations as a line in u' = (c1, s1, c2, s2) for each φ0 =
/// δ + 2 atan t, multiplied by (1 + t²): Û(t) + τ̂ v.
struct Parametrised {
    /// Û_p(t) = Q (rhs (1+t²) − M0 (ĉ0, ŝ0)): four quadratics in t (coefficients from t⁰).
    up: [[f64; 3]; 4],
    /// The null vector of M' (unit).
    v: Vector4<f64>,
}

/// One contact's circle c1² + s1² = 1 (or c2² + s2² = 1) on the line, multiplied by (1 + t²)²:
/// c2 τ̂² + c1(t) τ̂ + c0(t) = 0.
struct Circle {
    c2: f64,
    c1: [f64; 3],
    c0: [f64; 5],
}

impl Parametrised {
    /// From the affine rows: the null vector of M' (the last four columns, 3×4) by signed 3×3
    /// minors and the min-norm inverse Q = M'ᵀ(M'M'ᵀ)⁻¹; `None` if M' is rank-deficient.
    fn new(m: &SMatrix<f64, 3, 6>, rhs: &Vector3<f64>) -> Option<Self> {
        let m0 = m.fixed_columns::<2>(0).into_owned();
        let mp: Matrix3x4<f64> = m.fixed_columns::<4>(2).into_owned();
        let minor = |skip: usize| {
            let cols: Vec<usize> = (0..4).filter(|&c| c != skip).collect();
            let sub = Matrix3::from_fn(|r, c| mp[(r, cols[c])]);
            sub.determinant()
        };
        let v = Vector4::new(minor(0), -minor(1), minor(2), -minor(3));
        let inv = (mp * mp.transpose()).try_inverse()?;
        if v.norm() < 1e-12 {
            return None;
        }
        let v = v.normalize();
        let q = mp.transpose() * inv;
        // ĉ0 = c0 (1+t²), ŝ0 = s0 (1+t²) with φ0 = δ + 2 atan t:
        // ĉ0 = cos δ (1 − t²) − 2 t sin δ, ŝ0 = sin δ (1 − t²) + 2 t cos δ.
        let (sd, cd) = DELTA.sin_cos();
        let c_hat = [cd, -2.0 * sd, -cd];
        let s_hat = [sd, 2.0 * cd, -sd];
        let one_t2 = [1.0, 0.0, 1.0];
        let qb = q * rhs;
        let qm = q * m0;
        let mut up = [[0.0; 3]; 4];
        for (k, row) in up.iter_mut().enumerate() {
            for d in 0..3 {
                row[d] = qb[k] * one_t2[d] - qm[(k, 0)] * c_hat[d] - qm[(k, 1)] * s_hat[d];
            }
        }
        Some(Parametrised { up, v })
    }

    /// The circle of the contact whose (c, s) are components k0, k0 + 1 of u':
    /// τ̂² |v|² + 2τ̂ (Û·v) + |Û|² − (1+t²)².
    fn circle(&self, k0: usize) -> Circle {
        let (up, v) = (&self.up, &self.v);
        let one_t2 = [1.0, 0.0, 1.0];
        let mut one_t2_sq = [0.0; 5];
        poly_mul(&one_t2, &one_t2, &mut one_t2_sq);
        let c2 = v[k0] * v[k0] + v[k0 + 1] * v[k0 + 1];
        let mut c1 = [0.0; 3];
        for d in 0..3 {
            c1[d] = 2.0 * (up[k0][d] * v[k0] + up[k0 + 1][d] * v[k0 + 1]);
        }
        let (mut s0, mut s1) = ([0.0; 5], [0.0; 5]);
        poly_mul(&up[k0], &up[k0], &mut s0);
        poly_mul(&up[k0 + 1], &up[k0 + 1], &mut s1);
        let mut c0 = [0.0; 5];
        for d in 0..5 {
            c0[d] = s0[d] + s1[d] - one_t2_sq[d];
        }
        Circle { c2, c1, c0 }
    }
}

/// The reaction at the point `p` (N0 = j, shear directions φ), with the tangents of `sys`.
fn reaction(
    geom: &ContactGeometry,
    applied: &Applied,
    block: &Block,
    m: &[f64; 3],
    mu: &[f64; 3],
    tangents: &[(Vector3<f64>, Vector3<f64>); 3],
    p: &Point,
) -> Reaction {
    let mut normal = [Vector3::zeros(); 3];
    let mut shear = [Vector3::zeros(); 3];
    let mut force = applied.total_force();
    let mut moment = applied.total_moment();
    for i in 0..3 {
        let (t1, t2) = tangents[i];
        normal[i] = geom.n[i] * (p.j * m[i]);
        shear[i] = (t1 * p.sc[i].1 + t2 * p.sc[i].0) * (mu[i] * p.j * m[i]);
        let total = normal[i] + shear[i];
        force += total;
        moment += geom.r[i].cross(&total);
    }
    Reaction {
        normal,
        shear,
        angles: p.phi.map(wrap),
        accel: force.dot(&geom.frame.i) / block.mass,
        ang_accel: moment.dot(&geom.frame.j) / block.inertia,
    }
}

/// The shared start of [`all_solutions`] and [`follow`]: lift-off from the frictionless
/// normals, the ratios (27), and — for a frictionless scene — the one reaction, with no friction
/// solve at all.
fn prologue(
    geom: &ContactGeometry,
    applied: &Applied,
    block: &Block,
    c: &[f64; 3],
    friction: &[ContactStrength],
) -> Result<([f64; 3], Option<Reaction>), ReactionsError> {
    if let Some(k) = (0..3).find(|&k| c[k] <= 0.0) {
        return Err(ReactionsError::LiftOff(k));
    }
    let m = ratios(c);
    let frictionless = friction.is_frictionless().then(|| {
        let none = [(Vector3::zeros(), Vector3::zeros()); 3];
        reaction(
            geom,
            applied,
            block,
            &m,
            &[0.0; 3],
            &none,
            &Point {
                j: c[0],
                phi: [0.0; 3],
                sc: [(0.0, 1.0); 3],
            },
        )
    });
    Ok((m, frictionless))
}

/// Per-contact friction coefficients at N0 = j.
fn mu_at(friction: &[ContactStrength], m: &[f64; 3], j: f64) -> [f64; 3] {
    [0, 1, 2].map(|i| friction.coefficient(i, j * m[i]))
}

/// For a stress-dependent criterion (Barton–Choubey) μ_i depends on j: iterate j to a fixed
/// point from `p`, following the solution. `None` if it is lost on the way.
fn settle(
    geom: &ContactGeometry,
    applied: &Applied,
    m: &[f64; 3],
    friction: &[ContactStrength],
    mut p: Point,
) -> Option<Point> {
    if !friction.is_stress_dependent() {
        return Some(p);
    }
    for _ in 0..60 {
        let sys = System::new(geom, applied, m, &mu_at(friction, m, p.j));
        let (q, res) = sys.polish(p);
        if !(res < 1e-9 && q.j > 0.0) {
            return None;
        }
        let done = (q.j - p.j).abs() <= 1e-12 * p.j;
        p = q;
        if done {
            break;
        }
    }
    Some(p)
}

/// The reaction of a settled solution, with the friction coefficients at its N0.
fn reaction_at(
    geom: &ContactGeometry,
    applied: &Applied,
    block: &Block,
    m: &[f64; 3],
    friction: &[ContactStrength],
    sys: &System,
    p: Point,
) -> Reaction {
    let mu = mu_at(friction, m, p.j);
    reaction(geom, applied, block, m, &mu, &sys.tangents, &p)
}

/// Every solution of the paper's frictional system at this pose. With a frictionless scene
/// there is exactly one (the statics, no shear) and no friction solve is done.
/// `c` are the frictionless normal magnitudes (25)–(27) at this pose.
pub fn all_solutions(
    geom: &ContactGeometry,
    applied: &Applied,
    block: &Block,
    c: &[f64; 3],
    friction: &[ContactStrength],
) -> Result<Vec<Reaction>, ReactionsError> {
    let (m, frictionless) = prologue(geom, applied, block, c, friction)?;
    if let Some(r) = frictionless {
        return Ok(vec![r]);
    }
    // Coefficients at the frictionless normal forces, then (stress-dependent criteria) each
    // solution settled to its own fixed point.
    let sys = System::new(geom, applied, &m, &mu_at(friction, &m, c[0]));
    Ok(sys
        .solve()
        .into_iter()
        .filter_map(|s| settle(geom, applied, &m, friction, s))
        .map(|s| reaction_at(geom, applied, block, &m, friction, &sys, s))
        .collect())
}

/// The solution continuing `previous` at this pose: Newton on the four equations from the
/// previous increment's N0 and shear directions (continuation, cheap), or `None` if it does not
/// converge to a solution with N0 > 0 — then call [`all_solutions`] and [`select`].
pub fn follow(
    geom: &ContactGeometry,
    applied: &Applied,
    block: &Block,
    c: &[f64; 3],
    friction: &[ContactStrength],
    previous: &Reaction,
) -> Result<Option<Reaction>, ReactionsError> {
    let (m, frictionless) = prologue(geom, applied, block, c, friction)?;
    if let Some(r) = frictionless {
        return Ok(Some(r));
    }
    let j0 = previous.normal[0].norm();
    let sys = System::new(geom, applied, &m, &mu_at(friction, &m, j0));
    let (p, res) = sys.polish(Point::new(j0, previous.angles));
    if !(res < 1e-9 && p.j > 0.0 && continues(&previous.angles, &p.phi)) {
        return Ok(None);
    }
    Ok(settle(geom, applied, &m, friction, p)
        .map(|s| reaction_at(geom, applied, block, &m, friction, &sys, s)))
}

/// How far (rad) the shear direction of any contact may move from one increment to the next
/// for a solution to count as the same one continued.
pub const CONTINUATION_RADIUS: f64 = 0.3;

/// The largest change of a shear direction between `previous` and `angles` (rad, wrapped).
fn largest_turn(previous: &[f64; 3], angles: &[f64; 3]) -> f64 {
    (0..3)
        .map(|i| wrap(angles[i] - previous[i]).abs())
        .fold(0.0, f64::max)
}

/// Whether a solution with shear directions `angles` continues one with `previous`: no
/// direction moved by [`CONTINUATION_RADIUS`] or more.
pub fn continues(previous: &[f64; 3], angles: &[f64; 3]) -> bool {
    largest_turn(previous, angles) < CONTINUATION_RADIUS
}

/// Friction power Σ S_i·v_i for a rigid motion with CM velocity `v` and angular velocity `omega`.
pub fn friction_power(
    geom: &ContactGeometry,
    r: &Reaction,
    v: &Vector3<f64>,
    omega: &Vector3<f64>,
) -> f64 {
    (0..3)
        .map(|i| r.shear[i].dot(&(v + omega.cross(&geom.r[i]))))
        .sum()
}

/// The stated rule: keep following the solution chosen at the previous increment (the one
/// whose shear directions are nearest, if within 0.3 rad at every contact); otherwise take the
/// one that dissipates most — friction power most negative — for the current motion, or, at
/// rest, for the motion each solution itself starts (velocity along its own accelerations).
pub fn select(
    geom: &ContactGeometry,
    solutions: &[Reaction],
    previous: Option<&[f64; 3]>,
    velocity: Option<(Vector3<f64>, Vector3<f64>)>,
) -> Option<usize> {
    if let Some(prev) = previous {
        let near = solutions
            .iter()
            .enumerate()
            .map(|(k, s)| (k, largest_turn(prev, &s.angles)))
            .min_by(|a, b| a.1.total_cmp(&b.1));
        if let Some((k, d)) = near
            && d < CONTINUATION_RADIUS
        {
            return Some(k);
        }
    }
    solutions
        .iter()
        .enumerate()
        .map(|(k, s)| {
            let (v, w) = velocity.unwrap_or((geom.frame.i * s.accel, geom.frame.j * s.ang_accel));
            (k, friction_power(geom, s, &v, &w))
        })
        .min_by(|a, b| a.1.total_cmp(&b.1))
        .map(|(k, _)| k)
}

#[cfg(test)]
mod tests {
    use super::sin_cos_step;

    #[test]
    fn small_step_sin_cos_agrees_with_libm_to_round_off() {
        for k in -200..=200 {
            let x = 1e-4 * k as f64; // up to ±0.02, the series' range
            let (s, c) = sin_cos_step(x);
            assert!((s - x.sin()).abs() <= 2e-17 * (1.0 + x.abs() * 1e3), "{x}");
            assert!((c - x.cos()).abs() <= 2.3e-16, "{x}");
        }
        // Outside the range it is libm's.
        assert_eq!(sin_cos_step(0.5), 0.5f64.sin_cos());
    }
}
