//! Substep control of the rigid body: an increment in substeps, each tried, taken, halved
//! where the energy balance says RK4 does not resolve the motion, or cut at an event and the
//! event handled (`derivations/08-rigid-body.md` §3).

use super::events::{Bracket, Event, Heading, Rest, barely_exceeded, bracket_event, come_to_rest};
use super::{
    Eval, Hold, RigidBody, Y, accept, anchor_of, body_geometry, derivative, displacement, evaluate,
    hold, rest_eval, rest_row, rk4, row, static_check, stop_of,
};
use crate::mechanics::ContactGeometry;
use crate::mechanics::rigid_body::{self, Crease, Creases, Impact, ImpactLaw, RigidError};
use crate::route::dynamics::Flow;
use crate::route::outcome::Outcome;
use crate::route::pose_finder::PoseFinder;
use crate::route::rhs::Stop;
use crate::route::rhs::pose_at;
use crate::route::state::faces_of;
use crate::route::termination::Reason;
use crate::scene::{Scene, Simulation};
use nalgebra::{DMatrix, DVector, Vector3};

/// The fraction of the largest kinetic energy of the route below which the block counts as at
/// rest when a contact's slip passes through zero (see `RigidBody::cut_at_event`).
const REST: f64 = 1e-9;

/// A substep is halved when the energy balance W_h + W_f − ΔK − ΔU moves over it by more than
/// this fraction of the route's energy scale (the largest of its kinetic energy and of the
/// works so far), prorated to the substep. Where the motion is resolved RK4 moves it by about
/// 1e-18 a step; it is exceeded where friction makes the motion stiff — near a stop the friction
/// moments damp the rotation at a rate ∝ μ N r² / (I |v|) — or a slip swings round near zero.
const ENERGY_TOLERANCE: f64 = 1e-9;

/// The most events (stops that restart, pivots) resolved within one increment.
const MAX_EVENTS: usize = 16;

/// The shortest substep, as a fraction of dt (then the step is taken as it is).
const MIN_SUBSTEP: f64 = 1e-3;

/// Substep control: whether a substep of length `len` (of an increment `dt`) moved the energy
/// balance's residual from `before` to `after` by more than the tolerance — a fraction
/// `ENERGY_TOLERANCE` of the route's energy `scale`, prorated to the substep, and never below
/// the balance's own round-off — and may still be halved (it is longer than `MIN_SUBSTEP`·dt).
fn unresolved_substep(
    (before, after): (f64, f64),
    scale: f64,
    (len, dt): (f64, f64),
    round_off: f64,
) -> bool {
    (after - before).abs() > (ENERGY_TOLERANCE * scale * (len / dt)).max(round_off)
        && len > MIN_SUBSTEP * dt
}

/// What one substep came to.
enum Substep {
    /// Too long to resolve the motion or to locate a failure in: `h` was halved, try again.
    Retry,
    /// The state moved on without an event.
    Moved,
    /// An event was handled (a pivot, a release, a stop from which the block slips again).
    Event,
}

/// How a route ends within a substep.
enum Ending {
    /// A state off the model: the route ends at the state before the substep.
    Failed(Stop),
    /// An end decided where it happened (a stop held by friction, a failure located by
    /// bisection), its rows and energy balance already in the outcome.
    At(Reason, f64, String),
}

/// One attempted step: its length, the derivative at its start, and what it reached.
struct Trial<'f> {
    h: f64,
    k1: Y,
    /// The end state (the start's where the step failed) and its evaluation.
    next: Y,
    next_ev: Eval,
    /// An event met at one of the step's stages.
    crossed: Option<Event>,
    /// Where the step or its end state is off the model.
    failed: Option<Stop>,
    /// The pose finder at the end state.
    at_next: PoseFinder<'f>,
}

