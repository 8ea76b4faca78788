//! `slideroute report`: error against run time over ladders of dt, and the stiff and extreme
//! cases (`report/`), written as `work-precision.csv`, `.md` and `.svg`.

use super::progress_bar;
use crate::cli::ReportArgs;
use crate::exit::{CliError, failed, interrupted, outln};
use crate::output::folder::Folder;
use std::ops::ControlFlow;

/// Runs `slideroute report`.
pub fn report(args: &ReportArgs) -> Result<(), CliError> {
    let quick = args.quick;
    let bar = progress_bar(
        args.quiet,
        crate::report::point_count(quick) as u64,
        "report",
        "routes",
    );
    let (points, references) = crate::report::work_precision(quick, || {
        bar.inc(1);
        if interrupted() {
            ControlFlow::Break(())
        } else {
            ControlFlow::Continue(())
        }
    })
    .map_err(failed)?;
    bar.finish_and_clear();
    let extreme = crate::report::extreme(if quick { 20 } else { 200 }).map_err(failed)?;
    let mut folder = Folder::open(&args.out, "report").map_err(failed)?;
    let csv_path = folder
        .write_with("work-precision.csv", |tmp| {
            let file = std::fs::File::create(tmp)
                .map_err(|e| format!("{}: cannot write: {e}", tmp.display()))?;
            crate::output::report_files::write_csv(file, &points)
                .map_err(|e| format!("work-precision.csv: {e}"))
        })
        .map_err(failed)?;
    let md = crate::output::report_files::markdown(&points, &references, &extreme, quick);
    let md_path = folder
        .write_bytes("work-precision.md", md.as_bytes())
        .map_err(failed)?;
    #[allow(unused_mut)]
    let mut written = vec![csv_path, md_path];
    #[cfg(feature = "plots")]
    if !args.no_plots {
        written.push(
            folder
                .write_with("work-precision.svg", |tmp| {
                    crate::output::plots::work_precision(tmp, &points)
                })
                .map_err(failed)?,
        );
    }
    folder.finish().map_err(failed)?;
    if !args.quiet {
        for r in &references {
            outln!(
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
            );
        }
        let names: Vec<String> = written.iter().map(|p| p.display().to_string()).collect();
        outln!(
            "{} points, {} extreme cases; wrote {}",
            points.len(),
            extreme.len(),
            names.join(", ")
        );
    }
    Ok(())
}
