//! Any contact triangle and foundations of faces (issue #15): the paper's scene written in the
//! general forms follows the paper's route; a contact that reaches another face ends the route
//! there, naming both; every row agrees with the direct pose solver.

use crate::common;
use slideroute::stages::route::{self, Reason, Route};
use slideroute::stages::scene::{DynamicsModel, Scene};

fn scene_file(name: &str) -> Scene {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("scenes")
        .join(format!("{name}.toml"));
    Scene::from_file(&path).unwrap()
}

/// The default scene with its frame written as `contacts_m` (the general system's site).
fn default_as_contacts() -> Scene {
    let text = slideroute::stages::scene::DEFAULT_SCENE_TOML;
    let start = text.find("l1x =").unwrap();
    let end = text[start..].find("[foundation]").unwrap() + start;
    let text = format!(
        "{}contacts_m = [[-6.0, 5.0], [4.0, 5.0], [4.0, -5.0]]\n\n{}",
        &text[..start],
        &text[end..]
    );
    Scene::from_toml(&text, "contacts").unwrap()
}

fn run(s: &Scene, model: DynamicsModel) -> Route {
    route::run(&s.with_dynamics(model).unwrap()).unwrap()
}

/// The largest difference of position (m) and yaw (°) between two routes' rows.
fn worst(a: &Route, b: &Route) -> (f64, f64) {
    assert_eq!(a.rows.len(), b.rows.len());
    a.rows
        .iter()
        .zip(&b.rows)
        .fold((0.0f64, 0.0f64), |(p, t), (r, q)| {
            (
                p.max((r.x_m - q.x_m).abs()).max((r.z_m - q.z_m).abs()),
                t.max((r.theta_deg - q.theta_deg).abs()),
            )
        })
}

#[test]
fn the_papers_scene_as_any_triangle_follows_the_papers_route() {
    // Same frame, same planes, the general pose system instead of the paper's (13), (14): the
    // paper's dynamics agrees to round-off; the rigid body's events (stick, slip, pivots) are
    // located by bisection on quantities that round-off moves, so to 1e-6 m and 1e-5°.
    let (paper, general) = (Scene::default_scene(), default_as_contacts());
    assert!(general.site().as_paper().is_none());
    let (a, b) = (
        run(&paper, DynamicsModel::Paper),
        run(&general, DynamicsModel::Paper),
    );
    assert_eq!(a.termination.reason, b.termination.reason);
    let (dp, dt) = worst(&a, &b);
    assert!(dp < 1e-12 * a.travel_m && dt < 1e-10, "{dp:e} m, {dt:e}°");
    let (a, b) = (
        run(&paper, DynamicsModel::RigidBody),
        run(&general, DynamicsModel::RigidBody),
    );
    assert_eq!(a.termination.reason, b.termination.reason);
    assert!((a.termination.t_s - b.termination.t_s).abs() < 1e-6);
    let (dp, dt) = worst(&a, &b);
    assert!(dp < 1e-6 && dt < 1e-5, "{dp:e} m, {dt:e}°");
    common::assert_rows_match_direct(&general, &b.rows);
}

#[test]
fn on_the_papers_faces_contact_2_rides_the_crease_then_plane_1_alone_until_contact_0_meets_it() {
    // Contact 2 starts where the level face and both planes meet; it goes under plane 1 at
    // once and rides the crease of planes 1 and 2 (derivations/10-faces.md §4). Plane 2 lets
    // go of it at 3.79 s (Drake: 3.8 s) and it goes on along plane 1 alone; contact 0 meets
    // plane 1 at 4.217 s, and the impact lifts contact 1 off: the route ends there (Drake:
    // contact 0 crosses plane 1's strike at 4.2155 s, and contact 1 lifts). Drake's path is
    // compared in `drake_crosscheck.rs`.
    let s = scene_file("paper-like-faces");
    let r = run(&s, DynamicsModel::RigidBody);
    assert_eq!(r.termination.reason, Reason::ContactLiftedOff);
    assert!(
        r.termination
            .detail
            .contains("the impact of contact 0 on face 1 lifts contact 1 off face 1"),
        "{}",
        r.termination.detail
    );
    assert!(
        (r.termination.t_s - 4.217).abs() < 0.005,
        "{}",
        r.termination.t_s
    );
    // While it rides the crease (until plane 2 lets go, 3.79 s), contact 2 is on both planes:
    // the direct solver on the scene's planes (contact 2 on plane 2) puts it on plane 1 too.
    let (ground, _) = s.site().ground().unwrap();
    let plane_1 = ground.faces()[1];
    let mut near = None;
    let mut checked = 0;
    for row in r.rows.iter().filter(|w| w.t_s > 0.01 && w.t_s < 3.78) {
        let d = slideroute::stages::geometry::Displacement::new(
            row.x_m,
            row.z_m,
            row.theta_deg.to_radians(),
        );
        let p = match &near {
            Some(q) => slideroute::stages::geometry::direct::solve_from(s.site(), d, q),
            None => slideroute::stages::geometry::direct::solve(s.site(), d),
        }
        .unwrap();
        let off = plane_1.signed_distance(&p.vertices[2]);
        assert!(
            off.abs() < 1e-9,
            "contact 2 {off:e} m off plane 1 at {} s",
            row.t_s
        );
        near = Some(p);
        checked += 1;
    }
    assert!(checked > 3000, "{checked}");
    // The energy balance closes: the crease's projections book what they take as friction
    // work.
    let e = r.energy.unwrap();
    assert!(e.residual_j.abs() < 1e-6 * e.work_hydraulic_j, "{e:?}");
    // At 3 s, where Drake's refined path has travelled 4.578 m (horizontal) and turned 2.067°.
    let (travel, theta) = at_time(&r, 3.0);
    assert!((travel - 4.578).abs() < 0.01 * 4.578, "{travel}");
    assert!((theta - 2.067).abs() < 0.05, "{theta}");
    // The paper's dynamics moves contact 2 up plane 2, which rises faster along x' than plane
    // 1: it stays on its face, and the route is the paper's own.
    let (a, b) = (
        run(&Scene::default_scene(), DynamicsModel::Paper),
        run(&s, DynamicsModel::Paper),
    );
    assert_eq!(a.termination.reason, b.termination.reason);
    let (dp, dt) = worst(&a, &b);
    assert!(dp < 1e-9 && dt < 1e-7, "{dp:e} m, {dt:e}°");
}

