//! The ladders of the work–precision report: each series' error of the route against its run
//! time, over a ladder of increments or of tolerances, against its scene's reference; and the
//! points they give ([`Point`], [`Reference`]) and what is read off them ([`speedups`]).
//!
//! The paper's dynamics: the reference is exact mode, RK4, continuation, dt_ref = 0.02 s / 512,
//! over a horizon that ends before the route does (paper-like 1 s, shallow 0.5 s). Every dt of
//! the ladder (0.02 s / 2^k) is an exact binary multiple of dt_ref, so rows match in time
//! exactly. The reference is established by running it again at dt_ref / 2.
//!
//! The rigid body chooses its own steps against `solver.tolerance`, its rows every
//! 0.02 s / 8: the ladder is of tolerances (10⁻⁵ … 10⁻¹⁰), the reference at 10⁻¹³, established
//! by running it again at 10⁻¹⁴. Either way the largest CM distance between a reference and its
//! check must be below 1e-9·L (reported as `reference_change_m`).
//!
//! The paper's dynamics with RK4 takes as many substeps an increment as `solver.tolerance` asks
//! (`route/paper/mod.rs`): its ladder of increments runs at the loosest tolerance, 10⁻³, where
//! no increment of the ladder is cut, so that it shows RK4's order in dt; and one more series,
//! continuation in exact mode, runs the same ladder of tolerances as the rigid body with its
//! rows every 0.02 s, against the paper's reference.

use crate::{Computed, DynamicsModel, Integrator, Mode, PoseMethod, Route, Runner, Scene};
use serde::Serialize;
use std::time::Instant;

/// The shallow example scene, compiled in for the report.
const SHALLOW_SCENE_TOML: &str = include_str!("../../../scenes/shallow.toml");

/// One measured point of one series.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub(crate) struct Point {
    pub scene: String,
    pub dynamics: DynamicsModel,
    pub method: PoseMethod,
    pub mode: Mode,
    pub integrator: Integrator,
    /// The rows' interval; the paper's dynamics' increment.
    pub dt_s: f64,
    /// The tolerance the steps were chosen against: the rigid body's, and the paper's
    /// dynamics' in its series by tolerance; none for the paper's ladder of increments (its
    /// steps are dt, at the loosest tolerance).
    pub tolerance: Option<f64>,
    pub increments: usize,
    /// The integration steps: those chosen against the tolerance, else the increments.
    pub steps: usize,
    /// Median wall time of the repeats (s).
    pub wall_s: f64,
    /// Largest CM distance from the reference at matching times (m).
    pub error_m: f64,
}

/// How each scene's reference was established.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub(crate) struct Reference {
    pub scene: String,
    pub dynamics: DynamicsModel,
    pub horizon_s: f64,
    pub dt_s: f64,
    /// The rigid body's reference tolerance (checked at a tenth of it).
    pub tolerance: Option<f64>,
    /// Largest CM distance between the reference and the same run at dt_ref / 2, or at a
    /// tenth of the tolerance (m).
    pub change_m: f64,
    /// 1e-9·L.
    pub bound_m: f64,
}

const DT0: f64 = 0.02;

/// The rigid body's rows' interval in the report.
const RIGID_ROWS_DT: f64 = DT0 / 8.0;

/// The rigid body's reference tolerance.
const RIGID_REFERENCE_TOLERANCE: f64 = 1e-13;

/// The paper's dynamics' rows in its series by tolerance.
const PAPER_TOLERANCE_ROWS_DT: f64 = DT0;

/// How one series of the ladder runs: the dynamics, the pose method, the mode, the integrator,
/// and whether over a ladder of tolerances (else of increments).
#[derive(Debug, Clone, Copy, PartialEq)]
struct Series {
    dynamics: DynamicsModel,
    method: PoseMethod,
    mode: Mode,
    integrator: Integrator,
    by_tolerance: bool,
}