impl RigidBody<'_> {
    /// Increment `k` to `t_target` in substeps: each step checked for events — a stop, a
    /// pivot, a release, a failure — found by bisection on the step length, and halved where
    /// the energy balance says RK4 does not resolve the motion.
    pub(super) fn substeps<'s>(
        &mut self,
        finder: &mut PoseFinder<'_>,
        k: usize,
        t_target: f64,
        mut o: Outcome<'s>,
    ) -> Flow<'s> {
        let mut events = 0usize;
        while self.t < t_target * (1.0 - 1e-15) {
            if self.resting {
                o = match self.rest(finder, t_target, o) {
                    Flow::Go(o) if !self.resting => o,
                    flow => return flow,
                };
                continue;
            }
            // Past MAX_EVENTS in one increment (a contact's slip chattering about zero), the
            // rest of the increment is taken in plain substeps: its error shows in the energy
            // balance.
            let resolve = events < MAX_EVENTS;
            // A ground-motion record's samples are where its loads may turn: substeps end on
            // them (RK4 keeps its order between them).
            let until = match self.scene.record().and_then(|r| r.next_sample(self.t)) {
                Some(s) if s < t_target => s,
                _ => t_target,
            };
            match self.substep(finder, k, until - self.t, resolve, &mut o) {
                Ok(Substep::Event) => events += 1,
                Ok(Substep::Retry | Substep::Moved) => {}
                Err(Ending::Failed(stop)) => return Flow::Ended(self.fail(o, stop)),
                Err(Ending::At(reason, t, detail)) => {
                    return Flow::Ended(o.end(reason, t, detail));
                }
            }
        }
        self.t = t_target;
        Flow::Go(o)
    }

    /// An increment at rest, to `t_target`, while a ground-motion record shakes the
    /// foundation: the friction cones are checked with the loads then. Held, the block stays
    /// (and the route ends "stopped" once the record is over); not held, it slips from rest at
    /// the moment the cones stop holding it (found by bisection; `self.resting` is then false
    /// and the increment goes on in substeps).
    fn rest<'s>(
        &mut self,
        finder: &mut PoseFinder<'_>,
        t_target: f64,
        mut o: Outcome<'s>,
    ) -> Flow<'s> {
        let (scene, sections) = (self.scene, self.sections);
        let geom = ContactGeometry::with_normals(&finder.site().normals(), &self.ev.pose);
        // The joint's cohesion holds until the block first slides.
        let (faces, bonded) = (self.ev.faces, o.travel == 0.0);
        let check_at = |t: f64| static_check(sections, &geom, (t, faces, bonded));
        let holds = |t: f64| check_at(t).map(|c| c.holds());
        // The record's samples within the increment, where its loads turn: the cones are
        // checked at each (between them the loads are linear in time), the last at t_target.
        let mut at = self.t;
        let mut slips = None;
        let mut last = None;
        while at < t_target {
            let next = match scene.record().and_then(|r| r.next_sample(at)) {
                Some(s) if s < t_target => s,
                _ => t_target,
            };
            match check_at(next) {
                Ok(c) if c.holds() => {
                    at = next;
                    last = Some(c);
                }
                Ok(_) => {
                    slips = Some((at, next));
                    break;
                }
                Err(s) => return Flow::Ended(self.fail(o, s)),
            }
        }
        if let Some((mut lo, mut hi)) = slips {
            // Held at lo, not at hi: the onset of slip to a millionth of the interval.
            for _ in 0..20 {
                let mid = 0.5 * (lo + hi);
                match holds(mid) {
                    Ok(true) => lo = mid,
                    Ok(false) => hi = mid,
                    Err(s) => return Flow::Ended(self.fail(o, s)),
                }
            }
            // Just past the onset the loads exceed the cones by the cone program's tolerance,
            // too little for a consistent direction of slip: the start is sought a little later,
            // at lengths doubling from the bisection's, within the increment.
            let mut late = hi - lo;
            let mut tried = hi;
            loop {
                let mut y = self.y;
                y[8] = tried;
                match evaluate(scene, sections, finder, &y, Hold::default()) {
                    Ok(e) => {
                        self.y = y;
                        self.t = tried;
                        self.ev = e;
                        self.resting = false;
                        self.anchor = anchor_of(&self.ev, None);
                        self.h = sections.solver().dt;
                        return Flow::Go(o);
                    }
                    Err(s) if tried >= t_target => {
                        // Over the cones by too little for a consistent start of slip: held
                        // for this increment, checked again at the next.
                        let barely = check_at(t_target).is_ok_and(|c| barely_exceeded(&c));
                        if s.reason == Reason::ContactForcesUndetermined && barely {
                            self.t = t_target;
                            self.y[8] = t_target;
                            return Flow::Go(o);
                        }
                        return Flow::Ended(self.fail(o, s));
                    }
                    Err(_) => {
                        tried = (hi + late).min(t_target);
                        late *= 2.0;
                    }
                }
            }
        }
        self.t = t_target;
        self.y[8] = t_target;
        // Held through the increment: the check at its end (made above unless the increment
        // was empty).
        let check = match last.map_or_else(|| check_at(t_target), Ok) {
            Ok(c) => c,
            Err(s) => return Flow::Ended(self.fail(o, s)),
        };
        let over = scene.record().is_none_or(|r| t_target >= r.end());
        if over {
            let moved = o.travel > 0.0;
            o.push(rest_row(self.t, &self.y, &self.ev.pose, self.ev.faces));
            o.energy = Some(self.balance(&self.y, &self.ev));
            let (reason, what) = if moved {
                (Reason::Stopped, "the block came to rest")
            } else {
                (Reason::DoesNotSlide, "the block never slid")
            };
            return Flow::Ended(o.end(
                reason,
                self.t,
                format!(
                    "the ground-motion record ended at {:.6} s; {what} and static friction \
                     holds it (factor of safety {})",
                    scene.record().map_or(0.0, |r| r.end()),
                    check.factor_of_safety()
                ),
            ));
        }
        match rest_eval(sections, finder, self.ev.pose, &check) {
            Ok(e) => {
                self.ev = e;
                Flow::Go(o)
            }
            Err(s) => Flow::Ended(self.fail(o, s)),
        }
    }

    /// The route ended by a failure at the current state.
    fn fail<'s>(&self, mut o: Outcome<'s>, s: Stop) -> Outcome<'s> {
        o.energy = Some(self.balance(&self.y, &self.ev));
        o.finish(row(self.t, &self.y, &self.ev), s.reason, self.t, s.detail)
    }

    /// One substep of at most `left` (s): tried, then moved on, retried shorter, or cut at an
    /// event and the event handled.
    fn substep<'f>(
        &mut self,
        finder: &mut PoseFinder<'f>,
        k: usize,
        left: f64,
        resolve: bool,
        o: &mut Outcome<'_>,
    ) -> Result<Substep, Ending> {
        let mass = self.sections.block().mass;
        let motion = self.ev.motion;
        self.ke_max = self
            .ke_max
            .max(motion.twist.kinetic_energy(mass, &motion.inertia));
        let heading = Heading {
            before: &motion,
            mass,
        };
        let trial = self.trial(finder, self.h.min(left), resolve, &heading);
        let dt = self.sections.solver().dt;
        // A failure over a long substep may be the integrator's (a slip too young to be
        // watched for reversal, turned round within the step): retry in shorter substeps down
        // to the shortest, and only there locate it.
        if trial.failed.is_some() && trial.h > 2.0 * MIN_SUBSTEP * dt {
            self.h = 0.5 * trial.h;
            return Ok(Substep::Retry);
        }
        let at_end = match trial.failed {
            None => heading.event(&trial.next_ev.motion).filter(|_| resolve),
            Some(_) => None,
        };
        if trial.crossed.is_none() && at_end.is_none() && trial.failed.is_none() {
            return self.move_on(finder, trial, resolve, o);
        }
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
        let (scene, sections) = (self.scene, self.sections);
        let hold = Hold::of(&self.ev.motion);
        let k1 = derivative(&self.y, &self.ev.motion);
        let mut at_next = finder.clone();
        let step = rk4(scene, sections, finder, &self.y, &k1, h, heading).and_then(|(n, c)| {
            let e = evaluate(scene, sections, &mut at_next, &n, hold)?;
            Ok((n, c.filter(|_| resolve), e))
        });
        let (next, crossed, next_ev, failed) = match step {
            Ok((n, c, e)) => (accept(&n, &e), c, e, None),
            Err(stop) => (self.y, None, self.ev, Some(stop)),
        };
        Trial {
            h,
            k1,
            next,
            next_ev,
            crossed,
            failed,
            at_next,
        }
    }

    /// Whether a substep of length `len` to (y2, e2) moved the energy balance by more than the
    /// tolerance (and may still be halved).
    fn unresolved(&self, resolve: bool, len: f64, y2: &Y, e2: &Eval) -> bool {
        let y = &self.y;
        resolve
            && unresolved_substep(
                (
                    self.balance(y, &self.ev).residual_j,
                    self.balance(y2, e2).residual_j,
                ),
                self.ke_max.max(y[6].abs()).max(y[7].abs()).max(y2[6].abs()),
                (len, self.sections.solver().dt),
                self.round_off,
            )
    }

    /// No event in the step: take it unless the energy balance moved by more than the
    /// tolerance (then halve the substep and try again); a sticking contact is held where it
    /// stuck.
    fn move_on<'f>(
        &mut self,
        finder: &mut PoseFinder<'f>,
        trial: Trial<'f>,
        resolve: bool,
        o: &mut Outcome<'_>,
    ) -> Result<Substep, Ending> {
        let Trial {
            h,
            next,
            next_ev,
            at_next,
            ..
        } = trial;
        if self.unresolved(resolve, h, &next, &next_ev) {
            self.h = 0.5 * h;
            return Ok(Substep::Retry);
        }
        *finder = at_next;
        let (next, next_ev) = match self.anchor {
            Some((i, at)) if next_ev.motion.stuck == Some(i) => {
                hold(self.scene, self.sections, finder, &next, next_ev, i, at)
                    .map_err(Ending::Failed)?
            }
            _ => (next, next_ev),
        };
        let (next, next_ev) = hold_on_creases(self.scene, self.sections, finder, &next, next_ev)
            .map_err(Ending::Failed)?;
        self.go_to(o, next, next_ev);
        self.anchor = anchor_of(&self.ev, self.anchor);
        self.t += h;
        if h >= self.h {
            self.h = (2.0 * self.h).min(self.sections.solver().dt);
        }
        Ok(Substep::Moved)
    }

    /// Takes the state `y`, evaluated as `e`, its travel booked.
    fn go_to(&mut self, o: &mut Outcome<'_>, y: Y, e: Eval) {
        o.travel += (e.pose.cm - self.ev.pose.cm).norm();
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
        o: &mut Outcome<'_>,
    ) -> Result<Substep, Ending> {
        let (scene, sections) = (self.scene, self.sections);
        let hold = Hold::of(&self.ev.motion);
        let Bracket {
            lo,
            hi,
            y_lo,
            y_hi,
            found,
        } = bracket_event(
            scene,
            sections,
            finder,
            (&self.y, &trial.k1),
            (trial.h, trial.next),
            heading,
        );
        if let (Some(stop), None) = (trial.failed, found) {
            // A failure that is the ground's event (a contact meeting a face, a crease letting
            // go) changes what the contacts are held to and the route goes on; any other ends
            // it.
            if let Some(next) = self.crease_event(finder, k, (lo, y_lo), &stop, o)? {
                return Ok(next);
            }
            return Err(self.end_at_failure(finder, k, (lo, y_lo), stop, o));
        }
        // The substep up to the event must itself be resolved: else approach it in shorter
        // substeps.
        if lo > 0.0 {
            let mut f = finder.clone();
            let e = evaluate(scene, sections, &mut f, &y_lo, hold).map_err(Ending::Failed)?;
            if self.unresolved(resolve, lo, &accept(&y_lo, &e), &e) {
                self.h = 0.5 * lo;
                return Ok(Substep::Retry);
            }
        }
        // Which event: what the shortest step that reaches it shows. A pivot with the kinetic
        // energy at REST of the largest it had is the stop itself: as a block comes to rest its
        // contacts' slips pass through zero one after another ever faster (the Zeno behaviour
        // of Coulomb friction), and the travel left is of order REST of the stopping distance.
        let mass = sections.block().mass;
        let ke = (self.ev.motion.twist).kinetic_energy(mass, &self.ev.motion.inertia);
        let event = match found.or(at_end).or(trial.crossed).unwrap_or(Event::Stop) {
            Event::Pivot(_) if ke <= REST * self.ke_max => Event::Stop,
            e => e,
        };
        // A release goes on from just past the moment (the contact then slips, in the
        // direction `rigid_body::accelerations` gives); a pivot from just before it, the
        // contact's remaining slip (of the bisection's size) projected out, stuck while its
        // cone allows.
        let (y_at, len, stick) = match event {
            Event::Release(_) => (y_hi, hi, None),
            Event::Pivot(i) => (y_lo, lo, Some(i)),
            Event::Stop => return self.stop(finder, k, y_lo, self.t + hi, o),
        };
        let at = evaluate(scene, sections, finder, &y_at, hold.sticking(stick))
            .map_err(Ending::Failed)?;
        self.go_to(o, accept(&y_at, &at), at);
        self.anchor = anchor_of(&self.ev, None);
        self.t += len;
        Ok(Substep::Event)
    }

    /// A failure at `y_hi`, just past the last state that stands (`y_lo`, `lo` into the
    /// substep), that is an event of the ground (`derivations/10-faces.md` §4–6):
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
        (lo, y_lo): (f64, Y),
        stop: &Stop,
        o: &mut Outcome<'_>,
    ) -> Result<Option<Substep>, Ending> {
        let (scene, sections) = (self.scene, self.sections);
        let held = Hold::of(&self.ev.motion);
        let faces = finder.site().normals();
        // The route may end at the impact: on the site before it.
        let unchanged = finder.clone();
        let Some((hold, met)) = ground_event(scene, finder, &y_lo, stop, held) else {
            return Ok(None);
        };
        let before = (&y_lo, self.ev.motion.normal, faces);
        let (y_lo, hold) = match after_impact(scene, sections, finder, before, met, hold)? {
            Ok(after) => after,
            Err(lift) => {
                *finder = unchanged;
                return Err(self.end_at_failure(finder, k, (lo, y_lo), lift, o));
            }
        };
        let mut hold = hold;
        let mut at = None;
        for _ in 0..3 {
            match evaluate(scene, sections, finder, &y_lo, hold) {
                Ok(e) => {
                    at = Some(e);
                    break;
                }
                Err(next) => {
                    hold = ground_event(scene, finder, &y_lo, &next, hold)
                        .ok_or(Ending::Failed(next))?
                        .0;
                }
            }
        }
        let at = match at {
            Some(e) => e,
            None => evaluate(scene, sections, finder, &y_lo, hold).map_err(Ending::Failed)?,
        };
        let (y, at) = hold_on_creases(scene, sections, finder, &accept(&y_lo, &at), at)
            .map_err(Ending::Failed)?;
        self.go_to(o, y, at);
        self.anchor = anchor_of(&self.ev, self.anchor);
        self.t += lo;
        Ok(Some(Substep::Event))
    }

    /// No event before the failure: the route ends where it fails, after the last state that
    /// stands (`y_lo`, `lo` into the substep).
    fn end_at_failure(
        &mut self,
        finder: &mut PoseFinder<'_>,
        k: usize,
        (lo, y_lo): (f64, Y),
        stop: Stop,
        o: &mut Outcome<'_>,
    ) -> Ending {
        if lo > 0.0 {
            match evaluate(
                self.scene,
                self.sections,
                finder,
                &y_lo,
                Hold::of(&self.ev.motion),
            ) {
                Ok(e) => self.go_to(o, accept(&y_lo, &e), e),
                Err(e) => return Ending::Failed(e),
            }
        }
        let t_end = self.t + lo;
        o.push(row(t_end, &self.y, &self.ev));
        o.increments = k;
        o.energy = Some(self.balance(&self.y, &self.ev));
        Ending::At(stop.reason, t_end, stop.detail)
    }

    /// The motion stops at `t_event`: the block at rest at the state just before it (`y_lo`,
    /// its rates zeroed). Held there by static friction, the route ends "stopped"; not held,
    /// it slips again from rest.
    fn stop(
        &mut self,
        finder: &mut PoseFinder<'_>,
        k: usize,
        y_lo: Y,
        t_event: f64,
        o: &mut Outcome<'_>,
    ) -> Result<Substep, Ending> {
        let mut stopped = y_lo;
        stopped[3] = 0.0;
        stopped[4] = 0.0;
        stopped[5] = 0.0;
        match come_to_rest(
            (self.scene, self.sections, finder),
            (&stopped, &self.ev),
            (k, self.t, t_event),
            self.origin,
            o,
        ) {
            Rest::Failed(e) => Err(Ending::Failed(e)),
            // Held while a record still shakes the foundation: it rests, checked again at each
            // increment.
            Rest::Rests(e, at) => {
                self.ev = *e;
                self.y = stopped;
                self.y[8] = at;
                self.t = at;
                self.anchor = None;
                self.resting = true;
                Ok(Substep::Event)
            }
            Rest::Ended(reason, at, detail) => Err(Ending::At(reason, at, detail)),
            Rest::Slips(e) => {
                self.ev = *e;
                self.y = stopped;
                self.anchor = anchor_of(&self.ev, None);
                self.t = t_event;
                Ok(Substep::Event)
            }
        }
    }
}

