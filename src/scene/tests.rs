//! Every bad input gets one error naming the key and the reason; good inputs load.

use super::*;
use crate::model::{DynamicsModel, Friction, Integrator, Mode};

const GOOD: &str = r#"
name = "t"
[frame]
l1x = 6.0
l2x = 4.0
l1z = 5.0
l2z = 5.0
[foundation]
xi_deg = 20.0
zeta_deg = 25.0
kappa_deg = 30.0
[block]
mass_kg = 1.0e6
inertia_kg_m2 = 1.1e7
[loads]
hydraulic_force_n = 8.0e6
eccentricity_m = 1.0
gravity_m_s2 = 9.81
[friction]
model = "coulomb"
mu_k = 0.40
[solver]
mode = "exact"
dt_s = 1.0e-3
t_end_s = 20.0
"#;

/// GOOD with `key = old` replaced by `key = new` (the first occurrence).
fn with(key_line: &str, replacement: &str) -> String {
    assert!(GOOD.contains(key_line), "test bug: {key_line} not in GOOD");
    GOOD.replacen(key_line, replacement, 1)
}

fn err(text: &str) -> SceneError {
    Scene::from_toml(text, "dam.toml").expect_err("should be rejected")
}

/// The error names the file and `key`, and its reason contains `why`; one line.
fn assert_names(text: &str, key: &str, why: &str) {
    let e = err(text);
    let msg = e.to_string();
    assert_eq!(e.key, key, "{msg}");
    assert!(msg.starts_with("dam.toml: "), "{msg}");
    assert!(msg.contains(key), "{msg}");
    assert!(msg.contains(why), "expected {why:?} in {msg:?}");
    assert!(!msg.contains('\n'), "{msg:?}");
}

#[test]
fn good_scene_loads_in_radians() {
    let s = Scene::from_toml(GOOD, "dam.toml").unwrap();
    assert_eq!(s.name, "t");
    assert!((s.site.as_paper().unwrap().foundation.xi - 20f64.to_radians()).abs() < 1e-15);
    assert_eq!(s.l(), 10.0);
    assert!(s.simulation().is_ok());
    assert_eq!(s.settings.unwrap().mode, Mode::Exact);
}

#[test]
fn embedded_and_example_scenes_are_valid() {
    let s = Scene::default_scene();
    assert_eq!(s.name, "paper-like");
    for text in [
        include_str!("../../scenes/paper-like.toml"),
        include_str!("../../scenes/shallow.toml"),
    ] {
        Scene::from_toml(text, "example").unwrap();
    }
}

#[test]
fn integers_are_accepted_for_numbers() {
    let s = Scene::from_toml(&with("l1x = 6.0", "l1x = 6"), "d").unwrap();
    assert_eq!(s.site.as_paper().unwrap().frame.l1x, 6.0);
}

#[test]
fn geometry_only_scene_loads_but_cannot_simulate() {
    let text = GOOD.split("[block]").next().unwrap();
    let s = Scene::from_toml(text, "geo.toml").unwrap();
    let e = s.simulation().unwrap_err();
    assert_eq!(e.key, "block");
    assert!(e.to_string().contains("missing section [block]"));
}

#[test]
fn unknown_key_is_named() {
    assert_names(
        &with("l2z = 5.0", "l2z = 5.0\nl3z = 1.0"),
        "frame.l3z",
        "unknown key",
    );
    assert_names(
        &format!("colour = \"red\"\n{GOOD}"),
        "colour",
        "unknown key",
    );
    assert_names(
        &with("mu_k = 0.40", "mu_k = 0.4\nmu_s = 0.5"),
        "friction.mu_s",
        "unknown",
    );
}

#[test]
fn wrong_type_is_named() {
    assert_names(
        &with("l1x = 6.0", "l1x = \"six\""),
        "frame.l1x",
        "invalid type",
    );
    assert_names(
        &with("dt_s = 1.0e-3", "dt_s = true"),
        "solver.dt_s",
        "invalid type",
    );
}

#[test]
fn missing_section_and_key_are_named() {
    let no_foundation = GOOD.replace("[foundation]", "[nothing]");
    let e = err(&no_foundation);
    // Either the stray section or the missing one is reported, by name.
    assert!(e.key == "nothing" || e.key == "foundation", "{e}");
    let text = GOOD.replace(
        "[foundation]\nxi_deg = 20.0\nzeta_deg = 25.0\nkappa_deg = 30.0\n",
        "",
    );
    assert_names(&text, "foundation", "missing section [foundation]");
    assert_names(&with("l2x = 4.0\n", ""), "frame.l2x", "missing key");
}

#[test]
fn non_positive_lengths_are_named() {
    assert_names(
        &with("l1x = 6.0", "l1x = -6.0"),
        "frame.l1x",
        "must be positive",
    );
    assert_names(
        &with("l2z = 5.0", "l2z = 0.0"),
        "frame.l2z",
        "must be positive",
    );
}

#[test]
fn non_finite_numbers_are_named() {
    assert_names(&with("l1z = 5.0", "l1z = inf"), "frame.l1z", "finite");
    assert_names(
        &with("xi_deg = 20.0", "xi_deg = nan"),
        "foundation.xi_deg",
        "finite",
    );
    assert_names(
        &with("eccentricity_m = 1.0", "eccentricity_m = -inf"),
        "loads.eccentricity_m",
        "finite",
    );
}

