//! The command line against hostile input: a few hundred cases drawn from a fixed
//! seed over perturbed scenes (`scenes/*.toml` with values huge, tiny, negative, subnormal,
//! non-finite, of the wrong type, whole numbers beyond 2⁶³, keys missing or doubled), malformed
//! surfaces (OBJ), records (CSV, `.AT2`, columns) and grids (`roots --grid`), and flags
//! (`--set`, `--vary`, `--dist`, `--samples`, `--seed`), each run by the built binary in a
//! folder of its own. A case fails on a panic, a hang (killed after [`CASE_TIMEOUT`]), an exit
//! code other than 0, 1 or 2, an error that is not one line a fault (`slideroute: …`) or that
//! names neither the key, the flag, nor the file and line, a fault placed at a known line of a
//! file not reported at that line, and any NaN or infinity written in an output file (CSV, JSON,
//! SVG, HTML) of a run that exited 0.
//!
//! `SLIDEROUTE_HOSTILE_SEED` and `SLIDEROUTE_HOSTILE_CASES` draw other or more cases
//! (`SLIDEROUTE_HOSTILE_CASES=2000 cargo test --release --test integration hostile`);
//! `SLIDEROUTE_HOSTILE_LOG=FILE` writes every case's exit code and standard error there.
#![cfg(feature = "cli")]

use std::io::Write as _;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::sync::Mutex;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::time::{Duration, Instant};

/// The seed the cases are drawn from, unless `SLIDEROUTE_HOSTILE_SEED` says.
const SEED: u64 = 0x5EED_0032;
/// How many cases, unless `SLIDEROUTE_HOSTILE_CASES` says.
const CASES: usize = 320;
/// A case still running after this is a hang (a route is 0.2 s of simulated time, a sweep or a
/// probabilistic analysis at most a few of them: well under a second each in a debug build).
const CASE_TIMEOUT: Duration = Duration::from_secs(20);

/// SplitMix64: the cases depend on the seed alone, whatever the platform.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// A number in 0..n.
    fn below(&mut self, n: usize) -> usize {
        (self.next() % n as u64) as usize
    }

    fn pick<'a, T>(&mut self, items: &'a [T]) -> &'a T {
        &items[self.below(items.len())]
    }

    fn chance(&mut self, percent: usize) -> bool {
        self.below(100) < percent
    }
}

/// One run of the binary and what its result must be.
#[derive(Default)]
struct Case {
    /// What the case is, for the report.
    what: String,
    /// The arguments (paths relative to the case's folder, where it runs).
    args: Vec<String>,
    /// The files written into the case's folder first.
    files: Vec<(String, Vec<u8>)>,
    /// A fault placed at a known line: the run must exit 2 naming this file and line.
    fails_at: Option<(String, usize)>,
    /// A value wrong by itself (not finite, of another type, too large a whole number): if the
    /// run fails, an error names this key, at this line of the scene when it gives a line.
    names_key: Option<(String, usize)>,
    /// A value that cannot be taken: the run must exit 2.
    must_fail: bool,
    /// Files whose every fault must give a line (but for the faults of a file as a whole).
    line_files: Vec<String>,
    /// Text the input gave as a string (`name = "nan"`), which an output may quote back.
    quoted: Option<String>,
}

impl Case {
    fn new(what: impl Into<String>, args: &[&str]) -> Case {
        Case {
            what: what.into(),
            args: args.iter().map(|s| s.to_string()).collect(),
            ..Case::default()
        }
    }

    fn file(mut self, name: &str, bytes: impl Into<Vec<u8>>) -> Case {
        self.files.push((name.to_string(), bytes.into()));
        self
    }
}

/// What a run gave.
struct Ran {
    code: Option<i32>,
    stderr: String,
    seconds: f64,
}

fn scene_text(name: &str) -> String {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("scenes")
        .join(name);
    std::fs::read_to_string(path).expect("scene")
}

fn scene_bytes(name: &str) -> Vec<u8> {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("scenes")
        .join(name);
    std::fs::read(path).expect("scene file")
}

/// The files a scene of `scenes/` names, to be written beside it.
fn companions(scene: &str) -> Vec<(String, Vec<u8>)> {
    match scene {
        "valley.toml" => vec![("valley.obj".into(), scene_bytes("valley.obj"))],
        "shaken.toml" => vec![("shaken-motion.csv".into(), scene_bytes("shaken-motion.csv"))],
        _ => Vec::new(),
    }
}

const SCENES: [&str; 18] = [
    "paper-like.toml",
    "creeping-pivot.toml",
    "dam.toml",
    "four-faces.toml",
    "kicked.toml",
    "monolith-earthquake.toml",
    "monolith.toml",
    "paper-like-faces.toml",
    "paper-like-uncertain.toml",
    "pivot-escape.toml",
    "pivot-held.toml",
    "pivot-released.toml",
    "ramp-faces.toml",
    "shaken.toml",
    "shallow.toml",
    "strong-turning.toml",
    "turning.toml",
    "valley.toml",
];

/// The kind of a TOML value, as far as a scene's keys care.
#[derive(Clone, Copy, PartialEq, Debug)]
enum Kind {
    Number,
    Text,
    Bool,
    Array,
    Table,
    Other,
}

fn kind_of(value: &str) -> Kind {
    match value.as_bytes().first() {
        Some(b'"' | b'\'') => Kind::Text,
        Some(b'[') => Kind::Array,
        Some(b'{') => Kind::Table,
        _ if value == "true" || value == "false" => Kind::Bool,
        _ if value.parse::<f64>().is_ok() || ["inf", "nan"].iter().any(|w| value.contains(w)) => {
            Kind::Number
        }
        _ => Kind::Other,
    }
}

/// A hostile value, its kind, and whether it is wrong whatever the key (not finite, a whole
/// number beyond 2⁶³).
struct Hostile {
    text: &'static str,
    kind: Kind,
    wrong: bool,
}

const fn h(text: &'static str, kind: Kind, wrong: bool) -> Hostile {
    Hostile { text, kind, wrong }
}

/// Values no scene author means. None is a plausible long route: a large positive time limit
/// or a small positive increment would make a slow case, not a hostile one.
const HOSTILE: [Hostile; 37] = [
    h("1e300", Kind::Number, false),
    h("1.7976931348623157e308", Kind::Number, false),
    h("-1.7976931348623157e308", Kind::Number, false),
    h("1e30", Kind::Number, false),
    h("-1e30", Kind::Number, false),
    h("1e-300", Kind::Number, false),
    h("-1e-300", Kind::Number, false),
    h("5e-324", Kind::Number, false),
    h("2.2250738585072014e-308", Kind::Number, false),
    h("1e-30", Kind::Number, false),
    h("-1", Kind::Number, false),
    h("-0.0", Kind::Number, false),
    h("0", Kind::Number, false),
    h("0.0", Kind::Number, false),
    h("9223372036854775807", Kind::Number, false),
    h("-9223372036854775808", Kind::Number, false),
    h("inf", Kind::Number, true),
    h("-inf", Kind::Number, true),
    h("+inf", Kind::Number, true),
    h("nan", Kind::Number, true),
    h("-nan", Kind::Number, true),
    h("9223372036854775808", Kind::Number, true),
    h("18446744073709551616", Kind::Number, true),
    h("-9223372036854775809", Kind::Number, true),
    h("99999999999999999999999999999", Kind::Number, true),
    h("\"nan\"", Kind::Text, false),
    h("\"NaN\"", Kind::Text, false),
    h("\"inf\"", Kind::Text, false),
    h("\"1e400\"", Kind::Text, false),
    h("\"\"", Kind::Text, false),
    h("\"0.4\"", Kind::Text, false),
    h("true", Kind::Bool, false),
    h("[1, 2]", Kind::Array, false),
    h("[]", Kind::Array, false),
    h("{ a = 1 }", Kind::Table, false),
    h("1979-05-27T07:32:00Z", Kind::Other, false),
    h(
        "[[1.0, 2.0], [3.0, \"x\"], [nan, 1e308]]",
        Kind::Array,
        false,
    ),
];

/// A line `key = value  # comment` of a scene: its number (from 1), the dotted key a message
/// names (None in a list of tables or for a quoted key), the value's byte range.
struct KeyLine {
    number: usize,
    key: Option<String>,
    value: std::ops::Range<usize>,
    line: usize,
}

