//! eigenrad on a Cortex-M4F: evaluates the basis linked into flash for a fixed sequence of
//! channel levels (and, when the basis carries daylight, through two days of sun and sky) and
//! prints every reading, the RAM the evaluators take, the stack used and the instructions
//! spent per update and read, as lines a host test parses (`tests/firmware.rs`).
//!
//! Two evaluators run side by side: a `ChannelEvaluator` (channel levels only, the state a
//! controller that dims channels needs) prints the readings, and a full `Evaluator` (also
//! exitance set patch by patch) must read exactly the same at every step; the firmware stops
//! with an error if it does not.
//!
//! Output, one record a line, fields separated by single spaces, numbers in `{:e}` (the
//! shortest form that reads back to the same `f32`):
//!
//! ```text
//! basis bytes <len> bands <B> patches <n> modes <p> channels <m> sensors <s> zones <z>
//! evaluator size_of <bytes> ram_bytes <bytes> capacity <B> <n> <p> <m> <outputs>
//! channel_evaluator size_of <bytes> ram_bytes <bytes> capacity <B> <m>
//! step <k> op all <level> | op level <channel> <level> | op arc <channel> <arc>
//! step <k> levels <l0> <l1> ...                 relative level of every channel
//! reading <k> sensor <name> <v0> [<v1> <v2>]    W/m² per band, or lux
//! reading <k> zone <name> <v0> [<v1> <v2>]
//! exitance <k> patch <i> <v0> [<v1> <v2>]       every PATCH_STRIDE-th patch, W/m² or lux
//! systick calibration instructions <n> ticks <t> instructions_per_tick <x>
//! timing <what> reps <r> ticks <t> baseline_ticks <t0>
//! instructions <what> <per call>                see `measure` for the operations
//! control ...                                  the controller loop: see `control.rs`
//! daylight setup sky cie <type> diffuse_horizontal <lux> direct_normal <lux> sky_patches <n> nodes <D> sun_nodes <s>
//! daylight site latitude <deg> longitude <deg> elevation <m> utc_offset_minutes <min>
//! daylight_evaluator size_of <bytes> ram_bytes <bytes> capacity <sky> <outputs> <modes>
//! daylight zone work_plane <z>
//! daylight step <k> time <YYYY-MM-DDTHH:MM+HH:MM> altitude <deg> azimuth <deg> global_horizontal <lux>
//! daylight reading <k> sensor <name> <lux>      daylight alone
//! daylight reading <k> zone <name> <lux>
//! daylight figures <k> average <lux> minimum <lux> maximum <lux> uniformity <u> zone <name>
//! harvest ...                                  the daylight-harvesting day: see `harvest.rs`
//! stack high_water <bytes> region <bytes>
//! done
//! ```
//!
//! The `daylight` records (and their `timing` and `instructions` lines) come only from a
//! firmware built with a basis that carries daylight (`build.rs`): the two solstices of
//! sun and clear sky at the basis' site, stepped every 30 minutes while the sun is up, read
//! through a `DaylightEvaluator`; the sun's altitude and azimuth are `f64` (`{:e}` reads back
//! to the same `f64`). See `daylight.rs`. The `harvest` records, from the same bases only,
//! are a day of two controllers that keep the work plane at its target under an overcast sky
//! (`harvest.rs`). A firmware built with any other basis prints none of them and links none
//! of their code.
//!
//! Any error is printed as `error <message>` and QEMU exits with a failure status.
#![no_std]
#![no_main]
#![deny(unsafe_code)]

mod control;
// Called only when the linked basis carries daylight (`build.rs` sets `daylight`); compiled
// and linted always, and left out of the binary by the linker otherwise.
#[cfg_attr(not(daylight), allow(dead_code))]
mod daylight;
// The daylight-harvesting controller's day: as `daylight`, only with a daylight basis.
#[cfg_attr(not(daylight), allow(dead_code))]
mod harvest;
mod stack;
mod timing;

use core::fmt;
use core::hint::black_box;

use cortex_m_rt::entry;
use cortex_m_semihosting::{debug, hprintln};
use eigenrad_runtime::{Basis, ChannelEvaluator, Error, Evaluator};

use timing::Ticks;

/// The basis chosen at build time (`EIGENRAD_BASIS`, see `build.rs`), kept in flash.
static BASIS: &[u8] = include_bytes!(concat!(env!("OUT_DIR"), "/basis.bin"));

/// Evaluator capacities: a room of up to 2048 patches, 128 modes per band, 8 channels and 8
/// sensors plus zones (the channel evaluator needs only the channels). The same types serve
/// every basis that fits, so RAM does not depend on which basis is linked.
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
/// only `f32` tables; a patch's exitance reads its row of channel responses, a table an f16
/// or i16 basis stores in 16 bits. 97 is prime, so the sample does not follow the regular
/// order in which a mesher emits the patches of one wall.
const PATCH_STRIDE: usize = 97;

