//! Daylight in the basis (`eigenrad build` of a scene with a site and a window, `eigenrad eval
//! --time ... <sky>`), against the exact solve of the same mesh and sky (`eigenrad solve
//! --time`), which computes its daylight afresh and solves it in one piece:
//!
//! - without the sun, every sensor, zone and grid point is exact per sky patch: `eval` equals
//!   `solve` to `f32` ([`F32_SUMS`]), before sunrise too (the sky's light alone);
//! - with the sun at a node of the basis' sun grid, the runtime equals the exact solve of
//!   that sun (the same tolerance); between nodes the build report says how far it reads;
//! - with as many modes as patches, the daylight's patch exitance through the modes equals
//!   the exact one ([`FULL_MODES`]);
//! - the same scene builds the same bytes; a basis without daylight, or a sky of other
//!   patches, is an error naming the flag.
//!
//! The readings are taken in-process (the code behind the commands, optimised as tests are);
//! the errors through the binary.

mod common;

use std::path::{Path, PathBuf};

use common::{daylit_room, run, scratch, stderr, VIENNA};
use eigenrad_precompute::accuracy::runtime_eval::{evaluate_daylight, SkyState};
use eigenrad_precompute::cli::{self, DaylightArgs, LevelArgs, SkyInput};
use eigenrad_precompute::formfactor::{FormFactorOptions, Occluders};
use eigenrad_precompute::pipeline::{self, BuildOptions, ModeSelection};
use eigenrad_precompute::radiosity::eigen::{Formulation, Solver};
use eigenrad_precompute::radiosity::model::Model;
use eigenrad_precompute::sources::daylight::nodes::room_sun;
use eigenrad_precompute::sources::daylight::{sun_light, DaylightOptions};
use eigenrad_runtime::{Basis, Sun};

/// Relative difference of an `f32` sum over the ~150 daylight nodes (and the channels)
/// from the same sum in `f64`: a few hundred roundings of 6e-8.
const F32_SUMS: f64 = 2e-5;

/// Area-weighted RMS difference of the daylight's patch exitance through all the modes from
/// the exact solve: the modes are complete, what remains is `f32` rounding of `n` terms.
const FULL_MODES: f64 = 1e-4;

/// Area-weighted RMS difference, relative, between the runtime's daylight patch exitance and
/// the same expansion in `f64` on the host: `f32` sums of `r + p` terms and the sun lists'
/// floor of 10⁻⁶ of a node's largest entry.
const REFLECTION_ROUNDING: f64 = 1e-4;

fn no_cache() -> FormFactorOptions {
    FormFactorOptions {
        cache: None,
        ..FormFactorOptions::default()
    }
}

/// The daylit test room with the Vienna site, written to a scratch folder.
fn scene_file(test: &str) -> (PathBuf, PathBuf) {
    let dir = scratch(test);
    let path = dir.join("daylit.toml");
    std::fs::write(&path, daylit_room(VIENNA)).expect("write scene");
    (dir, path)
}

/// The basis of `scene` with `modes` modes, written next to it; its bytes.
fn build(scene: &Path, modes: ModeSelection) -> (PathBuf, Vec<u8>) {
    build_in(scene, modes, Formulation::Split)
}

/// [`build`] in the given formulation.
fn build_in(scene: &Path, modes: ModeSelection, formulation: Formulation) -> (PathBuf, Vec<u8>) {
    build_with(scene, modes, formulation, false)
}

/// [`build_in`], storing the sun's first reflection for the controller when `sun_first`.
fn build_with(
    scene: &Path,
    modes: ModeSelection,
    formulation: Formulation,
    sun_first: bool,
) -> (PathBuf, Vec<u8>) {
    let opts = BuildOptions {
        modes,
        formulation,
        form_factors: no_cache(),
        sun_first,
        ..BuildOptions::default()
    };
    let (bytes, report) = pipeline::build(scene, &opts).expect("build");
    let daylight = report.daylight.expect("a daylight section");
    assert_eq!(daylight.sky_patches, 145);
    assert!(daylight.sun_nodes > 0 && daylight.bytes > 0);
    let path = scene.with_extension("basis");
    std::fs::write(&path, &bytes).expect("write basis");
    (path, bytes)
}

fn sky(time: &str, input: SkyInput) -> DaylightArgs {
    DaylightArgs {
        time: time.to_owned(),
        input,
        water: 2.0,
        subdivision: 1,
    }
}

