//! `eigenrad inspect --gains`: what every sensor and zone reads per channel at level 1, the
//! table a controller's firmware needs (a reading is the sum of each channel's gain times its
//! level). Read through the runtime's [`ChannelEvaluator`] with one channel at 1 and the others
//! off: the stored exact responses, exactly as the firmware reads them.

use std::fmt::Write as _;
use std::path::Path;

use eigenrad_runtime::{Basis, ChannelEvaluator};
use serde::Serialize;

use super::readout::{band_names, basis_error, unit};
use super::units::Units;
use crate::accuracy::runtime_eval::MAX_CHANNELS;
use crate::error::Result;

/// One sensor's or zone's gains.
#[derive(Clone, Debug, Serialize)]
pub struct Gain {
    /// Sensor or zone name.
    pub name: String,
    /// `per_channel[c][b]`: the reading in band b with channel c at level 1 and every other
    /// channel off ([`Gains::unit`] per unit level).
    pub per_channel: Vec<Vec<f64>>,
    /// The reading per unit of daylight, per band: per lux of diffuse horizontal
    /// illuminance outside under the CIE overcast sky, its daylight factor as a fraction
    /// (the same in lux or fc), read through the runtime's `DaylightEvaluator`. `null` for a
    /// basis without daylight.
    pub per_daylight: Option<Vec<f64>>,
}

/// The JSON document of `inspect --gains`.
#[derive(Clone, Debug, Serialize)]
pub struct Gains {
    /// Unit of every gain, per unit of channel level: lux, fc or W/m².
    pub unit: &'static str,
    /// Band names.
    pub bands: Vec<&'static str>,
    /// Channel names, in the order of [`Gain::per_channel`].
    pub channels: Vec<String>,
    /// Sensor gains (irradiance or illuminance at the sensor).
    pub sensors: Vec<Gain>,
    /// Zone gains (area-average irradiance or illuminance).
    pub zones: Vec<Gain>,
}

/// `eigenrad inspect --gains`: the gains of the basis at `path` (`bytes`), in `units`.
pub fn gains(path: &Path, bytes: &[u8], units: Units) -> Result<Gains> {
    let basis = Basis::from_bytes(bytes).map_err(basis_error(path))?;
    let (unit, convert) = units.of(unit(basis.quantity()))?;
    let e = basis_error(path);
    let (sensors, zones) = match basis.bands() {
        1 => read::<1>(basis),
        _ => read::<3>(basis),
    }
    .map_err(&e)?;
    let factors = daylight_factors(bytes)?;
    type Name<'b> = dyn Fn(usize) -> std::result::Result<&'b str, eigenrad_runtime::Error> + 'b;
    let named = |values: PerOutput, name: &Name<'_>, first: usize| {
        values
            .into_iter()
            .enumerate()
            .map(|(i, per_channel)| {
                Ok(Gain {
                    name: name(i).map(str::to_owned).map_err(&e)?,
                    per_channel: per_channel
                        .into_iter()
                        .map(|v| v.into_iter().map(convert).collect())
                        .collect(),
                    per_daylight: factors.as_ref().map(|f| vec![f[first + i]]),
                })
            })
            .collect::<Result<Vec<_>>>()
    };
    Ok(Gains {
        unit,
        bands: band_names(basis.bands()),
        channels: (0..basis.channel_count())
            .map(|c| basis.channel_name(c).map(str::to_owned))
            .collect::<std::result::Result<_, _>>()
            .map_err(&e)?,
        sensors: named(sensors, &|s| basis.sensor_name(s), 0)?,
        zones: named(zones, &|z| basis.zone_name(z), basis.sensor_count())?,
    })
}

/// Every sensor's and zone's daylight factor (a fraction), `None` for a basis without
/// daylight: the reading under the CIE traditional overcast sky scaled to 1 lux of diffuse
/// horizontal illuminance, which with no sun is also the global horizontal illuminance that
/// lights the ground.
fn daylight_factors(bytes: &[u8]) -> Result<Option<Vec<f64>>> {
    use eigenrad_runtime::sky::cie::CieSky;
    let basis = Basis::from_bytes(bytes)?;
    let Some(patches) = basis.sky_patches() else {
        return Ok(None);
    };
    // The traditional overcast sky does not depend on the sun: any direction serves.
    let sky = CieSky::traditional_overcast([0.0, 0.0, 1.0])?;
    let mut sky_luminance = vec![0.0f32; patches.count()];
    patches.luminances(&sky, sky.zenith_luminance_for(1.0)?, &mut sky_luminance)?;
    let state = crate::accuracy::runtime_eval::SkyState {
        sky_luminance,
        global_horizontal: 1.0,
        sun: None,
    };
    let levels = vec![0.0; basis.channel_count()];
    let got = crate::accuracy::runtime_eval::evaluate_daylight(bytes, &state, &levels, false)?;
    Ok(Some(got.sensors.into_iter().chain(got.zones).collect()))
}

