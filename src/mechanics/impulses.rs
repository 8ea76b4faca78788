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

use super::pressure;
use nalgebra::{Matrix2, Matrix3, Vector2, Vector3};

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

/// A base lying flush on its rock (`derivations/13-base-contact.md` §9): the rows on it carry
/// the base's normal impulse, whose resultant [`pressure::spread`] shares over the base's area
/// as a rigid base on a uniform bed does; the friction then acts at the base's quadrature
/// points, each within μ times its share, and not at the rows. Where no such pressure has the
/// rows' resultant (it is at the edge of the points' hull: the base about to tip), the rows
/// carry their own friction, as without a patch.
#[derive(Debug, Clone, PartialEq)]
pub struct Patch {
    /// The rows on the flush base.
    pub members: Vec<usize>,
    /// Two unit axes in the base's plane (with the rows' normal, a right-handed frame).
    pub axes: (Vector3<f64>, Vector3<f64>),
    /// The quadrature points of the base over the flush rock.
    pub points: Vec<PatchPoint>,
}

/// One quadrature point of a flush base.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PatchPoint {
    /// r: from the CM to the point (m).
    pub arm: Vector3<f64>,
    /// Its weight: the area it stands for (m²).
    pub weight: f64,
    /// μ of the rock under it.
    pub mu: f64,
    /// Where the solve starts: its friction impulse at the last step (N·s, world), or zero.
    pub guess: Vector3<f64>,
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

/// A contact's tangential effective inverse mass W (2×2, symmetric positive definite) by its
/// eigenvectors and eigenvalues, W = Q diag(λ) Qᵀ, taken apart once a step.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Tangential {
    /// W itself.
    pub w: Matrix2<f64>,
    q: Matrix2<f64>,
    lam: Vector2<f64>,
}

impl Tangential {
    /// W taken apart.
    pub fn new(w: Matrix2<f64>) -> Tangential {
        let (lam, q) = crate::numeric::symmetric_eigen2(&w);
        Tangential { w, q, lam }
    }
}

/// The p of |p| ≤ `radius` that minimises ½ pᵀ W p + pᵀ u (W symmetric positive definite): the
/// friction impulse of one contact whose slip without it is `u`, W its tangential effective
/// inverse mass. Inside the disc, p = −W⁻¹u (it sticks); on its rim, p = −(W + ν I)⁻¹ u with
/// ν ≥ 0 making |p| the radius, so the slip W p + u = −ν p opposes p: Coulomb's maximal
/// dissipation. ν from the secular equation 1/|p(ν)| = 1/radius by Newton (Moré and
/// Sorensen's form, nearly linear in ν).
pub fn disc_minimum(w: &Tangential, u: &Vector2<f64>, radius: f64, nu: &mut f64) -> Vector2<f64> {
    if radius <= 0.0 || u.norm() == 0.0 {
        return Vector2::zeros();
    }
    let (q, lam) = (w.q, w.lam);
    let g = q.transpose() * u;
    let p_of = |nu: f64| -> Vector2<f64> {
        -(q * Vector2::new(g[0] / (lam[0] + nu), g[1] / (lam[1] + nu)))
    };
    if lam.min() > 0.0 && p_of(0.0).norm() <= radius {
        return p_of(0.0);
    }
    // |p(ν)| falls from above the radius (or from infinity) as ν grows; Newton from the last ν
    // this contact found (a slip that changes little needs a step or two).
    if !(*nu > 0.0 && p_of(*nu).norm() >= radius) {
        // |p(ν)| ≥ |u| / (λ_max + ν), so at this ν it is at least the radius: Newton on the
        // secular equation then climbs to the root without overshooting it.
        *nu = (u.norm() / radius - lam.max()).max(0.0);
    }
    let mut nu_k = *nu;
    for _ in 0..50 {
        let nu = nu_k;
        let p = p_of(nu);
        let norm = p.norm();
        if (norm - radius).abs() <= 1e-13 * radius {
            break;
        }
        // d|p|/dν = −Σ g_k² / (λ_k + ν)³ / |p|.
        let d = -(g[0] * g[0] / (lam[0] + nu).powi(3) + g[1] * g[1] / (lam[1] + nu).powi(3)) / norm;
        // Newton on φ(ν) = 1/|p| − 1/radius: φ' = −d/|p|².
        let phi = 1.0 / norm - 1.0 / radius;
        let step = phi / (-d / (norm * norm));
        let next = (nu - step).max(0.1 * nu);
        nu_k = next;
        if (next - nu).abs() <= 1e-15 * (nu.abs() + lam.max()) {
            break;
        }
    }
    *nu = nu_k;
    let p = p_of(nu_k);
    // On the rim exactly.
    p * (radius / p.norm())
}

