//! Weather years: the hourly irradiances, illuminances and temperatures of an EnergyPlus
//! weather file (EPW, [`epw`]) or an NREL TMY3 CSV ([`tmy3`]), with the site they belong to,
//! for running a controller through every hour of a year.
//!
//! **Time.** Both formats stamp a record with the hour it ends, 1 to 24, in the site's local
//! standard time (never daylight saving time): hour 1 holds what fell between 00:00 and 01:00.
//! The sky of a record is computed at the middle of that hour ([`Record::mid_hour_minutes`]),
//! as Radiance's `epw2wea` does.
//!
//! **Units.** Irradiances are the hour's mean in W/m² (the files' Wh/m² over one hour),
//! illuminances lux, temperatures °C, the site's latitude and longitude degrees north and
//! east, its elevation metres.
//!
//! **What must be there.** The simulation cannot invent sunlight: a record without its global,
//! direct or diffuse irradiance is an error naming the line and the field. Illuminances and
//! temperatures may be missing ([`None`]). The records must be consecutive hours from hour 1
//! of the first day to hour 24 of the last (8760 for a year, 8784 for a leap year, or any
//! whole number of days).
//!
//! **Illuminance units.** Daylight's luminous efficacy lies between about 90 and 130 lm/W
//! (P. J. Littlefair, "The luminous efficacy of daylight: a review", Lighting Research and
//! Technology 17(4), 162–182, 1985), so the median ratio of global illuminance to global
//! irradiance over the sunlit hours says the unit a file really used ([`Illuminance`]).
//! NREL's TMY3 files head their columns `(lx)` but hold hundreds of lux, the unit of their
//! documentation (1.07 "lm/W" as written in Greensboro's file): they are multiplied by 100.
//! Files that write 0 for every illuminance while the sun shines (many converters do) have
//! none.

pub mod epw;
mod text;
pub mod tmy3;

use std::path::{Path, PathBuf};

pub use epw::parse_epw;
pub use tmy3::parse_tmy3;

/// Mean radius of the Earth, km (the IUGG mean radius R₁, rounded as is usual for the
/// haversine formula).
pub const EARTH_RADIUS_KM: f64 = 6371.0;

/// A weather file that could not be read, or whose content is not a valid hourly weather
/// year. The message names the file, and the 1-based line and the field when the fault is in
/// one: `"{path}:{line}: {field}: {reason}"`. The commands report it as
/// [`crate::Error::Weather`].
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[error("{}{reason}", place(.path, .line, .field))]
pub struct WeatherError {
    /// The file.
    pub path: PathBuf,
    /// The 1-based line at fault, when the fault is in one.
    pub line: Option<usize>,
    /// The field at fault ("global horizontal radiation (field 14)", "`GHI (W/m^2)` (column
    /// 5)"), when the fault is in one.
    pub field: Option<String>,
    /// What is wrong.
    pub reason: String,
}

/// `"{path}:{line}: {field}: "` with what is known.
fn place(path: &Path, line: &Option<usize>, field: &Option<String>) -> String {
    let mut place = path.display().to_string();
    if let Some(line) = line {
        place.push_str(&format!(":{line}"));
    }
    place.push_str(": ");
    if let Some(field) = field {
        place.push_str(field);
        place.push_str(": ");
    }
    place
}

/// The result of this module's functions.
pub type Result<T> = std::result::Result<T, WeatherError>;

/// The format a weather file was read as.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
pub enum Format {
    /// EnergyPlus weather file (EnergyPlus Auxiliary Programs, "Weather Converter Program",
    /// the EPW data dictionary).
    Epw,
    /// NREL TMY3 CSV (S. Wilcox and W. Marion, "Users Manual for TMY3 Data Sets",
    /// NREL/TP-581-43156, 2008).
    Tmy3,
}

/// The site a weather file was measured at (EPW's `LOCATION` line, TMY3's first line).
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct Location {
    /// The station's or city's name as written.
    pub name: String,
    /// State, province or region as written (empty when the file has none).
    pub region: String,
    /// Country as written (empty when the file has none: TMY3 files are all of the USA and
    /// its territories, and do not say it).
    pub country: String,
    /// The station's number as written: WMO in an EPW, USAF in a TMY3 file.
    pub station: String,
    /// Latitude, degrees north (−90 to 90).
    pub latitude: f64,
    /// Longitude, degrees east (−180 to 180).
    pub longitude: f64,
    /// Height above sea level, m.
    pub elevation: f64,
    /// The file's standard time zone, hours east of UTC (−5 for US Eastern Standard Time).
    pub utc_offset_hours: f64,
}

impl Location {
    /// Great-circle distance from this site to another at `latitude` (degrees north) and
    /// `longitude` (degrees east), km: the haversine formula on a sphere of radius
    /// [`EARTH_RADIUS_KM`] (R. W. Sinnott, "Virtues of the Haversine", Sky and Telescope
    /// 68(2), 159, 1984). Within about 0.5 % of the distance on the ellipsoid.
    pub fn distance_km(&self, latitude: f64, longitude: f64) -> f64 {
        let (phi1, phi2) = (self.latitude.to_radians(), latitude.to_radians());
        let half_dphi = (phi2 - phi1) / 2.0;
        let half_dlambda = (longitude - self.longitude).to_radians() / 2.0;
        let h = half_dphi.sin().powi(2) + phi1.cos() * phi2.cos() * half_dlambda.sin().powi(2);
        // Rounding can lift h a hair above 1 for antipodes.
        2.0 * EARTH_RADIUS_KM * h.sqrt().min(1.0).asin()
    }
}

