//! What a year of the controller gives: the summary (text or JSON), the hourly CSV, and the
//! EnergyPlus `Schedule:File` of the lighting fraction.

use std::fmt::Write as _;

use eigenrad_runtime::Basis;
use serde::Serialize;

use super::controller::Controller;
use super::{GridMetrics, Hour, StrategyTotals, Year};
use crate::error::Result;

/// The weather a year ran on.
#[derive(Clone, Debug, Serialize)]
pub struct WeatherSummary {
    /// The file.
    pub path: String,
    /// `EPW` or `TMY3`.
    pub format: String,
    /// Its location's name.
    pub location: String,
    /// Its latitude (° north) and longitude (° east).
    pub latitude_longitude: [f64; 2],
    /// Its distance from the basis' site, km.
    pub distance_km: f64,
    /// Its records (hours).
    pub records: usize,
    /// Which of its fields drove the sky.
    pub sky_from: String,
}

/// One target's year.
#[derive(Clone, Debug, Serialize)]
pub struct TargetSummary {
    /// The zone.
    pub zone: String,
    /// Maintained illuminance, lux.
    pub illuminance_lux: f64,
    /// Occupied hours whose daylight alone met it.
    pub daylight_alone_hours: usize,
    /// The zone's daylight per unit of the sensor's under the CIE overcast sky (the open
    /// loop's and switching's commissioning; the model's under `controller_sky =
    /// "overcast"`).
    pub overcast_ratio: f64,
}

/// The summary of a year: what `eigenrad simulate` prints.
#[derive(Clone, Debug, Serialize)]
pub struct Summary {
    /// The basis file.
    pub basis: String,
    /// The controller file.
    pub controller: String,
    /// The weather.
    pub weather: WeatherSummary,
    /// The strategy the hourly CSV and the schedule give.
    pub strategy: &'static str,
    /// The photosensor.
    pub sensor: String,
    /// Hours simulated.
    pub hours: usize,
    /// Occupied hours.
    pub occupied_hours: usize,
    /// Floor area, m².
    pub floor_area_m2: f64,
    /// Every channel at full output, W.
    pub installed_power_w: f64,
    /// The closed loop's set point, lux at the sensor.
    pub closed_loop_setpoint_lux: f64,
    /// The targets.
    pub targets: Vec<TargetSummary>,
    /// Every strategy.
    pub strategies: Vec<StrategyTotals>,
    /// Every zone with a grid.
    pub daylight: Vec<GridMetrics>,
    /// Warnings (the weather's distance, its time zone).
    pub warnings: Vec<String>,
}

/// The summary of `year` run by `controller` over `hours`.
pub fn summary(
    basis: &str,
    controller: &Controller,
    weather: WeatherSummary,
    hours: &[Hour],
    year: &Year,
    warnings: Vec<String>,
) -> Summary {
    let occupied = hours.iter().filter(|h| h.occupied).count();
    let targets = controller
        .targets
        .iter()
        .enumerate()
        .map(|(k, t)| TargetSummary {
            zone: t.zone.clone(),
            illuminance_lux: t.illuminance,
            daylight_alone_hours: hours
                .iter()
                .zip(&year.hours)
                .filter(|(h, r)| {
                    h.occupied
                        && f64::from(r.zone_daylight[t.index])
                            >= t.illuminance * (1.0 - super::TARGET_TOLERANCE)
                })
                .count(),
            overcast_ratio: year.overcast_ratio.get(k).copied().unwrap_or(0.0),
        })
        .collect();
    Summary {
        basis: basis.to_owned(),
        controller: controller.path.display().to_string(),
        weather,
        strategy: controller.strategy.name(),
        sensor: controller.sensor.0.clone(),
        hours: hours.len(),
        occupied_hours: occupied,
        floor_area_m2: controller.floor_area_m2,
        installed_power_w: controller.channels.iter().map(|c| c.full_w).sum(),
        closed_loop_setpoint_lux: year.commissioning_setpoint_lux,
        targets,
        strategies: year.strategies.clone(),
        daylight: year.grids.clone(),
        warnings,
    }
}

