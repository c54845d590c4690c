//! A weather file's records as the hours of the year: each record's instant, its occupancy,
//! and its sky as the runtime's `set_sky` takes it, computed as `eigenrad eval --time T`
//! computes a sky (the same function), so that an hour of the year and `eval` at that hour
//! read the same daylight.
//!
//! **The instant.** EPW and TMY3 values are averages over the hour that ends at the
//! record's hour, in the file's local standard time. The sky of a record is computed at the
//! middle of that hour, `hour − 0.5`: the instant Radiance's `epw2wea` writes for the same
//! record, so that the two programs put the sun in the same place.
//!
//! **The sky.** The Perez all-weather sky: its state (clearness, brightness) from the
//! record's direct normal and diffuse horizontal irradiances, the quantities the model was
//! fitted to, scaled to the record's illuminances when the file gives them (the EPW's
//! fields 18 and 19, TMY3's `DN illum` and `DH illum`), else through the Perez efficacies,
//! with the precipitable water of the record's dew point (`w = exp(0.07 T_d − 0.075)` cm, Perez
//! et al., "Modeling daylight availability and irradiance components from direct and global
//! irradiance", Solar Energy 44(5), 1990, eq. 3), or [`WATER_DEFAULT_CM`] without one. A
//! record with neither diffuse nor direct light is dark; with the sun below the horizon the
//! sky keeps its diffuse light and drops the direct (`crate::daylight::sky`).

use chrono::{DateTime, Datelike, Duration, FixedOffset, NaiveDate, TimeZone};
use eigenrad_runtime::Basis;

use super::controller::Occupancy;
use super::{Hour, HourSky};
use crate::accuracy::runtime_eval::SkyState;
use crate::daylight::sky::{sky_at, SkyInput, SkyParams};
use crate::daylight::sun::Site;
use crate::error::{Error, Result};
use crate::weather::{Record, Weather};

/// Precipitable water without a dew point, cm: the Perez efficacies' mid-latitude value,
/// `eigenrad sky --water`'s default.
pub const WATER_DEFAULT_CM: f64 = 2.0;

/// Beyond this distance from the basis' site a weather file is another place's, km: the
/// simulation warns.
pub const WEATHER_DISTANCE_WARN_KM: f64 = 50.0;

/// Which of a weather file's fields drive the sky.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SkySource {
    /// The illuminances when the file gives them, else the irradiances.
    Illuminance,
    /// The irradiances through the Perez efficacies, always (as Radiance's `gendaymtx`).
    Irradiance,
}

/// How records become hours.
#[derive(Clone, Copy, Debug)]
pub struct HourOptions {
    /// The calendar year the records' dates are placed in (their weekdays and the sun's
    /// position); `None`: the first record's, or the latest year before it with as many
    /// days as the file.
    pub year: Option<i32>,
    /// Which fields drive the sky.
    pub source: SkySource,
}

/// The hours of `weather` at the basis' site, occupied as `occupancy` says, with the
/// warnings a user should read (the file's distance from the site, its time zone).
pub fn hours(
    weather: &Weather,
    basis: &Basis<'_>,
    occupancy: &Occupancy,
    options: HourOptions,
) -> Result<(Vec<Hour>, Vec<String>, String)> {
    let site = basis.site().ok_or(eigenrad_runtime::Error::NoDaylight)?;
    let patches = basis
        .sky_patches()
        .ok_or(eigenrad_runtime::Error::NoDaylight)?;
    let mut warnings = Vec::new();
    let location = &weather.location;
    let distance = location.distance_km(f64::from(site.latitude), f64::from(site.longitude));
    if distance > WEATHER_DISTANCE_WARN_KM {
        warnings.push(format!(
            "{} is for {} ({:.3}° N, {:.3}° E), {distance:.0} km from the basis' site ({:.3}° N, {:.3}° E): its weather is another place's",
            weather.path.display(), location.name, location.latitude, location.longitude, site.latitude, site.longitude
        ));
    }
    let site_offset_hours = f64::from(site.utc_offset_minutes) / 60.0;
    if (site_offset_hours - location.utc_offset_hours).abs() > 1e-6 {
        warnings.push(format!(
            "{} keeps standard time at UTC{:+} and the basis' site at UTC{:+}: the hours are the weather file's",
            weather.path.display(),
            location.utc_offset_hours,
            site_offset_hours
        ));
    }
    let offset = FixedOffset::east_opt((location.utc_offset_hours * 3600.0).round() as i32)
        .ok_or_else(|| {
            weather_error(
                weather,
                None,
                "LOCATION time zone",
                "not an offset from UTC",
            )
        })?;
    let year = options.year.unwrap_or_else(|| calendar_year(weather));
    let site_of = Site {
        latitude: f64::from(site.latitude),
        longitude: f64::from(site.longitude),
        elevation: f64::from(site.elevation),
    };
    let with_illuminance = options.source == SkySource::Illuminance
        && weather.illuminance.available()
        && weather
            .records
            .iter()
            .all(|r| r.direct_normal_lux.is_some() && r.diffuse_horizontal_lux.is_some());
    let sky_from = match (with_illuminance, weather.illuminance) {
        (true, crate::weather::Illuminance::HundredsOfLux { .. }) => {
            "illuminances (direct normal, diffuse horizontal; written in hundreds of lux)"
        }
        (true, _) => "illuminances (direct normal, diffuse horizontal)",
        (false, _) => {
            "irradiances (direct normal, diffuse horizontal) through the Perez efficacies"
        }
    };
    let place = Place {
        site: site_of,
        north: f64::from(site.north),
        subdivision: patches.subdivision(),
        dark: vec![0.0f32; patches.count()],
    };
    let mut out = Vec::with_capacity(weather.records.len());
    for r in &weather.records {
        let date = NaiveDate::from_ymd_opt(year, u32::from(r.month), u32::from(r.day)).ok_or_else(
            || {
                weather_error(
                    weather,
                    Some(r.line),
                    "date",
                    &format!(
                        "{:02}-{:02} is not a date of {year}: give a leap year with --year",
                        r.month, r.day
                    ),
                )
            },
        )?;
        let midnight = date.and_hms_opt(0, 0, 0).unwrap_or_default();
        let local = midnight + Duration::seconds((r.mid_hour_minutes() * 60.0).round() as i64);
        let time = offset
            .from_local_datetime(&local)
            .single()
            .ok_or_else(|| weather_error(weather, Some(r.line), "hour", "not a local time"))?;
        let water = r.dew_point.map_or(WATER_DEFAULT_CM, |t| {
            (0.07 * t - 0.075).exp().clamp(0.0, 10.0)
        });
        let sky = place
            .sky(&time, sky_input(r, with_illuminance), water)
            .map_err(|e| weather_error(weather, Some(r.line), "sky", &e.to_string()))?;
        out.push(hour_of(time, r.line, u32::from(r.hour), occupancy, sky));
    }
    Ok((out, warnings, sky_from.to_owned()))
}

