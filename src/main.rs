//! The `slideroute` command line: parses, calls the library, prints.

use clap::{Parser, Subcommand};
use slideroute::geometry::Displacement;
use slideroute::output::CoeffReport;
use slideroute::scene::Scene;
use std::path::PathBuf;
use std::process::ExitCode;

/// Three-dimensional failure route of a sliding dam monolith (after Galic & Glaser).
///
/// Units: metres, newtons, seconds; angles in degrees on the command line and in every file.
#[derive(Parser)]
#[command(name = "slideroute", version, about, long_about = None)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Print the coefficients of the small-angle system (15) (f1–f12) and of the exact form
    /// at one displacement (X, Z, θ) of the centre of mass.
    Coeffs {
        /// Scene file (TOML). Without it, the embedded default (paper-like) scene.
        #[arg(long, value_name = "FILE")]
        scene: Option<PathBuf>,
        /// X: CM displacement along the global X axis (forward), in metres.
        #[arg(long, value_name = "METRES", allow_negative_numbers = true)]
        x: f64,
        /// Z: CM displacement along the global Z axis (lateral), in metres.
        #[arg(long, value_name = "METRES", allow_negative_numbers = true)]
        z: f64,
        /// θ: yaw of side 01 from +X towards +Z, in degrees.
        #[arg(
            long = "theta-deg",
            value_name = "DEGREES",
            allow_negative_numbers = true
        )]
        theta_deg: f64,
        /// Print JSON instead of a table.
        #[arg(long)]
        json: bool,
    },
}

/// One line on standard error, exit code 2: bad input.
fn fail(msg: impl std::fmt::Display) -> ExitCode {
    eprintln!("slideroute: {msg}");
    ExitCode::from(2)
}

fn load(scene: Option<&PathBuf>) -> Result<Scene, slideroute::scene::SceneError> {
    match scene {
        Some(p) => Scene::from_file(p),
        None => Ok(Scene::default_scene()),
    }
}

fn finite_flag(name: &str, v: f64) -> Result<f64, String> {
    if v.is_finite() {
        Ok(v)
    } else {
        Err(format!("--{name}: must be a finite number, got {v}"))
    }
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    match cli.command {
        Command::Coeffs {
            scene,
            x,
            z,
            theta_deg,
            json,
        } => {
            let scene = match load(scene.as_ref()) {
                Ok(s) => s,
                Err(e) => return fail(e),
            };
            let d = match (
                finite_flag("x", x),
                finite_flag("z", z),
                finite_flag("theta-deg", theta_deg),
            ) {
                (Ok(x), Ok(z), Ok(t)) => Displacement::new(x, z, t.to_radians()),
                (Err(e), _, _) | (_, Err(e), _) | (_, _, Err(e)) => return fail(e),
            };
            let report = CoeffReport::new(&scene, d);
            if json {
                match serde_json::to_string_pretty(&report) {
                    Ok(s) => println!("{s}"),
                    Err(e) => return fail(format!("cannot write JSON: {e}")),
                }
            } else {
                print!("{report}");
            }
        }
    }
    ExitCode::SUCCESS
}
