//! Evaluating a basis on the host through the runtime crate: exactly the arithmetic firmware
//! performs, with capacities large enough for any basis the precompute writes.

use eigenrad_runtime::{Basis, ChannelEvaluator, DaylightEvaluator, Evaluator, Figures, Sun};

use crate::daylight::sky::SkyReport;
use crate::error::{Error, Result};

/// Patch capacity of the host evaluator.
pub const MAX_PATCHES: usize = 1 << 17;
/// Mode capacity of the host evaluator: the most modes a basis the build verifies may have.
pub const MAX_MODES: usize = 2048;
/// Channel capacity of the host evaluators.
pub const MAX_CHANNELS: usize = 1024;
/// Sensor and zone capacity of the host evaluators.
pub const MAX_OUTPUTS: usize = 1024;
/// Sky-patch capacity of the host's daylight evaluator: Reinhart MF:8, the finest sky a
/// basis may have (144 · 8² + 1).
pub const MAX_SKY_PATCHES: usize = 9217;

type Host<'a, const B: usize> = Evaluator<'a, B, MAX_PATCHES, MAX_MODES, MAX_CHANNELS, MAX_OUTPUTS>;

/// Every reading of a basis for one emitter state, per band (W/m² or lux).
#[derive(Clone, Debug, Default)]
pub struct Readout {
    /// `exitance[i][b]`.
    pub exitance: Vec<Vec<f64>>,
    /// `irradiance[i][b]`; `None` for a patch that is black in some band.
    pub irradiance: Vec<Option<Vec<f64>>>,
    /// `sensors[s][b]`.
    pub sensors: Vec<Vec<f64>>,
    /// `zones[z][b]`.
    pub zones: Vec<Vec<f64>>,
    /// `grid[g][b]`: every zone's grid points, zone by zone.
    pub grid: Vec<Vec<f64>>,
    /// `figures[z][b]`: each zone's grid figures as the runtime streams them
    /// (`zone_figures`), `None` for a zone without a grid.
    pub figures: Vec<Option<Vec<Figures>>>,
}

/// Evaluates `bytes` for channel `levels` and per-patch exitance `extra` (`extra[b][i]`,
/// empty for none). `patches`: also read every patch.
pub fn evaluate(
    bytes: &[u8],
    levels: &[f32],
    extra: &[Vec<f64>],
    patches: bool,
) -> Result<Readout> {
    let basis = Basis::from_bytes(bytes)?;
    // The evaluator's buffers are sized for the largest basis (a few MB): give it a stack of
    // its own rather than rely on the caller's.
    std::thread::scope(|s| {
        std::thread::Builder::new()
            .stack_size(64 << 20)
            .spawn_scoped(s, || match basis.bands() {
                1 => run::<1>(basis, levels, extra, patches),
                _ => run::<3>(basis, levels, extra, patches),
            })
            .map_err(|e| Error::Thread(format!("cannot start: {e}")))?
            .join()
            .unwrap_or_else(|_| Err(Error::Thread("panicked".into())))
    })
}

fn run<const B: usize>(
    basis: Basis<'_>,
    levels: &[f32],
    extra: &[Vec<f64>],
    patches: bool,
) -> Result<Readout> {
    let mut eval = Box::new(Host::<B>::new(basis)?);
    eval.set_channel_levels(levels)?;
    let n = basis.patch_count();
    if !extra.is_empty() {
        for i in 0..n {
            let x: [f32; B] = std::array::from_fn(|b| {
                extra.get(b).and_then(|e| e.get(i)).copied().unwrap_or(0.0) as f32
            });
            if x.iter().any(|v| *v != 0.0) {
                eval.set_patch_exitance(i, x)?;
            }
        }
    }
    let widen = |v: [f32; B]| v.iter().map(|&x| f64::from(x)).collect::<Vec<f64>>();
    let mut out = Readout::default();
    for s in 0..basis.sensor_count() {
        out.sensors.push(widen(eval.sensor_irradiance(s)?));
    }
    for z in 0..basis.zone_count() {
        out.zones.push(widen(eval.zone_irradiance(z)?));
        let points = basis.grid_points(z)?;
        for point in 0..points {
            out.grid.push(widen(eval.grid_point_irradiance(z, point)?));
        }
        out.figures.push(
            (points > 0)
                .then(|| eval.zone_figures(z))
                .transpose()?
                .map(Vec::from),
        );
    }
    if patches {
        for i in 0..n {
            out.exitance.push(widen(eval.exitance(i)?));
            out.irradiance.push(match eval.irradiance(i) {
                Ok(e) => Some(widen(e)),
                Err(eigenrad_runtime::Error::BlackPatch { .. }) => None,
                Err(e) => return Err(e.into()),
            });
        }
    }
    Ok(out)
}

