//! Where the base lies flush on its rock (`derivations/13-base-contact.md` §9): its whole face
//! on a plane of the rock, or an edge along one. There the touches found at corners and
//! vertices carry the base's normal impulse, but its pressure — and so its friction — is over
//! the area or along the edge, as on a stiff uniform bed; the impulse solve shares it over the
//! quadrature points found here. Where it rests on more than three points of one plane without
//! lying flush, equal springs at the points share it (§9, "Points on a plane").

use super::state::BodyState;
use crate::geometry::{Feature, Ground, Relief, Touch};
use crate::mechanics::impulses::{Patch, PatchPoint, tangents};
use crate::model::{Base, triangle_quadrature};
use nalgebra::Vector3;

/// A base lies flush on its rock where its normal is within this angle (rad) of the rock's.
const FLUSH_ANGLE: f64 = 1e-6;

/// … and its gap there within this fraction of its size.
const FLUSH_GAP: f64 = 1e-6;

/// A touch among others on one plane starts from the last step's friction at the same features
/// within this fraction of the base's size.
const WARM_REACH: f64 = 0.05;

/// Each triangle of the base cut into this many squared for its quadrature (three points each).
const AREA_SPLIT: usize = 2;

/// The base's quadrature points in body axes about the CM (m), with their weights.
#[derive(Debug, Clone, Default)]
pub(super) struct Quadrature {
    /// Over the area (weights in m²).
    pub area: Vec<(Vector3<f64>, f64)>,
    /// The area's points by the direction of the faces they are on: each unit normal into the
    /// block (body axes) and the points on faces along it — a flat base's one face, y′; a cast
    /// base's relief's, each set of parallel faces (the cosine between their normals within
    /// 1e-12 of one).
    pub faces: Vec<(Vector3<f64>, Vec<usize>)>,
    /// Along each edge k, from corner k to k + 1 (weights in m).
    pub edges: Vec<Vec<(Vector3<f64>, f64)>>,
}

impl Quadrature {
    /// The quadrature of `base` (`Base::quadrature`, `Base::edge_quadrature`).
    pub fn of(base: &Base) -> Quadrature {
        let body = |pts: Vec<([f64; 2], f64)>| -> Vec<(Vector3<f64>, f64)> {
            pts.into_iter()
                .map(|([x, z], w)| (Vector3::new(x, -base.depth(), z), w))
                .collect()
        };
        let area = body(base.quadrature(AREA_SPLIT));
        Quadrature {
            faces: vec![(Vector3::y(), (0..area.len()).collect())],
            area,
            edges: (0..base.outline().len())
                .map(|k| body(base.edge_quadrature(k)))
                .collect(),
        }
    }

    /// The quadrature of a cast base's relief: each face cut into triangles from its first
    /// corner, each triangle as a flat base's ear (`triangle_quadrature`, the weights its area
    /// in its own plane). No edges: a relief's bends are not flush on a plane.
    pub fn of_relief(relief: &Relief) -> Quadrature {
        let v = relief.vertices();
        let mut q = Quadrature::default();
        for face in relief.faces() {
            let group = match q
                .faces
                .iter()
                .position(|(m, _)| m.dot(&face.normal) >= 1.0 - 1e-12)
            {
                Some(g) => g,
                None => {
                    q.faces.push((face.normal, Vec::new()));
                    q.faces.len() - 1
                }
            };
            let c = &face.corners;
            for k in 1..c.len().saturating_sub(1) {
                let t = [v[c[0]], v[c[k]], v[c[k + 1]]];
                let area = 0.5 * (t[1] - t[0]).cross(&(t[2] - t[0])).norm();
                for point in triangle_quadrature(t, area, AREA_SPLIT) {
                    q.faces[group].1.push(q.area.len());
                    q.area.push(point);
                }
            }
        }
        q
    }
}

/// Which quadrature point: of the area, or node j of edge k.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) enum Spot {
    /// Point k of the area.
    Area(usize),
    /// Node j of edge k.
    Edge(usize, usize),
    /// A touch among others on one plane: its features, its face, and where it is on the
    /// base (body axes, m), by which the next step finds it again.
    Touch(Feature, usize, Vector3<f64>),
}

/// What the flush parts are sought on: the ground, the base's quadrature and size (m), and μ
/// by face.
pub(super) struct Bed<'a> {
    pub ground: &'a Ground,
    pub quadrature: &'a Quadrature,
    pub size: f64,
    pub mu: &'a dyn Fn(usize) -> f64,
}