/// Over-relaxation of the normal updates in the first sweeps: a corner in a crease is two
/// nearly opposed normals at one point, which plain Gauss–Seidel shares out slowly (37 sweeps a
/// step on the default scene, 27 with these; the solution is the same).
const RELAX: f64 = 1.7;

/// The sweeps over-relaxed.
const RELAXED_SWEEPS: usize = 8;

/// The rows next to row `i` at the same point of the body (the same arm).
fn point_group(rows: &[ContactRow], i: usize) -> std::ops::Range<usize> {
    let same = |j: usize| rows[j].arm == rows[i].arm;
    let mut start = i;
    while start > 0 && same(start - 1) {
        start -= 1;
    }
    let mut end = i + 1;
    while end < rows.len() && same(end) {
        end += 1;
    }
    start..end
}

/// The normal impulses of the first three contacts of `group` at one point of the body (a
/// fourth and more, which no ground of faces gives a corner but at a point where four planes
/// meet, go alone), the others held: the
/// small linear complementarity problem W p + q ≥ 0, p ≥ 0, p ⟂ (W p + q), solved exactly by
/// trying each set of contacts that push (W the group's normal effective inverse mass, q their
/// closing velocities without their own impulses). Where no set fits (a singular W: faces
/// whose normals are not independent), each contact alone.
fn normal_at_point(
    out: &mut Solved,
    rows: &[ContactRow],
    group: std::ops::Range<usize>,
    body: &Body,
    apply: &impl Fn(&mut Solved, &ContactRow, Vector3<f64>),
) {
    let g = group.len().min(3);
    let idx: Vec<usize> = group.clone().take(g).collect();
    let r = rows[idx[0]].arm;
    let u = out.v + out.w.cross(&r);
    let k = |a: &Vector3<f64>, b: &Vector3<f64>| {
        body.inv_mass * a.dot(b) + r.cross(a).dot(&(body.inv_inertia * r.cross(b)))
    };
    let mut w = Matrix3::zeros();
    let mut q = Vector3::zeros();
    for (a, &ia) in idx.iter().enumerate() {
        for (b, &ib) in idx.iter().enumerate() {
            w[(a, b)] = k(&rows[ia].normal, &rows[ib].normal);
        }
    }
    for (a, &ia) in idx.iter().enumerate() {
        let held: f64 = (0..g).map(|b| w[(a, b)] * out.normal[idx[b]]).sum();
        q[a] = rows[ia].normal.dot(&u) + rows[ia].closing - held;
    }
    let mut found = None;
    for set in 0u32..(1 << g) {
        let pushes = |a: usize| set & (1 << a) != 0;
        let mut p = Vector3::zeros();
        if set != 0 {
            // W and q of the contacts that push, the others' rows and columns the identity's
            // (their p stays zero): one 3 × 3 solve, on the stack.
            let ws = Matrix3::from_fn(|a, b| {
                if pushes(a) && pushes(b) {
                    w[(a, b)]
                } else if a == b {
                    1.0
                } else {
                    0.0
                }
            });
            let qs = Vector3::from_fn(|a, _| if pushes(a) { -q[a] } else { 0.0 });
            let Some(x) = ws.lu().solve(&qs) else {
                continue;
            };
            p = x;
        }
        let scale = q.abs().max() + 1e-300;
        let fits = (0..g).all(|a| {
            let gap_rate = (0..g).map(|b| w[(a, b)] * p[b]).sum::<f64>() + q[a];
            if pushes(a) {
                p[a] >= 0.0
            } else {
                gap_rate >= -1e-12 * scale
            }
        });
        if fits {
            found = Some(p);
            break;
        }
    }
    let Some(p) = found else {
        for &i in &idx {
            let c = &rows[i];
            let u = out.v + out.w.cross(&c.arm);
            let pn_old = out.normal[i];
            let pn = (pn_old - (c.normal.dot(&u) + c.closing) / k(&c.normal, &c.normal)).max(0.0);
            apply(out, c, c.normal * (pn - pn_old));
            out.normal[i] = pn;
        }
        return;
    };
    for (a, &i) in idx.iter().enumerate() {
        let c = &rows[i];
        apply(out, c, c.normal * (p[a] - out.normal[i]));
        out.normal[i] = p[a];
    }
}

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

