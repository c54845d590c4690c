//! The `eigenrad` command and its files, run as a user runs it: bad `--level` arguments,
//! unreadable bases, failed and interrupted builds (the previous basis survives, no temporary
//! file is left that could pass for a basis), and open scenes.

mod common;

use std::process::Output;
use std::time::Duration;

use common::{build, good_basis, listing, run, scene, scratch, stderr};

#[test]
fn cli_level_naming_an_unknown_channel_or_not_a_number_fails_and_says_so() {
    let dir = scratch("levels");
    let basis = good_basis(&dir);
    let basis = basis.to_str().expect("utf-8 path");
    let scene = dir.join("scene.toml");
    let scene = scene.to_str().expect("utf-8 path");

    let ok = run(&["eval", basis, "--level", "lamp=0.5"]);
    assert!(ok.status.success(), "eval failed: {}", stderr(&ok));

    for command in ["eval", "solve"] {
        let target = if command == "eval" { basis } else { scene };
        let o = run(&[command, target, "--level", "skylight=0.5"]);
        assert!(!o.status.success(), "{command}: unknown channel accepted");
        let e = stderr(&o);
        assert!(e.contains("skylight"), "{command}: channel not named: {e}");
        assert!(e.contains("no channel named"), "{command}: {e}");
        assert!(e.contains("lamp"), "{command}: channels not listed: {e}");

        let o = run(&[command, target, "--level", "lamp=bright"]);
        assert!(!o.status.success(), "{command}: non-number accepted");
        let e = stderr(&o);
        assert!(e.contains("`bright` is not a number"), "{command}: {e}");

        let o = run(&[command, target, "--level", "lamp"]);
        assert!(!o.status.success(), "{command}: missing value accepted");
        assert!(
            stderr(&o).contains("NAME=VALUE"),
            "{command}: {}",
            stderr(&o)
        );
    }
}

#[test]
fn cli_unreadable_basis_names_the_file_and_the_fault() {
    let dir = scratch("unreadable");
    let good = std::fs::read(good_basis(&dir)).expect("read basis");

    let garbage = dir.join("garbage.basis");
    std::fs::write(&garbage, b"this is not a basis, just some bytes.....").expect("write");
    let truncated = dir.join("truncated.basis");
    std::fs::write(&truncated, &good[..good.len() / 2]).expect("write");
    // Header bytes 8..10 are the format version, little-endian (docs/format.md): a basis
    // that says it is of the older version 1.
    let mut v1 = good.clone();
    v1[8..10].copy_from_slice(&1u16.to_le_bytes());
    let version1 = dir.join("version1.basis");
    std::fs::write(&version1, &v1).expect("write");
    let missing = dir.join("missing.basis");

    for (path, expected) in [
        (&garbage, "magic"),
        (&truncated, "truncated"),
        (&version1, "version 1 is not supported"),
        (&missing, "No such file"),
    ] {
        for command in ["eval", "inspect"] {
            let o = run(&[command, path.to_str().expect("utf-8 path")]);
            assert!(!o.status.success(), "{command} accepted {}", path.display());
            let e = stderr(&o);
            let name = path.file_name().and_then(|n| n.to_str()).expect("name");
            assert!(e.contains(name), "{command}: file not named: {e}");
            assert!(e.contains(expected), "{command}: `{expected}` missing: {e}");
        }
    }
}

#[test]
fn cli_failed_build_leaves_the_previous_basis_untouched() {
    let dir = scratch("failed-build");
    let basis = good_basis(&dir);
    let before = std::fs::read(&basis).expect("read basis");
    let broken = scene(1.0).replace("reflectance = 0.5", "reflectance = 1.5");
    let o = build(&dir, &broken, "good.basis", &[]);
    assert!(!o.status.success(), "broken scene built");
    let e = stderr(&o);
    assert!(
        e.contains("scene.toml") && e.contains("materials.wall.reflectance"),
        "{e}"
    );
    assert_eq!(std::fs::read(&basis).expect("read basis"), before);
    assert_eq!(listing(&dir), ["good.basis", "scene.toml"]);
}

#[test]
fn cli_killed_build_leaves_no_partial_basis_and_no_stray_file() {
    let dir = scratch("killed-build");
    let basis = good_basis(&dir);
    let before = std::fs::read(&basis).expect("read basis");
    // A finer mesh of the same cube (about 2400 patches): several seconds of form factors
    // and eigensolve even in the release profile, killed after 0.5 s.
    let scene_path = dir.join("scene.toml");
    std::fs::write(&scene_path, scene(0.1)).expect("write scene");
    let mut child = common::command()
        .args([
            "build",
            scene_path.to_str().expect("utf-8 path"),
            "-o",
            basis.to_str().expect("utf-8 path"),
        ])
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::null())
        .spawn()
        .expect("start build");
    std::thread::sleep(Duration::from_millis(500));
    let still_running = child.try_wait().expect("poll build").is_none();
    child.kill().expect("SIGKILL the build"); // Child::kill is SIGKILL on Unix
    let _ = child.wait();
    assert!(
        still_running,
        "the build finished before it could be interrupted; make the scene larger"
    );
    assert_eq!(std::fs::read(&basis).expect("read basis"), before);
    assert_eq!(listing(&dir), ["good.basis", "scene.toml"]);
}

