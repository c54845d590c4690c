//! What `eigenrad build` reports, and the checks of the written basis through the runtime
//! that fill it: every case against the exact solve, the grids' figures, the daylight.

use serde::Serialize;

use super::grids::{scene_grids, GridReadout, PieceLayout};
use crate::accuracy::metric::Worst;
use crate::accuracy::{self, runtime_eval, Case, ExactCases};
use crate::basis::BasisDaylight;
use crate::error::Result;
use crate::formfactor::{FormFactorHealth, Occluders};
use crate::radiosity::Model;
use crate::scene::Scene;
use crate::sources::luminaires::LuminaireFlux;

/// Accuracy of the written basis for one test case, evaluated through the runtime.
#[derive(Clone, Debug, Serialize)]
pub struct CaseAccuracy {
    /// Case name.
    pub case: String,
    /// [`accuracy::metric::patch_error`], worst band.
    pub patch_error: f64,
    /// The patch whose exitance is furthest from its own exact value, worst band.
    pub worst_patch: Worst,
    /// The surface it belongs to.
    pub worst_patch_surface: String,
    /// The sensor or zone (sensors first, then zones) whose reading is furthest from its own
    /// exact value, worst band.
    pub worst_reading: Worst,
    /// Its name.
    pub worst_reading_name: String,
}

/// How one band's modes were found.
#[derive(Clone, Debug, Serialize)]
pub struct EigensolveReport {
    /// "dense" (faer's full eigendecomposition) or "block Lanczos".
    pub method: &'static str,
    /// Largest explicit residual `‖H u − μ u‖₂` of a kept mode (dimensionless: `‖H‖ < 1`).
    pub max_residual: f64,
    /// Block Lanczos only: thick restarts.
    pub restarts: Option<usize>,
    /// Block Lanczos only: vectors the operator was applied to, what the solve's time is
    /// made of.
    pub operator_columns: Option<usize>,
}

impl EigensolveReport {
    /// The report of `modes`.
    pub fn of(modes: &crate::radiosity::eigen::Modes) -> EigensolveReport {
        use crate::radiosity::eigen::Method;
        EigensolveReport {
            method: match modes.method {
                Method::Dense => "dense",
                Method::Lanczos => "block Lanczos",
            },
            max_residual: modes.max_residual,
            restarts: modes.work.map(|w| w.restarts),
            operator_columns: modes.work.map(|w| w.columns),
        }
    }
}

/// Time spent in one stage.
#[derive(Clone, Debug, Serialize)]
pub struct Stage {
    /// Stage name.
    pub stage: &'static str,
    /// Wall-clock seconds.
    pub seconds: f64,
}

/// What `eigenrad build` reports.
#[derive(Clone, Debug, Serialize)]
pub struct BuildReport {
    /// Scene name.
    pub scene: String,
    /// Number of patches.
    pub patches: usize,
    /// Median and worst aspect ratio of the patches.
    pub aspect: crate::geometry::AspectSummary,
    /// Number of bands.
    pub bands: usize,
    /// Unit of exitance and irradiance.
    pub unit: &'static str,
    /// Formulation.
    pub formulation: &'static str,
    /// Storage precision.
    pub precision: &'static str,
    /// Modes kept per band.
    pub modes: usize,
    /// How each band's modes were found.
    pub eigensolve: Vec<EigensolveReport>,
    /// Basis size in bytes.
    pub bytes: usize,
    /// Form-factor health.
    pub form_factors: FormFactorHealth,
    /// How the form-factor operator was stored while the room was solved.
    pub operator: OperatorReport,
    /// Each luminaire's flux: stated, integrated, reaching the surfaces, escaping.
    pub luminaires: Vec<LuminaireFlux>,
    /// Accuracy per case, through the runtime.
    pub accuracy: Vec<CaseAccuracy>,
    /// Every zone's calculation grid with every channel at level 1, through the runtime.
    pub grids: Vec<GridReadout>,
    /// Largest relative difference of any grid figure (`E_avg`, `E_min`, `E_max`, `U_o`)
    /// through the runtime from the same figure of the exact solve, every channel at level 1.
    pub grid_figure_error: f64,
    /// The daylight the basis carries (a scene with a site and glazed windows).
    pub daylight: Option<DaylightReport>,
    /// Channel names, in the order of each sensor ratio's `per_channel`.
    pub channels: Vec<String>,
    /// Every sensor's ratio to every zone, per channel and per daylight, through the
    /// runtime: the figures a sensor is calibrated with.
    pub sensor_ratios: Vec<crate::accuracy::calibration::SensorRatio>,
    /// Time per stage.
    pub timings: Vec<Stage>,
    /// What the build expected of itself before its form factors.
    pub plan: super::Plan,
}

