//! The route in 3-D that `slideroute run` writes beside route.csv: route.glb read back by the
//! glTF project's reader and checked against route.csv, `--no-3d`, and route.html in a real
//! browser (headless Chromium, as `report_browser.rs` drives it), checked against
//! summary.json.
//!
//! The browser test is ignored by default (it needs Chromium); CI runs it with the Drake and
//! record tests (`cargo test -- --ignored browser`).

use std::path::{Path, PathBuf};
use std::process::Command;

/// A fresh folder for one test.
fn temp(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!(
        "slideroute-route-view-{name}-{}",
        std::process::id()
    ));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// `slideroute run ARGS --out OUT --quiet`, which must succeed.
fn run(out: &Path, args: &[&str]) {
    let o = Command::new(env!("CARGO_BIN_EXE_slideroute"))
        .arg("run")
        .args(args)
        .arg("--quiet")
        .arg("--out")
        .arg(out)
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
}

/// route.csv's rows as (t, x, y, z, θ°).
fn route_csv(dir: &Path) -> Vec<[f64; 5]> {
    let mut r = csv::Reader::from_path(dir.join("route.csv")).unwrap();
    let h = r.headers().unwrap().clone();
    let col = |name: &str| h.iter().position(|c| c == name).unwrap();
    let cols = ["t_s", "x_m", "y_m", "z_m", "theta_deg"].map(col);
    r.records()
        .map(|rec| {
            let rec = rec.unwrap();
            cols.map(|c| rec[c].parse::<f64>().unwrap())
        })
        .collect()
}

/// The value of linear keyframes (`times`, `values` of width N) at `t`.
fn sample<const N: usize>(times: &[f32], values: &[[f32; N]], t: f64) -> [f64; N] {
    let k = times
        .partition_point(|&s| f64::from(s) <= t)
        .clamp(1, times.len() - 1);
    let (t0, t1) = (f64::from(times[k - 1]), f64::from(times[k]));
    let f = if t1 > t0 {
        ((t - t0) / (t1 - t0)).clamp(0.0, 1.0)
    } else {
        0.0
    };
    std::array::from_fn(|i| {
        let (a, b) = (f64::from(values[k - 1][i]), f64::from(values[k][i]));
        a + f * (b - a)
    })
}

