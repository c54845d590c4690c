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
// A random basis (three bands)

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
    /// The `control` records (`examples/firmware/src/control.rs`), when the basis has them.
    control: Control,
    /// The `daylight` records (`examples/firmware/src/daylight.rs`), when the basis carries
    /// daylight.
    daylight: Option<Daylight>,
    /// The `harvest` records (`examples/firmware/src/harvest.rs`), when the basis carries
    /// daylight.
    harvest: Option<harvest::Harvest>,
    /// `size` lines of `scripts/firmware.sh`: label → field → bytes.
    sizes: HashMap<String, HashMap<String, usize>>,
}

/// The controller loop's records.
#[derive(Debug, Default, Clone)]
struct Control {
    /// Basis indices of the dimmed channels.
    channels: Vec<usize>,
    /// W at level 1 per dimmed channel.
    weights: Vec<f32>,
    sensor: usize,
    zone: usize,
    ratio: f32,
    /// Lux.
    target: f32,
    /// `size_of` the `LevelProblem` on the target, bytes.
    problem_size_of: usize,
    steps: Vec<ControlStep>,
}

/// One step of the controller loop; illuminances in lux.
#[derive(Debug, Default, Clone)]
struct ControlStep {
    daylight: f32,
    reading: f32,
    estimate: f32,
    ambient: f32,
    levels: Vec<f32>,
    arcs: Vec<u8>,
    /// W.
    power: f32,
    /// `None` when the target is met, else the failing bound and by how much (lux).
    unmet: Option<(usize, f32)>,
}

impl ControlStep {
    /// Reads `levels <l...> arc <a...> power <p> met | unmet <bound> <by>` into the step.
    fn parse_tail(&mut self, rest: &[&str], line: &str) {
        let at = |word: &str| {
            rest.iter()
                .position(|w| *w == word)
                .unwrap_or_else(|| panic!("no {word:?} in {line:?}"))
        };
        let (l, a, p) = (at("levels"), at("arc"), at("power"));
        self.levels = rest[l + 1..a].iter().map(|v| number(v, line)).collect();
        self.arcs = rest[a + 1..p].iter().map(|v| number(v, line)).collect();
        self.power = number(rest[p + 1], line);
        self.unmet = match &rest[p + 2..] {
            ["met"] => None,
            ["unmet", bound, by] => Some((number(bound, line), number(by, line))),
            _ => panic!("bad control status in {line:?}"),
        };
    }
}

/// The day loop's records.
#[derive(Debug, Default, Clone)]
struct Daylight {
    /// CIE standard general sky type.
    sky_type: u8,
    /// Lux.
    diffuse_horizontal: f32,
    /// Lux.
    direct_normal: f32,
    sky_patches: usize,
    nodes: usize,
    sun_nodes: usize,
    /// Latitude, longitude (degrees), elevation (m), UTC offset (minutes).
    site: [f32; 4],
    /// `(size_of, RAM_BYTES, [sky, outputs, modes])` of each daylight evaluator.
    evaluators: Vec<(usize, usize, [usize; 3])>,
    /// The zone a controller keeps, if the basis has zones.
    work_plane: Option<usize>,
    steps: Vec<DaylightStep>,
}

