//! The rigid body's mechanics against hand derivations, conservation laws and its own
//! constraints.

use super::contact::Ctx;
use super::kinematics::{longest_arm, pivot_direction, twist, unit};
use super::*;
use crate::geometry::{Displacement, Pose, direct};
use crate::mechanics::ContactGeometry;
use crate::mechanics::loads::Applied;
use crate::model::Friction;
use crate::model::{ContactStrength, Simulation};
use crate::scene::Scene;
use nalgebra::Vector3;

fn at(scene: &Scene, d: Displacement) -> ContactGeometry {
    let p = direct::solve(&scene.site, d).unwrap();
    let l = scene.l();
    let pose = Pose::from_tilts(scene.site.as_paper().unwrap(), d, p.alpha(l), p.beta(l)).unwrap();
    ContactGeometry::new(&scene.site().normals(), &pose)
}

/// The scene's block at `d` (its pose by the direct solver), every contact on its own plane's
/// criterion: what [`accelerations`] takes there.
struct AtPose {
    sim: Simulation,
    geom: ContactGeometry,
    applied: Applied,
    strength: [ContactStrength; 3],
}

impl AtPose {
    fn new(scene: &Scene, d: Displacement) -> AtPose {
        let sim = scene.simulation().unwrap();
        let geom = at(scene, d);
        let applied = Applied::new(
            sim.first_body().loads(),
            sim.first_body().block(),
            &geom.frame,
        );
        let strength = sim
            .first_body()
            .frame_strength(sim.strengths(), [0, 1, 2], false);
        AtPose {
            sim,
            geom,
            applied,
            strength,
        }
    }

    /// The accelerations moving with `rates`, in no crease.
    fn motion(&self, rates: [f64; 3]) -> Motion {
        let state = State {
            geom: &self.geom,
            applied: &self.applied,
            block: self.sim.first_body().block(),
            strength: &self.strength,
        };
        accelerations(&state, rates, 0.0, Creases::NONE).unwrap()
    }
}

#[test]
fn pivot_rates_leave_the_contact_at_rest_and_project() {
    // At a pose from the direct solver: the rates with contact i's slip removed move it
    // neither along its plane nor off it, and removing it again changes nothing.
    let scene = Scene::default_scene();
    let geom = at(&scene, Displacement::new(0.7, 0.2, 0.1));
    let block = scene.block.as_ref().unwrap();
    let inertia = Inertia::new(block, &geom).unwrap();
    let rates = [1.5, -0.4, 0.3];
    for i in 0..3 {
        let (p, removed) = pivot_rates(&geom, block, rates, i).unwrap();
        let v = twist(&geom, p).unwrap().at(&geom.r[i]);
        assert!(v.norm() < 1e-14 * 1.5, "contact {i}: {v:?}");
        let (q, again) = pivot_rates(&geom, block, p, i).unwrap();
        for k in 0..3 {
            assert!((q[k] - p[k]).abs() < 1e-14, "{q:?} {p:?}");
        }
        // The energy it removes is the kinetic energy of the removed motion (an impulse's
        // loss): ½|v − v'|²_M, Pythagoras in the kinetic-energy metric.
        let k = |r: [f64; 3]| {
            twist(&geom, r)
                .unwrap()
                .kinetic_energy(block.mass, &inertia)
        };
        let gap = k([rates[0] - p[0], rates[1] - p[1], rates[2] - p[2]]);
        assert!(
            removed < 0.0 && (removed + gap).abs() < 1e-9 * k(rates),
            "{removed} {gap}"
        );
        assert!(again.abs() < 1e-9 * k(rates), "{again}");
    }
}

