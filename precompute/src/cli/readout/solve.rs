//! `eigenrad solve`: the exact dense solve of a scene, its channels at their levels and,
//! with a time and a sky, the daylight of that moment through the scene's windows.

use std::path::Path;

use super::super::levels::{applied, parse_levels, LevelArgs};
use super::super::sky::{sky, SkyReport, SkyRequest};
use super::{
    band_names, daylight_err, with_site_offset, DaylightArgs, DaylightReadout, PatchReading,
    Reading, Readout,
};
use crate::error::Result;
use crate::formfactor::FormFactorOptions;
use crate::pipeline::{self, scene_grids};
use crate::radiosity::System;

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
    Ok(sky(&SkyRequest {
        site: site.location,
        time,
        north: site.north,
        input: args.input,
        water: args.water,
        subdivision: args.subdivision,
    })?)
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
