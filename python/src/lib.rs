//! `slideroute._native`: the library's scene, route, roots, pose, sweep and probabilistic
//! analysis for Python (issue #17). Plain Python values and NumPy arrays go out; the Python
//! package (`python/slideroute/__init__.py`) wraps them in classes with docstrings and pandas
//! DataFrames. Long computations release the interpreter's lock and run on every core.

use numpy::{PyArray1, PyArray2, PyReadonlyArray1, PyReadonlyArray2, PyUntypedArrayMethods};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};
use rayon::prelude::*;
use slideroute::internals::geometry::Displacement;
use slideroute::internals::roots::{self, classify};
use slideroute::internals::route::{self, Reason, Route, Row};
use slideroute::internals::{model::{DynamicsModel, Mode}, scene::{SceneError}};
use slideroute::internals::analysis::probabilistic::{Design, Distribution, Limits, Outcome, Sample, SampleResult, Sampling, Uncertain, merged, route_result, run_values, summarise};
use std::path::Path;
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::time::Duration;

/// A Python exception of `slideroute._errors`: `class(message, name)`.
fn raise(py: Python<'_>, class: &str, (message, name): (String, String)) -> PyErr {
    let made = py
        .import("slideroute._errors")
        .and_then(|m| m.getattr(class))
        .and_then(|c| c.call1((message, name)));
    match made {
        Ok(e) => PyErr::from_value(e),
        Err(e) => e,
    }
}

/// What a long computation and the thread watching it share: whether to stop, and how many
/// samples or combinations are done.
struct Watch {
    stop: AtomicBool,
    done: AtomicUsize,
}

impl Watch {
    fn stopped(&self) -> bool {
        self.stop.load(Ordering::Relaxed)
    }

    fn tick(&self) {
        self.done.fetch_add(1, Ordering::Relaxed);
    }
}

/// Runs `work` on a thread of its own while this one watches it, holding the interpreter only
/// for a moment now and then: a `KeyboardInterrupt` (or an exception of `progress`) raises
/// `stop`, the work ends at its next sample or combination, and the exception is raised here
/// (what was computed is dropped, as Python drops a loop's work when it is interrupted).
/// `progress`, a callable and the total, is called with (done, total) as the count moves (at
/// most about four times a second) and once at the end.
fn interruptible<T: Send>(
    py: Python<'_>,
    progress: Option<(&Bound<'_, PyAny>, usize)>,
    work: impl FnOnce(&Watch) -> T + Send,
) -> PyResult<T> {
    let watch = Watch {
        stop: AtomicBool::new(false),
        done: AtomicUsize::new(0),
    };
    let mut failed: Option<PyErr> = None;
    let mut told = (usize::MAX, std::time::Instant::now());
    let mut tell = |failed: &mut Option<PyErr>, last: bool| {
        let Some((f, total)) = progress else {
            return;
        };
        let done = watch.done.load(Ordering::Relaxed);
        let due = told.1.elapsed() >= Duration::from_millis(250);
        if failed.is_none() && done != told.0 && (due || last) {
            told = (done, std::time::Instant::now());
            if let Err(e) = f.call1((done, total)) {
                *failed = Some(e);
                watch.stop.store(true, Ordering::Relaxed);
            }
        }
    };
    let result = std::thread::scope(|s| {
        let handle = s.spawn(|| work(&watch));
        let mut nap = Duration::from_micros(200);
        while !handle.is_finished() {
            py.detach(|| std::thread::sleep(nap));
            nap = (nap * 2).min(Duration::from_millis(25));
            if failed.is_none() {
                if let Err(e) = py.check_signals() {
                    failed = Some(e);
                    watch.stop.store(true, Ordering::Relaxed);
                }
            }
            tell(&mut failed, false);
        }
        handle.join()
    });
    tell(&mut failed, true);
    if let Some(e) = failed {
        return Err(e);
    }
    result.map_err(|_| {
        raise(
            py,
            "RouteError",
            ("the computation failed unexpectedly".into(), String::new()),
        )
    })
}

/// A scene error as `SceneError(message, key, origin)`: the key it names is `e.key`.
fn scene_error(py: Python<'_>, e: &SceneError) -> PyErr {
    let made = py
        .import("slideroute._errors")
        .and_then(|m| m.getattr("SceneError"))
        .and_then(|c| c.call1((e.to_string(), e.key.clone(), e.origin.clone())));
    match made {
        Ok(e) => PyErr::from_value(e),
        Err(e) => e,
    }
}

/// A value a caller gave that cannot be used, as `InputError(message, name)`.
fn input_error(py: Python<'_>, name: &str, message: impl Into<String>) -> PyErr {
    raise(py, "InputError", (message.into(), name.to_string()))
}

fn json<'py>(py: Python<'py>, value: &impl serde::Serialize) -> PyResult<Bound<'py, PyAny>> {
    let text = serde_json::to_string(value).map_err(|e| {
        raise(
            py,
            "RouteError",
            (format!("cannot serialise: {e}"), String::new()),
        )
    })?;
    py.import("json")?.call_method1("loads", (text,))
}

