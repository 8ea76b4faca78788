//! The contact impulses of one step of bodies on many contacts (`derivations/13-base-contact.md`
//! §4): each contact's friction criterion, exactly, at every contact, and no contact pulling.
//!
//! Over a step h each body's velocity goes from its free value (the applied loads alone) to the
//! one the contact impulses leave it with: v⁺ = v* + Σ P_i / m, ω⁺ = ω* + I⁻¹ Σ r_i × P_i, the
//! sums over its rows (a row between two bodies gives the first P and the second −P). Each row
//! i, at gap g_i along its normal n_i, has the relative velocity u_i (the first body's point's
//! less the second's, or the rock's zero) and
//!
//! * in the normal: u_n + g/h ≥ 0, P_n ≥ 0, and one of them zero (the gap closes at most to
//!   zero by the step's end; a contact apart pulls nothing; a contact made is made inelastic,
//!   an impact);
//! * in the tangent: |P_t| ≤ S(P_n), the criterion's shear strength at the normal force
//!   P_n / h over the step (μ P_n for Coulomb's), and where it slides (u_t ≠ 0) P_t opposes
//!   u_t with that magnitude.
//!
//! Solved by projected Gauss–Seidel, row by row, on the bodies' velocities, from the last
//! step's impulses: the normal by its one-row update, over-relaxed; the tangent, the others
//! held, by the friction of least kinetic energy within its disc ([`disc_minimum`]), whose
//! slip opposes it: the criterion's law itself. Unlike a convex relaxation of the cone
//! (Anitescu's), the block does not rise as it slides (`derivations/13-base-contact.md` §4).

mod crease;
mod disc;
mod patch;
mod work;

pub use disc::{Tangential, disc_minimum};
pub use work::work;

use crate::contact::{ContactRow, Patch, Side};
use crate::geometry::contact::tangents;
use crease::{normal_at_point, point_group};
use nalgebra::{Matrix2, Matrix3, Vector2, Vector3};
use patch::Spreading;
use std::ops::Range;

/// A body the impulses act on.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Body {
    /// 1 / m (1/kg).
    pub inv_mass: f64,
    /// I⁻¹ in world axes (1/(kg·m²)).
    pub inv_inertia: Matrix3<f64>,
}

impl Body {
    /// The velocity along `a` that a unit impulse along `b` at `arm` gives the body's point
    /// there: its effective inverse mass between the two directions.
    #[inline]
    fn k(&self, arm: &Vector3<f64>, a: &Vector3<f64>, b: &Vector3<f64>) -> f64 {
        self.inv_mass * a.dot(b) + arm.cross(a).dot(&(self.inv_inertia * arm.cross(b)))
    }
}

/// A body's velocities.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Motion {
    /// v: the centre of mass's (m/s).
    pub v: Vector3<f64>,
    /// ω (rad/s).
    pub w: Vector3<f64>,
}

impl Motion {
    /// The velocity of the body's point at `arm` from its centre of mass (m/s).
    #[inline]
    pub fn at(&self, arm: &Vector3<f64>) -> Vector3<f64> {
        self.v + self.w.cross(arm)
    }
}

/// When the sweeps stop: a sweep moves the velocities by less than `tol` of their size, or
/// after `max_sweeps` sweeps.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Until {
    /// The change of the velocities that counts as settled.
    pub tol: f64,
    /// The most sweeps.
    pub max_sweeps: usize,
}

/// The solution: the bodies' velocities after the step and each row's impulse (N·s) as
/// (normal, tangential vector).
#[derive(Debug, Clone, PartialEq)]
pub struct Solved {
    /// Each body's velocities after the step, by body number.
    pub motion: Vec<Motion>,
    /// Each row's normal impulse (N·s).
    pub normal: Vec<f64>,
    /// Each row's tangential impulse (N·s, world).
    pub tangential: Vec<Vector3<f64>>,
    /// Each patch's points' impulses (N·s, world: a share of the normal impulse along the
    /// normal and the friction), empty for a patch whose rows carried their own friction.
    pub patch: Vec<Vec<Vector3<f64>>>,
    /// Sweeps taken.
    pub sweeps: usize,
    /// How far the last sweep moved the velocities (|Δv| + |Δω| × the longest arm), relative
    /// to their size and the largest impulse's: the most of any body's.
    pub change: f64,
}

