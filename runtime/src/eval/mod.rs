//! Evaluation of a basis for changing emitter levels, in fixed-size buffers.
//!
//! Two evaluators share the channel arithmetic. [`ChannelEvaluator`] holds one level per
//! channel and nothing else: every reading is a sum over the channels of their exact stored
//! responses (`channel_response`, `output_channels`). [`Evaluator`] adds exitance set patch by
//! patch, which goes through the modes, and the per-patch state that needs.
//! [`DaylightEvaluator`] reads the daylight of a basis that carries it, from a sky state, and
//! a reading's whole, daylight plus the electric light of either of the other two
//! ([`ElectricLight`]).

mod channels;
mod daylight;
mod figures;
mod patches;
mod reflection;
mod total;
mod weights;

pub use channels::ChannelEvaluator;
pub use daylight::{DaylightEvaluator, Sun};
pub(crate) use figures::Accumulator;
pub use figures::{Figures, Reading};
pub use patches::Evaluator;
pub use total::ElectricLight;

use crate::basis::Basis;
use crate::error::{Error, Result};
use crate::storage::f32_at;

/// Largest channel level accepted (relative; 1 is the level the basis was built for).
pub const MAX_LEVEL: f32 = 1.0e3;
/// Largest exitance accepted for a single patch, W/m² or lux.
pub const MAX_EXITANCE: f32 = 1.0e9;
/// `Ok` when the basis needs at most what the evaluator type has room for, else
/// [`Error::Capacity`] naming both sizes.
pub(crate) fn fits(what: &'static str, needed: usize, capacity: usize) -> Result<()> {
    if needed <= capacity {
        Ok(())
    } else {
        Err(Error::Capacity {
            what,
            needed,
            capacity,
        })
    }
}

/// `(M − emitted)/ρ` per band, or [`Error::BlackPatch`] when ρ = 0 in some band.
pub(crate) fn irradiance<const BANDS: usize>(
    basis: &Basis<'_>,
    patch: usize,
    exitance: [f32; BANDS],
    emitted: impl Fn(usize) -> f32,
) -> Result<[f32; BANDS]> {
    let mut out = [0.0f32; BANDS];
    for (b, (slot, &m)) in out.iter_mut().zip(&exitance).enumerate() {
        let rho = f32_at(
            basis.tables.patch_reflectance,
            patch * basis.counts.bands + b,
        );
        if rho == 0.0 {
            return Err(Error::BlackPatch { patch });
        }
        *slot = (m - emitted(b)) / rho;
    }
    Ok(out)
}

/// The figures of grid points `start..start + len` (zone `zone`'s) per band, each point read
/// once by `read` (its index among all grid points) and streamed: nothing is buffered.
/// [`Error::NoGrid`] when the zone has no points or a reading is not finite.
pub(crate) fn grid_figures<const BANDS: usize>(
    zone: usize,
    (start, len): (usize, usize),
    read: impl Fn(usize) -> Result<[f32; BANDS]>,
) -> Result<[Figures; BANDS]> {
    let mut acc = [Accumulator::<f32>::default(); BANDS];
    for g in start..start.saturating_add(len) {
        for (a, v) in acc.iter_mut().zip(read(g)?) {
            a.add(v);
        }
    }
    let mut out = [Figures::default(); BANDS];
    for (slot, a) in out.iter_mut().zip(&acc) {
        *slot = a.figures().ok_or(Error::NoGrid { zone })?;
    }
    Ok(out)
}

/// `M/π` per band.
pub(crate) fn luminance<const BANDS: usize>(mut exitance: [f32; BANDS]) -> [f32; BANDS] {
    for v in &mut exitance {
        *v /= core::f32::consts::PI;
    }
    exitance
}
