//! What the command line hands to people: typed reports that serialise to JSON and print as
//! tables, summaries, the files of an output folder and the pictures.

#[cfg(feature = "cli")]
pub mod check_files;
#[cfg(feature = "cli")]
pub mod check_report;
pub mod coeffs_report;
#[cfg(feature = "cli")]
pub mod compare_files;
#[cfg(feature = "cli")]
pub mod folder;
#[cfg(feature = "cli")]
pub mod grid_csv;
#[cfg(feature = "plots")]
pub mod plots;
#[cfg(feature = "cli")]
pub mod report_files;
pub mod roots_report;
#[cfg(feature = "cli")]
pub mod route_files;
#[cfg(feature = "cli")]
pub mod samples_files;
#[cfg(feature = "cli")]
pub mod summary;
#[cfg(feature = "cli")]
pub mod sweep_files;
#[cfg(feature = "cli")]
pub mod view;

pub use coeffs_report::CoeffReport;
pub use roots_report::RootsReport;

use serde::ser::{Serialize, SerializeMap, Serializer};

/// A map that keeps its insertion order when serialised (f1 … f12, not f1, f10, f11 …).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Ordered<V>(pub Vec<(String, V)>);

impl<V: Serialize> Serialize for Ordered<V> {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        let mut m = s.serialize_map(Some(self.0.len()))?;
        for (k, v) in &self.0 {
            m.serialize_entry(k, v)?;
        }
        m.end()
    }
}
