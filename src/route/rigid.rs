//! The route under rigid-body dynamics (`[solver] dynamics = "rigid-body"`, issue #7;
//! `derivations/08-rigid-body.md`).
//!
//! State y = (X, Z, θ, Ẋ, Ż, θ̇, W_h, W_f): the three degrees of freedom, their rates, and the
//! work done so far by the hydraulic force and couple (W_h) and by friction (W_f), integrated
//! with the motion by classic RK4 so that the energy balance can be checked to the
//! integrator's order. Constraint drift stays at round-off by construction: the pose is
//! recomputed from (X, Z, θ) by the tracker at every evaluation and the six-component twist is
//! the projection of (Ẋ, Ż, θ̇) onto the constraints (`mechanics::rigid_body::twist`).
//!
//! Stick and slip at the block level: at rest (the start, or when the motion stops), the block
//! stays put when static friction within the three cones can hold it
//! (`mechanics::static_friction`); otherwise it slips from rest in the direction that
//! reproduces itself. While sliding, a step over which the twist reverses (its kinetic-energy
//! inner product with the twist at the step's start turns non-positive) contains a stop; the
//! stop time is found by bisection on the step length and the velocity set to exactly zero.

use super::Route;
use super::pose_finder::{PoseFinder, PoseMethod};
use super::rhs::{Stop, pose_at};
use super::state::Row;
use super::termination::{Reason, Termination};
use crate::geometry::{Displacement, Pose};
use crate::mechanics::loads::Applied;
use crate::mechanics::rigid_body::{self, Motion, RigidError};
use crate::mechanics::static_friction::{self, StaticCheck};
use crate::mechanics::{ContactGeometry, statics};
use crate::scene::{Dynamics, Scene};
use serde::Serialize;

/// Energy bookkeeping of a rigid-body route (J), from the start to its last state.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize)]
pub struct EnergyBalance {
    /// Work of the hydraulic force and its couple.
    pub work_hydraulic_j: f64,
    /// Work of friction (≤ 0).
    pub work_friction_j: f64,
    /// Kinetic energy at the end.
    pub kinetic_j: f64,
    /// Change of potential energy m g ΔY_cm.
    pub potential_change_j: f64,
    /// W_h + W_f − (kinetic + potential change): zero up to the integrator's error.
    pub residual_j: f64,
}

type Y = [f64; 8];

/// One evaluation of the rigid-body right-hand side.
#[derive(Debug, Clone, Copy)]
struct Eval {
    pose: Pose,
    motion: Motion,
}

fn displacement(y: &Y) -> Displacement {
    Displacement::new(y[0], y[1], y[2])
}

fn stop_of(e: RigidError) -> Stop {
    let reason = match e {
        RigidError::LiftOff { .. } => Reason::ContactLiftedOff,
        RigidError::Singular(_) | RigidError::SlipFromRest => Reason::ContactForcesUndetermined,
    };
    Stop {
        reason,
        detail: e.to_string(),
    }
}

fn evaluate(
    scene: &Scene,
    dynamics: &Dynamics<'_>,
    finder: &mut PoseFinder<'_>,
    y: &Y,
) -> Result<Eval, Stop> {
    let pose = pose_at(scene, finder, displacement(y))?;
    let geom = ContactGeometry::new(scene, &pose);
    let applied = Applied::new(dynamics.loads, dynamics.block, &geom.frame);
    let motion = rigid_body::accelerations(
        &geom,
        &applied,
        dynamics.block,
        dynamics.friction,
        [y[3], y[4], y[5]],
    )
    .map_err(stop_of)?;
    Ok(Eval { pose, motion })
}

fn derivative(y: &Y, m: &Motion) -> Y {
    [
        y[3],
        y[4],
        y[5],
        m.acc[0],
        m.acc[1],
        m.acc[2],
        m.power_hydraulic,
        m.power_friction,
    ]
}

fn axpy(y: &Y, h: f64, k: &Y) -> Y {
    std::array::from_fn(|i| y[i] + h * k[i])
}

/// One classic RK4 step of length h from y, whose derivative k1 is known; stages evaluated on
/// clones of `finder`.
fn rk4(
    scene: &Scene,
    dynamics: &Dynamics<'_>,
    finder: &PoseFinder<'_>,
    y: &Y,
    k1: &Y,
    h: f64,
) -> Result<Y, Stop> {
    let stage = |y: &Y| {
        let mut f = finder.clone();
        evaluate(scene, dynamics, &mut f, y).map(|e| derivative(y, &e.motion))
    };
    let k2 = stage(&axpy(y, 0.5 * h, k1))?;
    let k3 = stage(&axpy(y, 0.5 * h, &k2))?;
    let k4 = stage(&axpy(y, h, &k3))?;
    Ok(std::array::from_fn(|i| {
        y[i] + h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i])
    }))
}

