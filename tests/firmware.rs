//! The firmware example (`examples/firmware`) run under QEMU agrees with a host evaluation,
//! and its evaluator's RAM does not grow with the basis.
//!
//! Each test writes a basis, runs `scripts/firmware.sh` on it (build for
//! `thumbv7em-none-eabihf`, run on QEMU `mps2-an386`), parses the records the firmware prints
//! and checks every sensor and zone reading against a reference evaluation at the levels the
//! firmware reports. The reference has the shape of `eigenrad eval --json` (see
//! [`reference_json`]): switching to the CLI means replacing that one function.
//!
//! When QEMU is missing and cannot be installed, the tests say so on stderr and return
//! without checking anything.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use std::collections::HashMap;
use std::path::PathBuf;
use std::process::Command;
use std::sync::{Arc, Mutex, OnceLock};

use eigenrad_runtime::dali::arc_power_to_level;
use eigenrad_runtime::writer::BasisTables;
use eigenrad_runtime::{Basis, Evaluator, Formulation, Precision, Quantity};
use serde_json::{json, Value};

/// Readings agree within this fraction. The firmware applies the levels step by step
/// (incremental updates), the reference evaluates each state from scratch; both are `f32`
/// with sums of `p` terms, so they differ by rounding, orders of magnitude below this.
const REL_TOL: f64 = 1e-4;

/// Capacities of the firmware's evaluator (`examples/firmware/src/main.rs`).
const FW_PATCHES: usize = 2048;
const FW_MODES: usize = 128;
const FW_CHANNELS: usize = 8;
const FW_OUTPUTS: usize = 8;

/// DALI arc levels the firmware applies to each channel in turn, and the level it sets
/// channel 0 to after all channels start at 1 (`examples/firmware/src/main.rs`).
const ARC_LEVELS: [u8; 5] = [254, 200, 128, 1, 0];
const HALF: f32 = 0.5;

// ---------------------------------------------------------------------------------------
// Bases

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
    let mut t = BasisTables {
        quantity: Some(if bands == 1 {
            Quantity::Photometric
        } else {
            Quantity::Radiometric
        }),
        formulation: Some(Formulation::Split),
        precision: Some(precision),
        bands,
        modes: p,
        surface_names: vec!["walls".into(), "luminaires".into()],
        channel_names: (0..m).map(|c| format!("ch{c}")).collect(),
        sensor_names: (0..d.sensors).map(|s| format!("desk{s}")).collect(),
        zone_names: (0..d.zones).map(|z| format!("plane{z}")).collect(),
        ..Default::default()
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
                t.mode_vectors
                    .push(if is_black { 0.0 } else { rng.range(-1.0, 1.0) });
            }
        }
    }
    t.black_projection = (0..black * bands * p)
        .map(|_| rng.range(-0.5, 0.5))
        .collect();
    t.channel_projection = (0..m * bands * p)
        .map(|_| rng.range(-50.0, 500.0))
        .collect();
    t.channel_bounce = (0..n * m * bands).map(|_| rng.range(0.0, 80.0)).collect();
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

/// The bases of the brief: 300 patches, 32 modes, 3 channels, 2 sensors, 1 zone.
const ROOM: Dims = Dims {
    patches: 300,
    modes: 32,
    bands: 1,
    channels: 3,
    sensors: 2,
    zones: 1,
};

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

fn tiny_basis() -> Vec<u8> {
    std::fs::read(root().join("runtime/tests/data/tiny.basis")).unwrap()
}

// ---------------------------------------------------------------------------------------
// Running the firmware

/// What one firmware run printed.
#[derive(Debug, Default)]
struct FirmwareRun {
    /// `basis ...` fields, e.g. `bytes`, `patches`.
    basis: HashMap<String, usize>,
    /// `size_of` the evaluator on the target, bytes.
    evaluator_size_of: usize,
    /// `Evaluator::RAM_BYTES` on the target.
    ram_bytes: usize,
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

/// Runs the firmware on `basis` (once per name in this test binary: runs are cached and
/// serialised, as they share one build directory). `None` when QEMU is unavailable.
fn firmware(name: &str, basis: &[u8]) -> Option<Arc<FirmwareRun>> {
    static RUNS: OnceLock<Mutex<HashMap<String, Option<Arc<FirmwareRun>>>>> = OnceLock::new();
    let mut runs = RUNS
        .get_or_init(Default::default)
        .lock()
        .unwrap_or_else(|e| e.into_inner());
    if let Some(run) = runs.get(name) {
        return run.clone();
    }
    let dir = root().join("target/firmware-test");
    std::fs::create_dir_all(&dir).unwrap();
    let basis_path = dir.join(format!("{name}.basis"));
    let out_path = dir.join(format!("{name}.out"));
    std::fs::write(&basis_path, basis).unwrap();
    let script = root().join("scripts/firmware.sh");
    let output = Command::new("bash")
        .arg(&script)
        .arg(&basis_path)
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
        "basis {:?}, evaluator size_of {} (RAM_BYTES {}), stack {} of {}, \
         instructions {:?} ({:.3} per tick), sizes {:?}",
        run.basis,
        run.evaluator_size_of,
        run.ram_bytes,
        run.stack_high_water,
        run.stack_region,
        run.instructions,
        run.instructions_per_tick,
        run.sizes
    )
}

