//! `slideroute._native`: the library's scene, route, roots, pose, sweep and probabilistic
//! analysis for Python, and their files (`outputs.rs`), through the library's public interface
//! alone. Plain Python values and
//! NumPy arrays go out; the Python package (`python/slideroute/__init__.py`) wraps them in
//! classes with docstrings and pandas DataFrames. Long computations release the interpreter's
//! lock and run on every core (`watch.rs`); the sweep and the probabilistic analysis are the
//! command line's own runner.

mod columns;
mod errors;
mod outputs;
mod probabilistic;
mod route_chunks;
mod scene;
mod watch;

use errors::input_error;
use pyo3::prelude::*;
use slideroute::UnknownName;
use std::str::FromStr;

/// `value` as a Python value, through JSON.
fn json<'py>(py: Python<'py>, value: &impl serde::Serialize) -> PyResult<Bound<'py, PyAny>> {
    let text = serde_json::to_string(value)
        .map_err(|e| errors::route_error(py, format!("cannot serialise: {e}")))?;
    py.import("json")?.call_method1("loads", (text,))
}

/// The value of a model's option (`name`) that `word` names, by the library's own names (those
/// a scene file and the command line take); `None` for no word.
fn named<T: FromStr<Err = UnknownName>>(
    py: Python<'_>,
    name: &str,
    word: Option<&str>,
) -> PyResult<Option<T>> {
    word.map(|w| {
        w.parse::<T>()
            .map_err(|e| input_error(py, name, format!("{name} `{w}`: {e}")))
    })
    .transpose()
}

/// Every end a route (or a row of many) can have: (machine name, sentence) pairs.
#[pyfunction]
fn reasons() -> Vec<(String, &'static str)> {
    columns::reasons()
}

/// The crate's version.
#[pyfunction]
fn version() -> &'static str {
    env!("CARGO_PKG_VERSION")
}

#[pymodule]
fn _native(m: &Bound<'_, PyModule>) -> PyResult<()> {
    // NumPy's array interface is fetched here, at import, once: fetched at the first array a
    // call makes, it imports NumPy's modules there, and a Ctrl-C arriving during that import
    // became a panic, or was lost and the analysis ran on (numpy::PyArray's first use).
    numpy::PyArray1::<f64>::zeros(m.py(), 0, false);
    m.add_class::<scene::PyScene>()?;
    m.add_class::<route_chunks::PyRouteChunks>()?;
    m.add_class::<outputs::PyRouteFiles>()?;
    m.add_class::<outputs::PyCheckFiles>()?;
    m.add_function(wrap_pyfunction!(probabilistic::sample_values, m)?)?;
    m.add_function(wrap_pyfunction!(probabilistic::run_samples, m)?)?;
    m.add_function(wrap_pyfunction!(probabilistic::distributions, m)?)?;
    m.add_function(wrap_pyfunction!(probabilistic::summarise_samples, m)?)?;
    m.add_function(wrap_pyfunction!(reasons, m)?)?;
    m.add_function(wrap_pyfunction!(version, m)?)?;
    Ok(())
}
