//! `slideroute roots`: every root of the pose system at one displacement, classified, the
//! physical one selected; or, with `--grid`, the same for every pose of a CSV file, on every
//! core, written in the file's order.

use super::{displacement, load, print_json};
use crate::cli::RootsArgs;
use crate::exit::{CliError, bad_input, failed, out};
use crate::output::{RootsReport, grid_csv};
use rayon::prelude::*;
use slideroute::internals::scene::input::open_bounded;
use slideroute::{Displacement, Mode, Scene};
use std::path::Path;

/// The largest grid of poses (bytes): some 300 000 rows.
const MAX_GRID_BYTES: u64 = 16 << 20;

/// Runs `slideroute roots`.
pub fn roots(args: &RootsArgs) -> Result<(), CliError> {
    let scene = load(&args.scene)?;
    let mode = args
        .mode
        .or(scene.settings().map(|s| s.mode))
        .unwrap_or(Mode::Exact);
    if let (Some(grid), Some(out)) = (&args.grid, &args.out) {
        return roots_grid(&scene, mode, grid, out);
    }
    let r = report(&scene, mode, displacement(&args.pose)?).map_err(bad_input)?;
    if args.json {
        print_json(&r)
    } else {
        out!("{r}");
        Ok(())
    }
}

/// Every root at `d`, as the report prints it.
fn report(scene: &Scene, mode: Mode, d: Displacement) -> Result<RootsReport, String> {
    slideroute::poses::solve_all(scene.site(), d, mode)
        .map(|all| RootsReport::new(scene, &all))
        .map_err(|e| e.to_string())
}

/// The report of every pose of the file `grid`, written to `out`.
fn roots_grid(scene: &Scene, mode: Mode, grid: &Path, out: &Path) -> Result<(), CliError> {
    let name = grid.display().to_string();
    let file = open_bounded(grid, MAX_GRID_BYTES).map_err(|e| bad_input(format!("{name}: {e}")))?;
    let poses = grid_csv::read_poses(file, &name).map_err(bad_input)?;
    // Every core, in the file's order.
    let reports = poses
        .par_iter()
        .map(|p| report(scene, mode, p.displacement()))
        .collect::<Result<Vec<_>, _>>()
        .map_err(bad_input)?;
    let out_name = out.display().to_string();
    let file =
        std::fs::File::create(out).map_err(|e| failed(format!("{out_name}: cannot write: {e}")))?;
    grid_csv::write_rows(file, &poses, &reports).map_err(|e| failed(format!("{out_name}: {e}")))?;
    eprintln!("slideroute: {} poses written to {out_name}", reports.len());
    Ok(())
}
