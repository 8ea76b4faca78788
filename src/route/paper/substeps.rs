//! RK4 over an increment of the paper's dynamics, in as many equal substeps as the tolerance
//! asks (`Paper::rk4_within`), and where a substep cannot be taken, its longest part that can
//! (by the event layer's bisection, `route/events.rs`).

use super::{Evaluation, State, evaluate, rk4_step, velocity};
use super::{Log, Paper, Stepped};
use crate::model::{Body, Simulation};
use crate::route::events::{Until, bisect};
use crate::route::integrator::error_ratio;
use crate::route::pose_finder::PoseFinder;
use crate::route::termination::Stop;
use std::convert::Infallible;

/// The most substeps RK4 takes over one increment (2¹²): where even these leave a substep's
/// error estimate over the tolerance, the increment is taken in this many.
const MAX_PIECES: usize = 1 << 12;

/// How the increment in a number of equal substeps came out: every substep taken (the increment,
/// the worst error ratio), or to be taken again in more (the substeps taken before).
// The increment taken comes back by value, as `rk4_within` returns it, once an increment;
// boxing it would add an allocation an increment to save a move.
#[allow(clippy::large_enum_variant)]
enum Pieces<'f> {
    Taken(Stepped<'f>, f64),
    Again(usize),
}

/// How a route ends within an increment: the reason, and the substeps taken before it (with
/// the longest part of the one that could not be), if any.
type EndedWithin<'f> = (Stop, Option<Box<Stepped<'f>>>);

impl Paper<'_> {
    /// RK4 over the increment from the state to `t_to` (of length `dt`), in as many equal
    /// substeps as the tolerance asks: each substep's error estimated as the rigid body's is
    /// (`derivations/08-rigid-body.md` §4a), h/6 (k4 − k5) on X, Z against `solver.tolerance`
    /// of the block's size and on θ against the tolerance in radians, at no cost beyond the
    /// evaluation at the substep's end, which the next substep starts from. An increment whose
    /// substep is over the tolerance is taken again in twice as many (up to [`MAX_PIECES`]); the
    /// next increment starts with as many as this one took, or half as many where half would
    /// have done by the estimate. Where one substep an increment does (the default increment
    /// of 1 ms), the route is the increment's single RK4 step, as before. The travel is summed
    /// over the substeps' chords, the friction solutions chosen afresh counted at each, and the
    /// substep where the block may stop is kept for the stop's search. A substep that cannot be
    /// taken ends the route: with the substeps taken before it, or at the increment's start.
    /// `finder` follows the substeps' ends, and is put back at the increment's start when it is
    /// taken again.
    pub(super) fn rk4_within<'f>(
        &mut self,
        finder: &mut PoseFinder<'f>,
        (t_to, dt): (f64, f64),
        o: &mut Log<'_>,
    ) -> Result<Stepped<'f>, EndedWithin<'f>> {
        let mut pieces = self.pieces.clamp(1, MAX_PIECES);
        // The finder at the increment's start: the first substep's stages start from it, and an
        // increment taken again in more substeps starts from it again (one copy an increment, as
        // a single RK4 step needs for its stages).
        let start = finder.clone();
        let mut again = false;
        loop {
            if again {
                *finder = start.clone();
            }
            again = true;
            match self.in_pieces(finder, &start, (t_to, dt), pieces, o)? {
                Pieces::Taken(done, worst) => {
                    o.report.steps.taken += pieces;
                    // Twice the substep multiplies the estimate by 16: halve their number only
                    // where that would leave it under half the tolerance.
                    self.pieces = if pieces > 1 && 16.0 * worst < 0.5 {
                        pieces / 2
                    } else {
                        pieces
                    };
                    return Ok(done);
                }
                Pieces::Again(taken) => {
                    o.report.steps.retried += taken + 1;
                    pieces *= 2;
                }
            }
        }
    }

    /// The increment to `t_to` (of length `dt`) in `pieces` equal substeps from the finder
    /// `start` at its start, `finder` following their ends: all taken, or to be taken again in
    /// more (a substep over the tolerance, or one longer than the reference step that cannot be
    /// taken, which may be the integrator's: its stages far from the motion, as the rigid
    /// body's), or the route ends within it.
    fn in_pieces<'f>(
        &self,
        finder: &mut PoseFinder<'f>,
        start: &PoseFinder<'f>,
        (t_to, dt): (f64, f64),
        pieces: usize,
        o: &mut Log<'_>,
    ) -> Result<Pieces<'f>, EndedWithin<'f>> {
        let sim = (self.sim, self.body);
        let (l, tol) = (self.body.l(), self.sim.settings().tolerance);
        // X and Z against τ L, θ against τ rad; the rates not weighed (as the rigid body's).
        let weights = [1.0 / (tol * l), 1.0 / (tol * l), 1.0 / tol, 0.0, 0.0, 0.0];
        let first_acc = self.ev.acc;
        let mut done = Stepped {
            next: self.state,
            ev: self.ev,
            switches: 0,
            travel: 0.0,
            crossing: None,
        };
        let h = dt / pieces as f64;
        let mut worst: f64 = 0.0;
        let mut taken = 0;
        while taken < pieces {
            let from = (done.next, done.ev);
            let later;
            let base = if taken == 0 {
                start
            } else {
                later = finder.clone();
                &later
            };
            // The last substep ends at t_to itself, not at a running sum.
            let t_end = (taken + 1 == pieces).then_some(t_to);
            let (next, k4, end) = match substep(sim, finder, base, (&from.0, &from.1), h, t_end) {
                Ok(x) => x,
                Err(stop) => {
                    let reference = self.sim.settings().reference_step();
                    if h > reference * (1.0 + 1e-12) && pieces < MAX_PIECES {
                        return Ok(Pieces::Again(taken));
                    }
                    o.report.steps.taken += taken;
                    let ended = ended_within(sim, finder, base, (done, taken), h, &first_acc);
                    return Err((stop, ended));
                }
            };
            let k5 = [
                next.vx, next.vz, next.omega, end.acc[0], end.acc[1], end.acc[2],
            ];
            let ratio = error_ratio(&weights, h, &k4, &k5);
            if ratio > 1.0 && pieces < MAX_PIECES {
                return Ok(Pieces::Again(taken));
            }
            worst = worst.max(ratio);
            done.take((next, end), h, &first_acc, base);
            taken += 1;
        }
        Ok(Pieces::Taken(done, worst))
    }
}

