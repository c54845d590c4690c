//! The firmware example (`examples/firmware`) run under QEMU agrees with `eigenrad eval`, its
//! evaluators' RAM does not grow with the basis, and on the office at 32 modes a channel
//! update and the read of every output stay within their instruction budgets.
//!
//! Each test takes a basis, runs `scripts/firmware.sh` on it (build for
//! `thumbv7em-none-eabihf` with the basis in flash, run on QEMU `mps2-an386`), parses the
//! records the firmware prints (read from its `ChannelEvaluator`; the firmware itself checks
//! that its full `Evaluator` reads the same, to the bit) and, for every step of the
//! firmware's level sequence, runs the real command `eigenrad eval BASIS --json --patches --level NAME=VALUE ...` at the levels
//! the firmware reports. Every sensor and zone reading and every patch exitance the firmware
//! prints (patches 0, 97, 194, ...) must agree with it within [`REL_TOL`].
//!
//! The bases, all written by `eigenrad build` except the last:
//!
//! - the office example (`examples/office/scene.toml`, 1070 patches, 5 channels, 2 sensors,
//!   2 zones) at 32 modes, f32 storage;
//! - the same office on a coarser mesh (`max_edge` 0.7 m instead of 0.35 m) at
//!   16 modes in f16 and at 64 modes in i16. A build's form factors cost grows as the square
//!   of the patch count, so the coarse mesh keeps the test's run time down while the
//!   precisions and mode counts still differ from the f32 basis;
//! - the daylight office (`examples/office-daylight/scene.toml`: the office with a glazed
//!   window at a site, 4 channels) at 32 modes in f16, the storage that fits its daylight in
//!   512 KiB of flash. The firmware also steps through the two solstices of sun and clear sky
//!   on it; every step's daylight readings must agree with
//!   `eigenrad eval --time ... --cie 12 --dhi-lux 10000 --dni-lux 60000 --json` within
//!   [`DAYLIGHT_REL_TOL`], the runtime's own sun position must be within 0.05° of SPA's at
//!   every step, and a whole sky update by the runtime alone (sun, sky, patch luminances,
//!   `set_sky`, every output) within 200 000 instructions (`firmware/daylight.rs`,
//!   `firmware_daylight_office`). Then it runs a day as a daylight-harvesting controller under
//!   an overcast sky built by the runtime, a model-based controller and one whose photocell
//!   was commissioned at night side by side; every step agrees with the host's computation
//!   of the same loop (`firmware/harvest.rs`, `firmware_harvest_office`);
//! - the Cornell box example (`examples/cornell-box/scene.toml`, three bands, one channel) as
//!   `eigenrad build` makes it by default;
//! - a random three-band basis (tables of plausible size but no room behind them, several
//!   channels).
//!
//! The `eigenrad` command is built with `cargo build --profile test` (a no-op when it is up
//! to date) unless `EIGENRAD_BIN` names one. Each basis is built once per test run, in
//! `target/firmware-test/`.
//!
//! When QEMU is missing and cannot be installed, the tests say so on stderr and return
//! without checking the firmware.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};
use std::sync::{Arc, Mutex, OnceLock};

use eigenrad::precompute::accuracy::rng::Rng;
use eigenrad_runtime::writer::BasisTables;
use eigenrad_runtime::{Formulation, Precision, Quantity};
use serde_json::Value;

// The test's root stays `tests/firmware.rs`, the file the docs and scripts name.
#[path = "firmware/checks.rs"]
mod checks;
#[path = "firmware/controller.rs"]
mod controller;
#[path = "firmware/daylight.rs"]
mod daylight;
#[path = "firmware/harvest.rs"]
mod harvest;
#[path = "firmware/random.rs"]
mod random;
#[path = "firmware/records.rs"]
mod records;

use random::rgb_basis;
use records::*;

/// Readings agree within this fraction of the larger of the reference and the output's
/// reading with every channel at 1. The firmware applies the levels step by step,
/// `eigenrad eval` sets each state at once; both sum the same `m` stored (f32, f16 or i16)
/// products per band in `f32` with the same runtime code, so they differ by the rounding of
/// two compilations of that sum at most (a few times 2⁻²⁴ ≈ 6e-8), orders of magnitude below
/// this.
const REL_TOL: f64 = 1e-4;

