//! The events within a rigid-body step — a stop, a pivot, a release — how they are recognised
//! ([`Heading`]), located by bisection on the step length ([`bracket_event`]), and what a stop
//! comes to ([`come_to_rest`]).

use super::{
    Eval, Hold, Y, cm_y, displacement, energy, evaluate, rest_eval, rest_row, rk4, static_check,
};
use crate::mechanics::ContactGeometry;
use crate::mechanics::rigid_body::Motion;
use crate::mechanics::static_friction::StaticCheck;
use crate::route::outcome::Outcome;
use crate::route::pose_finder::PoseFinder;
use crate::route::rhs::{Stop, pose_at};
use crate::route::termination::Reason;
use crate::scene::{Scene, Simulation};

/// The motion at the start of a step, against which the events of the step are recognised:
/// a stop — a later twist t has reversed, ⟨t, before⟩ ≤ 0 in the kinetic-energy inner
/// product —, a release — the contact that stuck no longer does — or a pivot — the slip of a
/// slipping contact no longer runs the way its friction at the start opposed, i.e. it passed
/// through zero.
#[derive(Clone, Copy)]
pub(super) struct Heading<'a> {
    pub(super) before: &'a Motion,
    pub(super) mass: f64,
}

/// What happened within a step.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) enum Event {
    /// The whole motion reversed: the block stopped.
    Stop,
    /// The slip of this contact passed through zero while the block moved on.
    Pivot(usize),
    /// The contact that stuck at the start of the step can no longer be held by its friction
    /// cone: it starts to slip.
    Release(usize),
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
    }
}

/// Where within a step an event lies: the longest step length `lo` known not to reach it (its
/// state `y_lo`), the shortest `hi` known to (its state `y_hi`), and the event, if one was seen.
pub(super) struct Bracket {
    pub(super) lo: f64,
    pub(super) hi: f64,
    pub(super) y_lo: Y,
    pub(super) y_hi: Y,
    pub(super) found: Option<Event>,
}

/// Event location: bisection on the length of the step from `y` (derivative `k1`) between 0
/// and `h` (whose end state is `end`), down to 1e-12·dt, for the longest step that neither
/// meets an event of `heading` (at its end or at one of its stages) nor fails.
pub(super) fn bracket_event(
    scene: &Scene,
    sections: &Simulation,
    finder: &PoseFinder<'_>,
    (y, k1): (&Y, &Y),
    (h, end): (f64, Y),
    heading: &Heading<'_>,
) -> Bracket {
    let hold = Hold::of(heading.before);
    let reaches = |len: f64| -> Result<(Option<Event>, Y), Stop> {
        let (yh, crossed) = rk4(scene, sections, finder, y, k1, len, heading)?;
        let mut f = finder.clone();
        let e = evaluate(scene, sections, &mut f, &yh, hold)?;
        Ok((heading.event(&e.motion).or(crossed), yh))
    };
    let mut b = Bracket {
        lo: 0.0,
        hi: h,
        y_lo: *y,
        y_hi: end,
        found: None,
    };
    for _ in 0..60 {
        if b.hi - b.lo <= 1e-12 * sections.solver().dt {
            break;
        }
        let mid = 0.5 * (b.lo + b.hi);
        match reaches(mid) {
            Ok((None, ym)) => {
                b.lo = mid;
                b.y_lo = ym;
            }
            Ok((event, ym)) => {
                b.hi = mid;
                b.y_hi = ym;
                b.found = event;
            }
            Err(_) => b.hi = mid,
        }
    }
    b
}

/// How far below 1 the factor of safety of a block at rest may be and the block still be
/// taken as held when no consistent start of slip is found (`mechanics::rigid_body`'s search
/// for it resolves accelerations down to about this fraction of g; below it the block would
/// creep at a rate no route could show).
pub(super) const BARELY: f64 = 1e-4;

