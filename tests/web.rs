//! The commissioning page (`examples/web`: the runtime in WebAssembly and a static page) in a
//! real headless browser reads what `eigenrad eval --json` prints.
//!
//! The test builds the page as `scripts/web.sh --build-only` does, serves it on the loopback,
//! and drives Debian's `chromium` through `chromedriver` (W3C WebDriver). It opens bases
//! written by `eigenrad build` through the page's file input and works the page as a lighting
//! engineer would:
//!
//! - the example office (`examples/office/scene.toml`, 8 modes): every channel at 1, then a slider
//!   moved with the keyboard, one set to a level, one channel's DALI arc typed in; after each,
//!   every sensor and zone reading on the page equals `eval --json` at the levels the page
//!   shows, to [`F32_ROUNDING`]; the plan's `E_avg`, `E_min`, `E_max`, `U_o` likewise; every
//!   cell of the plan, read back from the canvas, is a colour of the map whose bin (the
//!   scale `eigenrad render` takes of `eval`'s grid values, `Scale::around`) holds the grid
//!   value `eval` prints to half a bin ([`Scale::value_of`]); the CSV export carries the
//!   readings shown; the level solver's target (the work plane at 500 lux, the desk sensor
//!   at 300) is met at the levels it sets, by `eval`'s readings, with the power it shows;
//! - a daylit room (`tests/common`'s `daylit_room` in Vienna, coarse so that it builds in
//!   seconds) under a CIE clear sky with the sun, a Perez sky from irradiances and the CIE
//!   overcast sky: the total, electric and daylight part of every reading equal
//!   `eval --time ... <sky> --json` to [`F32_ROUNDING`].
//!
//! It prints the time per page update measured in the browser (`performance.now()` around
//! each of 400 slider updates: readings, levels, plan and colour bar) and writes a screenshot
//! of the office to `target/web-test/page.png` (and to `$EIGENRAD_WEB_SCREENSHOT` when set:
//! `docs/pictures.md` says how it is put there), and one of the daylit room beside it.
//!
//! When `chromium`, `chromedriver` or the `wasm32-unknown-unknown` target is missing it
//! prints `SKIPPED:` and passes; `scripts/test.sh` installs all three.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

mod common;
#[path = "web/webdriver.rs"]
mod webdriver;

use std::path::{Path, PathBuf};
use std::process::Command;

use common::{daylit_room, run, stderr, VIENNA};
use eigenrad_precompute::picture::colour::Scale;
use serde_json::{json, Value};
use webdriver::Browser;

/// Readings agree within this fraction of the larger magnitude (and 1e-6 lux near zero).
/// Page and `eval` run the same runtime code on the same bytes, the one compiled to
/// WebAssembly and the other to the host, with IEEE `f32` arithmetic in both; they may
/// differ only where the sun's position goes through the platforms' `f64` sine and cosine
/// (`libm` in the browser, the C library on the host) before it is rounded to `f32`: a few
/// `f32` roundings, 2⁻²⁴ each.
const F32_ROUNDING: f64 = 8.0 * f32::EPSILON as f64;

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

