//! `eigenrad inspect --gains`, DALI arc levels (`--arc`), footcandles (`--units fc`) and the
//! form-factor cache, run as a user runs them, each against an independent path:
//!
//! - gains against `eval` with that channel alone at level 1 (the full `Evaluator` instead of
//!   the `ChannelEvaluator`);
//! - arc levels against the IEC 62386-102 curve computed here, `X(n) = 10^((n − 1)/(253/3) − 1) %`;
//! - footcandles against lux × 0.3048² (1 fc = 1 lm/ft², 1 ft = 0.3048 m);
//! - cached form factors against the same command with `--no-cache`, byte for byte.

mod common;

use std::path::{Path, PathBuf};
use std::process::Output;

use common::{command, run, scratch, stderr};
use eigenrad::precompute::cache;
use eigenrad::precompute::formfactor::{self, FormFactorOptions};
use eigenrad::precompute::scene;
use serde_json::Value;

/// A closed 2 m cube with two ceiling lamps on channels `left` and `right`, a floor sensor off
/// centre, a work-plane zone and the floor as a zone. `bands`: `"photopic"` or `"rgb"`.
fn two_lamp_scene(bands: &str) -> String {
    let (rho, dark, flux) = if bands == "rgb" {
        ("[0.5, 0.4, 0.3]", "[0, 0, 0]", "[100, 120, 80]")
    } else {
        ("0.5", "0", "1000")
    };
    format!(
        r#"[scene]
name = "cube2"
bands = "{bands}"
unit = "m"
max_edge = 0.5

[materials]
wall = {{ reflectance = {rho} }}
lamp = {{ reflectance = {dark} }}

[[room]]
name = "room"
min = [0, 0, 0]
max = [2, 2, 2]
material = "wall"
openings = ["left", "right"]

[[quad]]
name = "left"
material = "lamp"
corners = [[0.3, 0.7, 2], [0.3, 1.3, 2], [0.7, 1.3, 2], [0.7, 0.7, 2]]

[[quad]]
name = "right"
material = "lamp"
corners = [[1.3, 0.7, 2], [1.3, 1.3, 2], [1.7, 1.3, 2], [1.7, 0.7, 2]]

[[channel]]
name = "left"
surfaces = ["left"]
flux = {flux}

[[channel]]
name = "right"
surfaces = ["right"]
flux = {flux}

[[sensor]]
name = "desk"
position = [0.6, 1.0, 0.75]
normal = [0, 0, 1]

[[zone]]
name = "work_plane"
work_plane = {{ room = "room", height = 0.75, margin = 0.25 }}

[[zone]]
name = "floor"
surfaces = ["room.floor"]
"#
    )
}

fn utf8(p: &Path) -> &str {
    p.to_str().expect("utf-8 path")
}

fn ok(o: Output, what: &str) -> Output {
    assert!(o.status.success(), "{what} failed: {}", stderr(&o));
    o
}

fn json(o: &Output) -> Value {
    serde_json::from_slice(&o.stdout).expect("JSON on stdout")
}

/// The scene written into `dir` and its basis built there (8 modes).
fn scene_and_basis(dir: &Path, bands: &str) -> (PathBuf, PathBuf) {
    let scene = dir.join("scene.toml");
    std::fs::write(&scene, two_lamp_scene(bands)).expect("write scene");
    let basis = dir.join("cube2.basis");
    ok(
        run(&["build", utf8(&scene), "-o", utf8(&basis), "--modes", "8"]),
        "build",
    );
    (scene, basis)
}