/// `[output][channel][band]` for sensors and zones, one channel at level 1 at a time.
type PerOutput = Vec<Vec<Vec<f64>>>;

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

/// The rows of the gains: (kind, name, band, one value per channel).
fn rows(g: &Gains) -> Vec<(&'static str, &str, &'static str, Vec<f64>)> {
    let mut out = Vec::new();
    for (kind, list) in [("sensor", &g.sensors), ("zone", &g.zones)] {
        for gain in list {
            for (b, band) in g.bands.iter().enumerate() {
                let values = gain.per_channel.iter().map(|v| v[b]).collect();
                out.push((kind, gain.name.as_str(), *band, values));
            }
        }
    }
    out
}

/// What the table says without daylight (the JSON has `per_daylight: null`).
const NO_DAYLIGHT: &str =
    "per unit of daylight: none (the basis carries no daylight: its scene had no [site] or no glazed window)";

/// The gains as a table: one line per sensor or zone (and band), one column per channel.
pub fn format_gains(g: &Gains) -> String {
    let mut s = String::new();
    let _ = writeln!(
        s,
        "gains: reading per channel at level 1, others off, {} ({})",
        g.unit,
        g.bands.join(" ")
    );
    let _ = write!(s, "{:<6} {:<20} {:<8}", "", "", "band");
    for c in &g.channels {
        let _ = write!(s, " {c:>14}");
    }
    s.push('\n');
    for (kind, name, band, values) in rows(g) {
        let _ = write!(s, "{kind:<6} {name:<20} {band:<8}");
        for v in values {
            let _ = write!(s, " {v:>14.4}");
        }
        let _ = writeln!(s, " {}", g.unit);
    }
    let daylit: Vec<&Gain> = g.sensors.iter().chain(&g.zones).collect();
    if daylit.iter().all(|x| x.per_daylight.is_none()) {
        let _ = writeln!(s, "{NO_DAYLIGHT}");
        return s;
    }
    let _ = writeln!(
        s,
        "per unit of daylight: daylight factor under the CIE overcast sky (reading per lux of diffuse horizontal illuminance outside)"
    );
    for (kind, list) in [("sensor", &g.sensors), ("zone", &g.zones)] {
        for x in list {
            if let Some(f) = &x.per_daylight {
                let _ = writeln!(s, "{kind:<6} {:<20} {:>8.3} %", x.name, 100.0 * f[0]);
            }
        }
    }
    s
}

/// The gains as CSV (RFC 4180): a header `kind,name,band,unit,<channel>...`, then one row per
/// sensor or zone and band, values at full precision.
pub fn gains_csv(g: &Gains) -> String {
    let mut s = String::new();
    let mut header = vec![
        "kind".to_owned(),
        "name".into(),
        "band".into(),
        "unit".into(),
    ];
    header.extend(g.channels.iter().map(|c| csv_field(c)));
    let _ = writeln!(s, "{}", header.join(","));
    for (kind, name, band, values) in rows(g) {
        let mut fields = vec![
            kind.to_owned(),
            csv_field(name),
            band.to_owned(),
            g.unit.into(),
        ];
        fields.extend(values.iter().map(|v| v.to_string()));
        let _ = writeln!(s, "{}", fields.join(","));
    }
    s
}

/// A CSV field, quoted when it holds a comma, a quote or a line break.
fn csv_field(text: &str) -> String {
    if text.contains([',', '"', '\n', '\r']) {
        format!("\"{}\"", text.replace('"', "\"\""))
    } else {
        text.to_owned()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn csv_fields_are_quoted_only_when_needed() {
        assert_eq!(csv_field("desk"), "desk");
        assert_eq!(csv_field("desk, north"), "\"desk, north\"");
        assert_eq!(csv_field("the \"big\" one"), "\"the \"\"big\"\" one\"");
    }
}
