//! The incremental failure route (paper §7): from the start of sliding, increment by
//! increment, until the route ends for a stated reason.

use super::Route;
use super::integrator::{paper_step, rk4_step};
use super::pose_finder::{PoseFinder, PoseMethod};
use super::rhs::{Evaluation, Stop, evaluate, velocity};
use super::state::{Row, State};
use super::termination::{Reason, Termination};
use crate::mechanics::ContactGeometry;
use crate::mechanics::loads::Applied;
use crate::mechanics::onset::factor_of_safety;
use crate::mechanics::static_friction::{self, FactorOfSafety};
use crate::scene::{DynamicsModel, Integrator, Scene, SceneError};
use std::ops::ControlFlow;
use std::time::Instant;

fn row(s: &State, ev: Option<&Evaluation>, pose: &crate::geometry::Pose) -> Row {
    Row {
        t_s: s.t,
        x_m: s.x,
        y_m: pose.cm.y,
        z_m: s.z,
        theta_deg: s.theta.to_degrees(),
        alpha_deg: pose.alpha.to_degrees(),
        beta_deg: pose.beta.to_degrees(),
        gamma_deg: pose.gamma.to_degrees(),
        vx_m_s: s.vx,
        vz_m_s: s.vz,
        omega_deg_s: s.omega.to_degrees(),
        n_n: ev.map(|e| e.reaction.normal.map(|v| v.norm())),
        s_n: ev.map(|e| e.reaction.shear.map(|v| v.norm())),
    }
}

/// What a route's loop produced (either dynamics), before the diagnostics are added. Rows go
/// through [`Outcome::push`]: each to the sink, if any (streamed as computed), and every
/// `keep_every`-th (and the last) kept in `rows`.
pub(super) struct Outcome<'s> {
    rows: Vec<Row>,
    sink: Option<&'s mut dyn FnMut(&Row)>,
    keep_every: usize,
    pushed: usize,
    last: Option<Row>,
    pub termination: Termination,
    /// The factor of safety at the start (the friction cones' definition).
    pub fs: Option<FactorOfSafety>,
    /// The paper's resisting-over-driving ratio at the start (paper's dynamics).
    pub paper_ratio: Option<f64>,
    pub travel: f64,
    pub increments: usize,
    /// How often the paper's frictional solution was chosen afresh (paper's dynamics).
    pub switches: usize,
    /// The energy balance (rigid-body dynamics).
    pub energy: Option<super::rigid::EnergyBalance>,
}

impl<'s> Outcome<'s> {
    /// Nothing yet: ends at the time limit unless told otherwise. Rows go to `sink` (if any)
    /// and every `keep_every`-th is kept.
    pub fn new(sink: Option<&'s mut dyn FnMut(&Row)>, keep_every: usize) -> Self {
        Outcome {
            rows: Vec::new(),
            sink,
            keep_every: keep_every.max(1),
            pushed: 0,
            last: None,
            termination: Termination {
                reason: Reason::TimeLimit,
                t_s: 0.0,
                detail: String::new(),
            },
            fs: None,
            paper_ratio: None,
            travel: 0.0,
            increments: 0,
            switches: 0,
            energy: None,
        }
    }

    /// The route ends for `reason` at `t`, its last state `last` recorded as the last row
    /// whatever the stride (issue #13).
    pub fn finish(mut self, last: Row, reason: Reason, t: f64, detail: String) -> Self {
        if self.last.is_none_or(|r| r.t_s != last.t_s) {
            self.push(last);
        }
        self.end(reason, t, detail)
    }

    /// One row of the route: to the sink, and kept if it is a `keep_every`-th.
    pub fn push(&mut self, row: Row) {
        if let Some(sink) = self.sink.as_mut() {
            sink(&row);
        }
        if self.pushed.is_multiple_of(self.keep_every) {
            self.rows.push(row);
        }
        self.pushed += 1;
        self.last = Some(row);
    }

    /// The kept rows, the last row always among them (taken out of the outcome).
    fn take_rows(&mut self) -> Vec<Row> {
        if let Some(last) = self.last {
            if self.rows.last().is_none_or(|r| r.t_s != last.t_s) {
                self.rows.push(last);
            }
        }
        std::mem::take(&mut self.rows)
    }

