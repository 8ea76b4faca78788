//! The rigid body's right-hand side at a state: the pose, the contacts held to what the step
//! holds them to, the loads, and the accelerations with the contact forces
//! (`mechanics::rigid_body`); and the RK4 step through it.

use super::Model;
use super::state::RigidState;
use crate::geometry::Pose;
use crate::mechanics::ContactGeometry;
use crate::mechanics::loads::Applied;
use crate::mechanics::rigid_body::{self, Creases, Motion, RigidError};
use crate::route::pose_finder::PoseFinder;
use crate::route::row::Row;
use crate::route::termination::{Reason, Stop};
use crate::route::three_point::{faces_of, frame_row};
use nalgebra::Vector3;

/// One evaluation of the rigid-body right-hand side.
#[derive(Debug, Clone, Copy)]
pub(super) struct Eval {
    pub pose: Pose,
    pub motion: Motion,
    /// The rates the motion was evaluated with (those of the state, with a sticking contact's
    /// slip projected out).
    pub rates: [f64; 3],
    /// The kinetic energy that projection removed (J, ≤ 0): friction work, booked when the
    /// state is taken ([`Eval::accept`]).
    pub removed: f64,
    /// The face each contact rests on (`Row::faces`).
    pub faces: [u32; 3],
}

impl Eval {
    /// The state `y` as the route takes it at this evaluation: its rates those the motion was
    /// evaluated with, and the kinetic energy their projection removed booked as friction work.
    pub fn accept(&self, y: &RigidState) -> RigidState {
        RigidState {
            work_friction: y.work_friction + self.removed,
            ..y.with_rates(self.rates)
        }
    }

    /// The row of state `y` evaluated here, at `t`.
    pub fn row(&self, t: f64, y: &RigidState) -> Row {
        let m = &self.motion;
        let on = (self.faces, m.creases.faces());
        let reactions = Some((m.normal, m.shear.map(|s| s.norm())));
        frame_row(t, y.frame_state(), &self.pose, on, reactions)
    }
}

/// The reason a state is off the model, from the mechanics' own.
pub(super) fn stop_of(e: RigidError) -> Stop {
    let (reason, contact) = match e {
        RigidError::LiftOff { contact, .. } | RigidError::ImpactLifts { contact, .. } => {
            (Reason::ContactLiftedOff, Some(contact))
        }
        // Events of a crease (`substep.rs` handles them where it finds them).
        RigidError::CreaseLetsGo { contact, .. } => (Reason::CreaseLetsGo, Some(contact)),
        RigidError::CreaseTakesOver { contact, .. } => (Reason::CreaseTakesOver, Some(contact)),
        RigidError::Wedged => (Reason::Wedged, None),
        RigidError::SlipStart { contact } => (Reason::ContactForcesUndetermined, Some(contact)),
        RigidError::Singular(_) | RigidError::SlipFromRest | RigidError::StickSingular { .. } => {
            (Reason::ContactForcesUndetermined, None)
        }
    };
    Stop {
        reason,
        detail: e.to_string(),
        contact,
    }
}

/// What the step holds contacts to: a contact that stuck at the start of the step, and the
/// contacts riding creases (`derivations/10-faces.md` §4).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub(super) struct Hold {
    pub stuck: Option<usize>,
    pub creases: Creases,
    /// A contact released from sticking at this moment: it slips, though its slip is still zero
    /// and its cone holds it to round-off ([`rigid_body::accelerations_releasing`]).
    pub released: Option<usize>,
}

impl Hold {
    /// What the motion `m` was evaluated holding.
    pub fn of(m: &Motion) -> Hold {
        Hold {
            stuck: m.stuck,
            creases: m.creases,
            released: None,
        }
    }

    /// The same creases, with `stuck` sticking.
    pub fn sticking(self, stuck: Option<usize>) -> Hold {
        Hold { stuck, ..self }
    }

    /// The same creases, contact `i` released from sticking at this moment.
    pub fn releasing(self, i: usize) -> Hold {
        Hold {
            stuck: None,
            released: Some(i),
            ..self
        }
    }
}

/// The right-hand side at state `y`. `hold.stuck`: the contact that stuck at the start of the
/// step; the integrator's drift of its slip is projected out (as an impulse would, the energy
/// it takes in `Eval::removed`) so that it stays stuck while its cone allows. `hold.creases`:
/// contacts riding creases; their velocities into their second faces are projected out likewise.
pub(super) fn evaluate(
    sim: &Model<'_>,
    finder: &mut PoseFinder<'_>,
    y: &RigidState,
    hold: Hold,
) -> Result<Eval, Stop> {
    let stuck = hold.stuck;
    let pose = finder.pose_at(y.displacement())?;
    let geom = body_geometry(sim, &finder.site().normals(), &pose);
    let applied =
        Applied::of(sim.body(), &geom, sim.foundation().acceleration(y.t)).about(&geom.cm_offset);
    let mut rates = y.rates();
    let mut removed = 0.0;
    if let Some(i) = stuck.or(hold.released) {
        // Always: a contact that stuck at the start of the step can only start to slip by its
        // cone no longer holding it (the release, which `accelerations` sees after this
        // projection), never by the integrator's drift, however long the step. A contact
        // released at this moment starts to slip from zero, not from that drift (of round-off's
        // size, it would set the young slip's direction and turn it round at once).
        (rates, removed) =
            rigid_body::pivot_rates(&geom, sim.body().block(), rates, i).map_err(stop_of)?;
    }
    let riding = hold.creases.without(stuck);
    if !riding.is_empty() {
        let (r, into) =
            rigid_body::crease_rates(&geom, sim.body().block(), rates, &riding).map_err(stop_of)?;
        (rates, removed) = (r, removed + into);
    }
    let faces = faces_of(finder.site());
    let at = rigid_body::State {
        geom: &geom,
        applied: &applied,
        block: sim.body().block(),
        strength: &sim.frame_strength(faces, false),
    };
    let step = sim.settings().reference_step();
    let motion = rigid_body::accelerations_releasing(&at, rates, step, hold.creases, hold.released)
        .map_err(stop_of)?;
    Ok(Eval {
        pose,
        motion,
        rates,
        removed,
        faces,
    })
}

/// The contacts with their arms from the centre of mass, which a monolith has above the base
/// point the pose is of (`derivations/11-dam-loads.md` §1): Newton–Euler about the centre of
/// mass. The static checks keep the arms from the base point, with the loads' moments about it.
pub(super) fn body_geometry(
    sim: &Model<'_>,
    normals: &[Vector3<f64>; 3],
    pose: &Pose,
) -> ContactGeometry {
    ContactGeometry::new(normals, pose).centred(sim.body().loads().cm_height)
}

/// The height of the centre of mass (m) at `pose`: the base point's and the monolith's ȳ along
/// j′. Gravity's work is m g times its fall.
pub(super) fn cm_y(sim: &Model<'_>, pose: &Pose) -> f64 {
    pose.cm.y + sim.body().loads().cm_height * pose.frame.j.y
}
