//! The checks: the firmware's readings against `eigenrad eval` for each basis, the
//! evaluator's RAM against the basis size, and the record parser.

use eigenrad_runtime::dali::arc_power_to_level;
use eigenrad_runtime::{Basis, ChannelEvaluator, Evaluator};

use super::*;

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
    // Besides those, the level solver's cost, timed where the controller loop runs, and the
    // day loop's, on a basis that carries daylight (and only there: a firmware built with any
    // other basis runs as it did before daylight).
    let controller = !run.control.steps.is_empty();
    assert_eq!(run.instructions.contains_key("solve_levels"), controller);
    let daylight = basis.has_daylight();
    assert_eq!(run.daylight.is_some(), daylight, "daylight records");
    assert_eq!(run.harvest.is_some(), daylight, "harvesting day records");
    for what in DAYLIGHT_INSTRUCTIONS {
        assert_eq!(run.instructions.contains_key(what), daylight, "{what}");
    }
    assert_eq!(
        run.instructions.len(),
        INSTRUCTIONS.len()
            + usize::from(controller)
            + if daylight {
                DAYLIGHT_INSTRUCTIONS.len()
            } else {
                0
            }
    );
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

/// The day loop's timed operations (`measure` in `examples/firmware/src/daylight.rs`).
const DAYLIGHT_INSTRUCTIONS: [&str; 7] = [
    "daylight_update_read_outputs",
    "daylight_update_read_outputs_modes",
    "daylight_sky",
    "daylight_sky_luminances",
    "daylight_sun_position",
    "daylight_sun_position_runtime",
    "daylight_sky_update",
];

/// Instruction budgets for the office at 32 modes (issue 12, docs/embedded.md): a full update
/// of every channel plus the read of every output, and one channel's update. QEMU counts
/// instructions exactly (`-icount shift=0`), so the figures repeat from run to run; a change
/// that exceeds a budget fails here rather than in a later table.
const BUDGET_FULL_UPDATE_READ_OUTPUTS: u64 = 1000;
const BUDGET_CHANNEL_UPDATE: u64 = 300;
/// RAM an evaluator takes on the target beyond its `RAM_BYTES`, bytes: the basis view it
/// holds (a pointer and a length per table of the payload, 8 bytes each, and the counts)
/// and its vectors' lengths. 520 bytes measured for the channel evaluator with format 8's
/// tables, 528 for the daylight evaluator; bounded a little above so that growth shows.
const BASIS_VIEW_BYTES_MAX: usize = 576;

/// Flash the runtime's own code may take (`.text`, bytes), as the code-size probes of the
/// firmware example measure it (`scripts/firmware.sh`, docs/embedded.md, "The runtime's own
/// code"), each a little above its figure so that growth shows here: decoding plus every
/// operation of the `ChannelEvaluator`, grids included (10 360 bytes, the channel-only
/// controller; budget 10.25 KiB, within the 12 KiB target), decoding plus every operation
/// of the full `Evaluator` but the grids' (12 988; format 8's four decoded tables added 412
/// to both), a channel-only controller that also solves its levels for a target (14 104),
/// and decoding plus every `DaylightEvaluator` operation with the runtime's sun and sky
/// (28 236: its update's tables summed eight or six rows at a time by kernels of their own, and
/// format 8's sun's first reflection, its candidates' loop, their view rows and the
/// per-power weights, which a controller reading daylight pays for whether its basis
/// stores candidates or not). Decoding checks the daylight
/// section's shape only, and the names' framing but not their UTF-8; those are checked,
/// and linked, where daylight or a name is read. The payload is read in place and moved
/// whole, and the magic and names are compared without `memcmp`: 1 244 bytes less in the
/// channel-only controller than format 8's first figures (11 604, 14 208, 15 860, 30 092).
const BUDGET_RUNTIME_TEXT: [(&str, usize); 4] = [
    ("runtime_channels", 10 * 1024 + 256),
    ("runtime_patches", 13 * 1024),
    ("runtime_levels", 14 * 1024),
    ("runtime_daylight", 28 * 1024),
];

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
    for (probe, budget) in BUDGET_RUNTIME_TEXT {
        let text = run.sizes[probe]["text"];
        assert!(
            0 < text && text <= budget,
            "{probe} .text {text} bytes, budget {budget}"
        );
    }
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

