//! `eigenrad sky` end to end: its JSON against closed forms, the sky before sunrise and at
//! night, every bad flag an error naming it (never a panic), a closed pipe ending quietly.

mod common;

use std::process::Stdio;

use common::{run, stderr};

const VIENNA: [&str; 6] = ["sky", "--lat", "48.2", "--lon", "16.4", "--time"];

fn sky(extra: &[&str]) -> std::process::Output {
    let mut args: Vec<&str> = VIENNA.to_vec();
    args.push("2026-06-21T12:00+02:00");
    args.extend_from_slice(extra);
    run(&args)
}

/// A uniform sky (CIE type 5) of 10 000 lux has luminance E/π everywhere (the cosine law),
/// so every patch reads 10 000/π cd/m² (f32, 10⁻⁵); the 145 Tregenza solid angles add up to
/// 2π sr; the sun's direction in scene axes is a unit vector turned by `--north` about z.
#[test]
fn uniform_sky_json() {
    let o = sky(&[
        "--cie",
        "5",
        "--dhi-lux",
        "10000",
        "--north",
        "90",
        "--json",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).expect("JSON");
    let patches = v["patches"].as_array().expect("patches");
    assert_eq!(patches.len(), 145);
    let l = 10_000.0 / std::f64::consts::PI;
    let mut omega = 0.0;
    for p in patches {
        let lp = p["luminance_cd_m2"].as_f64().unwrap();
        assert!((lp - l).abs() <= 1e-5 * l, "{lp} against {l}");
        omega += p["solid_angle_sr"].as_f64().unwrap();
    }
    assert!((omega - 2.0 * std::f64::consts::PI).abs() < 1e-4);
    let zl = v["zenith_luminance_cd_m2"].as_f64().unwrap();
    assert!((zl - l).abs() <= 1e-5 * l);
    // North = 90: the scene's +y points east, so the sun (south-east, azimuth A) has scene
    // components (sin(A − 90°) cos h, cos(A − 90°) cos h, sin h).
    let (h, a) = (
        v["sun"]["altitude"].as_f64().unwrap().to_radians(),
        v["sun"]["azimuth"].as_f64().unwrap().to_radians(),
    );
    let d: Vec<f64> = v["sun_direction_room"]
        .as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect();
    let want = [
        (a - std::f64::consts::FRAC_PI_2).sin() * h.cos(),
        (a - std::f64::consts::FRAC_PI_2).cos() * h.cos(),
        h.sin(),
    ];
    for (x, y) in d.iter().zip(want) {
        assert!((x - y).abs() < 1e-9);
    }
}

/// A CIE sky with a sun: the direct horizontal illuminance is the direct normal one times
/// the sine of the sun's altitude, and the global one adds the diffuse.
#[test]
fn cie_sky_with_the_sun() {
    let o = sky(&[
        "--cie",
        "12",
        "--dhi-lux",
        "15000",
        "--dni-lux",
        "80000",
        "--json",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).expect("JSON");
    let h = v["sun"]["altitude"].as_f64().unwrap().to_radians();
    let direct = v["direct_horizontal_lux"].as_f64().unwrap();
    assert!((direct - 80_000.0 * h.sin()).abs() < 1e-6 * direct);
    let global = v["global_horizontal_lux"].as_f64().unwrap();
    assert!((global - 15_000.0 - direct).abs() < 1e-6 * global);
}

/// Before sunrise (04:30+02:00 on 21 June in Vienna, the sun 3.9° below the horizon) the
/// Perez sky of 20 W/m² diffuse is its diffuse light alone: status 0, the sun below the
/// horizon in the JSON, no direct light (the 50 W/m² given dropped, a note saying so), the
/// patches lit; the text says so too. At midnight a diffuse of 0 is a dark sky.
#[test]
fn before_sunrise_and_at_night() {
    let mut args: Vec<&str> = VIENNA.to_vec();
    args.extend_from_slice(&["2026-06-21T04:30+02:00", "--dni", "50", "--dhi", "20"]);
    let text = run(&args);
    assert!(text.status.success(), "{}", stderr(&text));
    let out = String::from_utf8_lossy(&text.stdout);
    assert!(
        out.contains("sun below the horizon") && out.contains("50 W/m²"),
        "{out}"
    );
    args.push("--json");
    let o = run(&args);
    assert!(o.status.success(), "{}", stderr(&o));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).expect("JSON");
    assert!(v["sun"]["altitude"].as_f64().unwrap() < 0.0);
    assert_eq!(v["sun_below_horizon"], true);
    assert_eq!(v["direct_normal_lux"], 0.0);
    assert_eq!(v["perez"]["direct_normal_w_m2"], 0.0);
    assert_eq!(v["notes"].as_array().unwrap().len(), 1);
    let diffuse = v["diffuse_horizontal_lux"].as_f64().unwrap();
    assert!(diffuse > 0.0);
    assert_eq!(v["global_horizontal_lux"].as_f64().unwrap(), diffuse);
    let patches = v["patches"].as_array().unwrap();
    assert!(patches
        .iter()
        .all(|p| p["luminance_cd_m2"].as_f64().unwrap() > 0.0));

    let mut args: Vec<&str> = VIENNA.to_vec();
    args.extend_from_slice(&["2026-06-22T00:00+02:00", "--dni-lux", "0", "--dhi-lux", "0"]);
    args.push("--json");
    let o = run(&args);
    assert!(o.status.success(), "{}", stderr(&o));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).expect("JSON");
    assert_eq!(v["sun_below_horizon"], true);
    assert!(v["patches"]
        .as_array()
        .unwrap()
        .iter()
        .all(|p| p["luminance_cd_m2"].as_f64().unwrap() == 0.0));
    assert_eq!(v["global_horizontal_lux"], 0.0);
}