/// Every sensor's and zone's reading and daylight part, then every grid point's, of a
/// readout.
fn values(r: &cli::Readout) -> Vec<(String, f64, f64)> {
    let mut out: Vec<(String, f64, f64)> = r
        .sensors
        .iter()
        .chain(&r.zones)
        .map(|x| {
            let day = x.daylight.as_ref().expect("a daylight part")[0];
            (x.name.clone(), x.irradiance[0], day)
        })
        .collect();
    let day = r.daylight.as_ref().expect("daylight");
    for (g, d) in r.grids.iter().zip(&day.grids) {
        for (i, (p, q)) in g.points.iter().zip(&d.points).enumerate() {
            out.push((
                format!("{} point {i}", g.zone),
                p.irradiance[0],
                q.irradiance[0],
            ));
        }
    }
    out
}

fn close(a: f64, b: f64, tolerance: f64) -> bool {
    (a - b).abs() <= tolerance * a.abs().max(b.abs()).max(1e-9)
}

/// Under the CIE overcast sky (no sun) `eval` reads every sensor, zone and grid point,
/// its daylight part and its total with the lamp at 0.7, as `solve` does, and the grids'
/// figures likewise.
#[test]
fn eval_equals_solve_without_the_sun() {
    let (_dir, scene) = scene_file("overcast");
    let (basis, bytes) = build(&scene, ModeSelection::Count(16));
    let levels = LevelArgs {
        levels: vec!["lamp=0.7".into()],
        arcs: Vec::new(),
    };
    let args = sky(
        "2026-03-21T10:00",
        SkyInput::Cie {
            sky_type: 0,
            diffuse_horizontal: 12_000.0,
            direct_normal: 0.0,
        },
    );
    let eval = cli::eval_with_daylight(&basis, &bytes, &levels, Some(&args), false).unwrap();
    let solve = cli::solve_with_daylight(&scene, &levels, Some(&args), false, &no_cache()).unwrap();
    let (e, s) = (values(&eval), values(&solve));
    assert_eq!(e.len(), s.len());
    assert!(e.len() > 3, "sensors, zone and grid points");
    for (a, b) in e.iter().zip(&s) {
        assert_eq!(a.0, b.0);
        assert!(b.2 > 0.0, "{}: daylight reaches it", a.0);
        assert!(
            close(a.2, b.2, F32_SUMS),
            "{}: daylight {} vs {}",
            a.0,
            a.2,
            b.2
        );
        assert!(
            close(a.1, b.1, F32_SUMS),
            "{}: total {} vs {}",
            a.0,
            a.1,
            b.1
        );
    }
    for (a, b) in eval.grids.iter().zip(&solve.grids) {
        for (x, y) in [
            (&a.average, &b.average),
            (&a.minimum, &b.minimum),
            (&a.uniformity, &b.uniformity),
        ] {
            assert!(close(x[0], y[0], F32_SUMS), "{}: {x:?} vs {y:?}", a.zone);
        }
    }
    let (ed, sd) = (eval.daylight.unwrap(), solve.daylight.unwrap());
    assert_eq!(ed.time, sd.time, "the site's offset from the basis");
    assert_eq!(ed.patch_count, sd.patch_count);
    // `inspect --gains`: each sensor's and zone's daylight factor is its overcast daylight
    // per lux of diffuse horizontal illuminance.
    let gains = cli::gains(&basis, &bytes, cli::Units::Native).unwrap();
    // Each sensor's ratio to each zone under the overcast sky is the ratio of their
    // daylight factors; the clear sky and the sun (noon on an equinox) are read too.
    for r in &gains.ratios {
        let factor = |name: &str, list: &[cli::Gain]| {
            list.iter()
                .find(|g| g.name == name)
                .and_then(|g| g.per_daylight.as_ref())
                .map(|f| f[0])
                .expect("a daylight factor")
        };
        let expected = factor(&r.sensor, &gains.sensors) / factor(&r.zone, &gains.zones);
        assert_eq!(r.overcast, Some(expected), "{r:?}");
        assert!(r.clear_sky.is_some_and(|x| x > 0.0), "{r:?}");
        assert!(r.sun.is_some(), "{r:?}");
    }
    assert_eq!(gains.ratios.len(), gains.sensors.len() * gains.zones.len());
    for (g, x) in gains.sensors.iter().chain(&gains.zones).zip(&s) {
        let factor = g.per_daylight.as_ref().expect("a daylight factor")[0];
        assert!(
            close(factor * 12_000.0, x.2, F32_SUMS),
            "{}: {factor} vs {}",
            g.name,
            x.2 / 12_000.0
        );
    }
}

