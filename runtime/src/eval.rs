//! Evaluation of a basis for changing emitter levels, in fixed-size buffers.

use crate::basis::{check_index, Basis};
use crate::dali;
use crate::error::{Error, Result};
use crate::format::{Formulation, NO_CHANNEL};
use crate::storage::{axpy_f32, dot_f32, f32_at, f32_row, f32s, u16_at};

/// Largest channel level accepted (relative; 1 is the level the basis was built for).
pub const MAX_LEVEL: f32 = 1.0e3;
/// Largest exitance accepted for a single patch, W/m² or lux.
pub const MAX_EXITANCE: f32 = 1.0e9;

/// Turns emitter levels into exitance, irradiance, sensor and zone readings.
///
/// Capacities are compile-time: `BANDS` must equal the basis' band count (1 or 3), and the
/// basis may have at most `PATCHES` patches, `MODES` modes, `CHANNELS` channels and
/// `OUTPUTS` sensors plus zones. RAM use is fixed by these numbers
/// ([`Evaluator::RAM_BYTES`] bounds the state) and does not grow with the basis, which
/// stays in the caller's bytes.
///
/// State kept, per band: the amplitude of every mode (`MODES` values), the part of it that
/// comes from exitance set patch by patch, that exitance itself (`PATCHES` values), and its
/// direct contribution to each output (`OUTPUTS` values); plus one level per channel.
#[derive(Clone, Debug)]
pub struct Evaluator<
    'a,
    const BANDS: usize,
    const PATCHES: usize,
    const MODES: usize,
    const CHANNELS: usize,
    const OUTPUTS: usize,
