//! How a route is run: which dynamics, which pose system, the increments and what is recorded
//! (`[solver]` in a scene file).

use super::error::{ModelError, positive};
use super::names::named;

/// The most increments one run may take (t_end / dt).
pub const MAX_INCREMENTS: f64 = 1e8;

/// The rigid body's tolerance where `[solver]` gives none: each step's error estimate, on the
/// CM's position and path as a fraction of the block's size L and on the yaw in radians, at most
/// this (`derivations/08-rigid-body.md` §4a). The default scene's route then ends within 10⁻⁸ m
/// of the converged one, its travel within 1.1·10⁻⁹ m (fixed steps of 1 ms, as before, summed
/// it over chords: 1.8·10⁻⁸ m short).
pub const DEFAULT_TOLERANCE: f64 = 1e-9;

/// The loosest tolerance a scene may ask for (looser, RK4's error estimate no longer says how
/// far the step is from the motion).
pub const MAX_TOLERANCE: f64 = 1e-3;

/// The tightest tolerance a scene may ask for: a step's error relative to the block's size below
/// this is round-off.
pub const MIN_TOLERANCE: f64 = 1e-14;

/// The step the rigid body's model is built around, at most: the time over which a young, slow
/// slip's direction is slaved to its friction (`mechanics::rigid_body::accelerations`'s `step`),
/// and the unit to which the shortest substep and the energy balance's tolerance are set. It was
/// the integrator's fixed step when the rigid body stepped in increments of dt; now that dt is the
/// interval of the recorded rows, none of these changes with dt beyond 1 ms.
pub const REFERENCE_STEP: f64 = 1e-3;

/// Which dynamics moves the block.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum DynamicsModel {
    /// The paper's (§5–7): translation along x' and rotation about y', shear directions
    /// chosen so that this holds (`mechanics::reactions_paper`).
    Paper,
    /// A rigid body with the three contacts held on their planes and Coulomb-type friction
    /// opposing each contact's slip (`derivations/08-rigid-body.md`). The default: it moves
    /// every scene the paper's dynamics moves, and many it cannot start or continue.
    #[default]
    RigidBody,
}

named!(DynamicsModel, "dynamics", [Paper => "paper", RigidBody => "rigid-body"]);

impl DynamicsModel {
    /// The integrator a model takes unless told otherwise: the paper's update for the paper's
    /// dynamics, RK4 (its only one) for the rigid body.
    pub fn default_integrator(self) -> Integrator {
        match self {
            DynamicsModel::Paper => Integrator::Paper,
            DynamicsModel::RigidBody => Integrator::Rk4,
        }
    }
}

/// Which polynomial system gives the pose.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Mode {
    /// The exact relations (13), (14) (see `derivations/04-exact.md`).
    Exact,
    /// The paper's small-angle system (15) (see `derivations/03-small-angle.md`).
    SmallAngle,
}

named!(Mode, "solver mode", [Exact => "exact", SmallAngle => "small-angle"]);

/// How the state is advanced over one increment.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Integrator {
    /// The paper's update (30)–(41): accelerations at the start of the increment, then
    /// v += a·dt and x += v·dt + a·dt²/2. First order.
    #[default]
    Paper,
    /// Classic fourth-order Runge–Kutta on the same right-hand side.
    Rk4,
}

named!(Integrator, "integrator", [Paper => "paper", Rk4 => "rk4"]);

/// Where the block touches the ground.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Contacts {
    /// The paper's idealisation: three points of a frame, each on its own face.
    #[default]
    Frame,
    /// The block's whole base: it touches the ground wherever they meet, rests where it is set
    /// down, rocks, hops and lands (`derivations/13-base-contact.md`).
    Base,
}

named!(Contacts, "contacts", [Frame => "frame", Base => "base"]);

/// The run settings: which dynamics and pose system, the increment and the time limit, the
/// integrator and which increments are recorded.
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub struct RunSettings {
    /// The pose system.
    pub mode: Mode,
    /// The interval of the recorded rows (s): the increment of the paper's dynamics; the rigid
    /// body chooses its own steps against `tolerance` and records a row every `dt`.
    pub dt: f64,
    /// Time limit (s).
    pub t_end: f64,
    /// How an increment is taken.
    pub integrator: Integrator,
    /// Record every `stride`-th increment (≥ 1).
    pub stride: usize,
    /// Which dynamics moves the block.
    pub dynamics: DynamicsModel,
    /// Where the block touches the ground.
    pub contacts: Contacts,
    /// The error tolerance per step (see [`DEFAULT_TOLERANCE`]): the rigid body's steps, and
    /// the substeps the paper's dynamics takes with RK4.
    pub tolerance: f64,
}

