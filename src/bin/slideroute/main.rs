//! The `slideroute` command line: parses, calls the library, prints.

mod output;
mod probabilistic;
mod report;
mod sweep;

use crate::output::{CoeffReport, RootsReport, grid_csv};
use clap::{Args, Parser, Subcommand};
use rayon::prelude::*;
use slideroute::stages::geometry::Displacement;
use slideroute::stages::roots;
use slideroute::stages::scene::{DynamicsModel, Mode, Scene, SceneErrorKind};
use std::path::PathBuf;
use std::process::ExitCode;
use std::sync::atomic::{AtomicBool, Ordering};

/// Three-dimensional failure route of a sliding dam monolith (after Galic & Glaser).
///
/// Units: metres, newtons, seconds; angles in degrees on the command line and in every file.
#[derive(Parser)]
#[command(name = "slideroute", version, about)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Args)]
struct SceneArg {
    /// Scene file (TOML). Without it, the embedded default (paper-like) scene.
    #[arg(long, value_name = "FILE")]
    scene: Option<PathBuf>,
}

#[derive(Args)]
struct PoseArgs {
    /// X: CM displacement along the global X axis (forward), in metres.
    #[arg(long, value_name = "METRES", allow_negative_numbers = true)]
    x: Option<f64>,
    /// Z: CM displacement along the global Z axis (lateral), in metres.
    #[arg(long, value_name = "METRES", allow_negative_numbers = true)]
    z: Option<f64>,
    /// θ: yaw of side 01 from +X towards +Z, in degrees.
    #[arg(
        long = "theta-deg",
        value_name = "DEGREES",
        allow_negative_numbers = true
    )]
    theta_deg: Option<f64>,
}

