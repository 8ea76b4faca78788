//! A foundation of any number of faces. Two kinds:
//!
//! * a list of planes: the ground at (X, Z) is the highest of them there, a valley of rock
//!   faces, defined everywhere;
//! * a triangulated surface (Wavefront OBJ, `[foundation] surface`): the ground at (X, Z) is the
//!   triangle over it (the highest, where triangles overlap), found through a packed R-tree of
//!   the triangles' plan extents (`plan_tree.rs`) in O(log n); off the surface there is no
//!   ground. Ridges are allowed.
//!
//! Faces are numbered from 0: the planes in the order the scene lists them, the triangles in the
//! order of the file.

use super::plan_tree::{self, PlanTree, outward};
use super::plane::Plane;
use super::rock::Rock;
use nalgebra::Vector3;
use std::sync::{Arc, OnceLock};

/// The ground: its faces and how to find the one over a point.
#[derive(Debug, Clone)]
pub struct Ground {
    faces: Vec<Plane>,
    kind: Kind,
    /// The same ground in the collision library's shapes, built when first asked for.
    rock: OnceLock<Arc<Rock>>,
    /// Each surface triangle's corners that are flat ([`find_flat_corners`]), found when first
    /// asked for (by the block on its base only: loading a surface does not pay for them).
    flat: OnceLock<Vec<[bool; 3]>>,
}

#[derive(Debug, Clone)]
enum Kind {
    /// The upper envelope of the faces.
    Planes,
    /// Triangles: the face over a point is a triangle containing its plan position (the tree
    /// gives the triangles whose plan extent may hold it, their corners decide).
    Surface(Mesh),
}

/// A triangulated surface as it is kept: each corner once (X, Y, Z), each triangle by its
/// corners' numbers, and the packed R-tree of the triangles' plan extents (`plan_tree.rs`).
/// With the faces' planes, 24 bytes a corner and 12 + 32 + about 21 a triangle; the exact
/// tests are on the corners ([`contains_point`], [`distance_2`]).
#[derive(Debug, Clone)]
struct Mesh {
    vertices: Vec<[f64; 3]>,
    triangles: Vec<[u32; 3]>,
    tree: PlanTree,
}

impl Mesh {
    /// The plan corners (X, Z) of triangle `k`.
    fn corners(&self, k: usize) -> [[f64; 2]; 3] {
        self.triangles[k].map(|v| {
            let [x, _, z] = self.vertices[v as usize];
            [x, z]
        })
    }
}

/// The largest angle (rad, as its sine) between the triangles around a vertex taken as one
/// plane. A kink below it, skipped, lets a flat base sink at most 10⁻⁶ of a triangle's size
/// into the rock there: within the gap of 10⁻⁶ of the block's size and the angle of 10⁻⁶ rad
/// within which the base lies flush on its rock (`geometry/contact/patch.rs`), for triangles
/// smaller than the block. A surface written with nine decimals of a metre has kinks of
/// round-off's size up to about 10⁻⁹ / its cell; one written to the millimetre, up to 10⁻³ / its
/// cell, which this does not take for flat (its vertices stay touches, as before).
const FLAT: f64 = 1e-6;

/// Which corners of each triangle are flat: by position (the corners' exact coordinates, so a
/// surface given triangle by triangle is seen as one), a vertex whose triangles close a fan
/// around it (each other corner of them met twice) and whose triangles' normals agree to
/// [`FLAT`] radians. The ground is linear around such a vertex, so a flat base never touches
/// there first (`derivations/13-base-contact.md` §2). A vertex whose coordinates differ by
/// round-off from triangle to triangle is not recognised, and stays a touch as before (only a
/// cost).
fn find_flat_corners(
    vertices: &[[f64; 3]],
    triangles: &[[u32; 3]],
    faces: &[Plane],
) -> Vec<[bool; 3]> {
    use std::collections::HashMap;
    let key = |v: u32| vertices[v as usize].map(f64::to_bits);
    let mut around: HashMap<[u64; 3], Vec<(usize, usize)>> = HashMap::new();
    for (k, t) in triangles.iter().enumerate() {
        for (j, &v) in t.iter().enumerate() {
            around.entry(key(v)).or_default().push((k, j));
        }
    }
    let mut flat = vec![[false; 3]; triangles.len()];
    for fan in around.values() {
        let n = faces[fan[0].0].normal();
        let bent = |k: usize| {
            let m = faces[k].normal();
            m.dot(&n) <= 0.0 || m.cross(&n).norm() > FLAT
        };
        if fan.len() < 3 || fan.iter().any(|&(k, _)| bent(k)) {
            continue;
        }
        let mut others: HashMap<[u64; 3], usize> = HashMap::new();
        for &(k, j) in fan {
            for o in [(j + 1) % 3, (j + 2) % 3] {
                *others.entry(key(triangles[k][o])).or_default() += 1;
            }
        }
        if others.values().all(|&c| c == 2) {
            for &(k, j) in fan {
                flat[k][j] = true;
            }
        }
    }
    flat
}

