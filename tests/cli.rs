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