#[test]
fn dips_outside_open_quarter_turn_are_named() {
    for bad in ["0.0", "90.0", "-5.0", "120.0"] {
        assert_names(
            &with("xi_deg = 20.0", &format!("xi_deg = {bad}")),
            "foundation.xi_deg",
            "between 0° and 90°",
        );
        assert_names(
            &with("zeta_deg = 25.0", &format!("zeta_deg = {bad}")),
            "foundation.zeta_deg",
            "between 0° and 90°",
        );
    }
}

#[test]
fn kappa_outside_open_half_turn_is_named() {
    for bad in ["90.0", "-90.0", "135.0"] {
        assert_names(
            &with("kappa_deg = 30.0", &format!("kappa_deg = {bad}")),
            "foundation.kappa_deg",
            "between -90° and 90°",
        );
    }
    Scene::from_toml(&with("kappa_deg = 30.0", "kappa_deg = -89.0"), "d").unwrap();
}

#[test]
fn unequal_frame_sums_are_named() {
    assert_names(&with("l1x = 6.0", "l1x = 7.0"), "frame", "must be equal");
}

#[test]
fn non_positive_mass_inertia_and_times_are_named() {
    assert_names(
        &with("mass_kg = 1.0e6", "mass_kg = 0.0"),
        "block.mass_kg",
        "positive",
    );
    assert_names(
        &with("inertia_kg_m2 = 1.1e7", "inertia_kg_m2 = -1.0"),
        "block.inertia_kg_m2",
        "positive",
    );
    assert_names(
        &with("dt_s = 1.0e-3", "dt_s = 0.0"),
        "solver.dt_s",
        "positive",
    );
    assert_names(
        &with("t_end_s = 20.0", "t_end_s = -1.0"),
        "solver.t_end_s",
        "positive",
    );
    assert_names(
        &with("gravity_m_s2 = 9.81", "gravity_m_s2 = 0.0"),
        "loads.gravity_m_s2",
        "positive",
    );
    assert_names(
        &with("hydraulic_force_n = 8.0e6", "hydraulic_force_n = -1.0"),
        "loads.hydraulic_force_n",
        "zero or positive",
    );
}

#[test]
fn negative_friction_parameters_are_named() {
    assert_names(
        &with("mu_k = 0.40", "mu_k = -0.1"),
        "friction.mu_k",
        "zero or positive",
    );
    let bc = with(
        "model = \"coulomb\"\nmu_k = 0.40",
        "model = \"barton-choubey\"\njrc = -2.0\njcs_pa = 5.0e7\nphi_r_deg = 30.0\ncontact_area_m2 = 1.0",
    );
    assert_names(&bc, "friction.jrc", "zero or positive");
    let bc = bc
        .replace("jrc = -2.0", "jrc = 8.0")
        .replace("phi_r_deg = 30.0", "phi_r_deg = -3.0");
    assert_names(&bc, "friction.phi_r_deg", "0°");
    let ok = bc.replace("phi_r_deg = -3.0", "phi_r_deg = 30.0");
    let s = Scene::from_toml(&ok, "d").unwrap();
    assert!(matches!(s.friction(), Some(Friction::BartonChoubey { .. })));
}

#[test]
fn unknown_friction_model_and_solver_mode_are_named() {
    assert_names(
        &with("model = \"coulomb\"", "model = \"patton\""),
        "friction.model",
        "unknown friction model",
    );
    assert_names(
        &with("mode = \"exact\"", "mode = \"approximate\""),
        "solver.mode",
        "unknown solver mode",
    );
    let s = Scene::from_toml(&with("mode = \"exact\"", "mode = \"small-angle\""), "d").unwrap();
    assert_eq!(s.settings.unwrap().mode, Mode::SmallAngle);
}

#[test]
fn integrator_and_stride_are_optional_and_checked() {
    // The default dynamics is the rigid body's, which integrates with RK4; the paper's takes
    // its own update by default.
    let s = Scene::from_toml(GOOD, "d").unwrap();
    assert_eq!(s.settings.unwrap().integrator, Integrator::Rk4);
    assert_eq!(s.settings.unwrap().stride, 1);
    let paper = with("t_end_s = 20.0", "t_end_s = 20.0\ndynamics = \"paper\"");
    let s = Scene::from_toml(&paper, "d").unwrap();
    assert_eq!(s.settings.unwrap().integrator, Integrator::Paper);
    let t = with(
        "t_end_s = 20.0",
        "t_end_s = 20.0\nintegrator = \"rk4\"\nstride = 10",
    );
    let s = Scene::from_toml(&t, "d").unwrap();
    assert_eq!(s.settings.unwrap().integrator, Integrator::Rk4);
    assert_eq!(s.settings.unwrap().stride, 10);
    assert_names(
        &with("t_end_s = 20.0", "t_end_s = 20.0\nintegrator = \"euler\""),
        "solver.integrator",
        "unknown integrator",
    );
    assert_names(
        &with("t_end_s = 20.0", "t_end_s = 20.0\nstride = 0"),
        "solver.stride",
        "1 or more",
    );
}

#[test]
fn runs_longer_than_the_increment_limit_are_refused() {
    assert_names(
        &with("dt_s = 1.0e-3", "dt_s = 1.0e-12"),
        "solver.dt_s",
        "increments",
    );
}

#[test]
fn broken_toml_reports_line_and_column() {
    let e = err("[frame]\nl1x = = 6\n");
    let msg = e.to_string();
    assert!(msg.contains("not valid TOML"), "{msg}");
    assert!(msg.contains("line 2"), "{msg}");
    assert!(!msg.contains('\n'));
}

