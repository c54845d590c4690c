//! The firmware as a controller (`examples/firmware/src/control.rs`): the levels its loop
//! sets for a work-plane target against the host's solver at the same ambient light, and
//! the parser of its control records.

use eigenrad_runtime::dali::arc_power_to_level;
use eigenrad_runtime::{Basis, ChannelEvaluator};

use super::*;

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
