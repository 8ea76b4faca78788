//! The shape of the library: data flows one way, down the layers of `MAY_IMPORT` — the physical
//! model and everything that computes with it never import the scene reader, and nothing
//! imports a stage above it. Within a stage no file imports a sibling that imports it back. (A
//! stage's `mod.rs` is its facade — it re-exports its files and holds what they share — so
//! edges to and from it are not cycles of the flow.)

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

fn sources(dir: &Path, out: &mut Vec<PathBuf>) {
    for e in std::fs::read_dir(dir).unwrap() {
        let p = e.unwrap().path();
        if p.is_dir() {
            if p.file_name().is_some_and(|n| n != "bin") {
                sources(&p, out);
            }
        } else if p.extension().is_some_and(|x| x == "rs") {
            out.push(p);
        }
    }
}

/// The code of a file without its tests and comments (a stage's `tests.rs` is all tests).
fn code(path: &Path) -> String {
    if path.file_name().is_some_and(|n| n == "tests.rs") {
        return String::new();
    }
    let text = std::fs::read_to_string(path).unwrap();
    let text = match text.find("#[cfg(test)]") {
        Some(k) => &text[..k],
        None => &text[..],
    };
    text.lines()
        .map(|l| l.split("//").next().unwrap_or(""))
        .collect::<Vec<_>>()
        .join("\n")
}

/// The identifiers after each `prefix` in `text`: `prefix::name` and `prefix::{a, b::c}`.
fn names_after(text: &str, prefix: &str) -> Vec<String> {
    let ident = |s: &str| -> String {
        s.chars()
            .take_while(|c| c.is_alphanumeric() || *c == '_')
            .collect()
    };
    let mut out = Vec::new();
    for (k, _) in text.match_indices(prefix) {
        let before = text[..k].chars().next_back();
        if before.is_some_and(|c| c.is_alphanumeric() || c == '_') {
            continue;
        }
        let rest = &text[k + prefix.len()..];
        if let Some(list) = rest.strip_prefix('{') {
            let list = &list[..list.find('}').unwrap_or(list.len())];
            out.extend(list.split(',').map(|p| ident(p.trim())));
        } else {
            out.push(ident(rest));
        }
    }
    out.retain(|n| !n.is_empty());
    out
}

fn cycle(graph: &BTreeMap<String, BTreeSet<String>>) -> Option<Vec<String>> {
    fn visit(
        v: &str,
        g: &BTreeMap<String, BTreeSet<String>>,
        state: &mut BTreeMap<String, u8>,
        path: &mut Vec<String>,
    ) -> Option<Vec<String>> {
        state.insert(v.to_string(), 1);
        path.push(v.to_string());
        for w in g.get(v).into_iter().flatten() {
            match state.get(w.as_str()) {
                Some(1) => {
                    let at = path.iter().position(|p| p == w).unwrap_or(0);
                    let mut c = path[at..].to_vec();
                    c.push(w.clone());
                    return Some(c);
                }
                Some(_) => {}
                None => {
                    if let Some(c) = visit(w, g, state, path) {
                        return Some(c);
                    }
                }
            }
        }
        path.pop();
        state.insert(v.to_string(), 2);
        None
    }
    let mut state = BTreeMap::new();
    for v in graph.keys() {
        if !state.contains_key(v.as_str())
            && let Some(c) = visit(v, graph, &mut state, &mut Vec::new())
        {
            return Some(c);
        }
    }
    None
}

/// The stages each stage may import, from the bottom up (ARCHITECTURE.md, "Data flow"). The
/// model, the geometry, the coefficients, the roots and the mechanics never import the scene
/// (the input layer builds the model, not the other way round), nor the route or the analyses
/// above them. The output (files and pictures) is the top: no stage may import it.
const MAY_IMPORT: [(&str, &[&str]); 11] = [
    ("numeric", &[]),
    ("geometry", &["numeric"]),
    ("model", &["geometry", "numeric"]),
    ("coeffs", &["geometry", "model", "numeric"]),
    ("roots", &["coeffs", "geometry", "model", "numeric"]),
    ("contact", &["geometry", "model", "numeric"]),
    ("mechanics", &["contact", "geometry", "model", "numeric"]),
    (
        "route",
        &[
            "coeffs",
            "contact",
            "geometry",
            "mechanics",
            "model",
            "numeric",
            "roots",
        ],
    ),
    ("scene", &["geometry", "model", "numeric"]),
    (
        "analysis",
        &[
            "geometry",
            "mechanics",
            "model",
            "numeric",
            "route",
            "scene",
        ],
    ),
    (
        "output",
        &[
            "analysis",
            "coeffs",
            "geometry",
            "mechanics",
            "model",
            "numeric",
            "roots",
            "route",
            "scene",
        ],
    ),
];

