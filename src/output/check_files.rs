//! The files of a check of load cases, as `slideroute check` writes them: the route of every
//! case that fails in `case-N/`, `check.csv`, `report.html` (a page to hand in) and `check.json`
//! (the guideline and every case, with the manifest, last).

use super::check_tables::{AnchorTable, CheckTable};
use super::manifest::{Manifest, write_json_with_manifest};
use super::route_files::RouteFiles;
use super::{OutputError, OutputFolder, Written};
use crate::Scene;
use crate::check::{AnchorDesign, CaseResult, Guideline};
use std::fmt;
use std::ops::ControlFlow;

/// `check.json`: the guideline and every case.
#[derive(serde::Serialize)]
struct CheckJson<'a> {
    guideline: &'a Guideline,
    cases: &'a [CaseResult],
    /// With `--design-anchors`: each case's prestress.
    #[serde(skip_serializing_if = "Option::is_none")]
    anchor_design: Option<&'a [AnchorDesign]>,
}

/// The files of a check of `scene`'s load cases ([`check_cases`](crate::check::check_cases)),
/// whole or absent: what `slideroute check` writes. Each failing case's route is written as
/// [`RouteFiles`] writes a route, with its pictures and 3-D view unless turned off.
///
/// ```
/// use slideroute::output::{CheckFiles, OutputFolder};
/// let scene = slideroute::Scene::from_file("scenes/dam.toml".as_ref())?;
/// let results = slideroute::check::check_cases(&scene, |_| ())?;
/// let dir = std::env::temp_dir().join(format!("slideroute-doc-check-{}", std::process::id()));
/// let files = CheckFiles::new(&scene, &results).pictures(false).view(false);
/// let written = files.write(OutputFolder::open(&dir, "check")?, || false)?;
/// assert!(written.files.iter().any(|f| f.ends_with("report.html")));
/// println!("{}", files.table());
/// # std::fs::remove_dir_all(&dir)?;
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Debug, Clone, Copy)]
pub struct CheckFiles<'a> {
    scene: &'a Scene,
    results: &'a [CaseResult],
    design: Option<&'a [AnchorDesign]>,
    pictures: bool,
    view: bool,
}

impl<'a> CheckFiles<'a> {
    /// The files of `results`, the check of `scene`'s cases.
    pub fn new(scene: &'a Scene, results: &'a [CaseResult]) -> CheckFiles<'a> {
        CheckFiles {
            scene,
            results,
            design: None,
            pictures: true,
            view: true,
        }
    }

    /// With each case's least prestress ([`design_anchors`](crate::check::design_anchors)) in
    /// `check.json` and the printed table.
    pub fn anchor_design(self, design: &'a [AnchorDesign]) -> CheckFiles<'a> {
        CheckFiles {
            design: Some(design),
            ..self
        }
    }

    /// The failing cases' routes with their pictures or without them.
    pub fn pictures(self, on: bool) -> CheckFiles<'a> {
        CheckFiles {
            pictures: on,
            ..self
        }
    }

    /// The failing cases' routes with their 3-D view or without it.
    pub fn view(self, on: bool) -> CheckFiles<'a> {
        CheckFiles { view: on, ..self }
    }

    /// Writes the check's files into `folder` and finishes it: first each failing case's route
    /// in `case-N/` (N its number among the cases; computed again, every row to its route.csv:
    /// the same route, the computation being deterministic), then `check.csv`, `report.html`
    /// and `check.json`, whose manifest names every file beside it. `stop` is asked as the
    /// routes compute: when it answers true, the check's own files are not written
    /// ([`OutputError::Interrupted`]).
    pub fn write(
        &self,
        mut folder: OutputFolder,
        stop: impl Fn() -> bool,
    ) -> Result<Written, OutputError> {
        let mut written = self.failing_routes(&folder, &stop)?;
        written.files.push(folder.write_with("check.csv", |tmp| {
            let file = std::fs::File::create(tmp)
                .map_err(|e| format!("{}: cannot write: {e}", tmp.display()))?;
            super::check_csv::write_csv(file, self.results).map_err(|e| format!("check.csv: {e}"))
        })?);
        let manifest = Manifest::new(self.scene, &folder);
        let page = super::check_report::report(
            self.scene.name(),
            self.scene.guideline(),
            self.scene.monolith().map(|m| &m.section),
            self.results,
            &toml::to_string(&manifest.scene).unwrap_or_default(),
            &serde_json::to_string_pretty(&manifest).unwrap_or_default(),
        );
        written
            .files
            .push(folder.write_bytes("report.html", page.as_bytes())?);
        // The manifest of check.json names every file beside it, report.html too.
        let manifest = Manifest::new(self.scene, &folder);
        let json = CheckJson {
            guideline: self.scene.guideline(),
            cases: self.results,
            anchor_design: self.design,
        };
        written.files.push(write_json_with_manifest(
            &mut folder,
            "check.json",
            &json,
            &manifest,
        )?);
        folder.finish()?;
        Ok(written)
    }

    /// The route of each case that fails, in `case-N/`.
    fn failing_routes(
        &self,
        folder: &OutputFolder,
        stop: &impl Fn() -> bool,
    ) -> Result<Written, OutputError> {
        let mut written = Written::default();
        for (k, r) in self.results.iter().enumerate().filter(|(_, r)| !r.passes) {
            let input = |e: crate::SceneError| OutputError::Input(e.to_string());
            let case_scene = self.scene.for_case(&r.case).map_err(input)?;
            let sim = case_scene.simulation().map_err(input)?;
            let mut sub = folder.open_inside(&format!("case-{k}"), "check")?;
            let files = RouteFiles::new(&case_scene)
                .pictures(self.pictures)
                .view(self.view);
            let progress = |_: f64| {
                if stop() {
                    ControlFlow::Break(())
                } else {
                    ControlFlow::Continue(())
                }
            };
            let (csv, run) = files.stream(&mut sub, &sim, progress)?;
            written.files.push(csv);
            written.extend(files.write(sub, &run)?);
            if stop() {
                return Err(OutputError::Interrupted {
                    what: "interrupted: the check's failing cases' routes were being written; \
                           the check's own files were not written"
                        .into(),
                    written: written.files,
                });
            }
        }
        Ok(written)
    }

    /// The check's tables as `slideroute check` prints them: each case's loads, factor of
    /// safety, requirement and verdict, the base's resultant and pressures on a monolith, why
    /// each failing case fails, and with an anchor design each case's prestress.
    pub fn table(&self) -> impl fmt::Display + '_ {
        Tables(self)
    }
}

/// [`CheckFiles::table`].
struct Tables<'c, 'a>(&'c CheckFiles<'a>);

impl fmt::Display for Tables<'_, '_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let c = self.0;
        let table = CheckTable {
            scene: c.scene.name(),
            guideline: c.scene.guideline().describe(),
            results: c.results,
        };
        write!(f, "{table}")?;
        match c.design {
            Some(d) => write!(f, "{}", AnchorTable(d)),
            None => Ok(()),
        }
    }
}
