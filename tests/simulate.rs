//! `eigenrad simulate`: the controller's year against closed forms (energy, LENI and the
//! levels under a constant daylight), against `eval` at the same hours (the daylight of every
//! hour), and end to end on the shipped weather year.

mod common;

use std::path::{Path, PathBuf};

use chrono::{DateTime, FixedOffset};
use eigenrad_precompute::cli::{self, DaylightArgs, LevelArgs, SkyInput};
use eigenrad_precompute::simulate::{self, Hour, HourSky, Strategy};
use eigenrad_precompute::weather;
use eigenrad_runtime::sky::cie::CieSky;
use eigenrad_runtime::{Basis, ChannelEvaluator, DaylightEvaluator};

/// The daylit test room in Greensboro, where the shipped weather year was recorded.
const GREENSBORO: &str = r#"[site]
latitude = 36.1
longitude = -79.95
elevation = 273
north = 0
ground_reflectance = 0.2
utc_offset = "-05:00""#;

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// The shipped weather year (NREL TMY3 723170 as EPW, data/weather/PROVENANCE.md).
fn weather_year() -> PathBuf {
    root().join("data/weather/greensboro-723170-tmy3.epw")
}

/// The daylit room built in `dir` (4 modes, coarse): its basis' bytes and path.
fn daylit_basis(dir: &Path) -> (Vec<u8>, PathBuf) {
    let o = common::build(dir, &common::daylit_room(GREENSBORO), "room.basis", &[]);
    assert!(o.status.success(), "build failed: {}", common::stderr(&o));
    let path = dir.join("room.basis");
    (std::fs::read(&path).expect("basis"), path)
}

/// A controller of the daylit room's one channel, `lamp` (40 W, 0.5 W standby, no minimum,
/// continuous levels), keeping the work plane at `target` lux by the photocell.
fn controller_text(target: f64, extra: &str) -> String {
    format!(
        r#"sensor = "photocell"
floor_area = 12.0
dali = false
{extra}
[[target]]
zone = "work_plane"
illuminance = {target}

[[channel]]
name = "lamp"
power = 40
standby = 0.5
minimum_level = 0
"#
    )
}

/// The CIE overcast sky (standard type 1) at `diffuse` lux diffuse horizontal, as the runtime
/// computes it for the basis' patches.
fn overcast_hour_sky(basis: &Basis<'_>, diffuse: f32) -> HourSky {
    let patches = basis.sky_patches().expect("daylight");
    let mut centres = vec![[0.0f32; 3]; patches.count()];
    patches.centres(&mut centres).unwrap();
    let sky = CieSky::standard(1, [0.0, 0.0, 1.0]).unwrap();
    let zenith = sky.zenith_luminance_for(diffuse).unwrap();
    let mut luminance = vec![0.0f32; patches.count()];
    patches
        .luminances_at(&centres, &sky, zenith, &mut luminance)
        .unwrap();
    HourSky {
        luminance,
        global_horizontal: diffuse,
        sun: None,
        altitude_deg: 30.0,
        azimuth_deg: 180.0,
        diffuse_horizontal_lux: f64::from(diffuse),
        direct_normal_lux: 0.0,
    }
}

/// Daylight of `zone` and `sensor` per lux of overcast diffuse horizontal illuminance, and
/// the channel's gains at level 1 (zone, sensor), through the runtime.
fn per_unit(basis: Basis<'_>, zone: usize, sensor: usize) -> ([f64; 2], [f64; 2]) {
    let mut day = Box::new(DaylightEvaluator::<145, 8, 0>::new(basis).unwrap());
    let sky = overcast_hour_sky(&basis, 1000.0);
    day.set_sky(&sky.luminance, 1000.0, None).unwrap();
    let daylight = [
        f64::from(day.zone_illuminance(zone).unwrap()) / 1000.0,
        f64::from(day.sensor_illuminance(sensor).unwrap()) / 1000.0,
    ];
    let mut lamp = ChannelEvaluator::<1, 4>::new(basis).unwrap();
    lamp.set_channel_level(0, 1.0).unwrap();
    let gains = [
        f64::from(lamp.zone_irradiance(zone).unwrap()[0]),
        f64::from(lamp.sensor_irradiance(sensor).unwrap()[0]),
    ];
    (daylight, gains)
}