/// The horizontal path length of the CM and the yaw at the row nearest `t`.
fn at_time(r: &Route, t: f64) -> (f64, f64) {
    let mut travel = 0.0;
    for w in r.rows.windows(2) {
        travel += (w[1].x_m - w[0].x_m).hypot(w[1].z_m - w[0].z_m);
        if w[1].t_s >= t {
            return (travel, w[1].theta_deg);
        }
    }
    (travel, r.rows.last().unwrap().theta_deg)
}

#[test]
fn on_a_rough_valley_surface_the_route_runs_to_a_stated_end_on_the_faces_under_its_contacts() {
    // scenes/valley.toml: 864 triangles (scenes/valley.obj, from scenes/make_valley.py). The
    // block slides up the 20° floor until contact 1 meets the first rough triangle's edge,
    // where the ground falls away below its face: a ridge, the end of a three-point model.
    let s = scene_file("valley");
    let (ground, faces) = s.site().ground().unwrap();
    assert!(ground.is_surface());
    let r = run(&s, DynamicsModel::RigidBody);
    assert!(
        matches!(
            r.termination.reason,
            Reason::ContactOverRidge | Reason::ContactReachedAnotherFace | Reason::TimeLimit
        ),
        "{:?}",
        r.termination
    );
    assert!(r.travel_m > 1.0, "{}", r.travel_m);
    // Every row: each contact on its own face's plane (the direct solver on those planes).
    common::assert_rows_match_direct(&s, &r.rows);
    // And over that face's triangle, or on its edge, to the route's last accepted state.
    let last = r.rows.last().unwrap();
    let pose = slideroute::stages::geometry::direct::solve(
        s.site(),
        slideroute::stages::geometry::Displacement::new(
            last.x_m,
            last.z_m,
            last.theta_deg.to_radians(),
        ),
    )
    .unwrap();
    for (k, v) in pose.vertices.iter().enumerate() {
        let (_, top) = ground.top(v.x, v.z).expect("on the surface");
        let own = ground.faces()[faces[k]].height(v.x, v.z);
        assert!(
            (top - own).abs() < 1e-6,
            "contact {k}: ground {top}, own face {own}"
        );
    }
}

#[test]
fn on_four_faces_contacts_climb_from_face_to_face_and_every_row_stands_on_the_ground() {
    // scenes/four-faces.toml: contact 1 meets the 8° face (an impact), climbs onto it, leaves
    // it for the 20° face; contact 0 meets the 8° face; the impact of contact 0 on the 20° face
    // throws contact 1 off (Drake agrees: `drake_crosscheck.rs`). Every row: each contact on
    // the face the row names (the direct pose solver on the site of those faces gives the row's
    // CM height) and none under the ground; the energy balance closes with the impacts' losses
    // booked.
    let s = scene_file("four-faces");
    let (ground, _) = s.site().ground().unwrap();
    let r = run(&s, DynamicsModel::RigidBody);
    assert_eq!(r.termination.reason, Reason::ContactLiftedOff);
    assert!(
        r.termination
            .detail
            .contains("the impact of contact 0 on face 2 lifts contact 1"),
        "{}",
        r.termination.detail
    );
    let mut seen = vec![r.rows[0].faces];
    let l = s.l();
    let mut near: Option<slideroute::stages::geometry::direct::DirectPose> = None;
    for row in &r.rows {
        if *seen.last().unwrap() != row.faces {
            seen.push(row.faces);
            near = None;
        }
        let mut site = s.site().clone();
        for (k, &f) in row.faces.iter().enumerate() {
            site = site.with_face(k, f as usize).unwrap();
        }
        let d = slideroute::stages::geometry::Displacement::new(
            row.x_m,
            row.z_m,
            row.theta_deg.to_radians(),
        );
        let p = match &near {
            Some(q) => slideroute::stages::geometry::direct::solve_from(&site, d, q),
            None => slideroute::stages::geometry::direct::solve(&site, d),
        }
        .unwrap();
        assert!(
            (p.cm_y - row.y_m).abs() < 1e-9 * l,
            "CM height at {} s",
            row.t_s
        );
        for (k, v) in p.vertices.iter().enumerate() {
            let (_, top) = ground.top(v.x, v.z).unwrap();
            assert!(
                top - v.y < 1e-6 * l,
                "contact {k} under the ground at {} s",
                row.t_s
            );
        }
        near = Some(p);
    }
    assert_eq!(seen, [[0, 0, 3], [0, 1, 3], [0, 2, 3], [1, 2, 3]]);
    let e = r.energy.unwrap();
    assert!(e.residual_j.abs() < 1e-6 * e.work_hydraulic_j, "{e:?}");
    assert!(e.work_friction_j < 0.0);
}
