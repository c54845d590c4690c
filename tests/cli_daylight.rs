//! `eigenrad solve --time ... <sky>` end to end: daylight and electric light reported apart
//! and together, each exactly what its own solve gives; daylight linear in the sky's
//! illuminance; an overcast sky's daylight independent of the time; the site's UTC offset for
//! times given without one; every bad combination an error naming the flag or the file.

mod common;

use std::path::{Path, PathBuf};

use common::{run, scratch, stderr};
use serde_json::Value;

/// A 4 × 3 × 2.8 m room with a 2 × 1.3 m clear window in its y = 0 wall (facing south at
/// `north = 0`), a flush ceiling lamp (channel `lamp`), a desk sensor, a ceiling photocell and
/// a work plane; meshed coarsely (0.7 m) so that each solve takes a fraction of a second.
fn daylit_room(site: &str) -> String {
    format!(
        r#"[scene]
name = "daylit"
bands = "photopic"
unit = "m"
max_edge = 0.7

{site}

[materials]
floor = {{ reflectance = 0.2 }}
wall = {{ reflectance = 0.5 }}
ceiling = {{ reflectance = 0.7 }}
glass = {{ reflectance = 0.0, transmittance = 0.7 }}
lamp = {{ reflectance = 0.0 }}

[[room]]
name = "room"
min = [0, 0, 0]
max = [4, 3, 2.8]
material = "wall"
floor = "floor"
ceiling = "ceiling"
openings = ["window", "lamp"]

[[quad]]
name = "window"
material = "glass"
corners = [[1, 0, 0.9], [1, 0, 2.2], [3, 0, 2.2], [3, 0, 0.9]]

[[quad]]
name = "lamp"
material = "lamp"
corners = [[1.7, 1.2, 2.8], [1.7, 1.8, 2.8], [2.3, 1.8, 2.8], [2.3, 1.2, 2.8]]

[[channel]]
name = "lamp"
surfaces = ["lamp"]
flux = 2000

[[sensor]]
name = "desk"
position = [2, 1.5, 0.8]
normal = [0, 0, 1]

[[sensor]]
name = "photocell"
position = [2, 2.5, 2.79]
normal = [0, 0, -1]
half_angle = 45

[[zone]]
name = "work_plane"
work_plane = {{ room = "room", height = 0.8, margin = 0.5, max_edge = 0.7 }}
"#
    )
}

const VIENNA: &str = r#"[site]
latitude = 48.21
longitude = 16.37
north = 0
ground_reflectance = 0.2
utc_offset = "+01:00""#;

fn scene_file(test: &str, site: &str) -> (PathBuf, PathBuf) {
    let dir = scratch(test);
    let path = dir.join("daylit.toml");
    std::fs::write(&path, daylit_room(site)).expect("write scene");
    (dir, path)
}

fn solve(scene: &Path, extra: &[&str]) -> Value {
    let mut args = vec!["solve", scene.to_str().unwrap(), "--no-cache", "--json"];
    args.extend_from_slice(extra);
    let o = run(&args);
    assert!(o.status.success(), "{extra:?}: {}", stderr(&o));
    serde_json::from_slice(&o.stdout).expect("JSON readout")
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
const OVERCAST: [&str; 4] = ["--cie", "overcast", "--dhi-lux", "10000"];

/// With a sky, each reading is its daylight plus its electric part (1e-12, rounding); the
/// electric part is the reading without a sky (1e-9: the same factorisation, another
/// right-hand side), and the daylight part what the lamp switched off leaves; daylight
/// reaches every reading of a room with a window.
#[test]
fn daylight_and_electric_add_up() {
    let (_dir, path) = scene_file("add-up", VIENNA);
    let mut args = vec!["--time", NOON];
    args.extend_from_slice(&OVERCAST);
    let both = solve(&path, &args);
    let dark = {
        let mut a = args.clone();
        a.extend_from_slice(&["--level", "lamp=0"]);
        solve(&path, &a)
    };
    let night = solve(&path, &[]);
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
    let base = readings(&solve(
        &path,
        &["--time", NOON, "--cie", "overcast", "--dhi-lux", "10000"],
    ));
    let double = readings(&solve(
        &path,
        &["--time", NOON, "--cie", "overcast", "--dhi-lux", "20000"],
    ));
    let evening = readings(&solve(
        &path,
        &[
            "--time",
            "2026-06-21T18:30+02:00",
            "--cie",
            "overcast",
            "--dhi-lux",
            "10000",
        ],
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
    let sky = ["--cie", "12", "--dhi-lux", "15000", "--dni-lux", "70000"];
    let at = |time: &str| {
        let mut a = vec!["--time", time];
        a.extend_from_slice(&sky);
        solve(&path, &a)
    };
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

/// The text readout shows each reading's two parts; footcandles convert them too; the grid
/// CSV gets a daylight column after the total.
#[test]
fn text_units_and_csv_carry_the_parts() {
    let (dir, path) = scene_file("text", VIENNA);
    let mut args = vec![
        "solve",
        path.to_str().unwrap(),
        "--no-cache",
        "--time",
        NOON,
    ];
    args.extend_from_slice(&OVERCAST);
    let o = run(&args);
    assert!(o.status.success(), "{}", stderr(&o));
    let text = String::from_utf8_lossy(&o.stdout).into_owned();
    assert!(
        text.contains("daylight: CIE traditional overcast"),
        "{text}"
    );
    assert!(
        text.contains("= daylight ") && text.contains(" + electric "),
        "{text}"
    );
    assert!(text.contains("under daylight alone:"), "{text}");

    let lux = solve(
        &path,
        &["--time", NOON, "--cie", "overcast", "--dhi-lux", "10000"],
    );
    let fc = solve(
        &path,
        &[
            "--time",
            NOON,
            "--cie",
            "overcast",
            "--dhi-lux",
            "10000",
            "--units",
            "fc",
        ],
    );
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

    let csv = dir.join("grid.csv");
    let mut args = vec![
        "solve",
        path.to_str().unwrap(),
        "--no-cache",
        "--time",
        NOON,
        "--csv",
        csv.to_str().unwrap(),
        "--json",
    ];
    args.extend_from_slice(&OVERCAST);
    let o = run(&args);
    assert!(o.status.success(), "{}", stderr(&o));
    let v: Value = serde_json::from_slice(&o.stdout).unwrap();
    let table = std::fs::read_to_string(&csv).unwrap();
    let mut lines = table.lines();
    assert_eq!(
        lines.next(),
        Some("zone,point,x_m,y_m,z_m,photopic_lux,daylight_photopic_lux")
    );
    let day_points = v["daylight"]["grids"][0]["points"].as_array().unwrap();
    let rows: Vec<&str> = lines.collect();
    assert_eq!(rows.len(), day_points.len());
    for (row, p) in rows.iter().zip(day_points) {
        // serde_json's parsing of floats is within an ulp, not always the nearest.
        let last: f64 = row.rsplit(',').next().unwrap().parse().unwrap();
        assert!(
            close(last, p["irradiance"][0].as_f64().unwrap(), 1e-15),
            "{row}"
        );
    }
}

/// Every bad combination is an error (status 1, never a panic) naming what is wrong: no
/// `[site]`, a time without a sky, a sky without a time, the sun below the horizon.
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
            vec![
                "solve",
                p,
                "--time",
                "2026-12-21T23:00+01:00",
                "--cie",
                "overcast",
                "--dhi-lux",
                "1e4",
            ],
            "below the horizon",
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