/// A flush part of the base: the impulse solve's patch and which points it holds.
#[derive(Debug, Clone)]
pub(super) struct Flush {
    pub patch: Patch,
    pub spots: Vec<Spot>,
    /// Touches on the patch inside its members' hull, left out of the step's rows.
    pub dropped: Vec<usize>,
}

/// The flush parts of the base at state `s` among its `touches`, each point's impulse started
/// from `warm` (the last step's, by point): the base's face on a plane of the rock (at least
/// three of its area's points over rock in its plane), and each edge whose two corners touch
/// one plane of the rock with no gap (at least two of its nodes over that rock), with the
/// crossings along it; then the closed touches left, by normal, where three or more distinct
/// points share one (each of weight one, or its length along a ridge: `along_one_line`). No
/// touch is in two of them.
pub(super) fn flush(
    ctx: &Bed<'_>,
    s: &BodyState,
    touches: &[Touch],
    warm: &[(Spot, Vector3<f64>)],
) -> Vec<Flush> {
    let (cos, tol) = (FLUSH_ANGLE.cos(), FLUSH_GAP * ctx.size);
    let close = |t: &Touch| t.gap.abs() <= tol;
    let mut used = vec![false; touches.len()];
    let mut out = Vec::new();
    // The points of `pts` over rock flush with a plane of normal `n`.
    let on_rock = |n: &Vector3<f64>,
                   pts: &mut dyn Iterator<Item = (Spot, &(Vector3<f64>, f64))>| {
        let faces = ctx.ground.faces();
        let mut spots = Vec::new();
        let mut points = Vec::new();
        for (spot, (at, weight)) in pts {
            let q = s.pose.point(at);
            let Some((f, _)) = ctx.ground.top(q.x, q.z) else {
                continue;
            };
            let face = &faces[f];
            if face.normal().dot(n) >= cos && face.signed_distance(&q).abs() <= tol {
                let guess = warm
                    .iter()
                    .find(|(w, _)| *w == spot)
                    .map_or_else(Vector3::zeros, |(_, p)| *p);
                spots.push(spot);
                points.push(PatchPoint {
                    arm: q - s.pose.cm,
                    weight: *weight,
                    mu: (ctx.mu)(f),
                    guess,
                });
            }
        }
        (spots, points)
    };
    // The faces on planes: for each direction m of the base's faces (the flat base's one, its
    // normal; a cast base's relief's, each set of parallel faces), the touches closed flush
    // along m, and the area's points on those faces over rock in their plane.
    for (m_body, on_faces) in &ctx.quadrature.faces {
        let m = s.pose.rotation * m_body;
        let members: Vec<usize> = (0..touches.len())
            .filter(|&i| !used[i] && touches[i].normal.dot(&m) >= cos && close(&touches[i]))
            .collect();
        let Some(&first) = members.first() else {
            continue;
        };
        let n = touches[first].normal;
        let mut pts = on_faces
            .iter()
            .map(|&k| (Spot::Area(k), &ctx.quadrature.area[k]));
        let (spots, points) = on_rock(&n, &mut pts);
        if points.len() >= 3 {
            for &i in &members {
                used[i] = true;
            }
            // The members' normal impulses matter to the patch only by their resultant, whose
            // line lies in their points' convex hull; with one normal and gaps affine over the
            // plane, an inside member's constraint is implied by the corners'. Only the hull's
            // corners are kept (the others are left out of the step's rows).
            let kept: Vec<usize> =
                hull_across(&n, members.iter().map(|&i| touches[i].on_base - s.pose.cm))
                    .into_iter()
                    .map(|k| members[k])
                    .collect();
            let dropped: Vec<usize> = members
                .iter()
                .copied()
                .filter(|i| !kept.contains(i))
                .collect();
            let members = kept;
            out.push(Flush {
                dropped,
                patch: Patch {
                    members,
                    axes: tangents(&n),
                    points,
                },
                spots,
            });
        }
    }
    // Edges along a plane.
    let corners = ctx.quadrature.edges.len();
    for k in 0..corners {
        let ends = |c: usize| -> Vec<usize> {
            (0..touches.len())
                .filter(|&i| {
                    !used[i] && touches[i].feature == Feature::Corner(c) && close(&touches[i])
                })
                .collect()
        };
        let (from, to) = (ends(k), ends((k + 1) % corners));
        let pair = from.iter().find_map(|&a| {
            to.iter()
                .find(|&&b| touches[a].normal.dot(&touches[b].normal) >= cos)
                .map(|&b| (a, b))
        });
        let Some((a, b)) = pair else {
            continue;
        };
        let n = touches[a].normal;
        let mut pts = ctx.quadrature.edges[k]
            .iter()
            .enumerate()
            .map(|(j, p)| (Spot::Edge(k, j), p));
        let (spots, points) = on_rock(&n, &mut pts);
        if points.len() >= 2 {
            // The edge's corners and the ground's edges across it on that plane: one line.
            let members: Vec<usize> = (0..touches.len())
                .filter(|&i| {
                    i == a
                        || i == b
                        || (!used[i]
                            && touches[i].feature == Feature::Crossing(k)
                            && touches[i].normal.dot(&n) >= cos
                            && close(&touches[i]))
                })
                .collect();
            for &i in &members {
                used[i] = true;
            }
            out.push(Flush {
                patch: Patch {
                    members,
                    axes: tangents(&n),
                    points,
                },
                spots,
                dropped: Vec::new(),
            });
        }
    }
    // Points on a plane: the closed touches left that share one normal, three or more apart
    // (a flat base on the ground's vertices, a cast base's bends across the rock's crests).
    // The rigid body leaves their shares open beyond three; equal springs at them, a uniform
    // bed of points, fix them as the faces' bed does, and their friction acts with those shares.
    let mut rest: Vec<usize> = (0..touches.len())
        .filter(|&i| !used[i] && close(&touches[i]))
        .collect();
    while let Some(&first) = rest.first() {
        let n = touches[first].normal;
        let (members, others): (Vec<usize>, Vec<usize>) = rest
            .iter()
            .partition(|&&i| touches[i].normal.dot(&n) >= cos);
        rest = others;
        let (mut spots, mut points) = (Vec::new(), Vec::<PatchPoint>::new());
        for &i in &members {
            let t = &touches[i];
            let arm = t.on_base - s.pose.cm;
            if points.iter().any(|p| (p.arm - arm).norm() <= tol) {
                continue;
            }
            // The last step's friction at the same features nearest to it (a crossing slides
            // along its edges as the block moves).
            let guess = warm
                .iter()
                .filter_map(|(w, p)| match w {
                    Spot::Touch(feature, face, at) if *feature == t.feature && *face == t.face => {
                        Some(((at - t.body).norm(), *p))
                    }
                    _ => None,
                })
                .filter(|(d, _)| *d <= WARM_REACH * ctx.size)
                .min_by(|a, b| a.0.total_cmp(&b.0))
                .map_or_else(Vector3::zeros, |(_, p)| p);
            spots.push(Spot::Touch(t.feature, t.face, t.body));
            points.push(PatchPoint {
                arm,
                weight: 1.0,
                mu: (ctx.mu)(t.face),
                guess,
            });
        }
        if points.len() >= 3 {
            // A ridge of the rock along the base touches it all along, not at its points: the
            // rock is at the base midway between them too.
            let touching = |arm: &Vector3<f64>| {
                let q = s.pose.cm + arm;
                ctx.ground
                    .top(q.x, q.z)
                    .is_some_and(|(f, _)| ctx.ground.faces()[f].signed_distance(&q).abs() <= tol)
            };
            along_one_line(&mut points, tol, &touching);
            for &i in &members {
                used[i] = true;
            }
            out.push(Flush {
                spots,
                dropped: Vec::new(),
                patch: Patch {
                    members,
                    axes: tangents(&n),
                    points,
                },
            });
        }
    }
    out
}