/// The one-line `key = value` entries of a scene.
fn key_lines(text: &str) -> Vec<KeyLine> {
    // The table the lines are in: none (the top), a table by its name, or an item of a list of
    // tables (whose keys a message names by the item, `case[1].kh`: not known here).
    let mut table: Option<Option<String>> = None;
    let mut out = Vec::new();
    for (k, line) in text.lines().enumerate() {
        let trimmed = line.trim_start();
        if trimmed.starts_with("[[") {
            table = Some(None);
            continue;
        }
        if let Some(rest) = trimmed.strip_prefix('[') {
            table = Some(rest.split(']').next().map(str::to_string));
            continue;
        }
        if trimmed.starts_with('#') || !trimmed.contains('=') {
            continue;
        }
        let eq = line.find('=').unwrap();
        let key = line[..eq].trim();
        let after = &line[eq + 1..];
        let start = eq + 1 + (after.len() - after.trim_start().len());
        let rest = &line[start..];
        // The value: up to a comment (no scene's one-line value has a `#` inside).
        let end = start + rest.find('#').unwrap_or(rest.len());
        let end = start + line[start..end].trim_end().len();
        let value = &line[start..end];
        let closed = |open: char, close: char| {
            value.chars().filter(|c| *c == open).count()
                == value.chars().filter(|c| *c == close).count()
        };
        if value.is_empty() || !closed('[', ']') || !closed('{', '}') {
            continue;
        }
        let plain = key.chars().all(|c| c.is_ascii_alphanumeric() || c == '_');
        let key = match (&table, plain) {
            (_, false) | (Some(None), _) => None,
            (None, true) => Some(key.to_string()),
            (Some(Some(t)), true) => Some(format!("{t}.{key}")),
        };
        out.push(KeyLine {
            number: k + 1,
            key,
            value: start..end,
            line: k,
        });
    }
    out
}

/// The flags that keep a route short and quiet (with `pictures`, the pictures and the 3-D
/// files are written, to look in them too).
fn short_run(args: &mut Vec<String>, pictures: bool, set_time: bool) {
    if set_time {
        args.extend(["--set".into(), "solver.t_end_s=0.2".into()]);
    }
    args.push("--quiet".into());
    if !pictures {
        args.extend(["--no-plots".into(), "--no-3d".into()]);
    }
}

/// A scene of `scenes/` with one value, line or header changed.
fn scene_case(rng: &mut Rng) -> Case {
    let name = *rng.pick(&SCENES);
    let text = scene_text(name);
    let lines: Vec<&str> = text.lines().collect();
    let keys = key_lines(&text);
    let kl = rng.pick(&keys);
    let mut new_lines: Vec<String> = lines.iter().map(|s| s.to_string()).collect();
    let what;
    let mut names_key = None;
    let mut must_fail = false;
    let mut quoted = None;
    let mut time_key = kl.key.as_deref() == Some("solver.t_end_s");
    match rng.below(10) {
        0 => {
            // A key missing.
            what = format!("{name}: line {} removed", kl.number);
            new_lines[kl.line] = String::new();
        }
        1 => {
            // A key given twice.
            what = format!("{name}: line {} twice", kl.number);
            new_lines.insert(kl.line + 1, lines[kl.line].to_string());
            must_fail = true;
        }
        2 => {
            // A key no scene has, or a header no scene has.
            if rng.chance(50) {
                what = format!("{name}: unknown key after line {}", kl.number);
                new_lines.insert(kl.line + 1, "zz_unknown = 1".into());
            } else {
                let headers: Vec<usize> = (0..lines.len())
                    .filter(|&k| lines[k].starts_with('['))
                    .collect();
                let k = *rng.pick(&headers);
                what = format!("{name}: header of line {} renamed", k + 1);
                new_lines[k] = "[zz_unknown]".into();
                time_key |= lines[k].starts_with("[solver]");
            }
            must_fail = true;
        }
        3..=5
            if lines[kl.line][kl.value.clone()].parse::<f64>().is_ok()
                && !kl.key.as_deref().is_some_and(|k| k.starts_with("solver.")) =>
        {
            // A number far from its own, often still a scene that runs: the route is where
            // a non-number would come from (the time and the increment are left alone, for a
            // short route).
            let line = lines[kl.line];
            let old = &line[kl.value.clone()];
            let factor = *rng.pick(&[1e-12, 1e-6, 1e-3, 0.5, -1.0, 2.0, 1e3, 1e6, 1e12]);
            let new = format!("{:?}", old.parse::<f64>().unwrap() * factor);
            what = format!("{name}: line {} `{old}` → `{new}`", kl.number);
            new_lines[kl.line] = format!(
                "{}{}{}",
                &line[..kl.value.start],
                new,
                &line[kl.value.end..]
            );
        }
        _ => {
            let v = rng.pick(&HOSTILE);
            let line = lines[kl.line];
            let old = &line[kl.value.clone()];
            what = format!("{name}: line {} `{old}` → `{}`", kl.number, v.text);
            new_lines[kl.line] = format!(
                "{}{}{}",
                &line[..kl.value.start],
                v.text,
                &line[kl.value.end..]
            );
            if v.kind == Kind::Text {
                quoted = Some(v.text.to_string());
            }
            let differs = kind_of(old) != v.kind && kind_of(old) != Kind::Other;
            if v.wrong || differs {
                must_fail = true;
                names_key = kl.key.clone().map(|k| (k, kl.number));
            }
        }
    }
    let mut body = new_lines.join("\n");
    body.push('\n');
    let mut case = Case {
        what,
        must_fail,
        names_key,
        quoted,
        ..Case::default()
    };
    let command = rng.below(10);
    case.args = match command {
        0..=5 => {
            let mut a: Vec<String> = ["run", "--scene", "s.toml", "--out", "out"]
                .map(String::from)
                .to_vec();
            short_run(&mut a, rng.chance(15), !time_key);
            a
        }
        6..=8 => ["scene", "--check", "s.toml"].map(String::from).to_vec(),
        _ => {
            let mut a: Vec<String> = ["check", "--scene", "s.toml", "--out", "out"]
                .map(String::from)
                .to_vec();
            short_run(&mut a, false, !time_key);
            a
        }
    };
    if time_key && case.args[0] != "scene" {
        // The time limit perturbed: hostile values make no long route, but one left as the
        // file had it (a header renamed, a line doubled) or removed (the default, 20 s) would.
        let value = new_lines
            .iter()
            .find(|l| l.trim_start().starts_with("t_end_s"))
            .and_then(|l| l.split('=').nth(1))
            .and_then(|v| v.split('#').next())
            .map(str::trim)
            .map(|v| v.parse::<f64>().unwrap_or(0.0));
        if value.is_none_or(|t| t > 0.5 && t.is_finite() && t < 1e5) {
            case.args
                .extend(["--set".into(), "solver.t_end_s=0.2".into()]);
        }
    }
    case.files.push(("s.toml".into(), body.into_bytes()));
    case.files.extend(companions(name));
    case
}

/// Blank lines, comments and carriage returns through `lines`, none before `keep` (a header):
/// the numbers of the lines as they then are (`at[k]` the new number of old line k, from 1).
fn noisy(rng: &mut Rng, lines: &[String], keep: usize, comment: &str) -> (Vec<String>, Vec<usize>) {
    let crlf = rng.chance(25);
    let mut out = Vec::new();
    let mut at = Vec::new();
    for (k, line) in lines.iter().enumerate() {
        if k >= keep && rng.chance(8) {
            for _ in 0..=rng.below(3) {
                out.push(if rng.chance(30) && !comment.is_empty() {
                    comment.to_string()
                } else if rng.chance(30) {
                    "   ".to_string()
                } else {
                    String::new()
                });
            }
        }
        at.push(out.len() + 1);
        out.push(line.clone());
    }
    if crlf {
        for l in &mut out {
            l.push('\r');
        }
    }
    (out, at)
}

fn joined(lines: &[String]) -> Vec<u8> {
    let mut s = lines.join("\n");
    s.push('\n');
    s.into_bytes()
}

