//! The firmware as a controller: daylight harvesting to a work-plane target, on a one-band
//! (photopic) basis.
//!
//! Every channel except one named `window` is a luminaire the controller dims. At each step
//! of [`DAYLIGHT_AT_SENSOR`] the loop
//!
//! 1. reads a simulated photosensor: the electric light the basis predicts at the sensor for
//!    the levels the luminaires are at, plus that step's daylight (lux);
//! 2. estimates the daylight at the sensor as its reading minus the predicted electric light;
//! 3. converts it to the work plane with the commissioning ratio [`DAYLIGHT_RATIO`]: the basis
//!    has no daylight model of its own (the office's `window` channel is a fixed exitance,
//!    not the sky), so, as in a commissioned installation, the ratio of work-plane daylight to
//!    sensor daylight is measured once with the luminaires off and stored;
//! 4. solves the least-power levels that give the work plane at least [`TARGET`] lux with
//!    that daylight ([`LevelProblem`], power weights [`WATTS`]);
//! 5. rounds them up to DALI arc power levels ([`dali::level_to_arc_power`]), which is what
//!    it sends the control gear and what the luminaires are at for the next reading.
//!
//! Output, after the records of `main.rs`:
//!
//! ```text
//! control channels <c0> <c1> ...                       basis indices of the dimmed channels
//! control weights <w0> <w1> ...                        W at level 1, per dimmed channel
//! control setup sensor <s> zone <z> ratio <r> target <lux> size_of <bytes>
//! control step <k> daylight <lux> reading <lux> estimate <lux> ambient <lux> levels <l...> arc <a...> power <W> met
//! control step <k> ... power <W> unmet <bound> <lux short or over>
//! instructions solve_levels <per call>                 see `measure`
//! ```
//!
//! The photosensor is the sensor named `ceiling`, else sensor 0; the work plane the zone named
//! `work_plane`, else zone 0. A basis without a sensor, a zone or a dimmed channel, or with
//! three bands, prints no `control` records.

use core::hint::black_box;

use cortex_m_semihosting::hprintln;
use eigenrad_runtime::target::output_gains;
use eigenrad_runtime::{dali, Basis, ChannelEvaluator, Error, LevelProblem, Output};

use crate::timing::{Calibration, Ticks};
use crate::{Fail, Line, CHANNELS};

/// The work-plane illuminance the controller keeps, lux (EN 12464-1's figure for offices).
pub const TARGET: f32 = 500.0;
/// Daylight at the photosensor at each step, lux: night, then a brightening sky.
pub const DAYLIGHT_AT_SENSOR: [f32; 6] = [0.0, 25.0, 60.0, 120.0, 200.0, 400.0];
/// Commissioning ratio: work-plane daylight per lux of daylight at the photosensor (the
/// office's ceiling photocell looks down at the desks and floor, which reflect 20–40 %).
pub const DAYLIGHT_RATIO: f32 = 4.0;
/// Power of each dimmed channel at level 1, W, in the order of the basis' channels: four
/// luminaires of decreasing age and draw.
pub const WATTS: [f32; CHANNELS] = [36.0, 32.0, 28.0, 24.0, 20.0, 16.0, 12.0, 8.0];
/// Name of the channel that is daylight, not a luminaire.
const WINDOW: &str = "window";
/// Upper bound on every sensor in the timed problem, lux (a glare limit).
const SENSOR_MAX: f32 = 2000.0;
/// Repetitions of the timed solve.
const REPS: u32 = 100;

/// What the controller works on.
pub struct Plant {
    /// Basis indices of the dimmed channels: the first `count`.
    channels: [usize; CHANNELS],
    count: usize,
    /// The photosensor: the sensor named `ceiling`, else sensor 0.
    pub sensor: usize,
    /// The work plane: the zone named `work_plane`, else zone 0.
    pub zone: usize,
}

impl Plant {
    /// Basis indices of the dimmed channels: every channel but the one named `window`.
    pub fn dimmed(&self) -> &[usize] {
        self.channels.get(..self.count).unwrap_or(&[])
    }
}

/// The plant of a one-band basis with a sensor, a zone and a dimmed channel.
pub fn plant(basis: &Basis<'_>) -> Option<Plant> {
    if basis.bands() != 1 || basis.sensor_count() == 0 || basis.zone_count() == 0 {
        return None;
    }
    let mut plant = Plant {
        channels: [0; CHANNELS],
        count: 0,
        sensor: basis.find_sensor("ceiling").unwrap_or(0),
        zone: basis.find_zone("work_plane").unwrap_or(0),
    };
    for c in 0..basis.channel_count() {
        if basis.channel_name(c).ok()? != WINDOW {
            *plant.channels.get_mut(plant.count)? = c;
            plant.count += 1;
        }
    }
    (plant.count > 0).then_some(plant)
}