/// One hour of a weather file.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Record {
    /// 1-based line in the file, for messages.
    pub line: usize,
    /// Month, 1 to 12, of the record's date (local standard time).
    pub month: u8,
    /// Day of the month, 1 to 31, of the record's date (local standard time).
    pub day: u8,
    /// The hour the record ends, 1 to 24, local standard time: hour 1 is 00:00–01:00.
    pub hour: u8,
    /// The year as written. Typical years mix years across months (each month is the most
    /// typical of its own years), so it says where a month came from, not the calendar.
    pub year: i32,
    /// Global horizontal irradiance, W/m², the hour's mean (EPW: Wh/m² over the hour).
    pub global_horizontal: f64,
    /// Direct normal irradiance, W/m², the hour's mean.
    pub direct_normal: f64,
    /// Diffuse horizontal irradiance, W/m², the hour's mean.
    pub diffuse_horizontal: f64,
    /// Global horizontal illuminance, lux, the hour's mean; `None` when missing (EPW 999999,
    /// or none in the file: [`Illuminance`]).
    pub global_horizontal_lux: Option<f64>,
    /// Direct normal illuminance, lux; `None` when missing.
    pub direct_normal_lux: Option<f64>,
    /// Diffuse horizontal illuminance, lux; `None` when missing.
    pub diffuse_horizontal_lux: Option<f64>,
    /// Dew-point temperature, °C; `None` when missing (EPW 99.9).
    pub dew_point: Option<f64>,
    /// Dry-bulb temperature, °C; `None` when missing (EPW 99.9).
    pub dry_bulb: Option<f64>,
}

impl Record {
    /// The instant the sky is computed at: the middle of the hour the values average, local
    /// standard time, as minutes after local midnight of (`month`, `day`): (hour − 0.5) × 60.
    /// Radiance's `epw2wea` writes the same (hour − 0.5).
    pub fn mid_hour_minutes(&self) -> f64 {
        (f64::from(self.hour) - 0.5) * 60.0
    }
}

/// How a file's illuminances were read: the median luminous efficacy of its global
/// illuminance over the hours of global irradiance of at least
/// [`Illuminance::SUNLIT_W_M2`] says the unit.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub enum Illuminance {
    /// In lux as written (also when no hour is sunlit enough to tell).
    Lux,
    /// Written in hundreds of lux (TMY2's unit, and the TMY3 files' in fact): multiplied by
    /// 100. `efficacy` is the median ratio as written, lx per W/m² ÷ 100.
    HundredsOfLux {
        /// The median ratio of global illuminance as written to global irradiance.
        efficacy: f64,
    },
    /// No record has illuminances (missing codes throughout, or no such columns).
    Missing,
    /// 0 in every record although the sun shone: the file has none, and they are read as
    /// missing.
    AllZero,
    /// Neither lux nor hundreds of lux: read as missing. `efficacy` is the median ratio of
    /// global illuminance as written to global irradiance.
    Implausible {
        /// The median ratio as written, lx per W/m².
        efficacy: f64,
    },
}

impl Illuminance {
    /// Hours of at least this global irradiance (W/m²) judge the illuminance unit; the
    /// efficacy of the dimmest hours, at sunrise and sunset, strays further.
    pub const SUNLIT_W_M2: f64 = 50.0;
    /// The median global efficacies (lm/W) read as lux: daylight's, with room to spare.
    pub const LUX_EFFICACY: std::ops::RangeInclusive<f64> = 50.0..=250.0;

    /// Whether the records carry illuminances in lux (some may still be `None`).
    pub fn available(&self) -> bool {
        matches!(self, Illuminance::Lux | Illuminance::HundredsOfLux { .. })
    }
}

/// A weather year: the site and its hourly records.
#[derive(Clone, Debug, PartialEq)]
pub struct Weather {
    /// The file it was read from.
    pub path: PathBuf,
    /// The format it was read as.
    pub format: Format,
    /// The site.
    pub location: Location,
    /// One record per hour, consecutive, from hour 1 of the first day to hour 24 of the last.
    pub records: Vec<Record>,
    /// How the illuminances were read.
    pub illuminance: Illuminance,
}

impl Weather {
    /// The number of days the records cover (records ÷ 24; 365 for a year, 366 for a leap
    /// year).
    pub fn days(&self) -> usize {
        self.records.len() / 24
    }
}

/// Reads a weather file, recognising its format by content: an EPW when its first line
/// starts with `LOCATION,`, a TMY3 CSV when its second line starts with `Date (MM/DD/YYYY)`.
/// Text that is not UTF-8 is read as Latin-1 (the names of older files).
pub fn read(path: &Path) -> Result<Weather> {
    let bytes = std::fs::read(path).map_err(|e| WeatherError {
        path: path.to_path_buf(),
        line: None,
        field: None,
        reason: format!("cannot read file: {e}"),
    })?;
    let text = match String::from_utf8(bytes) {
        Ok(text) => text,
        Err(e) => e.into_bytes().iter().map(|&b| char::from(b)).collect(),
    };
    parse(path, &text)
}

/// Parses a weather file's text, recognising its format as [`read`] does; `path` is for
/// messages.
pub fn parse(path: &Path, text: &str) -> Result<Weather> {
    let mut lines = text::lines(text);
    let first = lines.next().map_or("", |(_, l)| l);
    let second = lines.next().map_or("", |(_, l)| l);
    if first.trim_start().starts_with("LOCATION,") {
        parse_epw(path, text)
    } else if second.trim_start().starts_with("Date (MM/DD/YYYY)") {
        parse_tmy3(path, text)
    } else {
        Err(WeatherError {
            path: path.to_path_buf(),
            line: Some(1),
            field: None,
            reason: "neither an EPW weather file (its first line starts with `LOCATION,`) nor a \
                     TMY3 CSV (its second line starts with `Date (MM/DD/YYYY)`)"
                .to_owned(),
        })
    }
}

#[cfg(test)]
mod tests;
