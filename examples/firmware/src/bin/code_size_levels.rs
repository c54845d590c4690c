//! Code-size probe of a channel-only controller that also solves its levels for a target:
//! what `code_size_channels` links plus `LevelProblem` (bounds from the basis' outputs, the
//! solve, DALI arc levels from the result), with inputs the optimiser cannot see through.
#![no_std]
#![no_main]
#![deny(unsafe_code)]

#[path = "../code_size/skeleton.rs"]
mod skeleton;

use core::hint::black_box;

use eigenrad_runtime::{dali, Basis, ChannelEvaluator, Error, LevelProblem, Output};
use skeleton::keep;

static BASIS: &[u8] = include_bytes!(concat!(env!("OUT_DIR"), "/basis.bin"));

/// Channel capacity as in the timing firmware (`src/main.rs`).
const CHANNELS: usize = 8;

fn exercise() -> Result<(), Error> {
    let basis = Basis::from_bytes(black_box(BASIS))?;
    let mut e: ChannelEvaluator<'_, 1, CHANNELS> = ChannelEvaluator::new(basis)?;
    let (channel, output) = (black_box(0), black_box(0));
    let m = e.basis().channel_count();
    e.set_channel_levels(black_box(&[1.0; CHANNELS]).get(..m).unwrap_or(&[]))?;
    e.set_channel_arc_power(channel, black_box(200))?;
    keep(e.sensor_irradiance(output)?[0] + e.zone_irradiance(output)?[0]);
    let channels = [0usize, 1, 2, 3, 4, 5, 6, 7];
    let controlled = channels.get(..m).unwrap_or(&[]);
    let weights = black_box([30.0f32; CHANNELS]);
    let mut problem = LevelProblem::new(weights.get(..m).unwrap_or(&[]))?;
    let ambient = e.reading_without(Output::Sensor(output), controlled)?;
    problem.add_output_bound(
        e.basis(),
        controlled,
        Output::Zone(output),
        black_box(ambient),
        black_box(500.0),
        f32::INFINITY,
    )?;
    let mut levels = [0.0f32; CHANNELS];
    let levels = levels.get_mut(..m).unwrap_or(&mut []);
    let solved = problem.solve(levels);
    for &level in levels.iter() {
        keep(f32::from(dali::level_to_arc_power(level)?));
    }
    keep(solved?.power);
    Ok(())
}

#[cortex_m_rt::entry]
fn main() -> ! {
    skeleton::run(exercise)
}