fn work_dir() -> PathBuf {
    let dir = root().join("target/web-test");
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// The first of `names` found as a file, in `/usr/bin` or on the `PATH`.
fn program(names: &[&str]) -> Option<PathBuf> {
    let path = std::env::var_os("PATH").unwrap_or_default();
    let dirs: Vec<PathBuf> = std::iter::once(PathBuf::from("/usr/bin"))
        .chain(std::env::split_paths(&path))
        .collect();
    names
        .iter()
        .flat_map(|n| dirs.iter().map(move |d| d.join(n)))
        .find(|p| p.is_file())
}

/// What the test needs that a machine may lack, or why it is missing.
fn tools() -> Result<(PathBuf, PathBuf), String> {
    let chromium = program(&["chromium", "chromium-browser"])
        .ok_or("no chromium (apt-get install chromium)")?;
    let driver =
        program(&["chromedriver"]).ok_or("no chromedriver (apt-get install chromium-driver)")?;
    let targets = Command::new("rustup")
        .args(["target", "list", "--installed"])
        .output()
        .map_err(|e| format!("rustup: {e}"))?;
    if !String::from_utf8_lossy(&targets.stdout)
        .lines()
        .any(|l| l.trim() == "wasm32-unknown-unknown")
    {
        return Err(
            "no wasm32-unknown-unknown target (rustup target add wasm32-unknown-unknown)".into(),
        );
    }
    Ok((chromium, driver))
}

/// `eigenrad eval BASIS --json ARGS...`.
fn eval(basis: &Path, args: &[String]) -> Value {
    let mut all = vec![
        "eval".to_owned(),
        basis.display().to_string(),
        "--json".to_owned(),
    ];
    all.extend_from_slice(args);
    let refs: Vec<&str> = all.iter().map(String::as_str).collect();
    let o = run(&refs);
    assert!(o.status.success(), "eval {all:?}: {}", stderr(&o));
    serde_json::from_slice(&o.stdout).unwrap()
}

/// The largest difference of a page's reading from `eval`'s seen, relative to the larger.
static WORST: std::sync::Mutex<f64> = std::sync::Mutex::new(0.0);

/// `a` and `b` agree to [`F32_ROUNDING`].
fn close(a: f64, b: f64) -> bool {
    let scale = a.abs().max(b.abs());
    if scale > 0.0 {
        let mut worst = WORST.lock().unwrap();
        *worst = worst.max((a - b).abs() / scale);
    }
    (a - b).abs() <= F32_ROUNDING * scale + 1e-6
}

/// The page's channel levels as `--level NAME=VALUE` flags (the `f32` levels the runtime
/// holds print as the shortest `f64` text, which `eval` reads back to the same `f32`), but
/// `--arc NAME=ARC` for the channels in `arcs`.
fn level_flags(browser: &Browser, arcs: &[(&str, u8)]) -> Vec<String> {
    let levels = browser.script(
        "return Array.from(document.querySelectorAll('#channels tr[data-channel]')).map(r =>
           [r.dataset.channel, Number(r.querySelector('.level').dataset.value)]);",
        json!([]),
    );
    let mut flags = Vec::new();
    for l in levels.as_array().unwrap() {
        let name = l[0].as_str().unwrap();
        match arcs.iter().find(|(n, _)| *n == name) {
            Some((_, arc)) => flags.push(format!("--arc={name}={arc}")),
            None => flags.push(format!("--level={name}={}", l[1].as_f64().unwrap())),
        }
    }
    flags
}

/// Every reading on the page equals `eval`'s (total, and with daylight its two parts); the
/// number of readings checked.
fn check_readings(browser: &Browser, reference: &Value, what: &str) -> usize {
    let page = browser.script(
        "return Array.from(document.querySelectorAll('#readings tr[data-output]')).map(r => {
           const v = (c) => { const e = r.querySelector('.' + c); return e ? Number(e.dataset.value) : null; };
           return [r.dataset.output, v('total'), v('electric'), v('daylight')]; });",
        json!([]),
    );
    let page = page.as_array().unwrap();
    let mut expected = Vec::new();
    for (kind, list) in [("sensor", "sensors"), ("zone", "zones")] {
        for r in reference[list].as_array().unwrap() {
            expected.push((format!("{kind}:{}", r["name"].as_str().unwrap()), r));
        }
    }
    assert_eq!(page.len(), expected.len(), "{what}: readings on the page");
    for (row, (name, r)) in page.iter().zip(&expected) {
        assert_eq!(row[0].as_str().unwrap(), name, "{what}: order of readings");
        let total = r["irradiance"][0].as_f64().unwrap();
        let got = row[1].as_f64().unwrap();
        assert!(
            close(got, total),
            "{what}: {name} reads {got} lux, eval {total}"
        );
        if let Some(d) = r.get("daylight") {
            let (d, e) = (d[0].as_f64().unwrap(), r["electric"][0].as_f64().unwrap());
            let (gd, ge) = (row[3].as_f64().unwrap(), row[2].as_f64().unwrap());
            assert!(close(gd, d), "{what}: {name} daylight {gd} lux, eval {d}");
            assert!(close(ge, e), "{what}: {name} electric {ge} lux, eval {e}");
        }
    }
    page.len()
}

