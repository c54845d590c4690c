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
//! - the office example (`examples/office/scene.toml`, 1101 patches, 5 channels, 2 sensors,
//!   2 zones) at 32 modes, f32 storage;
//! - the same office on a coarser mesh (`max_edge` 0.7 m instead of 0.35 m: 337 patches) at
//!   16 modes in f16 and at 64 modes in i16. A build's form factors cost grows as the square
//!   of the patch count, so the coarse mesh keeps the test's run time down while the
//!   precisions and mode counts still differ from the f32 basis;
//! - a random three-band basis (tables of plausible size but no room behind them): the RGB
//!   example scene, the Cornell box, takes as long to build as the office.
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

use eigenrad_runtime::dali::arc_power_to_level;
use eigenrad_runtime::writer::BasisTables;
use eigenrad_runtime::{Basis, ChannelEvaluator, Evaluator, Formulation, Precision, Quantity};
use serde_json::Value;

/// Readings agree within this fraction of the larger of the reference and the output's
/// reading with every channel at 1. The firmware applies the levels step by step,
/// `eigenrad eval` sets each state at once; both sum the same `m` stored (f32, f16 or i16)
/// products per band in `f32` with the same runtime code, so they differ by the rounding of
/// two compilations of that sum at most (a few times 2⁻²⁴ ≈ 6e-8), orders of magnitude below
/// this.
const REL_TOL: f64 = 1e-4;

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

/// The office scene with `max_edge` 0.7 m (337 patches instead of 1101), written next to
/// the test's bases. Everything else (geometry, materials, channels, sensors, zones) is
/// the example's.
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
    let coarse: Vec<&str> = text
        .lines()
        .enumerate()
        .map(|(i, l)| if i == matches[0] { COARSE_MAX_EDGE } else { l })
        .collect();
    let path = work_dir().join("office-coarse.toml");
    std::fs::write(&path, coarse.join("\n") + "\n").unwrap();
    path
}

/// Which office mesh a basis is built from.
#[derive(Clone, Copy, Debug)]
enum Mesh {
    /// `examples/office/scene.toml` as it is.
    Office,
    /// [`coarse_office_scene`].
    Coarse,
}

/// `eigenrad build` of the office at `modes` modes per band and storage `precision`
/// (`f32`, `f16`, `i16`), once per test run. Returns the basis' path and name.
fn office_basis(mesh: Mesh, modes: usize, precision: &str) -> (PathBuf, String) {
    static BUILT: OnceLock<Mutex<HashMap<String, PathBuf>>> = OnceLock::new();
    let name = match mesh {
        Mesh::Office => format!("office-p{modes}-{precision}"),
        Mesh::Coarse => format!("office-coarse-p{modes}-{precision}"),
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
    };
    let path = work_dir().join(format!("{name}.basis"));
    let modes = modes.to_string();
    let report = run_eigenrad(&[
        "build".as_ref(),
        scene.as_os_str(),
        "-o".as_ref(),
        path.as_os_str(),
        "--modes".as_ref(),
        modes.as_ref(),
        "--precision".as_ref(),
        precision.as_ref(),
    ]);
    eprintln!("built {name}:\n{}", String::from_utf8_lossy(&report.stdout));
    built.insert(name.clone(), path.clone());
    (path, name)
}

// ---------------------------------------------------------------------------------------
// A random basis (three bands)

/// xorshift64*: deterministic, dependency-free.
struct Rng(u64);
impl Rng {
    fn next_f64(&mut self) -> f64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        (self.0.wrapping_mul(0x2545_F491_4F6C_DD1D) >> 11) as f64 / (1u64 << 53) as f64
    }
    fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.next_f64()
    }
}

/// Dimensions of a random basis.
#[derive(Clone, Copy)]
struct Dims {
    patches: usize,
    modes: usize,
    bands: usize,
    channels: usize,
    sensors: usize,
    zones: usize,
}

