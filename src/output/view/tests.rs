use super::*;
use crate::geometry::direct;
use crate::{Displacement, Pose};
use nalgebra::Vector3;

fn scene(name: &str) -> Scene {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("scenes")
        .join(name);
    Scene::from_file(&path).unwrap()
}

fn route(scene: &Scene) -> Route {
    crate::analysis::run(scene).unwrap()
}

/// The contacts in world axes at kept pose `k` of `view`.
fn contacts_at(view: &View3d, k: usize) -> Vec<Vector3<f64>> {
    let p = &view.poses[k];
    let q = UnitQuaternion::from_quaternion(nalgebra::Quaternion::new(
        p.rotation[3],
        p.rotation[0],
        p.rotation[1],
        p.rotation[2],
    ));
    let at = Vector3::new(p.at[0], p.at[1], p.at[2]);
    view.points
        .iter()
        .map(|c| at + q * Vector3::new(c[0], c[1], c[2]))
        .collect()
}

/// The signed volume a closed mesh encloses (positive where every triangle faces out).
fn volume(mesh: &Mesh) -> f64 {
    mesh.triangles
        .iter()
        .map(|t| {
            let [a, b, c] = t.map(|k| {
                let p = mesh.positions[k as usize];
                Vector3::new(p[0], p[1], p[2])
            });
            a.dot(&b.cross(&c)) / 6.0
        })
        .sum()
}

#[test]
fn the_contacts_stand_where_the_plan_view_puts_them_on_the_papers_site() {
    // The plan view places the paper's frame by its tilts (`Pose::from_tilts`); the view's
    // node, rotated from the row's yaw and tilts, must put the contacts on the same points.
    let scene = Scene::default_scene();
    let route = route(&scene);
    let view = view_of(&scene, &route).unwrap();
    let paper = scene.site().as_paper().unwrap();
    assert!(view.poses.len() > 100);
    for k in [0, view.poses.len() / 3, view.poses.len() - 1] {
        let p = &view.poses[k];
        let d = Displacement::new(p.at[0], p.at[2], p.theta_deg.to_radians());
        let pose =
            Pose::from_tilts(paper, d, p.alpha_deg.to_radians(), p.beta_deg.to_radians()).unwrap();
        for (c, v) in contacts_at(&view, k).iter().zip(pose.vertices) {
            assert!((c - v).norm() < 1e-9, "pose {k}: {c} against {v}");
        }
    }
    // The default route turns to +40° and ends with contact 0 at an inclined plane's strike.
    let last = view.poses.last().unwrap();
    assert!((last.theta_deg - route.rows.last().unwrap().theta_deg).abs() < 1e-12);
    assert!(last.theta_deg > 30.0);
}

#[test]
fn the_contacts_stand_where_the_direct_solver_puts_them_on_faces() {
    // Away from the paper's site the plan view places the frame by the direct pose solver.
    let scene = scene("paper-like-faces.toml")
        .with_keys([
            ("solver.t_end_s", toml::Value::from(1.0)),
            ("solver.contacts", toml::Value::from("frame")),
        ])
        .unwrap();
    let route = route(&scene);
    let view = view_of(&scene, &route).unwrap();
    for k in [1, view.poses.len() / 2, view.poses.len() - 1] {
        let p = &view.poses[k];
        let d = Displacement::new(p.at[0], p.at[2], p.theta_deg.to_radians());
        let pose = direct::solve(scene.site(), d).unwrap();
        for (c, v) in contacts_at(&view, k).iter().zip(pose.vertices) {
            assert!((c - v).norm() < 1e-7, "pose {k}: {c} against {v}");
        }
    }
}

