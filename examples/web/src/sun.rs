//! The sky of a moment at a basis' site, computed as `eigenrad eval --time ... <sky>` computes
//! it (`precompute/src/cli/sky/`): the sun's position by NREL's SPA (`solar-positioning`, the
//! host's crate and settings: ΔT estimated from the local year and month, refraction in a
//! standard atmosphere of 1013.25 mbar and 15 °C), the sky models of the runtime, every patch's
//! luminance as the host forms it (the model's `f32` relative luminance times an `f64` scale,
//! rounded to `f32`), so that the page reads what `eval` prints.

use eigenrad_runtime::sky::{self, cie::CieSky, efficacy, perez, RelativeSky};
use eigenrad_runtime::{Error, Site, Sun};
use solar_positioning::time::JulianDate;
use solar_positioning::{delta_t, Location, RefractionCorrection, SolarPositions};

/// Standard atmosphere of the refraction correction, as the host's: mbar, °C.
const PRESSURE: f64 = 1013.25;
const TEMPERATURE: f64 = 15.0;

/// A local date and time at the site, in its standard time (the basis' UTC offset).
#[derive(Clone, Copy, Debug)]
pub struct Moment {
    /// Year, month (1–12) and day (1–31).
    pub year: i32,
    pub month: u32,
    pub day: u32,
    /// Minutes after local midnight.
    pub minute: u32,
    /// Local time minus UTC, minutes.
    pub offset: i32,
}

/// Which sky, and what drives it: the choices of `eigenrad eval`'s sky flags.
#[derive(Clone, Copy, Debug)]
pub enum SkyInput {
    /// CIE standard general sky type 1–15, or 0 for the traditional overcast sky, scaled to a
    /// diffuse horizontal illuminance (lux), with a sun of a direct normal illuminance (lux).
    Cie {
        sky_type: u8,
        diffuse_horizontal: f64,
        direct_normal: f64,
    },
    /// The Perez sky from a direct normal and a diffuse horizontal irradiance, W/m².
    PerezIrradiance {
        direct_normal: f64,
        diffuse_horizontal: f64,
        water: f64,
    },
    /// The Perez sky from a direct normal and a diffuse horizontal illuminance, lux.
    PerezIlluminance {
        direct_normal: f64,
        diffuse_horizontal: f64,
        water: f64,
    },
}

/// What went wrong with a moment or a sky.
#[derive(Debug)]
pub enum SkyError {
    /// The runtime refused an input.
    Runtime(&'static str, Error),
    /// The sun's position could not be computed.
    Sun(solar_positioning::Error),
    /// The date does not exist.
    Date,
    /// The sun is at or below the horizon: the sky models need it above.
    BelowHorizon { altitude: f64, azimuth: f64 },
}

impl core::fmt::Display for SkyError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            SkyError::Runtime(what, e) => write!(f, "{what}: {e}"),
            SkyError::Sun(e) => write!(f, "sun position: {e}"),
            SkyError::Date => write!(f, "the date does not exist"),
            SkyError::BelowHorizon { altitude, azimuth } => write!(
                f,
                "the sun is below the horizon then (altitude {altitude:.2}°, azimuth \
                 {azimuth:.2}°): the sky models need it above"
            ),
        }
    }
}

impl From<solar_positioning::Error> for SkyError {
    fn from(e: solar_positioning::Error) -> Self {
        SkyError::Sun(e)
    }
}

/// A sky state ready for the daylight evaluator, with the figures the page shows.
#[derive(Clone, Debug)]
pub struct SkyState {
    /// The sun's apparent altitude and azimuth (clockwise from north), degrees.
    pub altitude: f64,
    pub azimuth: f64,
    /// Every sky patch's luminance, cd/m², in the basis' order.
    pub luminance: Vec<f32>,
    /// Diffuse horizontal, direct normal and global horizontal illuminance, lux.
    pub diffuse_horizontal: f64,
    pub direct_normal: f64,
    pub global_horizontal: f64,
    /// The sun as the evaluator takes it (none without direct light).
    pub sun: Option<Sun>,
}

