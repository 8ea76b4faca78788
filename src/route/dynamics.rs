//! What a dynamics model is to the route: how the block starts, how it advances by one
//! increment, the row of its state, and what it adds to the route's end. The driver
//! (`driver.rs`) owns everything else — the increments and the exact end at t_end, the stride,
//! progress and interruption, the time limit, the factor of safety. The paper's dynamics
//! (`paper/`) and the rigid body's (`rigid/`) implement it; a third model is one new module and
//! one arm in `simulate.rs`.

use super::logbook::Logbook;
use super::pose_finder::PoseFinder;
use super::row::Row;
use crate::model::Simulation;

/// How a start came out: the block moves (the model, ready to advance), or the route ended at
/// t = 0 (it does not slide, or cannot be started), its row and reason in the logbook.
pub(super) enum Start<'s, M> {
    Moving(M, Logbook<'s>),
    Ended(Logbook<'s>),
}

/// How an increment came out: go on, or the route ended within it (an event the model decided:
/// a stop, a contact leaving its plane, …), its last row and reason in the logbook.
pub(super) enum Flow<'s> {
    Go(Logbook<'s>),
    Ended(Logbook<'s>),
}

/// One dynamics model.
pub(super) trait Dynamics<'a>: Sized {
    /// The start at t = 0 from the simulation's initial motion, its first row pushed.
    fn start<'s>(
        sim: &'a Simulation,
        finder: &mut PoseFinder<'_>,
        o: Logbook<'s>,
    ) -> Start<'s, Self>;

    /// Advances increment `k` to `t_to` (rows of events within it pushed as they happen).
    fn advance<'s>(
        &mut self,
        finder: &mut PoseFinder<'_>,
        k: usize,
        t_to: f64,
        o: Logbook<'s>,
    ) -> Flow<'s>;

    /// The row of the current state.
    fn row(&self) -> Row;

    /// What the model adds when the driver ends the route (the time limit, an interruption).
    fn close(&self, _o: &mut Logbook<'_>) {}

    /// What the model adds to the way the route ended, however it ended (the factor of safety
    /// known): where the model itself, not the physics, ends the route, the detail says so.
    fn explain_end(_o: &mut Logbook<'_>) {}
}
