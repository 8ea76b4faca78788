//! A base cast onto its rock (`[base] cast = true`; `derivations/13-base-contact.md` §10): its
//! underside is the foundation's own surface under the footprint where the block rests, the
//! paper's "matching interface", so that any displacement makes it ride up on the asperities.
//!
//! The underside is a [`Relief`]: convex planar faces in the block's own axes, each the part of
//! one face of the ground under one triangle of the footprint (`cast.rs`), with the vertices and
//! the edges where the relief bends or ends. Its touches with the ground (`touches.rs`) are of
//! the same three kinds as a flat base's, and for the same reason: over the plan overlap of a
//! face of the relief and a triangle of the ground the gap is linear, so it is least at a vertex
//! of the relief, a vertex of the ground, or where their edges cross.

mod cast;
mod touches;

pub use cast::{CastError, cast};
pub use touches::relief_touches;

use nalgebra::Vector3;
use rstar::RTree;
use rstar::primitives::{GeomWithData, Rectangle};

/// A plan rectangle in the block's axes (x′, z′) with the index it stands for.
type Boxed = GeomWithData<Rectangle<[f64; 2]>, usize>;

/// One face of a relief: a convex polygon in a plane.
#[derive(Debug, Clone, PartialEq)]
pub struct ReliefFace {
    /// Its corners (indices into the relief's vertices), counter-clockwise seen from above in
    /// the block's axes (x′, z′).
    pub corners: Vec<usize>,
    /// Its unit normal into the block (body axes; y′ > 0).
    pub normal: Vector3<f64>,
}

/// The underside of a cast base, in the block's own axes about its centre of mass (m).
#[derive(Debug, Clone)]
pub struct Relief {
    vertices: Vec<Vector3<f64>>,
    faces: Vec<ReliefFace>,
    /// The edges where the relief bends or ends (pairs of vertex indices).
    edges: Vec<[usize; 2]>,
    /// Each edge's normals into the block where it is convex on the block (`keel`).
    keels: Vec<Option<[Vector3<f64>; 2]>>,
    face_tree: RTree<Boxed>,
    edge_tree: RTree<Boxed>,
}

impl Relief {
    /// The relief of `faces` over `vertices` (body axes), its bends and rim found from which
    /// faces share an edge: an edge between two faces in one plane is neither.
    pub fn new(vertices: Vec<Vector3<f64>>, faces: Vec<ReliefFace>) -> Relief {
        let mut by_edge: std::collections::BTreeMap<[usize; 2], Vec<usize>> = Default::default();
        for (f, face) in faces.iter().enumerate() {
            let n = face.corners.len();
            for k in 0..n {
                let (a, b) = (face.corners[k], face.corners[(k + 1) % n]);
                if a != b {
                    by_edge.entry([a.min(b), a.max(b)]).or_default().push(f);
                }
            }
        }
        let (edges, edge_faces): (Vec<[usize; 2]>, Vec<Vec<usize>>) = by_edge
            .into_iter()
            .filter(|(_, fs)| {
                fs.len() != 2 || (faces[fs[0]].normal - faces[fs[1]].normal).norm() > 1e-9
            })
            .unzip();
        let keels = edges
            .iter()
            .zip(&edge_faces)
            .map(|(&e, fs)| keel_of(&vertices, &faces, e, fs))
            .collect();
        let plan = |ids: &mut dyn Iterator<Item = usize>| {
            let mut lo = [f64::INFINITY; 2];
            let mut hi = [f64::NEG_INFINITY; 2];
            for i in ids {
                let v = vertices[i];
                lo = [lo[0].min(v.x), lo[1].min(v.z)];
                hi = [hi[0].max(v.x), hi[1].max(v.z)];
            }
            Rectangle::from_corners(lo, hi)
        };
        let face_tree = RTree::bulk_load(
            faces
                .iter()
                .enumerate()
                .map(|(f, face)| Boxed::new(plan(&mut face.corners.iter().copied()), f))
                .collect(),
        );
        let edge_tree = RTree::bulk_load(
            edges
                .iter()
                .enumerate()
                .map(|(e, ab)| Boxed::new(plan(&mut ab.iter().copied()), e))
                .collect(),
        );
        Relief {
            vertices,
            faces,
            edges,
            keels,
            face_tree,
            edge_tree,
        }
    }

    /// The vertices (body axes about the CM, m).
    pub fn vertices(&self) -> &[Vector3<f64>] {
        &self.vertices
    }

    /// The faces.
    pub fn faces(&self) -> &[ReliefFace] {
        &self.faces
    }

    /// The edges where the relief bends or ends.
    pub fn edges(&self) -> &[[usize; 2]] {
        &self.edges
    }

