//! `eigenrad-bench`: the figures of `docs/performance.md`.
//!
//! - `eigenrad-bench update SCENE...`: cost of turning new channel levels into (a) every sensor
//!   and zone reading and (b) every patch exitance, for the eigenbasis through the runtime and
//!   for the alternatives (exact per-channel superposition, dense LU, Southwell shooting,
//!   Gauss–Seidel), with the accuracy each reaches against the exact solve; and the host
//!   evaluation against a memory-bandwidth bound.
//! - `eigenrad-bench scale SCENE...`: precompute stage times and peak memory, one child
//!   process per scene (so that each peak is its own), and each scene's total time against
//!   the first scene's.
//! - `eigenrad-bench eigen SCENE...`: dense against partial eigensolve on the same matrix.
//! - `eigenrad-bench compress SCENE...`: the hierarchical form-factor operator against a dense
//!   one: memory, form-factor time, every channel's readings, the strongest eigenvalues.
//! - `eigenrad-bench rays SCENE... [--points 2,3,4]`: sampled visibility against the exact
//!   shadows: CPU time, and how far row sums, products and every channel's readings move.
//! - `eigenrad-bench shadows SCENE...`: the luminaires' direct light with shadows as polygons
//!   against rays refined along shadow edges: CPU time, and how far the light moves.
//! - `eigenrad-bench sight SCENE...`: the hierarchical form factors without and with the
//!   scene's blocks as solids: CPU time, entries read, blocks, and how far the products move.
//! - `eigenrad-bench partition SCENE...`: how the hierarchical operator's block partition
//!   divides the entries before any is read (close, split by sight, compressed, dark), at
//!   sizes whose form factors would take hours.
//! - `eigenrad-bench daylight SCENE...`: the room's response to the sky (Tregenza, Reinhart
//!   MF:2) and to one sun direction, against the time to prepare the scene.
//! - `eigenrad-bench simulate BASIS... --weather FILE --controller FILE...`: a year of each
//!   controller (`eigenrad simulate`) part by part: the weather read, the skies, the loop.
//! - `eigenrad-bench building MANIFEST`: a building's rooms one after the other against all
//!   at once (the parallel speed-up), and each controller's basis size.
//!
//! Run in release: `cargo run --release -p eigenrad-precompute --bin eigenrad-bench -- …`.

mod building;
mod compress;
mod daylight;
mod eigen;
mod partition;
mod rays;
mod scale;
mod shadows;
mod sight;
mod simulate;
mod update;

use std::path::PathBuf;

use anyhow::Result;
use clap::{Parser, Subcommand};
use eigenrad_precompute::formfactor::OperatorChoice;
use eigenrad_precompute::pipeline;

/// The eigenbasis row every ratio is relative to, and the mode count of `eigen`: the default
/// build's (p = 32).
const REFERENCE_MODES: usize = pipeline::DEFAULT_MODES;

