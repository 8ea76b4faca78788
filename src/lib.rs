//! # slideroute
//!
//! The three-dimensional failure route of a rigid block — a concrete gravity-dam monolith —
//! sliding on its rock foundation, pushed by water whose line misses its centre of mass so that
//! it turns as it slides: after Galic & Glaser, "Outline of a Method for Determining the Three
//! Dimensional Failure Route of a Sliding Block". Equation numbers in the docs are the paper's.
//!
//! **From a scene file.** A [`Scene`] is read and checked, every fault a [`SceneError`] naming
//! its key and line; [`run`] gives its [`Route`]: the recorded [`Row`]s, how it ended
//! ([`Termination`], [`Reason`]), the factor of safety at the start ([`FactorOfSafety`]), the
//! travel and the energy balance.
//!
//! ```
//! let scene = slideroute::Scene::from_file("scenes/turning.toml".as_ref())?;
//! let route = slideroute::run(&scene)?;
//! println!("{} at t = {} s after {:.3} m", route.termination.reason, route.termination.t_s, route.travel_m);
//! # assert!(route.travel_m > 0.0);
//! # Ok::<(), slideroute::SceneError>(())
//! ```
//!
//! **From typed parts.** A [`Simulation`] is the model: its bodies — each [`Body`] a [`Block`]
//! with its [`Loads`], its [`Initial`] motion, its [`Base`] and anchors, and its three-point
//! frame on the rock (a [`Site`]: the contacts and the planes under them) —, the [`Foundation`]
//! they stand on (the rock as a [`Ground`], and a ground-motion [`Record`] shaking it), the
//! [`Joint`]s between bodies, what every pair of surfaces carries ([`Strengths`]: each rock
//! face's [`Friction`] criterion and cohesion, each joint's), and its [`RunSettings`]. It is
//! built by [`Simulation::builder`] and [`Body::builder`] (or [`Scene::simulation`]) and checked
//! once, every fault a [`ModelError`]. [`simulate`] runs it and cannot fail; a [`Runner`] also
//! reports progress, may be stopped, streams the rows and says how the computation went
//! ([`Diagnostics`]). The paper's dynamics and the three-point frame follow one body; a
//! simulation of several bodies (on their bases) is a valid model whose route, for now, ends at
//! once ([`Reason`]'s `SeveralBodies`).
//!
//! **Many routes.** A sweep of scene keys ([`sweep`]), a probabilistic analysis
//! ([`probabilistic`]), the load cases of a guideline ([`check`]) and the paper's dynamics
//! beside the rigid body's ([`compare`]) run through one runner, the command line and Python
//! alike; each of many routes comes to a [`RouteResult`], or an [`Outcome`] without one.
//!
//! **Their files** (`output`, with the `output` feature): the folders the command line writes —
//! `route.csv`, `summary.json`, the pictures (`plots`), the route in 3-D (`view`), a check's
//! `report.html`, the tables of sweeps and samples — written whole or not at all into a locked
//! folder, by the writers the command line and Python both call.
//!
//! **The poses behind it** ([`poses`]). The coefficients of the pose system (`SmallAngle`'s
//! f1–f12 of (15), `Exact`), all its roots by eigenvalues (`solve_all`), the physical one
//! followed by continuation (`Tracker`), and the independent direct solver every test measures
//! against (`direct_pose`):
//!
//! ```
//! use slideroute::poses::{CoeffInputs, SmallAngle, Tracker, direct_pose, solve_all};
//! use slideroute::{Displacement, Mode, Scene};
//! let scene = Scene::default_scene();
//! let d = Displacement::new(0.5, 0.1, 2f64.to_radians());
//! let f = SmallAngle::new(&CoeffInputs::new(scene.site().as_paper().unwrap(), d)); // f1–f12 of (15)
//! assert_eq!(f.f.len(), 12);
//! let all = solve_all(scene.site(), d, Mode::Exact).unwrap(); // every root, classified
//! let mut tracker = Tracker::new(scene.site(), Mode::Exact);
//! let here = tracker.advance(d).unwrap(); // u = (α, ψ) on the physical branch
//! let oracle = direct_pose(scene.site(), d).unwrap();
//! assert!((here.u[0] - oracle.alpha(scene.l())).abs() < 1e-9 && !all.roots.is_empty());
//! ```
//!
//! Data flows one way, one private module per stage (`ARCHITECTURE.md` says where each lives):
//! scene → model → geometry → coefficients (generated at build time by `codegen/`) → roots →
//! pose → mechanics (loads, friction, reactions) → route (one driver, a dynamics model each) →
//! analysis (many routes) → output (their files and pictures, the one stage that is public).
//! Units are SI; angles are radians in these types and degrees in every file a person reads or
//! writes.

