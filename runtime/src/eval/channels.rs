//! The channel-only evaluator: one level per channel, readings from the stored exact
//! responses.

use super::{grid_figures, irradiance, luminance, Figures, MAX_LEVEL};
use crate::basis::{check_index, Basis};
use crate::dali;
use crate::error::{Error, Result};
use crate::format::NO_CHANNEL;
use crate::storage::{dot_f32, f32_at, f32_row, u16_at};

/// Turns channel levels into exitance, irradiance, sensor and zone readings, exact to the
/// storage precision for every combination of levels.
///
/// The evaluator for a controller that only dims channels: its state is one level per
/// channel ([`ChannelEvaluator::RAM_BYTES`] = `4 × CHANNELS` bytes) besides the [`Basis`]
/// view. A channel update writes its level; a reading sums `m` stored products per band,
/// one per channel (`channel_response` for a patch, `output_channels` for a sensor or zone).
///
/// `BANDS` must equal the basis' band count (1 or 3) and the basis may have at most
/// `CHANNELS` channels. Exitance set patch by patch needs the modes and per-patch state:
/// use an [`Evaluator`](super::Evaluator) for that.
///
/// Readings cannot overflow: stored values are at most 10⁹ in magnitude, levels at most
/// [`MAX_LEVEL`] and channels fewer than 65535, so a sum stays below 10¹⁷ (and an irradiance,
/// divided by ρ ≥ 10⁻⁶, below 10²³), far inside `f32`.
#[derive(Clone, Debug)]
pub struct ChannelEvaluator<'a, const BANDS: usize, const CHANNELS: usize> {
    pub(super) basis: Basis<'a>,
    /// Level of every channel of the basis (relative, 1 = as built): `m` values.
    levels: heapless::Vec<f32, CHANNELS>,
}

impl<'a, const BANDS: usize, const CHANNELS: usize> ChannelEvaluator<'a, BANDS, CHANNELS> {
    /// Bytes of state an evaluator of this type holds besides the basis view and the
    /// levels' length: one `f32` level per channel.
    pub const RAM_BYTES: usize = 4 * CHANNELS;

    /// An evaluator for `basis` with every channel at level 0.
    ///
    /// Fails with [`Error::Capacity`] naming both sizes when the basis has another band
    /// count than `BANDS` or more channels than `CHANNELS`.
    pub fn new(basis: Basis<'a>) -> Result<Self> {
        const {
            assert!(
                BANDS == 1 || BANDS == 3,
                "BANDS must be 1 (photopic) or 3 (RGB)"
            )
        };
        if basis.bands() != BANDS {
            return Err(Error::Capacity {
                what: "bands",
                needed: basis.bands(),
                capacity: BANDS,
            });
        }
        let capacity = Error::Capacity {
            what: "channels",
            needed: basis.channel_count(),
            capacity: CHANNELS,
        };
        let mut levels = heapless::Vec::new();
        levels
            .resize(basis.channel_count(), 0.0)
            .map_err(|_| capacity)?;
        Ok(ChannelEvaluator { basis, levels })
    }