fn dynamics_of(py: Python<'_>, name: Option<&str>) -> PyResult<Option<DynamicsModel>> {
    match name {
        None => Ok(None),
        Some("rigid-body") => Ok(Some(DynamicsModel::RigidBody)),
        Some("paper") => Ok(Some(DynamicsModel::Paper)),
        Some(other) => Err(input_error(
            py,
            "dynamics",
            format!("dynamics `{other}`: \"rigid-body\" or \"paper\""),
        )),
    }
}

fn mode_of(py: Python<'_>, scene: &slideroute::Scene, name: Option<&str>) -> PyResult<Mode> {
    match name {
        None => Ok(scene.solver().map_or(Mode::Exact, |s| s.mode)),
        Some("exact") => Ok(Mode::Exact),
        Some("small-angle") => Ok(Mode::SmallAngle),
        Some(other) => Err(input_error(
            py,
            "mode",
            format!("mode `{other}`: \"exact\" or \"small-angle\""),
        )),
    }
}

fn sampling_of(py: Python<'_>, name: &str) -> PyResult<Sampling> {
    match name {
        "lhs" => Ok(Sampling::LatinHypercube),
        "mc" => Ok(Sampling::MonteCarlo),
        other => Err(input_error(
            py,
            "sampling",
            format!("sampling `{other}`: \"lhs\" or \"mc\""),
        )),
    }
}

