//! The firmware's daylight-harvesting day (`examples/firmware/src/harvest.rs`) against the
//! host: its records, their parser, and the check of every step.

use eigenrad_runtime::sky::{self, cie::CieSky};
use eigenrad_runtime::target::{output_gains, Output};
use eigenrad_runtime::{Basis, ChannelEvaluator, DaylightEvaluator};

use super::controller::greedy_levels;
use super::daylight::{eval_sky, offset_text};
use super::*;

/// The day (`harvest.rs`): its date, its steps (minutes after local midnight), the CIE sky
/// type, the work-plane target (lux) and the luminaires' power at level 1 (W, the controller
/// loop's, `control.rs`).
const HARVEST_DATE: (i32, u8, u8) = (2026, 3, 20);
const HARVEST_FIRST_MINUTE: u32 = 8 * 60;
const HARVEST_LAST_MINUTE: u32 = 16 * 60;
const HARVEST_STEP_MINUTES: u32 = 60;
const HARVEST_SKY_TYPE: u8 = 1;
const HARVEST_TARGET: f32 = 500.0;
const HARVEST_WATTS: [f32; 8] = [36.0, 32.0, 28.0, 24.0, 20.0, 16.0, 12.0, 8.0];

/// The runtime's sun position on the target against the same `f32` code on the host,
/// degrees: the two compilations may order a sum differently, a few roundings of an `f32`
/// angle of up to 360° (3 × 10⁻⁵° a unit in the last place there).
const HARVEST_SUN_TOL_DEG: f32 = 1e-3;
/// Daylight at the sensor and on the work plane against `eigenrad eval` under the same sky,
/// relative (floored at 1 lux): both weigh the same stored daylight; the overcast sky's
/// luminance does not depend on where the sun is, so the firmware's sun (the runtime's) and
/// eval's (SPA) give the same sky, and the diffuse horizontal illuminance is passed as the
/// firmware printed it. What differs is the `f32` quadrature of the zenith luminance on two
/// compilations and the sky's patch centres (the firmware's from `SkyPatches::centres`,
/// eval's by its own path): roundings of `f32` sums, far below this tolerance, which still catches
/// a wrong sky, sun or scale (each off by percents).
const HARVEST_DAYLIGHT_RTOL: f64 = 1e-5;
/// Levels (in [0, 1]), and the work plane's relative error, against the host's closed forms
/// in `f64`: the firmware's are sums and ratios of `f32` readings of a few hundred lux, good
/// to a few 10⁻⁷; the level solver's own tolerance is 2 × 10⁻⁶ (`target::FEASIBILITY`).
const HARVEST_LEVEL_TOL: f64 = 1e-4;
const HARVEST_ERROR_TOL: f64 = 1e-4;
/// Readings, set points and power, relative (floored at 1 lux or 1 W).
const HARVEST_RTOL: f64 = 1e-5;

/// The harvesting day's records.
#[derive(Debug, Default, Clone)]
pub(crate) struct Harvest {
    date: String,
    sky_type: u8,
    /// Lux.
    target: f32,
    sensor: usize,
    zone: usize,
    /// Commissioning at night, every luminaire at 1: the sensor's and the work plane's
    /// illuminance (lux), their ratio and the set point `ratio × target` (lux).
    night_sensor: f32,
    night_zone: f32,
    ratio: f32,
    setpoint: f32,
    steps: Vec<HarvestStep>,
}

/// One step of the day; illuminances in lux, power in W, errors as fractions of the target.
#[derive(Debug, Default, Clone)]
struct HarvestStep {
    time: String,
    /// The runtime's sun, degrees.
    altitude: f32,
    azimuth: f32,
    diffuse_horizontal: f32,
    sensor_daylight: f32,
    zone_daylight: f32,
    model: ModelStep,
    closed: ClosedStep,
}

/// The model's controller at a step.
#[derive(Debug, Default, Clone)]
struct ModelStep {
    reading: f32,
    estimate: f32,
    ambient: f32,
    levels: Vec<f32>,
    power: f32,
    work_plane: f32,
    error: f32,
}

/// The conventional controller at a step.
#[derive(Debug, Default, Clone)]
struct ClosedStep {
    reading: f32,
    level: f32,
    power: f32,
    work_plane: f32,
    error: f32,
}

