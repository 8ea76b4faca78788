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
//! method on the four equations. `derivations/07-reactions.md` has the details and what we
//! measured; we choose among the solutions by the stated rule in [`select`].

// The three contacts are handled by index into parallel arrays (normals, tangents, arms).
#![allow(clippy::needless_range_loop)]

use super::ContactGeometry;
use super::friction::FrictionCriterion;
use super::loads::Applied;
use super::statics::ratios;
use crate::numeric::{poly_mul, poly_roots, solve4, wrap_angle as wrap};
use crate::scene::{Block, Friction};
use nalgebra::{Matrix3, Matrix3x4, SMatrix, Vector3, Vector4};

/// One solution of the frictional system, with the accelerations it implies.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Reaction {
    pub normal: [Vector3<f64>; 3],
    pub shear: [Vector3<f64>; 3],
    /// Direction of each shear force in its plane (rad): 0 along the projection of +i', π
    /// against it.
    pub angles: [f64; 3],
    /// CM acceleration along i' (m/s²) and angular acceleration about j' (rad/s²), eq. (23).
    pub accel: f64,
    pub ang_accel: f64,
}

/// Why the paper's reactions cannot be had.
#[derive(Debug, Clone, Copy, PartialEq, Eq, thiserror::Error)]
pub enum ReactionsError {
    /// A frictionless normal reaction (25)–(27) is not positive: that contact lifts off.
    #[error("contact {0} lifts off (its frictionless normal reaction is not positive)")]
    LiftOff(usize),
    /// The statics are singular (degenerate frame).
    #[error("the frictionless statics are singular")]
    Singular,
}

/// Offset of the half-angle parameter, so that no solution sits at t = ∞ except by accident.
const DELTA: f64 = std::f64::consts::FRAC_PI_4 + 0.1;

/// The 4-vector (v·j', v·k', (r×v)·i', (r×v)·k') of a force v applied at r.
fn g(geom: &ContactGeometry, r: &Vector3<f64>, v: &Vector3<f64>) -> Vector4<f64> {
    let f = &geom.frame;
    let m = r.cross(v);
    Vector4::new(v.dot(&f.j), v.dot(&f.k), m.dot(&f.i), m.dot(&f.k))
}

/// The frictional system at one pose, with per-contact friction coefficients μ_i.
struct System {
    g0: Vector4<f64>,
    a: [Vector4<f64>; 3],
    b: [Vector4<f64>; 3],
    /// Right-hand side of j·(G0 + Σ …) = w.
    w: Vector4<f64>,
}

impl System {
    fn new(geom: &ContactGeometry, applied: &Applied, m: &[f64; 3], mu: &[f64; 3]) -> Self {
        let mut g0 = Vector4::zeros();
        let mut a = [Vector4::zeros(); 3];
        let mut b = [Vector4::zeros(); 3];
        for i in 0..3 {
            let (t1, t2) = geom.tangents(i);
            g0 += g(geom, &geom.r[i], &geom.n[i]) * m[i];
            a[i] = g(geom, &geom.r[i], &t1) * (mu[i] * m[i]);
            b[i] = g(geom, &geom.r[i], &t2) * (mu[i] * m[i]);
        }
        let f = &geom.frame;
        let loads = applied.weight + applied.force;
        let w = Vector4::new(
            -loads.dot(&f.j),
            -loads.dot(&f.k),
            -applied.moment.dot(&f.i),
            -applied.moment.dot(&f.k),
        );
        System { g0, a, b, w }
    }

    /// h(φ) = G0 + Σ (cos φ_i A_i + sin φ_i B_i); the equations read j·h(φ) = w.
    fn h(&self, phi: &[f64; 3]) -> Vector4<f64> {
        self.h_sc(&phi.map(f64::sin_cos))
    }

    /// h from precomputed (sin φ_i, cos φ_i).
    fn h_sc(&self, sc: &[(f64, f64); 3]) -> Vector4<f64> {
        let mut h = self.g0;
        for i in 0..3 {
            h += self.a[i] * sc[i].1 + self.b[i] * sc[i].0;
        }
        h
    }