/// The series of the ladder: every pose method, mode and integrator of the paper's dynamics
/// over increments, the paper's dynamics as continuation in exact mode with RK4 over
/// tolerances, then the rigid body as it runs by default (continuation, exact mode, RK4; it
/// takes no other mode or integrator) over tolerances.
fn series() -> Vec<Series> {
    let mut out = Vec::new();
    for method in [PoseMethod::Continuation, PoseMethod::AllRoots] {
        for mode in [Mode::Exact, Mode::SmallAngle] {
            for integrator in [Integrator::Paper, Integrator::Rk4] {
                out.push(Series {
                    dynamics: DynamicsModel::Paper,
                    method,
                    mode,
                    integrator,
                    by_tolerance: false,
                });
            }
        }
    }
    for dynamics in [DynamicsModel::Paper, DynamicsModel::RigidBody] {
        out.push(Series {
            dynamics,
            method: PoseMethod::Continuation,
            mode: Mode::Exact,
            integrator: Integrator::Rk4,
            by_tolerance: true,
        });
    }
    out
}

/// `scene` under `dynamics` in `mode` with `integrator`, `dt` and `t_end` (s), every increment
/// recorded.
fn with_solver(
    scene: &Scene,
    dynamics: DynamicsModel,
    mode: Mode,
    integrator: Integrator,
    (dt, tolerance): (f64, Option<f64>),
    t_end: f64,
) -> Result<Scene, String> {
    let tolerance = tolerance.unwrap_or(crate::DEFAULT_TOLERANCE);
    let keys: [(&str, toml::Value); 7] = [
        ("dynamics", dynamics.as_str().into()),
        ("mode", mode.as_str().into()),
        ("integrator", integrator.as_str().into()),
        ("dt_s", dt.into()),
        ("t_end_s", t_end.into()),
        ("stride", 1.into()),
        ("tolerance", tolerance.into()),
    ];
    // Its callers pass the report's own valid steps and horizons.
    scene
        .with_keys(keys.map(|(key, value)| (format!("solver.{key}"), value)))
        .map_err(|e| format!("report ladder scene: {e}"))
}

/// The route of `scene` by `method`, and how its computation went.
pub(super) fn computed(scene: &Scene, method: PoseMethod) -> Result<Computed, String> {
    let sim = scene.simulation().map_err(|e| e.to_string())?;
    Ok(Runner::new(&sim).pose_method(method).run())
}

/// The route of `scene` by `method`.
fn run(scene: &Scene, method: PoseMethod) -> Result<Route, String> {
    computed(scene, method).map(|c| c.route)
}

/// Largest CM distance between `coarse` and `fine` at the coarse times (fine dt divides coarse).
fn max_distance(coarse: &Route, fine: &Route, ratio: usize) -> f64 {
    coarse
        .rows
        .iter()
        .enumerate()
        .filter_map(|(k, r)| fine.rows.get(k * ratio).map(|q| (r, q)))
        .map(|(r, q)| {
            ((r.x_m - q.x_m).powi(2) + (r.y_m - q.y_m).powi(2) + (r.z_m - q.z_m).powi(2)).sqrt()
        })
        .fold(0.0, f64::max)
}

/// The scenes of the report with their horizons.
fn scenes() -> Result<Vec<(Scene, f64)>, String> {
    let shallow = Scene::from_toml(SHALLOW_SCENE_TOML, "shallow").map_err(|e| e.to_string())?;
    Ok(vec![(Scene::default_scene(), 1.0), (shallow, 0.5)])
}

