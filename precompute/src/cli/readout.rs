//! `eigenrad solve` and `eigenrad eval`: the readings of a scene's exact solve or of a basis
//! evaluated through the runtime, for channel levels given as `NAME=VALUE` or as DALI arc
//! levels `NAME=ARC`, and their table.

use std::fmt::Write as _;
use std::path::Path;

use eigenrad_runtime::{Basis, Quantity};
use serde::Serialize;

use super::sky::{sky, SkyInput, SkyReport, SkyRequest};
use crate::accuracy::runtime_eval;
use crate::error::{Error, Result};
use crate::formfactor::FormFactorOptions;
use crate::pipeline::{self, scene_grids, GridReadout, PieceLayout};
use crate::radiosity::System;

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
    /// Irradiance per band (W/m²) or illuminance (lux): all the light, daylight included.
    pub irradiance: Vec<f64>,
    /// With a sky (`solve --time`): the part of `irradiance` that daylight gives, lux.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub daylight: Option<Vec<f64>>,
    /// With a sky: the part the channels give at their levels, lux.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub electric: Option<Vec<f64>>,
}

impl Reading {
    /// A reading of all the light, without a daylight split.
    fn total(name: String, irradiance: Vec<f64>) -> Reading {
        Reading {
            name,
            irradiance,
            daylight: None,
            electric: None,
        }
    }
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
    /// With a sky (`solve --time`): the sky, and the grids under daylight alone.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub daylight: Option<DaylightReadout>,
}

/// Daylight for `solve`: a time and a sky, driven by the same flags as `eigenrad sky`. The
/// site and the room's orientation are the scene's `[site]`.
#[derive(Clone, Debug)]
pub struct DaylightArgs {
    /// Date-time, RFC 3339 with its UTC offset; without one, the site's `utc_offset`.
    pub time: String,
    /// The sky and what drives it.
    pub input: SkyInput,
    /// Precipitable water, cm (Perez efficacies).
    pub water: f64,
    /// Reinhart subdivision MF (1: Tregenza's 145 patches).
    pub subdivision: u8,
}

/// The sky a readout's daylight comes from, and the grids under daylight alone.
#[derive(Clone, Debug, Serialize)]
pub struct DaylightReadout {
    /// The time, RFC 3339 with its offset.
    pub time: String,
    /// `CIE type N`, `CIE traditional overcast` or `Perez`.
    pub model: String,
    /// The sun seen from the site (apparent altitude).
    pub sun: crate::daylight::sun::SunPosition,
    /// The sun's direction in the room's frame (unit vector).
    pub sun_direction_room: [f64; 3],
    /// Diffuse horizontal illuminance of the unobstructed sky, lux.
    pub diffuse_horizontal_lux: f64,
    /// Direct normal illuminance of the sun, lux.
    pub direct_normal_lux: f64,
    /// Global horizontal illuminance, lux: what lights the ground outside.
    pub global_horizontal_lux: f64,
    /// The sky patches: `tregenza` (MF:1) or `reinhart MF:n`, and how many.
    pub patch_set: String,
    /// Number of sky patches.
    pub patch_count: usize,
    /// The glazed surfaces the daylight enters through.
    pub windows: Vec<String>,
    /// The zones' grids under daylight alone, with their figures.
    pub grids: Vec<GridReadout>,
}

impl DaylightReadout {
    /// The readout of the sky of `report`, through `windows` (their names), with the grids
    /// under daylight alone.
    fn of(report: SkyReport, windows: Vec<String>, grids: Vec<GridReadout>) -> Self {
        DaylightReadout {
            patch_count: report.patches.len(),
            time: report.time,
            model: report.model,
            sun: report.sun,
            sun_direction_room: report.sun_direction_room,
            diffuse_horizontal_lux: report.diffuse_horizontal_lux,
            direct_normal_lux: report.direct_normal_lux,
            global_horizontal_lux: report.global_horizontal_lux,
            patch_set: report.patch_set,
            windows,
            grids,
        }
    }
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
    solve_with_daylight(scene_path, level_args, None, patches, form_factors)
}