#[test]
fn empty_and_binary_inputs_are_errors_not_panics() {
    for text in [
        "",
        "\u{0}\u{1}\u{2}",
        "[[frame]]",
        "frame = 3",
        "[frame]\nl1x = 1e400",
    ] {
        let _ = Scene::from_toml(text, "junk");
    }
    assert_names("", "frame", "missing section [frame]");
}

#[test]
fn unreadable_file_is_named() {
    let e = Scene::from_file(std::path::Path::new("/nonexistent/dam.toml")).unwrap_err();
    assert!(
        e.to_string()
            .starts_with("/nonexistent/dam.toml: cannot read"),
        "{e}"
    );
}

mod never_panics {
    use super::*;
    use proptest::prelude::*;

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(2000))]

        #[test]
        fn arbitrary_text_is_loaded_or_rejected_in_one_line(text in "\\PC{0,400}") {
            if let Err(e) = Scene::from_toml(&text, "fuzz.toml") {
                prop_assert!(!e.to_string().contains('\n'));
            }
        }

        #[test]
        fn good_scene_with_one_value_replaced_never_panics(
            line in 0usize..30,
            value in prop_oneof![
                Just("-1.0".to_string()), Just("nan".to_string()), Just("\"x\"".to_string()),
                Just("[1, 2]".to_string()), Just("{ a = 1 }".to_string()), Just("1e309".to_string()),
                any::<f64>().prop_map(|v| format!("{v:?}")),
            ],
        ) {
            let text: Vec<String> = GOOD
                .lines()
                .enumerate()
                .map(|(i, l)| match l.split_once(" = ") {
                    Some((k, _)) if i == line => format!("{k} = {value}"),
                    _ => l.to_string(),
                })
                .collect();
            if let Err(e) = Scene::from_toml(&text.join("\n"), "fuzz.toml") {
                prop_assert!(e.to_string().starts_with("fuzz.toml: "));
                prop_assert!(!e.to_string().contains('\n'));
            }
        }
    }
}

#[test]
fn rigid_body_keys_default_to_a_thin_plate_and_are_checked() {
    let s = Scene::default_scene();
    let b = s.block.unwrap();
    assert_eq!(
        (b.inertia_x, b.inertia_z, b.inertia_xz),
        (5.5e6, 5.5e6, 0.0)
    );
    assert_eq!(s.settings.unwrap().dynamics, DynamicsModel::RigidBody);
    let rb = with(
        "t_end_s = 20.0",
        "t_end_s = 20.0\ndynamics = \"rigid-body\"",
    );
    let s = Scene::from_toml(&rb, "s.toml").unwrap();
    let solver = s.settings.unwrap();
    assert_eq!(solver.dynamics, DynamicsModel::RigidBody);
    assert_eq!(solver.integrator, Integrator::Rk4);
    let bad = [
        (
            with(
                "t_end_s = 20.0",
                "t_end_s = 20.0\ndynamics = \"rigid-body\"\nintegrator = \"paper\"",
            ),
            "solver.integrator",
        ),
        (
            with("t_end_s = 20.0", "t_end_s = 20.0\ndynamics = \"newtonian\""),
            "solver.dynamics",
        ),
        (
            with(
                "inertia_kg_m2 = 1.1e7",
                "inertia_kg_m2 = 1.1e7\ninertia_xz_kg_m2 = 6.0e6",
            ),
            "block.inertia_xz_kg_m2",
        ),
        (
            with(
                "inertia_kg_m2 = 1.1e7",
                "inertia_kg_m2 = 1.1e7\ninertia_x_kg_m2 = 3.0e7",
            ),
            "block",
        ),
        (
            with(
                "inertia_kg_m2 = 1.1e7",
                "inertia_kg_m2 = 1.1e7\ninertia_z_kg_m2 = -1.0",
            ),
            "block.inertia_z_kg_m2",
        ),
    ];
    for (text, key) in bad {
        let e = Scene::from_toml(&text, "s.toml").unwrap_err();
        assert_eq!(e.key, key, "{e}");
    }
}

#[test]
fn initial_motion_defaults_to_rest_and_is_read_in_degrees_and_checked() {
    let s = Scene::from_toml(GOOD, "dam.toml").unwrap();
    assert!(s.initial.at_rest());
    let moving = format!("{GOOD}[initial]\nvx_m_s = 0.5\nomega_deg_s = 90\n");
    let s = Scene::from_toml(&moving, "dam.toml").unwrap();
    assert_eq!(s.initial.vx, 0.5);
    assert_eq!(s.initial.vz, 0.0);
    assert!((s.initial.omega - std::f64::consts::FRAC_PI_2).abs() < 1e-15);
    assert!(!s.initial.at_rest());
    assert_names(
        &format!("{GOOD}[initial]\nvz_m_s = inf\n"),
        "initial.vz_m_s",
        "finite",
    );
    assert_names(
        &format!("{GOOD}[initial]\nspeed_m_s = 1.0\n"),
        "initial.speed_m_s",
        "unknown key",
    );
}

#[test]
fn rigid_body_with_small_angle_geometry_is_refused_naming_the_mode() {
    // The combination cost about a thousand tracker steps an increment; it is
    // refused with the reason, and the paper's dynamics keep the small-angle system.
    let small = with("mode = \"exact\"", "mode = \"small-angle\"");
    let s = Scene::from_toml(&small, "s.toml").unwrap();
    let e = s.simulation().unwrap_err();
    assert_eq!(e.key, "solver.mode");
    assert!(e.to_string().contains("needs mode = \"exact\""), "{e}");
    let paper = s.with_dynamics(DynamicsModel::Paper).unwrap();
    assert!(paper.simulation().is_ok());
}