/// A Python value as a scene value: bool, int, float or str.
fn toml_value(py: Python<'_>, key: &str, v: &Bound<'_, PyAny>) -> PyResult<toml::Value> {
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

/// `{"key": "name:p1:p2…"}` or `[("key", "name:…")]` as uncertain values (their order kept).
fn uncertain_of(py: Python<'_>, given: &[(String, String)]) -> PyResult<Vec<Uncertain>> {
    given
        .iter()
        .map(|(key, spec)| {
            Distribution::parse(spec)
                .map(|distribution| Uncertain {
                    key: key.clone(),
                    distribution,
                })
                .map_err(|e| input_error(py, key, format!("{key}: {e}")))
        })
        .collect()
}

/// A scene: the contact frame, the foundation, the block, its loads and friction, the solver.
#[pyclass(frozen, module = "slideroute._native", name = "Scene")]
#[derive(Clone)]
struct PyScene {
    inner: slideroute::Scene,
}

impl PyScene {
    /// The scene with each uncertain key checked: a number of the scene (set to the middle of
    /// its distribution, it gives a valid scene).
    fn check_keys(&self, py: Python<'_>, uncertain: &[Uncertain]) -> PyResult<()> {
        for (k, u) in uncertain.iter().enumerate() {
            if uncertain[..k].iter().any(|w| w.key == u.key) {
                return Err(input_error(py, &u.key, format!("{}: given twice", u.key)));
            }
            let (section, name) = u.key.split_once('.').unwrap_or(("", &u.key));
            let present = self
                .inner
                .document()
                .get(section)
                .and_then(|t| t.as_table())
                .and_then(|t| t.get(name));
            if let Some(v) = present.filter(|v| !(v.is_float() || v.is_integer())) {
                return Err(input_error(
                    py,
                    &u.key,
                    format!("{}: not a number in the scene ({})", u.key, v.type_str()),
                ));
            }
            self.inner
                .with(&u.key, u.distribution.quantile(0.5))
                .map_err(|e| scene_error(py, &e))?;
        }
        Ok(())
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
        let scene = match dynamics_of(py, dynamics)? {
            Some(d) => self
                .inner
                .with_dynamics(d)
                .map_err(|e| scene_error(py, &e))?,
            None => self.inner.clone(),
        };
        let r: Route = py
            .detach(|| route::run(&scene))
            .map_err(|e| scene_error(py, &e))?;
        let columns = PyDict::new(py);
        // Each row's values once, then column by column.
        let mut cols = vec![Vec::with_capacity(r.rows.len()); Row::COLUMNS.len()];
        for row in &r.rows {
            for (col, v) in cols.iter_mut().zip(row.values()) {
                col.push(v.unwrap_or(f64::NAN));
            }
        }
        for (name, v) in Row::COLUMNS.iter().zip(cols) {
            columns.set_item(*name, PyArray1::from_vec(py, v))?;
        }
        Ok((columns, json(py, &r)?))
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
        let mode = mode_of(py, &self.inner, mode)?;
        let d = Displacement::new(x_m, z_m, theta_deg.to_radians());
        let all = roots::solve_all(self.inner.site(), d, mode)
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
        let selected = all.selected.and_then(|k| {
            let r = &all.roots[k];
            classify::pose(
                self.inner.site(),
                d,
                mode,
                [r.alpha.re, r.psi.unwrap_or(r.beta).re],
            )
        });
        match selected {
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
        let mode = mode_of(py, &self.inner, mode)?;
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
                    let Ok(all) = roots::solve_all(site, d, mode) else {
                        return [f64::NAN; 5];
                    };
                    let pose = all.selected.and_then(|s| {
                        let r = &all.roots[s];
                        classify::pose(site, d, mode, [r.alpha.re, r.psi.unwrap_or(r.beta).re])
                    });
                    match pose {
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
        let p = slideroute::direct_pose(self.inner.site(), d)
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
    /// its own core: columns of the keys' values and of what each route came to.
    #[pyo3(signature = (values, dynamics = None, progress = None))]
    fn sweep<'py>(
        &self,
        py: Python<'py>,
        values: Vec<(String, Vec<f64>)>,
        dynamics: Option<&str>,
        progress: Option<Bound<'py, PyAny>>,
    ) -> PyResult<Bound<'py, PyDict>> {
        let base = match dynamics_of(py, dynamics)? {
            Some(d) => self
                .inner
                .with_dynamics(d)
                .map_err(|e| scene_error(py, &e))?,
            None => self.inner.clone(),
        };
        let mut combos: Vec<Vec<f64>> = vec![vec![]];
        for (key, vs) in &values {
            if vs.is_empty() {
                return Err(input_error(py, key, format!("{key}: no values")));
            }
            combos = combos
                .into_iter()
                .flat_map(|c| {
                    vs.iter().map(move |v| {
                        let mut c = c.clone();
                        c.push(*v);
                        c
                    })
                })
                .collect();
        }
        let keys: Vec<&str> = values.iter().map(|(k, _)| k.as_str()).collect();
        // A key that is no number of the scene fails here, named, before any route runs.
        if let Some(first) = combos.first() {
            base.with_keys(keys.iter().copied().zip(first.iter().copied()))
                .map_err(|e| scene_error(py, &e))?;
        }
        let total = combos.len();
        let progress = progress.as_ref().map(|f| (f, total));
        let results: Vec<Result<SampleResult, String>> = interruptible(py, progress, |watch| {
            combos
                .par_iter()
                .map(|c| {
                    if watch.stopped() {
                        return Err(slideroute::internals::analysis::probabilistic::NOT_RUN.to_string());
                    }
                    let r = base
                        .with_keys(keys.iter().copied().zip(c.iter().copied()))
                        .and_then(|s| route_result(&s))
                        .map_err(|e| e.to_string());
                    watch.tick();
                    r
                })
                .collect()
        })?;
        let samples: Vec<Sample> = results
            .into_iter()
            .zip(combos)
            .enumerate()
            .map(|(index, (r, values))| Sample {
                index,
                values,
                outcome: match r {
                    Ok(r) => Outcome::Route(r),
                    Err(reason) => Outcome::Invalid { reason },
                },
            })
            .collect();
        columns_of(py, &keys, &samples)
    }
}

/// A column of samples' numbers: its name and how a route gives it.
type Column<'a> = (&'a str, &'a dyn Fn(&SampleResult) -> f64);

/// Samples as columns: each key's values, then what each came to.
fn columns_of<'py>(
    py: Python<'py>,
    keys: &[&str],
    samples: &[Sample],
) -> PyResult<Bound<'py, PyDict>> {
    let out = PyDict::new(py);
    out.set_item(
        "sample",
        PyArray1::from_vec(py, samples.iter().map(|s| s.index as i64).collect()),
    )?;
    for (k, key) in keys.iter().enumerate() {
        out.set_item(
            *key,
            PyArray1::from_vec(py, samples.iter().map(|s| s.values[k]).collect()),
        )?;
    }
    let route = |f: &dyn Fn(&SampleResult) -> f64| -> Vec<f64> {
        samples
            .iter()
            .map(|s| match &s.outcome {
                Outcome::Route(r) => f(r),
                _ => f64::NAN,
            })
            .collect()
    };
    let float_columns: [Column; 6] = [
        ("factor_of_safety", &|r| {
            r.factor_of_safety.unwrap_or(f64::NAN)
        }),
        ("t_end_s", &|r| r.t_s),
        ("travel_m", &|r| r.travel_m),
        ("final_yaw_deg", &|r| r.yaw_deg),
        ("final_x_m", &|r| r.x_m),
        ("final_z_m", &|r| r.z_m),
    ];
    for (name, f) in float_columns {
        out.set_item(name, PyArray1::from_vec(py, route(f)))?;
    }
    let reasons: Vec<String> = samples
        .iter()
        .map(|s| match &s.outcome {
            Outcome::Route(r) => r.reason.as_str().to_string(),
            Outcome::Invalid { .. } => "invalid scene".to_string(),
            Outcome::NotRun => slideroute::internals::analysis::probabilistic::NOT_RUN.to_string(),
        })
        .collect();
    let details: Vec<String> = samples
        .iter()
        .map(|s| match &s.outcome {
            Outcome::Invalid { reason } => reason.clone(),
            _ => String::new(),
        })
        .collect();
    out.set_item("reason", reasons)?;
    out.set_item("detail", details)?;
    Ok(out)
}

