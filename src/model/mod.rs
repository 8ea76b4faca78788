//! The physical model, at the bottom of the house: the bodies (each a block with its loads, its
//! motion at the start, its base, its anchors and its three-point frame), the foundation they
//! stand on and its shaking, the joints between bodies, what every pair of surfaces carries in
//! shear, the monolith's section and the water on it, how a route is run, and the load cases a
//! guideline checks. Plain typed values and their physics, each checked against its range
//! (the errors name each value as a scene file does), and put together in a [`Simulation`].
//! No file format lives here: the scene reader (`scene/`) builds these from a scene file.

mod anchor;
mod base;
mod block;
mod body;
mod error;
mod foundation;
mod friction;
mod guideline;
mod initial;
mod intensity;
mod joint;
mod loads;
mod monolith;
pub(crate) mod names;
mod record;
mod settings;
mod simulation;
mod strength;
mod water;

pub use anchor::{RockAnchor, STRAND_MODULUS_PA, Tendon};
pub use base::{Base, triangle_quadrature};
pub use block::Block;
pub(crate) use body::check_ratios;
pub use body::{Body, BodyBuilder};
pub use error::ModelError;
pub(crate) use error::{check, finite, non_negative, positive};
pub use foundation::Foundation;
pub use friction::Friction;
pub use guideline::{Category, Guideline, LoadCase, SiteInformation, Structure};
pub use initial::Initial;
pub use intensity::Intensity;
pub use joint::Joint;
pub use loads::Loads;
pub use monolith::{MassProperties, Monolith, Section};
pub use names::UnknownName;
pub use record::Record;
pub(crate) use record::bracket;
pub use settings::{
    Contacts, DEFAULT_TOLERANCE, DynamicsModel, Integrator, MAX_INCREMENTS, MAX_TOLERANCE,
    MIN_TOLERANCE, Mode, REFERENCE_STEP, RunSettings,
};
pub use simulation::{Simulation, SimulationBuilder};
pub(crate) use simulation::{check_anchored, check_rigid_only, face_count};
pub use strength::{
    ContactStrength, ContactStrengths, FaceStrength, PairStrength, Settling, Strengths, Surface,
    barycentric,
};
pub(crate) use water::water_loads_cracked;
pub use water::{Ice, Levels, Resultant, Silt, WaterLoads, uplift_heads};
