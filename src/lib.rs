//! # slideroute
//!
//! The three-dimensional failure route of a rigid block — a concrete gravity-dam monolith —
//! sliding on a foundation of one horizontal and two inclined planes with three-point contact,
//! after Galic & Glaser, "Outline of a Method for Determining the Three Dimensional Failure
//! Route of a Sliding Block". Equation numbers in the docs are the paper's.
//!
//! Data flows one way, one module per stage:
//! [`scene`] → [`coeffs`] (generated at build time by `codegen/`) → [`roots`] → [`geometry`]
//! (exact pose, and the independent direct pose solver that every test measures against) →
//! [`mechanics`] (loads, friction, the paper's reactions or the rigid body's) → [`route`] →
//! [`output`]. [`compare`] puts the paper's route beside the rigid body's.
//!
//! ```
//! use slideroute::{coeffs, geometry::Displacement, scene::Scene};
//! let scene = Scene::default_scene();
//! let d = Displacement::new(0.5, 0.1, 2f64.to_radians());
//! let f = coeffs::SmallAngle::new(&coeffs::CoeffInputs::new(&scene, d));
//! assert_eq!(f.f.len(), 12);
//! ```

pub mod coeffs;
pub mod compare;
pub mod geometry;
pub mod mechanics;
pub mod numeric;
pub mod roots;
pub mod route;
pub mod scene;