/// Daylight readings of the firmware agree with `eigenrad eval --time` within this fraction
/// of the host's reading (floored at 1 lux). Both weigh the same stored daylight with the
/// same runtime code in `f32`, and the sun's position agrees to 10⁻¹³° (the same SPA in
/// `f64`, the host's `std` math against the firmware's `libm`); the difference is the sky's
/// sun direction, which the host builds from the angles in `f64` and the firmware with the
/// runtime's `sky::direction` in `f32`: the clear sky's circumsolar peak moves by an `f32`
/// rounding, each patch's luminance by about 10⁻⁷ of itself, and the readings by up to
/// 3.1e-7 of themselves (measured; with the sky's sun built in `f64` as the host builds it,
/// 5.2e-8). The tolerance leaves 30 times that.
const DAYLIGHT_REL_TOL: f64 = 1e-5;
/// The sun's altitude and azimuth of the firmware against the host's, degrees.
const SUN_TOL_DEG: f64 = 1e-8;

/// Capacities of the firmware's evaluator (`examples/firmware/src/main.rs`).
const FW_PATCHES: usize = 2048;
const FW_MODES: usize = 128;
const FW_CHANNELS: usize = 8;
const FW_OUTPUTS: usize = 8;

/// DALI arc levels the firmware applies to each channel in turn, the level it sets channel 0
/// to after all channels start at 1, and the stride of the patches whose exitance it prints
/// (`examples/firmware/src/main.rs`).
const ARC_LEVELS: [u8; 5] = [254, 200, 128, 1, 0];
const HALF: f32 = 0.5;
const PATCH_STRIDE: usize = 97;

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// Where this test writes bases, scenes and firmware output.
fn work_dir() -> PathBuf {
    let dir = root().join("target/firmware-test");
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn tiny_basis_path() -> PathBuf {
    root().join("runtime/tests/data/tiny.basis")
}

// ---------------------------------------------------------------------------------------
// The eigenrad command

/// The `eigenrad` executable: `EIGENRAD_BIN`, or the one `cargo build --profile test`
/// reports (the test profile shares its compiled dependencies with this test).
fn eigenrad() -> &'static Path {
    static BIN: OnceLock<PathBuf> = OnceLock::new();
    BIN.get_or_init(|| {
        if let Some(bin) = std::env::var_os("EIGENRAD_BIN") {
            return PathBuf::from(bin);
        }
        let cargo = std::env::var_os("CARGO").unwrap_or_else(|| "cargo".into());
        let output = Command::new(cargo)
            .current_dir(root())
            .args(["build", "--quiet", "--profile", "test"])
            .args(["-p", "eigenrad-precompute", "--bin", "eigenrad"])
            .arg("--message-format=json-render-diagnostics")
            .output()
            .expect("run cargo build");
        assert!(
            output.status.success(),
            "cargo build of the eigenrad command failed:\n{}",
            String::from_utf8_lossy(&output.stderr)
        );
        String::from_utf8_lossy(&output.stdout)
            .lines()
            .filter_map(|line| serde_json::from_str::<Value>(line).ok())
            .filter(|m| m["reason"] == "compiler-artifact" && m["target"]["name"] == "eigenrad")
            .find_map(|m| m["executable"].as_str().map(PathBuf::from))
            .expect("cargo build named no eigenrad executable")
    })
}

/// Runs `eigenrad ARGS`, failing the test with its stderr when it fails.
fn run_eigenrad(args: &[&std::ffi::OsStr]) -> Output {
    let output = Command::new(eigenrad())
        // The form-factor cache beside this test's other files, never the user's.
        .env("EIGENRAD_CACHE_DIR", work_dir().join("form-factor-cache"))
        .args(args)
        .output()
        .expect("run eigenrad");
    assert!(
        output.status.success(),
        "eigenrad {:?} failed ({}):\n{}",
        args,
        output.status,
        String::from_utf8_lossy(&output.stderr)
    );
    output
}

// ---------------------------------------------------------------------------------------
// Bases

/// The office example's scene file.
fn office_scene() -> PathBuf {
    root().join("examples/office/scene.toml")
}