#[derive(Subcommand)]
enum Command {
    /// Compute the failure route: from the start of sliding, increment by increment, until it
    /// ends for a stated reason. Writes DIR/route.csv (one row per recorded increment) and
    /// DIR/summary.json, and prints a short summary.
    Run {
        #[command(flatten)]
        scene: SceneArg,
        /// Output folder (created if needed): route.csv, summary.json and the pictures
        /// plan.svg, profile.svg, angles.svg, reactions.svg.
        #[arg(long, value_name = "DIR", default_value = "out")]
        out: PathBuf,
        /// No progress bar and no summary (errors are still reported).
        #[arg(long)]
        quiet: bool,
        /// Write only route.csv and summary.json, no pictures.
        #[arg(long)]
        no_plots: bool,
        /// Dynamics model, overriding the scene's `[solver] dynamics`: `paper` (the paper's
        /// §5–7) or `rigid-body` (Newton–Euler with friction opposing each contact's slip).
        #[arg(long, value_enum, value_name = "MODEL")]
        dynamics: Option<DynamicsModel>,
        /// Run both dynamics models: DIR/paper/ and DIR/rigid-body/ (route.csv, summary.json),
        /// DIR/comparison.json (both summaries and where the routes part) and
        /// DIR/compare-plan.svg (both paths on one plan view).
        #[arg(long, conflicts_with = "dynamics")]
        compare_dynamics: bool,
    },
    /// Run the route for every combination of scene values, in parallel, and write
    /// DIR/sweep.csv (one row per combination: the varied values, how the route ended, travel,
    /// final yaw, largest tilts, factor of safety) and DIR/sweep.svg (travel against
    /// the first varied key). A combination that fails is a row with its reason.
    Sweep {
        #[command(flatten)]
        scene: SceneArg,
        /// A scene key to vary, `section.key=START:STOP:COUNT` (COUNT evenly spaced values,
        /// in the key's own units: e.g. `friction.mu_k=0.2:0.6:5`, `foundation.xi_deg=10:30:5`,
        /// `loads.hydraulic_force_n=6e6:1e7:9`). Repeat for more keys; every combination is run.
        #[arg(long, value_name = "KEY=START:STOP:COUNT", required = true)]
        vary: Vec<String>,
        /// Dynamics model for every combination, overriding the scene's `[solver] dynamics`.
        #[arg(long, value_enum)]
        dynamics: Option<DynamicsModel>,
        /// Output folder (created if needed).
        #[arg(long, value_name = "DIR", default_value = "out")]
        out: PathBuf,
        /// No progress bar and no summary.
        #[arg(long)]
        quiet: bool,
    },
    /// Uncertain scene values: sample them from their distributions (plain Monte Carlo or a
    /// Latin hypercube, reproducible for a seed whatever the number of threads), run every
    /// sample's route in parallel, and write DIR/samples.csv (one row per sample: the sampled
    /// values, factor of safety, how the route ended, travel, final yaw and position) and
    /// DIR/probabilistic.json (the probability of sliding, factor of safety below 1, with its
    /// 95 % interval; the probabilities of exceeding the limits given; percentiles).
    Probabilistic {
        #[command(flatten)]
        scene: SceneArg,
        /// How many samples.
        #[arg(long, default_value_t = 1000)]
        samples: usize,
        /// The seed the samples are drawn from.
        #[arg(long, default_value_t = 1)]
        seed: u64,
        /// An uncertain key and its distribution, `KEY=normal:MEAN:SD`,
        /// `KEY=truncnormal:MEAN:SD:LO:HI`, `KEY=lognormal:MEAN:SD`, `KEY=uniform:LO:HI` or
        /// `KEY=triangular:LO:MODE:HI`, in the key's own units (e.g.
        /// `friction.mu_k=normal:0.40:0.05`, `foundation.xi_deg=uniform:18:22`). Repeat for more.
        /// The scene's own `[uncertain]` table gives more; a key given both ways takes this one.
        #[arg(long = "dist", value_name = "KEY=DISTRIBUTION")]
        dist: Vec<String>,
        /// `lhs` (a Latin hypercube) or `mc` (plain Monte Carlo).
        #[arg(long, default_value = "lhs", value_parser = ["lhs", "mc"])]
        sampling: String,
        /// Report the probability that the travel exceeds this (m).
        #[arg(long, value_name = "M", allow_negative_numbers = true)]
        travel_limit_m: Option<f64>,
        /// Report the probability that the final yaw exceeds this in size (degrees).
        #[arg(long, value_name = "DEGREES", allow_negative_numbers = true)]
        rotation_limit_deg: Option<f64>,
        /// Dynamics model for every sample, overriding the scene's `[solver] dynamics`.
        #[arg(long, value_enum)]
        dynamics: Option<DynamicsModel>,
        /// Output folder (created if needed).
        #[arg(long, value_name = "DIR", default_value = "probabilistic")]
        out: PathBuf,
        /// No progress bar and no summary.
        #[arg(long)]
        quiet: bool,
        /// No pictures (route-fan.svg, factor-of-safety.svg, sensitivity.svg).
        #[arg(long)]
        no_plots: bool,
    },
    /// Check each load case of the scene (`[[case]]`; without any, the scene as written)
    /// against the sliding factor of safety its guideline requires (`[check]`: EM 1110-2-2100,
    /// Tables 3-2 and 3-3), print the table, write DIR/check.csv and DIR/check.json, and for
    /// every case that fails its route in DIR/case-N/ (route.csv, summary.json, pictures).
    Check {
        #[command(flatten)]
        scene: SceneArg,
        /// Output folder (created if needed).
        #[arg(long, value_name = "DIR", default_value = "check")]
        out: PathBuf,
        /// No table (errors are still reported).
        #[arg(long)]
        quiet: bool,
        /// No pictures for the failing cases' routes.
        #[arg(long)]
        no_plots: bool,
    },
    /// Measure error against run time: the paper-like and shallow scenes with each pose method
    /// (continuation, all roots at every increment), mode and integrator over a ladder of dt,
    /// against a fine reference; plus the stiff and extreme cases. Writes
    /// DIR/work-precision.csv, DIR/work-precision.svg and DIR/work-precision.md.
    Report {
        /// Fewer steps of dt and repeats (under a minute).
        #[arg(long)]
        quick: bool,
        /// Output folder (created if needed).
        #[arg(long, value_name = "DIR", default_value = "report")]
        out: PathBuf,
        /// No progress bar and no summary.
        #[arg(long)]
        quiet: bool,
    },
    /// Scene files: print the embedded default scene as a commented TOML file to start from,
    /// or check a scene file and report the first problem.
    Scene {
        /// Print the embedded default (paper-like) scene.
        #[arg(long, conflicts_with = "check")]
        print_default: bool,
        /// Check this scene file: prints `ok` or one line naming the key and the reason.
        #[arg(long, value_name = "FILE")]
        check: Option<PathBuf>,
    },
    /// Print the coefficients of the small-angle system (15) (f1–f12) and of the exact form
    /// at one displacement (X, Z, θ) of the centre of mass.
    Coeffs {
        #[command(flatten)]
        scene: SceneArg,
        #[command(flatten)]
        pose: PoseArgs,
        /// Print JSON instead of a table.
        #[arg(long)]
        json: bool,
    },
    /// Find every root of the pose system at (X, Z, θ), classify them (real, spurious,
    /// admissible) and select the physical pose by continuation from the start of sliding.
    /// With --grid, do so for every pose of a CSV file and write one row per pose.
    Roots {
        #[command(flatten)]
        scene: SceneArg,
        #[command(flatten)]
        pose: PoseArgs,
        /// Which system: exact or small-angle. Default: the scene's [solver] mode, else exact.
        #[arg(long, value_enum)]
        mode: Option<Mode>,
        /// CSV of poses with header `x_m,z_m,theta_deg` (m, m, degrees); needs --out.
        #[arg(long, value_name = "POSES.csv", conflicts_with_all = ["x", "z", "theta_deg"], requires = "out")]
        grid: Option<PathBuf>,
        /// Where to write the batch results (CSV), with --grid.
        #[arg(long, value_name = "OUT.csv", requires = "grid")]
        out: Option<PathBuf>,
        /// Print JSON instead of a table (single pose).
        #[arg(long)]
        json: bool,
    },
}

