//! Where a cast base's relief meets the ground (`derivations/13-base-contact.md` §10): its
//! vertices on the faces of the ground, the ground's vertices under its faces, and the ground's
//! edges across its bends and rim.
//!
//! On a ground of planes the rock is the union of the half-spaces under them, and the deepest
//! point of a polyhedral relief in a half-space is one of its vertices: the vertices against
//! every plane are the whole story, as the corners of a flat base are. On a surface the other
//! two kinds come from the triangles under the relief, found in the ground's R*-tree, and the
//! relief's own faces and edges are found in its trees.

use super::Relief;
use crate::geometry::touch::{Touches, holding_faces};
use crate::geometry::wedge::{RockEdge, between, rock_edge};
use crate::geometry::{BodyPose, Feature, Ground, Touch, plan_box};
use nalgebra::Vector3;
use std::collections::HashSet;

/// The touches of `relief` at `pose` on `ground` whose gap is below `reach` (m), each vertex
/// meeting the faces it may reach in a step that moves it up to `drift` (m). The vertices over
/// no ground are named in `off_ground`.
pub fn relief_touches(
    ground: &Ground,
    relief: &Relief,
    pose: &BodyPose,
    reach: f64,
    drift: f64,
) -> Touches {
    let mut out = Touches::default();
    let world: Vec<Vector3<f64>> = relief.vertices().iter().map(|v| pose.point(v)).collect();
    for (k, q) in world.iter().enumerate() {
        let Some(faces) = holding_faces(ground, q, drift) else {
            out.off_ground.push(k);
            continue;
        };
        for f in faces {
            let gap = ground.faces()[f].signed_distance(q);
            if gap < reach {
                out.touches.push(Touch {
                    on_base: *q,
                    body: relief.vertices()[k],
                    normal: ground.faces()[f].normal(),
                    gap,
                    face: f,
                    feature: Feature::ReliefVertex(k),
                });
            }
        }
    }
    if ground.is_surface() {
        let [x0, x1, z0, z1] = plan_box(world.iter().map(|c| [c.x, c.z]));
        let rect = (x0 - reach, x1 + reach, z0 - reach, z1 + reach);
        let mut seen: HashSet<[u64; 6]> = HashSet::new();
        for f in ground.faces_in(rect) {
            under_relief(ground, relief, pose, f, reach, &mut seen, &mut out);
        }
    }
    out
}

/// Surface triangle `f`'s vertices under the relief and its edges across the relief's bends and
/// rim, each vertex and edge once (`seen`, by its coordinates' bits).
fn under_relief(
    ground: &Ground,
    relief: &Relief,
    pose: &BodyPose,
    f: usize,
    reach: f64,
    seen: &mut HashSet<[u64; 6]>,
    out: &mut Touches,
) {
    let Some(tri) = ground.triangle(f) else {
        return;
    };
    let plane = &ground.faces()[f];
    let to_body = pose.rotation.transpose();
    let v: [Vector3<f64>; 3] = tri.map(|[x, z]| Vector3::new(x, plane.height(x, z), z));
    let b: [Vector3<f64>; 3] = v.map(|g| to_body * (g - pose.cm));
    let bits = |p: &Vector3<f64>| [p.x.to_bits(), p.y.to_bits(), p.z.to_bits()];
    for (g, gb) in v.iter().zip(&b) {
        let [x, y, z] = bits(g);
        if !seen.insert([x, y, z, 0, 0, 0]) {
            continue;
        }
        for face in relief.faces_over([gb.x, gb.z]) {
            let m = relief.faces()[face].normal;
            let gap = (relief.height(face, [gb.x, gb.z]) - gb.y) * m.y;
            if gap < reach {
                let body = gb + m * gap;
                out.touches.push(Touch {
                    on_base: pose.point(&body),
                    body,
                    normal: pose.rotation * m,
                    gap,
                    face: f,
                    feature: Feature::GroundVertex,
                });
            }
        }
    }
    for e in 0..3 {
        let (i, j) = (e, (e + 1) % 3);
        let (lo, hi) = if bits(&v[i]) <= bits(&v[j]) {
            (i, j)
        } else {
            (j, i)
        };
        let [a0, a1, a2] = bits(&v[lo]);
        let [b0, b1, b2] = bits(&v[hi]);
        if !seen.insert([a0, a1, a2, b0, b1, b2]) {
            continue;
        }
        let (ga, gb) = (b[i], b[j]);
        let mut rock = None;
        let lo = [ga.x.min(gb.x), ga.z.min(gb.z)];
        let hi = [ga.x.max(gb.x), ga.z.max(gb.z)];
        for k in relief.edges_in(lo, hi) {
            let [p, q] = relief.edges()[k].map(|i| relief.vertices()[i]);
            let Some((on, g)) = crossing([p, q], [ga, gb]) else {
                continue;
            };
            let mut n = (q - p).cross(&(gb - ga)).normalize();
            if n.y < 0.0 {
                n = -n;
            }
            // A touch only where both edges are convex and the normal lies between each one's
            // faces' (`wedge`): a keel across a ridge, not an edge along the rock's edge it was
            // cast from.
            let Some([ma, mb]) = relief.keel(k) else {
                continue;
            };
            let edge = *rock.get_or_insert_with(|| rock_edge(ground, f, &v[i], &v[j]));
            let held = match edge {
                RockEdge::Ridge(na, nb) => between(&n, &(to_body * na), &(to_body * nb)),
                RockEdge::Other => false,
                RockEdge::Rim => true,
            };
            if !held || !between(&n, &ma, &mb) {
                continue;
            }
            let gap = (on - g).dot(&n);
            if gap < reach {
                out.touches.push(Touch {
                    on_base: pose.point(&on),
                    body: on,
                    normal: pose.rotation * n,
                    gap,
                    face: f,
                    feature: Feature::ReliefCrossing(k),
                });
            }
        }
    }
}

