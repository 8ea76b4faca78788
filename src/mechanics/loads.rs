//! The loads in global coordinates at one pose (`derivations/11-dam-loads.md`).

use super::ContactGeometry;
use crate::geometry::LocalFrame;
use crate::model::{Block, Body, Loads, Tendon};
use nalgebra::Vector3;

/// The loads on the block at one pose (N, N·m; moments about the base point under the CM, the
/// frame's origin). The driving loads (`force`, `moment`) are those the factor of safety
/// scales; the weight and the held loads stay.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Applied {
    /// F·i' (eq. 40) and the horizontal pseudo-static force k_h m g X.
    pub force: Vector3<f64>,
    /// −c·F·j' (eq. 41 with the sign of `docs/conventions.md`: c > 0 makes θ grow), the
    /// water's pitch about k' from the heights of its pushes, and the horizontal pseudo-static
    /// force's moment at the CM's height.
    pub moment: Vector3<f64>,
    /// −m g Y.
    pub weight: Vector3<f64>,
    /// Uplift less the tailwater's weight along j', and the vertical pseudo-static force
    /// k_v m g Y.
    pub held_force: Vector3<f64>,
    /// Their moments, and the weight's at the CM's height.
    pub held_moment: Vector3<f64>,
}

impl Applied {
    /// The loads on `block` at the pose whose local axes are `frame`.
    pub fn new(loads: &Loads, block: &Block, frame: &LocalFrame) -> Self {
        Applied::shaken(loads, block, frame, [0.0; 3])
    }

    /// With the foundation accelerating at `acceleration` (g, along X, Y, Z; a ground-motion
    /// record): in the foundation's frame the block feels −m g `acceleration` more at its
    /// centre of mass, the horizontal part driving (as k_h), the vertical held (as k_v).
    pub fn shaken(
        loads: &Loads,
        block: &Block,
        frame: &LocalFrame,
        acceleration: [f64; 3],
    ) -> Self {
        let f = loads.hydraulic_force;
        let mg = block.mass * loads.gravity;
        let weight = Vector3::new(0.0, -mg, 0.0);
        let a = acceleration;
        let horizontal = Vector3::new((loads.kh - a[0]) * mg, 0.0, -a[2] * mg);
        let vertical = Vector3::new(0.0, (loads.kv - a[1]) * mg, 0.0);
        // From the base point under the CM to the CM.
        let arm = frame.j * loads.cm_height;
        Applied {
            force: frame.i * f + horizontal,
            moment: frame.j * (-loads.eccentricity * f)
                + frame.k * loads.hydraulic_pitch
                + arm.cross(&horizontal),
            weight,
            held_force: frame.j * loads.held_normal + vertical,
            held_moment: frame.k * loads.held_pitch + arm.cross(&(vertical + weight)),
        }
    }

    /// The loads on `body` at the contacts `geom`, the foundation accelerating at
    /// `acceleration` (g): [`Applied::shaken`] and the anchors' tendons' pull at the pose.
    pub fn of(body: &Body, geom: &ContactGeometry, acceleration: [f64; 3]) -> Self {
        Applied::shaken(body.loads(), body.block(), &geom.frame, acceleration).with_tendons(
            body.tendons(),
            &geom.frame,
            &geom.origin,
        )
    }

    /// The same loads with the pull of `tendons` where the block's frame is `frame` and its
    /// base point under the centre of mass (the moments' point) at `origin`: held loads, not
    /// scaled by a factor of safety (`derivations/11-dam-loads.md` §10).
    pub fn with_tendons(
        self,
        tendons: &[Tendon],
        frame: &LocalFrame,
        origin: &Vector3<f64>,
    ) -> Applied {
        tendons.iter().fold(self, |a, t| {
            let (arm, force) = t.pull(origin, frame);
            Applied {
                held_force: a.held_force + force,
                held_moment: a.held_moment + arm.cross(&force),
                ..a
            }
        })
    }