    /// Newton on the four equations j·h(φ) − w = 0 in (j, φ0, φ1, φ2); stops when the updates
    /// are at round-off (relative in j, absolute in the angles). Returns (j, φ, relative residual).
    fn polish(&self, mut j: f64, mut phi: [f64; 3]) -> (f64, [f64; 3], f64) {
        let scale = self.w.amax().max(1e-300);
        let mut sc = phi.map(f64::sin_cos);
        for _ in 0..8 {
            let h = self.h_sc(&sc);
            let r = h * j - self.w;
            let mut jac = [[0.0; 4]; 4];
            for e in 0..4 {
                jac[e][0] = h[e];
            }
            for i in 0..3 {
                let d = (self.b[i] * sc[i].1 - self.a[i] * sc[i].0) * j;
                for e in 0..4 {
                    jac[e][i + 1] = d[e];
                }
            }
            let Some(dx) = solve4(jac, [-r[0], -r[1], -r[2], -r[3]]) else {
                break;
            };
            j += dx[0];
            for i in 0..3 {
                phi[i] += dx[i + 1];
            }
            sc = phi.map(f64::sin_cos);
            let step = (dx[0] / j)
                .abs()
                .max(dx[1].abs())
                .max(dx[2].abs())
                .max(dx[3].abs());
            if step.is_nan() || step < 1e-13 {
                break;
            }
        }
        let res = (self.h_sc(&sc) * j - self.w).amax() / scale;
        (j, phi, res)
    }

