use super::*;
use crate::contact::Shear;
use crate::model::Friction;

/// Coulomb's friction μ over a step of 1 ms.
pub(super) fn coulomb(mu: f64) -> Shear {
    Shear {
        criterion: Friction::coulomb(mu),
        h: 1e-3,
        cohesion_n: 0.0,
    }
}

/// A row of body 0 on the rock at `arm` along `normal`, closed, from nothing.
pub(super) fn ground_row(arm: Vector3<f64>, normal: Vector3<f64>, shear: Shear) -> ContactRow {
    ContactRow {
        a: Side { body: 0, arm },
        b: None,
        normal,
        shear,
        closing: 0.0,
        guess: Vector3::zeros(),
    }
}

/// The solve of one body from its free velocities `(v, w)`.
pub(super) fn one_body(
    body: &Body,
    (v, w): (Vector3<f64>, Vector3<f64>),
    rows: &[ContactRow],
    patches: &[Patch],
    tol: f64,
    max_sweeps: usize,
) -> Solved {
    let until = Until { tol, max_sweeps };
    solve(&[*body], &[Motion { v, w }], rows, patches, until)
}

/// A 2 m cube of 1000 kg, its base corners 1 m below the CM.
fn cube() -> (Body, Vec<Vector3<f64>>) {
    let m = 1000.0;
    let i = m * (4.0 + 4.0) / 12.0;
    let body = Body {
        inv_mass: 1.0 / m,
        inv_inertia: Matrix3::identity() / i,
    };
    let corners = [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)]
        .iter()
        .map(|&(x, z)| Vector3::new(x, -1.0, z))
        .collect();
    (body, corners)
}

fn on_ground(corners: &[Vector3<f64>], mu: f64) -> Vec<ContactRow> {
    corners
        .iter()
        .map(|&arm| ground_row(arm, Vector3::y(), coulomb(mu)))
        .collect()
}

/// The solve of [`cube`] on level ground of friction `mu` from its free velocity `v`, unspun.
fn cube_on_ground(v: Vector3<f64>, mu: f64, max_sweeps: usize) -> Solved {
    let (body, corners) = cube();
    one_body(
        &body,
        (v, Vector3::zeros()),
        &on_ground(&corners, mu),
        &[],
        1e-14,
        max_sweeps,
    )
}

#[test]
fn a_block_resting_on_level_ground_is_held_by_normal_impulses_that_carry_its_weight() {
    let h = 1e-3;
    // One step of gravity: v* = −g h.
    let v = Vector3::new(0.0, -9.81 * h, 0.0);
    let s = cube_on_ground(v, 0.6, 500);
    let m = s.motion[0];
    assert!(m.v.norm() < 1e-12 && m.w.norm() < 1e-12, "{} {}", m.v, m.w);
    let total: f64 = s.normal.iter().sum();
    assert!((total - 1000.0 * 9.81 * h).abs() < 1e-9);
}

#[test]
fn a_sliding_block_loses_exactly_mu_g_h_of_speed_a_step_and_does_not_rise() {
    let (h, mu, g) = (1e-3, 0.4, 9.81);
    let v = Vector3::new(2.0, -g * h, 0.5);
    let s = cube_on_ground(v, mu, 2000);
    let after = s.motion[0].v;
    let speed = v.xz().norm() - mu * g * h;
    assert!((after.xz().norm() - speed).abs() < 1e-9, "{after}");
    // Friction opposes the slip: the direction of travel is kept.
    assert!((after.x / after.z - 4.0).abs() < 1e-9);
    assert!(after.y.abs() < 1e-12, "a rise of {}", after.y);
}

