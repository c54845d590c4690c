//! The full evaluator: channels as in [`ChannelEvaluator`], plus exitance set patch by patch,
//! which goes through the modes.

use super::{fits, grid_figures, irradiance, luminance, ChannelEvaluator, Figures, MAX_EXITANCE};
use crate::basis::{check_index, Basis};
use crate::error::{Error, Result};
use crate::format::Formulation;
use crate::storage::{dot_f32, f32_at, f32_row, f32s};

/// Turns channel levels and exitance set patch by patch into exitance, irradiance, sensor
/// and zone readings.
///
/// A [`ChannelEvaluator`] plus what exitance set patch by patch needs: channels read their
/// exact stored responses as there, and exitance set with
/// [`set_patch_exitance`](Self::set_patch_exitance) (on any patch, also one that belongs to
/// no channel) goes through the modes. With no patch exitance set, every reading equals the
/// [`ChannelEvaluator`]'s, to the bit, and costs the same.
///
/// Capacities are compile-time: `BANDS` must equal the basis' band count (1 or 3), and the
/// basis may have at most `PATCHES` patches, `MODES` modes, `CHANNELS` channels and
/// `OUTPUTS` sensors plus zones. RAM use is fixed by these numbers
/// ([`Evaluator::RAM_BYTES`] bounds the state) and does not grow with the basis, which
/// stays in the caller's bytes.
///
/// State kept besides the channel levels, per band: the amplitude of every mode from
/// exitance set patch by patch (`MODES` values), that exitance itself (`PATCHES` values), and
/// its direct contribution to each output (`OUTPUTS` values).
#[derive(Clone, Debug)]
pub struct Evaluator<
    'a,
    const BANDS: usize,
    const PATCHES: usize,
    const MODES: usize,
    const CHANNELS: usize,
    const OUTPUTS: usize,
> {
    channels: ChannelEvaluator<'a, BANDS, CHANNELS>,
    /// Mode amplitudes from exitance set patch by patch, coefficient included.
    amplitude: [[f32; MODES]; BANDS],
    /// Exitance set patch by patch (on top of the channels), W/m² or lux.
    patch_exitance: [[f32; BANDS]; PATCHES],
    /// Direct irradiance of every output from `patch_exitance`, W/m² or lux.
    patch_direct: [[f32; BANDS]; OUTPUTS],
    /// Patches whose `patch_exitance` is non-zero in some band. While it is 0 the modal and
    /// direct terms are exactly 0 and reads skip them.
    lit: usize,
}