/// A week of hours, every hour under the same overcast sky, occupied 08:00–18:00 on its
/// five weekdays (the controller's default occupancy).
fn constant_week(basis: &Basis<'_>, diffuse: f32, occupancy: &simulate::Occupancy) -> Vec<Hour> {
    let start: DateTime<FixedOffset> = "2026-01-05T00:30:00-05:00".parse().unwrap(); // a Monday
    (0..7 * 24)
        .map(|k| {
            let weekday = k / 24;
            let hour_ending = (k % 24 + 1) as u32;
            Hour {
                time: start + chrono::Duration::hours(k as i64),
                line: k + 9,
                hour_ending,
                weekday,
                occupied: occupancy.occupied(weekday, hour_ending),
                analysis: hour_ending > 8 && hour_ending <= 18,
                sky: overcast_hour_sky(basis, diffuse),
            }
        })
        .collect()
}

/// Under a constant overcast sky whose daylight gives the work plane a known share `f` of
/// its target, every strategy's levels, energy and LENI have closed forms:
///
/// - the model's controller (one channel of zone gain `g`, power `P`) sets
///   `l = (1 − f) T / g`: its estimate of the sensor's daylight is exact (its model is the
///   basis) and the overcast ratio carries it to the work plane exactly under that sky;
/// - open-loop dimming sets the same level (its sensor sees the daylight alone, its ratio
///   is the overcast one);
/// - the closed loop settles where the photocell reads its night set point
///   `S₁/W₁ · T`: `l = T/g − E_s,day/S₁`, in one step from any level (the reading is linear
///   in the level with slope `S₁`);
/// - switching keeps the lamp on (daylight alone is short), full output at 1.
///
/// Energy: `50 occupied hours × P l + 118 other hours × standby`, kWh; LENI that over the
/// floor area. Tolerance 1e-5 relative: the runtime reads in `f32`.
#[test]
fn constant_daylight_has_closed_forms() {
    let dir = common::scratch("simulate-closed-forms");
    let (bytes, _) = daylit_basis(&dir);
    let basis = Basis::from_bytes(&bytes).unwrap();
    let zone = basis.find_zone("work_plane").unwrap();
    let sensor = basis.find_sensor("photocell").unwrap();
    let (daylight, gains) = per_unit(basis, zone, sensor);
    let target = 500.0;
    let share = 0.3;
    let diffuse = share * target / daylight[0];
    let path = dir.join("controller.toml");
    let controller =
        simulate::parse_controller(&path, &controller_text(target, ""), &basis).unwrap();
    let hours = constant_week(&basis, diffuse as f32, &controller.occupancy);
    let occupied = hours.iter().filter(|h| h.occupied).count();
    assert_eq!(occupied, 50);
    let year = simulate::simulate(&bytes, &controller, &hours).unwrap();
    let (power, standby, area) = (40.0, 0.5, 12.0);
    let zone_daylight = share * target;
    let sensor_daylight = diffuse * daylight[1];
    let model_level = (target - zone_daylight) / gains[0];
    let closed_level = target / gains[0] - sensor_daylight / gains[1];
    let expected = [
        (Strategy::Model, model_level),
        (Strategy::ClosedLoop, closed_level),
        (Strategy::OpenLoop, model_level),
        (Strategy::Switching, 1.0),
        (Strategy::FullOutput, 1.0),
    ];
    let unoccupied = (hours.len() - occupied) as f64;
    for (strategy, level) in expected {
        assert!(level > 0.05 && level < 1.0 || level == 1.0, "{level}");
        let totals = year
            .strategies
            .iter()
            .find(|t| t.strategy == strategy.name())
            .unwrap();
        let kwh = (occupied as f64 * power * level + unoccupied * standby) / 1000.0;
        let close = |a: f64, b: f64| (a - b).abs() <= 1e-5 * b.abs();
        assert!(
            close(totals.total_kwh, kwh),
            "{}: {} kWh, closed form {kwh}",
            strategy.name(),
            totals.total_kwh
        );
        assert!(close(totals.leni_kwh_m2, kwh / area));
        assert!(close(totals.parasitic_kwh, unoccupied * standby / 1000.0));
        assert_eq!(totals.operating_hours, occupied);
    }
    // The model's hours meet the target exactly; the closed loop's miss it by its ratio's
    // error, the sign of the closed form's.
    let model = &year.hours;
    for (h, r) in hours.iter().zip(model) {
        if h.occupied {
            let total = f64::from(r.zone_total[zone]);
            assert!((total / target - 1.0).abs() < 1e-5, "{total}");
            assert!((f64::from(r.levels[0]) / model_level - 1.0).abs() < 1e-5);
        } else {
            assert_eq!(r.levels[0], 0.0);
        }
    }
    let model_totals = &year.strategies[0];
    let full = &year.strategies[4];
    assert!(
        (model_totals.saving_vs_full_output - (1.0 - model_totals.total_kwh / full.total_kwh))
            .abs()
            < 1e-12
    );
    assert_eq!(model_totals.hours_below_target, vec![0]);
}