#[test]
fn a_slow_block_stops_within_the_step_that_friction_can_stop_it_in() {
    let (h, mu, g) = (1e-3, 0.4, 9.81);
    let v = Vector3::new(0.5 * mu * g * h, -g * h, 0.0);
    let s = cube_on_ground(v, mu, 2000);
    assert!(s.motion[0].v.norm() < 1e-12, "{}", s.motion[0].v);
    let shear: f64 = s.tangential.iter().map(|p| p.norm()).sum();
    assert!(shear < mu * 1000.0 * g * h);
}

#[test]
fn a_falling_block_lands_without_bouncing_and_a_contact_apart_pulls_nothing() {
    let (body, corners) = cube();
    let mut rows = on_ground(&corners, 0.6);
    // Falling at 1 m/s, 0.4 mm above the ground: it lands within this 1 ms step.
    for r in &mut rows {
        r.closing = 0.4e-3 / 1e-3;
    }
    let down = (Vector3::new(0.0, -1.0, 0.0), Vector3::zeros());
    let s = one_body(&body, down, &rows, &[], 1e-14, 500);
    assert!((s.motion[0].v.y + 0.4).abs() < 1e-12, "{}", s.motion[0].v.y);
    // Far above: nothing.
    for r in &mut rows {
        r.closing = 5.0;
    }
    let s = one_body(&body, down, &rows, &[], 1e-14, 500);
    assert_eq!(s.normal, vec![0.0; 4]);
    assert_eq!(s.motion[0].v.y, -1.0);
}

/// A cube of `m` kg and 2 m side (its inertia about its centre).
fn cube_of(m: f64) -> Body {
    Body {
        inv_mass: 1.0 / m,
        inv_inertia: Matrix3::identity() / (m * 8.0 / 12.0),
    }
}

#[test]
fn a_block_standing_on_another_presses_it_down_with_its_weight_and_the_rock_carries_both() {
    // Body 0 (500 kg) on body 1 (1000 kg) on level rock, one step of gravity from rest: the
    // rows between them carry body 0's weight, on 0 upwards and on 1 downwards, and the rock's
    // rows both weights; neither moves.
    let (h, g) = (1e-3, 9.81);
    let bodies = [cube_of(500.0), cube_of(1000.0)];
    let corners = [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)];
    let mut rows: Vec<ContactRow> = corners
        .iter()
        .map(|&(x, z)| ContactRow {
            a: Side {
                body: 0,
                arm: Vector3::new(x, -1.0, z),
            },
            b: Some(Side {
                body: 1,
                arm: Vector3::new(x, 1.0, z),
            }),
            ..ground_row(Vector3::zeros(), Vector3::y(), coulomb(0.6))
        })
        .collect();
    rows.extend(corners.iter().map(|&(x, z)| {
        let mut r = ground_row(Vector3::new(x, -1.0, z), Vector3::y(), coulomb(0.6));
        r.a.body = 1;
        r
    }));
    let falling = Motion {
        v: Vector3::new(0.0, -g * h, 0.0),
        w: Vector3::zeros(),
    };
    let until = Until {
        tol: 1e-14,
        max_sweeps: 2000,
    };
    let s = solve(&bodies, &[falling, falling], &rows, &[], until);
    for m in &s.motion {
        assert!(m.v.norm() < 1e-12 && m.w.norm() < 1e-12, "{m:?}");
    }
    let between: f64 = s.normal[..4].iter().sum();
    let on_rock: f64 = s.normal[4..].iter().sum();
    assert!((between - 500.0 * g * h).abs() < 1e-9, "{between}");
    assert!((on_rock - 1500.0 * g * h).abs() < 1e-9, "{on_rock}");
}

