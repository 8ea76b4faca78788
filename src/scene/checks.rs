//! Checks of single values shared by the scene's validation (`validate`, `dam`, `cases`): a
//! key that must be there, a number in its range, a name among its options.

use super::SceneError;
use super::error::SceneErrorKind;

/// The value of a key its section needs.
pub(super) fn need<T>(origin: &str, key: &str, v: Option<T>) -> Result<T, SceneError> {
    v.ok_or_else(|| {
        let name = key.rsplit('.').next().unwrap_or(key);
        SceneError::of(
            SceneErrorKind::MissingKey,
            origin,
            key,
            format!("missing key `{name}`"),
        )
    })
}

/// A section the scene needs.
pub(super) fn section<'a, T>(
    origin: &str,
    name: &str,
    v: &'a Option<T>,
) -> Result<&'a T, SceneError> {
    v.as_ref().ok_or_else(|| {
        SceneError::of(
            SceneErrorKind::MissingSection,
            origin,
            name,
            format!("missing section [{name}]"),
        )
    })
}

/// The option named `word` among `all` (by their file names), or an error listing them.
pub(super) fn named<T: Copy>(
    origin: &str,
    key: &str,
    what: &str,
    word: &str,
    all: &[T],
    name: fn(T) -> &'static str,
) -> Result<T, SceneError> {
    all.iter()
        .copied()
        .find(|&t| name(t) == word)
        .ok_or_else(|| {
            let names: Vec<_> = all.iter().map(|&t| format!("\"{}\"", name(t))).collect();
            SceneError::new(
                origin,
                key,
                format!(
                    "unknown {what} \"{word}\"; expected one of {}",
                    names.join(", ")
                ),
            )
        })
}

/// Checks one number: finite, and `ok(v)`; `what` says what was expected.
pub(super) fn check(
    origin: &str,
    key: &str,
    v: f64,
    ok: bool,
    what: &str,
) -> Result<f64, SceneError> {
    if !v.is_finite() {
        return Err(SceneError::new(
            origin,
            key,
            format!("must be a finite number, got {v}"),
        ));
    }
    if !ok {
        return Err(SceneError::new(
            origin,
            key,
            format!("must be {what}, got {v}"),
        ));
    }
    Ok(v)
}

pub(super) fn positive(origin: &str, key: &str, v: f64) -> Result<f64, SceneError> {
    check(origin, key, v, v > 0.0, "positive")
}

pub(super) fn non_negative(origin: &str, key: &str, v: f64) -> Result<f64, SceneError> {
    check(origin, key, v, v >= 0.0, "zero or positive")
}
