//! What the `eigenrad` subcommands compute and print, kept in the library so tests can call
//! it. `main.rs` only parses arguments.

pub mod atomic;
pub mod guard;

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use eigenrad_runtime::{Basis, Quantity};
use serde::Serialize;

use crate::accuracy::runtime_eval;
use crate::error::{Error, Result};
use crate::formfactor::exchange;
use crate::formfactor::FormFactorOptions;
use crate::pipeline::{self, BuildReport};
use crate::radiosity::exact::ExactSolver;
use crate::radiosity::model;
use crate::verify::{self, VerifyReport};

/// A channel level as applied.
#[derive(Clone, Debug, Serialize)]
pub struct Level {
    /// Channel name.
    pub name: String,
    /// Relative level (1 = as built).
    pub level: f64,
}

/// One sensor or zone reading.
#[derive(Clone, Debug, Serialize)]
pub struct Reading {
    /// Sensor or zone name.
    pub name: String,
    /// Irradiance per band (W/m²) or illuminance (lux).
    pub irradiance: Vec<f64>,
}

/// One patch's results.
#[derive(Clone, Debug, Serialize)]
pub struct PatchReading {
    /// Patch index.
    pub id: usize,
    /// Surface name.
    pub surface: String,
    /// Area, m².
    pub area: f64,
    /// Centroid, m.
    pub centroid: [f64; 3],
    /// Exitance per band, W/m² or lux.
    pub exitance: Vec<f64>,
    /// Irradiance per band, W/m² or lux; `null` where the patch is black and the runtime
    /// cannot tell.
    pub irradiance: Option<Vec<f64>>,
}

/// The JSON document of `solve` and `eval`.
#[derive(Clone, Debug, Serialize)]
pub struct Readout {
    /// Unit of every irradiance and exitance.
    pub unit: &'static str,
    /// Band names.
    pub bands: Vec<&'static str>,
    /// Channel levels used.
    pub levels: Vec<Level>,
    /// Sensor readings.
    pub sensors: Vec<Reading>,
    /// Zone readings (area-average irradiance).
    pub zones: Vec<Reading>,
    /// Per patch, with `--patches`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub patches: Option<Vec<PatchReading>>,
}

fn band_names(count: usize) -> Vec<&'static str> {
    if count == 1 {
        vec!["photopic"]
    } else {
        vec!["red", "green", "blue"]
    }
}

/// Parses `NAME=VALUE` arguments against the channel names; unnamed channels stay at 1.
pub fn parse_levels(arguments: &[String], channels: &[String]) -> Result<Vec<f64>> {
    let mut levels = vec![1.0; channels.len()];
    for argument in arguments {
        let bad = |reason: String| Error::Level {
            argument: argument.clone(),
            reason,
        };
        let (name, value) = argument
            .split_once('=')
            .ok_or_else(|| bad("expected NAME=VALUE".into()))?;
        let index = channels.iter().position(|c| c == name).ok_or_else(|| {
            bad(format!(
                "no channel named `{name}` (channels: {})",
                channels.join(", ")
            ))
        })?;
        let value: f64 = value
            .trim()
            .parse()
            .map_err(|_| bad(format!("`{value}` is not a number")))?;
        if !value.is_finite() || value < 0.0 || value > f64::from(eigenrad_runtime::MAX_LEVEL) {
            return Err(bad(format!(
                "level must be between 0 and {}",
                eigenrad_runtime::MAX_LEVEL
            )));
        }
        levels[index] = value;
    }
    Ok(levels)
}