/// The valley scene on a malformed copy of its surface.
fn surface_case(rng: &mut Rng) -> Case {
    let obj: Vec<String> = scene_text("valley.obj").lines().map(String::from).collect();
    let vertices: Vec<usize> = (0..obj.len())
        .filter(|&k| obj[k].starts_with("v "))
        .collect();
    let faces: Vec<usize> = (0..obj.len())
        .filter(|&k| obj[k].starts_with("f "))
        .collect();
    let mut lines = obj.clone();
    let mut fault: Option<usize> = None;
    let what;
    match rng.below(12) {
        0 => {
            let k = *rng.pick(&faces);
            let bad = *rng.pick(&["99999", "0", "-99999", "x", "1.5", "99999999999999999999"]);
            lines[k] = format!("f 1 2 {bad}");
            what = format!("face of line {} names `{bad}`", k + 1);
            fault = Some(k);
        }
        1 => {
            lines.insert(2, "f 1 2 3".into());
            what = "a face before the vertices".into();
            fault = Some(2);
        }
        2 | 3 => {
            let k = *rng.pick(&vertices);
            let bad = *rng.pick(&["inf", "nan", "-inf", "1e999", "NaN", "-nan"]);
            lines[k] = format!("v 1.0 {bad} 2.0");
            what = format!("vertex of line {} has `{bad}`", k + 1);
            fault = Some(k);
        }
        4 => {
            let k = *rng.pick(&vertices);
            lines[k] = ["v 1.0 2.0", "v", "v 1 2 3 4 5", "v 1 2 3 0", "v 1 two 3"][rng.below(5)]
                .to_string();
            what = format!("vertex of line {} malformed: {}", k + 1, lines[k]);
            fault = Some(k);
        }
        5 => {
            let k = *rng.pick(&faces);
            let first = lines[k]
                .split_whitespace()
                .nth(1)
                .unwrap_or("1")
                .to_string();
            lines[k] = format!("f {first} {first} {first}");
            what = format!("face of line {} with one corner thrice", k + 1);
            fault = Some(k);
        }
        6 => {
            let k = *rng.pick(&faces);
            lines[k] = "f 1 2".into();
            what = format!("face of line {} with two corners", k + 1);
            fault = Some(k);
        }
        7 => {
            lines.clear();
            what = "an empty surface".into();
        }
        8 => {
            lines.retain(|l| !l.starts_with("f "));
            what = "vertices and no faces".into();
        }
        9 => {
            let k = *rng.pick(&vertices);
            lines[k] = "v 1e308 -1e308 1e308".into();
            what = format!("vertex of line {} huge", k + 1);
        }
        10 => {
            let cut = rng.below(lines.len());
            lines.truncate(cut);
            what = format!("cut after line {cut}");
        }
        _ => {
            what = "the surface as it is".into();
        }
    }
    let (mut noisy_lines, at) = noisy(rng, &lines, 0, "# a comment");
    if rng.chance(10) && !noisy_lines.is_empty() {
        noisy_lines[0].insert(0, '\u{feff}');
    }
    let mut case = if rng.chance(80) {
        Case::new(
            format!("surface: {what}"),
            &["scene", "--check", "valley.toml"],
        )
    } else {
        let mut c = Case::new(
            format!("surface: {what}"),
            &["run", "--scene", "valley.toml", "--out", "out"],
        );
        short_run(&mut c.args, false, true);
        c
    };
    case.fails_at = fault.map(|k| ("valley.obj".to_string(), at[k]));
    case.line_files = vec!["valley.obj".into()];
    case.file("valley.toml", scene_bytes("valley.toml"))
        .file("valley.obj", joined(&noisy_lines))
}

/// The shaken scene under a malformed copy of its record, or under one component of another
/// form (`.AT2`, columns).
fn record_case(rng: &mut Rng) -> Case {
    let scene = scene_text("shaken.toml");
    let (file, lines, fault, what, scene, keep) = if rng.chance(60) {
        // The four-column record.
        let mut lines: Vec<String> = scene_text("shaken-motion.csv")
            .lines()
            .map(String::from)
            .collect();
        let rows = lines.len();
        let k = 1 + rng.below(rows - 1);
        let mut fault = Some(k);
        let what;
        match rng.below(9) {
            0 => {
                let cell = *rng.pick(&["nan", "inf", "-inf", "1e999", "NaN", "x", "", "\"\""]);
                let mut cells: Vec<String> = lines[k].split(',').map(String::from).collect();
                let c = rng.below(4);
                cells[c] = cell.to_string();
                lines[k] = cells.join(",");
                what = format!("line {}: `{cell}` in column {c}", k + 1);
            }
            1 => {
                lines[k] = lines[k].split_once(',').map_or("", |x| x.1).to_string();
                what = format!("line {}: three cells", k + 1);
            }
            2 => {
                lines[k].push_str(",0.1");
                what = format!("line {}: five cells", k + 1);
            }
            3 if k > 1 => {
                let before = lines[k - 1].split(',').next().unwrap().to_string();
                let mut cells: Vec<String> = lines[k].split(',').map(String::from).collect();
                cells[0] = before;
                lines[k] = cells.join(",");
                what = format!("line {}: the time of the line before", k + 1);
            }
            4 => {
                let mut cells: Vec<String> = lines[k].split(',').map(String::from).collect();
                cells[1] = "12.5".into();
                lines[k] = cells.join(",");
                what = format!("line {}: 12.5 g", k + 1);
            }
            5 => {
                let header = *rng.pick(&["t,ax,ay,az", "t_s,ax_g,ay_g", "T_S,AX_G,AY_G,AZ_G", "x"]);
                lines[0] = header.to_string();
                what = format!("header `{header}`");
                fault = Some(0);
            }
            6 => {
                lines.truncate(rng.below(3));
                what = format!("{} lines", lines.len());
                fault = None;
            }
            7 => {
                lines = every_cell_quoted(&lines, " , ");
                what = "every cell quoted".into();
                fault = None;
            }
            _ => {
                what = "the record as it is".into();
                fault = None;
            }
        }
        ("shaken-motion.csv", lines, fault, what, scene.clone(), 1)
    } else if rng.chance(50) {
        // A PEER `.AT2` component along X.
        let mut lines: Vec<String> = vec![
            "PEER NGA STRONG MOTION DATABASE RECORD".into(),
            "Somewhere, 1/1/2000, station, 000".into(),
            "ACCELERATION TIME SERIES IN UNITS OF G".into(),
            "NPTS=   40, DT=   .0100 SEC".into(),
        ];
        for k in 0..8 {
            lines.push(
                (0..5)
                    .map(|j| format!("{:.7E}", 0.05 * ((k * 5 + j) as f64 * 0.7).sin()))
                    .collect::<Vec<_>>()
                    .join("  "),
            );
        }
        let k = 4 + rng.below(8);
        let mut fault = Some(k);
        let what;
        match rng.below(6) {
            0 => {
                let bad = *rng.pick(&["nan", "inf", "1e999", "x", "-NaN"]);
                lines[k] = format!("0.1 {bad} 0.2");
                what = format!("line {}: `{bad}`", k + 1);
            }
            1 => {
                let l4 = *rng.pick(&[
                    "NPTS=   41, DT=   .0100 SEC",
                    "NPTS=   40, DT=   0 SEC",
                    "NPTS=   40, DT=   -0.01 SEC",
                    "NPTS=   40, DT=   nan SEC",
                    "NPTS=   -4, DT=   .01 SEC",
                    "NPTS= 1e300, DT= .01 SEC",
                    "NPTS=   40, DT=   1e-320 SEC",
                ]);
                lines[3] = l4.to_string();
                what = format!("line 4 `{l4}`");
                fault = if l4.contains("1e-320") { None } else { Some(3) };
            }
            2 => {
                lines[2] = "VELOCITY TIME SERIES IN UNITS OF CM/SEC".into();
                what = "a velocity".into();
                fault = Some(2);
            }
            3 => {
                lines.truncate(rng.below(5));
                what = format!("{} lines", lines.len());
                fault = None;
            }
            _ => {
                what = "the component as it is".into();
                fault = None;
            }
        }
        let scene = scene.replace("record = \"shaken-motion.csv\"", "record_x = \"x.AT2\"");
        ("x.AT2", lines, fault, what, scene, 4)
    } else {
        // Two columns, time and acceleration, along Z.
        let mut lines: Vec<String> = vec!["time_s, acc_g".into()];
        for k in 0..30 {
            lines.push(format!(
                "{:.3}, {:.5}",
                k as f64 * 0.01,
                0.1 * (k as f64).sin()
            ));
        }
        let k = 2 + rng.below(29);
        let mut fault = Some(k);
        let what;
        match rng.below(5) {
            0 => {
                lines[k] = format!("{:.3}, 0.1", (k - 2) as f64 * 0.01);
                what = format!("line {}: a time going back", k + 1);
            }
            1 => {
                let bad = *rng.pick(&["nan", "inf", "x", "1e999"]);
                lines[k] = format!("0.5, {bad}");
                what = format!("line {}: `{bad}`", k + 1);
            }
            2 => {
                lines[k] = "0.5, 0.1, 0.2".into();
                what = format!("line {}: three numbers", k + 1);
            }
            _ => {
                what = "the component as it is".into();
                fault = None;
            }
        }
        let scene = scene.replace("record = \"shaken-motion.csv\"", "record_z = \"z.csv\"");
        ("z.csv", lines, fault, what, scene, 1)
    };
    let (noisy_lines, at) = noisy(rng, &lines, keep, "");
    let mut case = if rng.chance(75) {
        Case::new(
            format!("record {file}: {what}"),
            &["scene", "--check", "s.toml"],
        )
    } else {
        let mut c = Case::new(
            format!("record {file}: {what}"),
            &["run", "--scene", "s.toml", "--out", "out"],
        );
        short_run(&mut c.args, false, true);
        c
    };
    case.fails_at = fault.map(|k| (file.to_string(), at[k]));
    case.line_files = vec![file.to_string()];
    case.file("s.toml", scene).file(file, joined(&noisy_lines))
}

