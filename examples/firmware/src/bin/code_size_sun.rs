//! Code-size probe of the sun's position as the timing firmware computes it
//! (`src/daylight.rs`): NREL's SPA through the `solar-positioning` crate for a Julian date,
//! with ΔT estimated from the year and month and the refraction of a standard atmosphere,
//! in `f64` (software floating point on a Cortex-M4F), with inputs the optimiser cannot see
//! through. No basis and no part of the runtime.
#![no_std]
#![no_main]
#![deny(unsafe_code)]

#[path = "../code_size/skeleton.rs"]
mod skeleton;

use core::hint::black_box;

use skeleton::keep;
use solar_positioning::time::JulianDate;
use solar_positioning::{delta_t, Location, RefractionCorrection, SolarPositions};

fn exercise() -> Result<(), solar_positioning::Error> {
    let dt = delta_t::estimate_from_date(black_box(2026), black_box(6))?;
    let time = JulianDate::new(black_box(2_461_212.5), dt)?;
    let location = Location {
        latitude: black_box(48.21),
        longitude: black_box(16.37),
    };
    let refraction = RefractionCorrection::new(black_box(1013.25), black_box(15.0))?;
    let p =
        SolarPositions::new().at_from_julian(time, location, black_box(170.0), Some(refraction))?;
    keep(p.elevation_angle() as f32);
    keep(p.azimuth() as f32);
    Ok(())
}

#[cortex_m_rt::entry]
fn main() -> ! {
    skeleton::run(exercise)
}