/// The imports of `graph` that `MAY_IMPORT` does not allow, and the stages it does not list.
fn forbidden(graph: &BTreeMap<String, BTreeSet<String>>) -> Vec<String> {
    let mut out = Vec::new();
    for (stage, to) in graph {
        let Some((_, allowed)) = MAY_IMPORT.iter().find(|(s, _)| s == stage) else {
            out.push(format!("{stage}: a stage the layers do not list"));
            continue;
        };
        out.extend(
            to.iter()
                .filter(|t| !allowed.contains(&t.as_str()))
                .map(|t| format!("{stage} imports {t}")),
        );
    }
    out
}

/// The stages' imports of each other, and the files' imports of their siblings.
fn import_graphs() -> (
    BTreeMap<String, BTreeSet<String>>,
    BTreeMap<String, BTreeSet<String>>,
) {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let mut files = Vec::new();
    sources(&src, &mut files);
    let rel = |p: &Path| {
        p.strip_prefix(&src)
            .unwrap()
            .to_string_lossy()
            .replace('\\', "/")
    };
    let stage_of = |r: &str| {
        r.split('/')
            .next()
            .unwrap()
            .trim_end_matches(".rs")
            .to_string()
    };
    let stages: BTreeSet<String> = files
        .iter()
        .map(|p| stage_of(&rel(p)))
        .filter(|s| s != "lib")
        .collect();
    assert!(stages.len() >= 8, "{stages:?}");
    let mut between: BTreeMap<String, BTreeSet<String>> = BTreeMap::new();
    let mut within: BTreeMap<String, BTreeSet<String>> = BTreeMap::new();
    for p in &files {
        let r = rel(p);
        let stage = stage_of(&r);
        if stage == "lib" {
            continue;
        }
        let text = code(p);
        let to: BTreeSet<String> = names_after(&text, "crate::")
            .into_iter()
            .filter(|n| stages.contains(n) && *n != stage)
            .collect();
        between.entry(stage.clone()).or_default().extend(to);
        // Siblings: files of one folder, not its mod.rs.
        let dir = p.parent().unwrap();
        if p.file_name().is_some_and(|n| n == "mod.rs") || dir == src {
            continue;
        }
        let sibling = |n: &str| dir.join(format!("{n}.rs")).exists() || dir.join(n).is_dir();
        let me = p.file_stem().unwrap().to_string_lossy().to_string();
        let mut to: Vec<String> = names_after(&text, "super::");
        to.extend(names_after(&text, &format!("crate::{stage}::")));
        let key = |n: &str| format!("{}/{n}", rel(dir));
        let edges: BTreeSet<String> = to
            .into_iter()
            .filter(|n| *n != me && sibling(n))
            .map(|n| key(&n))
            .collect();
        within.entry(key(&me)).or_default().extend(edges);
    }
    assert!(
        between.values().map(BTreeSet::len).sum::<usize>() >= 10,
        "the scan found too few imports: {between:?}"
    );
    (between, within)
}

#[test]
fn each_stage_imports_only_the_stages_below_it() {
    let (between, _) = import_graphs();
    assert_eq!(forbidden(&between), Vec::<String>::new(), "{between:?}");
    for stage in ["model", "geometry", "roots", "mechanics", "coeffs", "route"] {
        assert!(
            !between.get(stage).is_some_and(|to| to.contains("scene")),
            "{stage} imports the scene"
        );
    }
}

#[test]
fn no_import_cycle_between_stages_or_between_the_files_of_a_stage() {
    let (between, within) = import_graphs();
    assert_eq!(cycle(&between), None, "stages: {between:?}");
    assert_eq!(cycle(&within), None);
}

#[test]
fn the_layer_check_finds_an_import_from_below() {
    let graph = |edges: &[(&str, &str)]| -> BTreeMap<String, BTreeSet<String>> {
        let mut g: BTreeMap<String, BTreeSet<String>> = BTreeMap::new();
        for (a, b) in edges {
            g.entry(a.to_string()).or_default().insert(b.to_string());
        }
        g
    };
    assert!(forbidden(&graph(&[("route", "mechanics"), ("scene", "model")])).is_empty());
    assert_eq!(
        forbidden(&graph(&[("model", "scene"), ("plots", "route")])),
        [
            "model imports scene",
            "plots: a stage the layers do not list"
        ]
    );
}