impl RunSettings {
    /// `dynamics` in increments of `dt` up to `t_end` (s), with the exact pose system, the
    /// model's own integrator, and every increment recorded.
    pub fn new(dynamics: DynamicsModel, dt: f64, t_end: f64) -> RunSettings {
        RunSettings {
            mode: Mode::Exact,
            dt,
            t_end,
            integrator: dynamics.default_integrator(),
            stride: 1,
            dynamics,
            contacts: Contacts::Frame,
            tolerance: DEFAULT_TOLERANCE,
        }
    }

    /// The same settings with the rigid body's error tolerance `tolerance`.
    #[must_use]
    pub fn with_tolerance(self, tolerance: f64) -> RunSettings {
        RunSettings { tolerance, ..self }
    }

    /// The rigid body's reference step: dt, up to [`REFERENCE_STEP`].
    pub fn reference_step(&self) -> f64 {
        self.dt.min(REFERENCE_STEP)
    }

    /// The same settings with the block touching the ground by `contacts`.
    #[must_use]
    pub fn with_contacts(self, contacts: Contacts) -> RunSettings {
        RunSettings { contacts, ..self }
    }

    /// The same settings with the pose system `mode`.
    #[must_use]
    pub fn with_mode(self, mode: Mode) -> RunSettings {
        RunSettings { mode, ..self }
    }

    /// The same settings with the integrator `integrator`.
    #[must_use]
    pub fn with_integrator(self, integrator: Integrator) -> RunSettings {
        RunSettings { integrator, ..self }
    }

    /// The same settings recording every `stride`-th increment.
    #[must_use]
    pub fn with_stride(self, stride: usize) -> RunSettings {
        RunSettings { stride, ..self }
    }

    /// The same settings with the other dynamics and that model's own integrator.
    #[must_use]
    pub fn with_dynamics(self, dynamics: DynamicsModel) -> RunSettings {
        RunSettings {
            dynamics,
            integrator: dynamics.default_integrator(),
            ..self
        }
    }

    /// Positive times, an increment no longer than the route, at most [`MAX_INCREMENTS`]
    /// increments, an integrator the dynamics has, a stride of at least 1.
    pub fn check(&self) -> Result<(), ModelError> {
        let (dt, t_end) = (self.dt, self.t_end);
        // Each time by itself first: `t_end_s = inf` is the time limit's fault, not the
        // increment's (t_end_s / dt_s is then infinite too).
        positive("solver.dt_s", dt)?;
        positive("solver.t_end_s", t_end)?;
        if dt > t_end && t_end > 0.0 {
            return Err(ModelError::new(
                "solver.dt_s",
                format!(
                    "the increment ({} s) is longer than the whole route (t_end_s = {} s)",
                    crate::numeric::given(dt),
                    crate::numeric::given(t_end)
                ),
            ));
        }
        let n = t_end / dt;
        if dt > 0.0 && t_end > 0.0 && n > MAX_INCREMENTS {
            // A count past the largest number (dt_s = 5e-324) is said in words, not `inf`
            // (which a sweep's table would hold as its reason).
            let count = if n.is_finite() {
                format!("{n:.3e}")
            } else {
                format!("{t_end} s / {dt:e} s, past the largest number of")
            };
            return Err(ModelError::new(
                "solver.dt_s",
                format!(
                    "t_end_s / dt_s = {count} increments, more than the {MAX_INCREMENTS:e} one \
                     run may take"
                ),
            ));
        }
        if self.dynamics == DynamicsModel::RigidBody && self.integrator != Integrator::Rk4 {
            return Err(ModelError::new(
                "solver.integrator",
                "the rigid-body dynamics integrates with \"rk4\" only (the paper's update \
                 belongs to the paper's dynamics)",
            ));
        }
        if self.contacts == Contacts::Base && self.dynamics != DynamicsModel::RigidBody {
            return Err(ModelError::new(
                "solver.contacts",
                "a base touching the ground wherever they meet moves as a rigid body: it needs \
                 solver.dynamics = \"rigid-body\"",
            ));
        }
        if self.stride == 0 {
            return Err(ModelError::new(
                "solver.stride",
                "must be a whole number of increments, 1 or more, got 0",
            ));
        }
        let tol = self.tolerance;
        if !(MIN_TOLERANCE..=MAX_TOLERANCE).contains(&tol) {
            return Err(ModelError::new(
                "solver.tolerance",
                format!(
                    "must be a number from {MIN_TOLERANCE:e} to {MAX_TOLERANCE:e} (a step's error \
                     as a fraction of the block's size), got {}",
                    crate::numeric::given(tol)
                ),
            ));
        }
        Ok(())
    }

