//! `eigenrad simulate`: a basis, a weather file and a controller file in; the year's summary,
//! hourly CSV and schedule out.

use std::path::Path;

use eigenrad_runtime::Basis;

use super::readout::basis_error;
use crate::error::Result;
use crate::simulate::{self, HourOptions, SkySource, Summary, WeatherSummary};
use crate::weather;

/// What `eigenrad simulate` is asked.
#[derive(Clone, Copy, Debug)]
pub struct SimulateRequest<'a> {
    /// The basis file.
    pub basis: &'a Path,
    /// The weather file.
    pub weather: &'a Path,
    /// The controller file.
    pub controller: &'a Path,
    /// The calendar year of the records (`None`: the first record's).
    pub year: Option<i32>,
    /// Which weather fields drive the sky.
    pub source: SkySource,
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
    let weather = weather::read(request.weather)?;
    let (hours, warnings, sky_from) = simulate::hours(
        &weather,
        &basis,
        &controller.occupancy,
        HourOptions {
            year: request.year,
            source: request.source,
        },
    )?;
    let year = simulate::simulate(bytes, &controller, &hours)?;
    let site = basis.site();
    let location = &weather.location;
    let summary = simulate::summary(
        &request.basis.display().to_string(),
        &controller,
        WeatherSummary {
            path: request.weather.display().to_string(),
            format: format!("{:?}", weather.format).to_uppercase(),
            location: location.name.clone(),
            latitude_longitude: [location.latitude, location.longitude],
            distance_km: site.map_or(0.0, |s| {
                location.distance_km(f64::from(s.latitude), f64::from(s.longitude))
            }),
            records: weather.records.len(),
            sky_from,
        },
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