/// The site's part of every hour's sky.
struct Place {
    site: Site,
    north: f64,
    subdivision: u8,
    /// Every patch at 0 cd/m²: the sky of a night.
    dark: Vec<f32>,
}

impl Place {
    /// The sky of `input` (none: dark) at `time` with `water` cm of precipitable water, as
    /// `eigenrad eval --time` computes it.
    fn sky(
        &self,
        time: &DateTime<FixedOffset>,
        input: Option<SkyInput>,
        water: f64,
    ) -> crate::daylight::Result<HourSky> {
        let Some(input) = input else {
            let position = crate::daylight::sun::position(
                &self.site,
                time,
                &crate::daylight::sun::SunOptions::default(),
            )?;
            return Ok(HourSky {
                luminance: self.dark.clone(),
                altitude_deg: position.altitude,
                azimuth_deg: position.azimuth,
                ..HourSky::default()
            });
        };
        let params = SkyParams {
            site: self.site,
            north: self.north,
            input,
            water,
            subdivision: self.subdivision,
        };
        let report = sky_at(&params, time)?;
        let state = SkyState::of(&report);
        Ok(HourSky {
            luminance: state.sky_luminance,
            global_horizontal: state.global_horizontal,
            sun: state.sun,
            altitude_deg: report.sun.altitude,
            azimuth_deg: report.sun.azimuth,
            diffuse_horizontal_lux: report.diffuse_horizontal_lux,
            direct_normal_lux: report.direct_normal_lux,
        })
    }
}

/// The hour at `time` (its middle) ending at `hour_ending`, occupied as `occupancy` says.
fn hour_of(
    time: DateTime<FixedOffset>,
    line: usize,
    hour_ending: u32,
    occupancy: &Occupancy,
    sky: HourSky,
) -> Hour {
    let weekday = time.weekday().num_days_from_monday() as usize;
    Hour {
        time,
        line,
        hour_ending,
        weekday,
        occupied: occupancy.occupied(weekday, hour_ending),
        analysis: hour_ending > 8 && hour_ending <= 18,
        sky,
    }
}

/// A sky without a weather file: the same sky every day, driven by the sun alone.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Recipe {
    /// The CIE standard general sky type 1 (overcast) at a diffuse horizontal illuminance
    /// of `300 + 21 000 sin(altitude)` lux (J. Krochmann and M. Seidl, Lighting Research and
    /// Technology 6(3), 1974, the mean overcast sky DIN 5034-2 adopts; the firmware's harvest
    /// loop computes the same); dark with the sun below the horizon.
    Overcast,
    /// The Perez sky of the Ineichen–Perez clear-sky irradiances
    /// ([`crate::daylight::clear_sky`]) for the site's height and this Linke turbidity.
    Clear {
        /// Linke turbidity.
        linke: f64,
    },
}

impl Recipe {
    /// How the summary names the sky.
    pub fn describe(&self) -> String {
        match self {
            Recipe::Overcast => {
                "the CIE overcast sky (standard type 1) at 300 + 21 000 sin(altitude) lux diffuse horizontal".into()
            }
            Recipe::Clear { linke } => format!(
                "the Perez sky of Ineichen–Perez clear-sky irradiances, Linke turbidity {linke}"
            ),
        }
    }
}