/// The indices of the corners of the convex hull of `points` seen along `n` (their coordinates
/// on the plane across it), as [`hull_corners`] gives them.
pub(super) fn hull_across(
    n: &Vector3<f64>,
    points: impl Iterator<Item = Vector3<f64>>,
) -> Vec<usize> {
    let axes = tangents(n);
    let plan: Vec<[f64; 2]> = points.map(|r| [r.dot(&axes.0), r.dot(&axes.1)]).collect();
    hull_corners(&plan)
}

/// The indices of the corners of the convex hull of `p` (Andrew's monotone chain; points on a
/// hull edge or repeated are left out).
pub(super) fn hull_corners(p: &[[f64; 2]]) -> Vec<usize> {
    if p.len() <= 2 {
        return (0..p.len()).collect();
    }
    let mut idx: Vec<usize> = (0..p.len()).collect();
    idx.sort_by(|&a, &b| {
        p[a][0]
            .total_cmp(&p[b][0])
            .then(p[a][1].total_cmp(&p[b][1]))
    });
    let cross = |o: usize, a: usize, b: usize| {
        (p[a][0] - p[o][0]) * (p[b][1] - p[o][1]) - (p[a][1] - p[o][1]) * (p[b][0] - p[o][0])
    };
    let mut hull: Vec<usize> = Vec::new();
    for pass in 0..2 {
        let start = hull.len();
        let order: Vec<usize> = if pass == 0 {
            idx.clone()
        } else {
            idx.iter().rev().copied().collect()
        };
        for i in order {
            while hull.len() >= start + 2
                && cross(hull[hull.len() - 2], hull[hull.len() - 1], i) <= 0.0
            {
                hull.pop();
            }
            hull.push(i);
        }
        hull.pop();
    }
    if hull.is_empty() {
        hull.push(idx[0]);
    }
    hull
}

