//! `eigenrad simulate`: the controller's year against closed forms (energy, LENI and the
//! levels under a constant daylight), against `eval` at the same hours (the daylight of every
//! hour), and end to end on the shipped weather year.

mod common;

use std::path::{Path, PathBuf};

use chrono::{DateTime, FixedOffset};
use eigenrad_precompute::cli::{self, DaylightArgs, LevelArgs, SkyInput};
use eigenrad_precompute::picture;
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
    // The daylight's share of the target, and a target the lamp meets at level 0.6 with it
    // (the room's one lamp gives its work plane about 120 lux at full output).
    let share = 0.3;
    let target = (0.6 * gains[0] / (1.0 - share)).round();
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
        // On: the gear's standby and the level's share of the rest.
        let on = standby + (power - standby) * level;
        let kwh = (occupied as f64 * on + unoccupied * standby) / 1000.0;
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

/// The controller file of the daylit room with a 500 lux target at `path`.
fn write_controller(path: &Path, text: &str) -> PathBuf {
    std::fs::write(path, text).expect("controller");
    path.to_path_buf()
}

/// Every hour of the year reads the daylight `eigenrad eval --time T <that hour's sky>` reads,
/// to 1e-6 of the larger reading (both are the runtime's `f32` on the same sky: the tolerance
/// is rounding), on a sample of hours: a dawn with the sun below the horizon and diffuse
/// light, noons in winter and summer, an overcast afternoon, evenings, a night. The hour's
/// sky is restated here from the weather record (its irradiances for the Perez state, its
/// illuminances for the scale, the water of its dew point), not taken from `simulate`.
#[test]
fn every_hour_reads_what_eval_reads() {
    let dir = common::scratch("simulate-against-eval");
    let (bytes, basis_path) = daylit_basis(&dir);
    let basis = Basis::from_bytes(&bytes).unwrap();
    let controller_path =
        write_controller(&dir.join("controller.toml"), &controller_text(100.0, ""));
    let controller = simulate::load_controller(&controller_path, &basis).unwrap();
    let weather = weather::read(&weather_year()).unwrap();
    let options = simulate::HourOptions {
        year: None,
        source: simulate::SkySource::Illuminance,
    };
    let (hours, warnings, _) =
        simulate::hours(&weather, &basis, &controller.occupancy, options).unwrap();
    assert!(warnings.is_empty(), "{warnings:?}");
    assert_eq!(hours.len(), 8760);
    let dawn = hours
        .iter()
        .position(|h| h.sky.altitude_deg < 0.0 && h.sky.diffuse_horizontal_lux > 0.0)
        .expect("an hour with the sun below the horizon and diffuse light");
    let at = |month: u8, day: u8, hour: u8| {
        weather
            .records
            .iter()
            .position(|r| (r.month, r.day, r.hour) == (month, day, hour))
            .unwrap()
    };
    let sample = [
        dawn,
        at(1, 15, 13),
        at(3, 21, 10),
        at(6, 21, 13),
        at(7, 14, 20),
        at(9, 2, 17),
        at(11, 30, 15),
        at(12, 21, 2),
    ];
    let mut daylit = 0;
    for k in sample {
        let (hour, record) = (&hours[k], &weather.records[k]);
        let year = simulate::simulate(&bytes, &controller, std::slice::from_ref(hour)).unwrap();
        let ours = &year.hours[0];
        let water = record.dew_point.map_or(simulate::WATER_DEFAULT_CM, |t| {
            (0.07 * t - 0.075).exp().clamp(0.0, 10.0)
        });
        let input = SkyInput::PerezMeasured {
            direct_normal: record.direct_normal,
            diffuse_horizontal: record.diffuse_horizontal,
            direct_normal_lux: record.direct_normal_lux.unwrap(),
            diffuse_horizontal_lux: record.diffuse_horizontal_lux.unwrap(),
        };
        let args = DaylightArgs {
            time: hour.time.to_rfc3339(),
            input,
            water,
            subdivision: 1,
        };
        let eval = cli::eval_with_daylight(
            &basis_path,
            &bytes,
            &LevelArgs::default(),
            Some(&args),
            false,
        )
        .unwrap_or_else(|e| panic!("eval at {}: {e}", args.time));
        let theirs: Vec<f64> = eval
            .sensors
            .iter()
            .chain(&eval.zones)
            .map(|r| r.daylight.as_ref().unwrap()[0])
            .collect();
        let mine: Vec<f64> = ours
            .sensor_daylight
            .iter()
            .chain(&ours.zone_daylight)
            .map(|&x| f64::from(x))
            .collect();
        for (a, b) in mine.iter().zip(&theirs) {
            let scale = a.abs().max(b.abs()).max(1e-9);
            assert!(
                (a - b).abs() <= 1e-6 * scale,
                "{}: simulate {a} lux, eval {b} lux",
                args.time
            );
        }
        daylit += usize::from(theirs.iter().any(|&x| x > 0.0));
    }
    // The night reads nothing; the others read daylight.
    assert_eq!(daylit, sample.len() - 1);
}

