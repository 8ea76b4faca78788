//! The scene file as written: TOML, degrees, exactly the documented keys (unknown keys are
//! errors). [`super::Scene`] is the validated, typed form, in radians.

use serde::Deserialize;

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawScene {
    pub name: Option<String>,
    pub frame: RawFrame,
    pub foundation: RawFoundation,
    pub block: Option<RawBlock>,
    pub loads: Option<RawLoads>,
    pub friction: Option<RawFriction>,
    pub solver: Option<RawSolver>,
    pub initial: Option<RawInitial>,
}

/// The motion at t = 0 (default: at rest).
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawInitial {
    pub vx_m_s: Option<f64>,
    pub vz_m_s: Option<f64>,
    pub omega_deg_s: Option<f64>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawFrame {
    pub l1x: f64,
    pub l2x: f64,
    pub l1z: f64,
    pub l2z: f64,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawFoundation {
    pub xi_deg: f64,
    pub zeta_deg: f64,
    pub kappa_deg: f64,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawBlock {
    pub mass_kg: f64,
    pub inertia_kg_m2: f64,
    /// Rigid-body mode: moments about x' and z' and the product ∫x'z' dm (default: a thin
    /// plate, half of `inertia_kg_m2` each, product 0).
    pub inertia_x_kg_m2: Option<f64>,
    pub inertia_z_kg_m2: Option<f64>,
    pub inertia_xz_kg_m2: Option<f64>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawLoads {
    pub hydraulic_force_n: f64,
    pub eccentricity_m: f64,
    pub gravity_m_s2: f64,
}

#[derive(Debug, Deserialize)]
#[serde(tag = "model", rename_all = "kebab-case", deny_unknown_fields)]
pub enum RawFriction {
    Coulomb {
        mu_k: f64,
    },
    BartonChoubey {
        jrc: f64,
        jcs_pa: f64,
        phi_r_deg: f64,
        contact_area_m2: f64,
    },
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawSolver {
    pub mode: super::Mode,
    pub dt_s: f64,
    pub t_end_s: f64,
    /// Default: "paper" for the paper's dynamics, "rk4" for the rigid body.
    pub integrator: Option<super::Integrator>,
    #[serde(default)]
    pub dynamics: super::DynamicsModel,
    /// Record every `stride`-th increment (default 1: every one).
    pub stride: Option<i64>,
}
