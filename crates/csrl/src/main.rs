//! `csrl`: the command-line program of the csrl workspace.
//!
//! Run `csrl --help` for the commands. Results go to stdout, errors and notes to stderr.
//!
//! Exit codes, one per kind of ending, the same in every command:
//!
//! | code | meaning |
//! |---:|---|
//! | 0 | success (also when a reader of stdout stops early, as `head` does) |
//! | 1 | an input that cannot be read or is not valid (a file, a map, a world, settings, data), said on stderr as `error: ...` |
//! | 2 | a usage error (clap's: an unknown flag, a missing or malformed argument) |
//! | 3 | `run --require-convergence` on a run that did not converge |
//! | 4 | an output file that cannot be written (`--svg`, `--save`, `--dot`, `--out`): a missing folder and a read-only one alike |
//! | 130 | a run stopped by Ctrl-C or SIGTERM, after printing what it reached |
//!
//! No input makes it panic, and a full or closed stderr loses the message but not the
//! exit code. A message says each thing once: a cause already said by the message it
//! explains is not repeated.

mod classify;
mod classify_args;
mod maps;
mod predict;
mod progress;
mod run;
mod testcost;
mod worlds;

use std::io::Write;
use std::process::ExitCode;

use clap::{Parser, Subcommand};

/// Cost-sensitive reinforcement learning (Tan, AAAI-91): grid maps, CS-QL runs and
/// cost-sensitive classification.
#[derive(Parser)]
#[command(
    name = "csrl",
    version,
    about,
    long_about = None,
    after_help = "Exit codes: 0 success; 1 an input that cannot be read or is not valid; \
2 a usage error; 3 `run --require-convergence` on a run that did not converge; \
4 an output file that cannot be written; 130 a run stopped by Ctrl-C or SIGTERM \
(after its report). With CSRL_READY_LINE set, `run` writes a line to stderr once a stop \
would be honoured."
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// List the built-in maps.
    Maps {
        /// Print one JSON array instead of text.
        #[arg(long)]
        json: bool,
    },
    /// Show or check a map.
    #[command(subcommand)]
    Map(maps::MapCommand),
    /// Worlds beyond grid maps (FrozenLake, Taxi, CliffWalking, world files), and any
    /// world as a world file.
    #[command(subcommand)]
    World(worlds::WorldCommand),
    /// Run CS-QL (or a baseline, `--learner`) once and report the measures of the paper's Table 1.
    Run(run::RunArgs),
    /// Stream a CSV table through a cost-sensitive learner and report errors and costs.
    Classify(Box<classify::ClassifyArgs>),
    /// Classify new rows with a model saved by `classify --save`: each row's class and
    /// what its measurements cost, as CSV (`line,class,cost,measured`).
    Predict(predict::PredictArgs),
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    let stdout = std::io::stdout();
    let mut out = stdout.lock();
    let result = match &cli.command {
        Command::Maps { json } => maps::list(*json, &mut out),
        Command::Map(cmd) => maps::run(cmd, &mut out),
        Command::World(cmd) => worlds::run(cmd, &mut out),
        Command::Run(args) => run::run(args, &mut out),
        Command::Classify(args) => classify::run(args, &mut out),
        Command::Predict(args) => predict::run(args, &mut out),
    }
    .and_then(|()| out.flush().map_err(anyhow::Error::from));
    match result {
        Ok(()) => ExitCode::SUCCESS,
        // A reader that stops early (`csrl ... | head`) is not an error of ours.
        Err(e) if is_broken_pipe(&e) => ExitCode::SUCCESS,
        Err(e) => match e.downcast_ref::<Status>() {
            Some(status) => {
                note(format_args!("{status}"));
                ExitCode::from(status.code)
            }
            None => {
                // What a file put in the message cannot drive the terminal.
                note(format_args!("error: {}", shown_lines(&message(&e))));
                let cannot_write = e.chain().any(|c| c.downcast_ref::<CannotWrite>().is_some());
                ExitCode::from(if cannot_write { 4 } else { 1 })
            }
        },
    }
}

