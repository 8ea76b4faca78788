//! The one route loop (issue #14): the increments of dt up to t_end (the last one shorter, so
//! that the route ends exactly there), the stride of the recorded rows, progress and
//! interruption, and the time limit, for any [`Dynamics`].

use super::dynamics::{Dynamics, Flow, Start};
use super::outcome::Outcome;
use super::pose_finder::PoseFinder;
use super::termination::Reason;
use crate::scene::{Scene, Simulation};
use std::ops::ControlFlow;

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

/// Drives model `M` from its start to the end of its route.
pub(super) fn drive<'a, 's, M: Dynamics<'a>>(
    scene: &'a Scene,
    sections: &'a Simulation,
    finder: &mut PoseFinder<'_>,
    mut progress: impl FnMut(f64) -> ControlFlow<()>,
    outcome: Outcome<'s>,
) -> Outcome<'s> {
    let solver = *sections.solver();
    let (mut model, mut o) = match M::start(scene, sections, finder, outcome) {
        Start::Moving(model, o) => (model, o),
        Start::Ended(o) => return o,
    };
    let stride = solver.stride.max(1);
    let n = increments(solver.t_end, solver.dt);
    let mut t = 0.0;
    for k in 1..=n {
        t = increment_end(solver.t_end, solver.dt, k);
        o = match model.advance(finder, k, t, o) {
            Flow::Go(o) => o,
            Flow::Ended(o) => return o,
        };
        o.increments = k;
        if k % stride == 0 || k == n {
            o.push(model.row());
        }
        if progress((t / solver.t_end).min(1.0)).is_break() {
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
        format!("t reached t_end = {} s", solver.t_end),
    )
}