/// One line on standard error, exit code 2: bad input.
/// How a command failed, which decides the exit code (README, "Exit codes"): 2 for bad input
/// (a scene, flag or input file that is wrong), 1 for any other failure (an output that cannot be
/// written, a full disk), and a quiet 0 when whoever reads standard output has closed it (as
/// `head` does), like other Unix tools.
#[derive(Debug)]
enum CliError {
    BadInput(String),
    Failed(String),
    ClosedPipe,
}

/// A scene, flag or input file that is wrong: exit 2.
fn bad_input(msg: String) -> CliError {
    CliError::BadInput(msg)
}

/// An output that could not be written: exit 1.
fn failed(msg: String) -> CliError {
    CliError::Failed(msg)
}

/// Writes to standard output without panicking: a closed pipe ends the command quietly, any
/// other error (a full disk) is a one-line failure.
fn stdout_error(e: std::io::Error) -> CliError {
    if e.kind() == std::io::ErrorKind::BrokenPipe {
        CliError::ClosedPipe
    } else {
        CliError::Failed(format!("standard output: {e}"))
    }
}

macro_rules! out {
    ($($arg:tt)*) => {{
        use std::io::Write as _;
        let mut o = std::io::stdout().lock();
        write!(o, $($arg)*).and_then(|_| o.flush()).map_err(stdout_error)?
    }};
}

macro_rules! outln {
    ($($arg:tt)*) => {{
        use std::io::Write as _;
        let mut o = std::io::stdout().lock();
        writeln!(o, $($arg)*).and_then(|_| o.flush()).map_err(stdout_error)?
    }};
}

fn fail(e: CliError) -> ExitCode {
    match e {
        CliError::BadInput(msg) => {
            eprintln!("slideroute: {msg}");
            ExitCode::from(2)
        }
        CliError::Failed(msg) => {
            eprintln!("slideroute: {msg}");
            ExitCode::from(1)
        }
        CliError::ClosedPipe => ExitCode::SUCCESS,
    }
}

/// The scene, with its dynamics model overridden when `dynamics` says.
fn load_with(arg: &SceneArg, dynamics: Option<DynamicsModel>) -> Result<Scene, CliError> {
    let base = load(arg)?;
    match dynamics {
        Some(model) => base
            .with_dynamics(model)
            .map_err(|e| bad_input(e.to_string())),
        None => Ok(base),
    }
}

fn load(arg: &SceneArg) -> Result<Scene, CliError> {
    let scene = match &arg.scene {
        Some(p) => Scene::from_file(p).map_err(|e| bad_input(e.to_string()))?,
        None => Scene::default_scene(),
    };
    // Likely mistakes get a line on standard error, not silence.
    for w in scene.warnings() {
        eprintln!("slideroute: warning: {w}");
    }
    Ok(scene)
}

fn displacement(p: &PoseArgs) -> Result<Displacement, CliError> {
    let get = |name: &str, v: Option<f64>| match v {
        None => Err(format!("--{name} is required")),
        Some(v) if !v.is_finite() => Err(format!("--{name}: must be a finite number, got {v}")),
        Some(v) => Ok(v),
    };
    Ok(Displacement::new(
        get("x", p.x).map_err(bad_input)?,
        get("z", p.z).map_err(bad_input)?,
        get("theta-deg", p.theta_deg)
            .map_err(bad_input)?
            .to_radians(),
    ))
}

fn print_json(value: &impl serde::Serialize) -> Result<(), CliError> {
    let s = serde_json::to_string_pretty(value)
        .map_err(|e| failed(format!("cannot write JSON: {e}")))?;
    outln!("{s}");
    Ok(())
}

fn coeffs(scene: &SceneArg, pose: &PoseArgs, json: bool) -> Result<(), CliError> {
    let scene = load(scene)?;
    let report = CoeffReport::new(&scene, displacement(pose)?).ok_or_else(|| {
        bad_input(format!(
            "{}: coeffs prints the paper's f1–f12 and exact (13), (14), which need the paper's \
             frame (l1x … l2z) and planes (xi_deg, zeta_deg, kappa_deg); this scene's pose comes \
             from the general system (derivations/09-general-pose.md)",
            scene.origin()
        ))
    })?;
    if json {
        print_json(&report)
    } else {
        out!("{report}");
        Ok(())
    }
}