/// The office's `[scene]` mesh setting, and the coarser one of the precision variants.
const OFFICE_MAX_EDGE: &str = "max_edge = 0.35";
const COARSE_MAX_EDGE: &str = "max_edge = 0.7";

/// The office scene with `max_edge` 0.7 m instead of 0.35 m, written next to the test's
/// bases. Everything else (geometry, materials, channels, luminaires, sensors, zones) is the
/// example's; the luminaires' photometric files are named by absolute path, since the scene
/// is written elsewhere.
fn coarse_office_scene() -> PathBuf {
    let text = std::fs::read_to_string(office_scene()).unwrap();
    let matches: Vec<usize> = text
        .lines()
        .enumerate()
        .filter(|(_, l)| l.starts_with(OFFICE_MAX_EDGE))
        .map(|(i, _)| i)
        .collect();
    assert_eq!(
        matches.len(),
        1,
        "examples/office/scene.toml: expected one line starting `{OFFICE_MAX_EDGE}`"
    );
    let office_dir = root().join("examples/office");
    let coarse: Vec<String> = text
        .lines()
        .enumerate()
        .map(|(i, l)| {
            if i == matches[0] {
                COARSE_MAX_EDGE.to_string()
            } else if let Some(file) = l
                .strip_prefix("file = \"")
                .and_then(|r| r.strip_suffix('"'))
            {
                format!("file = \"{}\"", office_dir.join(file).display())
            } else {
                l.to_string()
            }
        })
        .collect();
    let path = work_dir().join("office-coarse.toml");
    std::fs::write(&path, coarse.join("\n") + "\n").unwrap();
    path
}

/// Which office scene a basis is built from.
#[derive(Clone, Copy, Debug)]
enum Mesh {
    /// `examples/office/scene.toml` as it is.
    Office,
    /// [`coarse_office_scene`].
    Coarse,
    /// `examples/office-daylight/scene.toml` as it is: the office with a glazed window at a
    /// site, its daylight in the basis.
    Daylight,
    /// The daylight office built with `--sun-first` (the sun's first reflection computed on
    /// the controller) and `--no-grids` (its grid points' responses to the sun's candidates
    /// would leave no room for the firmware in the part's flash).
    DaylightSunFirst,
}

/// `eigenrad build` of the office at `modes` modes per band and storage `precision`
/// (`f32`, `f16`, `i16`), once per test run; the build's report goes to `<name>.report`
/// beside the basis. Returns the basis' path and name.
fn office_basis(mesh: Mesh, modes: usize, precision: &str) -> (PathBuf, String) {
    static BUILT: OnceLock<Mutex<HashMap<String, PathBuf>>> = OnceLock::new();
    let name = match mesh {
        Mesh::Office => format!("office-p{modes}-{precision}"),
        Mesh::Coarse => format!("office-coarse-p{modes}-{precision}"),
        Mesh::Daylight => format!("office-daylight-p{modes}-{precision}"),
        Mesh::DaylightSunFirst => format!("office-daylight-sun-first-p{modes}-{precision}"),
    };
    // Builds run one at a time: each uses every core for its form factors.
    let mut built = BUILT
        .get_or_init(Default::default)
        .lock()
        .unwrap_or_else(|e| e.into_inner());
    if let Some(path) = built.get(&name) {
        return (path.clone(), name);
    }
    let scene = match mesh {
        Mesh::Office => office_scene(),
        Mesh::Coarse => coarse_office_scene(),
        Mesh::Daylight | Mesh::DaylightSunFirst => {
            root().join("examples/office-daylight/scene.toml")
        }
    };
    let flags: &[&str] = match mesh {
        Mesh::DaylightSunFirst => &["--sun-first", "--no-grids"],
        _ => &[],
    };
    let path = work_dir().join(format!("{name}.basis"));
    let modes = modes.to_string();
    let mut args: Vec<&std::ffi::OsStr> = vec![
        "build".as_ref(),
        scene.as_os_str(),
        "-o".as_ref(),
        path.as_os_str(),
        "--modes".as_ref(),
        modes.as_ref(),
        "--precision".as_ref(),
        precision.as_ref(),
    ];
    args.extend(flags.iter().map(std::ffi::OsStr::new));
    let report = run_eigenrad(&args);
    eprintln!("built {name}:\n{}", String::from_utf8_lossy(&report.stdout));
    std::fs::write(work_dir().join(format!("{name}.report")), &report.stdout).unwrap();
    built.insert(name.clone(), path.clone());
    (path, name)
}