/// A random split-formulation basis with consistent dimensions and plausible magnitudes: the
/// numbers are not a room's, but every table the evaluator reads is filled.
fn random_basis(seed: u64, d: Dims, precision: Precision) -> Vec<u8> {
    let mut rng = Rng(seed | 1);
    let (n, p, bands, m) = (d.patches, d.modes, d.bands, d.channels);
    let outputs = d.sensors + d.zones;
    let quantity = if bands == 1 {
        Quantity::Photometric
    } else {
        Quantity::Radiometric
    };
    let mut t = BasisTables {
        surface_names: vec!["walls".into(), "luminaires".into()],
        channel_names: (0..m).map(|c| format!("ch{c}")).collect(),
        sensor_names: (0..d.sensors).map(|s| format!("desk{s}")).collect(),
        zone_names: (0..d.zones).map(|z| format!("plane{z}")).collect(),
        ..BasisTables::new(quantity, Formulation::Split, precision, bands, p)
    };
    t.eigenvalues = (0..bands * p).map(|_| rng.range(-0.3, 0.9)).collect();
    for i in 0..n {
        t.patch_area.push(rng.range(0.05, 0.5));
        t.patch_centroid.push([
            rng.range(0.0, 6.0),
            rng.range(0.0, 4.0),
            rng.range(0.0, 3.0),
        ]);
        let lamp = i % 11 == 5;
        t.patch_surface.push(u16::from(lamp));
        t.patch_channel.push(lamp.then_some((i % m) as u16));
        for _ in 0..bands {
            // Every other luminaire patch is black (ρ = 0), so the black-patch tables are
            // exercised too.
            t.patch_reflectance.push(if lamp && i % 2 == 1 {
                0.0
            } else {
                rng.range(0.05, 0.9)
            });
            t.patch_emission
                .push(if lamp { rng.range(500.0, 5000.0) } else { 0.0 });
        }
    }
    let black = (0..n)
        .filter(|&i| (0..bands).any(|b| t.patch_reflectance[i * bands + b] == 0.0))
        .count();
    for i in 0..n {
        for b in 0..bands {
            let is_black = t.patch_reflectance[i * bands + b] == 0.0;
            for _ in 0..p {
                t.modes
                    .push(if is_black { 0.0 } else { rng.range(-1.0, 1.0) });
            }
        }
    }
    t.black_projection = (0..black * bands * p)
        .map(|_| rng.range(-0.5, 0.5))
        .collect();
    // Each channel's exitance on every patch: reflected light everywhere plus the emission
    // of the channel's own luminaires, as an exact response has it.
    for i in 0..n {
        for c in 0..m {
            for b in 0..bands {
                let own = t.patch_channel[i] == Some(c as u16);
                let emission = if own {
                    t.patch_emission[i * bands + b]
                } else {
                    0.0
                };
                t.channel_response.push(emission + rng.range(0.0, 80.0));
            }
        }
    }
    t.sensor_geometry = (0..d.sensors)
        .map(|_| [1.0, 2.0, 0.8, 0.0, 0.0, 1.0, 1.2])
        .collect();
    t.zone_area = (0..d.zones).map(|_| rng.range(5.0, 20.0)).collect();
    // Mostly positive, as the dominant modes of a room are: readings stay well away from 0.
    t.output_modes = (0..outputs * bands * p)
        .map(|_| rng.range(-0.1, 0.5))
        .collect();
    t.output_channels = (0..outputs * bands * m)
        .map(|_| rng.range(0.0, 60.0))
        .collect();
    t.output_view = (0..n * outputs).map(|_| rng.range(0.0, 0.05)).collect();
    t.to_bytes().expect("random tables encode")
}

/// Dimensions of the random RGB basis: 200 patches, 24 modes, 3 bands, 3 channels, 2
/// sensors, 1 zone.
const RGB: Dims = Dims {
    patches: 200,
    modes: 24,
    bands: 3,
    channels: 3,
    sensors: 2,
    zones: 1,
};