#[derive(Parser)]
#[command(about = "Benchmarks of eigenrad (docs/performance.md)")]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Per-update cost and accuracy of every method on each scene (one band).
    Update {
        /// Scene files.
        scenes: Vec<PathBuf>,
        /// Skip the LU factorisation per update (seconds per update at n = 5000).
        #[arg(long)]
        skip_lu: bool,
    },
    /// Precompute stage times and peak memory, one child process per scene; each scene's
    /// total time against the first's.
    Scale {
        /// Scene files.
        scenes: Vec<PathBuf>,
        #[command(flatten)]
        build: scale::Settings,
    },
    /// (internal) One row of `scale`, in this process.
    ScaleOne {
        /// Scene file.
        scene: PathBuf,
        #[command(flatten)]
        build: scale::Settings,
    },
    /// The room's response to the sky and to one sun direction through its windows, against
    /// the time to prepare the scene (scenes with a `[site]` and glazed windows).
    Daylight {
        /// Scene files.
        scenes: Vec<PathBuf>,
    },
    /// The hierarchical operator against a dense one on each scene: memory, form-factor time,
    /// every channel's readings and the 32 strongest eigenvalues.
    Compress {
        /// Scene files.
        scenes: Vec<PathBuf>,
        /// The dense operator compared with.
        #[arg(long, value_enum, default_value_t = OperatorChoice::DenseF32)]
        reference: OperatorChoice,
    },
    /// The hierarchical form factors of each scene without and with its blocks as solids:
    /// CPU time, entries read, blocks, and the largest difference of their products.
    Sight {
        /// Scene files.
        scenes: Vec<PathBuf>,
    },
    /// How the hierarchical operator's partition divides each scene's entries before any is
    /// read: close, split by sight, compressed, dark (no form factor is computed).
    Partition {
        /// Scene files.
        scenes: Vec<PathBuf>,
    },
    /// Sampled visibility against the exact shadows on each scene: CPU time, and how far the
    /// row sums, products and every channel's readings move.
    Rays {
        /// Scene files.
        scenes: Vec<PathBuf>,
        /// How the form-factor operator is stored.
        #[arg(long, value_enum, default_value_t = OperatorChoice::Auto)]
        operator: OperatorChoice,
        /// Points per side of the sampled grids, one run each (comma-separated).
        #[arg(long, value_delimiter = ',', default_value = "2,3,4", num_args = 0..)]
        points: Vec<u32>,
        /// One more run with `--visibility clusters`.
        #[arg(long)]
        clusters: bool,
    },
    /// The luminaires' direct light with shadows as polygons against rays refined along the
    /// shadow edges: CPU time, and how far the light of patches and outputs moves.
    Shadows {
        /// Scene files.
        scenes: Vec<PathBuf>,
        /// Points along each side of the midpoint rule on the patch where the two differ most.
        #[arg(long, default_value_t = 1000)]
        midpoint: usize,
    },
    /// A building's rooms built one after the other, then all at once: wall times, the
    /// speed-up, and each controller's basis size.
    Building {
        /// Building manifest.
        manifest: PathBuf,
    },
    /// A year of each controller (`eigenrad simulate`), part by part: the weather file read,
    /// every hour's sun and sky, the controller's loop through the runtime (best of 3 runs).
    Simulate {
        /// Basis files (with daylight).
        bases: Vec<PathBuf>,
        /// Weather file (EPW or TMY3).
        #[arg(long)]
        weather: PathBuf,
        /// Controller files, one per basis, in order.
        #[arg(long = "controller", num_args = 1..)]
        controllers: Vec<PathBuf>,
    },
    /// Dense against partial eigensolve (p = 32) on each scene's form factors.
    Eigen {
        /// Scene files.
        scenes: Vec<PathBuf>,
        /// Largest reflecting-patch count for which the dense solve is run.
        #[arg(long, default_value_t = 5000)]
        dense_max: usize,
    },
}

fn main() -> Result<()> {
    match Cli::parse().command {
        Command::Update { scenes, skip_lu } => {
            machine();
            update::run(&scenes, skip_lu)?;
        }
        Command::Scale { scenes, build } => {
            machine();
            scale::run(&scenes, &build)?;
        }
        Command::ScaleOne { scene, build } => scale::one(&scene, &build)?,
        Command::Daylight { scenes } => {
            machine();
            daylight::run(&scenes)?;
        }
        Command::Compress { scenes, reference } => {
            machine();
            compress::run(&scenes, reference)?;
        }
        Command::Sight { scenes } => {
            machine();
            sight::run(&scenes)?;
        }
        Command::Partition { scenes } => {
            machine();
            partition::run(&scenes)?;
        }
        Command::Rays {
            scenes,
            operator,
            points,
            clusters,
        } => {
            machine();
            rays::run(&scenes, operator, &points, clusters)?;
        }
        Command::Shadows { scenes, midpoint } => {
            machine();
            shadows::run(&scenes, midpoint)?;
        }
        Command::Building { manifest } => {
            machine();
            building::run(&manifest)?;
        }
        Command::Simulate {
            bases,
            weather,
            controllers,
        } => {
            machine();
            simulate::run(&bases, &weather, &controllers)?;
        }
        Command::Eigen { scenes, dense_max } => {
            machine();
            eigen::run(&scenes, dense_max)?;
        }
    }
    Ok(())
}

/// Prints the CPU model and core count (`lscpu`).
fn machine() {
    let out = std::process::Command::new("lscpu")
        .output()
        .map(|o| String::from_utf8_lossy(&o.stdout).into_owned())
        .unwrap_or_default();
    let field = |name: &str| {
        out.lines()
            .find(|l| l.starts_with(name))
            .and_then(|l| l.split(':').nth(1))
            .map_or("?".to_string(), |v| v.trim().to_string())
    };
    println!(
        "machine: {} ({} CPUs), rayon threads {}",
        field("Model name"),
        field("CPU(s)"),
        rayon::current_num_threads()
    );
}