/// A flush patch within the sweeps: its points' frames and shares, and whether its points or
/// its rows carry the friction.
struct Spreading<'a> {
    patch: &'a Patch,
    /// Its number among the patches.
    number: usize,
    /// The rows' normal.
    normal: Vector3<f64>,
    frames: Vec<Frame>,
    /// The bed under the points; None where they have no extent (then the rows rub).
    bed: Option<pressure::Bed>,
    shares: Vec<f64>,
    nus: Vec<f64>,
    /// The points carry the friction (else the rows do).
    on: bool,
}

impl<'a> Spreading<'a> {
    fn new(body: &Body, (number, patch): (usize, &'a Patch), rows: &[ContactRow]) -> Spreading<'a> {
        let (e1, e2) = patch.axes;
        let normal = patch
            .members
            .first()
            .map_or(e1.cross(&e2), |&i| rows[i].normal);
        Spreading {
            patch,
            number,
            normal,
            frames: patch
                .points
                .iter()
                .map(|p| frame_at(body, &p.arm, &normal, (e1, e2)))
                .collect(),
            bed: pressure::Bed::new(
                &patch
                    .points
                    .iter()
                    .map(|p| [p.arm.dot(&e1), p.arm.dot(&e2)])
                    .collect::<Vec<_>>(),
                &patch.points.iter().map(|p| p.weight).collect::<Vec<_>>(),
            ),
            shares: Vec::new(),
            nus: vec![0.0; patch.points.len()],
            on: true,
        }
    }

    /// Shares the rows' normal impulse over the points and gives each its friction, or, where
    /// that cannot be, hands the friction back to the rows (true: the rows must take it now).
    ///
    /// Once the rows have the friction back, the points take it again only while `may_return`
    /// (the first sweeps, the normals still settling): a base tipping to and fro over the rim
    /// of its points' hull would keep the sweeps from settling.
    fn sweep(
        &mut self,
        out: &mut Solved,
        body: &Body,
        rows: &[ContactRow],
        may_return: bool,
    ) -> bool {
        if !self.on && !may_return {
            return false;
        }
        let (e1, e2) = self.patch.axes;
        let (normal, at) = (self.normal, self.number);
        let total: f64 = self.patch.members.iter().map(|&i| out.normal[i]).sum();
        let mut centre = [0.0; 2];
        for &i in &self.patch.members {
            let share = out.normal[i] / total;
            centre[0] += share * rows[i].arm.dot(&e1);
            centre[1] += share * rows[i].arm.dot(&e2);
        }
        let fits = self
            .bed
            .as_mut()
            .is_some_and(|bed| bed.spread(total, centre, &mut self.shares));
        if fits {
            if !self.on {
                // The rows' friction goes over to the points.
                for &i in &self.patch.members {
                    let old = std::mem::take(&mut out.tangential[i]);
                    apply_at(out, body, &rows[i].arm, -old);
                }
            }
            for (k, p) in self.patch.points.iter().enumerate() {
                let was = out.patch[at][k];
                let old = was - normal * normal.dot(&was);
                let radius = p.mu * self.shares[k];
                let new = friction_at(
                    out,
                    body,
                    &p.arm,
                    &self.frames[k],
                    radius,
                    old,
                    &mut self.nus[k],
                );
                out.patch[at][k] = normal * self.shares[k] + new;
            }
        } else if self.on {
            for (k, p) in self.patch.points.iter().enumerate() {
                let old = std::mem::take(&mut out.patch[at][k]);
                apply_at(out, body, &p.arm, -(old - normal * normal.dot(&old)));
            }
        }
        let hand_back = self.on && !fits;
        self.on = fits;
        hand_back
    }
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
        if out.change <= tol {
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

#[cfg(test)]
mod disc_tests {
    use super::*;

    /// The minimum of ½ pᵀWp + pᵀu over the disc by brute force: a fine polar grid.
    fn brute(w: &Matrix2<f64>, u: &Vector2<f64>, radius: f64) -> Vector2<f64> {
        let f = |p: Vector2<f64>| 0.5 * p.dot(&(w * p)) + p.dot(u);
        let mut best = (f64::INFINITY, Vector2::zeros());
        for i in 0..=400 {
            for j in 0..720 {
                let r = radius * i as f64 / 400.0;
                let a = (j as f64).to_radians() / 2.0;
                let p = Vector2::new(r * a.cos(), r * a.sin());
                if f(p) < best.0 {
                    best = (f(p), p);
                }
            }
        }
        best.1
    }

    #[test]
    fn a_corner_in_a_v_groove_is_held_by_both_faces_as_the_statics_of_the_groove_say() {
        // A point mass (no arm) dropped into a symmetric groove of faces at ±φ: both faces push,
        // each P = m g h / (2 cos φ), and it stops; with the groove tipped, the statics of two
        // forces along the normals carry the weight: P1 n1 + P2 n2 = m g h Y.
        let (m, g, h) = (1000.0, 9.81, 1e-3);
        let body = Body {
            inv_mass: 1.0 / m,
            inv_inertia: Matrix3::identity(),
        };
        for (a, b) in [(30f64, 30f64), (20.0, 50.0)] {
            let (a, b) = (a.to_radians(), b.to_radians());
            let n1 = Vector3::new(-a.sin(), a.cos(), 0.0);
            let n2 = Vector3::new(b.sin(), b.cos(), 0.0);
            let row = |n: Vector3<f64>| ContactRow {
                arm: Vector3::zeros(),
                normal: n,
                mu: 0.0,
                closing: 0.0,
                guess: Vector3::zeros(),
            };
            let v = Vector3::new(0.0, -g * h, 0.0);
            let s = solve(&body, v, Vector3::zeros(), &[row(n1), row(n2)], 1e-14, 50);
            assert!(s.v.norm() < 1e-14, "{}", s.v);
            // The two normals' statics by Cramer's rule in (X, Y).
            let det = n1.x * n2.y - n2.x * n1.y;
            let w = m * g * h;
            let p1 = (0.0 * n2.y - n2.x * w) / det;
            let p2 = (n1.x * w - 0.0 * n1.y) / det;
            assert!((s.normal[0] - p1).abs() < 1e-12 * w, "{} {p1}", s.normal[0]);
            assert!((s.normal[1] - p2).abs() < 1e-12 * w, "{} {p2}", s.normal[1]);
            // Solved together at the point in the first sweep; the second only finds nothing moves.
            assert_eq!(s.sweeps, 2);
        }
    }

    #[test]
    fn the_friction_of_one_contact_is_the_least_energy_in_its_disc_and_opposes_its_slip() {
        let w = Matrix2::new(2.0, 0.7, 0.7, 1.0);
        let t = Tangential::new(w);
        for (u, radius) in [
            (Vector2::new(3.0, -1.0), 0.5),
            (Vector2::new(0.2, 0.1), 5.0),
            (Vector2::new(-1.0, 4.0), 1.0),
        ] {
            let mut nu = 0.0;
            let p = disc_minimum(&t, &u, radius, &mut nu);
            let b = brute(&w, &u, radius);
            assert!((p - b).norm() < 0.02 * radius, "{p} against {b}");
            assert!(p.norm() <= radius * (1.0 + 1e-12));
            let slip = w * p + u;
            if p.norm() < radius * (1.0 - 1e-9) {
                // It sticks.
                assert!(slip.norm() < 1e-12, "{slip}");
            } else {
                // It slides against its friction.
                let cos = slip.dot(&p) / (slip.norm() * p.norm());
                assert!((cos + 1.0).abs() < 1e-12, "{cos}");
            }
        }
    }
}
