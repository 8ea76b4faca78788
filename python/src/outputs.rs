//! A route's and a check's files, through the library's writers (`slideroute::output`): the
//! same files the command line writes, into a folder written whole or not at all.

use crate::errors::{input_error, output_error};
use crate::watch::interruptible;
use numpy::PyReadonlyArray1;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use slideroute::check::CaseResult;
use slideroute::output::{CheckFiles, OutputFolder, RouteCsv, RouteFiles, Written};
use slideroute::{Computed, Row, Scene};
use std::path::PathBuf;

/// A route as computed (its summary and the rows it kept for the pictures), with its scene:
/// what its files are written from.
#[pyclass(frozen, module = "slideroute._native", name = "RouteFiles")]
pub struct PyRouteFiles {
    pub scene: Scene,
    pub computed: Computed,
}

/// The files written, as paths; each warning (what was left out, and why) as a Python warning.
fn files_of(py: Python<'_>, written: Written) -> PyResult<Vec<String>> {
    let warnings = py.import("warnings")?;
    for w in &written.warnings {
        warnings.call_method1("warn", (w.as_str(),))?;
    }
    Ok(written
        .files
        .iter()
        .map(|p| p.display().to_string())
        .collect())
}

#[pymethods]
impl PyRouteFiles {
    /// The plan view (`plan.svg`) written whole to `path`.
    fn plot_plan(&self, py: Python<'_>, path: PathBuf) -> PyResult<()> {
        py.detach(|| self.computed.route.plot_plan(&self.scene, &path))
            .map_err(|e| output_error(py, e))
    }

    /// The route's files in the folder `dir`, as `slideroute run` writes them: `route.csv` of
    /// `columns` (every row, `Row::COLUMNS` by name, NaN where a value could not be had), the
    /// route in 3-D and the pictures (unless turned off) and `summary.json`. The paths written.
    #[pyo3(signature = (dir, columns, pictures = true, view = true))]
    fn write(
        &self,
        py: Python<'_>,
        dir: PathBuf,
        columns: &Bound<'_, PyDict>,
        pictures: bool,
        view: bool,
    ) -> PyResult<Vec<String>> {
        let mut arrays: Vec<PyReadonlyArray1<'_, f64>> = Vec::with_capacity(Row::COLUMNS.len());
        for name in Row::COLUMNS {
            let column = columns
                .get_item(name)?
                .ok_or_else(|| input_error(py, "columns", format!("columns: no column {name}")))?;
            arrays.push(column.extract()?);
        }
        let cols: Vec<&[f64]> = arrays
            .iter()
            .map(|a| a.as_slice())
            .collect::<Result<_, _>>()?;
        let rows = cols.first().map_or(0, |c| c.len());
        if cols.iter().any(|c| c.len() != rows) {
            return Err(input_error(
                py,
                "columns",
                "columns: arrays of one length, one value a row",
            ));
        }
        let files = RouteFiles::new(&self.scene).pictures(pictures).view(view);
        let written = py
            .detach(|| {
                let mut folder = OutputFolder::open(&dir, "run")?;
                let csv = folder.write_with("route.csv", |tmp| {
                    let file = std::fs::File::create(tmp)
                        .map_err(|e| format!("{}: cannot write: {e}", tmp.display()))?;
                    let mut out = RouteCsv::new(file).map_err(|e| format!("route.csv: {e}"))?;
                    for k in 0..rows {
                        out.push_values(cols.iter().map(|c| c[k]));
                    }
                    out.finish()
                        .map(drop)
                        .map_err(|e| format!("route.csv: {e}"))
                })?;
                let mut written = files.write(folder, &self.computed)?;
                written.files.insert(0, csv);
                Ok(written)
            })
            .map_err(|e| output_error(py, e))?;
        files_of(py, written)
    }
}

/// A check of load cases as computed, with its scene: what its files are written from.
#[pyclass(frozen, module = "slideroute._native", name = "CheckFiles")]
pub struct PyCheckFiles {
    pub scene: Scene,
    pub results: Vec<CaseResult>,
}

#[pymethods]
impl PyCheckFiles {
    /// The check's files in the folder `dir`, as `slideroute check` writes them: each failing
    /// case's route in `case-N/` (with its pictures and 3-D view unless turned off),
    /// `check.csv`, `report.html` and `check.json`. Ctrl-C stops it with `KeyboardInterrupt`
    /// (the check's own files not written). The paths written.
    #[pyo3(signature = (dir, pictures = true, view = true))]
    fn write_report(
        &self,
        py: Python<'_>,
        dir: PathBuf,
        pictures: bool,
        view: bool,
    ) -> PyResult<Vec<String>> {
        let files = CheckFiles::new(&self.scene, &self.results)
            .pictures(pictures)
            .view(view);
        let written = interruptible(py, None, |watch| {
            let folder = OutputFolder::open(&dir, "check")?;
            files.write(folder, || watch.stopped())
        })?
        .map_err(|e| output_error(py, e))?;
        files_of(py, written)
    }

    /// The check's tables as `slideroute check` prints them.
    fn table(&self) -> String {
        CheckFiles::new(&self.scene, &self.results)
            .table()
            .to_string()
    }
}