#[test]
fn the_projected_twist_keeps_contacts_on_their_planes_and_gives_the_rates() {
    let scene = Scene::default_scene();
    let geom = at(&scene, Displacement::new(0.7, 0.2, 0.1));
    let tw = twist(&geom, [1.5, -0.4, 0.3]).unwrap();
    for i in 0..3 {
        assert!(geom.n[i].dot(&tw.at(&geom.r[i])).abs() < 1e-14);
    }
    assert_eq!((tw.v.x, tw.v.z), (1.5, -0.4));
    // θ̇ by finite differences of the yaw of i' rotated by ω dt.
    let u = geom.frame.i;
    let h = 1e-7;
    let u2 = u + tw.w.cross(&u) * h;
    let dtheta = (u2.z.atan2(u2.x) - u.z.atan2(u.x)) / h;
    assert!((dtheta - 0.3).abs() < 1e-6, "{dtheta}");
}

#[test]
fn frictionless_accelerations_keep_contact_accelerations_on_the_planes() {
    let scene = Scene::default_scene().with("friction.mu_k", 0.0).unwrap();
    let at = AtPose::new(&scene, Displacement::new(0.7, 0.2, 0.1));
    let (geom, applied) = (&at.geom, &at.applied);
    let m = at.motion([1.0, 0.1, 0.2]);
    for i in 0..3 {
        let r = geom.r[i];
        let acc = m.accel + m.ang_accel.cross(&r) + m.twist.w.cross(&m.twist.w.cross(&r));
        assert!(geom.n[i].dot(&acc).abs() < 1e-12, "{i}");
        assert_eq!(m.shear[i], Vector3::zeros());
    }
    // Newton: m a = F + W + Σ N.
    let total = applied.force
        + applied.weight
        + (0..3)
            .map(|i| geom.n[i] * m.normal[i])
            .sum::<Vector3<f64>>();
    assert!((total / at.sim.first_body().block().mass - m.accel).norm() < 1e-12);
}

#[test]
fn shear_opposes_slip_with_the_criterion_magnitude() {
    let scene = Scene::default_scene();
    let at = AtPose::new(&scene, Displacement::new(0.5, 0.0, -0.05));
    let m = at.motion([1.0, 0.1, 0.2]);
    for i in 0..3 {
        let s = m.slip[i];
        assert!((m.shear[i].norm() - 0.4 * m.normal[i]).abs() < 1e-6);
        assert!((m.shear[i].normalize() + s.normalize()).norm() < 1e-12);
    }
    assert!(m.power_friction < 0.0);
}

#[test]
fn from_rest_each_shear_opposes_its_contacts_tangential_acceleration() {
    let scene = Scene::default_scene();
    let at = AtPose::new(&scene, Displacement::new(0.0, 0.0, 0.0));
    let geom = &at.geom;
    let m = at.motion([0.0; 3]);
    for i in 0..3 {
        let r = geom.r[i];
        let acc = m.accel + m.ang_accel.cross(&r);
        let t = acc - geom.n[i] * acc.dot(&geom.n[i]);
        assert!(
            (m.shear[i].normalize() + t.normalize()).norm() < 1e-10,
            "{i}"
        );
    }
    // About 1 m/s² forward at the start (as a first hand estimate of the rigid body gave).
    assert!((0.8..1.3).contains(&m.accel.x), "{}", m.accel.x);
}

#[test]
fn a_pivot_its_cone_cannot_hold_slips_along_its_own_tangential_acceleration() {
    // While the block moves, a contact whose slip is zero and whose cone cannot
    // hold it starts to slip along d with its friction −μλ d, where the tangential
    // acceleration this gives points along d itself (a_t ∥ d, a_t·d ≥ 0). Checked by
    // recomputing a_t from the returned accelerations.
    let scene = Scene::default_scene().with("friction.mu_k", 0.05).unwrap();
    let at = AtPose::new(&scene, Displacement::new(0.5, 0.1, 0.05));
    let geom = &at.geom;
    let arm = longest_arm(geom);
    let mut checked = 0;
    for i in 0..3 {
        let p = pivot_direction(geom, arm, i).unwrap() * 2.0;
        let m = at.motion([p.x, p.y, p.z / arm]);
        assert!(
            m.slip[i].norm() < 1e-12,
            "contact {i} does not slip at the start"
        );
        if m.stuck == Some(i) {
            continue;
        }
        let r = geom.r[i];
        let acc = m.accel + m.ang_accel.cross(&r) + m.twist.w.cross(&m.twist.w.cross(&r));
        let a_t = acc - geom.n[i] * acc.dot(&geom.n[i]);
        let dir = -m.shear[i] / m.shear[i].norm();
        assert!((m.shear[i].norm() - 0.05 * m.normal[i]).abs() < 1e-9 * m.normal[i]);
        assert!(
            dir.cross(&a_t).norm() < 1e-8 * a_t.norm().max(1e-12),
            "{i}: {a_t:?} {dir:?}"
        );
        assert!(a_t.dot(&dir) >= 0.0, "{i}: the slip grows along d");
        checked += 1;
    }
    assert!(
        checked > 0,
        "no contact's cone failed: the test checks nothing"
    );
}

