//! The controller file: what a lighting controller holds besides its basis — its photosensor,
//! its targets, each channel's power, its dimming range, its occupancy — read from TOML and
//! checked against the basis, every error naming the file, the line and the field.

use std::path::{Path, PathBuf};

use eigenrad_runtime::Basis;
use serde::Deserialize;
use toml::Spanned;

use crate::error::{Error, Result};

/// The most channels a controller drives: the runtime's level solver's capacity.
pub const MAX_CONTROLLED: usize = eigenrad_runtime::target::MAX_CONTROLS;

/// A controller file's error: [`Error::Controller`] naming the file, the line when known,
/// the field and why.
fn error(path: &Path, line: Option<usize>, field: &str, reason: String) -> Error {
    Error::Controller {
        path: path.to_path_buf(),
        line,
        field: field.to_owned(),
        reason,
    }
}

/// How the controller sets its channels' levels, hour by hour.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Deserialize, serde::Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Strategy {
    /// The model's controller: its photosensor's daylight (the reading less the electric
    /// light the basis predicts there) carried to each target zone by the zone-to-sensor
    /// ratio of the controller's sky, then the least-power levels that meet every target
    /// (the runtime's `LevelProblem`), as the firmware's harvest loop.
    Model,
    /// The conventional closed loop: every channel at one level, driven so that the
    /// photosensor (daylight and electric light) reads the set point commissioned at night.
    ClosedLoop,
    /// Open-loop daylight-linked dimming: the photosensor sees daylight only; every channel
    /// at one level that makes up the target zone's shortfall by the commissioned ratio.
    OpenLoop,
    /// On/off switching: every channel on while the estimated daylight on a target zone is
    /// short of its target, off otherwise.
    Switching,
    /// No control: every channel at full output while occupied (the reference).
    FullOutput,
}

impl Strategy {
    /// Every strategy, in the order the summary lists them.
    pub const ALL: [Strategy; 5] = [
        Strategy::Model,
        Strategy::ClosedLoop,
        Strategy::OpenLoop,
        Strategy::Switching,
        Strategy::FullOutput,
    ];

    /// The name the controller file and the reports use.
    pub fn name(self) -> &'static str {
        match self {
            Strategy::Model => "model",
            Strategy::ClosedLoop => "closed-loop",
            Strategy::OpenLoop => "open-loop",
            Strategy::Switching => "switching",
            Strategy::FullOutput => "full-output",
        }
    }
}

/// The sky the model's controller assumes when it carries its sensor's daylight to the
/// target zones (it knows its clock and its site, not the weather).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Deserialize, serde::Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum ControllerSky {
    /// The CIE standard general sky type 1 (overcast, CIE S 011/E:2003), as the firmware's
    /// harvest loop computes it: its shape does not depend on the sun, so the ratio is one
    /// number per target for the whole year.
    Overcast,
    /// The sky of the weather file, hour by hour: a controller with a sky scanner or a
    /// weather feed (an upper bound of what the model's controller can do).
    Weather,
}