#[test]
fn cli_build_removes_temporary_files_of_dead_processes_only() {
    let dir = scratch("stale-temp");
    // A process that has exited: its id names a stale temporary file.
    let mut dead = common::command()
        .arg("--version")
        .stdout(std::process::Stdio::null())
        .spawn()
        .expect("start");
    let dead_pid = dead.id();
    dead.wait().expect("wait");
    let stale = dir.join(format!(".good.basis.{dead_pid}.tmp"));
    std::fs::write(&stale, b"half a basis").expect("write");
    // This test process is alive: its file may be in use and is kept.
    let live = dir.join(format!(".good.basis.{}.tmp", std::process::id()));
    std::fs::write(&live, b"in use").expect("write");
    good_basis(&dir);
    let names = listing(&dir);
    assert!(
        !names.contains(&format!(".good.basis.{dead_pid}.tmp")),
        "{names:?}"
    );
    assert!(
        names.contains(&format!(".good.basis.{}.tmp", std::process::id())),
        "{names:?}"
    );
    assert!(names.contains(&"good.basis".to_string()), "{names:?}");
}

/// The `form_factors` part of a `build --json` report.
fn form_factors(o: &Output) -> serde_json::Value {
    assert!(o.status.success(), "build failed: {}", stderr(o));
    let report: serde_json::Value =
        serde_json::from_slice(&o.stdout).expect("build --json prints one JSON document");
    report["form_factors"].clone()
}

/// How far a form-factor row sum of a closed room may be from 1 (the summation rule): the
/// quadrature's error between adjacent patches of a coarse mesh, 2e-3 measured on this cube,
/// with margin.
const ROW_SUM_TOLERANCE: f64 = 1e-2;

#[test]
fn cli_open_scene_builds_and_reports_open_and_flush_openings_keep_a_room_closed() {
    let dir = scratch("open");
    // The cube with a flush opening: every patch sees the whole room, so every row sums to 1.
    let ff = form_factors(&build(&dir, &scene(1.0), "closed.basis", &["--json"]));
    let (min, max) = (
        ff["row_sum_min"].as_f64().expect("row_sum_min"),
        ff["row_sum_max"].as_f64().expect("row_sum_max"),
    );
    assert!(
        (min - 1.0).abs() <= ROW_SUM_TOLERANCE && (max - 1.0).abs() <= ROW_SUM_TOLERANCE,
        "row sums {min} .. {max}"
    );
    // The same luminaire floating 2 cm below the ceiling instead: the ceiling patches behind
    // it see its back, and their rows fall short by the part it hides.
    let floating = scene(1.0)
        .replace("openings = [\"lamp\"]\n", "")
        .replace("0.7, 2]", "0.7, 1.98]")
        .replace("1.3, 2]", "1.3, 1.98]");
    let ff = form_factors(&build(&dir, &floating, "floating.basis", &["--json"]));
    let hidden = ff["row_sum_min"].as_f64().expect("row_sum_min");
    assert!(
        hidden < 1.0 - 5.0 * ROW_SUM_TOLERANCE,
        "row sum behind the luminaire {hidden}"
    );
    // The same cube built from quads without a ceiling: light leaves through the top.
    let open = r#"[scene]
name = "open-box"
bands = "photopic"
unit = "m"
max_edge = 1.0

[materials]
wall = { reflectance = 0.5 }

[[quad]]
name = "floor"
material = "wall"
corners = [[0, 0, 0], [2, 0, 0], [2, 2, 0], [0, 2, 0]]

[[quad]]
name = "wall_xmin"
material = "wall"
corners = [[0, 0, 0], [0, 2, 0], [0, 2, 2], [0, 0, 2]]

[[quad]]
name = "wall_xmax"
material = "wall"
corners = [[2, 0, 0], [2, 0, 2], [2, 2, 2], [2, 2, 0]]

[[quad]]
name = "wall_ymin"
material = "wall"
corners = [[0, 0, 0], [0, 0, 2], [2, 0, 2], [2, 0, 0]]

[[quad]]
name = "wall_ymax"
material = "wall"
corners = [[0, 2, 0], [2, 2, 0], [2, 2, 2], [0, 2, 2]]

[[channel]]
name = "floor"
surfaces = ["floor"]
exitance = 100
"#;
    let ff = form_factors(&build(&dir, open, "open.basis", &["--json"]));
    assert_eq!(ff["closed"].as_bool(), Some(false), "{ff}");
    assert!(dir.join("open.basis").is_file());
}

