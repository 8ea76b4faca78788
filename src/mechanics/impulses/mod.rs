//! The contact impulses of one step of a body on many contacts (`derivations/13-base-contact.md`
//! §4): Coulomb friction, exactly, at every contact, and no contact pulling.
//!
//! Over a step h the body's velocity goes from its free value (the applied loads alone) to the
//! one the contact impulses P_i leave it with: v⁺ = v* + Σ P_i / m, ω⁺ = ω* + I⁻¹ Σ r_i × P_i.
//! Each contact i, at gap g_i along its normal n_i, has the velocity u_i = v⁺ + ω⁺ × r_i and
//!
//! * in the normal: u_n + g/h ≥ 0, P_n ≥ 0, and one of them zero (the gap closes at most to
//!   zero by the step's end; a contact apart pulls nothing; a contact made is made inelastic,
//!   an impact);
//! * in the tangent: |P_t| ≤ μ P_n, and where it slides (u_t ≠ 0) P_t = −μ P_n u_t / |u_t|.
//!
//! Solved by projected Gauss–Seidel, contact by contact, on the body's velocity, from the last
//! step's impulses: the normal by its one-contact update, over-relaxed; the tangent, the others
//! held, by the friction of least kinetic energy within its disc ([`disc_minimum`]), whose
//! slip opposes it: Coulomb's law itself. Unlike a convex relaxation of the cone (Anitescu's),
//! the block does not rise as it slides (`derivations/13-base-contact.md` §4).

mod crease;
mod disc;
mod patch;

pub use disc::{Tangential, disc_minimum};
pub use patch::{Patch, PatchPoint};

use crease::{normal_at_point, point_group};
use nalgebra::{Matrix2, Matrix3, Vector2, Vector3};
use patch::Spreading;

/// One contact of the step: its arm from the CM, its frame, its friction and its gap.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactRow {
    /// r: from the CM to the contact point (m).
    pub arm: Vector3<f64>,
    /// n: unit normal into the body.
    pub normal: Vector3<f64>,
    /// μ.
    pub mu: f64,
    /// g / h: the normal velocity the contact may close at (m/s; negative inside the ground,
    /// asking for the depth to be undone in the step).
    pub closing: f64,
    /// Where the solve starts: the impulse (N·s, world) the contact carried at the last step,
    /// or zero (a warm start; the solution does not depend on it, only the sweeps it takes).
    pub guess: Vector3<f64>,
}

/// The body the impulses act on.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Body {
    /// 1 / m (1/kg).
    pub inv_mass: f64,
    /// I⁻¹ in world axes (1/(kg·m²)).
    pub inv_inertia: Matrix3<f64>,
}

/// The solution: the velocities after the step and each contact's impulse (N·s) as (normal,
/// tangential vector).
#[derive(Debug, Clone, PartialEq)]
pub struct Solved {
    /// v⁺ (m/s).
    pub v: Vector3<f64>,
    /// ω⁺ (rad/s).
    pub w: Vector3<f64>,
    /// Each contact's normal impulse (N·s).
    pub normal: Vec<f64>,
    /// Each contact's tangential impulse (N·s, world).
    pub tangential: Vec<Vector3<f64>>,
    /// Each patch's points' impulses (N·s, world: a share of the normal impulse along the
    /// normal and the friction), empty for a patch whose rows carried their own friction.
    pub patch: Vec<Vec<Vector3<f64>>>,
    /// Sweeps taken.
    pub sweeps: usize,
    /// How far the last sweep moved the velocities (|Δv| + |Δω| × the longest arm), relative
    /// to their size and the largest impulse's.
    pub change: f64,
}

/// Over-relaxation of the normal updates in the first sweeps: a corner in a crease is two
/// nearly opposed normals at one point, which plain Gauss–Seidel shares out slowly (37 sweeps a
/// step on the default scene, 27 with these; the solution is the same).
const RELAX: f64 = 1.7;

/// The sweeps over-relaxed.
const RELAXED_SWEEPS: usize = 8;

