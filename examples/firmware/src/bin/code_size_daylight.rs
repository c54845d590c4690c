//! Code-size probe of a controller's daylight: decoding the basis, every operation of a
//! `DaylightEvaluator` without modes (the sky update, every read, the grids' figures) and the
//! sky it is given: the CIE clear sky for a sun direction, scaled to a diffuse horizontal
//! illuminance, and the luminances of its patches, with inputs the optimiser cannot see
//! through. The sun's position is `code_size_sun`'s.
#![no_std]
#![no_main]
#![deny(unsafe_code)]

#[path = "../code_size/skeleton.rs"]
mod skeleton;

use core::hint::black_box;

use eigenrad_runtime::sky::{self, cie::CieSky};
use eigenrad_runtime::{Basis, DaylightEvaluator, Error, Sun};
use skeleton::keep;

static BASIS: &[u8] = include_bytes!(concat!(env!("OUT_DIR"), "/basis.bin"));

/// Capacities as in the timing firmware (`src/daylight.rs`): Tregenza's 145 sky patches,
/// 8 sensors and zones, no modes.
const SKY: usize = 145;
const OUTPUTS: usize = 8;

fn exercise() -> Result<(), Error> {
    let basis = Basis::from_bytes(black_box(BASIS))?;
    let mut e: DaylightEvaluator<'_, SKY, OUTPUTS, 0> = DaylightEvaluator::new(basis)?;
    let patches = e.basis().sky_patches().ok_or(Error::NoDaylight)?;
    let direction = sky::direction(black_box(0.8), black_box(3.0));
    let clear = CieSky::standard(black_box(12), direction)?;
    let zenith = clear.zenith_luminance_for(black_box(10_000.0))?;
    let mut luminance = [0.0f32; SKY];
    let luminance = luminance.get_mut(..patches.count()).unwrap_or_default();
    patches.luminances(&clear, zenith, luminance)?;
    let sun = Sun {
        direction,
        direct_normal: black_box(60_000.0),
    };
    e.set_sky(luminance, black_box(60_000.0), Some(sun))?;
    let (output, point) = (black_box(0), black_box(0));
    keep(e.sensor_illuminance(output)? + e.zone_illuminance(output)?);
    keep(e.grid_point_illuminance(output, point)?);
    let figures = e.zone_figures(output)?;
    keep(figures.average + figures.minimum + figures.maximum + figures.uniformity);
    Ok(())
}

#[cortex_m_rt::entry]
fn main() -> ! {
    skeleton::run(exercise)
}
