//! `eigenrad solve` and `eigenrad eval`: the readings of a scene's exact solve or of a basis
//! evaluated through the runtime, for channel levels given as `NAME=VALUE` or as DALI arc
//! levels `NAME=ARC`, and their table.

use std::fmt::Write as _;
use std::path::Path;

use eigenrad_runtime::{Basis, Quantity};
use serde::Serialize;

use crate::accuracy::runtime_eval;
use crate::error::{Error, Result};
use crate::formfactor::exchange;
use crate::formfactor::FormFactorOptions;
use crate::pipeline::{self, scene_grids, GridReadout, PieceLayout};
use crate::radiosity::exact::ExactSolver;
use crate::radiosity::model;

/// A channel level as applied.
#[derive(Clone, Debug, Serialize)]
pub struct Level {
    /// Channel name.
    pub name: String,
    /// Relative level (1 = as built).
    pub level: f64,
    /// The DALI arc power level it was given as (`--arc`), if it was.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub arc: Option<u8>,
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
    /// Calculation grids of the zones that have one, with their figures.
    pub grids: Vec<GridReadout>,
    /// Per patch, with `--patches`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub patches: Option<Vec<PatchReading>>,
}

pub(super) fn band_names(count: usize) -> Vec<&'static str> {
    if count == 1 {
        vec!["photopic"]
    } else {
        vec!["red", "green", "blue"]
    }
}

/// Each channel's name with the level applied to it, and the arc level it was given as.
/// `args` are the arguments [`parse_levels`] accepted.
fn applied(names: &[String], levels: &[f64], args: &LevelArgs) -> Vec<Level> {
    names
        .iter()
        .zip(levels)
        .map(|(name, &level)| Level {
            name: name.clone(),
            level,
            // The last `--arc` naming the channel, as in `parse_levels`.
            arc: args.arcs.iter().rev().find_map(|a| {
                let (n, v) = a.split_once('=')?;
                if n == name {
                    v.trim().parse().ok()
                } else {
                    None
                }
            }),
        })
        .collect()
}

/// Channel levels as given on the command line: relative levels (`--level NAME=VALUE`) and
/// DALI arc power levels (`--arc NAME=ARC`). Channels named in neither stay at 1.
#[derive(Clone, Debug, Default)]
pub struct LevelArgs {
    /// `NAME=VALUE`, the relative level (1 = as built), 0 to [`eigenrad_runtime::MAX_LEVEL`].
    pub levels: Vec<String>,
    /// `NAME=ARC`, a DALI arc power level 0..=254 (IEC 62386-102), turned into a relative
    /// level by [`eigenrad_runtime::dali::arc_power_to_level`], as the firmware does.
    pub arcs: Vec<String>,
}

/// The channel named in `argument` (`NAME=...`) and the text after `=`.
fn split_argument<'a>(
    flag: &'static str,
    argument: &'a str,
    channels: &[String],
) -> Result<(usize, &'a str)> {
    let bad = |reason: String| Error::Level {
        flag,
        argument: argument.to_owned(),
        reason,
    };
    let expected = if flag == "--arc" {
        "expected NAME=ARC"
    } else {
        "expected NAME=VALUE"
    };
    let (name, value) = argument
        .split_once('=')
        .ok_or_else(|| bad(expected.into()))?;
    let index = channels.iter().position(|c| c == name).ok_or_else(|| {
        bad(format!(
            "no channel named `{name}` (channels: {})",
            channels.join(", ")
        ))
    })?;
    Ok((index, value))
}

/// Parses `--level NAME=VALUE` and `--arc NAME=ARC` arguments against the channel names;
/// unnamed channels stay at 1. A channel given by both `--level` and `--arc` is an error
/// naming it; given twice by the same flag, the last value counts.
pub fn parse_levels(arguments: &LevelArgs, channels: &[String]) -> Result<Vec<f64>> {
    let mut levels = vec![1.0; channels.len()];
    let mut by_level = vec![false; channels.len()];
    for argument in &arguments.levels {
        let (index, value) = split_argument("--level", argument, channels)?;
        let bad = |reason: String| Error::Level {
            flag: "--level",
            argument: argument.clone(),
            reason,
        };
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
        by_level[index] = true;
    }
    for argument in &arguments.arcs {
        let (index, value) = split_argument("--arc", argument, channels)?;
        let bad = |reason: String| Error::Level {
            flag: "--arc",
            argument: argument.clone(),
            reason,
        };
        if by_level[index] {
            return Err(bad(format!(
                "channel `{}` is also given by --level; give each channel one way",
                channels[index]
            )));
        }
        let arc: u8 = match value.trim().parse::<u32>() {
            Ok(255) => {
                return Err(bad(
                    "255 is DALI's MASK (\"no change\"), not a light level; arc power levels are 0 (off) to 254 (100 %)".into(),
                ))
            }
            Ok(n) if n <= 254 => n as u8,
            _ => {
                return Err(bad(format!(
                    "`{value}` is not a DALI arc power level (a whole number 0 to 254)"
                )))
            }
        };
        let level =
            eigenrad_runtime::dali::arc_power_to_level(arc).map_err(|e| bad(e.to_string()))?;
        levels[index] = f64::from(level);
    }
    Ok(levels)
}