#[test]
fn route_glb_animates_the_block_through_route_csvs_centre_of_mass_and_yaw() {
    let dir = temp("glb");
    run(&dir, &["--no-plots"]);
    let bytes = std::fs::read(dir.join("route.glb")).unwrap();
    let gltf = gltf::Gltf::from_slice(&bytes).expect("a valid binary glTF");
    let blob = gltf.blob.as_deref().expect("a BIN chunk");
    let block = gltf
        .nodes()
        .find(|n| n.name() == Some("block"))
        .expect("a node named block");
    assert!(gltf.nodes().any(|n| n.name() == Some("foundation")));
    let animation = gltf.animations().next().expect("an animation");
    let (mut times, mut at, mut turn) = (Vec::new(), Vec::new(), Vec::new());
    for channel in animation.channels() {
        assert_eq!(channel.target().node().index(), block.index());
        let reader = channel.reader(|_| Some(blob));
        times = reader.read_inputs().unwrap().collect();
        match reader.read_outputs().unwrap() {
            gltf::animation::util::ReadOutputs::Translations(v) => at = v.collect(),
            gltf::animation::util::ReadOutputs::Rotations(v) => turn = v.into_f32().collect(),
            _ => panic!("the block is only moved and turned"),
        }
    }
    assert!(times.len() > 100 && times.len() <= 4000, "{}", times.len());
    assert_eq!((at.len(), turn.len()), (times.len(), times.len()));
    let rows = route_csv(&dir);
    let t0 = rows[0][0];
    // Three keyframes, the first, one inside and the last, each against route.csv's row at
    // that time.
    for k in [0, times.len() / 2 + 1, times.len() - 1] {
        let t = f64::from(times[k]);
        let row = rows
            .iter()
            .min_by(|a, b| (a[0] - t0 - t).abs().total_cmp(&(b[0] - t0 - t).abs()))
            .unwrap();
        assert!((row[0] - t0 - t).abs() < 1e-6, "no row at t = {t}");
        let p = sample(&times, &at, t);
        for i in 0..3 {
            assert!(
                (p[i] - row[1 + i]).abs() < 1e-6,
                "t = {t}: the block's {} is {} m, route.csv's {} m",
                ["X", "Y", "Z"][i],
                p[i],
                row[1 + i]
            );
        }
        // The yaw: the block's x′ axis, turned by its rotation, from +X towards +Z.
        let q = sample(&times, &turn, t);
        let n = q.iter().map(|v| v * v).sum::<f64>().sqrt();
        let [x, y, z, w] = q.map(|v| v / n);
        let i_x = 1.0 - 2.0 * (y * y + z * z);
        let i_z = 2.0 * (x * z - w * y);
        let theta = i_z.atan2(i_x).to_degrees();
        assert!(
            (theta - row[4]).abs() < 1e-4,
            "t = {t}: yaw {theta}° against route.csv's {}°",
            row[4]
        );
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn no_3d_writes_neither_route_html_nor_route_glb_and_removes_an_earlier_runs() {
    let dir = temp("no-3d");
    run(&dir, &["--no-plots", "--set", "solver.t_end_s=0.5"]);
    let html = std::fs::read_to_string(dir.join("route.html")).unwrap();
    assert!(html.len() < 10_000_000);
    assert!(html.contains("<canvas") && html.contains("three"));
    assert!(dir.join("route.glb").exists());
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("summary.json")).unwrap()).unwrap();
    let files: Vec<&str> = summary["manifest"]["files"]
        .as_array()
        .unwrap()
        .iter()
        .map(|f| f["name"].as_str().unwrap())
        .collect();
    assert!(
        files.contains(&"route.html") && files.contains(&"route.glb"),
        "{files:?}"
    );
    run(
        &dir,
        &["--no-plots", "--no-3d", "--set", "solver.t_end_s=0.5"],
    );
    assert!(!dir.join("route.html").exists() && !dir.join("route.glb").exists());
    assert!(dir.join("route.csv").exists() && dir.join("summary.json").exists());
    let _ = std::fs::remove_dir_all(&dir);
}

/// Chromium headless, WebGL by SwiftShader (no GPU), on `page#hash` with `extra` arguments,
/// three seconds of virtual time: its stdout and the console messages on its stderr.
fn browse(page: &Path, hash: &str, profile: &Path, extra: &[&str]) -> (String, Vec<String>) {
    let o = Command::new(crate::common::browser::chromium())
        .args([
            "--headless",
            "--no-sandbox",
            "--no-first-run",
            "--use-angle=swiftshader",
            "--enable-unsafe-swiftshader",
            "--enable-logging=stderr",
            "--v=0",
            "--window-size=1200,800",
            "--virtual-time-budget=3000",
        ])
        .arg(format!("--user-data-dir={}", profile.display()))
        .args(extra)
        .arg(format!("file://{}#{hash}", page.display()))
        .output()
        .expect("Chromium runs");
    let log = String::from_utf8_lossy(&o.stderr);
    assert!(o.status.success(), "{log}");
    let console = log
        .lines()
        .filter(|l| l.contains("CONSOLE"))
        .map(str::to_string)
        .collect();
    (String::from_utf8_lossy(&o.stdout).into_owned(), console)
}