    /// The same loads with their moments about the point `offset` from the frame's origin
    /// (the centre of mass above the base, [`crate::mechanics::ContactGeometry::centred`]):
    /// M' = M − offset × F, for the driving and the held loads each.
    pub fn about(&self, offset: &Vector3<f64>) -> Applied {
        Applied {
            moment: self.moment - offset.cross(&self.force),
            held_moment: self.held_moment - offset.cross(&(self.held_force + self.weight)),
            ..*self
        }
    }

    /// Every force: driving, weight and held (N).
    pub fn total_force(&self) -> Vector3<f64> {
        self.force + self.weight + self.held_force
    }

    /// Every moment: driving and held (N·m).
    pub fn total_moment(&self) -> Vector3<f64> {
        self.moment + self.held_moment
    }

    /// The power of the loads other than gravity's pull (W) at velocity `v` of the point their
    /// moments are about and angular velocity `w`: the water's, the pseudo-static forces', and,
    /// about the base point under the CM, the weight's moment at the CM's height (whose work is
    /// the change of m g times the CM's height above that point; about the CM itself, after
    /// [`Applied::about`], it has none).
    pub fn power(&self, v: &Vector3<f64>, w: &Vector3<f64>) -> f64 {
        (self.force + self.held_force).dot(v) + self.total_moment().dot(w)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::{Monolith, RockAnchor, Section};

    #[test]
    fn a_tendons_pull_acts_at_its_head_with_the_moment_of_its_arm_from_the_base_point() {
        // A 20 × 10 m base, 15 m high with a 5 m crest (x̄ = 7 m): a head at x 9, y 4, z 3 is
        // (2, 4, 3) from the base point under the centre of mass. Unfixed, the tendon pulls its
        // prestress along its direction; fixed where it stands, the same.
        let m = Monolith::new(Section {
            base_length: 20.0,
            width: 10.0,
            height: 15.0,
            crest_length: 5.0,
            density: 2400.0,
        })
        .unwrap();
        let anchor = RockAnchor {
            head: [9.0, 4.0, 3.0],
            plunge: 60f64.to_radians(),
            trend: 30f64.to_radians(),
            prestress: 2.0e6,
            capacity: 5.0e6,
            free_length: 20.0,
            steel_area: 1.0e-3,
            modulus: 2.0e11,
        };
        let tendon = Tendon::on(&m, anchor);
        let frame = LocalFrame::from_axes(Vector3::x(), Vector3::z());
        let origin = Vector3::new(10.0, 1.0, -2.0);
        let (s60, c60) = 60f64.to_radians().sin_cos();
        let (s30, c30) = 30f64.to_radians().sin_cos();
        let force = Vector3::new(c60 * c30, -s60, c60 * s30) * 2.0e6;
        let arm = Vector3::new(2.0, 4.0, 3.0);
        let moment = Vector3::new(
            arm.y * force.z - arm.z * force.y,
            arm.z * force.x - arm.x * force.z,
            arm.x * force.y - arm.y * force.x,
        );
        for t in [tendon, tendon.fixed_at(&origin, &frame)] {
            let zero = Applied {
                force: Vector3::zeros(),
                moment: Vector3::zeros(),
                weight: Vector3::zeros(),
                held_force: Vector3::zeros(),
                held_moment: Vector3::zeros(),
            };
            let a = zero.with_tendons(&[t], &frame, &origin);
            assert!((a.held_force - force).norm() < 1e-6, "{:?}", a.held_force);
            assert!(
                (a.held_moment - moment).norm() < 1e-5,
                "{:?}",
                a.held_moment
            );
            assert_eq!(a.force, Vector3::zeros());
        }
        // Moved 0.1 m upstream, away from its bond (which lies downstream of the head), the
        // fixed tendon stretches.
        let fixed = tendon.fixed_at(&origin, &frame);
        let moved = origin - Vector3::new(0.1, 0.0, 0.0);
        let rock = fixed.rock.unwrap();
        let head = moved + arm;
        let ell = (rock - head).norm();
        let want = (rock - head) / ell * (2.0e6 + 1.0e7 * (ell - 20.0));
        let (_, f) = fixed.pull(&moved, &frame);
        assert!((f - want).norm() < 1e-6, "{f:?} against {want:?}");
        assert!(f.norm() > 2.0e6);
    }
}