/// `eigenrad solve`: the exact dense solution.
pub fn solve(scene_path: &Path, level_args: &[String], patches: bool) -> Result<Readout> {
    let prepared = pipeline::prepare(scene_path, &FormFactorOptions::default())?;
    let scene = &prepared.scene;
    let names: Vec<String> = scene.channels.iter().map(|c| c.name.clone()).collect();
    let levels = parse_levels(level_args, &names)?;
    let n = scene.patches.len();
    let bands = scene.bands.count();
    let mut exitance = vec![vec![0.0; bands]; n];
    let mut irradiance = vec![vec![0.0; bands]; n];
    let mut outputs = vec![vec![0.0; bands]; prepared.output_rows.len()];
    let external: Vec<_> = prepared
        .lights
        .iter()
        .map(|l| l.external(&prepared.g, &prepared.area, &prepared.output_rows))
        .collect();
    for b in 0..bands {
        let rho: Vec<f64> = scene.reflectance.iter().map(|r| r[b]).collect();
        let solver = ExactSolver::new(prepared.g.as_ref(), &prepared.area, &rho)?;
        let m0 = model::initial_exitance(&prepared.lights, &external, &rho, b, &levels, &[]);
        let m = solver.solve(&m0);
        // E = F M (exact for black patches too), plus the light from beyond the patches.
        let mut e = exchange::patch_irradiance(&prepared.g, &prepared.area, &m);
        for (c, &l) in levels.iter().enumerate() {
            if let Some(e_ext) = &external[c].patches[b] {
                for (x, d) in e.iter_mut().zip(e_ext) {
                    *x += l * d;
                }
            }
        }
        let mut readings = exchange::output_irradiance(&prepared.output_rows, &m);
        model::add_external_readings(&mut readings, &external, b, &levels);
        for i in 0..n {
            exitance[i][b] = m[i];
            irradiance[i][b] = e[i];
        }
        for (o, r) in readings.iter().enumerate() {
            outputs[o][b] = *r;
        }
    }
    let sensors = scene.sensors.len();
    Ok(Readout {
        unit: scene.bands.unit(),
        bands: band_names(bands),
        levels: names
            .iter()
            .zip(&levels)
            .map(|(n, &l)| Level {
                name: n.clone(),
                level: l,
            })
            .collect(),
        sensors: scene
            .sensors
            .iter()
            .zip(&outputs)
            .map(|(s, o)| Reading {
                name: s.name.clone(),
                irradiance: o.clone(),
            })
            .collect(),
        zones: scene
            .zones
            .iter()
            .zip(outputs.iter().skip(sensors))
            .map(|(z, o)| Reading {
                name: z.name.clone(),
                irradiance: o.clone(),
            })
            .collect(),
        patches: patches.then(|| {
            scene
                .patches
                .iter()
                .enumerate()
                .map(|(i, p)| PatchReading {
                    id: i,
                    surface: scene.surfaces[p.surface].name.clone(),
                    area: p.area,
                    centroid: p.centroid.to_array(),
                    exitance: exitance[i].clone(),
                    irradiance: Some(irradiance[i].clone()),
                })
                .collect()
        }),
    })
}

fn basis_error(path: &Path) -> impl Fn(eigenrad_runtime::Error) -> Error + '_ {
    move |reason| Error::Basis {
        path: path.to_path_buf(),
        reason,
    }
}

/// `eigenrad eval`: the basis evaluated through the runtime.
pub fn eval(path: &Path, bytes: &[u8], level_args: &[String], patches: bool) -> Result<Readout> {
    let basis = Basis::from_bytes(bytes).map_err(basis_error(path))?;
    let names: Vec<String> = (0..basis.channel_count())
        .map(|c| basis.channel_name(c).map(str::to_owned))
        .collect::<std::result::Result<_, _>>()
        .map_err(basis_error(path))?;
    let levels = parse_levels(level_args, &names)?;
    let levels32: Vec<f32> = levels.iter().map(|&l| l as f32).collect();
    let got = runtime_eval::evaluate(bytes, &levels32, &[], patches)?;
    let name = |r: std::result::Result<&str, eigenrad_runtime::Error>| {
        r.map(str::to_owned).map_err(basis_error(path))
    };
    let mut sensors = Vec::new();
    for (s, v) in got.sensors.iter().enumerate() {
        sensors.push(Reading {
            name: name(basis.sensor_name(s))?,
            irradiance: v.clone(),
        });
    }
    let mut zones = Vec::new();
    for (z, v) in got.zones.iter().enumerate() {
        zones.push(Reading {
            name: name(basis.zone_name(z))?,
            irradiance: v.clone(),
        });
    }
    let patch_list = if patches {
        let mut list = Vec::new();
        for (i, (m, e)) in got.exitance.iter().zip(&got.irradiance).enumerate() {
            let info = basis.patch(i).map_err(basis_error(path))?;
            list.push(PatchReading {
                id: i,
                surface: name(basis.surface_name(info.surface))?,
                area: f64::from(info.area),
                centroid: info.centroid.map(f64::from),
                exitance: m.clone(),
                irradiance: e.clone(),
            });
        }
        Some(list)
    } else {
        None
    };
    Ok(Readout {
        unit: unit(basis.quantity()),
        bands: band_names(basis.bands()),
        levels: names
            .iter()
            .zip(&levels)
            .map(|(n, &l)| Level {
                name: n.clone(),
                level: l,
            })
            .collect(),
        sensors,
        zones,
        patches: patch_list,
    })
}

