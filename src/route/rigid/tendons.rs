//! Anchors' tendons along the route (`derivations/11-dam-loads.md` §10): each pulls with its
//! prestress and E A / L times its stretch as the block moves (a load on the body at its pose,
//! `mechanics::loads::Applied::of`), and breaks when its force reaches its capacity. A substep
//! that would carry a tendon past its capacity is halved, down to the shortest substep (10⁻³ dt),
//! so that the break falls within the shortest substep of where the force reaches the
//! capacity; there the tendon is let go and the state evaluated again without it. A stop checks
//! the tendons before it asks whether friction holds the block (the force peaks there).

use super::Log;
use super::evaluate::{Eval, Hold, evaluate};
use super::{Ending, RigidBody};
use crate::geometry::Pose;
use crate::route::AnchorBreak;
use crate::route::pose_finder::PoseFinder;

/// A tendon within this fraction of its capacity has reached it; a substep that carries one
/// further past is too long (down to the shortest substep).
pub(super) const AT_CAPACITY: f64 = 1e-9;

impl RigidBody<'_> {
    /// Whether a tendon left whole is past its capacity by more than `margin` (a fraction of it)
    /// at the evaluation `e`.
    pub(super) fn past_capacity(&self, e: &Eval, margin: f64) -> Option<usize> {
        self.sim
            .body()
            .tendons()
            .iter()
            .position(|t| t.past_capacity(&e.pose.cm, &e.pose.frame, margin))
    }

    /// Breaks every tendon that has reached its capacity with the block at `pose` at time `t`,
    /// each booked in the logbook (the caller evaluates the state again). Whether any broke.
    pub(super) fn break_tendons_at(&mut self, pose: &Pose, t: f64, o: &mut Log<'_>) -> bool {
        let mut broke = false;
        while let Some(k) = self
            .sim
            .body()
            .tendons()
            .iter()
            .position(|t| t.past_capacity(&pose.cm, &pose.frame, -AT_CAPACITY))
        {
            self.sim = self.sim.with_body(self.sim.body().tendon_broken(k));
            o.anchors_broken.push(AnchorBreak { anchor: k, t_s: t });
            broke = true;
        }
        broke
    }

    /// Breaks every tendon that has reached its capacity at the current state, each booked in
    /// the logbook, and evaluates the state again without them. Whether any broke.
    pub(super) fn break_tendons(
        &mut self,
        finder: &mut PoseFinder<'_>,
        o: &mut Log<'_>,
    ) -> Result<bool, Ending> {
        let pose = self.ev.pose;
        let broke = self.break_tendons_at(&pose, self.t, o);
        if broke {
            let hold = Hold::of(&self.ev.motion);
            self.ev = evaluate(&self.sim, finder, &self.y, hold).map_err(Ending::Failed)?;
        }
        Ok(broke)
    }
}