/// Every hour from local midnight of `from` to the end of `to` (both included, the basis'
/// standard time), its sky by `recipe`, occupied as `occupancy` says; each hour's sky at its
/// middle, as for a weather file.
pub fn recipe_hours(
    basis: &Basis<'_>,
    occupancy: &Occupancy,
    recipe: Recipe,
    from: NaiveDate,
    to: NaiveDate,
) -> Result<Vec<Hour>> {
    let site = basis.site().ok_or(eigenrad_runtime::Error::NoDaylight)?;
    let patches = basis
        .sky_patches()
        .ok_or(eigenrad_runtime::Error::NoDaylight)?;
    let recipe_error = |reason: String| crate::Error::Daylight {
        what: "--from/--to".into(),
        reason,
    };
    if to < from {
        return Err(recipe_error(format!("{to} is before {from}")));
    }
    let days = (to - from).num_days() + 1;
    if days > 366 * 10 {
        return Err(recipe_error(format!(
            "{days} days: at most ten years a run"
        )));
    }
    if let Recipe::Clear { linke } = recipe {
        if !(linke.is_finite() && (1.0..=10.0).contains(&linke)) {
            return Err(crate::Error::Daylight {
                what: "--linke".into(),
                reason: format!("{linke} is not a Linke turbidity from 1 to 10"),
            });
        }
    }
    let offset = FixedOffset::east_opt((site.utc_offset_minutes * 60.0).round() as i32)
        .ok_or(eigenrad_runtime::Error::NoDaylight)?;
    let place = Place {
        site: Site {
            latitude: f64::from(site.latitude),
            longitude: f64::from(site.longitude),
            elevation: f64::from(site.elevation),
        },
        north: f64::from(site.north),
        subdivision: patches.subdivision(),
        dark: vec![0.0f32; patches.count()],
    };
    let mut out = Vec::with_capacity(days as usize * 24);
    for k in 0..days {
        let date = from + Duration::days(k);
        let midnight = date.and_hms_opt(0, 0, 0).unwrap_or_default();
        for hour in 1..=24u32 {
            let local = midnight + Duration::minutes(i64::from(hour) * 60 - 30);
            let Some(time) = offset.from_local_datetime(&local).single() else {
                continue;
            };
            let position = crate::daylight::sun::position(
                &place.site,
                &time,
                &crate::daylight::sun::SunOptions::default(),
            )?;
            let input = (position.altitude > 0.0).then(|| match recipe {
                Recipe::Overcast => SkyInput::Cie {
                    sky_type: 1,
                    diffuse_horizontal: 300.0 + 21_000.0 * position.altitude.to_radians().sin(),
                    direct_normal: 0.0,
                },
                Recipe::Clear { linke } => {
                    let day = crate::daylight::sun::day_of_year(&time);
                    let c = crate::daylight::clear_sky::ineichen_perez(
                        position.zenith,
                        place.site.elevation,
                        day,
                        linke,
                    );
                    SkyInput::PerezIrradiance {
                        direct_normal: c.direct_normal,
                        diffuse_horizontal: c.diffuse_horizontal,
                    }
                }
            });
            let sky = place.sky(&time, input, WATER_DEFAULT_CM)?;
            out.push(hour_of(time, 0, hour, occupancy, sky));
        }
    }
    Ok(out)
}

/// The calendar a weather file's records are placed in without `--year`: the first record's
/// year when it has as many days as the file (a typical year's first month may be of a leap
/// year while the file has no 29 February), else the latest year before it that has.
fn calendar_year(weather: &Weather) -> i32 {
    let first = weather.records.first().map_or(2026, |r| r.year);
    let leap_file = weather.records.iter().any(|r| r.month == 2 && r.day == 29);
    let leap = |y: i32| NaiveDate::from_ymd_opt(y, 2, 29).is_some();
    (0..8)
        .map(|k| first - k)
        .find(|&y| leap(y) == leap_file)
        .unwrap_or(first)
}

/// The sky input of record `r`: its irradiances for the Perez state, scaled to its
/// illuminances when they drive the sky; `None` when it holds no daylight (night).
fn sky_input(r: &Record, with_illuminance: bool) -> Option<SkyInput> {
    let (dni, dhi) = (r.direct_normal, r.diffuse_horizontal);
    if with_illuminance {
        let (dni_lux, dhi_lux) = (r.direct_normal_lux?, r.diffuse_horizontal_lux?);
        (dhi_lux > 0.0 || dni_lux > 0.0).then_some(SkyInput::PerezMeasured {
            direct_normal: dni,
            diffuse_horizontal: dhi,
            direct_normal_lux: dni_lux,
            diffuse_horizontal_lux: dhi_lux,
        })
    } else {
        (dhi > 0.0 || dni > 0.0).then_some(SkyInput::PerezIrradiance {
            direct_normal: dni,
            diffuse_horizontal: dhi,
        })
    }
}

fn weather_error(weather: &Weather, line: Option<usize>, field: &str, reason: &str) -> Error {
    Error::Weather(crate::weather::WeatherError {
        path: weather.path.clone(),
        line,
        field: Some(field.to_owned()),
        reason: reason.to_owned(),
    })
}
