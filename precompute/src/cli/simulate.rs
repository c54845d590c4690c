//! `eigenrad simulate`: a basis, a weather file and a controller file in; the year's summary,
//! hourly CSV, schedule and heat map out.
//!
//! The year ([`crate::simulate`]) and the heat map's drawing ([`crate::picture::heatmap`]) do
//! not know each other: here the year's hours become the drawing's plain values.

use std::path::Path;
use std::str::FromStr;

use chrono::Timelike;
use eigenrad_runtime::Basis;

use super::readout::basis_error;
use crate::error::{Error, Result};
use crate::picture::heatmap::{HeatMap, HeatMapInput, HOURS};
use crate::simulate::{
    self, Controller, Hour, HourOptions, Recipe, SkySource, Summary, WeatherSummary, Year,
};
use crate::weather;
use chrono::NaiveDate;

/// Where a year's skies come from.
#[derive(Clone, Copy, Debug)]
pub enum Skies<'a> {
    /// A weather file.
    Weather {
        /// The file.
        path: &'a Path,
        /// The calendar year of the records (`None`: the first record's, or the latest year
        /// before it with as many days as the file).
        year: Option<i32>,
        /// Which of its fields drive the sky.
        source: SkySource,
    },
    /// A sky recipe over a range of days.
    Recipe {
        /// The recipe.
        recipe: Recipe,
        /// The first day.
        from: NaiveDate,
        /// The last day, included.
        to: NaiveDate,
    },
}
/// What the heat map of the year (`--heatmap-of`) colours each hour by.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub enum HeatMapQuantity {
    /// The power of the controller's strategy, W: the sum over its channels (standby when
    /// off), the hourly CSV's `power_w:*` columns added up.
    #[default]
    Power,
    /// The daylight illuminance of the zone of this name, lux (daylight alone, as the hourly
    /// CSV's `daylight_lux:zone:*`).
    Daylight(String),
}

impl FromStr for HeatMapQuantity {
    type Err = String;

    /// `power`, or `daylight:ZONE`.
    fn from_str(s: &str) -> std::result::Result<Self, String> {
        match s.split_once(':') {
            None if s == "power" => Ok(HeatMapQuantity::Power),
            Some(("daylight", zone)) if !zone.is_empty() => {
                Ok(HeatMapQuantity::Daylight(zone.to_owned()))
            }
            Some(("daylight", _)) => Err("name the zone: `daylight:ZONE`".into()),
            _ => Err(format!(
                "`{s}` is no quantity of the year: `power` (W, the controller's channels) or `daylight:ZONE` (lux)"
            )),
        }
    }
}

impl std::fmt::Display for HeatMapQuantity {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            HeatMapQuantity::Power => f.write_str("power"),
            HeatMapQuantity::Daylight(zone) => write!(f, "daylight:{zone}"),
        }
    }
}

/// What `eigenrad simulate` is asked.
#[derive(Clone, Copy, Debug)]
pub struct SimulateRequest<'a> {
    /// The basis file.
    pub basis: &'a Path,
    /// The skies.
    pub skies: Skies<'a>,
    /// The controller file.
    pub controller: &'a Path,
    /// Draw the year as a day × hour heat map of this quantity.
    pub heatmap: Option<&'a HeatMapQuantity>,
}

/// What a year gives.
#[derive(Clone, Debug)]
pub struct SimulateOutcome {
    /// The summary.
    pub summary: Summary,
    /// The hourly CSV.
    pub hourly_csv: String,
    /// The EnergyPlus schedule.
    pub schedule_csv: String,
    /// The heat map, when asked for, ready to draw as PNG or SVG.
    pub heatmap: Option<HeatMap>,
}

/// The zone a heat map of `quantity` reads (`None` for the power), checked against the basis
/// before the year runs.
fn heatmap_zone(
    quantity: &HeatMapQuantity,
    basis: &Basis<'_>,
    path: &Path,
) -> Result<Option<usize>> {
    let HeatMapQuantity::Daylight(zone) = quantity else {
        return Ok(None);
    };
    basis.find_zone(zone).map(Some).ok_or_else(|| {
        let names: Vec<&str> = (0..basis.zone_count())
            .filter_map(|z| basis.zone_name(z).ok())
            .collect();
        Error::Argument {
            flag: "--heatmap-of",
            argument: quantity.to_string(),
            reason: format!(
                "the basis {} has no zone `{zone}` (it has: {})",
                path.display(),
                if names.is_empty() {
                    "none".into()
                } else {
                    names.join(", ")
                }
            ),
        }
    })
}