/// `roots --grid` on a malformed grid.
fn grid_case(rng: &mut Rng) -> Case {
    let mut lines: Vec<String> = vec![
        "x_m,z_m,theta_deg".into(),
        "0.1,0,1".into(),
        "0.2,0.1,2".into(),
        "0.3,-0.1,-1".into(),
    ];
    let k = 1 + rng.below(3);
    let mut fault = Some(k);
    let what;
    match rng.below(7) {
        0 => {
            let bad = *rng.pick(&["nan", "inf", "-inf", "x", "", "1e999", "\"\""]);
            lines[k] = format!("0.1,{bad},1");
            what = format!("line {}: `{bad}`", k + 1);
        }
        1 => {
            lines[k] = "0.1,0".into();
            what = format!("line {}: two cells", k + 1);
        }
        2 => {
            lines[k] = "0.1,0,1,4".into();
            what = format!("line {}: four cells", k + 1);
        }
        3 => {
            lines[0] = rng
                .pick(&["x,z,theta", "x_m,z_m", "x_m,z_m,theta_deg,w"])
                .to_string();
            what = format!("header `{}`", lines[0]);
            fault = Some(0);
        }
        4 => {
            lines.truncate(rng.below(2));
            what = format!("{} lines", lines.len());
            fault = None;
        }
        5 => {
            lines = every_cell_quoted(&lines, ",");
            what = "every cell quoted".into();
            fault = None;
        }
        _ => {
            what = "the grid as it is".into();
            fault = None;
        }
    }
    let (noisy_lines, at) = noisy(rng, &lines, 1, "");
    let mut case = Case::new(
        format!("grid: {what}"),
        &["roots", "--grid", "g.csv", "--out", "o.csv"],
    );
    case.fails_at = fault.map(|k| ("g.csv".to_string(), at[k]));
    case.line_files = vec!["g.csv".into()];
    case.file("g.csv", joined(&noisy_lines))
}

/// Keys of the scene a flag may name.
const KEYS: [&str; 11] = [
    "friction.mu_k",
    "foundation.xi_deg",
    "loads.eccentricity_m",
    "block.mass_kg",
    "solver.dt_s",
    "solver.t_end_s",
    "solver.stride",
    "solver.mode",
    "solver.dynamics",
    "frame.l1x",
    "loads.hydraulic_force_n",
];

/// Keys no scene has, or not written as keys are.
const BAD_KEYS: [&str; 9] = [
    "name",
    "friction.nope",
    "nosection.key",
    "friction",
    "anchor[3].x_m",
    "friction.mu_k.deeper",
    ".mu_k",
    "friction.",
    "FRICTION.MU_K",
];

/// A value a flag may give (never a long route: no time limit over a second, no small
/// positive increment).
fn flag_value(rng: &mut Rng) -> String {
    if rng.chance(70) {
        rng.pick(&HOSTILE).text.to_string()
    } else {
        rng.pick(&[
            "0.3",
            "paper",
            "rigid-body",
            "small-angle",
            "abc",
            "1,2",
            "\"x",
            "=",
        ])
        .to_string()
    }
}

/// A key for a flag: mostly the scene's, sometimes one it does not have.
fn flag_key(rng: &mut Rng) -> &'static str {
    let keys: &[&'static str] = if rng.chance(20) { &BAD_KEYS } else { &KEYS };
    let key: &&'static str = rng.pick(keys);
    key
}

/// The command line: `--set`, `--vary`, `--dist`, `--samples`, `--seed`, one of them hostile
/// and the others as a user would give them, so that most cases run.
fn flag_case(rng: &mut Rng) -> Case {
    let mut case = match rng.below(5) {
        0 => {
            let key = flag_key(rng);
            let mut v = flag_value(rng);
            if key == "solver.t_end_s" && v.parse::<f64>().is_ok_and(|t| t > 0.5) {
                v = "0.5".into();
            }
            let set = if rng.chance(10) {
                rng.pick(&["", "=", "friction.mu_k", "=0.3", "friction.mu_k="])
                    .to_string()
            } else {
                format!("{key}={v}")
            };
            let mut c = Case::new(
                format!("--set {set}"),
                &[
                    "run",
                    "--out",
                    "out",
                    "--set",
                    "solver.t_end_s=0.2",
                    "--set",
                ],
            );
            if v.starts_with('"') {
                c.quoted = Some(v.clone());
            }
            c.args.push(set);
            short_run(&mut c.args, rng.chance(10), false);
            c
        }
        1 => {
            // Hostile values of a key that takes numbers, or good values of a hostile key.
            let (key, values) = if rng.chance(75) {
                let key = *rng.pick(&[
                    "friction.mu_k",
                    "foundation.xi_deg",
                    "loads.eccentricity_m",
                    "block.mass_kg",
                    "frame.l1x",
                    "solver.stride",
                    "solver.dt_s",
                ]);
                let values = *rng.pick(&[
                    "0.2:0.6:3",
                    "0.2:0.6:0",
                    "0.2:0.6:-1",
                    "0.2:0.6:2.5",
                    "0.2:0.6:18446744073709551616",
                    "0.2:0.6:99999999999",
                    ":0.6:3",
                    "nan:1:2",
                    "0:inf:2",
                    "1e308:-1e308:3",
                    "-1.7976931348623157e308:1.7976931348623157e308:4",
                    "0.6:0.2:2",
                    "0.3,,0.4",
                    ",",
                    "",
                    "0.3",
                    "1e400",
                    "paper,rigid-body",
                    "0.3:0.4:2:5",
                    "5e-324,-5e-324",
                    "9223372036854775808",
                    "1,2,3",
                    "-1e-300,0,1e300",
                ]);
                (key, values.to_string())
            } else {
                (flag_key(rng), "0.3,0.4".to_string())
            };
            let vary = format!("{key}={values}");
            let mut c = Case::new(
                format!("--vary {vary}"),
                &[
                    "sweep",
                    "--out",
                    "out",
                    "--set",
                    "solver.t_end_s=0.2",
                    "--vary",
                ],
            );
            c.args.push(vary);
            if rng.chance(20) {
                c.args
                    .extend(["--vary".into(), "foundation.xi_deg=19,21".into()]);
            }
            short_run(&mut c.args, rng.chance(15), false);
            c
        }
        k => {
            let (mut dist, mut samples, mut seed) = (
                "friction.mu_k=normal:0.4:0.05".to_string(),
                rng.pick(&["2", "3"]).to_string(),
                "1".to_string(),
            );
            match k {
                2 => {
                    let form = *rng.pick(&[
                        "normal:0.4:-1",
                        "normal:nan:1",
                        "normal:0.4",
                        "normal:0.4:0.05:1",
                        "uniform:0.5:0.3",
                        "uniform:-1e308:1e308",
                        "uniform:0.3:inf",
                        "lognormal:0.4:1e300",
                        "lognormal:-1:0.1",
                        "lognormal:1e200:1e200",
                        "lognormal:0.4:5e-324",
                        "triangular:0:2:1",
                        "triangular:0.3:0.4:0.5",
                        "triangular:0.4:0.4:0.4",
                        "truncnormal:0.4:0.1:0.5:0.3",
                        "truncnormal:0.4:0.1:0.3:0.5",
                        "truncnormal:0.4:1e-300:0.3:0.5",
                        "truncnormal:0.4:0.1:10:11",
                        "weird:1:2",
                        "",
                        "normal:::",
                        "normal:5e-324:5e-324",
                        "uniform:9223372036854775808:9223372036854775809",
                        "uniform:-1e-300:1e-300",
                    ]);
                    let key = if rng.chance(70) {
                        "friction.mu_k"
                    } else {
                        flag_key(rng)
                    };
                    dist = format!("{key}={form}");
                }
                3 => {
                    samples = rng
                        .pick(&[
                            "0",
                            "-5",
                            "1e3",
                            "ten",
                            "",
                            "18446744073709551616",
                            "10000001",
                            "99999999999999999999",
                            "2.5",
                            "-0",
                            "+3",
                            "1",
                        ])
                        .to_string();
                }
                _ => {
                    seed = rng
                        .pick(&[
                            "0",
                            "18446744073709551615",
                            "-1",
                            "18446744073709551616",
                            "1.5",
                            "x",
                            "",
                            "-0",
                        ])
                        .to_string();
                }
            }
            let mut c = Case::new(
                format!("--dist {dist} --samples {samples} --seed {seed}"),
                &[
                    "probabilistic",
                    "--out",
                    "out",
                    "--set",
                    "solver.t_end_s=0.2",
                    "--dist",
                ],
            );
            c.args.push(dist);
            c.args
                .extend(["--samples".into(), samples, "--seed".into(), seed]);
            if rng.chance(15) {
                c.args.extend([
                    "--scene".into(),
                    "s.toml".into(),
                    "--dist".into(),
                    "foundation.zeta_deg=uniform:22:28".into(),
                ]);
                c = c.file("s.toml", scene_bytes("paper-like-uncertain.toml"));
            }
            short_run(&mut c.args, rng.chance(15), false);
            c
        }
    };
    case.what = format!("flags: {}", case.what);
    case
}

