//! Stack high-water mark.
//!
//! cortex-m-rt's `paint-stack` feature fills RAM from `_stack_end` (the end of .bss and
//! .uninit) up to `_stack_start` (the top of RAM) with `STACK_PAINT_VALUE` before `main`.
//! The deepest stack use is where the paint stops being intact. Reading that RAM needs raw
//! pointer reads, the only `unsafe` in the firmware.
#![allow(unsafe_code)]

use cortex_m_rt::STACK_PAINT_VALUE;

extern "C" {
    /// Top of the stack (initial SP), from cortex-m-rt's `link.x`.
    static _stack_start: u32;
    /// Lowest address the stack may reach, from cortex-m-rt's `link.x`.
    static _stack_end: u32;
}

/// Stack figures, bytes.
pub struct Usage {
    /// Deepest the stack has been since reset.
    pub high_water: usize,
    /// Room the linker left for the stack.
    pub region: usize,
}

/// How deep the stack has gone since reset.
pub fn usage() -> Usage {
    let top = (&raw const _stack_start) as usize;
    let bottom = (&raw const _stack_end) as usize;
    // Words below the current SP are not in use, so scanning them races with nothing.
    let sp = cortex_m::register::msp::read() as usize;
    let mut addr = bottom;
    while addr < sp {
        // SAFETY: `addr` is word-aligned (`_stack_end` is 4-aligned, see link.x) and lies
        // in [_stack_end, SP): RAM that belongs to the stack but that no live frame uses,
        // and no interrupt is enabled that could push a frame there.
        let word = unsafe { core::ptr::read_volatile(addr as *const u32) };
        if word != STACK_PAINT_VALUE {
            break;
        }
        addr += 4;
    }
    Usage {
        high_water: top.saturating_sub(addr),
        region: top.saturating_sub(bottom),
    }
}
