//! `slideroute sweep`: every combination of the varied keys, in parallel (the library's
//! `slideroute::sweep`), written as `sweep.csv`, drawn as `sweep.svg` and in 3-D as
//! `sweep.html` (every combination's CM path over the ground).

use super::{load_with, progress_bar};
use crate::cli::SweepArgs;
use crate::exit::{CliError, bad_input, failed, interrupted, many_interrupted_after, outln};
use crate::output::folder::Folder;
use crate::output::sweep_files::SweepCsv;
use crate::output::view::many::MAX_FAN_PATHS;
use crate::sweep::SweepRow;
use slideroute::Outcome;
use slideroute::sweep::{Sweep, Vary};
use std::collections::BTreeMap;

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
    let mut folder = Folder::open(&args.out, "sweep").map_err(failed)?;
    let bar = progress_bar(args.quiet, n as u64, "sweep", "combinations");
    let varies = sweep.varies();
    // Each combination, as it comes, written to sweep.csv, counted, and what the picture shows
    // of it kept if it lies on a line the picture draws (in a temporary file in the staging
    // folder past a few MB); the first routes kept for the fan.
    #[cfg(feature = "plots")]
    let mut drawn =
        crate::output::plots::Drawn::new(varies, Some(folder.staging().map_err(failed)?));
    let mut counts: BTreeMap<String, usize> = BTreeMap::new();
    let mut routes = 0usize;
    let mut fan: Vec<Outcome> = Vec::new();
    let csv_path = folder
        .write_with("sweep.csv", |tmp| {
            let file = std::fs::File::create(tmp)
                .map_err(|e| format!("{}: cannot write: {e}", tmp.display()))?;
            let mut csv = SweepCsv::new(std::io::BufWriter::new(file), varies)
                .map_err(|e| format!("sweep.csv: {e}"))?;
            sweep.run_each(
                || bar.inc(1),
                interrupted,
                |ran| {
                    let row = SweepRow::from(&ran);
                    csv.push(&row).map_err(|e| format!("sweep.csv: {e}"))?;
                    *counts.entry(row.reason.clone()).or_default() += 1;
                    routes += usize::from(row.travel_m.is_some());
                    #[cfg(feature = "plots")]
                    if !args.no_plots {
                        drawn.add(&row).map_err(|e| format!("sweep picture: {e}"))?;
                    }
                    if fan.len() < MAX_FAN_PATHS && ran.outcome.route().is_some() {
                        fan.push(ran.outcome);
                    }
                    Ok::<(), String>(())
                },
            )?;
            csv.finish().map_err(|e| format!("sweep.csv: {e}"))
        })
        .map_err(failed)?;
    bar.finish_and_clear();
    let mut written = vec![csv_path];
    if !args.no_3d && !interrupted() {
        let (paths, _) = crate::output::view::many::cm_paths(&fan);
        let mut notes: Vec<String> = varies
            .iter()
            .map(|v| {
                let n = v.values.len();
                format!("{}: {n} value{}", v.key, if n == 1 { "" } else { "s" })
            })
            .collect();
        notes.push("the foundation is drawn as the base scene writes it".into());
        let page =
            crate::output::view::many::fan_page(&base, None, &paths, routes, "combinations", notes);
        written.extend(
            crate::output::view::many::write_page(&mut folder, "sweep.html", &page)
                .map_err(failed)?,
        );
    }
    #[cfg(feature = "plots")]
    if !args.no_plots {
        written.push(
            folder
                .write_with("sweep.svg", |tmp| {
                    crate::output::plots::sweep_drawn(tmp, varies, &drawn)
                })
                .map_err(failed)?,
        );
    }
    folder.finish().map_err(failed)?;
    if interrupted() {
        return Err(many_interrupted_after("combinations", &written));
    }
    if !args.quiet {
        let summary: Vec<String> = counts.iter().map(|(k, v)| format!("{v} × {k}")).collect();
        let plural = if n == 1 { "" } else { "s" };
        outln!("{n} combination{plural}: {}", summary.join(", "));
        let names: Vec<String> = written.iter().map(|p| p.display().to_string()).collect();
        outln!("wrote {}", names.join(", "));
    }
    Ok(())
}
