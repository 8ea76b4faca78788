//! What a route's loop produces, whatever the dynamics: the rows (streamed to a sink, a bounded
//! number kept), how the route ended, and the quantities gathered along it.

use super::row::Row;
use super::termination::{Reason, Termination};
use crate::mechanics::static_friction::{FactorOfSafety, YieldAcceleration};
use serde::Serialize;

/// Energy bookkeeping of a rigid-body route (J), from the start to its last state.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize)]
pub struct EnergyBalance {
    /// Work of the applied loads other than gravity's pull: the water's force and its couples,
    /// the pseudo-static and a record's inertial forces, the anchors' tendons.
    pub work_hydraulic_j: f64,
    /// Work of friction (≤ 0).
    pub work_friction_j: f64,
    /// Kinetic energy at the end.
    pub kinetic_j: f64,
    /// Kinetic energy at the start (0 unless the scene's `[initial]` sets the block moving).
    pub kinetic_initial_j: f64,
    /// Change of potential energy m g ΔY_cm.
    pub potential_change_j: f64,
    /// W_h + W_f − (kinetic − initial kinetic + potential change): zero up to the integrator's
    /// error.
    pub residual_j: f64,
}

/// What a route's loop produced (either dynamics), before the diagnostics are added. Rows go
/// through [`Logbook::push`]: each to the sink, if any (streamed as computed), and every
/// `keep_every`-th (and the last) kept in `rows`.
///
/// The logbook passes through every increment by value (`Dynamics::advance` takes it and gives
/// it back, or ends the route with it), so its contents are boxed: a move is a pointer's, not
/// the 864 bytes of its rows and reports (about a tenth of a default run's instructions were
/// such copies).
pub(super) struct Logbook<'s>(Box<Book<'s>>);

/// The contents of a [`Logbook`], reached through it.
pub(super) struct Book<'s> {
    rows: Vec<Row>,
    sink: Option<&'s mut dyn FnMut(&Row)>,
    keep_every: usize,
    pushed: usize,
    last: Option<Row>,
    /// The first row pushed.
    first: Option<Row>,
    pub termination: Termination,
    /// The factor of safety at the start (the friction cones' definition).
    pub fs: Option<FactorOfSafety>,
    /// What limits it: sliding or tipping.
    pub fs_limit: Option<crate::mechanics::static_friction::Limit>,
    /// The paper's resisting-over-driving ratio at the start (paper's dynamics).
    pub paper_ratio: Option<f64>,
    /// With a ground-motion record on the three-point frame, the yield acceleration at the
    /// start.
    pub yield_acceleration: Option<YieldAcceleration>,
    pub travel: f64,
    pub increments: usize,
    /// How often the paper's frictional solution was chosen afresh (paper's dynamics).
    pub switches: usize,
    /// The rigid body's integration steps: taken, and tried and shortened.
    pub steps: (usize, usize),
    /// The recorded rows within the rigid body's steps that were interpolated
    /// (`route/rigid/rows.rs`), not evaluated.
    pub interpolated: usize,
    /// The energy balance (rigid-body dynamics).
    pub energy: Option<EnergyBalance>,
    /// A block on its base: where it rested, what carried it, how deep its base went.
    pub base: Option<super::body::report::BaseReport>,
    /// The anchors' tendons broken so far.
    pub anchors_broken: Vec<super::AnchorBreak>,
}

impl<'s> std::ops::Deref for Logbook<'s> {
    type Target = Book<'s>;
    fn deref(&self) -> &Book<'s> {
        &self.0
    }
}

impl std::ops::DerefMut for Logbook<'_> {
    fn deref_mut(&mut self) -> &mut Self::Target {
        &mut self.0
    }
}

impl<'s> Logbook<'s> {
    /// Nothing yet: ends at the time limit unless told otherwise. Rows go to `sink` (if any)
    /// and every `keep_every`-th is kept.
    pub fn new(sink: Option<&'s mut dyn FnMut(&Row)>, keep_every: usize) -> Self {
        Logbook(Box::new(Book {
            rows: Vec::new(),
            sink,
            keep_every: keep_every.max(1),
            pushed: 0,
            last: None,
            first: None,
            termination: Termination {
                reason: Reason::TimeLimit,
                t_s: 0.0,
                detail: String::new(),
            },
            fs: None,
            yield_acceleration: None,
            paper_ratio: None,
            travel: 0.0,
            increments: 0,
            switches: 0,
            steps: (0, 0),
            interpolated: 0,
            energy: None,
            base: None,
            anchors_broken: Vec::new(),
            fs_limit: None,
        }))
    }

    /// The route ends for `reason` at `t`, its last state `last` recorded as the last row
    /// whatever the stride.
    pub fn finish(mut self, last: Row, reason: Reason, t: f64, detail: String) -> Self {
        if self.last.is_none_or(|r| r.t_s != last.t_s) {
            self.push(last);
        }
        self.end(reason, t, detail)
    }

    /// One row of the route: to the sink, and kept if it is a `keep_every`-th.
    pub fn push(&mut self, row: Row) {
        if let Some(sink) = self.sink.as_mut() {
            sink(&row);
        }
        if self.pushed.is_multiple_of(self.keep_every) {
            self.rows.push(row);
        }
        self.pushed += 1;
        self.last = Some(row);
        self.first.get_or_insert(row);
    }

    /// The first row pushed.
    pub fn first_row(&self) -> Option<Row> {
        self.first
    }

    /// The last row pushed.
    pub fn last_row(&self) -> Option<Row> {
        self.last
    }

    /// The kept rows, the last row always among them (taken out of the logbook).
    pub fn take_rows(&mut self) -> Vec<Row> {
        if let Some(last) = self.last
            && self.rows.last().is_none_or(|r| r.t_s != last.t_s)
        {
            self.rows.push(last);
        }
        std::mem::take(&mut self.rows)
    }

    /// The route ends for `reason` at `t`.
    pub fn end(mut self, reason: Reason, t: f64, detail: String) -> Self {
        self.termination = Termination {
            reason,
            t_s: t,
            detail,
        };
        self
    }
}