impl Solved {
    /// The velocity of the point of side `a` less that of side `b` (the rock's: zero).
    #[inline(always)]
    fn velocity(&self, a: &Side, b: Option<&Side>) -> Vector3<f64> {
        let u = self.motion[a.body].at(&a.arm);
        match b {
            None => u,
            Some(b) => u - self.motion[b.body].at(&b.arm),
        }
    }

    /// Adds the impulse `p` at side `a` and −`p` at side `b` to the bodies' velocities.
    #[inline(always)]
    fn apply(&mut self, bodies: &[Body], a: &Side, b: Option<&Side>, p: Vector3<f64>) {
        push(&mut self.motion[a.body], &bodies[a.body], &a.arm, p);
        if let Some(b) = b {
            push(&mut self.motion[b.body], &bodies[b.body], &b.arm, -p);
        }
    }
}

/// Adds the impulse `p` at `arm` to the velocities `m` of `body`.
#[inline(always)]
fn push(m: &mut Motion, body: &Body, arm: &Vector3<f64>, p: Vector3<f64>) {
    m.v += p * body.inv_mass;
    m.w += body.inv_inertia * arm.cross(&p);
}

/// Over-relaxation of the normal updates in the first sweeps: a corner in a crease is two
/// nearly opposed normals at one point, which plain Gauss–Seidel shares out slowly (37 sweeps a
/// step on the default scene, 27 with these; the solution is the same).
const RELAX: f64 = 1.7;

/// The sweeps over-relaxed.
const RELAXED_SWEEPS: usize = 8;

/// A contact's tangents and effective inverse masses.
#[derive(Debug, Clone, Copy)]
struct Frame {
    t1: Vector3<f64>,
    t2: Vector3<f64>,
    wn: f64,
    wt: Tangential,
}

/// A contact's frame for the sweeps between side `a` and side `b` (or the rock), with normal
/// `n` and tangents `t`: the normal's effective inverse mass and the tangential one.
fn frame_at(
    bodies: &[Body],
    (a, b): (&Side, Option<&Side>),
    n: &Vector3<f64>,
    t: (Vector3<f64>, Vector3<f64>),
) -> Frame {
    let body_a = &bodies[a.body];
    match b {
        None => frame_of(|x, y| body_a.k(&a.arm, x, y), n, t),
        Some(b) => {
            let body_b = &bodies[b.body];
            frame_of(|x, y| body_a.k(&a.arm, x, y) + body_b.k(&b.arm, x, y), n, t)
        }
    }
}

/// The frame of normal `n` and tangents `t` whose effective inverse mass between two
/// directions is `k`.
#[inline]
fn frame_of(
    k: impl Fn(&Vector3<f64>, &Vector3<f64>) -> f64,
    n: &Vector3<f64>,
    t: (Vector3<f64>, Vector3<f64>),
) -> Frame {
    let (t1, t2) = t;
    Frame {
        t1,
        t2,
        wn: k(n, n),
        wt: Tangential::new(Matrix2::new(
            k(&t1, &t1),
            k(&t1, &t2),
            k(&t2, &t1),
            k(&t2, &t2),
        )),
    }
}

/// Replaces the friction impulse `old` between sides `a` and `b` by the least-energy one
/// within `radius`, the others held (the criterion's law for this point), and returns it.
#[inline(always)]
fn friction_at(
    out: &mut Solved,
    bodies: &[Body],
    (a, b): (&Side, Option<&Side>),
    f: &Frame,
    (radius, old): (f64, Vector3<f64>),
    nu: &mut f64,
) -> Vector3<f64> {
    let u = out.velocity(a, b);
    let pt_old = Vector2::new(old.dot(&f.t1), old.dot(&f.t2));
    let ut = Vector2::new(u.dot(&f.t1), u.dot(&f.t2));
    let pt = disc_minimum(&f.wt, &(ut - f.wt.w * pt_old), radius, nu);
    let new = f.t1 * pt.x + f.t2 * pt.y;
    out.apply(bodies, a, b, new - old);
    new
}