/// The plan extent of a triangle's corners.
fn extent(c: &[[f64; 2]; 3]) -> ([f64; 2], [f64; 2]) {
    let lo = [
        c[0][0].min(c[1][0]).min(c[2][0]),
        c[0][1].min(c[1][1]).min(c[2][1]),
    ];
    let hi = [
        c[0][0].max(c[1][0]).max(c[2][0]),
        c[0][1].max(c[1][1]).max(c[2][1]),
    ];
    (lo, hi)
}

/// The squared plan distance (m²) from `point` to the triangle with plan corners `c`: 0 inside.
fn distance_2(c: &[[f64; 2]; 3], point: &[f64; 2]) -> f64 {
    if contains_point(c, point) {
        return 0.0;
    }
    // To the nearest edge.
    (0..3)
        .map(|k| segment_distance_2(c[k], c[(k + 1) % 3], *point))
        .fold(f64::INFINITY, f64::min)
}

/// Whether the triangle with plan corners `c` holds `point`.
fn contains_point(c: &[[f64; 2]; 3], point: &[f64; 2]) -> bool {
    let [a, b, c] = *c;
    let cross = |p: [f64; 2], q: [f64; 2]| {
        (q[0] - p[0]) * (point[1] - p[1]) - (q[1] - p[1]) * (point[0] - p[0])
    };
    let (d1, d2, d3) = (cross(a, b), cross(b, c), cross(c, a));
    // A point on a shared edge or corner, within round-off, is in both triangles: the
    // surface has no cracks of rounding (its corners' coordinates differ in the last bits).
    let side2 = |p: [f64; 2], q: [f64; 2]| (q[0] - p[0]).powi(2) + (q[1] - p[1]).powi(2);
    let eps = 1e-12 * side2(a, b).max(side2(b, c)).max(side2(c, a));
    let neg = d1 < -eps || d2 < -eps || d3 < -eps;
    let pos = d1 > eps || d2 > eps || d3 > eps;
    !(neg && pos)
}

