//! The README as a new user reads it: every shell command in its ```sh blocks runs as written
//! (`slideroute` on the PATH, as `cargo install --path .` puts it there), in order, in one
//! fresh folder, and exits 0; every ```text block that begins with `$ COMMAND` shows lines the
//! command prints, in the order it prints them. The README's ```python blocks are run by
//! `python/tests/test_readme.py`; its Rust blocks by the doc-tests.
//!
//! A line that cannot run here (it installs, runs the tests themselves, or needs a cluster) is
//! named in [`NOT_RUN_HERE`] with where it is checked instead; any other line must run.
#![cfg(feature = "cli")]

use std::path::{Path, PathBuf};
use std::process::Command;

/// Command lines of the README that this test does not run, and why.
const NOT_RUN_HERE: [(&str, &str); 6] = [
    ("cargo test", "the tests themselves"),
    (
        "cargo install --path .",
        "installs the binary this test runs (checked: the package's binary is slideroute)",
    ),
    (
        "pip install",
        "python/tests (the package installed by python/setup.sh)",
    ),
    (
        "python examples/dask_probabilistic.py --scheduler",
        "needs a cluster; python/tests/test_examples.py",
    ),
    ("crosscheck/setup.sh", "CI's Drake stage"),
    ("python/setup.sh", "CI's Python stage"),
];

/// A fenced block: its language and its lines.
struct Block {
    lang: String,
    lines: Vec<String>,
}

fn blocks(text: &str) -> Vec<Block> {
    let mut out = Vec::new();
    let mut current: Option<Block> = None;
    for line in text.lines() {
        if let Some(lang) = line.strip_prefix("```") {
            match current.take() {
                Some(b) => out.push(b),
                None => {
                    current = Some(Block {
                        lang: lang.trim().to_string(),
                        lines: Vec::new(),
                    })
                }
            }
        } else if let Some(b) = &mut current {
            b.lines.push(line.to_string());
        }
    }
    out
}

/// The commands of a shell block: continuation lines joined, comments and blank lines dropped.
fn commands(lines: &[String]) -> Vec<String> {
    let mut out = Vec::new();
    let mut pending = String::new();
    for line in lines {
        let line = match line.find(" #").or(line.starts_with('#').then_some(0)) {
            Some(at) => &line[..at],
            None => line.as_str(),
        };
        let line = line.trim_end();
        if let Some(part) = line.strip_suffix('\\') {
            pending.push_str(part.trim_end());
            pending.push(' ');
            continue;
        }
        pending.push_str(line.trim_start());
        let command = std::mem::take(&mut pending).trim().to_string();
        if !command.is_empty() {
            out.push(command);
        }
    }
    out
}

/// Runs `command` with `sh` in `dir`, `slideroute` being the binary under test.
fn shell(command: &str, dir: &Path) -> std::process::Output {
    let bin = PathBuf::from(env!("CARGO_BIN_EXE_slideroute"));
    let path = format!(
        "{}:{}",
        bin.parent().unwrap().display(),
        std::env::var("PATH").unwrap_or_default()
    );
    // The README's first command builds and runs the same binary.
    let command = command.replace("cargo run --release -- ", "slideroute ");
    Command::new("sh")
        .arg("-c")
        .arg(&command)
        .env("PATH", path)
        .current_dir(dir)
        .output()
        .unwrap()
}

fn repository() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// A fresh folder as a checkout's user has it: the repository's scenes beside them.
fn workspace(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("slideroute-readme-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    #[cfg(unix)]
    std::os::unix::fs::symlink(repository().join("scenes"), dir.join("scenes")).unwrap();
    dir
}

fn readme() -> String {
    std::fs::read_to_string(repository().join("README.md")).unwrap()
}

#[test]
fn every_shell_command_of_the_readme_runs_as_written() {
    let dir = workspace("sh");
    let mut ran = 0;
    for block in blocks(&readme()).iter().filter(|b| b.lang == "sh") {
        for command in commands(&block.lines) {
            if let Some((_, why)) = NOT_RUN_HERE.iter().find(|(p, _)| command.starts_with(p)) {
                eprintln!("not run here ({why}): {command}");
                continue;
            }
            let o = shell(&command, &dir);
            assert!(
                o.status.success(),
                "README: `{command}` failed: {}",
                String::from_utf8_lossy(&o.stderr)
            );
            ran += 1;
        }
    }
    // The first command, the probabilistic example, your own dam (print, run, sweep).
    assert!(ran >= 5, "only {ran} commands found");
    // What the commands wrote, each into its own folder.
    for file in [
        "out/run/route.csv",
        "fan/samples.csv",
        "dam.toml",
        "dam/summary.json",
        "dam-sweep/sweep.csv",
    ] {
        assert!(dir.join(file).is_file(), "{file}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn every_output_the_readme_shows_is_what_the_command_prints() {
    let dir = workspace("text");
    let mut shown = 0;
    for block in blocks(&readme()).iter().filter(|b| b.lang == "text") {
        let Some(command) = block.lines.first().and_then(|l| l.strip_prefix("$ ")) else {
            continue;
        };
        let o = shell(command, &dir);
        assert!(o.status.success(), "README: `{command}` failed");
        let printed = String::from_utf8_lossy(&o.stdout).into_owned();
        let mut lines = printed.lines();
        for expected in &block.lines[1..] {
            assert!(
                lines.any(|l| l.trim_end() == expected.trim_end()),
                "README: `{command}` does not print, in this order,\n{expected}\nit prints:\n{printed}"
            );
        }
        shown += 1;
    }
    // The default route, the paper's dynamics, the load cases, a record.
    assert!(shown >= 4, "only {shown} outputs found");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn the_readme_installs_the_command_it_then_uses() {
    let text = readme();
    assert!(text.contains("cargo install --path ."), "the install line");
    // `cargo install --path .` installs this package's binary under the name the README uses,
    // with the command line's features on by default.
    let manifest: toml::Table = std::fs::read_to_string(repository().join("Cargo.toml"))
        .unwrap()
        .parse()
        .unwrap();
    assert_eq!(manifest["package"]["name"].as_str(), Some("slideroute"));
    let default = manifest["features"]["default"].as_array().unwrap();
    assert!(default.iter().any(|f| f.as_str() == Some("cli")));
    assert!(repository().join("src/bin/slideroute/main.rs").is_file());
    // Every command line the test skips is one the README has.
    for (prefix, _) in NOT_RUN_HERE {
        assert!(text.contains(prefix), "{prefix} is no longer in the README");
    }
}

#[test]
fn commands_are_read_from_blocks_as_a_shell_reads_them() {
    let b = blocks("x\n```sh\na \\\n  b # note\n# c\n\nd\n```\n```text\n$ e\n```\n");
    assert_eq!(b.len(), 2);
    assert_eq!(commands(&b[0].lines), ["a b", "d"]);
    assert_eq!(b[1].lang, "text");
}
