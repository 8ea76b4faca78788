//! The dynamics models by name: the one place that picks a route's model from its settings, and
//! that knows what each model reports. Nothing else in the route names a model: the driver runs
//! any [`Dynamics`](super::dynamics::Dynamics), the logbook carries any report.
//!
//! The models' reports are an enum rather than a trait object: the models are a closed set
//! known where the settings name them (this file), the enum derives what a route needs of its
//! report (comparison, cloning, serialisation into summary.json) without erased serde or
//! downcasts, and a library user matches it to read a model's own numbers. A new model is one
//! variant here, one arm in [`drive`], and the few accessors below that its report answers.

use super::body::{FirstOrder, OnBase, Unmet};
use super::driver;
use super::energy::EnergyBalance;
use super::logbook::{Logbook, Sink};
use super::paper::Paper;
use super::pose_finder::PoseFinder;
use super::rigid::RigidBody;
use super::{Route, Steps};
use crate::model::{Contacts, DynamicsModel, Simulation};
use serde::Serialize;
use std::ops::ControlFlow;

pub use super::body::{BaseReport, Carrying, OVERTURN_DEG, OnBaseReport, Resting, pose_of_row};
pub use super::paper::PaperReport;
pub use super::rigid::RigidBodyReport;

/// What a route's dynamics model adds to it: each model's own report (its keys in summary.json
/// stand among the route's, as they are).
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(untagged)]
pub enum Report {
    /// The paper's dynamics (`[solver] dynamics = "paper"`).
    Paper(PaperReport),
    /// The rigid body on its three-point frame (`dynamics = "rigid-body"`).
    RigidBody(RigidBodyReport),
    /// The block on its whole base (`contacts = "base"`).
    OnBase(Box<OnBaseReport>),
}

impl Report {
    /// The energy balance, where the model keeps one (the rigid body's, the block on its base).
    pub fn energy(&self) -> Option<EnergyBalance> {
        match self {
            Report::Paper(_) => None,
            Report::RigidBody(r) => r.energy,
            Report::OnBase(r) => r.energy,
        }
    }

    /// The paper's resisting-over-driving ratio at the start (the paper's dynamics only).
    pub fn paper_ratio(&self) -> Option<f64> {
        match self {
            Report::Paper(r) => r.paper_ratio,
            _ => None,
        }
    }

    /// Where a block on its base rested, what carried it, how deep its base went.
    pub fn base(&self) -> Option<&BaseReport> {
        match self {
            Report::OnBase(r) => r.base.as_ref(),
            _ => None,
        }
    }

    /// The phases of a block on its base not held to the tolerance: those stepped by the
    /// time-stepping scheme alone (first order), and the steps taken over the tolerance at the
    /// shortest length (none for the other models).
    pub fn not_held(&self) -> (Option<FirstOrder>, Option<Unmet>) {
        match self {
            Report::OnBase(r) => (r.first_order, r.tolerance_unmet),
            _ => (None, None),
        }
    }

    /// How often the paper's frictional solution was lost and chosen afresh (none for the other
    /// models, which follow no such solution).
    pub fn friction_switches(&self) -> usize {
        match self {
            Report::Paper(r) => r.friction_switches,
            _ => 0,
        }
    }

    /// The integration steps chosen against the tolerance, where any was taken or tried: the
    /// rigid body's, the block on its base's extrapolated steps, and the paper's dynamics' RK4
    /// substeps (none for the paper's own update).
    pub fn steps(&self) -> Option<Steps> {
        match self {
            Report::Paper(r) => r.steps.if_any(),
            Report::RigidBody(r) => r.steps.if_any(),
            Report::OnBase(r) => r.steps.if_any(),
        }
    }
}

impl Route {
    /// A block on its base (`contacts = "base"`): where it rested before any load, what carried
    /// it, and the deepest its base went into the ground.
    pub fn base(&self) -> Option<&BaseReport> {
        self.report.base()
    }
}

/// The route of `sim` under the model its settings pick — the block on its base whatever the
/// dynamics, else the paper's dynamics or the rigid body on its three-point frame — by the one
/// driver, rows to `sink` (every `keep_every`-th kept).
pub(super) fn drive<'s>(
    sim: &Simulation,
    finder: &mut PoseFinder<'_>,
    progress: impl FnMut(f64) -> ControlFlow<()>,
    sink: Option<Sink<'s>>,
    keep_every: usize,
) -> Logbook<'s, Report> {
    let settings = sim.settings();
    match (settings.contacts, settings.dynamics) {
        (Contacts::Base, _) => {
            let log = Logbook::new(sink, keep_every);
            driver::drive::<OnBase>(sim, finder, progress, log)
                .map_report(|r| Report::OnBase(Box::new(r)))
        }
        (Contacts::Frame, DynamicsModel::Paper) => {
            let log = Logbook::new(sink, keep_every);
            driver::drive::<Paper>(sim, finder, progress, log).map_report(Report::Paper)
        }
        (Contacts::Frame, DynamicsModel::RigidBody) => {
            let log = Logbook::new(sink, keep_every);
            driver::drive::<RigidBody>(sim, finder, progress, log).map_report(Report::RigidBody)
        }
    }
}
