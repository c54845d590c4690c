//! `eigenrad build`: scene → form factors → modes → basis bytes, with a report of every
//! stage and the accuracy of the result measured through the runtime. The report's types and
//! its checks through the runtime are in `report`, the calculation grids' readouts in `grids`.

use std::io::Write;
use std::path::Path;
use std::sync::Arc;

use eigenrad_runtime::writer::BasisTables;
use eigenrad_runtime::Precision;

use crate::accuracy::runtime_eval;
use crate::accuracy::{self, Case, ExactCases};
use crate::basis;
use crate::cache;
use crate::error::{Error, Result};
use crate::flash::FlashBudget;
use crate::formfactor::hierarchical::Compression;
use crate::formfactor::{self, FormFactorHealth, FormFactorOperator, FormFactorOptions};
use crate::formfactor::{exchange, outputs};
use crate::formfactor::{Occluders, Storage};
use crate::memory;
use crate::radiosity::eigen::{Formulation, Solver};
use crate::radiosity::{Model, System};
use crate::scene::{self, Scene};
use crate::sources;
use crate::sources::luminaires::LuminaireFlux;

mod grids;
mod plan;
mod report;
mod stages;
pub mod time_model;

pub use grids::{scene_grids, GridPoint, GridReadout, PieceLayout};
pub use plan::{BasisSize, Blocking, Plan, StageSeconds};
use report::{grid_report, verify};
pub use report::{
    output_names, BuildReport, CaseAccuracy, DaylightReport, EigensolveReport, OperatorReport,
    Stage,
};
use stages::Stages;
pub use stages::{Narration, LINE_PREFIX};

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

/// Which sky patches a basis with daylight stores.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum SkySelection {
    /// Reinhart MF:n (1: Tregenza's 145 patches).
    Subdivision(u8),
    /// The coarsest of MF:1, 2 and 4 whose sky-discretisation error at the outputs
    /// ([`accuracy::sky::SkyDiscretisation`]) is at most this (relative).
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
    /// The sky's patches a basis with daylight stores (`--mf`, `--sky-tolerance`).
    pub sky: SkySelection,
    /// Relative error, in the area-weighted Frobenius norm, to which the sky's first
    /// reflection is stored for patch exitance under daylight (`--sky-rank-tolerance`;
    /// docs/math.md, "Daylight's first reflection").
    pub sky_rank_tolerance: f64,
    /// Store the patches the sun can light, so that the controller computes the sun
    /// patch's first reflection at the sun and reads the rest per unit of its power
    /// (`--sun-first`; docs/format.md, "The sun's first reflection"). Off by default: it
    /// costs 38 KB on the example daylight office, more than the firmware's flash holds
    /// beside its f16 basis, and does not yet meet the 2 % target (docs/accuracy.md).
    pub sun_first: bool,
    /// The flash the basis should fit (`--flash`): a build that would not fit says so before
    /// its form factors, naming the sections and what would bring it under.
    pub flash: FlashBudget,
    /// What the build tells on standard error while it runs.
    pub narration: Narration,
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
            sky: SkySelection::Subdivision(1),
            sky_rank_tolerance: sources::daylight::reflection::DEFAULT_SKY_RANK_TOLERANCE,
            sun_first: false,
            flash: FlashBudget::DEFAULT,
            narration: Narration::Silent,
        }
    }
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
    /// What the compression made of the form factors, for a hierarchical operator.
    pub compression: Option<Compression>,
    /// Stage timings so far.
    pub timings: Vec<Stage>,
    /// What the build expected of itself once the scene was meshed: time, memory, the basis'
    /// size.
    pub plan: Plan,
}

/// Bytes a build of `scene` holds at its peak: the form factors with the solvers' workspace
/// (`memory::build_bytes_of`), and the rows of its sensors, zones and grid points on top
/// (`memory::output_bytes`).
pub fn peak_bytes(scene: &Scene, opts: &FormFactorOptions) -> [f64; 2] {
    let n = scene.patches.len();
    let reflecting: Vec<f64> = (0..scene.bands.count())
        .map(|b| scene.reflectance.iter().filter(|r| r[b] > 0.0).count() as f64)
        .collect();
    let storage = opts.operator.storage(n);
    let solve = memory::build_bytes_of(
        n as f64,
        &reflecting,
        storage.operator_bytes(n as f64),
        storage == Storage::F64,
    );
    let rows = outputs::grid_offset(scene) + outputs::grid_points(scene).count();
    [solve, memory::output_bytes(rows as f64, n as f64)]
}