/// The reference route of `scene` under `dynamics` over `horizon` (exact mode, RK4,
/// continuation), and how it was established: the paper's dynamics at dt_ref, checked at
/// dt_ref / 2; the rigid body at its reference tolerance, checked at a tenth of it.
fn reference_of(
    scene: &Scene,
    dynamics: DynamicsModel,
    horizon: f64,
) -> Result<(Route, Reference), String> {
    let exact = |dt, tol| {
        with_solver(
            scene,
            dynamics,
            Mode::Exact,
            Integrator::Rk4,
            (dt, tol),
            horizon,
        )
    };
    let ref_dt = DT0 / 512.0;
    let (reference, change_m, (dt_s, tolerance)) = if dynamics == DynamicsModel::RigidBody {
        let tol = RIGID_REFERENCE_TOLERANCE;
        let reference = run(&exact(RIGID_ROWS_DT, Some(tol))?, PoseMethod::Continuation)?;
        let check = run(
            &exact(RIGID_ROWS_DT, Some(tol / 10.0))?,
            PoseMethod::Continuation,
        )?;
        let change = max_distance(&reference, &check, 1);
        (reference, change, (RIGID_ROWS_DT, Some(tol)))
    } else {
        let reference = run(&exact(ref_dt, None)?, PoseMethod::Continuation)?;
        let check = run(&exact(ref_dt / 2.0, None)?, PoseMethod::Continuation)?;
        let change = max_distance(&reference, &check, 2);
        (reference, change, (ref_dt, None))
    };
    let established = Reference {
        scene: scene.name().to_string(),
        dynamics,
        horizon_s: horizon,
        dt_s,
        tolerance,
        change_m,
        bound_m: 1e-9 * scene.l(),
    };
    Ok((reference, established))
}

/// The error of a report stopped by its caller.
pub(super) const INTERRUPTED: &str =
    "interrupted: the report was stopped before it was complete, and nothing was written";

/// Runs the ladder. `quick`: three steps of dt and three repeats (under a minute here);
/// otherwise six and seven. `progress()` is called after each point; when it answers
/// `ControlFlow::Break` (Ctrl-C) the report stops with the error [`INTERRUPTED`]: a report
/// half measured is not written.
pub(super) fn work_precision(
    quick: bool,
    progress: impl Fn() -> std::ops::ControlFlow<()>,
) -> Result<(Vec<Point>, Vec<Reference>), String> {
    let (levels, repeats) = if quick { (3, 3) } else { (6, 7) };
    let mut points = Vec::new();
    let mut references = Vec::new();
    for (scene, horizon) in scenes()? {
        for dynamics in [DynamicsModel::Paper, DynamicsModel::RigidBody] {
            // Each dynamics against its own reference: the error is of the integration, not
            // the difference between the models.
            let rigid = dynamics == DynamicsModel::RigidBody;
            let (reference, established) = reference_of(&scene, dynamics, horizon)?;
            let reference_dt = established.dt_s;
            references.push(established);
            for series in series().into_iter().filter(|s| s.dynamics == dynamics) {
                let Series {
                    method,
                    mode,
                    integrator,
                    by_tolerance,
                    ..
                } = series;
                for k in 0..levels {
                    // Over increments: dt halving, at the loosest tolerance (no increment cut);
                    // over tolerances: the tolerance falling tenfold (by a hundredfold in the
                    // quick report).
                    let (dt, tolerance) = if by_tolerance {
                        let decades = if quick { 2 * k + 6 } else { k + 5 };
                        let rows = if rigid {
                            RIGID_ROWS_DT
                        } else {
                            PAPER_TOLERANCE_ROWS_DT
                        };
                        (rows, Some(10f64.powi(-decades)))
                    } else {
                        (DT0 / f64::from(1u32 << k), None)
                    };
                    let runs_at = (dt, tolerance.or(Some(crate::MAX_TOLERANCE)));
                    let s = with_solver(&scene, dynamics, mode, integrator, runs_at, horizon)?;
                    let mut times = Vec::with_capacity(repeats);
                    let mut last = None;
                    for _ in 0..repeats {
                        let t0 = Instant::now();
                        let r = computed(&s, method)?;
                        times.push(t0.elapsed().as_secs_f64());
                        last = Some(r);
                    }
                    times.sort_by(f64::total_cmp);
                    let c: Computed = last.ok_or("no run")?;
                    let steps = c.route.steps().map_or(c.route.increments, |s| s.taken);
                    let r = c.route;
                    let ratio = (dt / reference_dt).round() as usize;
                    points.push(Point {
                        scene: scene.name().to_string(),
                        dynamics,
                        method,
                        mode,
                        integrator,
                        dt_s: dt,
                        tolerance,
                        increments: r.increments,
                        steps,
                        wall_s: times[times.len() / 2],
                        error_m: max_distance(&r, &reference, ratio),
                    });
                    if progress().is_break() {
                        return Err(INTERRUPTED.into());
                    }
                }
            }
        }
    }
    Ok((points, references))
}