impl Harvest {
    /// Reads one `harvest ...` record (the words after `harvest`).
    pub(crate) fn parse(&mut self, fields: &[&str], line: &str) {
        let step = |steps: &mut Vec<HarvestStep>, k: &str| -> usize {
            let k: usize = number(k, line);
            assert_eq!(k + 1, steps.len(), "harvest record out of order: {line:?}");
            k
        };
        match fields {
            ["setup", "date", d, "sky", "cie", t, "target", tg, "sensor", s, "zone", z] => {
                self.date = d.to_string();
                self.sky_type = number(t, line);
                self.target = number(tg, line);
                self.sensor = number(s, line);
                self.zone = number(z, line);
            }
            ["night", "sensor", s, "zone", z, "ratio", r, "setpoint", sp] => {
                self.night_sensor = number(s, line);
                self.night_zone = number(z, line);
                self.ratio = number(r, line);
                self.setpoint = number(sp, line);
            }
            ["step", k, "time", t, "altitude", a, "azimuth", az, "diffuse_horizontal", d, "sensor_daylight", sd, "zone_daylight", zd] =>
            {
                let k: usize = number(k, line);
                assert_eq!(k, self.steps.len(), "harvest steps out of order: {line:?}");
                self.steps.push(HarvestStep {
                    time: t.to_string(),
                    altitude: number(a, line),
                    azimuth: number(az, line),
                    diffuse_horizontal: number(d, line),
                    sensor_daylight: number(sd, line),
                    zone_daylight: number(zd, line),
                    ..HarvestStep::default()
                });
            }
            ["model", k, "reading", r, "estimate", e, "ambient", a, "levels", rest @ ..] => {
                let k = step(&mut self.steps, k);
                let p = rest
                    .iter()
                    .position(|w| *w == "power")
                    .unwrap_or_else(|| panic!("no power in {line:?}"));
                let (levels, tail) = rest.split_at(p);
                let ["power", power, "work_plane", w, "error", err] = tail else {
                    panic!("bad harvest model record {line:?}");
                };
                self.steps[k].model = ModelStep {
                    reading: number(r, line),
                    estimate: number(e, line),
                    ambient: number(a, line),
                    levels: levels.iter().map(|v| number(v, line)).collect(),
                    power: number(power, line),
                    work_plane: number(w, line),
                    error: number(err, line),
                };
            }
            ["closed", k, "reading", r, "level", l, "power", p, "work_plane", w, "error", e] => {
                let k = step(&mut self.steps, k);
                self.steps[k].closed = ClosedStep {
                    reading: number(r, line),
                    level: number(l, line),
                    power: number(p, line),
                    work_plane: number(w, line),
                    error: number(e, line),
                };
            }
            _ => panic!("unknown harvest record {line:?}"),
        }
    }
}

/// Readings by output name, lux.
type Named = Vec<(String, f64)>;

/// `eigenrad eval BASIS --json --time TIME --cie 1 --dhi-lux D --dni-lux 0`: the daylight
/// of the sensors and zones (lux) under the harvesting day's sky, by name.
fn eval_overcast(basis: &Path, time: &str, diffuse: f32) -> (Named, Named) {
    let json =
        eval_sky(basis, time, HARVEST_SKY_TYPE, diffuse, 0.0).unwrap_or_else(|e| panic!("{e}"));
    let outputs = |key: &str| -> Named {
        json[key]
            .as_array()
            .unwrap_or_else(|| panic!("no {key} in eval's JSON"))
            .iter()
            .map(|o| {
                let name = o["name"].as_str().expect("output name").to_string();
                (name, numbers(&o["daylight"], "daylight")[0])
            })
            .collect()
    };
    (outputs("sensors"), outputs("zones"))
}

/// `|got − want| ≤ tol × max(|want|, floor)`, else a failure naming `what`.
fn close(what: &dyn Fn() -> String, got: f32, want: f64, tol: f64, floor: f64) {
    let got = f64::from(got);
    assert!(
        (got - want).abs() <= tol * want.abs().max(floor),
        "{}: firmware {got:e}, host {want:e}",
        what()
    );
}