#[test]
fn no_stage_of_the_library_imports_the_output() {
    // The files and pictures are the top of the house: the command line and Python call them,
    // nothing below does.
    let (between, _) = import_graphs();
    assert!(between.contains_key("output"), "{between:?}");
    let importers: Vec<&String> = between
        .iter()
        .filter(|(_, to)| to.contains("output"))
        .map(|(stage, _)| stage)
        .collect();
    assert!(importers.is_empty(), "{importers:?} import the output");
    assert!(
        MAY_IMPORT
            .iter()
            .all(|(_, allowed)| !allowed.contains(&"output"))
    );
}

/// The lines of `text` without their comments.
fn without_comments(text: &str) -> String {
    text.lines()
        .map(|l| l.split("//").next().unwrap_or(""))
        .collect::<Vec<_>>()
        .join("\n")
}

#[test]
fn the_command_line_uses_the_public_interface_only() {
    // The binary reached into every stage through `internals` to write its files; its files
    // are now the library's `output`, and it names no internal stage.
    let bin = Path::new(env!("CARGO_MANIFEST_DIR")).join("src/bin");
    let mut files = Vec::new();
    let mut stack = vec![bin];
    while let Some(dir) = stack.pop() {
        for e in std::fs::read_dir(&dir).unwrap() {
            let p = e.unwrap().path();
            if p.is_dir() {
                stack.push(p);
            } else if p.extension().is_some_and(|x| x == "rs") {
                files.push(p);
            }
        }
    }
    assert!(files.len() >= 10, "{files:?}");
    let naming: Vec<&PathBuf> = files
        .iter()
        .filter(|p| without_comments(&std::fs::read_to_string(p).unwrap()).contains("internals"))
        .collect();
    assert!(naming.is_empty(), "{naming:?} name slideroute::internals");
    // Nor does its feature turn the internals on.
    let manifest =
        std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("Cargo.toml")).unwrap();
    let cli = manifest
        .lines()
        .find(|l| l.starts_with("cli = ["))
        .expect("the cli feature");
    assert!(!cli.contains("internals"), "{cli}");
}

#[test]
fn the_cycle_finder_finds_a_cycle() {
    let g: BTreeMap<String, BTreeSet<String>> = [
        ("a", vec!["b"]),
        ("b", vec!["c"]),
        ("c", vec!["a"]),
        ("d", vec![]),
    ]
    .into_iter()
    .map(|(k, v)| (k.into(), v.into_iter().map(String::from).collect()))
    .collect();
    assert_eq!(
        cycle(&g),
        Some(vec!["a".into(), "b".into(), "c".into(), "a".into()])
    );
    assert_eq!(
        names_after("use super::{rhs::Stop, state};", "super::"),
        vec!["rhs", "state"]
    );
}

/// The contact models' rooms in `src/route/`: each model's own folders and files, and the names
/// that are that model's (its types, its modules, what only it uses). Outside a model's room no
/// file of the route names them: the driver, the logbook, the event and rest layers work with
/// any model. `route/models.rs`, the one place that picks a model from the settings, names
/// them all.
const ROOMS: [(&str, &[&str], &[&str]); 2] = [
    (
        "the three-point frame",
        &["route/paper/", "route/rigid/", "route/three_point.rs"],
        &[
            "Contacts::Frame",
            "Paper",
            "PaperReport",
            "RigidBody",
            "RigidBodyReport",
            "faces_of",
            "paper::",
            "rigid::",
            "three_point::",
        ],
    ),
    (
        "the base",
        &["route/body/"],
        &[
            "Contacts::Base",
            "OnBase",
            "OnBaseReport",
            "BaseReport",
            "body::",
        ],
    ),
];

/// The one room that picks a model from the settings.
const SELECTION: &str = "route/models.rs";

/// A room's file that may name another room's module: the block on its base reports through the
/// three-point frame's points (route.csv's tilts, the factor of safety at the start), and asks
/// the frame's own room for them.
const MAY_NAME: [(&str, &str); 1] = [("route/body/", "three_point::")];

/// Whether `token` stands in `text` as a name of its own: not inside a longer identifier
/// (`body::` is not in `rigid_body::`, `Paper` not in `PaperPlanes`).
fn names(text: &str, token: &str) -> bool {
    let part = |c: char| c.is_alphanumeric() || c == '_';
    text.match_indices(token).any(|(k, _)| {
        let before = text[..k].chars().next_back();
        let after = text[k + token.len()..].chars().next();
        !before.is_some_and(part) && (token.ends_with("::") || !after.is_some_and(part))
    })
}

