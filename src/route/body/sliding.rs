//! The block on its base while the base lies flush on one face of the rock, alone
//! (`flush.rs`, `derivations/13-base-contact.md` §13): the slide's equation integrated by RK4
//! with its embedded error estimate held to the tolerance, each step ending at the record's
//! next sample (where its acceleration may turn); a stop located by Newton's method on the
//! step's length; at rest under a record each sample checked for the onset of slip, an onset
//! located between two samples by bisection. Where the base would leave the slide within a
//! step (another face touched, the face's edge reached, the loads lifting or tipping it) the
//! step is cut back by bisection to where it still lies flush, and the time-stepping scheme
//! takes the block on from there.

use super::extrapolate::Extrapolated;
use super::flush::{Flush, Leaves, Slide};
use super::state::renormalized;
use super::stepping::{MAX_ROWS_IN_A_STEP, SHORTEST, time_to_reach};
use super::{Log, OnBase, OnBaseReport, Unmet};
use crate::contact;
use crate::route::dynamics::Flow;
use crate::route::integrator::{error_ratio, rk4_stages};
use crate::route::rest;
use nalgebra::Rotation3;

/// The farthest a point of the base goes in one step of the slide, as a fraction of its size:
/// whether the base still lies flush alone is asked at each step's end, and a step this short
/// cannot pass over another face's touch and off it again.
const FLUSH_REACH: f64 = 0.05;

/// The bisections that locate where the base leaves the slide, and the onset of slip between
/// two samples (each halves the interval: 60 take 5 ms to round-off).
const BISECTIONS: usize = 60;

/// The Newton iterations that locate a stop.
const STOP_ITERATIONS: usize = 30;

/// The speed, against the weight's over the reference step, under which a block whose stop
/// was not located is taken to have stopped ([`OnBase::creep`]).
const CREEP: f64 = 1e-6;

/// A step of the slide under this fraction of the reference step is tiny, and this many tiny
/// steps in a row under a record a stall ([`OnBase::stalls`]).
const TINY: f64 = 1e-2;
const STALLED: usize = 20;

/// A stop is located when the speed left, against the weight's over the reference step, is
/// below this: the distance it would still go, s² / 2a, is then under 1e-20 of g h².
const STOPPED: f64 = 1e-10;

/// The most a step grows or shrinks at once, and the safety factor on the step the error
/// estimate asks for (RK4's embedded estimate falls as h⁴).
const MAX_GROWTH: f64 = 4.0;
const MAX_SHRINK: f64 = 0.2;
const SAFETY: f64 = 0.8;

/// The factor by which the next step is the last one's, from its error ratio.
fn step_factor(ratio: f64) -> f64 {
    if ratio <= 0.0 {
        return MAX_GROWTH;
    }
    (SAFETY * ratio.powf(-0.25)).clamp(MAX_SHRINK, MAX_GROWTH)
}

/// One step of the slide tried: the state at its end, its rate there, and its error over the
/// tolerance.
struct Tried {
    y: Slide,
    k: Slide,
    ratio: f64,
}

/// The speed of the slide's state `y` with the turn's at the base's size `l` (m/s).
fn speed(y: &Slide, l: f64) -> f64 {
    (y[3] * y[3] + y[4] * y[4] + l * l * y[5] * y[5]).sqrt()
}

/// The velocities of `y` along those of `y0` (the turn's at the base's size `l`), over the
/// speed of `y0`: its speed while it goes on in their sense, negative once it has turned back.
fn along(y: &Slide, y0: &Slide, l: f64) -> f64 {
    (y[3] * y0[3] + y[4] * y0[4] + l * l * y[5] * y0[5]) / speed(y0, l)
}

/// Where the velocities of `y` (the turn's at the base's size `l`) going on at their rate
/// `k` come nearest to zero, if that is ahead and within a quarter of their speed now of it:
/// a stop to be located. (A turn that dies away while the block slides on is not one.)
fn stop_ahead(y: &Slide, k: &Slide, l: f64) -> Option<f64> {
    let v = [y[3], y[4], l * y[5]];
    let a = [k[3], k[4], l * k[5]];
    let aa: f64 = a.iter().map(|x| x * x).sum();
    let t = -(v[0] * a[0] + v[1] * a[1] + v[2] * a[2]) / aa;
    let least: f64 = (0..3)
        .map(|i| (v[i] + a[i] * t).powi(2))
        .sum::<f64>()
        .sqrt();
    (t > 0.0 && least <= 0.25 * speed(y, l)).then_some(t)
}

