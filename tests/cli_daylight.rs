//! `eigenrad solve --time ... <sky>` end to end: daylight and electric light reported apart
//! and together, each exactly what its own solve gives; daylight linear in the sky's
//! illuminance; an overcast sky's daylight independent of the time; the site's UTC offset for
//! times given without one; dawn and night the sky's light or none, never an error; every bad
//! combination an error naming the flag or the file.
//!
//! The readings are taken in-process through `cli::solve_with_daylight` (the code behind
//! `eigenrad solve`, optimised as tests are) and turned into the JSON document `--json`
//! prints; the flags themselves, the text readout and the errors through the binary.

mod common;

use std::path::{Path, PathBuf};

use common::{daylit_room, run, scratch, stderr, VIENNA};
use eigenrad_precompute::cli::{self, DaylightArgs, LevelArgs, SkyInput, Units};
use eigenrad_precompute::formfactor::FormFactorOptions;
use serde_json::Value;

fn scene_file(test: &str, site: &str) -> (PathBuf, PathBuf) {
    let dir = scratch(test);
    let path = dir.join("daylit.toml");
    std::fs::write(&path, daylit_room(site)).expect("write scene");
    (dir, path)
}

/// The traditional CIE overcast sky (`--cie overcast --dhi-lux LUX`).
fn overcast(diffuse_horizontal: f64) -> SkyInput {
    SkyInput::Cie {
        sky_type: 0,
        diffuse_horizontal,
        direct_normal: 0.0,
    }
}

/// The readout of `eigenrad solve SCENE [--level ...] [--time TIME <sky>] --json`, with the
/// form factors computed afresh (`--no-cache`).
fn solve_in(scene: &Path, sky: Option<(&str, SkyInput)>, levels: &[&str], units: Units) -> Value {
    let daylight = sky.map(|(time, input)| DaylightArgs {
        time: time.to_owned(),
        input,
        water: 2.0,
        subdivision: 1,
    });
    let levels = LevelArgs {
        levels: levels.iter().map(|l| (*l).to_owned()).collect(),
        arcs: Vec::new(),
    };
    let ff = FormFactorOptions {
        cache: None,
        ..FormFactorOptions::default()
    };
    let readout =
        cli::solve_with_daylight(scene, &levels, daylight.as_ref(), false, &ff).expect("solve");
    let readout = cli::units::readout_in(readout, units).expect("units");
    serde_json::to_value(&readout).expect("JSON")
}

fn solve(scene: &Path, sky: Option<(&str, SkyInput)>, levels: &[&str]) -> Value {
    solve_in(scene, sky, levels, Units::Native)
}

/// `(name, total, daylight, electric)` of every sensor and zone (one band).
fn readings(v: &Value) -> Vec<(String, f64, Option<f64>, Option<f64>)> {
    let one = |x: &Value| x.as_array().map(|a| a[0].as_f64().unwrap());
    v["sensors"]
        .as_array()
        .unwrap()
        .iter()
        .chain(v["zones"].as_array().unwrap())
        .map(|r| {
            (
                r["name"].as_str().unwrap().to_owned(),
                r["irradiance"][0].as_f64().unwrap(),
                one(&r["daylight"]),
                one(&r["electric"]),
            )
        })
        .collect()
}

fn close(a: f64, b: f64, tolerance: f64) -> bool {
    (a - b).abs() <= tolerance * a.abs().max(b.abs()).max(1e-12)
}

const NOON: &str = "2026-06-21T12:00+02:00";