    /// Whether the dynamics can follow the pose system: the rigid body's contact constraints
    /// need the exact one.
    pub fn check_runnable(&self) -> Result<(), ModelError> {
        if self.dynamics == DynamicsModel::RigidBody && self.mode == Mode::SmallAngle {
            return Err(ModelError::new(
                "solver.mode",
                "the rigid-body dynamics needs mode = \"exact\": small-angle poses (the paper's \
                 approximation (15)) leave the contacts off their planes (about 1 % in α at \
                 20–25° dips), which the rigid body's contact constraints cannot follow (the \
                 tracker then takes about a thousand steps an increment); use \"exact\", or \
                 dynamics = \"paper\" (--dynamics paper) for the small-angle system",
            ));
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn times_not_finite_are_each_their_own_keys_fault_and_no_message_says_inf() {
        let at = |dt: f64, t_end: f64| {
            RunSettings::new(DynamicsModel::RigidBody, dt, t_end)
                .check()
                .unwrap_err()
        };
        // Before, `t_end_s = inf` was solver.dt_s's fault: "t_end_s / dt_s = inf increments".
        let e = at(1e-3, f64::INFINITY);
        assert_eq!(e.key, "solver.t_end_s");
        assert!(e.reason.contains("finite"), "{}", e.reason);
        assert_eq!(at(f64::NAN, 20.0).key, "solver.dt_s");
        // A count of increments past the largest number is said in words.
        let e = at(5e-324, 0.2);
        assert_eq!(e.key, "solver.dt_s");
        assert!(e.reason.contains("past the largest number"), "{}", e.reason);
        assert!(!e.reason.contains("inf"), "{}", e.reason);
        assert!(at(1e-9, 20.0).reason.contains("2.000e10 increments"));
    }

    #[test]
    fn each_dynamics_brings_its_own_integrator_and_refuses_the_others() {
        let s = RunSettings::new(DynamicsModel::RigidBody, 1e-3, 1.0);
        assert_eq!(s.integrator, Integrator::Rk4);
        assert!(s.check().is_ok());
        let e = s.with_integrator(Integrator::Paper).check().unwrap_err();
        assert_eq!(e.key, "solver.integrator");
        let p = s.with_dynamics(DynamicsModel::Paper);
        assert_eq!(p.integrator, Integrator::Paper);
        assert!(p.with_mode(Mode::SmallAngle).check_runnable().is_ok());
        let e = s.with_mode(Mode::SmallAngle).check_runnable().unwrap_err();
        assert_eq!(e.key, "solver.mode");
    }

    #[test]
    fn times_and_strides_out_of_range_are_refused_naming_their_key() {
        let s = |dt, t_end| RunSettings::new(DynamicsModel::Paper, dt, t_end);
        assert_eq!(s(2.0, 1.0).check().unwrap_err().key, "solver.dt_s");
        assert_eq!(s(1e-9, 1.0).check().unwrap_err().key, "solver.dt_s");
        assert_eq!(s(-1.0, 1.0).check().unwrap_err().key, "solver.dt_s");
        assert_eq!(s(1e-3, f64::NAN).check().unwrap_err().key, "solver.t_end_s");
        let e = s(1e-3, 1.0).with_stride(0).check().unwrap_err();
        assert_eq!(e.key, "solver.stride");
        for tol in [0.0, -1e-9, 1e-2, 1e-15, f64::NAN, f64::INFINITY] {
            let e = s(1e-3, 1.0).with_tolerance(tol).check().unwrap_err();
            assert_eq!(e.key, "solver.tolerance", "{tol}");
        }
        assert!(s(1e-3, 1.0).with_tolerance(1e-6).check().is_ok());
        // Numbers far from 1 are said as given, not in 300 digits.
        let e = s(1e300, 1.0).check().unwrap_err().to_string();
        assert!(e.contains("(1e300 s)"), "{e}");
        let e = s(1e-3, 1e-300).check().unwrap_err().to_string();
        assert!(e.contains("t_end_s = 1e-300 s"), "{e}");
        let e = s(1e-3, 1.0).with_tolerance(1e-300).check().unwrap_err();
        assert!(e.to_string().ends_with("got 1e-300"), "{e}");
        assert_eq!("small-angle".parse::<Mode>(), Ok(Mode::SmallAngle));
        assert!("rigid".parse::<DynamicsModel>().is_err());
    }
}