// ---------------------------------------------------------------------------------------
// The reference

/// One evaluation: the content of `eigenrad eval --json`.
#[derive(Debug)]
struct Evaluation {
    sensors: Vec<(String, Vec<f64>)>,
    zones: Vec<(String, Vec<f64>)>,
}

impl Evaluation {
    /// Reads `{"unit", "bands", "levels":[{name, level}], "sensors":[{name, irradiance}],
    /// "zones":[...]}`.
    fn from_json(v: &Value) -> Evaluation {
        let outputs = |key: &str| -> Vec<(String, Vec<f64>)> {
            v[key]
                .as_array()
                .unwrap_or_else(|| panic!("no {key:?} in {v}"))
                .iter()
                .map(|o| {
                    let name = o["name"].as_str().expect("output name").to_string();
                    let values = o["irradiance"]
                        .as_array()
                        .expect("irradiance")
                        .iter()
                        .map(|x| x.as_f64().expect("irradiance value"))
                        .collect();
                    (name, values)
                })
                .collect()
        };
        Evaluation {
            sensors: outputs("sensors"),
            zones: outputs("zones"),
        }
    }
}

/// The reference evaluation of `basis` with channels at `levels` (name → relative level),
/// as `eigenrad eval --json --level NAME=VALUE ...` will print it. For now the runtime's
/// evaluator on the host, with room to spare, evaluating each state from scratch.
fn reference_json(basis: &[u8], levels: &[(String, f32)]) -> Value {
    let basis = Basis::from_bytes(basis).unwrap();
    match basis.bands() {
        1 => host_json::<1>(basis, levels),
        3 => host_json::<3>(basis, levels),
        b => panic!("{b} bands"),
    }
}

fn host_json<const B: usize>(basis: Basis<'_>, levels: &[(String, f32)]) -> Value {
    let mut eval = Evaluator::<B, 4096, 256, 16, 16>::new(basis).unwrap();
    let mut all = vec![0.0; basis.channel_count()];
    for (name, level) in levels {
        let c = basis
            .find_channel(name)
            .unwrap_or_else(|| panic!("no channel {name}"));
        all[c] = *level;
    }
    eval.set_channel_levels(&all).unwrap();
    let sensors: Vec<Value> = (0..basis.sensor_count())
        .map(|s| {
            json!({"name": basis.sensor_name(s).unwrap(),
                   "irradiance": eval.sensor_irradiance(s).unwrap().to_vec()})
        })
        .collect();
    let zones: Vec<Value> = (0..basis.zone_count())
        .map(|z| {
            json!({"name": basis.zone_name(z).unwrap(),
                   "irradiance": eval.zone_irradiance(z).unwrap().to_vec()})
        })
        .collect();
    let levels: Vec<Value> = levels
        .iter()
        .map(|(name, level)| json!({"name": name, "level": level}))
        .collect();
    let bands = if B == 1 {
        vec!["photopic"]
    } else {
        vec!["red", "green", "blue"]
    };
    json!({"unit": if B == 1 { "lux" } else { "W/m2" }, "bands": bands,
           "levels": levels, "sensors": sensors, "zones": zones})
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

fn close(a: f64, b: f64, scale: f64) -> bool {
    (a - b).abs() <= REL_TOL * b.abs().max(scale)
}

/// Runs the firmware on `basis` and checks every reading against the reference.
fn check_against_host(name: &str, basis: &[u8]) {
    let Some(run) = firmware(name, basis) else {
        return;
    };
    let decoded = Basis::from_bytes(basis).unwrap();
    let m = decoded.channel_count();
    let channel_names: Vec<String> = (0..m)
        .map(|c| decoded.channel_name(c).unwrap().to_string())
        .collect();

    let expected = expected_steps(m);
    assert_eq!(run.steps.len(), expected.len(), "number of steps");

    // Each output's reading with every channel at 1 (step 0): all levels in the sequence are
    // at most 1, so the rounding residue of incremental updates is bounded by this scale. At
    // steps where the reading is small (channels off) a test relative to the reading itself
    // would measure that residue instead of a disagreement.
    let full = &run.steps[0];
    let scale = |kind: &str, o: usize, b: usize| -> f64 {
        let list = if kind == "sensor" {
            &full.sensors
        } else {
            &full.zones
        };
        list[o].1[b].abs()
    };

    let mut compared = 0;
    let mut worst = 0.0f64;
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
        let reference = Evaluation::from_json(&reference_json(basis, &named));
        for (kind, got, want) in [
            ("sensor", &step.sensors, &reference.sensors),
            ("zone", &step.zones, &reference.zones),
        ] {
            assert_eq!(got.len(), want.len(), "step {k}: {kind} count");
            for (o, ((gname, gv), (wname, wv))) in got.iter().zip(want).enumerate() {
                assert_eq!(gname, wname, "step {k}: {kind} {o} name");
                assert_eq!(gv.len(), wv.len(), "step {k}: {kind} {gname} bands");
                for (b, (&g, &w)) in gv.iter().zip(wv).enumerate() {
                    assert!(
                        close(g, w, scale(kind, o, b)),
                        "step {k} ({op}): {kind} {gname} band {b}: firmware {g:e}, host {w:e}"
                    );
                    compared += 1;
                    worst = worst.max((g - w).abs() / w.abs().max(scale(kind, o, b)));
                }
            }
        }
    }
    let outputs = decoded.sensor_count() + decoded.zone_count();
    assert_eq!(compared, expected.len() * outputs * decoded.bands());
    eprintln!("firmware {name}: {compared} readings, largest relative difference {worst:e}");

    // Measurements: present, and the SysTick scale is the one QEMU's mps2-an386 model implies
    // (25 MHz SYSCLK, 1 ns per instruction under -icount shift=0: 40 instructions a tick), to
    // the ±1 tick of quantisation over the calibration's 200 000 ticks.
    assert!(
        (run.instructions_per_tick - 40.0).abs() < 0.01,
        "instructions per SysTick tick: {}",
        run.instructions_per_tick
    );
    for what in ["full_update", "channel_update", "read_outputs"] {
        assert!(run.instructions.get(what).is_some_and(|&n| n > 0), "{what}");
    }
    assert!(0 < run.stack_high_water && run.stack_high_water < run.stack_region);
    assert_eq!(run.basis["bytes"], basis.len());
}

