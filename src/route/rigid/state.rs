//! The rigid body's state: the three degrees of freedom (X, Z, θ) and their rates, the work
//! done so far by the applied loads and by friction, and the time. The integrator sees it as an
//! array ([`RigidState::to_array`]); everything else by name.

use crate::geometry::Displacement;
use crate::mechanics::rigid_body::Motion;
use crate::model::Initial;

/// The state of the sliding block (m, rad, m/s, rad/s, J, s).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub(super) struct RigidState {
    /// The CM's displacement X and Z (m) and the yaw θ (rad).
    pub x: f64,
    pub z: f64,
    pub theta: f64,
    /// Their rates Ẋ, Ż (m/s) and θ̇ (rad/s).
    pub vx: f64,
    pub vz: f64,
    pub omega: f64,
    /// The work done so far by the applied loads — the water, the pseudo-static and a record's
    /// inertial forces — (W_h) and by friction (W_f, ≤ 0), integrated with the motion so that
    /// the energy balance holds to the integrator's order (J).
    pub work_applied: f64,
    pub work_friction: f64,
    /// The time (s), on which a ground-motion record's loads depend.
    pub t: f64,
    /// The length of the CM's path so far (m), integrated with the motion (its rate the CM's
    /// speed) so that it does not depend on how long the steps are.
    pub travel: f64,
}

/// The number of the state's values, as the integrator sees them.
pub(super) const VALUES: usize = 10;

impl RigidState {
    /// At the start: in place, moving as `initial` says, no work done, t = 0.
    pub fn start(initial: &Initial) -> RigidState {
        RigidState {
            vx: initial.vx,
            vz: initial.vz,
            omega: initial.omega,
            ..RigidState::default()
        }
    }

    /// Where the block is: (X, Z, θ).
    pub fn displacement(&self) -> Displacement {
        Displacement::new(self.x, self.z, self.theta)
    }

    /// (Ẋ, Ż, θ̇).
    pub fn rates(&self) -> [f64; 3] {
        [self.vx, self.vz, self.omega]
    }

    /// X, Z, θ and their rates: what a row on the three-point frame shows of the state.
    pub fn frame_state(&self) -> [f64; 6] {
        [self.x, self.z, self.theta, self.vx, self.vz, self.omega]
    }

    /// The same state with its rates replaced.
    pub fn with_rates(self, [vx, vz, omega]: [f64; 3]) -> RigidState {
        RigidState {
            vx,
            vz,
            omega,
            ..self
        }
    }

    /// The same state at rest: its rates zero.
    pub fn stopped(self) -> RigidState {
        self.with_rates([0.0; 3])
    }

    /// The same state at time `t`.
    pub fn at(self, t: f64) -> RigidState {
        RigidState { t, ..self }
    }

    /// The state's rate of change with the motion `m` at it: the rates, the accelerations, the
    /// loads' and friction's power, time's own rate and the CM's speed.
    pub fn derivative(&self, m: &Motion) -> [f64; VALUES] {
        [
            self.vx,
            self.vz,
            self.omega,
            m.acc[0],
            m.acc[1],
            m.acc[2],
            m.power_hydraulic,
            m.power_friction,
            1.0,
            m.twist.v.norm(),
        ]
    }

    /// The values in the integrator's order.
    pub fn to_array(self) -> [f64; VALUES] {
        [
            self.x,
            self.z,
            self.theta,
            self.vx,
            self.vz,
            self.omega,
            self.work_applied,
            self.work_friction,
            self.t,
            self.travel,
        ]
    }

    /// The state of values in the integrator's order.
    pub fn from_array(y: &[f64; VALUES]) -> RigidState {
        let [
            x,
            z,
            theta,
            vx,
            vz,
            omega,
            work_applied,
            work_friction,
            t,
            travel,
        ] = *y;
        RigidState {
            x,
            z,
            theta,
            vx,
            vz,
            omega,
            work_applied,
            work_friction,
            t,
            travel,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_state_reads_back_from_its_array_and_its_rates_are_its_own() {
        let s = RigidState {
            x: 1.0,
            z: 2.0,
            theta: 3.0,
            vx: 4.0,
            vz: 5.0,
            omega: 6.0,
            work_applied: 7.0,
            work_friction: 8.0,
            t: 9.0,
            travel: 10.0,
        };
        assert_eq!(RigidState::from_array(&s.to_array()), s);
        assert_eq!(
            s.to_array(),
            [1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0, 9.0, 10.0]
        );
        assert_eq!(s.rates(), [4.0, 5.0, 6.0]);
        assert_eq!(s.stopped().rates(), [0.0; 3]);
        assert_eq!(s.with_rates([1.0; 3]).t, 9.0);
    }
}