fn roots_cmd(
    scene: &SceneArg,
    pose: &PoseArgs,
    mode: Option<Mode>,
    grid: Option<&PathBuf>,
    out: Option<&PathBuf>,
    json: bool,
) -> Result<(), CliError> {
    let scene = load(scene)?;
    let mode = mode
        .or(scene.solver().map(|s| s.mode))
        .unwrap_or(Mode::Exact);
    let report = |d: Displacement| {
        roots::solve_all(scene.site(), d, mode)
            .map(|all| RootsReport::new(&scene, &all))
            .map_err(|e| e.to_string())
    };
    match (grid, out) {
        (Some(grid), Some(out)) => {
            let name = grid.display().to_string();
            let file = slideroute::stages::scene::input::open_bounded(
                grid,
                slideroute::stages::scene::input::MAX_GRID_BYTES,
            )
            .map_err(|e| bad_input(format!("{name}: {e}")))?;
            let poses = grid_csv::read_poses(file, &name).map_err(|e| bad_input(e.to_string()))?;
            // Every core, in the file's order (issue #17).
            let reports = poses
                .par_iter()
                .map(|p| report(p.displacement()))
                .collect::<Result<Vec<_>, _>>()
                .map_err(bad_input)?;
            let out_name = out.display().to_string();
            let file = std::fs::File::create(out)
                .map_err(|e| failed(format!("{out_name}: cannot write: {e}")))?;
            grid_csv::write_rows(file, &poses, &reports)
                .map_err(|e| failed(format!("{out_name}: {e}")))?;
            eprintln!("slideroute: {} poses written to {out_name}", reports.len());
            Ok(())
        }
        _ => {
            let r = report(displacement(pose)?).map_err(bad_input)?;
            if json {
                print_json(&r)
            } else {
                out!("{r}");
                Ok(())
            }
        }
    }
}

fn progress_bar(quiet: bool, len: u64, what: &str) -> indicatif::ProgressBar {
    if quiet {
        return indicatif::ProgressBar::hidden();
    }
    // Drawn on standard error only when it is a terminal.
    let bar = indicatif::ProgressBar::new(len);
    let style = indicatif::ProgressStyle::with_template(&format!(
        "{what} [{{bar:40}}] {{pos}}/{{len}} {{elapsed_precise}}"
    ))
    .unwrap_or_else(|_| indicatif::ProgressStyle::default_bar());
    bar.set_style(style.progress_chars("=> "));
    bar
}

/// The pictures (unless `no_plots`) and summary.json (with the manifest, last) into the locked
/// output folder, beside route.csv, each whole or absent, replacing an earlier run's outputs
/// there.
fn write_route_folder(
    mut folder: crate::output::folder::Folder,
    scene: &Scene,
    route: &slideroute::stages::route::Route,
    no_plots: bool,
) -> Result<Vec<PathBuf>, String> {
    use crate::output::route_files;
    let mut files = Vec::new();
    #[cfg(feature = "plots")]
    if !no_plots {
        let staging = folder.staging()?;
        let staged = crate::output::plots::write_route_plots(&staging, scene, route)?;
        files.extend(folder.adopt_all(staged)?);
    }
    #[cfg(not(feature = "plots"))]
    let _ = no_plots;
    let manifest = route_files::Manifest::new(scene, &folder);
    files.push(route_files::write_json_with_manifest(
        &mut folder,
        "summary.json",
        route,
        &manifest,
    )?);
    folder.finish()?;
    Ok(files)
}