/// The summary as text.
pub fn format_summary(s: &Summary) -> String {
    let mut t = String::new();
    let w = &s.weather;
    if w.path.is_empty() {
        let _ = writeln!(
            t,
            "skies: {} ({}), {} hours",
            w.sky_from, w.format, w.records
        );
    } else {
        let _ = writeln!(
            t,
            "weather: {} ({}, {}; {:.3}° N {:.3}° E, {:.0} km from the basis' site), {} hours, sky from its {}",
            w.path, w.format, w.location, w.latitude_longitude[0], w.latitude_longitude[1], w.distance_km, w.records, w.sky_from
        );
    }
    let _ = writeln!(
        t,
        "controller: {} on {}: photosensor `{}`, {} occupied hours, floor {:.2} m², installed {:.1} W",
        s.controller, s.basis, s.sensor, s.occupied_hours, s.floor_area_m2, s.installed_power_w
    );
    for target in &s.targets {
        let _ = writeln!(
            t,
            "target {}: {:.0} lux; daylight alone meets it {} of {} occupied hours; zone/sensor daylight under overcast {:.3}",
            target.zone, target.illuminance_lux, target.daylight_alone_hours, s.occupied_hours, target.overcast_ratio
        );
    }
    let _ = writeln!(
        t,
        "closed loop's set point (commissioned at night): {:.1} lux at the sensor",
        s.closed_loop_setpoint_lux
    );
    let _ = writeln!(t);
    let _ = writeln!(
        t,
        "{:<12} {:>10} {:>10} {:>10} {:>12} {:>10} {:>10} {:>9}  hours below target",
        "strategy",
        "light kWh",
        "stby kWh",
        "total kWh",
        // LENI is a year's (EN 15193-1); over another span it is that span's energy per m².
        if s.hours == 8760 || s.hours == 8784 {
            "LENI kWh/m²a"
        } else {
            "kWh/m²"
        },
        "vs full",
        "vs closed",
        "on hours"
    );
    for x in &s.strategies {
        let below: Vec<String> = x
            .hours_below_target
            .iter()
            .zip(&s.targets)
            .map(|(h, t)| format!("{} {h}", t.zone))
            .collect();
        let mark = if x.strategy == s.strategy { "*" } else { " " };
        let _ = writeln!(
            t,
            "{mark}{:<11} {:>10.2} {:>10.2} {:>10.2} {:>12.2} {:>9.1}% {:>9.1}% {:>9}  {}",
            x.strategy,
            x.lighting_kwh,
            x.parasitic_kwh,
            x.total_kwh,
            x.leni_kwh_m2,
            100.0 * x.saving_vs_full_output,
            100.0 * x.saving_vs_closed_loop,
            x.operating_hours,
            below.join(", ")
        );
    }
    let _ = writeln!(t, "(* the strategy of the hourly CSV and the schedule)");
    if !s.daylight.is_empty() {
        let _ = writeln!(t);
        let _ = writeln!(
            t,
            "daylight on the grids, {} hours (08:00-18:00 local standard time, every day; IES LM-83-12):",
            s.daylight[0].hours
        );
        let _ = writeln!(
            t,
            "{:<16} {:>6} {:>8} {:>9} {:>9} {:>7} {:>9} {:>9} {:>7} {:>9}",
            "zone",
            "points",
            "DA300",
            "sDA300/50",
            "ASE1000",
            "UDI<100",
            "100-300",
            "300-3000",
            ">3000",
            "mean lux"
        );
        for g in &s.daylight {
            let ase = g
                .ase_1000_250
                .map_or("n/a".to_owned(), |a| format!("{:.1}%", 100.0 * a));
            let _ = writeln!(
                t,
                "{:<16} {:>6} {:>7.1}% {:>8.1}% {:>9} {:>6.1}% {:>8.1}% {:>8.1}% {:>6.1}% {:>9.0}",
                g.zone,
                g.points,
                100.0 * g.da300_mean,
                100.0 * g.sda_300_50,
                ase,
                100.0 * g.udi[0],
                100.0 * g.udi[1],
                100.0 * g.udi[2],
                100.0 * g.udi[3],
                g.mean_lux
            );
        }
        let _ = writeln!(
            t,
            "(sDA without operable shading, which the basis does not model; ASE from the direct sun alone)"
        );
    }
    for warning in &s.warnings {
        let _ = writeln!(t, "warning: {warning}");
    }
    t
}