/// The form-factor operator a build solved the room with (`--operator`).
#[derive(Clone, Debug, Serialize)]
pub struct OperatorReport {
    /// `dense f64`, `dense f32` or `hierarchical f32`.
    pub storage: &'static str,
    /// Bytes it held.
    pub bytes: usize,
    /// Why it was chosen: the `--operator` given, or the size rule `auto` applied.
    pub reason: String,
    /// What the compression made of the form factors (a hierarchical operator).
    pub compression: Option<crate::formfactor::hierarchical::Compression>,
}

/// What the direct sun's tables of a basis hold.
#[derive(Clone, Debug, Serialize)]
pub struct DirectSunReport {
    /// Clear windows' faces.
    pub window_faces: usize,
    /// Room faces that shade some sensor or grid point from the sun through a window.
    pub room_occluders: usize,
    /// Obstruction faces that do.
    pub exterior_occluders: usize,
    /// Bytes of the six tables.
    pub bytes: usize,
    /// Candidate patches of the sun's first reflection on the controller (`--sun-first`;
    /// 0 without).
    pub candidates: usize,
    /// Polygons the zones' direct sun is computed on.
    pub zone_polygons: usize,
    /// Bytes of the sun's first reflection's tables, and of its responses among them.
    pub candidate_bytes: [usize; 2],
}

/// What the daylight's first reflection takes (docs/format.md, "First reflection").
#[derive(Clone, Debug, Serialize)]
pub struct FirstReflectionReport {
    /// `r`: the rank of the sky's first reflection.
    pub rank: usize,
    /// The tolerance it was chosen by (`--sky-rank-tolerance`).
    pub tolerance: f64,
    /// Its relative error in the area-weighted Frobenius norm (at most the tolerance).
    pub sky_error: f64,
    /// Patches the sun nodes' lists hold, over all nodes.
    pub sun_entries: usize,
    /// Bytes of its six tables (within [`DaylightReport::bytes`]); `daylight_modes` holds
    /// `p × (r + sun nodes)` values with it instead of `p × D`.
    pub bytes: usize,
}

/// What a basis' daylight holds, what it costs in flash and how close it reads.
#[derive(Clone, Debug, Serialize)]
pub struct DaylightReport {
    /// The sky's patches: `tregenza` or `reinhart MF:n`.
    pub sky: String,
    /// Number of sky patches.
    pub sky_patches: usize,
    /// The sun grid: declinations and hour angles.
    pub sun_grid: [usize; 2],
    /// Degrees between its declinations and between its hour angles.
    pub sun_step_deg: [f64; 2],
    /// The grid's nodes that light the room (stored).
    pub sun_nodes: usize,
    /// Every node: sky patches, the exterior, the sun nodes.
    pub nodes: usize,
    /// Bytes the daylight section adds to the basis.
    pub bytes: usize,
    /// The direct sun's tables (docs/format.md, "Direct sun"): window faces, room and
    /// exterior occluders stored, and the bytes they take (within [`Self::bytes`]).
    pub direct_sun: Option<DirectSunReport>,
    /// The first reflection stored for patch exitance, `None` when the basis stores none.
    pub first_reflection: Option<FirstReflectionReport>,
    /// The sun read between the grid's nodes against the exact sun.
    pub sun_interpolation: crate::accuracy::daylight::SunInterpolation,
    /// A sky state read through the runtime against the exact solve.
    pub check: crate::accuracy::daylight::DaylightCheck,
    /// The sky patches' discretisation error at the outputs, when the build chose them from
    /// a tolerance (`--sky-tolerance`); `None` for a subdivision taken as given.
    pub sky_discretisation: Option<crate::accuracy::sky::SkyDiscretisation>,
}

