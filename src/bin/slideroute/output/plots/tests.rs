//! The pictures read back as SVG: where their legends and data lie, what they name and mark.

use super::*;
use slideroute::SceneError;

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

/// Every point of every polyline of data (plotters draws line series as polylines; a legend's
/// mark is a polyline of two or three points).
fn polyline_points(svg: &str) -> Vec<(f64, f64)> {
    svg.split("<polyline")
        .skip(1)
        .filter(|s| {
            let points = s
                .split(" points=\"")
                .nth(1)
                .and_then(|p| p.split('"').next());
            points.is_some_and(|p| p.split_whitespace().count() > 3)
        })
        .flat_map(|s| {
            let points = s.split("points=\"").nth(1).unwrap_or("").split('"').next();
            points
                .unwrap_or("")
                .split_whitespace()
                .filter_map(|p| {
                    let (x, y) = p.split_once(',')?;
                    Some((x.parse().ok()?, y.parse().ok()?))
                })
                .collect::<Vec<_>>()
        })
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

fn temp_dir(name: &str) -> TempDir {
    let dir = std::env::temp_dir().join(format!("slideroute-plots-{name}-{}", std::process::id()));
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
    let route = slideroute::internals::analysis::run(scene).unwrap();
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
    let text = slideroute::Scene::DEFAULT_TOML;
    let start = text.find("[foundation]").unwrap();
    let end = text.find("[block]").unwrap();
    let text = format!("{}{faces}\n{}", &text[..start], &text[end..]);
    let scene = Scene::from_toml(&text, "four faces")
        .unwrap()
        .with_dynamics(slideroute::DynamicsModel::Paper)
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
            // The contacts' numbers are 15 px (12.1 in the SVG), larger than the ticks'.
            let n = t
                .iter()
                .filter(|t| t.text == i && t.x < panel_left(plan::SIZE.0) && t.size > 11.5)
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
        let Ok(route) = slideroute::run(&scene) else {
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
    let corners = route.base.as_ref().unwrap().outline_m.len();
    let svg = read(&dir, "plan.svg");
    // The base's outline: a closed path of its corners and the first again, at each drawn pose.
    let closed = svg
        .split("<polyline")
        .skip(1)
        .filter(|p| {
            let points = p
                .split("points=\"")
                .nth(1)
                .and_then(|q| q.split('"').next())
                .unwrap_or("");
            points.split_whitespace().count() == corners + 1
        })
        .count();
    assert!(closed >= 2, "{closed} outlines of {corners} corners");
    // No frame triangle: no closed path of three contacts and the first again.
    let triangles = svg
        .split("<polyline")
        .skip(1)
        .filter(|p| {
            let points = p
                .split("points=\"")
                .nth(1)
                .and_then(|q| q.split('"').next())
                .unwrap_or("");
            let pts: Vec<&str> = points.split_whitespace().collect();
            pts.len() == 4 && pts[0] == pts[3]
        })
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