#[test]
fn one_contact_stick_satisfies_newton_euler_and_its_constraints() {
    // The 11-equation stick mode, checked by recomputing the forces it returns.
    let scene = Scene::default_scene();
    let d = scene.simulation().unwrap();
    let geom = at(&scene, Displacement::new(0.5, 0.1, 0.05));
    let applied = Applied::new(d.first_body().loads(), d.first_body().block(), &geom.frame);
    let inertia = Inertia::new(d.first_body().block(), &geom).unwrap();
    let ctx = Ctx {
        geom: &geom,
        inertia,
        mass: d.first_body().block().mass,
        force: applied.force + applied.weight,
        torque: applied.moment,
        centripetal: [Vector3::zeros(); 3],
        arm: 10.0,
        creases: Creases::NONE,
    };
    let rates = ctx.pivot_direction(1).unwrap();
    let t = twist(&geom, [rates.x, rates.y, rates.z / ctx.arm]).unwrap();
    let dir = ctx.slip_of(&t).map(unit);
    assert!(ctx.slip_of(&t)[1].norm() < 1e-12, "contact 1 does not slip");
    let s = ctx.solve_stick(&dir, &[0.4; 3], 1).unwrap();
    let mut f = ctx.force;
    let mut m = ctx.torque;
    for j in 0..3 {
        let c = geom.n[j] * s.lambda[j] + s.shear[j];
        f += c;
        m += geom.r[j].cross(&c);
        let acc = s.a + s.e.cross(&geom.r[j]);
        assert!(geom.n[j].dot(&acc).abs() < 1e-10, "normal {j}");
        if j == 1 {
            assert!(ctx.tangential(1, acc).norm() < 1e-10, "contact 1 sticks");
        } else {
            assert!((s.shear[j].norm() - 0.4 * s.lambda[j]).abs() < 1e-6 * s.lambda[j]);
        }
    }
    assert!((f - s.a * d.first_body().block().mass).norm() < 1e-6 * f.norm().max(1.0));
    assert!((m - inertia.world * s.e).norm() < 1e-6 * m.norm().max(1.0));
}

/// The default scene's block flat at the start with contacts 0 and 1 on a level face and
/// contact 2 at the bottom of a groove along X, its faces dipping `dip` to either side: the
/// contact geometry (contact 2 on face A, normal leaning to +Z) and the crease (face B).
fn groove(dip: f64) -> (crate::model::Simulation, ContactGeometry, Crease, Applied) {
    let scene = Scene::default_scene();
    let pose = Pose::from_tilt_roll(&scene.site, Displacement::default(), 0.0, 0.0).unwrap();
    let (s, c) = dip.sin_cos();
    let level = Vector3::y();
    let geom = ContactGeometry::new(&[level, level, Vector3::new(0.0, c, s)], &pose);
    let crease = Crease {
        contact: 2,
        normal: Vector3::new(0.0, c, -s),
        offset: Vector3::new(0.0, c, -s).dot(&pose.vertices[2]),
        face: 1,
    };
    let sim = scene.simulation().unwrap();
    let applied = Applied::new(
        sim.first_body().loads(),
        sim.first_body().block(),
        &geom.frame,
    );
    (sim, geom, crease, applied)
}

