//! The block on its base from one recorded row to the next (`derivations/13-base-contact.md`
//! §12): where the whole base lies flush on one face, its slide (`sliding.rs`, §13); where
//! every touch is on one face of the rock otherwise and no record shakes it, steps of the
//! length the tolerance allows (`extrapolate.rs`), each tried, taken or shortened, a step that
//! cannot meet the tolerance at the shortest length taken as it is and booked, the rows within
//! a step from its dense output (`dense.rs`); elsewhere the step of `step.rs` alone, first
//! order, at the rows' interval, booked as such.

use super::dense::between;
use super::extrapolate::Extrapolated;
use super::state::BodyState;
use super::step::Ctx;
use super::step::Stepped;
use super::{FirstOrder, Log, OnBase, OnBaseReport, Unmet, not_finite, step_solve};
use crate::route::driver::recorded_within;
use crate::route::dynamics::Flow;
use crate::route::termination::Reason;
use nalgebra::Vector3;

/// The longest step, in recorded rows' intervals: the rows within one step are kept until the
/// driver takes them, so that this bounds their memory.
pub(super) const MAX_ROWS_IN_A_STEP: f64 = 1024.0;

/// The farthest a point of the base goes in one step, as a fraction of the base's size: an
/// event that its position brings on — the resultant reaching the edge of the base as it
/// slides over a step, a corner reaching the next face — begins within a step no longer, where
/// the substeps of a longer one could all start before it and none see it.
const REACH: f64 = 5e-4;

/// The shortest step, as a fraction of the reference step: a step whose error is still over
/// the tolerance at this length is taken as it is, and booked (`Unmet`).
pub(super) const SHORTEST: f64 = 1e-4;

/// The most a step grows or shrinks at once, and the safety factor on the step the error
/// estimate asks for (the usual controller: Hairer, Nørsett & Wanner, I, II.4).
const MAX_GROWTH: f64 = 4.0;
const MAX_SHRINK: f64 = 0.2;
const SAFETY: f64 = 0.8;

/// The factor by which the next step is the last one's, from its error ratio: the extrapolated
/// state's error estimate falls as h³.
pub(super) fn step_factor(ratio: f64) -> f64 {
    if ratio <= 0.0 {
        return MAX_GROWTH;
    }
    (SAFETY * ratio.powf(-1.0 / 3.0)).clamp(MAX_SHRINK, MAX_GROWTH)
}

/// The time in which a point moving at `speed` and accelerating at `accel` goes `reach`: the
/// positive root of a h² / 2 + s h = reach, written to keep its digits; unbounded where it
/// neither moves nor accelerates.
pub(super) fn time_to_reach(speed: f64, accel: f64, reach: f64) -> f64 {
    let h = 2.0 * reach / (speed + (speed * speed + 2.0 * accel * reach).sqrt());
    if h.is_finite() { h } else { f64::INFINITY }
}

