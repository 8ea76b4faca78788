//! The pictures read back as SVG: where their legends and data lie, what they name and mark.

use super::sweep::sweep;
use super::*;
use crate::SceneError;

/// A text element of an SVG: its position and content.
#[derive(Debug)]
struct SvgText {
    x: f64,
    size: f64,
    text: String,
}

fn attr(tag: &str, name: &str) -> Option<f64> {
    let key = format!(" {name}=\"");
    let start = tag.find(&key)? + key.len();
    tag[start..].split('"').next()?.parse().ok()
}

fn texts(svg: &str) -> Vec<SvgText> {
    svg.split("<text")
        .skip(1)
        .filter_map(|s| {
            let (tag, rest) = s.split_once('>')?;
            let text = rest.split("</text>").next()?.trim().replace("&amp;", "&");
            Some(SvgText {
                x: attr(tag, "x")?,
                size: attr(tag, "font-size")?,
                text,
            })
        })
        .collect()
}

/// Every polyline of an SVG: its tag, and its points.
fn polylines(svg: &str) -> Vec<(&str, Vec<(f64, f64)>)> {
    svg.split("<polyline")
        .skip(1)
        .map(|p| {
            let tag = p.split("/>").next().unwrap_or("");
            let points = tag
                .split("points=\"")
                .nth(1)
                .and_then(|q| q.split('"').next())
                .unwrap_or("")
                .split_whitespace()
                .filter_map(|q| {
                    let (x, y) = q.split_once(',')?;
                    Some((x.parse().ok()?, y.parse().ok()?))
                })
                .collect();
            (tag, points)
        })
        .collect()
}

/// Every point of every polyline of data (plotters draws line series as polylines; a legend's
/// mark is a polyline of two or three points).
fn polyline_points(svg: &str) -> Vec<(f64, f64)> {
    polylines(svg)
        .into_iter()
        .filter(|(_, points)| points.len() > 3)
        .flat_map(|(_, points)| points)
        .collect()
}

/// A temporary folder, removed when the test ends, passed or failed.
struct TempDir(PathBuf);

