//! The paper's route beside the rigid body's (`slideroute run --compare-dynamics`): both routes
//! of one scene, and where and how far they part.

use crate::model::DynamicsModel;
use crate::route::{Computed, Row, Runner};
use crate::scene::{Scene, SceneError};
use serde::Serialize;

/// How far apart the two centre-of-mass paths are, at matching times.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Parting {
    /// The separation that counts as "parted": 1% of the side length L (m).
    pub threshold_m: f64,
    /// The first time the CM positions are farther apart than the threshold (s); `None` if they
    /// never part while both run.
    pub parted_at_s: Option<f64>,
    /// Where the rigid body's CM is then: X (m).
    pub parted_at_x_m: Option<f64>,
    /// And Z (m).
    pub parted_at_z_m: Option<f64>,
    /// Over the time both routes run: the largest CM separation (m).
    pub max_separation_m: f64,
    /// When it is reached (s).
    pub max_separation_at_s: f64,
    /// The last time both routes run (s).
    pub common_until_s: f64,
    /// Their CM separation then (m).
    pub separation_at_end_m: f64,
    /// Their yaw difference then, rigid − paper (degrees).
    pub yaw_difference_at_end_deg: f64,
}

/// Both routes, how each was computed, and their parting.
#[derive(Debug, Clone, Serialize)]
pub struct Comparison {
    /// The route under the paper's dynamics.
    pub paper: Computed,
    /// The route under the rigid body's.
    pub rigid_body: Computed,
    /// Where and how far they part.
    pub parting: Parting,
}

/// Linear interpolation of a route's (X, Y, Z, θ°) at time t (rows ordered in time).
pub fn at_time(rows: &[Row], t: f64) -> Option<[f64; 4]> {
    let k = rows.partition_point(|r| r.t_s < t);
    let pick = |r: &Row| [r.x_m, r.y_m, r.z_m, r.theta_deg];
    if k == 0 {
        return rows.first().filter(|r| r.t_s == t).map(pick);
    }
    if k >= rows.len() {
        return None;
    }
    let (a, b) = (&rows[k - 1], &rows[k]);
    let w = if b.t_s > a.t_s {
        (t - a.t_s) / (b.t_s - a.t_s)
    } else {
        1.0
    };
    let (pa, pb) = (pick(a), pick(b));
    Some(std::array::from_fn(|i| pa[i] + w * (pb[i] - pa[i])))
}

/// The parting of two routes over their common time span, sampled at the first route's rows.
pub fn parting(scene: &Scene, a: &[Row], b: &[Row]) -> Parting {
    let threshold = 0.01 * scene.l();
    let end = a
        .last()
        .map_or(0.0, |r| r.t_s)
        .min(b.last().map_or(0.0, |r| r.t_s));
    let mut p = Parting {
        threshold_m: threshold,
        parted_at_s: None,
        parted_at_x_m: None,
        parted_at_z_m: None,
        max_separation_m: 0.0,
        max_separation_at_s: 0.0,
        common_until_s: end,
        separation_at_end_m: 0.0,
        yaw_difference_at_end_deg: 0.0,
    };
    let times = a
        .iter()
        .map(|r| r.t_s)
        .filter(|&t| t <= end)
        .chain(std::iter::once(end));
    for t in times {
        let (Some(pa), Some(pb)) = (at_time(a, t), at_time(b, t)) else {
            continue;
        };
        let sep =
            ((pa[0] - pb[0]).powi(2) + (pa[1] - pb[1]).powi(2) + (pa[2] - pb[2]).powi(2)).sqrt();
        if sep > p.max_separation_m {
            p.max_separation_m = sep;
            p.max_separation_at_s = t;
        }
        if sep > threshold && p.parted_at_s.is_none() {
            p.parted_at_s = Some(t);
            p.parted_at_x_m = Some(pb[0]);
            p.parted_at_z_m = Some(pb[2]);
        }
        p.separation_at_end_m = sep;
        p.yaw_difference_at_end_deg = pb[3] - pa[3];
    }
    p
}

/// Runs the scene with the paper's dynamics and with the rigid body's.
pub fn compare_dynamics(scene: &Scene) -> Result<Comparison, SceneError> {
    compare_dynamics_observed(scene, || false)
}

/// [`compare_dynamics`], both routes ending at their next increment as "interrupted" once
/// `stop()` answers true (Ctrl-C).
pub fn compare_dynamics_observed(
    scene: &Scene,
    stop: impl Fn() -> bool,
) -> Result<Comparison, SceneError> {
    compare_with(scene, stop, None)
}

