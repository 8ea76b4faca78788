//! `slideroute run`: one route, its rows streamed to route.csv as they are computed, then its
//! pictures and summary.json; `--compare-dynamics` is `compare.rs`.

use super::{ROUTE_STEPS, load, route_bar, warn_all};
use crate::cli::RunArgs;
use crate::exit::{CliError, bad_input, interrupted, interrupted_after, out, output_error};
use slideroute::output::{OutputFolder, RouteFiles};
use slideroute::{Contacts, Integrator, Reason, RunSettings, Scene};
use std::ops::ControlFlow;

/// Runs `slideroute run`.
pub fn run(args: &RunArgs) -> Result<(), CliError> {
    if args.compare_dynamics {
        return super::compare::compare(args);
    }
    let scene = with_dynamics(load(&args.scene)?, args)?;
    let sim = scene.simulation().map_err(bad_input)?;
    if let Some(w) = many_rows(sim.settings()) {
        eprintln!("slideroute: warning: {w}");
    }
    // Locked before the work, so that a second run into the same folder is refused at once.
    let mut folder = OutputFolder::open(&args.out_dir(), "run").map_err(output_error)?;
    let bar = route_bar(args.quiet, sim.settings().t_end);
    let progress = |f: f64| {
        bar.set_position((f * ROUTE_STEPS as f64) as u64);
        if interrupted() {
            ControlFlow::Break(())
        } else {
            ControlFlow::Continue(())
        }
    };
    let route_files = RouteFiles::new(&scene)
        .pictures(!args.no_plots)
        .view(!args.no_3d);
    let csv_path = route_files.stream(&mut folder, &sim, progress);
    bar.finish_and_clear();
    let (csv_path, computed) = csv_path.map_err(output_error)?;
    let written = route_files.write(folder, &computed).map_err(output_error)?;
    warn_all(&written.warnings);
    let files: Vec<_> = std::iter::once(csv_path).chain(written.files).collect();
    let route = &computed.route;
    if route.termination.reason == Reason::Interrupted {
        return Err(interrupted_after(&route.termination.detail, &files));
    }
    if !args.quiet {
        out!("{}", computed.summary(&files));
    }
    Ok(())
}

/// Rows of route.csv past which a run says how large the file may grow.
const MANY_ROWS: f64 = 1e6;

/// About one row of route.csv (bytes): 25 columns, most of them numbers to 17 digits.
const ROW_BYTES: f64 = 330.0;

/// What a run recording more than [`MANY_ROWS`] rows says before it starts: how many and how
/// large route.csv may grow (a route that ends earlier writes fewer), and where the steps are
/// chosen against `solver.tolerance` (RK4 on the three points), that `dt_s` is the rows'
/// interval only: a smaller one adds rows, not accuracy.
fn many_rows(s: &RunSettings) -> Option<String> {
    let rows = (s.t_end / s.dt / s.stride as f64).floor() + 1.0;
    if rows <= MANY_ROWS {
        return None;
    }
    let only_rows = if s.contacts == Contacts::Frame && s.integrator == Integrator::Rk4 {
        " (the steps are chosen against solver.tolerance: a smaller dt_s adds rows, not \
         accuracy)"
    } else {
        ""
    };
    Some(format!(
        "solver.dt_s: up to {rows:.2e} rows of route.csv, about {:.1} GB{only_rows}; \
         solver.stride = N keeps every N-th",
        rows * ROW_BYTES / 1e9
    ))
}

/// The scene with `--dynamics`'s model, saying so where that changes the scene's integrator
/// (each dynamics takes its own).
fn with_dynamics(scene: Scene, args: &RunArgs) -> Result<Scene, CliError> {
    let Some(model) = args.dynamics else {
        return Ok(scene);
    };
    let before = scene.settings().map(|s| (s.integrator, s.dynamics));
    // Whether the scene's file names its integrator, or took its dynamics' default.
    let written = scene
        .document()
        .get("solver")
        .and_then(|s| s.get("integrator"))
        .is_some();
    let scene = scene.with_dynamics(model).map_err(bad_input)?;
    if let (Some((b, was)), Some(after)) = (before, scene.settings().map(|s| s.integrator))
        && b != after
    {
        let whose = if written {
            "the scene's".to_string()
        } else {
            format!("the {was} dynamics' default")
        };
        eprintln!(
            "slideroute: note: --dynamics {model} integrates with \"{after}\" (its own \
                 default), not {whose} \"{b}\""
        );
    }
    Ok(scene)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn settings(keys: &[(&str, toml::Value)]) -> RunSettings {
        let mut scene = Scene::default_scene();
        for (k, v) in keys {
            scene = scene.with(k, v.clone()).unwrap();
        }
        *scene.settings().unwrap()
    }

    #[test]
    fn a_run_of_millions_of_rows_says_how_large_route_csv_may_grow() {
        // Before: `--set solver.dt_s=2e-7` wrote a 7 GB route.csv without a word.
        assert_eq!(many_rows(&settings(&[])), None);
        let fine = many_rows(&settings(&[("solver.dt_s", 2e-7.into())])).unwrap();
        // The default scene's 20 s at 2·10⁻⁷ s: 10⁸ rows and one, about 33 GB.
        assert!(
            fine.contains("1.00e8 rows") && fine.contains("33.0 GB"),
            "{fine}"
        );
        assert!(fine.contains("not accuracy"), "{fine}");
        // A stride thins them below the line.
        let strided = [("solver.dt_s", 2e-7.into()), ("solver.stride", 1000.into())];
        assert_eq!(many_rows(&settings(&strided)), None);
        // The paper's own update steps by dt_s: its rows are its steps.
        let paper = settings(&[
            ("solver.dt_s", 1e-5.into()),
            ("solver.dynamics", "paper".into()),
        ]);
        let paper = many_rows(&paper).unwrap();
        assert!(
            paper.contains("2.00e6 rows") && !paper.contains("accuracy"),
            "{paper}"
        );
    }

    #[test]
    fn a_row_of_route_csv_is_about_the_size_the_warning_counts() {
        // The default scene's route written as route.csv is: its bytes a row within a fifth of
        // ROW_BYTES (a run of dt_s = 2·10⁻⁷ s wrote 7.07 GB in 21.8 M rows, 324 bytes a row).
        let route = slideroute::run(&Scene::default_scene()).unwrap();
        let mut csv = slideroute::output::RouteCsv::new(Vec::new()).unwrap();
        for r in &route.rows {
            csv.push(r);
        }
        let bytes = csv.finish().unwrap();
        assert!(route.rows.len() > 1000, "{}", route.rows.len());
        let per_row = bytes.len() as f64 / route.rows.len() as f64;
        assert!(
            (per_row / ROW_BYTES - 1.0).abs() < 0.2,
            "{per_row} bytes a row"
        );
    }
}