impl Drop for TempDir {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

impl std::ops::Deref for TempDir {
    type Target = Path;
    fn deref(&self) -> &Path {
        &self.0
    }
}

/// A fresh folder of its own: the tests run at once, and two may ask for the same name.
fn temp_dir(name: &str) -> TempDir {
    static SERIAL: std::sync::atomic::AtomicUsize = std::sync::atomic::AtomicUsize::new(0);
    let k = SERIAL.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
    let dir = std::env::temp_dir().join(format!(
        "slideroute-plots-{name}-{}-{k}",
        std::process::id()
    ));
    std::fs::create_dir_all(&dir).unwrap();
    TempDir(dir)
}

/// The default scene with `t_end` (s) and the hydraulic force (N) replaced.
fn scene_with(t_end: f64, force: f64) -> Scene {
    let keys = [
        ("solver.t_end_s", t_end),
        ("loads.hydraulic_force_n", force),
    ];
    with_keys(&Scene::default_scene(), &keys).unwrap()
}

/// `scene` with each key set to its value, in the scene file's keys and units.
fn with_keys(scene: &Scene, keys: &[(&str, f64)]) -> Result<Scene, SceneError> {
    scene.with_keys(keys.iter().copied())
}

fn route_pictures(name: &str, scene: &Scene) -> (TempDir, Route) {
    let route = crate::analysis::run(scene).unwrap();
    let dir = temp_dir(name);
    write_route_plots(&dir, scene, &route).unwrap();
    (dir, route)
}

fn read(dir: &Path, file: &str) -> String {
    std::fs::read_to_string(dir.join(file)).unwrap()
}

/// The left edge of the side panel of a sheet `w` wide.
fn panel_left(w: u32) -> f64 {
    f64::from(w - sheet::PANEL_W)
}

#[test]
fn legends_never_cover_data() {
    let (dir, _) = route_pictures("legends", &scene_with(4.0, 8e6));
    for (file, (w, _), legend) in [
        ("reactions.svg", series::SIZE, "N2 normal, contact 2"),
        ("angles.svg", series::SIZE, "θ: yaw"),
        ("profile.svg", series::SIZE, "CM height"),
        ("plan.svg", plan::SIZE, "path of the centre of mass (CM)"),
    ] {
        let svg = read(&dir, file);
        let t = texts(&svg);
        let entry = t.iter().find(|t| t.text == legend);
        let entry = entry.unwrap_or_else(|| panic!("{file}: no legend entry {legend:?}"));
        assert!(
            entry.x >= panel_left(w),
            "{file}: legend at x = {}",
            entry.x
        );
        // Every line of data lies left of the panel (the plan's inset is not drawn for a route
        // this long).
        let points = polyline_points(&svg);
        assert!(!points.is_empty(), "{file}: no lines");
        let right = points.iter().map(|p| p.0).fold(f64::NEG_INFINITY, f64::max);
        assert!(right < panel_left(w), "{file}: data reaches x = {right}");
    }
}

#[test]
fn the_plan_view_shades_and_names_the_regions_and_draws_the_water_force() {
    let (dir, _) = route_pictures("regions", &scene_with(4.0, 8e6));
    let svg = read(&dir, "plan.svg");
    // The three regions filled in their own colours.
    for color in [plan::PLANE_1, plan::PLANE_2, plan::HORIZONTAL] {
        let fill = format!("fill=\"#{:02X}{:02X}{:02X}\"", color.0, color.1, color.2);
        assert!(
            svg.split("<polygon").skip(1).any(|p| p.contains(&fill)),
            "no region filled {fill}"
        );
    }
    let names: Vec<String> = texts(&svg).into_iter().map(|t| t.text).collect();
    for name in [
        "horizontal",
        "plane 1, dip 20°",
        "plane 2, dip 25°",
        "F = 8 MN",
    ] {
        assert!(
            names.iter().any(|n| n == name),
            "{name:?} missing: {names:?}"
        );
    }
    let words = names.join(" ");
    assert!(words.contains("line of action 1 m from the CM"), "{words}");
}

#[test]
fn a_foundation_of_faces_is_drawn_face_by_face_with_its_creases() {
    // Four faces: the paper's three and a steep one beyond X = 14 m; the paper's dynamics keeps
    // contact 2 on plane 2, so the route runs to its own end (2.024 s).
    let faces = "[foundation]\n\
        [[foundation.plane]]\ndip_deg = 0.0\ndip_direction_deg = 0.0\npoint_m = [0.0, 0.0, 0.0]\n\
        [[foundation.plane]]\ndip_deg = 20.0\ndip_direction_deg = 180.0\npoint_m = [4.0, 0.0, 0.0]\n\
        [[foundation.plane]]\ndip_deg = 25.0\ndip_direction_deg = 150.0\npoint_m = [4.0, 0.0, -5.0]\n\
        [[foundation.plane]]\ndip_deg = 60.0\ndip_direction_deg = 180.0\npoint_m = [14.0, 3.64, 0.0]\n";
    let text = crate::Scene::DEFAULT_TOML;
    let start = text.find("[foundation]").unwrap();
    let end = text.find("[block]").unwrap();
    let text = format!("{}{faces}\n{}", &text[..start], &text[end..]);
    let scene = Scene::from_toml(&text, "four faces")
        .unwrap()
        .with_dynamics(crate::DynamicsModel::Paper)
        .unwrap();
    let (dir, route) = route_pictures("faces", &scene);
    assert!(route.rows.len() > 100);
    let svg = read(&dir, "plan.svg");
    let names: Vec<String> = texts(&svg).into_iter().map(|t| t.text).collect();
    let words = names.join(" ");
    for name in [
        "face 0, dip 0°",
        "face 1, dip 20°",
        "face 2, dip 25°",
        "face 3, dip 60°",
    ] {
        assert!(words.contains(name), "{name:?} missing: {names:?}");
    }
    assert!(words.contains("its creases"), "{words}");
    assert!(!words.contains("horizontal plane (contact 0)"), "{words}");
}

#[test]
fn the_plan_view_marks_where_a_contact_rides_a_crease_and_changes_face() {
    let path =
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/paper-like-faces.toml");
    // The three-point frame's contacts (on its base a block has corners, not contacts).
    let scene = Scene::from_file(&path)
        .unwrap()
        .with("solver.contacts", "frame")
        .unwrap();
    let (dir, route) = route_pictures("crease", &scene);
    assert!(route.rows.iter().any(|r| r.crease == [None, None, Some(1)]));
    let svg = read(&dir, "plan.svg");
    let words = texts(&svg)
        .into_iter()
        .map(|t| t.text)
        .collect::<Vec<_>>()
        .join(" ");
    assert!(
        words.contains("contact 2 into the crease with face 1"),
        "{words}"
    );
    assert!(words.contains("contact 2 onto face 1"), "{words}");
    // No base there: no marks of where one touched the ground.
    assert!(!svg.contains("#E67800"), "touch marks on a frame route");
    assert!(words.contains("contacts 0, 1, 2 at the start"), "{words}");
}

#[test]
fn the_plan_view_numbers_the_contacts_at_the_start_and_the_end() {
    // At 4 s the end contacts stand apart from the start's; at the route's end (t_end 20 s)
    // contact 0 ends beside contact 1's start, and is numbered all the same.
    for t_end in [4.0, 20.0] {
        let (dir, _) = route_pictures("numbers", &scene_with(t_end, 8e6));
        let t = texts(&read(&dir, "plan.svg"));
        for i in ["0", "1", "2"] {
            // The contacts' numbers are 16 px, larger than the ticks' 14.5.
            let n = t
                .iter()
                .filter(|t| t.text == i && t.x < panel_left(plan::SIZE.0) && t.size > 15.0)
                .count();
            assert_eq!(n, 2, "t_end {t_end}: contact {i} numbered {n} times");
        }
    }
}

#[test]
fn a_short_route_is_drawn_enlarged_beside_the_plan() {
    let (dir, route) = route_pictures("short", &scene_with(0.2, 8e6));
    assert!(
        route.travel_m > 0.0 && route.travel_m < 0.1,
        "{}",
        route.travel_m
    );
    let svg = read(&dir, "plan.svg");
    let inset = texts(&svg)
        .into_iter()
        .find(|t| t.text.starts_with("CM path enlarged"))
        .expect("no inset");
    assert!(inset.x >= panel_left(plan::SIZE.0));
    // In the inset the path spans a good part of the panel, not a dash.
    let xs: Vec<f64> = polyline_points(&svg)
        .into_iter()
        .filter(|p| p.0 > panel_left(plan::SIZE.0))
        .map(|p| p.0)
        .collect();
    let span = xs.iter().copied().fold(f64::NEG_INFINITY, f64::max)
        - xs.iter().copied().fold(f64::INFINITY, f64::min);
    assert!(span > 100.0, "inset path spans {span} px");
    // A long route needs none.
    let (long, _) = route_pictures("long", &scene_with(4.0, 8e6));
    assert!(!read(&long, "plan.svg").contains("CM path enlarged"));
}

#[test]
fn a_scene_that_does_not_slide_gets_pictures_that_say_so() {
    let (dir, route) = route_pictures("still", &scene_with(20.0, 1e6));
    assert_eq!(route.termination.reason, Reason::DoesNotSlide);
    for file in ["profile.svg", "angles.svg", "reactions.svg"] {
        let svg = read(&dir, file);
        let words: String = texts(&svg).into_iter().map(|t| t.text + " ").collect();
        assert!(words.contains("does not slide"), "{file}: {words}");
        assert!(words.contains("factor of safety 6.8"), "{file}: {words}");
        // No axes: no tick labels, no lines.
        assert!(!svg.contains("<polyline"), "{file} has lines");
    }
    let plan = read(&dir, "plan.svg");
    assert!(
        texts(&plan)
            .iter()
            .any(|t| t.text.contains("does not slide"))
    );
}

#[test]
fn a_monolith_held_on_its_base_is_said_to_be_held_under_its_base_not_by_three_contacts() {
    let held = with_keys(&scene_file("monolith.toml"), &[("water.headwater_m", 6.0)]).unwrap();
    let (dir, route) = route_pictures("held-base", &held);
    assert_eq!(route.termination.reason, Reason::DoesNotSlide);
    assert!(route.base().is_some());
    let words: String = texts(&read(&dir, "profile.svg"))
        .into_iter()
        .map(|t| t.text + " ")
        .collect();
    assert!(words.contains("under its base"), "{words}");
    assert!(!words.contains("three contacts"), "{words}");
}

#[test]
fn pictures_of_odd_scenes_draw_without_fail() {
    // Frames from 1 cm to 10 km, any proportions, dips and strike, loads and offsets: every
    // scene that runs gets its four pictures, whole and small, and never a panic, on any input.
    let mut seed = 0x2545_f491_4f6c_dd1du64;
    let mut next = || {
        seed ^= seed << 13;
        seed ^= seed >> 7;
        seed ^= seed << 17;
        (seed >> 11) as f64 / (1u64 << 53) as f64
    };
    let mut drawn = 0;
    for k in 0..40 {
        let l = 10f64.powf(-2.0 + 6.0 * next());
        let (a, b) = (0.05 + 0.9 * next(), 0.05 + 0.9 * next());
        let inertia = 1.1e7 * (l / 10.0).powi(4);
        let keys = [
            ("frame.l1x", a * l),
            ("frame.l2x", (1.0 - a) * l),
            ("frame.l1z", b * l),
            ("frame.l2z", (1.0 - b) * l),
            ("foundation.xi_deg", 1.0 + 88.0 * next()),
            ("foundation.zeta_deg", 1.0 + 88.0 * next()),
            ("foundation.kappa_deg", -89.0 + 178.0 * next()),
            ("block.mass_kg", 1e6 * (l / 10.0).powi(2)),
            ("block.inertia_kg_m2", inertia),
            ("block.inertia_x_kg_m2", 0.5 * inertia),
            ("block.inertia_z_kg_m2", 0.5 * inertia),
            (
                "loads.hydraulic_force_n",
                10f64.powf(5.0 + 3.0 * next()) * (l / 10.0).powi(2),
            ),
            ("loads.eccentricity_m", (next() - 0.5) * l),
            ("solver.t_end_s", 1.0),
        ];
        let Ok(scene) = with_keys(&Scene::default_scene(), &keys) else {
            continue;
        };
        let Ok(route) = crate::run(&scene) else {
            continue;
        };
        let dir = temp_dir(&format!("odd-{k}"));
        write_route_plots(&dir, &scene, &route)
            .unwrap_or_else(|e| panic!("scene {k} (L = {l} m): {e}"));
        for file in ["plan.svg", "profile.svg", "angles.svg", "reactions.svg"] {
            let svg = read(&dir, file);
            assert!(svg.trim_end().ends_with("</svg>"), "scene {k}: {file} cut");
            assert!(svg.len() < 2_000_000, "scene {k}: {file} {} B", svg.len());
            assert!(!svg.contains("NaN"), "scene {k}: {file} has NaN");
        }
        drawn += 1;
    }
    assert!(drawn >= 30, "only {drawn} of 40 scenes ran");
}

#[test]
fn the_plan_view_of_a_block_on_its_base_draws_its_base_and_where_it_touched() {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/ramp-faces.toml");
    let scene = Scene::from_file(&path)
        .unwrap()
        .with("solver.t_end_s", 1.0)
        .unwrap();
    let (dir, route) = route_pictures("on-base", &scene);
    let corners = route.base().unwrap().outline_m.len();
    let svg = read(&dir, "plan.svg");
    // The base's outline: a closed path of its corners and the first again, at each drawn pose.
    let closed = polylines(&svg)
        .iter()
        .filter(|(_, pts)| pts.len() == corners + 1)
        .count();
    assert!(closed >= 2, "{closed} outlines of {corners} corners");
    // No frame triangle: no closed path of three contacts and the first again.
    let triangles = polylines(&svg)
        .iter()
        .filter(|(_, pts)| pts.len() == 4 && pts[0] == pts[3])
        .count();
    assert_eq!(triangles, 0, "a frame's triangle on a base route");
    // The touch marks on the plan (the legend's mark is larger), in their colour, and the
    // legend's words for them.
    let touches = svg
        .split("<circle")
        .skip(1)
        .filter(|c| c.contains(" r=\"3\"") && c.contains("fill=\"#E67800\""))
        .count();
    assert!(touches >= 1, "no touch marks");
    let words = texts(&svg)
        .into_iter()
        .map(|t| t.text)
        .collect::<Vec<_>>()
        .join(" ");
    assert!(words.contains("corners carrying the block"), "{words}");
    assert!(!words.contains("contact 0 onto"), "{words}");
}

/// The path of a scene file of the repository.
fn scene_file(name: &str) -> Scene {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("scenes")
        .join(name);
    Scene::from_file(&path).unwrap()
}

/// The closed polylines of an SVG (a frame or an outline: its corners and the first again),
/// each with its tag.
fn closed_polylines(svg: &str) -> Vec<(String, Vec<(f64, f64)>)> {
    polylines(svg)
        .into_iter()
        .filter(|(_, pts)| pts.len() >= 4 && pts.first() == pts.last())
        .map(|(tag, pts)| (tag.to_string(), pts))
        .collect()
}

/// The plotting area of a chart in an SVG, from its axes (the longest vertical and horizontal
/// black lines): least x, least y, greatest x, greatest y in pixels.
fn plotting_area(svg: &str) -> (f64, f64, f64, f64) {
    let mut best_v = (0.0, 0.0, 0.0, 0.0);
    let mut best_h = (0.0, 0.0, 0.0, 0.0);
    for (tag, pts) in polylines(svg) {
        if !tag.contains("stroke=\"#000000\"") {
            continue;
        }
        let [a, b] = pts[..] else {
            continue;
        };
        if a.0 == b.0 && (b.1 - a.1).abs() > (best_v.3 - best_v.1) {
            best_v = (a.0, a.1.min(b.1), a.0, a.1.max(b.1));
        }
        if a.1 == b.1 && (b.0 - a.0).abs() > (best_h.2 - best_h.0) {
            best_h = (a.0.min(b.0), a.1, a.0.max(b.0), a.1);
        }
    }
    (best_v.0, best_v.1, best_h.2, best_h.1)
}

#[test]
fn a_monolith_on_its_frame_is_drawn_with_its_base_outline_not_the_contact_triangle() {
    // The monolith's frame under the paper's dynamics: its 20 × 10 m base, not the triangle of
    // its three contacts, at the start (level, unturned, the CM 7 m from the heel).
    let scene = scene_file("monolith.toml")
        .with_dynamics(crate::DynamicsModel::Paper)
        .unwrap();
    let (dir, route) = route_pictures("monolith-frame", &scene);
    assert!(route.base().is_none());
    let svg = read(&dir, "plan.svg");
    let outlines = closed_polylines(&svg);
    let base = outlines
        .iter()
        .map(|(_, pts)| pts)
        .find(|pts| pts.len() == 5)
        .unwrap_or_else(|| panic!("no outline of four corners: {outlines:?}"));
    // Its corners: 20 m along X by 10 m along Z, at one scale on both axes.
    let xs: Vec<f64> = base.iter().map(|p| p.0).collect();
    let ys: Vec<f64> = base.iter().map(|p| p.1).collect();
    let span = |v: &[f64]| {
        v.iter().copied().fold(f64::NEG_INFINITY, f64::max)
            - v.iter().copied().fold(f64::INFINITY, f64::min)
    };
    let ratio = span(&xs) / span(&ys);
    assert!((ratio - 2.0).abs() < 0.02, "{base:?}: {ratio}");
    assert!(
        !outlines.iter().any(|(_, pts)| pts.len() == 4),
        "a contact triangle is drawn"
    );
    let words: String = texts(&svg).into_iter().map(|t| t.text + " ").collect();
    assert!(words.contains("footprint"), "{words}");
}

/// A route of `scene` made up: `n` rows from the origin straight along X to `x_end` (m), level
/// and unturned.
fn straight_rows(n: usize, x_end: f64) -> Vec<Row> {
    (0..n)
        .map(|k| Row {
            t_s: k as f64,
            x_m: x_end * k as f64 / (n - 1) as f64,
            ..Row::default()
        })
        .collect()
}

#[test]
fn the_force_label_stays_inside_the_plotting_area() {
    // A monolith that travels 150 m: the plan's scale is large, and the label, as wide in
    // pixels at any scale, would run left into the axis behind the arrow.
    let scene = scene_file("monolith.toml")
        .with_dynamics(crate::DynamicsModel::Paper)
        .unwrap();
    for x_end in [0.0, 150.0, 400.0] {
        let rows = straight_rows(20, x_end);
        let dir = temp_dir(&format!("force-label-{x_end}"));
        let path = dir.join("plan.svg");
        plan::plan_view(
            &path,
            &scene,
            &plan::PlanView {
                title: "a long route",
                tracks: &[plan::Track {
                    name: "path of the centre of mass (CM)".into(),
                    who: "the route".into(),
                    rows: &rows,
                    color: COLORS[0],
                    base: None,
                }],
                fan: None,
                notes: &[],
            },
        )
        .unwrap();
        let svg = std::fs::read_to_string(&path).unwrap();
        let (left, top, right, bottom) = plotting_area(&svg);
        let label = svg
            .split("<text")
            .skip(1)
            .find(|t| {
                t.split_once('>')
                    .is_some_and(|(_, rest)| rest.trim_start().starts_with("F = 9.418 MN"))
            })
            .expect("no force label");
        let tag = label.split('>').next().unwrap();
        let (x, y, size) = (
            attr(tag, "x").unwrap(),
            attr(tag, "y").unwrap(),
            attr(tag, "font-size").unwrap(),
        );
        // Anchored at its right end and its middle: its box, its characters at most 0.62 of
        // the font's size wide.
        assert!(tag.contains("text-anchor=\"end\""), "{tag}");
        let width = 0.62 * size * "F = 9.418 MN".chars().count() as f64;
        let (x0, x1, y0, y1) = (x - width, x, y - 0.6 * size, y + 0.6 * size);
        assert!(
            x0 > left && x1 < right && y0 > top && y1 < bottom,
            "x_end {x_end}: label {x0}…{x1} × {y0}…{y1} outside {left}…{right} × {top}…{bottom}"
        );
    }
}

#[test]
fn the_compare_plan_draws_the_start_frame_over_the_others_and_names_each_dynamics_frames() {
    let scene = scene_with(4.0, 8e6);
    let c = crate::compare::compare_dynamics(&scene).unwrap();
    let dir = temp_dir("compare");
    let path = dir.join("compare-plan.svg");
    compare_plan(&path, &scene, &c).unwrap();
    let svg = std::fs::read_to_string(&path).unwrap();
    let frames = closed_polylines(&svg);
    // The start frame: thick, black, after (over) every frame of either route.
    let start = frames
        .iter()
        .position(|(tag, _)| {
            tag.contains("stroke=\"#000000\"") && tag.contains("stroke-width=\"3\"")
        })
        .expect("no thick black frame at the start");
    assert_eq!(start + 1, frames.len(), "frames drawn over the start's");
    let paper = COLORS[3];
    let orange = format!("stroke=\"#{:02X}{:02X}{:02X}\"", paper.0, paper.1, paper.2);
    assert!(
        frames[..start].iter().any(|(tag, _)| tag.contains(&orange)),
        "no frame of the paper's dynamics"
    );
    // Both routes begin there: one frame at the start, not one of each.
    let (a, b) = (&c.rigid_body.route.rows[0], &c.paper.route.rows[0]);
    assert_eq!((a.x_m, a.z_m, a.theta_deg), (b.x_m, b.z_m, b.theta_deg));
    let words: String = texts(&svg).into_iter().map(|t| t.text + " ").collect();
    for want in [
        "at the start, where the routes begin",
        "rigid body: its frame",
        "paper&apos;s dynamics: its frame",
    ] {
        assert!(words.contains(want), "{want:?} in {words}");
    }
}

#[test]
fn every_picture_has_text_of_at_least_14_px() {
    // plotters' SVG backend writes a font's size in pixels of the picture at its default size.
    let check = |what: &str, svg: &str| {
        let sizes: Vec<f64> = svg
            .split("font-size=\"")
            .skip(1)
            .filter_map(|s| s.split('"').next()?.parse().ok())
            .collect();
        assert!(!sizes.is_empty(), "{what}: no text");
        let least = sizes.iter().copied().fold(f64::INFINITY, f64::min);
        assert!(least >= 14.0, "{what}: text of {least} px");
    };
    // A route, a monolith's, one that does not slide and one that ends at once.
    for (name, scene) in [
        ("default", scene_with(4.0, 8e6)),
        ("short", scene_with(0.2, 8e6)),
        ("still", scene_with(20.0, 1e6)),
        ("monolith", scene_file("monolith.toml")),
        (
            "monolith-frame",
            scene_file("monolith.toml")
                .with_dynamics(crate::DynamicsModel::Paper)
                .unwrap(),
        ),
    ] {
        let (dir, _) = route_pictures(name, &scene);
        for file in ["plan.svg", "profile.svg", "angles.svg", "reactions.svg"] {
            check(&format!("{name} {file}"), &read(&dir, file));
        }
    }
    // Both dynamics on one plan.
    let scene = scene_with(4.0, 8e6);
    let c = crate::compare::compare_dynamics(&scene).unwrap();
    let dir = temp_dir("sizes-compare");
    compare_plan(&dir.join("c.svg"), &scene, &c).unwrap();
    check("compare plan", &read(&dir, "c.svg"));
    // A sweep of μ over a change of regime, and one where nothing slid.
    let mu = [0.3, 0.4, 0.5, 0.6];
    let row = |m: f64, slid: bool| crate::output::sweep_row::SweepRow {
        values: vec![m],
        reason: if slid { "stopped" } else { "does-not-slide" }.into(),
        t_end_s: Some(if slid { 3.0 } else { 0.0 }),
        travel_m: Some(if slid { 12.9 } else { 0.0 }),
        final_theta_deg: Some(0.0),
        max_alpha_deg: Some(0.0),
        max_beta_deg: Some(0.0),
        permanent_x_m: None,
        permanent_z_m: None,
        factor_of_safety: Some(FactorOfSafety::Finite { value: 2.0 * m }),
        detail: String::new(),
    };
    let varies = [crate::sweep::Vary::numbers("friction.mu_k", mu.to_vec())];
    let dir = temp_dir("sizes-sweep");
    for (file, rows) in [
        (
            "a.svg",
            mu.iter().map(|&m| row(m, m < 0.45)).collect::<Vec<_>>(),
        ),
        ("b.svg", mu.iter().map(|&m| row(m, false)).collect()),
    ] {
        sweep(&dir.join(file), &varies, &rows).unwrap();
        check(file, &read(&dir, file));
    }
    // The work–precision chart of every series the report measures.
    let points = work_precision_points();
    work_precision(&dir.join("wp.svg"), &points).unwrap();
    check("work-precision", &read(&dir, "wp.svg"));
    // The route fan, the histogram and the sensitivity of a small probabilistic analysis.
    let uncertain = scene_file("paper-like-uncertain.toml");
    let design = crate::probabilistic::Design {
        scene: &uncertain,
        uncertain: uncertain.uncertain(),
        samples: 24,
        seed: 7,
        sampling: crate::probabilistic::Sampling::LatinHypercube,
    };
    let samples = design.run(|| {}, || false);
    let limits = crate::probabilistic::Limits::new(None, None).unwrap();
    let summary = crate::probabilistic::summarise(&design, limits, &samples);
    let nominal = crate::run(&uncertain).ok();
    let dir = temp_dir("sizes-probabilistic");
    let fs = |each: &mut dyn FnMut(Option<f64>)| {
        super::probabilistic::factors_of_safety(&samples, each);
        Ok(())
    };
    for p in write_probabilistic_plots(&dir, &uncertain, nominal.as_ref(), &samples, &fs, &summary)
        .unwrap()
    {
        check(
            &p.display().to_string(),
            &std::fs::read_to_string(&p).unwrap(),
        );
    }
}

/// A point of every series the report measures on two scenes, three steps of dt each.
fn work_precision_points() -> Vec<crate::output::work_precision::ladder::Point> {
    use crate::{DynamicsModel, Integrator, Mode, PoseMethod};
    let mut points = Vec::new();
    let mut ways = Vec::new();
    for method in [PoseMethod::Continuation, PoseMethod::AllRoots] {
        for mode in [Mode::Exact, Mode::SmallAngle] {
            for integrator in [Integrator::Paper, Integrator::Rk4] {
                ways.push((DynamicsModel::Paper, method, mode, integrator));
            }
        }
    }
    ways.push((
        DynamicsModel::RigidBody,
        PoseMethod::Continuation,
        Mode::Exact,
        Integrator::Rk4,
    ));
    for (s, scene) in ["paper-like", "shallow"].iter().enumerate() {
        for (w, &(dynamics, method, mode, integrator)) in ways.iter().enumerate() {
            for k in 0..3 {
                let dt_s = 0.02 / f64::from(1u32 << k);
                points.push(crate::output::work_precision::ladder::Point {
                    scene: (*scene).into(),
                    dynamics,
                    method,
                    mode,
                    integrator,
                    dt_s,
                    tolerance: None,
                    increments: 100 << k,
                    steps: 100 << k,
                    wall_s: 1e-4 * (1 + w + s) as f64 * f64::from(1u32 << k),
                    error_m: 1e-3 * dt_s / (1 + w) as f64,
                });
            }
        }
    }
    points
}

#[test]
fn no_two_work_precision_series_share_colour_and_marker() {
    let points = work_precision_points();
    let dir = temp_dir("work-precision");
    let path = dir.join("wp.svg");
    work_precision(&path, &points).unwrap();
    let svg = std::fs::read_to_string(&path).unwrap();
    // The markers on the chart (left of the panel): their shape and fill.
    let panel = f64::from(1300 - sheet::PANEL_W);
    let mut marks = std::collections::BTreeSet::new();
    let tags: Vec<(&str, &str)> = ["<circle", "<rect", "<polygon"]
        .iter()
        .flat_map(|shape| svg.split(*shape).skip(1).map(move |t| (*shape, t)))
        .collect();
    for (shape, tag) in tags {
        let tag = tag.split("/>").next().unwrap_or("");
        let Some(fill) = tag
            .split("fill=\"")
            .nth(1)
            .and_then(|f| f.split('"').next())
        else {
            continue;
        };
        if fill == "none" || fill == "#FFFFFF" {
            continue;
        }
        let x = attr(tag, "cx").or_else(|| attr(tag, "x")).or_else(|| {
            let first = tag.split("points=\"").nth(1)?.split(',').next()?;
            first.trim().parse().ok()
        });
        if x.is_some_and(|x| x < panel) {
            // A triangle's and a diamond's polygons differ in their number of corners.
            let corners = tag.split("points=\"").nth(1).map_or(0, |p| {
                p.split('"').next().unwrap_or("").split_whitespace().count()
            });
            marks.insert((shape, corners, fill.to_string()));
        }
    }
    // Two scenes × (eight ways of the paper's dynamics and the rigid body's one).
    assert_eq!(marks.len(), 18, "{marks:?}");
    // And the rigid body's series are named in the legend, one per scene.
    let words: Vec<String> = texts(&svg).into_iter().map(|t| t.text).collect();
    let rigid = words.iter().filter(|w| w.contains("rigid-body")).count();
    assert_eq!(rigid, 2, "{words:?}");
}

#[test]
fn a_subnormal_or_zero_eccentricity_draws_finite_numbers_in_every_legend() {
    // `loads.eccentricity_m = 1e-310` drew "inf×10⁻³¹⁰ m from the CM" in plan.svg's legend.
    for (e, want) in [(1e-310, "10⁻³¹⁰ m from the CM"), (0.0, " 0 m from the CM")] {
        let scene =
            with_keys(&scene_with(0.2, 8e6), &[("loads.eccentricity_m", e)]).expect("a scene");
        let (dir, _) = route_pictures("subnormal", &scene);
        for file in ["plan.svg", "profile.svg", "angles.svg", "reactions.svg"] {
            let svg = read(&dir, file);
            let words: Vec<String> = texts(&svg).into_iter().map(|t| t.text).collect();
            let words = words.join(" ");
            assert!(
                !words.contains("inf") && !words.contains("NaN"),
                "{e:e}: {file}: {words}"
            );
            if file == "plan.svg" {
                assert!(words.contains(want), "{e:e}: {words}");
            }
        }
    }
}