impl<
        'a,
        const BANDS: usize,
        const PATCHES: usize,
        const MODES: usize,
        const CHANNELS: usize,
        const OUTPUTS: usize,
    > Evaluator<'a, BANDS, PATCHES, MODES, CHANNELS, OUTPUTS>
{
    /// Bytes of state an evaluator of this type holds besides the basis view and a count:
    /// the [`ChannelEvaluator`]'s levels plus `4 × BANDS × (MODES + PATCHES + OUTPUTS)` for
    /// exitance set patch by patch.
    pub const RAM_BYTES: usize = ChannelEvaluator::<'a, BANDS, CHANNELS>::RAM_BYTES
        + 4 * BANDS * (MODES + PATCHES + OUTPUTS);

    /// An evaluator for `basis` with every channel at level 0 and no patch exitance.
    ///
    /// Fails with [`Error::Capacity`] naming both sizes when the basis does not fit.
    pub fn new(basis: Basis<'a>) -> Result<Self> {
        if basis.bands() != BANDS {
            return Err(Error::Capacity {
                what: "bands",
                needed: basis.bands(),
                capacity: BANDS,
            });
        }
        fits("patches", basis.patch_count(), PATCHES)?;
        fits("modes", basis.mode_count(), MODES)?;
        fits("channels", basis.channel_count(), CHANNELS)?;
        fits(
            "outputs",
            basis.sensor_count() + basis.zone_count(),
            OUTPUTS,
        )?;
        Ok(Evaluator {
            channels: ChannelEvaluator::new(basis)?,
            amplitude: [[0.0; MODES]; BANDS],
            patch_exitance: [[0.0; BANDS]; PATCHES],
            patch_direct: [[0.0; BANDS]; OUTPUTS],
            lit: 0,
        })
    }

    /// The basis being evaluated.
    pub fn basis(&self) -> &Basis<'a> {
        &self.channels.basis
    }

    /// The channel part of the state: what the evaluator reads with no patch exitance.
    pub fn channels(&self) -> &ChannelEvaluator<'a, BANDS, CHANNELS> {
        &self.channels
    }

    fn p(&self) -> usize {
        self.channels.basis.counts.mode_count
    }

    /// Sets every channel's level at once; see [`ChannelEvaluator::set_channel_levels`].
    /// O(m); exitance set patch by patch is kept.
    pub fn set_channel_levels(&mut self, levels: &[f32]) -> Result<()> {
        self.channels.set_channel_levels(levels)
    }

    /// Changes one channel's level; see [`ChannelEvaluator::set_channel_level`]. O(1).
    pub fn set_channel_level(&mut self, channel: usize, level: f32) -> Result<()> {
        self.channels.set_channel_level(channel, level)
    }

    /// Sets a channel from a DALI arc power level (IEC 62386-102 logarithmic curve, 0 = off,
    /// 254 = 100 %; 255 is MASK and rejected).
    pub fn set_channel_arc_power(&mut self, channel: usize, arc: u8) -> Result<()> {
        self.channels.set_channel_arc_power(channel, arc)
    }

    /// Current level of `channel` (relative).
    pub fn channel_level(&self, channel: usize) -> Result<f32> {
        self.channels.channel_level(channel)
    }

    /// Sets the exitance a patch emits on top of its channel (the general case of an
    /// arbitrary initial exitance `M0`), per band in W/m² or lux, at most [`MAX_EXITANCE`].
    /// Any patch may be given exitance, also one that belongs to no channel. Incremental:
    /// O(p·bands + outputs·bands).
    ///
    /// The patch's own exitance and its direct light on sensors and zones are exact (split
    /// formulation; in the seed one only on black patches); the light it sends into the room
    /// is carried by the modes, so its accuracy is that of the truncation (exact when
    /// `p = n`). An invalid value, or one that would overflow the state, is an error and
    /// changes nothing.
    pub fn set_patch_exitance(&mut self, patch: usize, exitance: [f32; BANDS]) -> Result<()> {
        let basis = self.channels.basis;
        check_index("patch", patch, basis.counts.patch_count)?;
        if exitance
            .iter()
            .any(|e| !e.is_finite() || !(0.0..=MAX_EXITANCE).contains(e))
        {
            return Err(Error::InvalidInput { what: "exitance" });
        }
        let old = self
            .patch_exitance
            .get(patch)
            .copied()
            .unwrap_or([0.0; BANDS]);
        // Two passes: check that every updated value stays finite, then apply, so that a
        // rejected request leaves the state exactly as it was.
        for apply in [false, true] {
            for b in 0..BANDS {
                let delta =
                    exitance.get(b).copied().unwrap_or(0.0) - old.get(b).copied().unwrap_or(0.0);
                if delta != 0.0 && !self.add_patch_exitance(patch, b, delta, apply) {
                    return Err(Error::InvalidInput { what: "exitance" });
                }
            }
        }
        let was_lit = old.iter().any(|&x| x != 0.0);
        let now_lit = exitance.iter().any(|&x| x != 0.0);
        if let Some(slot) = self.patch_exitance.get_mut(patch) {
            *slot = exitance;
        }
        match (was_lit, now_lit) {
            (false, true) => self.lit += 1,
            (true, false) => {
                self.lit = self.lit.saturating_sub(1);
                if self.lit == 0 {
                    // Nothing is set any more: drop the rounding residue of the increments,
                    // so that reads equal the channel evaluator's again.
                    self.clear_patch_exitance();
                }
            }
            _ => {}
        }
        Ok(())
    }

    /// Adds `delta` more exitance on `patch` in band `b` to the mode amplitudes and, where it
    /// is carried exactly, to the direct light on the outputs; with `apply` false only checks
    /// that every updated value would stay finite. `false` when one would not.
    ///
    /// Not inlined: [`set_patch_exitance`](Self::set_patch_exitance) calls it in both passes,
    /// and one copy of the loops over the three storage precisions is enough in flash.
    #[inline(never)]
    fn add_patch_exitance(&mut self, patch: usize, b: usize, delta: f32, apply: bool) -> bool {
        let basis = self.channels.basis;
        let outputs = basis.counts.sensor_count + basis.counts.zone_count;
        let mut ok = true;
        let Some(amp) = self.amplitude.get_mut(b) else {
            return true;
        };
        patch_response(&basis, patch, b, delta, |k, step| {
            if let Some(a) = amp.get_mut(k) {
                if apply {
                    *a += step;
                } else {
                    ok &= (*a + step).is_finite();
                }
            }
        });
        if identity(&basis, patch, b) {
            let direct = &mut self.patch_direct;
            basis
                .output_view()
                .for_each_compact(patch, 0, outputs.min(OUTPUTS), |o, f| {
                    if let Some(slot) = direct.get_mut(o).and_then(|r| r.get_mut(b)) {
                        if apply {
                            *slot += f * delta;
                        } else {
                            ok &= (*slot + f * delta).is_finite();
                        }
                    }
                });
        }
        ok
    }

    /// Removes all exitance set with [`set_patch_exitance`](Self::set_patch_exitance).
    pub fn clear_patch_exitance(&mut self) {
        self.amplitude = [[0.0; MODES]; BANDS];
        self.patch_exitance = [[0.0; BANDS]; PATCHES];
        self.patch_direct = [[0.0; BANDS]; OUTPUTS];
        self.lit = 0;
    }

    /// Exitance set on `patch` in `band` with [`set_patch_exitance`](Self::set_patch_exitance).
    fn own(&self, patch: usize, band: usize) -> f32 {
        self.patch_exitance
            .get(patch)
            .and_then(|e| e.get(band))
            .copied()
            .unwrap_or(0.0)
    }

    fn checked(values: [f32; BANDS]) -> Result<[f32; BANDS]> {
        if values.iter().all(|v| v.is_finite()) {
            Ok(values)
        } else {
            Err(Error::InvalidInput { what: "exitance" })
        }
    }

    /// Final exitance of `patch` per band, W/m² or lux (lm/m²): the channels' exact
    /// responses, plus, where exitance is set patch by patch, that exitance (where carried
    /// exactly) and the modes. O(m) per band, O(p + m) with patch exitance set.
    pub fn exitance(&self, patch: usize) -> Result<[f32; BANDS]> {
        let channels = self.channels.exitance(patch)?;
        self.with_patch_exitance(patch, channels)
    }

    /// `channels`, the channels' exitance of `patch`, plus what exitance set patch by patch
    /// adds there: nothing while none is set.
    fn with_patch_exitance(&self, patch: usize, channels: [f32; BANDS]) -> Result<[f32; BANDS]> {
        let mut out = channels;
        if self.lit == 0 {
            return Ok(out);
        }
        let basis = &self.channels.basis;
        let p = self.p();
        let modes = basis.modes();
        for (b, slot) in out.iter_mut().enumerate() {
            if identity(basis, patch, b) {
                *slot += self.own(patch, b);
            }
            let amp = self
                .amplitude
                .get(b)
                .map_or(&[][..], |a| a.get(..p).unwrap_or(&[]));
            *slot += modes.row_dot(patch, b * p, amp);
        }
        Self::checked(out)
    }

    /// Fills `out[i]` with the exitance of every patch `i` (W/m² or lux); `out` must have
    /// one entry per patch. O(n·m) per band, O(n·(p + m)) with patch exitance set: the
    /// channels' part row after row ([`ChannelEvaluator::exitance_all`]), then the modes'
    /// patch by patch, to the same values as [`exitance`](Self::exitance), to the bit.
    pub fn exitance_all(&self, out: &mut [[f32; BANDS]]) -> Result<()> {
        self.channels.exitance_all(out)?;
        if self.lit == 0 {
            return Ok(());
        }
        for (patch, slot) in out.iter_mut().enumerate() {
            *slot = self.with_patch_exitance(patch, *slot)?;
        }
        Ok(())
    }

    /// Irradiance (illuminance in a photopic basis) arriving on `patch`, W/m² or lux:
    /// `E = (M − M_emitted)/ρ`, the emitted part being the channel's and the exitance set on
    /// the patch. A patch with ρ = 0 in some band gives [`Error::BlackPatch`]: read a sensor
    /// or zone there instead.
    pub fn irradiance(&self, patch: usize) -> Result<[f32; BANDS]> {
        let m = self.exitance(patch)?;
        let out = irradiance(&self.channels.basis, patch, m, |b| {
            self.channels.emitted(patch, b) + self.own(patch, b)
        })?;
        Self::checked(out)
    }

    /// Luminance of `patch` as a Lambertian surface, `L = M/π`: W/(m²·sr), or cd/m² in a
    /// photopic basis.
    pub fn luminance(&self, patch: usize) -> Result<[f32; BANDS]> {
        Ok(luminance(self.exitance(patch)?))
    }

    /// Irradiance of output `o` (sensors first, then zones), already checked: the channels'
    /// exact readings, plus, with patch exitance set, the modes and its direct light.
    /// O(m) per band, O(p + m) with patch exitance set; independent of n.
    fn output(&self, o: usize) -> Result<[f32; BANDS]> {
        let mut out = self.channels.output(o);
        if self.lit == 0 {
            return Ok(out);
        }
        let p = self.p();
        let tables = &self.channels.basis.tables;
        for (b, slot) in out.iter_mut().enumerate() {
            let modes = f32_row(tables.output_modes, o * BANDS + b, p);
            let amp = self
                .amplitude
                .get(b)
                .map_or(&[][..], |a| a.get(..p).unwrap_or(&[]));
            let direct = self
                .patch_direct
                .get(o)
                .and_then(|d| d.get(b))
                .copied()
                .unwrap_or(0.0);
            *slot += dot_f32(modes, amp) + direct;
        }
        Self::checked(out)
    }

    /// Irradiance at sensor `sensor` (illuminance in lux for a photopic basis, W/m² per
    /// band otherwise). O(m) per band, O(p + m) with patch exitance set.
    pub fn sensor_irradiance(&self, sensor: usize) -> Result<[f32; BANDS]> {
        check_index("sensor", sensor, self.channels.basis.counts.sensor_count)?;
        self.output(sensor)
    }

    /// Area-average irradiance over zone `zone` (illuminance in lux for a photopic basis,
    /// W/m² per band otherwise). O(m) per band, O(p + m) with patch exitance set.
    pub fn zone_irradiance(&self, zone: usize) -> Result<[f32; BANDS]> {
        let counts = &self.channels.basis.counts;
        check_index("zone", zone, counts.zone_count)?;
        self.output(counts.sensor_count + zone)
    }

    /// Irradiance of grid point `g` (among all grid points), already checked: the channels'
    /// exact readings, plus, with patch exitance set, the modes and the direct light of the
    /// patches carrying exitance exactly (`grid_view`, summed over the patches: the point
    /// keeps no state of its own). O(m) per band, O(p + m + n) with patch exitance set.
    fn grid_reading(&self, g: usize) -> Result<[f32; BANDS]> {
        let mut out = self.channels.grid_reading(g);
        if self.lit == 0 {
            return Ok(out);
        }
        let basis = &self.channels.basis;
        let p = self.p();
        let n = basis.counts.patch_count;
        for (b, slot) in out.iter_mut().enumerate() {
            let modes = f32_row(basis.tables.grid_modes, g * BANDS + b, p);
            let amp = self
                .amplitude
                .get(b)
                .map_or(&[][..], |a| a.get(..p).unwrap_or(&[]));
            let mut direct = 0.0f32;
            basis.grid_view().for_each(g, 0, n, |j, f| {
                let own = self.own(j, b);
                if own != 0.0 && identity(basis, j, b) {
                    direct += f * own;
                }
            });
            *slot += dot_f32(modes, amp) + direct;
        }
        Self::checked(out)
    }

    /// Irradiance at point `point` of zone `zone`'s calculation grid (lux for a photopic
    /// basis, W/m² per band otherwise). O(m) per band, O(p + m + n) with patch exitance set.
    pub fn grid_point_irradiance(&self, zone: usize, point: usize) -> Result<[f32; BANDS]> {
        let g = self.channels.basis.grid_index(zone, point)?;
        self.grid_reading(g)
    }

    /// `E_avg`, `E_min`, `E_max` and `U_o` over zone `zone`'s grid points per band, read
    /// point by point without a buffer. [`Error::NoGrid`] for a zone without a grid.
    pub fn zone_figures(&self, zone: usize) -> Result<[Figures; BANDS]> {
        let range = self.channels.basis.grid_range(zone)?;
        grid_figures(zone, range, |g| self.grid_reading(g))
    }
}

