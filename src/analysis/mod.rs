//! Runs of routes from scenes: one route ([`run`]), and the one runner of many routes
//! (`runner.rs`) behind a sweep of scene keys (`sweep.rs`), a probabilistic analysis
//! (`probabilistic/`), a check of load cases against their guideline (`check.rs`), and the two
//! dynamics side by side (`compare.rs`). The command line and Python call these alike.

pub mod anchor_design;
pub mod check;
pub mod compare;
pub mod gravity_method;
pub mod probabilistic;
mod run;
pub mod runner;
pub mod sweep;

pub use run::{run, run_observed};
