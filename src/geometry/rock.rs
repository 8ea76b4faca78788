//! The ground as a collision library sees it (`parry3d-f64`): the check on our own geometry.
//!
//! The solver finds where base and ground meet with its own exact feature tests
//! (`touch`, `relief`, through the ground's R*-tree); nothing here is used by them. A [`Rock`]
//! is the same ground built once into parry's shapes — a triangle mesh with its own bounding
//! volume hierarchy for a surface, half-spaces for a list of planes — and asked only two
//! things: how high the rock is over a plan point (a vertical ray cast down onto it, the first
//! hit), and how far a triangle is from it. Those answer the independent checks of
//! `derivations/13-base-contact.md` §5: the deepest any point of the base goes into the rock, and
//! that the touches miss nothing.

use super::plane::Plane;
use nalgebra::Vector3;
use parry3d_f64::math::{Pose, Vector};
use parry3d_f64::query::{self, Ray, RayCast};
use parry3d_f64::shape::{HalfSpace, TriMesh, Triangle};

/// How far above a point a ray onto a ground of planes starts (m): planes run on without end,
/// so the ray starts this far over the point asked about; a point deeper than this is reported
/// this deep.
const PLANES_REACH: f64 = 1.0e3;

/// The ground in parry's shapes.
pub struct Rock {
    kind: Kind,
}

enum Kind {
    /// Each plane as the half-space below it, by a point on it.
    Planes(Vec<(HalfSpace, Vector)>),
    /// The surface's triangles as one mesh; rays start `above` (m) over its highest point.
    Surface { mesh: Box<TriMesh>, above: f64 },
}

impl std::fmt::Debug for Rock {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match &self.kind {
            Kind::Planes(p) => write!(f, "Rock({} half-spaces)", p.len()),
            Kind::Surface { mesh, .. } => write!(f, "Rock({} triangles)", mesh.num_triangles()),
        }
    }
}

fn v(p: &Vector3<f64>) -> Vector {
    Vector::new(p.x, p.y, p.z)
}

impl Rock {
    /// A ground of planes: each the half-space below it.
    pub fn planes(faces: &[Plane]) -> Rock {
        let planes = faces
            .iter()
            .map(|p| {
                let n = p.normal();
                (HalfSpace::new(v(&n)), v(&(n * p.offset())))
            })
            .collect();
        Rock {
            kind: Kind::Planes(planes),
        }
    }

    /// A surface of triangles (corners X, Y, Z; at least one with an area, none vertical) as
    /// one mesh.
    pub fn surface(triangles: impl ExactSizeIterator<Item = [[f64; 3]; 3]>) -> Rock {
        let mut vertices = Vec::with_capacity(3 * triangles.len());
        let mut indices = Vec::with_capacity(triangles.len());
        for t in triangles {
            let i = vertices.len() as u32;
            vertices.extend(t.iter().map(|&[x, y, z]| Vector::new(x, y, z)));
            indices.push([i, i + 1, i + 2]);
        }
        let top = vertices
            .iter()
            .map(|p| p.y)
            .fold(f64::NEG_INFINITY, f64::max);
        let low = vertices.iter().map(|p| p.y).fold(f64::INFINITY, f64::min);
        // `Ground::surface` admits only finite triangles of area: the mesh is valid.
        let mesh = TriMesh::new(vertices, indices).expect("a surface's triangles make a mesh");
        Rock {
            kind: Kind::Surface {
                mesh: Box::new(mesh),
                above: top + 1.0 + (top - low),
            },
        }
    }

    /// The height of the rock over plan point (X, Z) (m), found by a ray cast down from above
    /// onto it; over no surveyed ground, `None`. On planes, a rock more than 1 km above `near`
    /// (m, a height) is reported at `near` + 1 km.
    pub fn height(&self, x: f64, z: f64, near: f64) -> Option<f64> {
        let down = Vector::new(0.0, -1.0, 0.0);
        match &self.kind {
            Kind::Surface { mesh, above } => {
                let ray = Ray::new(Vector::new(x, *above, z), down);
                mesh.cast_local_ray(&ray, f64::MAX, false)
                    .map(|t| above - t)
            }
            Kind::Planes(planes) => {
                let start = near + PLANES_REACH;
                planes
                    .iter()
                    .filter_map(|(h, at)| {
                        let ray = Ray::new(Vector::new(x, start, z) - *at, down);
                        h.cast_local_ray(&ray, f64::MAX, true)
                    })
                    .reduce(f64::min)
                    .map(|t| start - t)
            }
        }
    }

