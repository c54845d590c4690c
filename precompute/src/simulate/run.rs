//! The controller's loop, hour by hour, through the runtime exactly as firmware calls it:
//! `set_sky` on a `DaylightEvaluator`, the photosensor's reading (daylight plus the electric
//! light at the current levels, through its angular response as the basis stores it), each
//! strategy's levels (the model's by the runtime's `LevelProblem`), a `ChannelEvaluator` per
//! strategy, and every reading that follows.

use eigenrad_runtime::sky::cie::CieSky;
use eigenrad_runtime::sky::direct::DirectSun;
use eigenrad_runtime::{dali, Basis, ChannelEvaluator, DaylightEvaluator, LevelProblem, Output};

use super::controller::{Controller, ControllerSky, Strategy};
use super::metrics::GridCounts;
use super::{Hour, HourResult, StrategyTotals, Year};
use crate::accuracy::runtime_eval::{MAX_CHANNELS, MAX_OUTPUTS, MAX_SKY_PATCHES};
use crate::error::{Error, Result};

/// A target counts as met when its zone reads at least `1 − TARGET_TOLERANCE` of it: the
/// level solver meets a bound to 2·10⁻⁶ of its row's scale in `f32`
/// ([`eigenrad_runtime::target::FEASIBILITY`]), and the readings after the levels are set
/// carry `f32` rounding of the same order.
pub const TARGET_TOLERANCE: f64 = 1.0e-4;

type Day<'a> = DaylightEvaluator<'a, MAX_SKY_PATCHES, MAX_OUTPUTS, 0>;
type Channels<'a> = ChannelEvaluator<'a, 1, MAX_CHANNELS>;

/// What the commissioning measured, once, before the year: the night's readings with every
/// channel at 1, and the target zones' daylight per unit of the sensor's under the
/// controller's sky.
struct Commissioning {
    /// The photosensor at night, every channel at 1 (lux): the closed loop's slope.
    night_sensor: f32,
    /// Each target zone at night, every channel at 1 (lux).
    night_zones: Vec<f32>,
    /// The closed loop's set point: `night_sensor / night_zones[0] × target[0]` (lux).
    setpoint: f32,
    /// Each target zone's daylight per unit of the sensor's under the CIE overcast sky.
    overcast_ratio: Vec<f32>,
}

/// The state a strategy carries from hour to hour: its evaluator (the levels it set) and,
/// for the closed loop, the one level it drives.
struct Running<'a> {
    strategy: Strategy,
    electric: Box<Channels<'a>>,
    level: f32,
    totals: StrategyTotals,
}

/// Runs every strategy of `controller` over `hours` on the basis `bytes`, and the daylight
/// metrics of every zone with a grid.
pub fn run(bytes: &[u8], controller: &Controller, hours: &[Hour]) -> Result<Year> {
    let basis = Basis::from_bytes(bytes)?;
    basis.check_daylight()?;
    // The evaluators' buffers are sized for the largest basis: a stack of their own, as the
    // host's other runtime evaluations have.
    std::thread::scope(|s| {
        std::thread::Builder::new()
            .stack_size(64 << 20)
            .spawn_scoped(s, || run_on(basis, controller, hours))
            .map_err(|e| Error::Thread(format!("cannot start: {e}")))?
            .join()
            .unwrap_or_else(|_| Err(Error::Thread("panicked".into())))
    })
}

