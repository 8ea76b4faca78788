//! Where a flat base meets the ground (`derivations/13-base-contact.md` §2).
//!
//! A flat polygon over a piecewise-planar ground touches it first at one of three kinds of
//! point, and at no other: a corner of the base on a face of the ground; a vertex of the ground
//! under the base (a bump under the middle); a ground edge crossing an edge of the base (a ridge
//! under the base's side). On a ground of planes (the highest of them, a convex valley) the
//! height of the ground above a plane is convex, so its largest over a polygon is at a corner:
//! the corners against every plane are the whole story. On a triangulated surface the other two
//! kinds are added from the triangles under the footprint, found in the ground's R*-tree, so a
//! surface of any size costs the triangles under the base, not the surface.
//!
//! Each [`Touch`] is a point pair, its normal (from the ground into the block) and its gap
//! along the normal (negative inside); the base's points are given in the block's own axes as
//! well, so the contact's arm follows the block.

use super::ground::{Ground, segment_distance_2};
use super::wedge::{RockEdge, between, rock_edge};
use nalgebra::{Matrix3, Vector3};

/// A rigid body's pose: where its centre of mass is and how it is turned (columns: the body's
/// x′, y′, z′ axes in world coordinates).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BodyPose {
    /// The centre of mass (m).
    pub cm: Vector3<f64>,
    /// Body to world.
    pub rotation: Matrix3<f64>,
}

impl BodyPose {
    /// Its axes x′, y′, z′ in world axes, as the three-point frame's (the loads are placed in
    /// them).
    pub fn frame(&self) -> super::LocalFrame {
        let r = self.rotation;
        super::LocalFrame::from_axes(r.column(0).into_owned(), r.column(2).into_owned())
    }

    /// The world position of the body point `p` (body axes about the CM).
    pub fn point(&self, p: &Vector3<f64>) -> Vector3<f64> {
        self.cm + self.rotation * p
    }

    /// The body's up, y′, in world coordinates.
    pub fn up(&self) -> Vector3<f64> {
        self.rotation.column(1).into_owned()
    }
}

/// A flat base: its outline (x′, z′ about the CM) at depth ȳ below the CM.
#[derive(Debug, Clone, Copy)]
pub struct Footprint<'a> {
    /// The corners, in order.
    pub outline: &'a [[f64; 2]],
    /// ȳ (m).
    pub depth: f64,
}

impl Footprint<'_> {
    /// Corner `k` in body axes.
    pub fn corner(&self, k: usize) -> Vector3<f64> {
        let [x, z] = self.outline[k];
        Vector3::new(x, -self.depth, z)
    }
}

/// Which feature of base and ground a touch is between.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Feature {
    /// Corner `k` of the base on a face.
    Corner(usize),
    /// A vertex of the ground under the base.
    GroundVertex,
    /// A ground edge across edge `k` of the base (from corner k to k + 1).
    Crossing(usize),
    /// Vertex `k` of a cast base's relief on a face.
    ReliefVertex(usize),
    /// A ground edge across edge `k` of a cast base's relief.
    ReliefCrossing(usize),
}

/// One place where base and ground touch or nearly do.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Touch {
    /// The point of the base (world, m).
    pub on_base: Vector3<f64>,
    /// The same point in body axes about the CM (m).
    pub body: Vector3<f64>,
    /// Unit normal from the ground into the block.
    pub normal: Vector3<f64>,
    /// The gap along the normal (m; negative inside the ground).
    pub gap: f64,
    /// The face of the ground it is on (for an edge or a vertex, one of the faces that meet
    /// there).
    pub face: usize,
    /// Which features touch.
    pub feature: Feature,
}

/// What the base finds under it at one pose.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Touches {
    /// Every touch whose gap is under the reach asked for.
    pub touches: Vec<Touch>,
    /// The corners of the base over no ground (off a surveyed surface).
    pub off_ground: Vec<usize>,
}