/// The cases of `seed`, `n` of them: about 40 % scenes, 12 % surfaces, 15 % records, 8 % grids,
/// 25 % flags.
fn cases(seed: u64, n: usize) -> Vec<Case> {
    let mut rng = Rng(seed);
    (0..n)
        .map(|_| match rng.below(100) {
            0..=39 => scene_case(&mut rng),
            40..=51 => surface_case(&mut rng),
            52..=66 => record_case(&mut rng),
            67..=74 => grid_case(&mut rng),
            _ => flag_case(&mut rng),
        })
        .collect()
}

/// Runs `case` in `dir`, killed after [`CASE_TIMEOUT`].
fn run_case(case: &Case, dir: &Path) -> Result<Ran, String> {
    let _ = std::fs::remove_dir_all(dir);
    std::fs::create_dir_all(dir).unwrap();
    for (name, bytes) in &case.files {
        std::fs::write(dir.join(name), bytes).unwrap();
    }
    let stdout = std::fs::File::create(dir.join(".stdout")).unwrap();
    let stderr = std::fs::File::create(dir.join(".stderr")).unwrap();
    let start = Instant::now();
    let mut child = Command::new(env!("CARGO_BIN_EXE_slideroute"))
        .args(&case.args)
        .current_dir(dir)
        .env_remove("RUST_BACKTRACE")
        .stdin(Stdio::null())
        .stdout(stdout)
        .stderr(stderr)
        .spawn()
        .expect("run slideroute");
    let status = loop {
        if let Some(status) = child.try_wait().unwrap() {
            break status;
        }
        if start.elapsed() > CASE_TIMEOUT {
            let _ = child.kill();
            let _ = child.wait();
            return Err(format!(
                "a hang: still running after {} s",
                CASE_TIMEOUT.as_secs()
            ));
        }
        std::thread::sleep(Duration::from_millis(5));
    };
    Ok(Ran {
        code: status.code(),
        stderr: String::from_utf8_lossy(&std::fs::read(dir.join(".stderr")).unwrap()).into_owned(),
        seconds: start.elapsed().as_secs_f64(),
    })
}

/// Whether `text` has `line N` (N whole, not the start of a longer number).
fn has_line(text: &str, n: usize) -> bool {
    let needle = format!("line {n}");
    text.match_indices(&needle).any(|(at, _)| {
        !text[at + needle.len()..]
            .chars()
            .next()
            .is_some_and(|c| c.is_ascii_digit())
    })
}

/// Whether `text` gives some line number (`line 12`).
fn any_line(text: &str) -> bool {
    text.match_indices("line ").any(|(at, _)| {
        text[at + 5..]
            .chars()
            .next()
            .is_some_and(|c| c.is_ascii_digit())
    })
}

/// A scene error's key: `FILE: KEY: reason`, KEY one word of letters, digits, `_`, `.`, `[]`.
fn leads_with_key(rest: &str) -> bool {
    rest.split_once(": ").is_some_and(|(key, _)| {
        !key.is_empty()
            && key
                .chars()
                .all(|c| c.is_ascii_alphanumeric() || "_.[]".contains(c))
    })
}

/// Faults of a file as a whole, which have no line.
const WHOLE_FILE: [&str; 7] = [
    "is empty",
    "no triangles",
    "at least two samples",
    "give the step",
    "leave out seismic.dt_s",
    "the file has",
    "NPTS",
];

/// What is wrong with how `case` ran (empty: nothing).
fn judge(case: &Case, ran: &Ran, dir: &Path) -> Vec<String> {
    let mut faults = Vec::new();
    let err = &ran.stderr;
    if ran.code == Some(101) || err.contains("panicked") || err.contains("RUST_BACKTRACE") {
        faults.push("a panic".to_string());
    }
    match ran.code {
        Some(0..=2) => {}
        other => faults.push(format!("exit code {other:?}")),
    }
    let lines: Vec<&str> = err
        .lines()
        .filter(|l| !l.starts_with("slideroute: warning: "))
        .collect();
    if ran.code == Some(0) {
        // Standard error may say what was written (`roots --grid`): only its outputs are judged.
        faults.extend(not_numbers(dir, case.quoted.as_deref()));
    } else if ran.code.is_some() {
        faults.extend(message_faults(case, &lines));
    }
    if ran.code != Some(2) && (case.must_fail || case.fails_at.is_some()) && ran.code.is_some() {
        faults.push(format!(
            "exit {:?} where the input cannot be taken (exit 2)",
            ran.code
        ));
    }
    faults
}