/// The exact solve of the channels at some levels, or of one further light alone: per band,
/// the exitance and irradiance of every patch and the reading of every output
/// (`[patch][band]`, `[output][band]`).
struct Solved {
    exitance: Vec<Vec<f64>>,
    irradiance: Vec<Vec<f64>>,
    outputs: Vec<Vec<f64>>,
}

impl Solved {
    fn new(patches: usize, outputs: usize, bands: usize) -> Solved {
        Solved {
            exitance: vec![vec![0.0; bands]; patches],
            irradiance: vec![vec![0.0; bands]; patches],
            outputs: vec![vec![0.0; bands]; outputs],
        }
    }

    /// Band `b`'s exitance, patch irradiance and readings.
    fn set(&mut self, b: usize, exitance: &[f64], irradiance: &[f64], readings: &[f64]) {
        for (i, (m, e)) in exitance.iter().zip(irradiance).enumerate() {
            self.exitance[i][b] = *m;
            self.irradiance[i][b] = *e;
        }
        for (o, r) in readings.iter().enumerate() {
            self.outputs[o][b] = *r;
        }
    }
}

/// The channels of `system` at `levels`, solved exactly in every band.
fn solve_levels(system: &System, levels: &[f64]) -> Result<Solved> {
    let mut out = Solved::new(
        system.patch_count(),
        system.output_count(),
        system.band_count(),
    );
    for b in 0..system.band_count() {
        let m = system.exact(b, levels, &[])?;
        let e = system.patch_irradiance(b, &m, levels);
        out.set(b, &m, &e, &system.readings(b, &m, levels));
    }
    Ok(out)
}

/// `light` alone (not a channel of `system`: a moment's daylight), solved exactly in every band.
fn solve_light(system: &System, light: &crate::sources::ChannelLight) -> Result<Solved> {
    let mut out = Solved::new(
        system.patch_count(),
        system.output_count(),
        system.band_count(),
    );
    for b in 0..system.band_count() {
        let (response, e) = system
            .light_responses_with_irradiance(b, std::slice::from_ref(light))?
            .remove(0);
        out.set(b, &response.exitance, &e, &response.readings);
    }
    Ok(out)
}

fn daylight_err(what: &str, reason: impl Into<String>) -> Error {
    Error::Daylight {
        what: what.to_owned(),
        reason: reason.into(),
    }
}

/// The sky of `args` over `scene`'s site: the sun, the illuminances and every sky patch's
/// centre luminance, as `eigenrad sky` reports them. A time without a UTC offset takes the
/// site's `utc_offset`.
fn sky_of_moment(
    scene: &crate::scene::Scene,
    scene_path: &Path,
    args: &DaylightArgs,
) -> Result<SkyReport> {
    let site = scene.site.as_ref().ok_or_else(|| {
        daylight_err(
            "--time",
            format!(
                "{} has no [site]: daylight needs the room's latitude, longitude and orientation (docs/scene.md, \"Daylight\")",
                scene_path.display()
            ),
        )
    })?;
    let time = with_site_offset(&args.time, site.utc_offset);
    sky(&SkyRequest {
        site: site.location,
        time,
        north: site.north,
        input: args.input,
        water: args.water,
        subdivision: args.subdivision,
    })
}

/// `time` as given, or with the site's UTC offset (seconds east) when it has none.
fn with_site_offset(time: &str, offset: Option<i32>) -> String {
    match (crate::daylight::sun::parse_time(time), offset) {
        (Ok(_), _) | (Err(_), None) => time.trim().to_owned(),
        (Err(_), Some(offset)) => match chrono::FixedOffset::east_opt(offset) {
            // Displayed as `+HH:MM`, the form `parse_time` reads.
            Some(offset) => format!("{}{offset}", time.trim()),
            None => time.trim().to_owned(),
        },
    }
}