#[test]
fn frictionless_in_a_groove_the_block_slides_along_it_and_turns_about_its_contact() {
    // Contacts 0, 1 on Y = 0 and contact 2 on the groove's bottom line keep the block flat
    // with contact 2 on the line Z = z2: two degrees of freedom, X and θ. At rest,
    // frictionless, F along x' and the couple cF (θ up): m Ẍ = F, and the groove's lateral
    // reaction R at contact 2 (x2 = 4 m ahead of the CM) gives m Z̈ = R with Z̈ = −x2 θ̈ and
    // I θ̈ = cF + x2 R, so θ̈ = cF / (I + m x2²).
    let (d, geom, crease, applied) = groove(30f64.to_radians());
    let (block, loads) = (d.first_body().block(), d.first_body().loads());
    let frictionless = [ContactStrength::from(Friction::Coulomb { mu_k: 0.0 }); 3];
    let m = accelerations(
        &State {
            geom: &geom,
            applied: &applied,
            block,
            strength: &frictionless,
        },
        [0.0; 3],
        0.0,
        crease.into(),
    )
    .unwrap();
    let (f, c, x2) = (loads.hydraulic_force, loads.eccentricity, 4.0);
    let theta_ddot = c * f / (block.inertia + block.mass * x2 * x2);
    let want = [f / block.mass, -x2 * theta_ddot, theta_ddot];
    for k in 0..3 {
        assert!(
            (m.acc[k] - want[k]).abs() < 1e-12 * want[0],
            "{:?} vs {want:?}",
            m.acc
        );
    }
    // Both groove faces push, and their lateral parts give R.
    let second = m.crease_normal[2].unwrap();
    assert!(m.normal[2] > 0.0 && second > 0.0);
    let r = (m.normal[2] - second) * 30f64.to_radians().sin();
    assert!((r + block.mass * x2 * theta_ddot).abs() < 1e-6 * f, "{r}");
    // Without the crease the block is free to move sideways: another motion.
    let free = accelerations(
        &State {
            geom: &geom,
            applied: &applied,
            block,
            strength: &frictionless,
        },
        [0.0; 3],
        0.0,
        Creases::NONE,
    )
    .unwrap();
    assert!((free.acc[2] - theta_ddot).abs() > 1e-3 * theta_ddot);
}

#[test]
fn sliding_in_a_groove_both_faces_rub_and_every_constraint_holds() {
    // Moving along the groove with friction: Newton–Euler from the returned forces, the
    // four constraint accelerations zero, and contact 2's friction μ(λ_A + λ_B) against its
    // slip — the wedge: per unit of vertical load, μ / cos δ instead of μ.
    let dip = 35f64.to_radians();
    let (d, geom, crease, applied) = groove(dip);
    let (block, loads) = (d.first_body().block(), d.first_body().loads());
    let mu = 0.4;
    let friction = [ContactStrength::from(Friction::Coulomb { mu_k: mu }); 3];
    let m = accelerations(
        &State {
            geom: &geom,
            applied: &applied,
            block,
            strength: &friction,
        },
        [1.0, 0.0, 0.0],
        0.0,
        crease.into(),
    )
    .unwrap();
    let second = m.crease_normal[2].unwrap();
    let normal_force = |j: usize| {
        let mut f = geom.n[j] * m.normal[j];
        if j == 2 {
            f += crease.normal * second;
        }
        f
    };
    let mut force = applied.force + applied.weight;
    let mut torque = applied.moment - m.twist.w.cross(&(m.inertia.world * m.twist.w));
    for j in 0..3 {
        let c = normal_force(j) + m.shear[j];
        force += c;
        torque += geom.r[j].cross(&c);
    }
    assert!((force - m.accel * block.mass).norm() < 1e-6 * loads.hydraulic_force);
    assert!((torque - m.inertia.world * m.ang_accel).norm() < 1e-6 * loads.hydraulic_force);
    let w = m.twist.w;
    for (j, n) in [
        (0, geom.n[0]),
        (1, geom.n[1]),
        (2, geom.n[2]),
        (2, crease.normal),
    ] {
        let r = geom.r[j];
        let acc = m.accel + m.ang_accel.cross(&r) + w.cross(&w.cross(&r));
        assert!(
            n.dot(&acc).abs() < 1e-9,
            "constraint of contact {j} along {n}"
        );
    }
    let slip = m.slip[2];
    assert!(slip.norm() > 0.9 && slip.y.abs() < 1e-12 && slip.z.abs() < 1e-12);
    let want = -slip.normalize() * (mu * (m.normal[2] + second));
    assert!((m.shear[2] - want).norm() < 1e-9 * want.norm());
    let vertical = m.normal[2] * geom.n[2].y + second * crease.normal.y;
    assert!((m.shear[2].norm() - mu * vertical / dip.cos()).abs() < 1e-6 * vertical);
}