impl DaylightReport {
    /// The report of the daylight `d` the basis `bytes` carries (`bytes_added` of them),
    /// read through the runtime and against the exact sun.
    pub(super) fn of(
        d: &BasisDaylight,
        bytes_added: usize,
        sky_rank_tolerance: f64,
        (scene, occluders, model): (&Scene, &Occluders, &Model),
        bytes: &[u8],
    ) -> Result<DaylightReport> {
        let grid = &d.nodes.sun_grid;
        let payload = eigenrad_runtime::format::decode(bytes)?;
        let first_reflection = (!payload.reflection_rank.is_empty()).then(|| {
            let rank = payload.reflection_rank.iter().take(4).enumerate();
            let rank = rank.fold(0usize, |r, (k, &b)| r | (usize::from(b) << (8 * k)));
            let tables = [
                payload.reflection_rank,
                payload.sky_reflection_weights,
                payload.sky_reflection.scales,
                payload.sky_reflection.data,
                payload.sun_reflection_counts,
                payload.sun_reflection_patches,
                payload.sun_reflection,
            ];
            FirstReflectionReport {
                rank,
                tolerance: sky_rank_tolerance,
                sky_error: crate::sources::daylight::reflection::sky_truncation_error(
                    &d.initial[..d.nodes.patches.count() + 1],
                    model.area(),
                    rank,
                ),
                sun_entries: payload.sun_reflection.len() / 4,
                bytes: tables.iter().map(|t| t.len()).sum(),
            }
        });
        Ok(DaylightReport {
            sky: if d.nodes.patches.subdivision() == 1 {
                "tregenza".to_owned()
            } else {
                format!("reinhart MF:{}", d.nodes.patches.subdivision())
            },
            sky_patches: d.nodes.patches.count(),
            sun_grid: [grid.rows, grid.columns],
            sun_step_deg: [grid.declination_step, grid.hour_step].map(f64::from),
            sun_nodes: d.nodes.sun_nodes.len(),
            nodes: d.nodes.len(),
            bytes: bytes_added,
            direct_sun: {
                let basis = eigenrad_runtime::Basis::from_bytes(bytes)?;
                eigenrad_runtime::sky::direct::DirectSun::new(&basis)?.map(|d| {
                    let [w, r, e] = d.polygon_counts();
                    let first = eigenrad_runtime::sky::sun_first::SunFirst::new(&basis, d);
                    DirectSunReport {
                        window_faces: w,
                        room_occluders: r,
                        exterior_occluders: e,
                        bytes: d.stored_bytes(),
                        candidates: first.map_or(0, |f| f.patch_count()),
                        zone_polygons: first.map_or(0, |f| f.zone_polygon_count()),
                        candidate_bytes: first
                            .map_or([0, 0], |f| [f.stored_bytes(), f.response_bytes()]),
                    }
                })
            },
            first_reflection,
            sun_interpolation: accuracy::daylight::sun_interpolation(
                scene, occluders, model, d, bytes,
            )?,
            check: accuracy::daylight::through_runtime(bytes, model, d)?,
            sky_discretisation: None,
        })
    }

    /// The report with the sky's discretisation error the build measured, if it did.
    pub(super) fn with_sky_discretisation(
        self,
        error: Option<crate::accuracy::sky::SkyDiscretisation>,
    ) -> DaylightReport {
        DaylightReport {
            sky_discretisation: error,
            ..self
        }
    }
}

/// `sensor NAME` for every sensor, `zone NAME` for every zone, then `zone NAME point I` for
/// every grid point: the outputs in the model's order.
pub fn output_names(scene: &Scene) -> Vec<String> {
    let sensors = scene.sensors.iter().map(|s| format!("sensor {}", s.name));
    let points = scene.zones.iter().flat_map(|z| {
        let count = z.grid.as_ref().map_or(0, |g| g.len());
        (0..count).map(move |i| format!("zone {} point {i}", z.name))
    });
    sensors
        .chain(scene.zones.iter().map(|z| format!("zone {}", z.name)))
        .chain(points)
        .collect()
}