/// Checks the harvesting day of the firmware run on the basis at `path` against the host:
///
/// - the night's commissioning (sensor and work plane with every luminaire at 1, from the
///   host's `ChannelEvaluator`), the ratio and the set point;
/// - each step's time, the runtime's sun (the same `f32` code on the host), the overcast
///   sky's diffuse horizontal illuminance, and the daylight at the sensor and on the work
///   plane against `eigenrad eval --time T --cie 1 --dhi-lux D --dni-lux 0 --json`;
/// - the model's controller against the least-power levels of the continuous knapsack
///   (`greedy_levels`, Dantzig's rule in `f64`) for the work plane's daylight, their power,
///   the work plane they give and its error;
/// - the conventional controller against its closed form in `f64`: the level
///   `clamp(target/W₁ − E_s,day/S₁, 0, 1)` at which its sensor reads the set point, its
///   power, and the work plane's error `(E_wp,day + level·W₁)/target − 1`;
/// - each controller's photosensor reading, the daylight plus the electric light at the
///   levels it had set the step before.
///
/// Returns the largest errors of the two controllers, or `None` without QEMU.
fn check_harvest(name: &str, path: &Path) -> Option<(f64, f64)> {
    let run = firmware(name, path)?;
    let h = run.harvest.as_ref().expect("harvest records");
    let bytes = std::fs::read(path).unwrap();
    let basis = Basis::from_bytes(&bytes).unwrap();
    let site = basis.site().unwrap();
    let dimmed: Vec<usize> = (0..basis.channel_count())
        .filter(|&c| basis.channel_name(c).unwrap() != "window")
        .collect();
    let sensor = basis.find_sensor("ceiling").unwrap_or(0);
    let zone = basis.find_zone("work_plane").unwrap_or(0);
    let (year, month, date) = HARVEST_DATE;
    let date = format!("{year:04}-{month:02}-{date:02}");
    assert_eq!(
        (h.date.as_str(), h.sky_type, h.target, h.sensor, h.zone),
        (
            date.as_str(),
            HARVEST_SKY_TYPE,
            HARVEST_TARGET,
            sensor,
            zone
        )
    );
    let target = f64::from(HARVEST_TARGET);
    let weights: Vec<f64> = HARVEST_WATTS[..dimmed.len()]
        .iter()
        .map(|&w| f64::from(w))
        .collect();
    let gains = |output: Output| -> Vec<f64> {
        let mut g = vec![0.0f32; dimmed.len()];
        output_gains(&basis, output, &dimmed, &mut g).unwrap();
        g.into_iter().map(f64::from).collect()
    };
    let (sensor_gains, zone_gains) = (gains(Output::Sensor(sensor)), gains(Output::Zone(zone)));
    let dot = |g: &[f64], levels: &[f64]| -> f64 { g.iter().zip(levels).map(|(a, b)| a * b).sum() };

    // The night: every luminaire at 1.
    let mut lights = ChannelEvaluator::<1, 8>::new(basis).unwrap();
    for &c in &dimmed {
        lights.set_channel_level(c, 1.0).unwrap();
    }
    let s1 = f64::from(lights.sensor_irradiance(sensor).unwrap()[0]);
    let w1 = f64::from(lights.zone_irradiance(zone).unwrap()[0]);
    let night = |what: &'static str| move || format!("{name}: night {what}");
    close(&night("sensor"), h.night_sensor, s1, HARVEST_RTOL, 1.0);
    close(&night("work plane"), h.night_zone, w1, HARVEST_RTOL, 1.0);
    close(&night("ratio"), h.ratio, s1 / w1, HARVEST_RTOL, 0.0);
    close(
        &night("set point"),
        h.setpoint,
        s1 / w1 * target,
        HARVEST_RTOL,
        1.0,
    );

    // The steps, hour by hour.
    let offset = offset_text(site.utc_offset_minutes.round() as i32);
    let minutes: Vec<u32> = (HARVEST_FIRST_MINUTE..=HARVEST_LAST_MINUTE)
        .step_by(HARVEST_STEP_MINUTES as usize)
        .collect();
    assert_eq!(h.steps.len(), minutes.len(), "{name}: harvest steps");
    let patches = basis.sky_patches().unwrap();
    let mut centres = vec![[0.0f32; 3]; patches.count()];
    patches.centres(&mut centres).unwrap();
    let mut luminance = vec![0.0f32; patches.count()];
    let mut day = DaylightEvaluator::<145, 8, 0>::new(basis).unwrap();
    let (mut model_levels, mut closed_level) = (vec![1.0f64; dimmed.len()], 1.0f64);
    let (mut worst_model, mut worst_closed) = (0.0f64, 0.0f64);
    let mut rows = Vec::new();
    for (k, (step, &minute)) in h.steps.iter().zip(&minutes).enumerate() {
        let time = format!("{date}T{:02}:{:02}{offset}", minute / 60, minute % 60);
        assert_eq!(step.time, time, "{name}: harvest step {k}");
        let at = |what: &'static str| {
            let time = time.clone();
            move || format!("{name}: harvest {time}: {what}")
        };

        // The sky: the runtime's sun and the overcast sky on the host.
        let sun = sky::sun::position(
            site.latitude,
            site.longitude,
            sky::sun::Utc {
                year,
                month,
                day: HARVEST_DATE.2,
                seconds: ((minute as i32 - site.utc_offset_minutes.round() as i32) * 60) as f32,
            },
        )
        .unwrap();
        assert!(
            (step.altitude - sun.altitude).abs() <= HARVEST_SUN_TOL_DEG
                && (step.azimuth - sun.azimuth).abs() <= HARVEST_SUN_TOL_DEG,
            "{time}: the firmware's sun {} {}, the host's {} {}",
            step.altitude,
            step.azimuth,
            sun.altitude,
            sun.azimuth
        );
        assert!(sun.altitude > 0.0, "{time}: the sun is up");
        let diffuse = 300.0 + 21_000.0 * f64::from(sun.altitude).to_radians().sin();
        close(
            &at("diffuse horizontal"),
            step.diffuse_horizontal,
            diffuse,
            HARVEST_RTOL,
            1.0,
        );
        let (sensors, zones) = eval_overcast(path, &time, step.diffuse_horizontal);
        let sd = sensors[sensor].1;
        let wd = zones[zone].1;
        close(
            &at("sensor daylight"),
            step.sensor_daylight,
            sd,
            HARVEST_DAYLIGHT_RTOL,
            1.0,
        );
        close(
            &at("work-plane daylight"),
            step.zone_daylight,
            wd,
            HARVEST_DAYLIGHT_RTOL,
            1.0,
        );
        // The host's runtime under the same sky reads what eval reads.
        let overcast = CieSky::standard(HARVEST_SKY_TYPE, sun.direction).unwrap();
        let zenith = overcast
            .zenith_luminance_for(step.diffuse_horizontal)
            .unwrap();
        patches
            .luminances_at(&centres, &overcast, zenith, &mut luminance)
            .unwrap();
        day.set_sky(&luminance, step.diffuse_horizontal, None)
            .unwrap();
        close(
            &at("host runtime's work-plane daylight"),
            day.zone_illuminance(zone).unwrap(),
            wd,
            HARVEST_DAYLIGHT_RTOL,
            1.0,
        );

        // The model's controller: its reading at the levels of the step before; the daylight
        // it carries to the work plane is the work plane's.
        let model = &step.model;
        close(
            &at("model reading"),
            model.reading,
            sd + dot(&sensor_gains, &model_levels),
            HARVEST_RTOL,
            1.0,
        );
        close(&at("model estimate"), model.estimate, sd, HARVEST_RTOL, 1.0);
        close(&at("model ambient"), model.ambient, wd, HARVEST_RTOL, 1.0);
        let (want, short) = greedy_levels(&zone_gains, &weights, wd, target);
        assert_eq!(model.levels.len(), want.len(), "{time}: model levels");
        for (i, (&got, &w)) in model.levels.iter().zip(&want).enumerate() {
            assert!(
                (f64::from(got) - w).abs() <= HARVEST_LEVEL_TOL,
                "{time}: model level of channel {} {got}, host {w}",
                dimmed[i]
            );
        }
        close(
            &at("model power"),
            model.power,
            dot(&weights, &want),
            HARVEST_RTOL,
            1.0,
        );
        let plane = wd + dot(&zone_gains, &want);
        close(
            &at("model work plane"),
            model.work_plane,
            plane,
            HARVEST_RTOL,
            1.0,
        );
        let error = plane / target - 1.0;
        assert!(
            (f64::from(model.error) - error).abs() <= HARVEST_ERROR_TOL,
            "{time}: model error {}, host {error}",
            model.error
        );
        if short == 0.0 {
            // Met: the work plane at the target, or above it on daylight alone.
            assert!(error >= -HARVEST_ERROR_TOL, "{time}: model error {error}");
        }
        model_levels = want;

        // The conventional controller: its reading at its level of the step before, then the
        // level at which its sensor reads the night's set point.
        let closed = &step.closed;
        close(
            &at("closed-loop reading"),
            closed.reading,
            sd + closed_level * s1,
            HARVEST_RTOL,
            1.0,
        );
        let level = (target / w1 - sd / s1).clamp(0.0, 1.0);
        assert!(
            (f64::from(closed.level) - level).abs() <= HARVEST_LEVEL_TOL,
            "{time}: closed-loop level {}, host {level}",
            closed.level
        );
        let power = level * weights.iter().sum::<f64>();
        close(
            &at("closed-loop power"),
            closed.power,
            power,
            HARVEST_RTOL,
            1.0,
        );
        let plane = wd + level * w1;
        close(
            &at("closed-loop work plane"),
            closed.work_plane,
            plane,
            HARVEST_RTOL,
            1.0,
        );
        let error = plane / target - 1.0;
        assert!(
            (f64::from(closed.error) - error).abs() <= HARVEST_ERROR_TOL,
            "{time}: closed-loop error {}, host {error}",
            closed.error
        );
        closed_level = level;
        worst_model = worst_model.max(f64::from(model.error).abs());
        worst_closed = worst_closed.max(f64::from(closed.error).abs());
        rows.push(format!(
            "{time}: daylight sensor {sd:.1} lx, work plane {wd:.1} lx; model {:.1} W error \
             {:+.2} %; night-calibrated {:.1} W (level {:.3}) error {:+.2} %",
            model.power,
            100.0 * model.error,
            closed.power,
            closed.level,
            100.0 * closed.error
        ));
    }
    eprintln!(
        "{name}: harvesting day, night ratio sensor/work plane {:.4}:\n  {}",
        h.ratio,
        rows.join("\n  ")
    );
    check_simulate_day(name, path, h, &dimmed);
    Some((worst_model, worst_closed))
}