/// With a sky, each reading is its daylight plus its electric part (1e-12, rounding); the
/// electric part is the reading without a sky (1e-9: the same factorisation, another
/// right-hand side), and the daylight part what the lamp switched off leaves; daylight
/// reaches every reading of a room with a window.
#[test]
fn daylight_and_electric_add_up() {
    let (_dir, path) = scene_file("add-up", VIENNA);
    let sky = Some((NOON, overcast(10_000.0)));
    let both = solve(&path, sky, &[]);
    let dark = solve(&path, sky, &["lamp=0"]);
    let night = solve(&path, None, &[]);
    let with = readings(&both);
    assert_eq!(with.len(), 3);
    for (((name, total, day, electric), lamp_off), no_sky) in
        with.iter().zip(readings(&dark)).zip(readings(&night))
    {
        let (day, electric) = (day.unwrap(), electric.unwrap());
        assert!(close(*total, day + electric, 1e-12), "{name}");
        assert!(
            close(electric, no_sky.1, 1e-9),
            "{name}: {electric} vs {}",
            no_sky.1
        );
        assert!(
            no_sky.2.is_none() && no_sky.3.is_none(),
            "{name}: no sky, no parts"
        );
        assert!(
            close(day, lamp_off.1, 1e-9),
            "{name}: {day} vs {}",
            lamp_off.1
        );
        assert!(lamp_off.3.unwrap() == 0.0, "{name}: lamp off");
        assert!(day > 0.0, "{name}: no daylight");
    }
    let d = &both["daylight"];
    assert_eq!(d["model"], "CIE traditional overcast");
    assert_eq!(d["patch_count"], 145);
    assert_eq!(d["windows"][0], "window");
    // The grids under daylight alone are the lamp-off grids.
    let day_grid = &d["grids"][0]["points"];
    let off_grid = &dark["grids"][0]["points"];
    let n = day_grid.as_array().unwrap().len();
    assert!(n > 0);
    for i in 0..n {
        let a = day_grid[i]["irradiance"][0].as_f64().unwrap();
        let b = off_grid[i]["irradiance"][0].as_f64().unwrap();
        assert!(close(a, b, 1e-9), "grid point {i}: {a} vs {b}");
    }
}

/// Light is linear in the sky: twice the diffuse horizontal illuminance, twice the daylight
/// (1e-9). The traditional overcast sky does not depend on the sun, and without --dni-lux
/// there is no sun: another time of day gives the same daylight (1e-9).
#[test]
fn daylight_is_linear_and_overcast_ignores_the_time() {
    let (_dir, path) = scene_file("linear", VIENNA);
    let base = readings(&solve(&path, Some((NOON, overcast(10_000.0))), &[]));
    let double = readings(&solve(&path, Some((NOON, overcast(20_000.0))), &[]));
    let evening = readings(&solve(
        &path,
        Some(("2026-06-21T18:30+02:00", overcast(10_000.0))),
        &[],
    ));
    for ((a, b), c) in base.iter().zip(&double).zip(&evening) {
        assert!(close(2.0 * a.2.unwrap(), b.2.unwrap(), 1e-9), "{}", a.0);
        assert!(close(a.2.unwrap(), c.2.unwrap(), 1e-9), "{}", a.0);
    }
}

/// A time without its offset takes the site's `utc_offset` (+01:00 here): 11:00 then is
/// 11:00+01:00, not 11:00 UTC. A clear sky with the sun tells the two apart.
#[test]
fn a_time_without_offset_takes_the_sites() {
    let (_dir, path) = scene_file("offset", VIENNA);
    let clear = SkyInput::Cie {
        sky_type: 12,
        diffuse_horizontal: 15_000.0,
        direct_normal: 70_000.0,
    };
    let at = |time: &str| solve(&path, Some((time, clear)), &[]);
    let bare = at("2026-06-21T11:00");
    let explicit = at("2026-06-21T11:00+01:00");
    let utc = at("2026-06-21T11:00Z");
    assert_eq!(bare["daylight"]["time"], explicit["daylight"]["time"]);
    assert_eq!(bare["daylight"]["sun"], explicit["daylight"]["sun"]);
    assert_ne!(bare["daylight"]["sun"], utc["daylight"]["sun"]);
    for (a, b) in readings(&bare).iter().zip(readings(&explicit)) {
        assert_eq!(a.1, b.1, "{}", a.0);
    }
    // Without a site offset, a bare time is an error naming --time.
    let (_dir2, no_offset) = scene_file("no-offset", "[site]\nlatitude = 48.21\nlongitude = 16.37");
    let o = run(&[
        "solve",
        no_offset.to_str().unwrap(),
        "--no-cache",
        "--time",
        "2026-06-21T11:00",
        "--cie",
        "overcast",
        "--dhi-lux",
        "10000",
    ]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("--time") && stderr(&o).contains("offset"),
        "{}",
        stderr(&o)
    );
}