/// The random RGB basis, written next to the test's other bases.
fn rgb_basis() -> PathBuf {
    let path = work_dir().join("random-rgb.basis");
    std::fs::write(&path, random_basis(12, RGB, Precision::F32)).unwrap();
    path
}

// ---------------------------------------------------------------------------------------
// Running the firmware

/// What one firmware run printed.
#[derive(Debug, Default)]
struct FirmwareRun {
    /// `basis ...` fields, e.g. `bytes`, `patches`.
    basis: HashMap<String, usize>,
    /// `size_of` the full evaluator on the target, bytes.
    evaluator_size_of: usize,
    /// `Evaluator::RAM_BYTES` on the target.
    ram_bytes: usize,
    /// `size_of` the channel evaluator on the target, bytes.
    channel_size_of: usize,
    /// `ChannelEvaluator::RAM_BYTES` on the target.
    channel_ram_bytes: usize,
    steps: Vec<Step>,
    /// Instructions per call, by operation (`full_update`, ...).
    instructions: HashMap<String, u64>,
    /// Measured instructions per SysTick tick.
    instructions_per_tick: f64,
    stack_high_water: usize,
    stack_region: usize,
    /// `size` lines of `scripts/firmware.sh`: label → field → bytes.
    sizes: HashMap<String, HashMap<String, usize>>,
}

/// One state of the firmware's level sequence.
#[derive(Debug, Default, Clone)]
struct Step {
    /// The operation as printed after `op`, e.g. `arc 1 200`.
    op: String,
    levels: Vec<f32>,
    sensors: Vec<(String, Vec<f64>)>,
    zones: Vec<(String, Vec<f64>)>,
    /// `(patch, exitance per band)` for the sample of patches the firmware prints.
    patches: Vec<(usize, Vec<f64>)>,
}

fn number<T: std::str::FromStr>(field: &str, line: &str) -> T {
    field
        .parse()
        .unwrap_or_else(|_| panic!("not a number: {field:?} in {line:?}"))
}

/// Values `name v0 [v1 v2]` at the end of a reading line; a name may contain spaces.
fn named_values(rest: &[&str], bands: usize, line: &str) -> (String, Vec<f64>) {
    assert!(rest.len() > bands, "short reading line {line:?}");
    let (name, values) = rest.split_at(rest.len() - bands);
    // Printed as the shortest decimal that reads back to the same f32: read it as one.
    let values = values
        .iter()
        .map(|v| f64::from(number::<f32>(v, line)))
        .collect();
    (name.join(" "), values)
}