/// Two unit tangents completing `n`.
pub fn tangents(n: &Vector3<f64>) -> (Vector3<f64>, Vector3<f64>) {
    let helper = if n.x.abs() < 0.9 {
        Vector3::x()
    } else {
        Vector3::z()
    };
    let t1 = n.cross(&helper).normalize();
    (t1, n.cross(&t1))
}

/// The impulses of one step from the free velocities `v`, `w`, until a sweep moves the
/// velocities by less than `tol` of their size (at most `max_sweeps` sweeps).
pub fn solve(
    body: &Body,
    v: Vector3<f64>,
    w: Vector3<f64>,
    rows: &[ContactRow],
    tol: f64,
    max_sweeps: usize,
) -> Solved {
    solve_with_patches(body, (v, w), rows, &[], tol, max_sweeps)
}

/// A contact's frame for the sweeps: its tangents, the normal's effective inverse mass and the
/// tangential one, at the arm `arm` with normal `n`.
fn frame_at(
    body: &Body,
    arm: &Vector3<f64>,
    n: &Vector3<f64>,
    t: (Vector3<f64>, Vector3<f64>),
) -> Frame {
    let k = |a: &Vector3<f64>, b: &Vector3<f64>| {
        body.inv_mass * a.dot(b) + arm.cross(a).dot(&(body.inv_inertia * arm.cross(b)))
    };
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

/// A contact's tangents and effective inverse masses.
#[derive(Debug, Clone, Copy)]
struct Frame {
    t1: Vector3<f64>,
    t2: Vector3<f64>,
    wn: f64,
    wt: Tangential,
}

/// Adds the impulse `p` at `arm` to the body's velocities.
fn apply_at(out: &mut Solved, body: &Body, arm: &Vector3<f64>, p: Vector3<f64>) {
    out.v += p * body.inv_mass;
    out.w += body.inv_inertia * arm.cross(&p);
}

/// Replaces the friction impulse `old` at `arm` by the least-energy one within `radius`, the
/// others held (Coulomb's law for this point), and returns it.
fn friction_at(
    out: &mut Solved,
    body: &Body,
    arm: &Vector3<f64>,
    f: &Frame,
    radius: f64,
    old: Vector3<f64>,
    nu: &mut f64,
) -> Vector3<f64> {
    let u = out.v + out.w.cross(arm);
    let pt_old = Vector2::new(old.dot(&f.t1), old.dot(&f.t2));
    let ut = Vector2::new(u.dot(&f.t1), u.dot(&f.t2));
    let pt = disc_minimum(&f.wt, &(ut - f.wt.w * pt_old), radius, nu);
    let new = f.t1 * pt.x + f.t2 * pt.y;
    apply_at(out, body, arm, new - old);
    new
}

/// Starts the solve from the guesses: each row's within its cone (without its friction where
/// a flush patch's points carry it, `spread_rows`), each patch point's friction.
fn warm_start(
    out: &mut Solved,
    body: &Body,
    rows: &[ContactRow],
    spread_rows: &[bool],
    spreading: &[Spreading],
) {
    for (i, c) in rows.iter().enumerate() {
        let pn = c.normal.dot(&c.guess).max(0.0);
        let mut pt = c.guess - c.normal * c.normal.dot(&c.guess);
        if spread_rows[i] {
            pt = Vector3::zeros();
        } else if pt.norm() > c.mu * pn {
            pt *= c.mu * pn / pt.norm();
        }
        if pn > 0.0 {
            apply_at(out, body, &c.arm, c.normal * pn + pt);
            out.normal[i] = pn;
            out.tangential[i] = pt;
        }
    }
    for s in spreading {
        let n = s.normal;
        let guesses: Vec<Vector3<f64>> = s
            .patch
            .points
            .iter()
            .map(|q| q.guess - n * n.dot(&q.guess))
            .collect();
        for (q, g) in s.patch.points.iter().zip(&guesses) {
            apply_at(out, body, &q.arm, *g);
        }
        out.patch.push(guesses);
    }
}

/// [`solve`] with the parts of the base lying flush on rock, `patches` (no row in two of
/// them; `derivations/13-base-contact.md` §9).
pub fn solve_with_patches(
    body: &Body,
    (v, w): (Vector3<f64>, Vector3<f64>),
    rows: &[ContactRow],
    patches: &[Patch],
    tol: f64,
    max_sweeps: usize,
) -> Solved {
    let m = rows.len();
    let mut out = Solved {
        v,
        w,
        normal: vec![0.0; m],
        tangential: vec![Vector3::zeros(); m],
        patch: Vec::new(),
        sweeps: 0,
        change: 0.0,
    };
    let frames: Vec<Frame> = rows
        .iter()
        .map(|c| frame_at(body, &c.arm, &c.normal, tangents(&c.normal)))
        .collect();
    let mut spreading: Vec<Spreading> = patches
        .iter()
        .enumerate()
        .map(|p| Spreading::new(body, p, rows))
        .collect();
    let mut member_of = vec![usize::MAX; m];
    for (k, p) in patches.iter().enumerate() {
        for &i in &p.members {
            member_of[i] = k;
        }
    }
    let is_member = |s: &[Spreading], i: usize| s.get(member_of[i]).is_some_and(|s| s.on);
    let apply = |out: &mut Solved, c: &ContactRow, p: Vector3<f64>| apply_at(out, body, &c.arm, p);
    let spread_rows: Vec<bool> = (0..m).map(|i| is_member(&spreading, i)).collect();
    warm_start(&mut out, body, rows, &spread_rows, &spreading);
    let arm = rows.iter().map(|c| c.arm.norm()).fold(0.0, f64::max);
    let mut nus = vec![0.0; m];
    for sweep in 1..=max_sweeps.max(1) {
        // Over-relaxed first, then plain Gauss–Seidel, which converges from wherever the first
        // sweeps left it (over-relaxation alone can cycle with the friction's discs).
        let relax = if sweep <= RELAXED_SWEEPS { RELAX } else { 1.0 };
        let mut largest: f64 = 1e-300;
        let (v_before, w_before) = (out.v, out.w);
        for (i, c) in rows.iter().enumerate() {
            // Normal: the contacts at one point of the body (a corner in a crease, on two or
            // three faces) together and exactly, at the first of them; any other alone.
            let group = point_group(rows, i);
            if group.len() > 1 && i - group.start < 3 {
                if group.start == i {
                    normal_at_point(&mut out, rows, group, body, &apply);
                }
            } else {
                let u = out.v + out.w.cross(&c.arm);
                let pn_old = out.normal[i];
                let pn = (pn_old - relax * (c.normal.dot(&u) + c.closing) / frames[i].wn).max(0.0);
                apply(&mut out, c, c.normal * (pn - pn_old));
                out.normal[i] = pn;
            }
            let pn = out.normal[i];
            largest = largest.max(pn);
            // Tangent: here, unless a flush patch's points carry it.
            if !is_member(&spreading, i) {
                let old = out.tangential[i];
                out.tangential[i] = friction_at(
                    &mut out,
                    body,
                    &c.arm,
                    &frames[i],
                    c.mu * pn,
                    old,
                    &mut nus[i],
                );
                largest = largest.max(out.tangential[i].norm());
            }
        }
        for s in spreading.iter_mut() {
            if s.sweep(&mut out, body, rows, sweep <= RELAXED_SWEEPS) {
                for &i in &s.patch.members {
                    let old = out.tangential[i];
                    let radius = rows[i].mu * out.normal[i];
                    out.tangential[i] = friction_at(
                        &mut out,
                        body,
                        &rows[i].arm,
                        &frames[i],
                        radius,
                        old,
                        &mut nus[i],
                    );
                }
            }
        }
        // The body's velocities are unique where the impulses are not (four corners on one
        // plane share the weight in many ways; a flush patch's friction follows the share
        // of the bed): the sweeps stop when the velocities settle.
        let moved = (out.v - v_before).norm() + (out.w - w_before).norm() * arm;
        let scale = largest * body.inv_mass + out.v.norm() + out.w.norm() * arm;
        out.sweeps = sweep;
        out.change = moved / scale;
        // A change that is not a number (impulses past the largest number) will not settle:
        // more sweeps would only spend the time (40 000 of them to hold a block of 1e300 N).
        if out.change <= tol || out.change.is_nan() {
            break;
        }
    }
    for s in &spreading {
        if !s.on {
            out.patch[s.number].clear();
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A 2 m cube of 1000 kg, its base corners 1 m below the CM.
    fn cube() -> (Body, Vec<Vector3<f64>>) {
        let m = 1000.0;
        let i = m * (4.0 + 4.0) / 12.0;
        let body = Body {
            inv_mass: 1.0 / m,
            inv_inertia: Matrix3::identity() / i,
        };
        let corners = [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)]
            .iter()
            .map(|&(x, z)| Vector3::new(x, -1.0, z))
            .collect();
        (body, corners)
    }

    fn on_ground(corners: &[Vector3<f64>], mu: f64) -> Vec<ContactRow> {
        corners
            .iter()
            .map(|&arm| ContactRow {
                arm,
                normal: Vector3::y(),
                mu,
                closing: 0.0,
                guess: Vector3::zeros(),
            })
            .collect()
    }

    #[test]
    fn a_block_resting_on_level_ground_is_held_by_normal_impulses_that_carry_its_weight() {
        let (body, corners) = cube();
        let h = 1e-3;
        // One step of gravity: v* = −g h.
        let v = Vector3::new(0.0, -9.81 * h, 0.0);
        let s = solve(
            &body,
            v,
            Vector3::zeros(),
            &on_ground(&corners, 0.6),
            1e-14,
            500,
        );
        assert!(s.v.norm() < 1e-12 && s.w.norm() < 1e-12, "{} {}", s.v, s.w);
        let total: f64 = s.normal.iter().sum();
        assert!((total - 1000.0 * 9.81 * h).abs() < 1e-9);
    }

    #[test]
    fn a_sliding_block_loses_exactly_mu_g_h_of_speed_a_step_and_does_not_rise() {
        let (body, corners) = cube();
        let (h, mu, g) = (1e-3, 0.4, 9.81);
        let v = Vector3::new(2.0, -g * h, 0.5);
        let s = solve(
            &body,
            v,
            Vector3::zeros(),
            &on_ground(&corners, mu),
            1e-14,
            2000,
        );
        let speed = v.xz().norm() - mu * g * h;
        assert!((s.v.xz().norm() - speed).abs() < 1e-9, "{}", s.v);
        // Friction opposes the slip: the direction of travel is kept.
        assert!((s.v.x / s.v.z - 4.0).abs() < 1e-9);
        assert!(s.v.y.abs() < 1e-12, "a rise of {}", s.v.y);
    }

    #[test]
    fn a_slow_block_stops_within_the_step_that_friction_can_stop_it_in() {
        let (body, corners) = cube();
        let (h, mu, g) = (1e-3, 0.4, 9.81);
        let v = Vector3::new(0.5 * mu * g * h, -g * h, 0.0);
        let s = solve(
            &body,
            v,
            Vector3::zeros(),
            &on_ground(&corners, mu),
            1e-14,
            2000,
        );
        assert!(s.v.norm() < 1e-12, "{}", s.v);
        let shear: f64 = s.tangential.iter().map(|p| p.norm()).sum();
        assert!(shear < mu * 1000.0 * g * h);
    }

    #[test]
    fn a_falling_block_lands_without_bouncing_and_a_contact_apart_pulls_nothing() {
        let (body, corners) = cube();
        let mut rows = on_ground(&corners, 0.6);
        // Falling at 1 m/s, 0.4 mm above the ground: it lands within this 1 ms step.
        for r in &mut rows {
            r.closing = 0.4e-3 / 1e-3;
        }
        let s = solve(
            &body,
            Vector3::new(0.0, -1.0, 0.0),
            Vector3::zeros(),
            &rows,
            1e-14,
            500,
        );
        assert!((s.v.y + 0.4).abs() < 1e-12, "{}", s.v.y);
        // Far above: nothing.
        for r in &mut rows {
            r.closing = 5.0;
        }
        let s = solve(
            &body,
            Vector3::new(0.0, -1.0, 0.0),
            Vector3::zeros(),
            &rows,
            1e-14,
            500,
        );
        assert_eq!(s.normal, vec![0.0; 4]);
        assert_eq!(s.v.y, -1.0);
    }
}
