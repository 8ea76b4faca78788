//! `Scene`: a scene read, changed by key, and run — its route, the roots and the direct pose at
//! one displacement or many, a sweep of its keys, the factor of safety at its start and its load
//! cases checked by their guideline.

use crate::columns::{RouteColumns, Row, columns_of, reason_code};
use crate::errors::{input_error, input_type_error, key_error, scene_error};
use crate::outputs::{PyCheckFiles, PyRouteFiles};
use crate::watch::interruptible;
use crate::{json, named};
use numpy::{PyArray1, PyReadonlyArray1};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};
use rayon::prelude::*;
use slideroute::check::CaseResult;
use slideroute::sweep::{Sweep, Vary};
use slideroute::{Displacement, DynamicsModel, FactorOfSafety, Mode, Runner};
use std::ops::ControlFlow;
use std::path::Path;

/// The rows `Scene.route` gives at most unless told otherwise: 10⁶ (200 MB of arrays).
const MAX_ROUTE_ROWS: usize = 1_000_000;

/// Bytes a row of `Scene.route`'s arrays takes: a double a column.
const ROW_BYTES: usize = 8 * slideroute::Row::COLUMNS.len();

/// A check as Python receives it: the guideline, the cases and the columns, and what writes its
/// files.
type Checked<'py> = (
    Bound<'py, PyAny>,
    Bound<'py, PyAny>,
    Bound<'py, PyDict>,
    PyCheckFiles,
);

/// A scene: the contact frame, the foundation, the block, its loads and friction, the solver.
#[pyclass(frozen, module = "slideroute._native", name = "Scene")]
#[derive(Clone)]
pub struct PyScene {
    pub inner: slideroute::Scene,
}

impl PyScene {
    /// The scene with the dynamics named `dynamics` (its own when `None`).
    fn with_dynamics(&self, py: Python<'_>, dynamics: Option<&str>) -> PyResult<slideroute::Scene> {
        match named::<DynamicsModel>(py, "dynamics", dynamics)? {
            Some(d) => self.inner.with_dynamics(d).map_err(|e| scene_error(py, &e)),
            None => Ok(self.inner.clone()),
        }
    }

    /// The pose system named `mode`: the scene's own when `None`, else exact.
    fn mode(&self, py: Python<'_>, mode: Option<&str>) -> PyResult<Mode> {
        Ok(named::<Mode>(py, "mode", mode)?
            .unwrap_or_else(|| self.inner.settings().map_or(Mode::Exact, |s| s.mode)))
    }
}

#[pymethods]
impl PyScene {
    /// The embedded default scene (paper-like).
    #[staticmethod]
    fn default() -> Self {
        PyScene {
            inner: slideroute::Scene::default_scene(),
        }
    }

    /// A scene file (TOML).
    #[staticmethod]
    fn from_file(py: Python<'_>, path: std::path::PathBuf) -> PyResult<Self> {
        slideroute::Scene::from_file(&path)
            .map(|inner| PyScene { inner })
            .map_err(|e| scene_error(py, &e))
    }

    /// A scene from its TOML text.
    #[staticmethod]
    #[pyo3(signature = (text, origin = "<string>"))]
    fn from_toml(py: Python<'_>, text: &str, origin: &str) -> PyResult<Self> {
        slideroute::Scene::from_toml(text, origin)
            .map(|inner| PyScene { inner })
            .map_err(|e| scene_error(py, &e))
    }

    /// A scene from a document in JSON (the Python package passes a dict this way); files it
    /// names are found from `folder`.
    #[staticmethod]
    #[pyo3(signature = (text, origin = "<dict>", folder = "."))]
    fn from_json(py: Python<'_>, text: &str, origin: &str, folder: &str) -> PyResult<Self> {
        let table: toml::Table = serde_json::from_str(text).map_err(|e| {
            input_error(
                py,
                "scene",
                format!("{origin}: not a scene's tables and keys: {e}"),
            )
        })?;
        slideroute::Scene::from_document(table, origin, Path::new(folder))
            .map(|inner| PyScene { inner })
            .map_err(|e| scene_error(py, &e))
    }