impl FirmwareRun {
    /// Parses the firmware's records; any unknown record fails, so the format stays in step
    /// with `examples/firmware/src/main.rs`.
    fn parse(stdout: &str, script_stdout: &str) -> FirmwareRun {
        let mut run = FirmwareRun::default();
        let mut done = false;
        for line in stdout.lines() {
            let f: Vec<&str> = line.split(' ').collect();
            let bands = run.basis.get("bands").copied().unwrap_or(1);
            match f.as_slice() {
                ["basis", kv @ ..] => {
                    for pair in kv.chunks(2) {
                        if let [k, v] = pair {
                            run.basis.insert(k.to_string(), number(v, line));
                        }
                    }
                }
                ["systick", "calibration", "instructions", i, "ticks", t, "instructions_per_tick", _] =>
                {
                    run.instructions_per_tick =
                        number::<f64>(i, line) / number::<f64>(t, line).max(1.0);
                }
                ["evaluator", "size_of", s, "ram_bytes", r, "capacity", ..] => {
                    run.evaluator_size_of = number(s, line);
                    run.ram_bytes = number(r, line);
                }
                ["channel_evaluator", "size_of", s, "ram_bytes", r, "capacity", ..] => {
                    run.channel_size_of = number(s, line);
                    run.channel_ram_bytes = number(r, line);
                }
                ["step", k, "op", op @ ..] => {
                    let k: usize = number(k, line);
                    assert_eq!(k, run.steps.len(), "steps out of order at {line:?}");
                    run.steps.push(Step {
                        op: op.join(" "),
                        ..Step::default()
                    });
                }
                ["step", k, "levels", levels @ ..] => {
                    assert_eq!(number::<usize>(k, line) + 1, run.steps.len());
                    let step = run.steps.last_mut().expect("levels before op");
                    step.levels = levels.iter().map(|v| number(v, line)).collect();
                }
                ["reading", k, kind @ ("sensor" | "zone"), rest @ ..] => {
                    assert_eq!(number::<usize>(k, line) + 1, run.steps.len());
                    let step = run.steps.last_mut().expect("reading before op");
                    let reading = named_values(rest, bands, line);
                    if *kind == "sensor" {
                        step.sensors.push(reading);
                    } else {
                        step.zones.push(reading);
                    }
                }
                ["exitance", k, "patch", i, values @ ..] => {
                    assert_eq!(number::<usize>(k, line) + 1, run.steps.len());
                    assert_eq!(values.len(), bands, "exitance bands in {line:?}");
                    let step = run.steps.last_mut().expect("exitance before op");
                    let values = values
                        .iter()
                        .map(|v| f64::from(number::<f32>(v, line)))
                        .collect();
                    step.patches.push((number(i, line), values));
                }
                ["timing", ..] => {}
                ["instructions", what, n] => {
                    run.instructions.insert(what.to_string(), number(n, line));
                }
                ["stack", "high_water", h, "region", r] => {
                    run.stack_high_water = number(h, line);
                    run.stack_region = number(r, line);
                }
                ["done"] => done = true,
                _ => panic!("unknown firmware record {line:?}"),
            }
        }
        assert!(done, "the firmware did not finish:\n{stdout}");
        for line in script_stdout.lines() {
            if let ["size", label, kv @ ..] = line.split(' ').collect::<Vec<_>>().as_slice() {
                let fields = kv
                    .chunks(2)
                    .filter_map(|p| match p {
                        [k, v] => Some((k.to_string(), number(v, line))),
                        _ => None,
                    })
                    .collect();
                run.sizes.insert(label.to_string(), fields);
            }
        }
        run
    }
}

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

// ---------------------------------------------------------------------------------------
// Checks

/// The operations and levels the firmware is meant to apply to a basis with `m` channels.
fn expected_steps(m: usize) -> Vec<(String, Vec<f32>)> {
    let mut levels = vec![1.0f32; m];
    let mut steps = vec![(format!("all {:e}", 1.0f32), levels.clone())];
    levels[0] = HALF;
    steps.push((format!("level 0 {HALF:e}"), levels.clone()));
    for c in 0..m {
        for arc in ARC_LEVELS {
            levels[c] = arc_power_to_level(arc).unwrap();
            steps.push((format!("arc {c} {arc}"), levels.clone()));
        }
    }
    steps
}

/// Largest difference seen so far, relative as in [`REL_TOL`], and where it was.
#[derive(Default)]
struct Worst {
    compared: usize,
    relative: f64,
    at: String,
}

impl Worst {
    /// Checks `firmware` against `reference` with `scale` (the reading with every channel at
    /// 1) as the floor of the relative test, and records the difference.
    fn check(&mut self, firmware: f64, reference: f64, scale: f64, what: &dyn Fn() -> String) {
        let relative = (firmware - reference).abs() / reference.abs().max(scale.abs());
        assert!(
            relative <= REL_TOL,
            "{}: firmware {firmware:e}, eigenrad eval {reference:e} (relative {relative:e})",
            what()
        );
        self.compared += 1;
        if relative > self.relative || self.at.is_empty() {
            self.relative = relative;
            self.at = what();
        }
    }
}

