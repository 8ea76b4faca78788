//! The files of the paper's route beside the rigid body's, as `slideroute run
//! --compare-dynamics` writes them: each route in its own folder (`paper/`, `rigid-body/`:
//! route.csv and summary.json), both in 3-D (`compare.html`), both CM paths on one plan view
//! (`compare-plan.svg`) and `comparison.json` (both summaries and where they part, with the
//! manifest, last).

use super::manifest::{Manifest, write_json_with_manifest};
use super::{OutputError, OutputFolder, RouteCsv, Written};
use crate::Scene;
use crate::compare::{Comparison, compare_dynamics_streamed};
use std::fs::File;
use std::path::{Path, PathBuf};

/// The comparison of a scene's two dynamics and its files, whole or absent: what `slideroute
/// run --compare-dynamics` writes.
///
/// ```
/// use slideroute::output::{ComparisonFiles, OutputFolder};
/// let scene = slideroute::Scene::default_scene().with("solver.t_end_s", 0.2)?;
/// let dir = std::env::temp_dir().join(format!("slideroute-doc-compare-{}", std::process::id()));
/// let (comparison, written) = ComparisonFiles::new(&scene)
///     .view(false)
///     .write(OutputFolder::open(&dir, "run")?, || false)?;
/// assert!(written.files.iter().any(|f| f.ends_with("paper/route.csv")));
/// println!("{}", comparison.summary(&written.files));
/// # std::fs::remove_dir_all(&dir)?;
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Debug, Clone, Copy)]
pub struct ComparisonFiles<'a> {
    scene: &'a Scene,
    pictures: bool,
    view: bool,
}

impl<'a> ComparisonFiles<'a> {
    /// The comparison of `scene`'s two dynamics, with its picture and 3-D page.
    pub fn new(scene: &'a Scene) -> ComparisonFiles<'a> {
        ComparisonFiles {
            scene,
            pictures: true,
            view: true,
        }
    }

    /// With `compare-plan.svg` or without it.
    pub fn pictures(self, on: bool) -> ComparisonFiles<'a> {
        ComparisonFiles {
            pictures: on,
            ..self
        }
    }

    /// With `compare.html` or without it.
    pub fn view(self, on: bool) -> ComparisonFiles<'a> {
        ComparisonFiles { view: on, ..self }
    }

    /// Computes both routes, every row of each to its route.csv as it is computed (staged,
    /// moved into place once both are done; a few kept for the summaries and pictures: bounded
    /// memory), then writes the page, the picture and the summaries into `folder` and finishes
    /// it. `stop` stops both routes at their next increment (they are written as far as they
    /// went). A scene whose dynamics cannot be compared is [`OutputError::Input`].
    pub fn write(
        &self,
        mut folder: OutputFolder,
        stop: impl Fn() -> bool,
    ) -> Result<(Comparison, Written), OutputError> {
        let staging = folder.staging()?;
        let staged = [
            ("paper/route.csv", staging.join("paper-route.csv")),
            ("rigid-body/route.csv", staging.join("rigid-body-route.csv")),
        ];
        let writer = |path: &Path| {
            File::create(path)
                .and_then(RouteCsv::new)
                .map_err(|e| OutputError::Write(format!("{}: cannot write: {e}", path.display())))
        };
        let (mut paper, mut rigid) = (writer(&staged[0].1)?, writer(&staged[1].1)?);
        let c = compare_dynamics_streamed(self.scene, stop, &mut |r| paper.push(r), &mut |r| {
            rigid.push(r)
        })
        .map_err(|e| OutputError::Input(e.to_string()))?;
        for (rows, (name, _)) in [paper, rigid].into_iter().zip(&staged) {
            rows.finish().map_err(|e| format!("{name}: {e}"))?;
        }
        let mut written = Written::default();
        for (name, path) in &staged {
            written.files.push(folder.adopt(name, path)?);
        }
        written.extend(self.pictured(&mut folder, &c)?);
        written
            .files
            .extend(write_summaries(&mut folder, self.scene, &c)?);
        folder.finish()?;
        Ok((c, written))
    }

    /// `compare.html` and `compare-plan.svg`, as asked and built.
    fn pictured(&self, folder: &mut OutputFolder, c: &Comparison) -> Result<Written, OutputError> {
        #[allow(unused_mut)]
        let mut written = Written::default();
        #[cfg(feature = "view")]
        if self.view {
            written.extend(super::view::write_compare_view(
                folder,
                self.scene,
                &c.paper.route,
                &c.rigid_body.route,
            )?);
        }
        #[cfg(feature = "plots")]
        if self.pictures {
            written
                .files
                .push(folder.write_with("compare-plan.svg", |tmp| {
                    super::plots::compare_plan(tmp, self.scene, c)
                })?);
        }
        #[cfg(not(all(feature = "view", feature = "plots")))]
        let _ = (self.pictures, self.view, folder, c);
        Ok(written)
    }
}

/// Each route's folder as the comparison names it, with its route.
fn both(c: &Comparison) -> [(&'static str, &crate::Computed); 2] {
    [("paper", &c.paper), ("rigid-body", &c.rigid_body)]
}

/// Writes both routes' `summary.json` and `comparison.json` (the manifests, last) into
/// `folder`; returns the paths written.
fn write_summaries(
    folder: &mut OutputFolder,
    scene: &Scene,
    c: &Comparison,
) -> Result<Vec<PathBuf>, OutputError> {
    let mut files = Vec::new();
    for (sub, computed) in both(c) {
        let scene = scene
            .with_dynamics(computed.route.dynamics)
            .map_err(|e| OutputError::Write(e.to_string()))?;
        let manifest = Manifest::new(&scene, folder);
        files.push(write_json_with_manifest(
            folder,
            &format!("{sub}/summary.json"),
            computed,
            &manifest,
        )?);
    }
    let manifest = Manifest::new(scene, folder);
    files.push(write_json_with_manifest(
        folder,
        "comparison.json",
        c,
        &manifest,
    )?);
    Ok(files)
}
