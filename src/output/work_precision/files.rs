//! The report's files: `work-precision.csv`, its points as a table; `work-precision.md`, the
//! whole report as markdown; and, with the pictures, `work-precision.svg`, drawn by
//! `plots/work_precision.rs`.

use super::extreme::ExtremeRow;
use super::ladder::{Point, Reference, speedups};
use crate::output::{OutputError, OutputFolder, Written};
use std::fmt::Write as _;
use std::io::Write;

const HEADER: [&str; 11] = [
    "scene",
    "dynamics",
    "method",
    "mode",
    "integrator",
    "dt_s",
    "tolerance",
    "increments",
    "steps",
    "wall_s",
    "error_m",
];

/// Writes `work-precision.csv`, `work-precision.md` and (with `pictures`, where the library
/// draws them) `work-precision.svg` into `folder`, and finishes it.
pub(super) fn write(
    mut folder: OutputFolder,
    (points, references, extreme): (&[Point], &[Reference], &[ExtremeRow]),
    quick: bool,
    pictures: bool,
) -> Result<Written, OutputError> {
    let csv = folder.write_with("work-precision.csv", |tmp| {
        let file = std::fs::File::create(tmp)
            .map_err(|e| format!("{}: cannot write: {e}", tmp.display()))?;
        write_csv(file, points).map_err(|e| format!("work-precision.csv: {e}"))
    })?;
    let md = markdown(points, references, extreme, quick);
    let md = folder.write_bytes("work-precision.md", md.as_bytes())?;
    #[allow(unused_mut)]
    let mut written = Written {
        files: vec![csv, md],
        warnings: Vec::new(),
    };
    #[cfg(feature = "plots")]
    if pictures {
        written
            .files
            .push(folder.write_with("work-precision.svg", |tmp| {
                crate::output::plots::work_precision(tmp, points)
            })?);
    }
    #[cfg(not(feature = "plots"))]
    let _ = pictures;
    folder.finish()?;
    Ok(written)
}

fn write_csv(out: impl Write, points: &[Point]) -> Result<(), csv::Error> {
    let mut w = csv::Writer::from_writer(out);
    w.write_record(HEADER)?;
    for p in points {
        w.write_record([
            p.scene.clone(),
            p.dynamics.as_str().to_string(),
            p.method.as_str().to_string(),
            p.mode.as_str().to_string(),
            p.integrator.as_str().to_string(),
            p.dt_s.to_string(),
            p.tolerance.map_or(String::new(), |t| t.to_string()),
            p.increments.to_string(),
            p.steps.to_string(),
            p.wall_s.to_string(),
            p.error_m.to_string(),
        ])?;
    }
    w.flush()?;
    Ok(())
}

/// The report as markdown: references, the work–precision table, continuation against all
/// roots, the extreme cases.
fn markdown(
    points: &[Point],
    references: &[Reference],
    extreme: &[ExtremeRow],
    quick: bool,
) -> String {
    let mut s = String::new();
    let _ = writeln!(
        s,
        "# Work–precision report{}\n",
        if quick { " (quick)" } else { "" }
    );
    let _ = writeln!(
        s,
        "Error: largest distance of the CM from the reference at matching times. Time: median wall time of the whole route (repeats)."
    );
    references_section(&mut s, references);
    points_section(&mut s, points);
    speedups_section(&mut s, points);
    extreme_section(&mut s, extreme);
    s
}

/// The section of the references: how each was established.
fn references_section(s: &mut String, references: &[Reference]) {
    section(
        s,
        "References",
        "",
        "scene | dynamics | horizon (s) | dt (s) | tolerance | change at dt/2 or tolerance/10 (m) | bound 1e-9·L (m)",
    );
    for r in references {
        let _ = writeln!(
            s,
            "| {} | {} | {} | {:.4e} | {} | {:.2e} | {:.0e} |",
            r.scene,
            r.dynamics.as_str(),
            r.horizon_s,
            r.dt_s,
            r.tolerance.map_or("—".into(), |t| format!("{t:.0e}")),
            r.change_m,
            r.bound_m
        );
    }
}

/// The section of the work–precision table: each point's error and time.
fn points_section(s: &mut String, points: &[Point]) {
    section(
        s,
        "Error and time",
        "Each dynamics against its own reference: the paper's over its increment dt (RK4 at the loosest tolerance, so that no increment is cut) and, continuation in exact mode with RK4, over its tolerance with rows every 0.02 s; the rigid body over its tolerance (its steps its own, its rows every dt).",
        "scene | dynamics | method | mode | integrator | dt (s) | tolerance | steps | time (ms) | error (m) | µs / step",
    );
    for p in points {
        let _ = writeln!(
            s,
            "| {} | {} | {} | {} | {} | {} | {} | {} | {:.3} | {:.2e} | {:.2} |",
            p.scene,
            p.dynamics.as_str(),
            p.method.as_str(),
            p.mode.as_str(),
            p.integrator.as_str(),
            p.dt_s,
            p.tolerance.map_or("—".into(), |t| format!("{t:.0e}")),
            p.steps,
            p.wall_s * 1e3,
            p.error_m,
            p.wall_s * 1e6 / p.steps.max(1) as f64
        );
    }
}

/// The section of continuation against all roots at equal error.
fn speedups_section(s: &mut String, points: &[Point]) {
    section(
        s,
        "Continuation against all roots",
        "The paper's dynamics, per increment, at equal error (the same dt gives the same route by both: the error gap is round-off). All roots: the eigenvalue solve for the pose and all solutions of the frictional reactions at every increment; continuation: the tracker and Newton from the previous increment's reactions.",
        "scene | mode | integrator | dt (s) | continuation (µs) | all roots (µs) | all roots / continuation | error gap (m)",
    );
    for r in speedups(points) {
        let _ = writeln!(
            s,
            "| {} | {} | {} | {} | {:.2} | {:.2} | {:.1}× | {:.1e} |",
            r.scene,
            r.mode.as_str(),
            r.integrator.as_str(),
            r.dt_s,
            r.continuation_us,
            r.all_roots_us,
            r.ratio,
            r.error_gap_m
        );
    }
}

/// The section of the stiff and extreme cases.
fn extreme_section(s: &mut String, extreme: &[ExtremeRow]) {
    section(
        s,
        "Stiff and extreme cases",
        "",
        "case | end | t (s) | travel (m) | increments | rejected steps | Newton / step | cond(J) at end | max tilt error vs direct (rad)",
    );
    for e in extreme {
        let _ = writeln!(
            s,
            "| {} | {} | {:.3} | {:.3} | {} | {} | {:.2} | {} | {} |",
            e.case,
            e.reason,
            e.t_s,
            e.travel_m,
            e.increments,
            e.rejected_steps,
            e.newton_per_step,
            e.end_jacobian_condition
                .map_or("—".into(), |c| format!("{c:.2e}")),
            e.max_tilt_error_rad
                .map_or("—".into(), |c| format!("{c:.1e}"))
        );
    }
}

/// A section of the markdown after a blank line: its `heading`, its `words` (where there are
/// any), and the head of its table, the `columns` as they stand in it ("a | b | c").
fn section(s: &mut String, heading: &str, words: &str, columns: &str) {
    let _ = write!(s, "\n## {heading}\n\n");
    if !words.is_empty() {
        let _ = write!(s, "{words}\n\n");
    }
    let _ = writeln!(s, "| {columns} |");
    let _ = writeln!(s, "|{}", " --- |".repeat(columns.split(" | ").count()));
}