/// The controller file as written.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct File {
    sensor: Spanned<String>,
    #[serde(default = "default_strategy")]
    strategy: Strategy,
    floor_area: Spanned<f64>,
    #[serde(default = "default_true")]
    dali: bool,
    #[serde(default = "default_true")]
    switch_off: bool,
    #[serde(default = "default_sky")]
    controller_sky: ControllerSky,
    #[serde(default)]
    target: Vec<TargetFile>,
    #[serde(default)]
    channel: Vec<ChannelFile>,
    #[serde(default)]
    occupancy: Option<OccupancyFile>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct TargetFile {
    zone: Spanned<String>,
    illuminance: Spanned<f64>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct ChannelFile {
    name: Spanned<String>,
    power: Spanned<f64>,
    standby: Option<Spanned<f64>>,
    minimum_level: Option<Spanned<f64>>,
    power_at_minimum: Option<Spanned<f64>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct OccupancyFile {
    days: Option<Spanned<String>>,
    hours: Option<Spanned<[u32; 2]>>,
}

fn default_strategy() -> Strategy {
    Strategy::Model
}
fn default_true() -> bool {
    true
}
fn default_sky() -> ControllerSky {
    ControllerSky::Overcast
}

/// Standby power of a channel's control gear when it is off, W: the most that Commission
/// Regulation (EU) 2019/2020 (ecodesign of light sources and separate control gears,
/// Annex II) allows a separate control gear in networked standby.
pub const DEFAULT_STANDBY_W: f64 = 0.5;
/// The lowest level a channel dims to, relative: 1 %, a common LED driver's lowest
/// (DALI's own lowest, arc 1, is 0.1 %).
pub const DEFAULT_MINIMUM_LEVEL: f64 = 0.01;
/// Occupancy by default: Monday to Friday.
pub const DEFAULT_DAYS: &str = "mon-fri";
/// Occupancy by default: 08:00 to 18:00 local standard time (the hours IES LM-83 takes
/// for its daylight metrics).
pub const DEFAULT_HOURS: [u32; 2] = [8, 18];

/// A target: a zone's maintained illuminance.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct Target {
    /// The zone's name.
    pub zone: String,
    /// Its index in the basis.
    pub index: usize,
    /// Maintained illuminance, lux.
    pub illuminance: f64,
}

/// One channel's power: at full output, in standby, and against its level.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct ChannelPower {
    /// The channel's name.
    pub name: String,
    /// Its index in the basis.
    pub index: usize,
    /// Power at level 1, W.
    pub full_w: f64,
    /// Power when off (level 0), W: the control gear's standby.
    pub standby_w: f64,
    /// The lowest level it dims to, relative (0 to 1).
    pub minimum_level: f64,
    /// Its power at that level above standby, as a fraction of `full_w − standby_w`: the
    /// power is linear in the level from (`minimum_level`, `power_at_minimum`) to (1, 1).
    pub power_at_minimum: f64,
}

impl ChannelPower {
    /// Power at `level` (0 to 1), W: standby when off; when on, the gear's standby and a
    /// share of the rest on the linear curve, so that a channel on at its minimum never
    /// draws less than one off: `P_sb + (P_full − P_sb)·f(level)`.
    pub fn power(&self, level: f64) -> f64 {
        if level <= 0.0 {
            return self.standby_w;
        }
        let span = 1.0 - self.minimum_level;
        let fraction = if span > 0.0 {
            self.power_at_minimum
                + (1.0 - self.power_at_minimum)
                    * (level.max(self.minimum_level) - self.minimum_level)
                    / span
        } else {
            1.0
        };
        self.standby_w + (self.full_w - self.standby_w).max(0.0) * fraction
    }
}

/// Which hours the room is occupied: days of the week and a span of local standard time.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct Occupancy {
    /// Days of the week, Monday first.
    pub days: [bool; 7],
    /// Occupied from this hour (local standard time, 0 to 23) ...
    pub from_hour: u32,
    /// ... to this one (1 to 24): a record whose hour lies within counts as occupied.
    pub to_hour: u32,
    /// The days as written (`mon-fri`).
    pub days_text: String,
}

impl Occupancy {
    /// Whether the hour from `hour − 1` to `hour` (hour-ending, 1 to 24) of a day with week
    /// day `weekday` (0 Monday) is occupied.
    pub fn occupied(&self, weekday: usize, hour: u32) -> bool {
        self.days.get(weekday).copied().unwrap_or(false)
            && hour > self.from_hour
            && hour <= self.to_hour
    }
}