/// The grids with every channel at level 1 through the runtime, and the largest relative
/// difference of their figures from those of the exact solve.
pub(super) fn grid_report(
    model: &Model,
    bytes: &[u8],
    scene: &Scene,
) -> Result<(Vec<GridReadout>, f64)> {
    let levels = vec![1.0; model.channel_count()];
    let got = runtime_eval::evaluate(bytes, &vec![1.0f32; levels.len()], &[], false)?;
    let basis = eigenrad_runtime::Basis::from_bytes(bytes)?;
    let mut exact = vec![Vec::new(); model.system.output_count()];
    for b in 0..model.bands.len() {
        let m = model
            .system
            .exact_many(b, &[(levels.as_slice(), &[][..])])?;
        for (slot, r) in exact.iter_mut().zip(model.readings(b, &m[0], &levels)) {
            slot.push(r);
        }
    }
    let reference = scene_grids(scene, &exact);
    let mut grids = Vec::new();
    let mut next = 0;
    for (z, zone) in scene.zones.iter().enumerate() {
        let Some(g) = &zone.grid else { continue };
        let positions = (0..g.len())
            .map(|i| basis.grid_point(z, i).map(|p| p.map(f64::from)))
            .collect::<std::result::Result<Vec<_>, _>>()?;
        let mut readout = GridReadout::new(
            zone.name.clone(),
            g.pieces.iter().map(PieceLayout::from).collect(),
            positions,
            &got.grid[next..next + g.len()],
            got.figures[z].as_deref(),
        );
        readout.obstructed = g.obstructed;
        grids.push(readout);
        next += g.len();
    }
    let mut worst = 0.0f64;
    for (r, e) in grids.iter().zip(&reference) {
        for (x, y) in [
            (&r.average, &e.average),
            (&r.minimum, &e.minimum),
            (&r.maximum, &e.maximum),
            (&r.uniformity, &e.uniformity),
        ] {
            for (a, b) in x.iter().zip(y) {
                worst = worst.max((a - b).abs() / b.abs().max(1e-12));
            }
        }
    }
    Ok((grids, worst))
}

/// Evaluates the encoded basis through the runtime for every case and compares with the
/// exact solve.
pub(super) fn verify(
    model: &Model,
    cases: &[Case],
    exact: &ExactCases,
    bytes: &[u8],
    scene: &Scene,
) -> Result<Vec<CaseAccuracy>> {
    let output_names = output_names(scene);
    let mut out = Vec::new();
    for (index, case) in cases.iter().enumerate() {
        let levels: Vec<f32> = case.levels.iter().map(|&l| l as f32).collect();
        let got = runtime_eval::evaluate(bytes, &levels, &case.extra, true)?;
        let mut patch_error = 0.0f64;
        let mut worst_patch = Worst::default();
        let mut worst_reading = Worst::default();
        for b in 0..model.bands.len() {
            let exact = exact.exitance(index, b);
            let exitance: Vec<f64> = got.exitance.iter().map(|e| e[b]).collect();
            let patches = accuracy::metric::patch_error(model.area(), &exitance, exact);
            patch_error = patch_error.max(patches);
            worst_patch = worst_patch.max(accuracy::metric::worst_reading(&exitance, exact));
            let readings: Vec<f64> = got
                .sensors
                .iter()
                .chain(&got.zones)
                .chain(&got.grid)
                .map(|r| r[b])
                .collect();
            let exact_readings = model.readings(b, exact, &case.levels);
            worst_reading =
                worst_reading.max(accuracy::metric::worst_reading(&readings, &exact_readings));
        }
        out.push(CaseAccuracy {
            case: case.name.clone(),
            patch_error,
            worst_patch,
            worst_reading,
            worst_reading_name: output_names
                .get(worst_reading.index)
                .cloned()
                .unwrap_or_default(),
            worst_patch_surface: scene
                .patches
                .get(worst_patch.index)
                .map(|p| scene.surfaces[p.surface].name.clone())
                .unwrap_or_default(),
        });
    }
    Ok(out)
}
