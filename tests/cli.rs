//! The command line, run as a user would: exit codes, one-line errors naming the input, output.
#![cfg(feature = "cli")]

use std::process::{Command, Output};

fn run(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_slideroute"))
        .args(args)
        .output()
        .expect("run slideroute")
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

fn assert_bad_input(o: &Output, needles: &[&str]) {
    let err = stderr(o);
    assert_eq!(o.status.code(), Some(2), "stderr: {err}");
    assert!(
        !err.contains("panicked") && !err.contains("RUST_BACKTRACE"),
        "{err}"
    );
    for n in needles {
        assert!(err.contains(n), "expected {n:?} in {err:?}");
    }
}

fn temp_file(name: &str, text: &str) -> std::path::PathBuf {
    let dir = std::env::temp_dir().join(format!("slideroute-cli-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let p = dir.join(name);
    std::fs::write(&p, text).unwrap();
    p
}

#[test]
fn coeffs_json_on_the_default_scene_has_f1_to_f12_and_the_exact_form() {
    let o = run(&[
        "coeffs",
        "--x",
        "0.5",
        "--z",
        "0.1",
        "--theta-deg",
        "-2",
        "--json",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).expect("JSON");
    let small = v["small_angle"].as_object().expect("small_angle object");
    let expected: Vec<String> = (1..=12).map(|k| format!("f{k}")).collect();
    assert_eq!(small.len(), 12);
    assert!(expected.iter().all(|k| small.contains_key(k)));
    // Printed in the paper's order f1 … f12.
    let text = String::from_utf8_lossy(&o.stdout);
    let pos: Vec<usize> = expected
        .iter()
        .map(|k| text.find(&format!("\"{k}\":")).expect("key"))
        .collect();
    assert!(pos.windows(2).all(|w| w[0] < w[1]), "f1…f12 out of order");
    assert!(small.values().all(|x| x.is_f64()));
    assert_eq!(small["f6"].as_f64(), Some(50.0)); // 2 L1Z² with L1Z = 5 m
    assert!(v["exact"]["eq13"]["sa"].is_f64());
    assert!(v["exact"]["eq14"]["ca_sp"].is_f64());
    assert_eq!(v["theta_deg"].as_f64(), Some(-2.0));

    // The same numbers as the library.
    let scene = slideroute::scene::Scene::default_scene();
    let d = slideroute::geometry::Displacement::new(0.5, 0.1, (-2f64).to_radians());
    let f = slideroute::coeffs::SmallAngle::new(&slideroute::coeffs::CoeffInputs::new(&scene, d));
    assert_eq!(small["f1"].as_f64(), Some(f.f[0]));
}

#[test]
fn coeffs_table_is_readable() {
    let o = run(&["coeffs", "--x", "1", "--z", "0", "--theta-deg", "0"]);
    assert!(o.status.success());
    let out = String::from_utf8_lossy(&o.stdout);
    assert!(out.contains("f12 ="), "{out}");
    assert!(out.contains("(13)") && out.contains("(14)"), "{out}");
}

#[test]
fn coeffs_reads_a_scene_file() {
    let p = temp_file("shallow.toml", include_str!("../scenes/shallow.toml"));
    let o = run(&[
        "coeffs",
        "--scene",
        p.to_str().unwrap(),
        "--x",
        "0.2",
        "--z",
        "0",
        "--theta-deg",
        "1",
        "--json",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(v["scene"], "shallow");
}

#[test]
fn bad_scene_file_is_one_line_naming_file_and_key() {
    let text = include_str!("../scenes/paper-like.toml").replace("xi_deg = 20.0", "xi_deg = 95.0");
    let p = temp_file("steep.toml", &text);
    let o = run(&[
        "coeffs",
        "--scene",
        p.to_str().unwrap(),
        "--x",
        "0",
        "--z",
        "0",
        "--theta-deg",
        "0",
    ]);
    assert_bad_input(&o, &["steep.toml", "foundation.xi_deg", "90°"]);
    assert_eq!(stderr(&o).trim_end().lines().count(), 1);
}

#[test]
fn missing_scene_file_is_named() {
    let o = run(&[
        "coeffs",
        "--scene",
        "/no/such/dam.toml",
        "--x",
        "0",
        "--z",
        "0",
        "--theta-deg",
        "0",
    ]);
    assert_bad_input(&o, &["/no/such/dam.toml", "cannot read"]);
}

#[test]
fn non_finite_and_malformed_flags_are_rejected() {
    assert_bad_input(
        &run(&["coeffs", "--x", "nan", "--z", "0", "--theta-deg", "0"]),
        &["--x", "finite"],
    );
    assert_bad_input(
        &run(&["coeffs", "--x", "0", "--z", "0", "--theta-deg", "inf"]),
        &["--theta-deg"],
    );
    assert_bad_input(
        &run(&["coeffs", "--x", "abc", "--z", "0", "--theta-deg", "0"]),
        &["--x"],
    );
    assert_bad_input(&run(&["coeffs", "--z", "0", "--theta-deg", "0"]), &["--x"]);
    assert_bad_input(
        &run(&[
            "coeffs",
            "--x",
            "0",
            "--z",
            "0",
            "--theta-deg",
            "0",
            "--bogus",
        ]),
        &["--bogus"],
    );
    assert_bad_input(&run(&["no-such-command"]), &["no-such-command"]);
}

#[test]
fn roots_json_has_selected_pose_roots_and_counts() {
    let o = run(&[
        "roots",
        "--x",
        "0.5",
        "--z",
        "0.1",
        "--theta-deg",
        "2",
        "--json",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).expect("JSON");
    for k in ["alpha_deg", "beta_deg", "gamma_deg", "cm_y_m"] {
        assert!(v["selected"][k].is_f64(), "selected.{k}");
    }
    assert_eq!(v["mode"], "exact");
    assert_eq!(
        v["finite_roots"].as_u64().unwrap() + v["roots_at_infinity"].as_u64().unwrap(),
        8
    );
    let roots = v["roots"].as_array().unwrap();
    assert!(!roots.is_empty());
    for r in roots {
        assert_eq!(r["alpha_deg"].as_array().unwrap().len(), 2);
        assert_eq!(r["beta_deg"].as_array().unwrap().len(), 2);
        assert!(r["admissible"].is_boolean() && r["spurious"].is_boolean());
    }
    // Agrees with the independent direct pose solver.
    let scene = slideroute::scene::Scene::default_scene();
    let d = slideroute::geometry::Displacement::new(0.5, 0.1, 2f64.to_radians());
    let p = slideroute::geometry::direct::solve(&scene, d).unwrap();
    let a = v["selected"]["alpha_deg"].as_f64().unwrap();
    assert!((a - p.alpha(scene.l()).to_degrees()).abs() < 1e-8);

    let o = run(&[
        "roots",
        "--x",
        "0.5",
        "--z",
        "0.1",
        "--theta-deg",
        "2",
        "--mode",
        "small-angle",
        "--json",
    ]);
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).expect("JSON");
    assert_eq!(
        v["finite_roots"].as_u64().unwrap() + v["roots_at_infinity"].as_u64().unwrap(),
        16
    );
}

#[test]
fn roots_table_names_the_selected_pose() {
    let o = run(&[
        "roots",
        "--x",
        "1",
        "--z",
        "0",
        "--theta-deg",
        "0",
        "--mode",
        "small-angle",
    ]);
    assert!(o.status.success());
    let out = String::from_utf8_lossy(&o.stdout);
    assert!(out.contains("selected: α ="), "{out}");
    assert!(out.contains("spurious"), "{out}");
}

#[test]
fn roots_grid_writes_one_row_per_pose_in_order() {
    let grid = temp_file(
        "poses.csv",
        "x_m,z_m,theta_deg\n0.5,0.1,2\n1.0,0,0\n1.0,0,-30\n2.0,0.3,-3\n",
    );
    let out = grid.with_file_name("out.csv");
    let o = run(&[
        "roots",
        "--grid",
        grid.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let text = std::fs::read_to_string(&out).unwrap();
    let lines: Vec<&str> = text.lines().collect();
    assert_eq!(lines.len(), 5, "{text}");
    assert!(lines[0].starts_with("x_m,z_m,theta_deg,status,alpha_deg,beta_deg"));
    assert!(lines[1].starts_with("0.5,0.1,2,selected,"));
    assert!(lines[3].contains("no admissible root"), "{}", lines[3]);
    assert!(lines[4].starts_with("2,0.3,-3,selected,"));
}

#[test]
fn bad_grid_files_name_the_line_and_column() {
    let grid = temp_file("bad.csv", "x_m,z_m,theta_deg\n0.5,0.1,2\n1.0,abc,0\n");
    let out = grid.with_file_name("o.csv");
    let o = run(&[
        "roots",
        "--grid",
        grid.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ]);
    assert_bad_input(&o, &["bad.csv", "line 3", "z_m", "abc"]);
    let grid = temp_file("hdr.csv", "x,z,theta\n0.5,0.1,2\n");
    let o = run(&[
        "roots",
        "--grid",
        grid.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ]);
    assert_bad_input(&o, &["hdr.csv", "line 1", "x_m,z_m,theta_deg"]);
    let o = run(&["roots", "--grid", grid.to_str().unwrap()]);
    assert_bad_input(&o, &["--out"]);
    assert_bad_input(
        &run(&[
            "roots",
            "--x",
            "1",
            "--z",
            "0",
            "--theta-deg",
            "0",
            "--mode",
            "huge",
        ]),
        &["huge"],
    );
    assert_bad_input(&run(&["roots", "--x", "1", "--z", "0"]), &["--theta-deg"]);
}

#[test]
fn run_writes_route_csv_and_summary_json() {
    let dir = std::env::temp_dir().join(format!("slideroute-run-{}", std::process::id()));
    let o = run(&["run", "--out", dir.to_str().unwrap()]);
    assert!(o.status.success(), "{}", stderr(&o));
    let out = String::from_utf8_lossy(&o.stdout);
    assert!(out.contains("factor of safety at onset"), "{out}");
    let csv = std::fs::read_to_string(dir.join("route.csv")).unwrap();
    let header = csv.lines().next().unwrap();
    assert_eq!(
        header,
        "t_s,x_m,y_m,z_m,theta_deg,alpha_deg,beta_deg,gamma_deg,vx_m_s,vz_m_s,omega_deg_s,n0_n,n1_n,n2_n,s0_n,s1_n,s2_n"
    );
    assert!(csv.lines().count() > 1000);
    let v: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("summary.json")).unwrap()).unwrap();
    for k in [
        "scene",
        "mode",
        "integrator",
        "termination",
        "factor_of_safety_onset",
        "travel_m",
        "increments",
        "wall_s",
    ] {
        assert!(!v[k].is_null(), "summary.{k}");
    }
    for k in ["reason", "t_s", "detail"] {
        assert!(!v["termination"][k].is_null(), "termination.{k}");
    }
    assert_eq!(v["mode"], "exact");
    assert_eq!(v["integrator"], "paper");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn run_on_a_geometry_only_scene_names_the_missing_section() {
    let text = include_str!("../scenes/paper-like.toml");
    let geo = text.split("[block]").next().unwrap();
    let p = temp_file("geo.toml", geo);
    assert_bad_input(
        &run(&["run", "--scene", p.to_str().unwrap(), "--out", "/tmp/never"]),
        &["geo.toml", "block", "missing section"],
    );
}