/// Where the segment `p`–`q` crosses the segment `a`–`b` in plan (x′, z′; body axes) within
/// both: the point of each there. `None` where they miss, meet at an end, or run parallel in
/// plan.
fn crossing(
    [p, q]: [Vector3<f64>; 2],
    [a, b]: [Vector3<f64>; 2],
) -> Option<(Vector3<f64>, Vector3<f64>)> {
    let d1 = [q.x - p.x, q.z - p.z];
    let d2 = [b.x - a.x, b.z - a.z];
    let den = d1[0] * d2[1] - d1[1] * d2[0];
    let scale = d1[0].hypot(d1[1]) * d2[0].hypot(d2[1]);
    if den.abs() <= 1e-9 * scale {
        return None;
    }
    let r = [a.x - p.x, a.z - p.z];
    let s = (r[0] * d2[1] - r[1] * d2[0]) / den;
    let t = (r[0] * d1[1] - r[1] * d1[0]) / den;
    // At an end of either edge the crossing is a vertex over a face, which the vertices' own
    // touches hold; taken here too, its normal across the two edges would be no normal of the
    // surfaces there (at a vertex where the relief bends, nearly horizontal) and would brake a
    // cast block that has not moved (with them its yaw after 0.25 s on the teeth was 8 % less).
    let inside = |u: f64| u > 1e-9 && u < 1.0 - 1e-9;
    (inside(s) && inside(t)).then(|| (p + (q - p) * s, a + (b - a) * t))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::relief::cast::cast;
    use nalgebra::Matrix3;

    /// A sawtooth along X (teeth `width` m long, flanks at `angle` rad), level along Z.
    fn sawtooth(width: f64, angle: f64, teeth: usize) -> Ground {
        let h = 0.5 * width * angle.tan();
        let mut tris = Vec::new();
        for k in 0..2 * teeth {
            let x0 = 0.5 * width * (k as f64 - teeth as f64);
            let x1 = x0 + 0.5 * width;
            let (y0, y1) = if k % 2 == 0 { (0.0, h) } else { (h, 0.0) };
            let (a, b) = ([x0, y0, -10.0], [x1, y1, -10.0]);
            let (c, d) = ([x1, y1, 10.0], [x0, y0, 10.0]);
            tris.push([a, b, c]);
            tris.push([a, c, d]);
        }
        Ground::surface(&tris).unwrap()
    }

    fn square(half: f64) -> Vec<[[f64; 2]; 3]> {
        let c = [[-half, -half], [half, -half], [half, half], [-half, half]];
        vec![[c[0], c[1], c[2]], [c[0], c[2], c[3]]]
    }

    #[test]
    fn a_cast_base_touches_its_rock_everywhere_and_nowhere_inside() {
        let ground = sawtooth(1.0, 10f64.to_radians(), 6);
        let pose = BodyPose {
            cm: Vector3::new(0.3, 1.0, 0.2),
            rotation: Matrix3::identity(),
        };
        let relief = cast(&ground, &square(2.0), &pose).unwrap();
        let found = relief_touches(&ground, &relief, &pose, 1e-9, 0.0);
        assert!(found.off_ground.is_empty());
        assert!(found.touches.iter().all(|t| t.gap.abs() < 1e-12));
        // Every vertex of the relief touches.
        for k in 0..relief.vertices().len() {
            assert!(
                found
                    .touches
                    .iter()
                    .any(|t| t.feature == Feature::ReliefVertex(k))
            );
        }
    }

    #[test]
    fn a_cast_base_at_rest_pushes_along_its_faces_normals_not_across_edges_meeting_at_a_vertex() {
        // Cast over a knoll of six triangles whose edges meet the relief's six bends at its
        // top: two edges that meet only there, not sides of one face, have no normal of the
        // surfaces between them.
        let rim: Vec<[f64; 3]> = (0..6)
            .map(|k| {
                let a = k as f64 * std::f64::consts::FRAC_PI_3;
                [3.0 * a.cos(), 0.05 * k as f64, 3.0 * a.sin()]
            })
            .collect();
        let top = [0.0, 0.4, 0.0];
        let tris: Vec<[[f64; 3]; 3]> = (0..6).map(|k| [top, rim[(k + 1) % 6], rim[k]]).collect();
        let ground = Ground::surface(&tris).unwrap();
        let pose = BodyPose {
            cm: Vector3::new(0.0, 1.2, 0.0),
            rotation: Matrix3::identity(),
        };
        let relief = cast(&ground, &square(1.0), &pose).unwrap();
        let found = relief_touches(&ground, &relief, &pose, 1e-9, 0.0);
        assert!(found.touches.len() >= relief.vertices().len());
        for t in &found.touches {
            let of_a_face = ground
                .faces()
                .iter()
                .any(|f| (t.normal - f.normal()).norm() < 1e-12);
            assert!(of_a_face && t.gap.abs() < 1e-12, "{t:?}");
        }
    }

    #[test]
    fn a_cast_base_slid_along_the_rocks_edges_it_was_cast_from_meets_them_along_no_level_normal() {
        // Slid 2 mm along the teeth (along Z), turned by 1e-5 rad, tilted along them by 1e-4 rad
        // and lifted 1 µm: each bend of the relief lies along the edge it was cast from and
        // crosses it at a grazing angle, their slopes apart. A ridge of the rock under a groove
        // of the base, or a keel over a valley, is no contact there; the normal across two
        // edges so nearly parallel is nearly level.
        let ground = sawtooth(1.0, 10f64.to_radians(), 6);
        let rest = BodyPose {
            cm: Vector3::new(0.3, 1.0, 0.2),
            rotation: Matrix3::identity(),
        };
        let relief = cast(&ground, &square(2.0), &rest).unwrap();
        let turn = nalgebra::Rotation3::from_axis_angle(&Vector3::y_axis(), 1e-5)
            * nalgebra::Rotation3::from_axis_angle(&Vector3::x_axis(), 1e-4);
        let pose = BodyPose {
            cm: rest.cm + Vector3::new(0.0, 1e-6, 2e-3),
            rotation: *turn.matrix(),
        };
        let found = relief_touches(&ground, &relief, &pose, 1e-3, 0.0);
        assert!(!found.touches.is_empty());
        for t in &found.touches {
            assert!(t.normal.y > 0.98, "{t:?}");
        }
    }

    #[test]
    fn a_cast_base_moved_along_its_teeth_rides_up_their_flanks() {
        // Moved 0.1 m along +X and raised by 0.1 tan 10°, the base rests on the flanks that
        // rise along +X and stands off those that fall, by 0.2 tan 10° cos 10° at most.
        let angle = 10f64.to_radians();
        let ground = sawtooth(1.0, angle, 6);
        let pose = BodyPose {
            cm: Vector3::new(0.0, 1.0, 0.0),
            rotation: Matrix3::identity(),
        };
        let relief = cast(&ground, &square(2.0), &pose).unwrap();
        let moved = BodyPose {
            cm: pose.cm + Vector3::new(0.1, 0.1 * angle.tan(), 0.0),
            ..pose
        };
        let found = relief_touches(&ground, &relief, &moved, 0.1, 0.0);
        let least = found
            .touches
            .iter()
            .map(|t| t.gap)
            .fold(f64::INFINITY, f64::min);
        assert!(least.abs() < 1e-12, "{least}");
        let most = found.touches.iter().map(|t| t.gap).fold(0.0, f64::max);
        assert!(
            (most - 0.2 * angle.tan() * angle.cos()).abs() < 1e-12,
            "{most}"
        );
        // Those at zero gap push back along −X: the flanks rising along +X.
        for t in found.touches.iter().filter(|t| t.gap.abs() < 1e-12) {
            assert!(t.normal.x < 0.0, "{t:?}");
        }
        // Lowered by a millimetre, it is a millimetre's vertical into the rising flanks.
        let low = BodyPose {
            cm: moved.cm - Vector3::new(0.0, 1e-3, 0.0),
            ..moved
        };
        let found = relief_touches(&ground, &relief, &low, 0.0, 0.0);
        let least = found
            .touches
            .iter()
            .map(|t| t.gap)
            .fold(f64::INFINITY, f64::min);
        assert!((least + 1e-3 * angle.cos()).abs() < 1e-12, "{least}");
    }
}