/// The plan: its figures equal `eval`'s grid figures, and every cell's colour on the canvas
/// maps back to `eval`'s value at its point within half a bin of the scale `eigenrad render`
/// takes of those values. Returns the cells checked.
fn check_plan(browser: &Browser, reference: &Value, zone: &str, what: &str) -> usize {
    let grid = reference["grids"]
        .as_array()
        .unwrap()
        .iter()
        .find(|g| g["zone"] == zone)
        .unwrap_or_else(|| panic!("{what}: eval has no grid of {zone}"));
    let values: Vec<f64> = grid["points"]
        .as_array()
        .unwrap()
        .iter()
        .map(|p| p["irradiance"][0].as_f64().unwrap())
        .collect();
    let figures = browser.script(
        "return ['e-avg','e-min','e-max','u-o'].map(id => Number(document.getElementById(id).dataset.value));",
        json!([]),
    );
    for (k, key) in ["average", "minimum", "maximum", "uniformity"]
        .iter()
        .enumerate()
    {
        let (got, want) = (figures[k].as_f64().unwrap(), grid[key][0].as_f64().unwrap());
        assert!(
            close(got, want),
            "{what}: {key} {got} on the page, eval {want}"
        );
    }
    let pixels = browser.script(
        "const cells = document.getElementById('plan-cells');
         const image = cells.getContext('2d').getImageData(0, 0, cells.width, cells.height);
         return window.eigenradPage.cellPixels().map(([x, y]) => {
           const i = 4 * (Math.floor(y) * cells.width + Math.floor(x));
           return [image.data[i], image.data[i + 1], image.data[i + 2], image.data[i + 3]]; });",
        json!([]),
    );
    let pixels = pixels.as_array().unwrap();
    assert_eq!(pixels.len(), values.len(), "{what}: cells on the plan");
    let (lo, hi) = values
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &v| {
            (a.min(v), b.max(v))
        });
    let scale = Scale::around(lo, hi, "lux");
    let half = scale.bin_width() / 2.0;
    for (p, &v) in pixels.iter().zip(&values) {
        let c: Vec<u8> = (0..4).map(|k| p[k].as_u64().unwrap() as u8).collect();
        assert_eq!(c[3], 255, "{what}: a cell centre is not opaque");
        let back = scale
            .value_of([c[0], c[1], c[2]])
            .unwrap_or_else(|| panic!("{what}: colour {c:?} is not one of the map's"));
        assert!(
            (back - v).abs() <= half * (1.0 + 1e-9),
            "{what}: a cell of {v} lux is drawn in the colour of {back} ± {half}"
        );
    }
    values.len()
}

/// Sets an input's value and fires the event the page listens to.
fn set_input(browser: &Browser, id: &str, value: &str, event: &str) {
    browser.script(
        "const e = document.getElementById(arguments[0]); e.value = arguments[1];
         e.dispatchEvent(new Event(arguments[2], { bubbles: true }));",
        json!([id, value, event]),
    );
}

/// Opens `basis` through the page's file input and waits for its first update.
fn open(browser: &Browser, basis: &Path) {
    let before = browser.script(
        "return Number(document.body.dataset.updates || 0);",
        json!([]),
    );
    browser.send_keys("#basis-file", &basis.display().to_string());
    browser.wait_for(
        &format!(
            "return Number(document.body.dataset.updates || 0) > {before} &&
                    document.getElementById('status').textContent.startsWith({:?});",
            basis.file_name().unwrap().to_str().unwrap()
        ),
        "the basis to open",
    );
}