/// A controller's basis of the example building (docs/building.md): the meeting room's, cut
/// from its room's tables with its modes, reads on the device what `eigenrad eval` reads.
#[test]
fn firmware_matches_eval_building_controller() {
    let (path, name) = building_controller_basis();
    let Some(run) = check_against_eval(&name, &path) else {
        return;
    };
    assert_eq!(run.basis["channels"], 2);
    assert_eq!(run.basis["sensors"], 1);
}

/// The RGB example as built by default: three bands, one channel.
#[test]
fn firmware_matches_eval_cornell_box() {
    let (path, name) = cornell_box_basis();
    let Some(run) = check_against_eval(&name, &path) else {
        return;
    };
    assert_eq!(run.basis["bands"], 3);
    assert_eq!(run.basis["channels"], 1);
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
    assert!(small_run.channel_size_of <= FwChannels::RAM_BYTES + BASIS_VIEW_BYTES_MAX);
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

/// The controller loop's constants (`examples/firmware/src/control.rs`).
const CONTROL_TARGET: f32 = 500.0;
const CONTROL_DAYLIGHT: [f32; 6] = [0.0, 25.0, 60.0, 120.0, 200.0, 400.0];
const CONTROL_RATIO: f32 = 4.0;
const CONTROL_WATTS: [f32; 8] = [36.0, 32.0, 28.0, 24.0, 20.0, 16.0, 12.0, 8.0];
/// Levels and readings of the firmware against the host's: the same f32 runtime code on two
/// compilations, a few roundings apart (see `tests/levels.rs` for the solver's own accuracy).
const CONTROL_LEVEL_TOL: f64 = 1e-4;
const CONTROL_RTOL: f64 = 1e-4;

/// The least-power levels for one lower bound `ambient + Σ gᵢ xᵢ ≥ target`, `xᵢ ∈ [0, 1]`:
/// the continuous knapsack, solved exactly by filling the channels in decreasing order of
/// light per watt `gᵢ/wᵢ` (Dantzig 1957), in f64. When even every channel at full falls
/// short, the closest levels are every channel with light at full. Returns the levels and
/// the shortfall (lux, 0 when met).
pub(crate) fn greedy_levels(
    gains: &[f64],
    weights: &[f64],
    ambient: f64,
    target: f64,
) -> (Vec<f64>, f64) {
    let mut order: Vec<usize> = (0..gains.len()).filter(|&i| gains[i] > 0.0).collect();
    let ratio = |i: usize| {
        if weights[i] == 0.0 {
            f64::INFINITY
        } else {
            gains[i] / weights[i]
        }
    };
    order.sort_by(|&a, &b| ratio(b).total_cmp(&ratio(a)));
    let mut levels = vec![0.0; gains.len()];
    let mut need = target - ambient;
    for i in order {
        if need <= 0.0 {
            break;
        }
        levels[i] = (need / gains[i]).min(1.0);
        need -= levels[i] * gains[i];
    }
    (levels, need.max(0.0))
}

/// Checks the firmware's controller loop on the basis at `path` against the host computation
/// of the same problems: the photosensor reading from the host evaluator at the levels the
/// firmware had sent, the daylight estimate, and the greedy least-power levels, their DALI arc
/// levels and the work plane they give. Returns the run, or `None` without QEMU.
fn check_controller(name: &str, path: &Path) -> Option<Arc<FirmwareRun>> {
    use eigenrad_runtime::dali::level_to_arc_power;
    use eigenrad_runtime::target::output_gains;
    use eigenrad_runtime::Output;

    let run = firmware(name, path)?;
    let control = &run.control;
    let bytes = std::fs::read(path).unwrap();
    let basis = Basis::from_bytes(&bytes).unwrap();
    // Every channel but `window` is dimmed; the sensor `ceiling` and the zone `work_plane`
    // when the basis has them.
    let dimmed: Vec<usize> = (0..basis.channel_count())
        .filter(|&c| basis.channel_name(c).unwrap() != "window")
        .collect();
    assert_eq!(control.channels, dimmed, "{name}: dimmed channels");
    assert_eq!(
        control.weights,
        CONTROL_WATTS[..dimmed.len()],
        "{name}: weights"
    );
    assert_eq!(control.sensor, basis.find_sensor("ceiling").unwrap_or(0));
    assert_eq!(control.zone, basis.find_zone("work_plane").unwrap_or(0));
    assert_eq!(
        (control.ratio, control.target),
        (CONTROL_RATIO, CONTROL_TARGET)
    );
    assert!(control.problem_size_of > 0);
    assert_eq!(
        control.steps.len(),
        CONTROL_DAYLIGHT.len(),
        "{name}: control steps"
    );
    assert!(run.instructions.contains_key("solve_levels"));

    let mut gains = vec![0.0f32; dimmed.len()];
    output_gains(&basis, Output::Zone(control.zone), &dimmed, &mut gains).unwrap();
    let gains: Vec<f64> = gains.iter().map(|&g| f64::from(g)).collect();
    let weights: Vec<f64> = control.weights.iter().map(|&w| f64::from(w)).collect();
    let mut lights = ChannelEvaluator::<1, 8>::new(basis).unwrap();
    // The luminaires start at full, the window channel off.
    let mut levels: Vec<f32> = (0..basis.channel_count())
        .map(|c| if dimmed.contains(&c) { 1.0 } else { 0.0 })
        .collect();
    let (mut met, mut unmet) = (0, 0);
    for (k, (step, &daylight)) in control.steps.iter().zip(&CONTROL_DAYLIGHT).enumerate() {
        let what = format!("{name} control step {k}");
        assert_eq!(step.daylight, daylight, "{what}");
        lights.set_channel_levels(&levels).unwrap();
        let predicted = f64::from(lights.sensor_irradiance(control.sensor).unwrap()[0]);
        let reading = predicted + f64::from(daylight);
        let close = |got: f32, want: f64, scale: f64| {
            (f64::from(got) - want).abs() <= CONTROL_RTOL * want.abs().max(scale)
        };
        assert!(
            close(step.reading, reading, 1.0),
            "{what}: reading {} lux, host {reading}",
            step.reading
        );
        assert!(
            close(step.estimate, f64::from(daylight), 1.0),
            "{what}: estimate"
        );
        let ambient = f64::from(CONTROL_RATIO) * f64::from(daylight);
        assert!(close(step.ambient, ambient, 1.0), "{what}: ambient");

        let (want, short) = greedy_levels(
            &gains,
            &weights,
            f64::from(step.ambient),
            f64::from(CONTROL_TARGET),
        );
        assert_eq!(step.levels.len(), dimmed.len(), "{what}: levels");
        for (i, (&got, &w)) in step.levels.iter().zip(&want).enumerate() {
            assert!(
                (f64::from(got) - w).abs() <= CONTROL_LEVEL_TOL,
                "{what}: channel {} level {got}, host {w}",
                dimmed[i]
            );
        }
        let power: f64 = want.iter().zip(&weights).map(|(l, w)| l * w).sum();
        assert!(
            close(step.power, power, 1e-3),
            "{what}: power {} W, host {power}",
            step.power
        );
        match step.unmet {
            None => {
                assert!(short <= 1e-3, "{what}: met, host {short} lux short");
                met += 1;
            }
            Some((bound, by)) => {
                assert_eq!(bound, 0, "{what}: failing bound");
                assert!(
                    close(by, short, 1.0),
                    "{what}: short by {by} lux, host {short}"
                );
                unmet += 1;
            }
        }
        // Arc levels round each level up, so the work plane gets at least the target.
        assert_eq!(step.arcs.len(), dimmed.len());
        for ((&arc, &level), &c) in step.arcs.iter().zip(&step.levels).zip(&dimmed) {
            assert_eq!(
                arc,
                level_to_arc_power(level).unwrap(),
                "{what}: arc of {level}"
            );
            levels[c] = arc_power_to_level(arc).unwrap();
        }
        lights.set_channel_levels(&levels).unwrap();
        let plane = f64::from(lights.zone_irradiance(control.zone).unwrap()[0]) + ambient;
        if step.unmet.is_none() {
            assert!(
                plane >= f64::from(CONTROL_TARGET) * (1.0 - 1e-6),
                "{what}: work plane {plane} lux at the arc levels"
            );
        }
    }
    eprintln!(
        "{name}: controller {met} steps met, {unmet} short; solve_levels {} instructions",
        run.instructions["solve_levels"]
    );
    Some(run)
}

/// The office controller: 4 dimmed luminaires, the ceiling photocell, the work plane; its
/// solver's instructions are measured on every zone ≥ 500 lux and every sensor ≤ 2000 lux.
#[test]
fn firmware_controller_office() {
    let (path, name) = office_basis(Mesh::Office, 32, "f32");
    let Some(run) = check_controller(&name, &path) else {
        return;
    };
    assert_eq!(run.control.channels.len(), 4);
    // Full daylight needs no electric light; the night needs some.
    let steps = &run.control.steps;
    assert!(steps.last().unwrap().levels.iter().all(|&l| l == 0.0));
    assert!(steps[0].power > 0.0);
}

/// The tiny basis: one channel of 40 lux on its zone, so the target is out of reach until the
/// daylight brings it within 40 lux (by hand: at 120 lux of sensor daylight, 480 lux on the
/// plane, the channel at 20/40 = 0.5).
#[test]
fn firmware_controller_tiny() {
    let Some(run) = check_controller("tiny", &tiny_basis_path()) else {
        return;
    };
    let steps = &run.control.steps;
    assert_eq!(steps[2].unmet.map(|u| u.0), Some(0));
    assert_eq!(steps[3].levels, vec![0.5]);
    assert_eq!(steps[3].unmet, None);
}

#[test]
fn parser_reads_control_records() {
    let stdout = "basis bytes 1 bands 1\ncontrol channels 0 2\ncontrol weights 3.6e1 2.4e1\n\
                  control setup sensor 1 zone 0 ratio 4e0 target 5e2 size_of 1288\n\
                  control step 0 daylight 0e0 reading 7e1 estimate 0e0 ambient 0e0 levels 1e0 \
                  5e-1 arc 254 229 power 4.8e1 unmet 0 4.5e1\n\
                  control step 1 daylight 2.5e1 reading 9e1 estimate 2.5e1 ambient 1e2 levels 0e0 \
                  0e0 arc 0 0 power 0e0 met\ndone\n";
    let run = FirmwareRun::parse(stdout, "");
    let c = &run.control;
    assert_eq!((c.channels.clone(), c.sensor, c.zone), (vec![0, 2], 1, 0));
    assert_eq!((c.ratio, c.target, c.problem_size_of), (4.0, 500.0, 1288));
    assert_eq!(c.steps[0].levels, vec![1.0, 0.5]);
    assert_eq!(c.steps[0].arcs, vec![254, 229]);
    assert_eq!(c.steps[0].unmet, Some((0, 45.0)));
    assert_eq!((c.steps[1].ambient, c.steps[1].unmet), (100.0, None));
}

/// The firmware's day loop (`examples/firmware/src/daylight.rs`): the dates, in order, and
/// the minutes between steps; the sky (CIE standard general sky type, diffuse horizontal and
/// direct normal illuminance, lux); the daylight evaluators' capacities (sky patches, outputs,
/// modes of the one with modes).
const DAYLIGHT_DATES: [&str; 2] = ["2026-06-21", "2026-12-21"];
const DAYLIGHT_STEP_MINUTES: u32 = 30;
const DAYLIGHT_SKY_TYPE: u8 = 12;
const DAYLIGHT_DHI: f32 = 10_000.0;
const DAYLIGHT_DNI: f32 = 60_000.0;
const FW_SKY: usize = 145;

/// Instruction budget of a whole sky update by the runtime alone on the daylight office (issue
/// 30, docs/embedded.md): the sun's position (`sky::sun`), the CIE clear sky and its zenith
/// luminance, the 145 patch luminances, `set_sky` and the read of every sensor and zone.
const BUDGET_SKY_UPDATE: u64 = 200_000;
/// The runtime's sun position against SPA's at every step of the day loop, degrees of
/// separation (`eigenrad_runtime::sky::sun`'s stated bound).
const RUNTIME_SUN_BOUND: f64 = 0.05;

/// Instruction budget of a sky update plus the read of every sensor and zone on the daylight
/// office at 32 modes, by a `DaylightEvaluator` without modes (issue 14, docs/embedded.md).
const BUDGET_DAYLIGHT_UPDATE_READ_OUTPUTS: u64 = 20_000;
/// The same with patch exitance (format 7's first reflection: the 32 modes' amplitudes and
/// the 18 coefficients of the sky's first reflection), held to the same 20 000 of the target
/// (issue 30): 19 521 measured (docs/embedded.md), of it about 13 900 in the
/// `4 × 146 + 18 × 146 + 32 × 18` = 3 788 multiply-adds, each at least 3 instructions on the
/// Cortex-M4F when the table is read from bytes.
const BUDGET_DAYLIGHT_UPDATE_READ_OUTPUTS_MODES: u64 = 20_000;

/// `eigenrad eval BASIS --json --time TIME` under the firmware's sky: the JSON, or what eval
/// said when it refused (the sun below the horizon).
fn eval_daylight(basis: &Path, time: &str) -> Result<Value, String> {
    eval_sky(basis, time, DAYLIGHT_SKY_TYPE, DAYLIGHT_DHI, DAYLIGHT_DNI)
}

/// `eigenrad eval BASIS --json --time TIME --cie TYPE --dhi-lux DHI --dni-lux DNI`: the
/// JSON, or what eval said when it refused.
pub(crate) fn eval_sky(
    basis: &Path,
    time: &str,
    sky_type: u8,
    diffuse_horizontal: f32,
    direct_normal: f32,
) -> Result<Value, String> {
    let output = Command::new(eigenrad())
        .env("EIGENRAD_CACHE_DIR", work_dir().join("form-factor-cache"))
        .arg("eval")
        .arg(basis)
        .args(["--json", "--time", time, "--cie"])
        .arg(sky_type.to_string())
        .arg("--dhi-lux")
        .arg(diffuse_horizontal.to_string())
        .arg("--dni-lux")
        .arg(direct_normal.to_string())
        .output()
        .expect("run eigenrad");
    if output.status.success() {
        Ok(serde_json::from_slice(&output.stdout).expect("eigenrad eval --json"))
    } else {
        Err(String::from_utf8_lossy(&output.stderr).into_owned())
    }
}

/// `±HH:MM` of a UTC offset in minutes.
pub(crate) fn offset_text(minutes: i32) -> String {
    let sign = if minutes < 0 { '-' } else { '+' };
    let m = minutes.unsigned_abs();
    format!("{sign}{:02}:{:02}", m / 60, m % 60)
}

/// `DATE`, minutes after midnight and offset of a step's time `YYYY-MM-DDTHH:MM±HH:MM`.
fn split_time(time: &str) -> (&str, u32, &str) {
    assert_eq!(time.len(), 22, "step time {time:?}");
    let (date, rest) = time.split_at(10);
    let hours: u32 = number(&rest[1..3], time);
    let minutes: u32 = number(&rest[4..6], time);
    (date, hours * 60 + minutes, &rest[6..])
}

/// The daylight office at 32 modes in f16 on the controller: its channels as every basis's
/// (against `eigenrad eval`), then the day loop. Every step's sun position, global horizontal
/// illuminance, sensor and zone daylight and grid figures agree with
/// `eigenrad eval --time <step> --cie 12 --dhi-lux 10000 --dni-lux 60000 --json`
/// ([`DAYLIGHT_REL_TOL`], [`SUN_TOL_DEG`]); the steps run every 30 minutes from the first
/// after sunrise to the last before sunset (eval refuses the half hours on either side, the
/// sun being below the horizon then); the evaluators' RAM is their `RAM_BYTES`; a sky
/// update plus every read stays within its instruction budgets; and the firmware fits the
/// part's flash.
#[test]
fn firmware_daylight_office() {
    use eigenrad_runtime::DaylightEvaluator;

    let (path, name) = office_basis(Mesh::Daylight, 32, "f16");
    let Some(run) = check_against_eval(&name, &path) else {
        return;
    };
    let bytes = std::fs::read(&path).unwrap();
    let basis = Basis::from_bytes(&bytes).unwrap();
    assert!(basis.has_daylight());
    let site = basis.site().unwrap();
    let day = run.daylight.as_ref().expect("daylight records");

    // What the firmware says it ran.
    assert_eq!(
        (day.sky_type, day.diffuse_horizontal, day.direct_normal),
        (DAYLIGHT_SKY_TYPE, DAYLIGHT_DHI, DAYLIGHT_DNI)
    );
    assert_eq!(day.sky_patches, basis.sky_patches().unwrap().count());
    assert_eq!(day.nodes, basis.daylight_node_count());
    assert_eq!(day.sun_nodes, basis.sun_node_count());
    assert_eq!(
        day.site,
        [
            site.latitude,
            site.longitude,
            site.elevation,
            site.utc_offset_minutes
        ]
    );
    assert_eq!(day.work_plane, basis.find_zone("work_plane"));
    type Plain<'a> = DaylightEvaluator<'a, FW_SKY, FW_OUTPUTS, 0>;
    type Modal<'a> = DaylightEvaluator<'a, FW_SKY, FW_OUTPUTS, FW_MODES>;
    assert_eq!(
        day.evaluators
            .iter()
            .map(|&(_, ram, capacity)| (ram, capacity))
            .collect::<Vec<_>>(),
        vec![
            (Plain::RAM_BYTES, [FW_SKY, FW_OUTPUTS, 0]),
            (Modal::RAM_BYTES, [FW_SKY, FW_OUTPUTS, FW_MODES]),
        ]
    );
    for &(size_of, ram, _) in &day.evaluators {
        // RAM_BYTES plus the basis view and the vectors' lengths, on the 32-bit target.
        assert!(
            ram <= size_of && size_of <= ram + BASIS_VIEW_BYTES_MAX,
            "{size_of} {ram}"
        );
    }

    // The steps: every DAYLIGHT_STEP_MINUTES of each date while the sun is up.
    let offset = offset_text(site.utc_offset_minutes.round() as i32);
    let mut per_date = vec![Vec::new(); DAYLIGHT_DATES.len()];
    for step in &day.steps {
        let (date, minute, zone) = split_time(&step.time);
        assert_eq!(zone, offset, "{}: the site's UTC offset", step.time);
        let d = DAYLIGHT_DATES
            .iter()
            .position(|&x| x == date)
            .unwrap_or_else(|| panic!("{}: not a date of the day loop", step.time));
        assert!(
            per_date[d + 1..].iter().all(Vec::is_empty),
            "{}: dates in order",
            step.time
        );
        per_date[d].push(minute);
    }
    for (date, minutes) in DAYLIGHT_DATES.iter().zip(&per_date) {
        assert!(!minutes.is_empty(), "{date}: no step with the sun up");
        for pair in minutes.windows(2) {
            assert_eq!(pair[1], pair[0] + DAYLIGHT_STEP_MINUTES, "{date}: steps");
        }
        assert_eq!(
            minutes[0] % DAYLIGHT_STEP_MINUTES,
            0,
            "{date}: on the lattice"
        );
        // The half hours on either side have the sun below the horizon: eval refuses them.
        let first = minutes[0] - DAYLIGHT_STEP_MINUTES;
        let last = minutes[minutes.len() - 1] + DAYLIGHT_STEP_MINUTES;
        assert!(last < 24 * 60, "{date}: the sun sets");
        for m in [first, last] {
            let time = format!("{date}T{:02}:{:02}{offset}", m / 60, m % 60);
            let refused = eval_daylight(&path, &time).expect_err(&time);
            assert!(
                refused.contains("below the horizon"),
                "{time}: eval refused for another reason:\n{refused}"
            );
        }
    }
    // Vienna: longer days in June than in December.
    assert!(per_date[0].len() > per_date[1].len(), "{per_date:?}");

    // Every step against eval.
    let mut worst = (0.0f64, String::new());
    let mut worst_sun = 0.0f64;
    let mut worst_runtime_sun = 0.0f64;
    let mut check = |what: &dyn Fn() -> String, firmware: f64, host: f64| {
        let relative = (firmware - host).abs() / host.abs().max(1.0);
        assert!(
            relative <= DAYLIGHT_REL_TOL,
            "{}: firmware {firmware:e}, eigenrad eval {host:e} (relative {relative:e})",
            what()
        );
        if relative >= worst.0 {
            worst = (relative, what());
        }
    };
    for (k, step) in day.steps.iter().enumerate() {
        let json = eval_daylight(&path, &step.time).unwrap_or_else(|e| panic!("{e}"));
        let light = &json["daylight"];
        let sun = &light["sun"];
        for (got, key) in [(step.altitude, "altitude"), (step.azimuth, "azimuth")] {
            let want = sun[key].as_f64().expect(key);
            assert!(
                (got - want).abs() <= SUN_TOL_DEG,
                "step {k} ({}): sun {key} {got}°, eval {want}°",
                step.time
            );
            worst_sun = worst_sun.max((got - want).abs());
        }
        assert!(step.altitude > 0.0);
        // The runtime's own sun against SPA's (the host's, printed by the firmware).
        let (alt, az) = step.runtime_sun.expect("the runtime's sun at every step");
        let (a1, a2) = (alt.to_radians(), step.altitude.to_radians());
        let cos =
            a1.sin() * a2.sin() + a1.cos() * a2.cos() * (az - step.azimuth).to_radians().cos();
        let separation = cos.clamp(-1.0, 1.0).acos().to_degrees();
        assert!(
            separation <= RUNTIME_SUN_BOUND,
            "step {k} ({}): the runtime's sun {alt}° {az}° is {separation}° from SPA's",
            step.time
        );
        worst_runtime_sun = worst_runtime_sun.max(separation);
        let global = light["global_horizontal_lux"].as_f64().expect("E_gh");
        assert!(
            (f64::from(step.global_horizontal) - global).abs() <= 1e-6 * global,
            "step {k}: E_gh {} lux, eval {global}",
            step.global_horizontal
        );
        for (kind, got, key) in [
            ("sensor", &step.sensors, "sensors"),
            ("zone", &step.zones, "zones"),
        ] {
            let want = json[key].as_array().expect(key);
            assert_eq!(got.len(), want.len(), "step {k}: {kind} count");
            for ((name, value), w) in got.iter().zip(want) {
                assert_eq!(w["name"].as_str(), Some(name.as_str()), "step {k}: {kind}");
                assert!(*value > 0.0, "step {k}: {kind} {name} has no daylight");
                let host = numbers(&w["daylight"], "daylight")[0];
                check(
                    &|| format!("step {k} ({}): {kind} {name}", step.time),
                    *value,
                    host,
                );
            }
        }
        let grids = light["grids"].as_array().expect("daylight grids");
        assert_eq!(step.figures.len(), grids.len(), "step {k}: grids");
        for ((zone, figures), g) in step.figures.iter().zip(grids) {
            assert_eq!(g["zone"].as_str(), Some(zone.as_str()), "step {k}: grid");
            for (i, key) in ["average", "minimum", "maximum", "uniformity"]
                .iter()
                .enumerate()
            {
                let host = numbers(&g[*key], key)[0];
                check(
                    &|| format!("step {k} ({}): {zone} grid {key}", step.time),
                    figures[i],
                    host,
                );
            }
        }
    }
    let (relative, at) = worst;
    eprintln!(
        "{name}: {} daylight steps ({} in June, {} in December) against eigenrad eval: \
         largest relative difference {relative:e} ({at}), sun within {worst_sun:e}°, the \
         runtime's sun within {worst_runtime_sun:e}° of SPA's",
        day.steps.len(),
        per_date[0].len(),
        per_date[1].len()
    );

    // Instructions.
    let update = run.instructions["daylight_update_read_outputs"];
    assert!(
        update <= BUDGET_DAYLIGHT_UPDATE_READ_OUTPUTS,
        "daylight update and every output read: {update} instructions, budget \
         {BUDGET_DAYLIGHT_UPDATE_READ_OUTPUTS}"
    );
    let modal = run.instructions["daylight_update_read_outputs_modes"];
    assert!(
        modal <= BUDGET_DAYLIGHT_UPDATE_READ_OUTPUTS_MODES,
        "daylight update with modes and every output read: {modal} instructions, budget \
         {BUDGET_DAYLIGHT_UPDATE_READ_OUTPUTS_MODES}"
    );
    assert!(modal > update, "the modes cost");
    let sky_update = run.instructions["daylight_sky_update"];
    assert!(
        sky_update <= BUDGET_SKY_UPDATE,
        "whole sky update (runtime sun, sky, patch luminances, set_sky, outputs): {sky_update} \
         instructions, budget {BUDGET_SKY_UPDATE}"
    );

    // Flash: the daylight tables as the build reports them, and the whole firmware.
    let report = std::fs::read_to_string(work_dir().join(format!("{name}.report"))).unwrap();
    let daylight_bytes: usize = report
        .lines()
        .find(|l| l.starts_with("daylight:"))
        .and_then(|l| l.rsplit(": ").next())
        .and_then(|t| t.strip_suffix(" bytes"))
        .map(|t| number(t, &report))
        .expect("the build's daylight: line");
    assert!(0 < daylight_bytes && daylight_bytes < bytes.len());
    let flash = run.sizes["basis"]["flash"];
    assert!(flash <= 512 * 1024, "flash {flash} bytes");
    eprintln!(
        "{name}: basis {} bytes, its daylight {daylight_bytes} bytes; firmware flash {flash} \
         bytes of 524288; daylight instructions {:?}; runtime daylight code {:?}, sun \
         position {:?}",
        bytes.len(),
        DAYLIGHT_INSTRUCTIONS.map(|w| run.instructions[w]),
        run.sizes["runtime_daylight"],
        run.sizes["sun_position"]
    );
}

#[test]
fn parser_reads_daylight_records() {
    let stdout = "basis bytes 1 bands 1\n\
        daylight setup sky cie 12 diffuse_horizontal 1e4 direct_normal 6e4 sky_patches 145 \
        nodes 310 sun_nodes 164\n\
        daylight site latitude 4.821e1 longitude 1.637e1 elevation 1.7e2 utc_offset_minutes 6e1\n\
        daylight_evaluator size_of 1044 ram_bytes 648 capacity 145 8 0\n\
        daylight zone work_plane 0\n\
        daylight step 0 time 2026-06-21T04:00+01:00 altitude 4.5e-1 azimuth 5.3e1 \
        global_horizontal 1.0473067e4\n\
        daylight sun_runtime 0 altitude 4.5e-1 azimuth 5.3e1\n\
        daylight reading 0 sensor north desk 2.5e2\n\
        daylight reading 0 zone work_plane 2.75e2\n\
        daylight figures 0 average 2.7e2 minimum 1.1e2 maximum 9.5e2 uniformity 4e-1 zone \
        work plane\ndone\n";
    let run = FirmwareRun::parse(stdout, "");
    let day = run.daylight.unwrap();
    assert_eq!((day.sky_type, day.nodes, day.sun_nodes), (12, 310, 164));
    assert_eq!(day.site, [48.21, 16.37, 170.0, 60.0]);
    assert_eq!(day.evaluators, vec![(1044, 648, [145, 8, 0])]);
    assert_eq!(day.work_plane, Some(0));
    let step = &day.steps[0];
    assert_eq!(step.time, "2026-06-21T04:00+01:00");
    assert_eq!((step.altitude, step.azimuth), (0.45, 53.0));
    assert_eq!(step.runtime_sun, Some((0.45, 53.0)));
    assert_eq!(step.sensors, vec![("north desk".to_string(), 250.0)]);
    assert_eq!(step.zones, vec![("work_plane".to_string(), 275.0)]);
    assert_eq!(
        step.figures,
        vec![(
            "work plane".to_string(),
            [270.0, 110.0, 950.0, f64::from(0.4f32)]
        )]
    );
    assert_eq!(split_time(&step.time), ("2026-06-21", 240, "+01:00"));
    assert_eq!(offset_text(-330), "-05:30");
}