/// The faults of a failed run's error lines.
fn message_faults(case: &Case, lines: &[&str]) -> Vec<String> {
    let mut faults = Vec::new();
    // The inputs an error may name: the case's files, and the scene built in.
    let files: Vec<&str> = case
        .files
        .iter()
        .map(|(n, _)| n.as_str())
        .chain(["<embedded default scene>"])
        .collect();
    let flags: Vec<&str> = case
        .args
        .iter()
        .filter(|a| a.starts_with("--"))
        .map(String::as_str)
        .collect();
    // The keys the flags name (`--set KEY=…`, `--vary KEY=…`, `--dist KEY=…`).
    let flag_keys: Vec<&str> = case
        .args
        .windows(2)
        .filter(|w| ["--set", "--vary", "--dist"].contains(&w[0].as_str()))
        .filter_map(|w| w[1].split_once('=').map(|(k, _)| k.trim()))
        .filter(|k| !k.is_empty())
        .collect();
    if lines.is_empty() {
        faults.push("failed with nothing on standard error".into());
    }
    // One line a fault; several only where a scene has several faults, each its own line.
    let scene_faults = lines.iter().all(|l| {
        files.iter().any(|f| {
            l.strip_prefix("slideroute: ")
                .and_then(|r| r.strip_prefix(*f))
                .and_then(|r| r.strip_prefix(": "))
                .is_some_and(leads_with_key)
        })
    });
    if lines.len() > 1 && !scene_faults {
        faults.push(format!("{} lines of error, not one", lines.len()));
    }
    for line in lines {
        let Some(msg) = line.strip_prefix("slideroute: ") else {
            faults.push(format!("an error line not `slideroute: …`: {line:?}"));
            continue;
        };
        let by_flag =
            flags.iter().any(|f| msg.contains(f)) || flag_keys.iter().any(|k| msg.contains(k));
        let by_file = files.iter().any(|f| {
            msg.strip_prefix(*f)
                .and_then(|r| r.strip_prefix(": "))
                .is_some_and(|rest| leads_with_key(rest) || any_line(rest))
        });
        if !by_flag && !by_file {
            faults.push(format!(
                "names neither the key, the flag nor the file and line: {msg:?}"
            ));
        }
        // A fault of a named file gives its line, unless it is the file's as a whole.
        for f in &case.line_files {
            let needle = format!("{f}: ");
            if let Some(at) = msg.find(&needle) {
                let rest = &msg[at + needle.len()..];
                let rest = rest.rsplit_once(" (line ").map_or(rest, |(r, _)| r);
                if !any_line(rest) && !WHOLE_FILE.iter().any(|w| rest.contains(w)) {
                    faults.push(format!("a fault of {f} without its line: {msg:?}"));
                }
            }
        }
    }
    if let Some((file, n)) = &case.fails_at {
        let named = lines.iter().any(|l| {
            l.find(&format!("{file}: "))
                .is_some_and(|at| has_line(&l[at..], *n))
        });
        if !named {
            faults.push(format!("the fault at {file} line {n} is not named there"));
        }
    }
    if let Some((key, n)) = &case.names_key {
        let right = lines.iter().any(|l| {
            l.contains(key.as_str())
                && l.rsplit_once(" (line ")
                    .is_none_or(|(_, at)| at.starts_with(&format!("{n},")))
        });
        if !right {
            faults.push(format!("no error names {key} at line {n}"));
        }
    }
    faults
}

/// Every NaN or infinity written in the output files under `dir` (CSV, JSON, SVG, HTML); the
/// text `quoted` (a string the input gave, with its quotes) is the input's own, passed over.
fn not_numbers(dir: &Path, quoted: Option<&str>) -> Vec<String> {
    let mut faults = Vec::new();
    let mut stack = vec![dir.to_path_buf()];
    while let Some(d) = stack.pop() {
        for entry in std::fs::read_dir(&d).unwrap().flatten() {
            let path = entry.path();
            if path.is_dir() {
                stack.push(path);
                continue;
            }
            let ext = path.extension().and_then(|e| e.to_str()).unwrap_or("");
            let name = path.file_name().unwrap().to_string_lossy();
            // The inputs the case wrote are not outputs.
            if !["csv", "json", "svg", "html"].contains(&ext)
                || (d == dir && ["g.csv", "shaken-motion.csv", "z.csv"].contains(&&*name))
            {
                continue;
            }
            let text = String::from_utf8_lossy(&std::fs::read(&path).unwrap()).into_owned();
            // A name the input gave (`name = "NaN"`) may be written back as it is, anywhere.
            let own = quoted.map(|q| q.trim_matches('"').to_ascii_lowercase());
            let bad = text
                .split(|c: char| !(c.is_ascii_alphanumeric() || "_.+-".contains(c)))
                .map(|t| t.trim_start_matches(['+', '-']).to_ascii_lowercase())
                .find(|t| {
                    ["nan", "inf", "infinity"].contains(&t.as_str()) && Some(t) != own.as_ref()
                });
            if let Some(t) = bad {
                faults.push(format!(
                    "`{t}` in {}",
                    path.strip_prefix(dir).unwrap().display()
                ));
            }
        }
    }
    faults
}

#[test]
fn hostile_scenes_surfaces_records_and_flags_never_panic_hang_or_write_a_non_number() {
    let seed = std::env::var("SLIDEROUTE_HOSTILE_SEED")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(SEED);
    let n = std::env::var("SLIDEROUTE_HOSTILE_CASES")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(CASES);
    let cases = cases(seed, n);
    let root = std::env::temp_dir().join(format!("slideroute-hostile-{}", std::process::id()));
    let next = AtomicUsize::new(0);
    let report: Mutex<Vec<String>> = Mutex::new(Vec::new());
    let slowest: Mutex<(f64, usize)> = Mutex::new((0.0, 0));
    // Exit codes 0, 1, 2 by the kind of case.
    let family = |what: &str| match what.split_once(':').map(|(f, _)| f) {
        Some("surface") => 1,
        Some(f) if f.starts_with("record") => 2,
        Some("grid") => 3,
        Some("flags") => 4,
        _ => 0,
    };
    let exits: Mutex<[[usize; 3]; 5]> = Mutex::new([[0; 3]; 5]);
    // Every case's outcome, one a line, where `SLIDEROUTE_HOSTILE_LOG` names a file.
    let log = std::env::var_os("SLIDEROUTE_HOSTILE_LOG")
        .map(|p| Mutex::new(std::fs::File::create(p).expect("the log file")));
    let threads = std::thread::available_parallelism().map_or(2, |n| n.get().min(4));
    let start = Instant::now();
    std::thread::scope(|s| {
        for _ in 0..threads {
            s.spawn(|| {
                loop {
                    let k = next.fetch_add(1, Ordering::Relaxed);
                    let Some(case) = cases.get(k) else { break };
                    let dir: PathBuf = root.join(k.to_string());
                    let faults = match run_case(case, &dir) {
                        Err(hang) => vec![hang],
                        Ok(ran) => {
                            let mut slow = slowest.lock().unwrap();
                            if ran.seconds > slow.0 {
                                *slow = (ran.seconds, k);
                            }
                            drop(slow);
                            if let Some(c @ 0..=2) = ran.code {
                                exits.lock().unwrap()[family(&case.what)][c as usize] += 1;
                            }
                            if let Some(log) = &log {
                                let _ = writeln!(
                                    log.lock().unwrap(),
                                    "{k}\t{}\t{:?}\t{}\t{}",
                                    case.what,
                                    ran.code,
                                    case.args.join(" "),
                                    ran.stderr.trim_end().replace('\n', " | ")
                                );
                            }
                            let mut f = judge(case, &ran, &dir);
                            if !f.is_empty() {
                                f.push(format!("stderr: {:?}", ran.stderr.trim_end()));
                            }
                            f
                        }
                    };
                    if faults.is_empty() {
                        let _ = std::fs::remove_dir_all(&dir);
                    } else {
                        report.lock().unwrap().push(format!(
                            "case {k} ({}): `slideroute {}` in {}:\n    {}",
                            case.what,
                            case.args.join(" "),
                            dir.display(),
                            faults.join("\n    ")
                        ));
                    }
                }
            });
        }
    });
    let report = report.into_inner().unwrap();
    let (slow, slow_case) = slowest.into_inner().unwrap();
    let by_family = exits.into_inner().unwrap();
    let exits: [usize; 3] = std::array::from_fn(|c| by_family.iter().map(|f| f[c]).sum());
    eprintln!(
        "hostile: {n} cases (seed {seed:#x}) in {:.1} s on {threads} threads, exits 0/1/2: \
         {exits:?} (scenes {:?}, surfaces {:?}, records {:?}, grids {:?}, flags {:?}), slowest \
         case {slow_case} {slow:.2} s",
        start.elapsed().as_secs_f64(),
        by_family[0],
        by_family[1],
        by_family[2],
        by_family[3],
        by_family[4]
    );
    if report.is_empty() {
        let _ = std::fs::remove_dir_all(&root);
    }
    assert!(
        report.is_empty(),
        "{} of {n} hostile cases failed:\n{}",
        report.len(),
        report.join("\n")
    );
    // Some of each outcome: the cases are hostile, not all refused before they run.
    assert!(
        exits[0] >= n / 10 && exits[2] >= n / 5,
        "exits 0/1/2: {exits:?}"
    );
}