/// A controller: its basis' sensor, targets and channels, its strategy and occupancy.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct Controller {
    /// The controller file.
    pub path: PathBuf,
    /// The photosensor's name and index in the basis.
    pub sensor: (String, usize),
    /// The strategy whose hours the hourly CSV and the schedule give.
    pub strategy: Strategy,
    /// Floor area, m² (LENI's denominator, EN 15193-1).
    pub floor_area_m2: f64,
    /// Levels quantised to DALI arc power levels, rounded up (IEC 62386-102).
    pub dali: bool,
    /// A channel no strategy needs is switched off (its standby counts); otherwise it stays
    /// at its minimum level while the room is occupied.
    pub switch_off: bool,
    /// The sky the model's controller assumes.
    pub controller_sky: ControllerSky,
    /// The targets, at least one.
    pub targets: Vec<Target>,
    /// Every channel of the basis, in the basis' order.
    pub channels: Vec<ChannelPower>,
    /// When the room is occupied.
    pub occupancy: Occupancy,
}

/// 1-based line of byte `offset` in `text`.
fn line_of(text: &str, offset: usize) -> usize {
    let end = offset.min(text.len());
    text.as_bytes()[..end]
        .iter()
        .filter(|&&b| b == b'\n')
        .count()
        + 1
}

/// The controller file at `path`, checked against `basis`.
pub fn load(path: &Path, basis: &Basis<'_>) -> Result<Controller> {
    let text = std::fs::read_to_string(path).map_err(|reason| Error::Io {
        path: path.to_path_buf(),
        reason,
    })?;
    parse(path, &text, basis)
}

/// The controller file `text` (read from `path`), checked against `basis`.
pub fn parse(path: &Path, text: &str, basis: &Basis<'_>) -> Result<Controller> {
    let err = |span: Option<std::ops::Range<usize>>, field: &str, reason: String| {
        error(path, span.map(|s| line_of(text, s.start)), field, reason)
    };
    let file: File =
        toml::from_str(text).map_err(|e| err(e.span(), "TOML", e.message().to_owned()))?;
    let sensor_name = file.sensor.get_ref().clone();
    let sensor = basis.find_sensor(&sensor_name).ok_or_else(|| {
        err(
            Some(file.sensor.span()),
            "sensor",
            format!(
                "the basis has no sensor `{sensor_name}` (it has: {})",
                names(basis.sensor_count(), |i| basis.sensor_name(i))
            ),
        )
    })?;
    let area = *file.floor_area.get_ref();
    if !(area.is_finite() && area > 0.0 && area <= 1.0e6) {
        return Err(err(
            Some(file.floor_area.span()),
            "floor_area",
            format!("{area} m² is not an area from 0 to 10⁶ m²"),
        ));
    }
    if file.target.is_empty() {
        return Err(err(
            None,
            "target",
            "no [[target]]: give at least one zone and its maintained illuminance (lux)".into(),
        ));
    }
    let mut targets: Vec<Target> = Vec::new();
    for t in &file.target {
        let zone = t.zone.get_ref().clone();
        let index = basis.find_zone(&zone).ok_or_else(|| {
            err(
                Some(t.zone.span()),
                "target.zone",
                format!(
                    "the basis has no zone `{zone}` (it has: {})",
                    names(basis.zone_count(), |i| basis.zone_name(i))
                ),
            )
        })?;
        if targets.iter().any(|o| o.index == index) {
            return Err(err(
                Some(t.zone.span()),
                "target.zone",
                format!("zone `{zone}` has two targets"),
            ));
        }
        let lux = *t.illuminance.get_ref();
        if !(lux.is_finite() && lux > 0.0 && lux <= 1.0e5) {
            return Err(err(
                Some(t.illuminance.span()),
                "target.illuminance",
                format!("{lux} lux is not an illuminance from 0 to 100 000 lux"),
            ));
        }
        targets.push(Target {
            zone,
            index,
            illuminance: lux,
        });
    }
    if targets.len() > eigenrad_runtime::target::MAX_BOUNDS {
        return Err(err(
            None,
            "target",
            format!(
                "{} targets: the controller's level solver holds at most {}",
                targets.len(),
                eigenrad_runtime::target::MAX_BOUNDS
            ),
        ));
    }
    let channels = channels(&file, basis, &err)?;
    let occupancy = occupancy(file.occupancy.as_ref(), &err)?;
    Ok(Controller {
        path: path.to_path_buf(),
        sensor: (sensor_name, sensor),
        strategy: file.strategy,
        floor_area_m2: area,
        dali: file.dali,
        switch_off: file.switch_off,
        controller_sky: file.controller_sky,
        targets,
        channels,
        occupancy,
    })
}

