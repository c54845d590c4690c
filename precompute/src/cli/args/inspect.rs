//! `eigenrad inspect`: what a basis holds, or with `--gains` what every sensor and zone reads
//! per channel.

use std::path::PathBuf;

use clap::Args;

use super::groups::{JsonFlag, UnitsFlag};
use super::{note_written, read};
use crate::cli::{self, atomic, guard};

/// The arguments of `eigenrad inspect`. Its unit is that of the gains, so it needs `--gains`.
#[derive(Args)]
#[command(mut_arg("units", |units| {
    units.help("With --gains: unit of illuminance").requires("gains")
}))]
pub(super) struct InspectArgs {
    /// Basis file.
    basis: PathBuf,
    /// Instead: for every sensor and zone, its reading per channel at level 1 with the
    /// other channels off (lux, fc or W/m² per band), through the runtime.
    #[arg(long)]
    gains: bool,
    /// With --gains: also write the gains as CSV to this file (atomically).
    #[arg(long, value_name = "FILE", requires = "gains")]
    csv: Option<PathBuf>,
    #[command(flatten)]
    units: UnitsFlag,
    #[command(flatten)]
    json: JsonFlag,
}

impl InspectArgs {
    /// Describes the basis, or prints (and with `--csv` writes) its gains.
    pub(super) fn run(self) -> anyhow::Result<()> {
        if self.gains {
            self.gains()
        } else {
            let bytes = read(&self.basis)?;
            let info = cli::inspect(&self.basis, &bytes)?;
            self.json.print(&info, cli::format_inspect)
        }
    }

    /// `--gains`: every sensor's and zone's reading per channel.
    fn gains(self) -> anyhow::Result<()> {
        if let Some(csv) = &self.csv {
            guard::check_file_output(csv)?;
            guard::check_outputs(std::slice::from_ref(csv), std::slice::from_ref(&self.basis))?;
        }
        let bytes = read(&self.basis)?;
        let gains = cli::gains(&self.basis, &bytes, self.units.units())?;
        if let Some(csv) = &self.csv {
            atomic::write(csv, cli::gains_csv(&gains).as_bytes())?;
            note_written(csv);
        }
        self.json.print(&gains, cli::format_gains)
    }
}