#[test]
fn the_hostile_cases_are_those_of_the_seed_and_cover_every_input() {
    let a = cases(SEED, CASES);
    let b = cases(SEED, CASES);
    assert!(
        a.iter()
            .zip(&b)
            .all(|(x, y)| x.args == y.args && x.files == y.files)
    );
    for kind in ["run", "sweep", "probabilistic", "check", "scene", "roots"] {
        assert!(a.iter().any(|c| c.args[0] == kind), "no `{kind}` case");
    }
    for what in ["surface:", "record ", "grid:", "flags:", ".toml:"] {
        assert!(
            a.iter().filter(|c| c.what.contains(what)).count() >= 15,
            "fewer than 15 `{what}` cases"
        );
    }
    // Faults placed at known lines, and values wrong by themselves.
    assert!(a.iter().filter(|c| c.fails_at.is_some()).count() >= 40);
    assert!(a.iter().filter(|c| c.names_key.is_some()).count() >= 20);
}

/// Runs `slideroute args…` in a folder of its own holding `files`, killed after
/// [`CASE_TIMEOUT`]; the folder is left for the caller to read.
fn run_with(name: &str, files: &[(&str, &[u8])], args: &[&str]) -> (Ran, PathBuf) {
    let mut case = Case::new(name, args);
    for (f, bytes) in files {
        case = case.file(f, *bytes);
    }
    let dir =
        std::env::temp_dir().join(format!("slideroute-hostile-{}-{name}", std::process::id()));
    let ran = run_case(&case, &dir).unwrap_or_else(|hang| panic!("{name}: {hang}"));
    assert!(
        !ran.stderr.contains("panicked") && ran.code != Some(101),
        "{}",
        ran.stderr
    );
    (ran, dir)
}

/// The default scene with `from` replaced by `to` (once).
fn default_with(from: &str, to: &str) -> Vec<u8> {
    let text = slideroute::Scene::DEFAULT_TOML;
    assert!(text.contains(from), "{from}");
    text.replacen(from, to, 1).into_bytes()
}

/// The line (from 1) of `scene` that starts with `key`.
fn line_of(scene: &[u8], key: &str) -> usize {
    String::from_utf8_lossy(scene)
        .lines()
        .position(|l| l.starts_with(key))
        .unwrap()
        + 1
}

#[test]
fn a_time_limit_of_inf_in_a_scene_is_the_time_limits_fault_at_its_own_line() {
    // Before: `solver.dt_s: t_end_s / dt_s = inf increments … (line 35, …)`, dt_s's line.
    let scene = default_with("t_end_s = 20.0", "t_end_s = inf");
    let (ran, dir) = run_with(
        "t-end-inf",
        &[("s.toml", &scene)],
        &["scene", "--check", "s.toml"],
    );
    assert_eq!(ran.code, Some(2));
    let want = format!(
        "slideroute: s.toml: solver.t_end_s: must be a finite number, got inf (line {}, column 1)\n",
        line_of(&scene, "t_end_s")
    );
    assert_eq!(ran.stderr, want);
    let _ = std::fs::remove_dir_all(dir);
}

#[test]
fn an_integer_beyond_2_63_in_a_scene_is_named_by_its_key_and_line() {
    // Before: `s.toml: not a table of keys: invalid type: integer … as i128`, no key, no line.
    for big in [
        "18446744073709551616",
        "9223372036854775808",
        "-9223372036854775809",
    ] {
        let scene = default_with("mu_k = 0.40", &format!("mu_k = {big}"));
        let (ran, dir) = run_with(
            "big-integer",
            &[("s.toml", &scene)],
            &["run", "--scene", "s.toml", "--out", "out", "--no-plots"],
        );
        assert_eq!(ran.code, Some(2), "{}", ran.stderr);
        let err = ran.stderr.trim_end();
        assert_eq!(err.lines().count(), 1, "{err}");
        assert!(
            err.starts_with("slideroute: s.toml: friction.mu_k: a whole number of ")
                && err.ends_with(&format!("(line {}, column 8)", line_of(&scene, "mu_k"))),
            "{err}"
        );
        // The number itself, which may be any length, is not echoed.
        assert!(!err.contains(big.trim_start_matches('-')), "{err}");
        let _ = std::fs::remove_dir_all(dir);
    }
}

#[test]
fn a_record_files_fault_after_blank_lines_is_named_at_its_own_line() {
    // Before, the csv crate left blank lines out of its count: a NaN on line 8 was "line 6".
    let scene = scene_bytes("shaken.toml");
    let motion = scene_text("shaken-motion.csv");
    let rows: Vec<&str> = motion.lines().collect();
    let faults = [
        ("0.015,nan,0,0", "not a finite number"),
        ("0.001,0,0,0", "does not come after"),
        (
            "0.015,0,0",
            "3 comma-separated fields where the header has 4",
        ),
        ("0.015,x,0,0", "`x` in ax_g is not a number"),
        ("0.015,12,0,0", "over 10 g"),
    ];
    for (row, why) in faults {
        // Lines 1-3 as written, two blank lines (one of spaces), a fifth and sixth, the fault.
        let text = format!(
            "{}\r\n{}\r\n{}\r\n\r\n   \r\n{}\r\n{}\r\n{row}\r\n{}\r\n",
            rows[0], rows[1], rows[2], rows[3], rows[4], rows[6]
        );
        let (ran, dir) = run_with(
            "record-lines",
            &[("s.toml", &scene), ("shaken-motion.csv", text.as_bytes())],
            &["scene", "--check", "s.toml"],
        );
        assert_eq!(ran.code, Some(2), "{row}: {}", ran.stderr);
        let at = ran.stderr.find("shaken-motion.csv: ").unwrap();
        assert!(
            has_line(&ran.stderr[at..], 8) && ran.stderr.contains(why),
            "{row}: {}",
            ran.stderr
        );
        let _ = std::fs::remove_dir_all(dir);
    }
    // Blank lines alone are no fault: the record loads.
    let spaced = motion.replace('\n', "\n\n");
    let (ran, dir) = run_with(
        "record-blank",
        &[("s.toml", &scene), ("shaken-motion.csv", spaced.as_bytes())],
        &["scene", "--check", "s.toml"],
    );
    assert_eq!(ran.code, Some(0), "{}", ran.stderr);
    let _ = std::fs::remove_dir_all(dir);
}

#[test]
fn a_grid_files_fault_after_blank_lines_is_named_at_its_own_line() {
    // Before: `line 5` for the sixth line, and `CSV error: record 2 (line: 3, byte: 24)` for a
    // short row on line 4.
    for (grid, want) in [
        (
            "x_m,z_m,theta_deg\n\n\n0,0,0\n\n0.1,x,0\n",
            "g.csv: line 6, column z_m: `x` is not a number",
        ),
        (
            "x_m,z_m,theta_deg\r\n\r\n0,0,0\r\n0.1,inf,0\r\n",
            "g.csv: line 4, column z_m: must be a finite number, got inf",
        ),
        (
            "x_m,z_m,theta_deg\n0,0,0\n\n0.1,0\n",
            "g.csv: line 4: 2 comma-separated fields where the header has 3",
        ),
        (
            "\n\nx,z,theta\n0,0,0\n",
            "g.csv: line 3: line 3 must be exactly the header `x_m,z_m,theta_deg`",
        ),
    ] {
        let (ran, dir) = run_with(
            "grid-lines",
            &[("g.csv", grid.as_bytes())],
            &["roots", "--grid", "g.csv", "--out", "o.csv"],
        );
        assert_eq!(ran.code, Some(2), "{grid:?}: {}", ran.stderr);
        assert!(ran.stderr.contains(want), "{grid:?}: {}", ran.stderr);
        assert!(!dir.join("o.csv").exists());
        let _ = std::fs::remove_dir_all(dir);
    }
    // Quoted cells and blank lines: three poses.
    let (ran, dir) = run_with(
        "grid-quoted",
        &[(
            "g.csv",
            b"\xef\xbb\xbfx_m,z_m,theta_deg\n\"0.1\",\"0\",\"1\"\n\n0.2,0.1,2\n   \n",
        )],
        &["roots", "--grid", "g.csv", "--out", "o.csv"],
    );
    assert_eq!(ran.code, Some(0), "{}", ran.stderr);
    let out = std::fs::read_to_string(dir.join("o.csv")).unwrap();
    assert_eq!(out.lines().count(), 3, "{out}");
    let _ = std::fs::remove_dir_all(dir);
}

