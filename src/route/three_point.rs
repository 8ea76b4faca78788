//! The three-point frame's own room beside the two models that move on it (the paper's
//! dynamics, `paper/`, and the rigid body's, `rigid/`): what both take of the frame — the face
//! each contact rests on, the row of the block on it, and the measures at the start on its three
//! contacts' friction cones.
//! A block on its base reports through the same three points (its reporting triangle: the
//! tilts of route.csv, the factor of safety at the start), and asks this room for them.

use super::logbook::Logbook;
use super::row::Row;
use crate::geometry::{Pose, Site};
use crate::mechanics::ContactGeometry;
use crate::mechanics::loads::Applied;
use crate::mechanics::static_friction;
use crate::mechanics::statics::frictionless_normals;
use crate::model::Simulation;

/// The face each contact of `site` rests on (see `Row::faces`).
pub fn faces_of(site: &Site) -> [u32; 3] {
    match site.ground() {
        Some((_, faces)) => faces.map(|f| f as u32),
        None => [0, 1, 2],
    }
}

/// The row of the block on its frame at time `t`: its CM at X, Z and its yaw θ (rad) with their
/// rates (`state`: X, Z, θ, Ẋ, Ż, θ̇), the CM's height and the tilts of `pose`, the contacts on
/// `faces` (riding `crease`s' second faces), the magnitudes of the normal and shear reactions
/// where they were had.
pub(super) fn frame_row(
    t: f64,
    state: [f64; 6],
    pose: &Pose,
    (faces, crease): ([u32; 3], [Option<u32>; 3]),
    reactions: Option<([f64; 3], [f64; 3])>,
) -> Row {
    let [x, z, theta, vx, vz, omega] = state;
    Row {
        body: 0,
        t_s: t,
        x_m: x,
        y_m: pose.cm.y,
        z_m: z,
        theta_deg: theta.to_degrees(),
        alpha_deg: pose.alpha.to_degrees(),
        beta_deg: pose.beta.to_degrees(),
        gamma_deg: pose.gamma.to_degrees(),
        vx_m_s: vx,
        vz_m_s: vz,
        omega_deg_s: omega.to_degrees(),
        n_n: reactions.map(|r| r.0),
        s_n: reactions.map(|r| r.1),
        faces,
        crease,
        corners_carrying: None,
        points_carrying: None,
    }
}

/// The factor of safety at the start and what limits it, where the route has none yet: the
/// largest multiple of the driving loads static friction within the frame's three cones holds
/// at `start` (the joint's cohesion whole), none where there is no pose or the cone program
/// fails. One factor of safety whatever the dynamics; of the one body the route follows (no one
/// body's frame speaks for several).
pub(super) fn factor_of_safety_at_start<R>(
    sim: &Simulation,
    start: Option<&Pose>,
    o: &mut Logbook<'_, R>,
) {
    let [body] = sim.bodies() else {
        return;
    };
    if o.fs.is_some() {
        return;
    }
    let strength = body.frame_strength(sim.strengths(), faces_of(body.site()), true);
    let check = start.and_then(|pose| {
        let geom = ContactGeometry::new(body.normals(), pose);
        let applied = Applied::of(body, &geom, [0.0; 3]);
        static_friction::at_rest(&geom, &applied, &strength).ok()
    });
    o.fs = check.as_ref().map(|c| c.factor_of_safety());
    o.fs_limit = check.and_then(|c| c.limit());
}

/// Under a ground-motion record, what a Newmark user reports first: the yield acceleration on
/// the frame's three contacts at `start` (`static_friction::yield_acceleration`), of the one
/// body the route follows.
pub(super) fn yield_acceleration_at_start<R>(
    sim: &Simulation,
    start: Option<&Pose>,
    o: &mut Logbook<'_, R>,
) {
    let [body] = sim.bodies() else {
        return;
    };
    if sim.foundation().record().is_none() {
        return;
    }
    let strength = body.frame_strength(sim.strengths(), faces_of(body.site()), true);
    o.yield_acceleration = start.and_then(|pose| {
        let geom = ContactGeometry::new(body.normals(), pose);
        let applied = Applied::of(body, &geom, [0.0; 3]);
        let statics = frictionless_normals(&geom, &applied).unwrap_or([1.0; 3]);
        let weight = body.block().mass * body.loads().gravity;
        let arm = geom.frame.j * body.loads().cm_height;
        static_friction::yield_acceleration(&geom, &applied, (weight, arm), &strength, &statics)
            .ok()
            .flatten()
    });
}