    /// The route ends for `reason` at `t`.
    pub fn end(mut self, reason: Reason, t: f64, detail: String) -> Self {
        self.termination = Termination {
            reason,
            t_s: t,
            detail,
        };
        self
    }
}

/// Runs the route of a scene (which needs its `[block]`, `[loads]`, `[friction]` and
/// `[solver]` sections).
pub fn run(scene: &Scene) -> Result<Route, SceneError> {
    run_observed(scene, |_| ControlFlow::Continue(()))
}

/// [`run`], calling `progress(t / t_end)` after every increment (for progress bars); when it
/// answers `ControlFlow::Break`, the route stops there with [`Reason::Interrupted`], its last
/// state the last row (issue #13: Ctrl-C writes what was computed).
pub fn run_observed(
    scene: &Scene,
    progress: impl FnMut(f64) -> ControlFlow<()>,
) -> Result<Route, SceneError> {
    run_with(scene, PoseMethod::Continuation, progress)
}

/// [`run_observed`] with a chosen method for the pose at each increment.
pub fn run_with(
    scene: &Scene,
    method: PoseMethod,
    progress: impl FnMut(f64) -> ControlFlow<()>,
) -> Result<Route, SceneError> {
    drive(scene, method, progress, Outcome::new(None, 1))
}

/// [`run_observed`] for routes of any length in bounded memory (issue #13): every row goes to
/// `sink` as it is computed (to be written out), and the returned route keeps only every
/// `keep_every`-th row and the last (for pictures and summaries).
pub fn run_streamed(
    scene: &Scene,
    progress: impl FnMut(f64) -> ControlFlow<()>,
    keep_every: usize,
    mut sink: impl FnMut(&Row),
) -> Result<Route, SceneError> {
    drive(
        scene,
        PoseMethod::Continuation,
        progress,
        Outcome::new(Some(&mut sink), keep_every),
    )
}

fn drive(
    scene: &Scene,
    method: PoseMethod,
    progress: impl FnMut(f64) -> ControlFlow<()>,
    outcome: Outcome<'_>,
) -> Result<Route, SceneError> {
    let started = Instant::now();
    let dynamics = scene.require_dynamics()?;
    let solver = *dynamics.solver;
    let mut finder = PoseFinder::new(scene, solver.mode, method);
    let start_pose = finder.pose();
    let mut o = match solver.dynamics {
        DynamicsModel::Paper => slide(scene, &dynamics, &mut finder, progress, outcome),
        DynamicsModel::RigidBody => {
            super::rigid::slide(scene, &dynamics, &mut finder, progress, outcome)
        }
    };
    if o.fs.is_none() {
        // One factor of safety whatever the dynamics: the friction cones' at the start.
        o.fs = start_pose.and_then(|pose| {
            let geom = ContactGeometry::with_normals(&dynamics.normals, &pose);
            let applied = Applied::new(dynamics.loads, dynamics.block, &geom.frame);
            static_friction::at_rest(&geom, &applied, dynamics.friction)
                .ok()
                .map(|c| c.factor_of_safety())
        });
    }
    if solver.dynamics == DynamicsModel::Paper {
        explain_paper_end(&mut o);
    }
    Ok(Route {
        scene: scene.name.clone(),
        mode: solver.mode,
        integrator: solver.integrator,
        dynamics: solver.dynamics,
        pose_method: method,
        rows: o.take_rows(),
        termination: o.termination,
        factor_of_safety: o.fs,
        paper_ratio: o.paper_ratio,
        travel_m: o.travel,
        increments: o.increments,
        friction_switches: o.switches,
        tracker: finder.stats(),
        end_jacobian_condition: finder.jacobian_condition(),
        energy: o.energy,
        wall_s: started.elapsed().as_secs_f64(),
    })
}

/// The number of increments of dt that reach `t_end`: the last may be shorter, so that the route
/// ends exactly at `t_end` (issue #13); a remainder below 1e-9·dt is dropped as round-off.
pub(super) fn increments(t_end: f64, dt: f64) -> usize {
    ((t_end / dt - 1e-9).ceil()).max(1.0) as usize
}

