//! The relief of a base cast onto its rock: the ground under the footprint, seen along the
//! block's own up where it rests (`derivations/13-base-contact.md` §10).
//!
//! The footprint's triangles (x′, z′) are clipped against each face of the ground in the
//! block's axes. On a triangulated surface a face covers its triangle's plan; on a ground of
//! planes (the highest of them) plane f covers the part of the plan where it stands above every
//! other, cut out of the triangle by the half-planes y′_f ≥ y′_g. Each piece is a convex
//! polygon lifted onto its face's plane.

use super::{Relief, ReliefFace};
use crate::geometry::{BodyPose, Ground, signed_area as area};
use nalgebra::Vector3;
use std::collections::HashMap;

/// Why a base cannot be cast onto the ground where it rests.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum CastError {
    /// Part of the footprint is over no ground.
    #[error("only {percent:.4} % of the footprint is over the surveyed ground where it rests")]
    OffGround {
        /// The part covered (%).
        percent: f64,
    },
    /// A face of the ground is vertical or overhangs seen from the block.
    #[error("face {0} of the ground is vertical or overhangs seen from the block as it rests")]
    Steep(usize),
}

/// y′ = h[0] + h[1] x′ + h[2] z′: a face's plane over the block's plan.
type Height = [f64; 3];

/// c[0] + c[1] x′ + c[2] z′ ≥ 0: a half-plane.
type Half = [f64; 3];

/// The relief of the ground under the footprint `triangles` (x′, z′, counter-clockwise) of a
/// block at `pose`.
pub fn cast(
    ground: &Ground,
    triangles: &[[[f64; 2]; 3]],
    pose: &BodyPose,
) -> Result<Relief, CastError> {
    let to_body = pose.rotation.transpose();
    // Face f's plane in body axes: m·p = e with m = Rᵀ n, e = e_world − n·cm.
    let height_of = |f: usize| -> Result<Height, CastError> {
        let plane = &ground.faces()[f];
        let m = to_body * plane.normal();
        if m.y <= 1e-9 {
            return Err(CastError::Steep(f));
        }
        let e = plane.offset() - plane.normal().dot(&pose.cm);
        Ok([e / m.y, -m.x / m.y, -m.z / m.y])
    };
    let corners = triangles.iter().flatten();
    let scale = corners
        .clone()
        .map(|p| p[0].abs().max(p[1].abs()))
        .fold(1.0, f64::max);
    let mut pieces: Vec<(Vec<[f64; 2]>, Height)> = Vec::new();
    if ground.is_surface() {
        let world: Vec<Vector3<f64>> = corners
            .map(|p| pose.point(&Vector3::new(p[0], 0.0, p[1])))
            .collect();
        let pad = scale;
        let [x0, x1, z0, z1] = crate::geometry::plan_box(world.iter().map(|w| [w.x, w.z]));
        for f in ground.faces_in((x0 - pad, x1 + pad, z0 - pad, z1 + pad)) {
            let Some(tri) = ground.triangle(f) else {
                continue;
            };
            let h = height_of(f)?;
            let plane = &ground.faces()[f];
            let mut plan: Vec<[f64; 2]> = tri
                .iter()
                .map(|&[x, z]| {
                    let b = to_body * (Vector3::new(x, plane.height(x, z), z) - pose.cm);
                    [b.x, b.z]
                })
                .collect();
            if area(&plan) < 0.0 {
                plan.reverse();
            }
            for t in triangles {
                let piece = edges_of(t).into_iter().fold(plan.clone(), clip);
                pieces.push((piece, h));
            }
        }
    } else {
        let heights = (0..ground.faces().len())
            .map(height_of)
            .collect::<Result<Vec<Height>, _>>()?;
        for t in triangles {
            for (f, h) in heights.iter().enumerate() {
                let above = heights
                    .iter()
                    .enumerate()
                    .filter(|&(g, _)| g != f)
                    .map(|(_, g)| [h[0] - g[0], h[1] - g[1], h[2] - g[2]]);
                let piece = above.fold(t.to_vec(), clip);
                pieces.push((piece, *h));
            }
        }
    }
    let tiny = 1e-12 * scale * scale;
    pieces.retain(|(p, _)| area(p) > tiny);
    let covered: f64 = pieces.iter().map(|(p, _)| area(p)).sum();
    let whole: f64 = triangles.iter().map(|t| area(t)).sum();
    if ground.is_surface() && covered < whole * (1.0 - 1e-9) {
        return Err(CastError::OffGround {
            percent: 100.0 * covered / whole,
        });
    }
    Ok(lift(&pieces, 1e-9 * scale))
}

/// The pieces lifted onto their planes, their corners shared where they coincide within `q`.
fn lift(pieces: &[(Vec<[f64; 2]>, Height)], q: f64) -> Relief {
    let mut vertices: Vec<Vector3<f64>> = Vec::new();
    let mut index: HashMap<[i64; 3], usize> = HashMap::new();
    let mut faces = Vec::with_capacity(pieces.len());
    for (plan, h) in pieces {
        let mut corners: Vec<usize> = Vec::with_capacity(plan.len());
        for &[x, z] in plan {
            let v = Vector3::new(x, h[0] + h[1] * x + h[2] * z, z);
            let key = [v.x, v.y, v.z].map(|c| (c / q).round() as i64);
            let i = *index.entry(key).or_insert_with(|| {
                vertices.push(v);
                vertices.len() - 1
            });
            if corners.last() != Some(&i) && corners.first() != Some(&i) {
                corners.push(i);
            }
        }
        if corners.len() >= 3 {
            let normal = Vector3::new(-h[1], 1.0, -h[2]).normalize();
            faces.push(ReliefFace { corners, normal });
        }
    }
    Relief::new(vertices, faces)
}

