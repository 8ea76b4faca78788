//! Why a part of the model cannot be used ([`ModelError`]), and the checks of single values
//! every part makes with it.

/// A part of the model that cannot be used, and why. `key` names the value as a scene file
/// writes it (`block.mass_kg`, `solver.dt_s`, `friction.face[1].mu_k`): the one vocabulary of
/// the scene file, the command line's `--vary` and Python, so that a simulation built in code
/// and one read from a file report the same fault the same way.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("{key}: {reason}")]
pub struct ModelError {
    /// The value at fault, as a scene key (or a section's name for a fault of the whole).
    pub key: String,
    /// Why, in one line.
    pub reason: String,
}

impl ModelError {
    /// A fault of `key`.
    pub fn new(key: impl Into<String>, reason: impl Into<String>) -> Self {
        ModelError {
            key: key.into(),
            reason: reason.into(),
        }
    }
}

/// One number: finite, and `ok`; `what` says what was expected.
pub(crate) fn check(key: &str, v: f64, ok: bool, what: &str) -> Result<f64, ModelError> {
    if !v.is_finite() {
        return Err(ModelError::new(
            key,
            format!("must be a finite number, got {}", crate::numeric::given(v)),
        ));
    }
    if !ok {
        return Err(ModelError::new(
            key,
            format!("must be {what}, got {}", crate::numeric::given(v)),
        ));
    }
    Ok(v)
}

/// A finite number.
pub(crate) fn finite(key: &str, v: f64) -> Result<f64, ModelError> {
    check(key, v, true, "finite")
}

/// A positive number.
pub(crate) fn positive(key: &str, v: f64) -> Result<f64, ModelError> {
    check(key, v, v > 0.0, "positive")
}

/// A number zero or more.
pub(crate) fn non_negative(key: &str, v: f64) -> Result<f64, ModelError> {
    check(key, v, v >= 0.0, "zero or positive")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_value_out_of_range_names_its_key_what_was_expected_and_what_was_given() {
        assert_eq!(positive("block.mass_kg", 2.0), Ok(2.0));
        let e = positive("block.mass_kg", -1.0).unwrap_err();
        assert_eq!(e.to_string(), "block.mass_kg: must be positive, got -1");
        let e = non_negative("friction.mu_k", f64::NAN).unwrap_err();
        assert_eq!(e.reason, "must be a finite number, got NaN");
        assert!(finite("x", f64::INFINITY).is_err() && non_negative("x", 0.0).is_ok());
        // A huge value as written, not its 301 digits.
        let e = positive("block.mass_kg", -1e300).unwrap_err();
        assert_eq!(e.reason, "must be positive, got -1e300");
    }
}