/// The touches of `base` at `pose` on `ground` whose gap is below `reach` (m). `drift` (m, in
/// world axes) is where each corner may go within the step, so that a corner about to cross
/// onto another triangle of a surface meets that triangle's plane too.
pub fn touches(
    ground: &Ground,
    base: Footprint<'_>,
    pose: &BodyPose,
    reach: f64,
    drift: f64,
) -> Touches {
    let mut out = Touches::default();
    let n = base.outline.len();
    let corners: Vec<Vector3<f64>> = (0..n).map(|k| pose.point(&base.corner(k))).collect();
    for (k, q) in corners.iter().enumerate() {
        let Some(faces) = holding_faces(ground, q, drift) else {
            out.off_ground.push(k);
            continue;
        };
        for f in faces {
            let plane = &ground.faces()[f];
            let gap = plane.signed_distance(q);
            if gap < reach {
                out.touches.push(Touch {
                    on_base: *q,
                    body: base.corner(k),
                    normal: plane.normal(),
                    gap,
                    face: f,
                    feature: Feature::Corner(k),
                });
            }
        }
    }
    if ground.is_surface() {
        surface_touches(ground, base, pose, &corners, reach, &mut out);
    }
    out
}

/// The faces of `ground` that may hold a point of the base at `q` within a step that moves it
/// up to `drift` (m): every plane of a ground of planes; on a surface the triangles within
/// `drift` in plan, each only where its plane is not above the ground under `q` (past a ridge
/// a neighbour's plane stands above the rock and does not hold the point; at a valley it is
/// below and does). `None` over no ground.
pub(crate) fn holding_faces(ground: &Ground, q: &Vector3<f64>, drift: f64) -> Option<Vec<usize>> {
    if !ground.is_surface() {
        return Some((0..ground.faces().len()).collect());
    }
    let (_, top) = ground.top(q.x, q.z)?;
    let tol = 1e-9 * (1.0 + top.abs());
    Some(
        ground
            .faces_by_distance(q.x, q.z, drift)
            .into_iter()
            .map(|(f, _)| f)
            .filter(|&f| ground.faces()[f].height(q.x, q.z) <= top + tol)
            .collect(),
    )
}