/// One RK4 substep of length `h` from `s` (evaluated as `ev`), its stages on copies of `base`,
/// its end at `t_end` where it is the increment's last (else at its running time) and
/// evaluated on `finder`: the state there, its last stage k4, and its evaluation.
fn substep(
    sim: (&Simulation, &Body),
    finder: &mut PoseFinder<'_>,
    base: &PoseFinder<'_>,
    (s, ev): (&State, &Evaluation),
    h: f64,
    t_end: Option<f64>,
) -> Result<(State, [f64; 6], Evaluation), Stop> {
    let prev = ev.reaction;
    rk4_step(s, &ev.acc, h, |q: &State| {
        let mut g = base.clone();
        evaluate(sim, &mut g, q.displacement(), Some(&prev), velocity(q)).map(|e| e.acc)
    })
    .and_then(|(next, k4)| {
        let next = match t_end {
            Some(t) => State { t, ..next },
            None => next,
        };
        let at = next.displacement();
        let end = evaluate(sim, finder, at, Some(&ev.reaction), velocity(&next))?;
        Ok((next, k4, end))
    })
}

/// A substep of length `h` from the substeps `done` so far (`taken` of them), its stages from
/// `base`, that cannot be taken: the route ends where the model does, inside it, after its
/// longest part that can be taken (a stop within the part is the route's end if friction holds
/// there, as in any substep: `Paper::stop_in`), `finder` there; or after the substeps taken
/// before it, or at the increment's start where there were none.
fn ended_within<'f>(
    sim: (&Simulation, &Body),
    finder: &mut PoseFinder<'f>,
    base: &PoseFinder<'f>,
    (mut done, taken): (Stepped<'f>, usize),
    h: f64,
    first_acc: &[f64; 3],
) -> Option<Box<Stepped<'f>>> {
    let part = longest_part(sim, base, (&done.next, &done.ev), h);
    let ended = match part {
        Some((len, next, end, f)) => {
            done.take((next, end), len, first_acc, base);
            *finder = f;
            true
        }
        None => taken > 0,
    };
    ended.then(|| Box::new(done))
}

/// The event layer's bisection for the longest part of a substep of length `h` from `s`
/// (evaluated as `ev`) that can be taken when the whole cannot (a contact left its plane, the
/// frictional system has no solution): single RK4 steps of the part's length from `s`, to 1e-12
/// of `h`. The part's length, the state there, its evaluation and the finder at it; none where
/// no part can be.
fn longest_part<'f>(
    sim: (&Simulation, &Body),
    base: &PoseFinder<'f>,
    (s, ev): (&State, &Evaluation),
    h: f64,
) -> Option<(f64, State, Evaluation, PoseFinder<'f>)> {
    let prev = ev.reaction;
    let part = |len: f64| {
        let (next, _) = rk4_step(s, &ev.acc, len, |q: &State| {
            let mut g = base.clone();
            evaluate(sim, &mut g, q.displacement(), Some(&prev), velocity(q)).map(|e| e.acc)
        })?;
        let mut f = base.clone();
        let end = evaluate(
            sim,
            &mut f,
            next.displacement(),
            Some(&prev),
            velocity(&next),
        )?;
        Ok::<_, Stop>((len, next, end, f))
    };
    // Some 40 halvings reach 1e-12 of the substep.
    let mut best = None;
    let Ok(_) = bisect::<Infallible>((0.0, h), Until::width(1e-12 * h, 64), |mid| {
        Ok(match part(mid) {
            Ok(p) => {
                best = Some(p);
                false
            }
            Err(_) => true,
        })
    });
    best
}
