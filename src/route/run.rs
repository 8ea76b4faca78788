//! The incremental failure route (paper §7): from the start of sliding, increment by
//! increment, until the route ends for a stated reason.

use super::Route;
use super::driver::drive as drive_model;
use super::outcome::Outcome;
use super::paper::{self, Paper};
use super::pose_finder::{PoseFinder, PoseMethod};
use super::rigid::RigidBody;
use super::state::Row;
use crate::mechanics::ContactGeometry;
use crate::mechanics::loads::Applied;
use crate::mechanics::static_friction;
use crate::scene::{DynamicsModel, Scene, SceneError, Simulation};
use std::ops::ControlFlow;
use std::time::Instant;

/// Runs the route of a scene (which needs its `[block]`, `[loads]`, `[friction]` and
/// `[solver]` sections): [`simulate`] on the scene's [`Simulation`], whose building is the
/// only thing that can fail.
pub fn run(scene: &Scene) -> Result<Route, SceneError> {
    run_observed(scene, |_| ControlFlow::Continue(()))
}

/// The route of a simulation, checked when it was built: nothing here can fail, every end is a
/// [`Reason`](super::Reason).
pub fn simulate(sim: &Simulation) -> Route {
    drive(
        sim,
        PoseMethod::Continuation,
        |_| ControlFlow::Continue(()),
        Outcome::new(None, 1),
    )
}

/// [`run`], calling `progress(t / t_end)` after every increment (for progress bars); when it
/// answers `ControlFlow::Break`, the route stops there with [`Reason::Interrupted`](super::Reason::Interrupted), its last
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
    let sim = Simulation::new(scene)?;
    Ok(drive(&sim, method, progress, Outcome::new(None, 1)))
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
    let sim = Simulation::new(scene)?;
    Ok(drive(
        &sim,
        PoseMethod::Continuation,
        progress,
        Outcome::new(Some(&mut sink), keep_every),
    ))
}

fn drive(
    dynamics: &Simulation,
    method: PoseMethod,
    progress: impl FnMut(f64) -> ControlFlow<()>,
    outcome: Outcome<'_>,
) -> Route {
    let started = Instant::now();
    let scene = dynamics.scene();
    let solver = *dynamics.solver();
    let mut finder = PoseFinder::new(scene, solver.mode, method);
    let start_pose = finder.pose();
    // One driver; the model is the only difference.
    let mut o = match solver.dynamics {
        DynamicsModel::Paper => {
            drive_model::<Paper>(scene, dynamics, &mut finder, progress, outcome)
        }
        DynamicsModel::RigidBody => {
            drive_model::<RigidBody>(scene, dynamics, &mut finder, progress, outcome)
        }
    };
    if o.fs.is_none() {
        // One factor of safety whatever the dynamics: the friction cones' at the start.
        o.fs = start_pose.and_then(|pose| {
            let geom = ContactGeometry::with_normals(dynamics.normals(), &pose);
            let applied = Applied::new(dynamics.loads(), dynamics.block(), &geom.frame);
            let strength = dynamics.strength(super::state::faces_of(&scene.site), true);
            static_friction::at_rest(&geom, &applied, &strength)
                .ok()
                .map(|c| c.factor_of_safety())
        });
    }
    if solver.dynamics == DynamicsModel::Paper {
        paper::explain_end(&mut o);
    }
    // Newmark's permanent displacement and rotation, when the foundation was shaken.
    let permanent = o
        .last_row()
        .filter(|_| scene.record().is_some())
        .map(|r| (r.x_m.hypot(r.z_m), r.theta_deg));
    Route {
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
        energy: o.energy,
        permanent_displacement_m: permanent.map(|p| p.0),
        permanent_rotation_deg: permanent.map(|p| p.1),
        diagnostics: super::Diagnostics {
            friction_switches: o.switches,
            tracker: finder.stats(),
            end_jacobian_condition: finder.jacobian_condition(),
            wall_s: started.elapsed().as_secs_f64(),
        },
    }
}
