//! The scene loader never panics: arbitrary bytes, arbitrary TOML documents, and a regression
//! corpus of awkward files (`tests/corpus/`) each load or give one line naming the file.
//! (Arbitrary text and single-value replacements are fuzzed in `src/scene/tests.rs` too.)

use proptest::prelude::*;
use slideroute::Displacement;
use slideroute::internals::{model::Mode, scene::Scene};

fn assert_one_line(text: &str, origin: &str) {
    if let Err(e) = Scene::from_toml(text, origin) {
        let msg = e.to_string();
        assert!(msg.starts_with(&format!("{origin}: ")), "{msg}");
        assert!(!msg.contains('\n'), "{msg:?}");
    }
}

#[test]
fn regression_corpus_loads_or_is_rejected_in_one_line() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/corpus");
    let mut n = 0;
    for entry in std::fs::read_dir(&dir).expect("corpus") {
        let path = entry.unwrap().path();
        let bytes = std::fs::read(&path).unwrap();
        let text = String::from_utf8_lossy(&bytes);
        assert_one_line(&text, &path.display().to_string());
        // Through the file API too (which also handles non-UTF-8).
        if let Err(e) = Scene::from_file(&path) {
            assert!(!e.to_string().contains('\n'));
        }
        n += 1;
    }
    assert!(n >= 15, "corpus has {n} files");
}

/// A TOML value of any kind, shallow.
fn value() -> impl Strategy<Value = String> {
    prop_oneof![
        any::<f64>().prop_map(|v| format!("{v:?}").replace("NaN", "nan")),
        any::<i64>().prop_map(|v| v.to_string()),
        "[a-z\u{00e9}\u{20ac} ]{0,8}".prop_map(|s| format!("{s:?}")),
        any::<bool>().prop_map(|b| b.to_string()),
        Just("[1, 2.5, \"x\"]".to_string()),
        Just("{ a = 1 }".to_string()),
        Just("1979-05-27T07:32:00Z".to_string()),
    ]
}

const SECTIONS: [&str; 8] = [
    "frame",
    "foundation",
    "block",
    "loads",
    "friction",
    "solver",
    "extra",
    "",
];
const KEYS: [&str; 12] = [
    "l1x",
    "l2x",
    "l1z",
    "l2z",
    "xi_deg",
    "zeta_deg",
    "kappa_deg",
    "mu_k",
    "model",
    "mode",
    "dt_s",
    "zz",
];

proptest! {
    #![proptest_config(ProptestConfig::with_cases(3000))]

    #[test]
    fn arbitrary_bytes_never_panic(bytes in proptest::collection::vec(any::<u8>(), 0..300)) {
        assert_one_line(&String::from_utf8_lossy(&bytes), "bytes.toml");
    }

    #[test]
    fn arbitrary_toml_documents_never_panic(
        entries in proptest::collection::vec((0..SECTIONS.len(), 0..KEYS.len(), value()), 0..30)
    ) {
        let mut text = String::new();
        let mut by_section: Vec<Vec<String>> = vec![Vec::new(); SECTIONS.len()];
        for (s, k, v) in entries {
            by_section[s].push(format!("{} = {v}", KEYS[k]));
        }
        for line in &by_section[SECTIONS.len() - 1] {
            text.push_str(line);
            text.push('\n');
        }
        for (s, lines) in by_section.iter().enumerate().take(SECTIONS.len() - 1) {
            if !lines.is_empty() {
                text.push_str(&format!("[{}]\n{}\n", SECTIONS[s], lines.join("\n")));
            }
        }
        assert_one_line(&text, "doc.toml");
    }
}

/// A scene of any contact triangle on a random valley of faces: one through each contact,
/// descending towards the triangle's centroid (so that, mostly, it is under the other contacts),
/// and walls further out; with the default scene's other sections.
fn faceted_scene() -> impl Strategy<Value = String> {
    (
        prop::array::uniform3(prop::array::uniform2(-15.0..15.0f64)),
        prop::array::uniform3((0.0..60.0f64, -0.5..0.5f64)),
        proptest::collection::vec(
            (5.0..70.0f64, 0.0..std::f64::consts::TAU, 35.0..60.0f64),
            0..5,
        ),
        prop_oneof![Just("rigid-body"), Just("paper")],
    )
        .prop_map(|(c, own, walls, dynamics)| {
            let mut text = format!(
                "[frame]\ncontacts_m = [[{:?}, {:?}], [{:?}, {:?}], [{:?}, {:?}]]\n[foundation]\n",
                c[0][0], c[0][1], c[1][0], c[1][1], c[2][0], c[2][1]
            );
            let g = [
                (c[0][0] + c[1][0] + c[2][0]) / 3.0,
                (c[0][1] + c[1][1] + c[2][1]) / 3.0,
            ];
            let mut face = |dip: f64, dir: f64, p: [f64; 3]| {
                text.push_str(&format!(
                    "[[foundation.plane]]\ndip_deg = {dip:?}\ndip_direction_deg = {:?}\n\
                     point_m = [{:?}, {:?}, {:?}]\n",
                    dir.to_degrees(),
                    p[0],
                    p[1],
                    p[2]
                ));
            };
            for (k, (dip, jitter)) in own.iter().enumerate() {
                let dir = (g[1] - c[k][1]).atan2(g[0] - c[k][0]) + jitter;
                face(*dip, dir, [c[k][0], 0.0, c[k][1]]);
            }
            for (dip, at, r) in walls {
                // Through a point far out at Y = 0, descending towards the origin.
                face(
                    dip,
                    at + std::f64::consts::PI,
                    [r * at.cos(), 0.0, r * at.sin()],
                );
            }
            let rest = slideroute::Scene::DEFAULT_TOML;
            let rest = &rest[rest.find("[block]").unwrap()..];
            let rest = rest.replace("t_end_s = 20.0", "t_end_s = 0.3").replace(
                "dt_s = 1.0e-3",
                &format!("dt_s = 1.0e-3\ndynamics = \"{dynamics}\""),
            );
            format!("{text}{rest}")
        })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(300))]

    #[test]
    fn faceted_scenes_load_or_are_refused_and_run_without_panic(text in faceted_scene()) {
        // Some are refused (a contact off the ground at the start); those that load (about six
        // in ten) run 0.3 s to a stated end, and every row they give is finite.
        match Scene::from_toml(&text, "faces.toml") {
            Err(e) => {
                let msg = e.to_string();
                prop_assert!(msg.starts_with("faces.toml: ") && !msg.contains('\n'), "{}", msg);
            }
            Ok(scene) => {
                // All roots of both modes somewhere near the start: no panic, a count within
                // the bound.
                for mode in [Mode::Exact, Mode::SmallAngle] {
                    let d = Displacement::new(0.3, -0.1, 0.05);
                    if let Ok(all) = slideroute::poses::solve_all(scene.site(), d, mode) {
                        prop_assert!(all.finite_roots <= 8);
                    }
                }
                if let Ok(route) = slideroute::internals::analysis::run(&scene) {
                    prop_assert!(!route.rows.is_empty());
                    prop_assert!(route.rows.iter().all(|r| r.x_m.is_finite()
                        && r.z_m.is_finite()
                        && r.theta_deg.is_finite()));
                }
            }
        }
    }
}