#[test]
fn a_long_route_is_thinned_to_at_most_four_thousand_poses_and_its_page_stays_small() {
    // 10⁵ rows: the default route's, each repeated with its time spread out.
    let scene = Scene::default_scene();
    let mut long = route(&scene);
    let rows = long.rows.clone();
    let n = 100_000;
    long.rows = (0..n)
        .map(|k| {
            let r = rows[k * rows.len() / n];
            Row {
                t_s: k as f64 * 1e-4,
                ..r
            }
        })
        .collect();
    let view = view_of(&scene, &long).unwrap();
    assert!(view.poses.len() <= MAX_POSES, "{}", view.poses.len());
    assert!(view.poses.len() > MAX_POSES / 2);
    assert_eq!(view.poses[0].t_s, 0.0);
    assert_eq!(view.poses.last().unwrap().t_s, (n - 1) as f64 * 1e-4);
    // The last pose's travel is the route's.
    assert!((view.poses.last().unwrap().travel_m - long.travel_m).abs() < 1e-9);
    let page = html::page(&view).unwrap();
    assert!(page.len() < 10_000_000, "{} bytes", page.len());
    // The page's data reads back, with its poses.
    let start = page.find(r#"id="route-data">"#).unwrap() + r#"id="route-data">"#.len();
    let end = start + page[start..].find("</script>").unwrap();
    let data: serde_json::Value = serde_json::from_str(&page[start..end]).unwrap();
    assert_eq!(data["mode"], "route");
    let data = &data["routes"][0];
    assert_eq!(
        data["poses"]["t"].as_array().unwrap().len(),
        view.poses.len()
    );
    assert_eq!(
        data["poses"]["q"].as_array().unwrap().len(),
        4 * view.poses.len()
    );
    // three.js and its controls are embedded, not fetched.
    assert!(!page.contains("src=\"http") && !page.contains("unpkg") && !page.contains("cdn"));
    assert!(page.contains("data:text/javascript;base64,"));
}

#[test]
fn every_block_shape_is_closed_and_faces_out() {
    // A monolith: its section (area (b + c)/2·h) over its width, base on y' = 0.
    let monolith = scene("monolith.toml");
    let m = *monolith.monolith().unwrap();
    let s = m.section;
    let contacts = *monolith.site().contacts();
    let (mesh, shape) = block_mesh(&monolith, monolith.base(), &contacts, 10.0);
    assert_eq!(shape, BlockShape::Monolith);
    let want = (s.base_length + s.crest_length) / 2.0 * s.height * s.width;
    assert!(
        (volume(&mesh) - want).abs() < 1e-9 * want,
        "{}",
        volume(&mesh)
    );
    let (lo, hi) = mesh.bounds().unwrap();
    assert!((lo[0] + m.props.cm_from_heel).abs() < 1e-12 && lo[1] == 0.0);
    assert!((hi[1] - s.height).abs() < 1e-12 && (hi[2] - s.width / 2.0).abs() < 1e-12);
    // The frame's triangle as a slab: L²/2 by 0.08 L.
    let paper = Scene::default_scene();
    let contacts = *paper.site().contacts();
    let (mesh, shape) = block_mesh(&paper, None, &contacts, 10.0);
    assert_eq!(shape, BlockShape::Frame);
    assert!((volume(&mesh) - 50.0 * 0.8).abs() < 1e-9);
    // A base: its outline's area by twice the CM's depth.
    let base = Base::polygon(
        vec![[-6.0, 5.0], [4.0, 5.0], [4.0, -5.0], [-6.0, -5.0]],
        1.5,
    )
    .unwrap();
    let (mesh, shape) = block_mesh(&paper, Some(&base), &contacts, 10.0);
    assert_eq!(shape, BlockShape::Base);
    assert!((volume(&mesh) - 100.0 * 3.0).abs() < 1e-9);
}

#[test]
fn the_foundation_covers_the_route_at_the_grounds_height() {
    for name in ["paper-like.toml", "paper-like-faces.toml", "valley.toml"] {
        let scene = scene(name).with("solver.t_end_s", 1.0).unwrap();
        let route = route(&scene);
        let view = view_of(&scene, &route).unwrap();
        assert!(!view.ground.triangles.is_empty(), "{name}");
        let (lo, hi) = view.ground.bounds().unwrap();
        for p in &view.poses {
            assert!(
                (lo[0]..=hi[0]).contains(&p.at[0]) && (lo[2]..=hi[2]).contains(&p.at[2]),
                "{name}: {:?} outside the ground",
                p.at
            );
        }
        // Every corner of the ground is on the scene's ground: the highest plane, or the
        // surface.
        let site = scene.site();
        for p in view.ground.positions.iter().step_by(7) {
            let top = match site.ground() {
                Some((g, _)) if g.is_surface() => continue,
                Some((g, _)) => g.top(p[0], p[2]).unwrap().1,
                None => site
                    .planes()
                    .iter()
                    .map(|q| q.height(p[0], p[2]))
                    .fold(f64::MIN, f64::max),
            };
            assert!((p[1] - top).abs() < 1e-9, "{name}: {p:?} against {top}");
        }
        assert_eq!(view.ground.colors.len(), view.ground.positions.len());
    }
}

#[test]
fn a_contact_held_by_friction_is_shown_sticking_and_a_sliding_one_slipping() {
    // The default route slides on all three contacts after its start.
    let paper = Scene::default_scene().with("solver.t_end_s", 1.0).unwrap();
    let view = view_of(&paper, &route(&paper)).unwrap();
    let mid = &view.poses[view.poses.len() / 2];
    assert_eq!(mid.touch, vec![Touch::Slipping; 3]);
    // scenes/pivot-held.toml: a contact sticks on its strike line while the block turns.
    let held = scene("pivot-held.toml");
    let view = view_of(&held, &route(&held)).unwrap();
    let sticking = view
        .poses
        .iter()
        .filter(|p| p.touch.contains(&Touch::Sticking) && p.touch.contains(&Touch::Slipping))
        .count();
    assert!(sticking > 10, "{sticking} poses with a contact sticking");
}

#[test]
fn route_glb_is_a_valid_binary_gltf_whose_block_starts_at_the_first_row() {
    let scene = Scene::default_scene().with("solver.t_end_s", 1.0).unwrap();
    let route = route(&scene);
    let view = view_of(&scene, &route).unwrap();
    let bytes = glb::glb(&view).unwrap();
    assert_eq!(&bytes[..4], b"glTF");
    assert_eq!(u32::from_le_bytes(bytes[4..8].try_into().unwrap()), 2);
    assert_eq!(
        u32::from_le_bytes(bytes[8..12].try_into().unwrap()) as usize,
        bytes.len()
    );
    let json_len = u32::from_le_bytes(bytes[12..16].try_into().unwrap()) as usize;
    assert_eq!(json_len % 4, 0);
    assert_eq!(&bytes[16..20], b"JSON");
    assert_eq!(&bytes[20 + json_len + 4..20 + json_len + 8], b"BIN\0");
    let gltf = gltf::Gltf::from_slice(&bytes).unwrap();
    let block = gltf.nodes().find(|n| n.name() == Some(glb::BLOCK)).unwrap();
    let (t, _, _) = block.transform().decomposed();
    let first = &route.rows[0];
    assert!((f64::from(t[0]) - first.x_m).abs() < 1e-6);
    assert_eq!(gltf.animations().count(), 1);
    assert_eq!(gltf.meshes().count(), 3);
}

#[test]
fn a_route_without_rows_or_with_a_number_not_finite_has_no_view_and_no_panic() {
    let scene = Scene::default_scene().with("solver.t_end_s", 0.1).unwrap();
    let mut r = route(&scene);
    let rows = r.rows.clone();
    r.rows.clear();
    assert_eq!(view_of(&scene, &r), Err(ViewError::NoRows));
    r.rows = rows.clone();
    r.rows[1].theta_deg = f64::NAN;
    assert_eq!(view_of(&scene, &r), Err(ViewError::NotFinite));
    // Tilts no rotation fits (sides rising more than they are long) keep the pose before.
    r.rows = rows;
    r.rows[2].alpha_deg = 80.0;
    r.rows[2].beta_deg = -80.0;
    let view = view_of(&scene, &r).unwrap();
    assert_eq!(view.poses[2].rotation, view.poses[1].rotation);
}

#[test]
fn compare_html_holds_both_dynamics_each_with_its_own_times_colour_and_end() {
    let scene = Scene::default_scene();
    let c = crate::compare::compare_dynamics_observed(&scene, || false).unwrap();
    let (paper, rigid) = (&c.paper.route, &c.rigid_body.route);
    let page = many::compare_page(&scene, paper, rigid).unwrap();
    assert_eq!(page.mode, many::Mode::Compare);
    assert_eq!(page.routes.len(), 2);
    assert_ne!(page.routes[0].color, page.routes[1].color);
    for (shown, route) in page.routes.iter().zip([paper, rigid]) {
        let times: Vec<f64> = shown.view.poses.iter().map(|p| p.t_s).collect();
        assert_eq!(times[0], route.rows[0].t_s);
        assert_eq!(*times.last().unwrap(), route.rows.last().unwrap().t_s);
        assert!(times.windows(2).all(|w| w[0] <= w[1]));
        assert_eq!(shown.view.dynamics, route.dynamics.to_string());
        assert!(shown.label.starts_with(&route.dynamics.to_string()));
        assert_eq!(shown.view.end_t_s, route.termination.t_s);
        // The one foundation covers this route too.
        let (lo, hi) = page.ground.bounds().unwrap();
        for p in &shown.view.poses {
            assert!((lo[0]..=hi[0]).contains(&p.at[0]) && (lo[2]..=hi[2]).contains(&p.at[2]));
        }
    }
    // The default scene's two dynamics end at different times: each keeps its own.
    assert!((page.routes[0].view.end_t_s - page.routes[1].view.end_t_s).abs() > 0.1);
    let data = html::page_data(&page);
    assert_eq!(data["mode"], "compare");
    let routes = data["routes"].as_array().unwrap();
    assert_eq!(routes.len(), 2);
    for (r, shown) in routes.iter().zip(&page.routes) {
        assert_eq!(r["label"], shown.label.as_str());
        assert_eq!(
            r["poses"]["t"].as_array().unwrap().len(),
            shown.view.poses.len()
        );
    }
    let html = html::page_of(&page).unwrap();
    assert!(html.len() < 10_000_000);
    assert!(html.contains("paper dynamics") && html.contains("rigid-body dynamics"));
}

#[test]
fn a_fan_draws_at_most_a_thousand_paths_of_a_few_dozen_points_each_on_the_ground_under_2_mb() {
    for name in ["paper-like.toml", "paper-like-faces.toml", "valley.toml"] {
        let scene = scene(name).with("solver.t_end_s", 0.5).unwrap();
        let nominal = route(&scene);
        // 1500 paths of 500 points, fanning out from the start over 12 m.
        let [x0, z0] = [nominal.rows[0].x_m, nominal.rows[0].z_m];
        let paths: Vec<Vec<[f64; 2]>> = (0..1500)
            .map(|k| {
                let a = (k as f64 / 1500.0 - 0.5) * 1.2;
                (0..500)
                    .map(|i| {
                        let s = 12.0 * i as f64 / 499.0;
                        [x0 + s * a.cos(), z0 + s * a.sin()]
                    })
                    .collect()
            })
            .collect();
        let refs: Vec<&[[f64; 2]]> = paths.iter().map(Vec::as_slice).collect();
        let page = many::fan_page(&scene, Some(&nominal), &refs, 1500, "routes", vec![]);
        assert_eq!(page.mode, many::Mode::Fan);
        let fan = page.fan.as_ref().unwrap();
        assert_eq!(fan.routes, 1500);
        assert!(!fan.paths.is_empty() && fan.paths.len() <= crate::output::MAX_FAN_PATHS);
        assert!(
            fan.label.contains("1000 drawn") || fan.paths.len() < 1000,
            "{name}"
        );
        for p in &fan.paths {
            assert!(
                !p.is_empty() && p.len() <= many::MAX_FAN_POINTS,
                "{}",
                p.len()
            );
            for q in p {
                let top = ground_height(&scene, q[0], q[2]).unwrap();
                assert!((q[1] - top).abs() < 1e-9, "{name}: {q:?} against {top}");
            }
        }
        // The scene as written in its own colour; the ground under every path.
        assert_eq!(page.routes.len(), 1);
        assert_ne!(page.routes[0].color, many::FAN_ORANGE);
        let (lo, hi) = page.ground.bounds().unwrap();
        for q in fan.paths.iter().flatten() {
            assert!((lo[0]..=hi[0]).contains(&q[0]) && (lo[2]..=hi[2]).contains(&q[2]));
        }
        let data = html::page_data(&page);
        let starts = data["fan"]["starts"].as_array().unwrap();
        assert_eq!(starts.len(), fan.paths.len());
        // Pictures and pages are promised under 2 MB (a thousand sampled paths made 2.08 MB).
        let bytes = html::page_of(&page).unwrap().len();
        assert!(bytes < 2_000_000, "{name}: {bytes} bytes");
    }
}

#[test]
fn the_fan_takes_the_first_thousand_routes_that_ran_as_route_fan_svg_does() {
    let scene = Scene::default_scene().with("solver.t_end_s", 0.3).unwrap();
    let result = crate::RouteResult::of(&route(&scene));
    let mut outcomes = vec![crate::Outcome::Invalid {
        reason: "no".into(),
    }];
    outcomes.extend((0..1200).map(|_| crate::Outcome::Route(result.clone())));
    outcomes.push(crate::Outcome::NotRun);
    let (paths, routes) = many::cm_paths(&outcomes);
    assert_eq!((paths.len(), routes), (crate::output::MAX_FAN_PATHS, 1200));
    assert!(paths.iter().all(|p| *p == result.cm_path_m.as_slice()));
    // A sweep with no nominal route: a page of the fan alone.
    let page = many::fan_page(&scene, None, &paths, routes, "combinations", vec![]);
    assert!(page.routes.is_empty());
    assert_eq!(page.fan.as_ref().unwrap().paths.len(), 1000);
    assert!(!page.ground.triangles.is_empty());
}

#[test]
fn a_scene_name_of_markup_stays_data_and_reads_back_whole() {
    // A scene file's name is the person's words: `</script>` or `<!--` in it must neither end
    // the page's data nor change how the browser reads the script.
    let name = "dam </script><script>alert(1)</script> <!-- x";
    let scene = Scene::default_scene()
        .with("name", name)
        .unwrap()
        .with("solver.t_end_s", 0.05)
        .unwrap();
    let page = html::page(&view_of(&scene, &route(&scene)).unwrap()).unwrap();
    assert!(!page.contains("alert(1)</script>") && !page.contains("<!-- x"));
    let start = page.find(r#"id="route-data">"#).unwrap() + r#"id="route-data">"#.len();
    let end = start + page[start..].find("</script>").unwrap();
    let data: serde_json::Value = serde_json::from_str(&page[start..end]).unwrap();
    assert!(
        data["title"].as_str().unwrap().contains(name),
        "{}",
        data["title"]
    );
}

#[test]
fn every_kept_pose_of_either_dynamics_stands_its_contacts_on_their_planes() {
    // Two side elevations and a yaw leave two ways to roll the frame about side 0→1; the view
    // must take the one the route is in, whatever the dynamics: each contact on its own plane.
    for dynamics in [crate::DynamicsModel::RigidBody, crate::DynamicsModel::Paper] {
        let scene = Scene::default_scene().with_dynamics(dynamics).unwrap();
        let route = route(&scene);
        let view = view_of(&scene, &route).unwrap();
        let planes = scene.site().planes();
        for k in 0..view.poses.len() {
            let c = contacts_at(&view, k);
            for (j, p) in c.iter().enumerate() {
                let gap = planes[j].signed_distance(p);
                assert!(
                    gap.abs() < 1e-6,
                    "{dynamics}: pose {k} (t = {} s), contact {j} is {gap} m off its plane",
                    view.poses[k].t_s
                );
            }
        }
    }
}

#[test]
fn a_fan_path_keeps_the_corner_of_a_sharp_turn_that_evenly_spread_points_cut() {
    // An L: 5 m along X, then 5 m along Z, 64 points evenly in time with the corner at point
    // 44 (the route slowed before it): 32 evenly spread points (points 43 and 45 about it)
    // miss it and cut the corner; the simplified path goes through it.
    let mut path: Vec<[f64; 2]> = (0..=44).map(|i| [5.0 * f64::from(i) / 44.0, 0.0]).collect();
    path.extend((1..=19).map(|i| [5.0, 5.0 * f64::from(i) / 19.0]));
    assert_eq!(path.len(), 64);
    // How far the points of `path` lie from the polyline `kept`.
    let deviation = |kept: &[[f64; 2]]| {
        path.iter()
            .map(|q| {
                kept.windows(2)
                    .map(|w| {
                        let (a, b) = (w[0], w[1]);
                        let (dx, dz) = (b[0] - a[0], b[1] - a[1]);
                        let t = (((q[0] - a[0]) * dx + (q[1] - a[1]) * dz) / (dx * dx + dz * dz))
                            .clamp(0.0, 1.0);
                        (q[0] - a[0] - t * dx).hypot(q[1] - a[1] - t * dz)
                    })
                    .fold(f64::INFINITY, f64::min)
            })
            .fold(0.0, f64::max)
    };
    let even = crate::analysis::runner::thin(&path, many::MAX_FAN_POINTS);
    let kept = many::simplified(&path, many::MAX_FAN_POINTS);
    assert!(
        !even.contains(&[5.0, 0.0]) && deviation(&even) > 0.05,
        "{}",
        deviation(&even)
    );
    assert!(kept.contains(&[5.0, 0.0]), "{kept:?}");
    assert!(deviation(&kept) < 1e-12, "{}", deviation(&kept));
    // Its ends, its order, at most the count; a straight path needs only its ends.
    assert_eq!((kept[0], *kept.last().unwrap()), (path[0], path[63]));
    assert!(kept.len() <= many::MAX_FAN_POINTS);
    let order: Vec<usize> = kept
        .iter()
        .map(|q| path.iter().position(|p| p == q).unwrap())
        .collect();
    assert!(order.windows(2).all(|w| w[0] < w[1]), "{order:?}");
    assert_eq!(many::simplified(&path[..45], 32), vec![path[0], path[44]]);
    assert_eq!(many::simplified(&path[..10], 32), path[..10].to_vec());
}