/// Before sunrise (21 June 03:30 at the site's +01:00, the sun 3.9° below the horizon)
/// `eval --time` reads the clear sky's light alone, as `solve --time` does: every sensor,
/// zone and grid point to `f32` ([`F32_SUMS`]), daylight above 0 everywhere, both with the
/// sun below the horizon and no direct light (the 60 000 lux given dropped, with a note).
/// The command refuses that clear sky (type 12) at noon without `--dni-lux`, naming it: its
/// sun would be left out.
#[test]
fn eval_equals_solve_before_sunrise() {
    let (_dir, scene) = scene_file("dawn");
    let (basis, bytes) = build(&scene, ModeSelection::Count(8));
    let levels = LevelArgs {
        levels: vec!["lamp=0".into()],
        arcs: Vec::new(),
    };
    let args = sky(
        "2026-06-21T03:30",
        SkyInput::Cie {
            sky_type: 12,
            diffuse_horizontal: 3_000.0,
            direct_normal: 60_000.0,
        },
    );
    let eval = cli::eval_with_daylight(&basis, &bytes, &levels, Some(&args), false).unwrap();
    let solve = cli::solve_with_daylight(&scene, &levels, Some(&args), false, &no_cache()).unwrap();
    for readout in [&eval, &solve] {
        let d = readout.daylight.as_ref().expect("daylight");
        assert!(d.sun_below_horizon && d.sun.altitude < 0.0, "{d:?}");
        assert_eq!(d.direct_normal_lux, 0.0);
        assert_eq!(d.notes.len(), 1, "{:?}", d.notes);
    }
    let b = basis.to_str().unwrap();
    let noon = [
        "eval",
        b,
        "--time",
        "2026-06-21T12:00",
        "--cie",
        "12",
        "--dhi-lux",
        "10000",
    ];
    let o = run(&noon);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    assert!(stderr(&o).contains("--dni-lux"), "{}", stderr(&o));
    let o = run(&[&noon[..], &["--dni-lux", "0"]].concat());
    assert!(o.status.success(), "{}", stderr(&o));
    let (e, s) = (values(&eval), values(&solve));
    assert_eq!(e.len(), s.len());
    for (a, b) in e.iter().zip(&s) {
        assert_eq!(a.0, b.0);
        assert!(b.2 > 0.0, "{}: daylight before sunrise", a.0);
        assert!(
            close(a.2, b.2, F32_SUMS),
            "{}: daylight {} vs {}",
            a.0,
            a.2,
            b.2
        );
    }
}

/// The exact response to the sun in room direction `sun` (per lux of direct normal
/// illuminance): every output's reading and every patch's exitance.
fn exact_sun(scene: &Path, sun: eigenrad_precompute::geometry::Vec3) -> (Vec<f64>, Vec<f64>) {
    let prepared = pipeline::prepare(scene, &no_cache()).unwrap();
    let occluders = Occluders::with_faces(&prepared.scene.patches, &prepared.scene.faces);
    let light = sun_light(
        &prepared.scene,
        &occluders,
        sun,
        &DaylightOptions::default(),
    );
    let model = Model::new(&prepared.system, Formulation::Split, 1, Solver::Auto).unwrap();
    let r = model.system.light_responses(0, &[light]).unwrap().remove(0);
    (r.readings, r.exitance)
}

/// With the sun at a node of the basis' grid and a dark sky, the runtime reads what the
/// exact solve of that sun gives, at every sensor, zone and grid point; and with all the
/// modes, the patches' exitance too, in either formulation.
#[test]
fn at_a_sun_node_the_runtime_is_exact() {
    sun_node_exact(Formulation::Split);
}

#[test]
fn at_a_sun_node_the_runtime_is_exact_in_the_seed_formulation() {
    sun_node_exact(Formulation::Seed);
}

/// The same with the sun's first reflection computed by the runtime (`--sun-first`): each
/// node stores its rest after the controller's own direct sun and first reflection and its
/// power as the controller computes it, so at a node the reading is exact again.
#[test]
fn at_a_sun_node_the_runtime_with_the_suns_first_reflection_is_exact() {
    sun_node_exact_with(Formulation::Split, true);
}

fn sun_node_exact(formulation: Formulation) {
    sun_node_exact_with(formulation, false);
}