/// The hourly CSV of the chosen strategy: per hour its sky, each channel's level and power,
/// each sensor's and zone's daylight and total, each target met.
pub fn hourly_csv(
    basis: &Basis<'_>,
    controller: &Controller,
    hours: &[Hour],
    year: &Year,
) -> Result<String> {
    let mut t = String::new();
    t.push_str("time,hour_ending,occupied,sun_altitude_deg,sun_azimuth_deg,diffuse_horizontal_lux,direct_normal_lux");
    for c in &controller.channels {
        let _ = write!(t, ",level:{}", c.name);
    }
    for c in &controller.channels {
        let _ = write!(t, ",power_w:{}", c.name);
    }
    for s in 0..basis.sensor_count() {
        let name = basis.sensor_name(s)?;
        let _ = write!(t, ",daylight_lux:sensor:{name},total_lux:sensor:{name}");
    }
    for z in 0..basis.zone_count() {
        let name = basis.zone_name(z)?;
        let _ = write!(t, ",daylight_lux:zone:{name},total_lux:zone:{name}");
    }
    for target in &controller.targets {
        let _ = write!(t, ",met:{}", target.zone);
    }
    t.push('\n');
    for (h, r) in hours.iter().zip(&year.hours) {
        let _ = write!(
            t,
            "{},{},{},{:.3},{:.3},{:.1},{:.1}",
            h.time.format("%Y-%m-%dT%H:%M%:z"),
            h.hour_ending,
            u8::from(h.occupied),
            h.sky.altitude_deg,
            h.sky.azimuth_deg,
            h.sky.diffuse_horizontal_lux,
            h.sky.direct_normal_lux
        );
        for l in &r.levels {
            let _ = write!(t, ",{l:.4}");
        }
        for p in &r.power_w {
            let _ = write!(t, ",{p:.3}");
        }
        for (d, s) in r.sensor_daylight.iter().zip(&r.sensor_total) {
            let _ = write!(t, ",{d:.2},{s:.2}");
        }
        for (d, s) in r.zone_daylight.iter().zip(&r.zone_total) {
            let _ = write!(t, ",{d:.2},{s:.2}");
        }
        for &m in &r.met {
            let _ = write!(t, ",{}", u8::from(m));
        }
        t.push('\n');
    }
    Ok(t)
}

/// The lighting fraction of the chosen strategy, hour by hour, for an EnergyPlus
/// `Schedule:File` (one header line to skip, then one value a line, column 1): the power of
/// the lit channels over the installed power. Standby is not in it: an energy model carries
/// parasitic power on its own.
pub fn schedule_csv(controller: &Controller, year: &Year) -> String {
    let installed: f64 = controller.channels.iter().map(|c| c.full_w).sum();
    let mut t = format!(
        "eigenrad lighting fraction ({} controller)\n",
        controller.strategy.name()
    );
    for r in &year.hours {
        let lit: f64 = r
            .levels
            .iter()
            .zip(&r.power_w)
            .filter(|(&l, _)| l > 0.0)
            .map(|(_, &p)| p)
            .sum();
        let fraction = if installed > 0.0 {
            lit / installed
        } else {
            0.0
        };
        let _ = writeln!(t, "{fraction:.4}");
    }
    t
}
