//! A basis' readings as bounds: which reading ([`Output`]), its gain per channel
//! ([`output_gains`]) and its ambient, the reading less the controlled channels' part
//! (`reading_without` on the evaluators).

use super::limits::MAX_CONTROLS;
use crate::basis::{check_index, Basis};
use crate::error::{Error, Result};
use crate::eval::{ChannelEvaluator, Evaluator};
use crate::storage::f32_at;

/// A reading of a basis a bound applies to.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Output {
    /// Sensor `index` (in the basis' order).
    Sensor(usize),
    /// Zone `index` (area average).
    Zone(usize),
}

impl Output {
    /// Row of `output_channels` (sensors first, then zones), checked against the basis.
    fn row(self, basis: &Basis<'_>) -> Result<usize> {
        let counts = &basis.counts;
        match self {
            Output::Sensor(s) => {
                check_index("sensor", s, counts.sensor_count)?;
                Ok(s)
            }
            Output::Zone(z) => {
                check_index("zone", z, counts.zone_count)?;
                Ok(counts.sensor_count + z)
            }
        }
    }
}

/// Fills `gains[k]` with the reading of `output` (lux in a photopic basis) per unit level of
/// basis channel `channels[k]`: the stored exact response `output_channels`. A three-band
/// basis is refused with [`Error::Capacity`] (`"bands"`, capacity 1).
pub fn output_gains(
    basis: &Basis<'_>,
    output: Output,
    channels: &[usize],
    gains: &mut [f32],
) -> Result<()> {
    if basis.bands() != 1 {
        return Err(Error::Capacity {
            what: "bands",
            needed: basis.bands(),
            capacity: 1,
        });
    }
    if gains.len() != channels.len() {
        return Err(Error::LengthMismatch {
            what: "gains",
            expected: channels.len(),
            found: gains.len(),
        });
    }
    let row = output.row(basis)?;
    let m = basis.counts.channel_count;
    for &c in channels {
        check_index("channel", c, m)?;
    }
    for (slot, &c) in gains.iter_mut().zip(channels) {
        *slot = f32_at(basis.tables.output_channels, row * m + c);
    }
    Ok(())
}

/// The reading of `output` less what `channels` contribute at their current levels: the
/// light the controlled channels do not give. `reading(eval) − Σ level_c · gain_c`.
fn without(
    basis: &Basis<'_>,
    output: Output,
    channels: &[usize],
    reading: f32,
    level: impl Fn(usize) -> Result<f32>,
) -> Result<f32> {
    let mut gains = [0.0f32; MAX_CONTROLS];
    let gains = gains.get_mut(..channels.len()).ok_or(Error::Capacity {
        what: "controlled channels",
        needed: channels.len(),
        capacity: MAX_CONTROLS,
    })?;
    output_gains(basis, output, channels, gains)?;
    let mut own = 0.0f32;
    for (&g, &c) in gains.iter().zip(channels) {
        own += g * level(c)?;
    }
    Ok(reading - own)
}

impl<const CHANNELS: usize> ChannelEvaluator<'_, 1, CHANNELS> {
    /// The current reading of `output` less the part `channels` give at their current levels
    /// (lux in a photopic basis): the ambient of a [`LevelProblem`](super::LevelProblem) bound
    /// whose controlled channels are `channels`. Channels not listed (a window channel, say)
    /// count as ambient.
    pub fn reading_without(&self, output: Output, channels: &[usize]) -> Result<f32> {
        let basis = self.basis();
        let [reading] = match output {
            Output::Sensor(s) => self.sensor_irradiance(s)?,
            Output::Zone(z) => self.zone_irradiance(z)?,
        };
        without(basis, output, channels, reading, |c| self.channel_level(c))
    }
}

impl<const N: usize, const P: usize, const CHANNELS: usize, const O: usize>
    Evaluator<'_, 1, N, P, CHANNELS, O>
{
    /// The current reading of `output`, patch exitance included, less the part `channels`
    /// give at their current levels (lux in a photopic basis): the ambient of a
    /// [`LevelProblem`](super::LevelProblem) bound whose controlled channels are `channels`.
    pub fn reading_without(&self, output: Output, channels: &[usize]) -> Result<f32> {
        let basis = self.basis();
        let [reading] = match output {
            Output::Sensor(s) => self.sensor_irradiance(s)?,
            Output::Zone(z) => self.zone_irradiance(z)?,
        };
        without(basis, output, channels, reading, |c| self.channel_level(c))
    }
}
