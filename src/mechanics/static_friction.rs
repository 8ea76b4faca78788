//! Static friction at rest in the rigid-body mode: does a state of contact forces exist that
//! holds the block, with each contact force inside its friction cone? And the factor of safety
//! at onset (`derivations/08-rigid-body.md` §5).
//!
//! With the block at rest the six equilibrium equations (force and moment) are linear in the
//! nine unknowns λ_i (normal) and the two in-plane components of each shear f_i; the friction
//! cones |f_i| ≤ μ_i λ_i are second-order cones. Scaling the driving loads (the hydraulic force
//! F and its couples, the horizontal pseudo-static force) by t while the weight and the held
//! loads (uplift, the tailwater's weight, the vertical pseudo-static force) stay — the guideline
//! factor of safety, μ(W − U)/H on a level base (`derivations/11-dam-loads.md` §4) — the set of
//! t for which such a state exists is an interval
//! [t_lo, t_hi] (a convex set: the projection of a convex cone program). We compute both ends
//! with the conic interior-point solver Clarabel:
//!
//! * the factor of safety at onset is FS = t_hi, the largest multiple of the driving loads that
//!   static friction can hold (FS ≥ 1 where the loads as given are held; ∞ if any multiple is);
//! * the block is held at the loads as given when t_lo ≤ 1 ≤ t_hi (t_lo > 1 would mean that the
//!   weight alone pushes it back down the planes, and less than F would be needed to hold it).
//!
//! For stress-dependent criteria (Barton–Choubey) the cone of each contact uses the secant
//! coefficient μ_i = S(λ_i)/λ_i at its own normal force, iterated to a fixed point. Each contact
//! has its own face's criterion, and, while the joint is bonded, its share C_i of the cohesion:
//! its cone is then |f_i| ≤ μ_i λ_i + C_i, with λ_i ≥ 0 stated apart
//! (`derivations/11-dam-loads.md` §8).

use super::ContactGeometry;
use super::loads::Applied;
use crate::model::{ContactStrength, ContactStrengths, Settling};
use clarabel::algebra::CscMatrix;
use clarabel::solver::{
    DefaultSettings, DefaultSolver, IPSolver, SolverStatus, SupportedConeT::NonnegativeConeT,
    SupportedConeT::SecondOrderConeT, SupportedConeT::ZeroConeT,
};
use nalgebra::Vector3;

/// Why the static check has no answer.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum StaticError {
    /// The conic solver's failure, in its words.
    #[error("the cone program could not be solved: {0}")]
    Solver(String),
}

/// The interval of load multiples that static friction can hold at one pose.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HoldingRange {
    /// t_hi: the factor of safety (∞ when every multiple is held; −∞ when none is).
    pub factor_of_safety: f64,
    /// t_lo (−∞ when unbounded below; +∞ when no multiple is held).
    pub lowest: f64,
    /// Normal reactions of a holding state at t = min(1, t_hi) (N), for reports.
    pub normal: [f64; 3],
}

/// The factor of safety of a block at rest: one definition, whatever the dynamics
/// that move it afterwards. It is t_hi, the largest multiple of the driving loads (the hydraulic
/// force and its couple) at which static friction within the three cones can still hold the
/// block — equivalently, the loads divided by 1/t_hi are the most it can take. Below 1 the
/// loads as given start it. Two cases have no number, and say so in words rather than with an
/// infinity:
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
#[serde(tag = "kind", rename_all = "kebab-case")]
pub enum FactorOfSafety {
    /// t_hi, finite.
    Finite {
        /// t_hi.
        value: f64,
    },
    /// Every multiple of the driving loads is held: no scaling of them starts the block (they
    /// do not push it along any way it could slide).
    Unbounded,
    /// No multiple of the driving loads, not even none, is held: the weight alone makes the
    /// block slide on its planes (friction too low for the dips).
    NotHoldable,
}