    /// All solutions (j, φ) with j > 0.
    fn solve(&self) -> Vec<(f64, [f64; 3])> {
        let (w0, w1) = (self.w[0], self.w[1]);
        // Three affine equations in u = (c0, s0, c1, s1, c2, s2): rows of M u = rhs.
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
        let m0 = m.fixed_columns::<2>(0).into_owned();
        let mp: Matrix3x4<f64> = m.fixed_columns::<4>(2).into_owned();
        // Null vector of M' (3×4) by signed 3×3 minors, and the min-norm inverse Q = M'ᵀ(M'M'ᵀ)⁻¹.
        let minor = |skip: usize| {
            let cols: Vec<usize> = (0..4).filter(|&c| c != skip).collect();
            let sub = Matrix3::from_fn(|r, c| mp[(r, cols[c])]);
            sub.determinant()
        };
        let v = Vector4::new(minor(0), -minor(1), minor(2), -minor(3));
        let Some(inv) = (mp * mp.transpose()).try_inverse() else {
            return Vec::new();
        };
        if v.norm() < 1e-12 {
            return Vec::new();
        }
        let v = v.normalize();
        let q = mp.transpose() * inv;
        // Û_p(t) = Q (rhs (1+t²) − M0 (ĉ0, ŝ0)), with ĉ0 = c0 (1+t²), ŝ0 = s0 (1+t²) and
        // φ0 = δ + 2 atan t: ĉ0 = cos δ (1 − t²) − 2 t sin δ, ŝ0 = sin δ (1 − t²) + 2 t cos δ.
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
        // Circle of contact c (components 2c−2, 2c−1 of u'): τ̂² |v|² + 2τ̂ (Û·v) + |Û|² − (1+t²)².
        let mut one_t2_sq = [0.0; 5];
        poly_mul(&one_t2, &one_t2, &mut one_t2_sq);
        let circle = |k0: usize| {
            let a2 = v[k0] * v[k0] + v[k0 + 1] * v[k0 + 1];
            let mut a1 = [0.0; 3];
            for d in 0..3 {
                a1[d] = 2.0 * (up[k0][d] * v[k0] + up[k0 + 1][d] * v[k0 + 1]);
            }
            let (mut s0, mut s1) = ([0.0; 5], [0.0; 5]);
            poly_mul(&up[k0], &up[k0], &mut s0);
            poly_mul(&up[k0 + 1], &up[k0 + 1], &mut s1);
            let mut a0 = [0.0; 5];
            for d in 0..5 {
                a0[d] = s0[d] + s1[d] - one_t2_sq[d];
            }
            (a2, a1, a0)
        };
        let (a2, a1, a0) = circle(0);
        let (b2, b1, b0) = circle(2);
        // R = (a2 b0 − a0 b2)² − (a2 b1 − a1 b2)(a1 b0 − a0 b1).
        let p: Vec<f64> = (0..5).map(|d| a2 * b0[d] - a0[d] * b2).collect();
        let qq: Vec<f64> = (0..3).map(|d| a2 * b1[d] - a1[d] * b2).collect();
        let (mut a1b0, mut a0b1) = ([0.0; 7], [0.0; 7]);
        poly_mul(&a1, &b0, &mut a1b0);
        poly_mul(&a0, &b1, &mut a0b1);
        let rr: Vec<f64> = (0..7).map(|d| a1b0[d] - a0b1[d]).collect();
        let (mut pp, mut qr) = ([0.0; 9], [0.0; 9]);
        poly_mul(&p, &p, &mut pp);
        poly_mul(&qq, &rr, &mut qr);
        let res: Vec<f64> = (0..9).map(|d| pp[d] - qr[d]).collect();
        let Some(ts) = poly_roots(&res) else {
            return Vec::new();
        };

        let mut out: Vec<(f64, [f64; 3])> = Vec::new();
        for (t, im) in ts {
            if im.abs() > 1e-6 * (1.0 + t.abs()) {
                continue;
            }
            let ev = |c: &[f64]| c.iter().rev().fold(0.0, |acc, &k| acc * t + k);
            let w2 = 1.0 + t * t;
            let upt: [f64; 4] = [ev(&up[0]), ev(&up[1]), ev(&up[2]), ev(&up[3])];
            // τ̂: the root of circle 1 that best satisfies circle 2.
            let (qa, qb_, qc) = (a2, ev(&a1), ev(&a0));
            let disc = qb_ * qb_ - 4.0 * qa * qc;
            if disc < -1e-9 * (qb_ * qb_ + (4.0 * qa * qc).abs()) {
                continue;
            }
            let sq = disc.max(0.0).sqrt();
            let qq_ = -0.5 * (qb_ + sq.copysign(qb_));
            let mut cands = vec![];
            if qa != 0.0 {
                cands.push(qq_ / qa);
            }
            if qq_ != 0.0 {
                cands.push(qc / qq_);
            }
            let other = |tau: f64| (b2 * tau * tau + ev(&b1) * tau + ev(&b0)).abs();
            let Some(tau) = cands
                .into_iter()
                .min_by(|x, y| other(*x).total_cmp(&other(*y)))
            else {
                continue;
            };
            let u: [f64; 4] = [0, 1, 2, 3].map(|k| (upt[k] + tau * v[k]) / w2);
            let phi0 = DELTA + 2.0 * t.atan();
            let phi = [phi0, u[1].atan2(u[0]), u[3].atan2(u[2])];
            // j from the two force equations (least squares), then Newton on all four.
            let h = self.h(&phi);
            let hh = h[0] * h[0] + h[1] * h[1];
            if hh == 0.0 {
                continue;
            }
            let j = (h[0] * w0 + h[1] * w1) / hh;
            let (j, phi, residual) = self.polish(j, phi);
            if !(residual < 1e-9 && j > 0.0) {
                continue;
            }
            let phi = phi.map(wrap);
            if !out
                .iter()
                .any(|(_, p)| (0..3).all(|i| wrap(p[i] - phi[i]).abs() < 1e-7))
            {
                out.push((j, phi));
            }
        }
        out
    }
}

