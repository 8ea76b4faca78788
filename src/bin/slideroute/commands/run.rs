//! `slideroute run`: one route, its rows streamed to route.csv as they are computed, then its
//! pictures and summary.json; `--compare-dynamics` is `compare.rs`.

use super::{ROUTE_STEPS, load, route_bar, write_route_folder};
use crate::cli::RunArgs;
use crate::exit::{CliError, bad_input, failed, interrupted, interrupted_after, out};
use crate::output::folder::Folder;
use crate::output::route_files::CsvRows;
use crate::output::summary::RouteSummary;
use slideroute::{Reason, Runner, Scene};
use std::ops::ControlFlow;

/// The most rows a route keeps for its pictures and summary, whatever its length (the rest go
/// to route.csv only): memory does not grow with the route.
const KEPT_ROWS: f64 = 4000.0;

/// Runs `slideroute run`.
pub fn run(args: &RunArgs) -> Result<(), CliError> {
    if args.compare_dynamics {
        return super::compare::compare(args);
    }
    let scene = with_dynamics(load(&args.scene)?, args)?;
    let sim = scene.simulation().map_err(bad_input)?;
    // Locked before the work, so that a second run into the same folder is refused at once.
    let mut folder = Folder::open(&args.out_dir(), "run").map_err(failed)?;
    let bar = route_bar(args.quiet, sim.settings().t_end);
    let progress = |f: f64| {
        bar.set_position((f * ROUTE_STEPS as f64) as u64);
        if interrupted() {
            ControlFlow::Break(())
        } else {
            ControlFlow::Continue(())
        }
    };
    let settings = sim.settings();
    let rows = (settings.t_end / settings.dt).ceil() / settings.stride as f64;
    let keep_every = (rows / KEPT_ROWS).ceil().max(1.0) as usize;
    let mut computed = None;
    let csv_path = folder.write_with("route.csv", |tmp| {
        let file = std::fs::File::create(tmp)
            .map_err(|e| format!("{}: cannot write: {e}", tmp.display()))?;
        let mut rows = CsvRows::new(file).map_err(|e| format!("route.csv: {e}"))?;
        let run = Runner::new(&sim)
            .progress(progress)
            .stream(keep_every, |r| rows.push(r))
            .run();
        computed = Some(run);
        rows.finish().map_err(|e| format!("route.csv: {e}"))
    });
    bar.finish_and_clear();
    let csv_path = csv_path.map_err(failed)?;
    let computed = computed.ok_or_else(|| failed("route.csv: no route"))?;
    let mut files = vec![csv_path];
    files.extend(
        write_route_folder(folder, &scene, &computed, args.no_plots, args.no_3d).map_err(failed)?,
    );
    let route = &computed.route;
    if route.termination.reason == Reason::Interrupted {
        return Err(interrupted_after(&route.termination.detail, &files));
    }
    if !args.quiet {
        out!(
            "{}",
            RouteSummary {
                computed: &computed,
                files: &files
            }
        );
    }
    Ok(())
}

/// The scene with `--dynamics`'s model, saying so where that changes the scene's integrator
/// (each dynamics takes its own).
fn with_dynamics(scene: Scene, args: &RunArgs) -> Result<Scene, CliError> {
    let Some(model) = args.dynamics else {
        return Ok(scene);
    };
    let before = scene.settings().map(|s| s.integrator);
    let scene = scene.with_dynamics(model).map_err(bad_input)?;
    if let (Some(b), Some(after)) = (before, scene.settings().map(|s| s.integrator))
        && b != after
    {
        eprintln!(
            "slideroute: note: --dynamics {model} integrates with \"{after}\" (its own \
                 default), not the scene's \"{b}\""
        );
    }
    Ok(scene)
}