    /// The same scene with keys set (`{"friction.mu_k": 0.3}`), validated as a file is.
    fn with_keys(&self, py: Python<'_>, keys: &Bound<'_, PyDict>) -> PyResult<Self> {
        let mut pairs = Vec::new();
        for (k, v) in keys.iter() {
            let key: String = k.extract().map_err(|_| {
                input_type_error(
                    py,
                    "keys",
                    format!(
                        "keys: expected a string like \"friction.mu_k\", got {}",
                        type_name(&k)
                    ),
                )
            })?;
            let value = toml_value(py, &key, &v)?;
            pairs.push((key, value));
        }
        self.inner
            .with_keys(pairs)
            .map(|inner| PyScene { inner })
            .map_err(|e| scene_error(py, &e))
    }

    /// The scene's name.
    #[getter]
    fn name(&self) -> String {
        self.inner.name().to_string()
    }

    /// Where the scene came from (a path, `<embedded default scene>`, `<dict>`).
    #[getter]
    fn origin(&self) -> String {
        self.inner.origin().to_string()
    }

    /// The folder the files the scene names are found from.
    #[getter]
    fn folder(&self) -> String {
        self.inner.folder().display().to_string()
    }

    /// The document as read, in the file's own keys and units (a dict).
    fn document<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        json(py, self.inner.document())
    }

    /// The `[uncertain]` table: (key, distribution) pairs, by key name.
    #[getter]
    fn uncertain(&self) -> Vec<(String, String)> {
        self.inner
            .uncertain()
            .iter()
            .map(|u| (u.key.clone(), u.distribution.to_string()))
            .collect()
    }

    /// The route: (columns, summary, files) with columns `Row::COLUMNS` as float arrays (NaN
    /// where a value could not be had), the summary as `summary.json` has it, and what writes
    /// its files (`RouteFiles`). `progress(done,
    /// total)` is told how many increments of dt are done; Ctrl-C stops the route with
    /// `KeyboardInterrupt`. A route that may record more than `max_rows` rows (from t_end, dt
    /// and stride) is refused before it starts: its arrays would take 200 bytes a row
    /// (`route_chunks` reads any length in chunks). The rows go straight into the columns, the
    /// route keeping only a few of its own: 200 bytes a row in all.
    #[pyo3(signature = (dynamics = None, progress = None, max_rows = MAX_ROUTE_ROWS))]
    fn route<'py>(
        &self,
        py: Python<'py>,
        dynamics: Option<&str>,
        progress: Option<Bound<'py, PyAny>>,
        max_rows: usize,
    ) -> PyResult<(Bound<'py, PyDict>, Bound<'py, PyAny>, PyRouteFiles)> {
        let scene = self.with_dynamics(py, dynamics)?;
        let sim = scene.simulation().map_err(|e| scene_error(py, &e))?;
        let settings = sim.settings();
        // As the route counts them (`src/route/driver.rs`): the last may be shorter.
        let increments = ((settings.t_end / settings.dt - 1e-9).ceil()).max(1.0) as usize;
        let recorded = increments.div_ceil(settings.stride.max(1));
        if recorded > max_rows {
            return Err(input_error(
                py,
                "max_rows",
                format!(
                    "{}: the route may record {recorded} rows (t_end_s / dt_s / stride), more \
                     than max_rows = {max_rows} ({} MB of arrays): raise solver.stride, pass a \
                     larger max_rows, or read it in chunks with Scene.route_chunks()",
                    scene.origin(),
                    recorded.saturating_mul(ROW_BYTES) / 1_000_000
                ),
            ));
        }
        let progress = progress.as_ref().map(|f| (f, increments));
        let (cols, computed) = interruptible(py, progress, |watch| {
            let mut cols = RouteColumns::with_capacity(0);
            let computed = Runner::new(&sim)
                .progress(|part| {
                    watch.set((part * increments as f64).round() as usize);
                    if watch.stopped() {
                        ControlFlow::Break(())
                    } else {
                        ControlFlow::Continue(())
                    }
                })
                .stream(1, |row| cols.push(row))
                .keep_at_most(slideroute::KEPT_ROWS)
                .run();
            (cols, computed)
        })?;
        let columns = cols.into_dict(py)?;
        let summary = json(py, &computed)?;
        Ok((columns, summary, PyRouteFiles { scene, computed }))
    }

    /// The route read in chunks of at most `rows` rows (columns as [`PyScene::route`] gives
    /// them), any length in bounded memory; the summary once the last chunk is read.
    #[pyo3(signature = (dynamics = None, rows = 16_384))]
    fn route_chunks(
        &self,
        py: Python<'_>,
        dynamics: Option<&str>,
        rows: usize,
    ) -> PyResult<crate::route_chunks::PyRouteChunks> {
        if rows == 0 {
            return Err(input_error(
                py,
                "rows",
                "rows 0: a chunk holds at least one row",
            ));
        }
        let scene = self.with_dynamics(py, dynamics)?;
        Ok(crate::route_chunks::PyRouteChunks::start(scene, rows))
    }

    /// The factor of safety at the start, as the route's summary has it (`{"kind": "finite",
    /// "value": …}`, `{"kind": "unbounded"}`, `{"kind": "not-holdable"}`) or `None` where the
    /// start has no pose: from the route's first increment, not the whole route.
    #[pyo3(signature = (dynamics = None))]
    fn factor_of_safety<'py>(
        &self,
        py: Python<'py>,
        dynamics: Option<&str>,
    ) -> PyResult<Bound<'py, PyAny>> {
        let scene = self.with_dynamics(py, dynamics)?;
        let sim = scene.simulation().map_err(|e| scene_error(py, &e))?;
        // The route computes it at its start whatever comes after: stopped at once.
        let computed = py.detach(|| Runner::new(&sim).progress(|_| ControlFlow::Break(())).run());
        json(py, &computed.route.factor_of_safety)
    }

    /// The load cases checked by their guideline, as `slideroute check` does: (guideline,
    /// cases as `check.json` has them, columns as `check.csv` has them with the route's end as
    /// `reason` and `reason_text`, what writes its files). `progress(done, total)` is told how
    /// many cases are done.
    #[pyo3(signature = (progress = None))]
    fn check<'py>(
        &self,
        py: Python<'py>,
        progress: Option<Bound<'py, PyAny>>,
    ) -> PyResult<Checked<'py>> {
        let scene = &self.inner;
        let total = scene.cases().len().max(1);
        let progress = progress.as_ref().map(|f| (f, total));
        let results = interruptible(py, progress, |watch| {
            slideroute::check::check_cases_until(scene, |_| watch.tick(), || watch.stopped())
        })?
        .map_err(|e| scene_error(py, &e))?;
        let columns = check_columns(py, &results)?;
        let (guideline, cases) = (json(py, scene.guideline())?, json(py, &results)?);
        let files = PyCheckFiles {
            scene: scene.clone(),
            results,
        };
        Ok((guideline, cases, columns, files))
    }

    /// Every root of the pose system at one displacement (`mode`: "exact" or "small-angle",
    /// the scene's own by default): a dict.
    #[pyo3(signature = (x_m, z_m, theta_deg, mode = None))]
    fn roots<'py>(
        &self,
        py: Python<'py>,
        x_m: f64,
        z_m: f64,
        theta_deg: f64,
        mode: Option<&str>,
    ) -> PyResult<Bound<'py, PyDict>> {
        let mode = self.mode(py, mode)?;
        let d = Displacement::new(x_m, z_m, theta_deg.to_radians());
        let all = slideroute::poses::solve_all(self.inner.site(), d, mode)
            .map_err(|e| input_error(py, "displacement", e.to_string()))?;
        let out = PyDict::new(py);
        out.set_item("finite_roots", all.finite_roots)?;
        out.set_item("roots_at_infinity", all.roots_at_infinity)?;
        let list = PyList::empty(py);
        for r in &all.roots {
            let row = PyDict::new(py);
            row.set_item(
                "alpha_deg",
                (r.alpha.re.to_degrees(), r.alpha.im.to_degrees()),
            )?;
            row.set_item("beta_deg", (r.beta.re.to_degrees(), r.beta.im.to_degrees()))?;
            row.set_item(
                "psi_deg",
                r.psi.map(|p| (p.re.to_degrees(), p.im.to_degrees())),
            )?;
            row.set_item("multiplicity", r.multiplicity)?;
            row.set_item("residual", r.residual)?;
            row.set_item("real", r.real)?;
            row.set_item("admissible", r.admissible)?;
            row.set_item("why_not", r.why_not.map(|w| format!("{w:?}")))?;
            list.append(row)?;
        }
        out.set_item("roots", list)?;
        match all.selected_pose(self.inner.site()) {
            Some(p) => {
                let s = PyDict::new(py);
                s.set_item("alpha_deg", p.alpha.to_degrees())?;
                s.set_item("beta_deg", p.beta.to_degrees())?;
                s.set_item("gamma_deg", p.gamma.to_degrees())?;
                s.set_item("psi_deg", p.psi.to_degrees())?;
                s.set_item("cm_y_m", p.cm.y)?;
                out.set_item("selected", s)?;
            }
            None => out.set_item("selected", py.None())?,
        }
        out.set_item(
            "selection_error",
            all.selection_error.as_ref().map(|e| e.to_string()),
        )?;
        Ok(out)
    }

    /// The selected pose at many displacements at once, on every core: arrays alpha_deg,
    /// beta_deg, gamma_deg, cm_y_m (NaN where no root is admissible) and finite_roots.
    /// `progress(done, total)` is told how many poses are done; Ctrl-C stops it with
    /// `KeyboardInterrupt`.
    #[pyo3(signature = (x_m, z_m, theta_deg, mode = None, progress = None))]
    fn roots_grid<'py>(
        &self,
        py: Python<'py>,
        x_m: PyReadonlyArray1<'py, f64>,
        z_m: PyReadonlyArray1<'py, f64>,
        theta_deg: PyReadonlyArray1<'py, f64>,
        mode: Option<&str>,
        progress: Option<Bound<'py, PyAny>>,
    ) -> PyResult<Bound<'py, PyDict>> {
        let mode = self.mode(py, mode)?;
        let (x, z, t) = (x_m.as_slice()?, z_m.as_slice()?, theta_deg.as_slice()?);
        if x.len() != z.len() || x.len() != t.len() {
            return Err(input_error(
                py,
                "x_m, z_m, theta_deg",
                format!(
                    "x_m, z_m, theta_deg: arrays of one length, not {}, {}, {}",
                    x.len(),
                    z.len(),
                    t.len()
                ),
            ));
        }
        let site = self.inner.site();
        let progress = progress.as_ref().map(|f| (f, x.len()));
        let rows: Vec<[f64; 5]> = interruptible(py, progress, |watch| {
            (0..x.len())
                .into_par_iter()
                .map(|k| {
                    if watch.stopped() {
                        return [f64::NAN; 5];
                    }
                    watch.tick();
                    let d = Displacement::new(x[k], z[k], t[k].to_radians());
                    let Ok(all) = slideroute::poses::solve_all(site, d, mode) else {
                        return [f64::NAN; 5];
                    };
                    match all.selected_pose(site) {
                        Some(p) => [
                            p.alpha.to_degrees(),
                            p.beta.to_degrees(),
                            p.gamma.to_degrees(),
                            p.cm.y,
                            all.finite_roots as f64,
                        ],
                        None => [
                            f64::NAN,
                            f64::NAN,
                            f64::NAN,
                            f64::NAN,
                            all.finite_roots as f64,
                        ],
                    }
                })
                .collect()
        })?;
        let out = PyDict::new(py);
        for (k, name) in [
            "alpha_deg",
            "beta_deg",
            "gamma_deg",
            "cm_y_m",
            "finite_roots",
        ]
        .iter()
        .enumerate()
        {
            out.set_item(
                *name,
                PyArray1::from_vec(py, rows.iter().map(|r| r[k]).collect()),
            )?;
        }
        Ok(out)
    }

    /// The pose by the direct solver (Newton on the contact conditions), independent of the
    /// polynomial systems: tilt, roll (degrees), cm_y_m, the vertices (m) and the residual.
    fn pose<'py>(
        &self,
        py: Python<'py>,
        x_m: f64,
        z_m: f64,
        theta_deg: f64,
    ) -> PyResult<Bound<'py, PyDict>> {
        let d = Displacement::new(x_m, z_m, theta_deg.to_radians());
        let p = slideroute::poses::direct_pose(self.inner.site(), d)
            .map_err(|e| input_error(py, "displacement", e.to_string()))?;
        let out = PyDict::new(py);
        out.set_item("tilt_deg", p.tilt.to_degrees())?;
        out.set_item("roll_deg", p.roll.to_degrees())?;
        out.set_item("cm_y_m", p.cm_y)?;
        out.set_item(
            "vertices_m",
            p.vertices
                .iter()
                .map(|v| (v.x, v.y, v.z))
                .collect::<Vec<_>>(),
        )?;
        out.set_item("residual_m", p.residual)?;
        Ok(out)
    }

    /// Every combination of the values given (`{"friction.mu_k": [0.3, 0.4]}`), each route on
    /// its own core, by the runner the command line's sweep uses: columns of the keys' values
    /// and of what each route came to, as `sweep.csv` has them.
    #[pyo3(signature = (values, dynamics = None, progress = None))]
    fn sweep<'py>(
        &self,
        py: Python<'py>,
        values: Vec<(String, Vec<f64>)>,
        dynamics: Option<&str>,
        progress: Option<Bound<'py, PyAny>>,
    ) -> PyResult<Bound<'py, PyDict>> {
        let base = self.with_dynamics(py, dynamics)?;
        if let Some((key, _)) = values.iter().find(|(_, vs)| vs.is_empty()) {
            return Err(input_error(py, key, format!("{key}: no values")));
        }
        let varies = values
            .iter()
            .map(|(key, vs)| Vary::numbers(key, vs.clone()))
            .collect();
        let sweep = Sweep::new(&base, varies).map_err(|e| key_error(py, &base, &e))?;
        let progress = progress.as_ref().map(|f| (f, sweep.count()));
        let rows = interruptible(py, progress, |watch| {
            sweep.run(|| watch.tick(), || watch.stopped())
        })?;
        let keys: Vec<&str> = values.iter().map(|(k, _)| k.as_str()).collect();
        let rows: Vec<Row<'_>> = rows
            .iter()
            .enumerate()
            .map(|(index, r)| Row {
                index,
                values: &r.values,
                outcome: &r.outcome,
            })
            .collect();
        columns_of(py, &keys, &rows)
    }
}

