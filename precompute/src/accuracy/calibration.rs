//! What a commissioning engineer calibrates a closed-loop photosensor with: each sensor's
//! reading per unit of each zone's (its work plane), separately for every channel and for
//! daylight under the CIE overcast sky, a clear sky and the sun, read through the runtime
//! from the basis' bytes exactly as a controller reads them. A sensor calibrated at night
//! (electric light) reads daylight with another ratio: the difference between these columns
//! is the error that calibration makes by day.

use eigenrad_runtime::sky::cie::CieSky;
use eigenrad_runtime::sky::sun_grid::direction_of;
use eigenrad_runtime::{Basis, ChannelEvaluator, Sun};
use serde::Serialize;

use super::runtime_eval::{evaluate_daylight, SkyState, MAX_CHANNELS};
use crate::error::Result;

/// The CIE standard sky type of the clear sky: 12, "CIE standard clear sky, low luminance
/// turbidity" (CIE S 011/E:2003, type V.4).
pub const CLEAR_SKY_TYPE: u8 = 12;

/// `[output][channel][band]`: sensors' or zones' readings with one channel at level 1 at a
/// time, others off (lux, fc or W/m² per unit level, as the basis stores them).
pub type PerOutput = Vec<Vec<Vec<f64>>>;

/// Every sensor's and zone's reading (sensors, then zones) per unit of each kind of daylight,
/// lux per lux: `None` for a basis without daylight.
#[derive(Clone, Debug, Default, Serialize)]
pub struct DaylightUnits {
    /// Under the CIE traditional overcast sky, per lux of diffuse horizontal illuminance
    /// outside (the daylight factor, a fraction).
    pub overcast: Vec<f64>,
    /// Under the clear sky ([`CLEAR_SKY_TYPE`]) with the sun at solar noon on an equinox,
    /// the sky alone, per lux of diffuse horizontal illuminance outside.
    pub clear_sky: Vec<f64>,
    /// The sun alone at that moment, per lux of direct normal illuminance; `None` when it
    /// is below the horizon at the site's latitude.
    pub sun: Option<Vec<f64>>,
}

/// One sensor's ratio to one zone: what it reads per unit of the zone's reading.
#[derive(Clone, Debug, Serialize)]
pub struct SensorRatio {
    /// Sensor name.
    pub sensor: String,
    /// Zone name.
    pub zone: String,
    /// Per channel (dimensionless): the ratio of the two readings' luminous values
    /// (photopic bases: the reading; rgb: the BT.709 luminance of the three bands); `None`
    /// where the zone reads nothing from that channel.
    pub per_channel: Vec<Option<f64>>,
    /// Under the CIE overcast sky; `None` without daylight or where the zone reads none.
    pub overcast: Option<f64>,
    /// Under the clear sky, the sky alone.
    pub clear_sky: Option<f64>,
    /// Under the sun alone.
    pub sun: Option<f64>,
}

/// Every sensor's and zone's reading with each channel at level 1 in turn, through the
/// runtime's [`ChannelEvaluator`].
pub fn channel_readings(basis: Basis<'_>) -> Result<(PerOutput, PerOutput)> {
    Ok(match basis.bands() {
        1 => read::<1>(basis)?,
        _ => read::<3>(basis)?,
    })
}

fn read<const B: usize>(
    basis: Basis<'_>,
) -> std::result::Result<(PerOutput, PerOutput), eigenrad_runtime::Error> {
    // Every channel starts at 0.
    let mut lights = ChannelEvaluator::<B, MAX_CHANNELS>::new(basis)?;
    let widen = |v: [f32; B]| v.iter().map(|&x| f64::from(x)).collect::<Vec<f64>>();
    let mut sensors = vec![Vec::new(); basis.sensor_count()];
    let mut zones = vec![Vec::new(); basis.zone_count()];
    for c in 0..basis.channel_count() {
        lights.set_channel_level(c, 1.0)?;
        for (s, row) in sensors.iter_mut().enumerate() {
            row.push(widen(lights.sensor_irradiance(s)?));
        }
        for (z, row) in zones.iter_mut().enumerate() {
            row.push(widen(lights.zone_irradiance(z)?));
        }
        lights.set_channel_level(c, 0.0)?;
    }
    Ok((sensors, zones))
}

/// The readings per unit of daylight of the basis in `bytes` ([`DaylightUnits`]), `None`
/// without daylight.
pub fn daylight_units(bytes: &[u8]) -> Result<Option<DaylightUnits>> {
    let basis = Basis::from_bytes(bytes)?;
    basis.check_daylight()?;
    let (Some(patches), Some(site)) = (basis.sky_patches(), basis.site()) else {
        return Ok(None);
    };
    let levels = vec![0.0; basis.channel_count()];
    let read = |state: &SkyState| -> Result<Vec<f64>> {
        let got = evaluate_daylight(bytes, state, &levels, false)?;
        Ok(got.sensors.into_iter().chain(got.zones).collect())
    };
    let sky_alone = |sky: &CieSky| -> Result<Vec<f64>> {
        let mut sky_luminance = vec![0.0f32; patches.count()];
        patches.luminances(sky, sky.zenith_luminance_for(1.0)?, &mut sky_luminance)?;
        // With no sun the diffuse horizontal illuminance is also the global one.
        read(&SkyState {
            sky_luminance,
            global_horizontal: 1.0,
            sun: None,
        })
    };
    // Solar noon on an equinox: declination 0, hour angle 0.
    let noon = direction_of(site.latitude, 0.0, 0.0);
    // The traditional overcast sky does not depend on the sun: any direction serves.
    let overcast = sky_alone(&CieSky::traditional_overcast([0.0, 0.0, 1.0])?)?;
    let clear_sky = sky_alone(&CieSky::standard(CLEAR_SKY_TYPE, noon)?)?;
    let sun = if noon[2] > 0.0 {
        Some(read(&SkyState {
            sky_luminance: vec![0.0; patches.count()],
            global_horizontal: 0.0,
            sun: Some(Sun {
                direction: noon,
                direct_normal: 1.0,
            }),
        })?)
    } else {
        None
    };
    Ok(Some(DaylightUnits {
        overcast,
        clear_sky,
        sun,
    }))
}

