//! The one route loop: the increments of dt up to t_end (the last one shorter, so that the route
//! ends exactly there), the stride of the recorded rows, progress and interruption, the time
//! limit, and the measures at the start asked of the model, for any [`Dynamics`].

use super::dynamics::{Dynamics, Flow, Start};
use super::logbook::Logbook;
use super::pose_finder::PoseFinder;
use super::termination::Reason;
use crate::model::{RunSettings, Simulation};
use std::ops::ControlFlow;

/// The number of increments of dt that reach `t_end`: the last may be shorter, so that the route
/// ends exactly at `t_end`; a remainder below 1e-9·dt is dropped as round-off.
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

/// The recorded rows' times strictly inside (`t0`, `t1`), in order: the ends k·dt of the
/// increments the driver records (every stride-th, and the last, at t_end). A model whose steps
/// are longer than dt gives the rows at these times from within its steps.
pub(super) fn recorded_within(
    settings: &RunSettings,
    t0: f64,
    t1: f64,
) -> impl Iterator<Item = f64> {
    let (dt, t_end) = (settings.dt, settings.t_end);
    let n = increments(t_end, dt);
    let stride = settings.stride.max(1);
    let first = ((t0 / dt).floor().max(0.0) as usize).max(1);
    (first..=n)
        .map(move |k| (k, increment_end(t_end, dt, k)))
        .take_while(move |&(_, t)| t < t1 * (1.0 - 1e-15))
        .filter(move |&(k, t)| t > t0 * (1.0 + 1e-15) && (k % stride == 0 || k == n))
        .map(|(_, t)| t)
}

/// Drives model `M` from its start to the end of its route, then asks it for the measures at
/// the start its start has not given, and for its word on how the route ended.
pub(super) fn drive<'a, 's, M: Dynamics<'a>>(
    sim: &'a Simulation,
    finder: &mut PoseFinder<'_>,
    progress: impl FnMut(f64) -> ControlFlow<()>,
    log: Logbook<'s, M::Report>,
) -> Logbook<'s, M::Report> {
    let start_pose = finder.pose();
    let mut o = increments_of::<M>(sim, finder, progress, log);
    M::at_start(sim, start_pose.as_ref(), &mut o);
    M::explain_end(&mut o);
    o
}

/// The loop: model `M` from its start, increment by increment, to the end of its route.
fn increments_of<'a, 's, M: Dynamics<'a>>(
    sim: &'a Simulation,
    finder: &mut PoseFinder<'_>,
    mut progress: impl FnMut(f64) -> ControlFlow<()>,
    log: Logbook<'s, M::Report>,
) -> Logbook<'s, M::Report> {
    let settings = *sim.settings();
    let (mut model, mut o) = match M::start(sim, finder, log) {
        Start::Moving(model, o) => (model, o),
        Start::Ended(o) => return o,
    };
    let stride = settings.stride.max(1);
    let n = increments(settings.t_end, settings.dt);
    let mut t = 0.0;
    for k in 1..=n {
        t = increment_end(settings.t_end, settings.dt, k);
        o = match model.advance(finder, k, t, o) {
            Flow::Go(o) => o,
            Flow::Ended(o) => return o,
        };
        o.increments = k;
        if k % stride == 0 || k == n {
            o.push(model.row());
        }
        if progress((t / settings.t_end).min(1.0)).is_break() {
            model.close(&mut o);
            return o.finish(
                model.row(),
                Reason::Interrupted,
                t,
                format!("interrupted at t = {} s", crate::numeric::seconds(t)),
            );
        }
    }
    model.close(&mut o);
    o.end(
        Reason::TimeLimit,
        t,
        format!("t reached t_end = {} s", settings.t_end),
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::DynamicsModel;

    #[test]
    fn the_recorded_times_within_a_step_are_the_strides_increment_ends_and_the_last() {
        let s = RunSettings::new(DynamicsModel::RigidBody, 0.1, 1.05).with_stride(3);
        let within = |t0, t1| recorded_within(&s, t0, t1).collect::<Vec<_>>();
        // k = 3, 6, 9 and the last (k = 11 at t_end); the ends themselves excluded.
        let all = within(0.0, 2.0);
        assert_eq!(all.len(), 4);
        assert!((all[0] - 0.3).abs() < 1e-15 && (all[2] - 0.9).abs() < 1e-15);
        assert_eq!(all[3], 1.05);
        assert_eq!(within(0.3, 0.9).len(), 1);
        assert!(within(0.31, 0.59).is_empty());
        assert_eq!(within(0.0, 0.3 + 1e-9), [0.30000000000000004]);
    }
}
