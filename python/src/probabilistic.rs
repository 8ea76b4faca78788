//! The probabilistic analysis for Python: a design's values, its samples run anywhere (a range
//! of the design, on every core), and what they come to — the library's analysis, as the
//! command line runs it.

use crate::columns::{Row, columns_of, samples_from};
use crate::errors::{input_error, key_error};
use crate::scene::PyScene;
use crate::watch::interruptible;
use crate::{json, named};
use numpy::{PyArray2, PyReadonlyArray2, PyUntypedArrayMethods};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use slideroute::probabilistic::{
    Design, Distribution, Limits, MAX_SAMPLES, Sampling, Uncertain, check_uncertain, merged,
    run_values, summarise,
};

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

/// The numbers a sample can have: below 2⁵³, each exactly a float too.
const MAX_SAMPLE_NUMBER: usize = 1 << 53;

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
    check_uncertain(&scene.inner, &u).map_err(|e| key_error(py, &scene.inner, &e))?;
    let sampling = named::<Sampling>(py, "sampling", Some(sampling))?.unwrap_or_default();
    Ok((u, sampling))
}

/// The values of each sample (rows) of each uncertain key (columns), from the seed.
#[pyfunction]
pub fn sample_values<'py>(
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
pub fn run_samples<'py>(
    py: Python<'py>,
    scene: &PyScene,
    uncertain: Vec<(String, String)>,
    values: PyReadonlyArray2<'py, f64>,
    first: usize,
    progress: Option<Bound<'py, PyAny>>,
) -> PyResult<Bound<'py, PyDict>> {
    let u = uncertain_of(py, &uncertain)?;
    check_uncertain(&scene.inner, &u).map_err(|e| key_error(py, &scene.inner, &e))?;
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
    // Each sample's number, first + k, must be a number (the Python layer keeps it below 2⁵³).
    if first
        .checked_add(shape[0])
        .is_none_or(|end| end > MAX_SAMPLE_NUMBER)
    {
        return Err(input_error(
            py,
            "first",
            format!(
                "first {first}: the samples' numbers, first to first + {} − 1, must stay below 2^53",
                shape[0]
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
    let rows: Vec<Row<'_>> = samples.iter().map(Row::from).collect();
    columns_of(py, &keys, &rows)
}

/// What the samples (columns, from [`run_samples`] of one design, in order) come to: the
/// summary `probabilistic.json` has.
#[pyfunction]
#[pyo3(signature = (scene, uncertain, samples, seed, sampling, columns, travel_limit_m = None, rotation_limit_deg = None, displacement_limit_m = None))]
#[allow(clippy::too_many_arguments)]
pub fn summarise_samples<'py>(
    py: Python<'py>,
    scene: &PyScene,
    uncertain: Vec<(String, String)>,
    samples: usize,
    seed: u64,
    sampling: &str,
    columns: &Bound<'py, PyDict>,
    travel_limit_m: Option<f64>,
    rotation_limit_deg: Option<f64>,
    displacement_limit_m: Option<f64>,
) -> PyResult<Bound<'py, PyAny>> {
    let (u, sampling) = design_of(py, scene, &uncertain, samples, sampling)?;
    let keys: Vec<String> = u.iter().map(|x| x.key.clone()).collect();
    let rows = samples_from(py, &keys, columns)?;
    // The summary is of the whole design: every sample's row, once (3 rows summarised as a
    // design of 1000 samples gave probabilities of 3 routes).
    let numbered = rows.iter().enumerate().all(|(k, r)| r.index == k);
    if rows.len() != samples || !numbered {
        return Err(input_error(
            py,
            "rows",
            format!(
                "rows: {} rows{} for a design of {samples} samples: give every sample's row, in \
                 order (Samples.concat joins chunks)",
                rows.len(),
                if numbered {
                    ""
                } else {
                    " not numbered 0, 1, 2, …"
                }
            ),
        ));
    }
    let design = Design {
        scene: &scene.inner,
        uncertain: &u,
        samples,
        seed,
        sampling,
    };
    let limits = Limits::new(travel_limit_m, rotation_limit_deg)
        .and_then(|l| l.with_displacement(displacement_limit_m))
        .map_err(|(name, l)| {
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
pub fn distributions(
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