/// The impulses of one step of `bodies` from their free velocities `free` (by body number) on
/// `rows`, with the parts lying flush on rock, `patches` (no row in two of them;
/// `derivations/13-base-contact.md` §9), swept `until` they settle.
pub fn solve(
    bodies: &[Body],
    free: &[Motion],
    rows: &[ContactRow],
    patches: &[Patch],
    until: Until,
) -> Solved {
    let mut s = Sweeps::new(bodies, free, rows, patches);
    s.warm_start();
    for sweep in 1..=until.max_sweeps.max(1) {
        // Over-relaxed first, then plain Gauss–Seidel, which converges from wherever the first
        // sweeps left it (over-relaxation alone can cycle with the friction's discs).
        let relaxed = sweep <= RELAXED_SWEEPS;
        s.before.copy_from_slice(&s.out.motion);
        let largest = s.rows_sweep(if relaxed { RELAX } else { 1.0 });
        s.patches_sweep(relaxed);
        s.out.sweeps = sweep;
        s.out.change = s.change(largest);
        // A change that is not a number (impulses past the largest number) will not settle:
        // more sweeps would only spend the time (40 000 of them to hold a block of 1e300 N).
        if s.out.change <= until.tol || s.out.change.is_nan() {
            break;
        }
    }
    s.finish()
}

/// The solve under way: the rows' frames and groups, the patches, the solution so far.
struct Sweeps<'a> {
    bodies: &'a [Body],
    rows: &'a [ContactRow],
    frames: Vec<Frame>,
    /// Each row's rows at one point of the same bodies.
    groups: Vec<Range<usize>>,
    spreading: Vec<Spreading<'a>>,
    /// Each row's patch (usize::MAX: none).
    member_of: Vec<usize>,
    /// Each row's last ν of its disc.
    nus: Vec<f64>,
    /// The longest arm (m).
    arm: f64,
    /// The velocities before the sweep.
    before: Vec<Motion>,
    out: Solved,
}

