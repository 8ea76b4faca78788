//! Scene errors: each names where it came from (file or embedded default), the key, and why.

use std::fmt;

/// A scene that cannot be used. Displays as one line:
/// `FILE: KEY: REASON (line L, column C)`.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub struct SceneError {
    /// The file path, or `<embedded default scene>`.
    pub origin: String,
    /// The key as `section.key` (or a section name, or empty for the file as a whole).
    pub key: String,
    /// Why it is rejected, in one line.
    pub reason: String,
    /// 1-based line and column in the file, when known.
    pub position: Option<(usize, usize)>,
    /// What kind of fault it is, for callers that act on it (the reason is for people).
    pub kind: SceneErrorKind,
}

/// The kinds of [`SceneError`].
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SceneErrorKind {
    /// The file cannot be read, or is not TOML.
    Unreadable,
    /// A key or section no scene has.
    UnknownKey,
    /// A section a scene, or the command, needs is absent.
    MissingSection,
    /// A key its section needs is absent.
    MissingKey,
    /// A value of the wrong type (a word for a number, …).
    WrongType,
    /// A value out of its range, a name no option has, or values that do not go together.
    Invalid,
}

impl SceneError {
    /// An [`SceneErrorKind::Invalid`] value.
    pub(crate) fn new(origin: &str, key: impl Into<String>, reason: impl Into<String>) -> Self {
        SceneError::of(SceneErrorKind::Invalid, origin, key, reason)
    }

    pub(crate) fn of(
        kind: SceneErrorKind,
        origin: &str,
        key: impl Into<String>,
        reason: impl Into<String>,
    ) -> Self {
        SceneError {
            origin: origin.to_string(),
            key: key.into(),
            reason: one_line(&reason.into()),
            position: None,
            kind,
        }
    }
}

/// Folds a multi-line message into one line.
pub(crate) fn one_line(s: &str) -> String {
    s.split('\n')
        .map(str::trim)
        .filter(|l| !l.is_empty())
        .collect::<Vec<_>>()
        .join("; ")
}

impl fmt::Display for SceneError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}: ", self.origin)?;
        if !self.key.is_empty() {
            write!(f, "{}: ", self.key)?;
        }
        write!(f, "{}", self.reason)?;
        if let Some((l, c)) = self.position {
            write!(f, " (line {l}, column {c})")?;
        }
        Ok(())
    }
}