fn run_cmd(
    scene: &SceneArg,
    out: &std::path::Path,
    quiet: bool,
    no_plots: bool,
    dynamics: Option<DynamicsModel>,
) -> Result<(), CliError> {
    let mut scene = load(scene)?;
    if let Some(model) = dynamics {
        let before = scene.solver().map(|s| s.integrator);
        scene = scene
            .with_dynamics(model)
            .map_err(|e| bad_input(e.to_string()))?;
        // Each dynamics takes its own integrator: say so where that changes the scene's.
        if let (Some(b), Some(after)) = (before, scene.solver().map(|s| s.integrator)) {
            if b != after {
                eprintln!(
                    "slideroute: note: --dynamics {} integrates with \"{}\" (its own default), \
                     not the scene's \"{}\"",
                    model.as_str(),
                    after.as_str(),
                    b.as_str()
                );
            }
        }
    }
    // Locked before the work, so that a second run into the same folder is refused at once.
    let folder = crate::output::folder::Folder::open(out).map_err(failed)?;
    let bar = progress_bar(quiet, 1000, "route");
    let progress = |f: f64| {
        bar.set_position((f * 1000.0) as u64);
        if INTERRUPTED.load(Ordering::Relaxed) {
            std::ops::ControlFlow::Break(())
        } else {
            std::ops::ControlFlow::Continue(())
        }
    };
    // Rows stream to route.csv as they are computed; the route keeps a bounded number of them
    // for the pictures and the summary (issue #13: memory does not grow with its length).
    let keep_every = scene.solver().map_or(1, |s| {
        let rows = (s.t_end / s.dt).ceil() / s.stride as f64;
        (rows / 4000.0).ceil().max(1.0) as usize
    });
    let mut folder = folder;
    let mut computed = None;
    let mut bad_scene = None;
    let csv_path = folder.write_with("route.csv", |tmp| {
        let file = std::fs::File::create(tmp)
            .map_err(|e| format!("{}: cannot write: {e}", tmp.display()))?;
        let mut rows = crate::output::route_files::CsvRows::new(std::io::BufWriter::new(file))
            .map_err(|e| format!("route.csv: {e}"))?;
        match slideroute::stages::route::run_streamed(&scene, progress, keep_every, |r| {
            rows.push(r)
        }) {
            Ok(route) => computed = Some(route),
            Err(e) => {
                bad_scene = Some(e.to_string());
                return Err(String::new());
            }
        }
        rows.finish().map_err(|e| format!("route.csv: {e}"))
    });
    bar.finish_and_clear();
    if let Some(e) = bad_scene {
        return Err(bad_input(e));
    }
    let csv_path = csv_path.map_err(failed)?;
    let route = computed.ok_or_else(|| failed("route.csv: no route".to_string()))?;
    let mut files = vec![csv_path];
    files.extend(write_route_folder(folder, &scene, &route, no_plots).map_err(failed)?);
    if route.termination.reason == slideroute::stages::route::Reason::Interrupted {
        let names: Vec<String> = files.iter().map(|f| f.display().to_string()).collect();
        return Err(failed(format!(
            "{}; wrote what was computed: {}",
            route.termination.detail,
            names.join(", ")
        )));
    }
    if quiet {
        return Ok(());
    }
    out!(
        "{}",
        crate::output::summary::RouteSummary {
            route: &route,
            files: &files
        }
    );
    Ok(())
}

fn compare_cmd(
    scene: &SceneArg,
    out: &std::path::Path,
    quiet: bool,
    no_plots: bool,
) -> Result<(), CliError> {
    let scene = load(scene)?;
    let mut folder = crate::output::folder::Folder::open(out).map_err(failed)?;
    let c = slideroute::stages::compare::compare_dynamics_observed(&scene, interrupted)
        .map_err(|e| bad_input(e.to_string()))?;
    #[allow(unused_mut)]
    let mut files = crate::output::compare_files::write(&mut folder, &scene, &c).map_err(failed)?;
    #[cfg(feature = "plots")]
    if !no_plots {
        let path = folder
            .write_with("compare-plan.svg", |tmp| {
                crate::output::plots::compare_plan(tmp, &scene, &c)
            })
            .map_err(failed)?;
        files.push(path);
    }
    #[cfg(not(feature = "plots"))]
    let _ = no_plots;
    folder.finish().map_err(failed)?;
    if interrupted() {
        let names: Vec<String> = files.iter().map(|f| f.display().to_string()).collect();
        return Err(failed(format!(
            "interrupted: the routes stopped at their next increment; wrote what was computed: {}",
            names.join(", ")
        )));
    }
    if quiet {
        return Ok(());
    }
    out!(
        "{}",
        crate::output::summary::CompareSummary {
            comparison: &c,
            files: &files
        }
    );
    Ok(())
}

/// The most samples one probabilistic analysis may run.
const MAX_SAMPLES: usize = 10_000_000;