/// Every reading of a `solve`/`eval` document, sensors then zones, per band.
fn readings(doc: &Value) -> Vec<Vec<f64>> {
    let numbers = |v: &Value| -> Vec<f64> {
        v.as_array()
            .expect("bands")
            .iter()
            .map(|x| x.as_f64().expect("number"))
            .collect()
    };
    let mut out: Vec<Vec<f64>> = ["sensors", "zones"]
        .iter()
        .flat_map(|k| doc[k].as_array().expect("list").iter())
        .map(|r| numbers(&r["irradiance"]))
        .collect();
    // Calculation grids: their figures (not U_o, a ratio) and every point.
    for g in doc["grids"].as_array().into_iter().flatten() {
        for k in ["average", "minimum", "maximum"] {
            out.push(numbers(&g[k]));
        }
        for p in g["points"].as_array().expect("points") {
            out.push(numbers(&p["irradiance"]));
        }
    }
    out
}

#[test]
fn cli_gains_equal_eval_with_one_channel_at_level_one() {
    let dir = scratch("gains");
    let (_, basis) = scene_and_basis(&dir, "photopic");
    let csv = dir.join("gains.csv");
    let gains = json(&ok(
        run(&[
            "inspect",
            "--gains",
            utf8(&basis),
            "--json",
            "--csv",
            utf8(&csv),
        ]),
        "inspect --gains",
    ));
    assert_eq!(gains["unit"], "lux");
    assert_eq!(gains["channels"], serde_json::json!(["left", "right"]));
    let outputs: Vec<&Value> = ["sensors", "zones"]
        .iter()
        .flat_map(|k| gains[k].as_array().expect("list").iter())
        .collect();
    assert_eq!(outputs.len(), 3, "one sensor and two zones");
    for o in &outputs {
        assert!(o["per_daylight"].is_null(), "no daylight in this scene");
    }
    for (c, (on, off)) in [("left", "right"), ("right", "left")].iter().enumerate() {
        let alone = json(&ok(
            run(&[
                "eval",
                utf8(&basis),
                "--json",
                "--level",
                &format!("{on}=1"),
                "--level",
                &format!("{off}=0"),
            ]),
            "eval",
        ));
        let expected = readings(&alone);
        for (o, gain) in outputs.iter().enumerate() {
            let got = gain["per_channel"][c][0].as_f64().expect("number");
            // Both read the stored exact responses through the runtime; the runtime's two
            // evaluators agree to the bit.
            assert_eq!(got, expected[o][0], "{} channel {on}", gain["name"]);
            assert!(got > 0.0, "{} sees {on}", gain["name"]);
        }
    }
    // The off-centre sensor sees its own lamp more.
    let desk = &gains["sensors"][0]["per_channel"];
    assert!(desk[0][0].as_f64() > desk[1][0].as_f64(), "{desk}");

    // The sensor's ratio to each zone per channel: its gain over the zone's, sensor by
    // sensor and zone by zone; no daylight here.
    let ratios = gains["ratios"].as_array().expect("ratios");
    let zones = gains["zones"].as_array().expect("zones");
    assert_eq!(ratios.len(), zones.len(), "one sensor times two zones");
    for (r, zone) in ratios.iter().zip(zones) {
        assert_eq!(r["sensor"], "desk");
        assert_eq!(r["zone"], zone["name"]);
        for c in 0..2 {
            let expected = desk[c][0].as_f64().expect("number")
                / zone["per_channel"][c][0].as_f64().expect("number");
            let got = r["per_channel"][c].as_f64().expect("a ratio");
            // The JSON parser may be one ulp off the correctly rounded value, in each of the
            // three numbers.
            assert!((got - expected).abs() <= 4e-16 * 3.0 * expected, "{r}");
        }
        for daylight in ["overcast", "clear_sky", "sun"] {
            assert!(r[daylight].is_null(), "no daylight: {r}");
        }
    }

    // The CSV holds the same numbers, one row per output and band.
    let text = std::fs::read_to_string(&csv).expect("CSV written");
    let mut lines = text.lines();
    assert_eq!(lines.next(), Some("kind,name,band,unit,left,right"));
    let rows: Vec<Vec<&str>> = lines.map(|l| l.split(',').collect()).collect();
    assert_eq!(rows.len(), outputs.len());
    for (row, gain) in rows.iter().zip(&outputs) {
        assert_eq!(row[1], gain["name"].as_str().expect("name"));
        assert_eq!(row[3], "lux");
        for c in 0..2 {
            let v: f64 = row[4 + c].parse().expect("number");
            let j = gain["per_channel"][c][0].as_f64().expect("number");
            // serde_json's default float parser may be one ulp off the correctly rounded value.
            const PARSE: f64 = 1e-15;
            assert!((v - j).abs() <= PARSE * j.abs(), "{v} vs {j}");
        }
    }

    // The table names every output, channel and the unit.
    let table = String::from_utf8(ok(run(&["inspect", "--gains", utf8(&basis)]), "table").stdout)
        .expect("utf-8");
    for word in [
        "desk",
        "work_plane",
        "floor",
        "left",
        "right",
        "lux",
        "daylight",
        "sensor to zone",
    ] {
        assert!(table.contains(word), "`{word}` missing:\n{table}");
    }
}

