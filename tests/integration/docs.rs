//! Hygiene: every file a doc comment or a document names is in the
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

/// Names the documents quote that are not this repository's: other languages' and the
/// standard library's, an environment variable, a suffix.
const NOT_OURS: [&str; 10] = [
    "FromStr",
    "Display",
    "PartialEq",
    "ValueError",
    "KeyboardInterrupt",
    "LocalCluster",
    "OUT_DIR",
    "sin_cos",
    "Cow",
    "_deg",
];

/// The names the code defines: items (`fn`, `struct`, `enum`, `trait`, `const`, `type`, `mod`,
/// `static`, macros), fields and variants, and the modules its files and folders are.
fn defined_names(root: &Path) -> std::collections::BTreeSet<String> {
    let mut sources = Vec::new();
    for dir in ["src", "codegen/src", "python/src", "tests", "benches"] {
        files(&root.join(dir), &mut sources);
    }
    let mut names = std::collections::BTreeSet::new();
    let ident = |s: &str| -> String {
        s.chars()
            .take_while(|c| c.is_alphanumeric() || *c == '_')
            .collect()
    };
    for file in sources
        .iter()
        .filter(|f| f.extension().is_some_and(|e| e == "rs"))
    {
        names.insert(file.file_stem().unwrap().to_string_lossy().to_string());
        if let Some(dir) = file.parent().and_then(|d| d.file_name()) {
            names.insert(dir.to_string_lossy().to_string());
        }
        let text = std::fs::read_to_string(file).unwrap_or_default();
        for line in text.lines() {
            let words: Vec<&str> = line.split_whitespace().collect();
            for pair in words.windows(2) {
                let item = [
                    "fn",
                    "struct",
                    "enum",
                    "trait",
                    "const",
                    "type",
                    "mod",
                    "static",
                    "macro_rules!",
                ];
                if item.contains(&pair[0]) {
                    names.insert(ident(pair[1]));
                }
            }
            // A field or a variant: the line's first word, before `:`, `,`, `(` or `{`.
            let first = line.trim_start().trim_start_matches("pub(crate) ");
            let first = first
                .trim_start_matches("pub(super) ")
                .trim_start_matches("pub ");
            let name = ident(first);
            if !name.is_empty()
                && first[name.len()..]
                    .trim_start()
                    .starts_with([':', ',', '(', '{'])
            {
                names.insert(name);
            }
        }
    }
    names
}

/// The code names `text` quotes: each `` `name` `` or `` `path::to::name` `` (with or without
/// `()`) that has an upper-case letter, an underscore or a `::`, plain words left out.
fn quoted_code_names(text: &str) -> Vec<String> {
    let mut out = Vec::new();
    for (k, quoted) in text.split('`').enumerate() {
        let t = quoted.trim().trim_end_matches("()");
        let is_path = k % 2 == 1
            && !t.is_empty()
            && t.split("::").all(|s| {
                s.chars()
                    .next()
                    .is_some_and(|c| c.is_alphabetic() || c == '_')
                    && s.chars().all(|c| c.is_alphanumeric() || c == '_')
            });
        if is_path && (t.contains("::") || t.contains('_') || t.chars().any(char::is_uppercase)) {
            out.push(t.to_string());
        }
    }
    out
}

#[test]
fn every_code_name_a_document_quotes_is_in_the_code() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let defined = defined_names(root);
    let mut documents = Vec::new();
    for dir in ["derivations", "docs", "crosscheck"] {
        files(&root.join(dir), &mut documents);
    }
    documents.retain(|f| f.extension().is_some_and(|e| e == "md"));
    documents.extend(["README.md", "ARCHITECTURE.md"].map(|f| root.join(f)));
    let mut stale = Vec::new();
    let mut seen = 0;
    for doc in &documents {
        let text = std::fs::read_to_string(doc).unwrap();
        for name in quoted_code_names(&text) {
            seen += 1;
            let unknown: Vec<&str> = name
                .split("::")
                .filter(|s| !["crate", "self", "super", "slideroute"].contains(s))
                .filter(|s| !defined.contains(*s) && !NOT_OURS.contains(s))
                .collect();
            if !unknown.is_empty() {
                let doc = doc.strip_prefix(root).unwrap().display();
                stale.push(format!("{doc}: `{name}` ({})", unknown.join(", ")));
            }
        }
    }
    assert!(
        seen > 50,
        "only {seen} code names found: the scan is broken"
    );
    assert!(
        stale.is_empty(),
        "quoted in the documents, not in the code:\n{}",
        stale.join("\n")
    );
}

#[test]
fn the_code_name_scan_finds_paths_and_names_and_skips_words() {
    let text = "the driver (`drive`), `ContactStrengths::settle`, `RigidBody::new()`, `route.csv`, \
                `slideroute run`, `accelerations_in_crease` and `x`";
    assert_eq!(
        quoted_code_names(text),
        vec![
            "ContactStrengths::settle",
            "RigidBody::new",
            "accelerations_in_crease"
        ]
    );
    let defined = defined_names(Path::new(env!("CARGO_MANIFEST_DIR")));
    assert!(defined.contains("Simulation") && defined.contains("settle"));
    assert!(!defined.contains("accelerations_in_crease"));
}