#[test]
fn a_crease_lets_go_of_the_face_that_pulls() {
    // A shallow groove (2°) cannot hold the lateral push of a strong turn: one face's
    // reaction would pull. Which one depends on which face is the crease's second.
    let (d, geom, crease, applied) = groove(2f64.to_radians());
    let block = d.first_body().block();
    let frictionless = [ContactStrength::from(Friction::Coulomb { mu_k: 0.0 }); 3];
    let run = |geom: &ContactGeometry, crease: Crease| {
        accelerations(
            &State {
                geom,
                applied: &applied,
                block,
                strength: &frictionless,
            },
            [0.0; 3],
            0.0,
            crease.into(),
        )
    };
    let first = run(&geom, crease).unwrap_err();
    let mut swapped = geom;
    swapped.n[2] = crease.normal;
    let other = Crease {
        normal: geom.n[2],
        ..crease
    };
    let second = run(&swapped, other).unwrap_err();
    let kinds = [&first, &second].map(|e| match e {
        RigidError::CreaseLetsGo { contact: 2, .. } => "lets go",
        RigidError::CreaseTakesOver { contact: 2, .. } => "takes over",
        _ => "other",
    });
    let mut sorted = kinds;
    sorted.sort_unstable();
    assert_eq!(sorted, ["lets go", "takes over"], "{first} / {second}");
}

#[test]
fn a_frictionless_impact_is_the_crease_projection_and_friction_takes_more() {
    // Contact 2 meets the groove's second face: frictionless, the impact leaves the motion
    // the crease projection gives (two routes to the same inelastic impact: impulses and a
    // projection in the kinetic-energy metric); with friction, every contact is still on
    // its faces after it, and it takes more kinetic energy, never adding any.
    let (d, geom, crease, _) = groove(30f64.to_radians());
    let block = d.first_body().block();
    let inertia = Inertia::new(block, &geom).unwrap();
    let creases = Creases::from(crease);
    let law = |mu: f64| ImpactLaw {
        mu: [mu; 3],
        release_speed: f64::INFINITY,
        crease_release_speed: f64::INFINITY,
    };
    for rates in [[1.0, 0.3, 0.0], [0.2, 0.5, 0.05], [0.5, 0.1, 0.1]] {
        let before = twist(&geom, rates).unwrap();
        let k0 = before.kinetic_energy(block.mass, &inertia);
        let plain = impact(&geom, &geom, block, rates, &creases, &law(0.0)).unwrap();
        let (projected, removed) = crease_rates(&geom, block, rates, &creases).unwrap();
        for (a, b) in plain.rates.iter().zip(projected) {
            assert!((a - b).abs() < 1e-9, "{plain:?}");
        }
        assert!((plain.removed - removed).abs() < 1e-9 * k0);
        assert_eq!(plain.creases, creases);
        let rough = impact(&geom, &geom, block, rates, &creases, &law(0.4)).unwrap();
        let after = twist(&geom, rough.rates).unwrap();
        let v2 = after.at(&geom.r[2]);
        let scale = before.at(&geom.r[2]).norm();
        assert!(crease.normal.dot(&v2).abs() < 1e-9 * scale, "{v2}");
        assert!(geom.n[2].dot(&v2).abs() < 1e-9 * scale, "{v2}");
        let k1 = after.kinetic_energy(block.mass, &inertia);
        assert!((k1 - k0 - rough.removed).abs() < 1e-9 * k0);
        assert!(
            rough.removed < plain.removed && rough.removed >= -k0,
            "{rough:?}"
        );
    }
}