/// The time at which increment `k` (1-based) ends: k·dt, and `t_end` for the last.
pub(super) fn increment_end(t_end: f64, dt: f64, k: usize) -> f64 {
    if k >= increments(t_end, dt) {
        t_end
    } else {
        k as f64 * dt
    }
}

/// The length of increment `k`.
fn increment_length(t_end: f64, dt: f64, k: usize) -> f64 {
    increment_end(t_end, dt, k) - (k - 1) as f64 * dt
}

/// Where the paper's dynamics cannot start or continue the block, the detail says so and names
/// the rigid body's (issue #12): its kinematics hold only where its frictional system has a
/// solution and its contacts stay on their planes, which is not physics ending the route.
fn explain_paper_end(o: &mut Outcome<'_>) {
    let t = &mut o.termination;
    let hint = match t.reason {
        Reason::DoesNotSlide if o.fs.is_some_and(|f| !f.at_least_one()) => Some(format!(
            "the paper's dynamics cannot start this block, yet the friction cones cannot hold \
             it (factor of safety {}): run it with --dynamics rigid-body",
            o.fs.map(|f| f.to_string()).unwrap_or_default()
        )),
        Reason::NoFrictionSolution
        | Reason::NoAdmissibleRoot
        | Reason::ContactLeftPlane
        | Reason::ContactLiftedOff => Some(
            "the paper's dynamics cannot continue here (its kinematics, translation along x' and \
             turning about y', hold only where its frictional system has a solution that keeps \
             the contacts on their planes); --dynamics rigid-body follows the block by Newton's \
             laws"
                .to_string(),
        ),
        _ => None,
    };
    if let Some(h) = hint {
        t.detail = format!("{}; {h}", t.detail);
    }
}

