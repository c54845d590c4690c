//! eigenrad on a Cortex-M4F: evaluates the basis linked into flash for a fixed sequence of
//! channel levels and prints every reading, the RAM the evaluator takes, the stack used and
//! the instructions spent per update, as lines a host test parses (`tests/firmware.rs`).
//!
//! Output, one record a line, fields separated by single spaces, numbers in `{:e}` (the
//! shortest form that reads back to the same `f32`):
//!
//! ```text
//! basis bytes <len> bands <B> patches <n> modes <p> channels <m> sensors <s> zones <z>
//! evaluator size_of <bytes> ram_bytes <bytes> capacity <B> <n> <p> <m> <outputs>
//! step <k> op all <level> | op level <channel> <level> | op arc <channel> <arc>
//! step <k> levels <l0> <l1> ...                 relative level of every channel
//! reading <k> sensor <name> <v0> [<v1> <v2>]    W/m² per band, or lux
//! reading <k> zone <name> <v0> [<v1> <v2>]
//! exitance <k> patch <i> <v0> [<v1> <v2>]       every PATCH_STRIDE-th patch, W/m² or lux
//! systick calibration instructions <n> ticks <t> instructions_per_tick <x>
//! timing <what> reps <r> ticks <t> baseline_ticks <t0>
//! instructions full_update|channel_update|read_outputs|patch_exitance <per call>
//! stack high_water <bytes> region <bytes>
//! done
//! ```
//!
//! Any error is printed as `error <message>` and QEMU exits with a failure status.
#![no_std]
#![no_main]
#![deny(unsafe_code)]

mod stack;
mod timing;

use core::fmt;
use core::hint::black_box;

use cortex_m_rt::entry;
use cortex_m_semihosting::{debug, hprintln};
use eigenrad_runtime::{Basis, Error, Evaluator};

use timing::Ticks;

/// The basis chosen at build time (`EIGENRAD_BASIS`, see `build.rs`), kept in flash.
static BASIS: &[u8] = include_bytes!(concat!(env!("OUT_DIR"), "/basis.bin"));

/// Evaluator capacities: a room of up to 2048 patches, 128 modes per band, 8 channels and 8
/// sensors plus zones. The same type serves every basis that fits, so RAM does not depend on
/// which basis is linked.
const PATCHES: usize = 2048;
const MODES: usize = 128;
const CHANNELS: usize = 8;
const OUTPUTS: usize = 8;

/// DALI arc power levels applied to each channel in turn: full, two dimmed levels, the
/// lowest non-zero level (0.1 %) and off.
const ARC_LEVELS: [u8; 5] = [254, 200, 128, 1, 0];
/// The level channel 0 is set to, incrementally, after all channels start at 1.
const HALF: f32 = 0.5;
/// Repetitions of each timed operation; the count is divided out.
const REPS: u32 = 1000;
/// The exitance of patches 0, 97, 194, ... is printed at every step. Sensors and zones read
/// only `f32` tables; a patch's exitance reads its row of mode vectors and first bounces,
/// the tables an f16 or i16 basis stores in 16 bits. 97 is prime, so the sample does not
/// follow the regular order in which a mesher emits the patches of one wall.
const PATCH_STRIDE: usize = 97;

/// Why the firmware stopped.
enum Fail {
    /// The runtime refused the basis or an input.
    Runtime(Error),
    /// Something about the board: a peripheral already taken, a basis with an odd shape.
    Board(&'static str),
}

impl From<Error> for Fail {
    fn from(e: Error) -> Self {
        Fail::Runtime(e)
    }
}

impl fmt::Display for Fail {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Fail::Runtime(e) => write!(f, "runtime: {e}"),
            Fail::Board(what) => write!(f, "board: {what}"),
        }
    }
}

#[entry]
fn main() -> ! {
    match run() {
        Ok(()) => {
            hprintln!("done");
            debug::exit(debug::EXIT_SUCCESS);
        }
        Err(e) => {
            hprintln!("error {}", e);
            debug::exit(debug::EXIT_FAILURE);
        }
    }
    // `exit` returns only when semihosting is off (not under QEMU); park the core.
    loop {
        cortex_m::asm::wfi();
    }
}

fn run() -> Result<(), Fail> {
    let peripherals = cortex_m::Peripherals::take().ok_or(Fail::Board("peripherals taken"))?;
    let mut ticks = Ticks::new(peripherals.SYST);
    let calibration = ticks.calibrate();
    let basis = Basis::from_bytes(BASIS)?;
    hprintln!(
        "basis bytes {} bands {} patches {} modes {} channels {} sensors {} zones {}",
        basis.byte_len(),
        basis.bands(),
        basis.patch_count(),
        basis.mode_count(),
        basis.channel_count(),
        basis.sensor_count(),
        basis.zone_count()
    );
    hprintln!(
        "systick calibration instructions {} ticks {} instructions_per_tick {:e}",
        calibration.instructions,
        calibration.ticks,
        calibration.per_tick()
    );
    // One instantiation per band count, each in its own frame: only one is ever live.
    match basis.bands() {
        1 => exercise::<1>(basis, &mut ticks, calibration)?,
        3 => exercise::<3>(basis, &mut ticks, calibration)?,
        _ => return Err(Fail::Board("basis band count is neither 1 nor 3")),
    }
    let stack = stack::usage();
    hprintln!(
        "stack high_water {} region {}",
        stack.high_water,
        stack.region
    );
    Ok(())
}

