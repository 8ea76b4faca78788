//! Patch reduction: where a body's underside lies flush on its rock
//! (`derivations/13-base-contact.md` §9) — its whole face on a plane of the rock, or an edge
//! along one. There the touches found at corners and vertices carry the base's normal impulse,
//! but its pressure, and so its friction, is over the area or along the edge, as on a stiff
//! uniform bed: a [`Patch`] of the quadrature points lying there. Where it rests on more than
//! three points of one plane without lying flush, equal springs at the points share it (§9,
//! "Points on a plane"). The touches inside a face's patch are implied by its hull's corners
//! and are left out ([`reduce`]).

use super::hull::{hull_across, tangents};
use crate::geometry::{BodyPose, Feature, Ground, Touch, Touches};
use nalgebra::Vector3;

/// A base lies flush on its rock where its normal is within this angle (rad) of the rock's.
const FLUSH_ANGLE: f64 = 1e-6;

/// … and its gap there within this fraction of its size.
const FLUSH_GAP: f64 = 1e-6;

/// A body's quadrature points in body axes about the CM (m), with their weights: where a base
/// lying flush on its rock presses and rubs. Built from a flat base or a cast relief in
/// `src/contact/quadrature.rs` (the triangles' rule is the model's).
#[derive(Debug, Clone, Default)]
pub struct Quadrature {
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

/// Which point of a patch: of the area, node j of edge k, or a touch.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Spot {
    /// Point k of the area.
    Area(usize),
    /// Node j of edge k.
    Edge(usize, usize),
    /// A touch among others on one plane: its features, its face, and where it is on the
    /// base (body axes, m), by which the next step finds it again.
    Touch(Feature, usize, Vector3<f64>),
}

/// What the flush parts are sought on: the ground, the body's quadrature and its size (m).
#[derive(Debug, Clone, Copy)]
pub struct Bed<'a> {
    /// The rock.
    pub ground: &'a Ground,
    /// The body's quadrature.
    pub quadrature: &'a Quadrature,
    /// The body's reach from its centre of mass (m): the scale of the flush tolerances.
    pub size: f64,
}

/// One point of a patch.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PatchPoint {
    /// r: from the CM to the point (m, world axes).
    pub arm: Vector3<f64>,
    /// The area it stands for (m²), its length along an edge (m), or one for a point among
    /// equal springs.
    pub weight: f64,
    /// The face of the rock under it.
    pub face: usize,
    /// Which point it is.
    pub spot: Spot,
}

/// A flush part of the underside, or points on a plane: the touches on it and its points.
#[derive(Debug, Clone, PartialEq)]
pub struct Patch {
    /// The touches on it (indices into the touches [`reduce`] keeps).
    pub members: Vec<usize>,
    /// Two unit axes in its plane (with its normal, a right-handed frame).
    pub axes: (Vector3<f64>, Vector3<f64>),
    /// Its points.
    pub points: Vec<PatchPoint>,
}

/// The touches with the patches among them: no touch in two patches.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Reduced {
    /// The touches left after those inside a flush face's hull are taken out.
    pub touches: Touches,
    /// The patches, their members numbered among `touches`.
    pub patches: Vec<Patch>,
}

/// The patches of a body at `pose` among the touches it `found` (`derivations/13-base-contact.md`
/// §9): its faces on planes of the rock (at least three of their points over rock in their
/// plane), each edge whose two corners touch one plane of the rock with no gap (at least two
/// of its nodes over that rock) with the crossings along it, then the closed touches left, by
/// normal, where three or more distinct points share one. The touches inside a face patch's
/// hull are left out, the others renumbered.
pub fn reduce(bed: &Bed<'_>, pose: &BodyPose, found: Touches) -> Reduced {
    let mut seek = Seek {
        bed,
        pose,
        touches: &found.touches,
        used: vec![false; found.touches.len()],
        cos: FLUSH_ANGLE.cos(),
        tol: FLUSH_GAP * bed.size,
        dropped: Vec::new(),
    };
    let mut patches = Vec::new();
    seek.faces(&mut patches);
    seek.edges(&mut patches);
    seek.points_on_planes(&mut patches);
    let dropped = seek.dropped;
    let mut found = found;
    if !dropped.is_empty() {
        let mut keep = vec![true; found.touches.len()];
        for &i in &dropped {
            keep[i] = false;
        }
        // Each kept touch's number among the kept.
        let new_index: Vec<usize> = keep
            .iter()
            .scan(0, |n, &k| {
                let here = *n;
                *n += usize::from(k);
                Some(here)
            })
            .collect();
        for m in patches.iter_mut().flat_map(|p| p.members.iter_mut()) {
            *m = new_index[*m];
        }
        let mut k = keep.iter().copied();
        found.touches.retain(|_| k.next().unwrap_or(true));
    }
    Reduced {
        touches: found,
        patches,
    }
}