#[test]
fn two_blocks_meeting_head_on_move_on_together_with_their_momentum() {
    // Body 1 (3000 kg) at 2 m/s along +X meets body 0 (1000 kg) at rest, their faces touching
    // on the line of their centres: an inelastic impact, both at 2·3000/4000 m/s after it,
    // and the impulse on each the other's opposite. No friction is asked for: no slip.
    let bodies = [cube_of(1000.0), cube_of(3000.0)];
    let row = ContactRow {
        a: Side {
            body: 0,
            arm: Vector3::new(-1.0, 0.0, 0.0),
        },
        b: Some(Side {
            body: 1,
            arm: Vector3::new(1.0, 0.0, 0.0),
        }),
        ..ground_row(Vector3::zeros(), Vector3::x(), coulomb(0.5))
    };
    let still = Motion {
        v: Vector3::zeros(),
        w: Vector3::zeros(),
    };
    let moving = Motion {
        v: Vector3::new(2.0, 0.0, 0.0),
        ..still
    };
    let until = Until {
        tol: 1e-14,
        max_sweeps: 50,
    };
    let s = solve(&bodies, &[still, moving], &[row], &[], until);
    let common = 2.0 * 3000.0 / 4000.0;
    for m in &s.motion {
        assert!(
            (m.v - Vector3::new(common, 0.0, 0.0)).norm() < 1e-12,
            "{m:?}"
        );
        assert!(m.w.norm() < 1e-15, "{m:?}");
    }
    assert!(
        (s.normal[0] - 1000.0 * common).abs() < 1e-9,
        "{}",
        s.normal[0]
    );
    let momentum = 1000.0 * s.motion[0].v + 3000.0 * s.motion[1].v;
    assert!((momentum.x - 6000.0).abs() < 1e-9, "{momentum}");
}

#[test]
fn a_point_sliding_under_a_stress_dependent_criterion_is_braked_by_its_shear_at_its_normal_force() {
    // A point mass of 1000 kg (no arm) pushed along level rock by F = 0.9 W, sliding at 1 m/s,
    // under Barton–Choubey: each step of 1 ms its speed grows by (F − S(W)) h / m, S(W) the
    // criterion's shear at the weight, W times its own coefficient at the stress W / A.
    let (m, g, h) = (1000.0, 9.81, 1e-3);
    let w = m * g;
    let criterion = Friction::barton_choubey(10.0, 5.0e7, 30f64.to_radians(), 1e-3);
    let body = Body {
        inv_mass: 1.0 / m,
        inv_inertia: Matrix3::identity(),
    };
    let row = ground_row(
        Vector3::zeros(),
        Vector3::y(),
        Shear {
            criterion,
            h,
            cohesion_n: 0.0,
        },
    );
    let mut v = 1.0;
    for _ in 0..1000 {
        let free = (Vector3::new(v + 0.9 * g * h, -g * h, 0.0), Vector3::zeros());
        let s = one_body(&body, free, &[row], &[], 1e-14, 100);
        v = s.motion[0].v.x;
        assert!(s.motion[0].v.y.abs() < 1e-15, "{}", s.motion[0].v);
    }
    let coefficient = criterion.coefficient(w);
    let exact = 1.0 + (0.9 - coefficient) * g;
    assert!((v - exact).abs() < 1e-9, "{v} against {exact}");
    // Its coefficient at another stress brakes otherwise: at a tenth of it the angle is JRC = 10°
    // steeper.
    assert!((criterion.coefficient(0.1 * w) - coefficient) * g > 0.5);
}

