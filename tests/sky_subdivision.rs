//! The sky's patches a basis stores (`eigenrad build --mf N`, `--sky-tolerance T`), against
//! the exact solve of the same mesh and sky (`eigenrad solve --time --mf N`), which computes
//! its daylight afresh on the same patches:
//!
//! - a basis of Reinhart MF:2 holds its 577 patches, the runtime fills them from its sky
//!   models, and every sensor, zone and grid point reads as the exact solve does to `f32`
//!   ([`F32_SUMS`]); asked for another subdivision it is an error naming `--mf`;
//! - `--sky-tolerance` takes the coarsest candidate whose discretisation error (measured
//!   here too, from the sky responses) meets it, reports it, and refuses a tolerance the
//!   finest candidate misses, naming the flag.

mod common;

use std::path::{Path, PathBuf};

use common::{daylit_room, run, scratch, stderr, VIENNA};
use eigenrad_precompute::accuracy::sky::discretisation;
use eigenrad_precompute::cli::{self, DaylightArgs, LevelArgs, SkyInput};
use eigenrad_precompute::formfactor::{FormFactorOptions, Occluders};
use eigenrad_precompute::pipeline::{self, BuildOptions, ModeSelection, SkySelection};
use eigenrad_precompute::sources::daylight::{sky_response, DaylightOptions};
use eigenrad_runtime::sky::patches::SkyPatches;

/// Relative difference of an `f32` sum over the ~600 daylight nodes from the same sum in
/// `f64`: a few hundred roundings of 6e-8 (as for Tregenza's 145 in `daylight_basis.rs`).
const F32_SUMS: f64 = 2e-5;

fn no_cache() -> FormFactorOptions {
    FormFactorOptions {
        cache: None,
        ..FormFactorOptions::default()
    }
}

/// The daylit test room with the Vienna site, meshed coarser (the sky's responses at up to
/// 9217 patches are the cost here), written to a scratch folder.
fn scene_file(test: &str) -> (PathBuf, PathBuf) {
    let dir = scratch(test);
    let path = dir.join("daylit.toml");
    let scene = daylit_room(VIENNA).replace("max_edge = 0.7", "max_edge = 1.0");
    std::fs::write(&path, scene).expect("write scene");
    (dir, path)
}

fn build(scene: &Path, sky: SkySelection) -> (Vec<u8>, pipeline::BuildReport) {
    let opts = BuildOptions {
        modes: ModeSelection::Count(8),
        sky,
        form_factors: no_cache(),
        ..BuildOptions::default()
    };
    pipeline::build(scene, &opts).expect("build")
}

fn overcast(subdivision: u8) -> DaylightArgs {
    DaylightArgs {
        time: "2026-03-21T10:00".to_owned(),
        input: SkyInput::Cie {
            sky_type: 0,
            diffuse_horizontal: 12_000.0,
            direct_normal: 0.0,
        },
        water: 2.0,
        subdivision,
    }
}

/// Every sensor's and zone's daylight part, then every grid point's.
fn daylight(r: &cli::Readout) -> Vec<(String, f64)> {
    let mut out: Vec<(String, f64)> = r
        .sensors
        .iter()
        .chain(&r.zones)
        .map(|x| (x.name.clone(), x.daylight.as_ref().expect("daylight")[0]))
        .collect();
    for g in &r.daylight.as_ref().expect("daylight").grids {
        for (i, p) in g.points.iter().enumerate() {
            out.push((format!("{} point {i}", g.zone), p.irradiance[0]));
        }
    }
    out
}

