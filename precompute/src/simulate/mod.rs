//! The controller's year (`eigenrad simulate`): a lighting controller's loop run on the host
//! for every hour of a weather year, through the runtime exactly as its firmware calls it,
//! with the energy it uses, how often it meets its targets and the daylight metrics of the
//! room's grids.
//!
//! The parts, each using only the ones before it:
//!
//! | file | what |
//! |---|---|
//! | `controller.rs` | the controller file: photosensor, targets, channels' power, occupancy |
//! | `sky.rs` | a weather file's records as the hours of the year: the sun and the sky of each |
//! | `metrics.rs` | daylight autonomy, sDA, ASE and UDI on the grids |
//! | `run.rs` | the loop: every strategy hour by hour through the runtime |
//! | `report.rs` | the summary (energy, LENI, savings, hours below target), the hourly CSV, the schedule |
//!
//! Every strategy runs in the same pass ([`Strategy::ALL`]), so the summary compares them
//! on the same hours; the controller file's `strategy` is the one the hourly CSV and the
//! schedule give.

mod controller;
mod metrics;
mod report;
mod run;
mod sky;

use chrono::{DateTime, FixedOffset};
use serde::Serialize;

pub use controller::{
    load as load_controller, parse as parse_controller, ChannelPower, Controller, ControllerSky,
    Occupancy, Strategy, Target, DEFAULT_HOURS, DEFAULT_MINIMUM_LEVEL, DEFAULT_STANDBY_W,
};
pub use metrics::{GridMetrics, ASE_HOURS, ASE_LUX, DA_LUX, SDA_SHARE, UDI_LIMITS};
pub use report::{format_summary, hourly_csv, schedule_csv, summary, Summary, WeatherSummary};
pub use run::{run, TARGET_TOLERANCE};
pub use sky::{hours, recipe_hours, HourOptions, Recipe, SkySource, WATER_DEFAULT_CM};

/// The sky of one hour as the runtime's `DaylightEvaluator::set_sky` takes it, with what
/// the reports show of it.
#[derive(Clone, Debug, Default)]
pub struct HourSky {
    /// Every sky patch's luminance, cd/m², in the basis' order (all 0 at night).
    pub luminance: Vec<f32>,
    /// Global horizontal illuminance, lux.
    pub global_horizontal: f32,
    /// The sun, when it is above the horizon and shines.
    pub sun: Option<eigenrad_runtime::Sun>,
    /// The sun's apparent altitude, degrees (negative below the horizon).
    pub altitude_deg: f64,
    /// The sun's azimuth, degrees clockwise from true north.
    pub azimuth_deg: f64,
    /// Diffuse horizontal illuminance, lux.
    pub diffuse_horizontal_lux: f64,
    /// Direct normal illuminance, lux.
    pub direct_normal_lux: f64,
}

/// One hour of the year: its time, whether it is occupied or an analysis hour, its sky.
#[derive(Clone, Debug)]
pub struct Hour {
    /// The middle of the hour, local standard time of the weather file: the instant its sky
    /// is computed at.
    pub time: DateTime<FixedOffset>,
    /// The weather record's line.
    pub line: usize,
    /// The record's hour, 1 to 24 (hour-ending).
    pub hour_ending: u32,
    /// Day of the week, 0 Monday.
    pub weekday: usize,
    /// The room is occupied: the controller lights it.
    pub occupied: bool,
    /// An analysis hour of the daylight metrics (08:00–18:00 local standard time, IES
    /// LM-83-12).
    pub analysis: bool,
    /// The sky.
    pub sky: HourSky,
}

/// What one strategy did in one hour.
#[derive(Clone, Debug, Default)]
pub struct HourResult {
    /// Each channel's level, as applied (after the minimum and DALI).
    pub levels: Vec<f32>,
    /// Each channel's power, W (standby when off).
    pub power_w: Vec<f64>,
    /// Each sensor's daylight, lux.
    pub sensor_daylight: Vec<f32>,
    /// Each sensor's daylight and electric light, lux.
    pub sensor_total: Vec<f32>,
    /// Each zone's daylight, lux.
    pub zone_daylight: Vec<f32>,
    /// Each zone's daylight and electric light, lux.
    pub zone_total: Vec<f32>,
    /// Each target met (unoccupied hours count as met).
    pub met: Vec<bool>,
}

