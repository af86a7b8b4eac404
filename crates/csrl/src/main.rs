//! `csrl`: the command-line program of the csrl workspace.
//!
//! Run `csrl --help` for the commands. Results go to stdout, errors to stderr with a
//! non-zero exit (2 for usage errors, 1 for anything else); no input makes it panic.

mod classify;
mod maps;
mod run;

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
    let result = match &cli.command {
        Command::Maps => maps::list(),
        Command::Map(cmd) => maps::run(cmd),
        Command::Run(args) => run::run(args),
        Command::Classify(args) => classify::run(args),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e:#}");
            ExitCode::FAILURE
        }
    }
}
