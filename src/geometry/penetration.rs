//! How far a base is inside the ground, by sampling: an independent check of the contact
//! model's own gaps (`derivations/13-base-contact.md` §5).
//!
//! The base is sampled on a grid over its outline's bounding box (the points on the base) and
//! along its edges; at each sample the rock's height over its plan point — a ray cast down onto
//! the ground in the collision library's shapes ([`super::rock::Rock`]) — is compared with the sample's own.
//! Nothing here uses the touches the dynamics uses, nor the ground's own geometry.

use super::ground::Ground;
use super::touch::{BodyPose, in_outline, plan_box};
use nalgebra::Vector3;

/// The deepest a sample of the base `outline` (x′, z′ about the CM, at `depth` below it) at
/// `pose` is below the ground, measured vertically (m; zero or negative when every sample is on
/// or above it), with `per_side` samples along each side of the grid and of each edge. Samples
/// over no ground are skipped.
#[cfg_attr(not(feature = "internals"), allow(dead_code))]
pub fn deepest(
    ground: &Ground,
    outline: &[[f64; 2]],
    depth: f64,
    pose: &BodyPose,
    per_side: usize,
) -> f64 {
    deepest_of(ground, &samples(outline, depth, per_side), pose)
}

/// The samples of the base `outline` at `depth` below the CM, in body axes (m), as [`deepest`]
/// takes them: a `per_side` × `per_side` grid over its bounding box, those on it, and `per_side`
/// along each edge.
pub fn samples(outline: &[[f64; 2]], depth: f64, per_side: usize) -> Vec<Vector3<f64>> {
    let per_side = per_side.max(2);
    let b = plan_box(outline.iter().copied());
    let step = |k: usize, i: usize| {
        b[2 * k] + (b[2 * k + 1] - b[2 * k]) * i as f64 / (per_side - 1) as f64
    };
    let mut points: Vec<[f64; 2]> = Vec::with_capacity(per_side * per_side);
    for i in 0..per_side {
        for j in 0..per_side {
            let p = [step(0, i), step(1, j)];
            if in_outline(outline, p) {
                points.push(p);
            }
        }
    }
    let n = outline.len();
    for k in 0..n {
        let (a, b) = (outline[k], outline[(k + 1) % n]);
        for i in 0..per_side {
            let s = i as f64 / per_side as f64;
            points.push([a[0] + s * (b[0] - a[0]), a[1] + s * (b[1] - a[1])]);
        }
    }
    points
        .into_iter()
        .map(|[x, z]| Vector3::new(x, -depth, z))
        .collect()
}

/// [`deepest`] over `samples` (body axes, m) at `pose`.
pub fn deepest_of(ground: &Ground, samples: &[Vector3<f64>], pose: &BodyPose) -> f64 {
    ground.rock().deepest(samples.iter().map(|s| pose.point(s)))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::Plane;
    use nalgebra::Matrix3;

    #[test]
    fn a_base_sunk_into_a_sloping_plane_is_as_deep_as_its_lowest_corner_is_below_it() {
        // A plane rising 10° along +X; the level base 2 m × 2 m with its centre at Y = 0.05 m:
        // its corner at X = +1 is tan 10° − 0.05 m below the plane, the deepest of its points.
        let dip = 10f64.to_radians();
        let plane = Plane::through(Vector3::new(-dip.sin(), dip.cos(), 0.0), Vector3::zeros());
        let ground = Ground::planes(vec![plane]);
        let outline = [[-1.0, -1.0], [1.0, -1.0], [1.0, 1.0], [-1.0, 1.0]];
        let pose = BodyPose {
            cm: Vector3::new(0.0, 0.05, 0.0),
            rotation: Matrix3::identity(),
        };
        let d = deepest(&ground, &outline, 0.0, &pose, 6);
        assert!((d - (dip.tan() - 0.05)).abs() < 1e-12, "{d}");
        // Lifted clear of it, the deepest sample is above the plane.
        let high = BodyPose {
            cm: Vector3::new(0.0, 0.5, 0.0),
            ..pose
        };
        assert!(deepest(&ground, &outline, 0.0, &high, 6) < 0.0);
    }
}