fn unit(q: Quantity) -> &'static str {
    match q {
        Quantity::Photometric => "lux",
        _ => "W/m²",
    }
}

/// A readout as a table, one line per sensor and zone (and per patch when it has them).
pub fn format_readout(r: &Readout) -> String {
    let fmt = |v: &[f64]| {
        v.iter()
            .map(|x| format!("{x:.4}"))
            .collect::<Vec<_>>()
            .join(" ")
    };
    let mut s = String::new();
    let _ = writeln!(
        s,
        "levels: {}",
        r.levels
            .iter()
            .map(|l| format!("{}={}", l.name, l.level))
            .collect::<Vec<_>>()
            .join(", ")
    );
    let _ = writeln!(s, "bands: {} ({})", r.bands.join(" "), r.unit);
    for x in &r.sensors {
        let _ = writeln!(s, "sensor {:<20} {} {}", x.name, fmt(&x.irradiance), r.unit);
    }
    for z in &r.zones {
        let _ = writeln!(
            s,
            "zone   {:<20} {} {} (average)",
            z.name,
            fmt(&z.irradiance),
            r.unit
        );
    }
    if let Some(patches) = &r.patches {
        let _ = writeln!(
            s,
            "{:>6} {:<20} {:>10} {:>28} {:>28}",
            "patch", "surface", "area m²", "exitance", "irradiance"
        );
        for p in patches {
            let e = p.irradiance.as_deref().map_or("-".into(), fmt);
            let _ = writeln!(
                s,
                "{:>6} {:<20} {:>10.5} {:>28} {:>28}",
                p.id,
                p.surface,
                p.area,
                fmt(&p.exitance),
                e
            );
        }
    }
    s
}

/// `value` as one pretty-printed JSON document, with a final newline.
pub fn json<T: Serialize>(value: &T) -> Result<String> {
    serde_json::to_string_pretty(value)
        .map(|mut text| {
            text.push('\n');
            text
        })
        .map_err(Error::Json)
}

/// Writes `text` to standard output and flushes it. A reader that went away (`| head`) is
/// [`Error::ClosedPipe`]; any other failure (a full disk) is [`Error::Stdout`].
pub fn print(text: &str) -> Result<()> {
    use std::io::Write as _;
    let mut out = std::io::stdout().lock();
    out.write_all(text.as_bytes())
        .and_then(|()| out.flush())
        .map_err(|e| match e.kind() {
            std::io::ErrorKind::BrokenPipe => Error::ClosedPipe,
            _ => Error::Stdout(e),
        })
}

/// One line per non-zero surface-to-surface form factor.
pub fn format_surface_form_factors(table: &[SurfaceFactor]) -> String {
    let mut s = String::new();
    for row in table {
        let _ = writeln!(s, "{:>24} -> {:<24} {:.6}", row.from, row.to, row.value);
    }
    s
}

/// One surface-to-surface form factor.
#[derive(Clone, Debug, Serialize)]
pub struct SurfaceFactor {
    /// Emitting surface.
    pub from: String,
    /// Receiving surface.
    pub to: String,
    /// `F_ST = Σ_{i∈S} Σ_{j∈T} A_i F_ij / A_S`.
    pub value: f64,
}

