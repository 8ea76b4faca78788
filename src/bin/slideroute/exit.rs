//! How a command ends: a typed failure that decides the exit code (README, "Exit codes") — 2 for
//! bad input (a scene, flag or input file that is wrong), 1 for any other failure (an output that
//! cannot be written, a full disk), and a quiet 0 when whoever reads standard output has closed
//! it (as `head` does), like other Unix tools; standard output written without panicking; and
//! the interruption by Ctrl-C or SIGTERM.

use slideroute::output::OutputError;
use std::path::PathBuf;
use std::process::ExitCode;
use std::sync::atomic::{AtomicBool, Ordering};

/// How a command failed. Each message is one line (a scene's several faults, one line each).
#[derive(Debug)]
pub enum CliError {
    /// A scene, flag or input file that is wrong: exit 2.
    BadInput(String),
    /// Anything else (an output that cannot be written): exit 1.
    Failed(String),
    /// Standard output was closed: a quiet 0.
    ClosedPipe,
}

/// A scene, flag or input file that is wrong: exit 2.
pub fn bad_input(msg: impl ToString) -> CliError {
    CliError::BadInput(msg.to_string())
}

/// An output that could not be written: exit 1.
pub fn failed(msg: impl ToString) -> CliError {
    CliError::Failed(msg.to_string())
}

/// What the library's writers could not do: an input they were asked of that cannot be used
/// is bad input (exit 2); a file that could not be written is a failure (exit 1), and so is an
/// interruption, which names the files already written whole.
pub fn output_error(e: OutputError) -> CliError {
    match e {
        OutputError::Input(msg) => CliError::BadInput(msg),
        OutputError::Write(msg) => CliError::Failed(msg),
        OutputError::Interrupted { what, written } if written.is_empty() => CliError::Failed(what),
        OutputError::Interrupted { what, written } => interrupted_after(&what, &written),
    }
}

/// A scene that cannot be used: bad input, each of its faults on its own line.
pub fn scene_faults(e: slideroute::SceneError) -> CliError {
    let lines: Vec<String> = e.faults().map(ToString::to_string).collect();
    CliError::BadInput(lines.join("\n"))
}

/// Writing to standard output failed: a closed pipe ends the command quietly, any other error
/// (a full disk) is a one-line failure.
pub fn stdout_error(e: std::io::Error) -> CliError {
    if e.kind() == std::io::ErrorKind::BrokenPipe {
        CliError::ClosedPipe
    } else {
        CliError::Failed(format!("standard output: {e}"))
    }
}

/// Prints to standard output (flushed) without panicking, returning a [`CliError`] from the
/// function it is used in.
macro_rules! out {
    ($($arg:tt)*) => {{
        use std::io::Write as _;
        let mut o = std::io::stdout().lock();
        write!(o, $($arg)*).and_then(|_| o.flush()).map_err($crate::exit::stdout_error)?
    }};
}

/// [`out!`] with a newline.
macro_rules! outln {
    ($($arg:tt)*) => {{
        use std::io::Write as _;
        let mut o = std::io::stdout().lock();
        writeln!(o, $($arg)*).and_then(|_| o.flush()).map_err($crate::exit::stdout_error)?
    }};
}

pub(crate) use {out, outln};

/// The exit code of a result, its failure said in one line on standard error.
pub fn exit_code(result: Result<(), CliError>) -> ExitCode {
    match result {
        Ok(()) | Err(CliError::ClosedPipe) => ExitCode::SUCCESS,
        Err(CliError::BadInput(msg)) => {
            // Several faults (a scene's): one line each.
            for line in msg.lines() {
                eprintln!("slideroute: {line}");
            }
            ExitCode::from(2)
        }
        Err(CliError::Failed(msg)) => {
            eprintln!("slideroute: {msg}");
            ExitCode::from(1)
        }
    }
}

/// How a command line that clap does not accept ends: help and the version printed as asked
/// (exit 0), every other fault in the one style of every error, one line on standard error,
/// `slideroute: REASON; see slideroute COMMAND --help`, exit 2.
pub fn usage_error(e: &clap::Error) -> ExitCode {
    use clap::error::ErrorKind;
    match e.kind() {
        ErrorKind::DisplayHelp | ErrorKind::DisplayVersion => {
            let _ = e.print();
            return ExitCode::SUCCESS;
        }
        ErrorKind::DisplayHelpOnMissingArgumentOrSubcommand => {
            let _ = e.print();
            return ExitCode::from(2);
        }
        _ => {}
    }
    // The command the line was for: the first word that names one.
    let command = std::env::args()
        .skip(1)
        .find(|w| {
            <crate::cli::Cli as clap::CommandFactory>::command()
                .get_subcommands()
                .any(|c| c.get_name() == w)
        })
        .map_or_else(|| "slideroute".to_string(), |c| format!("slideroute {c}"));
    eprintln!(
        "slideroute: {}; see {command} --help",
        usage_reason(&e.render().to_string())
    );
    ExitCode::from(2)
}

/// The reason of clap's rendered error in one line: its lines before the usage, joined, without
/// the `error:` prefix.
fn usage_reason(rendered: &str) -> String {
    let reason: Vec<&str> = rendered
        .lines()
        .take_while(|l| !l.starts_with("Usage:"))
        .map(str::trim)
        .filter(|l| !l.is_empty() && !l.starts_with("For more information"))
        .collect();
    reason
        .join(" ")
        .replace(" tip: ", "; ")
        .trim_start_matches("error: ")
        .trim_end_matches('.')
        .to_string()
}

/// Set by Ctrl-C (SIGINT) and SIGTERM: a route stops at its next increment and writes what it
/// computed, with termination "interrupted"; a second signal ends the process.
static INTERRUPTED: AtomicBool = AtomicBool::new(false);

/// Listens for Ctrl-C and SIGTERM.
pub fn catch_interruptions() {
    let _ = ctrlc::set_handler(|| {
        if INTERRUPTED.swap(true, Ordering::Relaxed) {
            std::process::exit(130);
        }
    });
}

/// Whether Ctrl-C or SIGTERM has come.
pub fn interrupted() -> bool {
    INTERRUPTED.load(Ordering::Relaxed)
}

/// The failure of a command that was interrupted after writing `files` whole: `what` stopped,
/// and what was computed was written.
pub fn interrupted_after(what: &str, files: &[PathBuf]) -> CliError {
    let names: Vec<String> = files.iter().map(|f| f.display().to_string()).collect();
    failed(format!(
        "{what}; wrote what was computed: {}",
        names.join(", ")
    ))
}

/// The failure of a run of many routes that was interrupted after writing `files` whole: the
/// `items` under way (samples, combinations) stopped, those not started are rows
/// [`NOT_RUN`](slideroute::NOT_RUN).
pub fn many_interrupted_after(items: &str, files: &[PathBuf]) -> CliError {
    interrupted_after(
        &format!(
            "interrupted: {items} under way stopped, those not started are rows \"{}\"",
            slideroute::NOT_RUN
        ),
        files,
    )
}
