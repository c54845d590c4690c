//! `eigenrad eval`: a basis evaluated through the runtime, as firmware computes it, its
//! channels at their levels and, with a time and a sky, the daylight the basis carries.

use std::path::Path;

use eigenrad_runtime::Basis;

use super::super::levels::{applied, parse_levels, LevelArgs};
use super::super::sky::{sky, SkyReport, SkyRequest};
use super::{
    band_names, basis_error, daylight_err, unit, with_site_offset, DaylightArgs, DaylightReadout,
    PatchReading, Reading, Readout,
};
use crate::accuracy::runtime_eval;
use crate::error::Result;
use crate::pipeline::{GridReadout, PieceLayout};

/// `eigenrad eval`: the basis evaluated through the runtime.
pub fn eval(path: &Path, bytes: &[u8], level_args: &LevelArgs, patches: bool) -> Result<Readout> {
    eval_with_daylight(path, bytes, level_args, None, patches)
}

/// `eigenrad eval`, with daylight when `daylight` gives a time and a sky: the basis' stored
/// daylight weighed by that sky through the runtime's [`eigenrad_runtime::DaylightEvaluator`],
/// reported apart from the channels and together with them, as `solve` reports the exact
/// solve.
pub fn eval_with_daylight(
    path: &Path,
    bytes: &[u8],
    level_args: &LevelArgs,
    daylight: Option<&DaylightArgs>,
    patches: bool,
) -> Result<Readout> {
    let electric = eval_channels(path, bytes, level_args, patches)?;
    match daylight {
        None => Ok(electric),
        Some(args) => add_basis_daylight(path, bytes, args, electric),
    }
}

/// The least-power channel levels for `targets` (`ZONE=LUX`, a zone's illuminance at
/// least, lux), found by the runtime's level solver (`LevelProblem`, as firmware finds them)
/// with every channel controlled, each weighed by `weights` (W at level 1; `None`: 1 each,
/// the least total level), over the daylight of `daylight` (none without it). Returns the
/// levels as `--level NAME=VALUE` arguments, and a note per target the channels cannot meet
/// even at full output (their levels are then the closest the solver finds).
pub fn levels_for_targets(
    path: &Path,
    bytes: &[u8],
    targets: &[String],
    weights: Option<&[f64]>,
    daylight: Option<&DaylightArgs>,
) -> Result<(LevelArgs, Vec<String>)> {
    use eigenrad_runtime::{LevelProblem, Output};
    let basis = Basis::from_bytes(bytes).map_err(basis_error(path))?;
    let m = basis.channel_count();
    let names: Vec<String> = (0..m)
        .map(|c| basis.channel_name(c).map(str::to_owned))
        .collect::<std::result::Result<_, _>>()
        .map_err(basis_error(path))?;
    let bad = |argument: &str, reason: String| crate::Error::Level {
        flag: "--target",
        argument: argument.to_owned(),
        reason,
    };
    let mut wanted = Vec::new();
    for argument in targets {
        let Some((zone, lux)) = argument.split_once('=') else {
            return Err(bad(argument, "give ZONE=LUX".into()));
        };
        let z = basis
            .find_zone(zone.trim())
            .ok_or_else(|| bad(argument, format!("the basis has no zone `{}`", zone.trim())))?;
        let lux: f64 = lux
            .trim()
            .parse()
            .ok()
            .filter(|x: &f64| x.is_finite() && *x > 0.0 && *x <= 1.0e5)
            .ok_or_else(|| {
                bad(
                    argument,
                    format!(
                        "`{}` is not an illuminance from 0 to 100 000 lux",
                        lux.trim()
                    ),
                )
            })?;
        wanted.push((argument.clone(), z, lux));
    }
    // The light the channels do not give: daylight, read with every channel off.
    let off = LevelArgs {
        levels: names.iter().map(|n| format!("{n}=0")).collect(),
        arcs: Vec::new(),
    };
    let dark = eval_with_daylight(path, bytes, &off, daylight, false)?;
    let all: Vec<usize> = (0..m).collect();
    let weights: Vec<f32> = match weights {
        Some(w) => w.iter().map(|&x| x as f32).collect(),
        None => vec![1.0; m],
    };
    let mut problem = LevelProblem::new(&weights)?;
    for (_, z, lux) in &wanted {
        let ambient = dark.zones[*z].irradiance[0];
        problem.add_output_bound(
            &basis,
            &all,
            Output::Zone(*z),
            ambient as f32,
            *lux as f32,
            f32::INFINITY,
        )?;
    }
    let mut levels = vec![0.0f32; m];
    let mut notes = Vec::new();
    match problem.solve(&mut levels) {
        Ok(_) => {}
        Err(eigenrad_runtime::Error::BoundUnmet { bound, by, .. }) => notes.push(format!(
            "--target {}: the channels at full output fall short of it by {by:.1} lux; the levels are the closest",
            wanted[bound].0
        )),
        Err(e) => return Err(e.into()),
    }
    Ok((
        LevelArgs {
            levels: names
                .iter()
                .zip(&levels)
                .map(|(n, l)| format!("{n}={l:?}"))
                .collect(),
            arcs: Vec::new(),
        },
        notes,
    ))
}