fn row(t: f64, y: &Y, e: &Eval) -> Row {
    Row {
        t_s: t,
        x_m: y[0],
        y_m: e.pose.cm.y,
        z_m: y[1],
        theta_deg: y[2].to_degrees(),
        alpha_deg: e.pose.alpha.to_degrees(),
        beta_deg: e.pose.beta.to_degrees(),
        gamma_deg: e.pose.gamma.to_degrees(),
        vx_m_s: y[3],
        vz_m_s: y[4],
        omega_deg_s: y[5].to_degrees(),
        n_n: Some(e.motion.normal),
        s_n: Some(e.motion.shear.map(|s| s.norm())),
    }
}

/// A row at rest (velocities zero; reactions not computed: static friction is indeterminate).
fn rest_row(t: f64, y: &Y, pose: &Pose) -> Row {
    Row {
        t_s: t,
        x_m: y[0],
        y_m: pose.cm.y,
        z_m: y[1],
        theta_deg: y[2].to_degrees(),
        alpha_deg: pose.alpha.to_degrees(),
        beta_deg: pose.beta.to_degrees(),
        gamma_deg: pose.gamma.to_degrees(),
        vx_m_s: 0.0,
        vz_m_s: 0.0,
        omega_deg_s: 0.0,
        n_n: None,
        s_n: None,
    }
}

/// The static check at a pose.
fn static_check(dynamics: &Dynamics<'_>, geom: &ContactGeometry) -> Result<StaticCheck, Stop> {
    let applied = Applied::new(dynamics.loads, dynamics.block, &geom.frame);
    let c = statics::frictionless_normals(geom, &applied).unwrap_or([1.0; 3]);
    static_friction::check(geom, &applied, dynamics.friction, &c).map_err(|err| Stop {
        reason: Reason::ContactForcesUndetermined,
        detail: err.to_string(),
    })
}

struct Outcome {
    rows: Vec<Row>,
    termination: Termination,
    fs: Option<f64>,
    travel: f64,
    increments: usize,
    energy: Option<EnergyBalance>,
}

/// Runs the rigid-body route of a scene whose dynamics sections are present.
pub(super) fn run(
    scene: &Scene,
    dynamics: &Dynamics<'_>,
    method: PoseMethod,
    progress: impl FnMut(f64),
) -> Route {
    let started = std::time::Instant::now();
    let solver = *dynamics.solver;
    let mut finder = PoseFinder::new(scene, solver.mode, method);
    let o = slide(scene, dynamics, &mut finder, progress);
    Route {
        scene: scene.name.clone(),
        mode: solver.mode,
        integrator: solver.integrator,
        dynamics: solver.dynamics,
        pose_method: method,
        rows: o.rows,
        termination: o.termination,
        factor_of_safety_onset: o.fs,
        travel_m: o.travel,
        increments: o.increments,
        friction_switches: 0,
        tracker: finder.stats(),
        end_jacobian_condition: finder.jacobian_condition(),
        energy: o.energy,
        wall_s: started.elapsed().as_secs_f64(),
    }
}

