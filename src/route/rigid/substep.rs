//! Step control of the rigid body: the route in steps, each tried, taken, shortened where its
//! error estimate exceeds the tolerance or the energy balance says RK4 does not resolve the
//! motion, or cut at an event and the event handled (`derivations/08-rigid-body.md` §3, §4a).
//! A step may be longer than the interval of the recorded rows: the rows within it are its dense
//! output, each evaluated at its own state, or, in a long step that holds no contact in a crease,
//! evaluated at a few and the rest interpolated between them (`rows.rs`).

use super::at_rest::Rest;
use super::evaluate::{Eval, Hold, evaluate};
use super::faces::{BeforeImpact, after_events, after_impact, face_event};
use super::heading::{Bracket, Heading, Span, bracket_event, confirmed, rk4_stages};
use super::hold::{Anchor, hold_anchor, hold_on_creases};
use super::rows;
use super::state::{RigidState, VALUES};
use super::tendons::AT_CAPACITY;
use super::{Ending, Model, RigidBody};
use super::{Log, RigidBodyReport};
use crate::mechanics::rigid_body::Motion;

use crate::route::driver::recorded_within;
use crate::route::dynamics::Flow;
use crate::route::events::{Event, cut_at};
use crate::route::integrator::{error_ratio, hermite};
use crate::route::pose_finder::PoseFinder;
use crate::route::rest;
use crate::route::row::Row;
use crate::route::termination::{Reason, Stop};

/// The fraction of the largest kinetic energy of the route below which the block counts as at
/// rest when a contact's slip passes through zero (see `RigidBody::cut_at_event`).
const REST: f64 = 1e-9;

/// The fraction of the largest kinetic energy since the block last slipped from rest below
/// which a slip is settling: a contact's slip passing through zero there, with the loads within
/// the friction cones, is the stop (see `RigidBody::cut_at_event`).
const SETTLED: f64 = 1e-6;

/// The most events (stops that restart, pivots) resolved within one increment.
const MAX_EVENTS: usize = 16;

/// Events at one moment, the route not moving on between them, past which the route ends
/// there ("the contact forces are not determined"): a contact that leaves a crease and meets
/// the crease's other face again at once would otherwise loop for ever (met under a record on
/// faces). Three events at one moment are the most a consistent motion takes (an impact that
/// lifts a contact off its face and puts it on the next, `crease_event`), so 64 is none of them.
const EVENTS_AT_ONE_MOMENT: usize = 64;

/// The most switches of friction's regime (`Event::Switch`) located within one increment; past
/// it the increment's steps cross them as they are.
const MAX_SWITCHES: usize = 16;

/// The shortest substep, as a fraction of the reference step (then the step is taken as it is).
const MIN_SUBSTEP: f64 = 1e-3;

/// The longest step, in recorded rows' intervals: the rows within one step are kept until the
/// driver takes them, so that this bounds their memory.
const MAX_ROWS_IN_A_STEP: f64 = 1024.0;

/// The most a step grows or shrinks at once, and the safety factor on the step the error
/// estimate asks for (the usual controller of an embedded pair: Hairer, Nørsett & Wanner, I,
/// II.4).
const MAX_GROWTH: f64 = 5.0;
const MAX_SHRINK: f64 = 0.2;
const SAFETY: f64 = 0.9;

/// Each value's weight in a step's error (`derivations/08-rigid-body.md` §4a): the CM's
/// position and its path against the block's size L and the yaw in radians, each over the
/// tolerance. The rates, the works and the time are not weighed: where friction switches within
/// a step (a contact starting to stick, or a switch of friction's regime past `MAX_SWITCHES` in
/// an increment; below it a switch is located as an event, `Event::Switch`), the
/// accelerations jump, and an estimate of the rates' error, first order there, would shrink the
/// step to the shortest at every switch; the positions' error, of second order there, keeps the
/// steps the motion needs, and the energy balance watches the rates.
pub(super) fn error_weights(sim: &Model<'_>) -> [f64; VALUES] {
    let (l, tol) = (sim.body().l(), sim.settings().tolerance);
    let none = f64::INFINITY;
    [l, l, 1.0, none, none, none, none, none, none, l].map(|s| 1.0 / (tol * s))
}

/// The factor by which the next step is the last one's, from its error ratio: the step whose
/// error would be the tolerance (the estimate falls as h⁴), with the safety factor, within the
/// growth and shrink bounds.
fn step_factor(ratio: f64) -> f64 {
    if ratio <= 0.0 {
        return MAX_GROWTH;
    }
    (SAFETY * ratio.powf(-0.25)).clamp(MAX_SHRINK, MAX_GROWTH)
}