#[test]
fn a_block_sliding_on_another_through_their_joint_is_braked_by_the_joints_friction_not_the_rocks() {
    // Two 2 m cubes of a simulation on level rock of μ 0.6: body 1 (2000 kg) on the rock,
    // body 0 (1000 kg) on body 1, their joint of μ 0.2. Body 0 slides at 2 m/s along +X; one
    // step of gravity. The pipeline as the route runs it: the rock's touches by the narrow
    // phase, the joint's by hand (no narrow phase between bodies yet), each pair's criterion
    // from the simulation's strengths, the rows, the solve. Body 0 loses 0.2 g h of speed, not
    // 0.6 g h; body 1, which the joint drags by 0.2 · 1000 g h and the rock may hold by
    // 0.6 · 3000 g h, stays still.
    use crate::contact::{ContactPair, Warm, on_rock, placed, rows};
    use crate::geometry::contact::{BodyTouch, all_on_rock};
    use crate::geometry::{BodyPose, Feature, Ground, Plane, Site};
    use crate::model::{
        Base, Block, Contacts, DynamicsModel, Foundation, Joint, Loads, RunSettings, Simulation,
        Surface,
    };
    use std::sync::Arc;
    let (h, g) = (1e-3, 9.81);
    let level = Plane::through(Vector3::y(), Vector3::zeros());
    let ground = Arc::new(Ground::planes(vec![level]));
    let site = Site::on_ground(
        [[-1.0, 1.0], [1.0, 1.0], [1.0, -1.0]],
        Arc::clone(&ground),
        [0; 3],
    );
    let cube = |mass: f64| {
        crate::model::Body::builder(site.clone())
            .block(Block::plate(mass, mass * 8.0 / 12.0))
            .loads(Loads::plain(0.0, 0.0, g))
            .base(Base::rectangle([-1.0, 1.0], [-1.0, 1.0], 1.0).unwrap())
            .build()
            .unwrap()
    };
    let sim = Simulation::builder()
        .body(cube(1000.0))
        .body(cube(2000.0))
        .joint(Joint::new([0, 1], Friction::coulomb(0.2)))
        .foundation(Foundation::new(Arc::clone(&ground)))
        .friction(Friction::coulomb(0.6))
        .settings(RunSettings::new(DynamicsModel::RigidBody, h, 1.0).with_contacts(Contacts::Base))
        .build()
        .unwrap();
    let at = |y: f64| BodyPose {
        cm: Vector3::new(0.0, y, 0.0),
        rotation: Matrix3::identity(),
    };
    let poses = [at(3.0), at(1.0)];
    let on = all_on_rock(&ground, &placed(&sim, &poses), 1e-9);
    assert!(
        on[0].touches.is_empty() && on[1].touches.len() == 4,
        "{on:?}"
    );
    let mut pairs = on_rock(1, &on[1].touches, sim.strengths());
    let joint = sim.strengths().between(Surface::Body(0), Surface::Body(1));
    let corners = [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)];
    pairs.extend(corners.iter().enumerate().map(|(k, &(x, z))| {
        // Body 0's base corner k on body 1's top, where its top corner k is.
        let t = BodyTouch {
            bodies: [0, 1],
            on_first: Vector3::new(x, 2.0, z),
            normal: Vector3::y(),
            gap: 0.0,
            features: [Feature::Corner(k), Feature::Corner(k)],
        };
        ContactPair::between(&t, &poses[0], joint.criterion)
    }));
    assert!(
        pairs[..4]
            .iter()
            .all(|p| p.criterion == Friction::coulomb(0.6))
    );
    assert!(
        pairs[4..]
            .iter()
            .all(|p| p.criterion == Friction::coulomb(0.2))
    );
    let cms = poses.map(|p| p.cm);
    let none = Warm {
        touches: &[],
        points: &[],
        size: 2.0,
    };
    let rows = rows(&pairs, &cms, h, &none, &[]);
    let free = |vx: f64| Motion {
        v: Vector3::new(vx, -g * h, 0.0),
        w: Vector3::zeros(),
    };
    let until = Until {
        tol: 1e-14,
        max_sweeps: 5000,
    };
    let s = solve(
        &[cube_of(1000.0), cube_of(2000.0)],
        &[free(2.0), free(0.0)],
        &rows,
        &[],
        until,
    );
    let [top, under] = [s.motion[0], s.motion[1]];
    assert!((top.v.x - (2.0 - 0.2 * g * h)).abs() < 1e-9, "{top:?}");
    assert!(top.v.y.abs() < 1e-12 && top.w.norm() < 1e-9, "{top:?}");
    assert!(under.v.norm() < 1e-9 && under.w.norm() < 1e-9, "{under:?}");
}