/// The squared plan distance (m²) from `q` to the segment from `a` to `b`.
pub fn segment_distance_2(a: [f64; 2], b: [f64; 2], q: [f64; 2]) -> f64 {
    let (dx, dz) = (b[0] - a[0], b[1] - a[1]);
    let len2 = dx * dx + dz * dz;
    let t = if len2 > 0.0 {
        (((q[0] - a[0]) * dx + (q[1] - a[1]) * dz) / len2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    (a[0] + t * dx - q[0]).powi(2) + (a[1] + t * dz - q[1]).powi(2)
}

/// Why a triangle cannot be a face.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum SurfaceError {
    /// No triangles at all.
    #[error("the surface has no triangles (an OBJ file gives them as `f` lines of vertex numbers)")]
    Empty,
    /// A triangle (its number) with a corner not a finite number.
    #[error("triangle {0} has a corner that is not a finite number")]
    NonFinite(usize),
    /// A triangle (its number) with no area.
    #[error("triangle {0} has no area (its corners are on one line)")]
    Degenerate(usize),
    /// A triangle (its number) so large that its normal overflows.
    #[error("triangle {0} is too large to compute with (its sides' products overflow)")]
    TooLarge(usize),
    /// More triangles than a surface may have: the most it may have.
    #[error("the surface has more than {0} triangles")]
    TooMany(usize),
    /// A triangle (its number) naming a corner (numbered from 0) that is not among the
    /// `count` corners.
    #[error("triangle {triangle} names corner {corner}, of {count} (numbered from 0)")]
    NoCorner {
        /// The triangle's number.
        triangle: usize,
        /// The corner it names.
        corner: u32,
        /// How many corners there are.
        count: usize,
    },
    /// A triangle that is vertical or overhangs: no ground a block slides on.
    #[error("triangle {index} is vertical or overhangs (its normal's Y part is {normal_y:.3e})")]
    Vertical {
        /// Its number.
        index: usize,
        /// Its upward normal's Y part.
        normal_y: f64,
    },
}

impl SurfaceError {
    /// The triangle (its number, from 0) the fault is of, if it is one triangle's: a file's
    /// reader then names the line the triangle came from.
    pub fn triangle(&self) -> Option<usize> {
        match *self {
            SurfaceError::NonFinite(k)
            | SurfaceError::Degenerate(k)
            | SurfaceError::TooLarge(k) => Some(k),
            SurfaceError::NoCorner { triangle, .. } => Some(triangle),
            SurfaceError::Vertical { index, .. } => Some(index),
            SurfaceError::Empty | SurfaceError::TooMany(_) => None,
        }
    }
}

impl Ground {
    /// A ground of planes (at least one).
    pub fn planes(faces: Vec<Plane>) -> Ground {
        assert!(!faces.is_empty(), "a ground has at least one face");
        Ground {
            faces,
            kind: Kind::Planes,
            rock: OnceLock::new(),
            flat: OnceLock::new(),
        }
    }

    /// A triangulated surface from its triangles' corners (X, Y, Z), each triangle's its own:
    /// [`Ground::mesh`] with no corner shared.
    pub fn surface(triangles: &[[[f64; 3]; 3]]) -> Result<Ground, SurfaceError> {
        // Every corner numbered by a `u32`.
        let most = u32::MAX as usize / 3;
        if triangles.len() > most {
            return Err(SurfaceError::TooMany(most));
        }
        let vertices = triangles.iter().flatten().copied().collect();
        let indices = (0..triangles.len() as u32)
            .map(|k| [3 * k, 3 * k + 1, 3 * k + 2])
            .collect();
        Ground::mesh(vertices, indices)
    }

    /// A triangulated surface from its corners (X, Y, Z) and its triangles, each by the
    /// numbers of its three corners (from 0), both kept as they are (the spare capacity given
    /// back). Each triangle must name corners there are, have finite corners and an area, and
    /// face up: a normal whose Y part is at least 1e-6 (so a dip below 90°; either winding is
    /// taken). Corners no triangle names are kept and not checked.
    pub fn mesh(
        mut vertices: Vec<[f64; 3]>,
        mut triangles: Vec<[u32; 3]>,
    ) -> Result<Ground, SurfaceError> {
        if triangles.is_empty() {
            return Err(SurfaceError::Empty);
        }
        if triangles.len() > plan_tree::MAX_ITEMS {
            return Err(SurfaceError::TooMany(plan_tree::MAX_ITEMS));
        }
        let mut faces = Vec::with_capacity(triangles.len());
        for (index, t) in triangles.iter().enumerate() {
            let mut p = [Vector3::zeros(); 3];
            for (p, &corner) in p.iter_mut().zip(t) {
                let Some(&[x, y, z]) = vertices.get(corner as usize) else {
                    return Err(SurfaceError::NoCorner {
                        triangle: index,
                        corner,
                        count: vertices.len(),
                    });
                };
                *p = Vector3::new(x, y, z);
            }
            if p.iter().any(|c| c.iter().any(|v| !v.is_finite())) {
                return Err(SurfaceError::NonFinite(index));
            }
            let n = (p[1] - p[0]).cross(&(p[2] - p[0]));
            let size = (p[1] - p[0]).norm().max((p[2] - p[0]).norm());
            if !(n.norm() * size).is_finite() {
                return Err(SurfaceError::TooLarge(index));
            }
            let has_area = n.norm() > 1e-12 * size * size;
            if !has_area {
                return Err(SurfaceError::Degenerate(index));
            }
            let n = if n.y < 0.0 { -n } else { n }.normalize();
            if n.y < 1e-6 {
                return Err(SurfaceError::Vertical {
                    index,
                    normal_y: n.y,
                });
            }
            faces.push(Plane::through(n, p[0]));
        }
        vertices.shrink_to_fit();
        triangles.shrink_to_fit();
        let plan = |k: usize| {
            triangles[k].map(|v| {
                let [x, _, z] = vertices[v as usize];
                [x, z]
            })
        };
        // Placed along the curve by the sum of its corners (three times its centroid).
        let tree = PlanTree::new(
            triangles.len(),
            |k| {
                let [a, b, c] = plan(k);
                [a[0] + b[0] + c[0], a[1] + b[1] + c[1]]
            },
            |k| {
                let (lo, hi) = extent(&plan(k));
                outward(lo, hi)
            },
        );
        Ok(Ground {
            faces,
            kind: Kind::Surface(Mesh {
                vertices,
                triangles,
                tree,
            }),
            rock: OnceLock::new(),
            flat: OnceLock::new(),
        })
    }

    /// Every face, in its number's order.
    pub fn faces(&self) -> &[Plane] {
        &self.faces
    }

    /// The same ground in the collision library's shapes, for checks independent of this
    /// type's own geometry (built on the first call, then shared by every clone made after).
    pub fn rock(&self) -> &Rock {
        self.rock.get_or_init(|| {
            Arc::new(match &self.kind {
                Kind::Planes => Rock::planes(&self.faces),
                Kind::Surface(mesh) => Rock::surface(
                    self.faces
                        .iter()
                        .enumerate()
                        .map(|(k, plane)| mesh.corners(k).map(|[x, z]| [x, plane.height(x, z), z])),
                ),
            })
        })
    }

    /// Whether the ground is a triangulated surface (else a list of planes).
    pub fn is_surface(&self) -> bool {
        matches!(self.kind, Kind::Surface(_))
    }

    /// The face the ground is made of over (X, Z) and its height there: the highest plane, or
    /// the highest triangle over the point; `None` off a surface.
    pub fn top(&self, x: f64, z: f64) -> Option<(usize, f64)> {
        // Of faces equally high, the first by number, whatever order they come in.
        let highest = |best: Option<(usize, f64)>, k: usize| {
            let h = self.faces[k].height(x, z);
            match best {
                Some((j, b)) if b > h || (b == h && j < k) => best,
                _ => Some((k, h)),
            }
        };
        match &self.kind {
            Kind::Planes => (0..self.faces.len()).fold(None, highest),
            Kind::Surface(_) => self.holding(x, z, 0.0).fold(None, highest),
        }
    }

    /// The face a contact at (X, Z) rests on: the face of the ground there; where several
    /// meet within `tol` (m) (a crease or an edge), the one that rises highest a step `step` (m)
    /// along the horizontal direction `dir`, then across it (+90°), then the first. `None` off
    /// a surface.
    pub fn face_under(
        &self,
        x: f64,
        z: f64,
        dir: (f64, f64),
        step: f64,
        tol: f64,
    ) -> Option<usize> {
        let (_, top) = self.top(x, z)?;
        let tied: Vec<usize> = self
            .faces_near(x, z, tol)
            .into_iter()
            .filter(|&k| (self.faces[k].height(x, z) - top).abs() <= tol)
            .collect();
        let ahead = |k: usize, (a, b): (f64, f64)| self.faces[k].height(x + step * a, z + step * b);
        let mut best = *tied.first()?;
        for &k in &tied[1..] {
            let (hk, hb) = (ahead(k, dir), ahead(best, dir));
            let across = (-dir.1, dir.0);
            if hk > hb + tol || (hk >= hb - tol && ahead(k, across) > ahead(best, across) + tol) {
                best = k;
            }
        }
        Some(best)
    }

    /// The faces that may be the ground within `tol` (m, in plan) of (X, Z): every plane, or
    /// the triangles within `tol` of the point (more than one at an edge or a corner), in
    /// ascending order.
    pub fn faces_near(&self, x: f64, z: f64, tol: f64) -> Vec<usize> {
        match &self.kind {
            Kind::Planes => (0..self.faces.len()).collect(),
            Kind::Surface(_) => {
                let mut v: Vec<usize> = self.holding(x, z, tol).collect();
                v.sort_unstable();
                v
            }
        }
    }

    /// The triangles of a surface within `tol` (m, in plan) of (X, Z), nearest first, each
    /// with its distance (0 for one the point is in); every plane, at distance 0, for a ground
    /// of planes.
    pub fn faces_by_distance(&self, x: f64, z: f64, tol: f64) -> Vec<(usize, f64)> {
        match &self.kind {
            Kind::Planes => (0..self.faces.len()).map(|k| (k, 0.0)).collect(),
            Kind::Surface(mesh) => {
                let mut v: Vec<(usize, f64)> = self
                    .holding(x, z, tol)
                    .map(|k| (k, distance_2(&mesh.corners(k), &[x, z]).sqrt()))
                    .collect();
                v.sort_unstable_by(|a, b| a.1.total_cmp(&b.1).then(a.0.cmp(&b.0)));
                v
            }
        }
    }

    /// Every face in a plan rectangle (for drawing): all planes, or the triangles whose extent
    /// meets it.
    pub fn faces_in(&self, (x0, x1, z0, z1): (f64, f64, f64, f64)) -> Vec<usize> {
        match &self.kind {
            Kind::Planes => (0..self.faces.len()).collect(),
            Kind::Surface(mesh) => {
                let meets = |k: &usize| {
                    let (lo, hi) = extent(&mesh.corners(*k));
                    lo[0] <= x1.max(x0)
                        && hi[0] >= x0.min(x1)
                        && lo[1] <= z1.max(z0)
                        && hi[1] >= z0.min(z1)
                };
                let mut v: Vec<usize> = mesh
                    .tree
                    .search(outward([x0.min(x1), z0.min(z1)], [x0.max(x1), z0.max(z1)]))
                    .filter(meets)
                    .collect();
                v.sort_unstable();
                v
            }
        }
    }

    /// The surface's triangles within `tol` (m, in plan) of (X, Z), 0 for those that hold it:
    /// the tree's cells whose extent reaches that far, then each triangle's exact distance.
    /// None for a ground of planes.
    fn holding(&self, x: f64, z: f64, tol: f64) -> impl Iterator<Item = usize> + '_ {
        let mesh = match &self.kind {
            Kind::Surface(mesh) => Some(mesh),
            Kind::Planes => None,
        };
        let reach = outward([x - tol, z - tol], [x + tol, z + tol]);
        mesh.into_iter().flat_map(move |mesh| {
            mesh.tree.search(reach).filter(move |&k| {
                let c = &mesh.corners(k);
                if tol > 0.0 {
                    distance_2(c, &[x, z]) <= tol * tol
                } else {
                    contains_point(c, &[x, z])
                }
            })
        })
    }

    /// Which corners of surface triangle `k` are flat (inside the surface, its triangles all in
    /// one plane, within 10⁻⁶ rad); none for a plane. The first call finds every triangle's.
    pub fn flat_corners(&self, k: usize) -> [bool; 3] {
        match &self.kind {
            Kind::Planes => [false; 3],
            Kind::Surface(mesh) => self
                .flat
                .get_or_init(|| find_flat_corners(&mesh.vertices, &mesh.triangles, &self.faces))
                .get(k)
                .copied()
                .unwrap_or([false; 3]),
        }
    }

    /// The plan corners of surface triangle `k` (none for a plane).
    pub fn triangle(&self, k: usize) -> Option<[[f64; 2]; 3]> {
        match &self.kind {
            Kind::Planes => None,
            Kind::Surface(mesh) => (k < mesh.triangles.len()).then(|| mesh.corners(k)),
        }
    }
}

