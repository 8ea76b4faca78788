//! The sweep as its files write and draw it: each combination's row with its values and what
//! its route came to as cells (`sweep.csv`, `sweep.svg`). The sweep itself — its keys' checks,
//! its combinations and their routes — is the analysis's (`src/analysis/sweep.rs`).

use crate::{FactorOfSafety, Outcome};

/// One combination as a row of the table.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct SweepRow {
    /// The varied values, in the order of the `--vary` flags.
    pub values: Vec<f64>,
    /// The termination reason, "invalid scene" or "not run (interrupted)".
    pub reason: String,
    pub t_end_s: Option<f64>,
    pub travel_m: Option<f64>,
    pub final_theta_deg: Option<f64>,
    pub max_alpha_deg: Option<f64>,
    pub max_beta_deg: Option<f64>,
    /// Under a ground-motion record, the permanent displacement along X and Z (m).
    pub permanent_x_m: Option<f64>,
    pub permanent_z_m: Option<f64>,
    /// The factor of safety at the start (friction cones), whatever the dynamics.
    pub factor_of_safety: Option<FactorOfSafety>,
    pub detail: String,
}

impl From<&crate::sweep::SweepRow> for SweepRow {
    fn from(row: &crate::sweep::SweepRow) -> SweepRow {
        let route = row.outcome.route();
        let of = |f: fn(&crate::RouteResult) -> f64| route.map(f);
        SweepRow {
            values: row.values.clone(),
            reason: row.outcome.reason().to_string(),
            t_end_s: of(|r| r.t_s),
            travel_m: of(|r| r.travel_m),
            final_theta_deg: of(|r| r.yaw_deg),
            max_alpha_deg: of(|r| r.max_alpha_deg),
            max_beta_deg: of(|r| r.max_beta_deg),
            permanent_x_m: route.and_then(|r| r.permanent_xz_m).map(|d| d[0]),
            permanent_z_m: route.and_then(|r| r.permanent_xz_m).map(|d| d[1]),
            factor_of_safety: route.and_then(|r| r.factor_of_safety),
            detail: match &row.outcome {
                Outcome::Route(r) => r.detail.clone(),
                Outcome::Invalid { reason } => reason.clone(),
                Outcome::NotRun => {
                    "the sweep was interrupted before this combination started".to_string()
                }
            },
        }
    }
}