/// One strategy's year.
#[derive(Clone, Debug, Serialize)]
pub struct StrategyTotals {
    /// The strategy.
    pub strategy: &'static str,
    /// Energy of the lit channels, kWh (EN 15193-1's W_L).
    pub lighting_kwh: f64,
    /// Standby energy of the channels that are off, kWh (the controls' share of EN
    /// 15193-1's parasitic energy W_P).
    pub parasitic_kwh: f64,
    /// `lighting_kwh + parasitic_kwh`.
    pub total_kwh: f64,
    /// LENI = total / floor area, kWh/(m²·a) (EN 15193-1; a year of records).
    pub leni_kwh_m2: f64,
    /// Saving against full output while occupied, share of its total energy.
    pub saving_vs_full_output: f64,
    /// Saving against the conventional closed loop, share of its total energy.
    pub saving_vs_closed_loop: f64,
    /// Hours with some channel on.
    pub operating_hours: usize,
    /// Per target, occupied hours its zone read less than the target.
    pub hours_below_target: Vec<usize>,
}

impl StrategyTotals {
    fn new(strategy: Strategy, controller: &Controller) -> Self {
        StrategyTotals {
            strategy: strategy.name(),
            lighting_kwh: 0.0,
            parasitic_kwh: 0.0,
            total_kwh: 0.0,
            leni_kwh_m2: 0.0,
            saving_vs_full_output: 0.0,
            saving_vs_closed_loop: 0.0,
            operating_hours: 0,
            hours_below_target: vec![0; controller.targets.len()],
        }
    }

    /// Adds one hour (1 h at the hour's power).
    fn add(&mut self, controller: &Controller, hour: &Hour, r: &HourResult) {
        let mut on = false;
        for (&level, &p) in r.levels.iter().zip(&r.power_w) {
            if level > 0.0 {
                self.lighting_kwh += p / 1000.0;
                on = true;
            } else {
                self.parasitic_kwh += p / 1000.0;
            }
        }
        self.total_kwh = self.lighting_kwh + self.parasitic_kwh;
        self.leni_kwh_m2 = self.total_kwh / controller.floor_area_m2;
        self.operating_hours += usize::from(on);
        if hour.occupied {
            for (below, &met) in self.hours_below_target.iter_mut().zip(&r.met) {
                *below += usize::from(!met);
            }
        }
    }
}

/// A year of the controller: the chosen strategy's hours, every strategy's totals, the
/// grids' daylight metrics.
#[derive(Clone, Debug)]
pub struct Year {
    /// The chosen strategy, hour by hour.
    pub hours: Vec<HourResult>,
    /// Every strategy's totals, in the order of [`Strategy::ALL`].
    pub strategies: Vec<StrategyTotals>,
    /// Every zone with a grid.
    pub grids: Vec<GridMetrics>,
    /// The closed loop's set point commissioned at night, lux at the sensor.
    pub commissioning_setpoint_lux: f64,
    /// Per target, its zone's daylight per unit of the sensor's under the CIE overcast sky.
    pub overcast_ratio: Vec<f64>,
}

impl Year {
    /// Fills each strategy's savings against full output and the closed loop.
    fn with_savings(mut self) -> Self {
        let total = |s: Strategy| {
            self.strategies
                .iter()
                .find(|t| t.strategy == s.name())
                .map_or(0.0, |t| t.total_kwh)
        };
        let (full, closed) = (total(Strategy::FullOutput), total(Strategy::ClosedLoop));
        let saving = |reference: f64, own: f64| {
            if reference > 0.0 {
                1.0 - own / reference
            } else {
                0.0
            }
        };
        for t in &mut self.strategies {
            t.saving_vs_full_output = saving(full, t.total_kwh);
            t.saving_vs_closed_loop = saving(closed, t.total_kwh);
        }
        self
    }
}

/// Runs `controller` on the basis `bytes` over `hours` ([`run`]) and fills the savings.
pub fn simulate(bytes: &[u8], controller: &Controller, hours: &[Hour]) -> crate::Result<Year> {
    Ok(run(bytes, controller, hours)?.with_savings())
}
