//! Files of `slideroute run --compare-dynamics`: each route in its own folder (`paper/`,
//! `rigid-body/`: route.csv and summary.json), `comparison.json` (both summaries and where
//! they part, with the manifest) and, with plots, `compare-plan.svg` (both CM paths on one plan
//! view, drawn by the command).

use super::folder::Folder;
use super::route_files::{self, Manifest};
use slideroute::Scene;
use slideroute::compare::Comparison;
use std::path::PathBuf;

/// Each route's folder as the comparison names it, with its route.
fn both(c: &Comparison) -> [(&'static str, &slideroute::Computed); 2] {
    [("paper", &c.paper), ("rigid-body", &c.rigid_body)]
}

/// Writes both routes' `summary.json` and `comparison.json` (the manifests, last) into
/// `folder`; returns the paths written.
pub fn write_summaries(
    folder: &mut Folder,
    scene: &Scene,
    c: &Comparison,
) -> Result<Vec<PathBuf>, String> {
    let mut files = Vec::new();
    for (sub, computed) in both(c) {
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