/// A contact's change of face at an event of the ground that makes an impact: it met face
/// `face` (and rides the crease), or, at a surface's ridge, went on along it.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Met {
    contact: usize,
    face: usize,
    ridge: bool,
}

/// The impact of a contact meeting a face, or running over a ridge onto one, at state `y`
/// (`met`; `hold` what the contacts are held to after it; `derivations/10-faces.md` §6): the
/// state just after it — its rates those the frictional, perfectly inelastic impulses leave
/// ([`rigid_body::impact_onto`]; the friction coefficients at the contacts' normal forces
/// `normals` before it, the block moving on the faces with unit normals `faces` until then), the
/// kinetic energy they take booked as friction work — and what the contacts are held to then;
/// the finder moves to the new site where the impact put a contact on the new face alone. Or,
/// where the impact would need a face to pull a contact on it faster than a hop, the stop that
/// ends the route there ("contact lifted off", or "ran over a ridge" for the contact that
/// crossed it).
fn after_impact(
    scene: &Scene,
    dynamics: &Simulation,
    finder: &mut PoseFinder<'_>,
    (y, normals, faces): (&Y, [f64; 3], [Vector3<f64>; 3]),
    met: Option<Met>,
    hold: Hold,
) -> Result<Result<(Y, Hold), Stop>, Ending> {
    let Some(met) = met else {
        return Ok(Ok((*y, hold)));
    };
    let mut f = finder.for_stages();
    let pose = pose_at(scene, &mut f, displacement(y)).map_err(Ending::Failed)?;
    let geom = body_geometry(dynamics, &finder.site().normals(), &pose);
    let before = body_geometry(dynamics, &faces, &pose);
    let creases = hold.creases.without(hold.stuck);
    // Each contact's friction coefficient at its normal force before the impact.
    let friction = dynamics.strength(faces_of(finder.site()), false);
    let mu = if friction.is_frictionless() {
        [0.0; 3]
    } else {
        friction.coefficients(&normals)
    };
    // A release slower than a hop of HOP·L under gravity is not a lift; one from a crease
    // slower than GRAZE·√(g L) is a graze.
    let g = dynamics.loads().gravity;
    let law = ImpactLaw {
        mu,
        release_speed: (2.0 * g * HOP * scene.l()).sqrt(),
        crease_release_speed: GRAZE * (g * scene.l()).sqrt(),
    };
    let Impact {
        rates,
        removed,
        creases,
        moved,
    } = match rigid_body::impact_onto(
        &before,
        &geom,
        dynamics.block(),
        [y[3], y[4], y[5]],
        &creases,
        &law,
    ) {
        Ok(after) => after,
        Err(RigidError::ImpactLifts {
            contact,
            impulse_n_s,
            speed_m_s,
        }) => {
            let off = faces_of(finder.site())[contact];
            let held = format!("(held, its impulse would be {impulse_n_s:.6e} N·s)");
            let (reason, detail) = match met {
                Met { ridge: true, .. } if contact == met.contact => (
                    Reason::ContactOverRidge,
                    format!(
                        "contact {contact} runs over a ridge onto face {off} and leaves it at \
                         {speed_m_s:.3e} m/s {held}"
                    ),
                ),
                Met { ridge: true, .. } => (
                    Reason::ContactLiftedOff,
                    format!(
                        "contact {} running over a ridge onto face {} lifts contact {contact} \
                         off face {off} at {speed_m_s:.3e} m/s {held}",
                        met.contact, met.face
                    ),
                ),
                Met { ridge: false, .. } => (
                    Reason::ContactLiftedOff,
                    format!(
                        "the impact of contact {} on face {} lifts contact {contact} off face \
                         {off} at {speed_m_s:.3e} m/s {held}",
                        met.contact, met.face
                    ),
                ),
            };
            return Ok(Err(Stop {
                reason,
                detail,
                contact: Some(contact),
            }));
        }
        Err(e) => return Err(Ending::Failed(stop_of(e))),
    };
    for c in moved.iter().flatten() {
        let Some(site) = finder.site().with_face(c.contact, c.face) else {
            return Err(Ending::Failed(Stop {
                reason: Reason::ContactReachedAnotherFace,
                detail: format!("contact {} cannot go on along face {}", c.contact, c.face),
                contact: Some(c.contact),
            }));
        };
        *finder = finder.on_site(site);
    }
    let mut z = *y;
    z[3..6].copy_from_slice(&rates);
    z[7] += removed;
    // A contact stuck before the impact keeps sticking while its cone allows.
    let creases = match hold.stuck.and_then(|i| hold.creases.at(i)) {
        Some(c) => creases.with(*c),
        None => creases,
    };
    Ok(Ok((z, Hold { creases, ..hold })))
}