type ErrFn<'e> = dyn Fn(Option<std::ops::Range<usize>>, &str, String) -> Error + 'e;

/// Every channel of the basis with its power, in the basis' order; each must be listed once.
fn channels(file: &File, basis: &Basis<'_>, err: &ErrFn<'_>) -> Result<Vec<ChannelPower>> {
    let m = basis.channel_count();
    if m > MAX_CONTROLLED {
        return Err(err(
            None,
            "channel",
            format!("the basis has {m} channels: a controller drives at most {MAX_CONTROLLED}"),
        ));
    }
    let mut slots: Vec<Option<ChannelPower>> = vec![None; m];
    for c in &file.channel {
        let name = c.name.get_ref().clone();
        let index = basis.find_channel(&name).ok_or_else(|| {
            err(
                Some(c.name.span()),
                "channel.name",
                format!(
                    "the basis has no channel `{name}` (it has: {})",
                    names(m, |i| basis.channel_name(i))
                ),
            )
        })?;
        if slots[index].is_some() {
            return Err(err(
                Some(c.name.span()),
                "channel.name",
                format!("channel `{name}` is listed twice"),
            ));
        }
        let value = |v: &Spanned<f64>, field: &str, lo: f64, hi: f64, unit: &str| {
            let x = *v.get_ref();
            if x.is_finite() && (lo..=hi).contains(&x) {
                Ok(x)
            } else {
                Err(err(
                    Some(v.span()),
                    field,
                    format!("{x}{unit} is outside {lo}{unit} to {hi}{unit}"),
                ))
            }
        };
        let full_w = value(&c.power, "channel.power", 0.0, 1.0e5, " W")?;
        let standby_w = match &c.standby {
            Some(v) => value(v, "channel.standby", 0.0, 1.0e4, " W")?,
            None => DEFAULT_STANDBY_W,
        };
        let minimum_level = match &c.minimum_level {
            Some(v) => value(v, "channel.minimum_level", 0.0, 1.0, "")?,
            None => DEFAULT_MINIMUM_LEVEL,
        };
        let power_at_minimum = match &c.power_at_minimum {
            Some(v) => value(v, "channel.power_at_minimum", 0.0, 1.0, "")?,
            None => minimum_level,
        };
        slots[index] = Some(ChannelPower {
            name,
            index,
            full_w,
            standby_w,
            minimum_level,
            power_at_minimum,
        });
    }
    let mut out = Vec::with_capacity(m);
    for (index, slot) in slots.into_iter().enumerate() {
        match slot {
            Some(c) => out.push(c),
            None => {
                let name = basis.channel_name(index).unwrap_or("?");
                return Err(err(
                    None,
                    "channel",
                    format!(
                        "the basis' channel `{name}` is not listed: give it a [[channel]] with its power at full output (W)"
                    ),
                ));
            }
        }
    }
    Ok(out)
}

/// The occupancy of the file, or the default (Monday to Friday, 08:00 to 18:00).
fn occupancy(file: Option<&OccupancyFile>, err: &ErrFn<'_>) -> Result<Occupancy> {
    let (days_text, days_span) = match file.and_then(|f| f.days.as_ref()) {
        Some(d) => (d.get_ref().trim().to_lowercase(), Some(d.span())),
        None => (DEFAULT_DAYS.to_owned(), None),
    };
    let days = parse_days(&days_text).map_err(|reason| err(days_span, "occupancy.days", reason))?;
    let [from_hour, to_hour] = match file.and_then(|f| f.hours.as_ref()) {
        Some(h) => {
            let [a, b] = *h.get_ref();
            if !(a < b && b <= 24) {
                return Err(err(
                    Some(h.span()),
                    "occupancy.hours",
                    format!("[{a}, {b}] is not a span of hours from 0 to 24, first before last"),
                ));
            }
            [a, b]
        }
        None => DEFAULT_HOURS,
    };
    Ok(Occupancy {
        days,
        from_hour,
        to_hour,
        days_text,
    })
}