/// A sky state as the runtime's [`DaylightEvaluator`] takes it.
#[derive(Clone, Debug)]
pub struct SkyState {
    /// Every sky patch's luminance, cd/m², in the basis' sky order.
    pub sky_luminance: Vec<f32>,
    /// Global horizontal illuminance, lux.
    pub global_horizontal: f32,
    /// The sun, if it shines.
    pub sun: Option<Sun>,
}

impl SkyState {
    /// The state of the sky `report` describes, as `eigenrad eval --time` hands it to the
    /// runtime: every patch's luminance and the global horizontal illuminance in `f32`, and
    /// the sun when its direct normal illuminance is above 0 (none below the horizon), its
    /// direction from the report's altitude and azimuth through the runtime's `f32`
    /// [`eigenrad_runtime::sky::direction`], as a controller builds it. Whatever else evaluates
    /// a report's sky through the runtime takes this, so that it reads what `eval` reads.
    pub fn of(report: &SkyReport) -> SkyState {
        let sun = (report.direct_normal_lux > 0.0).then(|| Sun {
            direction: eigenrad_runtime::sky::direction(
                report.sun.altitude.to_radians() as f32,
                report.sun.azimuth.to_radians() as f32,
            ),
            direct_normal: report.direct_normal_lux as f32,
        });
        SkyState {
            sky_luminance: report
                .patches
                .iter()
                .map(|p| p.luminance_cd_m2 as f32)
                .collect(),
            global_horizontal: report.global_horizontal_lux as f32,
            sun,
        }
    }
}

/// The daylight of a basis for one sky state, through the runtime, and the figures of the
/// grids under daylight and the channels at `levels` together.
#[derive(Clone, Debug, Default)]
pub struct DaylightReadout {
    /// `sensors[s]`, lux.
    pub sensors: Vec<f64>,
    /// `zones[z]`, lux.
    pub zones: Vec<f64>,
    /// `grid[g]`, lux: every zone's grid points, zone by zone.
    pub grid: Vec<f64>,
    /// Each zone's grid figures under daylight alone (`None` without a grid).
    pub figures: Vec<Option<Figures>>,
    /// Each zone's grid figures under daylight and the channels together.
    pub figures_with_channels: Vec<Option<Figures>>,
    /// Every patch's daylight exitance, lux (when asked): its first reflection from the
    /// basis' tables, the rest through the modes.
    pub exitance: Vec<f64>,
}

impl DaylightReadout {
    /// Every output's daylight in the model's order: sensors, zones, then grid points (lux).
    pub fn outputs(&self) -> Vec<f64> {
        let all = self.sensors.iter().chain(&self.zones).chain(&self.grid);
        all.copied().collect()
    }
}

/// Patch-exitance state of the host's daylight evaluator: the most modes and the first
/// reflection's largest rank (a sky's patches and the exterior).
const MAX_DAYLIGHT_STATE: usize = MAX_MODES + MAX_SKY_PATCHES + 1;

type HostDaylight<'a> = DaylightEvaluator<'a, MAX_SKY_PATCHES, MAX_OUTPUTS, MAX_DAYLIGHT_STATE>;

/// Evaluates the daylight of `bytes` under `sky`, with the channels at `levels` for the
/// figures of the two together; `patches`: also every patch's exitance.
pub fn evaluate_daylight(
    bytes: &[u8],
    sky: &SkyState,
    levels: &[f32],
    patches: bool,
) -> Result<DaylightReadout> {
    let basis = Basis::from_bytes(bytes)?;
    std::thread::scope(|s| {
        std::thread::Builder::new()
            .stack_size(64 << 20)
            .spawn_scoped(s, || run_daylight(basis, sky, levels, patches))
            .map_err(|e| Error::Thread(format!("cannot start: {e}")))?
            .join()
            .unwrap_or_else(|_| Err(Error::Thread("panicked".into())))
    })
}