fn sun_node_exact_with(formulation: Formulation, sun_first: bool) {
    let (_dir, scene) = scene_file(&format!("sun-node-{formulation:?}-{sun_first}"));
    let loaded = eigenrad_precompute::scene::load(&scene).unwrap();
    let n = loaded.patches.len();
    // The window and the lamp reflect nothing: the modes span the other patches.
    let reflecting = loaded.reflectance.iter().filter(|r| r[0] > 0.0).count();
    let (_basis, bytes) = build_with(&scene, ModeSelection::Count(n), formulation, sun_first);
    let basis = Basis::from_bytes(&bytes).unwrap();
    assert_eq!(
        eigenrad_runtime::sky::sun_first::SunFirst::stored(&basis),
        sun_first,
        "the sun's candidates stored as asked"
    );
    let grid = basis.sun_grid().unwrap();
    assert_eq!(basis.mode_count(), reflecting, "all the modes");
    // A stored node: the sun at noon in spring, or the first that lights the room.
    let site = eigenrad_precompute::scene::load(&scene)
        .unwrap()
        .site
        .unwrap();
    let node = (0..grid.len())
        .filter(|&k| {
            let (d, h) = grid.angles(k).unwrap();
            d.abs() < 6.0 && h.abs() < 16.0
        })
        .find(|&k| room_sun(&site, grid.direction(k).unwrap()).is_some())
        .expect("a node near noon at the equinox");
    let direction = grid.direction(node).unwrap();
    let state = SkyState {
        sky_luminance: vec![0.0; 145],
        global_horizontal: 0.0,
        sun: Some(Sun {
            direction,
            direct_normal: 1000.0,
        }),
    };
    let got = evaluate_daylight(&bytes, &state, &[0.0], true).unwrap();
    let (readings, exitance) = exact_sun(&scene, room_sun(&site, direction).unwrap());
    let read = got.outputs();
    assert_eq!(read.len(), readings.len());
    let peak = readings.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    assert!(peak > 0.0, "the sun lights the room");
    for (o, (a, b)) in read.iter().zip(&readings).enumerate() {
        let b = 1000.0 * b;
        assert!(
            (a - b).abs() <= F32_SUMS * b.abs().max(1e-3 * peak * 1000.0),
            "output {o}: {a} vs {b}"
        );
    }
    let exact: Vec<f64> = exitance.iter().map(|x| 1000.0 * x).collect();
    let area: Vec<f64> = eigenrad_precompute::scene::load(&scene)
        .unwrap()
        .patches
        .iter()
        .map(|p| p.area)
        .collect();
    let error = eigenrad_precompute::accuracy::metric::patch_error(&area, &got.exitance, &exact);
    assert!(
        error <= FULL_MODES,
        "patch exitance through all {n} modes: {error:.2e}"
    );
}

/// The same scene and flags build the same bytes, daylight included.
#[test]
fn daylight_bases_are_deterministic() {
    let (_dir, scene) = scene_file("deterministic");
    let (_, a) = build(&scene, ModeSelection::Count(8));
    let (_, b) = build(&scene, ModeSelection::Count(8));
    assert!(a == b, "two builds differ");
}

/// `eval --time` on a basis without daylight names --time and says why; a sky of other
/// patches than the basis' names --mf; neither panics.
#[test]
fn daylight_requests_a_basis_cannot_serve_are_errors() {
    let dir = scratch("daylight-errors");
    let plain = common::good_basis(&dir);
    let flags = [
        "--time",
        "2026-06-21T12:00+02:00",
        "--cie",
        "overcast",
        "--dhi-lux",
        "9000",
    ];
    let mut args = vec!["eval", plain.to_str().unwrap()];
    args.extend(flags);
    let o = run(&args);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("--time") && stderr(&o).contains("carries no daylight"),
        "{}",
        stderr(&o)
    );
    let (_d, scene) = scene_file("daylight-errors-mf");
    let (basis, _) = build(&scene, ModeSelection::Count(4));
    let mut args = vec!["eval", basis.to_str().unwrap()];
    args.extend(flags);
    args.extend(["--mf", "2"]);
    let o = run(&args);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("--mf") && stderr(&o).contains("MF:1"),
        "{}",
        stderr(&o)
    );
    assert!(!stderr(&o).contains("panicked"));
}

/// The area-weighted RMS error of a patch exitance `got` against `exact` over the patches
/// of `scene`.
fn patch_error_in(scene: &Path, got: &[f64], exact: &[f64]) -> f64 {
    let area: Vec<f64> = eigenrad_precompute::scene::load(scene)
        .unwrap()
        .patches
        .iter()
        .map(|p| p.area)
        .collect();
    eigenrad_precompute::accuracy::metric::patch_error(&area, got, exact)
}