/// Runs the firmware on the basis at `path` and checks every reading and every printed patch
/// exitance against `eigenrad eval --json` at each step. Returns the run, or `None` when
/// QEMU is unavailable.
fn check_against_eval(name: &str, path: &Path) -> Option<Arc<FirmwareRun>> {
    let run = firmware(name, path)?;
    let bytes = std::fs::read(path).unwrap();
    let basis = Basis::from_bytes(&bytes).unwrap();
    let m = basis.channel_count();
    let bands = basis.bands();
    let channel_names: Vec<String> = (0..m)
        .map(|c| basis.channel_name(c).unwrap().to_string())
        .collect();
    let unit = match basis.quantity() {
        Quantity::Photometric => "lux",
        _ => "W/m²",
    };
    let sample: Vec<usize> = (0..basis.patch_count()).step_by(PATCH_STRIDE).collect();

    let expected = expected_steps(m);
    assert_eq!(run.steps.len(), expected.len(), "number of steps");

    // Each quantity's value with every channel at 1 (step 0) is the floor of the relative
    // test: all levels in the sequence are at most 1, so the rounding residue of incremental
    // updates is bounded by it. Where a reading is small (its channels off) a test relative
    // to the reading itself would measure that residue instead of a disagreement.
    let full = &run.steps[0];
    let mut worst = Worst::default();
    for (k, (step, (op, levels))) in run.steps.iter().zip(&expected).enumerate() {
        assert_eq!(&step.op, op, "step {k}");
        assert_eq!(step.levels.len(), m, "step {k} levels");
        for (c, (&got, &want)) in step.levels.iter().zip(levels).enumerate() {
            // The same f32 DALI curve runs on both sides; the printed form reads back exactly.
            assert_eq!(got, want, "step {k} channel {c} level");
        }
        let named: Vec<(String, f32)> = channel_names
            .iter()
            .cloned()
            .zip(step.levels.iter().copied())
            .collect();
        let reference = eval_json(path, &named);
        assert_eq!(reference.unit, unit, "step {k}: unit");
        // eval used exactly the firmware's levels.
        assert_eq!(reference.levels.len(), m, "step {k}: eval levels");
        for ((rname, rlevel), (name, level)) in reference.levels.iter().zip(&named) {
            assert_eq!(rname, name, "step {k}: eval channel order");
            assert_eq!(*rlevel as f32, *level, "step {k}: eval level of {name}");
        }

        for (kind, got, want, at_full) in [
            ("sensor", &step.sensors, &reference.sensors, &full.sensors),
            ("zone", &step.zones, &reference.zones, &full.zones),
        ] {
            assert_eq!(got.len(), want.len(), "step {k}: {kind} count");
            for (o, ((gname, gv), (wname, wv))) in got.iter().zip(want).enumerate() {
                assert_eq!(gname, wname, "step {k}: {kind} {o} name");
                assert_eq!(gv.len(), bands, "step {k}: {kind} {gname} bands");
                assert_eq!(wv.len(), bands, "step {k}: eval {kind} {gname} bands");
                for b in 0..bands {
                    worst.check(gv[b], wv[b], at_full[o].1[b], &|| {
                        format!("step {k} ({op}): {kind} {gname} band {b}")
                    });
                }
            }
        }

        let printed: Vec<usize> = step.patches.iter().map(|(i, _)| *i).collect();
        assert_eq!(printed, sample, "step {k}: patches printed");
        assert_eq!(reference.patches.len(), basis.patch_count(), "eval patches");
        for (j, (i, gv)) in step.patches.iter().enumerate() {
            let wv = &reference.patches[*i];
            assert_eq!(wv.len(), bands, "step {k}: eval patch {i} bands");
            for b in 0..bands {
                worst.check(gv[b], wv[b], full.patches[j].1[b], &|| {
                    format!("step {k} ({op}): patch {i} exitance band {b}")
                });
            }
        }
    }
    let outputs = basis.sensor_count() + basis.zone_count();
    assert_eq!(
        worst.compared,
        expected.len() * (outputs + sample.len()) * bands
    );
    eprintln!(
        "firmware {name}: {} values against eigenrad eval, largest relative difference {:e} \
         ({})",
        worst.compared, worst.relative, worst.at
    );

    // Measurements: present, and the SysTick scale is the one QEMU's mps2-an386 model implies
    // (25 MHz SYSCLK, 1 ns per instruction under -icount shift=0: 40 instructions a tick), to
    // the ±1 tick of quantisation over the calibration's 200 000 ticks.
    assert!(
        (run.instructions_per_tick - 40.0).abs() < 0.01,
        "instructions per SysTick tick: {}",
        run.instructions_per_tick
    );
    for what in INSTRUCTIONS {
        assert!(run.instructions.get(what).is_some_and(|&n| n > 0), "{what}");
    }
    assert_eq!(run.instructions.len(), INSTRUCTIONS.len());
    assert!(0 < run.stack_high_water && run.stack_high_water < run.stack_region);
    assert_eq!(run.basis["bytes"], bytes.len());
    assert_eq!(run.basis["modes"], basis.mode_count());
    Some(run)
}

