//! What a route's loop produces, whatever the dynamics: the rows (streamed to a sink, a bounded
//! number kept), how the route ended, the quantities every route gathers along it, and the
//! model's own report (of a type the model names: the logbook knows none of them).

use super::row::Row;
use super::termination::{Reason, Termination};
use crate::mechanics::static_friction::{FactorOfSafety, YieldAcceleration};

/// What a route's loop produced (any dynamics), before the diagnostics are added. Rows go
/// through [`Logbook::push`]: each to the sink, if any (streamed as computed), and every
/// `keep_every`-th (and the last) kept in `rows`. `R` is what the model adds to its route, its
/// report (`Dynamics::Report`), filled in by the model as the route goes.
///
/// The logbook passes through every increment by value (`Dynamics::advance` takes it and gives
/// it back, or ends the route with it), so its contents are boxed: a move is a pointer's, not
/// the 864 bytes of its rows and reports (about a tenth of a default run's instructions were
/// such copies).
pub(super) struct Logbook<'s, R>(Box<Book<'s, R>>);

/// Where a route's rows go as they are made (streamed), beside those the logbook keeps.
pub(super) type Sink<'s> = &'s mut dyn FnMut(&Row);

/// The contents of a [`Logbook`], reached through it.
pub(super) struct Book<'s, R> {
    rows: Vec<Row>,
    sink: Option<Sink<'s>>,
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
    /// With a ground-motion record, the yield acceleration at the start, where the model gives
    /// one.
    pub yield_acceleration: Option<YieldAcceleration>,
    pub travel: f64,
    pub increments: usize,
    /// The anchors' tendons broken so far.
    pub anchors_broken: Vec<super::AnchorBreak>,
    /// What the model adds to its route.
    pub report: R,
}

impl<'s, R> std::ops::Deref for Logbook<'s, R> {
    type Target = Book<'s, R>;
    fn deref(&self) -> &Book<'s, R> {
        &self.0
    }
}

impl<R> std::ops::DerefMut for Logbook<'_, R> {
    fn deref_mut(&mut self) -> &mut Self::Target {
        &mut self.0
    }
}

impl<'s, R: Default> Logbook<'s, R> {
    /// Nothing yet: ends at the time limit unless told otherwise, the model's report its
    /// default. Rows go to `sink` (if any) and every `keep_every`-th is kept.
    pub fn new(sink: Option<Sink<'s>>, keep_every: usize) -> Self {
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
            travel: 0.0,
            increments: 0,
            anchors_broken: Vec::new(),
            fs_limit: None,
            report: R::default(),
        }))
    }
}

impl<'s, R> Logbook<'s, R> {
    /// The same logbook, the model's report turned into `S` by `into` (once, at the route's
    /// end: the models' reports into one type).
    pub fn map_report<S>(self, into: impl FnOnce(R) -> S) -> Logbook<'s, S> {
        let b = *self.0;
        Logbook(Box::new(Book {
            rows: b.rows,
            sink: b.sink,
            keep_every: b.keep_every,
            pushed: b.pushed,
            last: b.last,
            first: b.first,
            termination: b.termination,
            fs: b.fs,
            fs_limit: b.fs_limit,
            yield_acceleration: b.yield_acceleration,
            travel: b.travel,
            increments: b.increments,
            anchors_broken: b.anchors_broken,
            report: into(b.report),
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