impl FactorOfSafety {
    /// From t_hi as the cone programs give it (±∞, or NaN when infeasible).
    pub fn from_multiple(t_hi: f64) -> Self {
        if t_hi.is_finite() {
            FactorOfSafety::Finite { value: t_hi }
        } else if t_hi == f64::INFINITY {
            FactorOfSafety::Unbounded
        } else {
            FactorOfSafety::NotHoldable
        }
    }

    /// The number, where there is one.
    pub fn value(&self) -> Option<f64> {
        match self {
            FactorOfSafety::Finite { value } => Some(*value),
            _ => None,
        }
    }

    /// Whether the loads as given leave the block held (as far as t_hi says).
    pub fn at_least_one(&self) -> bool {
        match self {
            FactorOfSafety::Finite { value } => *value >= 1.0,
            FactorOfSafety::Unbounded => true,
            FactorOfSafety::NotHoldable => false,
        }
    }

    /// One word or number for a table cell: the value, `unbounded` or `not-holdable`.
    pub fn cell(&self) -> String {
        match self {
            FactorOfSafety::Finite { value } => format!("{value}"),
            FactorOfSafety::Unbounded => "unbounded".into(),
            FactorOfSafety::NotHoldable => "not-holdable".into(),
        }
    }
}

impl std::fmt::Display for FactorOfSafety {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            FactorOfSafety::Finite { value } => write!(f, "{value:.4}"),
            FactorOfSafety::Unbounded => {
                f.write_str("unbounded (no multiple of the water load starts the block)")
            }
            FactorOfSafety::NotHoldable => f.write_str(
                "none (the weight alone makes the block slide, whatever the water load)",
            ),
        }
    }
}

impl HoldingRange {
    /// The factor of safety this check gives.
    pub fn factor_of_safety(&self) -> FactorOfSafety {
        FactorOfSafety::from_multiple(self.factor_of_safety)
    }

    /// True when the loads as given are held: t_lo ≤ 1 ≤ t_hi.
    pub fn holds(&self) -> bool {
        self.lowest <= 1.0 && 1.0 <= self.factor_of_safety
    }

    /// What limits the load multiple t_hi, where it is finite: a contact that unloads there
    /// (its normal force under 1e-6 of theirs all: the loads' multiple tips the block onto the
    /// other two) or none (every contact presses and friction gives: it slides). The cone
    /// program's interior-point solution lies inside the set of optimal states, so a normal
    /// force is zero there only where every state at t_hi has it zero.
    pub fn limit(&self) -> Option<Limit> {
        if !self.factor_of_safety.is_finite() || self.normal.iter().any(|n| !n.is_finite()) {
            return None;
        }
        let total: f64 = self.normal.iter().map(|n| n.abs()).sum();
        if total <= 0.0 {
            return None;
        }
        let least = self.normal.iter().copied().fold(f64::INFINITY, f64::min);
        Some(if least <= 1e-6 * total {
            Limit::Tips
        } else {
            Limit::Slides
        })
    }
}

/// What limits the load multiple (`HoldingRange::limit`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Limit {
    /// Every contact presses at the limit: friction gives, the block slides.
    Slides,
    /// A contact unloads at the limit: the block tips onto the other two.
    Tips,
}

impl Limit {
    /// In words: "slides" or "tips".
    pub fn as_str(self) -> &'static str {
        match self {
            Limit::Slides => "slides",
            Limit::Tips => "tips",
        }
    }
}

const N_VAR: usize = 10;
const N_ROW: usize = 18;

