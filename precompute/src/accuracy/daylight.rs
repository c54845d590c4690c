//! How close a basis' daylight is to the exact solve: the sun read between the nodes of its
//! grid, and a sky state read through the runtime (docs/math.md, "Daylight in the basis").

use eigenrad_runtime::sky::cie::CieSky;
use eigenrad_runtime::sky::direct::DirectSun;
use eigenrad_runtime::sky::sun_grid::direction_of;
use eigenrad_runtime::sky::RelativeSky;
use eigenrad_runtime::Sun;
use serde::Serialize;

use super::metric::{patch_error, worst_reading};
use super::runtime_eval::{evaluate_daylight, sun_readings, SkyState};
use crate::basis::BasisDaylight;
use crate::error::Result;
use crate::formfactor::Occluders;
use crate::radiosity::model::Model;
use crate::scene::Scene;
use crate::sources::daylight::nodes::room_sun;
use crate::sources::daylight::{sun_light, DaylightOptions};

/// What reading the sun between the grid's nodes costs: at the centre of every cell of the
/// grid where the sun is up and lights the room (the point furthest from its four nodes),
/// the bilinear mean of the four nodes' exact readings against the exact reading of the sun
/// there. Each difference is relative to the reading's largest response to the sun over
/// the grid's nodes (lux per lux of direct normal illuminance), so that a reading at the
/// edge of a sun patch, where the exact value may be 0, is measured on the scale of its
/// sunlight.
///
/// The cells are evenly spread in declination and hour angle, so over a year about evenly
/// in time; a cell the sun crosses while an edge (the window's, an obstruction's, the sun
/// patch's on a point) moves across a reading is wrong by up to the whole sunlight there at
/// any grid spacing: the worst case shrinks in how often it happens, not in size, which the
/// 95th percentile shows.
#[derive(Clone, Debug, Default, Serialize)]
pub struct SunInterpolation {
    /// Cells measured.
    pub cells: usize,
    /// The zones (area averages, the work plane's mean among them).
    pub zones: ErrorSpread,
    /// The sensors.
    pub sensors: ErrorSpread,
    /// The calculation grids' points.
    pub grid_points: ErrorSpread,
    /// The controller's direct sun at the sensors and grid points
    /// (`eigenrad_runtime::sky::direct`) against the host's exact direct sun at the same
    /// cell centres, relative to the same largest responses: the geometry, its culling and
    /// `f32` alone, without the interpolation of the reflected part. Empty without the
    /// direct sun's geometry.
    pub direct: ErrorSpread,
    /// Where the error between nodes comes from, and what it would be with the sun patch's
    /// first reflection computed at the sun's own direction.
    pub parts: super::sun_parts::SunParts,
}

/// How a set of relative differences spreads: its mean, its 95th percentile and its
/// largest.
#[derive(Clone, Debug, Default, Serialize)]
pub struct ErrorSpread {
    /// Differences measured (cells times readings of the kind); 0 without such readings.
    pub count: usize,
    /// Mean.
    pub mean: f64,
    /// 95th percentile (nearest rank).
    pub p95: f64,
    /// Largest.
    pub max: f64,
}

impl ErrorSpread {
    /// The spread of `errors`.
    pub(crate) fn of(mut errors: Vec<f64>) -> ErrorSpread {
        if errors.is_empty() {
            return ErrorSpread::default();
        }
        errors.sort_by(f64::total_cmp);
        let rank = ((0.95 * errors.len() as f64).ceil() as usize).clamp(1, errors.len());
        ErrorSpread {
            count: errors.len(),
            mean: errors.iter().sum::<f64>() / errors.len() as f64,
            p95: errors[rank - 1],
            max: errors[errors.len() - 1],
        }
    }
}

