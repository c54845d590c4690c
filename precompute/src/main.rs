//! The `eigenrad` command: a thin layer over `eigenrad_precompute`. Each command's arguments
//! and what it runs are in `eigenrad_precompute::cli::args` (one file per command); here the
//! arguments are parsed, the command run and its outcome turned into an exit code. Every
//! number printed carries its unit.

use std::io::Write as _;
use std::process::ExitCode;

use clap::Parser;
use eigenrad_precompute::cli::args::Cli;
use eigenrad_precompute::Error;

fn main() -> ExitCode {
    match Cli::parse().run() {
        Ok(()) => ExitCode::SUCCESS,
        // The reader went away (`| head`): stop quietly, with the status a shell reports for
        // tools that SIGPIPE ends (128 + 13).
        Err(e) if matches!(e.downcast_ref::<Error>(), Some(Error::ClosedPipe)) => {
            ExitCode::from(141)
        }
        Err(e) => {
            // Nothing left to report to if standard error is closed too.
            let _ = writeln!(std::io::stderr(), "error: {e:#}");
            ExitCode::FAILURE
        }
    }
}
