//! `check`'s `report.html` in a real browser, as a reviewer opens it: headless Chromium (the
//! system's package, which `.ci/run` installs) loads the page, prints its DOM and takes a
//! screenshot. The test fails on a console message, a blank or one-colour page, or a page
//! without the section drawn and the verdicts of `check.json` in its tables.
//!
//! Ignored by default (it needs Chromium); CI runs it with the Drake and record tests
//! (`cargo test -- --ignored browser`).

use std::path::Path;
use std::process::Command;

/// The dam template with two anchors: one vertical from the crest, one from the base plunging
/// upstream.
const ANCHORS: &str = "
[[anchor]]
x_m = 2.0
y_m = 15.0
prestress_n = 2.0e6
capacity_n = 6.0e6
free_length_m = 30.0
steel_area_m2 = 4.0e-3

[[anchor]]
x_m = 3.0
plunge_deg = 60.0
trend_deg = 180.0
prestress_n = 3.0e6
capacity_n = 6.0e6
free_length_m = 25.0
steel_area_m2 = 4.0e-3
";

/// Chromium headless on `page` with `extra` arguments: its stdout and stderr.
fn browse(page: &Path, profile: &Path, extra: &[&str]) -> (String, String) {
    let o = Command::new(crate::common::browser::chromium())
        .args([
            "--headless",
            "--no-sandbox",
            "--disable-gpu",
            "--no-first-run",
            "--enable-logging=stderr",
            "--v=0",
            "--window-size=1200,1600",
        ])
        .arg(format!("--user-data-dir={}", profile.display()))
        .args(extra)
        .arg(format!("file://{}", page.display()))
        .output()
        .expect("Chromium runs");
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    (
        String::from_utf8_lossy(&o.stdout).into_owned(),
        String::from_utf8_lossy(&o.stderr).into_owned(),
    )
}

#[test]
#[ignore = "needs Chromium (CI installs it): cargo test -- --ignored browser"]
fn browser_shows_the_check_report_with_its_section_loads_and_verdicts_and_no_console_error() {
    let dir = std::env::temp_dir().join(format!("slideroute-browser-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let scene = dir.join("dam.toml");
    std::fs::write(&scene, format!("{}{ANCHORS}", slideroute::Scene::DAM_TOML)).unwrap();
    let out = dir.join("check");
    let o = Command::new(env!("CARGO_BIN_EXE_slideroute"))
        .args(["check", "--quiet", "--no-plots", "--scene"])
        .arg(&scene)
        .arg("--out")
        .arg(&out)
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let page = out.join("report.html");
    let profile = dir.join("profile");

    // The page as the browser built it: no console message, every case drawn and tabled.
    let (dom, log) = browse(&page, &profile, &["--dump-dom"]);
    let console: Vec<&str> = log.lines().filter(|l| l.contains("CONSOLE")).collect();
    assert!(console.is_empty(), "console: {console:?}");
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("check.json")).unwrap()).unwrap();
    let cases = json["cases"].as_array().unwrap();
    assert_eq!(
        dom.matches("<svg").count(),
        cases.len(),
        "one section drawn a case"
    );
    for case in cases {
        let name = case["case"]["name"].as_str().unwrap();
        assert!(dom.contains(name), "{name} is not on the page");
        let fs = case["sliding_fs"].as_f64().unwrap();
        let shown = format!("{fs:.3}");
        assert!(
            dom.contains(&shown),
            "{name}'s sliding FS {shown} is not on the page"
        );
    }
    for label in ["P1 ", "W ", "A0 ", "A1 ", "uplift U", "middle third"] {
        assert!(dom.contains(label), "the drawing has no {label:?}");
    }

    // The screenshot: neither blank nor one colour, the section's grey and the water's blue
    // among its colours.
    let shot = dir.join("report.png");
    let arg = format!("--screenshot={}", shot.display());
    let (_, log) = browse(&page, &profile, &[&arg]);
    assert!(!log.contains("CONSOLE"), "{log}");
    let (w, h, px) = crate::common::browser::pixels(&shot);
    assert_eq!((w, h), (1200, 1600));
    let mut colours: Vec<[u8; 4]> = px.clone();
    colours.sort_unstable();
    colours.dedup();
    assert!(
        colours.len() > 50,
        "{} colours: a blank page",
        colours.len()
    );
    let white = px.iter().filter(|p| p[..3] == [255, 255, 255]).count();
    assert!(
        white < px.len() * 9 / 10,
        "{white} of {} pixels white",
        px.len()
    );
    for (what, rgb) in [
        ("section", [0xc9, 0xc9, 0xc9]),
        ("water", [0xbc, 0xdc, 0xf2]),
    ] {
        let n = px.iter().filter(|p| p[..3] == rgb).count();
        assert!(n > 5000, "the {what}'s colour covers {n} pixels");
    }
    let _ = std::fs::remove_dir_all(&dir);
}