/// `eigenrad simulate`'s loop over the firmware's day equals the firmware's: the same basis,
/// the same moments and skies (the firmware's overcast sky at its printed diffuse horizontal
/// illuminance; CIE type 1 does not depend on the sun), a controller file of the firmware's
/// (the ceiling photocell, the work plane at its target, its luminaires' watts, continuous
/// levels from 0, every step occupied), run once per strategy through
/// `simulate::simulate`. The model's levels and work plane, and the closed loop's level and
/// work plane, agree with the firmware's records to [`HARVEST_LEVEL_TOL`] (levels) and
/// [`HARVEST_ERROR_TOL`] of the target (work plane): both run the runtime's `f32` code, the
/// one on the Cortex-M4F, the other on the host.
fn check_simulate_day(name: &str, path: &Path, h: &Harvest, dimmed: &[usize]) {
    use eigenrad_precompute::simulate::{self, Hour, HourSky};
    let bytes = std::fs::read(path).unwrap();
    let basis = Basis::from_bytes(&bytes).unwrap();
    let patches = basis.sky_patches().unwrap();
    let mut centres = vec![[0.0f32; 3]; patches.count()];
    patches.centres(&mut centres).unwrap();
    let mut channels = String::new();
    for (k, &c) in dimmed.iter().enumerate() {
        channels.push_str(&format!(
            "[[channel]]\nname = \"{}\"\npower = {}\nstandby = 0\nminimum_level = 0\n\n",
            basis.channel_name(c).unwrap(),
            HARVEST_WATTS[k]
        ));
    }
    let hours: Vec<Hour> = h
        .steps
        .iter()
        .enumerate()
        .map(|(k, step)| {
            let overcast = CieSky::standard(HARVEST_SKY_TYPE, [0.0, 0.0, 1.0]).unwrap();
            let zenith = overcast
                .zenith_luminance_for(step.diffuse_horizontal)
                .unwrap();
            let mut luminance = vec![0.0f32; patches.count()];
            patches
                .luminances_at(&centres, &overcast, zenith, &mut luminance)
                .unwrap();
            Hour {
                time: chrono::DateTime::parse_from_rfc3339(&format!(
                    "{}:00{}",
                    &step.time[..16],
                    &step.time[16..]
                ))
                .unwrap(),
                line: k,
                hour_ending: 9 + k as u32,
                weekday: 0,
                occupied: true,
                analysis: true,
                sky: HourSky {
                    luminance,
                    global_horizontal: step.diffuse_horizontal,
                    sun: None,
                    altitude_deg: f64::from(step.altitude),
                    azimuth_deg: f64::from(step.azimuth),
                    diffuse_horizontal_lux: f64::from(step.diffuse_horizontal),
                    direct_normal_lux: 0.0,
                },
            }
        })
        .collect();
    let controller = |strategy: &str| {
        let text = format!(
            "sensor = \"{}\"\nstrategy = \"{strategy}\"\nfloor_area = 24\ndali = false\n\n\
             [[target]]\nzone = \"{}\"\nilluminance = {}\n\n{channels}\
             [occupancy]\ndays = \"all\"\nhours = [0, 24]\n",
            basis.sensor_name(h.sensor).unwrap(),
            basis.zone_name(h.zone).unwrap(),
            HARVEST_TARGET
        );
        simulate::parse_controller(Path::new("harvest.toml"), &text, &basis).unwrap()
    };
    let model = simulate::simulate(&bytes, &controller("model"), &hours).unwrap();
    let closed = simulate::simulate(&bytes, &controller("closed-loop"), &hours).unwrap();
    let target = f64::from(HARVEST_TARGET);
    for (k, step) in h.steps.iter().enumerate() {
        let (m, c) = (&model.hours[k], &closed.hours[k]);
        for (i, &c) in dimmed.iter().enumerate() {
            let (ours, theirs) = (f64::from(m.levels[c]), f64::from(step.model.levels[i]));
            assert!(
                (ours - theirs).abs() <= HARVEST_LEVEL_TOL,
                "{name}: {}: simulate's model level of channel {c} {ours}, the firmware's {theirs}",
                step.time
            );
        }
        let plane = f64::from(m.zone_total[h.zone]);
        assert!(
            (plane - f64::from(step.model.work_plane)).abs() <= HARVEST_ERROR_TOL * target,
            "{name}: {}: simulate's model work plane {plane}, the firmware's {}",
            step.time,
            step.model.work_plane
        );
        let level = f64::from(c.levels[dimmed[0]]);
        assert!(
            (level - f64::from(step.closed.level)).abs() <= HARVEST_LEVEL_TOL,
            "{name}: {}: simulate's closed-loop level {level}, the firmware's {}",
            step.time,
            step.closed.level
        );
        let plane = f64::from(c.zone_total[h.zone]);
        assert!(
            (plane - f64::from(step.closed.work_plane)).abs() <= HARVEST_ERROR_TOL * target,
            "{name}: {}: simulate's closed-loop work plane {plane}, the firmware's {}",
            step.time,
            step.closed.work_plane
        );
    }
    eprintln!("{name}: simulate's day equals the firmware's (levels within {HARVEST_LEVEL_TOL}, work plane within {HARVEST_ERROR_TOL} of the target)");
}

