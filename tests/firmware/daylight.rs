//! The daylight office under the firmware's day loop: its daylight readings against
//! `eigenrad eval --time`, the runtime's sun against SPA, the daylight evaluators' RAM and
//! the daylight updates' instruction budgets, and the parser of the daylight records.

use eigenrad_runtime::Basis;

use super::checks::{check_against_eval, BASIS_VIEW_BYTES_MAX, DAYLIGHT_INSTRUCTIONS};
use super::*;

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

/// Every step of the firmware's day loop against `eigenrad eval --time` on the same basis:
/// the sun, the runtime's sun against SPA's, `E_gh`, every sensor, zone and grid figure.
fn steps_against_eval(name: &str, path: &Path, day: &Daylight) {
    let in_date = |date: &str| {
        day.steps
            .iter()
            .filter(|s| s.time.starts_with(date))
            .count()
    };
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
        let json = eval_daylight(path, &step.time).unwrap_or_else(|e| panic!("{e}"));
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
        in_date(DAYLIGHT_DATES[0]),
        in_date(DAYLIGHT_DATES[1])
    );
}

/// Instruction budget of a sky update plus the read of every sensor and zone on the daylight
/// office built with `--sun-first --no-grids`, by a `DaylightEvaluator` without modes: each of
/// its 486 candidate patches' sunlit polygon clipped at the sun, every reading's response to
/// it read, the work-plane zone's 60 receivers clipped for its direct sun. Measured 5 046 224
/// (docs/embedded.md): about 79 ms at 64 MHz, once per sun update.
const BUDGET_SUN_FIRST_UPDATE_READ_OUTPUTS: u64 = 5_500_000;

/// The daylight office with the sun's first reflection computed on the controller
/// (`--sun-first`, format 9): the firmware's day loop reads what `eigenrad eval --time` reads
/// from the same basis, and a sky update with every output read stays within its budget.
#[test]
fn firmware_daylight_office_sun_first() {
    let (path, name) = office_basis(Mesh::DaylightSunFirst, 32, "f16");
    let Some(run) = check_against_eval(&name, &path) else {
        return;
    };
    let bytes = std::fs::read(&path).unwrap();
    let basis = Basis::from_bytes(&bytes).unwrap();
    assert!(
        eigenrad_runtime::sky::sun_first::SunFirst::stored(&basis),
        "{name}: the sun's first reflection is in the basis"
    );
    let day = run.daylight.as_ref().expect("daylight records");
    assert!(!day.steps.is_empty());
    steps_against_eval(&name, &path, day);
    let update = run.instructions["daylight_update_read_outputs"];
    assert!(
        update <= BUDGET_SUN_FIRST_UPDATE_READ_OUTPUTS,
        "daylight update with the sun's first reflection and every output read: {update} \
         instructions, budget {BUDGET_SUN_FIRST_UPDATE_READ_OUTPUTS}"
    );
    eprintln!("{name}: a daylight update and every output read takes {update} instructions");
}

/// `eigenrad eval BASIS --json --time TIME` under the firmware's sky: the JSON, or what eval
/// said when it refused.
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
/// after sunrise to the last before sunset (eval reads the half hours on either side with the
/// sun below the horizon: the sky's light alone); the evaluators' RAM is their `RAM_BYTES`; a sky
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
        // The half hours on either side have the sun below the horizon: eval reads the sky's
        // light alone there (no direct sun, the 60 000 lux given dropped with a note).
        let first = minutes[0] - DAYLIGHT_STEP_MINUTES;
        let last = minutes[minutes.len() - 1] + DAYLIGHT_STEP_MINUTES;
        assert!(last < 24 * 60, "{date}: the sun sets");
        for m in [first, last] {
            let time = format!("{date}T{:02}:{:02}{offset}", m / 60, m % 60);
            let json = eval_daylight(&path, &time).unwrap_or_else(|e| panic!("{time}: {e}"));
            let light = &json["daylight"];
            assert!(
                light["sun_below_horizon"] == true
                    && light["sun"]["altitude"].as_f64().expect("altitude") < 0.0
                    && light["direct_normal_lux"] == 0.0,
                "{time}: the sun is not below the horizon in eval's sky:\n{light}"
            );
        }
    }
    // Vienna: longer days in June than in December.
    assert!(per_date[0].len() > per_date[1].len(), "{per_date:?}");

    // Every step against eval.
    steps_against_eval(&name, &path, day);

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