/// Substep control: whether a substep of length `len` moved the energy balance
/// W_h + W_f − ΔK − ΔU from `before` to `after` by more than the `tolerance` of the route's
/// energy `scale` (the largest of its kinetic energy and of the works so far), never below the
/// balance's own round-off, and may still be shortened (it is longer than `MIN_SUBSTEP` of the
/// `reference` step). Where the motion is resolved RK4 moves it by far less; it is exceeded where
/// friction makes the motion stiff — near a stop the friction moments damp the rotation at a
/// rate ∝ μ N r² / (I |v|) — or a slip swings round near zero, which the error estimate of a
/// step across such a swing may not see.
fn unresolved_substep(
    residual: Change,
    (scale, tolerance): (f64, f64),
    len: f64,
    reference: f64,
    round_off: f64,
) -> bool {
    (residual.after - residual.before).abs() > (tolerance * scale).max(round_off)
        && len > MIN_SUBSTEP * reference
}

/// A quantity before a substep and after it.
#[derive(Debug, Clone, Copy)]
struct Change {
    before: f64,
    after: f64,
}

/// What one substep came to.
enum Substep {
    /// Too long to resolve the motion or to locate a failure in: `h` was halved, try again.
    Retry,
    /// The state moved on without an event.
    Moved,
    /// An event was handled (a pivot, a release, a stop from which the block slips again).
    Event,
    /// The step ended where friction's regime switched.
    Switch,
}

/// One attempted step: its length, the derivative at its start, and what it reached.
struct Trial<'f> {
    h: f64,
    k1: [f64; VALUES],
    /// The end state (the start's where the step failed) and its evaluation.
    next: RigidState,
    next_ev: Eval,
    /// An event met at one of the step's stages.
    crossed: Option<Event>,
    /// The event met at a stage is a stop met at a middle stage.
    stop_at_middle: bool,
    /// Where the step or its end state is off the model.
    failed: Option<Stop>,
    /// The pose finder at the end state.
    at_next: PoseFinder<'f>,
    /// The step's last stage, k4 (for its error estimate).
    k4: [f64; VALUES],
}

/// A step's dense output and what its rows are held to: the rows within it are made from this.
struct DenseStep<'a> {
    sim: &'a Model<'a>,
    /// What the step holds its contacts to (the step's start's).
    hold: Hold,
    /// The sticking contact and where it stuck.
    anchor: Option<Anchor>,
    /// The step's start (s) and length (s).
    t0: f64,
    h: f64,
    /// The state and its derivative at the step's start, and at its end.
    y0: [f64; VALUES],
    k1: &'a [f64; VALUES],
    y1: [f64; VALUES],
    k5: [f64; VALUES],
}

impl DenseStep<'_> {
    /// The step's state at `t`: its cubic Hermite interpolant (`integrator::hermite`).
    fn at(&self, t: f64) -> RigidState {
        let (t0, h) = (self.t0, self.h);
        let y = RigidState::from_array(&hermite(
            (&self.y0, self.k1),
            (&self.y1, &self.k5),
            h,
            (t - t0) / h,
        ));
        y.at(self.y0[8] + (t - t0))
    }

    /// The model's row at `t`, held as the step's end is: a sticking contact where it stuck, a
    /// crease's contact on its second face.
    fn row_at(&self, f: &mut PoseFinder<'_>, t: f64) -> Result<Row, Stop> {
        let (sim, anchor) = (self.sim, self.anchor);
        let y = self.at(t);
        evaluate(sim, f, &y, self.hold).and_then(|mut e| {
            let mut y = match anchor {
                Some(a) if e.motion.stuck == Some(a.contact) => {
                    let held;
                    (held, e) = hold_anchor(sim, f, e.accept(&y), e, a)?;
                    held
                }
                _ => e.accept(&y),
            };
            hold_on_creases(sim, f, &mut y, &mut e)?;
            Ok(e.row(t, &y))
        })
    }

    /// The model's row at `t` for an interpolation of `values`: nothing held, the model at the
    /// dense state, as `row_at` has it (its holds do nothing here; this shorter path measured
    /// 1.4 % fewer instructions on the default route); a held contact, `row_at`'s.
    fn exact(&self, f: &mut PoseFinder<'_>, t: f64, values: rows::Values) -> Result<Row, Stop> {
        match values {
            rows::Values::Model => {
                let y = self.at(t);
                evaluate(self.sim, f, &y, self.hold).map(|e| e.row(t, &e.accept(&y)))
            }
            rows::Values::All => self.row_at(f, t),
        }
    }

    /// The row `like` with the dense state at `t` in place of its own.
    fn state_row(&self, t: f64, like: &Row) -> Row {
        let y = self.at(t);
        Row {
            t_s: t,
            x_m: y.x,
            z_m: y.z,
            theta_deg: y.theta.to_degrees(),
            vx_m_s: y.vx,
            vz_m_s: y.vz,
            omega_deg_s: y.omega.to_degrees(),
            ..*like
        }
    }
}

