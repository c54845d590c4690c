//! Where the sun's error between the grid's nodes comes from (docs/accuracy.md, "Daylight in
//! the basis"). Each exact reading of the sun splits into three parts:
//!
//! - `D`, its direct sun (through a window onto the receiver);
//! - `F = Σ_j R_oj M0_j`, the first reflection of the sun patch: the light the directly
//!   sunlit patches send to the receiver (`M0` their initial exitance, `R_o` the receiver's
//!   row, [`crate::radiosity::System::outputs`]);
//! - `Q`, the rest: what the room reflects after that.
//!
//! Read between nodes, each part the controller interpolates contributes its own error, and
//! the signed contributions add up to the reading's error. This module measures each part's
//! share under format 7's rule (sensors and grid points interpolate `F + Q` and add their
//! direct sun at the sun's direction, zones interpolate all three), and what the error would
//! be if `D` and `F` were both taken exactly at the sun's own direction and only `Q`
//! interpolated. Format 8's controller (`eigenrad build --sun-first`) computes `F` from a
//! few sample points a patch; what it reads is measured apart
//! ([`super::daylight::SunInterpolation`]).

use std::collections::HashMap;

use serde::Serialize;

use super::daylight::{sun_peaks, Cell, ErrorSpread};
use crate::basis::BasisDaylight;
use crate::formfactor::Occluders;
use crate::radiosity::model::Model;
use crate::radiosity::LightResponse;
use crate::scene::Scene;
use crate::sources::daylight::nodes::room_sun;
use crate::sources::daylight::{sun_light, DaylightOptions};

/// The parts of the error between nodes, per kind of reading (zones, sensors, grid points,
/// in that order; a kind the scene lacks has empty spreads and no worst case).
#[derive(Clone, Debug, Default, Serialize)]
pub struct SunParts {
    /// One entry per kind of reading.
    pub kinds: Vec<KindParts>,
    /// Patches that any stored sun node lights directly (a non-zero initial exitance): those
    /// whose first reflection a controller would compute at the sun's direction.
    pub sunlit_patches: usize,
}

/// The parts of the error between nodes of one kind of reading, each relative to the
/// reading's largest sun response over the nodes (as
/// [`super::daylight::SunInterpolation`]).
#[derive(Clone, Debug, Default, Serialize)]
pub struct KindParts {
    /// `zones`, `sensors` or `grid points`.
    pub kind: &'static str,
    /// The direct sun's contribution under the present rule (its interpolation at the
    /// zones; at the sensors and grid points the controller's `f32` direct sun against the
    /// host's).
    pub direct: ErrorSpread,
    /// The first reflection's contribution: its interpolation.
    pub first: ErrorSpread,
    /// The rest's contribution, its interpolation: the whole error if the direct sun and
    /// the first reflection were exact at the sun's direction and only the rest
    /// interpolated.
    pub rest: ErrorSpread,
    /// The whole error if the direct sun, the first reflection and its power `P` were exact
    /// at the sun's direction and the rest interpolated per unit of `P`: `P(s)` times the
    /// corners' `Q / P` weighed bilinearly over the corners the sun lights.
    pub rest_per_power: ErrorSpread,
    /// The reading and cell of the largest error under the present rule.
    pub worst: Option<WorstCell>,
    /// The reading and cell of the largest error under the rule that interpolates the rest
    /// per unit of the first reflection's power ([`Self::rest_per_power`]).
    pub worst_per_power: Option<WorstCell>,
}

/// The reading and cell with the largest error between nodes of one kind, and its parts
/// (signed: interpolated less exact; under the present rule they add up to `error`, under
/// the rule per unit of power `error` is `rest_per_power`).
#[derive(Clone, Debug, Default, Serialize)]
pub struct WorstCell {
    /// The sensor's or zone's name, or the grid point's number among all grid points.
    pub reading: String,
    /// The sun at the cell's centre: declination and hour angle, degrees.
    pub declination_hour: [f32; 2],
    /// Its largest sun response over the nodes, lux per lux of direct normal illuminance.
    pub peak: f64,
    /// The signed error under the present rule.
    pub error: f64,
    /// The direct sun's share of it.
    pub direct: f64,
    /// The first reflection's share of it.
    pub first: f64,
    /// The rest's share of it, its whole error if only the rest were interpolated.
    pub rest: f64,
    /// Its whole error if the rest were interpolated per unit of the first reflection's
    /// power.
    pub rest_per_power: f64,
    /// The first reflection's power at the cell's centre over its bilinear mean from the
    /// corners: how much more (or less) sunlight enters the room than the corners say.
    pub power_ratio: f64,
}