/// What each file of the route (its path from `src/`, its code) names of a contact model outside
/// that model's room. A module's declaration (`mod body;`) is the tree's shape, not a use.
fn named_outside_their_rooms(files: &[(String, String)]) -> Vec<String> {
    let mut out = Vec::new();
    for (path, text) in files {
        if !path.starts_with("route/") || path == SELECTION {
            continue;
        }
        let code: String = text
            .lines()
            .filter(|l| {
                let l = l.trim_start();
                let l = ["pub(crate) ", "pub(super) ", "pub "]
                    .iter()
                    .fold(l, |l, p| l.strip_prefix(p).unwrap_or(l));
                !(l.starts_with("mod ") && l.trim_end().ends_with(';'))
            })
            .collect::<Vec<_>>()
            .join("\n");
        for (room, places, tokens) in ROOMS {
            if places.iter().any(|p| path.starts_with(p)) {
                continue;
            }
            for token in tokens {
                let allowed = MAY_NAME
                    .iter()
                    .any(|(from, t)| path.starts_with(from) && t == token);
                if !allowed && names(&code, token) {
                    out.push(format!("{path} names `{token}` of {room}"));
                }
            }
        }
    }
    out
}

/// The route's files: their paths from `src/` and their code (no tests, no comments).
fn route_files() -> Vec<(String, String)> {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let mut files = Vec::new();
    sources(&src.join("route"), &mut files);
    files
        .iter()
        .map(|p| {
            let rel = p
                .strip_prefix(&src)
                .unwrap()
                .to_string_lossy()
                .replace('\\', "/");
            (rel, code(p))
        })
        .collect()
}

#[test]
fn no_file_of_the_route_names_a_contact_model_outside_that_models_room() {
    let files = route_files();
    assert!(files.len() >= 30, "{} files", files.len());
    // The scan sees the models where they are named: the selection names every room's types.
    let models = &files.iter().find(|(p, _)| p == SELECTION).unwrap().1;
    for token in ["OnBase", "Paper", "RigidBody"] {
        assert!(
            names(models, token),
            "{SELECTION} names no `{token}`: the scan is broken"
        );
    }
    assert_eq!(named_outside_their_rooms(&files), Vec::<String>::new());
}

#[test]
fn the_room_check_finds_a_model_named_outside_its_room() {
    let file = |path: &str, code: &str| (path.to_string(), code.to_string());
    let clean = [
        file(
            "route/driver.rs",
            "use crate::mechanics::rigid_body::Motion;",
        ),
        file(
            "route/mod.rs",
            "mod body;\npub mod paper;\npub(crate) mod three_point;",
        ),
        file(
            "route/models.rs",
            "use super::body::OnBase; use super::rigid::RigidBody;",
        ),
        file(
            "route/rigid/substep.rs",
            "use crate::route::three_point::faces_of;",
        ),
        file(
            "route/body/mod.rs",
            "use super::three_point::factor_of_safety_at_start;",
        ),
        file("route/events.rs", "use crate::geometry::PaperPlanes;"),
        file(
            "analysis/check.rs",
            "use crate::route::three_point::faces_of;",
        ),
    ];
    assert_eq!(named_outside_their_rooms(&clean), Vec::<String>::new());
    let injected = [
        file(
            "route/driver.rs",
            "if sim.settings().contacts == Contacts::Frame {",
        ),
        file(
            "route/logbook.rs",
            "pub base: Option<super::body::report::BaseReport>,",
        ),
        file("route/mod.rs", "pub use body::OnBase;"),
        file("route/rest.rs", "fn held(b: &RigidBody<'_>) {}"),
        file("route/rigid/heading.rs", "use crate::route::body::OnBase;"),
        file("route/body/mod.rs", "use super::three_point::faces_of;"),
    ];
    assert_eq!(
        named_outside_their_rooms(&injected),
        [
            "route/driver.rs names `Contacts::Frame` of the three-point frame",
            "route/logbook.rs names `BaseReport` of the base",
            "route/logbook.rs names `body::` of the base",
            "route/mod.rs names `OnBase` of the base",
            "route/mod.rs names `body::` of the base",
            "route/rest.rs names `RigidBody` of the three-point frame",
            "route/rigid/heading.rs names `OnBase` of the base",
            "route/rigid/heading.rs names `body::` of the base",
            "route/body/mod.rs names `faces_of` of the three-point frame",
        ]
    );
}
