//! Whether an edge of the base and an edge of the rock that cross in plan touch there along the
//! normal across both (`derivations/13-base-contact.md` §2, "Which crossings touch").
//!
//! Along an edge of the base, the gap to the rock has a local least value where it crosses an
//! edge of the rock only when both edges are convex — a ridge of the rock under the base's rim
//! or a cast base's keel; over a valley of the rock, or under a groove of a cast base, the gap
//! has its greatest value there, and the faces' own touches hold. And two convex edges touch
//! along their common normal n ∥ e_base × e_rock only when n lies between the normals of the
//! faces that meet at each edge (the two edges' normal cones meet). Otherwise — edges nearly
//! parallel in plan, whose common normal is nearly horizontal — the crossing is no contact: a
//! base's edge sliding along the rock's edge it was cast from, or over a ridge nearly along it,
//! would be braked along that normal by a rock it does not touch (`scenes/body/cast-adverse.toml`
//! lost 15 % of its speed in one step, against the bed of springs of `crosscheck/bed_body.py`).
//! There the vertices' own touches hold the edges.

use super::Ground;
use nalgebra::Vector3;

/// An edge of a surface's triangle, as a contact sees it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum RockEdge {
    /// A ridge: the upward unit normals of the two faces that meet there.
    Ridge(Vector3<f64>, Vector3<f64>),
    /// A valley, or a fold of one plane: no crossing touches there.
    Other,
    /// An edge of the surface, no other triangle beside it.
    Rim,
}

/// Surface triangle `f`'s edge from `p` to `q` (world, on the surface): a ridge (the
/// neighbour's far vertex below `f`'s plane), anything else, or the surface's rim.
pub(crate) fn rock_edge(ground: &Ground, f: usize, p: &Vector3<f64>, q: &Vector3<f64>) -> RockEdge {
    let length = (q - p).norm();
    let tol = 1e-9 * (1.0 + p.x.abs().max(p.z.abs()).max(length));
    let same =
        |c: [f64; 2], v: &Vector3<f64>| (c[0] - v.x).abs() <= tol && (c[1] - v.z).abs() <= tol;
    let mid = (p + q) / 2.0;
    for k in ground.faces_near(mid.x, mid.z, tol) {
        if k == f {
            continue;
        }
        let Some(tri) = ground.triangle(k) else {
            continue;
        };
        if !(tri.iter().any(|&c| same(c, p)) && tri.iter().any(|&c| same(c, q))) {
            continue;
        }
        let Some(&[x, z]) = tri.iter().find(|&&c| !same(c, p) && !same(c, q)) else {
            continue;
        };
        let other = &ground.faces()[k];
        let far = Vector3::new(x, other.height(x, z), z);
        let face = &ground.faces()[f];
        return if face.signed_distance(&far) < -1e-9 * length {
            RockEdge::Ridge(face.normal(), other.normal())
        } else {
            RockEdge::Other
        };
    }
    RockEdge::Rim
}

/// How far (rad) a crossing's normal may lie outside the arc of an edge's faces' normals and
/// still touch. A ridge of the rock lying along a flat base's face (a crest under a block that
/// rests on it, rolling by hundredths of a degree) meets the base's rim at each end with a
/// normal on the arc's end, now inside, now outside by round-off or the roll: those ends carry
/// the line (`geometry::contact::patch`'s `along_one_line`). Edges that do not touch are far
/// outside (a cast base's edge along the rock's edge it was cast from: 78°).
pub(crate) const SLACK: f64 = 0.01;