/// Exitance set on a patch when the evaluator's patch operations are timed, lux or W/m².
const PATCH_EXITANCE: f32 = 50.0;

/// Why the firmware stopped.
enum Fail {
    /// The runtime refused the basis or an input.
    Runtime(Error),
    /// Something about the board: a peripheral already taken, a basis with an odd shape.
    Board(&'static str),
    /// The two evaluators read different values at a step.
    Disagree(usize),
    /// The day of daylight stopped (only in a firmware built with a daylight basis, so that
    /// one built without links none of its code).
    #[cfg(daylight)]
    Daylight(daylight::Fail),
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
            Fail::Disagree(step) => write!(
                f,
                "step {step}: the full evaluator without patch exitance reads otherwise than \
                 the channel evaluator"
            ),
            #[cfg(daylight)]
            Fail::Daylight(e) => write!(f, "daylight: {e}"),
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
        1 => {
            exercise::<1>(basis, &mut ticks, calibration)?;
            controller(basis, &mut ticks, calibration)?;
            #[cfg(daylight)]
            daylight::run(basis, &mut ticks, calibration).map_err(Fail::Daylight)?;
            #[cfg(daylight)]
            harvest::run(basis)?;
        }
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
    let mut lights = ChannelEvaluator::<BANDS, CHANNELS>::new(basis)?;
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
    hprintln!(
        "channel_evaluator size_of {} ram_bytes {} capacity {} {}",
        core::mem::size_of_val(&lights),
        ChannelEvaluator::<BANDS, CHANNELS>::RAM_BYTES,
        BANDS,
        CHANNELS
    );
    let m = basis.channel_count();
    let mut step = 0usize;

    hprintln!("step {} op all {:e}", step, 1.0f32);
    let ones = [1.0f32; CHANNELS];
    let ones = ones.get(..m).unwrap_or(&[]);
    lights.set_channel_levels(ones)?;
    eval.set_channel_levels(ones)?;
    report(&lights, &eval, step)?;

    step += 1;
    hprintln!("step {} op level 0 {:e}", step, HALF);
    lights.set_channel_level(0, HALF)?;
    eval.set_channel_level(0, HALF)?;
    report(&lights, &eval, step)?;

    for channel in 0..m {
        for arc in ARC_LEVELS {
            step += 1;
            hprintln!("step {} op arc {} {}", step, channel, arc);
            lights.set_channel_arc_power(channel, arc)?;
            eval.set_channel_arc_power(channel, arc)?;
            report(&lights, &eval, step)?;
        }
    }

    measure(&mut lights, &mut eval, ticks, calibration)?;
    // Patch exitance set and cleared leaves the full evaluator reading the channels alone.
    for c in 0..m {
        eval.set_channel_level(c, lights.channel_level(c)?)?;
    }
    eval.clear_patch_exitance();
    compare(&lights, &eval, step + 1)
}

/// The controller loop of `control.rs` on a channel evaluator of its own (one band).
#[inline(never)]
fn controller(
    basis: Basis<'_>,
    ticks: &mut Ticks,
    calibration: timing::Calibration,
) -> Result<(), Fail> {
    let mut lights = ChannelEvaluator::<1, CHANNELS>::new(basis)?;
    control::run(&mut lights, ticks, calibration)
}

/// Prints the levels, every sensor and zone reading and a sample of patch exitances after
/// step `step`, read from the channel evaluator, and checks that the full evaluator reads
/// the same.
fn report<const B: usize, const N: usize, const P: usize, const C: usize, const O: usize>(
    lights: &ChannelEvaluator<'_, B, C>,
    eval: &Evaluator<'_, B, N, P, C, O>,
    step: usize,
) -> Result<(), Fail> {
    let basis = *lights.basis();
    let mut levels = Line::new();
    for c in 0..basis.channel_count() {
        levels.push(lights.channel_level(c)?);
    }
    hprintln!("step {} levels{}", step, levels);
    for s in 0..basis.sensor_count() {
        let values = Line::of(&lights.sensor_irradiance(s)?);
        hprintln!(
            "reading {} sensor {}{}",
            step,
            basis.sensor_name(s)?,
            values
        );
    }
    for z in 0..basis.zone_count() {
        let values = Line::of(&lights.zone_irradiance(z)?);
        hprintln!("reading {} zone {}{}", step, basis.zone_name(z)?, values);
    }
    for i in (0..basis.patch_count()).step_by(PATCH_STRIDE) {
        let values = Line::of(&lights.exitance(i)?);
        hprintln!("exitance {} patch {}{}", step, i, values);
    }
    compare(lights, eval, step)
}

/// Every level, reading and patch exitance of the two evaluators agrees to the bit, or
/// [`Fail::Disagree`].
fn compare<const B: usize, const N: usize, const P: usize, const C: usize, const O: usize>(
    lights: &ChannelEvaluator<'_, B, C>,
    eval: &Evaluator<'_, B, N, P, C, O>,
    step: usize,
) -> Result<(), Fail> {
    let basis = *lights.basis();
    let mut same = true;
    for c in 0..basis.channel_count() {
        same &= lights.channel_level(c)? == eval.channel_level(c)?;
    }
    for s in 0..basis.sensor_count() {
        same &= lights.sensor_irradiance(s)? == eval.sensor_irradiance(s)?;
    }
    for z in 0..basis.zone_count() {
        same &= lights.zone_irradiance(z)? == eval.zone_irradiance(z)?;
    }
    for i in 0..basis.patch_count() {
        same &= lights.exitance(i)? == eval.exitance(i)?;
    }
    if same {
        Ok(())
    } else {
        Err(Fail::Disagree(step))
    }
}

/// Counts instructions per call, each operation repeated [`REPS`] times and set against an
/// empty loop of the same shape:
///
/// - on the channel evaluator: `full_update` (`set_channel_levels`, every channel
///   changed), `channel_update` (`set_channel_level`), `read_outputs` (every sensor and
///   zone), `full_update_read_outputs` and `channel_update_read_outputs` (an update, then
///   every output), `channel_exitance` (one patch's exitance);
/// - on the full evaluator: `patch_update` (`set_patch_exitance` on one patch), then, with
///   exitance set on those patches, `patch_read_outputs` (every sensor and zone) and
///   `patch_exitance` (one patch's exitance).
fn measure<const B: usize, const N: usize, const P: usize, const C: usize, const O: usize>(
    lights: &mut ChannelEvaluator<'_, B, C>,
    eval: &mut Evaluator<'_, B, N, P, C, O>,
    ticks: &mut Ticks,
    calibration: timing::Calibration,
) -> Result<(), Fail> {
    let basis = *lights.basis();
    let m = basis.channel_count();
    // Two level sets that differ in every channel, so each update does real work.
    let low = [0.25f32; CHANNELS];
    let high = [0.75f32; CHANNELS];
    let low = low.get(..m).unwrap_or(&[]);
    let high = high.get(..m).unwrap_or(&[]);
    let level = |i: u32| if i % 2 == 0 { 0.25 } else { 0.75 };
    let n = basis.patch_count().max(1);
    // Patches spread through the basis, so that reads do not stay in one part of flash.
    let spread = |i: u32| i as usize * PATCH_STRIDE % n;

    let baseline = ticks.count(REPS, |i| {
        black_box(i);
        Ok::<(), Error>(())
    })?;
    let read_all = |lights: &ChannelEvaluator<'_, B, C>| {
        for s in 0..basis.sensor_count() {
            black_box(lights.sensor_irradiance(s)?);
        }
        for z in 0..basis.zone_count() {
            black_box(lights.zone_irradiance(z)?);
        }
        Ok::<(), Error>(())
    };
    let full = ticks.count(REPS, |i| {
        lights.set_channel_levels(if i % 2 == 0 { low } else { high })
    })?;
    let channel = ticks.count(REPS, |i| {
        lights.set_channel_level(i as usize % m.max(1), level(i))
    })?;
    let read = ticks.count(REPS, |_| read_all(lights))?;
    let full_read = ticks.count(REPS, |i| {
        lights.set_channel_levels(if i % 2 == 0 { low } else { high })?;
        read_all(lights)
    })?;
    let channel_read = ticks.count(REPS, |i| {
        lights.set_channel_level(i as usize % m.max(1), level(i))?;
        read_all(lights)
    })?;
    let channel_patch = ticks.count(REPS, |i| {
        black_box(lights.exitance(spread(i))?);
        Ok::<(), Error>(())
    })?;

    // The full evaluator with patch exitance set: the modal part of every read.
    eval.set_channel_levels(low)?;
    let patch_update = ticks.count(REPS, |i| {
        let x = if i % 2 == 0 { 1.0 } else { 2.0 };
        eval.set_patch_exitance(spread(i), [x * PATCH_EXITANCE; B])
    })?;
    let patch_read = ticks.count(REPS, |_| {
        for s in 0..basis.sensor_count() {
            black_box(eval.sensor_irradiance(s)?);
        }
        for z in 0..basis.zone_count() {
            black_box(eval.zone_irradiance(z)?);
        }
        Ok::<(), Error>(())
    })?;
    let patch = ticks.count(REPS, |i| {
        black_box(eval.exitance(spread(i))?);
        Ok::<(), Error>(())
    })?;
    for (what, t) in [
        ("full_update", full),
        ("channel_update", channel),
        ("read_outputs", read),
        ("full_update_read_outputs", full_read),
        ("channel_update_read_outputs", channel_read),
        ("channel_exitance", channel_patch),
        ("patch_update", patch_update),
        ("patch_read_outputs", patch_read),
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
