//! The work–precision report: error of the route against run time for each method, mode and
//! integrator of the paper's dynamics over a ladder of increments, and for the rigid body (the
//! default dynamics: exact mode, RK4, continuation) over a ladder of tolerances; and the stiff
//! and extreme cases.
//!
//! The ladders and the points they give are in `ladder.rs`, the stiff and extreme cases in
//! `extreme.rs`; `files.rs` writes them, with the picture drawn in `plots/work_precision.rs`.

mod extreme;
mod files;
pub(super) mod ladder;

use super::{OutputError, OutputFolder, Written};
use extreme::{ExtremeRow, extreme};
use ladder::{INTERRUPTED, Point, Reference, point_count, work_precision};
use std::fmt;
use std::ops::ControlFlow;
use std::path::PathBuf;

/// The work–precision report, as `slideroute report` measures and writes it: the error of the
/// route against its run time for each pose method, mode and integrator of the paper's dynamics
/// over a ladder of increments, and for the rigid body over a ladder of tolerances, each
/// against its own reference; and the stiff and extreme cases. Its files are
/// `work-precision.csv`, `work-precision.md` and, with the pictures, `work-precision.svg`.
///
/// ```no_run
/// use slideroute::output::{OutputFolder, WorkPrecision};
/// let report = WorkPrecision::measure(true, || std::ops::ControlFlow::Continue(()))?;
/// let written = report.write(OutputFolder::open("report".as_ref(), "report")?, true)?;
/// print!("{}", report.summary(&written.files));
/// # Ok::<(), slideroute::output::OutputError>(())
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct WorkPrecision {
    points: Vec<Point>,
    references: Vec<Reference>,
    extreme: Vec<ExtremeRow>,
    quick: bool,
}

impl WorkPrecision {
    /// How many routes [`WorkPrecision::measure`] times (each series' ladder on each scene),
    /// `quick` or not: the length of a progress bar.
    pub fn routes(quick: bool) -> usize {
        point_count(quick)
    }

    /// Measures the report: `quick`, three steps of each ladder and three repeats (under a
    /// minute), else six and seven; then the extreme cases. `progress` is called after each
    /// route timed; when it answers `Break`, the report stops ([`OutputError::Interrupted`]): a
    /// report half measured is not written.
    pub fn measure(
        quick: bool,
        progress: impl Fn() -> ControlFlow<()>,
    ) -> Result<WorkPrecision, OutputError> {
        let (points, references) = work_precision(quick, progress).map_err(|e| {
            if e == INTERRUPTED {
                OutputError::Interrupted {
                    what: e,
                    written: Vec::new(),
                }
            } else {
                OutputError::Write(e)
            }
        })?;
        let extreme = extreme(if quick { 20 } else { 200 })?;
        Ok(WorkPrecision {
            points,
            references,
            extreme,
            quick,
        })
    }

    /// Writes `work-precision.csv`, `work-precision.md` and (with `pictures`, where the library
    /// draws them) `work-precision.svg` into `folder`, and finishes it.
    pub fn write(&self, folder: OutputFolder, pictures: bool) -> Result<Written, OutputError> {
        let WorkPrecision {
            points,
            references,
            extreme,
            quick,
        } = self;
        files::write(folder, (points, references, extreme), *quick, pictures)
    }

    /// What `slideroute report` prints: how each reference was established, how many points
    /// and extreme cases were measured, and the files written.
    pub fn summary<'a>(&'a self, files: &'a [PathBuf]) -> impl fmt::Display + 'a {
        Summary {
            report: self,
            files,
        }
    }
}

/// [`WorkPrecision::summary`].
struct Summary<'a> {
    report: &'a WorkPrecision,
    files: &'a [PathBuf],
}

impl fmt::Display for Summary<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        for r in &self.report.references {
            writeln!(
                f,
                "reference {}, {} dynamics: {}, change at {} {:.1e} m (bound {:.0e} m)",
                r.scene,
                r.dynamics,
                r.tolerance
                    .map_or(format!("dt {:.4e} s", r.dt_s), |t| format!(
                        "tolerance {t:.0e}, rows every {:.4e} s",
                        r.dt_s
                    )),
                if r.tolerance.is_some() {
                    "tolerance/10"
                } else {
                    "dt/2"
                },
                r.change_m,
                r.bound_m
            )?;
        }
        let names: Vec<String> = self.files.iter().map(|p| p.display().to_string()).collect();
        writeln!(
            f,
            "{} points, {} extreme cases; wrote {}",
            self.report.points.len(),
            self.report.extreme.len(),
            names.join(", ")
        )
    }
}

#[cfg(test)]
mod extreme_tests;
