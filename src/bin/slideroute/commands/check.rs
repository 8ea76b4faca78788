//! `slideroute check`: each load case against its guideline — the tables, `check.csv`,
//! `check.json`, `report.html` (a page to hand in), and the route of every case that fails in
//! `case-N/`.

use super::{load, warn_all};
use crate::cli::CheckArgs;
use crate::exit::{CliError, bad_input, failed, interrupted, out, outln, output_error};
use slideroute::check::{check_cases_until, design_anchors};
use slideroute::output::{CheckFiles, OutputError, OutputFolder};

/// Runs `slideroute check`.
pub fn check(args: &CheckArgs) -> Result<(), CliError> {
    let scene = load(&args.scene)?;
    let folder = OutputFolder::open(&args.out, "check").map_err(output_error)?;
    let results = check_cases_until(&scene, |_| (), interrupted).map_err(bad_input)?;
    if interrupted() {
        // A check is filed whole: nothing of a partial one is written.
        let done = results
            .iter()
            .filter(|r| r.run.route.termination.reason != slideroute::Reason::Interrupted)
            .count();
        return Err(failed(format!(
            "interrupted: the check stopped after {done} of {} cases; nothing was written",
            scene.cases().len().max(1)
        )));
    }
    let design = if args.design_anchors {
        Some(design_anchors(&scene).map_err(bad_input)?)
    } else {
        None
    };
    let mut files = CheckFiles::new(&scene, &results)
        .pictures(!args.no_plots)
        .view(!args.no_3d);
    if let Some(d) = &design {
        files = files.anchor_design(d);
    }
    let written = files.write(folder, interrupted).map_err(|e| match e {
        // The failing cases' routes written so far are not the check's files.
        OutputError::Interrupted { what, .. } => failed(what),
        e => output_error(e),
    })?;
    warn_all(&written.warnings);
    if !args.quiet {
        out!("{}", files.table());
        let names: Vec<String> = written
            .files
            .iter()
            .map(|p| p.display().to_string())
            .collect();
        outln!("  wrote {}", names.join(", "));
    }
    Ok(())
}
