//! `slideroute sweep`: every combination of the varied keys, in parallel (the library's
//! `slideroute::sweep`), written as `sweep.csv`, drawn as `sweep.svg` and in 3-D as
//! `sweep.html` (every combination's CM path over the ground): `slideroute::output::SweepFiles`.

use super::{load_with, progress_bar, warn_all};
use crate::cli::SweepArgs;
use crate::exit::{CliError, bad_input, interrupted, many_interrupted_after, outln, output_error};
use slideroute::output::{OutputFolder, SweepFiles};
use slideroute::sweep::{Sweep, Vary};

/// Runs `slideroute sweep`.
pub fn sweep(args: &SweepArgs) -> Result<(), CliError> {
    // The base scene must itself be valid.
    let base = load_with(&args.scene, args.dynamics)?;
    let varies = args
        .vary
        .iter()
        .map(|v| v.parse::<Vary>())
        .collect::<Result<Vec<_>, _>>()
        .map_err(|e| bad_input(format!("--vary {e}")))?;
    let sweep = Sweep::new(&base, varies).map_err(|e| bad_input(format!("--vary {e}")))?;
    let n = sweep.count();
    let folder = OutputFolder::open(&args.out, "sweep").map_err(output_error)?;
    let bar = progress_bar(args.quiet, n as u64, "sweep", "combinations");
    let written = SweepFiles::new(&base, &sweep)
        .pictures(!args.no_plots)
        .view(!args.no_3d)
        .write(folder, || bar.inc(1), interrupted);
    bar.finish_and_clear();
    let (written, counts) = written.map_err(output_error)?;
    warn_all(&written.warnings);
    if interrupted() {
        return Err(many_interrupted_after("combinations", &written.files));
    }
    if !args.quiet {
        let summary: Vec<String> = counts.iter().map(|(k, v)| format!("{v} × {k}")).collect();
        let plural = if n == 1 { "" } else { "s" };
        outln!("{n} combination{plural}: {}", summary.join(", "));
        let names: Vec<String> = written
            .files
            .iter()
            .map(|p| p.display().to_string())
            .collect();
        outln!("wrote {}", names.join(", "));
    }
    Ok(())
}