    /// Whether edge `k` is convex on the block — a keel, where the relief's two faces fall away
    /// from each other (a valley of the rock it was cast on), or on the rim — and if so the
    /// normals into the block of the faces that meet there: the relief's (body axes), and on
    /// the rim the block's side's, level, into the block.
    pub fn keel(&self, k: usize) -> Option<[Vector3<f64>; 2]> {
        self.keels[k]
    }

    /// The faces whose plan (x′, z′) holds the point `p` (its boundary, within round-off,
    /// included).
    pub fn faces_over(&self, p: [f64; 2]) -> impl Iterator<Item = usize> + '_ {
        self.face_tree
            .locate_in_envelope_intersecting(&rstar::AABB::from_point(p))
            .map(|b| b.data)
            .filter(move |&f| self.holds(f, p))
    }

    /// The edges whose plan boxes meet the plan box from `lo` to `hi`.
    pub fn edges_in(&self, lo: [f64; 2], hi: [f64; 2]) -> impl Iterator<Item = usize> + '_ {
        self.edge_tree
            .locate_in_envelope_intersecting(&rstar::AABB::from_corners(lo, hi))
            .map(|b| b.data)
    }

    /// The height y′ (body axes, m) of face `f`'s plane over (x′, z′).
    pub fn height(&self, f: usize, [x, z]: [f64; 2]) -> f64 {
        let face = &self.faces[f];
        let a = self.vertices[face.corners[0]];
        let m = face.normal;
        a.y - (m.x * (x - a.x) + m.z * (z - a.z)) / m.y
    }

    /// Whether face `f`'s plan holds `p` (convex, counter-clockwise).
    fn holds(&self, f: usize, p: [f64; 2]) -> bool {
        let c = &self.faces[f].corners;
        let n = c.len();
        (0..n).all(|k| {
            let (a, b) = (self.vertices[c[k]], self.vertices[c[(k + 1) % n]]);
            let (dx, dz) = (b.x - a.x, b.z - a.z);
            let cross = dx * (p[1] - a.z) - dz * (p[0] - a.x);
            cross >= -1e-12 * dx.hypot(dz) * (1.0 + p[0].abs() + p[1].abs())
        })
    }

    /// Samples of the relief for the independent check of its penetration (body axes, m): its
    /// vertices and, on each face, a grid of `per_side` points along each side of its fan's
    /// triangles.
    pub fn samples(&self, per_side: usize) -> Vec<Vector3<f64>> {
        let per_side = per_side.max(2);
        let mut out = self.vertices.clone();
        for face in &self.faces {
            let c = &face.corners;
            for k in 1..c.len().saturating_sub(1) {
                let (a, b, d) = (
                    self.vertices[c[0]],
                    self.vertices[c[k]],
                    self.vertices[c[k + 1]],
                );
                for i in 0..=per_side {
                    for j in 0..=per_side - i {
                        let (s, t) = (i as f64 / per_side as f64, j as f64 / per_side as f64);
                        out.push(a + (b - a) * s + (d - a) * t);
                    }
                }
            }
        }
        out
    }

    /// The largest distance of a vertex from the centre of mass (m).
    pub fn reach(&self) -> f64 {
        self.vertices.iter().map(|v| v.norm()).fold(0.0, f64::max)
    }
}

/// [`Relief::keel`] of the edge from vertex `i` to `j` with the faces `beside` it.
fn keel_of(
    vertices: &[Vector3<f64>],
    faces: &[ReliefFace],
    [i, j]: [usize; 2],
    beside: &[usize],
) -> Option<[Vector3<f64>; 2]> {
    let (p, q) = (vertices[i], vertices[j]);
    match beside[..] {
        [f] => {
            // Level, at right angles to the edge, towards the face's middle.
            let face = &faces[f];
            let mid = face
                .corners
                .iter()
                .map(|&c| vertices[c])
                .sum::<Vector3<f64>>()
                / face.corners.len() as f64;
            let d = q - p;
            let mut inward = Vector3::new(-d.z, 0.0, d.x).normalize();
            if inward.dot(&(mid - p)) < 0.0 {
                inward = -inward;
            }
            Some([face.normal, inward])
        }
        [f, g] => {
            let (a, b) = (&faces[f], &faces[g]);
            let far = b
                .corners
                .iter()
                .map(|&c| vertices[c])
                .map(|w| (w - p).dot(&a.normal))
                .fold(f64::NEG_INFINITY, f64::max);
            (far > 1e-9 * (q - p).norm()).then_some([a.normal, b.normal])
        }
        _ => None,
    }
}
