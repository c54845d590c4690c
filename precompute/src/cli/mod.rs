//! What the `eigenrad` subcommands compute and print, kept in the library so tests can call
//! it. Each command's arguments, and how they turn into a call here and an output, are in
//! [`args`] (one file per command); `main.rs` only runs it. One file per command
//! (`readout/` for `solve` and `eval`, with the channel levels they take in `levels.rs`), the
//! build and verify outputs in `report.rs`, and what every command shares: atomic writes, the
//! check that no output replaces an input, JSON and standard output.

pub mod args;
mod figures;
mod form_factors;
mod gains;
pub mod guard;
/// Atomic writes ([`crate::atomic`]), which every command's output goes through.
pub use crate::atomic;
mod inspect;
mod levels;
mod readout;
mod render;
mod report;
mod simulate;
mod sky;
pub mod units;

use serde::Serialize;

use crate::error::{Error, Result};

pub use form_factors::{
    form_factor_table, format_health, format_surface_form_factors, surface_form_factors,
    FormFactorTable, SurfaceFactor,
};
pub use gains::{format_gains, gains, gains_csv, Gain, Gains};
pub use inspect::{format_inspect, inspect, BasisInfo};
pub use levels::{parse_levels, Level, LevelArgs};
pub use readout::{
    eval, eval_with_daylight, format_readout, grids_csv, levels_for_targets, solve,
    solve_with_daylight, DaylightArgs, DaylightReadout, PatchReading, Reading, Readout,
};
pub use render::{render, Pictures, RenderRequest, SurfaceQuantity};
pub use report::{format_build_report, verify_outputs, write_svgs};
pub use simulate::{simulate, HeatMapQuantity, SimulateOutcome, SimulateRequest, Skies};
pub use sky::{format_sky, sky, PatchReport, PerezReport, SkyInput, SkyReport, SkyRequest};
pub use units::Units;

/// `value` as one pretty-printed JSON document, with a final newline.
pub fn json<T: Serialize>(value: &T) -> Result<String> {
    serde_json::to_string_pretty(value)
        .map(|mut text| {
            text.push('\n');
            text
        })
        .map_err(Error::Json)
}

/// Writes `text` to standard output and flushes it. A reader that went away (`| head`) is
/// [`Error::ClosedPipe`]; any other failure (a full disk) is [`Error::Stdout`].
pub fn print(text: &str) -> Result<()> {
    use std::io::Write as _;
    let mut out = std::io::stdout().lock();
    out.write_all(text.as_bytes())
        .and_then(|()| out.flush())
        .map_err(|e| match e.kind() {
            std::io::ErrorKind::BrokenPipe => Error::ClosedPipe,
            _ => Error::Stdout(e),
        })
}
