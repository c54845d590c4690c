//! The firmware's records (the format is described at the top of
//! `examples/firmware/src/main.rs`) read into one value per run.

use std::collections::HashMap;

use super::harvest;

/// What one firmware run printed.
#[derive(Debug, Default)]
pub(crate) struct FirmwareRun {
    /// `basis ...` fields, e.g. `bytes`, `patches`.
    pub(crate) basis: HashMap<String, usize>,
    /// `size_of` the full evaluator on the target, bytes.
    pub(crate) evaluator_size_of: usize,
    /// `Evaluator::RAM_BYTES` on the target.
    pub(crate) ram_bytes: usize,
    /// `size_of` the channel evaluator on the target, bytes.
    pub(crate) channel_size_of: usize,
    /// `ChannelEvaluator::RAM_BYTES` on the target.
    pub(crate) channel_ram_bytes: usize,
    pub(crate) steps: Vec<Step>,
    /// Instructions per call, by operation (`full_update`, ...).
    pub(crate) instructions: HashMap<String, u64>,
    /// Measured instructions per SysTick tick.
    pub(crate) instructions_per_tick: f64,
    pub(crate) stack_high_water: usize,
    pub(crate) stack_region: usize,
    /// The `control` records (`examples/firmware/src/control.rs`), when the basis has them.
    pub(crate) control: Control,
    /// The `daylight` records (`examples/firmware/src/daylight.rs`), when the basis carries
    /// daylight.
    pub(crate) daylight: Option<Daylight>,
    /// The `harvest` records (`examples/firmware/src/harvest.rs`), when the basis carries
    /// daylight.
    pub(crate) harvest: Option<harvest::Harvest>,
    /// `size` lines of `scripts/firmware.sh`: label → field → bytes.
    pub(crate) sizes: HashMap<String, HashMap<String, usize>>,
}

/// The controller loop's records.
#[derive(Debug, Default, Clone)]
pub(crate) struct Control {
    /// Basis indices of the dimmed channels.
    pub(crate) channels: Vec<usize>,
    /// W at level 1 per dimmed channel.
    pub(crate) weights: Vec<f32>,
    pub(crate) sensor: usize,
    pub(crate) zone: usize,
    pub(crate) ratio: f32,
    /// Lux.
    pub(crate) target: f32,
    /// `size_of` the `LevelProblem` on the target, bytes.
    pub(crate) problem_size_of: usize,
    pub(crate) steps: Vec<ControlStep>,
}

/// One step of the controller loop; illuminances in lux.
#[derive(Debug, Default, Clone)]
pub(crate) struct ControlStep {
    pub(crate) daylight: f32,
    pub(crate) reading: f32,
    pub(crate) estimate: f32,
    pub(crate) ambient: f32,
    pub(crate) levels: Vec<f32>,
    pub(crate) arcs: Vec<u8>,
    /// W.
    pub(crate) power: f32,
    /// `None` when the target is met, else the failing bound and by how much (lux).
    pub(crate) unmet: Option<(usize, f32)>,
}

impl ControlStep {
    /// Reads `levels <l...> arc <a...> power <p> met | unmet <bound> <by>` into the step.
    pub(crate) fn parse_tail(&mut self, rest: &[&str], line: &str) {
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
pub(crate) struct Daylight {
    /// CIE standard general sky type.
    pub(crate) sky_type: u8,
    /// Lux.
    pub(crate) diffuse_horizontal: f32,
    /// Lux.
    pub(crate) direct_normal: f32,
    pub(crate) sky_patches: usize,
    pub(crate) nodes: usize,
    pub(crate) sun_nodes: usize,
    /// Latitude, longitude (degrees), elevation (m), UTC offset (minutes).
    pub(crate) site: [f32; 4],
    /// `(size_of, RAM_BYTES, [sky, outputs, modes])` of each daylight evaluator.
    pub(crate) evaluators: Vec<(usize, usize, [usize; 3])>,
    /// The zone a controller keeps, if the basis has zones.
    pub(crate) work_plane: Option<usize>,
    pub(crate) steps: Vec<DaylightStep>,
}

/// One step of the day loop; illuminances in lux.
#[derive(Debug, Default, Clone)]
pub(crate) struct DaylightStep {
    /// Local time with the site's UTC offset, as `eigenrad eval --time` reads it.
    pub(crate) time: String,
    /// Degrees.
    pub(crate) altitude: f64,
    /// Degrees clockwise from north.
    pub(crate) azimuth: f64,
    pub(crate) global_horizontal: f32,
    /// The runtime's own sun position (`sky::sun`, f32): altitude and azimuth, degrees.
    pub(crate) runtime_sun: Option<(f64, f64)>,
    pub(crate) sensors: Vec<(String, f64)>,
    pub(crate) zones: Vec<(String, f64)>,
    /// `(zone, [E_avg, E_min, E_max, U_o])` of each zone with a grid.
    pub(crate) figures: Vec<(String, [f64; 4])>,
}

/// One state of the firmware's level sequence.
#[derive(Debug, Default, Clone)]
pub(crate) struct Step {
    /// The operation as printed after `op`, e.g. `arc 1 200`.
    pub(crate) op: String,
    pub(crate) levels: Vec<f32>,
    pub(crate) sensors: Vec<(String, Vec<f64>)>,
    pub(crate) zones: Vec<(String, Vec<f64>)>,
    /// `(patch, exitance per band)` for the sample of patches the firmware prints.
    pub(crate) patches: Vec<(usize, Vec<f64>)>,
}

pub(crate) fn number<T: std::str::FromStr>(field: &str, line: &str) -> T {
    field
        .parse()
        .unwrap_or_else(|_| panic!("not a number: {field:?} in {line:?}"))
}

/// Values `name v0 [v1 v2]` at the end of a reading line; a name may contain spaces.
pub(crate) fn named_values(rest: &[&str], bands: usize, line: &str) -> (String, Vec<f64>) {
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
    pub(crate) fn parse(stdout: &str, script_stdout: &str) -> FirmwareRun {
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