/// One cone program: optimise `sense`·t (sense = −1: maximise). Returns t (±∞ when
/// unbounded, NaN when infeasible) and the normal forces (in units of the weight).
fn extreme_t(
    geom: &ContactGeometry,
    applied: &Applied,
    mu: &[f64; 3],
    cohesion: &[f64; 3],
    sense: f64,
) -> Result<(f64, [f64; 3]), StaticError> {
    let w = applied.weight.norm();
    let l = geom.r.iter().map(|r| r.norm()).fold(0.0, f64::max);
    let mut a = [[0.0; N_VAR]; N_ROW];
    let mut b = [0.0; N_ROW];
    // Columns: λ0, λ1, λ2, f0a, f0b, f1a, f1b, f2a, f2b, t.
    for i in 0..3 {
        let (t1, t2) = geom.tangents(i);
        let r = geom.r[i] / l;
        let cols = [(i, geom.n[i]), (3 + 2 * i, t1), (4 + 2 * i, t2)];
        for (c, v) in cols {
            let m = r.cross(&v);
            for k in 0..3 {
                a[k][c] = v[k];
                a[3 + k][c] = m[k];
            }
        }
        // λ_i ≥ 0 (with cohesion the cone alone would let a contact pull).
        a[6 + i][i] = -1.0;
        // Cone i: (μ λ_i + C_i, f_ia, f_ib) with s = b − A x, C_i its cohesion (in weights).
        a[9 + 3 * i][i] = -mu[i];
        b[9 + 3 * i] = cohesion[i] / w;
        a[10 + 3 * i][3 + 2 * i] = -1.0;
        a[11 + 3 * i][4 + 2 * i] = -1.0;
    }
    // Driving loads scaled by t; the weight and the held loads (uplift, the tailwater's
    // weight, the vertical pseudo-static force, and their moments) as they are.
    let force = applied.force / w;
    let moment = applied.moment / (w * l);
    let fixed = (applied.weight + applied.held_force) / w;
    let fixed_moment = applied.held_moment / (w * l);
    for k in 0..3 {
        a[k][9] = force[k];
        a[3 + k][9] = moment[k];
        b[k] = -fixed[k];
        b[3 + k] = -fixed_moment[k];
    }
    let p = CscMatrix::<f64>::zeros((N_VAR, N_VAR));
    let mut q = vec![0.0; N_VAR];
    q[9] = sense;
    let a = CscMatrix::from(&a);
    let cones = [
        ZeroConeT(6),
        NonnegativeConeT(3),
        SecondOrderConeT(3),
        SecondOrderConeT(3),
        SecondOrderConeT(3),
    ];
    let settings = DefaultSettings {
        verbose: false,
        ..DefaultSettings::default()
    };
    let mut solver = DefaultSolver::new(&p, &q, &a, &b, &cones, settings)
        .map_err(|e| StaticError::Solver(e.to_string()))?;
    solver.solve();
    let x = &solver.solution.x;
    match solver.solution.status {
        SolverStatus::Solved | SolverStatus::AlmostSolved => Ok((x[9], [x[0], x[1], x[2]])),
        SolverStatus::DualInfeasible | SolverStatus::AlmostDualInfeasible => {
            Ok((-sense * f64::INFINITY, [f64::NAN; 3]))
        }
        SolverStatus::PrimalInfeasible | SolverStatus::AlmostPrimalInfeasible => {
            Ok((f64::NAN, [f64::NAN; 3]))
        }
        other => Err(StaticError::Solver(format!("{other:?}"))),
    }
}

/// The static check at a pose (block at rest).
/// [`check`] with the frictionless normal reactions at the pose as the first normals of a
/// stress-dependent criterion (the block at rest, as at the start of a route).
pub fn at_rest(
    geom: &ContactGeometry,
    applied: &Applied,
    friction: &[ContactStrength],
) -> Result<HoldingRange, StaticError> {
    let c = super::statics::frictionless_normals(geom, applied).unwrap_or([1.0; 3]);
    check(geom, applied, friction, &c)
}

