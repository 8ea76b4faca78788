//! The state of the block on its base within a step (`derivations/13-base-contact.md` §12): a
//! step may be longer than the interval of the recorded rows, and the rows within it are its
//! dense output — the CM by the cubic through its two ends and their velocities, the turn from
//! the start as a rotation vector by the same cubic through the angular velocities, the works
//! and the path by a straight line. Within O(h⁴) of the motion in position where the step is
//! smooth.

use super::state::{BodyState, renormalized, turn_between};
use crate::route::integrator::hermite;
use nalgebra::{Rotation3, Vector3};

/// The state at the fraction `u` ∈ [0, 1] of a step of `h` from `s0` to `s1`.
pub(super) fn between(s0: &BodyState, s1: &BodyState, h: f64, u: f64) -> BodyState {
    let arr = |v: &Vector3<f64>| [v.x, v.y, v.z];
    let vec = |a: [f64; 3]| Vector3::new(a[0], a[1], a[2]);
    let cm = hermite(
        (&arr(&s0.pose.cm), &arr(&s0.v)),
        (&arr(&s1.pose.cm), &arr(&s1.v)),
        h,
        u,
    );
    let r0 = Rotation3::from_matrix_unchecked(s0.pose.rotation);
    let turned = turn_between(&s0.pose.rotation, &s1.pose.rotation);
    let turn = hermite((&[0.0; 3], &arr(&s0.w)), (&arr(&turned), &arr(&s1.w)), h, u);
    let lerp = |a: f64, b: f64| a + u * (b - a);
    let mut s = *s0;
    s.pose.cm = vec(cm);
    s.pose.rotation = renormalized(&(Rotation3::from_scaled_axis(vec(turn)) * r0)).into_inner();
    s.v = vec(slope(
        (&arr(&s0.pose.cm), &arr(&s0.v)),
        (&arr(&s1.pose.cm), &arr(&s1.v)),
        h,
        u,
    ));
    s.w = s0.w.lerp(&s1.w, u);
    s.work_applied = lerp(s0.work_applied, s1.work_applied);
    s.work_contacts = lerp(s0.work_contacts, s1.work_contacts);
    s.path = lerp(s0.path, s1.path);
    s
}

/// The derivative in time of [`hermite`]'s cubic at the fraction `s` of the step of `h`.
fn slope(
    (y0, f0): (&[f64; 3], &[f64; 3]),
    (y1, f1): (&[f64; 3], &[f64; 3]),
    h: f64,
    s: f64,
) -> [f64; 3] {
    let s2 = s * s;
    let d00 = (6.0 * s2 - 6.0 * s) / h;
    let d10 = 3.0 * s2 - 4.0 * s + 1.0;
    let d01 = (-6.0 * s2 + 6.0 * s) / h;
    let d11 = 3.0 * s2 - 2.0 * s;
    std::array::from_fn(|i| d00 * y0[i] + d10 * f0[i] + d01 * y1[i] + d11 * f1[i])
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::BodyPose;
    use nalgebra::Matrix3;

    /// A body falling freely and turning steadily: its CM a parabola, which the cubic holds
    /// exactly, and a steady turn about a fixed axis, which the rotation vector holds exactly.
    #[test]
    fn a_parabola_and_a_steady_turn_are_their_own_dense_output() {
        let g = Vector3::new(0.0, -9.81, 0.0);
        let w = Vector3::new(0.0, 0.7, 0.2);
        let at = |t: f64| {
            let mut s = BodyState::at_rest(BodyPose {
                cm: Vector3::new(1.0, 2.0, 3.0),
                rotation: Matrix3::identity(),
            });
            let v0 = Vector3::new(2.0, 1.0, -1.0);
            s.pose.cm += v0 * t + 0.5 * g * t * t;
            s.v = v0 + g * t;
            s.w = w;
            s.pose.rotation = Rotation3::from_scaled_axis(w * t).into_inner();
            s
        };
        let h = 0.4;
        for u in [0.1, 0.5, 0.93] {
            let s = between(&at(0.0), &at(h), h, u);
            let want = at(u * h);
            assert!((s.pose.cm - want.pose.cm).norm() < 1e-14, "{u}");
            assert!((s.v - want.v).norm() < 1e-13, "{u}");
            assert!((s.pose.rotation - want.pose.rotation).norm() < 1e-14, "{u}");
        }
    }
}