/// One step of the day loop; illuminances in lux.
#[derive(Debug, Default, Clone)]
struct DaylightStep {
    /// Local time with the site's UTC offset, as `eigenrad eval --time` reads it.
    time: String,
    /// Degrees.
    altitude: f64,
    /// Degrees clockwise from north.
    azimuth: f64,
    global_horizontal: f32,
    /// The runtime's own sun position (`sky::sun`, f32): altitude and azimuth, degrees.
    runtime_sun: Option<(f64, f64)>,
    sensors: Vec<(String, f64)>,
    zones: Vec<(String, f64)>,
    /// `(zone, [E_avg, E_min, E_max, U_o])` of each zone with a grid.
    figures: Vec<(String, [f64; 4])>,
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
                ["control", "channels", cs @ ..] => {
                    run.control.channels = cs.iter().map(|c| number(c, line)).collect();
                }
                ["control", "weights", ws @ ..] => {
                    run.control.weights = ws.iter().map(|w| number(w, line)).collect();
                }
                ["control", "setup", "sensor", s, "zone", z, "ratio", r, "target", t, "size_of", n] =>
                {
                    run.control.sensor = number(s, line);
                    run.control.zone = number(z, line);
                    run.control.ratio = number(r, line);
                    run.control.target = number(t, line);
                    run.control.problem_size_of = number(n, line);
                }
                ["control", "step", k, "daylight", d, "reading", r, "estimate", e, "ambient", a, rest @ ..] =>
                {
                    let k: usize = number(k, line);
                    assert_eq!(k, run.control.steps.len(), "control steps out of order");
                    let mut step = ControlStep {
                        daylight: number(d, line),
                        reading: number(r, line),
                        estimate: number(e, line),
                        ambient: number(a, line),
                        ..ControlStep::default()
                    };
                    step.parse_tail(rest, line);
                    run.control.steps.push(step);
                }
                ["daylight", "setup", "sky", "cie", t, "diffuse_horizontal", d, "direct_normal", n, "sky_patches", sp, "nodes", nodes, "sun_nodes", sun] =>
                {
                    let day = run.daylight.get_or_insert_with(Daylight::default);
                    day.sky_type = number(t, line);
                    day.diffuse_horizontal = number(d, line);
                    day.direct_normal = number(n, line);
                    day.sky_patches = number(sp, line);
                    day.nodes = number(nodes, line);
                    day.sun_nodes = number(sun, line);
                }
                ["daylight", "site", "latitude", la, "longitude", lo, "elevation", el, "utc_offset_minutes", off] =>
                {
                    let day = run.daylight.as_mut().expect("daylight site before setup");
                    day.site = [la, lo, el, off].map(|v| number(v, line));
                }
                ["daylight_evaluator", "size_of", s, "ram_bytes", r, "capacity", sky, o, p] => {
                    let day = run
                        .daylight
                        .as_mut()
                        .expect("daylight evaluator before setup");
                    let capacity = [sky, o, p].map(|v| number(v, line));
                    day.evaluators
                        .push((number(s, line), number(r, line), capacity));
                }
                ["daylight", "zone", "work_plane", z] => {
                    let day = run.daylight.as_mut().expect("daylight zone before setup");
                    day.work_plane = Some(number(z, line));
                }
                ["daylight", "step", k, "time", t, "altitude", a, "azimuth", az, "global_horizontal", g] =>
                {
                    let day = run.daylight.as_mut().expect("daylight step before setup");
                    let k: usize = number(k, line);
                    assert_eq!(
                        k,
                        day.steps.len(),
                        "daylight steps out of order at {line:?}"
                    );
                    day.steps.push(DaylightStep {
                        time: t.to_string(),
                        altitude: number(a, line),
                        azimuth: number(az, line),
                        global_horizontal: number(g, line),
                        ..DaylightStep::default()
                    });
                }
                ["daylight", "sun_runtime", k, "altitude", a, "azimuth", az] => {
                    let day = run.daylight.as_mut().expect("runtime sun before setup");
                    assert_eq!(number::<usize>(k, line) + 1, day.steps.len());
                    let step = day.steps.last_mut().expect("runtime sun before a step");
                    step.runtime_sun = Some((number(a, line), number(az, line)));
                }
                ["daylight", "reading", k, kind @ ("sensor" | "zone"), rest @ ..] => {
                    let day = run
                        .daylight
                        .as_mut()
                        .expect("daylight reading before setup");
                    assert_eq!(number::<usize>(k, line) + 1, day.steps.len());
                    let step = day
                        .steps
                        .last_mut()
                        .expect("daylight reading before a step");
                    let (name, values) = named_values(rest, 1, line);
                    if *kind == "sensor" {
                        step.sensors.push((name, values[0]));
                    } else {
                        step.zones.push((name, values[0]));
                    }
                }
                ["daylight", "figures", k, "average", a, "minimum", mi, "maximum", ma, "uniformity", u, "zone", name @ ..] =>
                {
                    let day = run
                        .daylight
                        .as_mut()
                        .expect("daylight figures before setup");
                    assert_eq!(number::<usize>(k, line) + 1, day.steps.len());
                    let step = day
                        .steps
                        .last_mut()
                        .expect("daylight figures before a step");
                    let figures = [a, mi, ma, u].map(|v| f64::from(number::<f32>(v, line)));
                    step.figures.push((name.join(" "), figures));
                }
                ["harvest", rest @ ..] => run
                    .harvest
                    .get_or_insert_with(Default::default)
                    .parse(rest, line),
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
