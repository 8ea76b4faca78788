//! `[solver]` and `[initial]`: how the route is run, and the motion at its start.

use super::Reader;
use crate::model::{Contacts, DynamicsModel, Initial, Mode, RunSettings};
use crate::scene::SceneError;
use crate::scene::raw::{RawInitial, RawScene, RawSolver};

/// The increment where `[solver]` gives no `dt_s` (s).
pub(crate) const DEFAULT_DT_S: f64 = 1e-3;
/// The time limit where `[solver]` gives no `t_end_s` (s).
pub(crate) const DEFAULT_T_END_S: f64 = 20.0;

impl Reader<'_> {
    /// Where the block touches the ground: `solver.contacts` as given, or by default its base
    /// wherever the rigid body runs on faces, a surface or under a monolith with Coulomb
    /// friction and no cohesion, and the paper's three-point frame on the paper's planes, under
    /// the paper's dynamics, or with cohesion or a stress-dependent criterion (whose routes have
    /// always been the frame's).
    pub(super) fn contacts_of(&self, raw: &RawScene) -> Result<Contacts, SceneError> {
        let solver = raw.solver.as_ref();
        if let Some(w) = solver.and_then(|s| s.contacts.as_deref()) {
            return self.named("solver.contacts", w);
        }
        let dynamics: DynamicsModel = match solver.and_then(|s| s.dynamics.as_deref()) {
            None => DynamicsModel::default(),
            Some(w) => self.named("solver.dynamics", w)?,
        };
        let faces = raw
            .foundation
            .as_ref()
            .is_some_and(|f| f.plane.is_some() || f.surface.is_some());
        let body = faces || raw.monolith.is_some();
        // A scene with cohesion or a stress-dependent criterion has always had its frame: it
        // stays on its frame unless told (a base takes both, `derivations/13-base-contact.md`
        // §11, with `contacts = "base"`).
        let coulomb = |model: Option<&str>, cohesion: Option<f64>| {
            model.is_none_or(|m| m == "coulomb") && cohesion.is_none_or(|c| c == 0.0)
        };
        let plain = raw.friction.as_ref().is_none_or(|f| {
            coulomb(f.model.as_deref(), f.cohesion_pa)
                && f.face
                    .iter()
                    .flatten()
                    .all(|g| coulomb(g.model.as_deref(), g.cohesion_pa))
        });
        Ok(if body && plain && dynamics == DynamicsModel::RigidBody {
            Contacts::Base
        } else {
            Contacts::Frame
        })
    }

    /// The run settings (each key's default where it is not given: `mode = "exact"`,
    /// [`DEFAULT_DT_S`], [`DEFAULT_T_END_S`], the rigid body), with each dynamics model's default integrator and the block touching
    /// the ground by `contacts`.
    pub(super) fn solver(
        &self,
        s: &RawSolver,
        contacts: Contacts,
    ) -> Result<RunSettings, SceneError> {
        let mode = match s.mode.as_deref() {
            None => Mode::Exact,
            Some(w) => self.named("solver.mode", w)?,
        };
        let dynamics: DynamicsModel = match s.dynamics.as_deref() {
            None => DynamicsModel::default(),
            Some(w) => self.named("solver.dynamics", w)?,
        };
        let mut settings = RunSettings::new(
            dynamics,
            s.dt_s.unwrap_or(DEFAULT_DT_S),
            s.t_end_s.unwrap_or(DEFAULT_T_END_S),
        )
        .with_mode(mode);
        if let Some(w) = s.integrator.as_deref() {
            settings = settings.with_integrator(self.named("solver.integrator", w)?);
        }
        settings = settings.with_contacts(contacts);
        if let Some(k) = s.stride {
            if k < 1 {
                return Err(self.invalid(
                    "solver.stride",
                    format!("must be a whole number of increments, 1 or more, got {k}"),
                ));
            }
            settings = settings.with_stride(usize::try_from(k).unwrap_or(usize::MAX));
        }
        if let Some(tol) = s.tolerance {
            settings = settings.with_tolerance(tol);
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