#[test]
fn an_increment_longer_than_the_route_is_an_error_naming_solver_dt_s() {
    // dt_s 30 with t_end_s 20 ran and ended "no admissible root".
    assert_names(
        &with("dt_s = 1.0e-3", "dt_s = 30.0"),
        "solver.dt_s",
        "longer than the whole route",
    );
}

#[test]
fn a_frame_whose_side_overflows_is_an_error_naming_the_frame() {
    // Four lengths of 1.5e308 m passed and wrote NaN tilts.
    let text = ["l1x = 6.0", "l2x = 4.0", "l1z = 5.0", "l2z = 5.0"]
        .iter()
        .fold(GOOD.to_string(), |t, k| {
            t.replace(k, &format!("{} = 1.5e308", &k[..3]))
        });
    assert_names(&text, "frame", "must be finite");
}

#[test]
fn likely_mistakes_give_warnings_naming_the_key() {
    // A dip under 1° (radians typed as degrees) and μ over 2 ran without a word.
    let s = Scene::from_toml(GOOD, "d").unwrap();
    assert!(s.warnings().is_empty(), "{:?}", s.warnings());
    let text = with("xi_deg = 20.0", "xi_deg = 0.35").replace("mu_k = 0.40", "mu_k = 22");
    let w = Scene::from_toml(&text, "d").unwrap().warnings();
    assert_eq!(w.len(), 2, "{w:?}");
    assert!(
        w[0].contains("foundation.xi_deg") && w[0].contains("radians"),
        "{w:?}"
    );
    assert!(w[1].contains("friction.mu_k"), "{w:?}");
}

#[test]
fn a_tolerance_given_to_the_block_on_its_base_warns_that_it_has_no_effect() {
    // The block on its base steps by dt_s (first order): a tolerance asked of it changed
    // nothing, without a word. The three points' rigid body takes it; so does a scene that
    // gives none.
    let base = |extra: &str| {
        Scene::default_scene()
            .with("solver.contacts", "base")
            .and_then(|s| match extra {
                "" => Ok(s),
                _ => s.with("solver.tolerance", 1e-12),
            })
            .unwrap()
            .warnings()
    };
    let w = base("tolerance");
    assert_eq!(w.len(), 1, "{w:?}");
    assert!(
        w[0].contains("solver.tolerance") && w[0].contains("dt_s"),
        "{w:?}"
    );
    assert!(base("").is_empty());
    let frame = Scene::default_scene()
        .with("solver.tolerance", 1e-12)
        .unwrap();
    assert!(frame.warnings().is_empty(), "{:?}", frame.warnings());
}

#[test]
fn derived_quantities_that_are_not_usable_are_errors_naming_the_key() {
    // Each input finite and positive, but the weight infinite, the water
    // load or a moment of inertia absurd against it: one line naming the key to change.
    assert_names(
        &with("mass_kg = 1.0e6", "mass_kg = 1.0e308"),
        "block.mass_kg",
        "weight",
    );
    assert_names(
        &with("gravity_m_s2 = 9.81", "gravity_m_s2 = 1e308"),
        "loads.gravity_m_s2",
        "weight",
    );
    assert_names(
        &with("hydraulic_force_n = 8.0e6", "hydraulic_force_n = 1e308"),
        "loads.hydraulic_force_n",
        "times the weight",
    );
    assert_names(
        &with("inertia_kg_m2 = 1.1e7", "inertia_kg_m2 = 1e-300"),
        "block.inertia_kg_m2",
        "outside 1e-6",
    );
}

#[test]
fn every_error_gives_the_line_of_the_key_it_names() {
    // Out of range, unknown name, missing key (its section's line), unknown key: each found by
    // the key, not by reading an error's text.
    let line_of = |text: &str| err(text).position.map(|p| p.0);
    let line = |key: &str| GOOD.lines().position(|l| l.starts_with(key)).unwrap() + 1;
    assert_eq!(line_of(&with("l1x = 6.0", "l1x = -6.0")), Some(line("l1x")));
    assert_eq!(
        line_of(&with("mode = \"exact\"", "mode = \"approx\"")),
        Some(line("mode ="))
    );
    assert_eq!(
        line_of(&with("xi_deg = 20.0\n", "")),
        Some(line("[foundation]"))
    );
    assert_eq!(
        line_of(&with("mu_k = 0.40", "mu_k = 0.4\nmu_s = 0.5")),
        Some(line("mu_k") + 1)
    );
}

#[test]
fn a_time_limit_that_is_not_finite_is_the_time_limits_fault_at_its_line() {
    // Before, `t_end_s = inf` was reported as solver.dt_s (t_end_s / dt_s = inf increments)
    // at dt_s's line.
    let line = GOOD.lines().position(|l| l.starts_with("t_end_s")).unwrap() + 1;
    for v in ["inf", "+inf", "nan", "-inf"] {
        let text = with("t_end_s = 20.0", &format!("t_end_s = {v}"));
        assert_names(&text, "solver.t_end_s", "finite");
        assert_eq!(err(&text).position.map(|p| p.0), Some(line), "{v}");
    }
    let text = with("dt_s = 1.0e-3", "dt_s = inf");
    assert_names(&text, "solver.dt_s", "finite");
}

