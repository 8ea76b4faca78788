//! `slideroute run --compare-dynamics`: the paper's route beside the rigid body's, each in its
//! own folder, where they part, both CM paths on one plan view and both routes in 3-D
//! (`compare.html`).

use super::load;
use crate::cli::RunArgs;
use crate::exit::{CliError, bad_input, failed, interrupted, interrupted_after, out};
use crate::output::folder::Folder;
use crate::output::route_files::CsvRows;
use crate::output::summary::CompareSummary;

/// Runs `slideroute run --compare-dynamics`.
pub fn compare(args: &RunArgs) -> Result<(), CliError> {
    let scene = load(&args.scene)?;
    let mut folder = Folder::open(&args.out_dir(), "run").map_err(failed)?;
    // Every row of each route to its route.csv as it is computed (staged, moved into place
    // once both are done), a few kept for the summaries and pictures: bounded memory.
    let staging = folder.staging().map_err(failed)?;
    let staged = [
        ("paper/route.csv", staging.join("paper-route.csv")),
        ("rigid-body/route.csv", staging.join("rigid-body-route.csv")),
    ];
    let writer = |path: &std::path::Path| {
        std::fs::File::create(path)
            .and_then(CsvRows::new)
            .map_err(|e| failed(format!("{}: cannot write: {e}", path.display())))
    };
    let (mut paper, mut rigid) = (writer(&staged[0].1)?, writer(&staged[1].1)?);
    let c = slideroute::compare::compare_dynamics_streamed(
        &scene,
        interrupted,
        &mut |r| paper.push(r),
        &mut |r| rigid.push(r),
    )
    .map_err(bad_input)?;
    for (rows, (name, _)) in [paper, rigid].into_iter().zip(&staged) {
        rows.finish().map_err(|e| failed(format!("{name}: {e}")))?;
    }
    let mut files = Vec::new();
    for (name, path) in &staged {
        files.push(folder.adopt(name, path).map_err(failed)?);
    }
    if !args.no_3d {
        files.extend(
            crate::output::view::many::write_compare_view(
                &mut folder,
                &scene,
                &c.paper.route,
                &c.rigid_body.route,
            )
            .map_err(failed)?,
        );
    }
    #[cfg(feature = "plots")]
    if !args.no_plots {
        let path = folder
            .write_with("compare-plan.svg", |tmp| {
                crate::output::plots::compare_plan(tmp, &scene, &c)
            })
            .map_err(failed)?;
        files.push(path);
    }
    files.extend(
        crate::output::compare_files::write_summaries(&mut folder, &scene, &c).map_err(failed)?,
    );
    folder.finish().map_err(failed)?;
    if interrupted() {
        return Err(interrupted_after(
            "interrupted: the routes stopped at their next increment",
            &files,
        ));
    }
    if !args.quiet {
        out!(
            "{}",
            CompareSummary {
                comparison: &c,
                files: &files
            }
        );
    }
    Ok(())
}