fn slide(
    scene: &Scene,
    dynamics: &Dynamics<'_>,
    finder: &mut PoseFinder<'_>,
    mut progress: impl FnMut(f64),
) -> Outcome {
    let solver = *dynamics.solver;
    let dt = solver.dt;
    let stride = solver.stride.max(1);
    let n_steps = (solver.t_end / dt).round().max(1.0) as usize;
    let mass = dynamics.block.mass;
    let g = dynamics.loads.gravity;
    let mut o = Outcome {
        rows: Vec::new(),
        termination: Termination {
            reason: Reason::TimeLimit,
            t_s: 0.0,
            detail: String::new(),
        },
        fs: None,
        travel: 0.0,
        increments: 0,
        energy: None,
    };
    let mut y: Y = [0.0; 8];
    let mut t = 0.0;
    let end = |mut o: Outcome, reason: Reason, t: f64, detail: String| {
        o.termination = Termination {
            reason,
            t_s: t,
            detail,
        };
        o
    };
    // The energy balance at a state with kinetic energy `kinetic` and CM height `cm_y`.
    let energy = |y: &Y, kinetic: f64, cm_y: f64, y0: f64| {
        let potential = mass * g * (cm_y - y0);
        EnergyBalance {
            work_hydraulic_j: y[6],
            work_friction_j: y[7],
            kinetic_j: kinetic,
            potential_change_j: potential,
            residual_j: y[6] + y[7] - kinetic - potential,
        }
    };
    let balance = |y: &Y, e: &Eval, y0: f64| {
        energy(
            y,
            e.motion.twist.kinetic_energy(mass, &e.motion.inertia),
            e.pose.cm.y,
            y0,
        )
    };

    // The start: at rest, held or not by static friction (decided before any acceleration is
    // sought: a held block has no consistent way to slip).
    let start_pose = finder.pose().expect("the flat start pose exists");
    let y0 = start_pose.cm.y;
    let check = match static_check(dynamics, &ContactGeometry::new(scene, &start_pose)) {
        Ok(c) => c,
        Err(Stop { reason, detail }) => {
            o.rows.push(rest_row(0.0, &y, &start_pose));
            return end(o, reason, 0.0, detail);
        }
    };
    o.fs = Some(check.factor_of_safety);
    if check.holds() {
        o.rows.push(rest_row(0.0, &y, &start_pose));
        let mut done = end(
            o,
            Reason::DoesNotSlide,
            0.0,
            format!(
                "static friction within the three cones holds the block: factor of safety {:.4} \
                 (the largest multiple of the hydraulic loads it can hold)",
                check.factor_of_safety
            ),
        );
        done.energy = Some(EnergyBalance::default());
        return done;
    }
    let mut ev = match evaluate(scene, dynamics, finder, &y) {
        Ok(e) => e,
        Err(Stop { reason, detail }) => {
            o.rows.push(rest_row(0.0, &y, &start_pose));
            return end(o, reason, 0.0, detail);
        }
    };
    o.rows.push(row(0.0, &y, &ev));

    let mut k = 0usize;
    let mut t_base = 0.0;
    let mut k_base = 0usize;
    // Restarts after a stop shift the time grid, so the loop ends on time (with a cap).
    while k < 2 * n_steps {
        let k1 = derivative(&y, &ev.motion);
        let mut next = match rk4(scene, dynamics, finder, &y, &k1, dt) {
            Ok(n) => n,
            Err(Stop { reason, detail }) => {
                o.energy = Some(balance(&y, &ev, y0));
                return end(o, reason, t, detail);
            }
        };
        let mut t_next = t_base + (k + 1 - k_base) as f64 * dt;
        let mut next_ev = match evaluate(scene, dynamics, finder, &next) {
            Ok(e) => e,
            Err(Stop { reason, detail }) => {
                o.energy = Some(balance(&y, &ev, y0));
                return end(o, reason, t, detail);
            }
        };
        // A stop inside the step: the twist reversed.
        let before = ev.motion.twist;
        let reversed = !before.is_zero()
            && next_ev
                .motion
                .twist
                .energy_dot(&before, mass, &ev.motion.inertia)
                <= 0.0;
        if reversed {
            let dot = |h: f64| -> Result<(f64, Y), Stop> {
                let yh = rk4(scene, dynamics, finder, &y, &k1, h)?;
                let geom_twist = {
                    let mut f = finder.clone();
                    let pose = pose_at(scene, &mut f, displacement(&yh))?;
                    let geom = ContactGeometry::new(scene, &pose);
                    rigid_body::twist(&geom, [yh[3], yh[4], yh[5]]).map_err(stop_of)?
                };
                Ok((geom_twist.energy_dot(&before, mass, &ev.motion.inertia), yh))
            };
            let (mut lo, mut hi) = (0.0, dt);
            let mut y_hi = next;
            for _ in 0..60 {
                if hi - lo <= 1e-12 * dt {
                    break;
                }
                let mid = 0.5 * (lo + hi);
                match dot(mid) {
                    Ok((d, _)) if d > 0.0 => lo = mid,
                    Ok((_, ym)) => {
                        hi = mid;
                        y_hi = ym;
                    }
                    Err(_) => hi = mid,
                }
            }
            let mut stopped = y_hi;
            stopped[3] = 0.0;
            stopped[4] = 0.0;
            stopped[5] = 0.0;
            let t_stop = t + hi;
            let stop_pose = match pose_at(scene, finder, displacement(&stopped)) {
                Ok(p) => p,
                Err(Stop { reason, detail }) => {
                    o.energy = Some(balance(&y, &ev, y0));
                    return end(o, reason, t, detail);
                }
            };
            o.travel += (stop_pose.cm - ev.pose.cm).norm();
            o.increments = k + 1;
            let check = match static_check(dynamics, &ContactGeometry::new(scene, &stop_pose)) {
                Ok(c) => c,
                Err(Stop { reason, detail }) => return end(o, reason, t, detail),
            };
            if check.holds() {
                o.rows.push(rest_row(t_stop, &stopped, &stop_pose));
                o.energy = Some(energy(&stopped, 0.0, stop_pose.cm.y, y0));
                return end(
                    o,
                    Reason::Stopped,
                    t_stop,
                    format!(
                        "the motion stopped at t = {t_stop:.6} s and static friction holds the \
                         block there (factor of safety {:.4})",
                        check.factor_of_safety
                    ),
                );
            }
            let stop_ev = match evaluate(scene, dynamics, finder, &stopped) {
                Ok(e) => e,
                Err(Stop { reason, detail }) => {
                    o.energy = Some(balance(&y, &ev, y0));
                    return end(o, reason, t_stop, detail);
                }
            };
            // Not held: it slips again from rest.
            next = stopped;
            next_ev = stop_ev;
            t_next = t_stop;
            t_base = t_stop;
            k_base = k + 1;
        } else {
            o.travel += (next_ev.pose.cm - ev.pose.cm).norm();
        }
        k += 1;
        o.increments = k;
        y = next;
        ev = next_ev;
        t = t_next;
        progress((t / solver.t_end).min(1.0));
        let last = t >= solver.t_end * (1.0 - 1e-12);
        if k % stride == 0 || last {
            o.rows.push(row(t, &y, &ev));
        }
        if last {
            break;
        }
    }
    o.energy = Some(balance(&y, &ev, y0));
    end(
        o,
        Reason::TimeLimit,
        t,
        format!("t reached t_end = {} s", solver.t_end),
    )
}