/// Points of a patch that lie on one line (within `tol` of the line through the two farthest
/// apart) where the rock `touching` the base midway between each two of them too — a ridge of
/// the rock along the base — stand for its length, not for one point each: each the trapezoid
/// rule's share of the line between its neighbours, as a uniform bed along the line presses.
/// Points apart (crossings of the base's edges with the rock's crests, on one line or not) keep
/// their weights.
fn along_one_line(points: &mut [PatchPoint], tol: f64, touching: &dyn Fn(&Vector3<f64>) -> bool) {
    let far = |from: &Vector3<f64>| {
        points
            .iter()
            .map(|p| p.arm)
            .max_by(|a, b| (a - from).norm().total_cmp(&(b - from).norm()))
    };
    if points.len() < 3 {
        return;
    }
    let Some(p1) = far(&points[0].arm) else {
        return;
    };
    let Some(p2) = far(&p1) else { return };
    let length = (p2 - p1).norm();
    if length <= tol {
        return;
    }
    let d = (p2 - p1) / length;
    let off = |q: &Vector3<f64>| (q - p1 - d * (q - p1).dot(&d)).norm();
    if points.iter().any(|p| off(&p.arm) > tol) {
        return;
    }
    let mut order: Vec<(f64, usize)> = points
        .iter()
        .enumerate()
        .map(|(i, p)| ((p.arm - p1).dot(&d), i))
        .collect();
    order.sort_by(|a, b| a.0.total_cmp(&b.0));
    let midway = |k: usize| (points[order[k].1].arm + points[order[k + 1].1].arm) / 2.0;
    if !(0..order.len() - 1).all(|k| touching(&midway(k))) {
        return;
    }
    for (k, &(s, i)) in order.iter().enumerate() {
        let before = if k == 0 { s } else { order[k - 1].0 };
        let after = order.get(k + 1).map_or(s, |o| o.0);
        points[i].weight = 0.5 * (after - before);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::{BodyPose, Footprint, Plane, touches};
    use nalgebra::{Matrix3, Rotation3};

    #[test]
    fn a_hull_keeps_its_corners_only() {
        // A 3 × 2 rectangle's corners among points inside it, on its edges and repeated: the
        // four corners, each once; then a triangle, two points and one.
        let mut p = vec![[0.0, 0.0], [3.0, 0.0], [3.0, 2.0], [0.0, 2.0]];
        let mut s = 7u64;
        for _ in 0..200 {
            s = s
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            let (u, v) = (
                (s >> 11) as f64 / 2f64.powi(53),
                (s >> 20) as f64 / 2f64.powi(44),
            );
            p.push([3.0 * u, 2.0 * v]);
        }
        p.extend([[1.5, 0.0], [3.0, 1.0], [0.0, 0.5], [3.0, 2.0], [0.0, 0.0]]);
        let mut hull = hull_corners(&p);
        hull.sort_unstable();
        let corners: Vec<[f64; 2]> = hull.iter().map(|&k| p[k]).collect();
        assert_eq!(corners.len(), 4, "{corners:?}");
        for c in [[0.0, 0.0], [3.0, 0.0], [3.0, 2.0], [0.0, 2.0]] {
            assert!(corners.contains(&c), "{c:?} in {corners:?}");
        }
        let mut t = hull_corners(&[[0.0, 0.0], [1.0, 0.2], [2.0, 0.0], [1.0, 1.0]]);
        t.sort_unstable();
        assert_eq!(t, [0, 2, 3]);
        assert_eq!(hull_corners(&[[0.0, 0.0], [1.0, 0.0]]).len(), 2);
        assert_eq!(hull_corners(&[[1.0, 1.0]]), [0]);
        assert!(hull_corners(&[]).is_empty());
        // Points on one line: its two ends.
        let mut line = hull_corners(&[[0.0, 0.0], [1.0, 1.0], [2.0, 2.0], [3.0, 3.0]]);
        line.sort_unstable();
        assert_eq!(line, [0, 3]);
    }

    /// A 4 m square base, its CM 1 m above it, at `pose` on level rock: the flush parts.
    fn flush_on_level(pose: BodyPose) -> Vec<Flush> {
        let base = Base::rectangle([-2.0, 2.0], [-2.0, 2.0], 1.0).unwrap();
        let ground = Ground::planes(vec![Plane::through(Vector3::y(), Vector3::zeros())]);
        let quadrature = Quadrature::of(&base);
        let footprint = Footprint {
            outline: base.outline(),
            depth: base.depth(),
        };
        let found = touches(&ground, footprint, &pose, 1e-3, 0.0);
        let mu = |_: usize| 0.5;
        let bed = Bed {
            ground: &ground,
            quadrature: &quadrature,
            size: base.size(),
            mu: &mu,
        };
        flush(&bed, &BodyState::at_rest(pose), &found.touches, &[])
    }

    #[test]
    fn a_base_lying_on_level_rock_presses_over_its_whole_area() {
        let parts = flush_on_level(BodyPose {
            cm: Vector3::new(3.0, 1.0, -1.0),
            rotation: Matrix3::identity(),
        });
        assert_eq!(parts.len(), 1);
        let patch = &parts[0].patch;
        assert_eq!(patch.members.len(), 4);
        assert_eq!(patch.points.len(), 24);
        let area: f64 = patch.points.iter().map(|p| p.weight).sum();
        assert!((area - 16.0).abs() < 1e-12);
        assert!(patch.points.iter().all(|p| p.mu == 0.5));
    }

    #[test]
    fn a_base_tipped_onto_an_edge_presses_along_that_edge_only() {
        // Tipped 5° about its edge at x′ = 2 (corners 1 and 2), that edge on the rock.
        let rotation = *Rotation3::from_axis_angle(&Vector3::z_axis(), -5f64.to_radians()).matrix();
        let pivot = Vector3::new(2.0, -1.0, 0.0);
        let pose = BodyPose {
            cm: -(rotation * pivot) + Vector3::new(2.0, 0.0, 0.0),
            rotation,
        };
        // The other edge is up in the air: 4 sin 5° above the rock.
        let heel = pose.point(&Vector3::new(-2.0, -1.0, 0.0));
        assert!(
            (heel.y - 4.0 * 5f64.to_radians().sin()).abs() < 1e-12,
            "{heel}"
        );
        let parts = flush_on_level(pose);
        assert_eq!(parts.len(), 1, "{parts:?}");
        assert_eq!(parts[0].patch.members.len(), 2);
        assert!(parts[0].spots.iter().all(|s| matches!(s, Spot::Edge(1, _))));
        let length: f64 = parts[0].patch.points.iter().map(|p| p.weight).sum();
        assert!((length - 4.0).abs() < 1e-12, "{length}");
        // Tipped more than the tolerance: nothing lies flush over the area.
        assert!(parts.iter().all(|p| p.patch.points.len() == 5));
    }

    /// Unit points at `zs` along z (and one more at `extra`, if given).
    fn points_at(zs: &[f64], extra: Option<Vector3<f64>>) -> Vec<PatchPoint> {
        zs.iter()
            .map(|&z| Vector3::new(-1.0, -0.1, z))
            .chain(extra)
            .map(|arm| PatchPoint {
                arm,
                weight: 1.0,
                mu: 0.5,
                guess: Vector3::zeros(),
            })
            .collect()
    }

    #[test]
    fn a_ridge_along_the_base_found_at_its_vertices_and_rim_weighs_by_length() {
        // A crest under the base from z = −5 to 5, its vertices at −4, −2, …, 4 (out of order):
        // each the trapezoid share of the line between its neighbours.
        let mut pts = points_at(&[0.0, -5.0, 5.0, -4.0, 4.0, -2.0, 2.0], None);
        along_one_line(&mut pts, 1e-9, &|_| true);
        let w: Vec<f64> = pts.iter().map(|p| p.weight).collect();
        let expect = [2.0, 0.5, 0.5, 1.5, 1.5, 2.0, 2.0];
        assert!(
            w.iter().zip(expect).all(|(a, b)| (a - b).abs() < 1e-12),
            "{w:?}"
        );
        // The same points where the rock is not at the base between them (crossings of the
        // base's edges with the rock's crests, on one line by chance): a point each.
        let mut apart = points_at(&[0.0, -5.0, 5.0, -4.0], None);
        along_one_line(&mut apart, 1e-9, &|arm| arm.z.abs() > 4.4);
        assert!(apart.iter().all(|p| p.weight == 1.0));
        // Not on one line: a point each.
        let mut off = points_at(&[0.0, -5.0, 5.0], Some(Vector3::new(0.0, -0.1, 1.0)));
        along_one_line(&mut off, 1e-9, &|_| true);
        assert!(off.iter().all(|p| p.weight == 1.0));
    }
}
