//! What a dynamics model is to the route (issue #14): how the block starts, how it advances by
//! one increment, and the row of its state. The driver (`driver.rs`) owns everything else —
//! the increments and the exact end at t_end, the stride, progress and interruption, the time
//! limit. The paper's dynamics (`paper.rs`) and the rigid body's (`rigid/`) implement it; a
//! third model is one new file and one arm in `run.rs`.

use super::outcome::Outcome;
use super::pose_finder::PoseFinder;
use super::state::Row;
use crate::scene::{Scene, Simulation};

/// How a start came out: the block moves (the model, ready to advance), or the route ended at
/// t = 0 (it does not slide, or cannot be started), its row and reason in the outcome.
pub(super) enum Start<'s, M> {
    Moving(M, Outcome<'s>),
    Ended(Outcome<'s>),
}

/// How an increment came out: go on, or the route ended within it (an event the model decided:
/// a stop, a contact leaving its plane, …), its last row and reason in the outcome.
pub(super) enum Flow<'s> {
    Go(Outcome<'s>),
    Ended(Outcome<'s>),
}

/// One dynamics model.
pub(super) trait Dynamics<'a>: Sized {
    /// The start at t = 0 from the scene's `[initial]` state, its first row pushed.
    fn start<'s>(
        scene: &'a Scene,
        sections: &'a Simulation,
        finder: &mut PoseFinder<'_>,
        o: Outcome<'s>,
    ) -> Start<'s, Self>;

    /// Advances increment `k` to `t_to` (rows of events within it pushed as they happen).
    fn advance<'s>(
        &mut self,
        finder: &mut PoseFinder<'_>,
        k: usize,
        t_to: f64,
        o: Outcome<'s>,
    ) -> Flow<'s>;

    /// The row of the current state.
    fn row(&self) -> Row;

    /// What the model adds when the driver ends the route (the time limit, an interruption).
    fn close(&self, _o: &mut Outcome<'_>) {}
}
