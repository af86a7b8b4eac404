//! `csrl`: the command-line program of the csrl workspace.
//!
//! Run `csrl --help` for the commands. Results go to stdout, errors to stderr with a
//! non-zero exit (2 for usage errors, 1 for anything else); no input makes it panic.

mod classify;
mod maps;
mod run;

use std::io::Write;
use std::process::ExitCode;

use clap::{Parser, Subcommand};

/// Cost-sensitive reinforcement learning (Tan, AAAI-91): grid maps, CS-QL runs and
/// cost-sensitive classification.
#[derive(Parser)]
#[command(name = "csrl", version, about, long_about = None)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// List the built-in maps.
    Maps,
    /// Show or check a map.
    #[command(subcommand)]
    Map(maps::MapCommand),
    /// Run CS-QL once and report the measures of the paper's Table 1.
    Run(run::RunArgs),
    /// Stream a CSV table through a cost-sensitive learner and report errors and costs.
    Classify(classify::ClassifyArgs),
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    let stdout = std::io::stdout();
    let mut out = stdout.lock();
    let result = match &cli.command {
        Command::Maps => maps::list(&mut out),
        Command::Map(cmd) => maps::run(cmd, &mut out),
        Command::Run(args) => run::run(args, &mut out),
        Command::Classify(args) => classify::run(args, &mut out),
    }
    .and_then(|()| out.flush().map_err(anyhow::Error::from));
    match result {
        Ok(()) => ExitCode::SUCCESS,
        // A reader that stops early (`csrl ... | head`) is not an error of ours.
        Err(e) if is_broken_pipe(&e) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e:#}");
            ExitCode::FAILURE
        }
    }
}

fn is_broken_pipe(e: &anyhow::Error) -> bool {
    e.chain().any(|c| {
        c.downcast_ref::<std::io::Error>()
            .is_some_and(|io| io.kind() == std::io::ErrorKind::BrokenPipe)
    })
}
