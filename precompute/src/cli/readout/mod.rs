//! `eigenrad solve` and `eigenrad eval`: the readings of a scene's exact solve
//! (`solve.rs`) or of a basis evaluated through the runtime (`eval.rs`), for channel levels
//! given as `NAME=VALUE` or as DALI arc levels `NAME=ARC` (`cli/levels.rs`), and their
//! table and CSV (`format.rs`). Both give the same document, [`Readout`].

mod eval;
mod format;
mod solve;

use std::path::Path;

use eigenrad_runtime::Quantity;
use serde::Serialize;

use super::levels::Level;
use super::sky::{SkyInput, SkyReport};
use crate::error::Error;
use crate::pipeline::GridReadout;

pub use eval::{eval, eval_with_daylight, levels_for_targets};
pub(super) use format::write_grids;
pub use format::{format_readout, grids_csv};
pub use solve::{solve, solve_with_daylight};

/// One sensor or zone reading.
#[derive(Clone, Debug, Serialize)]
pub struct Reading {
    /// Sensor or zone name.
    pub name: String,
    /// Irradiance per band (W/m²) or illuminance (lux): all the light, daylight included.
    pub irradiance: Vec<f64>,
    /// With a sky (`solve --time`): the part of `irradiance` that daylight gives, lux.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub daylight: Option<Vec<f64>>,
    /// With a sky: the part the channels give at their levels, lux.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub electric: Option<Vec<f64>>,
}

impl Reading {
    /// A reading of all the light, without a daylight split.
    pub(super) fn total(name: String, irradiance: Vec<f64>) -> Reading {
        Reading {
            name,
            irradiance,
            daylight: None,
            electric: None,
        }
    }
}

/// One patch's results.
#[derive(Clone, Debug, Serialize)]
pub struct PatchReading {
    /// Patch index.
    pub id: usize,
    /// Surface name.
    pub surface: String,
    /// Area, m².
    pub area: f64,
    /// Centroid, m.
    pub centroid: [f64; 3],
    /// Exitance per band, W/m² or lux.
    pub exitance: Vec<f64>,
    /// Irradiance per band, W/m² or lux; `null` where the patch is black and the runtime
    /// cannot tell.
    pub irradiance: Option<Vec<f64>>,
}

/// The JSON document of `solve` and `eval`.
#[derive(Clone, Debug, Serialize)]
pub struct Readout {
    /// Unit of every irradiance and exitance.
    pub unit: &'static str,
    /// Band names.
    pub bands: Vec<&'static str>,
    /// Channel levels used.
    pub levels: Vec<Level>,
    /// Sensor readings.
    pub sensors: Vec<Reading>,
    /// Zone readings (area-average irradiance).
    pub zones: Vec<Reading>,
    /// Calculation grids of the zones that have one, with their figures.
    pub grids: Vec<GridReadout>,
    /// Per patch, with `--patches`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub patches: Option<Vec<PatchReading>>,
    /// With a sky (`solve --time`): the sky, and the grids under daylight alone.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub daylight: Option<DaylightReadout>,
}

/// Daylight for `solve`: a time and a sky, driven by the same flags as `eigenrad sky`. The
/// site and the room's orientation are the scene's `[site]`.
#[derive(Clone, Debug)]
pub struct DaylightArgs {
    /// Date-time, RFC 3339 with its UTC offset; without one, the site's `utc_offset`.
    pub time: String,
    /// The sky and what drives it.
    pub input: SkyInput,
    /// Precipitable water, cm (Perez efficacies).
    pub water: f64,
    /// Reinhart subdivision MF (1: Tregenza's 145 patches).
    pub subdivision: u8,
}

/// The sky a readout's daylight comes from, and the grids under daylight alone.
#[derive(Clone, Debug, Serialize)]
pub struct DaylightReadout {
    /// The time, RFC 3339 with its offset.
    pub time: String,
    /// `CIE type N`, `CIE traditional overcast` or `Perez`.
    pub model: String,
    /// The sun seen from the site (apparent altitude).
    pub sun: crate::daylight::sun::SunPosition,
    /// The sun's direction in the room's frame (unit vector).
    pub sun_direction_room: [f64; 3],
    /// The sun is below the horizon: the sky's light alone, no direct sun.
    pub sun_below_horizon: bool,
    /// Diffuse horizontal illuminance of the unobstructed sky, lux.
    pub diffuse_horizontal_lux: f64,
    /// Direct normal illuminance of the sun, lux.
    pub direct_normal_lux: f64,
    /// Global horizontal illuminance, lux: what lights the ground outside.
    pub global_horizontal_lux: f64,
    /// The sky patches: `tregenza` (MF:1) or `reinhart MF:n`, and how many.
    pub patch_set: String,
    /// Number of sky patches.
    pub patch_count: usize,
    /// The glazed surfaces the daylight enters through.
    pub windows: Vec<String>,
    /// The zones' grids under daylight alone, with their figures.
    pub grids: Vec<GridReadout>,
    /// What the sky made of its input ([`SkyReport::notes`]): a direct light dropped below
    /// the horizon.
    pub notes: Vec<String>,
}

impl DaylightReadout {
    /// The readout of the sky of `report`, through `windows` (their names), with the grids
    /// under daylight alone.
    pub(super) fn of(report: SkyReport, windows: Vec<String>, grids: Vec<GridReadout>) -> Self {
        DaylightReadout {
            patch_count: report.patches.len(),
            time: report.time,
            model: report.model,
            sun: report.sun,
            sun_direction_room: report.sun_direction_room,
            sun_below_horizon: report.sun_below_horizon,
            diffuse_horizontal_lux: report.diffuse_horizontal_lux,
            direct_normal_lux: report.direct_normal_lux,
            global_horizontal_lux: report.global_horizontal_lux,
            patch_set: report.patch_set,
            windows,
            grids,
            notes: report.notes,
        }
    }
}

/// The names of a readout's bands: `photopic` for one band, else red, green and blue.
pub(super) fn band_names(count: usize) -> Vec<&'static str> {
    if count == 1 {
        vec!["photopic"]
    } else {
        vec!["red", "green", "blue"]
    }
}

/// The unit of a basis' readings of `q`: lux for photometric bands, W/m² for radiometric ones.
pub(super) fn unit(q: Quantity) -> &'static str {
    match q {
        Quantity::Photometric => "lux",
        _ => "W/m²",
    }
}

/// A runtime error about the basis at `path`, as the crate's error naming the file.
pub(super) fn basis_error(path: &Path) -> impl Fn(eigenrad_runtime::Error) -> Error + '_ {
    move |reason| Error::Basis {
        path: path.to_path_buf(),
        reason,
    }
}

/// An error about daylight, naming the flag (`what`) it concerns.
fn daylight_err(what: &str, reason: impl Into<String>) -> Error {
    Error::Daylight {
        what: what.to_owned(),
        reason: reason.into(),
    }
}

/// `time` as given, or with the site's UTC offset (seconds east) when it has none.
fn with_site_offset(time: &str, offset: Option<i32>) -> String {
    match (crate::daylight::sun::parse_time(time), offset) {
        (Ok(_), _) | (Err(_), None) => time.trim().to_owned(),
        (Err(_), Some(offset)) => match chrono::FixedOffset::east_opt(offset) {
            // Displayed as `+HH:MM`, the form `parse_time` reads.
            Some(offset) => format!("{}{offset}", time.trim()),
            None => time.trim().to_owned(),
        },
    }
}
