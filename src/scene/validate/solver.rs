//! `[solver]` and `[initial]`: how the route is run, and the motion at its start.

use super::Reader;
use crate::model::{DynamicsModel, Initial, RunSettings};
use crate::scene::SceneError;
use crate::scene::raw::{RawInitial, RawSolver};

impl Reader<'_> {
    /// The run settings, with each dynamics model's default integrator.
    pub(super) fn solver(&self, s: &RawSolver) -> Result<RunSettings, SceneError> {
        let mode = self.named("solver.mode", self.need("solver.mode", s.mode.as_deref())?)?;
        let dynamics: DynamicsModel = match s.dynamics.as_deref() {
            None => DynamicsModel::default(),
            Some(w) => self.named("solver.dynamics", w)?,
        };
        let mut settings = RunSettings::new(
            dynamics,
            self.need("solver.dt_s", s.dt_s)?,
            self.need("solver.t_end_s", s.t_end_s)?,
        )
        .with_mode(mode);
        if let Some(w) = s.integrator.as_deref() {
            settings = settings.with_integrator(self.named("solver.integrator", w)?);
        }
        if let Some(k) = s.stride {
            if k < 1 {
                return Err(self.invalid(
                    "solver.stride",
                    format!("must be a whole number of increments, 1 or more, got {k}"),
                ));
            }
            settings = settings.with_stride(usize::try_from(k).unwrap_or(usize::MAX));
        }
        settings.check().map_err(|e| self.model(e))?;
        Ok(settings)
    }

    /// `[initial]` in the file's units (degrees a second for the yaw rate); at rest without it.
    pub(super) fn initial(&self, i: Option<&RawInitial>) -> Result<Initial, SceneError> {
        let Some(i) = i else {
            return Ok(Initial::default());
        };
        let rate = |key: &str, v: Option<f64>| self.finite(key, v.unwrap_or(0.0));
        Ok(Initial::new(
            rate("initial.vx_m_s", i.vx_m_s)?,
            rate("initial.vz_m_s", i.vz_m_s)?,
            rate("initial.omega_deg_s", i.omega_deg_s)?.to_radians(),
        ))
    }
}
