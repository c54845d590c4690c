//! Argument groups several commands take, each written once and flattened into the commands
//! (`#[command(flatten)]`): channel levels, the unit of illuminance, JSON output and the
//! form-factor cache.
//!
//! A command whose help says more than the group's (what `--json` prints, what a level is
//! relative to) words its own with `#[command(mut_arg(ID, help(TEXT)))]` on its arguments:
//! the flag, its parsing and what it does stay the group's.

use std::io::IsTerminal;

use clap::{Args, ValueEnum};
use serde::Serialize;

use crate::cache;
use crate::cli;
use crate::formfactor::{
    hierarchical, FormFactorOptions, OperatorChoice, Visibility, MAX_PER_SIDE,
};

/// Sets an argument's help to `text` (as a doc comment does: one line, no final full stop),
/// for `#[command(mut_arg(ID, help(TEXT)))]`.
pub(super) fn help(text: &'static str) -> impl FnOnce(clap::Arg) -> clap::Arg {
    move |arg| arg.help(text)
}

/// Channel levels, relative or as DALI arc power levels: `solve`, `eval` and `render`.
#[derive(Args)]
pub(super) struct ChannelLevels {
    /// Channel level, relative (1 = as built); repeatable. Channels default to 1.
    #[arg(long = "level", value_name = "NAME=VALUE")]
    levels: Vec<String>,
    /// Channel level as a DALI arc power level, 0 (off) to 254 (100 %) on the IEC 62386-102
    /// curve, as the firmware converts it; repeatable. Not with --level for one channel.
    #[arg(long = "arc", value_name = "NAME=ARC")]
    arcs: Vec<String>,
}

impl ChannelLevels {
    /// The levels as given; the command checks them against its channels' names.
    pub(super) fn level_args(&self) -> cli::LevelArgs {
        cli::LevelArgs {
            levels: self.levels.clone(),
            arcs: self.arcs.clone(),
        }
    }
}

/// The unit of illuminance a command prints: `solve`, `eval`, `render` and `inspect --gains`.
#[derive(Args)]
pub(super) struct UnitsFlag {
    /// Unit of illuminance (and exitance) printed.
    #[arg(long, value_enum, default_value = "lux")]
    units: UnitsArg,
}

impl UnitsFlag {
    /// The unit asked for.
    pub(super) fn units(&self) -> cli::Units {
        match self.units {
            UnitsArg::Lux => cli::Units::Native,
            UnitsArg::Fc => cli::Units::Footcandles,
        }
    }
}

#[derive(Clone, Copy, ValueEnum)]
enum UnitsArg {
    /// Lux for a photometric basis or scene (W/m² for a radiometric one, whatever is asked).
    Lux,
    /// Footcandles: 1 fc = 1 lm/ft² = 10.7639 lx (photometric only).
    Fc,
}

/// `--json`: one JSON document on standard output instead of the text.
#[derive(Args)]
pub(super) struct JsonFlag {
    /// Print one JSON document on stdout.
    #[arg(long)]
    json: bool,
}

impl JsonFlag {
    /// Prints `value` on standard output: as one JSON document with `--json`, else as `text`
    /// writes it.
    pub(super) fn print<T: Serialize>(
        &self,
        value: &T,
        text: impl FnOnce(&T) -> String,
    ) -> anyhow::Result<()> {
        cli::print(&if self.json {
            cli::json(value)?
        } else {
            text(value)
        })?;
        Ok(())
    }
}

/// The form-factor cache of the commands that compute form factors.
#[derive(Args)]
pub(super) struct CacheArgs {
    /// Compute the form factors without reading or writing the form-factor cache
    /// ($EIGENRAD_CACHE_DIR, else $XDG_CACHE_HOME/eigenrad, else ~/.cache/eigenrad).
    #[arg(long)]
    no_cache: bool,
    /// How the form factors are stored while the room is solved: f64 up to 5792 patches and
    /// hierarchical above (auto), or always one of them
    #[arg(long, value_enum, default_value_t = OperatorChoice::Auto)]
    operator: OperatorChoice,
    /// How the visibility of a pair of patches that a blocker may cut is found
    #[arg(long, value_enum, default_value_t = VisibilityArg::Exact)]
    visibility: VisibilityArg,
    /// With --visibility sampled: points per side of each patch's grid of ray ends (the rays
    /// of a pair are this to the fourth power)
    #[arg(long, default_value_t = Visibility::DEFAULT_PER_SIDE,
          value_parser = clap::value_parser!(u32).range(1..=i64::from(MAX_PER_SIDE)))]
    visibility_points: u32,
    /// With --visibility clusters: a block of clusters read without shadows whose rays stray
    /// from its visible shares by more than this share of a patch's output is split further,
    /// down to blocks read with the exact shadows; smaller is closer to them and slower
    /// (docs/performance.md, "Visibility between clusters")
    #[arg(long, default_value_t = hierarchical::SHADE_MISFIT, value_parser = misfit)]
    cluster_misfit: f64,
}

/// A `--cluster-misfit`: a share, 0 or more (`inf` keeps every block whole).
fn misfit(text: &str) -> Result<f64, String> {
    match text.parse::<f64>() {
        Ok(x) if x >= 0.0 => Ok(x),
        _ => Err(format!(
            "`{text}` is not a share of 0 or more (such as 1e-3, or inf)"
        )),
    }
}

/// `--visibility`: the help texts are the command line's.
#[derive(Clone, Copy, ValueEnum)]
enum VisibilityArg {
    /// The blockers' shadows cut out of each target at every quadrature point: exact.
    Exact,
    /// Pairs that do not come close: unoccluded form factor times the share of a fixed grid of
    /// rays between the two patches that no blocker cuts; faster with many blockers, readings
    /// within about 1e-3 instead of 1e-6 (docs/performance.md, "Sampled visibility").
    Sampled,
    /// With the hierarchical operator: well-separated clusters of patches that a blocker may
    /// cut are read without shadows, times each patch's visible share of the other cluster
    /// from rays; close pairs keep the exact shadows; readings within about 1e-2
    /// (docs/performance.md, "Visibility between clusters")
    Clusters,
}

impl CacheArgs {
    /// Form-factor settings for a command: the defaults, a progress bar only where someone
    /// watches (never in logs, pipes or tests), and the cache unless `--no-cache`.
    pub(super) fn form_factors(&self) -> FormFactorOptions {
        FormFactorOptions {
            progress: std::io::stderr().is_terminal(),
            cache: if self.no_cache {
                None
            } else {
                cache::default_dir()
            },
            operator: self.operator,
            visibility: match self.visibility {
                VisibilityArg::Exact => Visibility::Exact,
                VisibilityArg::Sampled => Visibility::Sampled {
                    per_side: self.visibility_points,
                },
                VisibilityArg::Clusters => Visibility::Clusters,
            },
            cluster_misfit: self.cluster_misfit,
            ..FormFactorOptions::default()
        }
    }
}