/// A Python value as a scene value: bool, int, float or str.
pub fn toml_value(py: Python<'_>, key: &str, v: &Bound<'_, PyAny>) -> PyResult<toml::Value> {
    if let Ok(b) = v.extract::<bool>() {
        return Ok(toml::Value::Boolean(b));
    }
    if let Ok(i) = v.extract::<i64>() {
        return Ok(toml::Value::Integer(i));
    }
    if let Ok(x) = v.extract::<f64>() {
        return Ok(toml::Value::Float(x));
    }
    if let Ok(s) = v.extract::<String>() {
        return Ok(toml::Value::String(s));
    }
    Err(input_type_error(
        py,
        key,
        format!(
            "{key}: expected a number, a bool or a string, got {}",
            type_name(v)
        ),
    ))
}

/// A Python value's type as Python names it (`list`, `NoneType`).
fn type_name(v: &Bound<'_, PyAny>) -> String {
    v.get_type()
        .name()
        .map_or_else(|_| "an unknown type".to_string(), |n| n.to_string())
}

/// The cases as `check.csv` has them, column by column: numbers as floats (NaN where the case
/// has none; a sliding factor or load multiple ±∞ where unbounded or not holdable), the route's
/// end as `reason` (its machine name) and `reason_text`.
fn check_columns<'py>(py: Python<'py>, results: &[CaseResult]) -> PyResult<Bound<'py, PyDict>> {
    let out = PyDict::new(py);
    let texts = |f: fn(&CaseResult) -> &str| results.iter().map(f).collect::<Vec<_>>();
    out.set_item("case", texts(|r| &r.case.name))?;
    out.set_item("category", texts(|r| r.case.category.as_str()))?;
    for (name, f) in CHECK_NUMBERS {
        let column = results.iter().map(|r| f(r).unwrap_or(f64::NAN)).collect();
        out.set_item(name, PyArray1::from_vec(py, column))?;
    }
    out.set_item(
        "load_multiple_limit",
        texts(|r| r.load_multiple_limit.map_or("", |l| l.as_str())),
    )?;
    out.set_item(
        "required_fs",
        PyArray1::from_vec(py, results.iter().map(|r| r.required_fs).collect()),
    )?;
    out.set_item(
        "passes",
        results.iter().map(|r| r.passes).collect::<Vec<_>>(),
    )?;
    out.set_item(
        "reason",
        results
            .iter()
            .map(|r| reason_code(r.run.route.termination.reason))
            .collect::<Vec<_>>(),
    )?;
    out.set_item(
        "reason_text",
        texts(|r| r.run.route.termination.reason.as_str()),
    )?;
    out.set_item(
        "travel_m",
        PyArray1::from_vec(py, results.iter().map(|r| r.run.route.travel_m).collect()),
    )?;
    Ok(out)
}

