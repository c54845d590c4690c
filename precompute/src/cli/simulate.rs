//! `eigenrad simulate`: a basis, a weather file and a controller file in; the year's summary,
//! hourly CSV and schedule out.

use std::path::Path;

use eigenrad_runtime::Basis;

use super::readout::basis_error;
use crate::error::Result;
use chrono::NaiveDate;

use crate::simulate::{self, HourOptions, Recipe, SkySource, Summary, WeatherSummary};
use crate::weather;

/// Where a year's skies come from.
#[derive(Clone, Copy, Debug)]
pub enum Skies<'a> {
    /// A weather file.
    Weather {
        /// The file.
        path: &'a Path,
        /// The calendar year of the records (`None`: the first record's).
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

/// What `eigenrad simulate` is asked.
#[derive(Clone, Copy, Debug)]
pub struct SimulateRequest<'a> {
    /// The basis file.
    pub basis: &'a Path,
    /// The skies.
    pub skies: Skies<'a>,
    /// The controller file.
    pub controller: &'a Path,
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
    Ok(SimulateOutcome {
        hourly_csv: simulate::hourly_csv(&basis, &controller, &hours, &year)?,
        schedule_csv: simulate::schedule_csv(&controller, &year),
        summary,
    })
}