/// The operations the firmware times (`measure` in `examples/firmware/src/main.rs`).
const INSTRUCTIONS: [&str; 9] = [
    "full_update",
    "channel_update",
    "read_outputs",
    "full_update_read_outputs",
    "channel_update_read_outputs",
    "channel_exitance",
    "patch_update",
    "patch_read_outputs",
    "patch_exitance",
];

/// Instruction budgets for the office at 32 modes (issue 12, docs/embedded.md): a full update
/// of every channel plus the read of every output, and one channel's update. QEMU counts
/// instructions exactly (`-icount shift=0`), so the figures repeat from run to run; a change
/// that exceeds a budget fails here rather than in a later table.
const BUDGET_FULL_UPDATE_READ_OUTPUTS: u64 = 1000;
const BUDGET_CHANNEL_UPDATE: u64 = 300;

#[test]
fn firmware_matches_eval_office_f32() {
    let (path, name) = office_basis(Mesh::Office, 32, "f32");
    let Some(run) = check_against_eval(&name, &path) else {
        return;
    };
    // The office example as documented: 5 channels, 2 sensors, 2 zones, about 1100 patches.
    assert_eq!(run.basis["channels"], 5);
    assert_eq!(run.basis["sensors"], 2);
    assert_eq!(run.basis["zones"], 2);
    assert!(run.basis["patches"] > 1000);
    let full = run.instructions["full_update_read_outputs"];
    assert!(
        full <= BUDGET_FULL_UPDATE_READ_OUTPUTS,
        "full update and every output read: {full} instructions, budget \
         {BUDGET_FULL_UPDATE_READ_OUTPUTS}"
    );
    let one = run.instructions["channel_update"];
    assert!(
        one <= BUDGET_CHANNEL_UPDATE,
        "one channel: {one} instructions, budget {BUDGET_CHANNEL_UPDATE}"
    );
}

/// Mode vectors, channel responses and view rows in f16: the patch exitances read them.
#[test]
fn firmware_matches_eval_office_f16() {
    let (path, name) = office_basis(Mesh::Coarse, 16, "f16");
    check_against_eval(&name, &path);
}

/// The same tables in i16 with a per-column scale, at 64 modes.
#[test]
fn firmware_matches_eval_office_i16() {
    let (path, name) = office_basis(Mesh::Coarse, 64, "i16");
    check_against_eval(&name, &path);
}

#[test]
fn firmware_matches_eval_rgb() {
    check_against_eval("random-rgb", &rgb_basis());
}