/// What the page says it shows: the JSON of its `#status` element.
fn status(dom: &str) -> serde_json::Value {
    let start = dom.find(r#"<pre id="status">"#).expect("a status element") + 17;
    let end = start + dom[start..].find("</pre>").unwrap();
    serde_json::from_str(&dom[start..end].replace("&quot;", "\""))
        .unwrap_or_else(|e| panic!("the page wrote no status ({e}): {:?}", &dom[start..end]))
}

/// The screenshot's pixels (RGB).
fn pixels(png_file: &Path) -> (u32, u32, Vec<[u8; 3]>) {
    let (w, h, px) = crate::common::browser::pixels(png_file);
    (w, h, px.into_iter().map(|[r, g, b, _]| [r, g, b]).collect())
}

#[test]
#[ignore = "needs Chromium (CI installs it): cargo test -- --ignored browser"]
fn browser_plays_the_route_in_3d_with_the_block_in_view_and_ends_at_summary_jsons_time_and_travel()
{
    let dir = temp("browser");
    let out = dir.join("run");
    run(&out, &["--no-plots"]);
    let page = out.join("route.html");
    let profile = dir.join("profile");
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();

    // Opened as it is: it plays from the start, drawing, the block in view.
    let (dom, console) = browse(&page, "", &profile, &["--dump-dom"]);
    assert!(console.is_empty(), "console: {console:?}");
    let s = status(&dom);
    assert_eq!(s["ready"], true, "{s}");
    assert!(s["frames"].as_u64().unwrap() >= 1, "{s}");
    assert_eq!(s["blockInView"], true, "{s}");
    assert!(s["poses"].as_u64().unwrap() <= 4000, "{s}");

    // The slider at the end: the time and travel summary.json gives, the block still in view.
    let (dom, console) = browse(&page, "t=end", &profile, &["--dump-dom"]);
    assert!(console.is_empty(), "console: {console:?}");
    let s = status(&dom);
    let t_end = summary["termination"]["t_s"].as_f64().unwrap();
    let travel = summary["travel_m"].as_f64().unwrap();
    assert!(
        (s["time"].as_f64().unwrap() - t_end).abs() < 1e-3,
        "{s} against {t_end} s"
    );
    assert!(
        (s["travel"].as_f64().unwrap() - travel).abs() < 1e-3,
        "{s} against {travel} m"
    );
    assert_eq!(s["blockInView"], true, "{s}");
    assert_eq!(s["playing"], false, "{s}");
    for shown in [format!("t = {t_end:.3} s"), format!("travel {travel:.3} m")] {
        assert!(dom.contains(&shown), "the page does not show {shown:?}");
    }

    // Its picture, half-way: neither blank nor one colour; the ground, the water's blue arrow
    // and the red CM path drawn.
    let shot = dir.join("route.png");
    let arg = format!("--screenshot={}", shot.display());
    let (_, console) = browse(&page, "t=2", &profile, &[&arg]);
    assert!(console.is_empty(), "console: {console:?}");
    let (w, h, px) = pixels(&shot);
    assert_eq!((w, h), (1200, 800));
    let mut colours = px.clone();
    colours.sort_unstable();
    colours.dedup();
    assert!(
        colours.len() > 200,
        "{} colours: a blank picture",
        colours.len()
    );
    let background = px.iter().filter(|p| **p == [0xf4, 0xf1, 0xea]).count();
    assert!(
        background < px.len() * 3 / 4,
        "{background} of {} pixels background",
        px.len()
    );
    let near = |p: &[u8; 3], q: [u8; 3]| (0..3).all(|i| p[i].abs_diff(q[i]) <= 24);
    for (what, rgb, least) in [
        ("water force", [0x15, 0x65, 0xc0], 200),
        ("CM path", [0xd0, 0x02, 0x1b], 20),
    ] {
        let n = px.iter().filter(|p| near(p, rgb)).count();
        assert!(n >= least, "the {what}'s colour covers {n} pixels");
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// `slideroute ARGS --quiet --out OUT` (any command), which must succeed.
fn slideroute(out: &Path, args: &[&str]) {
    let o = Command::new(env!("CARGO_BIN_EXE_slideroute"))
        .args(args)
        .arg("--quiet")
        .arg("--out")
        .arg(out)
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
}

/// The scene with uncertain keys, for `probabilistic`.
fn uncertain_scene() -> String {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("scenes/paper-like-uncertain.toml")
        .display()
        .to_string()
}

/// `command` (its arguments) writes `page`, a small self-contained page; with `--no-3d` it
/// does not, and removes an earlier one.
fn writes_its_page_unless_no_3d(name: &str, command: &[&str], page: &str) {
    let dir = temp(name);
    slideroute(&dir, command);
    let html = std::fs::read_to_string(dir.join(page)).unwrap_or_else(|e| panic!("{page}: {e}"));
    assert!(html.len() < 10_000_000, "{page}: {} bytes", html.len());
    assert!(html.contains("<canvas") && html.contains("importmap"));
    assert!(!html.contains("src=\"http"));
    slideroute(&dir, &[command, &["--no-3d"]].concat());
    assert!(!dir.join(page).exists(), "{page} after --no-3d");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn compare_dynamics_writes_compare_html_unless_no_3d() {
    writes_its_page_unless_no_3d(
        "compare-no-3d",
        &[
            "run",
            "--compare-dynamics",
            "--no-plots",
            "--set",
            "solver.t_end_s=1",
        ],
        "compare.html",
    );
}

#[test]
fn sweep_writes_sweep_html_unless_no_3d() {
    writes_its_page_unless_no_3d(
        "sweep-no-3d",
        &[
            "sweep",
            "--no-plots",
            "--vary",
            "friction.mu_k=0.3:0.5:3",
            "--set",
            "solver.t_end_s=1",
        ],
        "sweep.html",
    );
}

#[test]
fn probabilistic_writes_route_fan_html_unless_no_3d() {
    let scene = uncertain_scene();
    writes_its_page_unless_no_3d(
        "probabilistic-no-3d",
        &[
            "probabilistic",
            "--scene",
            &scene,
            "--no-plots",
            "--samples",
            "8",
            "--set",
            "solver.t_end_s=1",
        ],
        "route-fan.html",
    );
}

/// How many of `px` are within 24 of `rgb` in each channel.
fn count_near(px: &[[u8; 3]], rgb: [u8; 3]) -> usize {
    px.iter()
        .filter(|p| (0..3).all(|i| p[i].abs_diff(rgb[i]) <= 24))
        .count()
}

/// The screenshot of `page#hash` is neither blank nor mostly background; returns its pixels.
fn screenshot(page: &Path, hash: &str, profile: &Path, shot: &Path) -> Vec<[u8; 3]> {
    let arg = format!("--screenshot={}", shot.display());
    let (_, console) = browse(page, hash, profile, &[&arg]);
    assert!(
        console.is_empty(),
        "{}: console: {console:?}",
        page.display()
    );
    let (w, h, px) = pixels(shot);
    assert_eq!((w, h), (1200, 800));
    let mut colours = px.clone();
    colours.sort_unstable();
    colours.dedup();
    assert!(
        colours.len() > 200,
        "{}: {} colours: a blank picture",
        page.display(),
        colours.len()
    );
    let background = px.iter().filter(|p| **p == [0xf4, 0xf1, 0xea]).count();
    assert!(
        background < px.len() * 3 / 4,
        "{}: {background} of {} pixels background",
        page.display(),
        px.len()
    );
    px
}

#[test]
#[ignore = "needs Chromium (CI installs it): cargo test -- --ignored browser"]
fn browser_shows_both_dynamics_and_the_route_fan_in_3d() {
    let dir = temp("browser-many");
    let profile = dir.join("profile");

    // compare.html: both routes, each ending at its own time (comparison.json's), both blocks
    // in view at the end, both colours drawn.
    let cmp = dir.join("compare");
    slideroute(&cmp, &["run", "--compare-dynamics", "--no-plots"]);
    let page = cmp.join("compare.html");
    let c: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(cmp.join("comparison.json")).unwrap())
            .unwrap();
    let (dom, console) = browse(&page, "", &profile, &["--dump-dom"]);
    assert!(console.is_empty(), "console: {console:?}");
    let s = status(&dom);
    assert_eq!(s["ready"], true, "{s}");
    assert_eq!(s["mode"], "compare", "{s}");
    assert!(s["frames"].as_u64().unwrap() >= 1, "{s}");
    let (dom, console) = browse(&page, "t=end", &profile, &["--dump-dom"]);
    assert!(console.is_empty(), "console: {console:?}");
    let s = status(&dom);
    let routes = s["routes"].as_array().unwrap();
    assert_eq!(routes.len(), 2, "{s}");
    for (r, key) in routes.iter().zip(["paper", "rigid_body"]) {
        let travel = c[key]["travel_m"].as_f64().unwrap();
        assert!(
            (r["travel"].as_f64().unwrap() - travel).abs() < 1e-3,
            "{key}: {r} against {travel} m"
        );
        assert_eq!(r["blockInView"], true, "{key}: {r}");
        assert!(r["poses"].as_u64().unwrap() <= 4000, "{r}");
    }
    let ends: Vec<f64> = routes.iter().map(|r| r["end"].as_f64().unwrap()).collect();
    assert!(
        (ends[0] - ends[1]).abs() > 0.1,
        "{ends:?}: each its own time"
    );
    for label in ["paper dynamics", "rigid-body dynamics"] {
        assert!(dom.contains(label), "the legend does not name {label}");
    }
    let px = screenshot(&page, "t=2", &profile, &dir.join("compare.png"));
    for (what, rgb) in [
        ("paper's CM path", [0x7b, 0x1f, 0xa2]),
        ("rigid body's CM path", [0x00, 0x89, 0x7b]),
        ("water force", [0x15, 0x65, 0xc0]),
    ] {
        let n = count_near(&px, rgb);
        assert!(n >= 20, "the {what}'s colour covers {n} pixels");
    }

    // route-fan.html: every sample's CM path drawn over the ground, the scene as written on
    // them with its block in view.
    let fan = dir.join("probabilistic");
    let scene = uncertain_scene();
    slideroute(
        &fan,
        &[
            "probabilistic",
            "--scene",
            &scene,
            "--no-plots",
            "--samples",
            "40",
        ],
    );
    let page = fan.join("route-fan.html");
    let p: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(fan.join("probabilistic.json")).unwrap())
            .unwrap();
    let (dom, console) = browse(&page, "", &profile, &["--dump-dom"]);
    assert!(console.is_empty(), "console: {console:?}");
    let s = status(&dom);
    assert_eq!(s["ready"], true, "{s}");
    assert_eq!(s["mode"], "fan", "{s}");
    assert_eq!(s["fanPaths"], p["routes"], "{s}");
    assert!(s["fanSegments"].as_u64().unwrap() > 40, "{s}");
    assert_eq!(s["routes"].as_array().unwrap().len(), 1, "{s}");
    assert_eq!(s["blockInView"], true, "{s}");
    let px = screenshot(&page, "t=end", &profile, &dir.join("route-fan.png"));
    // The fan's orange, a little transparent over the ground.
    let orange = px
        .iter()
        .filter(|p| p[0] > 190 && p[0] as i32 - p[2] as i32 > 110 && p[1] < 175)
        .count();
    assert!(orange >= 300, "the fan's orange covers {orange} pixels");
    if let Some(keep) = std::env::var_os("SLIDEROUTE_KEEP_SCREENSHOTS") {
        for f in ["compare.png", "route-fan.png"] {
            std::fs::copy(dir.join(f), Path::new(&keep).join(f)).unwrap();
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
}