/// The search for patches among one body's touches: which are in a patch already, and which
/// are left out.
struct Seek<'a> {
    bed: &'a Bed<'a>,
    pose: &'a BodyPose,
    touches: &'a [Touch],
    used: Vec<bool>,
    cos: f64,
    tol: f64,
    dropped: Vec<usize>,
}

impl Seek<'_> {
    /// A patch of `members` on the plane of normal `n`, over `points`: none of its members is
    /// sought again.
    fn take(
        &mut self,
        out: &mut Vec<Patch>,
        members: Vec<usize>,
        n: &Vector3<f64>,
        points: Vec<PatchPoint>,
    ) {
        for &i in &members {
            self.used[i] = true;
        }
        out.push(Patch {
            members,
            axes: tangents(n),
            points,
        });
    }

    /// Whether touch `t` is closed (its gap within the tolerance).
    fn close(&self, t: &Touch) -> bool {
        t.gap.abs() <= self.tol
    }

    /// The points of `pts` (body axes, with weights) over rock flush with a plane of normal `n`.
    fn on_rock<'q>(
        &self,
        n: &Vector3<f64>,
        pts: impl Iterator<Item = (Spot, &'q (Vector3<f64>, f64))>,
    ) -> Vec<PatchPoint> {
        let ground = self.bed.ground;
        let faces = ground.faces();
        let mut points = Vec::new();
        for (spot, (at, weight)) in pts {
            let q = self.pose.point(at);
            let Some((f, _)) = ground.top(q.x, q.z) else {
                continue;
            };
            let face = &faces[f];
            if face.normal().dot(n) >= self.cos && face.signed_distance(&q).abs() <= self.tol {
                points.push(PatchPoint {
                    arm: q - self.pose.cm,
                    weight: *weight,
                    face: f,
                    spot,
                });
            }
        }
        points
    }

    /// The faces on planes: for each direction m of the body's faces (the flat base's one, its
    /// normal; a cast base's relief's, each set of parallel faces), the touches closed flush
    /// along m, and the area's points on those faces over rock in their plane. Only the
    /// members' hull's corners stay: the members' normal impulses matter to the patch only by
    /// their resultant, whose line lies in their points' convex hull, and with one normal and
    /// gaps affine over the plane an inside member's constraint is implied by the corners'.
    fn faces(&mut self, out: &mut Vec<Patch>) {
        let quadrature = self.bed.quadrature;
        for (m_body, on_faces) in &quadrature.faces {
            let m = self.pose.rotation * m_body;
            let members: Vec<usize> = (0..self.touches.len())
                .filter(|&i| {
                    let t = &self.touches[i];
                    !self.used[i] && t.normal.dot(&m) >= self.cos && self.close(t)
                })
                .collect();
            let Some(&first) = members.first() else {
                continue;
            };
            let n = self.touches[first].normal;
            let pts = on_faces
                .iter()
                .map(|&k| (Spot::Area(k), &quadrature.area[k]));
            let points = self.on_rock(&n, pts);
            if points.len() >= 3 {
                for &i in &members {
                    self.used[i] = true;
                }
                let arms = members
                    .iter()
                    .map(|&i| self.touches[i].on_base - self.pose.cm);
                let kept: Vec<usize> = hull_across(&n, arms)
                    .into_iter()
                    .map(|k| members[k])
                    .collect();
                self.dropped
                    .extend(members.iter().copied().filter(|i| !kept.contains(i)));
                out.push(Patch {
                    members: kept,
                    axes: tangents(&n),
                    points,
                });
            }
        }
    }

    /// The edges along a plane: both corners closed on one plane, at least two of the edge's
    /// nodes over rock in it; the rock's edges crossing it there join its patch (one line).
    fn edges(&mut self, out: &mut Vec<Patch>) {
        let quadrature = self.bed.quadrature;
        let corners = quadrature.edges.len();
        let touches = self.touches;
        for k in 0..corners {
            let ends = |c: usize| -> Vec<usize> {
                (0..touches.len())
                    .filter(|&i| {
                        !self.used[i]
                            && touches[i].feature == Feature::Corner(c)
                            && self.close(&touches[i])
                    })
                    .collect()
            };
            let (from, to) = (ends(k), ends((k + 1) % corners));
            let pair = from.iter().find_map(|&a| {
                to.iter()
                    .find(|&&b| touches[a].normal.dot(&touches[b].normal) >= self.cos)
                    .map(|&b| (a, b))
            });
            let Some((a, b)) = pair else {
                continue;
            };
            let n = touches[a].normal;
            let pts = quadrature.edges[k]
                .iter()
                .enumerate()
                .map(|(j, p)| (Spot::Edge(k, j), p));
            let points = self.on_rock(&n, pts);
            if points.len() >= 2 {
                let members: Vec<usize> = (0..touches.len())
                    .filter(|&i| {
                        let t = &touches[i];
                        i == a
                            || i == b
                            || (!self.used[i]
                                && t.feature == Feature::Crossing(k)
                                && t.normal.dot(&n) >= self.cos
                                && self.close(t))
                    })
                    .collect();
                self.take(out, members, &n, points);
            }
        }
    }

    /// Points on a plane: the closed touches left that share one normal, three or more apart
    /// (a flat base on the ground's vertices, a cast base's bends across the rock's crests).
    /// The rigid body leaves their shares open beyond three; equal springs at them, a uniform
    /// bed of points, fix them as the faces' bed does, and their friction acts with those
    /// shares.
    fn points_on_planes(&mut self, out: &mut Vec<Patch>) {
        let touches = self.touches;
        let mut rest: Vec<usize> = (0..touches.len())
            .filter(|&i| !self.used[i] && self.close(&touches[i]))
            .collect();
        while let Some(&first) = rest.first() {
            let n = touches[first].normal;
            let (members, others): (Vec<usize>, Vec<usize>) = rest
                .iter()
                .partition(|&&i| touches[i].normal.dot(&n) >= self.cos);
            rest = others;
            let mut points = Vec::<PatchPoint>::new();
            for &i in &members {
                let t = &touches[i];
                let arm = t.on_base - self.pose.cm;
                if points.iter().any(|p| (p.arm - arm).norm() <= self.tol) {
                    continue;
                }
                points.push(PatchPoint {
                    arm,
                    weight: 1.0,
                    face: t.face,
                    spot: Spot::Touch(t.feature, t.face, t.body),
                });
            }
            if points.len() >= 3 {
                along_one_line(&mut points, self.tol, &|arm| self.touching(arm));
                self.take(out, members, &n, points);
            }
        }
    }

    /// Whether the rock is at the body's point `arm` from the CM (within the tolerance): a
    /// ridge of the rock along the base touches it all along, not at its points only.
    fn touching(&self, arm: &Vector3<f64>) -> bool {
        let q = self.pose.cm + arm;
        let ground = self.bed.ground;
        ground
            .top(q.x, q.z)
            .is_some_and(|(f, _)| ground.faces()[f].signed_distance(&q).abs() <= self.tol)
    }
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

    /// Unit points at `zs` along z (and one more at `extra`, if given).
    fn points_at(zs: &[f64], extra: Option<Vector3<f64>>) -> Vec<PatchPoint> {
        zs.iter()
            .map(|&z| Vector3::new(-1.0, -0.1, z))
            .chain(extra)
            .enumerate()
            .map(|(k, arm)| PatchPoint {
                arm,
                weight: 1.0,
                face: 0,
                spot: Spot::Area(k),
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
