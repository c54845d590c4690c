//! Code-size probe of a controller that only dims channels: decoding the basis and every
//! operation of a `ChannelEvaluator`, calculation grids included, with inputs the optimiser
//! cannot see through.
#![no_std]
#![no_main]
#![deny(unsafe_code)]

#[path = "../code_size/skeleton.rs"]
mod skeleton;

use core::hint::black_box;

use eigenrad_runtime::{Basis, ChannelEvaluator, Error};
use skeleton::keep;

static BASIS: &[u8] = include_bytes!(concat!(env!("OUT_DIR"), "/basis.bin"));

/// Channel capacity as in the timing firmware (`src/main.rs`).
const CHANNELS: usize = 8;

fn exercise() -> Result<(), Error> {
    let basis = Basis::from_bytes(black_box(BASIS))?;
    let mut e: ChannelEvaluator<'_, 1, CHANNELS> = ChannelEvaluator::new(basis)?;
    let (channel, patch, output) = (black_box(0), black_box(0), black_box(0));
    let m = e.basis().channel_count();
    e.set_channel_levels(black_box(&[1.0; CHANNELS]).get(..m).unwrap_or(&[]))?;
    e.set_channel_level(channel, black_box(0.5))?;
    e.set_channel_arc_power(channel, black_box(200))?;
    for v in [
        e.exitance(patch)?,
        e.irradiance(patch)?,
        e.luminance(patch)?,
        e.sensor_irradiance(output)?,
        e.zone_irradiance(output)?,
        e.grid_point_irradiance(output, black_box(0))?,
    ] {
        keep(v[0]);
    }
    let [figures] = e.zone_figures(output)?;
    keep(figures.average + figures.minimum + figures.maximum + figures.uniformity);
    let mut all = [[0.0f32; 1]; 4];
    let n = e.basis().patch_count().min(all.len());
    let out = all.get_mut(..n).unwrap_or_default();
    e.exitance_all(out)?;
    out.iter().for_each(|v| keep(v[0]));
    keep(e.channel_level(channel)?);
    if let Some(c) = e.basis().find_channel(black_box("lum1")) {
        keep(c as f32);
    }
    Ok(())
}

#[cortex_m_rt::entry]
fn main() -> ! {
    skeleton::run(exercise)
}
