//! Whether a block at rest on any number of contacts is held by static friction
//! (`derivations/13-base-contact.md` §6): does a state of contact forces exist, each inside its
//! friction cone, that balances the loads?
//!
//! The question of `static_friction.rs` for the three-point frame, asked of a base touching the
//! rock at many points: with the block at rest, the six equilibrium equations
//! Σ f_i + F = 0 and Σ r_i × f_i + M = 0 are linear in the contact forces
//! f_i = λ_i n_i + a_i t1_i + b_i t2_i, and each cone |(a_i, b_i)| ≤ μ_i λ_i + C_i, λ_i ≥ 0
//! (C_i its share of a bonded joint's cohesion, `derivations/13-base-contact.md` §11) is a
//! second-order cone. Whether the set of such forces is empty is one feasibility program
//! (Clarabel). It is the rigid body's criterion: a base lying flush over an area is held by it
//! exactly when it is held by forces at the area's corners, since a force inside the hull of
//! points on one plane splits among them within their cones with the same resultant and moment.
//!
//! A stress-dependent criterion's μ_i is its secant coefficient S(λ_i)/λ_i at the support's own
//! normal force, settled with the program's forces as the frame's are (`static_friction.rs`):
//! the program at μ, μ at its forces, until μ changes by less than [`SETTLED`].

use super::static_friction::StaticError;
use crate::geometry::contact::{hull_across, tangents};
use crate::model::Friction;
use clarabel::algebra::CscMatrix;
use clarabel::solver::{
    DefaultSettings, DefaultSolver, IPSolver, SolverStatus, SupportedConeT::NonnegativeConeT,
    SupportedConeT::SecondOrderConeT, SupportedConeT::ZeroConeT,
};
use nalgebra::Vector3;

/// A contact of a block at rest, free to carry any force within its cone.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Support {
    /// r: from the centre of mass to the contact point (m).
    pub arm: Vector3<f64>,
    /// n: unit normal into the block.
    pub normal: Vector3<f64>,
    /// The friction criterion there.
    pub criterion: Friction,
    /// Its share C of the joint's cohesion (N) while the joint is bonded: its cone is then
    /// |f_t| ≤ μ λ + C (`derivations/13-base-contact.md` §11); zero once the block has slid.
    pub cohesion_n: f64,
}

/// A stress-dependent criterion's coefficients are settled when no solve changes one by more
/// than this.
pub const SETTLED: f64 = 1e-10;

/// The most programs solved to settle them.
const MOST_SOLVES: usize = 50;

/// Whether the `supports` hold the block against the force `force` (N, the weight included)
/// and the moment `moment` about its centre of mass (N·m). `weight` (N) and `size` (m) scale
/// the program; an infeasible program means the loads start the block.
pub fn held(
    supports: &[Support],
    force: Vector3<f64>,
    moment: Vector3<f64>,
    weight: f64,
    size: f64,
) -> Result<bool, StaticError> {
    if supports.is_empty() {
        return Ok(false);
    }
    check_scales(weight, size)?;
    match constant(supports) {
        Some(mu) => {
            let (p, b) = Program::of(supports, &mu, force, moment, (weight, size));
            Ok(p.solve(&b, 0, false)?.is_some())
        }
        None => Ok(settled(supports, force, moment, (weight, size))?.is_some()),
    }
}

/// The most of a further load the `supports` hold: the largest s ≥ 0 for which the force
/// `force` + s `extra.0` and the moment `moment` + s `extra.1` (N, N·m about the centre of
/// mass) are held (`derivations/13-base-contact.md` §6, one cone program maximising s), a
/// stress-dependent criterion's coefficients those settled at the loads as given (as the
/// frame's yield acceleration takes them at its normal forces at rest). Zero where the loads
/// as given are not held; None where any multiple up to [`FAR`] is.
pub fn reach(
    supports: &[Support],
    force: Vector3<f64>,
    moment: Vector3<f64>,
    extra: (Vector3<f64>, Vector3<f64>),
    weight: f64,
    size: f64,
) -> Result<Option<f64>, StaticError> {
    if supports.is_empty() {
        return Ok(Some(0.0));
    }
    check_scales(weight, size)?;
    let mu = match constant(supports) {
        Some(mu) => mu,
        None => match settled(supports, force, moment, (weight, size))? {
            Some(mu) => mu,
            None => return Ok(Some(0.0)),
        },
    };
    let (p, b) = Program::of(supports, &mu, force, moment, (weight, size));
    farthest(p, b, extra, (weight, size))
}

