//! The rigid-body mode against Drake, a multibody engine nobody here wrote (issue #7).
//!
//! Needs the cross-check's Python environment: `crosscheck/setup.sh` (pydrake in
//! `crosscheck/.venv`; or set `SLIDEROUTE_DRAKE_PYTHON` to a Python that has it). `.ci/run`
//! sets it up and runs these with `cargo test --release --test drake_crosscheck -- --ignored`.
//! Without the environment the tests fail with that instruction (they never pass silently).

use slideroute::route::{self, Reason, Row};
use slideroute::scene::{DynamicsModel, Scene};
use std::path::{Path, PathBuf};
use std::process::Command;

const HORIZON_S: f64 = 3.0;

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

fn python() -> PathBuf {
    match std::env::var_os("SLIDEROUTE_DRAKE_PYTHON") {
        Some(p) => PathBuf::from(p),
        None => root().join("crosscheck/.venv/bin/python"),
    }
}

/// Drake's (t, X, Y, Z, θ°) for a scene file over the horizon.
fn drake_path(scene: &Path) -> Vec<[f64; 5]> {
    let py = python();
    assert!(
        py.exists(),
        "{} not found: run crosscheck/setup.sh first (or set SLIDEROUTE_DRAKE_PYTHON)",
        py.display()
    );
    let out_dir = root().join("target/crosscheck");
    std::fs::create_dir_all(&out_dir).unwrap();
    let stem = scene.file_stem().unwrap().to_string_lossy().to_string();
    let out = out_dir.join(format!("{stem}.drake.csv"));
    let status = Command::new(&py)
        .arg(root().join("crosscheck/drake_route.py"))
        .arg("--scene")
        .arg(scene)
        .arg("--t-end")
        .arg(HORIZON_S.to_string())
        .arg("--out")
        .arg(&out)
        .status()
        .expect("runs the Drake script");
    assert!(
        status.success(),
        "the Drake script failed on {}",
        scene.display()
    );
    let text = std::fs::read_to_string(&out).unwrap();
    text.lines()
        .skip(1)
        .map(|l| {
            let v: Vec<f64> = l.split(',').map(|x| x.parse().unwrap()).collect();
            [v[0], v[1], v[2], v[3], v[4]]
        })
        .collect()
}

fn ours(scene_file: &Path) -> (Vec<Row>, Reason) {
    let mut scene = Scene::from_file(scene_file)
        .unwrap()
        .with_dynamics(DynamicsModel::RigidBody);
    scene.solver.as_mut().unwrap().t_end = HORIZON_S;
    let r = route::run(&scene).unwrap();
    (r.rows, r.termination.reason)
}

fn travel(points: impl Iterator<Item = [f64; 3]>) -> f64 {
    let mut last: Option<[f64; 3]> = None;
    let mut sum = 0.0;
    for p in points {
        if let Some(q) = last {
            sum += ((p[0] - q[0]).powi(2) + (p[1] - q[1]).powi(2) + (p[2] - q[2]).powi(2)).sqrt();
        }
        last = Some(p);
    }
    sum
}

/// Travel within 0.5 %, CM positions within 0.5 % of travel and yaw within 0.2° at every
/// common time over 3 s.
fn agrees_with_drake(name: &str) {
    let file = root().join("scenes").join(format!("{name}.toml"));
    let drake = drake_path(&file);
    let (rows, reason) = ours(&file);
    assert_eq!(reason, Reason::TimeLimit, "{name}: must run the whole 3 s");
    assert_eq!(
        rows.len(),
        drake.len(),
        "{name}: one row per millisecond in both"
    );
    let t_ours = travel(rows.iter().map(|r| [r.x_m, r.y_m, r.z_m]));
    let t_drake = travel(drake.iter().map(|d| [d[1], d[2], d[3]]));
    let travel_err = (t_ours - t_drake).abs() / t_drake;
    let mut pos_err: f64 = 0.0;
    let mut yaw_err: f64 = 0.0;
    for (r, d) in rows.iter().zip(&drake) {
        assert!((r.t_s - d[0]).abs() < 1e-9);
        let e = ((r.x_m - d[1]).powi(2) + (r.y_m - d[2]).powi(2) + (r.z_m - d[3]).powi(2)).sqrt();
        pos_err = pos_err.max(e);
        yaw_err = yaw_err.max((r.theta_deg - d[4]).abs());
    }
    let last = rows.last().unwrap();
    println!(
        "{name}: travel {t_ours:.4} m (Drake {t_drake:.4} m, {:.3} %), largest CM gap {pos_err:.4} m \
         ({:.3} % of travel), largest yaw gap {yaw_err:.4}°; θ(3 s) = {:.3}°",
        100.0 * travel_err,
        100.0 * pos_err / t_drake,
        last.theta_deg
    );
    assert!(
        travel_err < 0.005,
        "{name}: travel differs by {:.3} %",
        100.0 * travel_err
    );
    assert!(
        pos_err < 0.005 * t_drake,
        "{name}: CM differs by {pos_err} m"
    );
    assert!(yaw_err < 0.2, "{name}: yaw differs by {yaw_err}°");
}

#[test]
#[ignore = "needs pydrake (crosscheck/setup.sh); run by .ci/run"]
fn rigid_body_paper_like_agrees_with_drake() {
    agrees_with_drake("paper-like");
}

#[test]
#[ignore = "needs pydrake (crosscheck/setup.sh); run by .ci/run"]
fn rigid_body_shallow_agrees_with_drake() {
    agrees_with_drake("shallow");
}

#[test]
#[ignore = "needs pydrake (crosscheck/setup.sh); run by .ci/run"]
fn rigid_body_strong_turning_agrees_with_drake() {
    agrees_with_drake("strong-turning");
}