/// The daylight the sky of `report` sends through the windows, as one light
/// ([`crate::sources::daylight::moment_light`]), and its summary.
fn daylight_light(
    scene: &crate::scene::Scene,
    occluders: &crate::formfactor::Occluders,
    args: &DaylightArgs,
    report: SkyReport,
) -> Result<(crate::sources::ChannelLight, DaylightReadout)> {
    use crate::sources::daylight;
    let patches = eigenrad_runtime::sky::patches::SkyPatches::reinhart(args.subdivision)
        .map_err(|e| daylight_err("--mf", e.to_string()))?;
    let luminances: Vec<f64> = report.patches.iter().map(|p| p.luminance_cd_m2).collect();
    let [x, y, z] = report.sun_direction_room;
    let moment = daylight::SkyMoment {
        patches,
        luminances: &luminances,
        global_horizontal_lux: report.global_horizontal_lux,
        direct_normal_lux: report.direct_normal_lux,
        toward_sun: crate::geometry::Vec3::new(x, y, z),
    };
    let light = daylight::moment_light(
        scene,
        occluders,
        &moment,
        &daylight::DaylightOptions::default(),
    );
    let windows = scene
        .windows
        .iter()
        .map(|w| scene.surfaces[w.surface].name.clone())
        .collect();
    let summary = DaylightReadout::of(report, windows, Vec::new());
    Ok((light, summary))
}