/// The largest s ≥ 0 for which program `p` with right-hand side `b` holds the further load
/// s `extra` as well (N, N·m about the centre of mass; `weight` and `size` its scales): zero
/// where the program does not hold the loads as given, None where it holds [`FAR`] of it.
fn farthest(
    mut p: Program,
    mut b: Vec<f64>,
    extra: (Vector3<f64>, Vector3<f64>),
    (weight, size): (f64, f64),
) -> Result<Option<f64>, StaticError> {
    // Column s: the further load on the six equations; s ≥ 0 and s ≤ FAR as two more rows.
    let col = p.columns.len();
    p.columns.push(Vec::new());
    for (r, v) in (extra.0 / weight)
        .iter()
        .chain((extra.1 / (weight * size)).iter())
        .enumerate()
    {
        p.put(r, col, *v);
    }
    let (low, high) = (p.rows(), p.rows() + 1);
    p.put(low, col, -1.0);
    p.put(high, col, 1.0);
    b.extend([0.0, FAR]);
    match p.solve(&b, 2, true)? {
        None => Ok(Some(0.0)),
        Some((s, _)) if s >= FAR * (1.0 - 1e-6) => Ok(None),
        Some((s, _)) => Ok(Some(s.max(0.0))),
    }
}

/// A part of the base that presses as a uniform bed (`derivations/13-base-contact.md` §9): a
/// linear pressure over its points, with no tension, its friction at the points.
#[derive(Debug, Clone, PartialEq)]
pub struct Bedded {
    /// n: its unit normal into the block.
    pub normal: Vector3<f64>,
    /// Two unit axes in its plane.
    pub axes: (Vector3<f64>, Vector3<f64>),
    /// Its points.
    pub points: Vec<BedPoint>,
}

/// One point of a [`Bedded`] part.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BedPoint {
    /// r: from the centre of mass to the point (m).
    pub arm: Vector3<f64>,
    /// The area (or length, or one) it stands for.
    pub weight: f64,
    /// Coulomb's μ there.
    pub mu: f64,
}

/// Whether the loads `force` (N, the weight included) and `moment` (N·m about the centre of
/// mass) are held by Coulomb friction on the supports `free` (each free within its cone) and on
/// the beds `beds`, each pressing as a uniform bed over all its points, its friction at each
/// point within μ times its share (`derivations/13-base-contact.md` §6): a rigid equilibrium
/// under the step's own law, where no part of a bed lifts. `weight` (N) and `size` (m) scale
/// the program. False where a criterion depends on the normal stress: the question is then
/// left to the trial step.
pub fn held_pressing(
    free: &[Support],
    beds: &[Bedded],
    force: Vector3<f64>,
    moment: Vector3<f64>,
    weight: f64,
    size: f64,
) -> Result<bool, StaticError> {
    let Some(mu) = constant(free) else {
        return Ok(false);
    };
    if free.is_empty() && beds.iter().all(|b| b.points.is_empty()) {
        return Ok(false);
    }
    check_scales(weight, size)?;
    let (p, b) = Program::pressing((free, &mu), beds, force, moment, (weight, size));
    Ok(p.solve(&b, 0, false)?.is_some())
}