/// `eigenrad build` of the Cornell box example (`examples/cornell-box/scene.toml`: three
/// bands, one channel) with the default settings, once per test run.
fn cornell_box_basis() -> (PathBuf, String) {
    static BUILT: OnceLock<PathBuf> = OnceLock::new();
    let name = "cornell-box".to_string();
    let path = BUILT.get_or_init(|| {
        let scene = root().join("examples/cornell-box/scene.toml");
        let path = work_dir().join(format!("{name}.basis"));
        let report = run_eigenrad(&[
            "build".as_ref(),
            scene.as_os_str(),
            "-o".as_ref(),
            path.as_os_str(),
        ]);
        eprintln!("built {name}:\n{}", String::from_utf8_lossy(&report.stdout));
        path
    });
    (path.clone(), name)
}

/// The meeting room's controller of the example building (`examples/building/`, controller
/// `meeting`, with the room's modes), built by `eigenrad building` from a manifest holding that
/// room and controller alone, once per test run.
fn building_controller_basis() -> (PathBuf, String) {
    static BUILT: OnceLock<PathBuf> = OnceLock::new();
    let name = "building-meeting".to_string();
    let path = BUILT.get_or_init(|| {
        let dir = work_dir().join("building");
        std::fs::create_dir_all(&dir).unwrap();
        let scene = root().join("examples/building/meeting.toml");
        let manifest = dir.join("building.toml");
        std::fs::write(
            &manifest,
            format!(
                "[building]\nname = \"meeting\"\n\n[[room]]\nname = \"meeting\"\nscene = {:?}\n\n\
                 [[controller]]\nname = \"meeting\"\nroom = \"meeting\"\ndrives = [\"table\", \"walls\"]\n\
                 sensors = [\"table\"]\ngrids = [\"work_plane\"]\nmodes = true\n",
                scene.display().to_string()
            ),
        )
        .unwrap();
        let out = dir.join("out");
        let report = run_eigenrad(&[
            "building".as_ref(),
            manifest.as_os_str(),
            "--out".as_ref(),
            out.as_os_str(),
        ]);
        eprintln!("built {name}:\n{}", String::from_utf8_lossy(&report.stdout));
        out.join("meeting.basis")
    });
    (path.clone(), name)
}

// ---------------------------------------------------------------------------------------
// Running the firmware

/// `scripts/firmware.sh` exits with this when QEMU is missing and cannot be installed.
const NO_QEMU: i32 = 77;

/// Runs the firmware on the basis at `basis_path` (once per name in this test binary: runs
/// are cached and serialised, as they share one build directory). `None` when QEMU is
/// unavailable.
fn firmware(name: &str, basis_path: &Path) -> Option<Arc<FirmwareRun>> {
    static RUNS: OnceLock<Mutex<HashMap<String, Option<Arc<FirmwareRun>>>>> = OnceLock::new();
    let mut runs = RUNS
        .get_or_init(Default::default)
        .lock()
        .unwrap_or_else(|e| e.into_inner());
    if let Some(run) = runs.get(name) {
        return run.clone();
    }
    let out_path = work_dir().join(format!("{name}.out"));
    let script = root().join("scripts/firmware.sh");
    let output = Command::new("bash")
        .arg(&script)
        .arg(basis_path)
        .arg(&out_path)
        .output()
        .expect("run scripts/firmware.sh");
    let stderr = String::from_utf8_lossy(&output.stderr);
    let run = match output.status.code() {
        Some(0) => {
            let stdout = std::fs::read_to_string(&out_path).unwrap();
            let script_stdout = String::from_utf8_lossy(&output.stdout);
            let run = FirmwareRun::parse(&stdout, &script_stdout);
            eprintln!("firmware {name}: {}", summary(&run));
            Some(Arc::new(run))
        }
        Some(NO_QEMU) => {
            eprintln!("SKIPPED firmware test ({name}): QEMU is unavailable:\n{stderr}");
            None
        }
        _ => panic!(
            "scripts/firmware.sh failed ({}):\n{stderr}\n{}",
            output.status,
            std::fs::read_to_string(&out_path).unwrap_or_default()
        ),
    };
    runs.insert(name.to_string(), run.clone());
    run
}