impl OnBase<'_> {
    /// Whether the base lies flush on one face now, alone, free of bonds and tendons, on
    /// constant friction: the slide set up there if it was not — the pose put on the plane
    /// (the base's normal along the face's, its foot on it), the velocities across it taken
    /// off, their energy and the snap's booked with the contacts' work.
    pub(super) fn flush_phase(&mut self) -> bool {
        if self.flush.is_some() {
            return true;
        }
        if self.bonded || self.tendons.iter().any(|t| !t.broken) {
            return false;
        }
        let Some(face) = self.ctx().flush_face(&self.s.pose) else {
            return false;
        };
        let criterion = contact::rock_criterion(self.sim.strengths(), face, 0);
        let Some(mu) = criterion.constant_mu() else {
            return false;
        };
        let plane = self.ground.faces()[face];
        let (n, depth) = (plane.normal(), self.base.depth());
        // Not while it moves across the plane (a landing that the time-stepping scheme's
        // impacts, with their friction, are still to resolve).
        let across = self.s.v.dot(&n).abs() + self.size * (self.s.w - n * n.dot(&self.s.w)).norm();
        if across > self.creep() {
            return false;
        }
        let mut pose = self.s.pose;
        let base_normal = pose.rotation.column(1).into_owned();
        // The turn that lays the base's normal on the face's (within 1e-6 rad of it: the
        // patch's flush angle), by its axis and angle: nalgebra's rotation between two
        // vectors so nearly parallel is not a number.
        let axis = base_normal.cross(&n);
        let (sin, cos) = (axis.norm(), base_normal.dot(&n));
        if sin > 0.0 {
            let r = Rotation3::from_scaled_axis(axis * (sin.atan2(cos) / sin));
            let turned = r * Rotation3::from_matrix_unchecked(pose.rotation);
            pose.rotation = renormalized(&turned).into_inner();
        }
        if !(pose
            .cm
            .iter()
            .chain(pose.rotation.iter())
            .all(|x| x.is_finite()))
        {
            return false;
        }
        pose.cm -= n * (plane.signed_distance(&pose.cm) - depth);
        let area = &self.quadrature.area;
        let Some(flush) = Flush::new(face, n, mu, pose, (area, depth)) else {
            return false;
        };
        let mass = self.body.block().mass;
        let before = self.s.kinetic(mass, &self.inertia);
        // The potential energy of the snap onto the plane (round-off of the base's size) is the
        // contacts' work too, so that the balance stays closed.
        let lift = pose.cm.y - self.s.pose.cm.y;
        self.s.pose = pose;
        self.s.v -= n * n.dot(&self.s.v);
        self.s.w = n * n.dot(&self.s.w);
        self.s.work_contacts +=
            self.s.kinetic(mass, &self.inertia) - before + mass * self.body.loads().gravity * lift;
        self.flush = Some(flush);
        true
    }

    /// One increment of the slide towards the driver's `t_to`: at rest under a record, its
    /// samples walked until one starts the block; moving, one step.
    pub(super) fn flush_increment<'s>(&mut self, t_to: f64, o: Log<'s>) -> Flow<'s, OnBaseReport> {
        let Some(flush) = self.flush.take() else {
            return Flow::Go(o);
        };
        if self.resting {
            self.rest_flush(flush, t_to, o)
        } else {
            self.slide(flush, o)
        }
    }

    /// At rest under a record: each of its samples to `t_to` checked for the onset of slip
    /// ([`Flush::onset`]; the record's acceleration is straight between samples), the onset
    /// located between the last sample that held and the first that does not.
    fn rest_flush<'s>(
        &mut self,
        mut flush: Flush,
        t_to: f64,
        o: Log<'s>,
    ) -> Flow<'s, OnBaseReport> {
        let foundation = self.sim.foundation();
        while self.t < t_to * (1.0 - 1e-15) {
            if !rest::shaking(foundation, self.t) {
                self.flush = Some(flush);
                return self.rest_until_the_record_ends(o);
            }
            let next = rest::next_turn(foundation, self.t, t_to);
            match self.starts(&mut flush, next) {
                Err(_) => return self.leave_flush(o),
                Ok(None) => self.t = next,
                Ok(Some(_)) => {
                    self.t = self.onset_between(&mut flush, self.t, next);
                    self.resting = false;
                    self.flush = Some(flush);
                    return Flow::Go(o);
                }
            }
        }
        self.flush = Some(flush);
        Flow::Go(o)
    }

    /// Whether the loads at time `t` start the block at rest where it is: the mode it starts
    /// in, kept for the slide, or None where friction holds it.
    fn starts(&self, flush: &mut Flush, t: f64) -> Result<Option<[f64; 3]>, Leaves> {
        let ctx = self.ctx();
        let (force, moment, _) = ctx.loads(&self.s.pose, t);
        let start = flush.onset(&ctx, &self.s.pose, (force, moment))?;
        flush.mode = start.map(|(mode, _)| mode);
        Ok(flush.mode)
    }

    /// The onset of slip between `held` (s), where friction holds the block, and `starts`,
    /// where it does not: bisected to round-off, the mode there kept.
    fn onset_between(&self, flush: &mut Flush, mut held: f64, mut starts: f64) -> f64 {
        for _ in 0..BISECTIONS {
            let mid = 0.5 * (held + starts);
            if mid <= held || mid >= starts {
                break;
            }
            match self.starts(flush, mid) {
                Ok(Some(_)) => starts = mid,
                _ => held = mid,
            }
        }
        // The mode where it starts.
        let _ = self.starts(flush, starts);
        starts
    }

    /// The slide's base leaves it here: the time-stepping scheme goes on from the present
    /// state, and the slide is not taken up again before a step of it.
    fn leave_flush<'s>(&mut self, o: Log<'s>) -> Flow<'s, OnBaseReport> {
        self.flush = None;
        self.left_flush_at = Some(self.t);
        Flow::Go(o)
    }

    /// One step of the slide from the block's state: from rest in the mode the loads start
    /// (or at rest for good where friction holds it), to a stop where one comes within the
    /// step the tolerance allows, else that step, shortened while its error is over the
    /// tolerance or the base would leave the slide.
    fn slide<'s>(&mut self, mut flush: Flush, mut o: Log<'s>) -> Flow<'s, OnBaseReport> {
        let l = self.size;
        let mut y0 = self.slide_state(&mut flush);
        if speed(&y0, l) == 0.0 && flush.mode.is_none() {
            match self.starts(&mut flush, self.t) {
                Err(_) => return self.leave_flush(o),
                Ok(None) => {
                    self.flush = Some(flush);
                    return self.come_to_rest(o);
                }
                Ok(Some(_)) => {}
            }
        }
        flush.step = self.h;
        let mut k1 = match flush.rate(&self.ctx(), &y0) {
            Ok(k) => k,
            Err(_) => return self.leave_flush(o),
        };
        // Slow enough for its slip's direction to be settled: the slip across it taken off.
        if flush.hold_along(&self.ctx(), &mut y0) {
            k1 = match flush.rate(&self.ctx(), &y0) {
                Ok(k) => k,
                Err(_) => return self.leave_flush(o),
            };
        }
        let mut h = self.h.min(self.slide_limit(&y0, &k1));
        if speed(&y0, l) == 0.0 {
            // From rest the first stage slides in the mode found at the onset, the others in
            // the motion's own directions: a step this short keeps the difference, should the
            // mode be settled only roughly, under round-off of the route; the next steps grow.
            h = h.min(SHORTEST * self.reference_step());
        }
        // Slowing to a stop within the step: the step ends there.
        if let Some(to_stop) = stop_ahead(&y0, &k1, l).filter(|&t| t < h) {
            if let Some((hs, tried)) = self.to_the_stop(&mut flush, &y0, to_stop) {
                return self.stopped_flush(flush, hs, tried, o);
            }
            h = to_stop;
        }
        let shortest = SHORTEST * self.reference_step();
        // A step cut short by the limit or a stop leaves the next as long as the last asked.
        let mut limited = h < self.h;
        loop {
            match self.try_slide(&mut flush, &y0, h) {
                Err(_) => return self.slide_until_it_leaves(flush, &y0, h, o),
                Ok(t) if t.ratio > 1.0 && h > shortest => {
                    o.report.steps.retried += 1;
                    h *= step_factor(t.ratio).min(0.5);
                    limited = false;
                }
                Ok(t) => {
                    if t.ratio > 1.0 {
                        Unmet::book(&mut o.report.tolerance_unmet, self.t, h, t.ratio);
                    }
                    let grown = h * step_factor(t.ratio);
                    self.h = if limited { self.h.max(grown) } else { grown };
                    let stalled = self.stalls(&mut flush, h, speed(&y0, l) == 0.0);
                    flush.mode = None;
                    self.flush = Some(flush);
                    return match self.took_slide(h, t.y, o) {
                        Flow::Go(o) if stalled => {
                            self.stalled = true;
                            self.leave_flush(o)
                        }
                        Flow::Go(o) if speed(&t.y, l) <= self.creep() => self.crept_to_rest(o),
                        flow => flow,
                    };
                }
            }
        }
    }

    /// Whether the slide has stalled under a record with this step of `h` (not one from
    /// rest): [`STALLED`] steps in a row each under [`TINY`] of the reference step, as a slow
    /// slip that friction turns takes (its direction is not settled near its own, so each step
    /// is held to the time friction takes to turn it). The time-stepping scheme then takes the
    /// block, first order and booked, until it rests again.
    fn stalls(&self, flush: &mut Flush, h: f64, from_rest: bool) -> bool {
        let tiny = h < TINY * self.reference_step() && !from_rest;
        flush.tiny = if tiny { flush.tiny + 1 } else { 0 };
        self.sim.foundation().record().is_some() && flush.tiny >= STALLED
    }

    /// The speed under which a block that has not stopped where a stop was located is taken
    /// to have stopped (m/s): a millionth of what its weight gives it over the reference
    /// step, the distance it would still go (s² / 2a) under 1e-12 of g h².
    fn creep(&self) -> f64 {
        CREEP * self.body.loads().gravity * self.reference_step()
    }

    /// A block creeping slower than [`OnBase::creep`]: at rest where friction holds it there
    /// (its kinetic energy booked with the contacts' work); else it slides on in the mode the
    /// loads start — its velocities along that mode kept, those across (or all, where the mode
    /// turns it back) taken off and booked likewise.
    fn crept_to_rest<'s>(&mut self, o: Log<'s>) -> Flow<'s, OnBaseReport> {
        let Some(mut flush) = self.flush.take() else {
            return Flow::Go(o);
        };
        let start = self.starts(&mut flush, self.t);
        match start {
            Err(_) => self.leave_flush(o),
            Ok(None) => {
                self.flush = Some(flush);
                self.come_to_rest(o)
            }
            Ok(Some(mode)) => {
                let mut y = self.slide_state(&mut flush);
                flush.along = Some(mode);
                flush.hold_along(&self.ctx(), &mut y);
                (self.s.v, self.s.w) = flush.velocities(&y);
                self.s.work_contacts = y[8];
                if speed(&y, self.size) > 0.0 {
                    flush.mode = None;
                }
                self.flush = Some(flush);
                Flow::Go(o)
            }
        }
    }

    /// The slide's state now, the slide's origin moved here.
    fn slide_state(&self, flush: &mut Flush) -> Slide {
        let s = &self.s;
        flush.start(
            (self.t, s.pose),
            (s.v, s.w),
            (s.path, s.work_applied, s.work_contacts),
        )
    }

    /// The end of the slide's step from `y0` (rate `k1`): at most [`MAX_ROWS_IN_A_STEP`] rows'
    /// intervals on, within [`FLUSH_REACH`] of the base's size, at the record's next sample or
    /// the route's end. Its length (s).
    fn slide_limit(&self, y0: &Slide, k1: &Slide) -> f64 {
        let settings = self.sim.settings();
        let l = self.size;
        let speed = speed(y0, l);
        let accel = (k1[3] * k1[3] + k1[4] * k1[4] + l * l * k1[5] * k1[5]).sqrt();
        let longest =
            (MAX_ROWS_IN_A_STEP * settings.dt).min(time_to_reach(speed, accel, FLUSH_REACH * l));
        let end = rest::next_turn(self.sim.foundation(), self.t, settings.t_end);
        (self.t + longest).min(end) - self.t
    }

    /// The slide's step of `h` from `y0`: RK4 and its error over the tolerance
    /// (the CM, the path and the turn against the base's size), or why the base leaves the
    /// slide within it (at a stage, or another face touched or the face's edge passed at its
    /// end).
    fn try_slide(&self, flush: &mut Flush, y0: &Slide, h: f64) -> Result<Tried, Leaves> {
        let ctx = self.ctx();
        // The rates for a step of this length (the band of settled slips is the step's).
        flush.step = h;
        let k1 = flush.rate(&ctx, y0)?;
        let (y, k4) = rk4_stages(y0, &k1, h, |y| flush.rate(&ctx, y))?;
        let k = flush.rate(&ctx, &y)?;
        if ctx.flush_face(&flush.pose(&y)) != Some(flush.face) {
            return Err(Leaves::Meets);
        }
        let tol = self.sim.settings().tolerance;
        let at = 1.0 / (tol * self.size);
        let weights = [at, at, 1.0 / tol, 0.0, 0.0, 0.0, at, 0.0, 0.0, 0.0];
        let ratio = error_ratio(&weights, h, &k4, &k).max(self.unbalanced(flush, (y0, &y), tol));
        Ok(Tried { y, k, ratio })
    }

    /// How far the step from `y0` to `y` moved the energy balance W + W_f − ΔK − ΔU, against
    /// the tolerance `tol` of the route's energy (the larger of the kinetic energies and the
    /// works so far, never below their round-off): above 1 where friction's stiffness made
    /// the step swing the slip about (a slow block turning), which the error estimate of the
    /// positions may not see.
    fn unbalanced(&self, flush: &Flush, (y0, y): (&Slide, &Slide), tol: f64) -> f64 {
        let mass = self.body.block().mass;
        let g = self.body.loads().gravity;
        let inertia = self.s.world_inertia(&self.inertia);
        let kinetic = |y: &Slide| {
            let (v, w) = flush.velocities(y);
            0.5 * mass * v.norm_squared() + 0.5 * w.dot(&(inertia * w))
        };
        let (k0, k1) = (kinetic(y0), kinetic(y));
        let lift = flush.pose(y).cm.y - flush.pose(y0).cm.y;
        let moved = (y[7] - y0[7]) + (y[8] - y0[8]) - (k1 - k0) - mass * g * lift;
        let scale = k0
            .max(k1)
            .max(y[7].abs())
            .max(y[8].abs())
            .max((y[8] - y0[8]).abs());
        moved.abs() / (tol * scale + 1e-14 * scale).max(f64::MIN_POSITIVE)
    }

    /// A stop expected `to_stop` (s) on from `y0`, located by Newton's method on
    /// the step's length, kept within the bracket of a step that has not stopped and one that
    /// has turned back (bisected where Newton's step leaves it), the stages past the stop
    /// sliding on in the start's sense: the step's length and its end, or None where the block
    /// does not stop there (the speed left across the start's direction is not round-off, the
    /// base would leave the slide, or the step is over the tolerance).
    fn to_the_stop(&self, flush: &mut Flush, y0: &Slide, to_stop: f64) -> Option<(f64, Tried)> {
        let l = self.size;
        let enough = STOPPED * self.body.loads().gravity * self.reference_step();
        flush.sense = Some(flush.velocities(y0));
        let (mut h, mut on, mut back) = (to_stop, 0.0, f64::INFINITY);
        let mut found = None;
        for _ in 0..STOP_ITERATIONS {
            let Ok(t) = self.try_slide(flush, y0, h) else {
                break;
            };
            let (g, slope) = (along(&t.y, y0, l), along(&t.k, y0, l));
            if t.ratio > 1.0 {
                break;
            }
            if g.abs() <= enough || (back.is_finite() && back - on <= 1e-15 * back) {
                if speed(&t.y, l) <= 2.0 * enough + 1e-6 * speed(y0, l) {
                    found = Some((h, t));
                }
                break;
            }
            if g > 0.0 {
                on = h;
            } else {
                back = h;
            }
            let newton = h - g / slope;
            h = if slope < 0.0 && newton > on && newton < back {
                newton
            } else if back.is_finite() {
                0.5 * (on + back)
            } else {
                2.0 * h
            };
        }
        flush.sense = None;
        found
    }

    /// The block stopped at the end of the step of `h` just located, `tried`: its last
    /// kinetic energy (round-off) booked with the contacts' work, at rest; then whether the
    /// loads start it again (the slide goes on in the mode they start), or friction holds it.
    fn stopped_flush<'s>(
        &mut self,
        flush: Flush,
        h: f64,
        mut tried: Tried,
        o: Log<'s>,
    ) -> Flow<'s, OnBaseReport> {
        let mass = self.body.block().mass;
        let (v, w) = flush.velocities(&tried.y);
        let inertia = self.s.world_inertia(&self.inertia);
        tried.y[8] -= 0.5 * mass * v.norm_squared() + 0.5 * w.dot(&(inertia * w));
        tried.y[3] = 0.0;
        tried.y[4] = 0.0;
        tried.y[5] = 0.0;
        self.h = h.max(SHORTEST * self.reference_step());
        self.flush = Some(flush);
        let flow = self.took_slide(h, tried.y, o);
        let Flow::Go(o) = flow else {
            return flow;
        };
        let Some(mut flush) = self.flush.take() else {
            return Flow::Go(o);
        };
        match self.starts(&mut flush, self.t) {
            Err(_) => self.leave_flush(o),
            Ok(Some(_)) => {
                self.flush = Some(flush);
                Flow::Go(o)
            }
            Ok(None) => {
                self.flush = Some(flush);
                self.come_to_rest(o)
            }
        }
    }

    /// Where the base leaves the slide within the step of `h` from `y0`: the
    /// longest step that keeps it flush, to round-off, taken; then the time-stepping scheme.
    fn slide_until_it_leaves<'s>(
        &mut self,
        mut flush: Flush,
        y0: &Slide,
        h: f64,
        o: Log<'s>,
    ) -> Flow<'s, OnBaseReport> {
        let (mut kept, mut left) = (0.0, h);
        let mut best = None;
        for _ in 0..BISECTIONS {
            let mid = 0.5 * (kept + left);
            if mid <= kept || mid >= left {
                break;
            }
            match self.try_slide(&mut flush, y0, mid) {
                Ok(t) => {
                    kept = mid;
                    best = Some(t.y);
                }
                Err(_) => left = mid,
            }
        }
        let Some(y) = best else {
            return self.leave_flush(o);
        };
        self.flush = Some(flush);
        match self.took_slide(kept, y, o) {
            Flow::Go(o) => self.leave_flush(o),
            ended => ended,
        }
    }

    /// The slide's step of `h` to `y` taken: the block's state there, its rows, its travel.
    fn took_slide<'s>(&mut self, h: f64, y: Slide, mut o: Log<'s>) -> Flow<'s, OnBaseReport> {
        let Some(flush) = self.flush.as_ref() else {
            return Flow::Go(o);
        };
        let mut s = self.s;
        s.pose = flush.pose(&y);
        (s.v, s.w) = flush.velocities(&y);
        s.path = y[6];
        s.work_applied = y[7];
        s.work_contacts = y[8];
        let x = Extrapolated {
            state: s,
            ratio: 0.0,
            last: self.last.clone(),
            stopped: false,
        };
        self.keep(h, x, &mut o);
        match self.off_the_model() {
            Some((reason, detail)) => self.end(o, reason, detail),
            None => Flow::Go(o),
        }
    }
}
