//! `slideroute check`: each load case against its guideline — the tables, `check.csv`,
//! `check.json`, `report.html` (a page to hand in), and the route of every case that fails in
//! `case-N/`.

use super::{load, stream_route_csv, write_route_folder};
use crate::cli::CheckArgs;
use crate::exit::{CliError, bad_input, failed, interrupted, out, outln};
use crate::output::folder::Folder;
use crate::output::{check_files, check_report, route_files};
use slideroute::Scene;
use slideroute::check::{AnchorDesign, CaseResult, Guideline, check_cases_until, design_anchors};
use std::ops::ControlFlow;
use std::path::PathBuf;

/// `check.json`: the guideline and every case.
#[derive(serde::Serialize)]
struct CheckJson<'a> {
    guideline: &'a Guideline,
    cases: &'a [CaseResult],
    /// With `--design-anchors`: each case's prestress.
    #[serde(skip_serializing_if = "Option::is_none")]
    anchor_design: Option<&'a [AnchorDesign]>,
}

/// Runs `slideroute check`.
pub fn check(args: &CheckArgs) -> Result<(), CliError> {
    let scene = load(&args.scene)?;
    let mut folder = Folder::open(&args.out, "check").map_err(failed)?;
    let results = check_cases_until(&scene, |_| (), interrupted).map_err(bad_input)?;
    if interrupted() {
        // A check is filed whole: nothing of a partial one is written.
        let done = results
            .iter()
            .filter(|r| r.run.route.termination.reason != slideroute::Reason::Interrupted)
            .count();
        return Err(failed(format!(
            "interrupted: the check stopped after {done} of {} cases; nothing was written",
            scene.cases().len().max(1)
        )));
    }
    let design = if args.design_anchors {
        Some(design_anchors(&scene).map_err(bad_input)?)
    } else {
        None
    };
    let mut written = failing_routes(&folder, &scene, &results, args)?;
    written.push(
        folder
            .write_with("check.csv", |tmp| {
                let file = std::fs::File::create(tmp)
                    .map_err(|e| format!("{}: cannot write: {e}", tmp.display()))?;
                check_files::write_csv(file, &results).map_err(|e| format!("check.csv: {e}"))
            })
            .map_err(failed)?,
    );
    let manifest = route_files::Manifest::new(&scene, &folder);
    let page = check_report::report(
        scene.name(),
        scene.guideline(),
        scene.monolith().map(|m| &m.section),
        &results,
        &toml::to_string(&manifest.scene).unwrap_or_default(),
        &serde_json::to_string_pretty(&manifest).unwrap_or_default(),
    );
    written.push(
        folder
            .write_bytes("report.html", page.as_bytes())
            .map_err(failed)?,
    );
    // The manifest of check.json names every file beside it, report.html too.
    let manifest = route_files::Manifest::new(&scene, &folder);
    let json = CheckJson {
        guideline: scene.guideline(),
        cases: &results,
        anchor_design: design.as_deref(),
    };
    written.push(
        route_files::write_json_with_manifest(&mut folder, "check.json", &json, &manifest)
            .map_err(failed)?,
    );
    folder.finish().map_err(failed)?;
    if !args.quiet {
        let table = check_files::CheckTable {
            scene: scene.name(),
            guideline: scene.guideline().describe(),
            results: &results,
        };
        out!("{table}");
        if let Some(d) = &design {
            out!("{}", check_files::AnchorTable(d));
        }
        let names: Vec<String> = written.iter().map(|p| p.display().to_string()).collect();
        outln!("  wrote {}", names.join(", "));
    }
    Ok(())
}

/// The route of each case that fails, in `case-N/` (N its number among the cases).
fn failing_routes(
    folder: &Folder,
    scene: &Scene,
    results: &[CaseResult],
    args: &CheckArgs,
) -> Result<Vec<PathBuf>, CliError> {
    let mut written = Vec::new();
    for (k, r) in results.iter().enumerate().filter(|(_, r)| !r.passes) {
        let case_scene = scene.for_case(&r.case).map_err(bad_input)?;
        let sim = case_scene.simulation().map_err(bad_input)?;
        let mut sub = folder
            .open_inside(&format!("case-{k}"), "check")
            .map_err(failed)?;
        // The check kept a few of the case's rows: its route again, every row to route.csv
        // as it is computed (the same route: the computation is deterministic).
        let stop = |_: f64| {
            if interrupted() {
                ControlFlow::Break(())
            } else {
                ControlFlow::Continue(())
            }
        };
        let (csv, run) = stream_route_csv(&mut sub, "route.csv", &sim, stop).map_err(failed)?;
        written.push(csv);
        written.extend(
            write_route_folder(sub, &case_scene, &run, args.no_plots, args.no_3d)
                .map_err(failed)?,
        );
        if interrupted() {
            return Err(failed(
                "interrupted: the check's failing cases' routes were being written; the \
                 check's own files were not written",
            ));
        }
    }
    Ok(written)
}