#[test]
fn cli_gains_csv_never_replaces_the_basis_and_needs_gains() {
    let dir = scratch("gains-guard");
    let (_, basis) = scene_and_basis(&dir, "photopic");
    let before = std::fs::read(&basis).expect("basis");
    let o = run(&["inspect", "--gains", utf8(&basis), "--csv", utf8(&basis)]);
    assert!(!o.status.success(), "CSV over the basis accepted");
    assert!(
        stderr(&o).contains("refusing to write over"),
        "{}",
        stderr(&o)
    );
    assert_eq!(std::fs::read(&basis).expect("basis"), before);
    let o = run(&["inspect", utf8(&basis), "--csv", utf8(&dir.join("x.csv"))]);
    assert!(!o.status.success(), "--csv without --gains accepted");
    assert!(stderr(&o).contains("--gains"), "{}", stderr(&o));
}

/// IEC 62386-102's logarithmic dimming curve, relative (0 to 1): `X(n) = 10^((n − 1)/(253/3) −
/// 1) %` for n in 1..=254, computed in f64.
fn iec_curve(n: u32) -> f64 {
    if n == 0 {
        0.0
    } else {
        10f64.powf((f64::from(n) - 1.0) / (253.0 / 3.0) - 1.0) / 100.0
    }
}

/// The level applied to channel `index` in a `solve`/`eval` document.
fn level(doc: &Value, index: usize) -> f64 {
    doc["levels"][index]["level"].as_f64().expect("level")
}

#[test]
fn cli_arc_levels_follow_the_iec_curve_on_host_and_runtime_alike() {
    let dir = scratch("arc");
    let (scene, basis) = scene_and_basis(&dir, "photopic");
    let (scene, basis) = (utf8(&scene), utf8(&basis));
    // The runtime computes the exponent and 10^x in f32: a few f32 ulps.
    const F32_LEVEL: f64 = 2e-6;
    for arc in [1u32, 2, 85, 128, 170, 200, 253, 254] {
        let arg = format!("left={arc}");
        let eval = json(&ok(
            run(&[
                "eval",
                basis,
                "--json",
                "--arc",
                &arg,
                "--level",
                "right=0.5",
            ]),
            "eval --arc",
        ));
        let solve = json(&ok(
            run(&[
                "solve",
                scene,
                "--json",
                "--arc",
                &arg,
                "--level",
                "right=0.5",
            ]),
            "solve --arc",
        ));
        let expected = iec_curve(arc);
        let got = level(&eval, 0);
        assert!(
            (got - expected).abs() <= F32_LEVEL * expected,
            "arc {arc}: level {got}, IEC {expected}"
        );
        // Host and firmware use the one conversion: the same level to the bit.
        assert_eq!(level(&solve, 0), got, "arc {arc}");
        assert_eq!(level(&eval, 1), 0.5);
        assert_eq!(eval["levels"][0]["arc"], arc, "the arc level is reported");
        assert!(eval["levels"][1].get("arc").is_none(), "no arc for --level");
    }
    // 254 is full output and 0 is off, exactly.
    for (arc, value) in [("254", "1"), ("0", "0")] {
        for (cmd, target) in [("eval", basis), ("solve", scene)] {
            let by_arc = ok(
                run(&[cmd, target, "--json", "--arc", &format!("left={arc}")]),
                cmd,
            );
            let by_level = ok(
                run(&[cmd, target, "--json", "--level", &format!("left={value}")]),
                cmd,
            );
            assert_eq!(
                readings(&json(&by_arc)),
                readings(&json(&by_level)),
                "{cmd} arc {arc}"
            );
        }
    }
}