/// The highest hop, as a fraction of L, that an impact may give a contact without ending the
/// route: a contact thrown off its face no faster than √(2 g HOP L) is kept on it — its flight
/// would reach at most a millimetre on a 10 m block (less: the block's turn brings a corner
/// down faster than g), within the roughness of a rock joint, and last some ten milliseconds;
/// Drake's refined contact shows such hops of micrometres. A faster one lifts off: the
/// three-point model ends there.
const HOP: f64 = 1e-4;

/// The slowest release, as a fraction of √(g L), with which a crease's face lets its contact
/// go at an impact (1 cm/s on a 10 m block): a contact meeting a face at a crease it is about to
/// ride leaves the other face at some 10⁻⁴ m/s (a graze; letting go would start a chatter of
/// impacts along the crease), one that climbs onto the face it met at a tenth of a metre per
/// second or more (holding the crease would stop its whole motion across it).
const GRAZE: f64 = 1e-3;

/// What a failure `stop` at `y` changes in what the contacts are held to (`held`), if it is an
/// event of the ground (see `RigidBody::crease_event`), and the contact whose change makes an
/// impact; the finder moves to the new site where a contact changes its face. `None` for any
/// other failure.
fn ground_event(
    scene: &Scene,
    finder: &mut PoseFinder<'_>,
    y: &Y,
    stop: &Stop,
    held: Hold,
) -> Option<(Hold, Option<Met>)> {
    let riding = stop.contact.and_then(|i| held.creases.at(i)).copied();
    let creases = match (stop.reason, riding) {
        (Reason::ContactReachedAnotherFace, _) => {
            let c = met_face(scene, finder, y, &held.creases)?;
            let met = Met {
                contact: c.contact,
                face: c.face,
                ridge: false,
            };
            return Some((
                Hold {
                    creases: held.creases.with(c),
                    ..held
                },
                Some(met),
            ));
        }
        // Over a surface's ridge: the contact goes on along the face beyond it.
        (Reason::ContactOverRidge, _) => {
            let (contact, face) = ridge_face(scene, finder, y, &held.creases)?;
            let site = finder.site().with_face(contact, face)?;
            *finder = finder.on_site(site);
            let met = Met {
                contact,
                face,
                ridge: true,
            };
            return Some((held, Some(met)));
        }
        (Reason::CreaseLetsGo, Some(c)) => held.creases.without(Some(c.contact)),
        // The contact leaves its own face for the crease's other one: the site changes, and
        // the branch goes on from the same point on it.
        (Reason::CreaseTakesOver, Some(c)) => {
            let site = finder.site().with_face(c.contact, c.face)?;
            *finder = finder.on_site(site);
            held.creases.without(Some(c.contact))
        }
        _ => return None,
    };
    Some((Hold { creases, ..held }, None))
}

