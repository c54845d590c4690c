//! `eigenrad build`: scene → form factors → modes → basis bytes, with a report of every
//! stage and the accuracy of the result measured through the runtime.

use std::path::Path;
use std::time::Instant;

use std::sync::Arc;

use eigenrad_runtime::Precision;
use serde::Serialize;

use crate::accuracy::metric::Worst;
use crate::accuracy::runtime_eval;
use crate::accuracy::{self, Case};
use crate::basis;
use crate::cache;
use crate::error::{Error, Result};
use crate::formfactor::{self, FormFactorHealth, FormFactorOperator, FormFactorOptions};
use crate::formfactor::{exchange, outputs};
use crate::formfactor::{Occluders, Storage};
use crate::memory;
use crate::radiosity::eigen::{Formulation, Solver};
use crate::radiosity::{Model, System};
use crate::scene::{self, Scene};
use crate::sources;
use crate::sources::luminaires::LuminaireFlux;

/// Modes kept when neither a count nor a tolerance is given. Channels are exact whatever the
/// count; the modes carry exitance set patch by patch: on the example office (1070 patches)
/// random emitter patterns read about 0.7 % off on the work plane and 1.4 % at the ceiling
/// photocell at this count, 5 % in per-patch exitance (`docs/accuracy.md`, "Office"); use
/// `--tolerance` for a stated bound.
pub const DEFAULT_MODES: usize = 32;

/// Most modes the tolerance search computes and tries: the eigensolve and the sweep grow with
/// it, and a tolerance not reached by then is reported ([`Error::Tolerance`]) rather than
/// searched further. At most [`runtime_eval::MAX_MODES`], so that the basis it picks can be
/// verified through the runtime.
pub const TOLERANCE_MAX_MODES: usize = 512;
const _: () = assert!(TOLERANCE_MAX_MODES <= runtime_eval::MAX_MODES);

/// How many modes to keep.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum ModeSelection {
    /// Exactly this many per band (fewer if a band has fewer reflecting patches).
    Count(usize),
    /// The smallest count, up to [`TOLERANCE_MAX_MODES`], whose relative error against the
    /// exact solve is at most this for every channel and every random emitter pattern.
    Tolerance(f64),
}

/// Options of a build.
#[derive(Clone, Debug)]
pub struct BuildOptions {
    /// Mode count or tolerance.
    pub modes: ModeSelection,
    /// Expansion.
    pub formulation: Formulation,
    /// Storage of the large tables.
    pub precision: Precision,
    /// Eigensolver path.
    pub solver: Solver,
    /// Form-factor settings.
    pub form_factors: FormFactorOptions,
    /// Random emitter patterns used by `--tolerance` and the report.
    pub random_patterns: usize,
    /// Store the zones' calculation grids (`--no-grids` leaves them out: a smaller basis,
    /// the zones still read as area averages).
    pub grids: bool,
    /// Degrees between the sun grid's declinations and between its hour angles, for a scene
    /// with daylight (`--sun-step`).
    pub sun_step: [f64; 2],
}

impl Default for BuildOptions {
    fn default() -> Self {
        BuildOptions {
            modes: ModeSelection::Count(DEFAULT_MODES),
            formulation: Formulation::Split,
            precision: Precision::F32,
            solver: Solver::Auto,
            form_factors: FormFactorOptions::default(),
            random_patterns: 4,
            grids: true,
            sun_step: sources::daylight::nodes::DEFAULT_SUN_STEP,
        }
    }
}

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
    /// Time per stage.
    pub timings: Vec<Stage>,
}

/// The form-factor operator a build solved the room with (`--operator`).
#[derive(Clone, Debug, Serialize)]
pub struct OperatorReport {
    /// `dense f64` or `dense f32`.
    pub storage: &'static str,
    /// Bytes it held.
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
    /// The sun read between the grid's nodes against the exact sun.
    pub sun_interpolation: crate::accuracy::daylight::SunInterpolation,
    /// A sky state read through the runtime against the exact solve.
    pub check: crate::accuracy::daylight::DaylightCheck,
}