/// Samples back from their columns (as [`columns_of`] wrote them, gathered from anywhere).
fn samples_from<'py>(
    py: Python<'py>,
    keys: &[String],
    columns: &Bound<'py, PyDict>,
) -> PyResult<Vec<Sample>> {
    let get = |name: &str| -> PyResult<Bound<'py, PyAny>> {
        columns
            .get_item(name)?
            .ok_or_else(|| input_error(py, name, format!("the samples have no column `{name}`")))
    };
    let floats = |name: &str| -> PyResult<Vec<f64>> {
        let a = get(name)?;
        a.extract::<Vec<f64>>()
            .map_err(|_| input_error(py, name, format!("`{name}`: numbers")))
    };
    let index: Vec<i64> = get("sample")?.extract()?;
    let n = index.len();
    let values: Vec<Vec<f64>> = keys.iter().map(|k| floats(k)).collect::<PyResult<_>>()?;
    let fs = floats("factor_of_safety")?;
    let t = floats("t_end_s")?;
    let travel = floats("travel_m")?;
    let yaw = floats("final_yaw_deg")?;
    let x = floats("final_x_m")?;
    let z = floats("final_z_m")?;
    let reason: Vec<String> = get("reason")?.extract()?;
    let detail: Vec<String> = get("detail")?.extract()?;
    let lengths = [
        fs.len(),
        t.len(),
        travel.len(),
        yaw.len(),
        x.len(),
        z.len(),
        reason.len(),
        detail.len(),
    ];
    if lengths
        .into_iter()
        .chain(values.iter().map(|v| v.len()))
        .any(|l| l != n)
    {
        return Err(input_error(py, "samples", "the columns differ in length"));
    }
    (0..n)
        .map(|k| {
            let outcome = match reason[k].as_str() {
                "invalid scene" => Outcome::Invalid {
                    reason: detail[k].clone(),
                },
                r if r == slideroute::internals::analysis::probabilistic::NOT_RUN => Outcome::NotRun,
                r => Outcome::Route(SampleResult {
                    factor_of_safety: (!fs[k].is_nan()).then_some(fs[k]),
                    reason: Reason::parse(r).ok_or_else(|| {
                        input_error(py, "reason", format!("`{r}` is no route's end"))
                    })?,
                    t_s: t[k],
                    travel_m: travel[k],
                    x_m: x[k],
                    z_m: z[k],
                    yaw_deg: yaw[k],
                    cm_path_m: vec![],
                }),
            };
            Ok(Sample {
                index: index[k] as usize,
                values: values.iter().map(|v| v[k]).collect(),
                outcome,
            })
        })
        .collect()
}

/// The most samples one design may have (as the command line's).
const MAX_SAMPLES: usize = 10_000_000;

/// A design's uncertain keys and sampling, checked: from 1 to [`MAX_SAMPLES`] samples, at
/// least one key, each a number of the scene.
fn design_of(
    py: Python<'_>,
    scene: &PyScene,
    uncertain: &[(String, String)],
    samples: usize,
    sampling: &str,
) -> PyResult<(Vec<Uncertain>, Sampling)> {
    if samples == 0 || samples > MAX_SAMPLES {
        return Err(input_error(
            py,
            "samples",
            format!("samples {samples}: from 1 to {MAX_SAMPLES}"),
        ));
    }
    let u = uncertain_of(py, uncertain)?;
    if u.is_empty() {
        return Err(input_error(py, "dists", "nothing is uncertain"));
    }
    scene.check_keys(py, &u)?;
    Ok((u, sampling_of(py, sampling)?))
}