/// The crease a contact meets at `y` (about where it reached another face of a ground of
/// planes — the failure may have been seen at a stage of the step just beyond): of the contacts
/// not riding a crease already (`creases`), the one nearest to going under another face, and
/// that face (a plane, or a surface's triangle within `MEETS` of the contact in plan), found at
/// the pose there without the regions' check. `None` if no face is within `MEETS` of a contact.
fn met_face(scene: &Scene, finder: &PoseFinder<'_>, y: &Y, creases: &Creases) -> Option<Crease> {
    let site = finder.site();
    let (ground, _) = site.ground()?;
    let mut f = finder.for_stages();
    let pose = pose_at(scene, &mut f, displacement(y)).ok()?;
    let planes = site.planes();
    let all = ground.faces();
    let near = MEETS * scene.l();
    (0..3)
        .filter(|&k| creases.at(k).is_none())
        .flat_map(|k| {
            let v = pose.vertices[k];
            let own = planes[k];
            ground
                .faces_near(v.x, v.z, near)
                .into_iter()
                .filter(move |&j| !all[j].is_parallel(&planes[k], PARALLEL))
                .map(move |j| (k, j, all[j].height(v.x, v.z) - own.height(v.x, v.z)))
        })
        .filter(|&(_, _, above)| above > -near)
        .max_by(|a, b| a.2.total_cmp(&b.2))
        .map(|(k, j, _)| Crease {
            contact: k,
            normal: all[j].normal(),
            offset: all[j].offset(),
            face: j,
        })
}