#[test]
fn a_whole_number_beyond_64_bits_is_named_by_its_key_and_line() {
    // Before: `not a table of keys: invalid type: integer … as i128`, no key, no line.
    let line = |key: &str| GOOD.lines().position(|l| l.starts_with(key)).unwrap() + 1;
    for big in [
        "9223372036854775808",
        "-9223372036854775809",
        "18446744073709551616",
        "99999999999999999999999999999",
        "0x1_0000_0000_0000_0000",
    ] {
        let text = with("mu_k = 0.40", &format!("mu_k = {big}"));
        assert_names(&text, "friction.mu_k", "64-bit");
        let e = err(&text);
        assert_eq!(e.kind, SceneErrorKind::WrongType);
        assert_eq!(e.position, Some((line("mu_k"), 8)), "{big}");
    }
    // In an array, an inline table and a list of tables: the key that holds it.
    let text = format!("{GOOD}[base]\noutline_m = [[0, 1], [2, 18446744073709551616]]\n");
    assert_names(&text, "base.outline_m", "64-bit");
    let text = format!("{GOOD}[[case]]\nname = \"a\"\n[[case]]\nkh = 18446744073709551616\n");
    assert_names(&text, "case[1].kh", "64-bit");
    let text = with("mu_k = 0.40", "mu_k = { a = 18446744073709551616 }");
    assert_names(&text, "friction.mu_k.a", "64-bit");
    // The largest and the smallest 64-bit integers are read (and then judged as values).
    let text = with("dt_s = 1.0e-3", "dt_s = 9223372036854775807");
    assert_eq!(err(&text).key, "solver.dt_s");
    assert!(!err(&text).reason.contains("64-bit"), "{}", err(&text));
}

#[test]
fn a_key_with_an_empty_part_is_refused_naming_it() {
    // Before, `.mu_k` gave "unknown key ``" naming nothing.
    let s = Scene::from_toml(GOOD, "dam.toml").unwrap();
    for key in [".mu_k", "friction.", "", "friction..mu_k", " . "] {
        let e = s.with(key, 0.3).unwrap_err();
        assert_eq!(e.key, key);
        assert_eq!(e.kind, SceneErrorKind::UnknownKey);
        assert!(e.to_string().contains(&format!("{key}: not a key")), "{e}");
    }
    // A key under a key is not a section's: said so, not an empty list of keys.
    let e = s.with("friction.mu_k.deeper", 0.3).unwrap_err();
    assert!(e.to_string().contains("is not a section of keys"), "{e}");
}

#[test]
fn each_error_says_its_kind() {
    let kind = |text: &str| err(text).kind;
    assert_eq!(kind("[frame\n"), SceneErrorKind::Unreadable);
    assert_eq!(
        kind(&with("l2z = 5.0", "l3z = 5.0")),
        SceneErrorKind::UnknownKey
    );
    assert_eq!(kind(&with("l2z = 5.0", "")), SceneErrorKind::MissingKey);
    assert_eq!(
        kind(&with("l2z = 5.0", "l2z = \"x\"")),
        SceneErrorKind::WrongType
    );
    assert_eq!(
        kind(&with("l2z = 5.0", "l2z = -5.0")),
        SceneErrorKind::Invalid
    );
    let geometry = GOOD.split("[block]").next().unwrap();
    let s = Scene::from_toml(geometry, "g").unwrap();
    let e = s.simulation().unwrap_err();
    assert_eq!(e.kind, SceneErrorKind::MissingSection);
}

#[test]
fn a_key_of_the_other_friction_model_is_refused_not_ignored() {
    assert_names(
        &with("mu_k = 0.40", "mu_k = 0.40\njrc = 5.0"),
        "friction.jrc",
        "unknown key for model = \"coulomb\"",
    );
    assert_names(&with("mu_k = 0.40", ""), "friction.mu_k", "missing key");
}

#[test]
fn a_scene_changed_by_key_is_the_scene_a_file_with_that_line_gives() {
    let s = Scene::from_toml(GOOD, "dam.toml").unwrap();
    let changed = s.with("foundation.xi_deg", 18.0).unwrap();
    let file = Scene::from_toml(&with("xi_deg = 20.0", "xi_deg = 18.0"), "dam.toml").unwrap();
    assert_eq!(changed, file);
    assert_eq!(
        changed.site().as_paper().unwrap().foundation.xi,
        18f64.to_radians()
    );
    // Validated as a file is, naming the key; the scene itself is unchanged.
    let e = s.with("friction.mu_k", -0.1).unwrap_err();
    assert_eq!(
        (e.key.as_str(), e.kind),
        ("friction.mu_k", SceneErrorKind::Invalid)
    );
    let e = s.with("frame.l3x", 1.0).unwrap_err();
    assert_eq!(
        (e.key.as_str(), e.kind),
        ("frame.l3x", SceneErrorKind::UnknownKey)
    );
    assert_eq!(
        s.with("solver", 1.0).unwrap_err().kind,
        SceneErrorKind::WrongType
    );
    // Keys that must agree change together; one at a time the frame would not close.
    let keys = [("frame.l1z", 4.0), ("frame.l2z", 6.0)];
    assert!(s.with("frame.l1z", 4.0).is_err());
    let moved = s.with_keys(keys).unwrap();
    assert_eq!(
        (moved.site().contacts()[0][1], moved.site().contacts()[2][1]),
        (4.0, -6.0)
    );
    // A section not yet present is added.
    let kicked = s.with("initial.vx_m_s", 0.5).unwrap();
    assert_eq!(kicked.initial().vx, 0.5);
}