/// The values of each sample (rows) of each uncertain key (columns), from the seed.
#[pyfunction]
fn sample_values<'py>(
    py: Python<'py>,
    scene: &PyScene,
    uncertain: Vec<(String, String)>,
    samples: usize,
    seed: u64,
    sampling: &str,
) -> PyResult<Bound<'py, PyArray2<f64>>> {
    let (u, sampling) = design_of(py, scene, &uncertain, samples, sampling)?;
    let design = Design {
        scene: &scene.inner,
        uncertain: &u,
        samples,
        seed,
        sampling,
    };
    PyArray2::from_vec2(py, &design.values()).map_err(|e| input_error(py, "samples", e.to_string()))
}

/// The samples numbered `first`, `first + 1`, … with `values` (rows of a design's values),
/// every route on every core: columns.
#[pyfunction]
#[pyo3(signature = (scene, uncertain, values, first = 0, progress = None))]
fn run_samples<'py>(
    py: Python<'py>,
    scene: &PyScene,
    uncertain: Vec<(String, String)>,
    values: PyReadonlyArray2<'py, f64>,
    first: usize,
    progress: Option<Bound<'py, PyAny>>,
) -> PyResult<Bound<'py, PyDict>> {
    let u = uncertain_of(py, &uncertain)?;
    scene.check_keys(py, &u)?;
    let shape = values.shape();
    if shape[1] != u.len() {
        return Err(input_error(
            py,
            "values",
            format!(
                "values: {} columns for {} uncertain keys",
                shape[1],
                u.len()
            ),
        ));
    }
    let a = values.as_array();
    let rows: Vec<Vec<f64>> = a.rows().into_iter().map(|r| r.to_vec()).collect();
    let base = &scene.inner;
    let progress = progress.as_ref().map(|f| (f, rows.len()));
    let samples = interruptible(py, progress, |watch| {
        run_values(base, &u, first, rows, || watch.tick(), || watch.stopped())
    })?;
    let keys: Vec<&str> = u.iter().map(|x| x.key.as_str()).collect();
    columns_of(py, &keys, &samples)
}

/// What the samples (columns, from [`run_samples`] of one design, in order) come to: the
/// summary `probabilistic.json` has.
#[pyfunction]
#[pyo3(signature = (scene, uncertain, samples, seed, sampling, columns, travel_limit_m = None, rotation_limit_deg = None))]
#[allow(clippy::too_many_arguments)]
fn summarise_samples<'py>(
    py: Python<'py>,
    scene: &PyScene,
    uncertain: Vec<(String, String)>,
    samples: usize,
    seed: u64,
    sampling: &str,
    columns: &Bound<'py, PyDict>,
    travel_limit_m: Option<f64>,
    rotation_limit_deg: Option<f64>,
) -> PyResult<Bound<'py, PyAny>> {
    let (u, sampling) = design_of(py, scene, &uncertain, samples, sampling)?;
    let keys: Vec<String> = u.iter().map(|x| x.key.clone()).collect();
    let rows = samples_from(py, &keys, columns)?;
    let design = Design {
        scene: &scene.inner,
        uncertain: &u,
        samples,
        seed,
        sampling,
    };
    let limits = Limits::new(travel_limit_m, rotation_limit_deg).map_err(|(name, l)| {
        input_error(
            py,
            name,
            format!("{name} {l}: a finite number, zero or more"),
        )
    })?;
    json(py, &summarise(&design, limits, &rows))
}

/// The uncertain values of an analysis: the scene's `[uncertain]` table, then `given` (a key
/// of both takes `given`'s), as (key, distribution) pairs.
#[pyfunction]
fn distributions(
    py: Python<'_>,
    scene: &PyScene,
    given: Vec<(String, String)>,
) -> PyResult<Vec<(String, String)>> {
    let given = uncertain_of(py, &given)?;
    Ok(merged(scene.inner.uncertain(), given)
        .into_iter()
        .map(|u| (u.key, u.distribution.to_string()))
        .collect())
}

/// The crate's version.
#[pyfunction]
fn version() -> &'static str {
    env!("CARGO_PKG_VERSION")
}

#[pymodule]
fn _native(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<PyScene>()?;
    m.add_function(wrap_pyfunction!(sample_values, m)?)?;
    m.add_function(wrap_pyfunction!(run_samples, m)?)?;
    m.add_function(wrap_pyfunction!(distributions, m)?)?;
    m.add_function(wrap_pyfunction!(summarise_samples, m)?)?;
    m.add_function(wrap_pyfunction!(version, m)?)?;
    Ok(())
}