/// The daylight office at 32 modes in f16 as a daylight-harvesting controller: every figure
/// of its day agrees with the host's ([`check_harvest`]). The model's controller keeps the
/// work plane at the target to within the comparison's tolerance; the night-calibrated one
/// misses it, since under the overcast sky the ceiling photocell sees daylight in another
/// ratio to the work plane than the luminaires' light.
#[test]
fn firmware_harvest_office() {
    let (path, name) = office_basis(Mesh::Daylight, 32, "f16");
    let Some((model, closed)) = check_harvest(&name, &path) else {
        return;
    };
    assert!(model <= HARVEST_ERROR_TOL, "model's largest error {model}");
    assert!(closed > 0.01, "night calibration's largest error {closed}");
}

#[test]
fn parser_reads_harvest_records() {
    let stdout = "basis bytes 1 bands 1\n\
        harvest setup date 2026-03-20 sky cie 1 target 5e2 sensor 1 zone 0\n\
        harvest night sensor 1.2e2 zone 6e2 ratio 2e-1 setpoint 1e2\n\
        harvest step 0 time 2026-03-20T08:00+01:00 altitude 1.3e1 azimuth 1.2e2 \
        diffuse_horizontal 5e3 sensor_daylight 2e1 zone_daylight 8e1\n\
        harvest model 0 reading 1.4e2 estimate 2e1 ambient 8e1 levels 1e0 5e-1 power 5e1 \
        work_plane 5e2 error 0e0\n\
        harvest closed 0 reading 1.4e2 level 6.7e-1 power 4e1 work_plane 4.8e2 error -4e-2\n\
        done\n";
    let run = FirmwareRun::parse(stdout, "");
    let h = run.harvest.unwrap();
    assert_eq!(
        (h.date.as_str(), h.sky_type, h.sensor, h.zone),
        ("2026-03-20", 1, 1, 0)
    );
    assert_eq!((h.night_sensor, h.ratio, h.setpoint), (120.0, 0.2, 100.0));
    let step = &h.steps[0];
    assert_eq!(step.time, "2026-03-20T08:00+01:00");
    assert_eq!((step.altitude, step.zone_daylight), (13.0, 80.0));
    assert_eq!(step.model.levels, vec![1.0, 0.5]);
    assert_eq!((step.model.power, step.model.error), (50.0, 0.0));
    assert_eq!((step.closed.level, step.closed.error), (0.67, -0.04));
}
