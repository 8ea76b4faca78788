//! The bodies of a simulation as the narrow phase sees them: each its number, its pose and its
//! underside.

use crate::geometry::contact::{Placed, Underside};
use crate::geometry::{BodyPose, Footprint};
use crate::model::Simulation;

/// The bodies of `sim` that stand on a base (`contacts = "base"`), each at its pose in `poses`
/// (by body number), with its flat base. A base cast onto its rock touches it with the relief
/// cast where the body rests (the route's: `Underside::Cast`).
#[cfg_attr(not(feature = "internals"), allow(dead_code))]
pub fn placed<'a>(sim: &'a Simulation, poses: &[BodyPose]) -> Vec<Placed<'a>> {
    sim.bodies()
        .iter()
        .zip(poses)
        .enumerate()
        .filter_map(|(k, (body, pose))| {
            let base = body.base()?;
            Some(Placed {
                body: k,
                pose: *pose,
                underside: Underside::Flat(Footprint {
                    outline: base.outline(),
                    depth: base.depth(),
                }),
            })
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::contact::{Against, on_rock};
    use crate::geometry::contact::all_on_rock;
    use crate::geometry::{Feature, Ground, Plane, Site};
    use crate::model::{
        Base, Block, Body, Contacts, DynamicsModel, Foundation, Friction, Loads, RunSettings,
    };
    use nalgebra::{Matrix3, Rotation3, Vector3};
    use std::sync::Arc;

    #[test]
    fn two_bodies_standing_apart_on_level_rock_each_touch_it_at_their_own_base_corners() {
        // Two bodies on one level rock: "left" on a 4 m × 3 m base 1 m below its CM, standing
        // at X = −5 m; "right" on a 2 m × 2 m base 0.5 m below its CM, at X = +6 m, Z = 1 m and
        // turned 90° about the vertical. The rock carries each at its base's corners, no gap,
        // along +Y; face 0 has its own friction, and each pair takes it.
        let level = Plane::through(Vector3::y(), Vector3::zeros());
        let ground = Arc::new(Ground::planes(vec![level]));
        let site = Site::on_ground(
            [[-2.0, 1.5], [2.0, 1.5], [2.0, -1.5]],
            Arc::clone(&ground),
            [0; 3],
        );
        let body = |name: &str, base: Base| {
            Body::builder(site.clone())
                .name(name)
                .block(Block::plate(1e6, 2.6e6))
                .loads(Loads::plain(0.0, 0.0, 9.81))
                .base(base)
                .build()
                .unwrap()
        };
        let left = Base::rectangle([-2.0, 2.0], [-1.5, 1.5], 1.0).unwrap();
        let right = Base::rectangle([-1.0, 1.0], [-1.0, 1.0], 0.5).unwrap();
        let settings =
            RunSettings::new(DynamicsModel::RigidBody, 1e-3, 1.0).with_contacts(Contacts::Base);
        let sim = Simulation::builder()
            .body(body("left", left))
            .body(body("right", right))
            .foundation(Foundation::new(Arc::clone(&ground)))
            .friction(Friction::coulomb(0.6))
            .settings(settings)
            .build()
            .unwrap();
        assert_eq!(sim.bodies().len(), 2);
        let turned = Rotation3::from_axis_angle(&Vector3::y_axis(), 90f64.to_radians());
        let poses = [
            BodyPose {
                cm: Vector3::new(-5.0, 1.0, 0.0),
                rotation: Matrix3::identity(),
            },
            BodyPose {
                cm: Vector3::new(6.0, 0.5, 1.0),
                rotation: *turned.matrix(),
            },
        ];
        let bodies = placed(&sim, &poses);
        let found = all_on_rock(&ground, &bodies, 1e-9);
        // By hand: body 0's corners (x′, z′) = (∓2, ∓1.5) at X = −5 + x′, Z = z′; body 1's
        // (x′, z′) = (∓1, ∓1), turned 90° about Y (x′ → −Z, z′ → +X): X = 6 + z′, Z = 1 − x′.
        let want = [
            vec![[-7.0, -1.5], [-3.0, -1.5], [-3.0, 1.5], [-7.0, 1.5]],
            vec![[5.0, 2.0], [5.0, 0.0], [7.0, 0.0], [7.0, 2.0]],
        ];
        assert_eq!(found.len(), 2);
        for (k, (touches, want)) in found.iter().zip(&want).enumerate() {
            assert!(touches.off_ground.is_empty());
            assert_eq!(touches.touches.len(), 4, "body {k}: {touches:?}");
            for (c, t) in touches.touches.iter().enumerate() {
                assert_eq!(t.feature, Feature::Corner(c));
                let at = Vector3::new(want[c][0], 0.0, want[c][1]);
                assert!((t.on_base - at).norm() < 1e-12, "body {k}: {t:?} at {at}");
                assert!((t.normal - Vector3::y()).norm() < 1e-15, "{t:?}");
                assert!(t.gap.abs() < 1e-12, "{t:?}");
            }
            // Their pairs: this body on face 0, with the face's friction.
            for p in on_rock(k, &touches.touches, sim.strengths()) {
                assert_eq!(p.body, k);
                assert_eq!(p.against, Against::Rock { face: 0 });
                assert_eq!(p.criterion, Friction::coulomb(0.6));
            }
        }
        // Lifted 1 mm, the right body touches nothing within the reach; the left still does.
        let mut poses = poses;
        poses[1].cm.y += 1e-3;
        let found = all_on_rock(&ground, &placed(&sim, &poses), 1e-9);
        assert_eq!((found[0].touches.len(), found[1].touches.len()), (4, 0));
    }
}