fn probabilistic_cmd(
    scene: &SceneArg,
    (samples, seed, sampling): (usize, u64, &str),
    dist: &[String],
    (travel_limit, rotation_limit): (Option<f64>, Option<f64>),
    dynamics: Option<DynamicsModel>,
    (out, quiet, no_plots): (&std::path::Path, bool, bool),
) -> Result<(), CliError> {
    use slideroute::stages::uncertainty::{Design, Limits, Sampling, Uncertain, merged, summarise};
    let base = load_with(scene, dynamics)?;
    if samples == 0 || samples > MAX_SAMPLES {
        return Err(bad_input(format!(
            "--samples {samples}: from 1 to {MAX_SAMPLES}"
        )));
    }
    let limits = Limits::new(travel_limit, rotation_limit).map_err(|(name, l)| {
        bad_input(format!(
            "--{} {l}: a finite number, zero or more",
            name.replace('_', "-")
        ))
    })?;
    let given = dist
        .iter()
        .map(|d| d.parse::<Uncertain>().map_err(|e| format!("--dist {e}")))
        .collect::<Result<Vec<_>, _>>()
        .map_err(bad_input)?;
    // The scene's [uncertain] table, then --dist: a key of both takes the command line's.
    let uncertain = merged(base.uncertain(), given);
    if uncertain.is_empty() {
        return Err(bad_input(format!(
            "{}: nothing is uncertain: give --dist KEY=DISTRIBUTION or an [uncertain] table in \
             the scene",
            base.origin()
        )));
    }
    // Every key must be a number of the scene, and given once.
    let as_vary: Vec<crate::sweep::Vary> = uncertain
        .iter()
        .map(|u| crate::sweep::Vary {
            key: u.key.clone(),
            values: vec![],
            words: None,
        })
        .collect();
    crate::sweep::check_keys(&base, &as_vary).map_err(|e| {
        // Named as it was given: on the command line, or in the scene's [uncertain] table.
        let named = uncertain
            .iter()
            .find(|u| e.starts_with(&format!("--vary {}:", u.key)))
            .filter(|u| {
                base.uncertain().contains(u)
                    && !dist.iter().any(|d| d.starts_with(&format!("{}=", u.key)))
            });
        match named {
            Some(u) => bad_input(e.replacen(
                &format!("--vary {}", u.key),
                &format!("{}: uncertain.\"{}\"", base.origin(), u.key),
                1,
            )),
            None => bad_input(e.replacen("--vary", "--dist", 1)),
        }
    })?;
    let sampling = if sampling == "mc" {
        Sampling::MonteCarlo
    } else {
        Sampling::LatinHypercube
    };
    let mut folder = crate::output::folder::Folder::open(out).map_err(failed)?;
    let bar = progress_bar(quiet, samples as u64, "samples");
    let design = Design {
        scene: &base,
        uncertain: &uncertain,
        samples,
        seed,
        sampling,
    };
    let rows = design.run(|| bar.inc(1), interrupted);
    bar.finish_and_clear();
    let csv_path = folder
        .write_with("samples.csv", |tmp| {
            let file = std::fs::File::create(tmp)
                .map_err(|e| format!("{}: cannot write: {e}", tmp.display()))?;
            crate::probabilistic::write_csv(std::io::BufWriter::new(file), &uncertain, &rows)
                .map_err(|e| format!("samples.csv: {e}"))
        })
        .map_err(failed)?;
    let summary = summarise(&design, limits, &rows);
    let mut written = vec![csv_path];
    #[cfg(feature = "plots")]
    if !no_plots && !interrupted() {
        // The scene as written, drawn in black on the fan.
        let nominal = slideroute::stages::route::run(&base).ok();
        let staging = folder.staging().map_err(failed)?;
        let staged = crate::output::plots::write_probabilistic_plots(
            &staging,
            &base,
            nominal.as_ref(),
            &rows,
            &summary,
        )
        .map_err(failed)?;
        written.extend(folder.adopt_all(staged).map_err(failed)?);
    }
    #[cfg(not(feature = "plots"))]
    let _ = no_plots;
    let manifest = crate::output::route_files::Manifest::new(&base, &folder);
    let json_path = crate::output::route_files::write_json_with_manifest(
        &mut folder,
        "probabilistic.json",
        &summary,
        &manifest,
    )
    .map_err(failed)?;
    folder.finish().map_err(failed)?;
    written.push(json_path);
    let written = written
        .iter()
        .map(|p| p.display().to_string())
        .collect::<Vec<_>>()
        .join(", ");
    if interrupted() {
        return Err(failed(format!(
            "interrupted: samples under way stopped, those not started are rows \"{}\"; wrote {written}",
            slideroute::stages::uncertainty::NOT_RUN
        )));
    }
    if !quiet {
        let p = summary.probability_of_sliding;
        println!(
            "probabilistic {}: {} samples ({}), {} routes, {} invalid",
            summary.scene,
            samples,
            if sampling == Sampling::MonteCarlo {
                "Monte Carlo"
            } else {
                "Latin hypercube"
            },
            summary.routes,
            summary.invalid_samples
        );
        println!("  probability of sliding (factor of safety below 1) {p}");
        for (what, prob) in [
            (
                "travel over the limit",
                summary.probability_travel_exceeds_limit,
            ),
            (
                "rotation over the limit",
                summary.probability_rotation_exceeds_limit,
            ),
        ] {
            if let Some(q) = prob {
                println!("  probability of {what} {q}");
            }
        }
        println!("  wrote {written}");
    }
    Ok(())
}