/// `eigenrad form-factors`: surface-to-surface form factors (area-weighted), non-zero ones.
pub fn surface_form_factors(scene_path: &Path) -> Result<Vec<SurfaceFactor>> {
    let prepared = pipeline::prepare(scene_path, &FormFactorOptions::default())?;
    let scene = &prepared.scene;
    let s = scene.surfaces.len();
    let mut sums = vec![vec![0.0f64; s]; s];
    let mut areas = vec![0.0f64; s];
    for (i, p) in scene.patches.iter().enumerate() {
        areas[p.surface] += p.area;
        for (j, q) in scene.patches.iter().enumerate() {
            sums[p.surface][q.surface] += prepared.g[(i, j)];
        }
    }
    let mut out = Vec::new();
    for a in 0..s {
        for b in 0..s {
            if sums[a][b] != 0.0 && areas[a] > 0.0 {
                out.push(SurfaceFactor {
                    from: scene.surfaces[a].name.clone(),
                    to: scene.surfaces[b].name.clone(),
                    value: sums[a][b] / areas[a],
                });
            }
        }
    }
    Ok(out)
}

/// What `inspect` shows.
#[derive(Clone, Debug, Serialize)]
pub struct BasisInfo {
    /// Format version.
    pub format_version: u16,
    /// Total bytes.
    pub bytes: usize,
    /// Unit.
    pub unit: &'static str,
    /// Band names.
    pub bands: Vec<&'static str>,
    /// `split` or `seed`.
    pub formulation: &'static str,
    /// `f32`, `f16` or `i16`.
    pub precision: &'static str,
    /// Number of patches.
    pub patches: usize,
    /// Modes per band.
    pub modes: usize,
    /// Surface names.
    pub surfaces: Vec<String>,
    /// Channel names.
    pub channels: Vec<String>,
    /// Sensor names.
    pub sensors: Vec<String>,
    /// Zone names with their areas (m²).
    pub zones: Vec<(String, f32)>,
    /// Eigenvalues of the first band.
    pub eigenvalues: Vec<f32>,
}

fn names<'a>(
    count: usize,
    f: impl Fn(usize) -> std::result::Result<&'a str, eigenrad_runtime::Error>,
) -> std::result::Result<Vec<String>, eigenrad_runtime::Error> {
    (0..count).map(|i| f(i).map(str::to_owned)).collect()
}

/// `eigenrad inspect`.
pub fn inspect(path: &Path, bytes: &[u8]) -> Result<BasisInfo> {
    let b = Basis::from_bytes(bytes).map_err(basis_error(path))?;
    let e = basis_error(path);
    let mut zones = Vec::new();
    for z in 0..b.zone_count() {
        zones.push((
            b.zone_name(z).map_err(&e)?.to_owned(),
            b.zone_area(z).map_err(&e)?,
        ));
    }
    Ok(BasisInfo {
        format_version: eigenrad_runtime::format::FORMAT_VERSION,
        bytes: b.byte_len(),
        unit: unit(b.quantity()),
        bands: band_names(b.bands()),
        formulation: b.formulation().name(),
        precision: b.precision().name(),
        patches: b.patch_count(),
        modes: b.mode_count(),
        surfaces: names(b.surface_count(), |i| b.surface_name(i)).map_err(&e)?,
        channels: names(b.channel_count(), |i| b.channel_name(i)).map_err(&e)?,
        sensors: names(b.sensor_count(), |i| b.sensor_name(i)).map_err(&e)?,
        zones,
        eigenvalues: (0..b.mode_count())
            .map(|k| b.eigenvalue(0, k))
            .collect::<std::result::Result<_, _>>()
            .map_err(&e)?,
    })
}