impl PartialEq for Ground {
    fn eq(&self, other: &Ground) -> bool {
        self.faces == other.faces && self.is_surface() == other.is_surface()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    /// A 4 × 4 grid of vertices 1 m apart at heights `y(i, j)`, two triangles a cell.
    fn heights(y: impl Fn(usize, usize) -> f64) -> Ground {
        let vertices = (0..16).map(|k| [(k / 4) as f64, y(k / 4, k % 4), (k % 4) as f64]);
        let mut triangles = Vec::new();
        for i in 0..3u32 {
            for j in 0..3u32 {
                let (a, b, c, d) = (
                    4 * i + j,
                    4 * (i + 1) + j,
                    4 * (i + 1) + j + 1,
                    4 * i + j + 1,
                );
                triangles.extend([[a, b, c], [a, c, d]]);
            }
        }
        Ground::mesh(vertices.collect(), triangles).unwrap()
    }

    /// The vertices (by grid number) that some triangle has as a flat corner.
    fn flat_vertices(g: &Ground) -> Vec<usize> {
        let Kind::Surface(mesh) = &g.kind else {
            panic!("a surface")
        };
        let mut flat: Vec<usize> = (0..mesh.triangles.len())
            .flat_map(|k| {
                (0..3)
                    .filter(move |&j| g.flat_corners(k)[j])
                    .map(move |j| (k, j))
            })
            .map(|(k, j)| mesh.triangles[k][j] as usize)
            .collect();
        flat.sort_unstable();
        flat.dedup();
        flat
    }

    #[test]
    fn a_vertex_inside_one_plane_of_the_rock_is_flat_and_no_other() {
        // A tilted plane: the four inner vertices are flat, none on the border (their fans
        // do not close).
        let tilted = heights(|i, j| 0.3 * i as f64 - 0.1 * j as f64);
        assert_eq!(flat_vertices(&tilted), [5, 6, 9, 10]);
        // The corner vertex 0 raised by 10⁻⁴ m: a kink in the two triangles through it, which
        // vertex 5's fan holds; 6, 9 and 10 keep a plane around them.
        let raised = |h: f64| heights(move |i, j| if (i, j) == (0, 0) { h } else { 0.0 });
        assert_eq!(flat_vertices(&raised(1e-4)), [6, 9, 10]);
        // A kink of round-off's size is still flat; one over 10⁻⁶ rad is not.
        assert_eq!(flat_vertices(&raised(1e-9)), [5, 6, 9, 10]);
        assert_eq!(flat_vertices(&raised(1e-5)), [6, 9, 10]);
        // The inner vertex 5 raised: every inner fan holds a triangle through it.
        let bent = heights(|i, j| if (i, j) == (1, 1) { 1e-4 } else { 0.0 });
        assert!(flat_vertices(&bent).is_empty());
        // Planes have no corners.
        assert!(!papers().flat_corners(0)[0]);
    }

    /// The paper's three planes as faces (`docs/conventions.md`).
    fn papers() -> Ground {
        let (xi, zeta, kappa) = (20f64.to_radians(), 25f64.to_radians(), 30f64.to_radians());
        Ground::planes(vec![
            Plane::from_dip(0.0, 0.0, Vector3::zeros()),
            Plane::from_dip(xi, PI, Vector3::new(4.0, 0.0, 0.0)),
            Plane::from_dip(zeta, PI - kappa, Vector3::new(4.0, 0.0, -5.0)),
        ])
    }

    #[test]
    fn a_triangle_whose_normal_overflows_is_refused_as_too_large_not_as_vertical() {
        let big = 1e150;
        let t = [[-big, 0.0, -big], [big, 0.0, -big], [big, 0.0, big]];
        assert_eq!(
            Ground::surface(&[t]).unwrap_err(),
            SurfaceError::TooLarge(0)
        );
    }

    #[test]
    fn the_ground_of_planes_is_the_highest_face() {
        let g = papers();
        assert_eq!(g.top(-6.0, 5.0), Some((0, 0.0)));
        let (k, h) = g.top(6.0, 5.0).unwrap();
        assert_eq!(k, 1);
        assert!((h - 2.0 * 20f64.to_radians().tan()).abs() < 1e-12);
    }

    #[test]
    fn a_contact_on_a_crease_takes_the_face_that_rises_first_along_the_push() {
        // The paper's contacts: 0 on the level face, 1 on plane 1's strike (plane 1 rises along
        // +X), 2 where the level face and both planes meet (plane 2 rises faster along +X).
        let g = papers();
        let under = |x: f64, z: f64| g.face_under(x, z, (1.0, 0.0), 1e-2, 1e-9).unwrap();
        assert_eq!(under(-6.0, 5.0), 0);
        assert_eq!(under(4.0, 5.0), 1);
        assert_eq!(under(4.0, -5.0), 2);
    }

    #[test]
    fn a_point_on_a_shared_edge_is_on_the_surface_despite_round_off() {
        // Two triangles sharing the edge from (0.1, 0.3) to (0.7, 1.9) in plan: points along it,
        // computed in floating point, fall a last bit to either side of it.
        let (a, b) = ([0.1, 0.0, 0.3], [0.7, 0.0, 1.9]);
        let g = Ground::surface(&[[a, b, [-1.0, 0.0, 1.0]], [a, [2.0, 0.0, 0.5], b]]).unwrap();
        for k in 0..=1000 {
            let t = k as f64 / 1000.0;
            let (x, z) = (a[0] + t * (b[0] - a[0]), a[2] + t * (b[2] - a[2]));
            assert!(g.top(x, z).is_some(), "t = {t}");
            assert_eq!(g.faces_near(x, z, 1e-9).len(), 2, "t = {t}");
        }
        // Off the surface a little more than round-off is off it.
        assert!(g.top(a[0] - 1e-6, a[2] - 1e-6).is_none());
    }

    #[test]
    fn the_faces_near_a_point_are_every_plane_or_the_triangles_within_reach() {
        assert_eq!(papers().faces_near(100.0, 100.0, 0.0), [0, 1, 2]);
        let g = roof();
        assert_eq!(g.faces_near(0.2, 0.5, 1e-9), [0]);
        assert_eq!(g.faces_near(0.5, 0.5, 1e-9), [0, 1]);
        assert_eq!(g.faces_near(1.0, 0.5, 1e-9), [1, 3]);
        assert_eq!(g.faces_near(1.5, 0.2, 0.6), [0, 1, 2, 3]);
        assert!(g.faces_near(5.0, 5.0, 1.0).is_empty());
        // Nearest first: (1.2, 0.5) is in triangle 3 ((1, 0), (2, 1), (1, 1)), 0.2 from
        // triangle 1 across the ridge, 0.3/√2 from triangle 2 across the diagonal.
        let by = g.faces_by_distance(1.2, 0.5, 0.25);
        let order: Vec<usize> = by.iter().map(|&(k, _)| k).collect();
        assert_eq!(order, [3, 1, 2]);
        assert_eq!(by[0].1, 0.0);
        assert!((by[1].1 - 0.2).abs() < 1e-12 && (by[2].1 - 0.3 / 2f64.sqrt()).abs() < 1e-12);
    }

    /// A ridge roof of two triangles over [0, 2] × [0, 1], the ridge along X = 1 at Y = 1.
    fn roof() -> Ground {
        Ground::surface(&[
            [[0.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 0.0, 1.0]],
            [[0.0, 0.0, 1.0], [1.0, 1.0, 0.0], [1.0, 1.0, 1.0]],
            [[1.0, 1.0, 0.0], [2.0, 0.0, 0.0], [2.0, 0.0, 1.0]],
            [[1.0, 1.0, 0.0], [2.0, 0.0, 1.0], [1.0, 1.0, 1.0]],
        ])
        .unwrap()
    }

    #[test]
    fn a_surface_is_the_triangle_over_the_point_and_nothing_off_it() {
        let g = roof();
        let (k, h) = g.top(0.5, 0.2).unwrap();
        assert!(k < 2 && (h - 0.5).abs() < 1e-15);
        let (k, h) = g.top(1.5, 0.7).unwrap();
        assert!(k >= 2 && (h - 0.5).abs() < 1e-15);
        assert_eq!(g.top(2.5, 0.5), None);
        assert_eq!(g.top(1.0, -0.1), None);
        // Ridges are allowed: the two sides' planes cross above the ground there.
        assert!(g.faces()[0].height(1.5, 0.5) > 0.5);
    }

    #[test]
    fn bad_triangles_are_named() {
        let flat = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]];
        let line = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [2.0, 0.0, 0.0]];
        let wall = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];
        let nan = [[0.0, f64::NAN, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]];
        assert_eq!(
            Ground::surface(&[flat, line]).unwrap_err(),
            SurfaceError::Degenerate(1)
        );
        assert!(matches!(
            Ground::surface(&[wall]).unwrap_err(),
            SurfaceError::Vertical { index: 0, .. }
        ));
        assert_eq!(
            Ground::surface(&[nan]).unwrap_err(),
            SurfaceError::NonFinite(0)
        );
        assert_eq!(Ground::surface(&[]).unwrap_err(), SurfaceError::Empty);
    }

    #[test]
    fn the_spatial_index_finds_the_same_face_as_a_scan() {
        // A 40 × 40 grid of 3200 triangles on a rough surface.
        let n = 40;
        let height = |i: usize, j: usize| ((i * 7 + j * 13) % 11) as f64 * 0.05;
        let mut tris = Vec::new();
        for i in 0..n {
            for j in 0..n {
                let c = |a: usize, b: usize| [a as f64, height(a, b), b as f64];
                tris.push([c(i, j), c(i + 1, j), c(i + 1, j + 1)]);
                tris.push([c(i, j), c(i + 1, j + 1), c(i, j + 1)]);
            }
        }
        let g = Ground::surface(&tris).unwrap();
        let mut seed = 12345u64;
        for _ in 0..500 {
            seed = seed
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            let x = (seed >> 11) as f64 / (1u64 << 53) as f64 * n as f64;
            seed = seed
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            let z = (seed >> 11) as f64 / (1u64 << 53) as f64 * n as f64;
            let (_, h) = g.top(x, z).unwrap();
            let scan = (0..tris.len())
                .filter(|&k| contains_point(&tris[k].map(|c| [c[0], c[2]]), &[x, z]))
                .map(|k| g.faces()[k].height(x, z))
                .fold(f64::NEG_INFINITY, f64::max);
            assert!((h - scan).abs() < 1e-12, "{h} vs {scan}");
        }
    }

    /// A grid of `n` × `n` cells of rough ground, two triangles a cell, over [0, n]² about
    /// `origin`: its corners, each once, and its triangles by their corners' numbers.
    fn grid(n: usize, origin: f64) -> (Vec<[f64; 3]>, Vec<[u32; 3]>) {
        let height = |i: usize, j: usize| ((i * 7 + j * 13) % 11) as f64 * 0.05;
        let vertices = (0..=n)
            .flat_map(|i| {
                (0..=n).map(move |j| [origin + i as f64, height(i, j), origin + j as f64])
            })
            .collect();
        let at = |i: usize, j: usize| (i * (n + 1) + j) as u32;
        let triangles = (0..n)
            .flat_map(|i| {
                (0..n).flat_map(move |j| {
                    [
                        [at(i, j), at(i + 1, j), at(i + 1, j + 1)],
                        [at(i, j), at(i + 1, j + 1), at(i, j + 1)],
                    ]
                })
            })
            .collect();
        (vertices, triangles)
    }

    #[test]
    fn a_surface_keeps_each_corner_once_and_under_eighty_bytes_a_triangle() {
        // docs/performance.md, "Foundations of faces": a corner is 24 bytes, shared by six
        // triangles on a grid; a triangle is its corners' numbers (12), its plane (32) and
        // about 21 bytes of the tree; nothing spare is kept.
        assert_eq!(std::mem::size_of::<[u32; 3]>(), 12);
        assert_eq!(std::mem::size_of::<Plane>(), 32);
        let (mut vertices, mut triangles) = grid(100, 0.0);
        vertices.reserve(1000);
        triangles.reserve(1000);
        let (n, corners) = (triangles.len(), vertices.len());
        let g = Ground::mesh(vertices, triangles).unwrap();
        let Kind::Surface(mesh) = &g.kind else {
            panic!("a surface")
        };
        assert_eq!(mesh.vertices.capacity(), corners);
        assert_eq!(mesh.triangles.capacity(), n);
        assert_eq!(g.faces.capacity(), n);
        let bytes = corners * 24 + n * 12 + n * 32 + mesh.tree.bytes();
        assert!(
            bytes < 80 * n,
            "{} bytes a triangle",
            bytes as f64 / n as f64
        );
    }

    #[test]
    fn a_surface_of_shared_corners_is_the_surface_of_the_same_triangles_each_with_its_own() {
        let (vertices, triangles) = grid(12, -3.0);
        let own: Vec<[[f64; 3]; 3]> = triangles
            .iter()
            .map(|t| t.map(|k| vertices[k as usize]))
            .collect();
        let (shared, apart) = (
            Ground::mesh(vertices, triangles).unwrap(),
            Ground::surface(&own).unwrap(),
        );
        assert_eq!(shared, apart);
        for k in 0..own.len() {
            assert_eq!(shared.triangle(k), apart.triangle(k));
        }
        assert_eq!(shared.triangle(own.len()), None);
        for (x, z) in [(0.3, 0.7), (-3.0, -3.0), (4.5, 2.25), (8.9, 8.99)] {
            assert_eq!(shared.top(x, z), apart.top(x, z));
            assert_eq!(
                shared.faces_by_distance(x, z, 0.6),
                apart.faces_by_distance(x, z, 0.6)
            );
        }
    }

    #[test]
    fn a_triangle_naming_a_corner_there_is_not_is_refused() {
        let (vertices, mut triangles) = grid(2, 0.0);
        triangles[5][2] = 9;
        assert_eq!(
            Ground::mesh(vertices, triangles).unwrap_err(),
            SurfaceError::NoCorner {
                triangle: 5,
                corner: 9,
                count: 9
            }
        );
    }

    #[test]
    fn of_triangles_equally_high_over_a_point_the_top_is_the_first_by_number() {
        // Level ground: at a corner six triangles meet, all at height 0; along a diagonal two.
        let (vertices, triangles) = grid(4, 0.0);
        let level = vertices.iter().map(|v| [v[0], 0.0, v[2]]).collect();
        let g = Ground::mesh(level, triangles).unwrap();
        for (x, z) in [(2.0, 2.0), (1.0, 3.0), (2.5, 2.5), (0.0, 0.0), (4.0, 4.0)] {
            let first = g.faces_near(x, z, 0.0)[0];
            assert_eq!(g.top(x, z), Some((first, 0.0)), "({x}, {z})");
        }
    }

    #[test]
    fn the_triangles_near_a_point_are_those_a_scan_of_every_triangle_finds() {
        // The tree holds each triangle's extent in single precision, rounded outwards; the
        // triangles it gives near a point, and their distances, must be a scan's of the exact
        // corners, however near an edge or far from the origin the point is.
        let (n, far) = (30, 1.0e5);
        let mut tris = Vec::new();
        for i in 0..n {
            for j in 0..n {
                let c = |a: usize, b: usize| {
                    let (x, z) = (far + a as f64 * 0.7, -far + b as f64 * 0.7);
                    [x, 0.01 * ((a * 3 + b * 5) % 7) as f64, z]
                };
                tris.push([c(i, j), c(i + 1, j), c(i + 1, j + 1)]);
                tris.push([c(i, j), c(i + 1, j + 1), c(i, j + 1)]);
            }
        }
        let g = Ground::surface(&tris).unwrap();
        let plan: Vec<[[f64; 2]; 3]> = tris.iter().map(|t| t.map(|c| [c[0], c[2]])).collect();
        let mut seed = 99u64;
        let mut next = || {
            seed = seed
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (seed >> 11) as f64 / (1u64 << 53) as f64
        };
        for k in 0..400 {
            // Points on a grid line (an edge) every other time.
            let mut x = far + next() * 0.7 * n as f64;
            let z = -far + next() * 0.7 * n as f64;
            if k % 2 == 0 {
                x = far + (x - far).round().min(0.7 * n as f64 - 0.7) / 0.7 * 0.7;
            }
            let tol = [0.0, 1e-9, 0.05, 0.9][k % 4];
            let near: Vec<usize> = (0..plan.len())
                .filter(|&t| distance_2(&plan[t], &[x, z]) <= tol * tol)
                .collect();
            assert_eq!(g.faces_near(x, z, tol), near, "at ({x}, {z}), tol {tol}");
            let mut by = g.faces_by_distance(x, z, tol);
            by.sort_unstable_by_key(|p| p.0);
            assert_eq!(by.iter().map(|p| p.0).collect::<Vec<_>>(), near);
            for (t, d) in by {
                assert_eq!(d, distance_2(&plan[t], &[x, z]).sqrt());
            }
            let holding: Vec<usize> = (0..plan.len())
                .filter(|&t| contains_point(&plan[t], &[x, z]))
                .collect();
            assert_eq!(g.top(x, z).is_some(), !holding.is_empty());
        }
        // A rectangle's faces are those whose extent meets it, as a scan finds them.
        let r = (far + 3.0, far + 5.2, -far + 1.0, -far + 1.4);
        let meets: Vec<usize> = (0..plan.len())
            .filter(|&t| {
                let (lo, hi) = extent(&plan[t]);
                lo[0] <= r.1 && hi[0] >= r.0 && lo[1] <= r.3 && hi[1] >= r.2
            })
            .collect();
        assert_eq!(g.faces_in(r), meets);
    }
}
