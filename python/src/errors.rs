//! The package's exceptions (`slideroute._errors`), made from the library's errors: a scene
//! that cannot be used (`SceneError`, naming its key), an argument that cannot be used
//! (`InputError`, naming it), a failure of the computation itself (`RouteError`), a file that
//! could not be written (`OutputError`). As Python's own: a file that does not exist is also a
//! `FileNotFoundError` (`SceneFileNotFoundError`), a value of the wrong type also a `TypeError`
//! (`SceneTypeError`, `InputTypeError`) whose message names Python's types, a file that could
//! not be written an `OSError`.

use pyo3::prelude::*;
use slideroute::SceneErrorKind;

/// The classes of `slideroute._errors` (`python/slideroute/_errors.py`) the extension raises,
/// by their Python names (which end as Python's own exceptions' do).
#[derive(Debug, Clone, Copy)]
#[allow(clippy::enum_variant_names)]
enum Class {
    SceneError,
    SceneTypeError,
    SceneFileNotFoundError,
    InputError,
    InputTypeError,
    RouteError,
    OutputError,
}

/// A Python exception of `slideroute._errors`: `class(*args)`.
fn raise(py: Python<'_>, class: Class, args: Vec<String>) -> PyErr {
    let made = py
        .import("slideroute._errors")
        .and_then(|m| m.getattr(format!("{class:?}")))
        .and_then(|c| c.call1(pyo3::types::PyTuple::new(py, args)?));
    match made {
        Ok(e) => PyErr::from_value(e),
        Err(e) => e,
    }
}

/// The library's words before the reason a file could not be opened (`src/scene/input.rs`).
const CANNOT_READ: &str = "cannot read the file: ";

/// The file a scene error is about, when it is one the scene (or its file) names and that file
/// does not exist: asked of the file system, not read from the words of the message. The scene
/// file itself is the error's origin (its reason begins with [`CANNOT_READ`]); a file it names
/// (`foundation.surface`, `seismic.record`) is the path before them.
fn missing_file(e: &slideroute::SceneError) -> Option<String> {
    let at = e.reason.find(CANNOT_READ)?;
    let named = e.reason[..at].trim_end_matches(": ").trim();
    let path = if named.is_empty() {
        e.origin.as_str()
    } else {
        named
    };
    match std::fs::metadata(path) {
        Err(io) if io.kind() == std::io::ErrorKind::NotFound => Some(path.to_string()),
        _ => None,
    }
}

/// Python's name of the type serde's words name (`string "six"`, `integer `3``), with the
/// value where they give it.
fn python_type(unexpected: &str) -> String {
    const NAMES: [(&str, &str); 7] = [
        ("boolean", "bool"),
        ("integer", "int"),
        ("floating point", "float"),
        ("string", "str"),
        ("character", "str"),
        ("sequence", "list"),
        ("map", "dict"),
    ];
    for (serde, python) in NAMES {
        if let Some(rest) = unexpected.strip_prefix(serde) {
            let value = match rest.trim().trim_matches('`') {
                "true" => "True",
                "false" => "False",
                v => v,
            };
            return if value.is_empty() {
                python.to_string()
            } else {
                format!("{python} {value}")
            };
        }
    }
    unexpected.to_string()
}

/// What serde's expectation (`f64`, `a string`, `the table [frame]`) asks, in Python's words.
fn python_expected(expected: &str) -> String {
    match expected {
        "f64" | "f32" | "a float" => "a number (float)".to_string(),
        "a string" | "string" => "a string (str)".to_string(),
        "a boolean" | "bool" => "true or false (bool)".to_string(),
        "u8" | "u16" | "u32" | "u64" | "usize" | "i8" | "i16" | "i32" | "i64" | "isize"
        | "an integer" => "a whole number (int)".to_string(),
        "a sequence" | "an array" => "a list".to_string(),
        e if e.contains("table") => format!("{e} (a dict)"),
        e => e.to_string(),
    }
}

/// A wrong type's reason in Python's words: serde's `invalid type: string "six", expected f64`
/// as `expected a number (float), got str "six"`; any other reason as it is.
fn type_reason(reason: &str) -> String {
    let Some(rest) = reason.strip_prefix("invalid type: ") else {
        return reason.to_string();
    };
    match rest.rsplit_once(", expected ") {
        Some((got, expected)) => format!(
            "expected {}, got {}",
            python_expected(expected.trim()),
            python_type(got.trim())
        ),
        None => reason.to_string(),
    }
}

/// A scene error as `SceneError(message, key, origin)`: the key it names is `e.key`. A file
/// that does not exist is a `SceneFileNotFoundError` (with `filename`), a value of the wrong
/// type a `SceneTypeError`.
pub fn scene_error(py: Python<'_>, e: &slideroute::SceneError) -> PyErr {
    if let Some(path) = missing_file(e) {
        return raise(
            py,
            Class::SceneFileNotFoundError,
            vec![e.to_string(), e.key.clone(), e.origin.clone(), path],
        );
    }
    if e.kind == SceneErrorKind::WrongType {
        let mut python = e.clone();
        python.reason = type_reason(&e.reason);
        return raise(
            py,
            Class::SceneTypeError,
            vec![python.to_string(), e.key.clone(), e.origin.clone()],
        );
    }
    raise(
        py,
        Class::SceneError,
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
        Class::SceneError,
        vec![message, e.key.clone(), scene.origin().to_string()],
    )
}

/// A value a caller gave that cannot be used, as `InputError(message, name)`.
pub fn input_error(py: Python<'_>, name: &str, message: impl Into<String>) -> PyErr {
    raise(
        py,
        Class::InputError,
        vec![message.into(), name.to_string()],
    )
}

/// A value a caller gave of a type that cannot be used, as `InputTypeError(message, name)`:
/// an `InputError` and a `TypeError`.
pub fn input_type_error(py: Python<'_>, name: &str, message: impl Into<String>) -> PyErr {
    raise(
        py,
        Class::InputTypeError,
        vec![message.into(), name.to_string()],
    )
}

/// Outputs the library's writers could not write, as `OutputError(message)` (an `OSError`
/// naming the file or folder); an input they were asked of that cannot be used as
/// `InputError`; a writing stopped by Ctrl-C as `KeyboardInterrupt`.
pub fn output_error(py: Python<'_>, e: slideroute::output::OutputError) -> PyErr {
    use slideroute::output::OutputError;
    match e {
        OutputError::Input(message) => raise(py, Class::InputError, vec![message, String::new()]),
        OutputError::Write(message) => raise(py, Class::OutputError, vec![message]),
        OutputError::Interrupted { what, .. } => {
            pyo3::exceptions::PyKeyboardInterrupt::new_err(what)
        }
    }
}

/// A failure of the computation itself, as `RouteError(message, "")`.
pub fn route_error(py: Python<'_>, message: impl Into<String>) -> PyErr {
    raise(py, Class::RouteError, vec![message.into(), String::new()])
}
