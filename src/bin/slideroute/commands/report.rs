//! `slideroute report`: error against run time over ladders of dt, and the stiff and extreme
//! cases, written as `work-precision.csv`, `.md` and `.svg` (`slideroute::output::WorkPrecision`).

use super::progress_bar;
use crate::cli::ReportArgs;
use crate::exit::{CliError, interrupted, out, output_error};
use slideroute::output::{OutputFolder, WorkPrecision};
use std::ops::ControlFlow;

/// Runs `slideroute report`.
pub fn report(args: &ReportArgs) -> Result<(), CliError> {
    let quick = args.quick;
    let bar = progress_bar(
        args.quiet,
        WorkPrecision::routes(quick) as u64,
        "report",
        "routes",
    );
    let report = WorkPrecision::measure(quick, || {
        bar.inc(1);
        if interrupted() {
            ControlFlow::Break(())
        } else {
            ControlFlow::Continue(())
        }
    });
    bar.finish_and_clear();
    let report = report.map_err(output_error)?;
    let folder = OutputFolder::open(&args.out, "report").map_err(output_error)?;
    let written = report.write(folder, !args.no_plots).map_err(output_error)?;
    if !args.quiet {
        out!("{}", report.summary(&written.files));
    }
    Ok(())
}