/// Loads a scene and computes its form factors and output rows.
pub fn prepare(path: &Path, opts: &FormFactorOptions) -> Result<Prepared> {
    let build = BuildOptions {
        form_factors: opts.clone(),
        ..BuildOptions::default()
    };
    let mut stages = Stages::new(Narration::Silent);
    let prepared = prepare_stages(path, &build, &mut stages)?;
    Ok(Prepared {
        timings: stages.into_timings(),
        ..prepared
    })
}

/// [`prepare`] for the build `build`, its stages run and told through `stages`; tells the
/// plan before the form factors when the build narrates.
fn prepare_stages(path: &Path, build: &BuildOptions, stages: &mut Stages) -> Result<Prepared> {
    let opts = &build.form_factors;
    let scene = stages.run("scene and meshing", None, || scene::load(path))?;
    // What the imported building models hold and the scene could not map: said, not hidden.
    for w in &scene.warnings {
        let _ = writeln!(std::io::stderr(), "warning: {w}");
    }
    let n = scene.patches.len();
    let storage = opts.operator.storage(n);
    // Refused before the n×n form factors are allocated (`memory::build_bytes`).
    let [needed, rows_needed] = peak_bytes(&scene, opts);
    let available = memory::budget_bytes();
    if needed > available {
        return Err(Error::TooLarge(format!(
            "{}: {n} patches need about {:.1} GB for the form-factor operator ({}) and the solvers' workspace, more than the {:.1} GB this machine can spare; raise `max_edge` to mesh coarser",
            path.display(),
            needed / 1e9,
            storage.name(),
            available / 1e9
        )));
    }
    // And before the output rows are: one per sensor, zone and grid point.
    let points = outputs::grid_points(&scene).count();
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
    let clusters = opts.visibility == formfactor::Visibility::Clusters;
    let plan = Plan::of(
        &scene,
        build,
        storage,
        opts.operator.reason(n),
        storage.operator_bytes(n as f64),
        needed + rows_needed,
        Blocking {
            share: formfactor::occluded_share(&scene.patches, &occluders),
            clusters: clusters && storage == Storage::Hierarchical,
        },
    );
    if clusters && storage != Storage::Hierarchical {
        // Said whatever the narration: the flag asked for something this build does not do.
        stages::tell(
            "note: --visibility clusters shades well-separated clusters of the hierarchical \
             operator only; this build's dense operator reads every pair with exact shadows \
             (--operator hierarchical to use it)",
        );
    }
    if stages.narration().tells_plan() {
        for line in plan.lines() {
            stages::tell(&line);
        }
    }
    let expected = plan.seconds.clone();
    let area: Vec<f64> = scene.patches.iter().map(|p| p.area).collect();
    let names: Vec<String> = scene.surfaces.iter().map(|s| s.name.clone()).collect();
    let (g, form_factor_health, compression): (Arc<dyn FormFactorOperator>, _, _) = stages.run(
        "form factors",
        Some(expected.form_factors),
        || match storage {
            Storage::F64 => {
                let ff = cache::form_factors(&scene.patches, &scene.faces, &occluders, opts);
                let health = FormFactorHealth::of(&ff, &scene.patches, &scene.faces, &names);
                let g: Arc<dyn FormFactorOperator> =
                    Arc::new(exchange::exchange_areas(ff.matrix, &area));
                Ok::<_, Error>((g, health, None))
            }
            // Not cached: chosen only on request, for scenes whose f64 matrix would outgrow
            // the cache's entries (`memory::AUTO_HIERARCHICAL_ABOVE`).
            Storage::F32 => {
                let ff = formfactor::patch_form_factors_f32(&scene.patches, &occluders, opts);
                let health = FormFactorHealth::of(&ff, &scene.patches, &scene.faces, &names);
                let g: Arc<dyn FormFactorOperator> = Arc::new(ff.matrix);
                Ok((g, health, None))
            }
            Storage::Hierarchical => {
                let settings = formfactor::hierarchical::Settings {
                    shade_mixed: opts.visibility == formfactor::Visibility::Clusters,
                    shade_misfit: opts.cluster_misfit,
                    ..formfactor::hierarchical::Settings::default()
                };
                let ff = cache::hierarchical_form_factors(
                    &scene.patches,
                    &scene.faces,
                    &occluders,
                    opts,
                    &settings,
                )
                .map_err(|e| Error::FormFactor {
                    scene: path.to_path_buf(),
                    patches: e.patches,
                })?;
                let health = FormFactorHealth::of(&ff, &scene.patches, &scene.faces, &names);
                let compression = ff.matrix.compression().clone();
                let g: Arc<dyn FormFactorOperator> = Arc::new(ff.matrix);
                Ok((g, health, Some(compression)))
            }
        },
    )?;
    let output_rows = stages.run("sensors and zones", Some(expected.outputs), || {
        cache::output_rows(&scene, g.as_ref(), &area, &occluders, opts)
    });
    let (lights, luminaire_flux) = stages.run("light sources", None, || {
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
        compression,
        timings: Vec::new(),
        plan,
    })
}