/// The contact that runs over a surface's ridge at `y` (the last state before it does) and
/// the triangle beyond the ridge: of the contacts not riding a crease (`creases`), the one
/// nearest in plan to a triangle not parallel to its own face (within `MEETS`·L), and that
/// triangle. `None` where there is none.
fn ridge_face(
    scene: &Scene,
    finder: &PoseFinder<'_>,
    y: &Y,
    creases: &Creases,
) -> Option<(usize, usize)> {
    let site = finder.site();
    let (ground, _) = site.ground().filter(|(g, _)| g.is_surface())?;
    let mut f = finder.for_stages();
    let pose = pose_at(scene, &mut f, displacement(y)).ok()?;
    let planes = site.planes();
    let all = ground.faces();
    (0..3)
        .filter(|&k| creases.at(k).is_none())
        .filter_map(|k| {
            let v = pose.vertices[k];
            ground
                .faces_by_distance(v.x, v.z, MEETS * scene.l())
                .into_iter()
                .find(|&(j, _)| !all[j].is_parallel(&planes[k], PARALLEL))
                .map(|(j, d)| (k, j, d))
        })
        .min_by(|a, b| a.2.total_cmp(&b.2))
        .map(|(k, j, _)| (k, j))
}

/// Faces whose normals are closer than this (rad) meet in no crease and make no ridge: a
/// contact crossing from one to the other does not notice (the rounding of a surface file's
/// corners tilts coplanar triangles by about 1e-9 rad).
const PARALLEL: f64 = 1e-7;

