//! A plane of the ground, m·P = e with m its unit upward normal (`docs/conventions.md`, "Planes
//! given by dip and dip direction"): what a contact rests on.

use nalgebra::Vector3;

/// A non-vertical plane, m·P = e, m the unit upward normal (m_Y > 0).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Plane {
    normal: Vector3<f64>,
    offset: f64,
}

impl Plane {
    /// The plane of true dip `dip` (rad, in [0, π/2)) whose steepest descent points along the
    /// horizontal direction `dip_direction` (rad, from +X towards +Z), through `point`.
    pub fn from_dip(dip: f64, dip_direction: f64, point: Vector3<f64>) -> Plane {
        let (sd, cd) = dip.sin_cos();
        let (sa, ca) = dip_direction.sin_cos();
        // Descending along (cos a, 0, sin a), the surface's upward normal leans that way.
        let normal = Vector3::new(sd * ca, cd, sd * sa);
        Plane {
            normal,
            offset: normal.dot(&point),
        }
    }

    /// The plane with upward unit normal `normal` through `point`.
    pub fn through(normal: Vector3<f64>, point: Vector3<f64>) -> Plane {
        Plane {
            normal,
            offset: normal.dot(&point),
        }
    }

    /// The unit upward normal m.
    pub fn normal(&self) -> Vector3<f64> {
        self.normal
    }

    /// e of m·P = e (m).
    pub fn offset(&self) -> f64 {
        self.offset
    }

    /// The height of the plane above (X, Z).
    pub fn height(&self, x: f64, z: f64) -> f64 {
        (self.offset - self.normal.x * x - self.normal.z * z) / self.normal.y
    }

    /// How far `p` lies above the plane, along its normal (m; negative: below).
    pub fn signed_distance(&self, p: &Vector3<f64>) -> f64 {
        self.normal.dot(p) - self.offset
    }

    /// Whether `other` is parallel to this plane within `angle` (rad): coplanar faces of a
    /// surface meet in no crease.
    pub fn is_parallel(&self, other: &Plane, angle: f64) -> bool {
        self.normal.cross(&other.normal).norm() <= angle.sin()
    }

    /// The true dip (rad).
    pub fn dip(&self) -> f64 {
        self.normal.y.clamp(-1.0, 1.0).acos()
    }

    /// The direction of steepest descent (rad, from +X towards +Z); 0 for a horizontal plane.
    pub fn dip_direction(&self) -> f64 {
        if self.normal.x == 0.0 && self.normal.z == 0.0 {
            0.0
        } else {
            self.normal.z.atan2(self.normal.x)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn planes_are_parallel_within_the_angle_between_their_normals() {
        let p = Plane::from_dip(0.3, 1.0, Vector3::zeros());
        let q = Plane::from_dip(0.3 + 1e-6, 1.0, Vector3::new(0.0, 5.0, 0.0));
        assert!(p.is_parallel(&q, 2e-6) && !p.is_parallel(&q, 0.5e-6));
        assert!(p.is_parallel(&p, 0.0));
    }

    #[test]
    fn a_plane_descends_along_its_dip_direction_at_its_dip() {
        let dip = 20f64.to_radians();
        for dir_deg in [0.0, 30.0, 150.0, -100.0] {
            let dir = f64::to_radians(dir_deg);
            let p = Plane::from_dip(dip, dir, Vector3::new(1.0, 2.0, -3.0));
            assert!((p.height(1.0, -3.0) - 2.0).abs() < 1e-14);
            // One metre along the dip direction: down by tan(dip).
            let (x, z) = (1.0 + dir.cos(), -3.0 + dir.sin());
            assert!((p.height(x, z) - (2.0 - dip.tan())).abs() < 1e-14);
            // Across it: level.
            let (x, z) = (1.0 - dir.sin(), -3.0 + dir.cos());
            assert!((p.height(x, z) - 2.0).abs() < 1e-14);
            assert!((p.dip() - dip).abs() < 1e-14);
            let back = p.dip_direction() - dir;
            assert!(back.sin().abs() < 1e-14 && back.cos() > 0.0);
            assert!((p.normal().norm() - 1.0).abs() < 1e-15 && p.normal().y > 0.0);
        }
    }

    #[test]
    fn the_papers_planes_have_the_papers_normals() {
        // Plane 1: dip direction 180°; plane 2: 180° − κ (docs/conventions.md).
        let (xi, zeta, kappa) = (20f64.to_radians(), 25f64.to_radians(), 30f64.to_radians());
        let one = Plane::from_dip(xi, std::f64::consts::PI, Vector3::zeros());
        assert!((one.normal() - Vector3::new(-xi.sin(), xi.cos(), 0.0)).norm() < 1e-15);
        let two = Plane::from_dip(zeta, std::f64::consts::PI - kappa, Vector3::zeros());
        let want = Vector3::new(
            -zeta.sin() * kappa.cos(),
            zeta.cos(),
            zeta.sin() * kappa.sin(),
        );
        assert!((two.normal() - want).norm() < 1e-15);
    }
}
