//! Files of `slideroute run --compare-dynamics`: each route in its own folder (`paper/`,
//! `rigid-body/`: route.csv and summary.json), `comparison.json` (both summaries and where
//! they part, with the manifest) and, with plots, `compare-plan.svg` (both CM paths on one plan
//! view, drawn by the command).

use super::folder::Folder;
use super::route_files::{self, Manifest};
use slideroute::Scene;
use slideroute::compare::Comparison;
use std::path::PathBuf;

/// Writes both routes and `comparison.json` into `folder`; returns the paths written.
pub fn write(folder: &mut Folder, scene: &Scene, c: &Comparison) -> Result<Vec<PathBuf>, String> {
    let mut files = Vec::new();
    for (sub, computed) in [("paper", &c.paper), ("rigid-body", &c.rigid_body)] {
        files.push(route_files::write_route_csv(
            folder,
            &format!("{sub}/route.csv"),
            &computed.route.rows,
        )?);
        let scene = scene
            .with_dynamics(computed.route.dynamics)
            .map_err(|e| e.to_string())?;
        let manifest = Manifest::new(&scene, folder);
        files.push(route_files::write_json_with_manifest(
            folder,
            &format!("{sub}/summary.json"),
            computed,
            &manifest,
        )?);
    }
    let manifest = Manifest::new(scene, folder);
    files.push(route_files::write_json_with_manifest(
        folder,
        "comparison.json",
        c,
        &manifest,
    )?);
    Ok(files)
}