/// Measures [`SunInterpolation`] for `daylight`'s grid: one exact sun per cell centre, read
/// as the controller reads the basis `bytes`, by the runtime's own evaluator
/// ([`sun_readings`]): the four nodes' stored readings interpolated, with the direct sun
/// (sensors and grid points) and the sun's first reflection (every reading, per unit of its
/// power) computed at the sun's direction when the basis stores their tables.
pub fn sun_interpolation(
    scene: &Scene,
    occluders: &Occluders,
    model: &Model,
    daylight: &BasisDaylight,
    bytes: &[u8],
) -> Result<SunInterpolation> {
    let basis = eigenrad_runtime::Basis::from_bytes(bytes)?;
    let direct = DirectSun::new(&basis)?;
    let Some(site) = &scene.site else {
        return Ok(SunInterpolation::default());
    };
    let peak = sun_peaks(daylight);
    let cells = lit_cells(scene, occluders, daylight, site);
    let lights: Vec<_> = cells.iter().map(|c| c.light.clone()).collect();
    let exact = model.system.light_responses(0, &lights)?;
    let zones_start = scene.sensors.len();
    let grid_start = crate::formfactor::outputs::grid_offset(scene);
    let (mut sensors, mut zones, mut points) = (Vec::new(), Vec::new(), Vec::new());
    // The controller's direct sun at output `o` (sensors and grid points) for the sun in
    // the site-frame direction `site`, lux per lux.
    let direct_at = |o: usize, site: [f32; 3]| -> f64 {
        let Some(direct) = &direct else { return 0.0 };
        let sun = direct.room_direction(site);
        f64::from(match o {
            o if o >= grid_start => direct.at_grid_point(o - grid_start, sun),
            o if o >= zones_start => 0.0,
            o => direct.at_sensor(o, sun),
        })
    };
    let mut direct_errors = Vec::new();
    // What the controller reads at each centre: the runtime itself on the basis.
    let centres: Vec<[f32; 3]> = cells.iter().map(|c| c.centre).collect();
    let devices = sun_readings(bytes, &centres)?;
    for ((cell, exact), device) in cells.iter().zip(&exact).zip(&devices) {
        let (centre, light) = (cell.centre, &cell.light);
        if direct.is_some() {
            let host = light.output_irradiance.first().map_or(&[][..], |v| &v[..]);
            for (o, h) in host.iter().enumerate() {
                if o < zones_start || o >= grid_start {
                    let error = (direct_at(o, centre) - h).abs() / peak[o].max(f64::MIN_POSITIVE);
                    direct_errors.push(error);
                }
            }
        }
        for (o, e) in exact.readings.iter().enumerate() {
            let read = device.get(o).copied().unwrap_or(0.0);
            let error = (read - e).abs() / peak[o].max(f64::MIN_POSITIVE);
            match o {
                o if o >= grid_start => points.push(error),
                o if o >= zones_start => zones.push(error),
                _ => sensors.push(error),
            }
        }
    }
    Ok(SunInterpolation {
        cells: cells.len(),
        zones: ErrorSpread::of(zones),
        sensors: ErrorSpread::of(sensors),
        grid_points: ErrorSpread::of(points),
        direct: ErrorSpread::of(direct_errors),
        parts: super::sun_parts::measure(
            scene,
            occluders,
            model,
            daylight,
            (&cells, &exact),
            &direct_at,
        ),
    })
}

/// A cell of the sun grid measured between its nodes: its four corners (node indices), the
/// sun's direction at its centre (site frame) and the exact light of that sun.
pub(crate) struct Cell {
    pub(crate) corners: [usize; 4],
    pub(crate) centre: [f32; 3],
    pub(crate) light: crate::sources::ChannelLight,
}

/// The cells of `daylight`'s grid whose centre sees the sun above the horizon and either
/// lights the room there or has a stored node among its corners.
pub(crate) fn lit_cells(
    scene: &Scene,
    occluders: &Occluders,
    daylight: &BasisDaylight,
    site: &crate::scene::Site,
) -> Vec<Cell> {
    let nodes = &daylight.nodes;
    let grid = nodes.sun_grid;
    let stored = |node: usize| nodes.sun_nodes.binary_search(&(node as u32)).is_ok();
    let mut cells = Vec::new();
    for row in 0..grid.rows.saturating_sub(1) {
        for column in 0..grid.columns.saturating_sub(1) {
            let corners = [
                row * grid.columns + column,
                row * grid.columns + column + 1,
                (row + 1) * grid.columns + column,
                (row + 1) * grid.columns + column + 1,
            ];
            let Some((declination, hour)) = grid.angles(corners[0]) else {
                continue;
            };
            let centre = direction_of(
                grid.latitude,
                declination + 0.5 * grid.declination_step,
                hour + 0.5 * grid.hour_step,
            );
            let Some(sun) = room_sun(site, centre) else {
                continue;
            };
            let light = sun_light(scene, occluders, sun, &DaylightOptions::default());
            let lit = light
                .output_irradiance
                .iter()
                .flatten()
                .chain(light.patch_irradiance.iter().flatten())
                .any(|&x| x != 0.0);
            if lit || corners.iter().any(|&c| stored(c)) {
                cells.push(Cell {
                    corners,
                    centre,
                    light,
                });
            }
        }
    }
    cells
}