/// Days from 1970-01-01 to the proleptic Gregorian date (H. Hinnant's `days_from_civil`).
fn days_from_civil(year: i32, month: u32, day: u32) -> i64 {
    let y = i64::from(year) - i64::from(month <= 2);
    let era = y.div_euclid(400);
    let yoe = y - era * 400;
    let m = i64::from(month);
    let doy = (153 * (if m > 2 { m - 3 } else { m + 9 }) + 2) / 5 + i64::from(day) - 1;
    let doe = yoe * 365 + yoe / 4 - yoe / 100 + doy;
    era * 146_097 + doe - 719_468
}

fn is_leap(year: i32) -> bool {
    (year % 4 == 0 && year % 100 != 0) || year % 400 == 0
}

impl Moment {
    /// Whether the date exists and the minute is within the day.
    fn check(&self) -> Result<(), SkyError> {
        let days = [
            31,
            28 + u32::from(is_leap(self.year)),
            31,
            30,
            31,
            30,
            31,
            31,
            30,
            31,
            30,
            31,
        ];
        let ok = (1..=12).contains(&self.month)
            && self.day >= 1
            && days
                .get(self.month as usize - 1)
                .is_some_and(|&d| self.day <= d)
            && self.minute < 24 * 60
            && (1..=9999).contains(&self.year);
        if ok {
            Ok(())
        } else {
            Err(SkyError::Date)
        }
    }

    /// Day of the local year, 1 to 366 (the Perez sky's extraterrestrial irradiance).
    fn day_of_year(&self) -> u16 {
        let first = days_from_civil(self.year, 1, 1);
        (days_from_civil(self.year, self.month, self.day) - first + 1) as u16
    }
}

/// The sun's apparent altitude, zenith angle and azimuth at `moment`, degrees.
fn position(site: &Site, moment: Moment) -> Result<(f64, f64, f64), SkyError> {
    let seconds = days_from_civil(moment.year, moment.month, moment.day) * 86_400
        + i64::from(moment.minute) * 60
        - i64::from(moment.offset) * 60;
    let dt = delta_t::estimate_from_date(moment.year, moment.month)?;
    let time = JulianDate::new(2_440_587.5 + seconds as f64 / 86_400.0, dt)?;
    let location = Location {
        latitude: f64::from(site.latitude),
        longitude: f64::from(site.longitude),
    };
    let refraction = RefractionCorrection::new(PRESSURE, TEMPERATURE)?;
    let p = SolarPositions::new().at_from_julian(
        time,
        location,
        f64::from(site.elevation),
        Some(refraction),
    )?;
    Ok((p.elevation_angle(), p.zenith_angle(), p.azimuth()))
}

/// A relative sky, the factor from its relative luminance to cd/m², and its diffuse
/// horizontal and direct normal illuminance, lux: `precompute/src/cli/sky/models.rs`.
type Built = (Box<dyn RelativeSky>, f64, f64, f64);

fn runtime(what: &'static str) -> impl Fn(Error) -> SkyError {
    move |e| SkyError::Runtime(what, e)
}

fn built_sky(input: SkyInput, sun: [f32; 3], zenith: f32, day: u16) -> Result<Built, SkyError> {
    match input {
        SkyInput::Cie {
            sky_type,
            diffuse_horizontal,
            direct_normal,
        } => {
            let sky = if sky_type == 0 {
                CieSky::traditional_overcast(sun)
            } else {
                CieSky::standard(sky_type, sun)
            }
            .map_err(runtime("CIE sky type"))?;
            let lz = sky
                .zenith_luminance_for(diffuse_horizontal as f32)
                .map_err(runtime("diffuse horizontal illuminance"))?;
            Ok((
                Box::new(sky),
                f64::from(lz),
                diffuse_horizontal,
                direct_normal,
            ))
        }
        SkyInput::PerezIrradiance {
            direct_normal,
            diffuse_horizontal,
            water,
        } => {
            let (dni, dhi) = (direct_normal as f32, diffuse_horizontal as f32);
            let c = perez::Conditions::from_irradiance(dhi, dni, zenith, day)
                .map_err(runtime("direct normal and diffuse horizontal irradiance"))?;
            perez_sky(&c, sun, water as f32, f64::from(dhi), f64::from(dni))
        }
        SkyInput::PerezIlluminance {
            direct_normal,
            diffuse_horizontal,
            water,
        } => {
            let (dni, dhi) = (direct_normal as f32, diffuse_horizontal as f32);
            let (c, dhi_w, dni_w) =
                perez::Conditions::from_illuminance(dhi, dni, zenith, day, water as f32)
                    .map_err(runtime("direct normal and diffuse horizontal illuminance"))?;
            let (sky, scale, diffuse, _) =
                perez_sky(&c, sun, water as f32, f64::from(dhi_w), f64::from(dni_w))?;
            // Scaled to the illuminances given, not to their round trip through the
            // efficacies.
            Ok((
                sky,
                scale * (diffuse_horizontal / diffuse),
                diffuse_horizontal,
                direct_normal,
            ))
        }
    }
}

