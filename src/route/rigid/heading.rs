//! The rigid body's events within a step — a stop, a pivot, a release, a switch of friction's
//! regime (`route/events.rs`'s [`Event`]) — recognised against the motion at the step's start
//! ([`Heading`]), met at a stage of the RK4 step ([`rk4_stages`]) and located by the event
//! layer's bisection on the step length ([`bracket_event`]).

use super::Model;
use super::evaluate::{Eval, Hold, evaluate};
use super::state::{RigidState, VALUES};
use crate::mechanics::rigid_body::Motion;
use crate::route::events::{Event, Until, bisect, met_first};
use crate::route::integrator::hermite;
use crate::route::pose_finder::PoseFinder;
use crate::route::termination::Stop;
use std::convert::Infallible;

/// The motion at the start of a step, against which the events of the step are recognised:
/// a stop — a later twist t has reversed, ⟨t, before⟩ ≤ 0 in the kinetic-energy inner
/// product —, a release — the contact that stuck no longer does — or a pivot — the slip of a
/// slipping contact no longer runs the way its friction at the start opposed, i.e. it passed
/// through zero.
#[derive(Clone, Copy)]
pub(super) struct Heading<'a> {
    pub before: &'a Motion,
    pub mass: f64,
    /// Whether a switch of friction's regime is an event.
    pub switches: bool,
}

impl Heading<'_> {
    pub(super) fn event(&self, m: &Motion) -> Option<Event> {
        let b = self.before;
        if b.twist.is_zero() {
            return None;
        }
        if m.twist.energy_dot(&b.twist, self.mass, &b.inertia) <= 0.0 {
            return Some(Event::Stop);
        }
        if let Some(i) = b.stuck.filter(|&i| m.stuck != Some(i)) {
            return Some(Event::Release(i));
        }
        // The slip's direction at the step's start is the one its friction opposes (for a slip
        // just started, the direction it starts in, which its velocity, still of round-off's
        // size, does not yet show).
        (0..3)
            .filter(|&i| b.stuck != Some(i) && b.shear[i].norm() > 0.0)
            .find(|&i| m.slip[i].dot(&b.shear[i]) >= 0.0)
            .map(Event::Pivot)
            .or_else(|| (self.switches && m.regime != b.regime).then_some(Event::Switch))
    }
}

/// A step searched for an event: from `y` (derivative `k1`), `h` long, reaching `end`.
pub(super) struct Span<'y> {
    pub y: &'y RigidState,
    pub k1: &'y [f64; VALUES],
    pub h: f64,
    pub end: RigidState,
}

/// Where within a step an event lies: the longest step length `lo` known not to reach it (its
/// state `y_lo`), the shortest `hi` known to (its state `y_hi`), and the event, if one was seen.
pub(super) struct Bracket {
    pub lo: f64,
    pub hi: f64,
    pub y_lo: RigidState,
    /// The last stage of the single step of length `lo` (its error estimate's k4; `span.k1`
    /// while `lo` is 0).
    pub k4_lo: [f64; VALUES],
    pub y_hi: RigidState,
    pub found: Option<Event>,
    /// The failure at the shortest length known to fail, if any: what the route meets first.
    pub failure: Option<Stop>,
}

/// Event location: the event layer's bisection on the length of the step `span` between 0 and
/// its length, down to 1e-12·dt, for the longest step that neither meets an event of `heading`
/// (at its end or at one of its stages, the first met as `events::met_first` orders them) nor
/// fails.
pub(super) fn bracket_event(
    sim: &Model<'_>,
    finder: &PoseFinder<'_>,
    span: Span<'_>,
    heading: &Heading<'_>,
) -> Bracket {
    let hold = Hold::of(heading.before);
    let reaches = |len: f64| -> Result<(Option<Event>, RigidState, [f64; VALUES]), Stop> {
        let (yh, k4, crossed) = rk4_stages(sim, finder, span.y, span.k1, len, heading)?;
        let mut f = finder.clone();
        let e = evaluate(sim, &mut f, &yh, hold)?;
        let seen = crossed
            .and_then(|c| confirmed(sim, finder, heading, (span.y, span.k1), (&yh, &e), len, c));
        Ok((met_first(heading.event(&e.motion), seen), yh, k4))
    };
    let mut b = Bracket {
        lo: 0.0,
        hi: span.h,
        y_lo: *span.y,
        k4_lo: *span.k1,
        y_hi: span.end,
        found: None,
        failure: None,
    };
    let until = Until::width(1e-12 * sim.settings().dt, 60);
    let Ok((lo, hi)) = bisect::<Infallible>((b.lo, b.hi), until, |mid| {
        Ok(match reaches(mid) {
            Ok((None, ym, k4)) => {
                b.y_lo = ym;
                b.k4_lo = k4;
                false
            }
            Ok((event, ym, _)) => {
                b.y_hi = ym;
                b.found = event;
                true
            }
            Err(stop) => {
                b.failure = Some(stop);
                true
            }
        })
    });
    (b.lo, b.hi) = (lo, hi);
    b
}