/// The supports that hold what all of `all` hold: of each set of one normal (to 10⁻⁹ rad), one
/// criterion and one cohesion, the corners of their hull across the normal. A force at a point
/// inside is the convex combination of the same force, within the same cone, at the corners,
/// with the same resultant and moment; so the program has the corners only, however finely the
/// rock under a flat part of the base is meshed. (Each corner keeps the cohesion it was given:
/// the caller shares a bonded area among the corners it gets back.)
pub fn hull_supports(all: &[Support]) -> Vec<Support> {
    let mut rest: Vec<usize> = (0..all.len()).collect();
    let mut out = Vec::new();
    while let Some(&first) = rest.first() {
        let (n, criterion) = (all[first].normal, all[first].criterion);
        let cohesion = all[first].cohesion_n;
        let same = |m: &Vector3<f64>| m.dot(&n) > 0.0 && m.cross(&n).norm() <= 1e-9;
        let (group, others): (Vec<usize>, Vec<usize>) = rest.iter().partition(|&&i| {
            same(&all[i].normal) && all[i].criterion == criterion && all[i].cohesion_n == cohesion
        });
        rest = others;
        let corners = hull_across(&n, group.iter().map(|&i| all[i].arm));
        out.extend(corners.into_iter().map(|k| all[group[k]]));
    }
    out
}

/// Each support's μ where every criterion's is a constant (Coulomb's); None where one
/// depends on the normal stress.
fn constant(supports: &[Support]) -> Option<Vec<f64>> {
    supports.iter().map(|s| s.criterion.constant_mu()).collect()
}

/// Each support's secant coefficient at its normal force, settled with the forces of the
/// feasibility program under `force` and `moment` (from the weight shared equally; at most
/// [`MOST_SOLVES`] programs): the coefficients where the program holds the block at each;
/// None where one does not.
fn settled(
    supports: &[Support],
    force: Vector3<f64>,
    moment: Vector3<f64>,
    (weight, size): (f64, f64),
) -> Result<Option<Vec<f64>>, StaticError> {
    let share = weight / supports.len() as f64;
    let mut mu: Vec<f64> = supports
        .iter()
        .map(|s| s.criterion.coefficient(share))
        .collect();
    for _ in 0..MOST_SOLVES {
        let (p, b) = Program::of(supports, &mu, force, moment, (weight, size));
        let Some((_, x)) = p.solve(&b, 0, false)? else {
            return Ok(None);
        };
        let mut change: f64 = 0.0;
        for (i, s) in supports.iter().enumerate() {
            let next = s.criterion.coefficient(x[3 * i].max(0.0) * weight);
            change = change.max((next - mu[i]).abs());
            mu[i] = next;
        }
        if change < SETTLED {
            break;
        }
    }
    Ok(Some(mu))
}

/// A force `dir` (in weights) at `arm` on the six equations: the force, and its moment about
/// the centre of mass over `size`.
fn equation(arm: &Vector3<f64>, dir: &Vector3<f64>, size: f64) -> [f64; 6] {
    let lever = (arm / size).cross(dir);
    [dir.x, dir.y, dir.z, lever.x, lever.y, lever.z]
}

/// The largest further load [`reach`] looks for (in units of the further load).
pub const FAR: f64 = 100.0;

fn check_scales(weight: f64, size: f64) -> Result<(), StaticError> {
    if weight > 0.0 && weight.is_finite() && size > 0.0 && size.is_finite() {
        Ok(())
    } else {
        Err(StaticError::Solver(format!(
            "the scales must be positive and finite (weight {weight} N, size {size} m)"
        )))
    }
}

/// The feasibility program's matrix, assembled by column: the six equations, then each
/// support's cone (three rows), then each one's floor (one row).
struct Program {
    columns: Vec<Vec<(usize, f64)>>,
    m: usize,
}

impl Program {
    /// The program of the loads `force` and `moment` on `supports` (in weights and
    /// weight·sizes): its matrix and right-hand side.
    fn of(
        supports: &[Support],
        mu: &[f64],
        force: Vector3<f64>,
        moment: Vector3<f64>,
        (weight, size): (f64, f64),
    ) -> (Program, Vec<f64>) {
        let mut p = Program::new(supports.len());
        for (i, s) in supports.iter().enumerate() {
            p.support(i, s, mu[i], size);
        }
        let mut b = p.loads(force, moment, (weight, size));
        p.bonded(supports, &mut b, weight);
        (p, b)
    }