/// The evaluators' state is fixed by their capacities: bases of 16, 32 and 64 modes, up to a
/// thousand times larger than the 2-patch one, take the same RAM on the host and on the
/// target, and the basis goes to flash. The channel evaluator holds one level per channel.
#[test]
fn evaluator_ram_does_not_grow_with_basis() {
    type Fw<'a> = Evaluator<'a, 1, FW_PATCHES, FW_MODES, FW_CHANNELS, FW_OUTPUTS>;
    type FwChannels<'a> = ChannelEvaluator<'a, 1, FW_CHANNELS>;
    let tiny = tiny_basis_path();
    let office = [
        office_basis(Mesh::Coarse, 16, "f16"),
        office_basis(Mesh::Office, 32, "f32"),
        office_basis(Mesh::Coarse, 64, "i16"),
    ];
    let small = std::fs::read(&tiny).unwrap();
    let a = Fw::new(Basis::from_bytes(&small).unwrap()).unwrap();
    let ca = FwChannels::new(Basis::from_bytes(&small).unwrap()).unwrap();
    for (path, name) in &office {
        let large = std::fs::read(path).unwrap();
        assert!(
            large.len() > 100 * small.len(),
            "{name}: a much larger basis"
        );
        let b = Fw::new(Basis::from_bytes(&large).unwrap()).unwrap();
        assert_eq!(
            std::mem::size_of_val(&a),
            std::mem::size_of_val(&b),
            "{name}"
        );
        let cb = FwChannels::new(Basis::from_bytes(&large).unwrap()).unwrap();
        assert_eq!(
            std::mem::size_of_val(&ca),
            std::mem::size_of_val(&cb),
            "{name}"
        );
    }
    // The state is RAM_BYTES plus the basis' slice headers (pointers and lengths).
    assert!(std::mem::size_of_val(&a) >= Fw::RAM_BYTES);
    assert!(std::mem::size_of_val(&ca) >= FwChannels::RAM_BYTES);
    assert_eq!(FwChannels::RAM_BYTES, 4 * FW_CHANNELS);

    let Some(small_run) = firmware("tiny", &tiny) else {
        return;
    };
    assert_eq!(small_run.ram_bytes, Fw::RAM_BYTES);
    assert_eq!(small_run.channel_ram_bytes, FwChannels::RAM_BYTES);
    // On the target the channel evaluator is its levels and the basis view: a few hundred
    // bytes against the full evaluator's kilobytes of per-patch state.
    assert!(small_run.channel_size_of < FwChannels::RAM_BYTES + 512);
    // Flash is where the basis goes: .rodata grows by the basis' size, give or take the
    // alignment padding around it (seen: 4 bytes less than the size difference).
    const PADDING: usize = 64;
    let rodata = |run: &FirmwareRun| run.sizes["basis"]["rodata"];
    for ((path, name), modes) in office.iter().zip([16, 32, 64]) {
        let Some(run) = firmware(name, path) else {
            return;
        };
        let bytes = std::fs::metadata(path).unwrap().len() as usize;
        assert_eq!(run.basis["modes"], modes, "{name}");
        assert_eq!(
            run.evaluator_size_of, small_run.evaluator_size_of,
            "{name}: evaluator size_of on the target"
        );
        assert_eq!(
            run.channel_size_of, small_run.channel_size_of,
            "{name}: channel evaluator size_of on the target"
        );
        assert_eq!(run.ram_bytes, Fw::RAM_BYTES, "{name}");
        assert_eq!(run.channel_ram_bytes, FwChannels::RAM_BYTES, "{name}");
        assert!(
            rodata(&run) + PADDING >= rodata(&small_run) + bytes - small.len(),
            "{name}: .rodata {} with the basis, {} with tiny.basis, basis {bytes} bytes",
            rodata(&run),
            rodata(&small_run)
        );
    }
}

#[test]
fn parser_reads_names_with_spaces() {
    let stdout = "basis bytes 1 bands 1\nstep 0 op all 1e0\nstep 0 levels 1e0\n\
                  reading 0 sensor north desk 2.5e2\nexitance 0 patch 97 1.5e1\ndone\n";
    let run = FirmwareRun::parse(stdout, "");
    assert_eq!(
        run.steps[0].sensors[0],
        ("north desk".to_string(), vec![250.0])
    );
    assert_eq!(run.steps[0].patches[0], (97, vec![15.0]));
}
