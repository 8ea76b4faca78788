//! The stiff and extreme cases of the work–precision report: scenes chosen to break naive
//! code, each run and its tilts checked against the direct pose solver.

use super::ladder::computed;
use crate::{Computed, DynamicsModel, Mode, PoseMethod, Scene};
use serde::Serialize;

/// A named case of the stiff and extreme suite.
#[derive(Debug, Clone)]
pub(crate) struct Case {
    pub name: &'static str,
    pub scene: Scene,
}

/// The keys that set the frame's l1z / l2z to `ratio`, keeping the side L.
fn l1z_over_l2z(s: &Scene, ratio: f64) -> [(&'static str, toml::Value); 2] {
    let l = s.l();
    let l1z = l * ratio / (1.0 + ratio);
    [("frame.l1z", l1z.into()), ("frame.l2z", (l - l1z).into())]
}

/// Scenes chosen to break naive code (see `docs/performance.md`, "Stiff and extreme cases").
pub(crate) fn extreme_cases() -> Result<Vec<Case>, String> {
    // The stiff and extreme cases are the paper's dynamics' unless a case says otherwise.
    let base = Scene::default_scene()
        .with_dynamics(DynamicsModel::Paper)
        .map_err(|e| e.to_string())?;
    // Each case is the base scene with some keys changed, as a scene file would change them.
    let case = |name: &'static str, keys: &[(&str, toml::Value)]| {
        let keys = keys.iter().map(|(k, v)| (*k, v.clone()));
        // The cases are fixed and valid (`every_extreme_case_is_a_valid_scene`).
        base.with_keys(keys.chain([("name", name.into())]))
            .map(|scene| Case { name, scene })
            .map_err(|e| format!("extreme case {name}: {e}"))
    };
    let f = |v: f64| toml::Value::Float(v);
    let force = |v: f64| ("loads.hydraulic_force_n", f(v));
    let dips = |xi: f64, zeta: f64| {
        [
            ("foundation.xi_deg", f(xi)),
            ("foundation.zeta_deg", f(zeta)),
        ]
    };
    // Paper-like: driving (F − 2.338 MN) against a capacity of 4.152 MN at μ = 0.4; FS = R / D.
    let force_for_fs = |fs: f64| 4.152_011e6 / fs + 2.337_862e6;
    let rigid = ("solver.dynamics", toml::Value::from("rigid-body"));
    [
        case("dips 0.5°", &dips(0.5, 0.5)),
        case("dips 1°/2°", &dips(1.0, 2.0)),
        case(
            "dips 60°/65°",
            &[dips(60.0, 65.0).as_slice(), &[force(3.0e7)]].concat(),
        ),
        case(
            "dips 75°/80°",
            &[dips(75.0, 80.0).as_slice(), &[force(8.0e7)]].concat(),
        ),
        case("κ = 0", &[("foundation.kappa_deg", f(0.0))]),
        case("κ = 85°", &[("foundation.kappa_deg", f(85.0))]),
        case("κ = −85°", &[("foundation.kappa_deg", f(-85.0))]),
        case("lopsided l1z/l2z = 0.05", &l1z_over_l2z(&base, 0.05)),
        case("lopsided l1z/l2z = 20", &l1z_over_l2z(&base, 20.0)),
        case(
            "tiny inertia I = 1e-5 m L²",
            &[("block.inertia_kg_m2", f(1e3))],
        ),
        case(
            "friction just below onset (FS 0.999)",
            &[force(force_for_fs(0.999))],
        ),
        case(
            "friction just above onset (FS 1.001)",
            &[force(force_for_fs(1.001))],
        ),
        case("huge dt 0.25 s", &[("solver.dt_s", f(0.25))]),
        case(
            "tiny dt 1 µs",
            &[("solver.dt_s", f(1e-6)), ("solver.t_end_s", f(0.05))],
        ),
        case("small-angle mode", &[("solver.mode", "small-angle".into())]),
        case("frictionless", &[("friction.mu_k", f(0.0))]),
        case(
            "kicked: 0.3 m/s under 3 MN (FS 6.3)",
            &[force(3.0e6), ("initial.vx_m_s", f(0.3))],
        ),
        case(
            "kicked, rigid body: 1 m/s, μ = 0.6",
            &[rigid, ("friction.mu_k", f(0.6)), ("initial.vx_m_s", f(1.0))],
        ),
    ]
    .into_iter()
    .collect()
}

/// The outcome of one stiff or extreme case.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub(crate) struct ExtremeRow {
    pub case: String,
    pub reason: String,
    pub t_s: f64,
    pub travel_m: f64,
    pub increments: usize,
    pub rejected_steps: usize,
    pub newton_per_step: f64,
    pub end_jacobian_condition: Option<f64>,
    /// Largest |α − α_direct|, |β − β_direct| over a sample of rows (rad; exact mode only).
    pub max_tilt_error_rad: Option<f64>,
    pub detail: String,
}

/// Runs the stiff and extreme cases, checking up to `sample` rows of each against the direct
/// pose solver (exact mode).
pub(crate) fn extreme(sample: usize) -> Result<Vec<ExtremeRow>, String> {
    Ok(extreme_cases()?
        .into_iter()
        .map(|c| {
            let Computed {
                route: r,
                diagnostics,
            } = match computed(&c.scene, PoseMethod::Continuation) {
                Ok(r) => r,
                Err(e) => {
                    return ExtremeRow {
                        case: c.name.into(),
                        reason: "invalid scene".into(),
                        t_s: 0.0,
                        travel_m: 0.0,
                        increments: 0,
                        rejected_steps: 0,
                        newton_per_step: 0.0,
                        end_jacobian_condition: None,
                        max_tilt_error_rad: None,
                        detail: e,
                    };
                }
            };
            let exact = c.scene.settings().is_some_and(|s| s.mode == Mode::Exact);
            let tilt_error = exact.then(|| {
                let l = c.scene.l();
                let every = (r.rows.len() / sample.max(1)).max(1);
                r.rows
                    .iter()
                    .step_by(every)
                    .filter_map(|row| {
                        let d = crate::geometry::Displacement::new(
                            row.x_m,
                            row.z_m,
                            row.theta_deg.to_radians(),
                        );
                        let p = crate::poses::direct_pose(c.scene.site(), d).ok()?;
                        Some(
                            (p.alpha(l) - row.alpha_deg.to_radians())
                                .abs()
                                .max((p.beta(l) - row.beta_deg.to_radians()).abs()),
                        )
                    })
                    .fold(0.0, f64::max)
            });
            let stats = diagnostics.tracker.unwrap_or_default();
            ExtremeRow {
                case: c.name.into(),
                reason: r.termination.reason.as_str().into(),
                t_s: r.termination.t_s,
                travel_m: r.travel_m,
                increments: r.increments,
                rejected_steps: stats.rejected,
                newton_per_step: stats.newton_iterations as f64 / stats.steps.max(1) as f64,
                end_jacobian_condition: diagnostics.end_jacobian_condition,
                max_tilt_error_rad: tilt_error,
                detail: r.termination.detail.clone(),
            }
        })
        .collect())
}
