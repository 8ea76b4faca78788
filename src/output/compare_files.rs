//! Files of `slideroute run --compare-dynamics`: each route in its own folder (`paper/`,
//! `rigid-body/`: route.csv and summary.json), `comparison.json` (both summaries and where
//! they part) and, with plots, `compare-plan.svg` (both CM paths on one plan view).

use super::route_files;
use crate::compare::Comparison;
use std::path::{Path, PathBuf};

/// Writes the comparison into `dir`; returns the paths written.
pub fn write(dir: &Path, c: &Comparison) -> Result<Vec<PathBuf>, String> {
    let mut files = Vec::new();
    files.extend(route_files::write(&dir.join("paper"), &c.paper)?);
    files.extend(route_files::write(&dir.join("rigid-body"), &c.rigid_body)?);
    let path = dir.join("comparison.json");
    let text = serde_json::to_string_pretty(c).map_err(|e| format!("comparison: {e}"))?;
    std::fs::write(&path, text + "\n")
        .map_err(|e| format!("{}: cannot write: {e}", path.display()))?;
    files.push(path);
    Ok(files)
}
