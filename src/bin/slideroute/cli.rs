//! The command line's words: every command and flag, with the help `--help` prints. Options
//! that name a model's value (`--dynamics`, `--mode`, `--sampling`) are read by the library's
//! own names (`FromStr`), as a scene file and Python read them.

use clap::builder::{PossibleValuesParser, TypedValueParser};
use clap::{Args, Parser, Subcommand};
use slideroute::probabilistic::Sampling;
use slideroute::{DynamicsModel, Mode, UnknownName};
use std::path::PathBuf;
use std::str::FromStr;

/// A value of a model's option by its names, the names listed in the help.
fn named<T, const N: usize>(names: [&'static str; N]) -> impl TypedValueParser<Value = T>
where
    T: FromStr<Err = UnknownName> + Clone + Send + Sync + 'static,
{
    PossibleValuesParser::new(names).try_map(|word| word.parse::<T>())
}

/// Three-dimensional failure route of a sliding dam monolith (after Galic & Glaser).
///
/// Units: metres, newtons, seconds; angles in degrees on the command line and in every file.
#[derive(Parser)]
#[command(name = "slideroute", version, about)]
pub struct Cli {
    #[command(subcommand)]
    pub command: Command,
}

/// The scene a command reads.
#[derive(Args)]
pub struct SceneArg {
    /// Scene file (TOML). Without it, the embedded default (paper-like) scene.
    #[arg(long, value_name = "FILE")]
    pub scene: Option<PathBuf>,
    /// Change one key of the scene without editing its file, in the file's units:
    /// `--set water.headwater_m=14.5`, `--set solver.mode=small-angle`; repeatable. The value
    /// is read as TOML (a number, true/false, a quoted string, an array), else as a word.
    #[arg(long = "set", value_name = "KEY=VALUE")]
    pub set: Vec<String>,
}

/// A displacement of the block (X, Z, θ): every part, unless a grid of them is given.
#[derive(Args)]
pub struct PoseArgs {
    /// X: CM displacement along the global X axis (forward), in metres.
    #[arg(
        long,
        value_name = "METRES",
        allow_negative_numbers = true,
        required_unless_present = "grid"
    )]
    pub x: Option<f64>,
    /// Z: CM displacement along the global Z axis (lateral), in metres.
    #[arg(
        long,
        value_name = "METRES",
        allow_negative_numbers = true,
        required_unless_present = "grid"
    )]
    pub z: Option<f64>,
    /// θ: yaw of side 01 from +X towards +Z, in degrees.
    #[arg(
        long = "theta-deg",
        value_name = "DEGREES",
        allow_negative_numbers = true,
        required_unless_present = "grid"
    )]
    pub theta_deg: Option<f64>,
}

/// A displacement of the block (X, Z, θ), every part required.
#[derive(Args)]
pub struct RequiredPoseArgs {
    /// X: CM displacement along the global X axis (forward), in metres.
    #[arg(long, value_name = "METRES", allow_negative_numbers = true)]
    pub x: f64,
    /// Z: CM displacement along the global Z axis (lateral), in metres.
    #[arg(long, value_name = "METRES", allow_negative_numbers = true)]
    pub z: f64,
    /// θ: yaw of side 01 from +X towards +Z, in degrees.
    #[arg(
        long = "theta-deg",
        value_name = "DEGREES",
        allow_negative_numbers = true
    )]
    pub theta_deg: f64,
}

impl From<&RequiredPoseArgs> for PoseArgs {
    fn from(p: &RequiredPoseArgs) -> PoseArgs {
        PoseArgs {
            x: Some(p.x),
            z: Some(p.z),
            theta_deg: Some(p.theta_deg),
        }
    }
}

