//! `eigenrad eval`: a basis evaluated through the runtime crate, exactly as firmware computes
//! it.

use std::path::PathBuf;

use std::io::Write as _;

use anyhow::Context;
use clap::Args;

use super::daylight::DaylightFlags;
use super::groups::{help, ChannelLevels, JsonFlag, UnitsFlag};
use super::{read, show_readout};
use crate::cli::{self, guard};

/// The arguments of `eigenrad eval`. Its arc levels go through the runtime's own conversion,
/// and its daylight is what the basis carries.
#[derive(Args)]
#[command(
    mut_arg(
        "arcs",
        help(
            "Channel level as a DALI arc power level, 0 (off) to 254 (100 %) on the IEC 62386-102 \
             curve, through the runtime's conversion; repeatable. Not with --level for one channel"
        )
    ),
    mut_arg(
        "time",
        help(
            "Daylight at this date and time (with its UTC offset, or the site's), from the sky \
             the sky flags give, through the daylight the basis carries (a basis built from a \
             scene with a `[site]` and glazed windows); readings then show daylight and \
             electric light apart and together"
        )
    )
)]
pub(super) struct EvalArgs {
    /// Basis file.
    basis: PathBuf,
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
    /// Instead of levels: the least-power levels that give this zone at least this
    /// illuminance (lux) over the daylight of --time, found by the runtime's level solver as
    /// firmware finds them; repeatable. Continuous levels (no DALI rounding).
    #[arg(long = "target", value_name = "ZONE=LUX", conflicts_with_all = ["levels", "arcs"])]
    targets: Vec<String>,
    /// With --target: each channel's power at full output from this controller file
    /// (docs/simulate.md), the weights of the least power; without it every channel weighs
    /// the same (the least total level).
    #[arg(long, value_name = "FILE", requires = "targets")]
    controller: Option<PathBuf>,
}

impl EvalArgs {
    /// Evaluates the basis and prints the readings (and writes the grid points with `--csv`).
    pub(super) fn run(self) -> anyhow::Result<()> {
        let daylight = self.daylight.daylight()?;
        if let Some(csv) = &self.csv {
            guard::check_file_output(csv)?;
            guard::check_outputs(std::slice::from_ref(csv), std::slice::from_ref(&self.basis))?;
        }
        let bytes = read(&self.basis)?;
        let level_args = if self.targets.is_empty() {
            self.levels.level_args()
        } else {
            let weights = match &self.controller {
                Some(file) => {
                    let basis = eigenrad_runtime::Basis::from_bytes(&bytes).map_err(|reason| {
                        crate::Error::Basis {
                            path: self.basis.clone(),
                            reason,
                        }
                    })?;
                    let controller = crate::simulate::load_controller(file, &basis)?;
                    Some(
                        controller
                            .channels
                            .iter()
                            .map(|c| c.full_w)
                            .collect::<Vec<_>>(),
                    )
                }
                None => None,
            };
            let (levels, notes) = cli::levels_for_targets(
                &self.basis,
                &bytes,
                &self.targets,
                weights.as_deref(),
                daylight.as_ref(),
            )?;
            for note in notes {
                let _ = writeln!(std::io::stderr(), "warning: {note}");
            }
            levels
        };
        let readout = cli::eval_with_daylight(
            &self.basis,
            &bytes,
            &level_args,
            daylight.as_ref(),
            self.patches,
        )
        .with_context(|| format!("evaluating {}", self.basis.display()))?;
        show_readout(readout, self.units.units(), self.csv.as_deref(), &self.json)
    }
}