fn perez_sky(
    c: &perez::Conditions,
    sun: [f32; 3],
    water: f32,
    dhi_w: f64,
    dni_w: f64,
) -> Result<Built, SkyError> {
    let sky = perez::PerezSky::new(c, sun).map_err(runtime("Perez sky"))?;
    let kd = efficacy::diffuse(c, water).map_err(runtime("precipitable water"))?;
    let kb = efficacy::direct(c, water).map_err(runtime("precipitable water"))?;
    let diffuse = dhi_w * f64::from(kd);
    let direct = dni_w * f64::from(kb);
    let scale = f64::from(
        sky.luminance_scale(diffuse as f32)
            .map_err(runtime("Perez sky"))?,
    );
    Ok((Box::new(sky), scale, diffuse, direct))
}

/// The sky of `input` at `moment` at `site`, with `patches`' luminances.
pub fn sky_state(
    site: &Site,
    patches: &sky::patches::SkyPatches,
    moment: Moment,
    input: SkyInput,
) -> Result<SkyState, SkyError> {
    moment.check()?;
    let (altitude, zenith, azimuth) = position(site, moment)?;
    if altitude < 0.0 {
        return Err(SkyError::BelowHorizon { altitude, azimuth });
    }
    // The sun in the site's frame, in f64 then f32, as the host's `room_direction`.
    let (h, a) = (altitude.to_radians(), azimuth.to_radians());
    let direction = [a.sin() * h.cos(), a.cos() * h.cos(), h.sin()].map(|x| x as f32);
    let zenith = (zenith.to_radians() as f32).min(core::f32::consts::FRAC_PI_2);
    let (relative, scale, diffuse, direct) =
        built_sky(input, direction, zenith, moment.day_of_year())?;
    let mut luminance = Vec::with_capacity(patches.count());
    for i in 0..patches.count() {
        let Some(p) = patches.patch(i) else { break };
        luminance.push((f64::from(relative.relative_luminance(p.direction)) * scale) as f32);
    }
    let sun = (direct > 0.0).then(|| Sun {
        direction: sky::direction(altitude.to_radians() as f32, azimuth.to_radians() as f32),
        direct_normal: direct as f32,
    });
    Ok(SkyState {
        altitude,
        azimuth,
        luminance,
        diffuse_horizontal: diffuse,
        direct_normal: direct,
        global_horizontal: diffuse + direct * altitude.to_radians().sin(),
        sun,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Hinnant's algorithm against dates counted by hand: 1970-01-01 is day 0, 2000-03-01 is
    /// 30 years (7 leap days: 72..96) plus Jan and Feb 2000 after it.
    #[test]
    fn civil_days() {
        assert_eq!(days_from_civil(1970, 1, 1), 0);
        assert_eq!(days_from_civil(2000, 3, 1), 30 * 365 + 7 + 31 + 29);
        let m = |month, day| Moment {
            year: 2024,
            month,
            day,
            minute: 0,
            offset: 0,
        };
        assert_eq!(m(12, 31).day_of_year(), 366);
        assert_eq!(m(3, 1).day_of_year(), 61);
        assert!(m(2, 30).check().is_err() && m(2, 29).check().is_ok());
    }
}
