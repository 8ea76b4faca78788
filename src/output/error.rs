//! What writing the outputs can come to: the files written (with what was left out and why), or
//! the one reason they could not be.

use std::path::PathBuf;

/// Why outputs could not be written. Each message is one line naming the file, folder or input
/// it is about.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum OutputError {
    /// An input the outputs were asked of that cannot be used (a load case's scene, a grid file
    /// that is not one): the caller's to mend.
    #[error("{0}")]
    Input(String),
    /// A file or folder that could not be written, read, moved or removed (a full disk, a link
    /// where an output goes, a folder another run holds), or a picture that could not be drawn.
    #[error("{0}")]
    Write(String),
    /// Stopped by the caller (`stop` answered true) before the outputs were whole: `what`
    /// stopped, and `written` are the files already written whole.
    #[error("{what}")]
    Interrupted {
        /// What stopped, in words.
        what: String,
        /// The files written whole before it stopped.
        written: Vec<PathBuf>,
    },
}

impl From<String> for OutputError {
    /// A failure to write, in words.
    fn from(message: String) -> OutputError {
        OutputError::Write(message)
    }
}

/// The files a writer wrote, in order, and what it left out with the reason (a route with
/// nothing to show in 3-D: the other files stand without its page).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Written {
    /// Every file written, whole, in the order written.
    pub files: Vec<PathBuf>,
    /// What was left out and why, one line each (`no route.html or route.glb: …`).
    pub warnings: Vec<String>,
}

impl Written {
    /// Adds `other`'s files and warnings after these.
    pub(crate) fn extend(&mut self, other: Written) {
        self.files.extend(other.files);
        self.warnings.extend(other.warnings);
    }
}