    /// The program of the loads `force` and `moment` on the supports `free`, each free within
    /// its cone of `mu`, and on the beds `beds`, each pressing linearly with no tension (in
    /// weights and weight·sizes): its matrix and right-hand side.
    fn pressing(
        (free, mu): (&[Support], &[f64]),
        beds: &[Bedded],
        force: Vector3<f64>,
        moment: Vector3<f64>,
        (weight, size): (f64, f64),
    ) -> (Program, Vec<f64>) {
        let points: usize = beds.iter().map(|b| b.points.len()).sum();
        let mut p = Program::new(free.len());
        p.m += points;
        for (i, s) in free.iter().enumerate() {
            p.support(i, s, mu[i], size);
        }
        let mut cone = free.len();
        for bed in beds {
            p.bed(bed, cone, size);
            cone += bed.points.len();
        }
        let mut b = p.loads(force, moment, (weight, size));
        p.bonded(free, &mut b, weight);
        (p, b)
    }

    /// The cohesion of each of `supports` (cones 0, 1, …) on the right-hand side `b`: cone i is
    /// (μ λ_i + C_i, a_i, b_i) = b − A x, C_i its share of a bonded joint's cohesion (in
    /// weights; `derivations/13-base-contact.md` §11).
    fn bonded(&self, supports: &[Support], b: &mut [f64], weight: f64) {
        for (i, s) in supports.iter().enumerate() {
            b[self.cone(i)] = s.cohesion_n / weight;
        }
    }

    /// The right-hand side: the loads `force` and `moment` on the six equations (in weights
    /// and weight·sizes), nothing on the cones.
    fn loads(
        &self,
        force: Vector3<f64>,
        moment: Vector3<f64>,
        (weight, size): (f64, f64),
    ) -> Vec<f64> {
        let mut b = vec![0.0; self.rows()];
        for k in 0..3 {
            b[k] = -force[k] / weight;
            b[3 + k] = -moment[k] / (weight * size);
        }
        b
    }

    /// Support `s` as cone `i` and columns 3i..3i+3: its force along its normal and tangents
    /// on the six equations, within its cone of `mu`.
    fn support(&mut self, i: usize, s: &Support, mu: f64, size: f64) {
        let (cone, floor) = (self.cone(i), self.floor(i));
        let (t1, t2) = tangents(&s.normal);
        for (k, dir) in [s.normal, t1, t2].into_iter().enumerate() {
            let col = 3 * i + k;
            self.on_equations(col, &equation(&s.arm, &dir, size));
            // The cone's rows: s = (μ λ, a, b) = −A x; and λ ≥ 0 (the cone alone lets a
            // frictionless contact pull).
            self.put(cone + k, col, if k == 0 { -mu } else { -1.0 });
            if k == 0 {
                self.put(floor, col, -1.0);
            }
        }
    }

    /// Bed `bed`, its points cones `first`, `first` + 1, …: three columns for its pressure
    /// p(ξ) = d + a₁ ξ₁ + a₂ ξ₂ (ξ along its axes over `size`), each point's normal force its
    /// weight's share of it, then each point's friction along its tangents (two columns).
    fn bed(&mut self, bed: &Bedded, first: usize, size: f64) {
        let total: f64 = bed.points.iter().map(|q| q.weight).sum();
        let (e1, e2) = bed.axes;
        let pressure = self.columns.len();
        self.columns.extend(std::iter::repeat_n(Vec::new(), 3));
        let mut on = [[0.0; 6]; 3];
        for (k, q) in bed.points.iter().enumerate() {
            let share = q.weight / total;
            let lam = [
                share,
                share * q.arm.dot(&e1) / size,
                share * q.arm.dot(&e2) / size,
            ];
            let unit = equation(&q.arm, &bed.normal, size);
            let (cone, floor) = (self.cone(first + k), self.floor(first + k));
            for (j, l) in lam.iter().enumerate() {
                for (r, u) in unit.iter().enumerate() {
                    on[j][r] += l * u;
                }
                self.put(cone, pressure + j, -q.mu * l);
                self.put(floor, pressure + j, -l);
            }
            for (j, t) in [e1, e2].into_iter().enumerate() {
                let col = self.columns.len();
                self.columns.push(Vec::new());
                self.on_equations(col, &equation(&q.arm, &t, size));
                self.put(cone + 1 + j, col, -1.0);
            }
        }
        for (j, row) in on.iter().enumerate() {
            self.on_equations(pressure + j, row);
        }
    }