fn reaction(
    geom: &ContactGeometry,
    applied: &Applied,
    block: &Block,
    m: &[f64; 3],
    mu: &[f64; 3],
    j: f64,
    phi: [f64; 3],
) -> Reaction {
    let mut normal = [Vector3::zeros(); 3];
    let mut shear = [Vector3::zeros(); 3];
    let mut force = applied.force + applied.weight;
    let mut moment = applied.moment;
    for i in 0..3 {
        let (t1, t2) = geom.tangents(i);
        normal[i] = geom.n[i] * (j * m[i]);
        shear[i] = (t1 * phi[i].cos() + t2 * phi[i].sin()) * (mu[i] * j * m[i]);
        force += normal[i] + shear[i];
        moment += geom.r[i].cross(&(normal[i] + shear[i]));
    }
    Reaction {
        normal,
        shear,
        angles: phi,
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
    friction: &Friction,
) -> Result<([f64; 3], Option<Reaction>), ReactionsError> {
    if let Some(k) = (0..3).find(|&k| c[k] <= 0.0) {
        return Err(ReactionsError::LiftOff(k));
    }
    let m = ratios(c);
    let frictionless = friction
        .is_frictionless()
        .then(|| reaction(geom, applied, block, &m, &[0.0; 3], c[0], [0.0; 3]));
    Ok((m, frictionless))
}

/// Per-contact friction coefficients at N0 = j.
fn mu_at(friction: &Friction, m: &[f64; 3], j: f64) -> [f64; 3] {
    [0, 1, 2].map(|i| friction.coefficient(j * m[i]))
}

/// For a stress-dependent criterion (Barton–Choubey) μ_i depends on j: iterate j to a fixed
/// point from (j, φ), following the solution. `None` if it is lost on the way.
fn settle(
    geom: &ContactGeometry,
    applied: &Applied,
    m: &[f64; 3],
    friction: &Friction,
    (mut j, mut phi): (f64, [f64; 3]),
) -> Option<(f64, [f64; 3])> {
    if matches!(friction, Friction::Coulomb { .. }) {
        return Some((j, phi));
    }
    for _ in 0..60 {
        let sys = System::new(geom, applied, m, &mu_at(friction, m, j));
        let (jn, pn, res) = sys.polish(j, phi);
        if !(res < 1e-9 && jn > 0.0) {
            return None;
        }
        let done = (jn - j).abs() <= 1e-12 * j;
        j = jn;
        phi = pn;
        if done {
            break;
        }
    }
    Some((j, phi))
}

/// The reaction of a settled solution (j, φ), with the friction coefficients at its N0.
fn reaction_at(
    geom: &ContactGeometry,
    applied: &Applied,
    block: &Block,
    m: &[f64; 3],
    friction: &Friction,
    (j, phi): (f64, [f64; 3]),
) -> Reaction {
    reaction(
        geom,
        applied,
        block,
        m,
        &mu_at(friction, m, j),
        j,
        phi.map(wrap),
    )
}

/// Every solution of the paper's frictional system at this pose. With a frictionless scene
/// there is exactly one (the statics, no shear) and no friction solve is done.
/// `c` are the frictionless normal magnitudes (25)–(27) at this pose.
pub fn all_solutions(
    geom: &ContactGeometry,
    applied: &Applied,
    block: &Block,
    c: &[f64; 3],
    friction: &Friction,
) -> Result<Vec<Reaction>, ReactionsError> {
    let (m, frictionless) = prologue(geom, applied, block, c, friction)?;
    if let Some(r) = frictionless {
        return Ok(vec![r]);
    }
    // Coefficients at the frictionless normal forces, then (stress-dependent criteria) each
    // solution settled to its own fixed point.
    let sols = System::new(geom, applied, &m, &mu_at(friction, &m, c[0])).solve();
    Ok(sols
        .into_iter()
        .filter_map(|s| settle(geom, applied, &m, friction, s))
        .map(|s| reaction_at(geom, applied, block, &m, friction, s))
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
    friction: &Friction,
    previous: &Reaction,
) -> Result<Option<Reaction>, ReactionsError> {
    let (m, frictionless) = prologue(geom, applied, block, c, friction)?;
    if let Some(r) = frictionless {
        return Ok(Some(r));
    }
    let j0 = previous.normal[0].norm();
    let sys = System::new(geom, applied, &m, &mu_at(friction, &m, j0));
    let (j, phi, res) = sys.polish(j0, previous.angles);
    let moved = (0..3)
        .map(|i| wrap(phi[i] - previous.angles[i]).abs())
        .fold(0.0, f64::max);
    if !(res < 1e-9 && j > 0.0 && moved < 0.3) {
        return Ok(None);
    }
    Ok(settle(geom, applied, &m, friction, (j, phi))
        .map(|s| reaction_at(geom, applied, block, &m, friction, s)))
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
    let dist = |a: f64| wrap(a).abs();
    if let Some(prev) = previous {
        let near = solutions
            .iter()
            .enumerate()
            .map(|(k, s)| {
                (
                    k,
                    (0..3)
                        .map(|i| dist(s.angles[i] - prev[i]))
                        .fold(0.0, f64::max),
                )
            })
            .min_by(|a, b| a.1.total_cmp(&b.1));
        if let Some((k, d)) = near {
            if d < 0.3 {
                return Some(k);
            }
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