fn run_daylight(
    basis: Basis<'_>,
    sky: &SkyState,
    levels: &[f32],
    patches: bool,
) -> Result<DaylightReadout> {
    let mut day = Box::new(HostDaylight::new(basis)?);
    day.set_sky(&sky.sky_luminance, sky.global_horizontal, sky.sun)?;
    let mut electric = Box::new(ChannelEvaluator::<1, MAX_CHANNELS>::new(basis)?);
    electric.set_channel_levels(levels)?;
    let mut out = DaylightReadout::default();
    for s in 0..basis.sensor_count() {
        out.sensors.push(f64::from(day.sensor_illuminance(s)?));
    }
    for z in 0..basis.zone_count() {
        out.zones.push(f64::from(day.zone_illuminance(z)?));
        let points = basis.grid_points(z)?;
        for point in 0..points {
            out.grid
                .push(f64::from(day.grid_point_illuminance(z, point)?));
        }
        out.figures
            .push((points > 0).then(|| day.zone_figures(z)).transpose()?);
        out.figures_with_channels.push(
            (points > 0)
                .then(|| day.zone_figures_with(z, &electric))
                .transpose()?,
        );
    }
    if patches {
        for i in 0..basis.patch_count() {
            out.exitance.push(f64::from(day.exitance(i)?));
        }
    }
    Ok(out)
}

/// Every output's reading (sensors, zones, then grid points; lux per lux of direct normal
/// illuminance) of the sun alone in each of the site-frame directions `suns`, as the
/// runtime's [`DaylightEvaluator`] reads `bytes` (no sky, no exterior): what a controller
/// reads between the sun grid's nodes.
pub fn sun_readings(bytes: &[u8], suns: &[[f32; 3]]) -> Result<Vec<Vec<f64>>> {
    let basis = Basis::from_bytes(bytes)?;
    std::thread::scope(|s| {
        std::thread::Builder::new()
            .stack_size(64 << 20)
            .spawn_scoped(s, || {
                let mut day = Box::new(HostDaylight::new(basis)?);
                let dark = vec![0.0; basis.sky_patches().map_or(0, |p| p.count())];
                let mut all = Vec::with_capacity(suns.len());
                for &direction in suns {
                    let sun = Sun {
                        direction,
                        direct_normal: 1.0,
                    };
                    day.set_sky(&dark, 0.0, Some(sun))?;
                    let mut readings = Vec::new();
                    for s in 0..basis.sensor_count() {
                        readings.push(f64::from(day.sensor_illuminance(s)?));
                    }
                    for z in 0..basis.zone_count() {
                        readings.push(f64::from(day.zone_illuminance(z)?));
                    }
                    for z in 0..basis.zone_count() {
                        for point in 0..basis.grid_points(z)? {
                            readings.push(f64::from(day.grid_point_illuminance(z, point)?));
                        }
                    }
                    all.push(readings);
                }
                Ok(all)
            })
            .map_err(|e| Error::Thread(format!("cannot start: {e}")))?
            .join()
            .unwrap_or_else(|_| Err(Error::Thread("panicked".into())))
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::daylight::sky::{sky, SkyInput, SkyRequest};
    use crate::daylight::sun::Site;

    fn report(direct_normal: f64) -> SkyReport {
        sky(&SkyRequest {
            site: Site {
                latitude: 48.2,
                longitude: 16.4,
                elevation: 0.0,
            },
            time: "2026-03-20T10:00+01:00".to_owned(),
            north: 30.0,
            input: SkyInput::Cie {
                sky_type: 12,
                diffuse_horizontal: 12_000.0,
                direct_normal,
            },
            water: 2.0,
            subdivision: 1,
        })
        .unwrap()
    }

    /// The state of a report: its patches' luminances and its global horizontal illuminance
    /// in `f32`, the sun in the site's frame (not the room's: `north` does not turn it) at
    /// its direct normal illuminance, and no sun without direct light.
    #[test]
    fn sky_state_of_a_report() {
        let r = report(60_000.0);
        let state = SkyState::of(&r);
        assert_eq!(state.sky_luminance.len(), r.patches.len());
        for (l, p) in state.sky_luminance.iter().zip(&r.patches) {
            assert_eq!(*l, p.luminance_cd_m2 as f32);
        }
        assert_eq!(state.global_horizontal, r.global_horizontal_lux as f32);
        let sun = state.sun.expect("a sun");
        assert_eq!(sun.direct_normal, 60_000.0);
        let site = crate::daylight::room_direction(r.sun.altitude, r.sun.azimuth, 0.0);
        for (a, b) in sun.direction.iter().zip(site) {
            assert!(
                (f64::from(*a) - b).abs() < 1e-6,
                "{:?} against {site:?}",
                sun.direction
            );
        }
        assert!(SkyState::of(&report(0.0)).sun.is_none());
    }
}