    /// Column `col`'s entries `e` on the six equations.
    fn on_equations(&mut self, col: usize, e: &[f64; 6]) {
        for (r, v) in e.iter().enumerate() {
            self.put(r, col, *v);
        }
    }

    /// The program of `m` supports: three columns each.
    fn new(m: usize) -> Program {
        Program {
            columns: vec![Vec::new(); 3 * m],
            m,
        }
    }

    fn rows(&self) -> usize {
        6 + 4 * self.m
    }

    /// The first row of support `i`'s cone.
    fn cone(&self, i: usize) -> usize {
        6 + 3 * i
    }

    /// The row of support `i`'s floor (λ_i ≥ 0).
    fn floor(&self, i: usize) -> usize {
        6 + 3 * self.m + i
    }

    fn put(&mut self, row: usize, col: usize, v: f64) {
        if v != 0.0 {
            self.columns[col].push((row, v));
        }
    }

    /// Solves A x + s = b with s in the cones, where the last `more` rows are further
    /// non-negative ones (Clarabel), maximising the last variable if `maximise`: that variable
    /// at the solution (zero without an objective) and the solution x, None where it is
    /// infeasible.
    fn solve(
        mut self,
        b: &[f64],
        more: usize,
        maximise: bool,
    ) -> Result<Option<(f64, Vec<f64>)>, StaticError> {
        let n = self.columns.len();
        let mut colptr = Vec::with_capacity(n + 1);
        let (mut rowval, mut nzval) = (Vec::new(), Vec::new());
        colptr.push(0);
        for col in &mut self.columns {
            col.sort_by_key(|e| e.0);
            for (r, v) in col.iter() {
                rowval.push(*r);
                nzval.push(*v);
            }
            colptr.push(rowval.len());
        }
        let a = CscMatrix::new(self.rows() + more, n, colptr, rowval, nzval);
        let mut cones = vec![ZeroConeT(6)];
        cones.extend(std::iter::repeat_n(SecondOrderConeT(3), self.m));
        cones.push(NonnegativeConeT(self.m + more));
        let p = CscMatrix::<f64>::zeros((n, n));
        let mut q = vec![0.0; n];
        if maximise {
            q[n - 1] = -1.0;
        }
        let settings = DefaultSettings {
            verbose: false,
            ..DefaultSettings::default()
        };
        let mut solver = DefaultSolver::new(&p, &q, &a, b, &cones, settings)
            .map_err(|e| StaticError::Solver(e.to_string()))?;
        solver.solve();
        match solver.solution.status {
            SolverStatus::Solved | SolverStatus::AlmostSolved => {
                let x = std::mem::take(&mut solver.solution.x);
                Ok(Some((if maximise { x[n - 1] } else { 0.0 }, x)))
            }
            SolverStatus::PrimalInfeasible | SolverStatus::AlmostPrimalInfeasible => Ok(None),
            other => Err(StaticError::Solver(format!("{other:?}"))),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const W: f64 = 1000.0 * 9.81;

    /// The four corners of a 2a × 2a base at depth d below the CM, on level ground.
    fn corners(a: f64, d: f64, mu: f64) -> Vec<Support> {
        [(-a, -a), (a, -a), (a, a), (-a, a)]
            .iter()
            .map(|&(x, z)| Support {
                arm: Vector3::new(x, -d, z),
                normal: Vector3::y(),
                criterion: Friction::coulomb(mu),
                cohesion_n: 0.0,
            })
            .collect()
    }

    fn holds(s: &[Support], force: Vector3<f64>, moment: Vector3<f64>) -> bool {
        held(s, force - Vector3::y() * W, moment, W, 2.0).unwrap()
    }

    #[test]
    fn a_block_on_level_ground_is_held_by_a_push_up_to_mu_times_its_weight() {
        let s = corners(1.0, 0.5, 0.6);
        // Pushed at the height of its CM, 0.5 m above the base: it would tip only at H·0.5 = W·1.
        let push = |h: f64| {
            let f = Vector3::new(h, 0.0, 0.0);
            holds(&s, f, Vector3::zeros())
        };
        assert!(push(0.999 * 0.6 * W));
        assert!(!push(1.001 * 0.6 * W));
    }

    #[test]
    fn a_bonded_block_is_held_by_a_push_up_to_its_friction_and_its_cohesion_and_never_pulled() {
        // Four corners of μ 0.4, each with a quarter of a cohesion c A = 0.3 W: a push through
        // the CM's height is held up to (0.4 + 0.3) W; the bond carries shear without a press,
        // but lifts nothing: a pull of 1.001 W upward is not held, however strong the bond.
        let bonded: Vec<Support> = corners(1.0, 0.5, 0.4)
            .into_iter()
            .map(|s| Support {
                cohesion_n: 0.3 * W / 4.0,
                ..s
            })
            .collect();
        let push = |h: f64| holds(&bonded, Vector3::new(h, 0.0, 0.0), Vector3::zeros());
        assert!(push(0.999 * 0.7 * W));
        assert!(!push(1.001 * 0.7 * W));
        let lift = |p: f64| holds(&bonded, Vector3::new(0.0, p, 0.0), Vector3::zeros());
        assert!(lift(0.999 * W));
        assert!(!lift(1.001 * W));
        // Its yield, a further push along X: (0.7 − 0.1) W beyond a push of 0.1 W.
        let along = (Vector3::new(W, 0.0, 0.0), Vector3::zeros());
        let force = Vector3::new(0.1 * W, -W, 0.0);
        let s = reach(&bonded, force, Vector3::zeros(), along, W, 2.0).unwrap();
        assert!((s.unwrap() - 0.6).abs() < 1e-6, "{s:?}");
        // Corners of another cohesion are their own hull: a corner inside the bonded ones'
        // square, unbonded, is kept.
        let mut all = bonded.clone();
        all.push(Support {
            arm: Vector3::new(0.0, -0.5, 0.0),
            cohesion_n: 0.0,
            ..bonded[0]
        });
        assert_eq!(hull_supports(&all).len(), 5);
        assert_eq!(hull_supports(&bonded).len(), 4);
    }

    #[test]
    fn a_couple_about_the_vertical_is_held_up_to_the_corners_friction_times_their_arm() {
        // Each corner carries W/4 and μ W/4 across its arm of √2 a: T = μ W √2 a.
        let (a, mu) = (1.5, 0.4);
        let s = corners(a, 1.0, mu);
        let limit = mu * W * 2f64.sqrt() * a;
        let turn = |t: f64| holds(&s, Vector3::zeros(), Vector3::new(0.0, t, 0.0));
        assert!(turn(0.999 * limit));
        assert!(!turn(1.001 * limit));
    }

    #[test]
    fn a_push_high_above_the_base_tips_the_block_however_rough_the_ground() {
        // H at 3 m above the base (2.5 m above the CM) about the front edge: tips when
        // H · 3 > W · a.
        let s = corners(1.0, 0.5, 10.0);
        let tip = W / 3.0;
        let push = |h: f64| {
            let f = Vector3::new(h, 0.0, 0.0);
            // The couple of a force at 2.5 m above the CM along +X: r × F = (0, 2.5, 0) × (H, 0, 0).
            holds(&s, f, Vector3::new(0.0, 2.5, 0.0).cross(&f))
        };
        assert!(push(0.999 * tip));
        assert!(!push(1.001 * tip));
    }

    #[test]
    fn a_frictionless_block_on_an_incline_is_not_held_and_on_level_ground_it_is() {
        let dip = 10f64.to_radians();
        let n = Vector3::new(dip.sin(), dip.cos(), 0.0);
        let mut s = corners(1.0, 0.5, 0.0);
        assert!(holds(&s, Vector3::zeros(), Vector3::zeros()));
        for c in &mut s {
            c.normal = n;
        }
        assert!(!holds(&s, Vector3::zeros(), Vector3::zeros()));
        // With friction above tan 10° it is.
        for c in &mut s {
            c.criterion = Friction::coulomb(1.01 * dip.tan());
        }
        assert!(holds(&s, Vector3::zeros(), Vector3::zeros()));
    }

    #[test]
    fn a_block_with_nothing_under_it_is_not_held_and_bad_scales_are_an_error() {
        let down = -Vector3::y() * W;
        assert!(!held(&[], down, Vector3::zeros(), W, 1.0).unwrap());
        let s = corners(1.0, 0.5, 0.5);
        assert!(held(&s, down, Vector3::zeros(), 0.0, 1.0).is_err());
        assert!(held(&s, down, Vector3::zeros(), W, f64::NAN).is_err());
    }

    #[test]
    fn the_reach_of_a_push_on_level_ground_is_mu_times_the_weight_or_its_tipping_load() {
        // μ W before it tips (CM 0.5 m above a base 1 m either side: tips at W·1/0.5 = 2 W).
        let s = corners(1.0, 0.5, 0.6);
        let push = (Vector3::new(W, 0.0, 0.0), Vector3::zeros());
        let r = reach(&s, -Vector3::y() * W, Vector3::zeros(), push, W, 2.0).unwrap();
        assert!((r.unwrap() - 0.6).abs() < 1e-6, "{r:?}");
        // Rough ground: it tips first, at 2 W.
        let s = corners(1.0, 0.5, 10.0);
        let r = reach(&s, -Vector3::y() * W, Vector3::zeros(), push, W, 2.0).unwrap();
        assert!((r.unwrap() - 2.0).abs() < 1e-6, "{r:?}");
        // Already pushed by 0.7 W on μ = 0.6: nothing more is held.
        let s = corners(1.0, 0.5, 0.6);
        let f = Vector3::new(0.7 * W, -W, 0.0);
        assert_eq!(
            reach(&s, f, Vector3::zeros(), push, W, 2.0).unwrap(),
            Some(0.0)
        );
        // A load along the normal is held whatever its size.
        let down = (-Vector3::y() * W, Vector3::zeros());
        assert_eq!(
            reach(&s, -Vector3::y() * W, Vector3::zeros(), down, W, 2.0).unwrap(),
            None
        );
    }

    #[test]
    fn a_push_is_held_up_to_what_a_stress_dependent_criterion_gives_each_corner_at_its_share() {
        // Barton–Choubey at four corners in the plane of the CM (nothing tips the block): each
        // carries W/4, whose secant coefficient μ(W/4) = tan(JRC log10(JCS A / (W/4)) + φr)
        // holds a push up to μ(W/4) W, settled from the program's forces; the reach of a push
        // is that multiple.
        let criterion = Friction::barton_choubey(10.0, 5.0e7, 30f64.to_radians(), 0.01);
        let mut s = corners(1.0, 0.0, 0.0);
        for c in &mut s {
            c.criterion = criterion;
        }
        let sigma = W / 4.0 / 0.01;
        let mu = (10.0 * (5.0e7 / sigma).log10() + 30.0).to_radians().tan();
        assert!((criterion.coefficient(W / 4.0) - mu).abs() < 1e-12);
        let push = |h: f64| holds(&s, Vector3::new(h * W, 0.0, 0.0), Vector3::zeros());
        assert!(push(0.99 * mu));
        assert!(!push(1.01 * mu));
        let along = (Vector3::new(W, 0.0, 0.0), Vector3::zeros());
        let r = reach(&s, -Vector3::y() * W, Vector3::zeros(), along, W, 2.0).unwrap();
        assert!((r.unwrap() - mu).abs() < 1e-6, "{r:?} against {mu}");
        // At the weight's whole, a coefficient JRC log10(4) = 6° flatter would hold less.
        assert!(criterion.coefficient(W) < 0.9 * mu);
    }
}