    /// The basis being evaluated.
    pub fn basis(&self) -> &Basis<'a> {
        &self.basis
    }

    fn check_level(level: f32) -> Result<()> {
        if level.is_finite() && (0.0..=MAX_LEVEL).contains(&level) {
            Ok(())
        } else {
            Err(Error::InvalidInput { what: "level" })
        }
    }

    /// Sets every channel's level at once (relative, 1 = as built; at most [`MAX_LEVEL`]).
    /// `levels` has one entry per channel of the basis. O(m).
    ///
    /// A wrong length or any invalid level is an error and changes nothing.
    pub fn set_channel_levels(&mut self, levels: &[f32]) -> Result<()> {
        let m = self.basis.counts.channel_count;
        if levels.len() != m {
            return Err(Error::LengthMismatch {
                what: "levels",
                expected: m,
                found: levels.len(),
            });
        }
        for &l in levels {
            Self::check_level(l)?;
        }
        for (slot, &l) in self.levels.iter_mut().zip(levels) {
            *slot = l;
        }
        Ok(())
    }

    /// Changes one channel's level (relative, 1 = as built; at most [`MAX_LEVEL`]). O(1): it
    /// writes the level, readings sum the channels when they are read.
    pub fn set_channel_level(&mut self, channel: usize, level: f32) -> Result<()> {
        check_index("channel", channel, self.basis.counts.channel_count)?;
        Self::check_level(level)?;
        if let Some(slot) = self.levels.get_mut(channel) {
            *slot = level;
        }
        Ok(())
    }

    /// Sets a channel from a DALI arc power level (IEC 62386-102 logarithmic curve, 0 = off,
    /// 254 = 100 %; 255 is MASK and rejected).
    pub fn set_channel_arc_power(&mut self, channel: usize, arc: u8) -> Result<()> {
        self.set_channel_level(channel, dali::arc_power_to_level(arc)?)
    }

    /// Current level of `channel` (relative).
    pub fn channel_level(&self, channel: usize) -> Result<f32> {
        check_index("channel", channel, self.basis.counts.channel_count)?;
        Ok(self.levels.get(channel).copied().unwrap_or(0.0))
    }

    /// Final exitance of `patch` per band, W/m² or lux (lm/m²): `Σ_c L_c ·
    /// channel_response[patch][c·B + b]`, emission included. O(m) per band.
    pub fn exitance(&self, patch: usize) -> Result<[f32; BANDS]> {
        check_index("patch", patch, self.basis.counts.patch_count)?;
        Ok(self.exitance_unchecked(patch))
    }

    /// [`exitance`](Self::exitance) for an index already checked: the patch's row of
    /// channel responses weighted by the levels.
    fn exitance_unchecked(&self, patch: usize) -> [f32; BANDS] {
        self.basis
            .channel_response()
            .weighted_row(patch, &self.levels)
    }

    /// Fills `out[i]` with the exitance of every patch `i` (W/m² or lux); `out` must have
    /// one entry per patch. O(n·m) per band: the channel responses are read row after row,
    /// each row checked and its precision dispatched once, to the same values as
    /// [`exitance`](Self::exitance) patch by patch, to the bit.
    pub fn exitance_all(&self, out: &mut [[f32; BANDS]]) -> Result<()> {
        let n = self.basis.counts.patch_count;
        if out.len() != n {
            return Err(Error::LengthMismatch {
                what: "out",
                expected: n,
                found: out.len(),
            });
        }
        self.basis
            .channel_response()
            .weighted_rows(&self.levels, out);
        Ok(())
    }

    /// Exitance `patch` emits itself in `band` through its channel: the channel's level
    /// times `patch_emission`, W/m² or lux.
    pub(super) fn emitted(&self, patch: usize, band: usize) -> f32 {
        let c = u16_at(self.basis.tables.patch_channel, patch);
        if c == NO_CHANNEL {
            return 0.0;
        }
        let level = self.levels.get(usize::from(c)).copied().unwrap_or(0.0);
        level
            * f32_at(
                self.basis.tables.patch_emission,
                patch * self.basis.counts.bands + band,
            )
    }

    /// Irradiance (illuminance in a photopic basis) arriving on `patch`, W/m² or lux:
    /// `E = (M − M_emitted)/ρ`. A patch with ρ = 0 in some band gives
    /// [`Error::BlackPatch`]: read a sensor or zone there instead.
    pub fn irradiance(&self, patch: usize) -> Result<[f32; BANDS]> {
        let m = self.exitance(patch)?;
        irradiance(&self.basis, patch, m, |b| self.emitted(patch, b))
    }

    /// Luminance of `patch` as a Lambertian surface, `L = M/π`: W/(m²·sr), or cd/m² in a
    /// photopic basis.
    pub fn luminance(&self, patch: usize) -> Result<[f32; BANDS]> {
        Ok(luminance(self.exitance(patch)?))
    }

    /// Irradiance of output `o` (sensors first, then zones), already checked:
    /// `Σ_c L_c · output_channels[o][b][c]`. O(m) per band, independent of n.
    pub(super) fn output(&self, o: usize) -> [f32; BANDS] {
        let levels = &self.levels;
        let m = levels.len();
        let mut out = [0.0f32; BANDS];
        for (b, slot) in out.iter_mut().enumerate() {
            let row = f32_row(self.basis.tables.output_channels, o * BANDS + b, m);
            *slot = dot_f32(row, levels);
        }
        out
    }

    /// Irradiance at sensor `sensor` (illuminance in lux for a photopic basis, W/m² per
    /// band otherwise). O(m) per band.
    pub fn sensor_irradiance(&self, sensor: usize) -> Result<[f32; BANDS]> {
        check_index("sensor", sensor, self.basis.counts.sensor_count)?;
        Ok(self.output(sensor))
    }

    /// Area-average irradiance over zone `zone` (illuminance in lux for a photopic basis,
    /// W/m² per band otherwise). O(m) per band.
    pub fn zone_irradiance(&self, zone: usize) -> Result<[f32; BANDS]> {
        check_index("zone", zone, self.basis.counts.zone_count)?;
        Ok(self.output(self.basis.counts.sensor_count + zone))
    }

    /// Irradiance of grid point `g` (among all grid points), already checked:
    /// `Σ_c L_c · grid_channels[g][b][c]`. O(m) per band.
    pub(super) fn grid_reading(&self, g: usize) -> [f32; BANDS] {
        let levels = &self.levels;
        let m = levels.len();
        let mut out = [0.0f32; BANDS];
        for (b, slot) in out.iter_mut().enumerate() {
            let row = f32_row(self.basis.tables.grid_channels, g * BANDS + b, m);
            *slot = dot_f32(row, levels);
        }
        out
    }

    /// Irradiance at point `point` of zone `zone`'s calculation grid (lux for a photopic
    /// basis, W/m² per band otherwise), exact per channel as a sensor's. O(m) per band.
    pub fn grid_point_irradiance(&self, zone: usize, point: usize) -> Result<[f32; BANDS]> {
        let g = self.basis.grid_index(zone, point)?;
        Ok(self.grid_reading(g))
    }

    /// `E_avg`, `E_min`, `E_max` and `U_o` over zone `zone`'s grid points per band, read
    /// point by point without a buffer. O(points · m) per band. [`Error::NoGrid`] for a zone
    /// without a grid.
    pub fn zone_figures(&self, zone: usize) -> Result<[Figures; BANDS]> {
        let range = self.basis.grid_range(zone)?;
        grid_figures(zone, range, |g| Ok(self.grid_reading(g)))
    }
}