> {
    basis: Basis<'a>,
    /// One level per channel of the basis (length m).
    levels: heapless::Vec<f32, CHANNELS>,
    /// Mode amplitudes from channels and patches together, coefficient included.
    amplitude: [[f32; MODES]; BANDS],
    /// The part of `amplitude` that comes from per-patch exitance.
    patch_amplitude: [[f32; MODES]; BANDS],
    /// Exitance set patch by patch (on top of the channels), W/m² or lux.
    patch_exitance: [[f32; BANDS]; PATCHES],
    /// Direct irradiance of every output from `patch_exitance`, W/m² or lux.
    patch_direct: [[f32; BANDS]; OUTPUTS],
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
    /// Bytes of state an evaluator of this type holds besides the basis views.
    pub const RAM_BYTES: usize =
        4 * (CHANNELS + 2 * BANDS * MODES + BANDS * PATCHES + BANDS * OUTPUTS);

    /// An evaluator for `basis` with every channel at level 0 and no patch exitance.
    ///
    /// Fails with [`Error::Capacity`] naming both sizes when the basis does not fit.
    pub fn new(basis: Basis<'a>) -> Result<Self> {
        const {
            assert!(
                BANDS == 1 || BANDS == 3,
                "BANDS must be 1 (photopic) or 3 (RGB)"
            )
        };
        let fits = |what: &'static str, needed: usize, capacity: usize| {
            if needed <= capacity {
                Ok(())
            } else {
                Err(Error::Capacity {
                    what,
                    needed,
                    capacity,
                })
            }
        };
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
        let mut levels = heapless::Vec::new();
        levels
            .resize(basis.channel_count(), 0.0)
            .map_err(|_| Error::Capacity {
                what: "channels",
                needed: basis.channel_count(),
                capacity: CHANNELS,
            })?;
        Ok(Evaluator {
            basis,
            levels,
            amplitude: [[0.0; MODES]; BANDS],
            patch_amplitude: [[0.0; MODES]; BANDS],
            patch_exitance: [[0.0; BANDS]; PATCHES],
            patch_direct: [[0.0; BANDS]; OUTPUTS],
        })
    }

    /// The basis being evaluated.
    pub fn basis(&self) -> &Basis<'a> {
        &self.basis
    }

    fn p(&self) -> usize {
        self.basis.counts.mode_count
    }

    fn check_level(level: f32) -> Result<()> {
        if level.is_finite() && (0.0..=MAX_LEVEL).contains(&level) {
            Ok(())
        } else {
            Err(Error::InvalidInput { what: "level" })
        }
    }

    /// Bytes of channel `c`'s mode projection in band `b`.
    fn channel_projection(&self, c: usize, b: usize) -> &'a [u8] {
        f32_row(
            self.basis.tables.channel_projection,
            c * self.basis.counts.bands + b,
            self.p(),
        )
    }

    /// Sets every channel's level at once (relative, 1 = as built) and recomputes the mode
    /// amplitudes from scratch, which also clears rounding drift of incremental updates.
    /// O(m·p·bands).
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
        self.recompute_amplitude(levels);
        if self.amplitude_is_finite() {
            for (slot, &l) in self.levels.iter_mut().zip(levels) {
                *slot = l;
            }
            Ok(())
        } else {
            // Back to the previous, valid levels.
            let old = self.levels.clone();
            self.recompute_amplitude(&old);
            Err(Error::InvalidInput { what: "levels" })
        }
    }

    /// `amplitude = patch_amplitude + Σ_c levels[c] · projection[c]`, over the first p modes.
    fn recompute_amplitude(&mut self, levels: &[f32]) {
        let p = self.p();
        for b in 0..BANDS {
            let (Some(amp), Some(base)) = (self.amplitude.get_mut(b), self.patch_amplitude.get(b))
            else {
                continue;
            };
            let amp = amp.get_mut(..p).unwrap_or(&mut []);
            amp.copy_from_slice(base.get(..p).unwrap_or(&[]));
            for (c, &l) in levels.iter().enumerate() {
                let projection = f32_row(
                    self.basis.tables.channel_projection,
                    c * self.basis.counts.bands + b,
                    p,
                );
                axpy_f32(l, projection, amp);
            }
        }
    }

    fn amplitude_is_finite(&self) -> bool {
        let p = self.p();
        self.amplitude
            .iter()
            .all(|a| a.get(..p).unwrap_or(&[]).iter().all(|v| v.is_finite()))
    }

    /// Changes one channel's level (relative, 1 = as built), updating the mode amplitudes
    /// incrementally in O(p·bands) without touching the other channels.
    pub fn set_channel_level(&mut self, channel: usize, level: f32) -> Result<()> {
        check_index("channel", channel, self.basis.counts.channel_count)?;
        Self::check_level(level)?;
        let old = self.levels.get(channel).copied().unwrap_or(0.0);
        let delta = level - old;
        let p = self.p();
        for b in 0..BANDS {
            let proj = self.channel_projection(channel, b);
            if let Some(amp) = self.amplitude.get_mut(b) {
                axpy_f32(delta, proj, amp.get_mut(..p).unwrap_or(&mut []));
            }
        }
        if !self.amplitude_is_finite() {
            let levels = self.levels.clone();
            self.recompute_amplitude(&levels);
            return Err(Error::InvalidInput { what: "level" });
        }
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

    /// Current level of `channel`.
    pub fn channel_level(&self, channel: usize) -> Result<f32> {
        check_index("channel", channel, self.basis.counts.channel_count)?;
        Ok(self.levels.get(channel).copied().unwrap_or(0.0))
    }

    fn identity(&self, patch: usize, band: usize) -> bool {
        identity(&self.basis, patch, band)
    }

    fn reflectance(&self, patch: usize, band: usize) -> f32 {
        f32_at(
            self.basis.tables.patch_reflectance,
            patch * self.basis.counts.bands + band,
        )
    }

    /// Sets the exitance a patch emits on top of its channel (the general case of an
    /// arbitrary initial exitance `M0`), per band in W/m² or lux. Incremental: O(p·bands +
    /// outputs·bands).
    ///
    /// The patch's own exitance and its direct light on sensors and zones are exact; the
    /// light it sends into the room is carried by the modes, so its accuracy is that of the
    /// truncation (exact when `p = n`).
    pub fn set_patch_exitance(&mut self, patch: usize, exitance: [f32; BANDS]) -> Result<()> {
        check_index("patch", patch, self.basis.counts.patch_count)?;
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
        let outputs = self.outputs();
        // Two passes: check that every updated value stays finite, then apply, so that a
        // rejected request leaves the state exactly as it was.
        for apply in [false, true] {
            for b in 0..BANDS {
                let delta =
                    exitance.get(b).copied().unwrap_or(0.0) - old.get(b).copied().unwrap_or(0.0);
                if delta == 0.0 {
                    continue;
                }
                let mut ok = true;
                let (amp, patch_amp) = (self.amplitude.get_mut(b), self.patch_amplitude.get_mut(b));
                let (Some(amp), Some(patch_amp)) = (amp, patch_amp) else {
                    continue;
                };
                let basis = &self.basis;
                patch_response(basis, patch, b, delta, |k, step| {
                    if let (Some(a), Some(pa)) = (amp.get_mut(k), patch_amp.get_mut(k)) {
                        if apply {
                            *a += step;
                            *pa += step;
                        } else {
                            ok &= (*a + step).is_finite() && (*pa + step).is_finite();
                        }
                    }
                });
                if identity(basis, patch, b) {
                    let direct = &mut self.patch_direct;
                    basis
                        .output_view()
                        .for_each(patch, 0, outputs.min(OUTPUTS), |o, f| {
                            if let Some(slot) = direct.get_mut(o).and_then(|r| r.get_mut(b)) {
                                if apply {
                                    *slot += f * delta;
                                } else {
                                    ok &= (*slot + f * delta).is_finite();
                                }
                            }
                        });
                }
                if !ok {
                    return Err(Error::InvalidInput { what: "exitance" });
                }
            }
        }
        if let Some(slot) = self.patch_exitance.get_mut(patch) {
            *slot = exitance;
        }
        Ok(())
    }

    /// Removes all exitance set with [`set_patch_exitance`](Self::set_patch_exitance).
    pub fn clear_patch_exitance(&mut self) {
        for (a, pa) in self.amplitude.iter_mut().zip(&mut self.patch_amplitude) {
            for (x, y) in a.iter_mut().zip(pa.iter_mut()) {
                *x -= *y;
                *y = 0.0;
            }
        }
        self.patch_exitance = [[0.0; BANDS]; PATCHES];
        self.patch_direct = [[0.0; BANDS]; OUTPUTS];
    }

    fn outputs(&self) -> usize {
        self.basis.counts.sensor_count + self.basis.counts.zone_count
    }

    /// Exitance the patch emits itself in `band`: its channel's share plus its own.
    fn emitted(&self, patch: usize, band: usize) -> f32 {
        let own = self
            .patch_exitance
            .get(patch)
            .and_then(|e| e.get(band))
            .copied()
            .unwrap_or(0.0);
        let c = u16_at(self.basis.tables.patch_channel, patch);
        if c == NO_CHANNEL {
            return own;
        }
        let level = self.levels.get(usize::from(c)).copied().unwrap_or(0.0);
        own + level
            * f32_at(
                self.basis.tables.patch_emission,
                patch * self.basis.counts.bands + band,
            )
    }

    fn checked(values: [f32; BANDS]) -> Result<[f32; BANDS]> {
        if values.iter().all(|v| v.is_finite()) {
            Ok(values)
        } else {
            Err(Error::InvalidInput { what: "levels" })
        }
    }

    /// Final exitance of `patch` per band, W/m² or lux (lm/m²). O(p + m) per band.
    pub fn exitance(&self, patch: usize) -> Result<[f32; BANDS]> {
        check_index("patch", patch, self.basis.counts.patch_count)?;
        let p = self.p();
        let bands = self.basis.counts.bands;
        let m = self.basis.counts.channel_count;
        let mut out = [0.0f32; BANDS];
        for (b, slot) in out.iter_mut().enumerate() {
            if self.identity(patch, b) {
                *slot = self.emitted(patch, b);
            }
        }
        let bounce = self.basis.channel_bounce();
        if bounce.cols != 0 {
            // One pass over the row (channel-major, band-minor), no index arithmetic per value.
            let (mut channel, mut band) = (0, 0);
            bounce.for_each(patch, 0, m * bands, |_, v| {
                if let (Some(slot), Some(&level)) = (out.get_mut(band), self.levels.get(channel)) {
                    *slot += v * level;
                }
                band += 1;
                if band == bands {
                    band = 0;
                    channel += 1;
                }
            });
        }
        let modes = self.basis.modes();
        for (b, slot) in out.iter_mut().enumerate() {
            let amp = self
                .amplitude
                .get(b)
                .map_or(&[][..], |a| a.get(..p).unwrap_or(&[]));
            *slot += modes.row_dot(patch, b * p, amp);
        }
        Self::checked(out)
    }

    /// Fills `out[i]` with the exitance of every patch `i` (W/m² or lux); `out` must have
    /// one entry per patch. O(n·(p + m)) per band.
    pub fn exitance_all(&self, out: &mut [[f32; BANDS]]) -> Result<()> {
        let n = self.basis.counts.patch_count;
        if out.len() != n {
            return Err(Error::LengthMismatch {
                what: "out",
                expected: n,
                found: out.len(),
            });
        }
        for (i, slot) in out.iter_mut().enumerate() {
            *slot = self.exitance(i)?;
        }
        Ok(())
    }

    /// Irradiance (illuminance in a photopic basis) arriving on `patch`, W/m² or lux:
    /// `E = (M − M_emitted)/ρ`. A patch with ρ = 0 in some band gives
    /// [`Error::BlackPatch`]: read a sensor or zone there instead.
    pub fn irradiance(&self, patch: usize) -> Result<[f32; BANDS]> {
        let m = self.exitance(patch)?;
        let mut out = [0.0f32; BANDS];
        for (b, (slot, &mb)) in out.iter_mut().zip(&m).enumerate() {
            let rho = self.reflectance(patch, b);
            if rho == 0.0 {
                return Err(Error::BlackPatch { patch });
            }
            *slot = (mb - self.emitted(patch, b)) / rho;
        }
        Self::checked(out)
    }

    /// Luminance of `patch` as a Lambertian surface, `L = M/π`: W/(m²·sr), or cd/m² in a
    /// photopic basis.
    pub fn luminance(&self, patch: usize) -> Result<[f32; BANDS]> {
        let mut m = self.exitance(patch)?;
        for v in &mut m {
            *v /= core::f32::consts::PI;
        }
        Ok(m)
    }

    /// Irradiance of output `o` (sensors first, then zones): modes, exact channel part and
    /// direct light from per-patch exitance. O(p + m) per band, independent of n.
    fn output(&self, o: usize) -> Result<[f32; BANDS]> {
        let p = self.p();
        let m = self.basis.counts.channel_count;
        let bands = self.basis.counts.bands;
        let mut out = [0.0f32; BANDS];
        for (b, slot) in out.iter_mut().enumerate() {
            let modes = f32_row(self.basis.tables.output_modes, o * bands + b, p);
            let amp = self
                .amplitude
                .get(b)
                .map_or(&[][..], |a| a.get(..p).unwrap_or(&[]));
            let chans = f32_row(self.basis.tables.output_channels, o * bands + b, m);
            let direct = self
                .patch_direct
                .get(o)
                .and_then(|d| d.get(b))
                .copied()
                .unwrap_or(0.0);
            *slot = dot_f32(modes, amp) + dot_f32(chans, &self.levels) + direct;
        }
        Self::checked(out)
    }

    /// Irradiance at sensor `sensor` (illuminance in lux for a photopic basis). O(p + m).
    pub fn sensor_irradiance(&self, sensor: usize) -> Result<[f32; BANDS]> {
        check_index("sensor", sensor, self.basis.counts.sensor_count)?;
        self.output(sensor)
    }

    /// Area-average irradiance over zone `zone` (illuminance in lux for a photopic basis).
    /// O(p + m).
    pub fn zone_irradiance(&self, zone: usize) -> Result<[f32; BANDS]> {
        check_index("zone", zone, self.basis.counts.zone_count)?;
        self.output(self.basis.counts.sensor_count + zone)
    }
}

/// Whether exitance of `patch` in `band` is carried exactly (not through the modes): all
/// patches in the split formulation, black patches only in the seed formulation.
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