/// Which of a row's values are interpolated in a step whose start's motion is `m0` and end's
/// `m1`, the sticking contact `anchor`: nothing held, the state is the dense output's as it is
/// (`Eval::accept` changes no rate, `hold_anchor` and `hold_on_creases` nothing), and the
/// model's values are interpolated; a contact held where it stuck at both ends, the state is
/// the hold's, and every value is; else none (each row evaluated).
fn interpolated_values(anchor: Option<Anchor>, m0: &Motion, m1: &Motion) -> Option<rows::Values> {
    match (anchor, m0.stuck, m1.stuck) {
        (None, None, None) => Some(rows::Values::Model),
        (Some(a), Some(i), Some(j)) if i == a.contact && j == a.contact => Some(rows::Values::All),
        _ => None,
    }
}

/// The rows of `step` at `times` (inside it, at least one) into `out`, the finder at the step's
/// start `start`, its ends evaluated as `ends` ((evaluation, state) at its start and at its
/// end): interpolated where the step is `smooth`, holds no contact in a crease, holds either no
/// contact or the same one sticking at both ends and passes at least `rows::FEWEST` rows (and the
/// interpolant passes its check); else each evaluated. The number interpolated; `None` where an
/// evaluated row's state is off the model.
fn rows_of(
    step: &DenseStep<'_>,
    start: &PoseFinder<'_>,
    times: &[f64],
    ((ev, y), (end_ev, end)): ((&Eval, &RigidState), (&Eval, &RigidState)),
    smooth: bool,
    out: &mut Vec<Row>,
) -> Option<usize> {
    let no_creases = |m: &Motion| m.creases.is_empty();
    if let Some(values) = interpolated_values(step.anchor, &ev.motion, &end_ev.motion)
        && smooth
        && times.len() >= rows::FEWEST
        && no_creases(&ev.motion)
        && no_creases(&end_ev.motion)
    {
        let (t0, h) = (step.t0, step.h);
        let mut f = start.clone();
        let first = ev.row(t0, y);
        let last = end_ev.row(t0 + h, end);
        let exact = |t: f64| step.exact(&mut f, t, values);
        let state = |t: f64, like: &Row| step.state_row(t, like);
        let scale = (step.sim.body().l(), step.sim.settings().tolerance);
        let (from, to) = ((t0, &first), (t0 + h, &last));
        match rows::interpolate(times, from, to, scale, values, exact, state, out) {
            Ok(rows::Interpolated::Done) => return Some(times.len() - rows::EVALUATED),
            Ok(rows::Interpolated::Evaluate) => out.clear(),
            Err(_) => return None,
        }
    }
    let mut f = start.clone();
    for &t in times {
        match step.row_at(&mut f, t) {
            Ok(r) => out.push(r),
            Err(_) => return None,
        }
    }
    Some(0)
}