/// The ground's vertices under the base and its edges across the base's edges.
fn surface_touches(
    ground: &Ground,
    base: Footprint<'_>,
    pose: &BodyPose,
    corners: &[Vector3<f64>],
    reach: f64,
    out: &mut Touches,
) {
    let [x0, x1, z0, z1] = plan_box(corners.iter().map(|c| [c.x, c.z]));
    let rect = (x0 - reach, x1 + reach, z0 - reach, z1 + reach);
    let up = pose.up();
    let to_body = pose.rotation.transpose();
    let n = base.outline.len();
    for f in ground.faces_in(rect) {
        let Some(tri) = ground.triangle(f) else {
            continue;
        };
        let plane = &ground.faces()[f];
        let v: [Vector3<f64>; 3] = tri.map(|[x, z]| Vector3::new(x, plane.height(x, z), z));
        let flat = ground.flat_corners(f);
        for (j, g) in v.iter().enumerate() {
            // Inside a plane of the rock the ground is linear: never touched there first.
            if flat[j] {
                continue;
            }
            let b = to_body * (g - pose.cm);
            if !in_outline(base.outline, [b.x, b.z]) {
                continue;
            }
            let gap = -base.depth - b.y;
            if gap < reach {
                let body = Vector3::new(b.x, -base.depth, b.z);
                out.touches.push(Touch {
                    on_base: pose.point(&body),
                    body,
                    normal: up,
                    gap,
                    face: f,
                    feature: Feature::GroundVertex,
                });
            }
        }
        for e in 0..3 {
            // An edge with a flat end lies inside one plane of the rock (both its triangles are
            // in that end's fan): it is no ridge, and no crossing of it touches.
            if flat[e] || flat[(e + 1) % 3] {
                continue;
            }
            let (ga, gb) = (
                to_body * (v[e] - pose.cm),
                to_body * (v[(e + 1) % 3] - pose.cm),
            );
            let mut rock = None;
            for k in 0..n {
                let Some((body, g)) = crossing(base, k, [ga, gb]) else {
                    continue;
                };
                // The normal across both edges, to the base's side: along it the gap's rate is
                // the base point's velocity alone (along the base's normal the crossing would
                // also slide up or down the ground edge).
                let (a, b) = (base.corner(k), base.corner((k + 1) % n));
                let across = pose.rotation * (b - a).cross(&(gb - ga));
                if across.norm() <= 1e-9 * (b - a).norm() * (gb - ga).norm() {
                    continue;
                }
                let mut normal = across.normalize();
                if normal.dot(&up) < 0.0 {
                    normal = -normal;
                }
                // A touch only where the rock's edge is a ridge and the normal lies between
                // its faces' and between the base's and its side's (`wedge`).
                let edge =
                    *rock.get_or_insert_with(|| rock_edge(ground, f, &v[e], &v[(e + 1) % 3]));
                let rim = b - a;
                let inward = pose.rotation * Vector3::new(-rim.z, 0.0, rim.x).normalize();
                let held = match edge {
                    RockEdge::Ridge(na, nb) => between(&normal, &na, &nb),
                    RockEdge::Other => false,
                    RockEdge::Rim => true,
                };
                if !held || !between(&normal, &up, &inward) {
                    continue;
                }
                // The ground's point is below the base's along the base's normal by -depth - g.y.
                let gap = normal.dot(&up) * (-base.depth - g.y);
                if gap < reach {
                    out.touches.push(Touch {
                        on_base: pose.point(&body),
                        body,
                        normal,
                        gap,
                        face: f,
                        feature: Feature::Crossing(k),
                    });
                }
            }
        }
    }
}

/// Where base edge `k` (from corner k to k + 1) crosses the ground edge from `ga` to `gb` (body
/// axes) seen along the base's normal: the base's point there and the ground edge's (body
/// axes); `None` where they do not cross or run parallel. The ground under a flat base is
/// highest over it at a ground vertex, at a corner of the base, or here: the gap of the
/// ground's point below the base plane is what holds.
fn crossing(
    base: Footprint<'_>,
    k: usize,
    [ga, gb]: [Vector3<f64>; 2],
) -> Option<(Vector3<f64>, Vector3<f64>)> {
    let n = base.outline.len();
    let (a, b) = (base.outline[k], base.outline[(k + 1) % n]);
    let d1 = [b[0] - a[0], b[1] - a[1]];
    let d2 = [gb.x - ga.x, gb.z - ga.z];
    let den = d1[0] * d2[1] - d1[1] * d2[0];
    let r = [ga.x - a[0], ga.z - a[1]];
    let s = (r[0] * d2[1] - r[1] * d2[0]) / den;
    let t = (r[0] * d1[1] - r[1] * d1[0]) / den;
    // At an end of either edge the crossing is a corner on a face or a ground vertex under the
    // base, which those touches hold (`geometry::relief` says why not here too). (Parallel
    // edges, den = 0, give no finite s and t; most pairs are told apart here, before the
    // lengths the parallel test needs.)
    let inside = |u: f64| u > 1e-9 && u < 1.0 - 1e-9;
    if !inside(s) || !inside(t) {
        return None;
    }
    let scale = (d1[0].hypot(d1[1])) * (d2[0].hypot(d2[1]));
    if den.abs() <= 1e-12 * scale {
        return None;
    }
    let body = Vector3::new(a[0] + s * d1[0], -base.depth, a[1] + s * d1[1]);
    Some((body, ga + (gb - ga) * t))
}