/// [`at_rest`] with the normal forces `c` at which a stress-dependent criterion's
/// coefficients start their fixed point.
pub fn check(
    geom: &ContactGeometry,
    applied: &Applied,
    friction: &[ContactStrength],
    statics: &[f64; 3],
) -> Result<HoldingRange, StaticError> {
    let w = applied.weight.norm();
    let mut mu = friction.coefficients(statics);
    let cohesion = &friction.cohesions();
    let stress_dependent = friction.is_stress_dependent();
    let hi = if stress_dependent {
        // The normals are per unit weight: the coefficients are those at λ·W.
        friction
            .settle(
                &mut mu,
                Settling {
                    tol: 1e-10,
                    max_solves: 50,
                },
                |mu| extreme_t(geom, applied, mu, cohesion, -1.0),
                |hi| hi.1[0].is_finite().then(|| hi.1.map(|l| l * w)),
            )?
            .0
    } else {
        extreme_t(geom, applied, &mu, cohesion, -1.0)?
    };
    let lo = extreme_t(geom, applied, &mu, cohesion, 1.0)?;
    if hi.0.is_nan() {
        // No multiple of the loads is held.
        return Ok(HoldingRange {
            factor_of_safety: f64::NEG_INFINITY,
            lowest: f64::INFINITY,
            normal: [f64::NAN; 3],
        });
    }
    Ok(HoldingRange {
        factor_of_safety: hi.0,
        lowest: lo.0,
        normal: hi.1.map(|l| l * w),
    })
}

/// The largest multiple t of the driving loads of `applied` that static friction within the
/// cones holds, the held loads (and the weight) as they are: ∞ when every multiple is, none
/// when no multiple is (with no driving loads: whether the held loads alone are held). With the driving loads a change of the loads along one direction,
/// how far along it the block stays held (`route/rigid/held_region.rs`). Constant coefficients
/// (a stress-dependent criterion's cones move with the normal forces).
pub fn reach(
    geom: &ContactGeometry,
    applied: &Applied,
    friction: &[ContactStrength],
) -> Result<Option<f64>, StaticError> {
    let mu = friction.coefficients(&[1.0; 3]);
    let (t, _) = extreme_t(geom, applied, &mu, &friction.cohesions(), -1.0)?;
    Ok((!t.is_nan()).then_some(t))
}

/// The yield acceleration of a block at rest (`derivations/11-dam-loads.md` §7): the least
/// horizontal ground acceleration, in any direction, that static friction within the cones
/// cannot hold with the loads as given.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct YieldAcceleration {
    /// k_y (g): zero where the loads as given already start the block.
    pub ky_g: f64,
    /// Where the block is then pushed, its inertial force's direction in plan (degrees from
    /// X towards Z); the ground accelerates the other way.
    pub push_deg: f64,
}

/// The step of the scan of directions for the yield acceleration (degrees).
const SCAN_DEG: f64 = 4.0;

/// [`YieldAcceleration`] at the pose of `geom` under `applied`, the block's weight m g (N) at
/// its centre of mass `arm` from the frame's origin (m), with the coefficients of `friction`
/// at the normal forces `statics` (N). The most ground acceleration held with the block pushed
/// along u, k(u), is one cone program (the driving loads are those of one g along u, all
/// else held); k_y is its least over u, found on a scan every `SCAN_DEG` and then by golden
/// section to 1e-9 rad about the least. None where no horizontal acceleration starts the
/// block. k(u) is the radial extent of a convex set about the origin, smooth between the
/// directions of its corners; a minimum narrower than the scan's step could be missed.
pub fn yield_acceleration(
    geom: &ContactGeometry,
    applied: &Applied,
    (weight, arm): (f64, Vector3<f64>),
    friction: &[ContactStrength],
    statics: &[f64; 3],
) -> Result<Option<YieldAcceleration>, StaticError> {
    let mu = friction.coefficients(statics);
    let cohesion = &friction.cohesions();
    let pushed = |angle: f64| -> Result<f64, StaticError> {
        let u = Vector3::new(angle.cos(), 0.0, angle.sin()) * weight;
        let unit = Applied {
            force: u,
            moment: arm.cross(&u),
            weight: applied.weight,
            held_force: applied.held_force + applied.force,
            held_moment: applied.held_moment + applied.moment,
        };
        let (t, _) = extreme_t(geom, &unit, &mu, cohesion, -1.0)?;
        // Infeasible at every multiple: not held even unshaken.
        Ok(if t.is_nan() { 0.0 } else { t.max(0.0) })
    };
    least_over_directions(pushed)
}