/// A scene with its radiosity system: everything before the eigensolve.
pub struct Prepared {
    /// The scene.
    pub scene: Scene,
    /// The scene's occluders, built once and shared by the form factors, the luminaires and
    /// the daylight.
    pub occluders: Occluders,
    /// The room's radiosity problem: form-factor operator, areas, reflectances, receivers,
    /// the channels' light, and its exact solves.
    pub system: System,
    /// Where each luminaire's flux goes.
    pub luminaire_flux: Vec<LuminaireFlux>,
    /// Form-factor health.
    pub form_factor_health: FormFactorHealth,
    /// Stage timings so far.
    pub timings: Vec<Stage>,
}

fn timed<T>(timings: &mut Vec<Stage>, stage: &'static str, f: impl FnOnce() -> T) -> T {
    let start = Instant::now();
    let out = f();
    timings.push(Stage {
        stage,
        seconds: start.elapsed().as_secs_f64(),
    });
    out
}

/// Loads a scene and computes its form factors and output rows.
pub fn prepare(path: &Path, opts: &FormFactorOptions) -> Result<Prepared> {
    let mut timings = Vec::new();
    let scene = timed(&mut timings, "scene and meshing", || scene::load(path))?;
    let n = scene.patches.len();
    // Refused before the n×n form factors are allocated (`memory::build_bytes`).
    let reflecting: Vec<f64> = (0..scene.bands.count())
        .map(|b| scene.reflectance.iter().filter(|r| r[b] > 0.0).count() as f64)
        .collect();
    let storage = opts.operator.storage(n);
    let needed = memory::build_bytes_stored(n as f64, &reflecting, storage.entry_bytes() as f64);
    let available = memory::budget_bytes();
    if needed > available {
        return Err(Error::TooLarge(format!(
            "{}: {n} patches need about {:.1} GB for the form-factor matrix and the solvers' workspace, more than the {:.1} GB this machine can spare; raise `max_edge` to mesh coarser",
            path.display(),
            needed / 1e9,
            available / 1e9
        )));
    }
    // And before the output rows are: one per sensor, zone and grid point.
    let points = outputs::grid_points(&scene).count();
    let rows = outputs::grid_offset(&scene) + points;
    let rows_needed = memory::output_bytes(rows as f64, n as f64);
    if needed + rows_needed > available {
        return Err(Error::TooLarge(format!(
            "{}: {} sensors, {} zones and {points} calculation-grid points over {n} patches need about {:.1} GB for their rows on top of {:.1} GB for the form factors, more than the {:.1} GB this machine can spare; use fewer sensors or zones, a coarser `grid.spacing`, or `max_edge`",
            path.display(),
            scene.sensors.len(),
            scene.zones.len(),
            rows_needed / 1e9,
            needed / 1e9,
            available / 1e9
        )));
    }
    let occluders = Occluders::with_faces(&scene.patches, &scene.faces);
    let area: Vec<f64> = scene.patches.iter().map(|p| p.area).collect();
    let names: Vec<String> = scene.surfaces.iter().map(|s| s.name.clone()).collect();
    let (g, form_factor_health): (Arc<dyn FormFactorOperator>, _) =
        timed(&mut timings, "form factors", || match storage {
            Storage::F64 => {
                let ff = cache::form_factors(&scene.patches, &scene.faces, &occluders, opts);
                let health = FormFactorHealth::of(&ff, &scene.patches, &scene.faces, &names);
                let g: Arc<dyn FormFactorOperator> =
                    Arc::new(exchange::exchange_areas(ff.matrix, &area));
                (g, health)
            }
            // Not cached: an f32 operator is chosen where the f64 one outgrows the cache's
            // entries (`memory::AUTO_F32_ABOVE`).
            Storage::F32 => {
                let ff = formfactor::patch_form_factors_f32(&scene.patches, &occluders, opts);
                let health = FormFactorHealth::of(&ff, &scene.patches, &scene.faces, &names);
                let g: Arc<dyn FormFactorOperator> = Arc::new(ff.matrix);
                (g, health)
            }
        });
    let output_rows = timed(&mut timings, "sensors and zones", || {
        cache::output_rows(&scene, g.as_ref(), &area, &occluders, opts)
    });
    let (lights, luminaire_flux) = timed(&mut timings, "light sources", || {
        let surfaces = sources::surfaces::channel_lights(&scene, g.as_ref(), &area, &output_rows);
        if scene.luminaires.is_empty() {
            // Left exactly as it is: scenes without luminaires build the bases they always did.
            return (surfaces, Vec::new());
        }
        let options = sources::luminaires::LuminaireOptions::default();
        let (luminaires, flux) = sources::luminaires::lights_and_flux(&scene, &occluders, &options);
        let lights = surfaces
            .iter()
            .zip(&luminaires)
            .map(|(s, l)| s.plus(l))
            .collect();
        (lights, flux)
    });
    let reflectance = (0..scene.bands.count())
        .map(|b| scene.reflectance.iter().map(|r| r[b]).collect())
        .collect();
    let system = System::new(g, area, reflectance, output_rows, lights);
    Ok(Prepared {
        scene,
        occluders,
        system,
        luminaire_flux,
        form_factor_health,
        timings,
    })
}

