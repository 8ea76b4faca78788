//! The `slideroute` command line: parses (`cli.rs`), calls the command (`commands/`), and ends
//! with the exit code its result calls for (`exit.rs`). Its files and pictures are the
//! library's (`slideroute::output`); it keeps the arguments, the progress bars, Ctrl-C and the
//! exit codes.

mod cli;
mod commands;
mod exit;

use clap::Parser as _;
use cli::{Cli, Command};
use std::process::ExitCode;

fn main() -> ExitCode {
    let cli = match Cli::try_parse() {
        Ok(cli) => cli,
        Err(e) => return exit::usage_error(&e),
    };
    exit::catch_interruptions();
    exit::exit_code(match &cli.command {
        Command::Run(args) => commands::run::run(args),
        Command::Sweep(args) => commands::sweep::sweep(args),
        Command::Probabilistic(args) => commands::probabilistic::probabilistic(args),
        Command::Check(args) => commands::check::check(args),
        Command::Report(args) => commands::report::report(args),
        Command::Scene(args) => commands::scene::scene(args),
        Command::Coeffs(args) => commands::coeffs::coeffs(args),
        Command::Roots(args) => commands::roots::roots(args),
    })
}
