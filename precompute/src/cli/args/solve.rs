//! `eigenrad solve`: the exact dense solve of a scene, for reference.

use std::path::PathBuf;

use clap::Args;

use super::daylight::DaylightFlags;
use super::groups::{help, CacheArgs, ChannelLevels, JsonFlag, UnitsFlag};
use super::show_readout;
use crate::cli::{self, guard};
use crate::scene;

/// The arguments of `eigenrad solve`. Its levels are relative to the scene itself, which has
/// not been built.
#[derive(Args)]
#[command(mut_arg(
    "levels",
    help("Channel level, relative (1 = as in the scene); repeatable. Channels default to 1")
))]
pub(super) struct SolveArgs {
    /// Scene file (TOML).
    scene: PathBuf,
    #[command(flatten)]
    levels: ChannelLevels,
    /// Also print every patch.
    #[arg(long)]
    patches: bool,
    #[command(flatten)]
    units: UnitsFlag,
    #[command(flatten)]
    json: JsonFlag,
    /// Write every calculation grid point (zone, position in m, irradiance per band) to
    /// this CSV file, atomically.
    #[arg(long, value_name = "FILE")]
    csv: Option<PathBuf>,
    #[command(flatten)]
    daylight: DaylightFlags,
    #[command(flatten)]
    cache: CacheArgs,
}

impl SolveArgs {
    /// Solves the scene and prints the readings (and writes the grid points with `--csv`).
    pub(super) fn run(self) -> anyhow::Result<()> {
        let daylight = self.daylight.daylight()?;
        if let Some(csv) = &self.csv {
            guard::check_file_output(csv)?;
            guard::check_outputs(
                std::slice::from_ref(csv),
                &scene::inputs(&self.scene)?.files,
            )?;
        }
        let readout = cli::solve_with_daylight(
            &self.scene,
            &self.levels.level_args(),
            daylight.as_ref(),
            self.patches,
            &self.cache.form_factors(),
        )?;
        show_readout(readout, self.units.units(), self.csv.as_deref(), &self.json)
    }
}
