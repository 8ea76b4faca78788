//! Hygiene (issue #14, item 5): every file a doc comment or a document names is in the
//! repository.

use std::path::{Path, PathBuf};

/// The folders whose files a reference may name.
const ROOTS: [&str; 9] = [
    "derivations/",
    "docs/",
    "scenes/",
    "crosscheck/",
    "tests/",
    "src/",
    "codegen/",
    "benches/",
    "shared/",
];

fn files(dir: &Path, out: &mut Vec<PathBuf>) {
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        let name = path.file_name().unwrap().to_string_lossy().to_string();
        if name.starts_with('.') || name == "target" {
            continue;
        }
        if path.is_dir() {
            files(&path, out);
        } else if ["rs", "md", "toml", "py", "sh"]
            .iter()
            .any(|e| path.extension().is_some_and(|x| x == *e))
        {
            out.push(path);
        }
    }
}

/// Paths named in `text`: a known folder followed by a file name with an extension.
fn references(text: &str) -> Vec<String> {
    let mut found = Vec::new();
    for root in ROOTS {
        let mut rest = text;
        while let Some(at) = rest.find(root) {
            let before = rest[..at].chars().next_back();
            let path: String = rest[at..]
                .chars()
                .take_while(|c| c.is_ascii_alphanumeric() || "_-./".contains(*c))
                .collect();
            rest = &rest[at + root.len()..];
            // Part of a longer path (`tests/integration/...` found from `integration/`), or
            // a folder, not a file.
            if before.is_some_and(|c| c.is_ascii_alphanumeric() || "_-/".contains(c)) {
                continue;
            }
            let path = path.trim_end_matches('.');
            let ext = Path::new(path)
                .extension()
                .map(|e| e.to_string_lossy().to_string());
            if ext.is_some_and(|e| ["rs", "md", "toml", "py", "sh", "csv", "svg"].contains(&&*e)) {
                found.push(path.to_string());
            }
        }
    }
    found
}

#[test]
fn every_file_a_document_names_is_in_the_repository() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut all = Vec::new();
    for dir in [
        "src",
        "codegen",
        "tests",
        "derivations",
        "docs",
        "crosscheck",
        "benches",
    ] {
        files(&root.join(dir), &mut all);
    }
    for top in ["README.md", "ARCHITECTURE.md", "build.rs"] {
        if root.join(top).exists() {
            all.push(root.join(top));
        }
    }
    let mut missing = Vec::new();
    let mut seen = 0;
    // This file names missing paths on purpose, in its own test of the scan.
    let this = root.join("tests/integration/docs.rs");
    for file in all.iter().filter(|f| **f != this) {
        let text = std::fs::read_to_string(file).unwrap_or_default();
        for r in references(&text) {
            seen += 1;
            if !root.join(&r).exists() {
                missing.push(format!(
                    "{}: {r}",
                    file.strip_prefix(root).unwrap().display()
                ));
            }
        }
    }
    assert!(
        seen > 20,
        "only {seen} references found: the scan is broken"
    );
    assert!(
        missing.is_empty(),
        "named but not in the repository:\n{}",
        missing.join("\n")
    );
}

#[test]
fn the_reference_scan_finds_paths_and_skips_parts_of_longer_ones() {
    let text = "see `derivations/04-exact.md`, shared/conventions.md and tests/integration/route.rs; \
                a folder derivations/ is not a file.";
    assert_eq!(
        references(text),
        vec![
            "derivations/04-exact.md",
            "tests/integration/route.rs",
            "shared/conventions.md"
        ]
    );
}