#![forbid(unsafe_code)]
#![warn(missing_docs)]

mod analysis;
mod coeffs;
mod contact;
mod geometry;
mod mechanics;
mod model;
mod numeric;
#[cfg(feature = "output")]
pub mod output;
mod roots;
mod route;
mod scene;

pub use analysis::runner::{NOT_RUN, Outcome, RouteResult};
pub use analysis::{run, run_observed};
pub use geometry::{BodyPose, Displacement, Frame, Ground, PaperPlanes, Plane, Pose, Site};
pub use mechanics::static_friction::{FactorOfSafety, Limit};
pub use model::{
    Base, Block, Body, BodyBuilder, ContactStrength, Contacts, DEFAULT_TOLERANCE, DynamicsModel,
    FaceStrength, Foundation, Friction, Initial, Integrator, Joint, Levels, Loads, MAX_INCREMENTS,
    MAX_TOLERANCE, MIN_TOLERANCE, MassProperties, Mode, ModelError, Monolith, PairStrength,
    REFERENCE_STEP, Record, Resultant, RockAnchor, RunSettings, STRAND_MODULUS_PA, Section,
    Simulation, SimulationBuilder, Strengths, Surface, Tendon, UnknownName, WaterLoads,
};
pub use route::models::{
    BaseReport, Carrying, OVERTURN_DEG, OnBaseReport, PaperReport, Resting, RigidBodyReport,
    pose_of_row,
};
pub use route::{
    AnchorBreak, Computed, Diagnostics, EnergyBalance, KEPT_ROWS, PoseMethod, Reason, Report,
    Route, Row, Runner, Steps, Termination, simulate,
};
pub use scene::{LoadsUsed, Scene, SceneError, SceneErrorKind};

/// The poses behind a route: the coefficients of the pose systems, all their roots by
/// eigenvalues, the physical one followed by continuation, and the independent direct solver.
pub mod poses {
    pub use crate::coeffs::{CoeffInputs, Exact, SmallAngle};
    pub use crate::geometry::DirectPose;
    pub use crate::geometry::direct::solve as direct_pose;
    pub use crate::roots::{
        AllRoots, BatchSolver, BranchPoint, Inadmissible, Root, TrackError, TrackStats, Tracker,
        solve_all, solve_all_batch,
    };
}

/// Load cases checked against the sliding factor of safety their guideline requires.
pub mod check {
    pub use crate::analysis::anchor_design::{AnchorDesign, design_anchors};
    pub use crate::analysis::check::{CaseResult, check_cases, check_cases_until, meets};
    pub use crate::analysis::gravity_method::{
        GravityCase, GravityVerdict, gravity_method, required_compression,
    };
    pub use crate::model::uplift_heads;
    pub use crate::model::{Category, Guideline, LoadCase, SiteInformation, Structure};
}

/// The paper's dynamics beside the rigid body's: both routes of one scene, and where they part.
pub mod compare {
    pub use crate::analysis::compare::{
        Comparison, Parting, compare_dynamics, compare_dynamics_observed, compare_dynamics_streamed,
    };
}

/// Sweeps: every combination of values of some scene keys, each combination's route.
pub mod sweep {
    pub use crate::analysis::sweep::{
        KeyError, MAX_COMBINATIONS, MAX_VALUES, Sweep, SweepRow, Vary, check_key,
    };
}

/// The probabilistic analysis: uncertain scene keys with their distributions, a design of
/// samples drawn from a seed, every sample's route, and what they come to.
pub mod probabilistic {
    pub use crate::analysis::probabilistic::{
        CHUNK, Columns, Design, Distribution, FORMS, Given, Limits, MAX_SAMPLES, Percentiles,
        Probability, Sample, Sampling, Sensitivity, Summary, Tally, Uncertain, check_uncertain,
        merged, proportion, run_values, sample_rows, sample_scene, sample_values, summarise,
    };
}

/// Every stage with everything in it, so that the tests and benchmarks can measure them one by
/// one: not an interface to build on, and behind the `internals` feature (which only the tests
/// and benchmarks turn on).
#[cfg(feature = "internals")]
#[doc(hidden)]
pub mod internals {
    pub mod analysis {
        pub use crate::analysis::*;
    }
    pub mod coeffs {
        pub use crate::coeffs::*;
    }
    pub mod contact {
        pub use crate::contact::*;
    }
    pub mod geometry {
        pub use crate::geometry::*;
    }
    pub mod mechanics {
        pub use crate::mechanics::*;
    }
    pub mod model {
        pub use crate::model::*;
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
}

/// The README's Rust examples, compiled and run as doc-tests.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
pub struct ReadmeDoctests;