/// [`compare_dynamics_observed`] in bounded memory: every row of the paper's route to
/// `paper_rows` and of the rigid body's to `rigid_rows` as they are computed, each route
/// keeping at most [`KEPT_ROWS`](crate::route::KEPT_ROWS) of them; where the routes part is
/// found on the kept rows (interpolated in time between them).
pub fn compare_dynamics_streamed(
    scene: &Scene,
    stop: impl Fn() -> bool,
    paper_rows: &mut dyn FnMut(&Row),
    rigid_rows: &mut dyn FnMut(&Row),
) -> Result<Comparison, SceneError> {
    compare_with(scene, stop, Some([paper_rows, rigid_rows]))
}

/// Where a route's rows go as they are computed.
type Sink<'s> = &'s mut dyn FnMut(&Row);

/// Both routes, every row kept, or streamed to `sinks` (the paper's, the rigid body's).
fn compare_with(
    scene: &Scene,
    stop: impl Fn() -> bool,
    sinks: Option<[Sink<'_>; 2]>,
) -> Result<Comparison, SceneError> {
    let [mut paper_sink, mut rigid_sink] = match sinks {
        Some([a, b]) => [Some(a), Some(b)],
        None => [None, None],
    };
    let mut run = |model: DynamicsModel| -> Result<Computed, SceneError> {
        let sim = scene.with_dynamics(model)?.simulation()?;
        let observe = |_: f64| {
            if stop() {
                std::ops::ControlFlow::Break(())
            } else {
                std::ops::ControlFlow::Continue(())
            }
        };
        let runner = Runner::new(&sim).progress(observe);
        let sink = match model {
            DynamicsModel::Paper => paper_sink.take(),
            DynamicsModel::RigidBody => rigid_sink.take(),
        };
        Ok(match sink {
            Some(sink) => runner
                .stream(1, sink)
                .keep_at_most(crate::route::KEPT_ROWS)
                .run(),
            None => runner.run(),
        })
    };
    let paper = run(DynamicsModel::Paper)?;
    let rigid_body = run(DynamicsModel::RigidBody)?;
    let parting = parting(scene, &paper.route.rows, &rigid_body.route.rows);
    Ok(Comparison {
        paper,
        rigid_body,
        parting,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parting_of_a_route_with_itself_is_zero_and_a_shift_is_seen() {
        let scene = Scene::default_scene();
        let rows: Vec<Row> = (0..=100)
            .map(|k| {
                let t = k as f64 * 0.01;
                Row {
                    t_s: t,
                    x_m: t * t,
                    theta_deg: 10.0 * t,
                    ..Row::default()
                }
            })
            .collect();
        let same = parting(&scene, &rows, &rows);
        assert_eq!(same.max_separation_m, 0.0);
        assert_eq!(same.parted_at_s, None);
        let shifted: Vec<Row> = rows
            .iter()
            .map(|r| Row {
                z_m: 0.5 * r.t_s,
                theta_deg: r.theta_deg + 1.0,
                ..*r
            })
            .collect();
        let p = parting(&scene, &rows, &shifted);
        // 1% of L = 0.1 m is first exceeded at t = 0.21 s (0.5 t > 0.1).
        assert_eq!(p.parted_at_s, Some(0.21));
        assert!((p.max_separation_m - 0.5).abs() < 1e-12);
        assert!((p.yaw_difference_at_end_deg - 1.0).abs() < 1e-12);
    }

    #[test]
    fn a_streamed_comparison_gives_every_row_and_parts_where_the_whole_one_does() {
        // Both routes held whole took 200 bytes a row (657 MB at dt = 2 µs): streamed, every
        // row goes out and at most KEPT_ROWS stay.
        let scene = Scene::default_scene()
            .with("solver.dt_s", 1e-4)
            .and_then(|s| s.with("solver.t_end_s", 1.0))
            .unwrap();
        let whole = compare_dynamics(&scene).unwrap();
        let (mut paper, mut rigid) = (Vec::new(), Vec::new());
        let streamed =
            compare_dynamics_streamed(&scene, || false, &mut |r| paper.push(*r), &mut |r| {
                rigid.push(*r)
            })
            .unwrap();
        assert_eq!(paper, whole.paper.route.rows);
        assert_eq!(rigid, whole.rigid_body.route.rows);
        assert!(whole.rigid_body.route.rows.len() > 2 * crate::route::KEPT_ROWS);
        for kept in [&streamed.paper.route.rows, &streamed.rigid_body.route.rows] {
            assert!(kept.len() <= crate::route::KEPT_ROWS + 1, "{}", kept.len());
        }
        assert_eq!(
            streamed.rigid_body.route.termination,
            whole.rigid_body.route.termination
        );
        // Parted within one kept row's spacing of the whole rows' parting.
        let (a, b) = (streamed.parting, whole.parting);
        let spacing = 1.0 / crate::route::KEPT_ROWS as f64 * 3.0;
        assert!(
            (a.parted_at_s.unwrap() - b.parted_at_s.unwrap()).abs() <= spacing,
            "{a:?} {b:?}"
        );
        assert!((a.separation_at_end_m - b.separation_at_end_m).abs() < 1e-9);
    }
}