/// One classic RK4 step of length h from y, whose derivative k1 is known; stages evaluated on
/// copies of `finder`. Also gives its last stage k4 (for the step's error estimate) and says
/// whether a stage met an event of `heading`: then the step passed through a stop or a pivot,
/// where Coulomb friction jumps and the step's result means nothing (its later stages push on
/// with friction turned round).
pub(super) fn rk4_stages(
    sim: &Model<'_>,
    finder: &PoseFinder<'_>,
    y: &RigidState,
    k1: &[f64; VALUES],
    h: f64,
    heading: &Heading<'_>,
) -> Result<(RigidState, [f64; VALUES], Option<AtStage>), Stop> {
    let mut crossed = None;
    let mut stages = 0;
    let hold = Hold::of(heading.before);
    let mut stage = |y: &[f64; VALUES]| {
        let mut f = finder.for_stages();
        let y = RigidState::from_array(y);
        stages += 1;
        evaluate(sim, &mut f, &y, hold).map(|e| {
            // A switch is told at the step's end only: a stage's state is off the motion by
            // O(h²), and a switch there and back within the step is no jump at its end.
            crossed = crossed.or(heading
                .event(&e.motion)
                .filter(|&e| e != Event::Switch)
                .map(|event| AtStage {
                    event,
                    mid: stages < 3,
                }));
            y.with_rates(e.rates).derivative(&e.motion)
        })
    };
    let (next, k4) = crate::route::integrator::rk4_stages(&y.to_array(), k1, h, &mut stage)?;
    Ok((RigidState::from_array(&next), k4, crossed))
}

/// An event met at a stage of an RK4 step: at one of the two at its middle (the second and
/// third), or at the last, at its end.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct AtStage {
    pub event: Event,
    pub mid: bool,
}

/// Whether an event met at a stage of the step of length `h` from `y0` (its derivative `k1`) to
/// `y1` (evaluated there as `e1`) is the motion's (`derivations/08-rigid-body.md` §4a). The middle
/// stages' states are off the motion by O(h²): enough to turn round a slip just started from
/// zero, and a "pivot" there starts it from zero again, and again, as often as the steps' ends
/// fall there (so that where a route ends moved with the rows' interval). A pivot met at a
/// middle stage is taken where the step's dense output at its middle, within O(h⁴) of the
/// motion, shows an event too. A pivot met at the last stage, which is at the step's end, is
/// taken as met: the bisection that locates it moves that stage off it, where friction turned
/// round in the last stage would otherwise leave a first-order error that only steps of the
/// tolerance's square root keep within it. A stop or a release is taken as met here; but a
/// trial step whose stop was met only at a middle stage is taken again at half its length
/// before any bisection (`RigidBody::substep`).
pub(super) fn confirmed(
    sim: &Model<'_>,
    finder: &PoseFinder<'_>,
    heading: &Heading<'_>,
    (y0, k1): (&RigidState, &[f64; VALUES]),
    (y1, e1): (&RigidState, &Eval),
    h: f64,
    at: AtStage,
) -> Option<Event> {
    if !at.mid || !matches!(at.event, Event::Pivot(_)) {
        return Some(at.event);
    }
    let end = e1.accept(y1);
    let (a, b, k5) = (y0.to_array(), end.to_array(), end.derivative(&e1.motion));
    let mid = RigidState::from_array(&hermite((&a, k1), (&b, &k5), h, 0.5)).at(y0.t + 0.5 * h);
    let mut f = finder.for_stages();
    match evaluate(sim, &mut f, &mid, Hold::of(heading.before)) {
        Ok(e) => heading.event(&e.motion),
        // Off the model at the middle: as the stage said.
        Err(_) => Some(at.event),
    }
}