#[test]
fn a_change_of_dynamics_brings_that_models_own_integrator() {
    let paper = with(
        "t_end_s = 20.0",
        "t_end_s = 20.0\ndynamics = \"paper\"\nintegrator = \"paper\"",
    );
    let s = Scene::from_toml(&paper, "d").unwrap();
    let rigid = s.with_dynamics(DynamicsModel::RigidBody).unwrap();
    assert_eq!(rigid.settings().unwrap().integrator, Integrator::Rk4);
    let back = rigid.with_dynamics(DynamicsModel::Paper).unwrap();
    assert_eq!(back.settings().unwrap().integrator, Integrator::Paper);
    // The same model keeps the scene's own choice.
    let rk4 = paper.replace("integrator = \"paper\"", "integrator = \"rk4\"");
    let s = Scene::from_toml(&rk4, "d").unwrap();
    let same = s.with_dynamics(DynamicsModel::Paper).unwrap();
    assert_eq!(same.settings().unwrap().integrator, Integrator::Rk4);
}

/// GOOD with the paper's foundation replaced by faces (each `(dip, dip direction, point)`).
fn with_faces(faces: &[(f64, f64, [f64; 3])]) -> String {
    let mut text = String::from("[foundation]\n");
    for (dip, dir, p) in faces {
        text.push_str(&format!(
            "[[foundation.plane]]\ndip_deg = {dip:?}\ndip_direction_deg = {dir:?}\n\
             point_m = [{:?}, {:?}, {:?}]\n",
            p[0], p[1], p[2]
        ));
    }
    with(
        "[foundation]\nxi_deg = 20.0\nzeta_deg = 25.0\nkappa_deg = 30.0\n",
        &text,
    )
}

/// The paper's three planes as faces, with κ (degrees).
fn papers_faces(kappa: f64) -> Vec<(f64, f64, [f64; 3])> {
    vec![
        (0.0, 0.0, [0.0, 0.0, 0.0]),
        (20.0, 180.0, [4.0, 0.0, 0.0]),
        (25.0, 180.0 - kappa, [4.0, 0.0, -5.0]),
    ]
}

#[test]
fn any_contact_triangle_is_read_from_contacts_m() {
    let text = with(
        "l1x = 6.0\nl2x = 4.0\nl1z = 5.0\nl2z = 5.0\n",
        "contacts_m = [[-3.0, 2.0], [5.0, 1.0], [1.0, -4.0]]\n",
    );
    let s = Scene::from_toml(&text, "tri.toml").unwrap();
    assert_eq!(s.site().contacts(), &[[-3.0, 2.0], [5.0, 1.0], [1.0, -4.0]]);
    assert!(s.site().as_paper().is_none());
    // The paper's planes, each through its contact's start.
    for (k, c) in s.site().contacts().iter().enumerate() {
        assert!(s.site().planes()[k].height(c[0], c[1]).abs() < 1e-12);
    }
    assert!(s.simulation().is_ok());
    // Both forms, neither, a line, or the wrong shape: named.
    assert_names(
        &with(
            "l2z = 5.0\n",
            "l2z = 5.0\ncontacts_m = [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]]\n",
        ),
        "frame.contacts_m",
        "not both",
    );
    let none = with("l1x = 6.0\nl2x = 4.0\nl1z = 5.0\nl2z = 5.0\n", "");
    assert_names(&none, "frame", "contacts_m");
    for bad in [
        "[[0.0, 0.0], [1.0, 1.0], [2.0, 2.0]]",
        "[[0.0, 0.0], [1.0, 0.0]]",
        "[[0.0, 0.0, 1.0], [1.0, 0.0], [0.0, 1.0]]",
        "[[0.0, 0.0], [1.0, 0.0], [0.0, nan]]",
        "[[0.0, 0.0], [1e300, 0.0], [0.0, 1e300]]",
    ] {
        let text = with(
            "l1x = 6.0\nl2x = 4.0\nl1z = 5.0\nl2z = 5.0\n",
            &format!("contacts_m = {bad}\n"),
        );
        assert_names(&text, "frame.contacts_m", "must");
    }
}

#[test]
fn a_foundation_of_faces_puts_each_contact_on_the_face_under_it() {
    let s = Scene::from_toml(&with_faces(&papers_faces(30.0)), "faces.toml").unwrap();
    let (ground, faces) = s.site().ground().expect("a ground of faces");
    assert_eq!(ground.faces().len(), 3);
    // Contact 0 on the level face; 1 on plane 1's strike; 2 where all three meet takes plane 2,
    // which rises first along x' (docs/conventions.md, the paper's own assignment).
    assert_eq!(faces, [0, 1, 2]);
    let paper = Scene::from_toml(GOOD, "paper.toml").unwrap();
    for k in 0..3 {
        let (a, b) = (s.site().normals()[k], paper.site().normals()[k]);
        assert!((a - b).norm() < 1e-15, "{a} vs {b}");
    }
    // Echoed as given.
    let used = s.as_used();
    assert_eq!(used["foundation"]["plane"].as_array().unwrap().len(), 3);
}

/// The same scene with the block on the paper's three-point frame (`contacts = "frame"`).
fn on_frame(text: &str) -> String {
    text.replacen("[solver]\n", "[solver]\ncontacts = \"frame\"\n", 1)
}

#[test]
fn a_start_under_the_ground_or_above_it_is_refused_naming_the_contact_and_the_face() {
    // The paper's planes with κ = −30°: plane 2 stands 2.33 m above contact 1's start
    // (−L sin κ tan ζ with L = 10 m, ζ = 25°).
    let e = err(&on_frame(&with_faces(&papers_faces(-30.0))));
    assert_eq!(e.key, "foundation.plane");
    let msg = e.to_string();
    assert!(msg.contains("contact 1") && msg.contains("face 2"), "{msg}");
    assert!(
        msg.contains("under the ground") && msg.contains("2.33"),
        "{msg}"
    );
    // A level ground 1 m down: every contact in the air.
    let e = err(&on_frame(&with_faces(&[(0.0, 0.0, [0.0, -1.0, 0.0])])));
    assert!(e.to_string().contains("above the ground"), "{e}");
    // The position points at the faces.
    assert!(e.position.is_some());
}