fn summary(run: &FirmwareRun) -> String {
    format!(
        "basis {:?}, evaluator size_of {} (RAM_BYTES {}), channel evaluator size_of {} \
         (RAM_BYTES {}), stack {} of {}, instructions {:?} ({:.3} per tick), sizes {:?}",
        run.basis,
        run.evaluator_size_of,
        run.ram_bytes,
        run.channel_size_of,
        run.channel_ram_bytes,
        run.stack_high_water,
        run.stack_region,
        run.instructions,
        run.instructions_per_tick,
        run.sizes
    )
}

// ---------------------------------------------------------------------------------------
// The reference: `eigenrad eval --json`

/// One evaluation, as `eigenrad eval --json --patches` prints it: `{"unit", "bands",
/// "levels":[{name, level}], "sensors":[{name, irradiance}], "zones":[...],
/// "patches":[{id, surface, area, centroid, exitance, irradiance}]}`.
#[derive(Debug)]
struct Evaluation {
    unit: String,
    levels: Vec<(String, f64)>,
    sensors: Vec<(String, Vec<f64>)>,
    zones: Vec<(String, Vec<f64>)>,
    /// Exitance per band of every patch, in patch order.
    patches: Vec<Vec<f64>>,
}

fn numbers(v: &Value, what: &str) -> Vec<f64> {
    v.as_array()
        .unwrap_or_else(|| panic!("{what}: not an array: {v}"))
        .iter()
        .map(|x| {
            x.as_f64()
                .unwrap_or_else(|| panic!("{what}: not a number: {x}"))
        })
        .collect()
}

impl Evaluation {
    fn from_json(v: &Value) -> Evaluation {
        let list = |key: &str| -> &Vec<Value> {
            v[key]
                .as_array()
                .unwrap_or_else(|| panic!("no {key:?} in the eval JSON"))
        };
        let outputs = |key: &str| -> Vec<(String, Vec<f64>)> {
            list(key)
                .iter()
                .map(|o| {
                    let name = o["name"].as_str().expect("output name").to_string();
                    (name, numbers(&o["irradiance"], key))
                })
                .collect()
        };
        let patches = list("patches")
            .iter()
            .enumerate()
            .map(|(i, p)| {
                assert_eq!(p["id"].as_u64(), Some(i as u64), "patch ids in order");
                numbers(&p["exitance"], "patch exitance")
            })
            .collect();
        Evaluation {
            unit: v["unit"].as_str().expect("unit").to_string(),
            levels: list("levels")
                .iter()
                .map(|l| {
                    let name = l["name"].as_str().expect("level name").to_string();
                    (name, l["level"].as_f64().expect("level value"))
                })
                .collect(),
            sensors: outputs("sensors"),
            zones: outputs("zones"),
            patches,
        }
    }
}

/// `eigenrad eval BASIS --json --patches --level NAME=VALUE ...` with every channel named.
/// Each level is passed as the shortest decimal that reads back to the same `f32`.
fn eval_json(basis: &Path, levels: &[(String, f32)]) -> Evaluation {
    let mut args: Vec<std::ffi::OsString> = vec![
        "eval".into(),
        basis.into(),
        "--json".into(),
        "--patches".into(),
    ];
    for (name, level) in levels {
        args.push("--level".into());
        args.push(format!("{name}={level}").into());
    }
    let args: Vec<&std::ffi::OsStr> = args.iter().map(|a| a.as_os_str()).collect();
    let output = run_eigenrad(&args);
    let json: Value = serde_json::from_slice(&output.stdout).unwrap_or_else(|e| {
        panic!(
            "eigenrad eval printed no JSON ({e}):\n{}",
            String::from_utf8_lossy(&output.stdout)
        )
    });
    Evaluation::from_json(&json)
}
