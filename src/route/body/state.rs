//! The state of a body on its base: its pose, its velocities, and the work done on it so far.

use crate::geometry::BodyPose;
use nalgebra::{Matrix3, Rotation3, UnitQuaternion, Vector3};

/// Where the body is, how it moves, and the work done on it since the start.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct BodyState {
    /// The centre of mass and the rotation.
    pub pose: BodyPose,
    /// The CM's velocity (m/s, world).
    pub v: Vector3<f64>,
    /// The angular velocity (rad/s, world).
    pub w: Vector3<f64>,
    /// Work of the applied loads other than gravity's pull (J).
    pub work_applied: f64,
    /// Work of the contacts: friction and the impacts' losses (J, ≤ 0 up to round-off).
    pub work_contacts: f64,
    /// The path of the base's point under the CM since the start (m).
    pub path: f64,
}

impl BodyState {
    /// At rest in `pose`.
    pub fn at_rest(pose: BodyPose) -> Self {
        BodyState {
            pose,
            v: Vector3::zeros(),
            w: Vector3::zeros(),
            work_applied: 0.0,
            work_contacts: 0.0,
            path: 0.0,
        }
    }

    /// The inertia tensor in world axes, from the body's own `body` (about the CM).
    pub fn world_inertia(&self, body: &Matrix3<f64>) -> Matrix3<f64> {
        let r = self.pose.rotation;
        r * body * r.transpose()
    }

    /// The kinetic energy (J) of mass `mass` and body inertia `body`.
    pub fn kinetic(&self, mass: f64, body: &Matrix3<f64>) -> f64 {
        0.5 * mass * self.v.norm_squared() + 0.5 * self.w.dot(&(self.world_inertia(body) * self.w))
    }

    /// Moves the pose over `h` (s) at the velocities (the step's end velocities: the
    /// semi-implicit Euler step), the rotation by the exact exponential of ω h, kept a
    /// rotation.
    ///
    /// A motion over the step that is not finite (a step gone wrong) leaves the pose where it
    /// is, for the caller to end the route on the velocities: a rotation of NaN is never made
    /// (renormalising one would not converge, and the route would hang).
    pub fn drift(&mut self, h: f64) {
        let (dx, turn) = (self.v * h, self.w * h);
        if !dx.iter().chain(turn.iter()).all(|x| x.is_finite()) {
            return;
        }
        self.pose.cm += dx;
        let turn = Rotation3::from_scaled_axis(turn);
        let r = turn * Rotation3::from_matrix_unchecked(self.pose.rotation);
        self.pose.rotation = renormalized(&r).into_inner();
    }

    /// The yaw θ (rad): the angle of x′'s projection from +X towards +Z.
    pub fn yaw(&self) -> f64 {
        let i = self.pose.rotation.column(0);
        i.z.atan2(i.x)
    }

    /// θ̇ (rad/s): the rate of the yaw.
    pub fn yaw_rate(&self) -> f64 {
        let i: Vector3<f64> = self.pose.rotation.column(0).into_owned();
        let di = self.w.cross(&i);
        (i.x * di.z - i.z * di.x) / (i.x * i.x + i.z * i.z)
    }
}

/// The turn from rotation `r0` to `r1` as a rotation vector (rad, world axes): by way of the
/// quaternion, which stays exact for the smallest turns (the angle from the matrix's trace
/// loses its digits there, and its arc-cosine can be of a number just over one).
pub(super) fn turn_between(r0: &Matrix3<f64>, r1: &Matrix3<f64>) -> Vector3<f64> {
    let r = Rotation3::from_matrix_unchecked(r1 * r0.transpose());
    UnitQuaternion::from_rotation_matrix(&r).scaled_axis()
}

/// The rotation nearest `r`, as nalgebra's `Rotation3::renormalize` finds it (from `r`'s
/// quaternion, then at most [`RENORMALIZE_ITERATIONS`] of its iterations, where nalgebra's
/// own has no bound and some turns of 10¹⁵ rad never converged): the same rotation whenever
/// those converge, as they do within a few.
pub(super) fn renormalized(r: &Rotation3<f64>) -> Rotation3<f64> {
    let mut guess = UnitQuaternion::from_rotation_matrix(r);
    guess.renormalize();
    Rotation3::from_matrix_eps(
        r.matrix(),
        f64::EPSILON,
        RENORMALIZE_ITERATIONS,
        guess.to_rotation_matrix(),
    )
}

/// The most iterations [`renormalized`] takes.
const RENORMALIZE_ITERATIONS: usize = 100;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_turn_about_y_lowers_the_yaw_as_the_conventions_say() {
        let mut s = BodyState::at_rest(BodyPose {
            cm: Vector3::zeros(),
            rotation: Matrix3::identity(),
        });
        s.w = Vector3::new(0.0, 0.3, 0.0);
        assert!((s.yaw_rate() + 0.3).abs() < 1e-15);
        s.drift(1.0);
        assert!((s.yaw() + 0.3).abs() < 1e-14);
        let r = s.pose.rotation;
        assert!((r.transpose() * r - Matrix3::identity()).norm() < 1e-14);
    }

    #[test]
    fn a_motion_that_is_not_finite_leaves_the_pose_and_returns() {
        let pose = BodyPose {
            cm: Vector3::new(1.0, 2.0, 3.0),
            rotation: Matrix3::identity(),
        };
        for (v, w) in [
            (Vector3::zeros(), Vector3::new(0.0, f64::NAN, 0.0)),
            (Vector3::new(f64::INFINITY, 0.0, 0.0), Vector3::zeros()),
            (Vector3::zeros(), Vector3::new(1e308, 0.0, 0.0)),
        ] {
            let mut s = BodyState::at_rest(pose);
            s.v = v;
            s.w = w;
            // Before, a NaN turn renormalised for ever.
            s.drift(10.0);
            assert_eq!(s.pose, pose);
        }
    }
}