#[test]
fn a_block_on_its_base_is_set_down_wherever_the_ground_is() {
    // The same grounds with the block on its base (the default on faces): it starts where it
    // rests, whatever height the faces are at.
    for faces in [papers_faces(-30.0), vec![(0.0, 0.0, [0.0, -1.0, 0.0])]] {
        let s = Scene::from_toml(&with_faces(&faces), "dam.toml").unwrap();
        assert_eq!(s.settings().unwrap().contacts, crate::model::Contacts::Base);
        assert!(s.simulation().is_ok());
    }
}

#[test]
fn faces_are_checked_key_by_key() {
    let face = |dip: &str, dir: &str, point: &str| {
        with(
            "[foundation]\nxi_deg = 20.0\nzeta_deg = 25.0\nkappa_deg = 30.0\n",
            &format!(
                "[foundation]\n[[foundation.plane]]\ndip_deg = {dip}\ndip_direction_deg = {dir}\n\
                 point_m = {point}\n"
            ),
        )
    };
    assert_names(
        &face("90.0", "0.0", "[0.0, 0.0, 0.0]"),
        "foundation.plane[0].dip_deg",
        "90°",
    );
    assert_names(
        &face("10.0", "inf", "[0.0, 0.0, 0.0]"),
        "foundation.plane[0].dip_direction_deg",
        "finite",
    );
    assert_names(
        &face("10.0", "0.0", "[0.0, 0.0]"),
        "foundation.plane[0].point_m",
        "three finite numbers",
    );
    let unknown =
        face("0.0", "0.0", "[0.0, 0.0, 0.0]").replace("dip_deg = 0.0", "dip_deg = 0.0\nstrike = 1");
    let e = err(&unknown);
    assert_eq!(e.key, "foundation.plane[0].strike", "{e}");
    assert!(e.reason.contains("dip_direction_deg"), "{e}");
    assert!(e.position.is_some(), "{e}");
    assert_names(
        &with("[foundation]\n", "[foundation]\nplane = []\n"),
        "foundation.plane",
        "not more",
    );
    let empty = with(
        "[foundation]\nxi_deg = 20.0\nzeta_deg = 25.0\nkappa_deg = 30.0\n",
        "[foundation]\nplane = []\n",
    );
    assert_names(&empty, "foundation.plane", "at least one");
}

/// GOOD with the foundation replaced by `surface = "<name>"`, read from `folder`.
fn with_surface(
    folder: &std::path::Path,
    name: &str,
    obj: Option<&str>,
    frame: bool,
) -> Result<Scene, SceneError> {
    if let Some(obj) = obj {
        std::fs::write(folder.join(name), obj).unwrap();
    }
    let text = with(
        "[foundation]\nxi_deg = 20.0\nzeta_deg = 25.0\nkappa_deg = 30.0\n",
        &format!("[foundation]\nsurface = \"{name}\"\n"),
    );
    let text = if frame { on_frame(&text) } else { text };
    let path = folder.join("scene.toml");
    std::fs::write(&path, text).unwrap();
    Scene::from_file(&path)
}

