//! The block at rest, one layer for every model that rests: whether a ground-motion record still
//! shakes the foundation, the record's samples walked within an increment while the block is
//! held, the onset of slip between a held sample and one that is not, the row of a block at
//! rest, and the route's end at rest — its reason and its words, "stopped", "does not slide",
//! "the ground-motion record ended at … s; the block came to rest / never slid and static
//! friction holds it".
//!
//! Who rests how:
//! - the rigid body on its frame (`rigid/`) rests under a record between its samples, held by
//!   its three friction cones, and slips at the moment they no longer hold it (located here,
//!   [`first_unheld`] and [`onset`]);
//! - the block on its base (`body/`) is time-stepped: at rest under a record each increment is a
//!   step from rest, kept only if it moves the block (`derivations/13-base-contact.md` §6), so it
//!   walks no samples and locates no onset; its stop and its end at rest are told here;
//! - the paper's dynamics (`paper/`) follows no record (a scene with one is refused) and rests
//!   only at its stop, where its own onset ratio says whether the block stays.

use super::row::Row;
use super::termination::Reason;
use crate::mechanics::static_friction::FactorOfSafety;
use crate::model::Foundation;

/// Whether a ground-motion record still shakes the foundation at `t` (its last sample not yet
/// reached): a block held at rest then rests on, checked again as the record's loads change,
/// rather than end its route.
pub(super) fn shaking(foundation: &Foundation, t: f64) -> bool {
    foundation.record().is_some_and(|r| t < r.end())
}

/// The record's next sample after `t`, where its loads may turn, or `limit` where none comes
/// before it (or there is no record): a step ends there, and a block at rest is checked there.
pub(super) fn next_turn(foundation: &Foundation, t: f64, limit: f64) -> f64 {
    match foundation.record().and_then(|r| r.next_sample(t)) {
        Some(s) if s < limit => s,
        _ => limit,
    }
}

/// The record's samples from `from` to `to` (the last at `to`) walked while the block at rest is
/// `held` at each: between two samples the record's loads are linear in time and the loads the
/// block is held under a convex set, so a block held at both is held between them. The first
/// interval from a held sample to one where it is not, or none where it is held throughout; an
/// error of `held` ends the walk with it.
pub(super) fn first_unheld<E>(
    foundation: &Foundation,
    (from, to): (f64, f64),
    mut held: impl FnMut(f64) -> Result<bool, E>,
) -> Result<Option<(f64, f64)>, E> {
    let mut at = from;
    while at < to {
        let next = next_turn(foundation, at, to);
        if !held(next)? {
            return Ok(Some((at, next)));
        }
        at = next;
    }
    Ok(None)
}

/// The onset of slip between `lo`, where the block is held, and `hi`, where it is not: at
/// `exit`, the fraction of the interval where the segment of the record's accelerations leaves
/// the held set, where a cone program gave it; else by the event layer's bisection on `holds`
/// (20 halvings: to a millionth of the interval), the first time found not held.
pub(super) fn onset<E>(
    (lo, hi): (f64, f64),
    exit: Option<f64>,
    mut holds: impl FnMut(f64) -> Result<bool, E>,
) -> Result<f64, E> {
    match exit {
        Some(s) => Ok(lo + s.clamp(0.0, 1.0) * (hi - lo)),
        None => {
            let slips = |t: f64| holds(t).map(|held| !held);
            let (_, not) =
                super::events::bisect((lo, hi), super::events::Until::halvings(20), slips)?;
            Ok(not)
        }
    }
}

/// The row of a block at rest, from the row its model gives at its state: its velocities zero,
/// no reactions (the static friction that holds it is indeterminate), on no crease. (The paper's
/// dynamics keeps its reactions at its stop: its frictional system gives them. The block on its
/// base reports its own rows at rest: its state's velocities are zero and it reports no
/// reactions.)
pub(super) fn row_at_rest(row: Row) -> Row {
    Row {
        vx_m_s: 0.0,
        vz_m_s: 0.0,
        omega_deg_s: 0.0,
        n_n: None,
        s_n: None,
        crease: [None; 3],
        ..row
    }
}

/// How a route ends at rest.
#[derive(Debug, Clone, PartialEq)]
pub(super) enum AtRest {
    /// Held where it starts, or unable to start: "does not slide", for the reason given.
    NeverSlid(String),
    /// The motion stopped where static friction holds the block: "stopped", for the reason
    /// given.
    Stopped(String),
    /// At rest when the ground-motion record was over: "stopped" where the block had moved,
    /// else "does not slide"; `on` where it came to rest (" on its base", or nothing), `holding`
    /// the factor of safety there, where the model's static check gives one.
    RecordOver {
        moved: bool,
        on: &'static str,
        holding: Option<FactorOfSafety>,
    },
}

