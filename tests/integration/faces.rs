//! Any contact triangle and foundations of faces: the paper's scene written in the
//! general forms follows the paper's route; a contact that reaches another face ends the route
//! there, naming both; every row agrees with the direct pose solver.

use crate::common;
use slideroute::Plane;
use slideroute::internals::{model::DynamicsModel, scene::Scene};
use slideroute::{Reason, Route};

fn scene_file(name: &str) -> Scene {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("scenes")
        .join(format!("{name}.toml"));
    Scene::from_file(&path).unwrap()
}

/// The default scene with its frame written as `contacts_m` (the general system's site).
fn default_as_contacts() -> Scene {
    let text = slideroute::Scene::DEFAULT_TOML;
    let start = text.find("l1x =").unwrap();
    let end = text[start..].find("[foundation]").unwrap() + start;
    let text = format!(
        "{}contacts_m = [[-6.0, 5.0], [4.0, 5.0], [4.0, -5.0]]\n\n{}",
        &text[..start],
        &text[end..]
    );
    Scene::from_toml(&text, "contacts").unwrap()
}

/// The route of `s` under `model` on the paper's three-point frame (`contacts = "frame"`: these
/// tests are the frame's on faces; `base_contact.rs` has the base's).
fn run(s: &Scene, model: DynamicsModel) -> Route {
    let s = s.with_dynamics(model).unwrap();
    slideroute::run(&s.with("solver.contacts", "frame").unwrap()).unwrap()
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
        let d = slideroute::internals::geometry::Displacement::new(
            row.x_m,
            row.z_m,
            row.theta_deg.to_radians(),
        );
        let p = match &near {
            Some(q) => slideroute::internals::geometry::direct::solve_from(s.site(), d, q),
            None => slideroute::poses::direct_pose(s.site(), d),
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
    let e = r.energy().unwrap();
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
fn on_a_rough_valley_surface_contacts_cross_ridges_and_the_route_runs_to_a_stated_end() {
    // scenes/valley.toml: 864 triangles (scenes/valley.obj, from scenes/make_valley.py). The
    // block slides up the 20° floor; contact 1 runs over the first rough triangle's edge onto a
    // gentler face (a ridge it crosses: the hop is far below a millimetre), contacts 1 and 2
    // meet steeper triangles and climb onto them, and the route ends where a ridge would throw
    // a contact off faster than a hop.
    let s = scene_file("valley");
    let (ground, _) = s.site().ground().unwrap();
    assert!(ground.is_surface());
    let r = run(&s, DynamicsModel::RigidBody);
    assert!(
        matches!(
            r.termination.reason,
            Reason::ContactLiftedOff
                | Reason::ContactOverRidge
                | Reason::ContactReachedAnotherFace
                | Reason::TimeLimit
        ),
        "{:?}",
        r.termination
    );
    assert!(!r.termination.detail.is_empty());
    assert!(r.travel_m > 2.0, "{}", r.travel_m);
    let seen = assert_rows_on_their_faces(&s, &r);
    assert!(seen.len() > 1, "a contact changes its face: {seen:?}");
}

/// Every row of `r` has each contact on the face the row names (the direct pose solver on the
/// site of those faces gives the row's CM height) and none under the ground; the energy
/// balance closes with the impacts' losses booked. Returns the faces under the contacts, in
/// turn.
fn assert_rows_on_their_faces(s: &Scene, r: &Route) -> Vec<[u32; 3]> {
    let (ground, _) = s.site().ground().unwrap();
    let mut seen = vec![r.rows[0].faces];
    let l = s.l();
    let mut near: Option<slideroute::poses::DirectPose> = None;
    for row in &r.rows {
        if *seen.last().unwrap() != row.faces {
            seen.push(row.faces);
            near = None;
        }
        let mut site = s.site().clone();
        for (k, &f) in row.faces.iter().enumerate() {
            site = site.with_face(k, f as usize).unwrap();
        }
        let d = slideroute::internals::geometry::Displacement::new(
            row.x_m,
            row.z_m,
            row.theta_deg.to_radians(),
        );
        let p = match &near {
            Some(q) => slideroute::internals::geometry::direct::solve_from(&site, d, q),
            None => slideroute::poses::direct_pose(&site, d),
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
    let e = r.energy().unwrap();
    assert!(e.residual_j.abs() < 1e-6 * e.work_hydraulic_j, "{e:?}");
    assert!(e.work_friction_j < 0.0);
    seen
}

#[test]
fn on_four_faces_contacts_climb_from_face_to_face_and_every_row_stands_on_the_ground() {
    // scenes/four-faces.toml: contact 1 meets the 8° face (an impact), climbs onto it, leaves
    // it for the 20° face; contact 0 meets the 8° face; the impact of contact 0 on the 20° face
    // throws contact 1 off (Drake agrees: `drake_crosscheck.rs`).
    let s = scene_file("four-faces");
    let r = run(&s, DynamicsModel::RigidBody);
    assert_eq!(r.termination.reason, Reason::ContactLiftedOff);
    assert!(
        r.termination
            .detail
            .contains("the impact of contact 0 on face 2 lifts contact 1"),
        "{}",
        r.termination.detail
    );
    let seen = assert_rows_on_their_faces(&s, &r);
    assert_eq!(seen, [[0, 0, 3], [0, 1, 3], [0, 2, 3], [1, 2, 3]]);
}

/// The ground of `planes` (the highest of them) as triangles over the plan rectangle
/// (x0, x1, z0, z1): each plane's part — the rectangle clipped by h_f ≥ h_g for every other
/// plane g, a convex polygon — fanned into triangles (X, Y, Z), each split `levels` times into
/// four at its sides' midpoints (so that contacts cross coplanar neighbours, and ride creases
/// past the corners of triangles).
fn envelope_triangles(
    planes: &[Plane],
    (x0, x1, z0, z1): (f64, f64, f64, f64),
    levels: u32,
) -> Vec<[[f64; 3]; 3]> {
    fn split(t: [[f64; 3]; 3], levels: u32) -> Vec<[[f64; 3]; 3]> {
        if levels == 0 {
            return vec![t];
        }
        let mid = |a: [f64; 3], b: [f64; 3]| {
            [
                0.5 * (a[0] + b[0]),
                0.5 * (a[1] + b[1]),
                0.5 * (a[2] + b[2]),
            ]
        };
        let (ab, bc, ca) = (mid(t[0], t[1]), mid(t[1], t[2]), mid(t[2], t[0]));
        [[t[0], ab, ca], [ab, t[1], bc], [ca, bc, t[2]], [ab, bc, ca]]
            .into_iter()
            .flat_map(|q| split(q, levels - 1))
            .collect()
    }
    let mut out = Vec::new();
    for (f, pf) in planes.iter().enumerate() {
        let mut poly = vec![[x0, z0], [x1, z0], [x1, z1], [x0, z1]];
        for (g, pg) in planes.iter().enumerate() {
            if g == f || poly.is_empty() {
                continue;
            }
            // Sutherland–Hodgman against d ≥ 0, d affine in (X, Z).
            let d = |p: &[f64; 2]| pf.height(p[0], p[1]) - pg.height(p[0], p[1]);
            let mut next = Vec::new();
            for k in 0..poly.len() {
                let (a, b) = (poly[k], poly[(k + 1) % poly.len()]);
                let (da, db) = (d(&a), d(&b));
                if da >= 0.0 {
                    next.push(a);
                }
                if (da >= 0.0) != (db >= 0.0) {
                    let t = da / (da - db);
                    next.push([a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1])]);
                }
            }
            poly = next;
        }
        let at = |p: [f64; 2]| [p[0], pf.height(p[0], p[1]), p[1]];
        for k in 1..poly.len().saturating_sub(1) {
            let t = [at(poly[0]), at(poly[k]), at(poly[k + 1])];
            // Slivers of round-off at a corner are no faces.
            let (u, v) = (
                [t[1][0] - t[0][0], t[1][2] - t[0][2]],
                [t[2][0] - t[0][0], t[2][2] - t[0][2]],
            );
            if (u[0] * v[1] - u[1] * v[0]).abs() > 1e-9 {
                out.extend(split(t, levels));
            }
        }
    }
    out
}

/// `name`'s scene with its plane list replaced by the same ground as a triangulated surface
/// (written to a scratch folder as OBJ).
pub(super) fn as_surface(name: &str) -> Scene {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes");
    let text = std::fs::read_to_string(root.join(format!("{name}.toml"))).unwrap();
    let s = Scene::from_toml(&text, name).unwrap();
    let (ground, _) = s.site().ground().unwrap();
    let triangles = envelope_triangles(ground.faces(), (-30.0, 60.0, -40.0, 40.0), 4);
    let dir =
        std::env::temp_dir().join(format!("slideroute-{name}-surface-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let mut obj = String::new();
    for t in &triangles {
        for v in t {
            obj += &format!("v {:.17e} {:.17e} {:.17e}\n", v[0], v[1], v[2]);
        }
    }
    for k in 0..triangles.len() {
        obj += &format!("f {} {} {}\n", 3 * k + 1, 3 * k + 2, 3 * k + 3);
    }
    std::fs::write(dir.join("ground.obj"), obj).unwrap();
    let start = text.find("[foundation]").unwrap();
    let end = text.find("[block]").unwrap();
    let text = format!(
        "{}[foundation]\nsurface = \"ground.obj\"\n\n{}",
        &text[..start],
        &text[end..]
    );
    std::fs::write(dir.join("scene.toml"), text).unwrap();
    Scene::from_file(&dir.join("scene.toml")).unwrap()
}

#[test]
fn a_ground_of_planes_written_as_a_triangulated_surface_gives_the_same_route() {
    // The surface's events (a contact meeting a triangle, riding the crease of two, climbing
    // onto one, an impact that lifts a contact) against the plane list's, which Drake checks
    // (`drake_crosscheck.rs`): the same triangles' planes, so the same route — crossings onto a
    // coplanar neighbour unnoticed.
    for name in ["four-faces", "paper-like-faces"] {
        let planes = scene_file(name);
        let surface = as_surface(name);
        let a = run(&planes, DynamicsModel::RigidBody);
        let b = run(&surface, DynamicsModel::RigidBody);
        assert_eq!(a.termination.reason, b.termination.reason, "{name}");
        assert!(
            (a.termination.t_s - b.termination.t_s).abs() < 1e-6,
            "{name}: {} s against {} s",
            a.termination.t_s,
            b.termination.t_s
        );
        let (pos, yaw) = worst(&a, &b);
        assert!(
            pos < 1e-6 * planes.l() && yaw < 1e-6,
            "{name}: {pos} m, {yaw}°"
        );
        // The faces under the contacts, as planes: each triangle's plane is its plane's.
        let (tri, _) = surface.site().ground().unwrap();
        let (pl, _) = planes.site().ground().unwrap();
        for (r, q) in a.rows.iter().zip(&b.rows) {
            for k in 0..3 {
                let (p, t) = (
                    pl.faces()[r.faces[k] as usize],
                    tri.faces()[q.faces[k] as usize],
                );
                assert!(
                    p.is_parallel(&t, 1e-9),
                    "{name}: contact {k} at {} s",
                    r.t_s
                );
            }
        }
        assert_rows_on_their_faces(&surface, &b);
    }
}

/// [`common::crease_chatter_text`] as a scene.
fn crease_chatter(dt_s: &str, t_end_s: &str) -> Scene {
    Scene::from_toml(
        &common::crease_chatter_text(dt_s, t_end_s),
        "crease-chatter",
    )
    .unwrap()
}

#[test]
fn a_block_shaken_at_a_crease_runs_to_the_records_end_alike_at_every_step() {
    // crease_chatter. At dt 2, 2.5 and 3 ms the route looped at one moment and ended "the
    // contact forces are not determined" (1.7805, 1.7791 and 1.4488 s; it had looped for ever
    // before the 64-events guard): contact 0's slow slip, its direction slaved in its own
    // tangent plane while contact 2 rode the crease, made the crease's second face pull, and
    // contact 2, let go, went back into that face at once. A block in a crease has no slip
    // slaved now (`derivations/08-rigid-body.md` §3). With young slips no longer slaved, at
    // 2 to 6 ms contact 2 grazed plane 1 at 0.7214 s, just after the block began to slip, and
    // at the crease could neither stay nor slip consistently: the route ended "the contact
    // forces are not determined". It leaves one of the crease's faces there, the one it moves
    // off (`derivations/10-faces.md` §6). It runs to the record's end at every step from 0.25
    // to 6 ms, where the finest ends (measured: x within 1.2e-3 of it; against refined Drake
    // in `drake_crosscheck.rs`).
    let end = |dt: &str| {
        let route = slideroute::run(&crease_chatter(dt, "1.9")).unwrap();
        let end = &route.termination;
        assert_eq!(
            end.reason,
            Reason::TimeLimit,
            "dt {dt}: {} at {} s",
            end.detail,
            end.t_s
        );
        let w = *route.rows.last().unwrap();
        (w.x_m, w.z_m, w.theta_deg)
    };
    let fine = end("2.5e-4");
    for dt in ["6.0e-3", "5.0e-3", "3.0e-3", "2.5e-3", "2.0e-3", "1.0e-3"] {
        let (x, z, theta) = end(dt);
        assert!(
            (x - fine.0).abs() < 2e-3 * fine.0,
            "dt {dt}: x {x} against {fine:?}"
        );
        assert!((z - fine.1).abs() < 5e-5, "dt {dt}: z {z} against {fine:?}");
        assert!(
            (theta - fine.2).abs() < 1e-3,
            "dt {dt}: θ {theta}° against {fine:?}"
        );
    }
}
