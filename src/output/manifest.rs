//! What produced an output folder, written into its manifest (`summary.json`, `check.json`,
//! `comparison.json`, `probabilistic.json`): the version, the command line, the scene as used,
//! its loads and the files beside it.

use super::{OutputError, OutputFolder};
use crate::Scene;
use std::path::PathBuf;

/// What produced an output folder: `summary.json` carries it, so that anyone
/// holding the folder can tell.
#[derive(Debug, Clone, serde::Serialize)]
pub(crate) struct Manifest {
    /// The slideroute version.
    pub slideroute_version: &'static str,
    /// The command line, word for word.
    pub command_line: Vec<String>,
    /// The scene exactly as used: every value, defaults filled in, in the file's keys and units
    /// (`Scene::as_used`).
    pub scene: toml::Table,
    /// The loads the route used, in the engineer's terms (`Scene::loads_used`): weight, the
    /// water's net push and its couples, the uplift, the pseudo-static coefficients, and from
    /// `[water]` each water load with where it acts.
    pub loads: Option<crate::LoadsUsed>,
    /// The other files this run wrote into the folder, with their sizes.
    pub files: Vec<FileEntry>,
}

/// One file of an output folder.
#[derive(Debug, Clone, serde::Serialize)]
pub(crate) struct FileEntry {
    pub name: String,
    pub bytes: u64,
}

impl Manifest {
    /// For this process's command line, `scene`, and the files `folder` holds so far.
    pub(crate) fn new(scene: &Scene, folder: &OutputFolder) -> Manifest {
        Manifest {
            slideroute_version: env!("CARGO_PKG_VERSION"),
            command_line: std::env::args().collect(),
            scene: scene.as_used(),
            loads: scene.loads_used(),
            files: folder
                .written()
                .iter()
                .map(|(name, bytes)| FileEntry {
                    name: name.clone(),
                    bytes: *bytes,
                })
                .collect(),
        }
    }
}

/// `value` with the manifest, as pretty JSON, written as `name` into `folder`: the command's
/// manifest ([`OutputFolder::write_manifest`]), so written after every other file of the run.
pub(crate) fn write_json_with_manifest(
    folder: &mut OutputFolder,
    name: &str,
    value: &impl serde::Serialize,
    manifest: &Manifest,
) -> Result<PathBuf, OutputError> {
    #[derive(serde::Serialize)]
    struct WithManifest<'a, T: serde::Serialize> {
        #[serde(flatten)]
        value: &'a T,
        manifest: &'a Manifest,
    }
    let text = serde_json::to_string_pretty(&WithManifest { value, manifest })
        .map_err(|e| format!("{name}: {e}"))?;
    folder.write_manifest(name, (text + "\n").as_bytes())
}
