//! What every code-size probe shares: the sink that keeps results alive, the entry point and
//! a panic handler without a message (formatting would add its own code).

use core::sync::atomic::{AtomicU32, Ordering};

/// Where every result goes, so that the optimiser keeps the code computing it.
static SINK: AtomicU32 = AtomicU32::new(0);

pub fn keep(v: f32) {
    SINK.fetch_xor(v.to_bits(), Ordering::Relaxed);
}

/// Runs `exercise` once, records whether it failed, and parks the core.
pub fn run<E>(exercise: impl FnOnce() -> Result<(), E>) -> ! {
    if exercise().is_err() {
        SINK.store(u32::MAX, Ordering::Relaxed);
    }
    loop {
        cortex_m::asm::wfi();
    }
}

#[panic_handler]
fn panic(_: &core::panic::PanicInfo<'_>) -> ! {
    loop {
        cortex_m::asm::wfi();
    }
}
