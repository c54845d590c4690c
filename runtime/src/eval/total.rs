//! A sensor's or zone's whole reading, daylight plus electric light, by one method of the
//! [`DaylightEvaluator`] that takes either electric evaluator: a controller's loop reads the
//! same figure its photosensor measures, in lux, without adding two evaluators' results of
//! different types.

use super::{ChannelEvaluator, DaylightEvaluator, Evaluator};
use crate::error::Result;

/// The electric light under daylight: a photopic [`ChannelEvaluator`] or [`Evaluator`] of
/// the same basis as the [`DaylightEvaluator`] (daylight is photopic). Sealed: the runtime's
/// evaluators are the only ones.
pub trait ElectricLight: sealed::Sealed {
    /// Illuminance at sensor `sensor` from the electric light, lux.
    fn sensor_lux(&self, sensor: usize) -> Result<f32>;
    /// Illuminance averaged over zone `zone` from the electric light, lux.
    fn zone_lux(&self, zone: usize) -> Result<f32>;
}

mod sealed {
    pub trait Sealed {}
    impl<const C: usize> Sealed for super::ChannelEvaluator<'_, 1, C> {}
    impl<const N: usize, const P: usize, const C: usize, const O: usize> Sealed
        for super::Evaluator<'_, 1, N, P, C, O>
    {
    }
}

impl<const C: usize> ElectricLight for ChannelEvaluator<'_, 1, C> {
    fn sensor_lux(&self, sensor: usize) -> Result<f32> {
        let [e] = self.sensor_irradiance(sensor)?;
        Ok(e)
    }
    fn zone_lux(&self, zone: usize) -> Result<f32> {
        let [e] = self.zone_irradiance(zone)?;
        Ok(e)
    }
}

impl<const N: usize, const P: usize, const C: usize, const O: usize> ElectricLight
    for Evaluator<'_, 1, N, P, C, O>
{
    fn sensor_lux(&self, sensor: usize) -> Result<f32> {
        let [e] = self.sensor_irradiance(sensor)?;
        Ok(e)
    }
    fn zone_lux(&self, zone: usize) -> Result<f32> {
        let [e] = self.zone_irradiance(zone)?;
        Ok(e)
    }
}

impl<const SKY: usize, const OUTPUTS: usize, const MODES: usize>
    DaylightEvaluator<'_, SKY, OUTPUTS, MODES>
{
    /// What sensor `sensor` reads under the current sky and the levels of `electric` (the
    /// same basis) together, lux: its daylight plus its electric light, each exact as the
    /// two evaluators read them. O(1) plus the electric evaluator's read.
    pub fn sensor_total(&self, sensor: usize, electric: &impl ElectricLight) -> Result<f32> {
        Ok(self.sensor_illuminance(sensor)? + electric.sensor_lux(sensor)?)
    }

    /// What zone `zone` reads on average under the current sky and the levels of
    /// `electric` (the same basis) together, lux.
    pub fn zone_total(&self, zone: usize, electric: &impl ElectricLight) -> Result<f32> {
        Ok(self.zone_illuminance(zone)? + electric.zone_lux(zone)?)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Basis;

    /// The total is the sum of the two evaluators' own reads, whichever electric evaluator
    /// gives it, to the bit (the same two `f32` values added once).
    #[test]
    fn totals_add_daylight_to_either_electric_evaluator() -> Result<()> {
        let bytes: &[u8] = include_bytes!("../../tests/data/tiny-daylight.basis");
        let basis = Basis::from_bytes(bytes)?;
        let mut day = DaylightEvaluator::<145, 2, 0>::new(basis)?;
        let sky = [1000.0f32; 145];
        day.set_sky(&sky, 10_000.0, None)?;
        let mut lights = ChannelEvaluator::<1, 4>::new(basis)?;
        let mut full = Evaluator::<1, 64, 16, 4, 4>::new(basis)?;
        for c in 0..basis.channel_count() {
            lights.set_channel_level(c, 0.7)?;
            full.set_channel_level(c, 0.7)?;
        }
        for s in 0..basis.sensor_count() {
            let expected = day.sensor_illuminance(s)? + lights.sensor_irradiance(s)?[0];
            assert!(day.sensor_illuminance(s)? > 0.0);
            assert_eq!(day.sensor_total(s, &lights)?, expected);
            assert_eq!(day.sensor_total(s, &full)?, expected);
        }
        for z in 0..basis.zone_count() {
            let expected = day.zone_illuminance(z)? + lights.zone_irradiance(z)?[0];
            assert_eq!(day.zone_total(z, &lights)?, expected);
            assert_eq!(day.zone_total(z, &full)?, expected);
        }
        // A sensor past the basis' is refused, not read as zero.
        assert!(day.sensor_total(basis.sensor_count(), &lights).is_err());
        Ok(())
    }
}
