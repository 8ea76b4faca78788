//! What a dynamics model is to the route: how the block starts, how it advances by one
//! increment, the row of its state, what it reports, the measures it takes at the start, and
//! what it adds to the route's end. The driver (`driver.rs`) owns everything else — the
//! increments and the exact end at t_end, the stride, progress and interruption, the time
//! limit — and knows no model. The paper's dynamics (`paper/`), the rigid body's (`rigid/`) and
//! the block on its base (`body/`) implement it; another model is one new module and its arm
//! and report in `models.rs`.

use super::logbook::Logbook;
use super::pose_finder::PoseFinder;
use super::row::Row;
use crate::geometry::Pose;
use crate::model::Simulation;

/// How a start came out: the block moves (the model, ready to advance), or the route ended at
/// t = 0 (it does not slide, or cannot be started), its row and reason in the logbook.
pub(super) enum Start<'s, M, R> {
    Moving(M, Logbook<'s, R>),
    Ended(Logbook<'s, R>),
}

/// How an increment came out: go on, or the route ended within it (an event the model decided:
/// a stop, a contact leaving its plane, …), its last row and reason in the logbook.
pub(super) enum Flow<'s, R> {
    Go(Logbook<'s, R>),
    Ended(Logbook<'s, R>),
}

/// One dynamics model.
pub(super) trait Dynamics<'a>: Sized {
    /// What the model adds to its route (kept in the logbook as the route goes; one of
    /// `models::Report`'s variants at the end).
    type Report: Default;

    /// The start at t = 0 from the simulation's initial motion, its first row pushed.
    fn start<'s>(
        sim: &'a Simulation,
        finder: &mut PoseFinder<'_>,
        o: Logbook<'s, Self::Report>,
    ) -> Start<'s, Self, Self::Report>;

    /// Advances increment `k` to `t_to` (rows of events within it pushed as they happen).
    fn advance<'s>(
        &mut self,
        finder: &mut PoseFinder<'_>,
        k: usize,
        t_to: f64,
        o: Logbook<'s, Self::Report>,
    ) -> Flow<'s, Self::Report>;

    /// The row of the current state.
    fn row(&self) -> Row;

    /// What the model adds when the driver ends the route (the time limit, an interruption).
    fn close(&self, _o: &mut Logbook<'_, Self::Report>) {}

    /// The measures at the start the model's own start has left unknown, however the route went
    /// on: the factor of safety (and what limits it) and, under a ground-motion record, the
    /// yield acceleration, at `start`, the pose the route started from (none where it has
    /// none). By default none: a model that has them says so.
    fn at_start(_sim: &'a Simulation, _start: Option<&Pose>, _o: &mut Logbook<'_, Self::Report>) {}

    /// What the model adds to the way the route ended, however it ended (the factor of safety
    /// known): where the model itself, not the physics, ends the route, the detail says so.
    fn explain_end(_o: &mut Logbook<'_, Self::Report>) {}
}