/// Runs the whole build; returns the basis bytes and the report. Writes nothing.
pub fn build(path: &Path, opts: &BuildOptions) -> Result<(Vec<u8>, BuildReport)> {
    build_tables(path, opts).map(|built| (built.bytes, built.report))
}

/// What a build makes: the basis' tables in `f64`, its bytes (the tables written in the
/// build's precision) and the report.
pub struct Built {
    /// Every table of the basis, before the storage precision rounds them.
    pub tables: BasisTables,
    /// The basis as written.
    pub bytes: Vec<u8>,
    /// The build's report.
    pub report: BuildReport,
}

/// Runs the whole build as [`build`] does and keeps the tables too (a building cuts its
/// controllers' bases from them). Writes nothing.
pub fn build_tables(path: &Path, opts: &BuildOptions) -> Result<Built> {
    build_tables_and(path, opts, None, |_, _, _, _| Ok(())).map(|(built, ())| built)
}

/// [`build_tables`], and `also` asked of the meshed scene, its occluders, its radiosity system
/// and its daylight (when the basis carries one) once the channels' and the daylight's exact responses
/// are solved (a building's room answers for its ports there), told as the stage `stage` when
/// it is one.
pub fn build_tables_and<T>(
    path: &Path,
    opts: &BuildOptions,
    stage: Option<&'static str>,
    also: impl FnOnce(&Scene, &Occluders, &System, Option<&basis::BasisDaylight>) -> Result<T>,
) -> Result<(Built, T)> {
    let mut stages = Stages::new(opts.narration);
    let prepared = prepare_stages(path, opts, &mut stages)?;
    let Prepared {
        mut scene,
        occluders,
        mut system,
        luminaire_flux,
        form_factor_health,
        compression,
        timings: _,
        plan,
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
    // Said again now that the operator's size is known.
    let expected = plan.seconds_once_built(
        system.operator().stored_bytes(),
        p_max * system.band_count(),
    );
    let modes = stages.run("eigenbasis", Some(expected.eigenbasis), || {
        Model::modes(&system, opts.formulation, p_max, opts.solver)
    })?;
    // The exact reference every figure is measured against, and the channels' exact
    // responses the basis stores: LU for small scenes, conjugate gradients on G above
    // `EXACT_LU_MAX` patches (no n×n copy, no n³ factorisation). Made once, kept by the system,
    // after the modes, whose dense workspace is gone by then.
    let model = stages.run(
        "exact channel responses (LU or CG)",
        Some(expected.exact_solves),
        || Model::from_modes(&system, opts.formulation, modes),
    )?;
    let bands = model.bands.len();
    let cases = accuracy::standard_cases(&scene, opts.random_patterns);
    let exact = stages.run(
        "exact reference of the report's cases",
        Some(expected.exact_cases),
        || ExactCases::solve(&system, &cases),
    )?;
    let available = accuracy::modes_held(&model);
    let p = match opts.modes {
        ModeSelection::Count(p) => p.min(available),
        ModeSelection::Tolerance(t) => stages.run("mode count search", None, || {
            smallest_count(&model, &cases, &exact, available, t)
        })?,
    };
    let daylight = if scene.site.is_some() && !scene.windows.is_empty() {
        Some(stages.run("daylight through the windows", None, || {
            let daylight_opts = sources::daylight::DaylightOptions::default();
            let (sky, discretisation) =
                accuracy::sky::choose(&scene, &occluders, opts.sky, &daylight_opts)?;
            let nodes = sources::daylight::nodes::nodes_with_sky(
                &scene,
                &occluders,
                sky,
                opts.sun_step,
                &daylight_opts,
            );
            let responses = system.light_responses(0, &nodes.lights)?;
            let initial = system.initial_exitances(0, &nodes.lights);
            let lit_between_nodes = match &scene.site {
                Some(site) if opts.sun_first => sources::daylight::sun_first::lit_between_nodes(
                    &scene,
                    &occluders,
                    site,
                    &nodes.sun_grid,
                    &daylight_opts,
                ),
                _ => Vec::new(),
            };
            Ok::<_, Error>((
                basis::BasisDaylight {
                    nodes,
                    responses,
                    initial,
                    lit_between_nodes,
                },
                discretisation,
            ))
        })?)
    } else {
        None
    };
    let (daylight, sky_discretisation) = match daylight {
        Some((d, error)) => (Some(d), error),
        None => (None, None),
    };
    let extra = match stage {
        Some(stage) => stages.run(stage, None, || {
            also(&scene, &occluders, &system, daylight.as_ref())
        })?,
        None => also(&scene, &occluders, &system, daylight.as_ref())?,
    };
    let (tables, bytes, daylight_bytes) =
        stages.run("serialization", Some(expected.serialization), || {
            serialize(&scene, &model, p, opts, daylight.as_ref())
        })?;
    let accuracy = stages.run(
        "verification through the runtime",
        Some(expected.verification),
        || verify(&model, &cases, &exact, &bytes, &scene),
    )?;
    let (grids, grid_figure_error) = stages.run("grids through the runtime", None, || {
        grid_report(&model, &bytes, &scene)
    })?;
    let daylight = match &daylight {
        None => None,
        Some(d) => Some(stages.run("daylight through the runtime", None, || {
            DaylightReport::of(
                d,
                daylight_bytes,
                opts.sky_rank_tolerance,
                (&scene, &occluders, &model),
                &bytes,
            )
            .map(|r| r.with_sky_discretisation(sky_discretisation))
        })?),
    };
    let sensor_ratios = stages.run("sensor ratios through the runtime", None, || {
        crate::accuracy::calibration::ratios_of(&bytes)
    })?;
    let report = BuildReport {
        scene: scene.name.clone(),
        patches: n,
        aspect: crate::geometry::aspect_summary(&scene.patches),
        bands,
        unit: scene.bands.unit(),
        formulation: opts.formulation.name(),
        precision: opts.precision.name(),
        modes: p,
        eigensolve: model
            .bands
            .iter()
            .map(|b| EigensolveReport::of(&b.modes))
            .collect(),
        bytes: bytes.len(),
        form_factors: form_factor_health,
        operator: OperatorReport {
            storage: system.operator().storage(),
            bytes: system.operator().stored_bytes(),
            reason: plan.operator_reason.clone(),
            compression,
        },
        luminaires: luminaire_flux,
        accuracy,
        grids,
        grid_figure_error,
        daylight,
        channels: scene.channels.iter().map(|c| c.name.clone()).collect(),
        sensor_ratios,
        timings: stages.into_timings(),
        plan,
    };
    Ok((
        Built {
            tables,
            bytes,
            report,
        },
        extra,
    ))
}

/// The smallest mode count up to `available` at which every case is within `tolerance` of
/// the exact solve ([`ModeSelection::Tolerance`]).
fn smallest_count(
    model: &Model,
    cases: &[Case],
    exact: &ExactCases,
    available: usize,
    tolerance: f64,
) -> Result<usize> {
    let ladder = accuracy::mode_ladder(available.max(1));
    let curves: Vec<_> = cases
        .iter()
        .enumerate()
        .map(|(k, c)| accuracy::curve(model, c, (exact, k), &ladder))
        .collect();
    accuracy::smallest_p(&curves, tolerance).ok_or_else(|| Error::Tolerance {
        tolerance,
        modes: available,
        best: curves
            .iter()
            .map(|c| {
                let last = |e: &[f64]| e.last().copied().unwrap_or(f64::NAN);
                last(&c.patch_error).max(last(&c.reading_error))
            })
            .fold(0.0, f64::max),
    })
}

/// The tables and basis bytes of the first `p` modes of `model`, and the bytes its daylight
/// adds.
fn serialize(
    scene: &Scene,
    model: &Model,
    p: usize,
    opts: &BuildOptions,
    daylight: Option<&basis::BasisDaylight>,
) -> Result<(BasisTables, Vec<u8>, usize)> {
    let mut tables = basis::basis_tables(scene, model, p, opts.precision);
    let Some(d) = daylight else {
        let bytes = tables.to_bytes()?;
        return Ok((tables, bytes, 0));
    };
    let without = tables.to_bytes()?.len();
    basis::daylight_tables(
        &mut tables,
        scene,
        model,
        d,
        (opts.sky_rank_tolerance, opts.sun_first),
    )?;
    let bytes = tables.to_bytes()?;
    let added = bytes.len() - without;
    Ok((tables, bytes, added))
}
