//! A route's files, as `slideroute run` writes them into its folder: `route.csv` (streamed as
//! the route computes), the route in 3-D (`route.html`, `route.glb`), the pictures (`plan.svg`,
//! `profile.svg`, `angles.svg`, `reactions.svg`) and `summary.json` (with the manifest, last).

use super::manifest::{Manifest, write_json_with_manifest};
use super::{OutputError, OutputFolder, RouteCsv, Written};
use crate::{Computed, KEPT_ROWS, Runner, Scene, Simulation};
use std::ops::ControlFlow;
use std::path::PathBuf;

/// The files of one route in an output folder, whole or absent: what `slideroute run` writes.
/// The pictures and the 3-D view are written where the library was built with them (the
/// `plots` and `view` features) and asked for (both are, unless turned off).
///
/// ```
/// use slideroute::output::{OutputFolder, RouteFiles};
/// let scene = slideroute::Scene::default_scene().with("solver.t_end_s", 0.05)?;
/// let sim = scene.simulation()?;
/// let dir = std::env::temp_dir().join(format!("slideroute-doc-route-{}", std::process::id()));
/// let mut folder = OutputFolder::open(&dir, "run")?;
/// let files = RouteFiles::new(&scene).view(false);
/// // route.csv, every row written as it is computed.
/// let (csv, computed) = files.stream(&mut folder, &sim, |_| std::ops::ControlFlow::Continue(()))?;
/// // The pictures and summary.json beside it; the folder finished.
/// let written = files.write(folder, &computed)?;
/// assert!(csv.ends_with("route.csv") && written.files.iter().any(|f| f.ends_with("summary.json")));
/// # std::fs::remove_dir_all(&dir)?;
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Debug, Clone, Copy)]
pub struct RouteFiles<'a> {
    scene: &'a Scene,
    pictures: bool,
    view: bool,
}

impl<'a> RouteFiles<'a> {
    /// The files of a route of `scene`, pictures and the 3-D view included.
    pub fn new(scene: &'a Scene) -> RouteFiles<'a> {
        RouteFiles {
            scene,
            pictures: true,
            view: true,
        }
    }

    /// With the pictures or without them.
    pub fn pictures(self, on: bool) -> RouteFiles<'a> {
        RouteFiles {
            pictures: on,
            ..self
        }
    }

    /// With the route in 3-D (`route.html`, `route.glb`) or without it.
    pub fn view(self, on: bool) -> RouteFiles<'a> {
        RouteFiles { view: on, ..self }
    }

    /// The route of `sim` with every row streamed into `route.csv` in `folder` as it is
    /// computed, at most [`KEPT_ROWS`] rows kept in memory for the pictures and the summary: a
    /// route of any length in bounded memory. `progress` as [`Runner::progress`] (a `Break`
    /// stops the route, which ends "interrupted" and is written as far as it went).
    pub fn stream(
        &self,
        folder: &mut OutputFolder,
        sim: &Simulation,
        progress: impl FnMut(f64) -> ControlFlow<()>,
    ) -> Result<(PathBuf, Computed), OutputError> {
        stream_csv(folder, "route.csv", sim, progress)
    }

    /// The rest of the route's files beside its `route.csv`: the route in 3-D, the pictures,
    /// and `summary.json` (the manifest, last, naming every file of the folder), each whole or
    /// absent, replacing an earlier run's outputs there; then the folder is finished. A route
    /// with nothing to show in 3-D gets no page, with a warning.
    pub fn write(
        &self,
        mut folder: OutputFolder,
        computed: &Computed,
    ) -> Result<Written, OutputError> {
        #[allow(unused_mut)]
        let mut written = Written::default();
        #[cfg(not(all(feature = "view", feature = "plots")))]
        let _ = (self.pictures, self.view);
        #[cfg(feature = "view")]
        if self.view {
            written.extend(super::view::write_route_view(
                &mut folder,
                self.scene,
                &computed.route,
            )?);
        }
        #[cfg(feature = "plots")]
        if self.pictures {
            let staging = folder.staging()?;
            let staged = super::plots::write_route_plots(&staging, self.scene, &computed.route)?;
            written.files.extend(folder.adopt_all(staged)?);
        }
        let manifest = Manifest::new(self.scene, &folder);
        written.files.push(write_json_with_manifest(
            &mut folder,
            "summary.json",
            computed,
            &manifest,
        )?);
        folder.finish()?;
        Ok(written)
    }
}

/// The route of `sim` with every row streamed into `name` in `folder` as it is computed (as
/// [`RouteFiles::stream`]).
pub(crate) fn stream_csv(
    folder: &mut OutputFolder,
    name: &str,
    sim: &Simulation,
    progress: impl FnMut(f64) -> ControlFlow<()>,
) -> Result<(PathBuf, Computed), OutputError> {
    let mut computed = None;
    let path = folder.write_with(name, |tmp| {
        let file = std::fs::File::create(tmp)
            .map_err(|e| format!("{}: cannot write: {e}", tmp.display()))?;
        let mut rows = RouteCsv::new(file).map_err(|e| format!("{name}: {e}"))?;
        let run = Runner::new(sim)
            .progress(progress)
            .stream(1, |r| rows.push(r))
            .keep_at_most(KEPT_ROWS)
            .run();
        computed = Some(run);
        rows.finish().map(drop).map_err(|e| format!("{name}: {e}"))
    })?;
    let computed = computed.ok_or_else(|| format!("{name}: no route"))?;
    Ok((path, computed))
}