impl AtRest {
    /// The reason the route ends for and its words for people, under the `foundation`'s record.
    pub fn words(self, foundation: &Foundation) -> (Reason, String) {
        match self {
            AtRest::NeverSlid(why) => (Reason::DoesNotSlide, why),
            AtRest::Stopped(why) => (Reason::Stopped, why),
            AtRest::RecordOver { moved, on, holding } => {
                let (reason, what, on) = if moved {
                    (Reason::Stopped, "the block came to rest", on)
                } else {
                    (Reason::DoesNotSlide, "the block never slid", "")
                };
                let fs = holding.map_or(String::new(), |f| format!(" (factor of safety {f})"));
                let detail = format!(
                    "the ground-motion record ended at {:.6} s; {what}{on} and static friction \
                     holds it{fs}",
                    foundation.record().map_or(0.0, |r| r.end())
                );
                (reason, detail)
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn shaken() -> Foundation {
        let path = concat!(env!("CARGO_MANIFEST_DIR"), "/scenes/shaken.toml");
        let sim = crate::scene::Scene::from_file(path.as_ref())
            .unwrap()
            .simulation()
            .unwrap();
        sim.foundation().clone()
    }

    #[test]
    fn a_held_block_is_walked_sample_by_sample_to_the_first_it_is_not_held_at() {
        let rock = shaken();
        let r = rock.record().unwrap();
        let (a, b) = (
            r.next_sample(0.0).unwrap(),
            r.next_sample(r.next_sample(0.0).unwrap()),
        );
        let b = b.unwrap();
        assert!(shaking(&rock, 0.0) && !shaking(&rock, r.end()));
        assert_eq!(next_turn(&rock, 0.0, 1.0), a);
        assert_eq!(next_turn(&rock, 0.0, 0.5 * a), 0.5 * a);
        let mut seen = Vec::new();
        let first = first_unheld(&rock, (0.0, 1.0), |t| {
            seen.push(t);
            Ok::<_, ()>(t < b)
        });
        assert_eq!(first, Ok(Some((a, b))));
        assert_eq!(seen, [a, b]);
        assert_eq!(
            first_unheld(&rock, (0.0, 0.5 * a), |_| Ok::<_, ()>(true)),
            Ok(None)
        );
        // The onset: at the exit where a cone program gave one, else bisected.
        assert_eq!(onset((1.0, 2.0), Some(1.5), |_| Ok::<_, ()>(true)), Ok(2.0));
        let t = onset((1.0, 2.0), None, |t| Ok::<_, ()>(t < 1.3)).unwrap();
        assert!(t >= 1.3 && t - 1.3 < 1e-6, "{t}");
    }

    #[test]
    fn a_route_at_rest_ends_in_the_words_of_its_reason() {
        let rock = shaken();
        let over = |moved, on| AtRest::RecordOver {
            moved,
            on,
            holding: Some(FactorOfSafety::from_multiple(1.25)),
        };
        let (reason, words) = over(true, " on its base").words(&rock);
        assert_eq!(reason, Reason::Stopped);
        assert!(
            words.starts_with("the ground-motion record ended at ")
                && words.ends_with(
                    " s; the block came to rest on its base and static friction holds it \
                     (factor of safety 1.2500)"
                ),
            "{words}"
        );
        let (reason, words) = over(false, " on its base").words(&rock);
        assert_eq!(reason, Reason::DoesNotSlide);
        assert!(
            words.contains("; the block never slid and static"),
            "{words}"
        );
        let no_fs = AtRest::RecordOver {
            moved: false,
            on: "",
            holding: None,
        };
        assert!(no_fs.words(&rock).1.ends_with("static friction holds it"));
        assert_eq!(
            AtRest::Stopped("held".into()).words(&rock),
            (Reason::Stopped, "held".into())
        );
        assert_eq!(
            AtRest::NeverSlid("held".into()).words(&rock).0,
            Reason::DoesNotSlide
        );
    }

    #[test]
    fn a_row_at_rest_has_no_velocity_reaction_or_crease() {
        let moving = Row {
            x_m: 1.0,
            vx_m_s: 2.0,
            vz_m_s: -1.0,
            omega_deg_s: 3.0,
            n_n: Some([1.0; 3]),
            s_n: Some([0.5; 3]),
            crease: [Some(4), None, None],
            faces: [7, 8, 9],
            ..Row::default()
        };
        let r = row_at_rest(moving);
        assert_eq!((r.vx_m_s, r.vz_m_s, r.omega_deg_s), (0.0, 0.0, 0.0));
        assert_eq!((r.n_n, r.s_n, r.crease), (None, None, [None; 3]));
        assert_eq!((r.x_m, r.faces), (1.0, [7, 8, 9]));
    }
}