/// The error and its causes, each said once: a cause whose text the message so far
/// already holds (a wrapper that printed its source itself) is left out.
fn message(e: &anyhow::Error) -> String {
    let mut text = String::new();
    for cause in e.chain() {
        // Some causes end their text with a newline (TOML's): compare what is said.
        let part = cause.to_string();
        let part = part.trim_end();
        if text.is_empty() {
            text = part.to_string();
        } else if !text.contains(part) {
            text.push_str(": ");
            text.push_str(part);
        }
    }
    text
}

/// An output file that cannot be written (exit code 4).
#[derive(Debug)]
pub(crate) struct CannotWrite {
    path: std::path::PathBuf,
    source: std::io::Error,
}

impl std::fmt::Display for CannotWrite {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "cannot write {}", self.path.display())
    }
}

impl std::error::Error for CannotWrite {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        Some(&self.source)
    }
}

/// A [`CannotWrite`] for `path`, as an error.
pub(crate) fn cannot_write(path: &std::path::Path, source: std::io::Error) -> anyhow::Error {
    anyhow::Error::new(CannotWrite {
        path: path.to_path_buf(),
        source,
    })
}

/// Write `contents` to `path`; a failure is a [`CannotWrite`].
pub(crate) fn write_file(path: &std::path::Path, contents: impl AsRef<[u8]>) -> anyhow::Result<()> {
    std::fs::write(path, contents).map_err(|source| cannot_write(path, source))
}

/// `text` as it may reach a terminal: its control characters (escape sequences, a
/// carriage return, a newline) written as Rust escapes (`\u{1b}`, `\r`, `\n`), the rest
/// as it is. Names from a world or map file pass through this before they are printed.
pub(crate) fn shown(text: &str) -> std::borrow::Cow<'_, str> {
    if !text.chars().any(char::is_control) {
        return std::borrow::Cow::Borrowed(text);
    }
    let mut out = String::with_capacity(text.len() + 8);
    for c in text.chars() {
        if c.is_control() {
            out.extend(c.escape_default());
        } else {
            out.push(c);
        }
    }
    std::borrow::Cow::Owned(out)
}

/// `text` as [`shown`] writes it, but with its newlines kept: lines stay lines.
pub(crate) fn shown_lines(text: &str) -> String {
    text.split('\n').map(shown).collect::<Vec<_>>().join("\n")
}

/// Write a line to stderr. Unlike `eprintln!`, a full or closed stderr is no panic: the
/// line is lost, and the exit code still says what happened.
pub(crate) fn note(line: std::fmt::Arguments<'_>) {
    let _ = writeln!(std::io::stderr().lock(), "{line}");
}

/// An ending that is not a plain failure: its own exit code and a line for stderr.
#[derive(Debug)]
pub(crate) struct Status {
    code: u8,
    message: String,
}

impl Status {
    /// `run --require-convergence` on a run that did not converge.
    pub(crate) fn not_converged(trials: u32) -> Status {
        Status {
            code: 3,
            message: format!(
                "error: the run did not converge in {trials} trials (--require-convergence)"
            ),
        }
    }

    /// A run stopped by Ctrl-C or SIGTERM.
    pub(crate) fn interrupted(trials: u64) -> Status {
        Status {
            code: 130,
            message: format!(
                "interrupted after {trials} trials: the report above is what the run reached"
            ),
        }
    }
}

impl std::fmt::Display for Status {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.message)
    }
}

impl std::error::Error for Status {}

fn is_broken_pipe(e: &anyhow::Error) -> bool {
    e.chain().any(|c| {
        c.downcast_ref::<std::io::Error>()
            .is_some_and(|io| io.kind() == std::io::ErrorKind::BrokenPipe)
    })
}