impl RigidBody<'_> {
    /// Increment `k` to `t_target` in steps: each step checked for events — a stop, a pivot, a
    /// release, a failure — found by bisection on the step length, and shortened where its
    /// error estimate exceeds the tolerance or the energy balance says RK4 does not resolve the
    /// motion. An event-free step may end past `t_target` (the rows it passes are its dense
    /// output); a step with an event ends by `t_target`, so that the rows stay in time order.
    pub(super) fn substeps<'s>(
        &mut self,
        finder: &mut PoseFinder<'_>,
        k: usize,
        t_target: f64,
        mut o: Log<'s>,
    ) -> Flow<'s, RigidBodyReport> {
        let mut events = 0usize;
        let mut switches = 0usize;
        self.switching = true;
        // Events met at one moment without the route moving on: (the moment, how many).
        let mut at_one_moment = (f64::NAN, 0usize);
        while self.t < t_target * (1.0 - 1e-15) {
            if self.resting {
                o = match self.rest(finder, t_target, o) {
                    Flow::Go(o) if !self.resting => o,
                    flow => return flow,
                };
                continue;
            }
            // Past MAX_EVENTS in one increment (a contact's slip chattering about zero), the
            // rest of the increment is taken in plain substeps: no event resolved, each still
            // within the tolerance by its error estimate.
            let resolve = events < MAX_EVENTS && !self.through;
            self.switching &= switches < MAX_SWITCHES;
            // A ground-motion record's samples are where its loads may turn: steps end on them
            // (RK4 keeps its order between them); and none goes past the route's end.
            let until = rest::next_turn(self.sim.foundation(), self.t, self.sim.settings().t_end);
            let before = self.t;
            let left = (until - self.t, t_target - self.t);
            match self.substep(finder, k, left, resolve, &mut o) {
                Ok(step @ (Substep::Event | Substep::Switch)) => {
                    self.through = false;
                    o.report.steps.taken += 1;
                    match step {
                        Substep::Switch => switches += 1,
                        _ => events += 1,
                    }
                    at_one_moment = match at_one_moment {
                        (t, n) if t == before && self.t == before => (t, n + 1),
                        _ => (self.t, 1),
                    };
                    if at_one_moment.1 > EVENTS_AT_ONE_MOMENT {
                        let detail = format!(
                            "at t = {:.6} s the route met {} events at one moment without moving on \
                             (a contact that leaves a crease meets the crease's other face again \
                             at once, or a slip turning round and round): no consistent \
                             motion on from here",
                            self.t, EVENTS_AT_ONE_MOMENT
                        );
                        return Flow::Ended(o.end(
                            Reason::ContactForcesUndetermined,
                            self.t,
                            detail,
                        ));
                    }
                }
                Ok(Substep::Retry) => o.report.steps.retried += 1,
                Ok(Substep::Moved) => {
                    self.through = false;
                    o.report.steps.taken += 1;
                }
                Err(Ending::Failed(stop)) => return Flow::Ended(self.fail(o, stop)),
                Err(Ending::At(reason, t, detail)) => {
                    return Flow::Ended(o.end(reason, t, detail));
                }
            }
        }
        if self.t <= t_target * (1.0 + 1e-15) {
            self.t = t_target;
        }
        Flow::Go(o)
    }

    /// One step of at most `left.0` (s) and, if it meets an event, of at most `left.1` (to the
    /// driver's time): tried, then moved on, retried shorter, or cut at an event and the event
    /// handled.
    fn substep<'f>(
        &mut self,
        finder: &mut PoseFinder<'f>,
        k: usize,
        (left, to_target): (f64, f64),
        resolve: bool,
        o: &mut Log<'_>,
    ) -> Result<Substep, Ending> {
        if self.break_tendons(finder, o)? {
            return Ok(Substep::Event);
        }
        let mass = self.sim.body().block().mass;
        let motion = self.ev.motion;
        let ke = motion.twist.kinetic_energy(mass, &motion.inertia);
        self.ke_max = self.ke_max.max(ke);
        self.slip_peak = self.slip_peak.max(ke);
        let heading = Heading {
            before: &motion,
            mass,
            switches: self.switching && resolve,
        };
        let longest =
            MAX_ROWS_IN_A_STEP * self.sim.settings().dt * self.sim.settings().stride as f64;
        let reference = self.sim.settings().reference_step();
        // Through a moment of a pivot met again at once: the shortest substep, or shorter where
        // it had to be taken again (`through` stays set until a step is taken).
        let h = match self.through {
            true => self.h.min(MIN_SUBSTEP * reference),
            false => self.h,
        };
        let mut trial = self.trial(finder, h.min(left).min(longest), resolve, &heading);
        let eventful = |t: &Trial<'_>| {
            t.failed.is_some()
                || t.crossed.is_some()
                || heading
                    .event(&t.next_ev.motion)
                    .filter(|_| resolve)
                    .is_some()
        };
        if trial.h > to_target * (1.0 + 1e-12) && eventful(&trial) {
            // An event beyond the driver's time would push its rows before that time's: the
            // step is taken again to the driver's time, and the event met in the next.
            trial = self.trial(finder, to_target, resolve, &heading);
        }
        // A failure over a long substep may be the integrator's (a slip too young to be
        // watched for reversal, turned round within the step): retry in shorter substeps down
        // to the shortest, and only there locate it.
        if trial.failed.is_some() && trial.h > 2.0 * MIN_SUBSTEP * reference {
            self.h = 0.5 * trial.h;
            return Ok(Substep::Retry);
        }
        // A stop met only at a middle stage may be that stage's overshoot, not the motion's: a
        // middle stage extrapolates the start's deceleration over half the step, and where the
        // slip only comes near zero (the ground's acceleration turning back) it passes zero
        // there. Located and taken as met, that stop cost a block of a closed form its velocity
        // (2.4e-5 of Newmark's distance in three records of 120). The step is taken again at
        // half its length, as an error estimate over the tolerance would have it, until a
        // stage no longer overshoots or the stop shows at the step's end or its last stage.
        let at_end = match trial.failed {
            None => heading.event(&trial.next_ev.motion).filter(|_| resolve),
            Some(_) => None,
        };
        if trial.stop_at_middle && at_end.is_none() && trial.h > 2.0 * MIN_SUBSTEP * reference {
            self.h = 0.5 * trial.h;
            return Ok(Substep::Retry);
        }
        if trial.crossed.is_none() && at_end.is_none() && trial.failed.is_none() {
            return self.move_on(finder, trial, resolve, o);
        }
        self.within.clear();
        self.cut_at_event(finder, k, trial, at_end, resolve, &heading, o)
    }

    /// The step of length `h` from the current state, and the state at its end. Where either
    /// fails (a stage or the end state off the model: a contact lifting off, leaving its plane's
    /// region, …) the failure is kept, to be located like an event, by bisection, so that an
    /// event before it (a pivot that would keep the contact on its plane) is handled first and
    /// a route that ends does so at the moment it must, not at the next increment's end.
    fn trial<'f>(
        &self,
        finder: &PoseFinder<'f>,
        h: f64,
        resolve: bool,
        heading: &Heading<'_>,
    ) -> Trial<'f> {
        let model = self.sim.clone();
        let sim: &Model<'_> = &model;
        let hold = Hold::of(&self.ev.motion);
        let k1 = self.y.derivative(&self.ev.motion);
        let mut at_next = finder.clone();
        let step = rk4_stages(sim, finder, &self.y, &k1, h, heading).and_then(|(n, k4, c)| {
            let e = evaluate(sim, &mut at_next, &n, hold)?;
            let c = c.filter(|_| resolve);
            let seen =
                c.and_then(|c| confirmed(sim, finder, heading, (&self.y, &k1), (&n, &e), h, c));
            let middle = c.is_some_and(|c| c.mid && c.event == Event::Stop);
            Ok((n, k4, seen, e, middle))
        });
        let (next, k4, crossed, next_ev, failed, stop_at_middle) = match step {
            Ok((n, k4, c, e, middle)) => (e.accept(&n), k4, c, e, None, middle),
            Err(stop) => (self.y, k1, None, self.ev, Some(stop), false),
        };
        Trial {
            h,
            k1,
            next,
            next_ev,
            crossed,
            stop_at_middle,
            failed,
            at_next,
            k4,
        }
    }

    /// Whether a substep of length `len` to (y2, e2) moved the energy balance by more than the
    /// tolerance (and may still be halved).
    fn unresolved(&self, resolve: bool, len: f64, y2: &RigidState, e2: &Eval) -> bool {
        if !resolve {
            return false;
        }
        let y = &self.y;
        let residual = Change {
            before: self.balance(y, &self.ev).residual_j,
            after: self.balance(y2, e2).residual_j,
        };
        let scale = self
            .ke_max
            .max(y.work_applied.abs())
            .max(y.work_friction.abs())
            .max(y2.work_applied.abs());
        let reference = self.sim.settings().reference_step();
        let tolerance = self.sim.settings().tolerance;
        unresolved_substep(residual, (scale, tolerance), len, reference, self.round_off)
    }

    /// No event in the step: take it unless its error estimate exceeds the tolerance or the
    /// energy balance moved by more than its own (then shorten the step and try again); a
    /// sticking contact is held where it stuck. The rows the step passes are its dense output
    /// (`rows_within`). The next step's length follows from this one's error.
    fn move_on<'f>(
        &mut self,
        finder: &mut PoseFinder<'f>,
        trial: Trial<'f>,
        resolve: bool,
        o: &mut Log<'_>,
    ) -> Result<Substep, Ending> {
        let Trial {
            h,
            k1,
            k4,
            next,
            next_ev,
            at_next,
            ..
        } = trial;
        let reference = self.sim.settings().reference_step();
        let shortest = MIN_SUBSTEP * reference;
        let ratio = error_ratio(&self.weights, h, &k4, &next.derivative(&next_ev.motion));
        // Plain steps too (past MAX_EVENTS in an increment: events not resolved), so that
        // friction turning within them costs no more than the tolerance allows in position.
        if ratio > 1.0 && h > shortest {
            self.h = (h * step_factor(ratio)).max(shortest);
            return Ok(Substep::Retry);
        }
        if self.unresolved(resolve, h, &next, &next_ev)
            || (self.past_capacity(&next_ev, AT_CAPACITY).is_some() && h > shortest)
        {
            // Too long to resolve the motion, or carrying a tendon past its capacity: the break
            // is located as the substep shortens (`tendons.rs`).
            self.h = 0.5 * h;
            return Ok(Substep::Retry);
        }
        let mut at_next = at_next;
        let (next, next_ev) = match self.anchor {
            Some(a) if next_ev.motion.stuck == Some(a.contact) => {
                hold_anchor(&self.sim, &mut at_next, next, next_ev, a).map_err(Ending::Failed)?
            }
            _ => (next, next_ev),
        };
        let (mut next, mut next_ev) = (next, next_ev);
        hold_on_creases(&self.sim, &mut at_next, &mut next, &mut next_ev)
            .map_err(Ending::Failed)?;
        // Interpolated rows only where every event within the step is located (so that it is
        // smooth), not past `MAX_EVENTS` or `MAX_SWITCHES`.
        let smooth = resolve && self.switching;
        let Some(interpolated) = self.rows_within(finder, h, &k1, (&next, &next_ev), smooth) else {
            // A row within the step off the model: shorter steps.
            self.h = 0.5 * h;
            return Ok(Substep::Retry);
        };
        o.report.steps.rows_interpolated += interpolated;
        *finder = at_next;
        self.go_to(o, next, next_ev);
        self.anchor = Anchor::after(&self.ev, self.anchor);
        self.t += h;
        let proposed = (h * step_factor(ratio)).min(MAX_GROWTH * self.h);
        // A step cut short (at a record's sample, the route's end) says nothing against the
        // step before it.
        self.h = if h < self.h {
            proposed.max(self.h)
        } else {
            proposed
        };
        Ok(Substep::Moved)
    }

    /// The recorded rows strictly inside the step of length `h` from the current state (its
    /// derivative `k1`) to `end`: the step's dense output (`integrator::hermite`) at each row's
    /// time, evaluated there on a copy of `start`, the finder at the step's start — or, in a
    /// step that holds no contact in a crease, and none sticking or the same one at both ends,
    /// and passes at least `rows::FEWEST` rows, evaluated at a few and the rest interpolated
    /// between them (`rows.rs`) where the step is `smooth` (every event within it located). The
    /// number of rows interpolated; `None` where an evaluated row's state is off the model.
    fn rows_within(
        &mut self,
        start: &PoseFinder<'_>,
        h: f64,
        k1: &[f64; VALUES],
        (end, end_ev): (&RigidState, &Eval),
        smooth: bool,
    ) -> Option<usize> {
        self.within.clear();
        let t0 = self.t;
        let mut times = std::mem::take(&mut self.times);
        times.clear();
        times.extend(recorded_within(self.sim.settings(), t0, t0 + h));
        let rows = if times.is_empty() {
            Some(0)
        } else {
            let step = DenseStep {
                sim: &self.sim,
                hold: Hold::of(&self.ev.motion),
                anchor: self.anchor,
                t0,
                h,
                y0: self.y.to_array(),
                k1,
                y1: end.to_array(),
                k5: end.derivative(&end_ev.motion),
            };
            let ends = ((&self.ev, &self.y), (end_ev, end));
            rows_of(&step, start, &times, ends, smooth, &mut self.within)
        };
        self.times = times;
        rows
    }

    /// Takes the state `y`, evaluated as `e`, its travel booked.
    fn go_to(&mut self, o: &mut Log<'_>, y: RigidState, e: Eval) {
        o.travel += (y.travel - self.y.travel).max(0.0);
        self.y = y;
        self.ev = e;
    }

    /// An event inside the substep (at its end or at one of its stages), or a failure:
    /// bisection on the step length for the longest step that does not reach it, then the
    /// event's own handling.
    #[allow(clippy::too_many_arguments)]
    fn cut_at_event<'f>(
        &mut self,
        finder: &mut PoseFinder<'f>,
        k: usize,
        trial: Trial<'f>,
        at_end: Option<Event>,
        resolve: bool,
        heading: &Heading<'_>,
        o: &mut Log<'_>,
    ) -> Result<Substep, Ending> {
        let span = Span {
            y: &self.y,
            k1: &trial.k1,
            h: trial.h,
            end: trial.next,
        };
        let bracket = bracket_event(&self.sim, finder, span, heading);
        if let (Some(stop), None) = (trial.failed, bracket.found) {
            // A failure that is an event of the rock's faces (a contact meeting a face, a crease
            // letting go) changes what the contacts are held to and the route goes on; any other
            // ends it, told as it is first met: at the bracket's end, not the step's.
            if let Some(next) = self.crease_event(finder, k, &bracket, &stop, o)? {
                return Ok(next);
            }
            let stop = bracket.failure.clone().unwrap_or(stop);
            return Err(self.end_at_failure(finder, k, &bracket, stop, o));
        }
        let Bracket {
            lo,
            hi,
            y_lo,
            k4_lo,
            y_hi,
            found,
            ..
        } = bracket;
        if let Some(retry) = self.approach_in_shorter_steps(finder, (lo, &y_lo, &k4_lo), resolve)? {
            return Ok(retry);
        }
        let cut = cut_at(found, at_end, trial.crossed);
        let event = match self.event_at(finder, cut, (lo, &y_lo), resolve) {
            Ok(event) => event,
            Err(retry) => return Ok(retry),
        };
        if event == Event::Switch
            && let Some(retry) = self.switch_met_again_or_far(lo, hi)
        {
            return Ok(retry);
        }
        self.go_on_from(finder, k, event, (lo, y_lo), (hi, y_hi), o)
    }

    /// The step up to an event, `lo` long to `y_lo` (its single step's last stage `k4_lo`), must
    /// itself be resolved — within the tolerance by its error estimate, and its energy balance —
    /// else the event is approached in shorter steps (the retry): the bisection tries single
    /// steps as long as the trial's, and one too long for the motion can show an event the
    /// motion does not have (a young slip passing through zero within a step of 4 ms that steps
    /// of 1 ms, each within the tolerance, never see).
    fn approach_in_shorter_steps(
        &mut self,
        finder: &PoseFinder<'_>,
        (lo, y_lo, k4_lo): (f64, &RigidState, &[f64; VALUES]),
        resolve: bool,
    ) -> Result<Option<Substep>, Ending> {
        if lo > 0.0 {
            let hold = Hold::of(&self.ev.motion);
            let mut f = finder.clone();
            let e = evaluate(&self.sim, &mut f, y_lo, hold).map_err(Ending::Failed)?;
            let shortest = MIN_SUBSTEP * self.sim.settings().reference_step();
            if resolve && lo > shortest {
                let at = e.accept(y_lo);
                let ratio = error_ratio(&self.weights, lo, k4_lo, &at.derivative(&e.motion));
                if ratio > 1.0 {
                    self.h = (lo * step_factor(ratio)).max(shortest);
                    return Ok(Some(Substep::Retry));
                }
            }
            if self.unresolved(resolve, lo, &e.accept(y_lo), &e) {
                self.h = 0.5 * lo;
                return Ok(Some(Substep::Retry));
            }
        }
        Ok(None)
    }

    /// Which event the step meets, `cut` as the event layer orders them, as the shortest step
    /// that reaches it shows (`lo` long, to `y_lo`); or the step to take again (`Err`). A pivot
    /// with the kinetic energy at REST of the largest it had is the stop itself: as a block comes
    /// to rest its contacts' slips pass through zero one after another ever faster (the Zeno
    /// behaviour of Coulomb friction), and the travel left is of order REST of the stopping
    /// distance.
    fn event_at(
        &mut self,
        finder: &PoseFinder<'_>,
        cut: Event,
        (lo, y_lo): (f64, &RigidState),
        resolve: bool,
    ) -> Result<Event, Substep> {
        let mass = self.sim.body().block().mass;
        let ke = (self.ev.motion.twist).kinetic_energy(mass, &self.ev.motion.inertia);
        Ok(match cut {
            Event::Pivot(_) if ke <= REST * self.ke_max => Event::Stop,
            // The same pivot again at the same moment: the contact's slip, not held by its cone,
            // starts so as to pass through zero again at once. Where the block is settling
            // this is its stop; a block under way passes through the moment in one plain step
            // of the shortest substep (its friction turning within it), as it would were the
            // moments apart (`through`).
            Event::Pivot(i)
                if self.pivoted.is_some_and(|(j, at)| {
                    i == j
                        && (self.t + lo - at).abs() <= 1e-9 * self.sim.settings().reference_step()
                }) =>
            {
                if ke <= SETTLED * self.slip_peak && self.holds_at(finder, y_lo) {
                    Event::Stop
                } else if resolve {
                    self.through = true;
                    return Err(Substep::Retry);
                } else {
                    // Within a plain step already, which could not be taken whole: the pivot
                    // as any other (the contact held where it stuck while its cone allows),
                    // never the stop of a block under way; events at one moment without moving
                    // on are bounded (`EVENTS_AT_ONE_MOMENT`).
                    Event::Pivot(i)
                }
            }
            Event::Pivot(_) if ke <= SETTLED * self.slip_peak && self.holds_at(finder, y_lo) => {
                Event::Stop
            }
            e => e,
        })
    }

    /// A switch of friction's regime located between `lo` and `hi` into the step that is not
    /// to be taken as it is: the same switch again at the moment of the last (the regime
    /// flipping to and fro there: the rest of the increment crosses switches as they are), or
    /// one too far into the step (then approached); the retry, if so.
    fn switch_met_again_or_far(&mut self, lo: f64, hi: f64) -> Option<Substep> {
        let reference = self.sim.settings().reference_step();
        if (self.t + hi - self.switched_at).abs() <= 1e-9 * reference {
            self.switching = false;
            return Some(Substep::Retry);
        }
        // The rates past the switch set where a young slip set free goes, and a single
        // step's error in them is not watched (`error_weights`): a switch is located within
        // a step of at most a tenth of the reference step (within 1 ms, route ends moved
        // with the rows' interval by up to 3e-5 s at τ = 1e-13; within 0.1 ms, by 4e-7 s).
        let within = 0.1 * reference;
        if lo > within {
            self.h = lo - 0.5 * within;
            return Some(Substep::Retry);
        }
        None
    }

    /// The route goes on from `event`, met between `lo` (state `y_lo`) and `hi` (`y_hi`) into
    /// the step: a release from just past the moment (the contact then slips, in the direction
    /// `rigid_body::accelerations` gives); a pivot from just before it, the contact's remaining
    /// slip (of the bisection's size) projected out, stuck while its cone allows; a switch from
    /// just past it, in the new regime, nothing else changed; a stop comes to rest there.
    fn go_on_from(
        &mut self,
        finder: &mut PoseFinder<'_>,
        k: usize,
        event: Event,
        (lo, y_lo): (f64, RigidState),
        (hi, y_hi): (f64, RigidState),
        o: &mut Log<'_>,
    ) -> Result<Substep, Ending> {
        let hold = Hold::of(&self.ev.motion);
        let switched = event == Event::Switch;
        if !switched {
            self.pivoted = match event {
                Event::Pivot(i) => Some((i, self.t + lo)),
                _ => None,
            };
        }
        let (y_at, len, hold) = match event {
            Event::Release(i) => (y_hi, hi, hold.releasing(i)),
            Event::Pivot(i) => (y_lo, lo, hold.sticking(Some(i))),
            Event::Switch => (y_hi, hi, hold),
            Event::Stop => return self.stop(finder, k, y_lo, self.t + hi, o),
        };
        let at = evaluate(&self.sim, finder, &y_at, hold).map_err(Ending::Failed)?;
        self.go_to(o, at.accept(&y_at), at);
        self.anchor = Anchor::after(&self.ev, self.anchor.filter(|_| switched));
        self.t += len;
        if switched {
            self.switched_at = self.t;
            return Ok(Substep::Switch);
        }
        Ok(Substep::Event)
    }

    /// A failure just past the last state that stands (the bracket's `y_lo`, `lo` into the
    /// substep), that is an event of the rock's faces (`derivations/10-faces.md` §4–6):
    ///
    /// * a contact reached a face: it rides the crease from `y_lo` on, its velocity into the
    ///   face taken by perfectly inelastic, frictional impulses (the energy booked as friction
    ///   work; [`after_impact`]);
    /// * a contact ran over a surface's ridge: it goes on along the face beyond it, the
    ///   velocity off that face taken by the same impulses if it is a hop, else the route ends;
    /// * a crease's second face let go of its contact: the contact goes on along its own face;
    /// * a crease contact's own face let go: the contact goes on along the crease's other face
    ///   (the site changes: that face becomes the contact's own).
    ///
    /// Other contacts keep their creases. The contact forces just after the event may call for
    /// the next at once (a contact that meets a steeper face is lifted off its own by the
    /// impact): up to three such events are taken at the same moment. `None` for any other
    /// failure (it ends the route).
    fn crease_event(
        &mut self,
        finder: &mut PoseFinder<'_>,
        k: usize,
        bracket: &Bracket,
        stop: &Stop,
        o: &mut Log<'_>,
    ) -> Result<Option<Substep>, Ending> {
        let model = self.sim.clone();
        let sim: &Model<'_> = &model;
        let held = Hold::of(&self.ev.motion);
        let before = BeforeImpact {
            normal_n: self.ev.motion.normal,
            faces: finder.site().normals(),
        };
        // The route may end at the impact: on the site before it.
        let unchanged = finder.clone();
        let Some((hold, met)) = face_event(sim, finder, &bracket.y_lo, stop, held) else {
            return Ok(None);
        };
        let (y_lo, hold) = match after_impact(sim, finder, &bracket.y_lo, &before, met, hold)? {
            Ok(after) => after,
            Err(lift) => {
                *finder = unchanged;
                return Err(self.end_at_failure(finder, k, bracket, lift, o));
            }
        };
        let (y, at) = after_events(sim, finder, &y_lo, hold)?;
        self.go_to(o, y, at);
        self.anchor = Anchor::after(&self.ev, self.anchor);
        self.t += bracket.lo;
        Ok(Some(Substep::Event))
    }

    /// No event before the failure: the route ends where it fails, after the last state that
    /// stands (the bracket's `y_lo`, `lo` into the substep).
    fn end_at_failure(
        &mut self,
        finder: &mut PoseFinder<'_>,
        k: usize,
        bracket: &Bracket,
        stop: Stop,
        o: &mut Log<'_>,
    ) -> Ending {
        let (lo, y_lo) = (bracket.lo, bracket.y_lo);
        if lo > 0.0 {
            match evaluate(&self.sim, finder, &y_lo, Hold::of(&self.ev.motion)) {
                Ok(e) => self.go_to(o, e.accept(&y_lo), e),
                Err(e) => return Ending::Failed(e),
            }
        }
        let t_end = self.t + lo;
        o.push(self.ev.row(t_end, &self.y));
        o.increments = k;
        o.report.energy = Some(self.balance(&self.y, &self.ev));
        Ending::At(stop.reason, t_end, stop.detail)
    }

    /// The motion stops at `t_event`: the block at rest at the state just before it (`y_lo`,
    /// its rates zeroed). Held there by static friction, the route ends "stopped"; not held,
    /// it slips again from rest.
    fn stop(
        &mut self,
        finder: &mut PoseFinder<'_>,
        k: usize,
        y_lo: RigidState,
        t_event: f64,
        o: &mut Log<'_>,
    ) -> Result<Substep, Ending> {
        let stopped = y_lo.stopped();
        // A tendon that reached its capacity as the block stopped breaks before the block is
        // found held (the force peaks as the motion stops).
        if !self.sim.body().tendons().is_empty()
            && let Ok(pose) = finder.clone().pose_at(stopped.displacement())
        {
            self.break_tendons_at(&pose, t_event, o);
        }
        match self.come_to_rest(finder, &stopped, k, t_event, o) {
            Rest::Failed(e) => Err(Ending::Failed(e)),
            // Held while a record still shakes the foundation: it rests, checked again at each
            // increment.
            Rest::Rests(e, at) => {
                self.ev = *e;
                self.y = stopped.at(at);
                self.t = at;
                self.anchor = None;
                self.resting = true;
                self.region = None;
                Ok(Substep::Event)
            }
            Rest::Ended(reason, at, detail) => Err(Ending::At(reason, at, detail)),
            Rest::Slips(e) => {
                self.ev = *e;
                self.y = stopped;
                self.anchor = Anchor::after(&self.ev, None);
                self.t = t_event;
                Ok(Substep::Event)
            }
        }
    }
}