    /// The deepest any of `points` (world, m) is below the rock, measured vertically (negative
    /// when every one is above it; points over no ground are skipped, and none at all gives
    /// −∞).
    pub fn deepest(&self, points: impl IntoIterator<Item = Vector3<f64>>) -> f64 {
        points
            .into_iter()
            .filter_map(|q| self.height(q.x, q.z, q.y).map(|h| h - q.y))
            .fold(f64::NEG_INFINITY, f64::max)
    }

    /// The distance (m) from the triangle with corners `t` (world) to the rock's faces: to the
    /// nearest triangle of a surface, or the nearest plane's half-space; zero where it meets
    /// one (parry's intersection within its own tolerance, seen at 1e-7 m on a 10 m base).
    /// A triangle wholly under a surface meets none of its triangles: [`Rock::deepest`] of its
    /// corners tells.
    pub fn distance(&self, t: [Vector3<f64>; 3]) -> f64 {
        let tri = Triangle::new(v(&t[0]), v(&t[1]), v(&t[2]));
        let here = Pose::IDENTITY;
        let to = |at: &Pose, shape: &dyn parry3d_f64::shape::Shape| {
            query::distance(at, shape, &here, &tri).map_or(f64::INFINITY, |d| d.distance)
        };
        match &self.kind {
            Kind::Surface { mesh, .. } => to(&here, mesh.as_ref()),
            Kind::Planes(planes) => planes
                .iter()
                .map(|(h, at)| to(&Pose::from_translation(*at), h))
                .fold(f64::INFINITY, f64::min),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::fixtures::pyramid;

    #[test]
    fn the_rock_of_a_pyramid_is_as_high_as_its_faces_over_every_point_and_absent_off_it() {
        // The peak 1 m over the 4 m square: over (x, z) the height is 1 − max(|x|, |z|)/2.
        let ground = pyramid(1.0);
        let rock = ground.rock();
        for (x, z) in [
            (0.0, 0.0),
            (0.5, -0.25),
            (-1.9, 1.2),
            (1.0, 1.0),
            (0.3, 1.99),
        ] {
            let h = rock.height(x, z, 0.0).unwrap();
            let exact = 1.0 - f64::max(f64::abs(x), f64::abs(z)) / 2.0;
            assert!((h - exact).abs() < 1e-12, "({x}, {z}): {h} against {exact}");
        }
        assert_eq!(rock.height(2.5, 0.0, 0.0), None);
        // A point 0.2 m under the peak is 0.2 m in it; one off the surface is skipped.
        let d = rock.deepest([Vector3::new(0.0, 0.8, 0.0), Vector3::new(9.0, -5.0, 0.0)]);
        assert!((d - 0.2).abs() < 1e-12, "{d}");
    }

    #[test]
    fn the_rock_of_planes_is_the_highest_plane_over_a_point_even_far_above_it() {
        // A level plane at Y = 0 and one rising 30° along +X through the origin.
        let up = Vector3::y();
        let s = 30f64.to_radians();
        let rising = Vector3::new(-s.sin(), s.cos(), 0.0);
        let rock = Rock::planes(&[
            Plane::through(up, Vector3::zeros()),
            Plane::through(rising, Vector3::zeros()),
        ]);
        assert!((rock.height(-3.0, 1.0, 0.0).unwrap() - 0.0).abs() < 1e-12);
        let h = rock.height(3.0, 1.0, 0.0).unwrap();
        assert!((h - 3.0 * s.tan()).abs() < 1e-12, "{h}");
        // Asked from 10 m below the rock, it is still found (the ray starts 1 km over the point).
        let h = rock.height(3.0, 1.0, -10.0).unwrap();
        assert!((h - 3.0 * s.tan()).abs() < 1e-12, "{h}");
    }

    #[test]
    fn a_triangle_over_the_rock_is_as_far_from_it_as_its_lowest_corner_and_meets_it_below() {
        // Over the pyramid's flank rising towards −X at 1/2 (x < 0, |z| < |x|): the triangle's
        // corner (−1, 1, 0) is 0.5 m over the flank, a distance 0.5 · 2/√5 along its normal.
        let ground = pyramid(1.0);
        let rock = ground.rock();
        let t = [
            Vector3::new(-1.0, 1.0, 0.0),
            Vector3::new(-1.5, 2.0, 0.2),
            Vector3::new(-1.2, 2.0, -0.3),
        ];
        let d = rock.distance(t);
        assert!((d - 1.0 / 5f64.sqrt()).abs() < 1e-9, "{d}");
        let sunk = t.map(|c| c - Vector3::new(0.0, 0.6, 0.0));
        assert_eq!(rock.distance(sunk), 0.0);
        // Against planes: a level plane 0.25 m below the lowest corner.
        let flat = Rock::planes(&[Plane::through(Vector3::y(), Vector3::new(0.0, 0.75, 0.0))]);
        assert!((flat.distance(t) - 0.25).abs() < 1e-9);
    }
}