/// The overcast types (1 to 5, and the traditional overcast sky) take no sun unless given
/// one; the sunny types (6 to 15) take `--dni-lux 0` for a sky without its sun.
#[test]
fn overcast_skies_need_no_sun_and_sunny_ones_may_have_none() {
    for extra in [
        &["--cie", "overcast", "--dhi-lux", "100"][..],
        &["--cie", "5", "--dhi-lux", "100"][..],
        &["--cie", "15", "--dhi-lux", "100", "--dni-lux", "0"][..],
    ] {
        let mut args = extra.to_vec();
        args.push("--json");
        let o = sky(&args);
        assert!(o.status.success(), "{extra:?}: {}", stderr(&o));
        let v: serde_json::Value = serde_json::from_slice(&o.stdout).expect("JSON");
        assert_eq!(v["direct_normal_lux"], 0.0, "{extra:?}");
    }
}

#[test]
fn bad_flags_are_errors_naming_them() {
    for (extra, flag) in [
        (vec!["--dni", "700", "--dhi", "-1"], "--dhi"),
        (vec!["--dni", "-700", "--dhi", "100"], "--dni"),
        (vec!["--cie", "16", "--dhi-lux", "100"], "--cie"),
        (vec!["--cie", "3"], "--dhi-lux"),
        // A sky with a sun (types 6 to 15) needs its direct light.
        (vec!["--cie", "6", "--dhi-lux", "100"], "--dni-lux"),
        (vec!["--cie", "12", "--dhi-lux", "10000"], "--dni-lux"),
        (vec!["--cie", "3", "--dhi-lux", "100", "--mf", "0"], "--mf"),
        (
            vec!["--cie", "3", "--dhi-lux", "100", "--north", "nan"],
            "--north",
        ),
        (vec!["--dni-lux", "100", "--dhi-lux", "1e9"], "--dhi-lux"),
    ] {
        let o = sky(&extra);
        assert_ne!(
            o.status.code(),
            Some(101),
            "{extra:?} panicked: {}",
            stderr(&o)
        );
        assert!(!o.status.success(), "{extra:?}");
        assert!(stderr(&o).contains(flag), "{extra:?}: {}", stderr(&o));
    }
    let mut args: Vec<&str> = VIENNA.to_vec();
    args.extend_from_slice(&["2026-06-21 12:00", "--cie", "3", "--dhi-lux", "100"]);
    let o = run(&args);
    assert_eq!(o.status.code(), Some(1));
    assert!(stderr(&o).contains("--time"), "{}", stderr(&o));
    let o = run(&[
        "sky",
        "--lat",
        "91",
        "--lon",
        "0",
        "--time",
        "2026-06-21T12:00Z",
        "--cie",
        "3",
        "--dhi-lux",
        "100",
    ]);
    assert_eq!(o.status.code(), Some(1));
    assert!(stderr(&o).contains("--lat"), "{}", stderr(&o));
}

/// 9217 patches of JSON (MF:8) are far more than a pipe's buffer: closing it ends the
/// command with status 141 and nothing on standard error.
#[test]
fn closed_pipe_ends_quietly() {
    let mut args: Vec<&str> = VIENNA.to_vec();
    args.extend_from_slice(&[
        "2026-06-21T12:00+02:00",
        "--cie",
        "12",
        "--dhi-lux",
        "10000",
        "--dni-lux",
        "60000",
        "--mf",
        "8",
        "--json",
    ]);
    let mut child = common::command()
        .args(&args)
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("start eigenrad");
    drop(child.stdout.take());
    let o = child.wait_with_output().expect("wait");
    assert_eq!(o.status.code(), Some(141), "{}", stderr(&o));
    assert!(o.stderr.is_empty(), "{}", stderr(&o));
}
