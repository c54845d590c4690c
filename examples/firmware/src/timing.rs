//! Instruction counts from SysTick under QEMU's `-icount shift=0`.
//!
//! With `shift=0` QEMU's virtual clock advances exactly 1 ns per guest instruction, and the
//! `mps2-an386` model clocks SysTick's core source at SYSCLK = 25 MHz, so one tick should be
//! 40 ns = 40 instructions. [`Ticks::calibrate`] measures the ratio instead of trusting it:
//! it times two `cortex_m::asm::delay` loops of known length (the loop body is `subs` +
//! `bne`, run `cycles + 1` times) and divides the difference in instructions by the
//! difference in ticks. It measures 40 (± one tick of quantisation in 200 000). Cross-checked
//! once by hand against the CMSDK APB timer 0 at 0x4000_0000, also clocked at 25 MHz: the
//! long loop took 250 000 ticks of both, and the tick count doubles with each step of
//! `shift` (1, 2, 3), as 2^shift ns per instruction implies. Counts are guest instructions,
//! not Cortex-M4 cycles: loads, FPU operations and taken branches take more than one cycle
//! on silicon.

use core::hint::black_box;

use cortex_m::peripheral::syst::SystClkSource;
use cortex_m::peripheral::SYST;

/// SysTick's largest reload: a 24-bit counter.
const RELOAD: u32 = 0x00FF_FFFF;
/// Ticks per full turn of the counter.
const PERIOD: u64 = RELOAD as u64 + 1;

/// The two calibration loop lengths, in `delay` iterations less one.
const SHORT: u32 = 1_000_000;
const LONG: u32 = 5_000_000;
/// Polls of SysTick allowed for its first reload; a tick is tens of instructions.
const RELOAD_WAIT: u32 = 10_000;

/// Measured instructions per SysTick tick, as a ratio of two exact counts.
#[derive(Clone, Copy)]
pub struct Calibration {
    /// Instructions between the two calibration loops.
    pub instructions: u64,
    /// SysTick ticks between them.
    pub ticks: u64,
}

impl Calibration {
    /// Instructions per tick, for printing.
    pub fn per_tick(&self) -> f32 {
        self.instructions as f32 / self.ticks.max(1) as f32
    }

    /// Instructions in `ticks` ticks.
    pub fn instructions_for(&self, ticks: u64) -> u64 {
        ticks.saturating_mul(self.instructions) / self.ticks.max(1)
    }
}

/// A free-running SysTick on the core clock, read as a down-counter with wrap counting.
pub struct Ticks {
    syst: SYST,
}

impl Ticks {
    /// Starts SysTick on the core clock with the largest reload, interrupt off.
    pub fn new(mut syst: SYST) -> Self {
        syst.disable_interrupt();
        syst.set_clock_source(SystClkSource::Core);
        syst.set_reload(RELOAD);
        syst.clear_current();
        syst.enable_counter();
        // Writing CVR leaves it at 0 until the first tick reloads it; a measurement that
        // started there would see no wrap and count nothing. Wait for the reload (bounded, in
        // case SysTick does not run at all: calibration then reports 0 ticks).
        for _ in 0..RELOAD_WAIT {
            if SYST::get_current() != 0 {
                break;
            }
        }
        Ticks { syst }
    }

    /// Ticks taken by `reps` calls of `f(i)`, stopping at the first error.
    ///
    /// Wraps are counted after every call, so one call must take less than one period
    /// (2²⁴ ticks, about 671 million instructions).
    pub fn count<E>(
        &mut self,
        reps: u32,
        mut f: impl FnMut(u32) -> Result<(), E>,
    ) -> Result<u64, E> {
        let _ = self.syst.has_wrapped(); // reading COUNTFLAG clears it
        let start = SYST::get_current();
        let mut wraps = 0u64;
        for i in 0..reps {
            f(black_box(i))?;
            if self.syst.has_wrapped() {
                wraps += 1;
            }
        }
        let end = SYST::get_current();
        if self.syst.has_wrapped() {
            wraps += 1;
        }
        Ok((wraps * PERIOD + u64::from(start)).saturating_sub(u64::from(end)))
    }

    /// Measures instructions per tick with two delay loops of known instruction counts.
    pub fn calibrate(&mut self) -> Calibration {
        let time = |ticks: &mut Self, cycles: u32| {
            ticks
                .count(1, |_| {
                    cortex_m::asm::delay(cycles);
                    Ok::<(), ()>(())
                })
                .unwrap_or(0)
        };
        let short = time(self, SHORT);
        let long = time(self, LONG);
        Calibration {
            // Two instructions per iteration; the call and set-up cancel in the difference.
            instructions: 2 * u64::from(LONG - SHORT),
            ticks: long.saturating_sub(short),
        }
    }
}