/// The signed area (m²) of the polygon `p` given as (x, z): the shoelace sum over (x, z) taken
/// as a plane's (x, y). A base keeps the winding that makes it positive.
pub fn signed_area(p: &[[f64; 2]]) -> f64 {
    let n = p.len();
    (0..n)
        .map(|k| {
            let (a, b) = (p[k], p[(k + 1) % n]);
            a[0] * b[1] - b[0] * a[1]
        })
        .sum::<f64>()
        / 2.0
}

/// The plan box [x0, x1, z0, z1] of `points` given as (x, z).
pub fn plan_box(points: impl IntoIterator<Item = [f64; 2]>) -> [f64; 4] {
    points.into_iter().fold(
        [
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::INFINITY,
            f64::NEG_INFINITY,
        ],
        |[x0, x1, z0, z1], [x, z]| [x0.min(x), x1.max(x), z0.min(z), z1.max(z)],
    )
}

/// Whether point `q` is inside or on the simple polygon `p` (crossing number, with the
/// boundary counted in).
pub fn in_outline(p: &[[f64; 2]], q: [f64; 2]) -> bool {
    let n = p.len();
    let size = p
        .iter()
        .map(|a| a[0].abs().max(a[1].abs()))
        .fold(1.0, f64::max);
    let tol = 1e-12 * size;
    let mut inside = false;
    for k in 0..n {
        let (a, b) = (p[k], p[(k + 1) % n]);
        if segment_distance_2(a, b, q) <= tol * tol {
            return true;
        }
        if (a[1] > q[1]) != (b[1] > q[1]) {
            let x = a[0] + (q[1] - a[1]) / (b[1] - a[1]) * (b[0] - a[0]);
            if q[0] < x {
                inside = !inside;
            }
        }
    }
    inside
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::Plane;

    fn square(half: f64) -> Vec<[f64; 2]> {
        vec![[-half, -half], [half, -half], [half, half], [-half, half]]
    }

    fn flat(cm_y: f64) -> BodyPose {
        BodyPose {
            cm: Vector3::new(0.0, cm_y, 0.0),
            rotation: Matrix3::identity(),
        }
    }

    #[test]
    fn a_base_over_a_valley_of_planes_touches_at_its_corners_on_each_plane() {
        let level = Plane::through(Vector3::y(), Vector3::zeros());
        let rising = Plane::from_dip(10f64.to_radians(), 270f64.to_radians(), Vector3::zeros());
        let ground = Ground::planes(vec![level, rising]);
        let outline = square(1.0);
        let base = Footprint {
            outline: &outline,
            depth: 0.5,
        };
        let t = touches(&ground, base, &flat(0.5), 1e-9, 0.0);
        // The rising plane reaches the corners at x = +1 above Y = 0 (whichever way it dips,
        // two corners are inside one of the planes or on them).
        assert!(!t.touches.is_empty());
        for touch in &t.touches {
            let plane = &ground.faces()[touch.face];
            assert!((touch.gap - plane.signed_distance(&touch.on_base)).abs() < 1e-15);
        }
    }

    #[test]
    fn a_bump_under_the_middle_of_a_base_is_a_ground_vertex_touch_at_its_height() {
        // Four triangles rising to a peak 0.1 m high at the origin, a 4 m square.
        let ground = crate::geometry::fixtures::pyramid(0.1);
        let outline = square(1.0);
        let base = Footprint {
            outline: &outline,
            depth: 0.0,
        };
        // The base flat at 0.1 m touches the peak; its corners are 0.05 m above the faces.
        let t = touches(&ground, base, &flat(0.1), 0.06, 0.0);
        let peak_touch = t
            .touches
            .iter()
            .find(|t| t.feature == Feature::GroundVertex)
            .expect("the peak");
        assert!(peak_touch.gap.abs() < 1e-15);
        assert!((peak_touch.normal - Vector3::y()).norm() < 1e-15);
        let corner_gaps: Vec<f64> = t
            .touches
            .iter()
            .filter(|t| matches!(t.feature, Feature::Corner(_)))
            .map(|t| t.gap)
            .collect();
        // The faces rise 0.1 m over 2 m: at a corner (1, 1) the ground is 0.05 m high, and the
        // gap along the face's normal is 0.05 cos(atan 0.05).
        let expect = 0.05 * (0.05f64).atan().cos();
        // Each corner is on a diagonal, so on two triangles: eight touches, all alike.
        assert_eq!(corner_gaps.len(), 8);
        assert!(corner_gaps.iter().all(|g| (g - expect).abs() < 1e-12));
    }

    /// A ridge along X at Z = 0, 0.2 m high, its sides falling 0.1 over 2 m.
    fn ridge_along_x() -> Ground {
        let a = [[-3.0, 0.2, 0.0], [3.0, 0.2, 0.0], [3.0, 0.1, 2.0]];
        let b = [[-3.0, 0.2, 0.0], [3.0, 0.1, 2.0], [-3.0, 0.1, 2.0]];
        let c = [[-3.0, 0.2, 0.0], [-3.0, 0.1, -2.0], [3.0, 0.1, -2.0]];
        let d = [[-3.0, 0.2, 0.0], [3.0, 0.1, -2.0], [3.0, 0.2, 0.0]];
        Ground::surface(&[a, b, c, d]).unwrap()
    }

    #[test]
    fn a_ridge_under_a_base_edge_touches_where_they_cross() {
        let ground = ridge_along_x();
        let outline = square(1.0);
        let base = Footprint {
            outline: &outline,
            depth: 0.0,
        };
        let t = touches(&ground, base, &flat(0.2), 1e-9, 0.0);
        let crossings: Vec<&Touch> = t
            .touches
            .iter()
            .filter(|t| matches!(t.feature, Feature::Crossing(_)))
            .collect();
        assert!(!crossings.is_empty());
        for c in crossings {
            assert!(c.on_base.z.abs() < 1e-12 && (c.on_base.x.abs() - 1.0).abs() < 1e-12);
            assert!(c.gap.abs() < 1e-12);
        }
    }

    #[test]
    fn a_base_edge_lying_nearly_along_a_ridge_meets_it_along_no_level_normal() {
        // The ridge along X (its crest at Z = 0, 0.2 m high); a base whose
        // edge z′ = -1 lies along the crest 1 µm above it, turned by 1e-5 rad so that it
        // crosses the crest in plan and tilted along it by 1e-4 rad. Along a crest the normal
        // across both edges is nearly level: no normal of the rock or the base there.
        let ground = ridge_along_x();
        let outline = square(1.0);
        let base = Footprint {
            outline: &outline,
            depth: 0.0,
        };
        let turn = nalgebra::Rotation3::from_axis_angle(&Vector3::y_axis(), 1e-5)
            * nalgebra::Rotation3::from_axis_angle(&Vector3::z_axis(), 1e-4);
        let pose = BodyPose {
            cm: Vector3::new(0.0, 0.2 + 1e-6, 1.0),
            rotation: *turn.matrix(),
        };
        let t = touches(&ground, base, &pose, 1e-3, 0.0);
        assert!(!t.touches.is_empty());
        for t in &t.touches {
            assert!(t.normal.y > 0.99, "{t:?}");
        }
    }

    #[test]
    fn a_corner_off_the_surface_is_named() {
        let tri = [[[0.0, 0.0, 0.0], [10.0, 0.0, 0.0], [0.0, 0.0, 10.0]]];
        let ground = Ground::surface(&tri).unwrap();
        let outline = vec![[1.0, 1.0], [4.0, 1.0], [8.0, 8.0], [1.0, 4.0]];
        let base = Footprint {
            outline: &outline,
            depth: 0.0,
        };
        let t = touches(&ground, base, &flat(0.0), 1e-9, 0.0);
        assert_eq!(t.off_ground, vec![2]);
    }
}
