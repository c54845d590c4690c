//! Illuminance in lux or in footcandles (`--units`): the one conversion, used by every
//! command that prints illuminance (`eval`, `solve`, `inspect --gains`).

use super::readout::Readout;
use crate::error::{Error, Result};

/// Lux in one footcandle. 1 fc = 1 lm/ft² and the international foot is 0.3048 m exactly
/// (1959), so 1 fc = 1/0.3048² lx = 10.763 910 4… lx.
pub const LUX_PER_FOOTCANDLE: f64 = 1.0 / (0.3048 * 0.3048);

/// Lux as footcandles.
pub fn footcandles(lux: f64) -> f64 {
    lux / LUX_PER_FOOTCANDLE
}

/// A conversion of readings: the unit they are printed in and the function applied to each.
pub type Conversion = (&'static str, fn(f64) -> f64);

/// The unit readings are printed in.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Units {
    /// The basis' or scene's own unit: lux for a photometric band, W/m² for radiometric ones.
    #[default]
    Native,
    /// Footcandles (lm/ft²), for a photometric basis or scene only. Exitance is then in lm/ft²
    /// too.
    Footcandles,
}

impl Units {
    /// The conversion from readings in `unit` (`"lux"` or `"W/m²"`): the unit they are printed
    /// in and the function applied to each value. Footcandles of radiometric readings are an
    /// error saying so.
    pub fn of(self, unit: &'static str) -> Result<Conversion> {
        match self {
            Units::Native => Ok((unit, |x| x)),
            Units::Footcandles if unit == "lux" => Ok(("fc", footcandles)),
            Units::Footcandles => Err(Error::Units {
                units: "fc",
                reason: format!(
                    "footcandles measure visible light, and these readings are radiometric ({unit} per band); leave out --units or use --units lux"
                ),
            }),
        }
    }
}

/// `readout` with every irradiance and exitance in `units`.
pub fn readout_in(mut readout: Readout, units: Units) -> Result<Readout> {
    let (unit, f) = units.of(readout.unit)?;
    readout.unit = unit;
    let convert = |v: &mut Vec<f64>| v.iter_mut().for_each(|x| *x = f(*x));
    for r in readout.sensors.iter_mut().chain(&mut readout.zones) {
        convert(&mut r.irradiance);
        for part in [&mut r.daylight, &mut r.electric].into_iter().flatten() {
            convert(part);
        }
    }
    for p in readout.patches.iter_mut().flatten() {
        convert(&mut p.exitance);
        if let Some(e) = &mut p.irradiance {
            convert(e);
        }
    }
    // A grid's figures scale with its points (U_o is a ratio and stays).
    let daylight_grids = readout.daylight.iter_mut().flat_map(|d| &mut d.grids);
    for g in readout.grids.iter_mut().chain(daylight_grids) {
        for v in [&mut g.average, &mut g.minimum, &mut g.maximum] {
            convert(v);
        }
        for point in &mut g.points {
            convert(&mut point.irradiance);
        }
    }
    Ok(readout)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// 1 fc = 1 lm/ft² with 1 ft = 0.3048 m: 1 lx = 0.3048² fc, computed here from the
    /// definition rather than from the constant.
    #[test]
    fn footcandles_are_lumens_per_square_foot() {
        for lux in [0.0, 1.0, 10.763_910_416_709_722, 500.0, 12_345.678] {
            let expected = lux * 0.3048 * 0.3048;
            assert!((footcandles(lux) - expected).abs() <= 1e-15 * expected.max(1.0));
        }
        assert!((LUX_PER_FOOTCANDLE - 10.7639).abs() < 1e-4);
    }

    #[test]
    fn radiometric_readings_have_no_footcandles() {
        let e = Units::Footcandles.of("W/m²").unwrap_err().to_string();
        assert!(e.contains("--units fc") && e.contains("W/m²"), "{e}");
        assert_eq!(Units::Footcandles.of("lux").unwrap().0, "fc");
        assert_eq!(Units::Native.of("W/m²").unwrap().0, "W/m²");
    }
}
