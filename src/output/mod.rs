//! The files and pictures of routes and analyses, written as the command line writes them, for
//! any caller (the command line and Python call the same writers).
//!
//! An [`OutputFolder`] is a folder a person can trust: locked while one command writes into it,
//! each file whole or absent, nothing written or removed through a link, and the files a
//! command wrote there before and did not write again removed when it finishes, its manifest
//! (`summary.json`, `check.json`, …) written last and naming every file beside it. Into it:
//!
//! * a route ([`RouteFiles`]): `route.csv` ([`RouteCsv`], streamed as the route computes), the
//!   pictures (`plan.svg` like the paper's Figure 12, `profile.svg`, `angles.svg`,
//!   `reactions.svg`), the route in 3-D (`route.html`, which plays it offline, and `route.glb`)
//!   and `summary.json`; the plan view alone by [`Route::plot_plan`](crate::Route::plot_plan),
//!   and what the command line prints of it by
//!   [`Computed::summary`](crate::Computed::summary);
//! * a check of load cases ([`CheckFiles`]): `check.csv`, `report.html` (a page to hand in:
//!   each case's section drawn with its loads, the verdicts and where they come from),
//!   `check.json`, and each failing case's route;
//! * both dynamics' routes of a scene ([`ComparisonFiles`]), a sweep ([`SweepFiles`]), a
//!   probabilistic analysis ([`ProbabilisticFiles`]), the work–precision report
//!   ([`WorkPrecision`]);
//! * every root at one displacement ([`RootsReport`]) or at each pose of a grid file
//!   ([`GridPoses`], [`GridRows`]), and the paper's coefficients there ([`CoeffReport`]).
//!
//! Every writer says what it wrote ([`Written`]) or why it could not ([`OutputError`]). The
//! pictures need the `plots` feature, the 3-D view the `view` feature (both on by default).
//!
//! ```
//! use slideroute::output::{OutputFolder, RouteFiles};
//! let scene = slideroute::Scene::from_file("scenes/turning.toml".as_ref())?;
//! let sim = scene.simulation()?;
//! let dir = std::env::temp_dir().join(format!("slideroute-doc-output-{}", std::process::id()));
//! let mut folder = OutputFolder::open(&dir, "run")?;
//! let files = RouteFiles::new(&scene);
//! let (csv, computed) = files.stream(&mut folder, &sim, |_| std::ops::ControlFlow::Continue(()))?;
//! let written = files.write(folder, &computed)?;
//! print!("{}", computed.summary(&written.files));
//! # assert!(csv.is_file() && dir.join("plan.svg").is_file() && dir.join("route.html").is_file());
//! # std::fs::remove_dir_all(&dir)?;
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

mod check_csv;
mod check_files;
mod check_report;
mod check_tables;
mod coeffs_report;
mod compare_files;
mod error;
mod folder;
mod grid_csv;
#[cfg(any(feature = "plots", feature = "view"))]
mod half_plane;
mod manifest;
#[cfg(feature = "plots")]
mod plots;
mod probabilistic_files;
mod roots_report;
mod route_csv;
mod route_files;
mod samples_csv;
mod summary;
mod sweep_csv;
mod sweep_files;
mod sweep_row;
#[cfg(feature = "view")]
mod view;
mod work_precision;

pub use check_files::CheckFiles;
pub use coeffs_report::CoeffReport;
pub use compare_files::ComparisonFiles;
pub use error::{OutputError, Written};
pub use folder::OutputFolder;
pub use grid_csv::{GridPose, GridPoses, GridRows};
pub use probabilistic_files::ProbabilisticFiles;
pub use roots_report::RootsReport;
pub use route_csv::RouteCsv;
pub use route_files::RouteFiles;
pub use sweep_files::SweepFiles;
pub use work_precision::WorkPrecision;

use serde::ser::{Serialize, SerializeMap, Serializer};

/// The most routes of many whose CM paths a fan draws (`route-fan.svg`, `route-fan.html`,
/// `sweep.html`): the first that ran, in order.
const MAX_FAN_PATHS: usize = 1000;

/// A number as the tables write it (a cell of `sweep.csv` or `samples.csv`) and as a message
/// quotes it: its shortest form that reads back the same, in scientific notation past 10¹⁶ or
/// below 10⁻⁵ in size (`1e-300`, not 300 zeros); empty where it is not a finite number, as for
/// a quantity a row does not have (none is expected): never `inf` or `NaN`.
///
/// ```
/// use slideroute::output::number;
/// assert_eq!(number(0.25), "0.25");
/// assert_eq!(number(1e308), "1e308");
/// assert_eq!(number(f64::NAN), "");
/// ```
pub fn number(v: f64) -> String {
    if v.is_finite() {
        crate::numeric::given(v).to_string()
    } else {
        String::new()
    }
}

/// A map that keeps its insertion order when serialised (f1 … f12, not f1, f10, f11 …).
#[derive(Debug, Clone, PartialEq, Default)]
struct Ordered<V>(Vec<(String, V)>);

impl<V: Serialize> Serialize for Ordered<V> {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        let mut m = s.serialize_map(Some(self.0.len()))?;
        for (k, v) in &self.0 {
            m.serialize_entry(k, v)?;
        }
        m.end()
    }
}
