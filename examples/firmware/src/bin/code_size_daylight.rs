//! Code-size probe of a controller's daylight: decoding the basis, every operation of a
//! `DaylightEvaluator` without modes (the sky update, every read, the grids' figures) and the
//! sky it is given: the sun's position by the runtime (`sky::sun`, single precision), the CIE
//! clear sky for it, scaled to a diffuse horizontal illuminance, and the luminances of its
//! patches from their centres computed once, with inputs the optimiser cannot see through:
//! all a controller needs for daylight. SPA's position, which the timing firmware uses as
//! the reference, is `code_size_sun`'s.
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
    let time = sky::sun::Utc {
        year: black_box(2026),
        month: black_box(6),
        day: black_box(21),
        seconds: black_box(36_000.0),
    };
    let direction = sky::sun::position(black_box(48.21), black_box(16.37), time)?.direction;
    let clear = CieSky::standard(black_box(12), direction)?;
    let zenith = clear.zenith_luminance_for(black_box(10_000.0))?;
    let mut centres = [[0.0f32; 3]; SKY];
    let centres = centres.get_mut(..patches.count()).unwrap_or_default();
    patches.centres(centres)?;
    let mut luminance = [0.0f32; SKY];
    let luminance = luminance.get_mut(..patches.count()).unwrap_or_default();
    patches.luminances_at(centres, &clear, zenith, luminance)?;
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