/// The commands.
#[derive(Subcommand)]
pub enum Command {
    /// Compute the failure route: from the start of sliding, increment by increment, until it
    /// ends for a stated reason. Writes DIR/route.csv (one row per recorded increment) and
    /// DIR/summary.json, and prints a short summary.
    Run(RunArgs),
    /// Run the route for every combination of scene values, in parallel, and write
    /// DIR/sweep.csv (one row per combination: the varied values, how the route ended, travel,
    /// final yaw, largest tilts, factor of safety) and DIR/sweep.svg (travel against
    /// the first varied key). A combination that fails is a row with its reason.
    Sweep(SweepArgs),
    /// Uncertain scene values: sample them from their distributions (plain Monte Carlo or a
    /// Latin hypercube, reproducible for a seed whatever the number of threads), run every
    /// sample's route in parallel, and write DIR/samples.csv (one row per sample: the sampled
    /// values, factor of safety, how the route ended, travel, final yaw and position) and
    /// DIR/probabilistic.json (the probability of sliding, factor of safety below 1, with its
    /// 95 % interval; the probabilities of exceeding the limits given; percentiles).
    Probabilistic(ProbabilisticArgs),
    /// Check each load case of the scene (`[[case]]`; without any, the scene as written)
    /// against the sliding factor of safety its guideline requires (`[check]`: EM 1110-2-2100,
    /// Tables 3-2 and 3-3), print the table, write DIR/check.csv and DIR/check.json, and for
    /// every case that fails its route in DIR/case-N/ (route.csv, summary.json, pictures).
    Check(CheckArgs),
    /// Measure error against run time: the paper-like and shallow scenes with each pose method
    /// (continuation, all roots at every increment), mode and integrator over a ladder of dt,
    /// against a fine reference; plus the stiff and extreme cases. Writes
    /// DIR/work-precision.csv, DIR/work-precision.svg and DIR/work-precision.md.
    Report(ReportArgs),
    /// Scene files: print the embedded default scene as a commented TOML file to start from,
    /// or check a scene file and report its problems (up to ten).
    Scene(SceneFileArgs),
    /// Print the coefficients of the small-angle system (15) (f1–f12) and of the exact form
    /// at one displacement (X, Z, θ) of the centre of mass.
    Coeffs(CoeffsArgs),
    /// Find every root of the pose system at (X, Z, θ), classify them (real, spurious,
    /// admissible) and select the physical pose by continuation from the start of sliding.
    /// With --grid, do so for every pose of a CSV file and write one row per pose.
    Roots(RootsArgs),
}

/// `slideroute run`.
#[derive(Args)]
pub struct RunArgs {
    #[command(flatten)]
    pub scene: SceneArg,
    /// Output folder (created if needed; default `out/run`, with --compare-dynamics
    /// `out/compare`): route.csv, summary.json, the pictures plan.svg, profile.svg,
    /// angles.svg, reactions.svg, and the route in 3-D, route.html and route.glb. A run
    /// replaces only what `run` wrote there before.
    #[arg(long, value_name = "DIR")]
    pub out: Option<PathBuf>,
    /// No progress bar and no summary (errors are still reported).
    #[arg(long)]
    pub quiet: bool,
    /// Write only route.csv and summary.json, no pictures.
    #[arg(long)]
    pub no_plots: bool,
    /// No route in 3-D: neither route.html (the route played in a browser) nor route.glb
    /// (glTF); with --compare-dynamics, no compare.html.
    #[arg(long)]
    pub no_3d: bool,
    /// Dynamics model, overriding the scene's `[solver] dynamics`: `paper` (the paper's
    /// §5–7) or `rigid-body` (Newton–Euler with friction opposing each contact's slip).
    #[arg(long, value_name = "MODEL", value_parser = named::<DynamicsModel, _>(DynamicsModel::ALL.map(DynamicsModel::as_str)))]
    pub dynamics: Option<DynamicsModel>,
    /// Run both dynamics models: DIR/paper/ and DIR/rigid-body/ (route.csv, summary.json),
    /// DIR/comparison.json (both summaries and where the routes part) and
    /// DIR/compare-plan.svg (both paths on one plan view) and DIR/compare.html (both routes
    /// in 3-D).
    #[arg(long, conflicts_with = "dynamics")]
    pub compare_dynamics: bool,
}

impl RunArgs {
    /// The output folder: `--out`, else `out/run` (`out/compare` with --compare-dynamics).
    pub fn out_dir(&self) -> PathBuf {
        self.out.clone().unwrap_or_else(|| {
            PathBuf::from(if self.compare_dynamics {
                "out/compare"
            } else {
                "out/run"
            })
        })
    }
}