#[test]
fn cli_bad_arc_levels_are_refused_with_the_reason() {
    let dir = scratch("arc-bad");
    let (scene, basis) = scene_and_basis(&dir, "photopic");
    for (cmd, target) in [("eval", &basis), ("solve", &scene)] {
        for (args, expected) in [
            (vec!["--arc", "left=255"], "MASK"),
            (vec!["--arc", "left=256"], "not a DALI arc power level"),
            (vec!["--arc", "left=-1"], "not a DALI arc power level"),
            (vec!["--arc", "left=half"], "not a DALI arc power level"),
            (vec!["--arc", "left"], "NAME=ARC"),
            (vec!["--arc", "skylight=10"], "no channel named `skylight`"),
            (
                vec!["--level", "left=0.5", "--arc", "left=200"],
                "channel `left` is also given by --level",
            ),
        ] {
            let mut all = vec![cmd, utf8(target)];
            all.extend(&args);
            let o = run(&all);
            assert!(!o.status.success(), "{cmd} {args:?} accepted");
            let e = stderr(&o);
            assert!(e.contains(expected), "{cmd} {args:?}: {e}");
            assert!(e.contains("--arc"), "{cmd} {args:?}: flag not named: {e}");
        }
    }
}

#[test]
fn cli_footcandles_are_lux_times_the_square_of_a_foot() {
    let dir = scratch("fc");
    let (scene, basis) = scene_and_basis(&dir, "photopic");
    let foot2 = 0.3048 * 0.3048;
    // Two roundings (the division and the test's product).
    const ROUNDING: f64 = 1e-15;
    for (cmd, target) in [("eval", &basis), ("solve", &scene)] {
        let lux = json(&ok(run(&[cmd, utf8(target), "--json"]), cmd));
        let fc = json(&ok(
            run(&[cmd, utf8(target), "--json", "--units", "fc"]),
            cmd,
        ));
        assert_eq!(fc["unit"], "fc");
        for (l, f) in readings(&lux).iter().zip(readings(&fc)) {
            let expected = l[0] * foot2;
            assert!((f[0] - expected).abs() <= ROUNDING * expected, "{cmd}");
        }
        let table = String::from_utf8(ok(run(&[cmd, utf8(target), "--units", "fc"]), cmd).stdout)
            .expect("utf-8");
        assert!(table.contains(" fc") && !table.contains("lux"), "{table}");
    }
    let lux = json(&ok(
        run(&["inspect", "--gains", utf8(&basis), "--json"]),
        "gains",
    ));
    let fc = json(&ok(
        run(&[
            "inspect",
            "--gains",
            utf8(&basis),
            "--json",
            "--units",
            "fc",
        ]),
        "gains fc",
    ));
    assert_eq!(fc["unit"], "fc");
    let l = lux["zones"][0]["per_channel"][1][0].as_f64().expect("gain");
    let f = fc["zones"][0]["per_channel"][1][0].as_f64().expect("gain");
    assert!((f - l * foot2).abs() <= ROUNDING * l * foot2);
}

