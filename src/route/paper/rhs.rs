//! The right-hand side of the motion: at a state, the pose (from the pose finder), the reactions
//! (the paper's) and the accelerations of (X, Z, θ).
//!
//! Both polynomial systems of an increment are solved by the finder's method: with
//! continuation, the pose by the tracker and the frictional reactions by Newton from the
//! previous increment's solution ([`reactions_paper::follow`]); with all roots, the pose by the
//! eigenvalue solve and the reactions by all solutions of their degree-8 resultant
//! ([`reactions_paper::all_solutions`]), the one continuing the previous chosen by the stated
//! rule ([`reactions_paper::select`]). Both give the same route (`tests/integration/route.rs`).
//!
//! The paper's kinematics (eqs. 23, 30–35): the CM accelerates along i' by a = ΣF·i'/m, whose
//! horizontal components give Ẍ, Z̈ (eqs. 30, 31, 33, 34); the block turns about j' by
//! A = ΣM·j'/I (eqs. 32, 35, with A_Y for the misprinted A_X). θ is measured from +X towards +Z,
//! the opposite sense of a rotation about +Y, so θ̈ = −A·(j'·Y).

use super::state::State;
use crate::geometry::{Displacement, Pose};
use crate::mechanics::loads::Applied;
use crate::mechanics::reactions_paper::{self, Reaction, ReactionsError};
use crate::mechanics::{ContactGeometry, statics};
use crate::model::{Body, Simulation};
use crate::numeric::fixed;
use crate::route::pose_finder::{PoseFinder, PoseMethod};
use crate::route::termination::{Reason, Stop};
use crate::route::three_point::faces_of;
use nalgebra::Vector3;

/// Everything known at one state.
#[derive(Debug, Clone, Copy)]
pub struct Evaluation {
    /// The pose.
    pub pose: Pose,
    /// The contacts at it.
    pub geom: ContactGeometry,
    /// The paper's reactions there.
    pub reaction: Reaction,
    /// (Ẍ, Z̈, θ̈) in m/s², m/s², rad/s².
    pub acc: [f64; 3],
    /// Frictionless normal reactions (25)–(27) at this pose (N).
    pub statics: [f64; 3],
    /// True when the reaction was chosen afresh by the rule — at the start, or when the
    /// solution followed so far was lost — rather than continuing the previous one.
    pub fresh: bool,
}

/// Evaluates the right-hand side at displacement `d`, moving `tracker` there. `previous` is
/// the reaction chosen at the last state (continuity); `velocity` the current CM velocity and
/// angular velocity (None at rest).
pub fn evaluate(
    (sim, body): (&Simulation, &Body),
    tracker: &mut PoseFinder<'_>,
    d: Displacement,
    previous: Option<&Reaction>,
    velocity: Option<(Vector3<f64>, Vector3<f64>)>,
) -> Result<Evaluation, Stop> {
    let pose = tracker.pose_at(d)?;
    let geom = ContactGeometry::new(body.normals(), &pose);
    let applied = Applied::new(body.loads(), body.block(), &geom.frame);
    // The paper's dynamics keeps the start's planes (their normals above), and their faces'
    // criteria; it knows no cohesion (refused when the scene is read).
    let friction = body.frame_strength(sim.strengths(), faces_of(body.site()), false);
    let c = statics::frictionless_normals(&geom, &applied).ok_or_else(|| Stop {
        contact: None,
        reason: Reason::NoAdmissibleRoot,
        detail: "the frictionless statics are singular".into(),
    })?;
    let lift = |e: ReactionsError| Stop {
        contact: None,
        reason: Reason::ContactLiftedOff,
        detail: e.to_string(),
    };
    let followed = match previous {
        Some(p) if tracker.method() == PoseMethod::Continuation => {
            reactions_paper::follow(&geom, &applied, body.block(), &c, &friction, p)
                .map_err(lift)?
        }
        _ => None,
    };
    let (reaction, fresh) = match followed {
        Some(r) => (r, false),
        None => {
            let all = reactions_paper::all_solutions(&geom, &applied, body.block(), &c, &friction)
                .map_err(lift)?;
            let k = reactions_paper::select(&geom, &all, previous.map(|p| &p.angles), velocity)
                .ok_or_else(|| Stop {
                    contact: None,
                    reason: Reason::NoFrictionSolution,
                    detail: format!(
                        "no solution with N0 > 0 at X = {} m, Z = {} m, θ = {}°",
                        fixed(d.x, 6),
                        fixed(d.z, 6),
                        fixed(d.theta.to_degrees(), 6)
                    ),
                })?;
            let continued =
                previous.is_some_and(|p| reactions_paper::continues(&p.angles, &all[k].angles));
            (all[k], !continued)
        }
    };
    let i = geom.frame.i;
    let acc = [
        reaction.accel * i.x,
        reaction.accel * i.z,
        -reaction.ang_accel * geom.frame.j.y,
    ];
    Ok(Evaluation {
        pose,
        geom,
        reaction,
        acc,
        statics: c,
        fresh,
    })
}

/// CM velocity and angular velocity vectors of a state (the angular velocity about −Y, the
/// sense in which θ grows).
pub fn velocity(s: &State) -> Option<(Vector3<f64>, Vector3<f64>)> {
    if s.speed() == 0.0 && s.omega == 0.0 {
        None
    } else {
        Some((
            Vector3::new(s.vx, 0.0, s.vz),
            Vector3::new(0.0, -s.omega, 0.0),
        ))
    }
}