/// `slideroute sweep`.
#[derive(Args)]
pub struct SweepArgs {
    #[command(flatten)]
    pub scene: SceneArg,
    /// A scene key and its values: `KEY=START:STOP:COUNT`, `KEY=A,B,C` or `KEY=A`.
    ///
    /// `START:STOP:COUNT` is COUNT evenly spaced values, STOP included, in the key's own
    /// units (`friction.mu_k=0.2:0.6:5`, `foundation.xi_deg=10:30:5`,
    /// `loads.hydraulic_force_n=6e6:1e7:9`); `A,B,C` a list of values, or of words for a key
    /// that takes words (`solver.dynamics=paper,rigid-body`); `A` one value
    /// (`solver.t_end_s=5`). Repeat for more keys; every combination is run.
    #[arg(long, value_name = "KEY=VALUES", required = true)]
    pub vary: Vec<String>,
    /// Dynamics model for every combination, overriding the scene's `[solver] dynamics`.
    #[arg(long, value_name = "MODEL", value_parser = named::<DynamicsModel, _>(DynamicsModel::ALL.map(DynamicsModel::as_str)))]
    pub dynamics: Option<DynamicsModel>,
    /// Output folder (created if needed). A sweep replaces only what a sweep wrote there
    /// before.
    #[arg(long, value_name = "DIR", default_value = "out/sweep")]
    pub out: PathBuf,
    /// No progress bar and no summary (errors are still reported).
    #[arg(long)]
    pub quiet: bool,
    /// No picture (sweep.svg).
    #[arg(long)]
    pub no_plots: bool,
    /// No sweep.html (every combination's CM path over the ground in 3-D, in a browser).
    #[arg(long)]
    pub no_3d: bool,
}

/// `slideroute probabilistic`.
#[derive(Args)]
pub struct ProbabilisticArgs {
    #[command(flatten)]
    pub scene: SceneArg,
    /// How many samples.
    // A negative count is read as the flag's value, and refused naming the flag (not taken
    // for an unknown argument).
    #[arg(
        long,
        value_name = "N",
        default_value_t = 1000,
        allow_negative_numbers = true
    )]
    pub samples: usize,
    /// The seed the samples are drawn from.
    #[arg(
        long,
        value_name = "S",
        default_value_t = 1,
        allow_negative_numbers = true
    )]
    pub seed: u64,
    /// An uncertain key and its distribution, `KEY=normal:MEAN:SD`,
    /// `KEY=truncnormal:MEAN:SD:LO:HI`, `KEY=lognormal:MEAN:SD`, `KEY=uniform:LO:HI` or
    /// `KEY=triangular:LO:MODE:HI`, in the key's own units (e.g.
    /// `friction.mu_k=normal:0.40:0.05`, `foundation.xi_deg=uniform:18:22`). Repeat for more.
    /// The scene's own `[uncertain]` table gives more; a key given both ways takes this one.
    #[arg(long = "dist", value_name = "KEY=DISTRIBUTION")]
    pub dist: Vec<String>,
    /// `lhs` (a Latin hypercube) or `mc` (plain Monte Carlo).
    #[arg(long, value_name = "SAMPLING", default_value = "lhs", value_parser = named::<Sampling, _>(Sampling::ALL.map(Sampling::as_str)))]
    pub sampling: Sampling,
    /// Report the probability that the travel exceeds this (m).
    #[arg(long, value_name = "METRES", allow_negative_numbers = true)]
    pub travel_limit_m: Option<f64>,
    /// Report the probability that the final yaw exceeds this in size (degrees).
    #[arg(long, value_name = "DEGREES", allow_negative_numbers = true)]
    pub rotation_limit_deg: Option<f64>,
    /// Under a ground-motion record: report the probability that the permanent displacement
    /// exceeds this (m).
    #[arg(long, value_name = "METRES", allow_negative_numbers = true)]
    pub displacement_limit_m: Option<f64>,
    /// Dynamics model for every sample, overriding the scene's `[solver] dynamics`.
    #[arg(long, value_name = "MODEL", value_parser = named::<DynamicsModel, _>(DynamicsModel::ALL.map(DynamicsModel::as_str)))]
    pub dynamics: Option<DynamicsModel>,
    /// Output folder (created if needed).
    #[arg(long, value_name = "DIR", default_value = "out/probabilistic")]
    pub out: PathBuf,
    /// No progress bar and no summary (errors are still reported).
    #[arg(long)]
    pub quiet: bool,
    /// No pictures (route-fan.svg, factor-of-safety.svg, sensitivity.svg).
    #[arg(long)]
    pub no_plots: bool,
    /// No route-fan.html (every sample's CM path over the ground in 3-D, in a browser).
    #[arg(long)]
    pub no_3d: bool,
}

