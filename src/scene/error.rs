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
    /// The scene's other faults found with this one (each with its own key; at most
    /// ten in all): sections that do not depend on each other are each checked, so
    /// that a file with several mistakes is told of them together. Not shown by `Display`,
    /// which is this fault's one line; [`SceneError::faults`] gives them all.
    pub also: Box<[SceneError]>,
}

/// The most faults one [`SceneError`] reports (itself and [`SceneError::also`]).
pub(crate) const MAX_FAULTS: usize = 10;

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
            also: Box::default(),
        }
    }

    /// This fault and the others found with it ([`SceneError::also`]), in the order found.
    pub fn faults(&self) -> impl Iterator<Item = &SceneError> {
        std::iter::once(self).chain(self.also.iter())
    }

    /// This fault with `more` found besides: those of another key than every fault already
    /// held, up to [`MAX_FAULTS`] in all.
    pub(crate) fn with_also(mut self, more: impl IntoIterator<Item = SceneError>) -> Self {
        let mut also = std::mem::take(&mut self.also).into_vec();
        for e in more.into_iter().flat_map(|e| {
            let nested = e.also.clone();
            std::iter::once(SceneError {
                also: Box::default(),
                ..e
            })
            .chain(nested)
        }) {
            if also.len() + 1 >= MAX_FAULTS {
                break;
            }
            if self.key != e.key && also.iter().all(|f| f.key != e.key) {
                also.push(e);
            }
        }
        self.also = also.into_boxed_slice();
        self
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