/// Whether the loads exceed the friction cones of `check` by less than [`BARELY`].
pub(super) fn barely_exceeded(check: &StaticCheck) -> bool {
    check.lowest <= 1.0 && check.factor_of_safety >= 1.0 - BARELY
}

/// What a stop comes to (see [`come_to_rest`]).
pub(super) enum Rest {
    /// Not held: the block slips again from rest, from this evaluation.
    Slips(Box<Eval>),
    /// Held where it stopped while a ground-motion record still shakes the foundation: it
    /// rests from this evaluation at this time, checked again as the record's loads change.
    Rests(Box<Eval>, f64),
    /// The route ends: held where it stopped, or the slip from rest cannot be had.
    Ended(Reason, f64, String),
    /// The state at rest is off the model (as a failed step).
    Failed(Stop),
}

/// Where the motion stops, at `t_event`: the block at rest at `stopped` (the state just before
/// the stop, its rates zeroed; `from` the evaluation the step started from). Held there by
/// static friction, the route ends "stopped"; not held, it slips again from rest. The travel
/// to the rest point, the increment, the rest row and the energy balance go into `o`.
pub(super) fn come_to_rest(
    (scene, sections, finder): (&Scene, &Simulation, &mut PoseFinder<'_>),
    (stopped, from): (&Y, &Eval),
    (k, t, t_event): (usize, f64, f64),
    origin: (f64, f64),
    o: &mut Outcome<'_>,
) -> Rest {
    let (mass, g) = (sections.block().mass, sections.loads().gravity);
    let stop_pose = match pose_at(scene, finder, displacement(stopped)) {
        Ok(p) => p,
        Err(e) => return Rest::Failed(e),
    };
    o.travel += (stop_pose.cm - from.pose.cm).norm();
    o.increments = k;
    let geom = ContactGeometry::with_normals(&finder.site().normals(), &stop_pose);
    let check = match static_check(sections, &geom, (t_event, from.faces, false)) {
        Ok(c) => c,
        Err(Stop { reason, detail, .. }) => return Rest::Ended(reason, t, detail),
    };
    // At rest there: its energy balance and its row; while a record shakes the foundation it
    // rests, else the route ends "stopped" for `why`.
    let balance = energy(stopped, 0.0, cm_y(sections, &stop_pose), origin, mass, g);
    let held = |o: &mut Outcome<'_>, finder: &PoseFinder<'_>, why: String| {
        o.push(rest_row(t_event, stopped, &stop_pose, from.faces));
        o.energy = Some(balance);
        if scene.record().is_some_and(|r| t_event < r.end()) {
            match rest_eval(sections, finder, stop_pose, &check) {
                Ok(e) => Rest::Rests(Box::new(e), t_event),
                Err(stop) => Rest::Failed(stop),
            }
        } else {
            Rest::Ended(Reason::Stopped, t_event, why)
        }
    };
    if check.holds() {
        return held(
            o,
            finder,
            format!(
                "the motion stopped at t = {t_event:.6} s and static friction holds the block \
                 there (factor of safety {})",
                check.factor_of_safety()
            ),
        );
    }
    match evaluate(
        scene,
        sections,
        finder,
        stopped,
        Hold::of(&from.motion).sticking(None),
    ) {
        Ok(e) => Rest::Slips(Box::new(e)),
        Err(Stop { reason, .. })
            if reason == Reason::ContactForcesUndetermined && barely_exceeded(&check) =>
        {
            held(
                o,
                finder,
                format!(
                    "the motion stopped at t = {t_event:.6} s; the loads exceed the friction \
                     cones by {:.1e} of themselves there, too little for a consistent start of \
                     slip, and the block is taken as held (factor of safety {})",
                    1.0 - check.factor_of_safety,
                    check.factor_of_safety()
                ),
            )
        }
        Err(Stop { reason, detail, .. }) => {
            o.energy = Some(balance);
            Rest::Ended(reason, t_event, detail)
        }
    }
}
