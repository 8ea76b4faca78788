//! `Scene`: a scene read, changed by key, and run — its route, the roots and the direct pose at
//! one displacement or many, and a sweep of its keys.

use crate::columns::{Row, columns_of};
use crate::errors::{input_error, key_error, scene_error};
use crate::watch::interruptible;
use crate::{json, named};
use numpy::{PyArray1, PyReadonlyArray1};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};
use rayon::prelude::*;
use slideroute::sweep::{Sweep, Vary};
use slideroute::{Displacement, DynamicsModel, Mode, Runner};
use std::path::Path;

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
            let key: String = k
                .extract()
                .map_err(|_| input_error(py, "keys", "keys are strings like \"friction.mu_k\""))?;
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

    /// The route: (columns, summary) with columns `Row::COLUMNS` as float arrays (NaN where a
    /// value could not be had) and the summary as `summary.json` has it.
    #[pyo3(signature = (dynamics = None))]
    fn route<'py>(
        &self,
        py: Python<'py>,
        dynamics: Option<&str>,
    ) -> PyResult<(Bound<'py, PyDict>, Bound<'py, PyAny>)> {
        let scene = self.with_dynamics(py, dynamics)?;
        let sim = scene.simulation().map_err(|e| scene_error(py, &e))?;
        let computed = py.detach(|| Runner::new(&sim).run());
        let columns = PyDict::new(py);
        // Each row's values once, then column by column.
        let rows = &computed.route.rows;
        let mut cols = vec![Vec::with_capacity(rows.len()); slideroute::Row::COLUMNS.len()];
        for row in rows {
            for (col, v) in cols.iter_mut().zip(row.values()) {
                col.push(v.unwrap_or(f64::NAN));
            }
        }
        for (name, v) in slideroute::Row::COLUMNS.iter().zip(cols) {
            columns.set_item(*name, PyArray1::from_vec(py, v))?;
        }
        Ok((columns, json(py, &computed)?))
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
    #[pyo3(signature = (x_m, z_m, theta_deg, mode = None))]
    fn roots_grid<'py>(
        &self,
        py: Python<'py>,
        x_m: PyReadonlyArray1<'py, f64>,
        z_m: PyReadonlyArray1<'py, f64>,
        theta_deg: PyReadonlyArray1<'py, f64>,
        mode: Option<&str>,
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
        let rows: Vec<[f64; 5]> = py.detach(|| {
            (0..x.len())
                .into_par_iter()
                .map(|k| {
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
        });
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
    Err(input_error(
        py,
        key,
        format!("{key}: a number, a bool or a string, not {}", v.get_type()),
    ))
}