#[test]
fn a_basis_of_mf2_reads_as_the_exact_solve_of_mf2() {
    let (_dir, scene) = scene_file("sky-mf2");
    let (bytes, report) = build(&scene, SkySelection::Subdivision(2));
    let d = report.daylight.expect("a daylight section");
    assert_eq!((d.sky, d.sky_patches), ("reinhart MF:2".to_owned(), 577));
    assert!(d.sky_discretisation.is_none(), "--mf is taken unchecked");
    let basis = scene.with_extension("basis");
    std::fs::write(&basis, &bytes).expect("write basis");
    let levels = LevelArgs {
        levels: vec!["lamp=0".into()],
        arcs: Vec::new(),
    };
    let eval =
        cli::eval_with_daylight(&basis, &bytes, &levels, Some(&overcast(2)), false).expect("eval");
    let solve = cli::solve_with_daylight(&scene, &levels, Some(&overcast(2)), false, &no_cache())
        .expect("solve");
    let (e, s) = (daylight(&eval), daylight(&solve));
    assert_eq!(e.len(), s.len());
    assert!(e.len() > 3, "sensors, zone and grid points");
    for ((name, a), (_, b)) in e.iter().zip(&s) {
        assert!(*b > 0.0, "{name} sees daylight");
        assert!(
            (a - b).abs() <= F32_SUMS * b,
            "{name}: basis {a} against the exact {b} lux"
        );
    }
    // The basis' subdivision is part of what it is: another one is refused.
    let o = run(&[
        "eval",
        basis.to_str().unwrap(),
        "--time",
        "2026-03-21T10:00",
        "--cie",
        "overcast",
        "--dhi-lux",
        "12000",
    ]);
    assert!(!o.status.success());
    assert!(
        stderr(&o).contains("--mf") && stderr(&o).contains("MF:2"),
        "{}",
        stderr(&o)
    );
}

#[test]
fn the_sky_tolerance_takes_the_coarsest_subdivision_that_meets_it() {
    let (_dir, scene) = scene_file("sky-tolerance");
    // The errors the build will measure, from the room's own sky responses.
    let loaded = pipeline::prepare(&scene, &no_cache()).expect("prepare");
    let occluders = Occluders::with_faces(&loaded.scene.patches, &loaded.scene.faces);
    let response = |n| {
        sky_response(
            &loaded.scene,
            &occluders,
            SkyPatches::reinhart(n).unwrap(),
            &DaylightOptions::default(),
        )
    };
    let [one, two, four] = [1, 2, 4].map(response);
    let e1 = discretisation(&one, &two).unwrap();
    let e2 = discretisation(&two, &four).unwrap();
    assert!(e1.readings > 0 && e1.max > 0.0, "{e1:?}");
    assert!(e2.max < e1.max, "the error shrinks: {e2:?} against {e1:?}");

    // A tolerance MF:1 meets keeps Tregenza's 145 patches and says how close they are.
    let (_, report) = build(&scene, SkySelection::Tolerance(1.01 * e1.max));
    let d = report.daylight.expect("daylight");
    assert_eq!(d.sky_patches, 145);
    assert_eq!(d.sky_discretisation.as_ref(), Some(&e1));
    // Between the two, MF:2.
    let (_, report) = build(&scene, SkySelection::Tolerance(0.5 * (e1.max + e2.max)));
    let d = report.daylight.expect("daylight");
    assert_eq!(d.sky_patches, 577);
    assert_eq!(d.sky_discretisation.as_ref(), Some(&e2));
}

#[test]
fn a_sky_tolerance_no_candidate_meets_is_an_error_naming_it() {
    let (dir, scene) = scene_file("sky-tolerance-missed");
    let opts = BuildOptions {
        modes: ModeSelection::Count(4),
        sky: SkySelection::Tolerance(1e-9),
        form_factors: no_cache(),
        ..BuildOptions::default()
    };
    let err = pipeline::build(&scene, &opts)
        .expect_err("no candidate meets 1e-9")
        .to_string();
    assert!(
        err.contains("--sky-tolerance") && err.contains("MF:4") && err.contains("MF:8"),
        "{err}"
    );
    // Flags out of range are refused before any work, naming the flag; nothing is written.
    let out = dir.join("out.basis");
    for bad in [["--mf", "0"], ["--mf", "9"], ["--sky-tolerance", "0"]] {
        let mut args = vec![
            "build",
            scene.to_str().unwrap(),
            "-o",
            out.to_str().unwrap(),
        ];
        args.extend(bad);
        let o = run(&args);
        assert!(
            !o.status.success() && stderr(&o).contains(bad[0]),
            "{}",
            stderr(&o)
        );
    }
    assert!(!out.exists(), "nothing written");
}
