//! A body's quadrature (`derivations/13-base-contact.md` §9): where its base, lying flush on its
//! rock, presses and rubs — over a flat base's area and along its edges (the model's rule for
//! a base, `Base::quadrature`), or over a cast base's relief's faces.

use crate::geometry::Relief;
use crate::geometry::contact::Quadrature;
use crate::model::{Base, triangle_quadrature};
use nalgebra::Vector3;

/// Each triangle of the base cut into this many squared for its quadrature (three points each).
const AREA_SPLIT: usize = 2;

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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::contact::{Bed, Patch, Spot, reduce};
    use crate::geometry::{BodyPose, Footprint, Ground, Plane, touches};
    use nalgebra::{Matrix3, Rotation3};

    /// A 4 m square base, its CM 1 m above it, at `pose` on level rock: its patches.
    fn patches_on_level(pose: BodyPose) -> Vec<Patch> {
        let base = Base::rectangle([-2.0, 2.0], [-2.0, 2.0], 1.0).unwrap();
        let ground = Ground::planes(vec![Plane::through(Vector3::y(), Vector3::zeros())]);
        let quadrature = Quadrature::of(&base);
        let footprint = Footprint {
            outline: base.outline(),
            depth: base.depth(),
        };
        let found = touches(&ground, footprint, &pose, 1e-3, 0.0);
        let bed = Bed {
            ground: &ground,
            quadrature: &quadrature,
            size: base.size(),
        };
        reduce(&bed, &pose, found).patches
    }

    #[test]
    fn a_base_lying_on_level_rock_presses_over_its_whole_area() {
        let parts = patches_on_level(BodyPose {
            cm: Vector3::new(3.0, 1.0, -1.0),
            rotation: Matrix3::identity(),
        });
        assert_eq!(parts.len(), 1);
        let patch = &parts[0];
        assert_eq!(patch.members.len(), 4);
        assert_eq!(patch.points.len(), 24);
        let area: f64 = patch.points.iter().map(|p| p.weight).sum();
        assert!((area - 16.0).abs() < 1e-12);
        assert!(patch.points.iter().all(|p| p.face == 0));
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
        let parts = patches_on_level(pose);
        assert_eq!(parts.len(), 1, "{parts:?}");
        assert_eq!(parts[0].members.len(), 2);
        assert!(
            parts[0]
                .points
                .iter()
                .all(|p| matches!(p.spot, Spot::Edge(1, _)))
        );
        let length: f64 = parts[0].points.iter().map(|p| p.weight).sum();
        assert!((length - 4.0).abs() < 1e-12, "{length}");
        // Tipped more than the tolerance: nothing lies flush over the area.
        assert!(parts.iter().all(|p| p.points.len() == 5));
    }
}
