//! `eigenrad inspect --gains`: what every sensor and zone reads per channel at level 1, the
//! table a controller's firmware needs (a reading is the sum of each channel's gain times its
//! level). Read through the runtime's [`ChannelEvaluator`] with one channel at 1 and the others
//! off: the stored exact responses, exactly as the firmware reads them.

use std::fmt::Write as _;
use std::path::Path;

use eigenrad_runtime::Basis;
use serde::Serialize;

use super::readout::{band_names, basis_error, unit};
use super::units::Units;
use crate::accuracy::calibration::{
    channel_readings, daylight_units, format_ratios, sensor_ratios, PerOutput, SensorRatio,
};
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
    /// Every sensor's ratio to every zone, per channel and per daylight: the figures a
    /// sensor is calibrated with.
    pub ratios: Vec<SensorRatio>,
}

/// `eigenrad inspect --gains`: the gains of the basis at `path` (`bytes`), in `units`.
pub fn gains(path: &Path, bytes: &[u8], units: Units) -> Result<Gains> {
    let basis = Basis::from_bytes(bytes).map_err(basis_error(path))?;
    let (unit, convert) = units.of(unit(basis.quantity()))?;
    let e = basis_error(path);
    let (sensors, zones) = channel_readings(basis)?;
    let daylight = daylight_units(bytes)?;
    let factors = daylight.as_ref().map(|d| d.overcast.clone());
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
    let channels = (0..basis.channel_count())
        .map(|c| basis.channel_name(c).map(str::to_owned))
        .collect::<std::result::Result<Vec<_>, _>>()
        .map_err(&e)?;
    let sensor_gains = named(sensors.clone(), &|s| basis.sensor_name(s), 0)?;
    let zone_gains = named(zones.clone(), &|z| basis.zone_name(z), basis.sensor_count())?;
    let names = |g: &[Gain]| g.iter().map(|x| x.name.clone()).collect::<Vec<_>>();
    let ratios = sensor_ratios(
        &sensors,
        &zones,
        daylight.as_ref(),
        &names(&sensor_gains),
        &names(&zone_gains),
    );
    Ok(Gains {
        unit,
        bands: band_names(basis.bands()),
        channels,
        sensors: sensor_gains,
        zones: zone_gains,
        ratios,
    })
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
        s += &format_ratios(&g.ratios, &g.channels);
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
    s += &format_ratios(&g.ratios, &g.channels);
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
