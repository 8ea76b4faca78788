//! The events of a route, one layer for every model: what an event is, how one is located within
//! a step or an interval (by bisection), and which of the events found in one step the route
//! meets first.
//!
//! Who meets which:
//! - the rigid body on its frame (`rigid/`) meets every kind of [`Event`], recognised against the
//!   motion at its step's start (`rigid/heading.rs`) and located by [`bisect`] on the step's
//!   length; a state off its model (a contact leaving its face's region, lifting off) is located
//!   the same way, as a failure, so that an event before it is handled first and a route that
//!   ends does so at the moment it must;
//! - the paper's dynamics (`paper/`) meets a stop only — the velocity along the increment's first
//!   acceleration passing through zero — and places it in closed form, not by bisection: its
//!   update freezes the accelerations over a step, so the zero is where (v + a τ)·a = 0. A state
//!   off its model it locates by [`bisect`], as the longest part of its substep that can be
//!   taken;
//! - a block at rest under a ground-motion record (`rest.rs`) meets the onset of slip between two
//!   of the record's samples, located by [`bisect`] where no cone program gives it;
//! - the block on its base (`body/`) locates none: it is time-stepped (first order, every change
//!   of its contacts inside a step; `derivations/13-base-contact.md`), and its stop, its rest and
//!   a part of its base going over no ground are told at a step's end.

/// What happens within a step that the step cannot simply be taken across: the motion is no
/// longer the smooth one the step's start set out on, and the route goes on from the event (or
/// ends there) as the model decides. A contact meeting another face (and the impact that
/// follows), running over a ridge or let go by a crease is met as a state off the model,
/// located as a failure and taken by the model as an event of the rock's faces (`rigid/faces.rs`);
/// the record's end is met at rest (`rest.rs`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) enum Event {
    /// The whole motion reversed: the block stopped.
    Stop,
    /// The slip of this contact passed through zero while the block moved on.
    Pivot(usize),
    /// The contact that stuck at the start of the step can no longer be held by its friction
    /// cone: it starts to slip.
    Release(usize),
    /// Friction's regime (a young slip's direction slaved or free, a slow block's slips settled
    /// together or not) is no longer the step's start's: the accelerations jump there, a
    /// first-order error in a step across it that its error estimate does not see. Nothing
    /// changes at it; the step ends there.
    Switch,
}

/// Of the events a step meets at its end and at one of its stages, the one the route meets
/// first: a stop, a pivot or a release met at a stage comes before a switch told at the end
/// (the step passed through it, and its end, where friction was turned round in the later
/// stages, is no state to go on from: taken as the switch's, it had left a block of a closed
/// form 1.6e-5 m/s off at a stop and reversal); otherwise the end's, else the stage's.
pub(super) fn met_first(at_end: Option<Event>, at_stage: Option<Event>) -> Option<Event> {
    match (at_end, at_stage) {
        (Some(Event::Switch), Some(stage)) => Some(stage),
        (end, stage) => end.or(stage),
    }
}

/// The event a step is cut at: the one its bisection found (the earliest of the step by
/// construction), else the one told at the step's end, else at one of its stages; a stop where
/// none shows on the shortest step that reaches it (the motion reversed within a bisection's
/// width).
pub(super) fn cut_at(
    found: Option<Event>,
    at_end: Option<Event>,
    at_stage: Option<Event>,
) -> Event {
    found.or(at_end).or(at_stage).unwrap_or(Event::Stop)
}

/// How far a bisection goes: until its interval is no wider than `width`, at most `most`
/// halvings.
#[derive(Debug, Clone, Copy)]
pub(super) struct Until {
    width: f64,
    most: usize,
}

impl Until {
    /// Down to an interval of `width`, in at most `most` halvings.
    pub fn width(width: f64, most: usize) -> Self {
        Until { width, most }
    }

    /// `n` halvings, whatever the interval's width then.
    pub fn halvings(n: usize) -> Self {
        Until {
            width: f64::NEG_INFINITY,
            most: n,
        }
    }
}

/// Bisection of the interval from `near`, a point known not to reach what is sought (an event,
/// a failure, the onset of slip), to `far`, one known to: `reaches(mid)` says whether the middle
/// `0.5 (near + far)` does, and the half that brackets it is kept, as far as `until` says. The
/// last `(near, far)`; an error of `reaches` ends the search with it. What each probe found
/// (the state there, the event) is the caller's to keep.
pub(super) fn bisect<E>(
    (mut near, mut far): (f64, f64),
    until: Until,
    mut reaches: impl FnMut(f64) -> Result<bool, E>,
) -> Result<(f64, f64), E> {
    for _ in 0..until.most {
        if far - near <= until.width {
            break;
        }
        let mid = 0.5 * (near + far);
        if reaches(mid)? {
            far = mid;
        } else {
            near = mid;
        }
    }
    Ok((near, far))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bisection_brackets_the_first_point_reached_to_its_width_or_its_halvings() {
        let reaches = |t: f64| Ok::<_, ()>(t >= 0.3);
        let (near, far) = bisect((0.0, 1.0), Until::width(1e-9, 60), reaches).unwrap();
        assert!(
            near < 0.3 && far >= 0.3 && far - near <= 1e-9,
            "{near} {far}"
        );
        let (near, far) = bisect((0.0, 1.0), Until::halvings(3), reaches).unwrap();
        assert_eq!((near, far), (0.25, 0.375));
        // An interval already narrow enough is not probed.
        let probed = std::cell::Cell::new(0);
        let count = |_: f64| {
            probed.set(probed.get() + 1);
            Ok::<_, ()>(true)
        };
        assert_eq!(
            bisect((0.0, 1.0), Until::width(2.0, 60), count),
            Ok((0.0, 1.0))
        );
        assert_eq!(probed.get(), 0);
        // An error ends it.
        let failing = |t: f64| if t < 0.5 { Ok(false) } else { Err(t) };
        assert_eq!(bisect((0.0, 1.0), Until::halvings(10), failing), Err(0.5));
    }

    #[test]
    fn a_stage_event_comes_before_a_switch_told_at_the_end_and_the_bisections_first() {
        assert_eq!(
            met_first(Some(Event::Switch), Some(Event::Pivot(1))),
            Some(Event::Pivot(1))
        );
        assert_eq!(
            met_first(Some(Event::Stop), Some(Event::Pivot(1))),
            Some(Event::Stop)
        );
        assert_eq!(
            met_first(None, Some(Event::Release(2))),
            Some(Event::Release(2))
        );
        assert_eq!(met_first(Some(Event::Switch), None), Some(Event::Switch));
        assert_eq!(
            cut_at(Some(Event::Pivot(0)), Some(Event::Stop), None),
            Event::Pivot(0)
        );
        assert_eq!(
            cut_at(None, None, Some(Event::Release(1))),
            Event::Release(1)
        );
        assert_eq!(cut_at(None, None, None), Event::Stop);
    }
}
