//! The scene loader never panics: arbitrary bytes, arbitrary TOML documents, and a regression
//! corpus of awkward files (`tests/corpus/`) each load or give one line naming the file.
//! (Arbitrary text and single-value replacements are fuzzed in `src/scene/tests.rs` too.)

use proptest::prelude::*;
use slideroute::stages::scene::Scene;

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