fn run_on(basis: Basis<'_>, controller: &Controller, hours: &[Hour]) -> Result<Year> {
    let mut day = Box::new(Day::new(basis)?);
    let commissioning = commission(&basis, controller, &mut day)?;
    let channels: Vec<usize> = controller.channels.iter().map(|c| c.index).collect();
    let weights: Vec<f32> = controller
        .channels
        .iter()
        .map(|c| c.full_w as f32)
        .collect();
    let mut problem = LevelProblem::new(&weights)?;
    let mut running = Vec::new();
    for strategy in Strategy::ALL {
        running.push(Running {
            strategy,
            electric: Box::new(Channels::new(basis)?),
            level: 0.0,
            totals: StrategyTotals::new(strategy, controller),
        });
    }
    let direct = DirectSun::new(&basis)?;
    let mut grids = GridCounts::new(&basis, direct.is_some())?;
    let mut out = Vec::with_capacity(hours.len());
    let mut levels = vec![0.0f32; channels.len()];
    for hour in hours {
        day.set_sky(
            &hour.sky.luminance,
            hour.sky.global_horizontal,
            hour.sky.sun,
        )?;
        let mut moment = Moment {
            basis: &basis,
            day: &day,
            controller,
            commissioning: &commissioning,
            channels: &channels,
            problem: &mut problem,
            sensor_daylight: day.sensor_illuminance(controller.sensor.1)?,
        };
        let mut chosen = None;
        for run in running.iter_mut() {
            if hour.occupied {
                moment.decide(run, &mut levels)?;
                for (l, c) in levels.iter_mut().zip(&controller.channels) {
                    *l = applied_level(*l, c.minimum_level as f32, controller)?;
                }
                if run.strategy == Strategy::ClosedLoop {
                    // The loop goes on from the level it set, as the gear applied it.
                    run.level = levels.first().copied().unwrap_or(0.0);
                }
            } else {
                levels.iter_mut().for_each(|l| *l = 0.0);
                run.level = 0.0;
            }
            for (&c, &l) in channels.iter().zip(levels.iter()) {
                run.electric.set_channel_level(c, l)?;
            }
            let result = readings(&basis, &day, &run.electric, controller, &levels, hour)?;
            run.totals.add(controller, hour, &result);
            if run.strategy == controller.strategy {
                chosen = Some(result);
            }
        }
        grids.add(&day, direct.as_ref(), hour)?;
        // Every strategy ran, the controller's among them.
        out.extend(chosen);
    }
    Ok(Year {
        hours: out,
        strategies: running.into_iter().map(|r| r.totals).collect(),
        grids: grids.metrics(),
        commissioning_setpoint_lux: f64::from(commissioning.setpoint),
        overcast_ratio: commissioning
            .overcast_ratio
            .iter()
            .map(|&r| f64::from(r))
            .collect(),
    })
}

/// What every strategy reads in one hour: the basis, the hour's daylight, the
/// commissioning, and the level solver the model's controller fills.
struct Moment<'m, 'a> {
    basis: &'m Basis<'a>,
    day: &'m Day<'a>,
    controller: &'m Controller,
    commissioning: &'m Commissioning,
    channels: &'m [usize],
    problem: &'m mut LevelProblem,
    /// The photosensor's daylight this hour, lux.
    sensor_daylight: f32,
}

impl Moment<'_, '_> {
    /// The levels `run`'s strategy sets this (occupied) hour, before the gear's minimum and
    /// DALI.
    fn decide(&mut self, run: &mut Running<'_>, levels: &mut [f32]) -> Result<()> {
        let targets = &self.controller.targets;
        let c = self.commissioning;
        match run.strategy {
            Strategy::Model => self.model(&run.electric, levels)?,
            Strategy::ClosedLoop => {
                let reading = self
                    .day
                    .sensor_total(self.controller.sensor.1, &*run.electric)?;
                run.level = (run.level + (c.setpoint - reading) / c.night_sensor).clamp(0.0, 1.0);
                levels.fill(run.level);
            }
            Strategy::OpenLoop => {
                let mut level = 0.0f32;
                for ((t, r), w1) in targets.iter().zip(&c.overcast_ratio).zip(&c.night_zones) {
                    let short = t.illuminance as f32 - r * self.sensor_daylight;
                    level = level.max((short / w1).clamp(0.0, 1.0));
                }
                levels.fill(level);
            }
            Strategy::Switching => {
                let short = targets
                    .iter()
                    .zip(&c.overcast_ratio)
                    .any(|(t, r)| r * self.sensor_daylight < t.illuminance as f32);
                levels.fill(if short { 1.0 } else { 0.0 });
            }
            Strategy::FullOutput => levels.fill(1.0),
        }
        Ok(())
    }

    /// The model's controller, as the firmware's harvest loop: its photosensor's reading less
    /// the electric light the basis predicts there is its daylight, carried to each target
    /// zone by the ratio of its sky; then the least-power levels that meet every target.
    fn model(&mut self, electric: &Channels<'_>, levels: &mut [f32]) -> Result<()> {
        let sensor = self.controller.sensor.1;
        let reading = self.day.sensor_total(sensor, electric)?;
        let [own] = electric.sensor_irradiance(sensor)?;
        let estimate = reading - own;
        self.problem.clear_bounds();
        for (t, overcast) in self
            .controller
            .targets
            .iter()
            .zip(&self.commissioning.overcast_ratio)
        {
            let ambient = match self.controller.controller_sky {
                ControllerSky::Overcast => estimate * overcast,
                ControllerSky::Weather => {
                    let zone = self.day.zone_illuminance(t.index)?;
                    if self.sensor_daylight > 0.0 {
                        estimate * (zone / self.sensor_daylight)
                    } else {
                        zone
                    }
                }
            };
            self.problem.add_output_bound(
                self.basis,
                self.channels,
                Output::Zone(t.index),
                ambient.max(0.0),
                t.illuminance as f32,
                f32::INFINITY,
            )?;
        }
        match self.problem.solve(levels) {
            // Short of a target even at full output: the closest levels.
            Ok(_) | Err(eigenrad_runtime::Error::BoundUnmet { .. }) => Ok(()),
            Err(e) => Err(e.into()),
        }
    }
}