/// Patch exitance under daylight from a basis of 16 modes (its first reflection stored, what
/// the room reflects after it through the modes) against the exact solve of the same mesh:
///
/// - under the CIE overcast sky (`eval --time` against `solve --time`, which computes the
///   daylight afresh), within the error the same 16 modes make for electric light set patch
///   by patch (the build report's worst case);
/// - under the sun at a node of the basis' grid, against the exact solve of that sun, within
///   [`REFLECTION_ROUNDING`] of the best the 16 modes can do once the first reflection is
///   exact: the exact first reflection (`System::initial_exitances`) plus the exact rest
///   projected on the modes, computed here on the host;
/// - both far closer (a fifth at most) than the modes alone carry the exact exitance, what
///   format version 6 stored.
#[test]
fn patch_exitance_under_daylight_is_as_close_as_under_electric_light() {
    let (_dir, scene) = scene_file("daylight-patches");
    let opts = BuildOptions {
        modes: ModeSelection::Count(16),
        form_factors: no_cache(),
        ..BuildOptions::default()
    };
    let (bytes, report) = pipeline::build(&scene, &opts).expect("build");
    let first = report.daylight.as_ref().unwrap().first_reflection.clone();
    let first = first.expect("a first reflection");
    assert!(first.rank > 0 && first.sky_error <= opts.sky_rank_tolerance);
    let electric = report
        .accuracy
        .iter()
        .map(|c| c.patch_error)
        .fold(0.0f64, f64::max);
    assert!(
        electric > 0.0,
        "exitance set patch by patch goes through the modes"
    );
    let basis = scene.with_extension("basis");
    std::fs::write(&basis, &bytes).unwrap();
    let off = LevelArgs {
        levels: vec!["lamp=0".into()],
        arcs: Vec::new(),
    };
    let args = sky(
        "2026-03-21T10:00",
        SkyInput::Cie {
            sky_type: 0,
            diffuse_horizontal: 12_000.0,
            direct_normal: 0.0,
        },
    );
    let exitance = |r: &cli::Readout| -> Vec<f64> {
        let patches = r.patches.as_ref().expect("patches");
        patches.iter().map(|p| p.exitance[0]).collect()
    };
    let eval = cli::eval_with_daylight(&basis, &bytes, &off, Some(&args), true).unwrap();
    let solve = cli::solve_with_daylight(&scene, &off, Some(&args), true, &no_cache()).unwrap();
    let overcast = patch_error_in(&scene, &exitance(&eval), &exitance(&solve));
    // The sun alone at a stored node near noon at the equinox.
    let decoded = Basis::from_bytes(&bytes).unwrap();
    let grid = decoded.sun_grid().unwrap();
    let site = eigenrad_precompute::scene::load(&scene)
        .unwrap()
        .site
        .unwrap();
    let node = (0..grid.len())
        .filter(|&k| {
            let (d, h) = grid.angles(k).unwrap();
            d.abs() < 6.0 && h.abs() < 16.0
        })
        .find(|&k| room_sun(&site, grid.direction(k).unwrap()).is_some())
        .expect("a node near noon at the equinox");
    let direction = grid.direction(node).unwrap();
    let state = SkyState {
        sky_luminance: vec![0.0; 145],
        global_horizontal: 0.0,
        sun: Some(Sun {
            direction,
            direct_normal: 1.0,
        }),
    };
    let got = evaluate_daylight(&bytes, &state, &[0.0], true).unwrap();
    let (_, exact) = exact_sun(&scene, room_sun(&site, direction).unwrap());
    let sun = patch_error_in(&scene, &got.exitance, &exact);
    // The modes alone: the exact exitance projected on the same 16 modes.
    let prepared = pipeline::prepare(&scene, &no_cache()).unwrap();
    let model = Model::new(&prepared.system, Formulation::Split, 16, Solver::Auto).unwrap();
    let through_modes = |m: &[f64]| -> Vec<f64> {
        let a = model.mode_amplitudes(0, m, 16);
        let v = &model.bands[0].modes.vectors;
        (0..m.len())
            .map(|i| (0..v.ncols()).map(|k| v[(i, k)] * a[k]).sum())
            .collect()
    };
    let sun_modes_alone = patch_error_in(&scene, &through_modes(&exact), &exact);
    // The best 16 modes do with the first reflection exact.
    let occluders = Occluders::with_faces(&prepared.scene.patches, &prepared.scene.faces);
    let light = sun_light(
        &prepared.scene,
        &occluders,
        room_sun(&site, direction).unwrap(),
        &DaylightOptions::default(),
    );
    let first_reflection = prepared.system.initial_exitances(0, &[light]).remove(0);
    let rest: Vec<f64> = exact
        .iter()
        .zip(&first_reflection)
        .map(|(m, m0)| m - m0)
        .collect();
    let best: Vec<f64> = through_modes(&rest)
        .iter()
        .zip(&first_reflection)
        .map(|(r, m0)| r + m0)
        .collect();
    let sun_best = patch_error_in(&scene, &best, &exact);
    let overcast_modes_alone =
        patch_error_in(&scene, &through_modes(&exitance(&solve)), &exitance(&solve));
    println!(
        "patch exitance at 16 modes: overcast {overcast:.2e} (modes alone {overcast_modes_alone:.2e}), sun {sun:.2e} (best {sun_best:.2e}, modes alone {sun_modes_alone:.2e}); electric light set patch by patch {electric:.2e}; sky rank {}",
        first.rank
    );
    assert!(
        overcast <= electric,
        "overcast {overcast:.2e} vs {electric:.2e}"
    );
    assert!(
        (sun - sun_best).abs() <= REFLECTION_ROUNDING,
        "sun {sun:.2e} vs the modes' best {sun_best:.2e}"
    );
    assert!(overcast < 0.2 * overcast_modes_alone);
    assert!(sun < 0.2 * sun_modes_alone);
}