#[test]
fn an_impact_with_friction_takes_energy_and_stops_the_contacts_on_their_faces() {
    // The impact as a process (friction turning with each slip within it): whatever the
    // motion into the groove's face and however rough, every held contact ends with no
    // velocity into its faces, and the kinetic energy taken is what it books, more than
    // none and at most all there was.
    let (d, geom, crease, _) = groove(30f64.to_radians());
    let block = d.first_body().block();
    let inertia = Inertia::new(block, &geom).unwrap();
    let creases = Creases::from(crease);
    for mu in [0.2, 0.8, 2.0] {
        let law = ImpactLaw {
            mu: [mu; 3],
            release_speed: f64::INFINITY,
            crease_release_speed: f64::INFINITY,
        };
        for rates in [
            [1.0, 0.3, 0.0],
            [0.2, 0.5, 0.05],
            [0.5, 0.1, 0.1],
            [0.0, 0.4, -0.2],
        ] {
            let before = twist(&geom, rates).unwrap();
            let k0 = before.kinetic_energy(block.mass, &inertia);
            let after = impact(&geom, &geom, block, rates, &creases, &law).unwrap();
            let u = twist(&geom, after.rates).unwrap();
            let k1 = u.kinetic_energy(block.mass, &inertia);
            assert!(
                (k1 - k0 - after.removed).abs() < 1e-9 * k0,
                "{mu} {rates:?}"
            );
            assert!(after.removed < 0.0 && after.removed >= -k0 * (1.0 + 1e-9));
            let v2 = u.at(&geom.r[2]);
            let scale = before.at(&geom.r[2]).norm();
            assert!(
                crease.normal.dot(&v2).abs() < 1e-9 * scale,
                "{mu} {rates:?}"
            );
        }
    }
}

#[test]
fn an_impact_lets_a_face_go_only_if_its_contact_would_leave_it_fast_enough() {
    // A block moving along −Z meets the groove's face B at contact 2 from the side it
    // leaves: the impulse that would hold contact 2 on B pulls. Let go if the release is
    // faster than the law's crease release speed; otherwise held (the forces just after
    // decide).
    let (d, geom, crease, _) = groove(30f64.to_radians());
    let block = d.first_body().block();
    let creases = Creases::from(crease);
    let rates = [0.0, -1.0, 0.0];
    let go = |crease_release_speed: f64| {
        let law = ImpactLaw {
            mu: [0.0; 3],
            release_speed: f64::INFINITY,
            crease_release_speed,
        };
        impact(&geom, &geom, block, rates, &creases, &law).unwrap()
    };
    let let_go = go(1e-3);
    assert_eq!(let_go.creases, Creases::NONE);
    assert!(let_go.removed.abs() < 1e-9, "{let_go:?}");
    assert!((0..3).all(|c| (let_go.rates[c] - rates[c]).abs() < 1e-12));
    let held = go(f64::INFINITY);
    assert_eq!(held.creases, creases);
    assert!(held.removed < 0.0);
}