/// `slideroute check`.
#[derive(Args)]
pub struct CheckArgs {
    #[command(flatten)]
    pub scene: SceneArg,
    /// Output folder (created if needed).
    #[arg(long, value_name = "DIR", default_value = "out/check")]
    pub out: PathBuf,
    /// No progress bar and no summary (errors are still reported).
    #[arg(long)]
    pub quiet: bool,
    /// No pictures for the failing cases' routes.
    #[arg(long)]
    pub no_plots: bool,
    /// No route in 3-D (route.html, route.glb) for the failing cases' routes.
    #[arg(long)]
    pub no_3d: bool,
    /// Also give the least total prestress of the scene's [[anchor]]s (shared as their
    /// prestresses are, equally where none is given) for each case to meet its guideline: for
    /// sliding alone and for every verdict (in the table and check.json's anchor_design).
    #[arg(long)]
    pub design_anchors: bool,
}

/// `slideroute report`.
#[derive(Args)]
pub struct ReportArgs {
    /// Fewer steps of dt and repeats (under a minute).
    #[arg(long)]
    pub quick: bool,
    /// Output folder (created if needed).
    #[arg(long, value_name = "DIR", default_value = "out/report")]
    pub out: PathBuf,
    /// No progress bar and no summary (errors are still reported).
    #[arg(long)]
    pub quiet: bool,
    /// No picture (work-precision.svg).
    #[arg(long)]
    pub no_plots: bool,
}

/// `slideroute scene`.
#[derive(Args)]
pub struct SceneFileArgs {
    /// Print the embedded default (paper-like) scene.
    #[arg(long, conflicts_with_all = ["check", "template"])]
    pub print_default: bool,
    /// Print a commented scene to start from: `paper` (the default scene) or `dam` (a gravity
    /// monolith with its water, silt, ice, guideline and load cases).
    #[arg(long, value_name = "KIND", conflicts_with = "check")]
    pub template: Option<Template>,
    /// Check this scene file: prints `ok`, or a line for each fault naming the key and the
    /// reason (up to ten).
    #[arg(long, value_name = "FILE")]
    pub check: Option<PathBuf>,
}

/// A scene template (`slideroute scene --template`).
#[derive(Clone, Copy, Debug, clap::ValueEnum)]
pub enum Template {
    /// The paper-like default scene.
    Paper,
    /// A gravity-dam monolith with every section a dam analysis may use.
    Dam,
}

/// `slideroute coeffs`.
#[derive(Args)]
pub struct CoeffsArgs {
    #[command(flatten)]
    pub scene: SceneArg,
    #[command(flatten)]
    pub pose: RequiredPoseArgs,
    /// Print JSON instead of a table.
    #[arg(long)]
    pub json: bool,
}

/// `slideroute roots`.
#[derive(Args)]
pub struct RootsArgs {
    #[command(flatten)]
    pub scene: SceneArg,
    #[command(flatten)]
    pub pose: PoseArgs,
    /// Which system: exact or small-angle. Default: the scene's [solver] mode, else exact.
    #[arg(long, value_name = "MODE", value_parser = named::<Mode, _>(Mode::ALL.map(Mode::as_str)))]
    pub mode: Option<Mode>,
    /// CSV of poses with header `x_m,z_m,theta_deg` (m, m, degrees); needs --out.
    #[arg(long, value_name = "POSES.csv", conflicts_with_all = ["x", "z", "theta_deg"], requires = "out")]
    pub grid: Option<PathBuf>,
    /// Where to write the batch results (CSV), with --grid.
    #[arg(long, value_name = "OUT.csv", requires = "grid")]
    pub out: Option<PathBuf>,
    /// Print JSON instead of a table (single pose; --grid writes CSV).
    #[arg(long, conflicts_with = "grid")]
    pub json: bool,
}