/// How close (as a fraction of L) a contact must be to going under another face for
/// [`met_face`] to take that face as the one it met: a good deal more than a located event's
/// distance (a step's stage beyond it), far less than any face's size.
const MEETS: f64 = 1e-5;

/// Puts each contact riding a crease back on its crease's second face: the least change of
/// (X, Z, L θ) that removes their distances from those faces (Gauss–Newton with the contacts'
/// velocity maps, the minimum-norm step, as `hold` does for a sticking contact), a move of the
/// size of the integrator's error.
fn hold_on_creases(
    scene: &Scene,
    dynamics: &Simulation,
    finder: &mut PoseFinder<'_>,
    y: &Y,
    ev: Eval,
) -> Result<(Y, Eval), Stop> {
    let l = scene.l();
    let (mut y, mut ev) = (*y, ev);
    for _ in 0..4 {
        let creases = ev.motion.creases.without(ev.motion.stuck);
        let gaps: Vec<f64> = creases
            .iter()
            .map(|c| c.normal.dot(&ev.pose.vertices[c.contact]) - c.offset)
            .collect();
        if gaps.iter().all(|g| g.abs() <= 1e-14 * l) {
            break;
        }
        let geom = ContactGeometry::with_normals(&finder.site().normals(), &ev.pose);
        // Row k: the distance's rate for unit (Ẋ, Ż, L θ̇).
        let rows = creases
            .iter()
            .map(|c| {
                rigid_body::contact_velocity_map(&geom, l, c.contact)
                    .map(|v| Vector3::from(v.map(|col| c.normal.dot(&col))))
            })
            .collect::<Result<Vec<_>, _>>()
            .map_err(stop_of)?;
        let k = rows.len();
        let jjt = DMatrix::from_fn(k, k, |a, b| rows[a].dot(&rows[b]));
        let Some(m) = jjt
            .lu()
            .solve(&DVector::from_iterator(k, gaps.iter().map(|g| -g)))
            .filter(|m| m.iter().all(|v| v.is_finite()))
        else {
            break;
        };
        let delta: Vector3<f64> = (0..k).map(|a| rows[a] * m[a]).sum();
        y[0] += delta[0];
        y[1] += delta[1];
        y[2] += delta[2] / l;
        ev = evaluate(scene, dynamics, finder, &y, Hold::of(&ev.motion))?;
        y = accept(&y, &ev);
    }
    Ok((y, ev))
}
