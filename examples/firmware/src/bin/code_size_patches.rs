//! Code-size probe of a controller that also sets exitance patch by patch: decoding the basis
//! and every operation of an `Evaluator` (which holds a `ChannelEvaluator`) but the
//! calculation grids' (the channel probe reads those), with inputs the optimiser cannot see
//! through.
#![no_std]
#![no_main]
#![deny(unsafe_code)]

#[path = "../code_size/skeleton.rs"]
mod skeleton;

use core::hint::black_box;

use eigenrad_runtime::{Basis, Error, Evaluator};
use skeleton::keep;

static BASIS: &[u8] = include_bytes!(concat!(env!("OUT_DIR"), "/basis.bin"));

/// Capacities as in the timing firmware (`src/main.rs`).
const PATCHES: usize = 2048;
const MODES: usize = 128;
const CHANNELS: usize = 8;
const OUTPUTS: usize = 8;

fn exercise() -> Result<(), Error> {
    let basis = Basis::from_bytes(black_box(BASIS))?;
    let mut e: Evaluator<'_, 1, PATCHES, MODES, CHANNELS, OUTPUTS> = Evaluator::new(basis)?;
    let (channel, patch, output) = (black_box(0), black_box(0), black_box(0));
    let m = e.basis().channel_count();
    e.set_channel_levels(black_box(&[1.0; CHANNELS]).get(..m).unwrap_or(&[]))?;
    e.set_channel_level(channel, black_box(0.5))?;
    e.set_channel_arc_power(channel, black_box(200))?;
    e.set_patch_exitance(patch, [black_box(50.0)])?;
    for v in [
        e.exitance(patch)?,
        e.irradiance(patch)?,
        e.luminance(patch)?,
        e.sensor_irradiance(output)?,
        e.zone_irradiance(output)?,
    ] {
        keep(v[0]);
    }
    let mut all = [[0.0f32; 1]; 4];
    let n = e.basis().patch_count().min(all.len());
    let out = all.get_mut(..n).unwrap_or_default();
    e.exitance_all(out)?;
    out.iter().for_each(|v| keep(v[0]));
    keep(e.channel_level(channel)? + e.basis().eigenvalue(0, 0)?);
    if let Some(c) = e.basis().find_channel(black_box("lum1")) {
        keep(c as f32);
    }
    e.clear_patch_exitance();
    Ok(())
}

#[cortex_m_rt::entry]
fn main() -> ! {
    skeleton::run(exercise)
}