/// Whether the unit vector `n` lies on the shorter great-circle arc from `a` to `b` (unit,
/// `n` at right angles to `a × b`), or within [`SLACK`] of it; never when `a` and `b` are
/// parallel.
pub(crate) fn between(n: &Vector3<f64>, a: &Vector3<f64>, b: &Vector3<f64>) -> bool {
    let c = a.cross(b);
    let size = c.norm();
    if size <= 1e-12 {
        return false;
    }
    let c = c / size;
    let tol = SLACK.sin();
    a.cross(n).dot(&c) >= -tol && n.cross(b).dot(&c) >= -tol && n.dot(&(a + b)) > 0.0
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A ridge along Z at X = 0 between faces falling at `slope` each way, level beyond.
    fn ridge(slope: f64) -> Ground {
        let h = slope;
        Ground::surface(&[
            [[-1.0, 0.0, -5.0], [0.0, h, -5.0], [0.0, h, 5.0]],
            [[-1.0, 0.0, -5.0], [0.0, h, 5.0], [-1.0, 0.0, 5.0]],
            [[0.0, h, -5.0], [1.0, 0.0, -5.0], [1.0, 0.0, 5.0]],
            [[0.0, h, -5.0], [1.0, 0.0, 5.0], [0.0, h, 5.0]],
        ])
        .unwrap()
    }

    fn face_with(ground: &Ground, p: [f64; 2], q: [f64; 2]) -> usize {
        (0..ground.faces().len())
            .find(|&k| {
                let t = ground.triangle(k).unwrap();
                t.contains(&p) && t.contains(&q)
            })
            .unwrap()
    }

    #[test]
    fn a_crest_is_a_ridge_with_its_two_faces_and_a_hollow_is_not() {
        let up = ridge(0.1);
        let f = face_with(&up, [0.0, -5.0], [0.0, 5.0]);
        let (p, q) = (Vector3::new(0.0, 0.1, -5.0), Vector3::new(0.0, 0.1, 5.0));
        let RockEdge::Ridge(a, b) = rock_edge(&up, f, &p, &q) else {
            panic!("the crest is a ridge: {:?}", rock_edge(&up, f, &p, &q));
        };
        // Its faces fall away at 0.1 each way: normals (±0.1, 1, 0)/√1.01.
        let s = 1.01f64.sqrt();
        assert!((a.x.abs() - 0.1 / s).abs() < 1e-12 && (b.x.abs() - 0.1 / s).abs() < 1e-12);
        assert!(a.x * b.x < 0.0);
        let down = ridge(-0.1);
        let (p, q) = (Vector3::new(0.0, -0.1, -5.0), Vector3::new(0.0, -0.1, 5.0));
        let g = face_with(&down, [0.0, -5.0], [0.0, 5.0]);
        assert_eq!(rock_edge(&down, g, &p, &q), RockEdge::Other);
        // The diagonal of one face's two triangles is a fold of one plane; its outer side the
        // surface's rim.
        let d = face_with(&up, [-1.0, -5.0], [0.0, 5.0]);
        let (p, q) = (Vector3::new(-1.0, 0.0, -5.0), Vector3::new(0.0, 0.1, 5.0));
        assert_eq!(rock_edge(&up, d, &p, &q), RockEdge::Other);
        let r = face_with(&up, [-1.0, -5.0], [-1.0, 5.0]);
        let (p, q) = (Vector3::new(-1.0, 0.0, -5.0), Vector3::new(-1.0, 0.0, 5.0));
        assert_eq!(rock_edge(&up, r, &p, &q), RockEdge::Rim);
    }

    #[test]
    fn a_normal_is_between_two_faces_only_on_the_short_arc_joining_them() {
        let (a, b) = (
            Vector3::new(-0.1, 1.0, 0.0).normalize(),
            Vector3::new(0.1, 1.0, 0.0).normalize(),
        );
        assert!(between(&Vector3::y(), &a, &b));
        assert!(between(&a, &a, &b) && between(&b, &a, &b));
        assert!(!between(&Vector3::x(), &a, &b));
        assert!(!between(&-Vector3::y(), &a, &b));
        assert!(!between(&Vector3::new(0.2, 1.0, 0.0).normalize(), &a, &b));
        // Within the slack past an end, and not beyond it.
        let past = |angle: f64| {
            let t = 0.1f64.atan() + angle;
            Vector3::new(t.sin(), t.cos(), 0.0)
        };
        assert!(between(&past(0.9 * SLACK), &a, &b));
        assert!(!between(&past(1.1 * SLACK), &a, &b));
        assert!(!between(&Vector3::y(), &a, &a));
    }
}