/// The text readout shows each reading's two parts; footcandles convert them too;
/// the grid CSV gets a daylight column after the total.
#[test]
fn text_units_and_csv_carry_the_parts() {
    let (_dir, path) = scene_file("text", VIENNA);
    let sky = Some((NOON, overcast(10_000.0)));
    let lux = solve(&path, sky, &[]);
    let fc = solve_in(&path, sky, &[], Units::Footcandles);
    assert_eq!(fc["unit"], "fc");
    let lux_per_fc = 1.0 / (0.3048 * 0.3048);
    for (a, b) in readings(&lux).iter().zip(readings(&fc)) {
        assert!(
            close(a.2.unwrap(), b.2.unwrap() * lux_per_fc, 1e-12),
            "{}",
            a.0
        );
        assert!(
            close(a.3.unwrap(), b.3.unwrap() * lux_per_fc, 1e-12),
            "{}",
            a.0
        );
    }
    let fc_grid = &fc["daylight"]["grids"][0]["points"][0]["irradiance"][0];
    let lux_grid = &lux["daylight"]["grids"][0]["points"][0]["irradiance"][0];
    assert!(close(
        lux_grid.as_f64().unwrap(),
        fc_grid.as_f64().unwrap() * lux_per_fc,
        1e-12
    ));

    let readout: cli::Readout = {
        let ff = FormFactorOptions {
            cache: None,
            ..FormFactorOptions::default()
        };
        let args = DaylightArgs {
            time: NOON.to_owned(),
            input: overcast(10_000.0),
            water: 2.0,
            subdivision: 1,
        };
        cli::solve_with_daylight(&path, &LevelArgs::default(), Some(&args), false, &ff)
            .expect("solve")
    };
    let text = cli::format_readout(&readout);
    assert!(
        text.contains("daylight: CIE traditional overcast"),
        "{text}"
    );
    assert!(
        text.contains("= daylight ") && text.contains(" + electric "),
        "{text}"
    );
    assert!(text.contains("under daylight alone:"), "{text}");
    // Every lamp is off: the electric parts are 0 up to rounding, never shown as `-0.0000`.
    assert!(
        !text.contains("-0.0000") && !text.contains(" -0 "),
        "a negative zero in: {text}"
    );
    let table = cli::grids_csv(&readout);
    let mut lines = table.lines();
    assert_eq!(
        lines.next(),
        Some("zone,point,x_m,y_m,z_m,photopic_lux,daylight_photopic_lux")
    );
    let day = &readout.daylight.as_ref().expect("daylight").grids[0].points;
    let rows: Vec<&str> = lines.collect();
    assert_eq!(rows.len(), day.len());
    for (row, p) in rows.iter().zip(day) {
        let last: f64 = row.rsplit(',').next().unwrap().parse().unwrap();
        assert_eq!(last, p.irradiance[0], "{row}");
    }
}

/// Every bad combination is an error (status 1, never a panic) naming what is wrong: no
/// `[site]`, a time without a sky, a sky without a time. (The sun below the horizon is not
/// one: [`dawn_and_night_are_the_skys_light_or_none`].)
#[test]
fn bad_daylight_requests_are_errors() {
    let (_dir, path) = scene_file("errors", VIENNA);
    let (_dir2, siteless) = scene_file("siteless", "");
    let p = path.to_str().unwrap();
    let s = siteless.to_str().unwrap();
    for (args, needle) in [
        (
            vec![
                "solve",
                s,
                "--time",
                NOON,
                "--cie",
                "overcast",
                "--dhi-lux",
                "1e4",
            ],
            "[site]",
        ),
        (vec!["solve", p, "--time", NOON], "--time needs a sky"),
        (
            vec!["solve", p, "--cie", "overcast", "--dhi-lux", "1e4"],
            "needs --time",
        ),
        (
            vec!["solve", p, "--time", NOON, "--cie", "overcast"],
            "--dhi-lux",
        ),
        (
            vec!["solve", p, "--time", NOON, "--dni", "700", "--dhi", "-3"],
            "--dhi",
        ),
    ] {
        let mut args = args.clone();
        args.push("--no-cache");
        let o = run(&args);
        assert_ne!(
            o.status.code(),
            Some(101),
            "{args:?} panicked: {}",
            stderr(&o)
        );
        assert!(!o.status.success(), "{args:?}");
        assert!(stderr(&o).contains(needle), "{args:?}: {}", stderr(&o));
    }
}