#[test]
fn firmware_matches_host_f32() {
    check_against_host("room-f32", &random_basis(11, ROOM, Precision::F32));
}

/// Sensors and zones read only `f32` tables (output modes and channels, channel projections),
/// so their readings equal the f32 basis' exactly; what this adds is decoding and linking a
/// basis whose mode vectors, channel bounce and view factors are f16.
#[test]
fn firmware_matches_host_f16() {
    check_against_host("room-f16", &random_basis(11, ROOM, Precision::F16));
}

#[test]
fn firmware_matches_host_rgb() {
    let rgb = Dims {
        patches: 200,
        modes: 24,
        bands: 3,
        ..ROOM
    };
    check_against_host("room-rgb", &random_basis(12, rgb, Precision::F32));
}

/// The evaluator's state is fixed by its capacities: a basis 100 times larger takes the same
/// RAM, on the host and on the target.
#[test]
fn evaluator_ram_does_not_grow_with_basis() {
    type Fw<'a> = Evaluator<'a, 1, FW_PATCHES, FW_MODES, FW_CHANNELS, FW_OUTPUTS>;
    let small = tiny_basis();
    let large = random_basis(11, ROOM, Precision::F32);
    assert!(
        large.len() > 100 * small.len(),
        "bases of very different sizes"
    );

    let a = Fw::new(Basis::from_bytes(&small).unwrap()).unwrap();
    let b = Fw::new(Basis::from_bytes(&large).unwrap()).unwrap();
    assert_eq!(std::mem::size_of_val(&a), std::mem::size_of_val(&b));
    // The state is RAM_BYTES plus the basis' slice headers (pointers and lengths).
    assert!(std::mem::size_of_val(&a) >= Fw::RAM_BYTES);

    let (Some(small_run), Some(large_run)) =
        (firmware("tiny", &small), firmware("room-f32", &large))
    else {
        return;
    };
    assert_eq!(small_run.evaluator_size_of, large_run.evaluator_size_of);
    assert_eq!(small_run.ram_bytes, Fw::RAM_BYTES);
    assert_eq!(large_run.ram_bytes, Fw::RAM_BYTES);
    // Flash is where the basis goes: it grows by the basis' size, give or take the section
    // alignment padding around it (a few bytes).
    let rodata = |run: &FirmwareRun| run.sizes["basis"]["rodata"];
    let growth = large.len() - small.len();
    assert!(rodata(&large_run) + 64 >= rodata(&small_run) + growth);
}

#[test]
fn parser_reads_names_with_spaces() {
    let stdout = "basis bytes 1 bands 1\nstep 0 op all 1e0\nstep 0 levels 1e0\n\
                  reading 0 sensor north desk 2.5e2\ndone\n";
    let run = FirmwareRun::parse(stdout, "");
    assert_eq!(
        run.steps[0].sensors[0],
        ("north desk".to_string(), vec![250.0])
    );
}