/// The sky of `args` at the site a basis' daylight was built for: its patches are the basis'
/// (`--mf` must agree), a time without an offset takes the site's.
fn basis_sky(path: &Path, basis: &Basis<'_>, args: &DaylightArgs) -> Result<SkyReport> {
    let (Some(site), Some(patches)) = (basis.site(), basis.sky_patches()) else {
        return Err(daylight_err(
            "--time",
            format!(
                "{} carries no daylight: build it from a scene with a [site] and glazed windows (docs/scene.md, \"Daylight\")",
                path.display()
            ),
        ));
    };
    if args.subdivision != patches.subdivision() {
        return Err(daylight_err(
            "--mf",
            format!(
                "{} holds the daylight of the sky patches of MF:{}; give --mf {} or none",
                path.display(),
                patches.subdivision(),
                patches.subdivision()
            ),
        ));
    }
    let offset = (site.utc_offset_minutes * 60.0).round() as i32;
    let time = with_site_offset(&args.time, Some(offset));
    Ok(sky(&SkyRequest {
        site: crate::daylight::sun::Site {
            latitude: f64::from(site.latitude),
            longitude: f64::from(site.longitude),
            elevation: f64::from(site.elevation),
        },
        time,
        north: f64::from(site.north),
        input: args.input,
        water: args.water,
        subdivision: patches.subdivision(),
    })?)
}

/// The daylight of `args` from the basis, added to the channels' readout `electric`.
fn add_basis_daylight(
    path: &Path,
    bytes: &[u8],
    args: &DaylightArgs,
    electric: Readout,
) -> Result<Readout> {
    let basis = Basis::from_bytes(bytes).map_err(basis_error(path))?;
    // The sky is computed at the stored site: its values are checked first.
    basis.check_daylight().map_err(basis_error(path))?;
    let report = basis_sky(path, &basis, args)?;
    let state = runtime_eval::SkyState::of(&report);
    let levels: Vec<f32> = electric.levels.iter().map(|l| l.level as f32).collect();
    let day = runtime_eval::evaluate_daylight(bytes, &state, &levels, electric.patches.is_some())?;
    let together = |name: &str, e: &[f64], d: f64| Reading {
        name: name.to_owned(),
        irradiance: vec![e[0] + d],
        daylight: Some(vec![d]),
        electric: Some(e.to_vec()),
    };
    let sensors = electric
        .sensors
        .iter()
        .zip(&day.sensors)
        .map(|(e, &d)| together(&e.name, &e.irradiance, d))
        .collect();
    let zones = electric
        .zones
        .iter()
        .zip(&day.zones)
        .map(|(e, &d)| together(&e.name, &e.irradiance, d))
        .collect();
    // The grids: zone by zone as the readout lists them (zones with a grid only).
    let mut grids = Vec::new();
    let mut daylight_grids = Vec::new();
    let mut next = 0;
    let mut with_grid = (0..basis.zone_count()).filter(|&z| basis.grid_points(z).unwrap_or(0) > 0);
    for g in &electric.grids {
        let z = with_grid.next().unwrap_or(0);
        let points = g.points.len();
        let daylight: Vec<Vec<f64>> = day.grid[next..next + points]
            .iter()
            .map(|&d| vec![d])
            .collect();
        let total: Vec<Vec<f64>> = g
            .points
            .iter()
            .zip(&daylight)
            .map(|(p, d)| vec![p.irradiance[0] + d[0]])
            .collect();
        let positions: Vec<[f64; 3]> = g.points.iter().map(|p| p.position_m).collect();
        let figures = |f: Option<&eigenrad_runtime::Figures>| f.map(|f| vec![*f]);
        grids.push(GridReadout::new(
            g.zone.clone(),
            g.pieces.clone(),
            positions.clone(),
            &total,
            figures(day.figures_with_channels[z].as_ref()).as_deref(),
        ));
        daylight_grids.push(GridReadout::new(
            g.zone.clone(),
            g.pieces.clone(),
            positions,
            &daylight,
            figures(day.figures[z].as_ref()).as_deref(),
        ));
        next += points;
    }
    let patches = electric.patches.map(|list| {
        list.into_iter()
            .zip(&day.exitance)
            .map(|(p, &m)| {
                let rho = basis
                    .patch(p.id)
                    .map_or(0.0, |i| f64::from(i.reflectance[0]));
                PatchReading {
                    exitance: vec![p.exitance[0] + m],
                    irradiance: p
                        .irradiance
                        .map(|e| vec![e[0] + if rho > 0.0 { m / rho } else { 0.0 }]),
                    ..p
                }
            })
            .collect()
    });
    Ok(Readout {
        unit: electric.unit,
        bands: electric.bands,
        levels: electric.levels,
        sensors,
        zones,
        grids,
        patches,
        // A basis does not name its windows.
        daylight: Some(DaylightReadout::of(report, Vec::new(), daylight_grids)),
    })
}

/// The channels of a basis at their levels through the runtime (`eigenrad eval` without a
/// sky).
fn eval_channels(
    path: &Path,
    bytes: &[u8],
    level_args: &LevelArgs,
    patches: bool,
) -> Result<Readout> {
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
        sensors.push(Reading::total(name(basis.sensor_name(s))?, v.clone()));
    }
    let mut zones = Vec::new();
    for (z, v) in got.zones.iter().enumerate() {
        zones.push(Reading::total(name(basis.zone_name(z))?, v.clone()));
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
        daylight: None,
    })
}