/// Every reading's response to a unit of first reflection on a patch
/// (`sun_first_responses`, one adjoint solve per reading), against the reading of the
/// exact forward solve of that patch's unit exitance alone, `R_o (I − R F)⁻¹ e_j`, for a
/// patch of each kind (floor, wall, ceiling of the daylit test room, with a zone made of its
/// floor): within 1e-9 of the largest response.
#[test]
fn responses_to_the_first_reflection_are_the_forward_solves() {
    let dir = scratch("responses");
    let scene = dir.join("daylit.toml");
    // With a zone of surfaces, whose rows take its patches' own irradiance too.
    let text = format!(
        "{}\n[[zone]]\nname = \"floor\"\nsurfaces = [\"room.floor\"]\n",
        daylit_room(VIENNA)
    );
    std::fs::write(&scene, text).expect("write scene");
    let prepared = pipeline::prepare(&scene, &no_cache()).unwrap();
    let system = &prepared.system;
    let n = system.area.len();
    let rho = &system.reflectance[0];
    let readings = system.output_rows.len();
    let candidates: Vec<u32> = (0..n as u32).filter(|&j| rho[j as usize] > 0.0).collect();
    let t = eigenrad_precompute::sources::daylight::sun_first::sun_first_responses(
        &prepared.scene,
        system,
        &candidates,
        readings,
    )
    .unwrap();
    assert_eq!(t.len(), candidates.len() * readings);
    let largest = t.iter().fold(0.0f64, |a, &b| a.max(b.abs()));
    let solver = system.solver(0).unwrap();
    let mut checked = 0;
    for surface in ["room.floor", "room.wall_ymax", "room.ceiling"] {
        let Some(j) = (0..n).find(|&j| {
            prepared.scene.surfaces[prepared.scene.patches[j].surface].name == surface
                && rho[j] > 0.0
        }) else {
            continue;
        };
        let mut e = vec![0.0; n];
        e[j] = 1.0;
        let m = solver.solve(&e);
        let forward = system.outputs(&m);
        let k = candidates.binary_search(&(j as u32)).unwrap();
        for (o, want) in forward.iter().enumerate() {
            let mut want = *want;
            // A zone of surfaces also takes the patch's own irradiance, `1 / ρ_j` per unit
            // of its exitance, in its area-weighted mean.
            if let Some(z) = o.checked_sub(prepared.scene.sensors.len()) {
                if let Some(zone) = prepared.scene.zones.get(z) {
                    if let eigenrad_precompute::scene::ZoneKind::Surfaces(members) = &zone.kind {
                        if members.contains(&j) {
                            let area: f64 = members.iter().map(|&i| system.area[i]).sum();
                            want += system.area[j] / (area * rho[j]);
                        }
                    }
                }
            }
            let got = t[k * readings + o];
            assert!(
                (got - want).abs() <= 1e-9 * largest,
                "{surface} patch {j}, reading {o}: {got} against {want}"
            );
        }
        checked += 1;
    }
    assert_eq!(checked, 3, "kinds of patch found");
}
