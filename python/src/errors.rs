//! The package's exceptions (`slideroute._errors`), made from the library's errors: a scene
//! that cannot be used (`SceneError`, naming its key), an argument that cannot be used
//! (`InputError`, naming it), a failure of the computation itself (`RouteError`).

use pyo3::prelude::*;

/// A Python exception of `slideroute._errors`: `class(*args)`.
fn raise(py: Python<'_>, class: &str, args: Vec<String>) -> PyErr {
    let made = py
        .import("slideroute._errors")
        .and_then(|m| m.getattr(class))
        .and_then(|c| c.call1(pyo3::types::PyTuple::new(py, args)?));
    match made {
        Ok(e) => PyErr::from_value(e),
        Err(e) => e,
    }
}

/// A scene error as `SceneError(message, key, origin)`: the key it names is `e.key`.
pub fn scene_error(py: Python<'_>, e: &slideroute::SceneError) -> PyErr {
    raise(
        py,
        "SceneError",
        vec![e.to_string(), e.key.clone(), e.origin.clone()],
    )
}

/// A scene key that cannot take what it was given, as `SceneError(message, key, origin)`.
pub fn key_error(
    py: Python<'_>,
    scene: &slideroute::Scene,
    e: &slideroute::sweep::KeyError,
) -> PyErr {
    let message = format!("{}: {e}", scene.origin());
    raise(
        py,
        "SceneError",
        vec![message, e.key.clone(), scene.origin().to_string()],
    )
}

/// A value a caller gave that cannot be used, as `InputError(message, name)`.
pub fn input_error(py: Python<'_>, name: &str, message: impl Into<String>) -> PyErr {
    raise(py, "InputError", vec![message.into(), name.to_string()])
}

/// A failure of the computation itself, as `RouteError(message, "")`.
pub fn route_error(py: Python<'_>, message: impl Into<String>) -> PyErr {
    raise(py, "RouteError", vec![message.into(), String::new()])
}