/// `eigenrad simulate` end to end on the shipped weather year: the summary in JSON, the
/// hourly CSV and the schedule (8760 hours each), the same bytes on a second run; a wrong
/// controller names its file, line and field and writes nothing; weather of another place
/// is warned about.
#[test]
fn a_year_end_to_end() {
    let dir = common::scratch("simulate-end-to-end");
    let (_, basis) = daylit_basis(&dir);
    let controller = write_controller(&dir.join("controller.toml"), &controller_text(100.0, ""));
    let weather = weather_year();
    let run = |hourly: &Path, schedule: &Path| {
        common::run(&[
            "simulate",
            basis.to_str().unwrap(),
            "--weather",
            weather.to_str().unwrap(),
            "--controller",
            controller.to_str().unwrap(),
            "--hourly",
            hourly.to_str().unwrap(),
            "--schedule",
            schedule.to_str().unwrap(),
            "--json",
        ])
    };
    let (hourly, schedule) = (dir.join("hours.csv"), dir.join("schedule.csv"));
    let o = run(&hourly, &schedule);
    assert!(o.status.success(), "{}", common::stderr(&o));
    let summary: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(summary["hours"], 8760);
    assert_eq!(summary["occupied_hours"].as_u64().unwrap() % 10, 0);
    assert!(summary["weather"]["distance_km"].as_f64().unwrap() < 1.0);
    assert_eq!(summary["strategies"].as_array().unwrap().len(), 5);
    let full = &summary["strategies"][4];
    assert_eq!(full["strategy"], "full-output");
    // Full output: 40 W every occupied hour (its standby among them), 0.5 W standby every
    // other hour.
    let occupied = summary["occupied_hours"].as_f64().unwrap();
    let expected = (40.0 * occupied + 0.5 * (8760.0 - occupied)) / 1000.0;
    assert!((full["total_kwh"].as_f64().unwrap() - expected).abs() < 1e-9 * expected);
    let grid = &summary["daylight"][0];
    assert_eq!(grid["zone"], "work_plane");
    assert_eq!(grid["hours"], 3650);
    for key in ["da300_mean", "sda_300_50", "ase_1000_250"] {
        let x = grid[key].as_f64().unwrap();
        assert!((0.0..=1.0).contains(&x), "{key} {x}");
    }
    let udi: f64 = grid["udi"]
        .as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap())
        .sum();
    assert!((udi - 1.0).abs() < 1e-9, "UDI bands sum to {udi}");
    let text = std::fs::read_to_string(&hourly).unwrap();
    assert_eq!(text.lines().count(), 8761);
    assert!(text.starts_with("time,hour_ending,occupied,"));
    let fractions = std::fs::read_to_string(&schedule).unwrap();
    assert_eq!(fractions.lines().count(), 8761);
    for line in fractions.lines().skip(1) {
        let x: f64 = line.parse().unwrap();
        assert!((0.0..=1.0).contains(&x), "{line}");
    }
    // The same bytes again.
    let (hourly2, schedule2) = (dir.join("hours2.csv"), dir.join("schedule2.csv"));
    let again = run(&hourly2, &schedule2);
    assert_eq!(again.stdout, o.stdout);
    assert_eq!(std::fs::read(&hourly2).unwrap(), text.as_bytes());
    assert_eq!(std::fs::read(&schedule2).unwrap(), fractions.as_bytes());

    // A zone the basis does not have: the file, its line and the field; nothing written.
    let bad = write_controller(
        &dir.join("bad.toml"),
        &controller_text(100.0, "").replace("zone = \"work_plane\"", "zone = \"desks\""),
    );
    let out = dir.join("never.csv");
    let o = common::run(&[
        "simulate",
        basis.to_str().unwrap(),
        "--weather",
        weather.to_str().unwrap(),
        "--controller",
        bad.to_str().unwrap(),
        "--hourly",
        out.to_str().unwrap(),
    ]);
    assert!(!o.status.success());
    let e = common::stderr(&o);
    assert!(
        e.contains("bad.toml:6: target.zone") && e.contains("desks"),
        "{e}"
    );
    assert!(!out.exists());

    // The same room in Vienna: the Greensboro weather is another place's.
    let vienna = dir.join("vienna");
    std::fs::create_dir_all(&vienna).unwrap();
    let b = common::build(
        &vienna,
        &common::daylit_room(common::VIENNA),
        "v.basis",
        &[],
    );
    assert!(b.status.success(), "{}", common::stderr(&b));
    let o = common::run(&[
        "simulate",
        vienna.join("v.basis").to_str().unwrap(),
        "--weather",
        weather.to_str().unwrap(),
        "--controller",
        controller.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", common::stderr(&o));
    let text = String::from_utf8_lossy(&o.stdout);
    assert!(
        text.contains("warning:") && text.contains("7524 km"),
        "{text}"
    );
}

/// Without a weather file: the overcast recipe's hours have the diffuse light of
/// `300 + 21 000 sin(altitude)` lux (Krochmann and Seidl) with the sun up and none with it
/// down, every hour of every day from `--from` to `--to`; the clear recipe's noon is brighter
/// than the overcast one's; a range that runs backwards is refused.
#[test]
fn sky_recipes_without_weather() {
    let dir = common::scratch("simulate-recipes");
    let (_, basis_path) = daylit_basis(&dir);
    let bytes = std::fs::read(&basis_path).unwrap();
    let basis = Basis::from_bytes(&bytes).unwrap();
    let controller =
        simulate::parse_controller(&dir.join("c.toml"), &controller_text(100.0, ""), &basis)
            .unwrap();
    let date = |d: &str| chrono::NaiveDate::parse_from_str(d, "%Y-%m-%d").unwrap();
    let (from, to) = (date("2026-03-16"), date("2026-03-22"));
    let overcast = simulate::recipe_hours(
        &basis,
        &controller.occupancy,
        simulate::Recipe::Overcast,
        from,
        to,
    )
    .unwrap();
    assert_eq!(overcast.len(), 7 * 24);
    assert_eq!(overcast.iter().filter(|h| h.occupied).count(), 50);
    for h in &overcast {
        if h.sky.altitude_deg > 0.0 {
            let want = 300.0 + 21_000.0 * h.sky.altitude_deg.to_radians().sin();
            assert!((h.sky.diffuse_horizontal_lux - want).abs() < 1e-9 * want);
            assert!(h.sky.sun.is_none());
        } else {
            assert!(h.sky.luminance.iter().all(|&l| l == 0.0));
        }
    }
    let clear = simulate::recipe_hours(
        &basis,
        &controller.occupancy,
        simulate::Recipe::Clear { linke: 3.0 },
        from,
        to,
    )
    .unwrap();
    let noon = 12;
    assert!(
        clear[noon].sky.direct_normal_lux > 50_000.0,
        "{:?}",
        clear[noon].sky.direct_normal_lux
    );
    assert!(clear[noon].sky.sun.is_some());
    assert!(
        clear[noon].sky.diffuse_horizontal_lux + clear[noon].sky.direct_normal_lux
            > overcast[noon].sky.diffuse_horizontal_lux
    );
    let year = simulate::simulate(&bytes, &controller, &overcast).unwrap();
    assert_eq!(year.hours.len(), overcast.len());
    let e = simulate::recipe_hours(
        &basis,
        &controller.occupancy,
        simulate::Recipe::Overcast,
        to,
        from,
    )
    .unwrap_err()
    .to_string();
    assert!(e.contains("--from/--to") && e.contains("before"), "{e}");
}

/// `eval --target ZONE=LUX`: the levels for a target alone, over a moment's daylight. The
/// daylit room's one channel at the level `(T − E_day)/g` gives its work plane the target
/// (to 1e-5, `f32`); a target beyond full output is warned about and the level is 1.
#[test]
fn eval_finds_the_levels_for_a_target() {
    let dir = common::scratch("simulate-eval-target");
    let (_, basis) = daylit_basis(&dir);
    let basis = basis.to_str().unwrap();
    let sky = [
        "--time",
        "2026-12-21T12:00",
        "--cie",
        "1",
        "--dhi-lux",
        "2000",
    ];
    let json = |args: &[&str]| -> serde_json::Value {
        let o = common::run(args);
        assert!(o.status.success(), "{}", common::stderr(&o));
        serde_json::from_slice(&o.stdout).unwrap()
    };
    let mut args = vec!["eval", basis, "--target", "work_plane=150", "--json"];
    args.extend_from_slice(&sky);
    let got = json(&args);
    let zone = &got["zones"][0];
    assert_eq!(zone["name"], "work_plane");
    let total = zone["irradiance"][0].as_f64().unwrap();
    assert!((total / 150.0 - 1.0).abs() < 1e-5, "{total}");
    let daylight = zone["daylight"][0].as_f64().unwrap();
    let level = got["levels"][0]["level"].as_f64().unwrap();
    let full = json(&["eval", basis, "--json"]);
    let gain = full["zones"][0]["irradiance"][0].as_f64().unwrap();
    assert!(
        (level - (150.0 - daylight) / gain).abs() < 1e-5,
        "{level} against {}",
        (150.0 - daylight) / gain
    );
    let o = common::run(&["eval", basis, "--target", "work_plane=100000"]);
    assert!(o.status.success());
    let e = common::stderr(&o);
    assert!(
        e.contains("warning: --target work_plane=100000") && e.contains("fall short"),
        "{e}"
    );
    let o = common::run(&["eval", basis, "--target", "nowhere=100"]);
    assert!(!o.status.success());
    assert!(common::stderr(&o).contains("no zone `nowhere`"));
}

/// The PNG's width, height and RGB pixels.
fn decode_png(bytes: &[u8]) -> (u32, u32, Vec<u8>) {
    let decoder = png::Decoder::new(std::io::Cursor::new(bytes));
    let mut reader = decoder.read_info().expect("a PNG");
    let mut buf = vec![0; reader.output_buffer_size().unwrap()];
    let info = reader.next_frame(&mut buf).expect("its pixels");
    assert_eq!(info.color_type, png::ColorType::Rgb);
    buf.truncate(info.buffer_size());
    (info.width, info.height, buf)
}

/// `simulate --heatmap`: the year of the controller's power hour by hour as a PNG whose
/// bytes are the library's drawing of the same year, and each of whose 8760 cells, found by
/// the hour's date and hour in the hourly CSV, reads back that hour's power (the sum of its
/// `power_w:*` columns) within half a colour bin; a zone's daylight as an SVG; a zone the
/// basis lacks refused before the weather is even read, nothing written; a picture of another
/// extension, and `--heatmap-of` without `--heatmap`, refused.
#[test]
fn a_year_as_heat_maps() {
    let dir = common::scratch("simulate-heatmap");
    let (bytes, basis) = daylit_basis(&dir);
    let controller = write_controller(&dir.join("controller.toml"), &controller_text(100.0, ""));
    let weather = weather_year();
    let args = |extra: &[&str]| {
        let mut a = vec![
            "simulate".to_owned(),
            basis.to_str().unwrap().to_owned(),
            "--weather".to_owned(),
            weather.to_str().unwrap().to_owned(),
            "--controller".to_owned(),
            controller.to_str().unwrap().to_owned(),
        ];
        a.extend(extra.iter().map(|s| s.to_string()));
        a
    };
    let run = |extra: &[&str]| {
        let a = args(extra);
        common::run(&a.iter().map(String::as_str).collect::<Vec<_>>())
    };
    let (png_path, hourly) = (dir.join("power.png"), dir.join("hours.csv"));
    let o = run(&[
        "--hourly",
        hourly.to_str().unwrap(),
        "--heatmap",
        png_path.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", common::stderr(&o));
    let file = std::fs::read(&png_path).expect("the heat map");
    let (width, height, pixels) = decode_png(&file);
    assert!(width > 1095 && height > 288, "{width} × {height}");

    // The library's drawing of the same year: the same bytes, and where its cells lie.
    let quantity = cli::HeatMapQuantity::Power;
    let request = cli::SimulateRequest {
        basis: &basis,
        skies: cli::Skies::Weather {
            path: &weather,
            year: None,
            source: simulate::SkySource::Illuminance,
        },
        controller: &controller,
        heatmap: Some(&quantity),
    };
    let map = cli::simulate(&request, &bytes).unwrap().heatmap.unwrap();
    let (drawn, frame) = map.png().unwrap();
    assert_eq!(drawn, file, "the CLI's file is the library's drawing");
    // The TMY's first record is of 1988, a leap year, and the typical year has no
    // 29 February: its records are placed in 1987, every cell of the year drawn.
    assert_eq!(map.days(), 365);
    let grey = (0..365)
        .flat_map(|d| (0..24).map(move |h| (d, h)))
        .filter(|&(d, h)| {
            let (c, r) = frame.pixel(d as f64 + 0.5, h as f64 + 0.5);
            let k = (r as usize * width as usize + c as usize) * 3;
            pixels[k..k + 3] == picture::colour::NO_VALUE
        })
        .count();
    assert_eq!(grey, 0);

    let text = std::fs::read_to_string(&hourly).unwrap();
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let power: Vec<usize> = (0..header.len())
        .filter(|&k| header[k].starts_with("power_w:"))
        .collect();
    assert_eq!(power.len(), 1);
    let date = |t: &str| chrono::NaiveDate::parse_from_str(&t[..10], "%Y-%m-%d").unwrap();
    let first = date(&text.lines().nth(1).unwrap()[..10]);
    // The CSV's powers are rounded to 1e-3 W.
    let half = map.scale.bin_width() / 2.0 + 1e-3;
    let mut hours = 0;
    for line in lines {
        let fields: Vec<&str> = line.split(',').collect();
        let day = (date(fields[0]) - first).num_days() as f64;
        let hour: f64 = fields[0][11..13].parse().unwrap();
        let watts: f64 = power
            .iter()
            .map(|&k| fields[k].parse::<f64>().unwrap())
            .sum();
        let (c, r) = frame.pixel(day + 0.5, hour + 0.5);
        let k = (r as usize * width as usize + c as usize) * 3;
        let rgb = [pixels[k], pixels[k + 1], pixels[k + 2]];
        let back = map.scale.value_of(rgb).expect("a colour of the scale");
        assert!(
            (back - watts).abs() <= half,
            "{}: {watts} W drawn as {back} W",
            fields[0]
        );
        hours += 1;
    }
    assert_eq!(hours, 8760);

    // A zone's daylight, as SVG.
    let svg_path = dir.join("daylight.svg");
    let o = run(&[
        "--heatmap-of",
        "daylight:work_plane",
        "--heatmap",
        svg_path.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", common::stderr(&o));
    let svg = std::fs::read_to_string(&svg_path).expect("the daylight heat map");
    assert!(svg.starts_with("<svg ") && svg.trim_end().ends_with("</svg>"));
    for text in [
        "room.basis: daylight on zone work_plane",
        "\nlux\n",
        "\nJul\n",
    ] {
        assert!(svg.contains(text), "{text} not in the SVG");
    }

    // A zone the basis lacks: refused before the weather is read (this one does not exist).
    let never = dir.join("never.png");
    let missing = dir.join("no-such-weather.epw");
    let o = common::run(&[
        "simulate",
        basis.to_str().unwrap(),
        "--weather",
        missing.to_str().unwrap(),
        "--controller",
        controller.to_str().unwrap(),
        "--heatmap-of",
        "daylight:desks",
        "--heatmap",
        never.to_str().unwrap(),
    ]);
    assert!(!o.status.success());
    let e = common::stderr(&o);
    assert!(
        e.contains("--heatmap-of daylight:desks")
            && e.contains("no zone `desks`")
            && e.contains("work_plane"),
        "{e}"
    );
    assert!(!never.exists());
    // Another extension, and a quantity without a file.
    let o = run(&["--heatmap", dir.join("map.jpg").to_str().unwrap()]);
    assert!(!o.status.success());
    assert!(common::stderr(&o).contains(".png or .svg"));
    let o = run(&["--heatmap-of", "power"]);
    assert!(!o.status.success());
    assert!(common::stderr(&o).contains("--heatmap"));
    assert!(!dir.join("map.jpg").exists());
}
