//! Contacts held where the motion must keep them against the integrator's drift: a sticking
//! contact on the point where it stuck, and each contact riding a crease on the crease's second
//! face — each by the least change of (X, Z, L θ) that puts it back, a move of the size of the
//! integrator's error.

use super::Model;
use super::evaluate::{Eval, Hold, body_geometry, evaluate, stop_of};
use super::state::RigidState;
use crate::mechanics::ContactGeometry;
use crate::mechanics::rigid_body;
use crate::route::pose_finder::PoseFinder;
use crate::route::termination::Stop;
use nalgebra::{DMatrix, DVector, Vector3};

/// A sticking contact and the point where it stuck.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Anchor {
    pub contact: usize,
    pub at: Vector3<f64>,
}

impl Anchor {
    /// The sticking contact after evaluation `ev` and where it stuck: the point `before` kept
    /// for a contact still sticking, the contact's present point for one that just stuck.
    pub fn after(ev: &Eval, before: Option<Anchor>) -> Option<Anchor> {
        match ev.motion.stuck {
            Some(i) if before.is_some_and(|a| a.contact == i) => before,
            Some(i) => Some(Anchor {
                contact: i,
                at: ev.pose.vertices[i],
            }),
            None => None,
        }
    }
}

/// Puts the sticking contact back on the point where it stuck. The integrator keeps its velocity
/// at zero only to its order, so without this its position creeps by a little every step and a
/// contact that sticks on a strike line (where contacts 1 and 2 start) drifts off its plane's
/// region after a time that depends on dt. The correction is the least change of (X, Z, L θ)
/// that returns the contact's horizontal position to the anchor (Gauss–Newton with the contact's
/// velocity map as the Jacobian; the contact stays on its plane through the pose).
pub(super) fn hold_anchor(
    sim: &Model<'_>,
    finder: &mut PoseFinder<'_>,
    mut y: RigidState,
    mut ev: Eval,
    anchor: Anchor,
) -> Result<(RigidState, Eval), Stop> {
    let (i, at) = (anchor.contact, anchor.at);
    let l = sim.body().l();
    for _ in 0..4 {
        let p = ev.pose.vertices[i];
        let r = [at.x - p.x, at.z - p.z];
        if r[0].hypot(r[1]) <= 1e-14 * l || ev.motion.stuck != Some(i) {
            break;
        }
        let geom = body_geometry(sim, &finder.site().normals(), &ev.pose);
        // The contact's horizontal velocity for unit (Ẋ, Ż, L θ̇): rows X and Z.
        let v = rigid_body::contact_velocity_map(&geom, l, i).map_err(stop_of)?;
        let j = [v.map(|c| c.x), v.map(|c| c.z)];
        let dot = |a: &[f64; 3], b: &[f64; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
        let (a, b, d) = (dot(&j[0], &j[0]), dot(&j[0], &j[1]), dot(&j[1], &j[1]));
        let det = a * d - b * b;
        if det.abs() <= 1e-12 * a.max(d).powi(2) || !det.is_finite() {
            break;
        }
        let m = [(d * r[0] - b * r[1]) / det, (a * r[1] - b * r[0]) / det];
        let delta: [f64; 3] = std::array::from_fn(|c| j[0][c] * m[0] + j[1][c] * m[1]);
        y.x += delta[0];
        y.z += delta[1];
        y.theta += delta[2] / l;
        ev = evaluate(sim, finder, &y, Hold::of(&ev.motion).sticking(Some(i)))?;
        y = ev.accept(&y);
    }
    Ok((y, ev))
}

/// Puts each contact riding a crease back on its crease's second face: the least change of
/// (X, Z, L θ) that removes their distances from those faces (Gauss–Newton with the contacts'
/// velocity maps, the minimum-norm step, as [`hold_anchor`] does for a sticking contact).
pub(super) fn hold_on_creases(
    sim: &Model<'_>,
    finder: &mut PoseFinder<'_>,
    y: &mut RigidState,
    ev: &mut Eval,
) -> Result<(), Stop> {
    let l = sim.body().l();
    for _ in 0..4 {
        let creases = ev.motion.creases.without(ev.motion.stuck);
        if creases.is_empty() {
            break;
        }
        let gaps: Vec<f64> = creases
            .iter()
            .map(|c| c.normal.dot(&ev.pose.vertices[c.contact]) - c.offset)
            .collect();
        if gaps.iter().all(|g| g.abs() <= 1e-14 * l) {
            break;
        }
        let geom = ContactGeometry::new(&finder.site().normals(), &ev.pose);
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
        y.x += delta[0];
        y.z += delta[1];
        y.theta += delta[2] / l;
        *ev = evaluate(sim, finder, y, Hold::of(&ev.motion))?;
        *y = ev.accept(y);
    }
    Ok(())
}