impl<'a> Sweeps<'a> {
    fn new(
        bodies: &'a [Body],
        free: &[Motion],
        rows: &'a [ContactRow],
        patches: &'a [Patch],
    ) -> Sweeps<'a> {
        let m = rows.len();
        let mut member_of = vec![usize::MAX; m];
        for (k, p) in patches.iter().enumerate() {
            for &i in &p.members {
                member_of[i] = k;
            }
        }
        Sweeps {
            bodies,
            rows,
            frames: rows
                .iter()
                .map(|c| frame_at(bodies, (&c.a, c.b.as_ref()), &c.normal, tangents(&c.normal)))
                .collect(),
            groups: (0..m).map(|i| point_group(rows, i)).collect(),
            spreading: patches
                .iter()
                .enumerate()
                .map(|p| Spreading::new(bodies, p, rows))
                .collect(),
            member_of,
            nus: vec![0.0; m],
            arm: rows
                .iter()
                .map(|c| {
                    c.b.map_or(c.a.arm.norm(), |b| c.a.arm.norm().max(b.arm.norm()))
                })
                .fold(0.0, f64::max),
            before: free.to_vec(),
            out: Solved {
                motion: free.to_vec(),
                normal: vec![0.0; m],
                tangential: vec![Vector3::zeros(); m],
                patch: Vec::new(),
                sweeps: 0,
                change: 0.0,
            },
        }
    }

    /// Whether row `i` is in a patch whose points carry its friction.
    fn spread(&self, i: usize) -> bool {
        self.spreading.get(self.member_of[i]).is_some_and(|s| s.on)
    }

    /// Starts the solve from the guesses: each row's within its disc (without its friction
    /// where a flush patch's points carry it), each patch point's friction.
    fn warm_start(&mut self) {
        let (bodies, rows) = (self.bodies, self.rows);
        for (i, c) in rows.iter().enumerate() {
            let pn = c.normal.dot(&c.guess).max(0.0);
            let mut pt = c.guess - c.normal * c.normal.dot(&c.guess);
            if self.spread(i) {
                pt = Vector3::zeros();
            } else {
                let radius = c.shear.radius(pn);
                if pt.norm() > radius {
                    pt *= radius / pt.norm();
                }
            }
            if pn > 0.0 {
                self.out
                    .apply(bodies, &c.a, c.b.as_ref(), c.normal * pn + pt);
                self.out.normal[i] = pn;
                self.out.tangential[i] = pt;
            }
        }
        for s in &self.spreading {
            let n = s.normal;
            let guesses: Vec<Vector3<f64>> = s
                .patch
                .points
                .iter()
                .map(|q| q.guess - n * n.dot(&q.guess))
                .collect();
            for (q, g) in s.patch.points.iter().zip(&guesses) {
                let at = Side {
                    body: s.patch.body,
                    arm: q.arm,
                };
                self.out.apply(bodies, &at, None, *g);
            }
            self.out.patch.push(guesses);
        }
    }

    /// One sweep over the rows, the normal updates over-relaxed by `relax`: the largest
    /// impulse met.
    fn rows_sweep(&mut self, relax: f64) -> f64 {
        let (bodies, rows) = (self.bodies, self.rows);
        let mut largest: f64 = 1e-300;
        for (i, c) in rows.iter().enumerate() {
            // Normal: the rows at one point of the bodies (a corner in a crease, on two or
            // three faces) together and exactly, at the first of them; any other alone.
            let group = &self.groups[i];
            if group.len() > 1 && i - group.start < 3 {
                if group.start == i {
                    normal_at_point(&mut self.out, rows, group.clone(), bodies);
                }
            } else {
                let u = self.out.velocity(&c.a, c.b.as_ref());
                let pn_old = self.out.normal[i];
                let pn =
                    (pn_old - relax * (c.normal.dot(&u) + c.closing) / self.frames[i].wn).max(0.0);
                self.out
                    .apply(bodies, &c.a, c.b.as_ref(), c.normal * (pn - pn_old));
                self.out.normal[i] = pn;
            }
            let pn = self.out.normal[i];
            largest = largest.max(pn);
            // Tangent: here, unless a flush patch's points carry it.
            if !self.spread(i) {
                let old = self.out.tangential[i];
                self.out.tangential[i] = friction_at(
                    &mut self.out,
                    bodies,
                    (&c.a, c.b.as_ref()),
                    &self.frames[i],
                    (c.shear.radius(pn), old),
                    &mut self.nus[i],
                );
                largest = largest.max(self.out.tangential[i].norm());
            }
        }
        largest
    }

    /// One sweep over the patches: each shares its rows' normal impulse over its points, or
    /// hands its friction back to its rows, which take it now (their points' friction may
    /// come back while `may_return`).
    fn patches_sweep(&mut self, may_return: bool) {
        let (bodies, rows) = (self.bodies, self.rows);
        for s in self.spreading.iter_mut() {
            if s.sweep(&mut self.out, bodies, rows, may_return) {
                for &i in &s.patch.members {
                    let c = &rows[i];
                    let old = self.out.tangential[i];
                    let radius = c.shear.radius(self.out.normal[i]);
                    self.out.tangential[i] = friction_at(
                        &mut self.out,
                        bodies,
                        (&c.a, c.b.as_ref()),
                        &self.frames[i],
                        (radius, old),
                        &mut self.nus[i],
                    );
                }
            }
        }
    }

    /// How far the sweep moved each body's velocities from `before`, relative to their size
    /// and the `largest` impulse's: the most of any body's (a change that is not a number
    /// wins). The bodies' velocities are unique where the impulses are not (four corners on
    /// one plane share the weight in many ways; a flush patch's friction follows the share of
    /// the bed): the sweeps stop when the velocities settle.
    fn change(&self, largest: f64) -> f64 {
        let arm = self.arm;
        let mut most = f64::NEG_INFINITY;
        for ((m, b), body) in self.out.motion.iter().zip(&self.before).zip(self.bodies) {
            let moved = (m.v - b.v).norm() + (m.w - b.w).norm() * arm;
            let scale = largest * body.inv_mass + m.v.norm() + m.w.norm() * arm;
            let change = moved / scale;
            if change.is_nan() || change > most {
                most = change;
            }
            if most.is_nan() {
                break;
            }
        }
        most
    }

    /// The solution, each patch whose rows carried their own friction without its points'.
    fn finish(mut self) -> Solved {
        for s in &self.spreading {
            if !s.on {
                self.out.patch[s.number].clear();
            }
        }
        self.out
    }
}

#[cfg(test)]
mod tests;