/// The three parts of every output's reading at one sun direction, lux per lux, and the
/// power of the first reflection, `P = Σ_i A_i M0_i` (lm per lux).
struct Parts {
    direct: Vec<f64>,
    first: Vec<f64>,
    rest: Vec<f64>,
    power: f64,
}

impl Parts {
    /// Splits `readings` (exact, direct included) given its `direct` part and the patches'
    /// initial exitance `m0`.
    fn of(model: &Model, readings: &[f64], direct: &[f64], m0: &[f64]) -> Parts {
        let first = model.system.outputs(m0);
        let rest = readings
            .iter()
            .enumerate()
            .map(|(o, r)| r - direct.get(o).copied().unwrap_or(0.0) - first[o])
            .collect();
        let mut direct = direct.to_vec();
        direct.resize(readings.len(), 0.0);
        let power = model.area().iter().zip(m0).map(|(a, m)| a * m).sum();
        Parts {
            direct,
            first,
            rest,
            power,
        }
    }
}

/// Measures [`SunParts`] over `cells` (with their exact responses), `controller_direct`
/// being the controller's direct sun at output `o` for a sun in a site-frame direction (0
/// at the zones and without the direct sun's geometry).
pub(crate) fn measure(
    scene: &Scene,
    occluders: &Occluders,
    model: &Model,
    daylight: &BasisDaylight,
    (cells, exact): (&[Cell], &[LightResponse]),
    controller_direct: &dyn Fn(usize, [f32; 3]) -> f64,
) -> SunParts {
    let Some(site) = &scene.site else {
        return SunParts::default();
    };
    let nodes = &daylight.nodes;
    let grid = nodes.sun_grid;
    let first_sun = nodes.patches.count() + 1;
    let peak = sun_peaks(daylight);
    // Each stored corner node's parts: its exact direct sun from the host, its first
    // reflection from its stored initial exitance.
    let mut node_parts: HashMap<usize, Parts> = HashMap::new();
    for cell in cells {
        for &c in &cell.corners {
            if node_parts.contains_key(&c) {
                continue;
            }
            let Ok(i) = nodes.sun_nodes.binary_search(&(c as u32)) else {
                continue;
            };
            let Some(sun) = grid.direction(c).and_then(|d| room_sun(site, d)) else {
                continue;
            };
            let light = sun_light(scene, occluders, sun, &DaylightOptions::default());
            let direct = light.output_irradiance.first().map_or(&[][..], |v| &v[..]);
            let r = &daylight.responses[first_sun + i];
            node_parts.insert(
                c,
                Parts::of(model, &r.readings, direct, &daylight.initial[first_sun + i]),
            );
        }
    }
    let zones_start = scene.sensors.len();
    let grid_start = crate::formfactor::outputs::grid_offset(scene);
    let kind_of = |o: usize| match o {
        o if o >= grid_start => 2,
        o if o >= zones_start => 0,
        _ => 1,
    };
    // Per kind: each part's absolute contributions and the worst case.
    let mut shares: [[Vec<f64>; 4]; 3] = Default::default();
    let mut worst: [Option<WorstCell>; 3] = Default::default();
    let mut worst_per_power: [Option<WorstCell>; 3] = Default::default();
    for (cell, exact) in cells.iter().zip(exact) {
        let direct = cell
            .light
            .output_irradiance
            .first()
            .map_or(&[][..], |v| &v[..]);
        let m0 = model
            .system
            .initial_exitances(0, std::slice::from_ref(&cell.light));
        let Some(m0) = m0.first() else { continue };
        let centre = Parts::of(model, &exact.readings, direct, m0);
        let corners: Vec<(&Parts, [f32; 3])> = cell
            .corners
            .iter()
            .filter_map(|c| Some((node_parts.get(c)?, grid.direction(*c)?)))
            .collect();
        let mean = |part: &dyn Fn(&Parts) -> f64| -> f64 {
            corners.iter().map(|(p, _)| 0.25 * part(p)).sum()
        };
        // A part per unit of the first reflection's power, weighed over the lit corners.
        let lit: f64 = corners
            .iter()
            .filter(|(p, _)| p.power > 0.0)
            .map(|_| 0.25)
            .sum();
        let ratio = |part: &dyn Fn(&Parts) -> f64| -> f64 {
            let sum: f64 = corners
                .iter()
                .filter(|(p, _)| p.power > 0.0)
                .map(|(p, _)| 0.25 * part(p) / p.power)
                .sum();
            if lit > 0.0 {
                sum / lit
            } else {
                0.0
            }
        };
        for o in 0..exact.readings.len() {
            let scale = peak[o].max(f64::MIN_POSITIVE);
            let k = kind_of(o);
            let direct = if k == 0 {
                mean(&|p| p.direct[o]) - centre.direct[o]
            } else {
                let controller: f64 = corners
                    .iter()
                    .map(|(_, d)| 0.25 * controller_direct(o, *d))
                    .sum();
                (controller_direct(o, cell.centre) - centre.direct[o])
                    - (controller - mean(&|p| p.direct[o]))
            };
            let first = mean(&|p| p.first[o]) - centre.first[o];
            let rest = mean(&|p| p.rest[o]) - centre.rest[o];
            let error = (direct + first + rest) / scale;
            let per_power = centre.power * ratio(&|p| p.rest[o]) - centre.rest[o];
            let [d, f, q, n] = [direct, first, rest, per_power].map(|x| x / scale);
            for (share, x) in shares[k].iter_mut().zip([d, f, q, n]) {
                share.push(x.abs());
            }
            let larger = |w: &Option<WorstCell>, x: f64| {
                w.as_ref()
                    .is_none_or(|w: &WorstCell| x.abs() > w.error.abs())
            };
            if larger(&worst[k], error) || larger(&worst_per_power[k], n) {
                let (declination, hour) = grid.angles(cell.corners[0]).unwrap_or_default();
                let case = WorstCell {
                    reading: match k {
                        0 => scene.zones[o - zones_start].name.clone(),
                        1 => scene.sensors[o].name.clone(),
                        _ => format!("grid point {}", o - grid_start),
                    },
                    declination_hour: [
                        declination + 0.5 * grid.declination_step,
                        hour + 0.5 * grid.hour_step,
                    ],
                    peak: peak[o],
                    error,
                    direct: d,
                    first: f,
                    rest: q,
                    rest_per_power: n,
                    power_ratio: centre.power / mean(&|p| p.power).max(f64::MIN_POSITIVE),
                };
                if larger(&worst_per_power[k], n) {
                    worst_per_power[k] = Some(WorstCell {
                        error: n,
                        ..case.clone()
                    });
                }
                if larger(&worst[k], error) {
                    worst[k] = Some(case);
                }
            }
        }
    }
    let names = ["zones", "sensors", "grid points"];
    let sunlit_patches = (0..model.patch_count())
        .filter(|&i| daylight.initial[first_sun..].iter().any(|m0| m0[i] != 0.0))
        .count();
    SunParts {
        sunlit_patches,
        kinds: shares
            .into_iter()
            .zip(worst)
            .zip(worst_per_power)
            .zip(names)
            .map(|(((s, worst), worst_per_power), kind)| {
                let [direct, first, rest, rest_per_power] = s.map(ErrorSpread::of);
                KindParts {
                    kind,
                    direct,
                    first,
                    rest,
                    rest_per_power,
                    worst,
                    worst_per_power,
                }
            })
            .collect(),
    }
}