/// The least of `pushed(u)` (g) over the horizontal directions u (rad from X towards Z): a
/// scan every [`SCAN_DEG`], then golden section to 1e-9 rad about the least. None where it is
/// infinite everywhere (nothing starts the block).
pub(crate) fn least_over_directions<E>(
    mut pushed: impl FnMut(f64) -> Result<f64, E>,
) -> Result<Option<YieldAcceleration>, E> {
    let steps = (360.0 / SCAN_DEG).round() as usize;
    let scan: Vec<f64> = (0..steps)
        .map(|k| pushed((k as f64 * SCAN_DEG).to_radians()))
        .collect::<Result<_, _>>()?;
    let (best, &k) = scan
        .iter()
        .enumerate()
        .min_by(|a, b| a.1.total_cmp(b.1))
        .expect("a scan of directions");
    if k.is_infinite() {
        return Ok(None);
    }
    // Golden section on the step either side.
    let at = best as f64 * SCAN_DEG;
    let (mut lo, mut hi) = ((at - SCAN_DEG).to_radians(), (at + SCAN_DEG).to_radians());
    let ratio = (5f64.sqrt() - 1.0) / 2.0;
    let (mut a, mut b) = (hi - ratio * (hi - lo), lo + ratio * (hi - lo));
    let (mut fa, mut fb) = (pushed(a)?, pushed(b)?);
    while hi - lo > 1e-9 {
        if fa <= fb {
            hi = b;
            (b, fb) = (a, fa);
            a = hi - ratio * (hi - lo);
            fa = pushed(a)?;
        } else {
            lo = a;
            (a, fa) = (b, fb);
            b = lo + ratio * (hi - lo);
            fb = pushed(b)?;
        }
    }
    let (angle, ky) = if fa.min(fb) < k {
        if fa <= fb { (a, fa) } else { (b, fb) }
    } else {
        (at.to_radians(), k)
    };
    Ok(Some(YieldAcceleration {
        ky_g: ky,
        push_deg: angle.to_degrees().rem_euclid(360.0),
    }))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::Pose;
    use crate::mechanics::statics::frictionless_normals;
    use crate::scene::Scene;

    /// The holding range of the default scene with `keys` set, at the start (level, unturned),
    /// from its frictionless normal forces.
    fn held_at_start(keys: &[(&str, f64)]) -> HoldingRange {
        let s = Scene::default_scene()
            .with_keys(keys.iter().copied())
            .unwrap();
        let pose =
            Pose::from_tilts(s.site.as_paper().unwrap(), Default::default(), 0.0, 0.0).unwrap();
        let g = ContactGeometry::new(&s.site().normals(), &pose);
        let d = s.simulation().unwrap();
        let applied = Applied::new(d.first_body().loads(), d.first_body().block(), &g.frame);
        let c = frictionless_normals(&g, &applied).unwrap();
        check(
            &g,
            &applied,
            &d.first_body()
                .frame_strength(d.strengths(), [0, 1, 2], false),
            &c,
        )
        .unwrap()
    }

    #[test]
    fn a_flat_block_without_couple_is_held_up_to_mu_times_weight() {
        // Nearly flat planes, no eccentricity: the held force is μ W (the planes' normals lean
        // by 0.01°, which changes it by O(1e-4)).
        let st = held_at_start(&[
            ("foundation.xi_deg", 0.01),
            ("foundation.zeta_deg", 0.01),
            ("loads.eccentricity_m", 0.0),
        ]);
        let want = 0.4 * 9.81e6 / 8e6;
        assert!(
            (st.factor_of_safety - want).abs() < 1e-3 * want,
            "{}",
            st.factor_of_safety
        );
        assert!(!st.holds());
    }

    #[test]
    fn high_friction_holds_and_zero_friction_does_not() {
        for (mu_k, holds) in [(2.0, true), (0.0, false)] {
            let st = held_at_start(&[("friction.mu_k", mu_k)]);
            assert_eq!(st.holds(), holds, "{st:?}");
        }
    }
}