#[test]
fn page_reads_what_eval_prints() {
    let (chromium, driver) = match tools() {
        Ok(t) => t,
        Err(why) => {
            println!("SKIPPED: {why}");
            return;
        }
    };
    let work = work_dir();
    let site = work.join("site");
    let built = Command::new(root().join("scripts/web.sh"))
        .arg("--build-only")
        .arg(&site)
        .output()
        .expect("run scripts/web.sh");
    assert!(
        built.status.success(),
        "scripts/web.sh --build-only: {}",
        stderr(&built)
    );
    println!(
        "page files (bytes):\n{}",
        String::from_utf8_lossy(&built.stdout)
    );

    // The bases, written by the project's command. The office's readings and grid are its
    // channels' exact responses, whatever the mode count: 8 modes from the partial
    // eigensolver keep the build short.
    let office = work.join("office.basis");
    let o = run(&[
        "build",
        root().join("examples/office/scene.toml").to_str().unwrap(),
        "-o",
        office.to_str().unwrap(),
        "--modes",
        "8",
        "--solver",
        "partial",
    ]);
    assert!(o.status.success(), "build the office: {}", stderr(&o));
    let daylit_dir = work.join("daylit");
    std::fs::create_dir_all(&daylit_dir).unwrap();
    let o = common::build(&daylit_dir, &daylit_room(VIENNA), "daylit.basis", &[]);
    assert!(o.status.success(), "build the daylit room: {}", stderr(&o));
    let daylit = daylit_dir.join("daylit.basis");

    let port = webdriver::serve(vec![site.clone()]);
    let browser = Browser::start(&chromium, &driver, &work);
    browser.goto(&format!("http://127.0.0.1:{port}/index.html"));
    browser.wait_for(
        "return !!(window.eigenradPage && window.eigenradPage.ready());",
        "the runtime to load",
    );

    // The office, every channel at 1 as it opens.
    open(&browser, &office);
    let levels = browser.script(
        "return Array.from(document.querySelectorAll('#channels .level')).map(c => Number(c.dataset.value));",
        json!([]),
    );
    assert!(
        levels.as_array().unwrap().iter().all(|l| l == 1.0),
        "levels as opened: {levels}"
    );
    let mut checked = 0;
    let mut cells = 0;
    let mut step = |browser: &Browser, what: &str, arcs: &[(&str, u8)]| {
        let reference = eval(&office, &level_flags(browser, arcs));
        checked += check_readings(browser, &reference, what);
        cells += check_plan(browser, &reference, "work_plane", what);
        reference
    };
    step(&browser, "office, levels 1", &[]);

    // A slider moved with the keyboard: Home (off), then two steps up.
    browser.send_keys("#level-0", "\u{E011}\u{E013}\u{E013}");
    let moved = browser.script(
        "return Number(document.getElementById('level-0').value);",
        json!([]),
    );
    let moved = moved.as_f64().unwrap();
    assert!(moved > 0.0 && moved < 0.01, "lum1's slider reads {moved}");
    step(&browser, "office, lum1 moved by keys", &[]);
    set_input(&browser, "level-2", "0.42", "input");
    step(&browser, "office, lum3 at 0.42", &[]);
    set_input(&browser, "arc-3", "200", "change");
    let reference = step(&browser, "office, lum4 at arc 200", &[("lum4", 200)]);

    // The export carries the readings shown.
    let csv = browser.script("return window.eigenradPage.csv();", json!([]));
    let csv = csv.as_str().unwrap();
    for r in reference["sensors"].as_array().unwrap() {
        let name = r["name"].as_str().unwrap();
        let line = csv
            .lines()
            .find(|l| l.starts_with(&format!("sensor,{name},")))
            .unwrap_or_else(|| panic!("no row of sensor {name} in the CSV:\n{csv}"));
        let total: f64 = line.split(',').nth(4).unwrap().parse().unwrap();
        assert!(close(total, r["irradiance"][0].as_f64().unwrap()), "{line}");
    }

    // The level solver: the work plane at 500 lux and the desk sensor at 300 with the four
    // luminaires (30 W each at level 1), the window channel as it is.
    set_input(&browser, "target-zone-lux", "500", "input");
    set_input(&browser, "target-sensor-lux", "300", "input");
    browser.click("#solve");
    let solution = browser.script(
        "const s = document.getElementById('solution');
         return [s.className, Number(s.dataset.power), s.textContent];",
        json!([]),
    );
    assert_eq!(solution[0], "", "the target is not met: {}", solution[2]);
    let flags = level_flags(&browser, &[]);
    let reference = step(&browser, "office, solved levels", &[]);
    let zone = &reference["zones"][0];
    assert_eq!(zone["name"], "work_plane");
    let sensor = &reference["sensors"][0];
    assert_eq!(sensor["name"], "desk1");
    let target = |r: &Value, lux: f64| r["irradiance"][0].as_f64().unwrap() >= lux * (1.0 - 1e-5);
    assert!(target(zone, 500.0) && target(sensor, 300.0), "{flags:?}");
    let power: f64 = reference["levels"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|l| l["name"] != "window")
        .map(|l| 30.0 * l["level"].as_f64().unwrap())
        .sum();
    let shown = solution[1].as_f64().unwrap();
    assert!(
        (shown - power).abs() <= 1e-4 * power,
        "power {shown} W shown, {power} W at the levels"
    );

    // The screenshot of the docs: the office at the levels the solver set.
    let png = browser.screenshot();
    assert!(
        png.starts_with(b"\x89PNG\r\n\x1a\n"),
        "the screenshot is no PNG"
    );
    std::fs::write(work.join("page.png"), &png).unwrap();
    if let Some(path) = std::env::var_os("EIGENRAD_WEB_SCREENSHOT") {
        std::fs::write(path, &png).unwrap();
    }

    // The time per update, in the browser.
    let timing = browser.script("return window.eigenradPage.timeUpdates(400, 1);", json!([]));
    println!("page update, office (1070 patches, work plane grid): {timing}");
    set_input(&browser, "level-1", "0.8", "input");

    // Daylight: the daylit room under three skies.
    open(&browser, &daylit);
    set_input(&browser, "level-0", "0.5", "input");
    let skies: [(&str, &str, &str, &str, Vec<&str>); 3] = [
        (
            "cie:12",
            "10000",
            "60000",
            "10:30",
            vec!["--cie", "12", "--dhi-lux", "10000", "--dni-lux", "60000"],
        ),
        (
            "perez-w",
            "120",
            "700",
            "14:15",
            vec!["--dni", "700", "--dhi", "120"],
        ),
        (
            "cie:0",
            "15000",
            "0",
            "12:00",
            vec!["--cie", "overcast", "--dhi-lux", "15000"],
        ),
    ];
    for (model, dhi, dni, time, sky_flags) in skies {
        set_input(&browser, "sky-date", "2026-06-21", "change");
        set_input(&browser, "sky-time", time, "change");
        set_input(&browser, "sky-dhi", dhi, "change");
        set_input(&browser, "sky-dni", dni, "change");
        set_input(&browser, "sky-model", model, "change");
        let sun = browser.script(
            "return document.getElementById('sun').textContent;",
            json!([]),
        );
        assert!(sun.as_str().unwrap().starts_with("Sun "), "{model}: {sun}");
        let mut flags = level_flags(&browser, &[]);
        flags.push(format!("--time=2026-06-21T{time}"));
        flags.extend(sky_flags.iter().map(|s| s.to_string()));
        let reference = eval(&daylit, &flags);
        let what = format!("daylit room, {model} at {time}");
        checked += check_readings(&browser, &reference, &what);
        cells += check_plan(&browser, &reference, "work_plane", &what);
    }
    // The daylit room under the last sky, for a look (not in the docs).
    std::fs::write(work.join("page-daylight.png"), browser.screenshot()).unwrap();
    println!(
        "{checked} readings and {cells} plan cells agree with eigenrad eval; largest relative \
         difference of a reading {:e}",
        *WORST.lock().unwrap()
    );
}