impl OnBase<'_> {
    /// From the block's time to the driver's `t_to`: at rest under the record, or in steps
    /// (the last may end past `t_to`, its rows within kept for the driver).
    pub(super) fn go_to<'s>(&mut self, t_to: f64, mut o: Log<'s>) -> Flow<'s, OnBaseReport> {
        self.shown_t = t_to;
        while self.t < t_to * (1.0 - 1e-15) {
            // Under a record the slide is taken where it shakes the block along one line
            // (`sliding.rs`: a slow slip turning under two components at once is not yet).
            self.stalled &= !self.resting;
            let flush = (self.flush.is_some() || self.last.one_face)
                && self.along_one_line
                && !self.stalled
                && self.left_flush_at != Some(self.t)
                && self.flush_phase();
            let flow = if flush {
                self.flush_increment(t_to, o)
            } else if self.sim.foundation().record().is_some() {
                self.shaken_increment(t_to, o)
            } else if self.last.one_face
                || self.last.impulses.is_empty() && self.last.patch.is_empty()
            {
                self.take_step(o)
            } else {
                self.first_order_step(t_to, o)
            };
            o = match flow {
                Flow::Go(o) => o,
                ended => return ended,
            };
        }
        Flow::Go(o)
    }

    /// Under a record, one increment to `t_to` of the time-stepping scheme alone, first order
    /// (`derivations/13-base-contact.md` §6): at rest, a step from rest that keeps the block
    /// only if it moves it; moving, a step as any other. Booked as first order.
    fn shaken_increment<'s>(&mut self, t_to: f64, mut o: Log<'s>) -> Flow<'s, OnBaseReport> {
        let h = t_to - self.t;
        let bonded = self.bonded;
        let (s, stepped) = self.step_on(h, &mut o);
        // The bond broken here, the base flush on one face slides from where it rests.
        if bonded && !self.bonded && self.flush_phase() {
            return Flow::Go(o);
        }
        // A step that leaves a velocity or the pose not finite ends the route at the last
        // state that was (no row of NaN).
        if let Some(what) = not_finite(&s) {
            let detail = format!("the step from t = {} s gave no finite {what}", self.t);
            return self.end(o, Reason::ContactForcesUndetermined, detail);
        }
        if self.resting && self.slow(&s, h) {
            // Held under the record's loads now: it stays where it rests.
            self.t = t_to;
            self.last = stepped;
            return self.rest_until_the_record_ends(o);
        }
        self.resting = false;
        FirstOrder::book(&mut o.report.first_order, self.t, h);
        let x = Extrapolated {
            state: s,
            ratio: 0.0,
            last: stepped,
            stopped: false,
        };
        match self.took((h, h), x, o) {
            Flow::Go(o) if self.resting => self.rest_until_the_record_ends(o),
            flow => flow,
        }
    }

    /// One step of `h` from the block's state (from rest while it rests under a record): the
    /// state it leaves and what it found. A bonded block the step moves has broken its bond at
    /// the step's start: the step is taken again without it, so that once it moves it slides
    /// by friction alone (`derivations/13-base-contact.md` §11).
    fn step_on(&mut self, h: f64, o: &mut Log<'_>) -> (BodyState, Stepped) {
        let from = |on: &Self| {
            let mut s = on.s;
            if on.resting {
                s.v = Vector3::zeros();
                s.w = Vector3::zeros();
            }
            let stepped = on.ctx().step(&mut s, on.t, h, &on.last);
            (s, stepped)
        };
        let (s, stepped) = from(self);
        if self.bonded && !(self.resting && self.slow(&s, h)) {
            self.break_bond(o);
            return from(self);
        }
        (s, stepped)
    }

    /// The reference step (s): the length of the step from rest that says whether the block
    /// stays, and the unit of [`OnBase::slow`]'s speed.
    pub(super) fn reference_step(&self) -> f64 {
        self.sim.settings().reference_step()
    }

    /// The end of the step from the block's time: at most [`MAX_ROWS_IN_A_STEP`] rows' intervals
    /// on, within the base's reach ([`time_to_reach`]), at the route's end. (No record shakes a
    /// block in these steps: its samples need not end them.)
    fn step_limit(&self) -> f64 {
        let settings = self.sim.settings();
        let l = self.size;
        let speed = self.s.v.norm() + l * self.s.w.norm();
        let accel = self
            .slowing
            .map_or(0.0, |(a, alpha)| a.norm() + l * alpha.norm());
        let mut longest =
            (MAX_ROWS_IN_A_STEP * settings.dt).min(time_to_reach(speed, accel, REACH * l));
        if self.tendons.iter().any(|t| !t.broken) {
            // A tendon is let go at the end of the step that takes it to its capacity: located
            // to the reference step, as before the steps were extrapolated.
            longest = longest.min(self.reference_step());
        }
        (self.t + longest).min(settings.t_end)
    }

    /// One step from the block's time (perhaps past the driver's time): tried at the length
    /// the last asked for, shortened until its error is within the tolerance (or taken as it is
    /// at the shortest, and booked), then taken.
    fn take_step<'s>(&mut self, mut o: Log<'s>) -> Flow<'s, OnBaseReport> {
        let limit = self.step_limit();
        let shortest = SHORTEST * self.reference_step();
        let tolerance = self.sim.settings().tolerance;
        loop {
            let h = self.h.min(limit - self.t);
            // The impulse solve held to the tolerance too.
            let ctx = Ctx {
                solve: step_solve(tolerance),
                ..self.ctx()
            };
            let x = ctx.extrapolated(&self.s, self.t, h, &self.last, tolerance);
            if x.ratio > 1.0 && h > shortest {
                o.report.steps.retried += 1;
                let shorter = h * step_factor(x.ratio).min(0.5);
                // A stop or a reversal within the step: the next tried ends where the slowing
                // before it brings the block to rest, if that is sooner.
                self.h = match self.time_to_stop() {
                    Some(t) if x.stopped && t < h && t >= shortest => t,
                    _ => shorter,
                };
                continue;
            }
            if let Some(what) = not_finite(&x.state) {
                let detail = format!("the step from t = {} s gave no finite {what}", self.t);
                return self.end(o, Reason::ContactForcesUndetermined, detail);
            }
            if x.ratio > 1.0 {
                Unmet::book(&mut o.report.tolerance_unmet, self.t, h, x.ratio);
            }
            let grown = h * step_factor(x.ratio);
            // A step cut short by the limit leaves the next as long as the last asked.
            self.h = if h < self.h { self.h.max(grown) } else { grown };
            return self.took((h, self.reference_step()), x, o);
        }
    }

    /// The time in which the block's motion comes to rest at the rate it slowed over the last
    /// step (its velocities, the turn's at the base's size, along those at the start of the
    /// step): none where it was not slowing.
    fn time_to_stop(&self) -> Option<f64> {
        let (a, alpha) = self.slowing?;
        let l2 = self.size * self.size;
        let speed2 = self.s.v.norm_squared() + l2 * self.s.w.norm_squared();
        let rate = self.s.v.dot(&a) + l2 * self.s.w.dot(&alpha);
        (rate < 0.0).then(|| -speed2 / rate)
    }

    /// A step to `t_to` of the time-stepping scheme alone, first order, where the base touches
    /// more than one face of the rock (rough rock, a crest, an edge: the touches change faster
    /// than the extrapolation can follow); booked as such in the report.
    fn first_order_step<'s>(&mut self, t_to: f64, mut o: Log<'s>) -> Flow<'s, OnBaseReport> {
        let h = t_to - self.t;
        let mut s = self.s;
        let last = self.ctx().step(&mut s, self.t, h, &self.last);
        FirstOrder::book(&mut o.report.first_order, self.t, h);
        let x = Extrapolated {
            state: s,
            ratio: 0.0,
            last,
            stopped: false,
        };
        if let Some(what) = not_finite(&x.state) {
            let detail = format!("the step from t = {} s gave no finite {what}", self.t);
            return self.end(o, Reason::ContactForcesUndetermined, detail);
        }
        self.h = self.h.min(h.max(SHORTEST * self.reference_step()));
        self.took((h, h), x, o)
    }

    /// The step of `h` just tried, `x`, taken: the rows within it kept, the tendons at their
    /// capacity let go, the travel booked; then whether it left the model, or stopped (slow
    /// against a step of `slow`: the step itself, or the reference step for an extrapolated
    /// one).
    fn took<'s>(
        &mut self,
        (h, slow): (f64, f64),
        x: Extrapolated,
        mut o: Log<'s>,
    ) -> Flow<'s, OnBaseReport> {
        self.keep(h, x, &mut o);
        if let Some((reason, detail)) = self.off_the_model() {
            return self.end(o, reason, detail);
        }
        self.stopped_or_resting(o, slow)
    }

    /// The step of `h` just tried, `x`, kept: the rows within it, the tendons at their
    /// capacity let go, the travel booked.
    pub(super) fn keep(&mut self, h: f64, x: Extrapolated, o: &mut Log<'_>) {
        let (s0, t0) = (self.s, self.t);
        o.report.steps.taken += 1;
        self.s = x.state;
        self.slowing = Some(((self.s.v - s0.v) / h, (self.s.w - s0.w) / h));
        self.t = t0 + h;
        self.last = x.last;
        self.rows_within(&s0, t0, h);
        self.break_tendons(o);
        o.travel += self.s.path - s0.path;
    }

    /// The recorded rows strictly within the step of `h` from `s0` at `t0` to the block's
    /// state, from the step's dense output.
    fn rows_within(&mut self, s0: &BodyState, t0: f64, h: f64) {
        self.within.clear();
        let s1 = self.s;
        for t in recorded_within(self.sim.settings(), t0, t0 + h) {
            let s = between(s0, &s1, h, (t - t0) / h);
            let row = self.row_of(t, &s);
            self.within.push(row);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_step_within_the_tolerance_grows_and_one_over_it_shrinks_within_the_bounds() {
        assert_eq!(step_factor(0.0), MAX_GROWTH);
        assert_eq!(step_factor(1e-12), MAX_GROWTH);
        assert!((step_factor(1.0) - SAFETY).abs() < 1e-15);
        // An error 8 times the tolerance asks for half the step, less the safety factor.
        assert!((step_factor(8.0) - 0.5 * SAFETY).abs() < 1e-15);
        assert_eq!(step_factor(1e9), MAX_SHRINK);
    }

    #[test]
    fn the_reach_is_gone_in_the_time_the_motions_closed_form_takes() {
        // Steady: reach / s. From rest: √(2 reach / a). Both: s h + a h² / 2 = reach.
        assert!((time_to_reach(2.0, 0.0, 1e-3) - 5e-4).abs() < 1e-18);
        assert!((time_to_reach(0.0, 8.0, 1e-3) - (2e-3f64 / 8.0).sqrt()).abs() < 1e-15);
        let h = time_to_reach(0.3, 4.0, 2e-3);
        assert!((0.3 * h + 2.0 * h * h - 2e-3).abs() < 1e-18, "{h}");
        assert_eq!(time_to_reach(0.0, 0.0, 1e-3), f64::INFINITY);
    }
}