fn sweep_cmd(
    scene: &SceneArg,
    vary: &[String],
    dynamics: Option<DynamicsModel>,
    out: &std::path::Path,
    quiet: bool,
) -> Result<(), CliError> {
    // The base scene must itself be valid.
    let base = load_with(scene, dynamics)?;
    let varies = vary
        .iter()
        .map(|v| crate::sweep::parse_vary(v))
        .collect::<Result<Vec<_>, _>>()
        .map_err(bad_input)?;
    crate::sweep::check_keys(&base, &varies).map_err(bad_input)?;
    let n = crate::sweep::count(&varies);
    if n > crate::sweep::MAX_COMBINATIONS {
        return Err(bad_input(format!(
            "--vary: {n} combinations, more than the {} one sweep may run",
            crate::sweep::MAX_COMBINATIONS
        )));
    }
    let mut folder = crate::output::folder::Folder::open(out).map_err(failed)?;
    let bar = progress_bar(quiet, n as u64, "sweep");
    let rows = crate::sweep::run(&base, &varies, || bar.inc(1), interrupted).map_err(bad_input)?;
    bar.finish_and_clear();
    let csv_path = folder
        .write_with("sweep.csv", |tmp| {
            let file = std::fs::File::create(tmp)
                .map_err(|e| format!("{}: cannot write: {e}", tmp.display()))?;
            crate::output::sweep_files::write_csv(file, &varies, &rows)
                .map_err(|e| format!("sweep.csv: {e}"))
        })
        .map_err(failed)?;
    #[allow(unused_mut)]
    let mut written = vec![csv_path.display().to_string()];
    #[cfg(feature = "plots")]
    {
        let svg = folder
            .write_with("sweep.svg", |tmp| {
                crate::output::plots::sweep(tmp, &varies, &rows)
            })
            .map_err(failed)?;
        written.push(svg.display().to_string());
    }
    folder.finish().map_err(failed)?;
    if interrupted() {
        return Err(failed(format!(
            "interrupted: combinations under way stopped, those not started are rows \"{}\"; wrote {}",
            crate::sweep::NOT_RUN,
            written.join(", ")
        )));
    }
    if !quiet {
        let mut counts: std::collections::BTreeMap<&str, usize> = std::collections::BTreeMap::new();
        for r in &rows {
            *counts.entry(r.reason.as_str()).or_default() += 1;
        }
        let summary: Vec<String> = counts.iter().map(|(k, v)| format!("{v} × {k}")).collect();
        let plural = if n == 1 { "" } else { "s" };
        outln!("{n} combination{plural}: {}", summary.join(", "));
        outln!("wrote {}", written.join(", "));
    }
    Ok(())
}

fn check_cmd(
    scene: &SceneArg,
    out: &std::path::Path,
    quiet: bool,
    no_plots: bool,
) -> Result<(), CliError> {
    use crate::output::{check_files, route_files};
    let scene = load(scene)?;
    let mut folder = crate::output::folder::Folder::open(out).map_err(failed)?;
    let results = slideroute::check_cases(&scene, |_| ()).map_err(|e| bad_input(e.to_string()))?;
    let mut written = Vec::new();
    for (k, r) in results.iter().enumerate().filter(|(_, r)| !r.passes) {
        let case_scene = scene
            .for_case(&r.case)
            .map_err(|e| bad_input(e.to_string()))?;
        let mut sub =
            crate::output::folder::Folder::open(&out.join(format!("case-{k}"))).map_err(failed)?;
        written.push(
            route_files::write_route_csv(&mut sub, "route.csv", &r.route.rows).map_err(failed)?,
        );
        written.extend(write_route_folder(sub, &case_scene, &r.route, no_plots).map_err(failed)?);
    }
    written.push(
        folder
            .write_with("check.csv", |tmp| {
                let file = std::fs::File::create(tmp)
                    .map_err(|e| format!("{}: cannot write: {e}", tmp.display()))?;
                check_files::write_csv(file, &results).map_err(|e| format!("check.csv: {e}"))
            })
            .map_err(failed)?,
    );
    #[derive(serde::Serialize)]
    struct CheckJson<'a> {
        guideline: &'a slideroute::stages::scene::cases::Guideline,
        cases: &'a [slideroute::CaseResult],
    }
    let manifest = route_files::Manifest::new(&scene, &folder);
    written.push(
        route_files::write_json_with_manifest(
            &mut folder,
            "check.json",
            &CheckJson {
                guideline: scene.guideline(),
                cases: &results,
            },
            &manifest,
        )
        .map_err(failed)?,
    );
    folder.finish().map_err(failed)?;
    if !quiet {
        let table = check_files::CheckTable {
            scene: scene.name(),
            guideline: scene.guideline().describe(),
            results: &results,
        };
        out!("{table}");
        let names: Vec<String> = written.iter().map(|p| p.display().to_string()).collect();
        outln!("  wrote {}", names.join(", "));
    }
    Ok(())
}