#[test]
fn cli_footcandles_of_a_radiometric_basis_are_refused() {
    let dir = scratch("fc-rgb");
    let (scene, basis) = scene_and_basis(&dir, "rgb");
    for args in [
        vec!["eval", utf8(&basis), "--units", "fc"],
        vec!["solve", utf8(&scene), "--units", "fc"],
        vec!["inspect", "--gains", utf8(&basis), "--units", "fc"],
    ] {
        let o = run(&args);
        assert!(!o.status.success(), "{args:?} accepted");
        let e = stderr(&o);
        assert!(
            e.contains("--units fc") && e.contains("W/m²"),
            "{args:?}: {e}"
        );
    }
    // The RGB gains: one row per band, in W/m².
    let gains = json(&ok(
        run(&["inspect", "--gains", utf8(&basis), "--json"]),
        "gains",
    ));
    assert_eq!(gains["unit"], "W/m²");
    assert_eq!(
        gains["sensors"][0]["per_channel"][0]
            .as_array()
            .map(Vec::len),
        Some(3)
    );
}

/// `eigenrad ARGS` with the form-factor cache in `cache_dir`.
fn run_cached(cache_dir: &Path, args: &[&str]) -> Output {
    command()
        .env("EIGENRAD_CACHE_DIR", cache_dir)
        .args(args)
        .output()
        .expect("run eigenrad")
}

fn entries(cache_dir: &Path) -> Vec<PathBuf> {
    let mut list: Vec<PathBuf> = std::fs::read_dir(cache_dir)
        .map(|d| d.flatten().map(|e| e.path()).collect())
        .unwrap_or_default();
    list.sort();
    list
}

#[test]
fn cli_cached_form_factors_give_the_same_bytes() {
    let dir = scratch("cache-same");
    let cache_dir = dir.join("cache");
    let (scene, _) = scene_and_basis(&dir, "photopic");
    let scene = utf8(&scene);
    let fresh = ok(
        run_cached(
            &cache_dir,
            &["solve", scene, "--json", "--patches", "--no-cache"],
        ),
        "solve --no-cache",
    );
    assert!(entries(&cache_dir).is_empty(), "--no-cache wrote the cache");
    let miss = ok(
        run_cached(&cache_dir, &["solve", scene, "--json", "--patches"]),
        "solve, first",
    );
    let stored = entries(&cache_dir);
    assert_eq!(stored.len(), 2, "patches and outputs: {stored:?}");
    let before: Vec<Vec<u8>> = stored
        .iter()
        .map(|p| std::fs::read(p).expect("entry"))
        .collect();
    let hit = ok(
        run_cached(&cache_dir, &["solve", scene, "--json", "--patches"]),
        "solve, second",
    );
    assert_eq!(miss.stdout, fresh.stdout);
    assert_eq!(hit.stdout, fresh.stdout);
    assert!(stderr(&hit).is_empty(), "{}", stderr(&hit));
    let after: Vec<Vec<u8>> = stored
        .iter()
        .map(|p| std::fs::read(p).expect("entry"))
        .collect();
    assert_eq!(after, before, "a hit rewrote an entry");

    // The entries are the library's keys for this scene: the cache is keyed by content.
    let loaded = scene::load(Path::new(scene)).expect("scene");
    let opts = FormFactorOptions::default();
    let key = cache::key(&loaded.patches, &loaded.faces, &opts);
    assert!(stored.contains(&cache::entry_path(&cache_dir, &key)));
    let rows = cache::rows_key(&loaded, &opts);
    assert!(stored.contains(&cache::entry_path(&cache_dir, &rows)));

    // build, verify and form-factors reuse it and print what they print without it.
    for (cmd, extra) in [("verify", vec![]), ("form-factors", vec!["--json"])] {
        let mut args = vec![cmd, scene];
        args.extend(&extra);
        let with = ok(run_cached(&cache_dir, &args), cmd);
        args.push("--no-cache");
        let without = ok(run_cached(&cache_dir, &args), cmd);
        assert_eq!(with.stdout, without.stdout, "{cmd}");
    }
    let a = dir.join("a.basis");
    let b = dir.join("b.basis");
    ok(
        run_cached(
            &cache_dir,
            &["build", scene, "-o", utf8(&a), "--modes", "8"],
        ),
        "build",
    );
    ok(
        run_cached(
            &cache_dir,
            &["build", scene, "-o", utf8(&b), "--modes", "8", "--no-cache"],
        ),
        "build --no-cache",
    );
    assert_eq!(std::fs::read(&a).ok(), std::fs::read(&b).ok());
    assert_eq!(entries(&cache_dir).len(), 2, "same scene, same entries");
}