/// Luminance weights of linear RGB (ITU-R BT.709 primaries): a reading's luminous value.
const LUMINANCE: [f64; 3] = [0.2126, 0.7152, 0.0722];

/// The luminous value of a reading in one band (photopic) or three (rgb).
fn luminous(bands: &[f64]) -> f64 {
    match bands {
        [one] => *one,
        _ => bands.iter().zip(LUMINANCE).map(|(v, w)| v * w).sum(),
    }
}

/// `a / b`, `None` where `b` is not positive (the zone reads nothing).
fn ratio(a: f64, b: f64) -> Option<f64> {
    (b > 0.0).then(|| a / b)
}

/// Every sensor's ratio to every zone, sensor by sensor, from the channels' readings and
/// the daylight's (`names`: sensors' and zones' names).
pub fn sensor_ratios(
    sensors: &PerOutput,
    zones: &PerOutput,
    daylight: Option<&DaylightUnits>,
    sensor_names: &[String],
    zone_names: &[String],
) -> Vec<SensorRatio> {
    let count = sensors.len();
    let of = |values: Option<&Vec<f64>>, s: usize, z: usize| {
        values.and_then(|v| ratio(*v.get(s)?, *v.get(count + z)?))
    };
    let mut out = Vec::new();
    for (s, sensor) in sensors.iter().enumerate() {
        for (z, zone) in zones.iter().enumerate() {
            out.push(SensorRatio {
                sensor: sensor_names.get(s).cloned().unwrap_or_default(),
                zone: zone_names.get(z).cloned().unwrap_or_default(),
                per_channel: sensor
                    .iter()
                    .zip(zone)
                    .map(|(a, b)| ratio(luminous(a), luminous(b)))
                    .collect(),
                overcast: of(daylight.map(|d| &d.overcast), s, z),
                clear_sky: of(daylight.map(|d| &d.clear_sky), s, z),
                sun: of(daylight.and_then(|d| d.sun.as_ref()), s, z),
            });
        }
    }
    out
}

/// Every sensor's ratio to every zone of the basis in `bytes`.
pub fn ratios_of(bytes: &[u8]) -> Result<Vec<SensorRatio>> {
    let basis = Basis::from_bytes(bytes)?;
    let (sensors, zones) = channel_readings(basis)?;
    let daylight = daylight_units(bytes)?;
    let sensor_names = (0..basis.sensor_count())
        .map(|k| basis.sensor_name(k).map(str::to_owned))
        .collect::<eigenrad_runtime::Result<Vec<_>>>()?;
    let zone_names = (0..basis.zone_count())
        .map(|k| basis.zone_name(k).map(str::to_owned))
        .collect::<eigenrad_runtime::Result<Vec<_>>>()?;
    Ok(sensor_ratios(
        &sensors,
        &zones,
        daylight.as_ref(),
        &sensor_names,
        &zone_names,
    ))
}

/// The ratios as a table: one line per sensor and zone, one column per channel, then the
/// overcast sky, the clear sky and the sun; `-` where the zone reads nothing.
pub fn format_ratios(ratios: &[SensorRatio], channels: &[String]) -> String {
    use std::fmt::Write as _;
    let mut s = String::new();
    if ratios.is_empty() {
        return s;
    }
    let _ = writeln!(
        s,
        "sensor to zone: what each sensor reads per unit of the zone's reading, per channel and per daylight (overcast: CIE overcast sky; clear sky: CIE type {CLEAR_SKY_TYPE}, the sky alone, sun at solar noon on an equinox; sun: that sun alone)"
    );
    let _ = write!(s, "{:<20} {:<20}", "sensor", "zone");
    for c in channels
        .iter()
        .map(String::as_str)
        .chain(["overcast", "clear sky", "sun"])
    {
        let _ = write!(s, " {c:>12}");
    }
    s.push('\n');
    let cell = |v: Option<f64>| v.map_or_else(|| "-".to_owned(), |v| format!("{v:.4}"));
    for r in ratios {
        let _ = write!(s, "{:<20} {:<20}", r.sensor, r.zone);
        for v in r
            .per_channel
            .iter()
            .copied()
            .chain([r.overcast, r.clear_sky, r.sun])
        {
            let _ = write!(s, " {:>12}", cell(v));
        }
        s.push('\n');
    }
    s
}
