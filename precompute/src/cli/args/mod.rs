//! The `eigenrad` command line: one file per command holding its arguments (clap derive, their
//! doc comments the help text) and its `run`, which checks them, calls what the command
//! computes ([`crate::cli`]) and prints. The argument groups several commands take are
//! written once and flattened into each: channel levels, units, JSON and the form-factor
//! cache in `groups.rs`, a time and a sky in `daylight.rs`.

mod build;
mod building;
mod daylight;
mod eval;
mod form_factors;
mod groups;
mod inspect;
mod render;
mod simulate;
mod sky;
mod solve;
mod verify;

use std::io::Write as _;
use std::path::Path;

use clap::{Parser, Subcommand};

use crate::cli::{self, atomic};
use crate::error::Error;
use groups::JsonFlag;

/// Real-time radiosity for lighting controllers: precompute a room's eigenbasis, evaluate it
/// like the firmware does, and check it against the exact solution.
#[derive(Parser)]
#[command(name = "eigenrad", version, about, long_about = None)]
pub struct Cli {
    #[command(subcommand)]
    command: Command,
}

impl Cli {
    /// Runs the command the arguments name: its output on standard output, what it wrote
    /// noted on standard error. A reader that went away is [`Error::ClosedPipe`] in the chain.
    pub fn run(self) -> anyhow::Result<()> {
        match self.command {
            Command::Build(args) => args.run(),
            Command::Building(args) => args.run(),
            Command::Merge(args) => args.run(),
            Command::Solve(args) => args.run(),
            Command::Eval(args) => args.run(),
            Command::Render(args) => args.run(),
            Command::FormFactors(args) => args.run(),
            Command::Inspect(args) => args.run(),
            Command::Sky(args) => args.run(),
            Command::Simulate(args) => args.run(),
            Command::Verify(args) => args.run(),
        }
    }
}

// The variants' doc comments are the commands' help; each command's arguments are in its file.
#[derive(Subcommand)]
enum Command {
    /// Build a basis from a scene and report patches, modes, size, form-factor health,
    /// accuracy per channel and time per stage.
    Build(build::BuildArgs),
    /// Build a building's rooms (docs/building.md): all of them, in parallel as far as
    /// memory allows, then every controller's basis; or with --room or --shard one part, for
    /// `eigenrad merge`.
    Building(building::BuildingArgs),
    /// Write every controller's basis of a building from its rooms' parts, each checked
    /// against its flash budget.
    Merge(building::MergeArgs),
    /// Exact dense solve of a scene (LU), for reference.
    Solve(solve::SolveArgs),
    /// Evaluate a basis through the runtime crate: exactly what firmware computes.
    Eval(eval::EvalArgs),
    /// False-colour pictures (PNG or SVG, by the file's extension): the plan of a work plane
    /// with isolux lines, and the room's surfaces unfolded; from the exact solve of the scene,
    /// or with --basis from a basis built from it, evaluated as the firmware does.
    Render(render::RenderArgs),
    /// Surface-to-surface form factors, area-weighted over each surface's patches.
    FormFactors(form_factors::FormFactorsArgs),
    /// Describe a basis: dimensions, names, sizes; or, with --gains, what every sensor and
    /// zone reads per channel.
    Inspect(inspect::InspectArgs),
    /// The sun's position and a sky (CIE standard general sky or Perez all-weather sky) for a
    /// site, a time and a weather state: sun altitude and azimuth, efficacies, zenith
    /// luminance, horizontal illuminances, and with --json every sky patch's luminance.
    Sky(sky::SkyArgs),
    /// The controller's year: its loop run through the runtime for every hour of a weather
    /// file (EPW or TMY3), every strategy compared; energy, LENI, hours below target, the
    /// grids' daylight metrics (sDA, ASE, UDI), an hourly CSV and an EnergyPlus schedule.
    Simulate(simulate::SimulateArgs),
    /// Accuracy report: relative error against the exact solve as the mode count grows, for
    /// both formulations and the per-channel baseline, as markdown tables and SVG curves.
    Verify(verify::VerifyArgs),
}

/// Tells on standard error what was written; a closed standard error is no reason to fail.
fn note_written(path: &Path) {
    let _ = writeln!(std::io::stderr(), "wrote {}", path.display());
}

/// The bytes of the file at `path` (a basis); an error names it.
fn read(path: &Path) -> anyhow::Result<Vec<u8>> {
    std::fs::read(path).map_err(|reason| {
        Error::Io {
            path: path.to_path_buf(),
            reason,
        }
        .into()
    })
}

/// What `solve` and `eval` end with: the readings in the asked units, their grid points to
/// `csv` (checked against the inputs beforehand) and the readout on standard output.
fn show_readout(
    readout: cli::Readout,
    units: cli::Units,
    csv: Option<&Path>,
    json: &JsonFlag,
) -> anyhow::Result<()> {
    let readout = cli::units::readout_in(readout, units)?;
    if let Some(csv) = csv {
        atomic::write(csv, cli::grids_csv(&readout).as_bytes())?;
    }
    json.print(&readout, cli::format_readout)
}