/// `eigenrad solve`: the exact dense solution.
///
/// `form_factors` sets the form-factor computation, its progress bar and cache.
pub fn solve(
    scene_path: &Path,
    level_args: &LevelArgs,
    patches: bool,
    form_factors: &FormFactorOptions,
) -> Result<Readout> {
    let prepared = pipeline::prepare(scene_path, form_factors)?;
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
        levels: applied(&names, &levels, level_args),
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
        grids: scene_grids(scene, &outputs),
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

pub(super) fn basis_error(path: &Path) -> impl Fn(eigenrad_runtime::Error) -> Error + '_ {
    move |reason| Error::Basis {
        path: path.to_path_buf(),
        reason,
    }
}

/// `eigenrad eval`: the basis evaluated through the runtime.
pub fn eval(path: &Path, bytes: &[u8], level_args: &LevelArgs, patches: bool) -> Result<Readout> {
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
    let mut grids = Vec::new();
    let mut next = 0;
    for z in 0..basis.zone_count() {
        let points = basis.grid_points(z).map_err(basis_error(path))?;
        if points == 0 {
            continue;
        }
        let mut pieces = Vec::new();
        for k in 0..basis.grid_piece_count(z).map_err(basis_error(path))? {
            let piece = basis.grid_piece(z, k).map_err(basis_error(path))?;
            pieces.push(PieceLayout::from(piece));
        }
        let mut positions = Vec::with_capacity(points);
        for i in 0..points {
            let at = basis.grid_point(z, i).map_err(basis_error(path))?;
            positions.push(at.map(f64::from));
        }
        grids.push(GridReadout::new(
            name(basis.zone_name(z))?,
            pieces,
            positions,
            &got.grid[next..next + points],
            got.figures[z].as_deref(),
        ));
        next += points;
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
        levels: applied(&names, &levels, level_args),
        sensors,
        zones,
        grids,
        patches: patch_list,
    })
}

/// Every grid point of `r` as CSV: a header naming the units, then one line per point, zones
/// in basis order and points first side fastest, positions to 0.1 mm. Names are quoted
/// (doubling any quote).
pub fn grids_csv(r: &Readout) -> String {
    let unit = match r.unit {
        "lux" => "lux",
        _ => "W_per_m2",
    };
    let mut s = String::from("zone,point,x_m,y_m,z_m");
    for b in &r.bands {
        let _ = write!(s, ",{b}_{unit}");
    }
    s.push('\n');
    for g in &r.grids {
        let zone = g.zone.replace('"', "\"\"");
        for (i, p) in g.points.iter().enumerate() {
            let [x, y, z] = p.position_m;
            let _ = write!(s, "\"{zone}\",{i},{x:.4},{y:.4},{z:.4}");
            for v in &p.irradiance {
                let _ = write!(s, ",{v}");
            }
            s.push('\n');
        }
    }
    s
}

/// Two lines per grid: its layout, then its figures (`unit`: lux or W/m²).
pub(super) fn write_grids(s: &mut String, grids: &[GridReadout], unit: &str) {
    let fmt = |v: &[f64]| {
        v.iter()
            .map(|x| format!("{x:.4}"))
            .collect::<Vec<_>>()
            .join(" ")
    };
    let layout = |p: &PieceLayout| {
        let kept = if p.points < p.counts[0] * p.counts[1] {
            format!(" ({} on the area)", p.points)
        } else {
            String::new()
        };
        format!(
            "{} × {} points{kept}, spacing ≤ {:.3} m, cells {:.3} × {:.3} m, border {:.2} m",
            p.counts[0], p.counts[1], p.spacing_m, p.cell_m[0], p.cell_m[1], p.border_m
        )
    };
    for g in grids {
        match &g.pieces[..] {
            [one] => {
                let _ = writeln!(s, "grid   {:<20} {} (EN 12464-1)", g.zone, layout(one));
            }
            pieces => {
                let _ = writeln!(
                    s,
                    "grid   {:<20} {} points in {} pieces (EN 12464-1)",
                    g.zone,
                    g.points.len(),
                    pieces.len()
                );
                for (k, p) in pieces.iter().enumerate() {
                    let _ = writeln!(s, "       piece {:<14} {}", k + 1, layout(p));
                }
            }
        }
        let _ = writeln!(
            s,
            "       E_avg {} {unit}, E_min {} {unit}, E_max {} {unit}, U_o {}",
            fmt(&g.average),
            fmt(&g.minimum),
            fmt(&g.maximum),
            fmt(&g.uniformity),
        );
    }
}

pub(super) fn unit(q: Quantity) -> &'static str {
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
            .map(|l| match l.arc {
                Some(arc) => format!("{}={} (arc {arc})", l.name, l.level),
                None => format!("{}={}", l.name, l.level),
            })
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
    write_grids(&mut s, &r.grids, r.unit);
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