/// The water levels of a case, where it has water.
fn water(r: &CaseResult) -> Option<slideroute::Levels> {
    r.loads
        .as_ref()
        .and_then(|l| l.water.as_ref())
        .map(|w| w.levels)
}

/// check.csv's numeric columns, each by its name and how a case gives it (none: NaN).
type CheckNumber = (&'static str, fn(&CaseResult) -> Option<f64>);

/// The numeric columns of [`check_columns`], in check.csv's order.
const CHECK_NUMBERS: [CheckNumber; 16] = [
    ("headwater_m", |r| water(r).map(|w| w.headwater)),
    ("tailwater_m", |r| water(r).map(|w| w.tailwater)),
    ("kh", |r| r.loads.as_ref().map(|l| l.kh)),
    ("kv", |r| r.loads.as_ref().map(|l| l.kv)),
    ("hydraulic_force_n", |r| {
        r.loads.as_ref().map(|l| l.hydraulic_force_n)
    }),
    ("uplift_n", |r| {
        r.gravity
            .map(|g| g.uplift_n)
            .or(r.loads.as_ref().map(|l| l.uplift_n))
    }),
    ("weight_n", |r| r.loads.as_ref().map(|l| l.weight_n)),
    ("horizontal_n", |r| match (&r.gravity, &r.loads) {
        (Some(g), _) => Some(g.shear_n),
        (None, Some(l)) => Some(l.hydraulic_force_n + l.kh * l.weight_n),
        _ => None,
    }),
    ("sliding_fs", |r| {
        r.gravity.map(|g| g.sliding_fs.unwrap_or(f64::INFINITY))
    }),
    ("resultant_from_heel_m", |r| {
        r.gravity.and_then(|g| g.resultant_from_heel_m)
    }),
    ("base_in_compression_pct", |r| {
        r.gravity.map(|g| g.base_in_compression_pct)
    }),
    ("heel_pressure_pa", |r| {
        r.gravity.map(|g| g.heel_pressure_pa)
    }),
    ("toe_pressure_pa", |r| r.gravity.map(|g| g.toe_pressure_pa)),
    ("crack_length_m", |r| r.gravity.map(|g| g.crack_length_m)),
    ("load_multiple", |r| {
        r.factor_of_safety.map(|f| match f {
            FactorOfSafety::Finite { value } => value,
            FactorOfSafety::Unbounded => f64::INFINITY,
            FactorOfSafety::NotHoldable => f64::NEG_INFINITY,
        })
    }),
    ("anchor_force_n", |r| r.gravity.map(|g| g.anchor_force_n)),
];