#[test]
fn cli_a_well_formed_entry_is_what_the_commands_use() {
    // A doctored entry with a valid checksum, holding the form factors of other geometry:
    // if the command reads the cache, its result changes; this proves hits are hits.
    let dir = scratch("cache-used");
    let cache_dir = dir.join("cache");
    let (scene, _) = scene_and_basis(&dir, "photopic");
    let loaded = scene::load(&scene).expect("scene");
    let opts = FormFactorOptions::default();
    let mut ff = formfactor::patch_form_factors(&loaded.patches, &opts);
    // Half of every exchange: a room that loses half its light.
    for j in 0..ff.matrix.ncols() {
        for i in 0..ff.matrix.nrows() {
            ff.matrix[(i, j)] *= 0.5;
        }
    }
    let key = cache::key(&loaded.patches, &loaded.faces, &opts);
    std::fs::create_dir_all(&cache_dir).expect("cache folder");
    std::fs::write(
        cache::entry_path(&cache_dir, &key),
        cache::encode_form_factors(&ff, &key),
    )
    .expect("write");
    let scene = utf8(&scene);
    let doctored = json(&ok(
        run_cached(&cache_dir, &["solve", scene, "--json"]),
        "solve",
    ));
    let true_doc = json(&ok(
        run_cached(&cache_dir, &["solve", scene, "--json", "--no-cache"]),
        "solve --no-cache",
    ));
    let floor = |d: &Value| d["zones"][1]["irradiance"][0].as_f64().expect("floor");
    assert!(
        floor(&doctored) < floor(&true_doc),
        "the cached entry was not used: {} vs {}",
        floor(&doctored),
        floor(&true_doc)
    );
}

#[test]
fn cli_a_corrupt_cache_entry_is_recomputed_with_a_warning() {
    let dir = scratch("cache-corrupt");
    let cache_dir = dir.join("cache");
    let (scene, _) = scene_and_basis(&dir, "photopic");
    let scene = utf8(&scene);
    let reference = ok(
        run_cached(&cache_dir, &["solve", scene, "--json"]),
        "solve, filling the cache",
    );
    let paths = entries(&cache_dir);
    assert_eq!(paths.len(), 2, "patches and outputs: {paths:?}");
    for path in &paths {
        let good = std::fs::read(path).expect("entry");
        let mut flipped = good.clone();
        let middle = flipped.len() / 2;
        flipped[middle] ^= 0x01;
        for (what, bad) in [
            ("truncated", good[..good.len() - 7].to_vec()),
            ("flipped", flipped),
            ("empty", Vec::new()),
        ] {
            std::fs::write(path, &bad).expect("damage the entry");
            let o = ok(run_cached(&cache_dir, &["solve", scene, "--json"]), what);
            let e = stderr(&o);
            assert!(
                e.contains("warning") && e.contains("unusable") && e.contains(utf8(path)),
                "{what}: {e}"
            );
            assert_eq!(o.stdout, reference.stdout, "{what}: result changed");
            assert_eq!(
                std::fs::read(path).expect("entry"),
                good,
                "{what}: not rewritten"
            );
        }
    }
}