/// Whether exitance set on `patch` in `band` is carried exactly (not through the modes): on
/// every patch in the split formulation, on black patches only in the seed formulation.
fn identity(basis: &Basis<'_>, patch: usize, band: usize) -> bool {
    basis.formulation == Formulation::Split
        || f32_at(
            basis.tables.patch_reflectance,
            patch * basis.counts.bands + band,
        ) == 0.0
}

/// Calls `f(k, response)` with the mode-space response to `delta` more exitance on `patch`
/// in `band`, coefficient included: `α_k (A/ρ) v_k` for a reflecting patch, the stored row for
/// a black one. `α_k = μ_k/(1−μ_k)` (split) or `1/λ_k` (seed).
fn patch_response(
    basis: &Basis<'_>,
    patch: usize,
    band: usize,
    delta: f32,
    mut f: impl FnMut(usize, f32),
) {
    let p = basis.counts.mode_count;
    let rho = f32_at(
        basis.tables.patch_reflectance,
        patch * basis.counts.bands + band,
    );
    let eigenvalues = f32_row(basis.tables.eigenvalues, band, p);
    if rho == 0.0 {
        if let Some(j) = basis.black_index(patch) {
            let row = f32_row(
                basis.tables.black_projection,
                j * basis.counts.bands + band,
                p,
            );
            for (k, x) in f32s(row).enumerate() {
                f(k, delta * x);
            }
        }
        return;
    }
    // b_i = A_i / ρ_i is finite: ρ is 0 or at least MIN_REFLECTANCE.
    let weight = delta * f32_at(basis.tables.patch_area, patch) / rho;
    let mut mu = f32s(eigenvalues);
    basis.modes().for_each(patch, band * p, p, |k, v| {
        let e = mu.next().unwrap_or(0.0);
        let coefficient = match basis.formulation {
            Formulation::Split => e / (1.0 - e),
            Formulation::Seed => 1.0 / e,
        };
        f(k, weight * v * coefficient);
    });
}