fn report_cmd(quick: bool, out: &std::path::Path, quiet: bool) -> Result<(), CliError> {
    let bar = progress_bar(quiet, crate::report::point_count(quick) as u64, "report");
    let (points, references) = crate::report::work_precision(quick, || {
        bar.inc(1);
        if interrupted() {
            std::ops::ControlFlow::Break(())
        } else {
            std::ops::ControlFlow::Continue(())
        }
    })
    .map_err(failed)?;
    bar.finish_and_clear();
    let extreme = crate::report::extreme(if quick { 20 } else { 200 });
    let mut folder = crate::output::folder::Folder::open(out).map_err(failed)?;
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
    let mut written = vec![
        csv_path.display().to_string(),
        md_path.display().to_string(),
    ];
    #[cfg(feature = "plots")]
    {
        let svg = folder
            .write_with("work-precision.svg", |tmp| {
                crate::output::plots::work_precision(tmp, &points)
            })
            .map_err(failed)?;
        written.push(svg.display().to_string());
    }
    folder.finish().map_err(failed)?;
    if !quiet {
        for r in &references {
            outln!(
                "reference {}: dt {:.4e} s, change at dt/2 {:.1e} m (bound {:.0e} m)",
                r.scene,
                r.dt_s,
                r.change_m,
                r.bound_m
            );
        }
        outln!(
            "{} points, {} extreme cases; wrote {}",
            points.len(),
            extreme.len(),
            written.join(", ")
        );
    }
    Ok(())
}

fn scene_cmd(print_default: bool, check: Option<&PathBuf>) -> Result<(), CliError> {
    match (print_default, check) {
        (true, _) => {
            out!("{}", slideroute::stages::scene::DEFAULT_SCENE_TOML);
            Ok(())
        }
        (false, Some(p)) => {
            let s = Scene::from_file(p).map_err(|e| bad_input(e.to_string()))?;
            let sections = match slideroute::stages::scene::Simulation::new(&s) {
                Ok(_) => "all sections",
                Err(e) if e.kind == SceneErrorKind::MissingSection => {
                    "geometry only (frame, foundation)"
                }
                // Present but not runnable as written (e.g. small-angle with the rigid body).
                Err(e) => return Err(bad_input(e.to_string())),
            };
            outln!("{}: ok ({sections})", p.display());
            Ok(())
        }
        (false, None) => Err(bad_input(
            "scene: say --print-default or --check FILE".to_string(),
        )),
    }
}

/// Set by Ctrl-C (SIGINT) and SIGTERM: a route stops at its next increment and writes what it
/// computed, with termination "interrupted" (issue #13); a second signal ends the process.
static INTERRUPTED: AtomicBool = AtomicBool::new(false);

/// Whether Ctrl-C or SIGTERM has come.
fn interrupted() -> bool {
    INTERRUPTED.load(Ordering::Relaxed)
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    let _ = ctrlc::set_handler(|| {
        if INTERRUPTED.swap(true, Ordering::Relaxed) {
            std::process::exit(130);
        }
    });
    let result = match &cli.command {
        Command::Run {
            scene,
            out,
            quiet,
            no_plots,
            dynamics,
            compare_dynamics,
        } => {
            if *compare_dynamics {
                compare_cmd(scene, out, *quiet, *no_plots)
            } else {
                run_cmd(scene, out, *quiet, *no_plots, *dynamics)
            }
        }
        Command::Sweep {
            scene,
            vary,
            dynamics,
            out,
            quiet,
        } => sweep_cmd(scene, vary, *dynamics, out, *quiet),
        Command::Probabilistic {
            scene,
            samples,
            seed,
            dist,
            sampling,
            travel_limit_m,
            rotation_limit_deg,
            dynamics,
            out,
            quiet,
            no_plots,
        } => probabilistic_cmd(
            scene,
            (*samples, *seed, sampling),
            dist,
            (*travel_limit_m, *rotation_limit_deg),
            *dynamics,
            (out, *quiet, *no_plots),
        ),
        Command::Report { quick, out, quiet } => report_cmd(*quick, out, *quiet),
        Command::Check {
            scene,
            out,
            quiet,
            no_plots,
        } => check_cmd(scene, out, *quiet, *no_plots),
        Command::Scene {
            print_default,
            check,
        } => scene_cmd(*print_default, check.as_ref()),
        Command::Coeffs { scene, pose, json } => coeffs(scene, pose, *json),
        Command::Roots {
            scene,
            pose,
            mode,
            grid,
            out,
            json,
        } => roots_cmd(scene, pose, *mode, grid.as_ref(), out.as_ref(), *json),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => fail(e),
    }
}
