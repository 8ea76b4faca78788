//! `slideroute run`: one route, its rows streamed to route.csv as they are computed, then its
//! pictures and summary.json; `--compare-dynamics` is `compare.rs`.

use super::{ROUTE_STEPS, load, route_bar, stream_route_csv, write_route_folder};
use crate::cli::RunArgs;
use crate::exit::{CliError, bad_input, failed, interrupted, interrupted_after, out};
use crate::output::folder::Folder;
use crate::output::summary::RouteSummary;
use slideroute::{Reason, Scene};
use std::ops::ControlFlow;

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
    let csv_path = stream_route_csv(&mut folder, "route.csv", &sim, progress);
    bar.finish_and_clear();
    let (csv_path, computed) = csv_path.map_err(failed)?;
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