/// Output rows are counted before they are allocated: a scene whose calculation grids (10 000
/// points a zone, the most a zone may have) would need more memory for their rows than the
/// machine can spare is refused with the counts, before any form factor, and writes nothing.
/// The zone count is derived from this machine's budget, so the test holds on any machine.
#[test]
fn cli_build_refuses_output_rows_beyond_memory_before_computing_them() {
    use eigenrad::precompute::memory;
    let dir = scratch("output-rows");
    // A 10 × 10 × 3 m room at 0.4 m: about 2 000 patches (form factors 32 MB).
    let patches = 2000.0;
    let per_zone = memory::output_bytes(10_000.0, patches);
    let zones = (memory::budget_bytes() / per_zone).ceil() as usize + 1;
    let mut text = String::from(
        "[scene]\nname = \"big\"\nbands = \"photopic\"\nunit = \"m\"\nmax_edge = 0.4\n\n\
         [materials]\nwall = { reflectance = 0.5 }\n\n\
         [[room]]\nname = \"room\"\nmin = [0, 0, 0]\nmax = [10, 10, 3]\nmaterial = \"wall\"\n\n\
         [[channel]]\nname = \"all\"\nsurfaces = [\"room.ceiling\"]\nflux = 1000\n\n",
    );
    for z in 0..zones {
        text += &format!(
            "[[zone]]\nname = \"plane{z}\"\nwork_plane = {{ room = \"room\", height = 0.8, \
             margin = 0.5, max_edge = 3, grid = {{ spacing = 0.09 }} }}\n\n"
        );
    }
    let o = build(&dir, &text, "big.basis", &[]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    let e = stderr(&o);
    assert!(
        e.contains("scene.toml")
            && e.contains(&format!("{zones} zones"))
            && e.contains("calculation-grid points")
            && e.contains("can spare"),
        "{e}"
    );
    assert!(!dir.join("big.basis").exists());
}

/// `--operator` chooses how the form factors are stored and the report says so: the cube's
/// build in f32 reads what the f64 build reads (sensor and zone readings within 1e-6
/// relative: entries within 2⁻²⁴, the responses within 2u ρmax/(1 − ρmax) of docs/math.md),
/// and `auto` keeps f64 at this size.
#[test]
fn cli_operator_flag_chooses_the_storage_and_the_report_names_it() {
    let dir = scratch("operator");
    let report = |extra: &[&str], out: &str| -> serde_json::Value {
        let mut args = vec!["--json"];
        args.extend_from_slice(extra);
        let o = build(&dir, &scene(1.0), out, &args);
        assert!(o.status.success(), "build failed: {}", stderr(&o));
        serde_json::from_slice(&o.stdout).expect("build --json prints one JSON document")
    };
    let auto = report(&[], "auto.basis");
    let f32 = report(&["--operator", "dense-f32"], "f32.basis");
    let f64 = report(&["--operator", "dense"], "f64.basis");
    assert_eq!(auto["operator"]["storage"], "dense f64");
    assert_eq!(f64["operator"]["storage"], "dense f64");
    assert_eq!(f32["operator"]["storage"], "dense f32");
    let n = f64["patches"].as_u64().expect("patches");
    assert_eq!(f32["operator"]["bytes"].as_u64(), Some(4 * n * n + 8 * n));
    assert_eq!(f64["operator"]["bytes"].as_u64(), Some(8 * n * n));
    // The exact solve through either operator: the same readings.
    let path = dir.join("cube.toml");
    std::fs::write(&path, scene(1.0)).expect("write the scene");
    let path = path.to_str().expect("a UTF-8 path");
    let readings = |operator: &str| -> Vec<f64> {
        let o = run(&["solve", path, "--json", "--operator", operator]);
        assert!(o.status.success(), "solve failed: {}", stderr(&o));
        let r: serde_json::Value = serde_json::from_slice(&o.stdout).expect("one JSON document");
        let sensors = r["sensors"].as_array().expect("sensors").iter();
        sensors
            .chain(r["zones"].as_array().expect("zones"))
            .map(|s| s["irradiance"][0].as_f64().expect("irradiance"))
            .collect()
    };
    let (a, b) = (readings("dense"), readings("dense-f32"));
    assert!(!a.is_empty() && a.len() == b.len());
    for (x, y) in a.iter().zip(&b) {
        assert!((x - y).abs() <= 1e-6 * x.abs(), "{x} against {y}");
    }
    let bad = run(&["build", "x.toml", "-o", "y.basis", "--operator", "sparse"]);
    assert!(!bad.status.success());
    assert!(stderr(&bad).contains("dense-f32"), "{}", stderr(&bad));
}