fn slide<'s>(
    scene: &Scene,
    dynamics: &crate::scene::Dynamics<'_>,
    finder: &mut PoseFinder<'_>,
    mut progress: impl FnMut(f64) -> ControlFlow<()>,
    outcome: Outcome<'s>,
) -> Outcome<'s> {
    let solver = *dynamics.solver;
    let dt = solver.dt;
    // At rest, or moving as the scene's [initial] says.
    let mut state = State {
        vx: scene.initial.vx,
        vz: scene.initial.vz,
        omega: scene.initial.omega,
        ..State::default()
    };
    let mut o = outcome;

    // The start: pose, statics and whether the block slides at all (a block that starts
    // moving goes on until it stops, whatever the factor of safety).
    let start_pose = finder.pose().expect("the flat start pose exists");
    let mut ev = match evaluate(
        scene,
        dynamics,
        finder,
        state.displacement(),
        None,
        velocity(&state),
    ) {
        Ok(ev) => ev,
        Err(Stop { reason, detail }) => {
            o.push(row(&state, None, &start_pose));
            return o.end(reason, 0.0, detail);
        }
    };
    let applied = Applied::new(dynamics.loads, dynamics.block, &ev.geom.frame);
    let (fs, driving, resisting) =
        factor_of_safety(&ev.geom, &applied, &ev.statics, dynamics.friction);
    o.paper_ratio = fs.is_finite().then_some(fs);
    o.push(row(&state, Some(&ev), &ev.pose));
    if scene.initial.at_rest() && (fs >= 1.0 || ev.reaction.accel <= 0.0) {
        let detail = if driving <= 0.0 {
            format!("nothing drives the block: net driving force along x' is {driving:.6e} N")
        } else if fs >= 1.0 {
            format!(
                "factor of safety {fs:.4} ≥ 1: resisting capacity {resisting:.6e} N against driving {driving:.6e} N"
            )
        } else {
            format!(
                "the paper's reactions give no forward acceleration ({:.6e} m/s²)",
                ev.reaction.accel
            )
        };
        return o.end(Reason::DoesNotSlide, 0.0, detail);
    }

    let stride = solver.stride.max(1);
    let n_steps = increments(solver.t_end, dt);
    for k in 1..=n_steps {
        // Advance one increment; the last one ends exactly at t_end.
        let dt = increment_length(solver.t_end, dt, k);
        let next = match solver.integrator {
            Integrator::Paper => Ok(paper_step(&state, &ev.acc, dt)),
            Integrator::Rk4 => {
                let base = finder.clone();
                let prev = ev.reaction;
                rk4_step(&state, &ev.acc, dt, |s: &State| {
                    let mut f = base.clone();
                    evaluate(
                        scene,
                        dynamics,
                        &mut f,
                        s.displacement(),
                        Some(&prev),
                        velocity(s),
                    )
                    .map(|e| e.acc)
                })
            }
        };
        let next = match next {
            // Time as k·dt (t_end at the last), not a running sum.
            Ok(n) => State {
                t: increment_end(solver.t_end, solver.dt, k),
                ..n
            },
            Err(Stop { reason, detail }) => {
                return o.finish(row(&state, Some(&ev), &ev.pose), reason, state.t, detail);
            }
        };
        let new_ev = match evaluate(
            scene,
            dynamics,
            finder,
            next.displacement(),
            Some(&ev.reaction),
            velocity(&next),
        ) {
            Ok(e) => e,
            Err(Stop { reason, detail }) => {
                return o.finish(row(&state, Some(&ev), &ev.pose), reason, state.t, detail);
            }
        };
        if new_ev.fresh {
            o.switches += 1;
        }
        o.increments = k;
        // Stopped: the CM velocity along the acceleration — along i', the direction the paper's
        // dynamics drive (eqs. 30–35) — passes through zero in the increment, and friction
        // holds there. The paper's model has no friction against the velocity across i' (a
        // drift of a fraction of a per cent of the speed where we measured it), so the speed
        // itself only passes through a minimum; the stop sets it to zero.
        let (v, a) = ([state.vx, state.vz], [ev.acc[0], ev.acc[1]]);
        let along = |w: [f64; 2]| w[0] * a[0] + w[1] * a[1];
        if along(v) < 0.0 && along([next.vx, next.vz]) >= 0.0 {
            // Where the paper's update (accelerations frozen over the increment) brings it to
            // zero: (v + a τ)·a = 0 (with RK4, to first order in τ).
            let tau = (-along(v) / along(a)).clamp(0.0, dt);
            let mut stop = paper_step(&state, &ev.acc, tau);
            stop.vx = 0.0;
            stop.vz = 0.0;
            stop.omega = 0.0;
            let mut at_stop = finder.clone();
            let stop_ev = match evaluate(
                scene,
                dynamics,
                &mut at_stop,
                stop.displacement(),
                Some(&ev.reaction),
                None,
            ) {
                Ok(e) => e,
                Err(Stop { reason, detail }) => {
                    return o.finish(row(&state, Some(&ev), &ev.pose), reason, state.t, detail);
                }
            };
            let applied = Applied::new(dynamics.loads, dynamics.block, &stop_ev.geom.frame);
            let (fs_here, _, _) =
                factor_of_safety(&stop_ev.geom, &applied, &stop_ev.statics, dynamics.friction);
            if fs_here >= 1.0 {
                o.travel += (stop_ev.pose.cm - ev.pose.cm).norm();
                o.push(row(&stop, Some(&stop_ev), &stop_ev.pose));
                let detail = format!(
                    "speed reached zero at t = {:.6} s; factor of safety there {fs_here:.4}",
                    stop.t
                );
                return o.end(Reason::Stopped, stop.t, detail);
            }
        }
        o.travel += (new_ev.pose.cm - ev.pose.cm).norm();
        state = next;
        ev = new_ev;
        if k % stride == 0 || k == n_steps {
            o.push(row(&state, Some(&ev), &ev.pose));
        }
        if progress(k as f64 / n_steps as f64).is_break() {
            let t = state.t;
            return o.finish(
                row(&state, Some(&ev), &ev.pose),
                Reason::Interrupted,
                t,
                format!("interrupted at t = {} s", crate::numeric::seconds(t)),
            );
        }
    }
    let detail = format!("t reached t_end = {} s", solver.t_end);
    let t = state.t;
    o.end(Reason::TimeLimit, t, detail)
}
