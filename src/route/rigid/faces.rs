//! Events of the rock's faces: a contact meeting another face (it rides the crease), running
//! over a surface's ridge (it goes on along the face beyond), or let go by one of its crease's
//! faces, and the frictional, perfectly inelastic impact that follows a contact's meeting a face
//! (`derivations/10-faces.md` §4–6).

use super::Ending;
use super::Model;
use super::evaluate::{Eval, Hold, body_geometry, evaluate, stop_of};
use super::hold::hold_on_creases;
use super::state::RigidState;
use crate::mechanics::rigid_body::{self, Crease, Creases, Impact, ImpactLaw, RigidError};
use crate::model::ContactStrengths;
use crate::route::pose_finder::PoseFinder;
use crate::route::termination::{Reason, Stop};
use crate::route::three_point::faces_of;
use nalgebra::Vector3;

/// A contact's change of face at an event of the rock's faces that makes an impact: it met
/// face `face` (and rides the crease), or, at a surface's ridge, went on along it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Met {
    contact: usize,
    face: usize,
    ridge: bool,
}

/// The block just before an impact: the contacts' normal forces (N), and the upward unit
/// normals of the faces it moved on.
pub(super) struct BeforeImpact {
    pub normal_n: [f64; 3],
    pub faces: [Vector3<f64>; 3],
}

