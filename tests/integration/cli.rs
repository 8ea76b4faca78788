//! The command line, run as a user would: exit codes, one-line errors naming the input, output.
#![cfg(feature = "cli")]

use std::process::{Command, Output};

fn run(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_slideroute"))
        .args(args)
        .output()
        .expect("run slideroute")
}

/// `run --scene SCENE --out OUT --no-plots`.
fn run_scene(scene: &std::path::Path, out: &std::path::Path) -> Output {
    run(&[
        "run",
        "--scene",
        scene.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
        "--no-plots",
    ])
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
    let scene = slideroute::internals::scene::Scene::default_scene();
    let d = slideroute::internals::geometry::Displacement::new(0.5, 0.1, (-2f64).to_radians());
    let f = slideroute::internals::coeffs::SmallAngle::new(
        &slideroute::internals::coeffs::CoeffInputs::new(scene.site().as_paper().unwrap(), d),
    );
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
fn coeffs_at_a_displacement_past_what_the_system_can_be_evaluated_at_is_refused() {
    // Before: `f1 = NaN`, `f2 = -inf` and X in 309 digits, exit 0 (and `null`s in --json).
    for json in [false, true] {
        let mut args = vec![
            "coeffs",
            "--x",
            "1e308",
            "--z",
            "1e308",
            "--theta-deg",
            "1e308",
        ];
        if json {
            args.push("--json");
        }
        let o = run(&args);
        assert_bad_input(&o, &["--x 1e308", "is not a finite number there"]);
        assert_eq!(stderr(&o).trim_end().lines().count(), 1, "{}", stderr(&o));
        assert!(o.stdout.is_empty());
    }
    // Far, but finite: printed, X as given.
    let o = run(&["coeffs", "--x", "1e10", "--z", "0", "--theta-deg", "0"]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(String::from_utf8_lossy(&o.stdout).contains("X = 10000000000 m"));
}

#[test]
fn roots_of_a_grid_refuse_json_rather_than_ignore_it() {
    // Before: --json with --grid was ignored without a word.
    let o = run(&["roots", "--grid", "g.csv", "--out", "o.csv", "--json"]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(stderr(&o).contains("--json"), "{}", stderr(&o));
    assert_eq!(stderr(&o).trim_end().lines().count(), 1, "{}", stderr(&o));
}

#[test]
fn coeffs_reads_a_scene_file() {
    let p = temp_file("shallow.toml", include_str!("../../scenes/shallow.toml"));
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
    let text =
        include_str!("../../scenes/paper-like.toml").replace("xi_deg = 20.0", "xi_deg = 95.0");
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
    let scene = slideroute::internals::scene::Scene::default_scene();
    let d = slideroute::internals::geometry::Displacement::new(0.5, 0.1, 2f64.to_radians());
    let p = slideroute::poses::direct_pose(scene.site(), d).unwrap();
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
fn a_grid_that_fails_part_way_leaves_an_earlier_output_whole_and_no_temporary() {
    // `roots --grid --out FILE` must not write in place: a fault (or a full disk) part way
    // would truncate an earlier good file.
    let dir = temp_dir("grid-keep");
    std::fs::create_dir_all(&dir).unwrap();
    let out = dir.join("poses-out.csv");
    std::fs::write(&out, "an earlier good file\n").unwrap();
    let mut text = String::from("x_m,z_m,theta_deg\n");
    for k in 0..5000 {
        text.push_str(&format!("{},0,0\n", k as f64 * 1e-4));
    }
    text.push_str("1.0,abc,0\n");
    let grid = dir.join("grid.csv");
    std::fs::write(&grid, text).unwrap();
    let o = run(&[
        "roots",
        "--grid",
        grid.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ]);
    assert_bad_input(&o, &["grid.csv", "line 5002", "z_m"]);
    assert_eq!(
        std::fs::read_to_string(&out).unwrap(),
        "an earlier good file\n"
    );
    let names: Vec<String> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    assert_eq!(names.len(), 2, "{names:?}");
    // Given a device, it writes there (nothing renamed over /dev/null).
    std::fs::write(&grid, "x_m,z_m,theta_deg\n0.5,0.1,2\n").unwrap();
    let o = run(&[
        "roots",
        "--grid",
        grid.to_str().unwrap(),
        "--out",
        "/dev/null",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    #[cfg(unix)]
    {
        use std::os::unix::fs::FileTypeExt;
        assert!(
            std::fs::metadata("/dev/null")
                .unwrap()
                .file_type()
                .is_char_device()
        );
    }
    let _ = std::fs::remove_dir_all(&dir);
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
    assert!(out.contains("factor of safety 0.8"), "{out}");
    let csv = std::fs::read_to_string(dir.join("route.csv")).unwrap();
    let header = csv.lines().next().unwrap();
    assert_eq!(
        header,
        "body,t_s,x_m,y_m,z_m,theta_deg,alpha_deg,beta_deg,gamma_deg,vx_m_s,vz_m_s,omega_deg_s,n0_n,n1_n,n2_n,s0_n,s1_n,s2_n,face0,face1,face2,crease_face0,crease_face1,crease_face2,corners_carrying,points_carrying"
    );
    // The paper's planes: contact k on plane k, no crease.
    let second = csv.lines().nth(1).unwrap();
    assert!(second.ends_with(",0,1,2,,,,,"), "{second}");
    assert!(csv.lines().count() > 1000);
    let v: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("summary.json")).unwrap()).unwrap();
    for k in [
        "scene",
        "mode",
        "integrator",
        "termination",
        "factor_of_safety",
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
    // The default dynamics is the rigid body's, integrated with RK4.
    assert_eq!(v["dynamics"], "rigid-body");
    assert_eq!(v["integrator"], "rk4");
    // One factor of safety, the friction cones', as a typed value: never null or infinite.
    assert_eq!(v["factor_of_safety"]["kind"], "finite");
    let fs = v["factor_of_safety"]["value"].as_f64().unwrap();
    assert!((0.8..0.9).contains(&fs), "{fs}");
    assert!(
        v["paper_ratio"].is_null(),
        "the paper's ratio is the paper's dynamics' only"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn run_on_a_geometry_only_scene_names_the_missing_section() {
    let text = include_str!("../../scenes/paper-like.toml");
    let geo = text.split("[block]").next().unwrap();
    let p = temp_file("geo.toml", geo);
    assert_bad_input(
        &run(&["run", "--scene", p.to_str().unwrap(), "--out", "/tmp/never"]),
        &["geo.toml", "block", "missing section"],
    );
}

/// Runs `slideroute sweep --quiet --out DIR` with `args`; on success, sweep.csv's text.
fn sweep_csv(dir: &std::path::Path, args: &[&str]) -> String {
    let mut all = vec!["sweep", "--quiet", "--out", dir.to_str().unwrap()];
    all.extend_from_slice(args);
    let o = run(&all);
    assert!(o.status.success(), "{}", stderr(&o));
    std::fs::read_to_string(dir.join("sweep.csv")).unwrap()
}

fn temp_dir(name: &str) -> std::path::PathBuf {
    let d = std::env::temp_dir().join(format!("slideroute-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    d
}

#[test]
fn run_without_arguments_draws_the_four_pictures() {
    let dir = temp_dir("pictures");
    let o = run(&["run", "--out", dir.to_str().unwrap()]);
    assert!(o.status.success(), "{}", stderr(&o));
    for name in ["plan.svg", "profile.svg", "angles.svg", "reactions.svg"] {
        let text =
            std::fs::read_to_string(dir.join(name)).unwrap_or_else(|e| panic!("{name}: {e}"));
        assert!(text.starts_with("<svg"), "{name}");
        assert!(
            text.contains("(m)") || text.contains("(°)") || text.contains("(MN)"),
            "{name} has units"
        );
    }
    let plan = std::fs::read_to_string(dir.join("plan.svg")).unwrap();
    assert!(plan.contains("plane 1, dip 20°") && plan.contains("path of the centre of mass"));
    let out = String::from_utf8_lossy(&o.stdout);
    for part in ["travel", "final yaw", "factor of safety", "increments"] {
        assert!(out.contains(part), "summary lacks {part}: {out}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn quiet_run_prints_nothing_and_still_writes() {
    let dir = temp_dir("quiet");
    let o = run(&["run", "--quiet", "--out", dir.to_str().unwrap()]);
    assert!(o.status.success());
    assert!(o.stdout.is_empty() && o.stderr.is_empty(), "{}", stderr(&o));
    assert!(dir.join("route.csv").exists());
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn print_default_is_the_embedded_scene_and_loads() {
    let o = run(&["scene", "--print-default"]);
    assert!(o.status.success());
    let text = String::from_utf8_lossy(&o.stdout);
    assert!(text.contains("# ") && text.contains("hydraulic_force_n"));
    let s = slideroute::internals::scene::Scene::from_toml(&text, "printed").unwrap();
    assert_eq!(s.name(), "paper-like");
    let p = temp_file("printed.toml", &text);
    let o = run(&["scene", "--check", p.to_str().unwrap()]);
    assert!(o.status.success() && String::from_utf8_lossy(&o.stdout).contains("ok"));
    let bad = temp_file("bad.toml", &text.replace("mu_k = 0.40", "mu_k = -0.40"));
    assert_bad_input(
        &run(&["scene", "--check", bad.to_str().unwrap()]),
        &["bad.toml", "friction.mu_k"],
    );
    assert_bad_input(&run(&["scene"]), &["--print-default"]);
}

#[test]
fn the_dam_template_is_a_commented_scene_with_every_dam_section_that_checks() {
    let o = run(&["scene", "--template", "dam"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let text = String::from_utf8_lossy(&o.stdout);
    for section in [
        "[monolith]",
        "[water]",
        "[silt]",
        "[ice]",
        "[friction]",
        "[check]",
        "[[case]]",
    ] {
        assert!(text.contains(section), "{section} in the template");
    }
    let s = slideroute::internals::scene::Scene::from_toml(&text, "dam").unwrap();
    let w = s.loads().unwrap().water.unwrap();
    assert!(w.levels.crack && w.levels.silt.is_some() && w.levels.ice.is_some());
    assert!(
        s.cases()
            .iter()
            .any(|c| c.keys.iter().any(|k| k.0 == "water.drain_efficiency"))
    );
    let p = temp_file("dam-template.toml", &text);
    let o = run(&["scene", "--check", p.to_str().unwrap()]);
    assert!(o.status.success() && String::from_utf8_lossy(&o.stdout).contains("all sections"));
    let paper = run(&["scene", "--template", "paper"]);
    assert_eq!(paper.stdout, run(&["scene", "--print-default"]).stdout);
    assert_bad_input(&run(&["scene", "--template", "arch"]), &["arch"]);
}

#[test]
fn sweep_of_200_combinations_has_a_row_for_each() {
    let dir = temp_dir("sweep");
    let o = run(&[
        "sweep",
        "--vary",
        "friction.mu_k=0.2:0.7:20",
        "--vary",
        "loads.eccentricity_m=-1:1:10",
        "--out",
        dir.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let csv = std::fs::read_to_string(dir.join("sweep.csv")).unwrap();
    let mut lines = csv.lines();
    assert!(
        lines
            .next()
            .unwrap()
            .starts_with("friction.mu_k,loads.eccentricity_m,reason,")
    );
    let rows: Vec<&str> = lines.collect();
    assert_eq!(rows.len(), 200);
    assert!(
        rows.iter()
            .all(|r| !r.split(',').nth(2).unwrap_or("").is_empty())
    );
    assert!(
        std::fs::read_to_string(dir.join("sweep.svg"))
            .unwrap()
            .starts_with("<svg")
    );
    assert!(String::from_utf8_lossy(&o.stdout).contains("200 combinations"));
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn sweep_rows_for_invalid_combinations_say_why() {
    let dir = temp_dir("sweep-invalid");
    let o = run(&[
        "sweep",
        "--vary",
        "foundation.xi_deg=60:120:3",
        "--out",
        dir.to_str().unwrap(),
        "--quiet",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let csv = std::fs::read_to_string(dir.join("sweep.csv")).unwrap();
    let last = csv.lines().last().unwrap();
    assert!(
        last.starts_with("120,invalid scene,") && last.contains("foundation.xi_deg"),
        "{last}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn sweep_flags_are_checked() {
    assert_bad_input(
        &run(&["sweep", "--vary", "friction.mu=0:1:3"]),
        &["--vary friction.mu", "mu_k"],
    );
    assert_bad_input(
        &run(&["sweep", "--vary", "friction.mu_k=0:1"]),
        &["--vary friction.mu_k=0:1", "START:STOP:COUNT"],
    );
    assert_bad_input(
        &run(&["sweep", "--vary", "friction.mu_k=0:1:0"]),
        &["COUNT"],
    );
    assert_bad_input(&run(&["sweep"]), &["--vary"]);
    assert_bad_input(
        &run(&[
            "sweep",
            "--vary",
            "friction.mu_k=0:1:100000",
            "--vary",
            "loads.eccentricity_m=0:1:100000",
        ]),
        &["combinations"],
    );
}

#[test]
fn every_command_explains_its_flags() {
    for cmd in ["run", "sweep", "scene", "roots", "coeffs"] {
        let o = run(&[cmd, "--help"]);
        assert!(o.status.success(), "{cmd}");
        let text = String::from_utf8_lossy(&o.stdout);
        assert!(text.contains("Usage:"), "{cmd}");
    }
    let roots = String::from_utf8_lossy(&run(&["roots", "--help"]).stdout).to_string();
    assert!(roots.contains("metres") && roots.contains("degrees"));
    let top = String::from_utf8_lossy(&run(&["--help"]).stdout).to_string();
    assert!(top.contains("degrees") && top.contains("metres"));
}

#[test]
fn report_quick_writes_csv_markdown_and_picture() {
    let dir = temp_dir("report");
    let o = run(&["report", "--quick", "--out", dir.to_str().unwrap()]);
    assert!(o.status.success(), "{}", stderr(&o));
    let csv = std::fs::read_to_string(dir.join("work-precision.csv")).unwrap();
    assert_eq!(
        csv.lines().next().unwrap(),
        "scene,dynamics,method,mode,integrator,dt_s,tolerance,increments,steps,wall_s,error_m"
    );
    assert_eq!(
        csv.lines().count(),
        // Quick: 2 scenes × (the paper's dynamics' 2 pose methods × 2 modes × 2 integrators
        // over dt, the paper's RK4 over tolerances, and the rigid body over tolerances) × 3.
        1 + 2 * (2 * 2 * 2 + 2) * 3
    );
    let md = std::fs::read_to_string(dir.join("work-precision.md")).unwrap();
    assert!(md.contains("## Stiff and extreme cases") && md.contains("## References"));
    assert!(
        std::fs::read_to_string(dir.join("work-precision.svg"))
            .unwrap()
            .starts_with("<svg")
    );
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn run_no_plots_writes_only_the_data() {
    let dir = temp_dir("noplots");
    let o = run(&[
        "run",
        "--no-plots",
        "--quiet",
        "--out",
        dir.to_str().unwrap(),
    ]);
    assert!(o.status.success());
    assert!(dir.join("route.csv").exists() && !dir.join("plan.svg").exists());
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn run_with_rigid_body_dynamics_reports_it_and_its_energy() {
    let dir = temp_dir("rigid");
    let o = run(&[
        "run",
        "--dynamics",
        "rigid-body",
        "--no-plots",
        "--out",
        dir.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let out = String::from_utf8_lossy(&o.stdout);
    assert!(out.contains("rigid-body dynamics"), "{out}");
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("summary.json")).unwrap()).unwrap();
    assert_eq!(summary["dynamics"], "rigid-body");
    assert_eq!(summary["integrator"], "rk4");
    // The balance holds to the step control's tolerance of the energy scale (about 1e8 J).
    let energy = &summary["energy"];
    let scale = energy["work_hydraulic_j"].as_f64().unwrap();
    assert!(
        energy["residual_j"].as_f64().unwrap().abs() < 1e-9 * scale,
        "{energy}"
    );
}

#[test]
fn compare_dynamics_writes_both_routes_and_where_they_part() {
    let dir = temp_dir("compare");
    let o = run(&["run", "--compare-dynamics", "--out", dir.to_str().unwrap()]);
    assert!(o.status.success(), "{}", stderr(&o));
    let out = String::from_utf8_lossy(&o.stdout);
    assert!(out.contains("the routes part"), "{out}");
    for f in [
        "paper/route.csv",
        "rigid-body/route.csv",
        "comparison.json",
        "compare-plan.svg",
    ] {
        assert!(dir.join(f).exists(), "{f}");
    }
    let c: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("comparison.json")).unwrap())
            .unwrap();
    assert_eq!(c["paper"]["dynamics"], "paper");
    assert_eq!(c["rigid_body"]["dynamics"], "rigid-body");
    assert!(c["parting"]["parted_at_s"].as_f64().unwrap() > 0.0);
    // The two flags exclude each other.
    let both = run(&["run", "--compare-dynamics", "--dynamics", "paper"]);
    assert_eq!(both.status.code(), Some(2));
}

#[test]
fn a_kicked_scene_ends_stopped_with_its_last_row_at_rest() {
    let dir = temp_dir("kicked");
    let scene = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/kicked.toml");
    let o = run(&[
        "run",
        "--scene",
        scene.to_str().unwrap(),
        "--no-plots",
        "--out",
        dir.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let out = String::from_utf8_lossy(&o.stdout);
    assert!(out.contains("stopped at t = "), "{out}");
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("summary.json")).unwrap()).unwrap();
    assert_eq!(summary["termination"]["reason"], "stopped");
    assert!(summary["energy"]["kinetic_initial_j"].as_f64().unwrap() > 4e5);
    assert_eq!(summary["energy"]["kinetic_j"].as_f64().unwrap(), 0.0);
    let csv = std::fs::read_to_string(dir.join("route.csv")).unwrap();
    let last: Vec<&str> = csv.lines().last().unwrap().split(',').collect();
    // vx_m_s, vz_m_s, omega_deg_s are columns 10–12 (after the body's).
    assert_eq!(&last[9..12], &["0", "0", "0"], "{last:?}");
}

#[test]
fn small_angle_geometry_with_the_default_rigid_body_is_refused_and_runs_with_the_papers_dynamics() {
    // The combination cost about a thousand tracker steps an increment; `scene
    // --check` and `run` refuse it naming the key and the remedy, `--dynamics paper` runs it.
    let dir = temp_dir("small-angle");
    std::fs::create_dir_all(&dir).unwrap();
    let scene = dir.join("sa.toml");
    let text = slideroute::Scene::DEFAULT_TOML.replace(
        "mode = \"exact\"       # or \"small-angle\"",
        "mode = \"small-angle\" # or \"exact\"",
    );
    assert!(text.contains("mode = \"small-angle\""));
    std::fs::write(&scene, text).unwrap();
    let s = scene.to_str().unwrap();
    for args in [
        vec!["scene", "--check", s],
        vec![
            "run",
            "--quiet",
            "--no-plots",
            "--scene",
            s,
            "--out",
            dir.join("o").to_str().unwrap(),
        ],
    ] {
        assert_bad_input(&run(&args), &["solver.mode", "exact", "--dynamics paper"]);
    }
    let o = run(&[
        "run",
        "--quiet",
        "--no-plots",
        "--dynamics",
        "paper",
        "--scene",
        s,
        "--out",
        dir.join("p").to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn roots_at_the_rest_pose_select_the_flat_frame() {
    // `roots` at X = Z = θ = 0 answered "no pose selected".
    let o = run(&["roots", "--x", "0", "--z", "0", "--theta-deg", "0"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let out = String::from_utf8_lossy(&o.stdout);
    assert!(
        out.contains("selected: α = 0.000000°, β = 0.000000°"),
        "{out}"
    );
}

#[test]
fn a_closed_pipe_on_stdout_ends_quietly() {
    // Like `slideroute roots … --json | head -0`, whoever reads standard
    // output has gone before it is written. It used to panic ("failed printing to stdout", exit
    // 101); now it ends quietly, as other Unix tools do.
    let dir = temp_dir("closed-pipe");
    let closed_out = dir.join("out");
    for args in [
        vec![
            "roots",
            "--x",
            "1",
            "--z",
            "0",
            "--theta-deg",
            "0",
            "--json",
        ],
        vec!["scene", "--print-default"],
        // The commands of many routes print their tables at the end (`probabilistic` panicked).
        vec![
            "probabilistic",
            "--samples",
            "8",
            "--dist",
            "friction.mu_k=normal:0.4:0.04",
            "--no-plots",
            "--no-3d",
            "--out",
            closed_out.to_str().unwrap(),
        ],
        vec![
            "sweep",
            "--vary",
            "friction.mu_k=0.3:0.4:2",
            "--no-plots",
            "--no-3d",
            "--out",
            closed_out.to_str().unwrap(),
        ],
        vec![
            "check",
            "--no-plots",
            "--no-3d",
            "--out",
            closed_out.to_str().unwrap(),
        ],
    ] {
        let (reader, writer) = std::io::pipe().unwrap();
        drop(reader);
        let o = Command::new(env!("CARGO_BIN_EXE_slideroute"))
            .args(&args)
            .stdout(writer)
            .output()
            .unwrap();
        assert_eq!(o.status.code(), Some(0), "{args:?}: {}", stderr(&o));
        assert!(stderr(&o).is_empty(), "{args:?}: {}", stderr(&o));
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_full_disk_is_a_one_line_failure_with_exit_code_1() {
    // Standard output on a full device (/dev/full) and an output folder that
    // cannot be made are failures, not bad input: one line, exit 1.
    let full = std::fs::File::options()
        .write(true)
        .open("/dev/full")
        .unwrap();
    let o = Command::new(env!("CARGO_BIN_EXE_slideroute"))
        .args(["scene", "--print-default"])
        .stdout(full)
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    let err = stderr(&o);
    assert_eq!(err.lines().count(), 1, "{err}");
    assert!(
        err.contains("standard output") && !err.contains("panicked"),
        "{err}"
    );
    let o = run(&["run", "--quiet", "--out", "/dev/full/out"]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    assert!(stderr(&o).contains("/dev/full/out"), "{}", stderr(&o));
    // Bad input stays exit 2.
    assert_bad_input(
        &run(&["run", "--scene", "/nonexistent.toml"]),
        &["/nonexistent.toml"],
    );
}

#[test]
fn sweep_keys_are_given_once_whole_number_keys_take_whole_numbers_and_stop_is_hit_exactly() {
    let dir = temp_dir("sweep-keys");
    let d = dir.to_str().unwrap();
    assert_bad_input(
        &run(&[
            "sweep",
            "--quiet",
            "--out",
            d,
            "--vary",
            "friction.mu_k=0.3:0.5:2",
            "--vary",
            "friction.mu_k=0.4:0.6:2",
        ]),
        &["friction.mu_k", "twice"],
    );
    std::fs::create_dir_all(&dir).unwrap();
    let scene = dir.join("stride.toml");
    std::fs::write(
        &scene,
        slideroute::Scene::DEFAULT_TOML
            .replace("# stride = 1             #", "stride = 1 #")
            .replace("t_end_s = 20.0", "t_end_s = 0.05"),
    )
    .unwrap();
    let s = scene.to_str().unwrap();
    assert_bad_input(
        &run(&[
            "sweep",
            "--quiet",
            "--scene",
            s,
            "--out",
            d,
            "--vary",
            "solver.stride=1:10:3",
        ]),
        &["solver.stride", "whole numbers", "5.5"],
    );
    let csv = sweep_csv(&dir, &["--scene", s, "--vary", "solver.stride=1:10:4"]);
    let strides: Vec<&str> = csv
        .lines()
        .skip(1)
        .map(|l| l.split(',').next().unwrap())
        .collect();
    assert_eq!(strides, ["1", "4", "7", "10"]);
    assert!(
        csv.lines().skip(1).all(|l| !l.contains("invalid scene")),
        "{csv}"
    );
    // STOP itself, not 0.1 + 0.6 with its rounding (0.7000000000000001).
    let csv = sweep_csv(&dir, &["--scene", s, "--vary", "friction.mu_k=0.1:0.7:7"]);
    assert_eq!(
        csv.lines().last().unwrap().split(',').next().unwrap(),
        "0.7"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn sweep_dynamics_flag_runs_every_combination_with_that_dynamics() {
    // `sweep --dynamics paper` on the default (rigid-body) scene.
    let dir = temp_dir("sweep-dynamics");
    let csv = sweep_csv(
        &dir,
        &["--dynamics", "paper", "--vary", "friction.mu_k=0.4:0.4:1"],
    );
    let row = csv.lines().nth(1).unwrap();
    // The paper's dynamics end on the default scene: its frictional system at 2.024 s.
    assert!(
        row.contains("the paper's frictional system has no solution"),
        "{row}"
    );
    assert!(row.contains(",2.024,"), "{row}");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn inputs_that_are_not_regular_files_or_too_large_are_refused() {
    // `scene --check /dev/zero` grew to 3.3 GB, `roots --grid /dev/zero`
    // aborted on an 8 GB allocation, a FIFO with no writer blocked for ever.
    assert_bad_input(
        &run(&["scene", "--check", "/dev/zero"]),
        &["/dev/zero", "regular file"],
    );
    assert_bad_input(
        &run(&["roots", "--grid", "/dev/zero", "--out", "/dev/null"]),
        &["/dev/zero", "regular file"],
    );
    let dir = temp_dir("inputs");
    std::fs::create_dir_all(&dir).unwrap();
    let fifo = dir.join("fifo");
    let made = Command::new("mkfifo")
        .arg(&fifo)
        .status()
        .map(|s| s.success());
    if made.unwrap_or(false) {
        assert_bad_input(
            &run(&["scene", "--check", fifo.to_str().unwrap()]),
            &["fifo", "regular file"],
        );
    }
    let big = dir.join("big.toml");
    std::fs::write(&big, " ".repeat(2 << 20)).unwrap();
    assert_bad_input(
        &run(&["run", "--scene", big.to_str().unwrap()]),
        &["big.toml", "bytes"],
    );
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_second_run_into_a_folder_in_use_is_refused() {
    // Two runs into one --out spliced their route.csv files. A run holds the operating
    // system's lock on its folder's lock file (here held by this test's own process).
    let dir = temp_dir("locked");
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join(".slideroute.lock"), std::process::id().to_string()).unwrap();
    let held = std::fs::OpenOptions::new()
        .read(true)
        .write(true)
        .open(dir.join(".slideroute.lock"))
        .unwrap();
    held.lock().unwrap();
    let o = run(&["run", "--quiet", "--out", dir.to_str().unwrap()]);
    assert!(
        stderr(&o).contains(&format!("(process {})", std::process::id())),
        "{}",
        stderr(&o)
    );
    drop(held);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("another slideroute run"),
        "{}",
        stderr(&o)
    );
    assert!(!dir.join("route.csv").exists());
    // A lock file left by a process that is gone (nothing holds its lock) is taken over.
    std::fs::write(dir.join(".slideroute.lock"), "4294967295").unwrap();
    let o = run(&[
        "run",
        "--quiet",
        "--no-plots",
        "--out",
        dir.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(!dir.join(".slideroute.lock").exists());
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_run_replaces_every_output_of_an_earlier_run_and_nothing_else() {
    // `--no-plots` or `--compare-dynamics` into a used folder left another
    // run's pictures beside the new route.
    let dir = temp_dir("replace");
    let d = dir.to_str().unwrap();
    assert!(run(&["run", "--quiet", "--out", d]).status.success());
    std::fs::write(dir.join("notes.txt"), "mine").unwrap();
    assert!(
        run(&[
            "run",
            "--quiet",
            "--compare-dynamics",
            "--no-plots",
            "--out",
            d
        ])
        .status
        .success()
    );
    let mut names: Vec<String> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| !n.starts_with('.'))
        .collect();
    names.sort();
    assert_eq!(
        names,
        [
            "compare.html",
            "comparison.json",
            "notes.txt",
            "paper",
            "rigid-body"
        ]
    );
    assert!(
        run(&["run", "--quiet", "--no-plots", "--out", d])
            .status
            .success()
    );
    let mut names: Vec<String> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| !n.starts_with('.'))
        .collect();
    names.sort();
    assert_eq!(
        names,
        [
            "notes.txt",
            "route.csv",
            "route.glb",
            "route.html",
            "summary.json"
        ]
    );
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn summary_json_is_a_manifest_of_what_produced_the_folder() {
    // The version, the command line, the scene as used (defaults filled in)
    // and the files written with their sizes.
    let dir = temp_dir("manifest");
    let d = dir.to_str().unwrap();
    assert!(
        run(&["run", "--quiet", "--dynamics", "paper", "--out", d])
            .status
            .success()
    );
    let v: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("summary.json")).unwrap()).unwrap();
    let m = &v["manifest"];
    assert_eq!(m["slideroute_version"], env!("CARGO_PKG_VERSION"));
    let cmd: Vec<&str> = m["command_line"]
        .as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_str().unwrap())
        .collect();
    assert_eq!(
        &cmd[1..],
        ["run", "--quiet", "--dynamics", "paper", "--out", d]
    );
    assert_eq!(m["scene"]["solver"]["dynamics"], "paper");
    assert_eq!(m["scene"]["solver"]["integrator"], "paper");
    assert_eq!(m["scene"]["foundation"]["xi_deg"], 20.0);
    assert_eq!(m["scene"]["block"]["inertia_x_kg_m2"], 5.5e6);
    let files = m["files"].as_array().unwrap();
    assert_eq!(
        files.len(),
        7,
        "route.csv, route.html, route.glb and four pictures: {files:?}"
    );
    for f in files {
        let name = f["name"].as_str().unwrap();
        let size = std::fs::metadata(dir.join(name)).unwrap().len();
        assert_eq!(f["bytes"].as_u64(), Some(size), "{name}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn an_interrupted_run_stops_at_the_next_increment_and_writes_what_it_computed() {
    // Ctrl-C (here SIGINT by `kill`) while a long route runs.
    let dir = temp_dir("interrupt");
    let scene = long_scene(&dir);
    let out = dir.join("out");
    let child = Command::new(env!("CARGO_BIN_EXE_slideroute"))
        .args(["run", "--quiet", "--scene", scene.to_str().unwrap()])
        .arg("--out")
        .arg(&out)
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    std::thread::sleep(std::time::Duration::from_millis(500));
    let killed = Command::new("kill")
        .args(["-INT", &child.id().to_string()])
        .status()
        .unwrap();
    assert!(killed.success());
    let o = child.wait_with_output().unwrap();
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    assert!(stderr(&o).contains("interrupted"), "{}", stderr(&o));
    let v: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    assert_eq!(v["termination"]["reason"], "interrupted");
    let t = v["termination"]["t_s"].as_f64().unwrap();
    assert!(t > 0.0 && t < 20.0, "{t}");
    // route.csv is whole: every line has all its fields, and the last row is the last state.
    let csv = std::fs::read_to_string(out.join("route.csv")).unwrap();
    assert!(
        csv.lines().all(|l| l.split(',').count() == 26),
        "a cut line"
    );
    // The time, after the body's number.
    let last: f64 = csv
        .lines()
        .last()
        .unwrap()
        .split(',')
        .nth(1)
        .unwrap()
        .parse()
        .unwrap();
    assert_eq!(last, t);
    assert!(!out.join(".slideroute.lock").exists());
    let _ = std::fs::remove_dir_all(&dir);
}

/// Starts `slideroute args…`, sends it SIGINT after `ms` milliseconds, and waits for it.
fn interrupted_after(args: &[&str], ms: u64) -> std::process::Output {
    let child = Command::new(env!("CARGO_BIN_EXE_slideroute"))
        .args(args)
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    std::thread::sleep(std::time::Duration::from_millis(ms));
    let killed = Command::new("kill")
        .args(["-INT", &child.id().to_string()])
        .status()
        .unwrap();
    assert!(killed.success());
    child.wait_with_output().unwrap()
}

/// A scene whose route takes seconds (rows every 2 µs, a slow slide; at 10 µs, with the rows
/// of a step that holds a sticking contact interpolated, `check` ran its case in 0.7 s and the
/// interrupt after 0.4 s came while it wrote).
fn long_scene(dir: &std::path::Path) -> std::path::PathBuf {
    std::fs::create_dir_all(dir).unwrap();
    let scene = dir.join("long.toml");
    std::fs::write(
        &scene,
        slideroute::Scene::DEFAULT_TOML
            .replace("dt_s = 1.0e-3", "dt_s = 2.0e-6")
            .replace("eccentricity_m = 1.0 ", "eccentricity_m = 0.0 ")
            .replace("hydraulic_force_n = 8.0e6", "hydraulic_force_n = 7.0e6"),
    )
    .unwrap();
    scene
}

#[test]
fn an_interrupted_sweep_writes_a_row_for_every_combination() {
    // Routes under way stop at their next increment, those not started are rows "not run
    // (interrupted)"; the files are whole, the lock gone.
    let dir = temp_dir("interrupt-sweep");
    let scene = long_scene(&dir);
    let out = dir.join("out");
    let o = interrupted_after(
        &[
            "sweep",
            "--quiet",
            "--scene",
            scene.to_str().unwrap(),
            "--vary",
            "friction.mu_k=0.2:0.3:400",
            "--out",
            out.to_str().unwrap(),
        ],
        500,
    );
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    assert!(stderr(&o).contains("interrupted"), "{}", stderr(&o));
    let mut csv = csv::Reader::from_path(out.join("sweep.csv")).unwrap();
    let column = csv.headers().unwrap().iter().position(|h| h == "reason");
    let column = column.expect("a reason column");
    let reasons: Vec<String> = csv
        .records()
        .map(|r| r.unwrap()[column].to_string())
        .collect();
    // Four hundred routes of some 20 ms each on two cores: some done, those under way
    // interrupted, the rest not run.
    assert_eq!(reasons.len(), 400, "a row for every combination");
    assert!(
        reasons.iter().any(|r| r == "not run (interrupted)"),
        "{reasons:?}"
    );
    let ended: Vec<&String> = reasons
        .iter()
        .filter(|r| *r != "not run (interrupted)")
        .collect();
    assert!(
        ended
            .iter()
            .all(|r| *r == "interrupted" || *r == "stopped" || r.starts_with("contact")),
        "{ended:?}"
    );
    assert!(out.join("sweep.svg").exists());
    assert!(!out.join(".slideroute.lock").exists());
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn an_interrupted_comparison_writes_both_routes_as_far_as_they_went() {
    let dir = temp_dir("interrupt-compare");
    let scene = long_scene(&dir);
    let out = dir.join("out");
    let o = interrupted_after(
        &[
            "run",
            "--compare-dynamics",
            "--quiet",
            "--scene",
            scene.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
        ],
        500,
    );
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    assert!(stderr(&o).contains("interrupted"), "{}", stderr(&o));
    let v: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("comparison.json")).unwrap())
            .unwrap();
    assert_eq!(v["rigid_body"]["termination"]["reason"], "interrupted");
    for sub in ["paper", "rigid-body"] {
        let csv = std::fs::read_to_string(out.join(sub).join("route.csv")).unwrap();
        assert!(
            csv.lines().all(|l| l.split(',').count() == 26),
            "{sub}: a cut line"
        );
    }
    assert!(!out.join(".slideroute.lock").exists());
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn an_interrupted_report_writes_nothing_and_says_so() {
    // A work–precision report half measured would mislead: it is not written.
    let dir = temp_dir("interrupt-report");
    let out = dir.join("out");
    let o = interrupted_after(
        &[
            "report",
            "--quick",
            "--quiet",
            "--out",
            out.to_str().unwrap(),
        ],
        300,
    );
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    assert!(stderr(&o).contains("interrupted"), "{}", stderr(&o));
    assert!(!out.join("work-precision.csv").exists());
    assert!(!out.join("work-precision.md").exists());
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn an_interrupted_check_stops_and_writes_nothing() {
    // `check` ran its cases to the end through the first Ctrl-C (and a second left no message).
    let dir = temp_dir("interrupt-check");
    let scene = long_scene(&dir);
    let out = dir.join("out");
    let o = interrupted_after(
        &[
            "check",
            "--scene",
            scene.to_str().unwrap(),
            "--no-plots",
            "--no-3d",
            "--quiet",
            "--out",
            out.to_str().unwrap(),
        ],
        400,
    );
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    let e = stderr(&o);
    assert!(
        e.contains("interrupted: the check stopped after 0 of 1 cases"),
        "{e}"
    );
    assert_eq!(e.lines().count(), 1, "{e}");
    for name in ["check.csv", "check.json", "report.html", ".slideroute.lock"] {
        assert!(!out.join(name).exists(), "{name}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn pictures_stay_small_whatever_the_routes_length() {
    // A 4.4e6-increment route drew a 207 MB reactions.svg. Here 202 400
    // increments (the paper's dynamics at dt = 10 µs): every picture under 2 MB.
    let dir = temp_dir("big-pictures");
    std::fs::create_dir_all(&dir).unwrap();
    let scene = dir.join("fine.toml");
    std::fs::write(
        &scene,
        slideroute::Scene::DEFAULT_TOML.replace("dt_s = 1.0e-3", "dt_s = 1.0e-5"),
    )
    .unwrap();
    let out = dir.join("out");
    let o = run(&[
        "run",
        "--quiet",
        "--dynamics",
        "paper",
        "--scene",
        scene.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let rows = std::fs::read_to_string(out.join("route.csv"))
        .unwrap()
        .lines()
        .count();
    assert!(rows > 200_000, "{rows}");
    for name in ["plan.svg", "profile.svg", "angles.svg", "reactions.svg"] {
        let size = std::fs::metadata(out.join(name)).unwrap().len();
        assert!(size < 2 << 20, "{name}: {size} bytes");
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn sweeps_vary_words_and_lists() {
    // `--vary solver.dynamics=paper,rigid-body`, `solver.mode=…`, number
    // lists; a wrong word is bad input (it made every row "invalid scene" with exit 0).
    let dir = temp_dir("sweep-words");
    let d = dir.to_str().unwrap();
    let csv = sweep_csv(
        &dir,
        &[
            "--vary",
            "solver.dynamics=paper,rigid-body",
            "--vary",
            "friction.mu_k=0.3,0.4",
        ],
    );
    let lines: Vec<&str> = csv.lines().collect();
    assert_eq!(lines.len(), 5, "{csv}");
    assert!(
        lines[1].starts_with("paper,0.3,the paper's frictional system"),
        "{csv}"
    );
    assert!(
        lines[4].starts_with("rigid-body,0.4,contact 0 reached an inclined plane"),
        "{csv}"
    );
    assert_bad_input(
        &run(&[
            "sweep",
            "--quiet",
            "--out",
            d,
            "--vary",
            "solver.dynamics=paper,rigid",
        ]),
        &["solver.dynamics", "not one of paper, rigid-body"],
    );
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_change_of_dynamics_that_changes_the_integrator_says_so() {
    // `with_dynamics` brings the model's own integrator; the command line says so.
    let dir = temp_dir("dynamics-note");
    let o = run(&[
        "run",
        "--quiet",
        "--dynamics",
        "paper",
        "--out",
        dir.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("--dynamics paper integrates with \"paper\""),
        "{}",
        stderr(&o)
    );
    // The default scene names no integrator: the one replaced is its dynamics' default, not
    // the scene's (as the note said before).
    assert!(
        stderr(&o).contains("not the rigid-body dynamics' default \"rk4\""),
        "{}",
        stderr(&o)
    );
    // The same dynamics as the scene's changes nothing and says nothing.
    let o = run(&[
        "run",
        "--quiet",
        "--dynamics",
        "rigid-body",
        "--out",
        dir.to_str().unwrap(),
    ]);
    assert!(o.status.success() && o.stderr.is_empty(), "{}", stderr(&o));
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn general_scenes_run_from_the_command_line_and_coeffs_says_why_it_cannot() {
    // A foundation of faces and a triangulated surface run like any scene; `coeffs`, which
    // prints the paper's own coefficients, says in one line that they need the paper's site.
    let root = env!("CARGO_MANIFEST_DIR");
    for (scene, end) in [
        // On its base (the default on faces and surfaces) the block slides on where its
        // three-point frame ended.
        ("scenes/paper-like-faces.toml", "t reached t_end"),
        ("scenes/valley.toml", "of the base went over no ground"),
    ] {
        let path = format!("{root}/{scene}");
        let out = std::env::temp_dir().join(format!(
            "slideroute-cli-general-{}-{}",
            std::process::id(),
            scene.len()
        ));
        let o = run(&[
            "run",
            "--scene",
            &path,
            "--no-plots",
            "--out",
            out.to_str().unwrap(),
        ]);
        assert!(o.status.success(), "{scene}: {}", stderr(&o));
        let text = String::from_utf8_lossy(&o.stdout);
        assert!(text.contains(end), "{scene}: {text}");
        let o = run(&["scene", "--check", &path]);
        assert!(o.status.success(), "{}", stderr(&o));
        let _ = std::fs::remove_dir_all(out);
    }
    let o = run(&[
        "coeffs",
        "--scene",
        &format!("{root}/scenes/valley.toml"),
        "--x",
        "0.5",
        "--z",
        "0",
        "--theta-deg",
        "0",
    ]);
    assert_bad_input(&o, &["valley.toml", "paper's frame", "general system"]);
}

#[test]
fn a_surface_that_is_not_obj_is_bad_input_naming_the_file() {
    let obj = temp_file("junk.obj", "v 0 0 0\nf 1 2 3 4 5\nthis is not obj\n");
    let text = slideroute::Scene::DEFAULT_TOML;
    let start = text.find("[foundation]").unwrap();
    let end = text.find("[block]").unwrap();
    let scene = format!(
        "{}[foundation]\nsurface = \"{}\"\n\n{}",
        &text[..start],
        obj.file_name().unwrap().to_str().unwrap(),
        &text[end..]
    );
    let path = temp_file("junk-surface.toml", &scene);
    let o = run(&["scene", "--check", path.to_str().unwrap()]);
    assert_bad_input(&o, &["junk-surface.toml", "foundation.surface", "junk.obj"]);
}

#[test]
fn check_prints_the_load_case_table_and_routes_the_case_that_fails() {
    // scenes/monolith.toml: three load cases under EM 1110-2-2100's normal structure, ordinary
    // site information (usual 1.5, unusual 1.3, extreme 1.1); the earthquake case fails and
    // slides, and its route is written beside the table.
    let root = env!("CARGO_MANIFEST_DIR");
    let out = std::env::temp_dir().join(format!("slideroute-cli-check-{}", std::process::id()));
    let o = run(&[
        "check",
        "--scene",
        &format!("{root}/scenes/monolith.toml"),
        "--no-plots",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let text = String::from_utf8_lossy(&o.stdout);
    for needle in [
        "EM 1110-2-2100, normal structure, ordinary site information",
        "normal pool",
        "1.622      1.50   1.582 slides    pass",
        "1.30   1.349 slides    pass",
        "1.10   0.776 slides    FAIL",
        "earthquake at normal pool fails: sliding",
        "earthquake at normal pool slides",
        "resultant from heel m",
    ] {
        assert!(text.contains(needle), "{needle:?} in {text}");
    }
    let csv = std::fs::read_to_string(out.join("check.csv")).unwrap();
    assert_eq!(csv.lines().count(), 4, "{csv}");
    assert!(out.join("case-2/route.csv").exists());
    assert!(!out.join("case-0").exists());
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("check.json")).unwrap()).unwrap();
    assert_eq!(json["cases"][2]["passes"], false);
    assert_eq!(json["cases"][2]["required_fs"], 1.1);
    assert_eq!(json["cases"][0]["load_multiple_limit"], "slides");
    assert_eq!(json["cases"][0]["faces"][0]["face"], 0);
    for key in [
        "sliding_fs",
        "resultant_from_heel_m",
        "base_in_compression_pct",
        "heel_pressure_pa",
        "toe_pressure_pa",
        "crack_length_m",
        "uplift_n",
        "required_fs",
        "anchor_force_n",
    ] {
        assert!(
            json["cases"][0][key].is_number(),
            "{key} in {}",
            json["cases"][0]
        );
    }
    // The page to hand in: the section drawn per case, each case's verdicts as check.json has
    // them, the scene and the manifest.
    let page = std::fs::read_to_string(out.join("report.html")).unwrap();
    assert_eq!(page.matches("<svg").count(), 3, "one drawing a case");
    assert_eq!(page.matches("<svg").count(), page.matches("</svg>").count());
    for (k, case) in json["cases"].as_array().unwrap().iter().enumerate() {
        let name = case["case"]["name"].as_str().unwrap();
        assert!(page.contains(&format!("Case {k}: {name}")), "{name}");
        let fs = format!("{:.3}", case["sliding_fs"].as_f64().unwrap());
        assert!(page.contains(&fs), "{name}'s sliding FS {fs}");
        let at = format!(
            "{:.2} m from the heel",
            case["resultant_from_heel_m"].as_f64().unwrap()
        );
        assert!(page.contains(&at), "{name}'s resultant {at}");
    }
    for needle in [
        "EM 1110-2-2100",
        "The scene as used",
        "slideroute_version",
        "FAILS",
    ] {
        assert!(page.contains(needle), "{needle}");
    }
    assert!(
        !page.contains("NaN") && !page.contains("inf<") && !page.contains("inf "),
        "no number is not one"
    );
    assert_eq!(json["guideline"]["structure"], "normal");
    assert!(json["manifest"]["loads"]["uplift_n"].as_f64().unwrap() > 0.0);
    let _ = std::fs::remove_dir_all(out);
    // A case the guideline has no category for is refused, naming it.
    let bad = std::fs::read_to_string(format!("{root}/scenes/monolith.toml"))
        .unwrap()
        .replace("category = \"unusual\"", "category = \"rare\"");
    let p = temp_file("bad-case.toml", &bad);
    let o = run(&["check", "--scene", p.to_str().unwrap()]);
    assert_bad_input(&o, &["case[1].category", "unknown category \"rare\""]);
}

#[test]
fn a_shaken_scene_reports_newmarks_permanent_displacement_and_rotation() {
    let dir = temp_dir("shaken");
    let scene = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/shaken.toml");
    let o = run_scene(&scene, &dir);
    assert!(o.status.success(), "{}", stderr(&o));
    let out = String::from_utf8_lossy(&o.stdout);
    // 0.80544 m (0.80544 at dt 0.25 ms; before a slow block's directions were settled together,
    // 0.80560, and 0.80550 at 0.25 ms).
    assert!(out.contains("permanent displacement 0.805 m"), "{out}");
    let v: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("summary.json")).unwrap()).unwrap();
    let d = v["permanent_displacement_m"].as_f64().unwrap();
    let rot = v["permanent_rotation_deg"].as_f64().unwrap();
    // The last row's CM offset and yaw, relative to the foundation.
    let csv = std::fs::read_to_string(dir.join("route.csv")).unwrap();
    let last: Vec<f64> = csv
        .lines()
        .last()
        .unwrap()
        .split(',')
        .take(6)
        .map(|x| x.parse().unwrap())
        .collect();
    // body, t_s, x_m, y_m, z_m, theta_deg.
    assert!((d - last[2].hypot(last[4])).abs() < 1e-9, "{d} {last:?}");
    assert!((rot - last[5]).abs() < 1e-9, "{rot} {last:?}");
    // The record is echoed with the scene.
    assert_eq!(
        v["manifest"]["scene"]["seismic"]["record"],
        "shaken-motion.csv"
    );
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn probabilistic_samples_are_the_same_for_a_seed_whatever_the_threads() {
    let scene = temp_file(
        "prob.toml",
        &std::fs::read_to_string(
            std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/paper-like.toml"),
        )
        .unwrap()
        .replace("t_end_s = 20.0", "t_end_s = 0.5"),
    );
    let go = |dir: &std::path::Path, threads: &str, seed: &str| {
        let o = Command::new(env!("CARGO_BIN_EXE_slideroute"))
            .env("RAYON_NUM_THREADS", threads)
            .args([
                "probabilistic",
                "--scene",
                scene.to_str().unwrap(),
                "--samples",
                "24",
                "--seed",
                seed,
                "--dist",
                "friction.mu_k=normal:0.40:0.05",
                "--dist",
                "loads.eccentricity_m=truncnormal:0:0.5:-1:1",
                "--travel-limit-m",
                "0.5",
                "--out",
                dir.to_str().unwrap(),
                "--quiet",
            ])
            .output()
            .unwrap();
        assert!(o.status.success(), "{}", stderr(&o));
        std::fs::read_to_string(dir.join("samples.csv")).unwrap()
    };
    let (a, b, c) = (temp_dir("prob-a"), temp_dir("prob-b"), temp_dir("prob-c"));
    let one = go(&a, "1", "7");
    assert_eq!(one, go(&b, "2", "7"));
    assert_ne!(one, go(&c, "2", "8"));
    assert_eq!(one.lines().count(), 25);
    assert!(one.starts_with("sample,friction.mu_k,loads.eccentricity_m,factor_of_safety,"));
    // The summary: its probability inside its interval, counts that add up, the manifest.
    let v: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(a.join("probabilistic.json")).unwrap())
            .unwrap();
    let p = &v["probability_of_sliding"];
    let (x, lo, hi) = (
        p["value"].as_f64().unwrap(),
        p["ci95"][0].as_f64().unwrap(),
        p["ci95"][1].as_f64().unwrap(),
    );
    assert!(lo <= x && x <= hi, "{p}");
    assert_eq!(v["routes"], 24);
    assert!(v["probability_travel_exceeds_limit"]["value"].is_number());
    assert_eq!(v["sampling"], "lhs");
    assert!(v["manifest"]["scene"].is_object());
    // The fraction of rows below a factor of safety of 1 is the probability.
    let below = one
        .lines()
        .skip(1)
        .filter(|l| l.split(',').nth(3).unwrap().parse::<f64>().unwrap() < 1.0)
        .count();
    assert_eq!(below as f64 / 24.0, x);
}

#[test]
fn probabilistic_inputs_it_cannot_use_are_named() {
    let out = temp_dir("prob-bad");
    let o = out.to_str().unwrap();
    for (args, needles) in [
        (
            vec!["--dist", "friction.mu_k=gauss:0:1"],
            vec!["--dist", "unknown distribution"],
        ),
        (
            vec!["--dist", "friction.mu_q=normal:0.4:0.05"],
            vec!["--dist friction.mu_q", "no key `mu_q`"],
        ),
        (
            vec!["--dist", "friction.mu_k=normal:0.4:0"],
            vec!["sd must be positive"],
        ),
        (
            vec!["--dist", "friction.mu_k=normal:0.4:0.05", "--samples", "0"],
            vec!["--samples 0"],
        ),
        (vec![], vec!["nothing is uncertain", "[uncertain]"]),
        (
            vec![
                "--dist",
                "friction.mu_k=normal:0.4:0.05",
                "--travel-limit-m",
                "-1",
            ],
            vec!["--travel-limit-m"],
        ),
        (
            vec![
                "--dist",
                "friction.mu_k=normal:0.4:0.05",
                "--displacement-limit-m",
                "0.1",
            ],
            vec!["--displacement-limit-m", "no ground-motion record"],
        ),
    ] {
        let mut all = vec!["probabilistic", "--out", o, "--quiet"];
        all.extend(args);
        assert_bad_input(&run(&all), &needles);
    }
    // A sample whose values make no valid scene is a row that says why, not an abort.
    let o = run(&[
        "probabilistic",
        "--out",
        out.to_str().unwrap(),
        "--samples",
        "8",
        "--dist",
        "friction.mu_k=uniform:-0.2:0.1",
        "--quiet",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let csv = std::fs::read_to_string(out.join("samples.csv")).unwrap();
    assert!(csv.contains("invalid scene"), "{csv}");
    assert!(csv.contains("friction.mu_k"), "{csv}");
}

#[test]
fn a_sweep_under_a_record_tables_each_combinations_permanent_displacement() {
    let scene = concat!(env!("CARGO_MANIFEST_DIR"), "/scenes/shaken.toml");
    let csv = sweep_csv(
        &temp_dir("sweep-shaken"),
        &["--scene", scene, "--vary", "friction.mu_k=0.4,0.42"],
    );
    let mut lines = csv.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let col = |name: &str| header.iter().position(|h| *h == name).unwrap();
    let (px, pz) = (col("permanent_x_m"), col("permanent_z_m"));
    for (line, mu) in lines.zip(["0.4", "0.42"]) {
        let cells: Vec<&str> = line.split(',').collect();
        let out = temp_dir(&format!("sweep-shaken-{mu}"));
        let doc = std::fs::read_to_string(scene)
            .unwrap()
            .replace(
                "record = \"shaken-motion.csv\"",
                &format!(
                    "record = \"{}/scenes/shaken-motion.csv\"",
                    env!("CARGO_MANIFEST_DIR")
                ),
            )
            .replace("mu_k = 0.40", &format!("mu_k = {mu}"));
        let file = temp_file(&format!("shaken-{mu}.toml"), &doc);
        let o = run(&[
            "run",
            "--scene",
            file.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
        ]);
        assert!(o.status.success(), "{}", stderr(&o));
        let summary: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap())
                .unwrap();
        let want = &summary["permanent_displacement_xz_m"];
        assert_eq!(cells[px].parse::<f64>().unwrap(), want[0].as_f64().unwrap());
        assert_eq!(cells[pz].parse::<f64>().unwrap(), want[1].as_f64().unwrap());
    }
}

#[test]
fn probabilistic_under_a_record_reports_the_chance_of_a_permanent_displacement_over_a_limit() {
    let out = temp_dir("prob-shaken");
    let scene = concat!(env!("CARGO_MANIFEST_DIR"), "/scenes/shaken.toml");
    let o = run(&[
        "probabilistic",
        "--scene",
        scene,
        "--out",
        out.to_str().unwrap(),
        "--samples",
        "6",
        "--dist",
        "friction.mu_k=uniform:0.38:0.42",
        "--displacement-limit-m",
        "0.5",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let text = String::from_utf8_lossy(&o.stdout);
    assert!(
        text.contains("probability the record displaces the block 1.0000")
            && text.contains("probability the permanent displacement exceeds 0.5 m"),
        "{text}"
    );
    assert!(!text.contains("factor of safety below 1"), "{text}");
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("probabilistic.json")).unwrap())
            .unwrap();
    assert_eq!(json["shaken"], true);
    assert_eq!(json["displacement_limit_m"], 0.5);
    // scenes/shaken.toml's block moves 0.80 m: every sample over 0.5 m.
    assert_eq!(json["probability_displacement_exceeds_limit"]["value"], 1.0);
    // Its histogram does not call a static factor of safety over 1 held.
    let svg = std::fs::read_to_string(out.join("factor-of-safety.svg")).unwrap();
    assert!(
        svg.contains("held without the record") && !svg.contains("1 or more: held"),
        "the legend"
    );
}

#[test]
fn probabilistic_takes_the_scenes_uncertain_table_and_the_command_line_replaces_a_key() {
    let scene = temp_file(
        "prob-table.toml",
        &std::fs::read_to_string(
            std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
                .join("scenes/paper-like-uncertain.toml"),
        )
        .unwrap()
        .replace("t_end_s = 20.0", "t_end_s = 0.2"),
    );
    let go = |dir: &std::path::Path, extra: &[&str]| {
        let mut args = vec![
            "probabilistic",
            "--scene",
            scene.to_str().unwrap(),
            "--samples",
            "12",
            "--out",
            dir.to_str().unwrap(),
            "--quiet",
        ];
        args.extend(extra);
        let o = run(&args);
        assert!(o.status.success(), "{}", stderr(&o));
        let v: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(dir.join("probabilistic.json")).unwrap())
                .unwrap();
        (std::fs::read_to_string(dir.join("samples.csv")).unwrap(), v)
    };
    let (a, b) = (temp_dir("prob-table-a"), temp_dir("prob-table-b"));
    let (csv, v) = go(&a, &[]);
    assert!(
        csv.starts_with("sample,foundation.zeta_deg,friction.mu_k,loads.eccentricity_m,"),
        "{csv}"
    );
    assert_eq!(v["distributions"][1]["distribution"], "normal:0.4:0.05");
    // The pictures are written beside the tables.
    for f in ["route-fan.svg", "factor-of-safety.svg", "sensitivity.svg"] {
        let svg = std::fs::read_to_string(a.join(f)).unwrap();
        assert!(svg.starts_with("<svg"), "{f}");
    }
    assert!(
        std::fs::read_to_string(a.join("route-fan.svg"))
            .unwrap()
            .contains("CM paths of the 12 sampled routes")
    );
    assert_eq!(v["rank_correlations"].as_array().unwrap().len(), 3);
    // --dist replaces the table's friction (its column moves to the end).
    let (_, v) = go(
        &b,
        &["--dist", "friction.mu_k=uniform:0.3:0.5", "--no-plots"],
    );
    let given: Vec<(String, String)> = v["distributions"]
        .as_array()
        .unwrap()
        .iter()
        .map(|d| {
            (
                d["key"].as_str().unwrap().to_string(),
                d["distribution"].as_str().unwrap().to_string(),
            )
        })
        .collect();
    assert_eq!(given.len(), 3);
    assert!(given.contains(&("friction.mu_k".into(), "uniform:0.3:0.5".into())));
    assert!(!b.join("route-fan.svg").exists());
    // Again into the first folder without pictures: the earlier run's pictures go.
    go(&a, &["--no-plots"]);
    for f in ["route-fan.svg", "factor-of-safety.svg", "sensitivity.svg"] {
        assert!(!a.join(f).exists(), "{f} left from the earlier run");
    }
    assert!(a.join("samples.csv").exists() && a.join("probabilistic.json").exists());
}

#[test]
fn probabilistic_with_no_valid_sample_says_there_is_no_probability() {
    let out = temp_dir("prob-none");
    let o = run(&[
        "probabilistic",
        "--out",
        out.to_str().unwrap(),
        "--samples",
        "4",
        "--dist",
        "friction.mu_k=uniform:-2:-1",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let said = String::from_utf8_lossy(&o.stdout);
    assert!(said.contains("none (no route ran)"), "{said}");
    let v: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("probabilistic.json")).unwrap())
            .unwrap();
    assert!(v["probability_of_sliding"]["value"].is_null(), "{v}");
    assert_eq!(v["invalid_samples"], 4);
    let fan = std::fs::read_to_string(out.join("route-fan.svg")).unwrap();
    assert!(fan.contains("4 samples made no valid scene"));
    let fs = std::fs::read_to_string(out.join("factor-of-safety.svg")).unwrap();
    assert!(fs.contains("No sample has a finite factor of safety"));
}

#[test]
fn a_record_along_x_alone_prints_its_measures_and_dashes_for_the_components_it_lacks() {
    // The shaken scene's record along X alone, as one column 5 ms apart.
    let motion = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/scenes/shaken-motion.csv"
    ))
    .unwrap();
    let column: String = motion
        .lines()
        .skip(1)
        .map(|l| format!("{}\n", l.split(',').nth(1).unwrap()))
        .collect();
    let dir = temp_dir("record-x-alone");
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("x.txt"), column).unwrap();
    let doc = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/scenes/shaken.toml"))
        .unwrap()
        .replace(
            "record = \"shaken-motion.csv\"",
            "record_x = \"x.txt\"\ndt_s = 0.005",
        );
    let file = dir.join("scene.toml");
    std::fs::write(&file, doc).unwrap();
    let out = dir.join("out");
    let o = run_scene(&file, &out);
    assert!(o.status.success(), "{}", stderr(&o));
    let text = String::from_utf8_lossy(&o.stdout);
    // 0.7 g at its peak (an envelope of 1 from 0.5 s to 2 s over a 1.5 Hz sine).
    assert!(text.contains("PGA 0.700 / — / — g"), "{text}");
    assert!(
        text.contains("D5–95 ") && !text.contains("0.00 s"),
        "{text}"
    );
}

#[test]
fn set_changes_a_scene_key_without_editing_the_file_and_names_what_is_wrong() {
    let root = env!("CARGO_MANIFEST_DIR");
    let monolith = format!("{root}/scenes/monolith.toml");
    let out = std::env::temp_dir().join(format!("slideroute-cli-set-{}", std::process::id()));
    // A word in quotes and a number: the guideline's table and a level.
    let o = run(&[
        "check",
        "--scene",
        &monolith,
        "--set",
        "check.structure=\"critical\"",
        "--set",
        "friction.mu_k=0.5",
        "--no-plots",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("check.json")).unwrap()).unwrap();
    assert_eq!(json["guideline"]["structure"], "critical");
    assert_eq!(json["cases"][0]["case"]["required_fs"], 2.0);
    assert_eq!(json["cases"][0]["tan_phi"], 0.5);
    let _ = std::fs::remove_dir_all(&out);
    for (set, needles) in [
        ("friction.mu_k", vec!["--set friction.mu_k", "KEY=VALUE"]),
        ("friction.mu_k=abc", vec!["friction.mu_k", "expected f64"]),
        ("friction.mu_k=-1", vec!["friction.mu_k"]),
        ("nonsense.key=1", vec!["nonsense", "unknown key"]),
        // Before: `invalid type: string "99999999999999999999", expected i64`.
        (
            "solver.stride=99999999999999999999",
            vec!["past the largest whole number", "9223372036854775807"],
        ),
    ] {
        let o = run(&[
            "run",
            "--set",
            set,
            "--quiet",
            "--no-plots",
            "--out",
            out.to_str().unwrap(),
        ]);
        assert_bad_input(&o, &needles);
    }
    // A bare word is a string.
    let o = run(&[
        "run",
        "--set",
        "solver.t_end_s=0.01",
        "--set",
        "solver.dynamics=paper",
        "--quiet",
        "--no-plots",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let summary = std::fs::read_to_string(out.join("summary.json")).unwrap();
    assert!(summary.contains("\"paper\""), "{summary}");
    let _ = std::fs::remove_dir_all(&out);
}

#[test]
fn check_design_anchors_prints_each_cases_prestress_and_writes_it_into_check_json() {
    let dir = std::env::temp_dir().join(format!("slideroute-design-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let bare = dir.join("bare.toml");
    std::fs::write(&bare, slideroute::Scene::DAM_TOML).unwrap();
    let out = dir.join("out");
    let args = |scene: &std::path::Path| {
        run(&[
            "check",
            "--scene",
            scene.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
            "--no-plots",
            "--design-anchors",
        ])
    };
    // Without an anchor: one line naming the key, exit 2.
    assert_bad_input(
        &args(&bare),
        &["anchor: designing anchors needs at least one"],
    );
    let anchored = dir.join("anchored.toml");
    std::fs::write(
        &anchored,
        format!(
            "{}\n[[anchor]]\nx_m = 2.0\ny_m = 15.0\nprestress_n = 1.0e6\ncapacity_n = 2.0e7\n\
             free_length_m = 30.0\nsteel_area_m2 = 4.0e-3\n",
            slideroute::Scene::DAM_TOML
        ),
    )
    .unwrap();
    let o = args(&anchored);
    assert!(o.status.success(), "{}", stderr(&o));
    let text = String::from_utf8_lossy(&o.stdout);
    assert!(text.contains("for sliding MN"), "{text}");
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("check.json")).unwrap()).unwrap();
    let design = json["anchor_design"].as_array().unwrap();
    assert_eq!(design.len(), json["cases"].as_array().unwrap().len());
    // The earthquake fails without anchors and needs some; the usual case none.
    assert_eq!(design[0]["for_sliding_n"].as_f64(), Some(0.0));
    let quake = design[3]["for_sliding_n"].as_f64().unwrap();
    assert!(quake > 1.0e6, "{quake}");
    assert_eq!(json["cases"][0]["anchor_force_n"].as_f64(), Some(1.0e6));
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_reservoir_above_the_crest_is_refused_naming_the_key_and_the_case() {
    let dir = std::env::temp_dir().join(format!("slideroute-crest-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let scene = dir.join("dam.toml");
    let text = slideroute::Scene::DAM_TOML.replacen("headwater_m = 15.0", "headwater_m = 15.5", 1);
    std::fs::write(&scene, text).unwrap();
    let out = dir.join("out");
    let o = run(&[
        "check",
        "--scene",
        scene.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ]);
    assert_bad_input(
        &o,
        &[
            "water.headwater_m",
            "in case \"flood to the crest\"",
            "at most the crest",
        ],
    );
    let o = run(&[
        "run",
        "--scene",
        scene.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
        "--set",
        "water.headwater_m=15.01",
    ]);
    assert_bad_input(&o, &["water.headwater_m", "at most the crest"]);
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn each_command_writes_its_own_default_folder_and_keeps_the_others_files() {
    // Each command has its own default folder: a sweep must not remove a route's files.
    let dir = temp_dir("defaults");
    std::fs::create_dir_all(&dir).unwrap();
    let at = |args: &[&str]| {
        let o = Command::new(env!("CARGO_BIN_EXE_slideroute"))
            .args(args)
            .current_dir(&dir)
            .output()
            .unwrap();
        assert!(o.status.success(), "{args:?}: {}", stderr(&o));
    };
    let short = ["--quiet", "--no-plots", "--set", "solver.t_end_s=0.05"];
    at(&[&["run"][..], &short].concat());
    at(&[&["run", "--compare-dynamics"][..], &short].concat());
    at(&[
        "sweep",
        "--quiet",
        "--no-plots",
        "--vary",
        "solver.t_end_s=0.02,0.03",
    ]);
    at(&[
        "probabilistic",
        "--quiet",
        "--no-plots",
        "--samples",
        "2",
        "--dist",
        "friction.mu_k=uniform:0.3:0.4",
        "--set",
        "solver.t_end_s=0.02",
    ]);
    for file in [
        "out/run/route.csv",
        "out/run/summary.json",
        "out/compare/comparison.json",
        "out/compare/paper/route.csv",
        "out/sweep/sweep.csv",
        "out/probabilistic/samples.csv",
    ] {
        assert!(dir.join(file).exists(), "{file} is gone");
    }
    // --no-plots: no picture.
    assert!(!dir.join("out/sweep/sweep.svg").exists());
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_command_into_a_folder_removes_only_what_the_same_command_wrote_there() {
    // A sweep into a project folder must not delete the person's own summary.json and
    // plan.svg, nor a run into a folder a sweep wrote delete sweep.csv.
    let dir = temp_dir("own-files");
    std::fs::create_dir_all(&dir).unwrap();
    for (name, text) in [("summary.json", "mine"), ("plan.svg", "mine")] {
        std::fs::write(dir.join(name), text).unwrap();
    }
    let d = dir.to_str().unwrap();
    let ok = |o: Output| assert!(o.status.success(), "{}", stderr(&o));
    ok(run(&[
        "sweep",
        "--quiet",
        "--out",
        d,
        "--vary",
        "solver.t_end_s=0.02",
    ]));
    for name in ["summary.json", "plan.svg"] {
        assert_eq!(std::fs::read_to_string(dir.join(name)).unwrap(), "mine");
    }
    assert!(dir.join("sweep.svg").exists());
    // A run replaces the person's files it writes itself (their names are its outputs) but
    // keeps the sweep's.
    ok(run(&[
        "run",
        "--quiet",
        "--out",
        d,
        "--set",
        "solver.t_end_s=0.02",
    ]));
    assert!(dir.join("sweep.csv").exists() && dir.join("sweep.svg").exists());
    assert!(dir.join("plan.svg").exists());
    // A second sweep without pictures removes the sweep's own earlier picture only.
    ok(run(&[
        "sweep",
        "--quiet",
        "--no-plots",
        "--out",
        d,
        "--vary",
        "solver.t_end_s=0.02",
    ]));
    assert!(!dir.join("sweep.svg").exists());
    for name in ["route.csv", "summary.json", "plan.svg", "sweep.csv"] {
        assert!(dir.join(name).exists(), "{name} is gone");
    }
    // A run with --no-plots removes its own earlier pictures.
    ok(run(&[
        "run",
        "--quiet",
        "--no-plots",
        "--out",
        d,
        "--set",
        "solver.t_end_s=0.02",
    ]));
    assert!(!dir.join("plan.svg").exists());
    assert!(dir.join("sweep.csv").exists());
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn every_command_line_fault_is_one_line_in_the_one_style_naming_the_command_help() {
    // One style of error: not clap's (`error: …`, a usage block) beside `slideroute: …`.
    for (args, needle, help) in [
        (
            &["sweep"][..],
            "--vary <KEY=VALUES>",
            "slideroute sweep --help",
        ),
        (
            &["coeffs", "--x", "1"][..],
            "--z <METRES>",
            "slideroute coeffs --help",
        ),
        (&["run", "--bogus"][..], "--bogus", "slideroute run --help"),
        (&["runn"][..], "'run'", "slideroute --help"),
        (
            &["probabilistic", "--samples", "abc"][..],
            "--samples <N>",
            "slideroute probabilistic --help",
        ),
        (
            &["run", "--dynamics", "foo"][..],
            "paper, rigid-body",
            "slideroute run --help",
        ),
    ] {
        let o = run(args);
        let err = stderr(&o);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {err}");
        assert_eq!(err.lines().count(), 1, "{args:?}: {err}");
        assert!(err.starts_with("slideroute: "), "{err}");
        assert!(!err.contains("error:") && !err.contains("Usage"), "{err}");
        assert!(
            err.contains(needle) && err.trim_end().ends_with(help),
            "{err}"
        );
    }
    // Help is still help, on standard output, exit 0; coeffs names its required flags.
    let o = run(&["coeffs", "--help"]);
    assert!(o.status.success());
    let help = String::from_utf8_lossy(&o.stdout);
    assert!(
        help.contains(
            "Usage: slideroute coeffs [OPTIONS] --x <METRES> --z <METRES> --theta-deg <DEGREES>"
        ),
        "{help}"
    );
}

#[test]
fn the_same_value_has_the_same_metavar_in_every_command_and_no_help_names_the_code() {
    // One name per argument: not `<MODEL>` in one command and `<DYNAMICS>` in another.
    let mut seen: std::collections::BTreeMap<String, String> = Default::default();
    for command in [
        "run",
        "sweep",
        "probabilistic",
        "check",
        "report",
        "coeffs",
        "roots",
    ] {
        let o = run(&[command, "--help"]);
        let help = String::from_utf8_lossy(&o.stdout).into_owned();
        for line in help.lines().map(str::trim).filter(|l| l.starts_with("--")) {
            let mut words = line.split_whitespace();
            let flag = words.next().unwrap().to_string();
            let Some(meta) = words.next().filter(|w| w.starts_with('<')) else {
                continue;
            };
            let kind = if flag.ends_with("-m") || ["--x", "--z"].contains(&flag.as_str()) {
                "a length".to_string()
            } else if command == "roots" && flag == "--out" {
                "a file".to_string() // the grid's rows, not a folder
            } else {
                flag.clone()
            };
            let previous = seen.entry(kind.clone()).or_insert_with(|| meta.to_string());
            assert_eq!(previous, meta, "{command} {flag}: {kind}");
        }
        // No name of the code's own (a module path, an issue number) in what a user reads.
        assert!(
            !help.contains("::") && !help.contains("issue #") && !help.contains(".rs"),
            "{command}: {help}"
        );
        // Every command that draws can be told not to.
        if ["run", "sweep", "probabilistic", "check", "report"].contains(&command) {
            assert!(help.contains("--no-plots"), "{command}");
        }
    }
    assert_eq!(seen["a length"], "<METRES>");
}

#[test]
fn a_scene_with_several_faults_gets_a_line_for_each() {
    let scene = temp_file(
        "several-faults.toml",
        &slideroute::Scene::DEFAULT_TOML
            .replacen("mu_k = 0.40", "mu_k = -0.4", 1)
            .replacen("xi_deg = 20.0", "xi_deg = 95.0", 1),
    );
    let o = run(&["scene", "--check", scene.to_str().unwrap()]);
    let err = stderr(&o);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert_eq!(err.lines().count(), 2, "{err}");
    assert!(err.lines().all(|l| l.starts_with("slideroute: ")), "{err}");
    assert!(
        err.contains("foundation.xi_deg") && err.contains("friction.mu_k"),
        "{err}"
    );
}

/// The files under `dir` that a person sees (no hidden names), relative, sorted.
fn visible_files(dir: &std::path::Path) -> Vec<String> {
    fn walk(root: &std::path::Path, at: &std::path::Path, out: &mut Vec<String>) {
        for e in std::fs::read_dir(at).unwrap() {
            let e = e.unwrap();
            let name = e.file_name().to_string_lossy().into_owned();
            if name.starts_with('.') {
                continue;
            }
            if e.file_type().unwrap().is_dir() {
                walk(root, &e.path(), out);
            } else {
                let rel = e.path().strip_prefix(root).unwrap().to_path_buf();
                out.push(rel.to_string_lossy().into_owned());
            }
        }
    }
    let mut out = Vec::new();
    walk(dir, dir, &mut out);
    out.sort();
    out
}

#[test]
fn a_manifest_is_written_last_and_names_exactly_the_files_beside_it() {
    // summary.json was written before the files it should name, and an earlier run's pictures
    // stayed beside a later run's summary until the very end.
    let dir = temp_dir("manifest-exact");
    let out = dir.join("out");
    let o = out.to_str().unwrap();
    let short = ["--set", "solver.t_end_s=0.3"];
    let cases: [(&[&str], &str); 5] = [
        (&["run", "--quiet", "--out", o], "summary.json"),
        // The same folder again without pictures: the pictures go, and the summary says so.
        (
            &["run", "--quiet", "--no-plots", "--out", o],
            "summary.json",
        ),
        (
            &[
                "run",
                "--quiet",
                "--compare-dynamics",
                "--no-3d",
                "--out",
                o,
            ],
            "comparison.json",
        ),
        (
            &[
                "probabilistic",
                "--quiet",
                "--samples",
                "4",
                "--dist",
                "friction.mu_k=normal:0.4:0.04",
                "--out",
                o,
            ],
            "probabilistic.json",
        ),
        (&["check", "--quiet", "--out", o], "check.json"),
    ];
    for (args, manifest) in cases {
        let _ = std::fs::remove_dir_all(&out);
        // Twice, the second over the first's files.
        for _ in 0..2 {
            let mut all = args.to_vec();
            if args[0] == "run" && !args.contains(&"--compare-dynamics") {
                all.extend(short);
            }
            let r = run(&all);
            assert_eq!(r.status.code(), Some(0), "{args:?}: {}", stderr(&r));
        }
        let json: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(out.join(manifest)).unwrap()).unwrap();
        let mut named: Vec<String> = json["manifest"]["files"]
            .as_array()
            .unwrap()
            .iter()
            .map(|f| f["name"].as_str().unwrap().to_string())
            .collect();
        // A manifest names the files beside it, not itself; a check's failing cases are in
        // folders of their own, with their own summaries.
        named.push(manifest.to_string());
        named.sort();
        let beside: Vec<String> = visible_files(&out)
            .into_iter()
            .filter(|f| !f.starts_with("case-"))
            .collect();
        // The other manifests of a comparison (each route's summary) are named by the last.
        assert_eq!(named, beside, "{args:?}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// Whether `dir` is whole: where it has a summary.json, the files it names are those beside it
/// (hidden ones aside), each of the size it says.
fn folder_is_whole(dir: &std::path::Path) -> Result<(), String> {
    let Ok(text) = std::fs::read_to_string(dir.join("summary.json")) else {
        return Ok(()); // no manifest: recognisably incomplete, which the next run cleans
    };
    let json: serde_json::Value = serde_json::from_str(&text).map_err(|e| e.to_string())?;
    let mut named = vec!["summary.json".to_string()];
    for f in json["manifest"]["files"].as_array().ok_or("no files")? {
        let name = f["name"].as_str().ok_or("no name")?;
        let bytes = std::fs::metadata(dir.join(name)).map_err(|e| format!("{name}: {e}"))?;
        if Some(bytes.len()) != f["bytes"].as_u64() {
            return Err(format!(
                "{name}: {} bytes, the manifest says {}",
                bytes.len(),
                f["bytes"]
            ));
        }
        named.push(name.to_string());
    }
    named.sort();
    let beside = visible_files(dir);
    if named != beside {
        return Err(format!("named {named:?}, beside {beside:?}"));
    }
    Ok(())
}

#[test]
fn a_run_killed_at_any_moment_leaves_a_folder_whose_summary_names_exactly_what_is_there() {
    // SIGKILL after the new route.csv was renamed in but before summary.json left the new
    // route beside the old summary and pictures (10 of 12 trials).
    let dir = temp_dir("killed-runs");
    let out = dir.join("out");
    let o = out.to_str().unwrap();
    // A first, complete run with pictures; then runs without them, killed part way.
    let first = run(&["run", "--quiet", "--set", "solver.t_end_s=1", "--out", o]);
    assert_eq!(first.status.code(), Some(0), "{}", stderr(&first));
    let args = [
        "run",
        "--quiet",
        "--no-3d",
        "--set",
        "solver.dt_s=2e-4",
        "--out",
        o,
    ];
    let started = std::time::Instant::now();
    let whole = run(&args);
    assert_eq!(whole.status.code(), Some(0), "{}", stderr(&whole));
    let takes = started.elapsed();
    folder_is_whole(&out).unwrap();
    for k in 1..=12 {
        // Each killed run's route differs from the last complete one's (its own t_end), so a
        // new route.csv beside an old summary shows in its size.
        let t_end = format!("solver.t_end_s={}", 2.0 + 0.01 * f64::from(k));
        let mut child = Command::new(env!("CARGO_BIN_EXE_slideroute"))
            .args(args)
            .args(["--set", &t_end])
            .stdout(std::process::Stdio::null())
            .stderr(std::process::Stdio::null())
            .spawn()
            .unwrap();
        std::thread::sleep(takes * k / 13);
        let _ = child.kill(); // SIGKILL
        let _ = child.wait();
        folder_is_whole(&out).unwrap_or_else(|e| panic!("killed at {k}/13 of a run: {e}"));
    }
    // The next run, finishing, makes it whole with its summary.
    let last = run(&args);
    assert_eq!(last.status.code(), Some(0), "{}", stderr(&last));
    folder_is_whole(&out).unwrap();
    assert!(out.join("summary.json").exists());
    let _ = std::fs::remove_dir_all(&dir);
}