fn scratch(name: &str) -> std::path::PathBuf {
    let dir = std::env::temp_dir().join(format!("slideroute-scene-{name}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// A level square of two triangles over [−10, 10]², Y = `y`.
fn level_square(y: f64) -> String {
    format!("v -10 {y} -10\nv 10 {y} -10\nv 10 {y} 10\nv -10 {y} 10\nf 1 2 3\nf 1 3 4\n")
}

#[test]
fn a_surface_is_read_from_an_obj_file_beside_the_scene() {
    let dir = scratch("surface");
    let s = with_surface(&dir, "square.obj", Some(&level_square(0.0)), false).unwrap();
    let (ground, faces) = s.site().ground().unwrap();
    assert!(ground.is_surface());
    assert_eq!(ground.faces().len(), 2);
    assert!(faces.iter().all(|&f| f < 2));
    // And the repository's valley.
    let valley = Scene::from_file(std::path::Path::new(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/scenes/valley.toml"
    )))
    .unwrap();
    assert_eq!(valley.site().ground().unwrap().0.faces().len(), 864);
    // Changed by key, it still finds its file.
    assert!(valley.with("friction.mu_k", 0.3).is_ok());
    // And keeps the surface it read, without reading it again: a scene whose file is gone is
    // still edited; one that names another surface reads that.
    std::fs::remove_file(dir.join("square.obj")).unwrap();
    let edited = s.with("friction.mu_k", 0.3).unwrap();
    let shared = |s: &Scene| s.site.shared_ground().unwrap().clone();
    assert!(std::sync::Arc::ptr_eq(&shared(&s), &shared(&edited)));
    let e = s.with("foundation.surface", "other.obj").unwrap_err();
    assert!(e.to_string().contains("other.obj"), "{e}");
    let _ = std::fs::remove_dir_all(dir);
}

#[test]
fn a_bad_surface_is_named_with_its_file_and_reason() {
    let dir = scratch("bad-surface");
    let reason = |name: &str, obj: Option<&str>| {
        let e = with_surface(&dir, name, obj, true).unwrap_err();
        assert_eq!(e.key, "foundation.surface", "{e}");
        e.reason
    };
    let missing = reason("missing.obj", None);
    assert!(
        missing.contains("missing.obj") && missing.contains("cannot read"),
        "{missing}"
    );
    assert!(reason("empty.obj", Some("# nothing\n")).contains("no triangles"));
    let wall = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
    assert!(reason("wall.obj", Some(wall)).contains("vertical"));
    let line = "v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\n";
    assert!(reason("line.obj", Some(line)).contains("no area"));
    let dangling = "v 0 0 0\nv 1 0 0\nf 1 2 9\n";
    let r = reason("dangling.obj", Some(dangling));
    assert!(r.contains("OBJ") || r.contains("vertex"), "{r}");
    // Under and above the ground, and off it.
    assert!(reason("high.obj", Some(&level_square(0.5))).contains("under the ground"));
    assert!(reason("low.obj", Some(&level_square(-0.5))).contains("above the ground"));
    let small = "v -1 0 -1\nv 1 0 -1\nv 1 0 1\nf 1 2 3\n";
    assert!(reason("small.obj", Some(small)).contains("off the surveyed surface"));
    // One form of foundation only.
    let both = with(
        "kappa_deg = 30.0\n",
        "kappa_deg = 30.0\nsurface = \"square.obj\"\n",
    );
    assert_names(&both, "foundation.surface", "not more");
    let _ = std::fs::remove_dir_all(dir);
}

#[test]
fn a_scene_without_solver_or_its_mode_runs_with_the_documented_defaults() {
    // `[solver]` and `mode` may be left out: the README calls exact the default.
    let without = GOOD.split("[solver]").next().unwrap();
    let s = Scene::from_toml(without, "dam.toml").unwrap();
    let settings = *s.settings().unwrap();
    assert_eq!(settings.mode, Mode::Exact);
    assert_eq!(settings.dynamics, DynamicsModel::RigidBody);
    assert_eq!(settings.integrator, Integrator::Rk4);
    assert_eq!(settings.dt, super::validate::DEFAULT_DT_S);
    assert_eq!(settings.t_end, super::validate::DEFAULT_T_END_S);
    assert_eq!((settings.dt, settings.t_end), (1e-3, 20.0));
    // The same as the file that writes them out.
    let written = Scene::from_toml(GOOD, "dam.toml").unwrap();
    assert_eq!(s.simulation().unwrap(), written.simulation().unwrap());
    let no_mode = Scene::from_toml(&with("mode = \"exact\"\n", ""), "dam.toml").unwrap();
    assert_eq!(no_mode.settings().unwrap().mode, Mode::Exact);
    // Other keys of [solver] still checked.
    assert_names(&with("dt_s = 1.0e-3", "dt_s = -1.0"), "solver.dt_s", "");
}

#[test]
fn a_scene_with_several_mistakes_is_told_of_each_at_once() {
    // Several wrong keys are reported together, not one at a time.
    let text = with("xi_deg = 20.0", "xi_deg = 95.0")
        .replacen("mu_k = 0.40", "mu_k = -0.4", 1)
        .replacen("dt_s = 1.0e-3", "dt_s = -1.0", 1)
        .replacen("gravity_m_s2 = 9.81", "gravity_m_s2 = 9.81\ncolour = 3", 1);
    let e = err(&text);
    let keys: Vec<&str> = e.faults().map(|f| f.key.as_str()).collect();
    assert_eq!(
        keys,
        [
            "loads.colour",
            "foundation.xi_deg",
            "solver.dt_s",
            "friction.mu_k"
        ]
    );
    // Each at its own line of the file, each one line; Display is the first alone.
    let lines: Vec<usize> = e.faults().map(|f| f.position.unwrap().0).collect();
    for (f, line) in e.faults().zip(lines) {
        let key = f.key.rsplit('.').next().unwrap();
        assert!(text.lines().nth(line - 1).unwrap().starts_with(key), "{f}");
        assert!(!f.to_string().contains('\n'));
    }
    assert!(!e.to_string().contains("mu_k"));
    // A scene edited by key is told the same way, and never more than MAX_FAULTS.
    let s = Scene::from_toml(GOOD, "dam.toml").unwrap();
    let e = s
        .with_keys([
            ("friction.mu_k".to_string(), toml::Value::Float(-1.0)),
            ("solver.dt_s".to_string(), toml::Value::Float(-1.0)),
        ])
        .unwrap_err();
    assert_eq!(e.faults().count(), 2, "{:?}", e.also);
    let mut many = GOOD.to_string();
    for k in 0..30 {
        many = many.replacen("[frame]", &format!("[frame]\nextra{k} = 1"), 1);
    }
    assert_eq!(err(&many).faults().count(), super::error::MAX_FAULTS);
}

#[test]
fn a_cases_scene_carries_no_list_of_cases_so_a_check_grows_linearly_with_them() {
    // Each case's scene is read from the scene's document without its `[[case]]` list: with it,
    // reading every case again for each made a check of 1000 cases take 2.2 s of CPU against
    // 0.2 s for 250 (0.38 s and 0.09 s without).
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    let scene = Scene::from_file(&dir.join("scenes/dam.toml")).unwrap();
    assert!(scene.cases().len() >= 2);
    for case in scene.cases() {
        let s = scene.for_case(case).unwrap();
        assert!(s.cases().is_empty(), "{}", case.name);
        assert!(s.name().ends_with(&case.name));
        // The same loads and settings as the whole scene with the case's keys set.
        let whole = scene
            .with_keys(case.keys.iter().map(|(k, v)| (k.as_str(), *v)))
            .unwrap();
        assert_eq!(
            format!("{:?}", s.loads_used()),
            format!("{:?}", whole.loads_used()),
            "{}",
            case.name
        );
        assert_eq!(s.settings(), whole.settings());
    }
}
