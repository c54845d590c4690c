//! The smallest firmware that evaluates an eigenrad basis: the basis in flash, a channel
//! evaluator on the stack, a level set and a sensor read in a loop. Replace the loop's body
//! with your controller: read a photosensor, set levels (`eigenrad_runtime::LevelProblem`),
//! drive the lamps (`eigenrad_runtime::dali`).

#![no_std]
#![no_main]

use core::panic::PanicInfo;

use cortex_m_rt::entry;
use eigenrad_runtime::{Basis, ChannelEvaluator, Result};

/// The basis, linked into flash as it is: `eigenrad build` writes it. This one is the
/// runtime's small test basis (one channel `main`, one sensor); put your own here.
static BASIS: &[u8] = include_bytes!("../../../runtime/tests/data/tiny.basis");

/// Channels the evaluator has room for: at least the basis' (checked when it is made).
const CHANNELS: usize = 4;

#[entry]
fn main() -> ! {
    // A basis that does not decode or does not fit is a data failure: report it your way
    // (a status LED, a log line); here the firmware stops.
    let _ = run();
    loop {
        core::hint::spin_loop();
    }
}

/// Decodes the basis once, then sets a level and reads the first sensor, lux.
fn run() -> Result<f32> {
    let basis = Basis::from_bytes(BASIS)?;
    let mut lights = ChannelEvaluator::<1, CHANNELS>::new(basis)?;
    lights.set_channel_level(0, 0.8)?;
    let [desk] = lights.sensor_irradiance(0)?;
    Ok(desk)
}

/// No unwinding on the device: a panic stops here. The runtime itself never panics on any
/// basis bytes; it returns an error.
#[panic_handler]
fn panic(_: &PanicInfo) -> ! {
    loop {
        core::hint::spin_loop();
    }
}