/// Continuation against all roots at one (scene, mode, integrator, dt): the cost of an
/// increment by each, and how far apart their errors are (equal error: the same route).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub(crate) struct Speedup {
    pub scene: String,
    pub mode: Mode,
    pub integrator: Integrator,
    pub dt_s: f64,
    /// Median wall time per increment (µs).
    pub continuation_us: f64,
    pub all_roots_us: f64,
    /// all_roots_us / continuation_us.
    pub ratio: f64,
    /// |error(all roots) − error(continuation)| (m).
    pub error_gap_m: f64,
}

/// Pairs each continuation point with the all-roots point of the same series and dt.
pub(crate) fn speedups(points: &[Point]) -> Vec<Speedup> {
    let per_increment = |p: &Point| p.wall_s * 1e6 / p.increments.max(1) as f64;
    points
        .iter()
        .filter(|c| c.method == PoseMethod::Continuation)
        .filter_map(|c| {
            let a = points.iter().find(|a| {
                a.method == PoseMethod::AllRoots
                    && a.scene == c.scene
                    && a.dynamics == c.dynamics
                    && a.mode == c.mode
                    && a.integrator == c.integrator
                    && a.dt_s == c.dt_s
                    && a.tolerance == c.tolerance
            })?;
            let (cu, au) = (per_increment(c), per_increment(a));
            Some(Speedup {
                scene: c.scene.clone(),
                mode: c.mode,
                integrator: c.integrator,
                dt_s: c.dt_s,
                continuation_us: cu,
                all_roots_us: au,
                ratio: au / cu,
                error_gap_m: (a.error_m - c.error_m).abs(),
            })
        })
        .collect()
}

/// Number of points [`work_precision`] measures: each series' ladder on each scene.
pub(super) fn point_count(quick: bool) -> usize {
    let levels = if quick { 3 } else { 6 };
    2 * series().len() * levels
}

#[cfg(test)]
mod tests {
    use super::*;

    fn point(method: PoseMethod, dt_s: f64, wall_s: f64, error_m: f64) -> Point {
        Point {
            scene: "s".into(),
            dynamics: DynamicsModel::Paper,
            method,
            mode: Mode::Exact,
            integrator: Integrator::Paper,
            dt_s,
            tolerance: None,
            increments: 100,
            steps: 100,
            wall_s,
            error_m,
        }
    }

    #[test]
    fn speedups_pair_each_continuation_point_with_its_all_roots_twin() {
        let points = [
            point(PoseMethod::Continuation, 0.02, 1e-4, 1e-3),
            point(PoseMethod::Continuation, 0.01, 5e-5, 5e-4),
            point(PoseMethod::AllRoots, 0.01, 6e-4, 5e-4 + 1e-17),
            point(PoseMethod::AllRoots, 0.02, 3e-4, 1e-3),
        ];
        let s = speedups(&points);
        assert_eq!(s.len(), 2);
        assert_eq!(s[0].dt_s, 0.02);
        assert!((s[0].continuation_us - 1.0).abs() < 1e-12);
        assert!((s[0].ratio - 3.0).abs() < 1e-12);
        assert!((s[1].ratio - 12.0).abs() < 1e-12);
        assert!((s[1].error_gap_m - 1e-17).abs() < 1e-18);
        // A continuation point without its twin is left out.
        assert_eq!(speedups(&points[..2]).len(), 0);
    }
}