#[test]
fn a_grid_is_not_overwritten_by_its_own_roots() {
    // Before: `roots --grid g.csv --out g.csv` replaced the poses by their roots, exit 0; a
    // link to the grid did the same.
    let grid = b"x_m,z_m,theta_deg\n0.1,0,1\n";
    for out in ["g.csv", "./g.csv", "link.csv"] {
        let dir = std::env::temp_dir().join(format!("slideroute-grid-self-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        std::fs::write(dir.join("g.csv"), grid).unwrap();
        std::fs::hard_link(dir.join("g.csv"), dir.join("link.csv")).unwrap();
        let ran = std::process::Command::new(env!("CARGO_BIN_EXE_slideroute"))
            .current_dir(&dir)
            .args(["roots", "--grid", "g.csv", "--out", out])
            .output()
            .unwrap();
        let stderr = String::from_utf8_lossy(&ran.stderr);
        assert_eq!(ran.status.code(), Some(2), "{out}: {stderr}");
        assert!(stderr.contains("is the grid itself"), "{out}: {stderr}");
        assert_eq!(stderr.trim_end().lines().count(), 1, "{stderr}");
        assert_eq!(std::fs::read(dir.join("g.csv")).unwrap(), grid);
        let _ = std::fs::remove_dir_all(&dir);
    }
}

#[test]
fn a_grid_that_cannot_be_written_names_its_output() {
    // Before: `cannot write: No space left on device`, naming no file.
    if !std::path::Path::new("/dev/full").exists() {
        return;
    }
    let (ran, dir) = run_with(
        "grid-full",
        &[("g.csv", b"x_m,z_m,theta_deg\n0.1,0,1\n")],
        &["roots", "--grid", "g.csv", "--out", "/dev/full"],
    );
    assert_eq!(ran.code, Some(1), "{}", ran.stderr);
    assert!(
        ran.stderr
            .starts_with("slideroute: /dev/full: cannot write"),
        "{}",
        ran.stderr
    );
    let _ = std::fs::remove_dir_all(dir);
}

#[test]
fn an_obj_fault_names_the_line_of_its_vertex_or_face() {
    // Before: `valley.obj: triangle 174 has a corner that is not a finite number`, no line.
    let scene = scene_bytes("valley.toml");
    let obj = scene_text("valley.obj");
    let lines: Vec<&str> = obj.lines().collect();
    let vertex = lines.iter().position(|l| l.starts_with("v ")).unwrap();
    let face = lines.iter().position(|l| l.starts_with("f ")).unwrap();
    let first = lines[face].split_whitespace().nth(1).unwrap();
    let cases = [
        (
            vertex,
            "v 1.0 nan 2.0".to_string(),
            "a vertex's coordinates must be finite numbers",
        ),
        (vertex, "v 1.0 1e999 2.0".to_string(), "finite numbers"),
        (
            face,
            format!("f {first} {first} {first}"),
            "triangle 0 has no area",
        ),
        (face, "f 1 2 99999".to_string(), "a face names vertex 99999"),
    ];
    for (k, replacement, why) in cases {
        // Blank lines before the fault, which must not shift its number.
        let mut edited: Vec<String> = lines.iter().map(|l| l.to_string()).collect();
        edited[k] = replacement.clone();
        edited.insert(1, String::new());
        edited.insert(1, "   ".into());
        let text = edited.join("\n") + "\n";
        let (ran, dir) = run_with(
            "obj-lines",
            &[("valley.toml", &scene), ("valley.obj", text.as_bytes())],
            &["scene", "--check", "valley.toml"],
        );
        assert_eq!(ran.code, Some(2), "{replacement}: {}", ran.stderr);
        let want = format!("valley.obj: line {}: ", k + 3);
        let want_obj = format!("valley.obj: not a Wavefront OBJ surface: line {}: ", k + 3);
        assert!(
            (ran.stderr.contains(&want) || ran.stderr.contains(&want_obj))
                && ran.stderr.contains(why),
            "{replacement}: {}",
            ran.stderr
        );
        let _ = std::fs::remove_dir_all(dir);
    }
}

#[test]
fn a_negative_sample_count_or_seed_is_refused_naming_its_flag() {
    // Before: `unexpected argument '-5' found`, naming no flag.
    for (flag, value) in [("--samples", "-5"), ("--seed", "-1"), ("--samples", "-0")] {
        let mut args = vec!["probabilistic", "--out", "out", "--quiet", "--no-plots"];
        args.extend(["--dist", "friction.mu_k=normal:0.4:0.05", flag, value]);
        let (ran, dir) = run_with("negative", &[], &args);
        assert_eq!(ran.code, Some(2));
        assert_eq!(ran.stderr.lines().count(), 1, "{}", ran.stderr);
        assert!(
            ran.stderr
                .contains(&format!("invalid value '{value}' for '{flag} ")),
            "{}",
            ran.stderr
        );
        let _ = std::fs::remove_dir_all(dir);
    }
}

#[test]
fn a_friction_coefficient_of_1e_300_ends_its_route_instead_of_hanging() {
    // Before, its friction impulses were NaN (ν = |u|/radius overflowed) and the rotation's
    // renormalisation looped for ever: no row, Ctrl-C ignored.
    for mu in ["1e-300", "5e-324"] {
        let scene = scene_text("dam.toml").replacen("mu_k = 0.45", &format!("mu_k = {mu}"), 1);
        let (ran, dir) = run_with(
            "tiny-friction",
            &[("s.toml", scene.as_bytes())],
            &[
                "run",
                "--scene",
                "s.toml",
                "--out",
                "out",
                "--set",
                "solver.t_end_s=0.2",
                "--quiet",
                "--no-plots",
                "--no-3d",
            ],
        );
        assert_eq!(ran.code, Some(0), "{mu}: {}", ran.stderr);
        assert!(not_numbers(&dir, None).is_empty());
        let summary = std::fs::read_to_string(dir.join("out/summary.json")).unwrap();
        assert!(summary.contains("\"time-limit\""), "{summary}");
        let _ = std::fs::remove_dir_all(dir);
    }
}

#[test]
fn a_sweep_over_a_range_wider_than_the_largest_number_writes_no_nan() {
    // Before: `1e308:-1e308:3`'s middle value was NaN (STOP − START overflowed), written as
    // `NaN` in sweep.csv, and 5e-324's reason said `inf increments`; both exited 0.
    for vary in ["solver.dt_s=1e308:-1e308:3", "solver.dt_s=5e-324,-5e-324"] {
        let (ran, dir) = run_with(
            "wide-sweep",
            &[],
            &[
                "sweep",
                "--out",
                "out",
                "--vary",
                vary,
                "--quiet",
                "--no-plots",
                "--no-3d",
            ],
        );
        assert_eq!(ran.code, Some(0), "{}", ran.stderr);
        assert_eq!(not_numbers(&dir, None), Vec::<String>::new(), "{vary}");
        let _ = std::fs::remove_dir_all(dir);
    }
}

#[test]
fn a_weight_of_1e306_n_is_not_held_by_forty_thousand_sweeps_of_nan() {
    // Before, its contact impulses were NaN and every step of `check`'s held test ran all its
    // 40 000 sweeps: minutes for a 0.2 s route on a surface.
    let scene =
        scene_text("valley.toml").replacen("gravity_m_s2 = 9.81", "gravity_m_s2 = 1e300", 1);
    let start = Instant::now();
    let (ran, dir) = run_with(
        "huge-weight",
        &[
            ("s.toml", scene.as_bytes()),
            ("valley.obj", &scene_bytes("valley.obj")),
        ],
        &[
            "check",
            "--scene",
            "s.toml",
            "--out",
            "out",
            "--set",
            "solver.t_end_s=0.2",
            "--quiet",
            "--no-plots",
            "--no-3d",
        ],
    );
    assert!(matches!(ran.code, Some(0 | 2)), "{}", ran.stderr);
    assert!(
        start.elapsed() < Duration::from_secs(10),
        "{:?}",
        start.elapsed()
    );
    assert!(not_numbers(&dir, None).is_empty());
    let _ = std::fs::remove_dir_all(dir);
}

/// `lines` with every comma-separated cell in double quotes, the cells joined by `comma`.
fn every_cell_quoted(lines: &[String], comma: &str) -> Vec<String> {
    lines
        .iter()
        .map(|l| {
            l.split(',')
                .map(|c| format!("\"{c}\""))
                .collect::<Vec<_>>()
                .join(comma)
        })
        .collect()
}
