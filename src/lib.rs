//! # slideroute
//!
//! The three-dimensional failure route of a rigid block — a concrete gravity-dam monolith —
//! sliding on a foundation of one horizontal and two inclined planes with three-point contact,
//! after Galic & Glaser, "Outline of a Method for Determining the Three Dimensional Failure
//! Route of a Sliding Block". Equation numbers in the docs are the paper's.
//!
//! A route from a scene file (`run` checks the scene first; [`Simulation::new`] then
//! [`simulate`] does it in two steps, and a `Simulation` runs without failing):
//!
//! ```
//! let scene = slideroute::Scene::from_file("scenes/turning.toml".as_ref())?;
//! let route = slideroute::run(&scene)?;
//! println!("{} at t = {} s after {:.3} m", route.termination.reason, route.termination.t_s, route.travel_m);
//! # assert!(route.travel_m > 0.0);
//! # Ok::<(), slideroute::SceneError>(())
//! ```
//!
//! The poses behind it — the coefficients of the pose system, all its roots, the physical one
//! followed by continuation, and the independent direct solver every test measures against:
//!
//! ```
//! use slideroute::{CoeffInputs, Displacement, Mode, Scene, SmallAngle, Tracker};
//! let scene = Scene::default_scene();
//! let d = Displacement::new(0.5, 0.1, 2f64.to_radians());
//! let f = SmallAngle::new(&CoeffInputs::new(scene.site().as_paper().unwrap(), d)); // f1–f12 of (15)
//! assert_eq!(f.f.len(), 12);
//! let all = slideroute::solve_all(scene.site(), d, Mode::Exact).unwrap(); // every root, classified
//! let mut tracker = Tracker::new(scene.site(), Mode::Exact);
//! let here = tracker.advance(d).unwrap(); // u = (α, ψ) on the physical branch
//! let oracle = slideroute::direct_pose(scene.site(), d).unwrap();
//! assert!((here.u[0] - oracle.alpha(scene.l())).abs() < 1e-9 && !all.roots.is_empty());
//! ```
//!
//! Data flows one way, one private module per stage (`ARCHITECTURE.md` says where each lives):
//! scene → geometry (the model's frame and planes) → coefficients (generated at build time by
//! `codegen/`) → roots → pose → mechanics (loads, friction, reactions) → route (one driver, a
//! [`Dynamics`](stages::route) per model) → rows. [`stages`] opens them for the command line,
//! the tests and the benchmarks; it is not the library's interface.

mod check;
mod coeffs;
mod compare;
mod geometry;
mod mechanics;
mod numeric;
mod roots;
mod route;
mod scene;
mod uncertainty;

pub use check::{CaseResult, check_cases};
pub use coeffs::{CoeffInputs, Exact, SmallAngle};
pub use compare::{Comparison, compare_dynamics, compare_dynamics_observed};
pub use geometry::direct::solve as direct_pose;
pub use geometry::{Displacement, Pose, Site};
pub use mechanics::static_friction::FactorOfSafety;
pub use roots::{AllRoots, Root, Tracker, solve_all};
pub use route::{
    Diagnostics, EnergyBalance, PoseMethod, Reason, Route, Row, Termination, run, run_observed,
    run_streamed, run_with, simulate,
};
pub use scene::{DynamicsModel, Friction, Integrator, Mode, Scene, SceneError, Simulation};

/// The stages themselves, each with everything in it public, so that the command line can
/// report them and the tests and benchmarks can measure them one by one. Not the library's
/// interface: use the items at the crate's root.
pub mod stages {
    pub mod check {
        pub use crate::check::*;
    }
    pub mod coeffs {
        pub use crate::coeffs::*;
    }
    pub mod compare {
        pub use crate::compare::*;
    }
    pub mod geometry {
        pub use crate::geometry::*;
    }
    pub mod mechanics {
        pub use crate::mechanics::*;
    }
    pub mod numeric {
        pub use crate::numeric::*;
    }
    pub mod roots {
        pub use crate::roots::*;
    }
    pub mod route {
        pub use crate::route::*;
    }
    pub mod scene {
        pub use crate::scene::*;
    }
    pub mod uncertainty {
        pub use crate::uncertainty::*;
    }
}

/// The README's Rust examples, compiled and run as doc-tests.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
pub struct ReadmeDoctests;