/// The impact of a contact meeting a face, or running over a ridge onto one, at state `y`
/// (`met`; `hold` what the contacts are held to after it; `derivations/10-faces.md` §6): the
/// state just after it — its rates those the frictional, perfectly inelastic impulses leave
/// ([`rigid_body::impact`]; the friction coefficients at the contacts' normal forces
/// before it, the block moving on the faces it moved on until then, both in `before`), the
/// kinetic energy they take booked as friction work — and what the contacts are held to then;
/// the finder moves to the new site where the impact put a contact on the new face alone. Or,
/// where the impact would need a face to pull a contact on it faster than a hop, the stop that
/// ends the route there ("contact lifted off", or "ran over a ridge" for the contact that
/// crossed it).
pub(super) fn after_impact(
    sim: &Model<'_>,
    finder: &mut PoseFinder<'_>,
    y: &RigidState,
    before: &BeforeImpact,
    met: Option<Met>,
    hold: Hold,
) -> Result<Result<(RigidState, Hold), Stop>, Ending> {
    let Some(met) = met else {
        return Ok(Ok((*y, hold)));
    };
    let mut f = finder.for_stages();
    let pose = f.pose_at(y.displacement()).map_err(Ending::Failed)?;
    let geom = body_geometry(sim, &finder.site().normals(), &pose);
    let moving = body_geometry(sim, &before.faces, &pose);
    let creases = hold.creases.without(hold.stuck);
    let law = impact_law(sim, finder, before);
    let Impact {
        rates,
        removed,
        creases,
        moved,
    } = match rigid_body::impact(
        &moving,
        &geom,
        sim.body().block(),
        y.rates(),
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
            return Ok(Err(lifted(met, (contact, off), impulse_n_s, speed_m_s)));
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
    let mut z = y.with_rates(rates);
    z.work_friction += removed;
    // A contact stuck before the impact keeps sticking while its cone allows.
    let creases = match hold.stuck.and_then(|i| hold.creases.at(i)) {
        Some(c) => creases.with(*c),
        None => creases,
    };
    Ok(Ok((z, Hold { creases, ..hold })))
}

/// The law of an impact on the site of `finder`: each contact's friction coefficient at its
/// normal force before it (`before`); a release slower than a hop of HOP·L under gravity is not
/// a lift, one from a crease slower than GRAZE·√(g L) a graze.
fn impact_law(sim: &Model<'_>, finder: &PoseFinder<'_>, before: &BeforeImpact) -> ImpactLaw {
    let friction = sim.frame_strength(faces_of(finder.site()), false);
    let mu = if friction.is_frictionless() {
        [0.0; 3]
    } else {
        friction.coefficients(&before.normal_n)
    };
    let body = sim.body();
    let g = body.loads().gravity;
    ImpactLaw {
        mu,
        release_speed: (2.0 * g * HOP * body.l()).sqrt(),
        crease_release_speed: GRAZE * (g * body.l()).sqrt(),
    }
}

/// Where an impact at `met` would need face `off` to pull contact `contact` on it faster than a
/// hop (its impulse `impulse_n_s`, N·s, the speed it would leave at, m/s): the stop that ends
/// the route there, "ran over a ridge" for the contact that crossed it, else "contact lifted
/// off".
fn lifted(met: Met, (contact, off): (usize, u32), impulse_n_s: f64, speed_m_s: f64) -> Stop {
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
    Stop {
        reason,
        detail,
        contact: Some(contact),
    }
}

/// The state just after an event of the rock's faces at `y`, its contacts held to `hold`:
/// evaluated there, each crease's contact put back on its second face — or, where that calls for
/// the next event at once (a contact that meets a steeper face is lifted off its own by the
/// impact; a contact in a crease that can neither stay nor slip leaves a face), after up to three
/// such events at the same moment.
pub(super) fn after_events(
    sim: &Model<'_>,
    finder: &mut PoseFinder<'_>,
    y: &RigidState,
    hold: Hold,
) -> Result<(RigidState, Eval), Ending> {
    let mut hold = hold;
    let mut after = None;
    for _ in 0..3 {
        match settle(sim, finder, y, hold) {
            Ok(e) => {
                after = Some(e);
                break;
            }
            Err(next) => {
                if let Some(e) = leave_a_face(sim, finder, y, hold, &next) {
                    after = Some(e);
                    break;
                }
                hold = face_event(sim, finder, y, &next, hold)
                    .ok_or(Ending::Failed(next))?
                    .0;
            }
        }
    }
    match after {
        Some(e) => Ok(e),
        None => settle(sim, finder, y, hold).map_err(Ending::Failed),
    }
}

/// The state `y` just after an event of the rock's faces, evaluated holding `hold`, each crease's
/// contact put back on its second face (which may itself call for the next event).
fn settle(
    sim: &Model<'_>,
    finder: &mut PoseFinder<'_>,
    y: &RigidState,
    hold: Hold,
) -> Result<(RigidState, Eval), Stop> {
    let mut at = evaluate(sim, finder, y, hold)?;
    let mut settled = at.accept(y);
    hold_on_creases(sim, finder, &mut settled, &mut at)?;
    Ok((settled, at))
}

/// A contact riding a crease that can neither stay at it nor slip from it along a direction
/// consistent with its friction (`next`, why the state `y` just after could not be settled): it
/// leaves one of the two faces, the first (its own, then the crease's second) that it moves off
/// rather than into; the state then, the finder on its site. None where it leaves neither.
fn leave_a_face(
    sim: &Model<'_>,
    finder: &mut PoseFinder<'_>,
    y: &RigidState,
    hold: Hold,
    next: &Stop,
) -> Option<(RigidState, Eval)> {
    let c = next
        .contact
        .filter(|_| next.reason == Reason::ContactForcesUndetermined)
        .and_then(|i| hold.creases.at(i))?;
    let own = finder.site().normals()[c.contact];
    [
        (Reason::CreaseTakesOver, own),
        (Reason::CreaseLetsGo, c.normal),
    ]
    .into_iter()
    .find_map(|(reason, left)| {
        let stop = Stop {
            reason,
            detail: String::new(),
            contact: Some(c.contact),
        };
        let mut f = finder.clone();
        let (h, _) = face_event(sim, &mut f, y, &stop, hold)?;
        let (y, e) = settle(sim, &mut f, y, h).ok()?;
        let m = &e.motion;
        let r = e.pose.vertices[c.contact] - e.pose.cm;
        let (w, v) = (m.twist.w, m.twist.v + m.twist.w.cross(&r));
        let a = m.accel + m.ang_accel.cross(&r) + w.cross(&w.cross(&r));
        // Off it, or along it to round-off on the block's scale.
        let g = sim.body().loads().gravity;
        let off = |u: Vector3<f64>, scale: f64| left.dot(&u) >= -1e-9 * scale;
        if !(off(v, (g * sim.body().l()).sqrt()) && off(a, g)) {
            return None;
        }
        *finder = f;
        Some((y, e))
    })
}

/// The highest hop, as a fraction of L, that an impact may give a contact without ending the
/// route: a contact thrown off its face no faster than √(2 g HOP L) is kept on it — its flight
/// would reach at most a millimetre on a 10 m block (less: the block's turn brings a corner
/// down faster than g), within the roughness of a rock joint, and last some ten milliseconds;
/// Drake's refined contact shows such hops of micrometres. A faster one lifts off: the
/// three-point model ends there.
const HOP: f64 = 1e-4;

/// The slowest release, as a fraction of √(g L), with which a crease's face lets its contact
/// go at an impact (1 mm/s on a 10 m block): a contact meeting a face at a crease it is about to
/// ride leaves the other face at some 10⁻⁵ to 10⁻⁴ m/s (a graze; letting go would start a
/// chatter of impacts along the crease), one that climbs onto the face it met faster (holding
/// the crease would stop its whole motion across it: at 7 mm/s, from the paper's plane 1 onto
/// plane 2 under a record, 20 mm/s of it that refined Drake's block keeps;
/// `derivations/10-faces.md` §6).
const GRAZE: f64 = 1e-4;

/// What a failure `stop` at `y` changes in what the contacts are held to (`held`), if it is an
/// event of the rock's faces (see `RigidBody::crease_event`), and the contact whose change makes
/// an impact; the finder moves to the new site where a contact changes its face. `None` for any
/// other failure.
pub(super) fn face_event(
    sim: &Model<'_>,
    finder: &mut PoseFinder<'_>,
    y: &RigidState,
    stop: &Stop,
    held: Hold,
) -> Option<(Hold, Option<Met>)> {
    let riding = stop.contact.and_then(|i| held.creases.at(i)).copied();
    let creases = match (stop.reason, riding) {
        (Reason::ContactReachedAnotherFace, _) => {
            let c = met_face(sim, finder, y, &held.creases)?;
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
            let (contact, face) = ridge_face(sim, finder, y, &held.creases)?;
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
fn met_face(
    sim: &Model<'_>,
    finder: &PoseFinder<'_>,
    y: &RigidState,
    creases: &Creases,
) -> Option<Crease> {
    let site = finder.site();
    let (ground, _) = site.ground()?;
    let mut f = finder.for_stages();
    let pose = f.pose_at(y.displacement()).ok()?;
    let planes = site.planes();
    let all = ground.faces();
    let near = MEETS * sim.body().l();
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
    sim: &Model<'_>,
    finder: &PoseFinder<'_>,
    y: &RigidState,
    creases: &Creases,
) -> Option<(usize, usize)> {
    let site = finder.site();
    let (ground, _) = site.ground().filter(|(g, _)| g.is_surface())?;
    let mut f = finder.for_stages();
    let pose = f.pose_at(y.displacement()).ok()?;
    let planes = site.planes();
    let all = ground.faces();
    (0..3)
        .filter(|&k| creases.at(k).is_none())
        .filter_map(|k| {
            let v = pose.vertices[k];
            ground
                .faces_by_distance(v.x, v.z, MEETS * sim.body().l())
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
