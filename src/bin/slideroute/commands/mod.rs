//! One file per command: each reads its arguments, calls the library, has it write its files
//! (`slideroute::output`) and prints its summary. What they share is here: the scene a command
//! reads, the progress bar, a displacement from flags, and JSON on standard output.

pub mod check;
pub mod coeffs;
pub mod compare;
pub mod probabilistic;
pub mod report;
pub mod roots;
pub mod run;
pub mod scene;
pub mod sweep;

use crate::cli::{PoseArgs, SceneArg};
use crate::exit::{CliError, bad_input, failed, outln, scene_faults};
use slideroute::{Displacement, DynamicsModel, Scene};

/// The scene of `arg` (the embedded default without a file), its likely mistakes warned of on
/// standard error.
pub fn load(arg: &SceneArg) -> Result<Scene, CliError> {
    let scene = match &arg.scene {
        Some(p) => Scene::from_file(p).map_err(scene_faults)?,
        None => Scene::default_scene(),
    };
    let scene = if arg.set.is_empty() {
        scene
    } else {
        let keys = arg
            .set
            .iter()
            .map(|s| setting(s))
            .collect::<Result<Vec<_>, _>>()?;
        scene.with_keys(keys).map_err(scene_faults)?
    };
    for w in scene.warnings() {
        eprintln!("slideroute: warning: {w}");
    }
    Ok(scene)
}

/// One `--set KEY=VALUE`: the key, and the value read as TOML (`14.5`, `true`, `"a b"`,
/// `[1, 2]`), else as a word (`small-angle`).
fn setting(s: &str) -> Result<(String, toml::Value), CliError> {
    let Some((key, value)) = s.split_once('=') else {
        return Err(bad_input(format!(
            "--set {s}: say KEY=VALUE, e.g. --set water.headwater_m=14.5"
        )));
    };
    let (key, value) = (key.trim(), value.trim());
    if key.is_empty() || value.is_empty() {
        return Err(bad_input(format!(
            "--set {s}: say KEY=VALUE, e.g. --set water.headwater_m=14.5"
        )));
    }
    let parsed = format!("v = {value}")
        .parse::<toml::Table>()
        .ok()
        .and_then(|mut t| t.remove("v"));
    // Digits that TOML does not take: a whole number past i64 (else read as a word, and
    // refused as "invalid type: string").
    let digits = value.strip_prefix(['+', '-']).unwrap_or(value);
    if parsed.is_none() && !digits.is_empty() && digits.bytes().all(|b| b.is_ascii_digit()) {
        return Err(bad_input(format!(
            "--set {s}: {value} is past the largest whole number a scene takes ({})",
            i64::MAX
        )));
    }
    Ok((
        key.to_string(),
        parsed.unwrap_or_else(|| toml::Value::String(value.to_string())),
    ))
}

/// [`load`], with its dynamics model overridden when `dynamics` says.
pub fn load_with(arg: &SceneArg, dynamics: Option<DynamicsModel>) -> Result<Scene, CliError> {
    let base = load(arg)?;
    match dynamics {
        Some(model) => base.with_dynamics(model).map_err(bad_input),
        None => Ok(base),
    }
}

/// A progress bar of `len` `units` (`combinations`, `samples`, …) labelled `what`, with the
/// time elapsed and the time left at the pace so far, drawn on standard error only when it is
/// a terminal; none when `quiet`.
pub fn progress_bar(quiet: bool, len: u64, what: &str, units: &str) -> indicatif::ProgressBar {
    styled_bar(
        quiet,
        len,
        &format!("{what} [{{bar:30}}] {{pos}}/{{len}} {units}"),
    )
}

/// A progress bar of a route to `t_end_s` of simulated time, in thousandths of it.
pub fn route_bar(quiet: bool, t_end_s: f64) -> indicatif::ProgressBar {
    styled_bar(
        quiet,
        ROUTE_STEPS,
        &format!("route [{{bar:30}}] {{percent:>3}} % of {t_end_s} s simulated"),
    )
}

/// The steps of [`route_bar`].
pub const ROUTE_STEPS: u64 = 1000;

fn styled_bar(quiet: bool, len: u64, head: &str) -> indicatif::ProgressBar {
    if quiet {
        return indicatif::ProgressBar::hidden();
    }
    let bar = indicatif::ProgressBar::new(len);
    let style = indicatif::ProgressStyle::with_template(&format!(
        "{head}, {{elapsed}} elapsed, about {{eta}} left"
    ))
    .unwrap_or_else(|_| indicatif::ProgressStyle::default_bar());
    bar.set_style(style.progress_chars("=> "));
    bar
}

/// The displacement the flags give, each of X, Z and θ required and finite.
pub fn displacement(p: &PoseArgs) -> Result<Displacement, CliError> {
    let get = |name: &str, v: Option<f64>| match v {
        None => Err(bad_input(format!("--{name} is required"))),
        Some(v) if !v.is_finite() => Err(bad_input(format!(
            "--{name}: must be a finite number, got {v}"
        ))),
        Some(v) => Ok(v),
    };
    Ok(Displacement::new(
        get("x", p.x)?,
        get("z", p.z)?,
        get("theta-deg", p.theta_deg)?.to_radians(),
    ))
}

/// Says each of `warnings` (what a writer left out, and why) on standard error.
pub fn warn_all(warnings: &[String]) {
    for w in warnings {
        eprintln!("slideroute: warning: {w}");
    }
}

/// `value` as pretty JSON on standard output.
pub fn print_json(value: &impl serde::Serialize) -> Result<(), CliError> {
    let s = serde_json::to_string_pretty(value)
        .map_err(|e| failed(format!("cannot write JSON: {e}")))?;
    outln!("{s}");
    Ok(())
}