/// A strategy's level as the channel's gear applies it: a level between 0 and the channel's
/// minimum is raised to the minimum (0 stays off), then quantised up to a DALI arc power
/// level when the controller speaks DALI.
fn applied_level(level: f32, minimum: f32, controller: &Controller) -> Result<f32> {
    let level = if level <= 0.0 {
        if controller.switch_off {
            return Ok(0.0);
        }
        minimum
    } else {
        level.max(minimum).min(1.0)
    };
    if !controller.dali || level <= 0.0 {
        return Ok(level);
    }
    let arc = dali::level_to_arc_power(level)?;
    Ok(dali::arc_power_to_level(arc)?)
}

/// The commissioning of every strategy: at night with every channel at 1, and under the
/// CIE overcast sky for the ratios.
fn commission(
    basis: &Basis<'_>,
    controller: &Controller,
    day: &mut Day<'_>,
) -> Result<Commissioning> {
    let sensor = controller.sensor.1;
    let mut full = Box::new(Channels::new(*basis)?);
    for c in &controller.channels {
        full.set_channel_level(c.index, 1.0)?;
    }
    let [night_sensor] = full.sensor_irradiance(sensor)?;
    let mut night_zones = Vec::new();
    for t in &controller.targets {
        let [zone] = full.zone_irradiance(t.index)?;
        if zone.is_nan() || zone <= 0.0 {
            return Err(commissioning_error(format!(
                "the channels at full output give zone `{}` no light",
                t.zone
            )));
        }
        night_zones.push(zone);
    }
    if night_sensor.is_nan() || night_sensor <= 0.0 {
        return Err(commissioning_error(format!(
            "the channels at full output give sensor `{}` no light: a closed loop cannot read them",
            controller.sensor.0
        )));
    }
    let setpoint = night_sensor / night_zones[0] * controller.targets[0].illuminance as f32;
    // The overcast sky: CIE standard general sky type 1, whose luminance does not depend
    // on the sun, at 10 000 lux diffuse horizontal (ratios do not depend on the scale).
    let patches = basis
        .sky_patches()
        .ok_or(eigenrad_runtime::Error::NoDaylight)?;
    let mut centres = vec![[0.0f32; 3]; patches.count()];
    patches.centres(&mut centres)?;
    let overcast = CieSky::standard(1, [0.0, 0.0, 1.0])?;
    const DIFFUSE: f32 = 10_000.0;
    let zenith = overcast.zenith_luminance_for(DIFFUSE)?;
    let mut luminance = vec![0.0f32; patches.count()];
    patches.luminances_at(&centres, &overcast, zenith, &mut luminance)?;
    day.set_sky(&luminance, DIFFUSE, None)?;
    let sensor_daylight = day.sensor_illuminance(sensor)?;
    if sensor_daylight.is_nan() || sensor_daylight <= 0.0 {
        return Err(commissioning_error(format!(
            "sensor `{}` sees no daylight under an overcast sky: the model, open-loop and switching controllers estimate daylight from it; choose a sensor that sees the window or the room it lights",
            controller.sensor.0
        )));
    }
    let mut overcast_ratio = Vec::new();
    for t in &controller.targets {
        overcast_ratio.push(day.zone_illuminance(t.index)? / sensor_daylight);
    }
    Ok(Commissioning {
        night_sensor,
        night_zones,
        setpoint,
        overcast_ratio,
    })
}

fn commissioning_error(reason: String) -> Error {
    Error::Daylight {
        what: "commissioning".into(),
        reason,
    }
}

/// Every reading of an hour with the levels a strategy set.
fn readings(
    basis: &Basis<'_>,
    day: &Day<'_>,
    electric: &Channels<'_>,
    controller: &Controller,
    levels: &[f32],
    hour: &Hour,
) -> Result<HourResult> {
    let mut r = HourResult {
        levels: levels.to_vec(),
        power_w: controller
            .channels
            .iter()
            .zip(levels)
            .map(|(c, &l)| c.power(f64::from(l)))
            .collect(),
        ..HourResult::default()
    };
    for s in 0..basis.sensor_count() {
        r.sensor_daylight.push(day.sensor_illuminance(s)?);
        r.sensor_total.push(day.sensor_total(s, electric)?);
    }
    for z in 0..basis.zone_count() {
        r.zone_daylight.push(day.zone_illuminance(z)?);
        r.zone_total.push(day.zone_total(z, electric)?);
    }
    r.met = controller
        .targets
        .iter()
        .map(|t| {
            !hour.occupied
                || f64::from(r.zone_total[t.index]) >= t.illuminance * (1.0 - TARGET_TOLERANCE)
        })
        .collect();
    Ok(r)
}