#[inline(never)]
fn exercise<const BANDS: usize>(
    basis: Basis<'_>,
    ticks: &mut Ticks,
    calibration: timing::Calibration,
) -> Result<(), Fail> {
    let mut eval = Evaluator::<BANDS, PATCHES, MODES, CHANNELS, OUTPUTS>::new(basis)?;
    hprintln!(
        "evaluator size_of {} ram_bytes {} capacity {} {} {} {} {}",
        core::mem::size_of_val(&eval),
        Evaluator::<BANDS, PATCHES, MODES, CHANNELS, OUTPUTS>::RAM_BYTES,
        BANDS,
        PATCHES,
        MODES,
        CHANNELS,
        OUTPUTS
    );
    let m = basis.channel_count();
    let mut step = 0usize;

    hprintln!("step {} op all {:e}", step, 1.0f32);
    let ones = [1.0f32; CHANNELS];
    eval.set_channel_levels(ones.get(..m).unwrap_or(&[]))?;
    report(&eval, step)?;

    step += 1;
    hprintln!("step {} op level 0 {:e}", step, HALF);
    eval.set_channel_level(0, HALF)?;
    report(&eval, step)?;

    for channel in 0..m {
        for arc in ARC_LEVELS {
            step += 1;
            hprintln!("step {} op arc {} {}", step, channel, arc);
            eval.set_channel_arc_power(channel, arc)?;
            report(&eval, step)?;
        }
    }

    measure(&mut eval, ticks, calibration)
}

/// Prints the levels, every sensor and zone reading and a sample of patch exitances after
/// step `step`.
fn report<const B: usize, const N: usize, const P: usize, const C: usize, const O: usize>(
    eval: &Evaluator<'_, B, N, P, C, O>,
    step: usize,
) -> Result<(), Fail> {
    let basis = *eval.basis();
    let mut levels = Line::new();
    for c in 0..basis.channel_count() {
        levels.push(eval.channel_level(c)?);
    }
    hprintln!("step {} levels{}", step, levels);
    for s in 0..basis.sensor_count() {
        let values = Line::of(&eval.sensor_irradiance(s)?);
        hprintln!(
            "reading {} sensor {}{}",
            step,
            basis.sensor_name(s)?,
            values
        );
    }
    for z in 0..basis.zone_count() {
        let values = Line::of(&eval.zone_irradiance(z)?);
        hprintln!("reading {} zone {}{}", step, basis.zone_name(z)?, values);
    }
    for i in (0..basis.patch_count()).step_by(PATCH_STRIDE) {
        let values = Line::of(&eval.exitance(i)?);
        hprintln!("exitance {} patch {}{}", step, i, values);
    }
    Ok(())
}

/// Counts instructions for full updates, single-channel updates, reads of all outputs and
/// reads of one patch's exitance, each repeated [`REPS`] times and set against an empty loop of the same shape.
fn measure<const B: usize, const N: usize, const P: usize, const C: usize, const O: usize>(
    eval: &mut Evaluator<'_, B, N, P, C, O>,
    ticks: &mut Ticks,
    calibration: timing::Calibration,
) -> Result<(), Fail> {
    let basis = *eval.basis();
    let m = basis.channel_count();
    // Two level sets that differ in every channel, so each update does real work.
    let low = [0.25f32; CHANNELS];
    let high = [0.75f32; CHANNELS];
    let low = low.get(..m).unwrap_or(&[]);
    let high = high.get(..m).unwrap_or(&[]);

    let baseline = ticks.count(REPS, |i| {
        black_box(i);
        Ok::<(), Error>(())
    })?;
    let full = ticks.count(REPS, |i| {
        eval.set_channel_levels(if i % 2 == 0 { low } else { high })
    })?;
    let channel = ticks.count(REPS, |i| {
        let c = i as usize % m.max(1);
        eval.set_channel_level(c, if i % 2 == 0 { 0.25 } else { 0.75 })
    })?;
    let read = ticks.count(REPS, |_| {
        for s in 0..basis.sensor_count() {
            black_box(eval.sensor_irradiance(s)?);
        }
        for z in 0..basis.zone_count() {
            black_box(eval.zone_irradiance(z)?);
        }
        Ok::<(), Error>(())
    })?;
    // One patch's exitance: the read that decodes the f16/i16 tables (mode vectors and first
    // bounces), over patches spread through the basis.
    let n = basis.patch_count().max(1);
    let patch = ticks.count(REPS, |i| {
        black_box(eval.exitance(i as usize * PATCH_STRIDE % n)?);
        Ok::<(), Error>(())
    })?;
    for (what, t) in [
        ("full_update", full),
        ("channel_update", channel),
        ("read_outputs", read),
        ("patch_exitance", patch),
    ] {
        hprintln!(
            "timing {} reps {} ticks {} baseline_ticks {}",
            what,
            REPS,
            t,
            baseline
        );
        let per_call = calibration.instructions_for(t.saturating_sub(baseline)) / u64::from(REPS);
        hprintln!("instructions {} {}", what, per_call);
    }
    Ok(())
}

/// Up to three numbers (one per band) or up to [`CHANNELS`] levels, printed as ` <v>` each.
struct Line {
    values: [f32; CHANNELS],
    len: usize,
}

impl Line {
    fn new() -> Self {
        Line {
            values: [0.0; CHANNELS],
            len: 0,
        }
    }

    fn of(values: &[f32]) -> Self {
        let mut line = Line::new();
        for &v in values {
            line.push(v);
        }
        line
    }

    fn push(&mut self, v: f32) {
        if let Some(slot) = self.values.get_mut(self.len) {
            *slot = v;
            self.len += 1;
        }
    }
}

impl fmt::Display for Line {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        for v in self.values.get(..self.len).unwrap_or(&[]) {
            write!(f, " {v:e}")?;
        }
        Ok(())
    }
}

#[panic_handler]
fn panic(info: &core::panic::PanicInfo<'_>) -> ! {
    hprintln!("panic {}", info);
    debug::exit(debug::EXIT_FAILURE);
    loop {
        cortex_m::asm::wfi();
    }
}