const DAY_NAMES: [&str; 7] = ["mon", "tue", "wed", "thu", "fri", "sat", "sun"];

/// `mon-fri`, `mon,wed,fri`, `sat-sun`, `all`: days of the week, Monday first.
fn parse_days(text: &str) -> std::result::Result<[bool; 7], String> {
    let day = |s: &str| {
        DAY_NAMES
            .iter()
            .position(|d| *d == s.trim())
            .ok_or_else(|| {
                format!("`{s}` is not a day: mon, tue, wed, thu, fri, sat, sun (or `all`)")
            })
    };
    let mut days = [false; 7];
    if text == "all" {
        return Ok([true; 7]);
    }
    for part in text.split(',') {
        match part.split_once('-') {
            Some((a, b)) => {
                let (a, b) = (day(a)?, day(b)?);
                let mut d = a;
                loop {
                    days[d] = true;
                    if d == b {
                        break;
                    }
                    d = (d + 1) % 7;
                }
            }
            None => days[day(part)?] = true,
        }
    }
    Ok(days)
}

/// `name(0), name(1), ...` for a list in an error.
fn names<'a>(
    count: usize,
    name: impl Fn(usize) -> std::result::Result<&'a str, eigenrad_runtime::Error>,
) -> String {
    let list: Vec<&str> = (0..count).filter_map(|i| name(i).ok()).collect();
    if list.is_empty() {
        "none".into()
    } else {
        list.join(", ")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn days_parse() {
        assert_eq!(
            parse_days("mon-fri").unwrap(),
            [true, true, true, true, true, false, false]
        );
        assert_eq!(
            parse_days("fri-mon").unwrap(),
            [true, false, false, false, true, true, true]
        );
        assert_eq!(parse_days("all").unwrap(), [true; 7]);
        assert_eq!(
            parse_days("tue,thu").unwrap(),
            [false, true, false, true, false, false, false]
        );
        assert!(parse_days("monday").unwrap_err().contains("monday"));
    }

    /// The power curve: standby when off; linear from the minimum to full.
    #[test]
    fn power_curve() {
        let c = ChannelPower {
            name: "a".into(),
            index: 0,
            full_w: 40.0,
            standby_w: 0.5,
            minimum_level: 0.1,
            power_at_minimum: 0.2,
        };
        assert_eq!(c.power(0.0), 0.5);
        assert!((c.power(1.0) - 40.0).abs() < 1e-12);
        // 0.5 W standby and 20 % of the other 39.5 W.
        assert!((c.power(0.1) - 8.4).abs() < 1e-12);
        // Half way from 0.1 to 1 in level is half way from 0.2 to 1 in the power above
        // standby.
        assert!((c.power(0.55) - (0.5 + 39.5 * 0.6)).abs() < 1e-12);
        // Below the minimum (never set by a strategy) it draws the minimum's power.
        assert!((c.power(0.05) - 8.4).abs() < 1e-12);
        // On at its minimum it draws more than off.
        let low = ChannelPower {
            minimum_level: 0.01,
            power_at_minimum: 0.01,
            ..c
        };
        assert!(low.power(0.01) > low.power(0.0));
    }

    #[test]
    fn occupancy_hours_are_hour_ending() {
        let o = Occupancy {
            days: parse_days("mon-fri").unwrap(),
            from_hour: 8,
            to_hour: 18,
            days_text: "mon-fri".into(),
        };
        assert!(!o.occupied(0, 8));
        assert!(o.occupied(0, 9));
        assert!(o.occupied(4, 18));
        assert!(!o.occupied(4, 19));
        assert!(!o.occupied(5, 12));
        assert_eq!((1..=24).filter(|&h| o.occupied(2, h)).count(), 10);
    }
}