/// Runs the whole build; returns the basis bytes and the report. Writes nothing.
pub fn build(path: &Path, opts: &BuildOptions) -> Result<(Vec<u8>, BuildReport)> {
    let prepared = prepare(path, &opts.form_factors)?;
    let Prepared {
        mut scene,
        occluders,
        mut system,
        luminaire_flux,
        form_factor_health,
        mut timings,
    } = prepared;
    if !opts.grids {
        // The grid points are the outputs after the sensors and zones: drop them all.
        let keep = outputs::grid_offset(&scene);
        for zone in &mut scene.zones {
            zone.grid = None;
        }
        system = system.with_outputs(keep);
    }
    let n = scene.patches.len();
    let p_max = match opts.modes {
        ModeSelection::Count(p) => p.min(n),
        ModeSelection::Tolerance(_) => n.min(TOLERANCE_MAX_MODES),
    };
    // The exact reference every figure is measured against, and the channels' exact
    // responses the basis stores: LU for small scenes, conjugate gradients on G above
    // `EXACT_LU_MAX` patches (no n×n copy, no n³ factorisation). Made once, kept by the system.
    timed(&mut timings, "exact channel responses (LU or CG)", || {
        system.channel_responses().map(|_| ())
    })?;
    let model = timed(&mut timings, "eigenbasis", || {
        Model::new(&system, opts.formulation, p_max, opts.solver)
    })?;
    let bands = model.bands.len();
    let cases = accuracy::standard_cases(&scene, opts.random_patterns);
    let available = accuracy::modes_held(&model);
    let p = match opts.modes {
        ModeSelection::Count(p) => p.min(available),
        ModeSelection::Tolerance(t) => timed(&mut timings, "mode count search", || {
            let ladder = accuracy::mode_ladder(available.max(1));
            let curves = cases
                .iter()
                .map(|c| accuracy::curve(&model, c, &ladder))
                .collect::<std::result::Result<Vec<_>, _>>()?;
            accuracy::smallest_p(&curves, t).ok_or_else(|| Error::Tolerance {
                tolerance: t,
                modes: available,
                best: curves
                    .iter()
                    .map(|c| {
                        let last = |e: &[f64]| e.last().copied().unwrap_or(f64::NAN);
                        last(&c.patch_error).max(last(&c.reading_error))
                    })
                    .fold(0.0, f64::max),
            })
        })?,
    };
    let daylight = if scene.site.is_some() && !scene.windows.is_empty() {
        Some(timed(&mut timings, "daylight through the windows", || {
            let nodes = sources::daylight::nodes::nodes(
                &scene,
                &occluders,
                eigenrad_runtime::sky::patches::SkyPatches::TREGENZA,
                opts.sun_step,
                &sources::daylight::DaylightOptions::default(),
            );
            let responses = system.light_responses(0, &nodes.lights)?;
            Ok::<_, Error>(basis::BasisDaylight { nodes, responses })
        })?)
    } else {
        None
    };
    let (bytes, daylight_bytes) = timed(&mut timings, "serialization", || {
        let mut tables = basis::basis_tables(&scene, &model, p, opts.precision);
        let Some(d) = &daylight else {
            return tables.to_bytes().map(|b| (b, 0));
        };
        let without = tables.to_bytes()?.len();
        basis::daylight_tables(&mut tables, &scene, &model, d);
        let bytes = tables.to_bytes()?;
        let added = bytes.len() - without;
        Ok::<_, eigenrad_runtime::Error>((bytes, added))
    })?;
    let accuracy = timed(&mut timings, "verification through the runtime", || {
        verify(&model, &cases, &bytes, &scene)
    })?;
    let (grids, grid_figure_error) = timed(&mut timings, "grids through the runtime", || {
        grid_report(&model, &bytes, &scene)
    })?;
    let daylight = match &daylight {
        None => None,
        Some(d) => Some(timed(&mut timings, "daylight through the runtime", || {
            let grid = &d.nodes.sun_grid;
            Ok::<_, Error>(DaylightReport {
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
                bytes: daylight_bytes,
                sun_interpolation: crate::accuracy::daylight::sun_interpolation(
                    &scene, &occluders, &model, d,
                )?,
                check: crate::accuracy::daylight::through_runtime(&bytes, &model, d)?,
            })
        })?),
    };
    let report = BuildReport {
        scene: scene.name.clone(),
        patches: n,
        aspect: crate::geometry::aspect_summary(&scene.patches),
        bands,
        unit: scene.bands.unit(),
        formulation: opts.formulation.name(),
        precision: opts.precision.name(),
        modes: p,
        bytes: bytes.len(),
        form_factors: form_factor_health,
        operator: OperatorReport {
            storage: system.operator().storage(),
            bytes: system.operator().stored_bytes(),
        },
        luminaires: luminaire_flux,
        accuracy,
        grids,
        grid_figure_error,
        daylight,
        timings,
    };
    Ok((bytes, report))
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

/// One point of a calculation grid.
#[derive(Clone, Debug, Serialize)]
pub struct GridPoint {
    /// Position, m.
    pub position_m: [f64; 3],
    /// Irradiance per band (W/m²) or illuminance (lux).
    pub irradiance: Vec<f64>,
}

/// One piece of a calculation grid's layout (a lattice over a rectangle of a plane).
#[derive(Clone, Copy, Debug, Serialize, PartialEq)]
pub struct PieceLayout {
    /// Cells along the piece's first and second side.
    pub counts: [usize; 2],
    /// Points the piece keeps: the cell centres on its area.
    pub points: usize,
    /// Largest spacing the layout used, m.
    pub spacing_m: f64,
    /// Cell sides, m.
    pub cell_m: [f64; 2],
    /// Band left out at the walls, m.
    pub border_m: f64,
    /// Unit normal the piece's points face.
    pub normal: [f64; 3],
}

impl From<&crate::scene::grid::GridPiece> for PieceLayout {
    fn from(g: &crate::scene::grid::GridPiece) -> Self {
        PieceLayout {
            counts: g.counts,
            points: g.points.len(),
            spacing_m: g.spacing,
            cell_m: g.cell,
            border_m: g.border,
            normal: g.normal.to_array(),
        }
    }
}

impl From<eigenrad_runtime::GridPiece> for PieceLayout {
    fn from(g: eigenrad_runtime::GridPiece) -> Self {
        let wide = f64::from;
        PieceLayout {
            counts: g.counts,
            points: g.points,
            spacing_m: wide(g.spacing),
            cell_m: g.cell.map(wide),
            border_m: wide(g.border),
            normal: g.normal.map(wide),
        }
    }
}

/// A zone's calculation grid (EN 12464-1:2021, 4.4) and its figures, per band.
#[derive(Clone, Debug, Serialize)]
pub struct GridReadout {
    /// Zone name.
    pub zone: String,
    /// The lattices the grid is made of: one for a work plane or a task area, up to four for
    /// the band around a task area, one per plane of a surface zone.
    pub pieces: Vec<PieceLayout>,
    /// `E_avg` per band: mean over the points.
    pub average: Vec<f64>,
    /// `E_min` per band.
    pub minimum: Vec<f64>,
    /// `E_max` per band.
    pub maximum: Vec<f64>,
    /// `U_o = E_min / E_avg` per band.
    pub uniformity: Vec<f64>,
    /// Every point, first side fastest.
    pub points: Vec<GridPoint>,
}

impl GridReadout {
    /// A grid's readout from its layout and its points' readings (`values[point][band]`).
    /// The figures are [`eigenrad_runtime::Figures`], the one definition: `figures` as the
    /// runtime read them (per band), or, when `None`, taken here of `values` in `f64`.
    pub fn new(
        zone: String,
        pieces: Vec<PieceLayout>,
        positions: Vec<[f64; 3]>,
        values: &[Vec<f64>],
        figures: Option<&[eigenrad_runtime::Figures]>,
    ) -> GridReadout {
        let bands = values.first().map_or(0, Vec::len);
        let figures: Vec<Option<eigenrad_runtime::Figures<f64>>> = match figures {
            Some(read) => read
                .iter()
                .map(|f| {
                    Some(eigenrad_runtime::Figures {
                        average: f64::from(f.average),
                        minimum: f64::from(f.minimum),
                        maximum: f64::from(f.maximum),
                        uniformity: f64::from(f.uniformity),
                        points: f.points,
                    })
                })
                .collect(),
            None => (0..bands)
                .map(|b| eigenrad_runtime::Figures::of(values.iter().map(|v| v[b])))
                .collect(),
        };
        let pick = |f: fn(&eigenrad_runtime::Figures<f64>) -> f64| {
            figures
                .iter()
                .map(|x| x.as_ref().map_or(f64::NAN, f))
                .collect()
        };
        GridReadout {
            zone,
            pieces,
            average: pick(|f| f.average),
            minimum: pick(|f| f.minimum),
            maximum: pick(|f| f.maximum),
            uniformity: pick(|f| f.uniformity),
            points: positions
                .into_iter()
                .zip(values)
                .map(|(position_m, v)| GridPoint {
                    position_m,
                    irradiance: v.clone(),
                })
                .collect(),
        }
    }
}

/// The grids of `scene`'s zones from the model's outputs (`outputs[o][band]`: sensors, zones,
/// then grid points).
pub fn scene_grids(scene: &crate::scene::Scene, outputs: &[Vec<f64>]) -> Vec<GridReadout> {
    let mut next = crate::formfactor::outputs::grid_offset(scene);
    let mut grids = Vec::new();
    for z in &scene.zones {
        let Some(g) = &z.grid else { continue };
        let values = &outputs[next..next + g.len()];
        next += g.len();
        grids.push(GridReadout::new(
            z.name.clone(),
            g.pieces.iter().map(PieceLayout::from).collect(),
            g.points().map(|(p, _)| p.to_array()).collect(),
            values,
            None,
        ));
    }
    grids
}

/// The grids with every channel at level 1 through the runtime, and the largest relative
/// difference of their figures from those of the exact solve.
fn grid_report(model: &Model, bytes: &[u8], scene: &Scene) -> Result<(Vec<GridReadout>, f64)> {
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
        grids.push(GridReadout::new(
            zone.name.clone(),
            g.pieces.iter().map(PieceLayout::from).collect(),
            positions,
            &got.grid[next..next + g.len()],
            got.figures[z].as_deref(),
        ));
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
fn verify(model: &Model, cases: &[Case], bytes: &[u8], scene: &Scene) -> Result<Vec<CaseAccuracy>> {
    let output_names = output_names(scene);
    // Every case's exact solution at once, per band.
    let exact_all = (0..model.bands.len())
        .map(|b| {
            let inputs: Vec<(&[f64], &[f64])> = cases
                .iter()
                .map(|c| (c.levels.as_slice(), c.extra[b].as_slice()))
                .collect();
            model.system.exact_many(b, &inputs)
        })
        .collect::<std::result::Result<Vec<_>, _>>()?;
    let mut out = Vec::new();
    for (index, case) in cases.iter().enumerate() {
        let levels: Vec<f32> = case.levels.iter().map(|&l| l as f32).collect();
        let got = runtime_eval::evaluate(bytes, &levels, &case.extra, true)?;
        let mut patch_error = 0.0f64;
        let mut worst_patch = Worst::default();
        let mut worst_reading = Worst::default();
        for b in 0..model.bands.len() {
            let exact = &exact_all[b][index];
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