/// The heat map of the year: each hour's value placed by its local standard date and hour
/// (the middle of the hour, [`Hour::time`]), so that a record missing from the weather file
/// is a grey cell and not a shift of every later hour.
fn heatmap(
    quantity: &HeatMapQuantity,
    zone: Option<usize>,
    request: &SimulateRequest<'_>,
    controller: &Controller,
    hours: &[Hour],
    year: &Year,
) -> HeatMap {
    let value = |r: &simulate::HourResult| match zone {
        Some(z) => r.zone_daylight.get(z).map_or(f64::NAN, |&x| f64::from(x)),
        None => r.power_w.iter().sum(),
    };
    let first_day = hours
        .iter()
        .map(|h| h.time.date_naive())
        .min()
        .unwrap_or_default();
    let mut values = Vec::new();
    for (h, r) in hours.iter().zip(&year.hours) {
        let day = (h.time.date_naive() - first_day).num_days() as usize;
        let k = day * HOURS + h.time.hour() as usize;
        if values.len() <= k {
            values.resize(k + 1, f64::NAN);
        }
        values[k] = value(r);
    }
    let name = |p: &Path| {
        p.file_name().map_or_else(
            || p.display().to_string(),
            |n| n.to_string_lossy().into_owned(),
        )
    };
    let strategy = controller.strategy.name();
    let (title, quantity_name, unit, what) = match quantity {
        HeatMapQuantity::Power => {
            let kwh = year
                .hours
                .iter()
                .map(|r| r.power_w.iter().sum::<f64>())
                .sum::<f64>()
                / 1000.0;
            let channels: Vec<&str> = controller
                .channels
                .iter()
                .map(|c| c.name.as_str())
                .collect();
            (
                format!("{}: the {strategy} controller's power, hour by hour", name(request.basis)),
                "power".to_owned(),
                "W",
                format!(
                    "power: the sum over the channels {} (standby when off), {kwh:.1} kWh over the hours drawn",
                    channels.join(", ")
                ),
            )
        }
        HeatMapQuantity::Daylight(zone) => (
            format!(
                "{}: daylight on zone {zone}, hour by hour",
                name(request.basis)
            ),
            format!("daylight on {zone}"),
            "lux",
            "daylight alone (no electric light), the zone's illuminance as `eval --time` reads it"
                .to_owned(),
        ),
    };
    HeatMap::new(HeatMapInput {
        title,
        quantity: quantity_name,
        unit,
        first_day,
        values,
        notes: vec![
            what,
            format!(
                "{}, controller {} ({strategy} strategy)",
                match request.skies {
                    Skies::Weather { path, .. } => format!("weather {}", name(path)),
                    Skies::Recipe { recipe, from, to } => {
                        format!("{} from {from} to {to}", recipe.describe())
                    }
                },
                name(request.controller)
            ),
        ],
    })
}

/// Runs the year the request names on the basis `bytes`.
pub fn simulate(request: &SimulateRequest<'_>, bytes: &[u8]) -> Result<SimulateOutcome> {
    let basis = Basis::from_bytes(bytes).map_err(basis_error(request.basis))?;
    if !basis.has_daylight() {
        return Err(crate::Error::Daylight {
            what: "simulate".into(),
            reason: format!(
                "{} carries no daylight: build it from a scene with a [site] and glazed windows (docs/scene.md, \"Daylight\")",
                request.basis.display()
            ),
        });
    }
    basis.check_daylight().map_err(basis_error(request.basis))?;
    let heatmap_zone = request
        .heatmap
        .map(|q| heatmap_zone(q, &basis, request.basis))
        .transpose()?
        .flatten();
    let controller = simulate::load_controller(request.controller, &basis)?;
    let (hours, weather, warnings) = match request.skies {
        Skies::Weather { path, year, source } => {
            let weather = weather::read(path)?;
            let (hours, warnings, sky_from) = simulate::hours(
                &weather,
                &basis,
                &controller.occupancy,
                HourOptions { year, source },
            )?;
            let location = &weather.location;
            let summary = WeatherSummary {
                path: path.display().to_string(),
                format: format!("{:?}", weather.format).to_uppercase(),
                location: location.name.clone(),
                latitude_longitude: [location.latitude, location.longitude],
                distance_km: basis.site().map_or(0.0, |s| {
                    location.distance_km(f64::from(s.latitude), f64::from(s.longitude))
                }),
                records: weather.records.len(),
                sky_from,
            };
            (hours, summary, warnings)
        }
        Skies::Recipe { recipe, from, to } => {
            let hours = simulate::recipe_hours(&basis, &controller.occupancy, recipe, from, to)?;
            let site = basis.site();
            let summary = WeatherSummary {
                path: String::new(),
                format: format!("no weather file: {from} to {to}"),
                location: "the basis' site".into(),
                latitude_longitude: site.map_or([0.0; 2], |s| {
                    [f64::from(s.latitude), f64::from(s.longitude)]
                }),
                distance_km: 0.0,
                records: hours.len(),
                sky_from: recipe.describe(),
            };
            (hours, summary, Vec::new())
        }
    };
    let year = simulate::simulate(bytes, &controller, &hours)?;
    let summary = simulate::summary(
        &request.basis.display().to_string(),
        &controller,
        weather,
        &hours,
        &year,
        warnings,
    );
    let heatmap = request
        .heatmap
        .map(|q| heatmap(q, heatmap_zone, request, &controller, &hours, &year));
    Ok(SimulateOutcome {
        heatmap,
        hourly_csv: simulate::hourly_csv(&basis, &controller, &hours, &year)?,
        schedule_csv: simulate::schedule_csv(&controller, &year),
        summary,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `power` and `daylight:ZONE` read back as they are written; a zone left out or another
    /// quantity is refused with what is accepted.
    #[test]
    fn heat_map_quantities_parse() {
        for text in ["power", "daylight:work_plane", "daylight:a:b"] {
            let q: HeatMapQuantity = text.parse().unwrap();
            assert_eq!(q.to_string(), text);
        }
        assert_eq!(
            "daylight:desk".parse::<HeatMapQuantity>(),
            Ok(HeatMapQuantity::Daylight("desk".into()))
        );
        assert!("daylight:"
            .parse::<HeatMapQuantity>()
            .unwrap_err()
            .contains("daylight:ZONE"));
        for bad in ["lux", "Power", "total:work_plane", ""] {
            let e = bad.parse::<HeatMapQuantity>().unwrap_err();
            assert!(
                e.contains("`power`") && e.contains("`daylight:ZONE`"),
                "{e}"
            );
        }
    }
}