/// Runs the controller loop and times the solver; nothing for a basis it does not apply to.
pub fn run<const C: usize>(
    lights: &mut ChannelEvaluator<'_, 1, C>,
    ticks: &mut Ticks,
    calibration: Calibration,
) -> Result<(), Fail> {
    let basis = *lights.basis();
    let Some(plant) = plant(&basis) else {
        return Ok(());
    };
    let dimmed = plant.dimmed();
    let weights = WATTS
        .get(..dimmed.len())
        .ok_or(Fail::Board("too many channels"))?;
    let mut problem = LevelProblem::new(weights)?;
    hprintln!("control channels{}", Indices(dimmed));
    hprintln!("control weights{}", Line::of(weights));
    hprintln!(
        "control setup sensor {} zone {} ratio {:e} target {:e} size_of {}",
        plant.sensor,
        plant.zone,
        DAYLIGHT_RATIO,
        TARGET,
        core::mem::size_of_val(&problem)
    );

    // Every luminaire at full, the window channel off: its daylight is the sequence's.
    for c in 0..basis.channel_count() {
        let on = dimmed.contains(&c);
        lights.set_channel_level(c, if on { 1.0 } else { 0.0 })?;
    }
    let mut levels = [0.0f32; CHANNELS];
    let levels = levels.get_mut(..dimmed.len()).unwrap_or(&mut []);
    for (k, &daylight) in DAYLIGHT_AT_SENSOR.iter().enumerate() {
        let [predicted] = lights.sensor_irradiance(plant.sensor)?;
        let reading = predicted + daylight;
        let estimate = reading - predicted;
        let ambient = DAYLIGHT_RATIO * estimate;
        problem.clear_bounds();
        problem.add_output_bound(
            &basis,
            dimmed,
            Output::Zone(plant.zone),
            ambient,
            TARGET,
            f32::INFINITY,
        )?;
        let status = match problem.solve(levels) {
            Ok(_) => Status::Met,
            Err(Error::BoundUnmet { bound, by, .. }) => Status::Unmet(bound, by),
            Err(e) => return Err(e.into()),
        };
        let mut arcs = [0u8; CHANNELS];
        for ((arc, &level), &c) in arcs.iter_mut().zip(levels.iter()).zip(dimmed) {
            *arc = dali::level_to_arc_power(level)?;
            lights.set_channel_arc_power(c, *arc)?;
        }
        let power = problem.power(levels)?;
        hprintln!(
            "control step {} daylight {:e} reading {:e} estimate {:e} ambient {:e} levels{} arc{} power {:e} {}",
            k,
            daylight,
            reading,
            estimate,
            ambient,
            Line::of(levels),
            Arcs(arcs.get(..dimmed.len()).unwrap_or(&[])),
            power,
            status
        );
    }
    measure(lights, &plant, &mut problem, ticks, calibration)
}

/// Instructions per [`LevelProblem::solve`] for every zone at least [`TARGET`] lux and every
/// sensor at most [`SENSOR_MAX`] lux, the window channel at 0.5 and the luminaires at 0.3
/// giving the ambient ([`ChannelEvaluator::reading_without`]), the problem built once.
fn measure<const C: usize>(
    lights: &mut ChannelEvaluator<'_, 1, C>,
    plant: &Plant,
    problem: &mut LevelProblem,
    ticks: &mut Ticks,
    calibration: Calibration,
) -> Result<(), Fail> {
    let basis = *lights.basis();
    let dimmed = plant.dimmed();
    for c in 0..basis.channel_count() {
        lights.set_channel_level(c, if dimmed.contains(&c) { 0.3 } else { 0.5 })?;
    }
    problem.clear_bounds();
    let mut gains = [0.0f32; CHANNELS];
    let gains = gains.get_mut(..dimmed.len()).unwrap_or(&mut []);
    let outputs = (0..basis.zone_count())
        .map(|z| (Output::Zone(z), TARGET, f32::INFINITY))
        .chain((0..basis.sensor_count()).map(|s| (Output::Sensor(s), 0.0, SENSOR_MAX)));
    for (output, lower, upper) in outputs {
        output_gains(&basis, output, dimmed, gains)?;
        let ambient = lights.reading_without(output, dimmed)?;
        if problem.bound_count() < eigenrad_runtime::target::MAX_BOUNDS {
            problem.add_bound(gains, ambient, lower, upper)?;
        }
    }
    let mut levels = [0.0f32; CHANNELS];
    let levels = levels.get_mut(..dimmed.len()).unwrap_or(&mut []);
    let baseline = ticks.count(REPS, |i| {
        black_box(i);
        Ok::<(), Error>(())
    })?;
    let t = ticks.count(REPS, |_| match black_box(&*problem).solve(levels) {
        Ok(s) => {
            black_box(s);
            Ok(())
        }
        Err(Error::BoundUnmet { .. }) => Ok(()),
        Err(e) => Err(e),
    })?;
    hprintln!(
        "timing solve_levels reps {} ticks {} baseline_ticks {}",
        REPS,
        t,
        baseline
    );
    let per_call = calibration.instructions_for(t.saturating_sub(baseline)) / u64::from(REPS);
    hprintln!("instructions solve_levels {}", per_call);
    Ok(())
}

/// Whether the levels met the target.
enum Status {
    Met,
    /// Bound index and by how much it is missed, lux.
    Unmet(usize, f32),
}

impl core::fmt::Display for Status {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            Status::Met => f.write_str("met"),
            Status::Unmet(bound, by) => write!(f, "unmet {bound} {by:e}"),
        }
    }
}

/// Channel indices, printed as ` <c>` each.
struct Indices<'a>(&'a [usize]);

impl core::fmt::Display for Indices<'_> {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        for c in self.0 {
            write!(f, " {c}")?;
        }
        Ok(())
    }
}

/// DALI arc levels, printed as ` <a>` each.
struct Arcs<'a>(&'a [u8]);

impl core::fmt::Display for Arcs<'_> {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        for a in self.0 {
            write!(f, " {a}")?;
        }
        Ok(())
    }
}
