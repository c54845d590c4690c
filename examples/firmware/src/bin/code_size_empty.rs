//! Code-size probe without the runtime: its `.text` is the skeleton every probe shares
//! (vector table handlers, reset, the sink), subtracted from the others by
//! `scripts/code-size.sh`. Nothing runs the probes.
#![no_std]
#![no_main]
#![deny(unsafe_code)]

#[path = "../code_size/skeleton.rs"]
mod skeleton;

use core::hint::black_box;

#[cortex_m_rt::entry]
fn main() -> ! {
    skeleton::run(|| {
        skeleton::keep(black_box(1.0));
        Ok::<(), ()>(())
    })
}