/// `(name, daylight)` of every sensor and zone in the JSON of `solve --json` or
/// `eval --json` with a sky.
fn daylight_parts(v: &Value) -> Vec<(String, f64)> {
    readings(v)
        .into_iter()
        .map(|(name, _, day, _)| (name, day.expect("a daylight part")))
        .collect()
}

/// The JSON `eigenrad ARGS --json` prints, after checking that it ran (status 0).
fn json_of(args: &[&str]) -> Value {
    let mut args = args.to_vec();
    args.push("--json");
    let o = run(&args);
    assert!(o.status.success(), "{args:?}: {}", stderr(&o));
    serde_json::from_slice(&o.stdout).expect("JSON")
}

/// Before sunrise (Vienna, 21 June 04:30+02:00: the sun 3.9° below the horizon) a clear sky
/// of 3000 lux diffuse lights the room through its window and `solve --time` says so (status
/// 0): daylight above 0 at every sensor and zone, the sun below the horizon in the readout,
/// no direct light, the 500 lux direct normal given dropped with a note. At midnight a
/// diffuse of 0 is a dark sky (the Perez sky of `--dni 0 --dhi 0`, and the CIE sky of
/// `--dhi-lux 0 --dni-lux 0`): every daylight part 0, status 0. The text readout says the
/// sun is below the horizon and carries the note.
#[test]
fn dawn_and_night_are_the_skys_light_or_none() {
    let (_dir, path) = scene_file("dawn", VIENNA);
    let p = path.to_str().unwrap();
    let dawn = [
        "solve",
        p,
        "--no-cache",
        "--time",
        "2026-06-21T04:30+02:00",
        "--cie",
        "12",
        "--dhi-lux",
        "3000",
        "--dni-lux",
        "500",
    ];
    let v = json_of(&dawn);
    let d = &v["daylight"];
    assert!(d["sun"]["altitude"].as_f64().unwrap() < 0.0, "{d}");
    assert_eq!(d["sun_below_horizon"], true);
    assert_eq!(d["direct_normal_lux"], 0.0);
    assert_eq!(d["global_horizontal_lux"], 3000.0);
    let notes = d["notes"].as_array().unwrap();
    assert!(
        notes.len() == 1 && notes[0].as_str().unwrap().contains("500 lux"),
        "{notes:?}"
    );
    for (name, day) in daylight_parts(&v) {
        assert!(day > 0.0, "{name}: daylight {day} before sunrise");
    }
    let text = run(&dawn);
    let out = String::from_utf8_lossy(&text.stdout);
    assert!(text.status.success(), "{}", stderr(&text));
    assert!(
        out.contains("the sun is below the horizon") && out.contains("note: "),
        "{out}"
    );

    for sky in [
        &["--dni", "0", "--dhi", "0"][..],
        &["--cie", "12", "--dhi-lux", "0", "--dni-lux", "0"][..],
    ] {
        let mut night = vec!["solve", p, "--no-cache", "--time", "2026-06-22T00:00+02:00"];
        night.extend_from_slice(sky);
        let v = json_of(&night);
        assert_eq!(v["daylight"]["sun_below_horizon"], true);
        for (name, day) in daylight_parts(&v) {
            assert_eq!(day, 0.0, "{sky:?} {name}: daylight at midnight");
        }
    }
}