#[test]
fn running_over_a_ridge_is_a_hop_kept_on_the_face_beyond_or_a_lift_at_the_speed_off_it() {
    // The block slides flat along +X at v on level faces; contact 1's face becomes one that
    // falls away ahead at δ (a convex edge): the contact leaves it at v sin δ. With a release
    // speed above that, the impact keeps it on the face (every contact's velocity along its
    // face's normal zero after it, the kinetic energy lost what the impact books); below,
    // it lifts off at exactly v sin δ.
    let scene = Scene::default_scene();
    let pose = Pose::from_tilt_roll(&scene.site, Displacement::default(), 0.0, 0.0).unwrap();
    let level = Vector3::y();
    let delta = 5f64.to_radians();
    let beyond = Vector3::new(delta.sin(), delta.cos(), 0.0);
    let before = ContactGeometry::new(&[level; 3], &pose);
    let after = ContactGeometry::new(&[level, beyond, level], &pose);
    let sim = scene.simulation().unwrap();
    let block = sim.first_body().block();
    let v = 2.0;
    let law = |release_speed| ImpactLaw {
        mu: [0.0; 3],
        release_speed,
        crease_release_speed: f64::INFINITY,
    };
    let onto = |release_speed| {
        impact(
            &before,
            &after,
            block,
            [v, 0.0, 0.0],
            &Creases::NONE,
            &law(release_speed),
        )
    };
    match onto(0.9 * v * delta.sin()) {
        Err(RigidError::ImpactLifts {
            contact, speed_m_s, ..
        }) => {
            assert_eq!(contact, 1);
            assert!((speed_m_s - v * delta.sin()).abs() < 1e-12, "{speed_m_s}");
        }
        other => panic!("{other:?}"),
    }
    let kept = onto(1.1 * v * delta.sin()).unwrap();
    let inertia = Inertia::new(block, &after).unwrap();
    let u0 = twist(&before, [v, 0.0, 0.0]).unwrap();
    let u1 = twist(&after, kept.rates).unwrap();
    for k in 0..3 {
        assert!(after.n[k].dot(&u1.at(&after.r[k])).abs() < 1e-12);
    }
    let (k0, k1) = (
        u0.kinetic_energy(block.mass, &inertia),
        u1.kinetic_energy(block.mass, &inertia),
    );
    assert!(kept.removed < 0.0);
    assert!(
        (k1 - k0 - kept.removed).abs() < 1e-9 * k0,
        "{k0} {k1} {kept:?}"
    );
    // At most the energy of the velocity off the face, as if contact 1 were the whole mass.
    let off = 0.5 * block.mass * (v * delta.sin()).powi(2);
    assert!(-kept.removed < off, "{} {off}", kept.removed);
}

#[test]
fn the_crease_projection_stops_the_contact_at_the_second_face_and_takes_only_that_energy() {
    // Rates that drive contact 2 into the groove's second face: after the projection its
    // velocity along that face's normal is zero, and the kinetic energy lost is exactly what
    // the projection says it removed (a projection in the kinetic-energy metric keeps the
    // part of the motion that is free and drops the rest, ½|Δv|²_M).
    let (d, geom, crease, _) = groove(30f64.to_radians());
    let block = d.first_body().block();
    let inertia = Inertia::new(block, &geom).unwrap();
    for rates in [[1.0, 0.3, 0.0], [0.2, -0.5, 0.05], [0.0, 0.0, 0.1]] {
        let before = twist(&geom, rates).unwrap();
        let into = crease.normal.dot(&before.at(&geom.r[2]));
        assert!(into.abs() > 1e-3, "the test rates must push into the face");
        let (projected, removed) = crease_rates(&geom, block, rates, &crease.into()).unwrap();
        let after = twist(&geom, projected).unwrap();
        assert!(crease.normal.dot(&after.at(&geom.r[2])).abs() < 1e-12);
        let (k0, k1) = (
            before.kinetic_energy(block.mass, &inertia),
            after.kinetic_energy(block.mass, &inertia),
        );
        assert!(removed < 0.0);
        assert!((k1 - k0 - removed).abs() < 1e-9 * k0, "{k0} {k1} {removed}");
        // Rates already on the face are left as they are.
        let (again, none) = crease_rates(&geom, block, projected, &crease.into()).unwrap();
        assert!((0..3).all(|k| (again[k] - projected[k]).abs() < 1e-12));
        assert!(none.abs() < 1e-9 * k0);
    }
}