/// `eigenrad solve`, with daylight when `daylight` gives a time and a sky: the channels at
/// their levels and the daylight of that moment, solved apart and reported apart and together.
pub fn solve_with_daylight(
    scene_path: &Path,
    level_args: &LevelArgs,
    daylight: Option<&DaylightArgs>,
    patches: bool,
    form_factors: &FormFactorOptions,
) -> Result<Readout> {
    // The sky first: a bad time or a scene without a site is an error before any form factor.
    let moment = match daylight {
        None => None,
        Some(args) => Some(sky_of_moment(
            &crate::scene::load(scene_path)?,
            scene_path,
            args,
        )?),
    };
    let prepared = pipeline::prepare(scene_path, form_factors)?;
    let scene = &prepared.scene;
    let names: Vec<String> = scene.channels.iter().map(|c| c.name.clone()).collect();
    let levels = parse_levels(level_args, &names)?;
    let system = &prepared.system;
    let mut solved = vec![solve_levels(system, &levels)?];
    let mut daylight_readout = None;
    if let Some((args, report)) = daylight.zip(moment) {
        let (light, summary) = daylight_light(scene, &prepared.occluders, args, report)?;
        solved.push(solve_light(system, &light)?);
        daylight_readout = Some(summary);
    }
    let sum = |a: &[Vec<f64>], b: Option<&[Vec<f64>]>| -> Vec<Vec<f64>> {
        match b {
            None => a.to_vec(),
            Some(b) => a
                .iter()
                .zip(b)
                .map(|(x, y)| x.iter().zip(y).map(|(p, q)| p + q).collect())
                .collect(),
        }
    };
    let electric = &solved[0];
    let day = solved.get(1);
    let outputs = sum(&electric.outputs, day.map(|d| d.outputs.as_slice()));
    let exitance = sum(&electric.exitance, day.map(|d| d.exitance.as_slice()));
    let irradiance = sum(&electric.irradiance, day.map(|d| d.irradiance.as_slice()));
    if let (Some(readout), Some(day)) = (&mut daylight_readout, day) {
        readout.grids = scene_grids(scene, &day.outputs);
    }
    let reading = |name: &str, o: usize| Reading {
        name: name.to_owned(),
        irradiance: outputs[o].clone(),
        daylight: day.map(|d| d.outputs[o].clone()),
        electric: day.map(|_| electric.outputs[o].clone()),
    };
    let sensors = scene.sensors.len();
    Ok(Readout {
        unit: scene.bands.unit(),
        bands: band_names(scene.bands.count()),
        levels: applied(&names, &levels, level_args),
        sensors: scene
            .sensors
            .iter()
            .enumerate()
            .map(|(o, s)| reading(&s.name, o))
            .collect(),
        zones: scene
            .zones
            .iter()
            .enumerate()
            .map(|(z, zone)| reading(&zone.name, sensors + z))
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
        daylight: daylight_readout,
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
    sky(&SkyRequest {
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
    })
}

/// The daylight of `args` from the basis, added to the channels' readout `electric`.
fn add_basis_daylight(
    path: &Path,
    bytes: &[u8],
    args: &DaylightArgs,
    electric: Readout,
) -> Result<Readout> {
    let basis = Basis::from_bytes(bytes).map_err(basis_error(path))?;
    let report = basis_sky(path, &basis, args)?;
    let sun = (report.direct_normal_lux > 0.0).then(|| eigenrad_runtime::Sun {
        direction: eigenrad_runtime::sky::direction(
            report.sun.altitude.to_radians() as f32,
            report.sun.azimuth.to_radians() as f32,
        ),
        direct_normal: report.direct_normal_lux as f32,
    });
    let state = runtime_eval::SkyState {
        sky_luminance: report
            .patches
            .iter()
            .map(|p| p.luminance_cd_m2 as f32)
            .collect(),
        global_horizontal: report.global_horizontal_lux as f32,
        sun,
    };
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

/// Every grid point of `r` as CSV: a header naming the units, then one line per point, zones
/// in basis order and points first side fastest, positions to 0.1 mm. Names are quoted
/// (doubling any quote).
pub fn grids_csv(r: &Readout) -> String {
    let unit = match r.unit {
        "lux" => "lux",
        _ => "W_per_m2",
    };
    // With daylight, each point's daylight part follows its total, band by band.
    let daylight = r.daylight.as_ref().map(|d| &d.grids);
    let mut s = String::from("zone,point,x_m,y_m,z_m");
    for b in &r.bands {
        let _ = write!(s, ",{b}_{unit}");
    }
    if daylight.is_some() {
        for b in &r.bands {
            let _ = write!(s, ",daylight_{b}_{unit}");
        }
    }
    s.push('\n');
    for (k, g) in r.grids.iter().enumerate() {
        let zone = g.zone.replace('"', "\"\"");
        let day = daylight.and_then(|d| d.get(k));
        for (i, p) in g.points.iter().enumerate() {
            let [x, y, z] = p.position_m;
            let _ = write!(s, "\"{zone}\",{i},{x:.4},{y:.4},{z:.4}");
            let day_point = day.and_then(|d| d.points.get(i));
            let parts = day_point.map(|d| d.irradiance.as_slice()).unwrap_or(&[]);
            for v in p.irradiance.iter().chain(parts) {
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
    if let Some(d) = &r.daylight {
        let _ = writeln!(
            s,
            "daylight: {} at {}; sun altitude {:.2}°, azimuth {:.2}°; diffuse horizontal {:.1} lux, direct normal {:.1} lux, global horizontal {:.1} lux; {} sky patches ({}); through {}",
            d.model,
            d.time,
            d.sun.altitude,
            d.sun.azimuth,
            d.diffuse_horizontal_lux,
            d.direct_normal_lux,
            d.global_horizontal_lux,
            d.patch_count,
            d.patch_set,
            if d.windows.is_empty() {
                // A basis does not name its windows.
                "the windows".to_owned()
            } else {
                d.windows.join(", ")
            }
        );
    }
    // With daylight, each reading is followed by its two parts.
    let parts = |x: &Reading| match (&x.daylight, &x.electric) {
        (Some(d), Some(e)) => format!(" = daylight {} + electric {}", fmt(d), fmt(e)),
        _ => String::new(),
    };
    for x in &r.sensors {
        let _ = writeln!(
            s,
            "sensor {:<20} {} {}{}",
            x.name,
            fmt(&x.irradiance),
            r.unit,
            parts(x)
        );
    }
    for z in &r.zones {
        let _ = writeln!(
            s,
            "zone   {:<20} {} {} (average){}",
            z.name,
            fmt(&z.irradiance),
            r.unit,
            parts(z)
        );
    }
    write_grids(&mut s, &r.grids, r.unit);
    if let Some(d) = &r.daylight {
        if !d.grids.is_empty() {
            let _ = writeln!(s, "under daylight alone:");
            write_grids(&mut s, &d.grids, r.unit);
        }
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