/// Human-readable `inspect`.
pub fn format_inspect(i: &BasisInfo) -> String {
    let mut s = String::new();
    let _ = writeln!(s, "format v{}, {} bytes", i.format_version, i.bytes);
    let _ = writeln!(
        s,
        "{} patches, {} modes per band, bands: {} ({})",
        i.patches,
        i.modes,
        i.bands.join(" "),
        i.unit
    );
    let _ = writeln!(s, "formulation {}, storage {}", i.formulation, i.precision);
    let _ = writeln!(
        s,
        "surfaces ({}): {}",
        i.surfaces.len(),
        i.surfaces.join(", ")
    );
    let _ = writeln!(
        s,
        "channels ({}): {}",
        i.channels.len(),
        i.channels.join(", ")
    );
    let _ = writeln!(s, "sensors ({}): {}", i.sensors.len(), i.sensors.join(", "));
    let zones: Vec<String> = i
        .zones
        .iter()
        .map(|(n, a)| format!("{n} ({a:.2} m²)"))
        .collect();
    let _ = writeln!(s, "zones ({}): {}", i.zones.len(), zones.join(", "));
    let head: Vec<String> = i
        .eigenvalues
        .iter()
        .take(8)
        .map(|e| format!("{e:.4}"))
        .collect();
    let _ = writeln!(s, "leading eigenvalues (band 1): {}", head.join(" "));
    s
}

/// Human-readable build report.
pub fn format_build_report(r: &BuildReport, output: &Path) -> String {
    let mut s = String::new();
    let _ = writeln!(
        s,
        "scene {}: {} patches, {} band(s) in {}",
        r.scene, r.patches, r.bands, r.unit
    );
    let f = &r.form_factors;
    let _ = writeln!(
        s,
        "form factors: before symmetrising, the two directions of a pair differ by at most {:.1e} of a patch's output ({:.1e} relative to the exchange, floored at 0.1 % of the output); row sums {:.5} .. {:.5}; {}",
        f.reciprocity_share,
        f.reciprocity_mismatch,
        f.row_sum_min,
        f.row_sum_max,
        if f.closed {
            "closed scene".to_owned()
        } else {
            format!(
                "open scene: {:.2} % of the light leaving the surfaces escapes through openings",
                100.0 * f.escaping
            )
        }
    );
    let _ = writeln!(
        s,
        "basis: {} modes, formulation {}, storage {}, {} bytes -> {}",
        r.modes,
        r.formulation,
        r.precision,
        r.bytes,
        output.display()
    );
    let _ = writeln!(
        s,
        "accuracy through the runtime against the exact solve (relative error):"
    );
    let _ = writeln!(
        s,
        "  {:<28} {:>10}  {:<34}  {:<30}",
        "case", "exitance", "worst patch", "worst sensor or zone"
    );
    for a in &r.accuracy {
        let patch = format!(
            "{:.1e} (patch {}, {})",
            a.worst_patch.error, a.worst_patch.index, a.worst_patch_surface
        );
        let reading = format!("{:.1e} ({})", a.worst_reading.error, a.worst_reading_name);
        let _ = writeln!(
            s,
            "  {:<28} {:>10.1e}  {:<34}  {:<30}",
            a.case, a.patch_error, patch, reading
        );
    }
    let _ = writeln!(
        s,
        "  (exitance: area-weighted RMS over the patches; a patch, sensor or zone against its own exact value, floored at {:.0e} of the largest)",
        crate::accuracy::metric::READING_FLOOR
    );
    let _ = writeln!(s, "time per stage:");
    for t in &r.timings {
        let _ = writeln!(s, "  {:<34} {:>8.3} s", t.stage, t.seconds);
    }
    s
}

/// Every file `eigenrad verify --out dir` may write for the scene named `scene`: the tables
/// and one SVG per metric.
pub fn verify_outputs(dir: &Path, scene: &str) -> Vec<PathBuf> {
    let mut out = vec![dir.join(format!("{scene}.md"))];
    out.extend(
        verify::Metric::ALL
            .iter()
            .map(|m| dir.join(format!("{scene}-{}.svg", m.label()))),
    );
    out
}

/// Writes `eigenrad verify`'s curves into `dir` (created if missing), one SVG per metric
/// ([`verify::svgs`]), each atomically. Returns the files written.
pub fn write_svgs(r: &VerifyReport, dir: &Path) -> Result<Vec<PathBuf>> {
    std::fs::create_dir_all(dir).map_err(|reason| Error::Io {
        path: dir.to_path_buf(),
        reason,
    })?;
    let mut written = Vec::new();
    for (name, svg) in verify::svgs(r)? {
        let path = dir.join(name);
        atomic::write(&path, svg.as_bytes())?;
        written.push(path);
    }
    Ok(written)
}