/// The three half-planes inside the counter-clockwise triangle `t`.
fn edges_of(t: &[[f64; 2]; 3]) -> [Half; 3] {
    [0, 1, 2].map(|k| {
        let (a, b) = (t[k], t[(k + 1) % 3]);
        let (dx, dz) = (b[0] - a[0], b[1] - a[1]);
        // (b − a) × (p − a) ≥ 0.
        [dz * a[0] - dx * a[1], -dz, dx]
    })
}

/// The part of the convex polygon `p` in the half-plane `c` (Sutherland–Hodgman).
fn clip(p: Vec<[f64; 2]>, c: Half) -> Vec<[f64; 2]> {
    let value = |q: [f64; 2]| c[0] + c[1] * q[0] + c[2] * q[1];
    let n = p.len();
    let mut out = Vec::with_capacity(n + 1);
    for k in 0..n {
        let (a, b) = (p[k], p[(k + 1) % n]);
        let (va, vb) = (value(a), value(b));
        if va >= 0.0 {
            out.push(a);
        }
        if (va >= 0.0) != (vb >= 0.0) {
            let s = va / (va - vb);
            out.push([a[0] + s * (b[0] - a[0]), a[1] + s * (b[1] - a[1])]);
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::Plane;
    use nalgebra::Matrix3;

    fn square(half: f64) -> Vec<[[f64; 2]; 3]> {
        let c = [[-half, -half], [half, -half], [half, half], [-half, half]];
        vec![[c[0], c[1], c[2]], [c[0], c[2], c[3]]]
    }

    fn at(cm: [f64; 3]) -> BodyPose {
        BodyPose {
            cm: Vector3::from(cm),
            rotation: Matrix3::identity(),
        }
    }

    #[test]
    fn a_base_cast_on_one_plane_is_its_flat_footprint_on_it() {
        let ground = Ground::planes(vec![Plane::through(Vector3::y(), Vector3::zeros())]);
        let relief = cast(&ground, &square(2.0), &at([0.0, 1.5, 0.0])).unwrap();
        // Two faces in one plane: no bend between them, four corners, the rim's four edges.
        assert_eq!(relief.faces().len(), 2);
        assert_eq!(relief.vertices().len(), 4);
        assert_eq!(relief.edges().len(), 4);
        assert!(relief.vertices().iter().all(|v| (v.y + 1.5).abs() < 1e-15));
    }

    #[test]
    fn a_base_cast_on_a_valley_of_two_planes_bends_where_they_meet() {
        // Two planes rising 10° away from X = 0 on either side: the valley's floor at X = 0.
        let t = 10f64.to_radians();
        let ground = Ground::planes(vec![
            Plane::from_dip(t, 0.0, Vector3::zeros()),
            Plane::from_dip(t, std::f64::consts::PI, Vector3::zeros()),
        ]);
        let relief = cast(&ground, &square(2.0), &at([0.0, 1.0, 0.0])).unwrap();
        // Every vertex on the ground: y′ = |x′| tan 10° − 1.
        for v in relief.vertices() {
            assert!((v.y - (v.x.abs() * t.tan() - 1.0)).abs() < 1e-12, "{v}");
        }
        // The bend along x′ = 0 from z′ = −2 to 2 is made of edges (cut where the footprint's
        // diagonal crosses it).
        let bend: f64 = relief
            .edges()
            .iter()
            .map(|&[a, b]| (relief.vertices()[a], relief.vertices()[b]))
            .filter(|(p, q)| p.x.abs() < 1e-12 && q.x.abs() < 1e-12)
            .map(|(p, q)| (p - q).norm())
            .sum();
        assert!((bend - 4.0).abs() < 1e-12, "{bend}");
        let plan: f64 = relief
            .faces()
            .iter()
            .map(|f| {
                let p: Vec<[f64; 2]> = f
                    .corners
                    .iter()
                    .map(|&i| [relief.vertices()[i].x, relief.vertices()[i].z])
                    .collect();
                area(&p)
            })
            .sum();
        assert!((plan - 16.0).abs() < 1e-12);
    }

    #[test]
    fn a_base_cast_on_a_surface_is_its_triangles_under_the_footprint() {
        // A pyramid 0.2 m high over a 4 m square, the base 2 m square over its top.
        let ground = crate::geometry::fixtures::pyramid(0.2);
        let relief = cast(&ground, &square(1.0), &at([0.0, 1.2, 0.0])).unwrap();
        for v in relief.vertices() {
            let top = ground.top(v.x, v.z).unwrap().1;
            assert!((v.y + 1.2 - top).abs() < 1e-12, "{v}");
        }
        // The peak is a vertex, and the four ridges from it are bends.
        assert!(
            relief
                .vertices()
                .iter()
                .any(|v| v.x.abs() + v.z.abs() < 1e-12)
        );
        assert_eq!(relief.edges().len(), 4 + 4);
        let err = cast(&ground, &square(3.0), &at([0.0, 1.2, 0.0])).unwrap_err();
        assert!(
            matches!(err, CastError::OffGround { percent } if (percent - 16.0 / 36.0 * 100.0).abs() < 1e-6)
        );
    }
}