/// Each output's largest response to the sun over the stored nodes (lux per lux of direct
/// normal illuminance): the scale of the between-nodes errors.
pub(crate) fn sun_peaks(daylight: &BasisDaylight) -> Vec<f64> {
    let first_sun = daylight.nodes.patches.count() + 1;
    let outputs = daylight.responses.first().map_or(0, |r| r.readings.len());
    let mut peak = vec![0.0f64; outputs];
    for r in &daylight.responses[first_sun..] {
        for (p, x) in peak.iter_mut().zip(&r.readings) {
            *p = p.max(x.abs());
        }
    }
    peak
}

/// A sky state the runtime reads against the exact solve: the CIE overcast sky at a zenith
/// luminance of 3000 cd/m² and `E_gh` of 10 000 lux, with (`sun`) or without the sun at the
/// stored node in the middle of the list at 50 000 lux of direct normal illuminance.
/// Returns the state and each node's weight in it.
fn sample_sky(daylight: &BasisDaylight, sun: bool) -> Option<(SkyState, Vec<f64>)> {
    let nodes = &daylight.nodes;
    let sun = nodes
        .sun_nodes
        .get(nodes.sun_nodes.len() / 2)
        .filter(|_| sun)
        .and_then(|&n| nodes.sun_grid.direction(n as usize).map(|d| (n, d)));
    let sky = CieSky::traditional_overcast(sun.map_or([0.0, 0.0, 1.0], |(_, d)| d)).ok()?;
    let zenith = 3000.0 / sky.relative_luminance([0.0, 0.0, 1.0]);
    let mut sky_luminance = vec![0.0f32; nodes.patches.count()];
    nodes
        .patches
        .luminances(&sky, zenith, &mut sky_luminance)
        .ok()?;
    let global_horizontal = 10_000.0f32;
    let mut weights: Vec<f64> = sky_luminance.iter().map(|&l| f64::from(l)).collect();
    weights.push(f64::from(global_horizontal) / std::f64::consts::PI);
    weights.resize(nodes.len(), 0.0);
    let direct_normal = 50_000.0f32;
    if let Some((node, _)) = sun {
        let at = nodes.sun_nodes.binary_search(&node).unwrap_or(0);
        weights[nodes.patches.count() + 1 + at] = f64::from(direct_normal);
    }
    Some((
        SkyState {
            sky_luminance,
            global_horizontal,
            sun: sun.map(|(_, direction)| Sun {
                direction,
                direct_normal,
            }),
        },
        weights,
    ))
}

/// Two sky states read through the runtime against the exact solve.
#[derive(Clone, Debug, Default, Serialize)]
pub struct DaylightCheck {
    /// Largest relative error of a sensor, zone or grid point under either state (exact per
    /// node: `f32` and storage rounding).
    pub readings: f64,
    /// Patch exitance under the overcast sky (its first reflection from the basis' tables
    /// when it stores them, the rest through the modes): [`patch_error`] against the
    /// exact exitance.
    pub patch_error_overcast: f64,
    /// The same with the sun at a node besides: the sun patch's sharp edges are what `p`
    /// modes carry least well.
    pub patch_error_sun: f64,
}

/// Reads the sample skies through the runtime from `bytes` and compares with the exact
/// response, summed over the nodes in `f64`.
pub fn through_runtime(
    bytes: &[u8],
    model: &Model,
    daylight: &BasisDaylight,
) -> Result<DaylightCheck> {
    let mut check = DaylightCheck::default();
    for sun in [false, true] {
        let Some((state, weights)) = sample_sky(daylight, sun) else {
            continue;
        };
        let got = evaluate_daylight(bytes, &state, &vec![0.0; model.channel_count()], true)?;
        let n = model.patch_count();
        let rows = daylight.responses.first().map_or(0, |r| r.readings.len());
        let mut exitance = vec![0.0; n];
        let mut readings = vec![0.0; rows];
        for (w, r) in weights.iter().zip(&daylight.responses) {
            for (x, y) in exitance.iter_mut().zip(&r.exitance) {
                *x += w * y;
            }
            for (x, y) in readings.iter_mut().zip(&r.readings) {
                *x += w * y;
            }
        }
        let read = got.outputs();
        check.readings = check.readings.max(worst_reading(&read, &readings).error);
        let patches = patch_error(model.area(), &got.exitance, &exitance);
        if sun {
            check.patch_error_sun = patches;
        } else {
            check.patch_error_overcast = patches;
        }
    }
    Ok(check)
}
