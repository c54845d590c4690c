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
pub(crate) fn check_against_eval(name: &str, path: &Path) -> Option<Arc<FirmwareRun>> {
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
pub(crate) const DAYLIGHT_INSTRUCTIONS: [&str; 7] = [
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
pub(crate) const BASIS_VIEW_BYTES_MAX: usize = 576;

/// Flash the runtime's own code may take (`.text`, bytes), as the code-size probes of the
/// firmware example measure it (`scripts/firmware.sh`, docs/embedded.md, "The runtime's own
/// code"), each a little above its figure so that growth shows here: decoding plus every
/// operation of the `ChannelEvaluator`, grids included (10 480 bytes, the channel-only
/// controller, 120 more than format 8's for the decoder's four more tables; budget 10.25
/// KiB, within the 12 KiB target), decoding plus every operation of the full `Evaluator`
/// but the grids' (12 988 in format 8; format 8's four decoded tables added 412 to both),
/// a channel-only controller that also solves its levels for a target (14 104 in format 8),
/// and decoding plus every `DaylightEvaluator` operation with the runtime's sun and sky
/// (35 556: its update's tables summed eight or six rows at a time by kernels of their own,
/// the sun's first reflection, its candidates' loop, their view rows or responses and the
/// per-power weights, format 9's clipping of their sunlit polygons and the zones', and the
/// refusal of a reading that overflows: 7 320 bytes more than format 8's 28 236), which a
/// controller reading daylight pays for whether its basis stores candidates or not). Decoding checks the daylight
/// section's shape only, and the names' framing but not their UTF-8; those are checked,
/// and linked, where daylight or a name is read. The payload is read in place and moved
/// whole, and the magic and names are compared without `memcmp`: 1 244 bytes less in the
/// channel-only controller than format 8's first figures (11 604, 14 208, 15 860, 30 092).
const BUDGET_RUNTIME_TEXT: [(&str, usize); 4] = [
    ("runtime_channels", 10 * 1024 + 256),
    ("runtime_patches", 13 * 1024),
    ("runtime_levels", 14 * 1024),
    ("runtime_daylight", 35 * 1024),
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
