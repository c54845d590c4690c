//! Sensor grids imported from a Honeybee model (`[[import]]`, docs/scene.md "Importing a
//! building model", "Sensor grids"):
//!
//! - a grid whose points are those of the TOML work plane's grid of the same room reads what
//!   that grid reads, point by point and in its figures, under luminaires and an overcast sky
//!   (within [`SAME_POINTS`]); its zone reads the mean of its points;
//! - a grid facing sideways and askew (vertical illuminance at a façade) reads what
//!   `[[sensor]]`s at the same points with the same normals read;
//! - honeybee-schema's `model_radiance_grid_views` sample imports with its two grids, builds,
//!   and the runtime reads them as the exact solve does (within [`RUNTIME_RTOL`]);
//! - sensors outside their room, a `room_identifier` not in the model, an unknown grid name,
//!   a zero direction and a duplicate zone name are refused naming the file, the grid and the
//!   sensor; a sensor inside a block is left out and counted; `sensor_grids = false` and a
//!   room not imported leave grids out.
//!
//! Run with `cargo test --test import_grids -- --nocapture` to see the figures.

mod common;

use std::path::{Path, PathBuf};

use common::l_office::{self, root};

use eigenrad_precompute::cli::{self, DaylightArgs, LevelArgs, Readout, SkyInput};
use eigenrad_precompute::formfactor::FormFactorOptions;
use eigenrad_precompute::pipeline::{self, BuildOptions, ModeSelection};
use eigenrad_precompute::radiosity::eigen::Solver;
use eigenrad_precompute::scene::{load, ZoneKind};

/// The same receivers in the same room: the same f64 sums, the room's patches possibly in
/// another order (the TOML and the imported room), 1e-9 relative.
const SAME_POINTS: f64 = 1e-9;
/// Through the runtime with every mode kept: f32 storage and arithmetic (tests/grids.rs).
const RUNTIME_RTOL: f64 = 2e-5;

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!(
        "eigenrad-import-grids-{}-{name}",
        std::process::id()
    ));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// The L-office's Honeybee model with `grids` as its sensor grids.
fn model_with(grids: serde_json::Value) -> serde_json::Value {
    let text = std::fs::read_to_string(root().join("examples/import/l-office.hbjson")).unwrap();
    let mut model: serde_json::Value = serde_json::from_str(&text).unwrap();
    model["properties"]["radiance"]["sensor_grids"] = grids;
    model
}

fn write_model(dir: &Path, model: &serde_json::Value) -> PathBuf {
    let path = dir.join("model.hbjson");
    std::fs::write(&path, serde_json::to_string_pretty(model).unwrap()).unwrap();
    path
}

fn sensors_json(points: &[([f64; 3], [f64; 3])]) -> serde_json::Value {
    points
        .iter()
        .map(|(p, d)| serde_json::json!({"pos": p, "dir": d}))
        .collect()
}

/// The exact solve under the west wing at full level, the east at half and the CIE overcast
/// sky of 10 klx.
fn solved(scene: &Path) -> Readout {
    let levels = LevelArgs {
        levels: vec!["west=1".into(), "east=0.5".into()],
        arcs: Vec::new(),
    };
    let sky = DaylightArgs {
        time: "2026-03-21T10:00".into(),
        input: SkyInput::Cie {
            sky_type: 0,
            diffuse_horizontal: 10_000.0,
            direct_normal: 0.0,
        },
        water: 2.0,
        subdivision: 1,
    };
    let no_cache = FormFactorOptions {
        cache: None,
        ..FormFactorOptions::default()
    };
    cli::solve_with_daylight(scene, &levels, Some(&sky), false, &no_cache)
        .unwrap_or_else(|e| panic!("{}: {e:#}", scene.display()))
}

fn close(a: f64, b: f64, tolerance: f64) -> bool {
    (a - b).abs() <= tolerance * a.abs().max(b.abs())
}

/// Electric and daylight readings of grid `zone`'s points.
fn grid_points(r: &Readout, zone: &str) -> Vec<(f64, f64)> {
    let k = r.grids.iter().position(|g| g.zone == zone).unwrap();
    let day = &r.daylight.as_ref().unwrap().grids[k];
    (r.grids[k].points.iter().zip(&day.points))
        .map(|(p, d)| (p.irradiance[0], d.irradiance[0]))
        .collect()
}

/// Electric and daylight reading of the sensor or zone `name`.
fn reading(r: &Readout, name: &str) -> (f64, f64) {
    let x = r.sensors.iter().chain(&r.zones).find(|x| x.name == name);
    let x = x.unwrap_or_else(|| panic!("no sensor or zone `{name}`"));
    (x.irradiance[0], x.daylight.as_ref().unwrap()[0])
}

/// Façade points: two facing the south windows, one the east window, one askew (south-east
/// and 30° down), one at the west wall facing north.
fn facade() -> Vec<([f64; 3], [f64; 3])> {
    let (c, s) = (30f64.to_radians().cos(), 30f64.to_radians().sin());
    let h = std::f64::consts::FRAC_1_SQRT_2;
    vec![
        ([3.0, 1.0, 1.5], [0.0, -1.0, 0.0]),
        ([9.0, 1.0, 1.5], [0.0, -1.0, 0.0]),
        ([11.0, 2.0, 1.5], [1.0, 0.0, 0.0]),
        ([10.0, 2.5, 1.2], [c * h, -c * h, -s]),
        ([0.5, 6.0, 1.2], [0.0, 1.0, 0.0]),
    ]
}

#[test]
fn an_imported_grid_reads_as_the_toml_grid_and_sensors() {
    let dir = scratch("same");
    let toml = dir.join("toml.toml");
    std::fs::write(&toml, l_office::scene(None)).unwrap();
    let plane: Vec<([f64; 3], [f64; 3])> = load(&toml).unwrap().zones[0]
        .grid
        .as_ref()
        .unwrap()
        .points()
        .map(|(p, n)| (p.to_array(), n.to_array()))
        .collect();
    let model = model_with(serde_json::json!([
        {"type": "SensorGrid", "identifier": "plane_grid", "display_name": "plane",
         "room_identifier": "office", "sensors": sensors_json(&plane)},
        {"type": "SensorGrid", "identifier": "facade", "sensors": sensors_json(&facade())},
    ]));
    let path = write_model(&dir, &model);
    let mut text = l_office::scene(Some(&format!(
        "[[import]]\nfile = {:?}\n",
        path.display().to_string()
    )));
    for (k, (p, n)) in facade().iter().enumerate() {
        text += &format!("\n[[sensor]]\nname = \"v{k}\"\nposition = {p:?}\nnormal = {n:?}\n");
    }
    let imported = dir.join("imported.toml");
    std::fs::write(&imported, text).unwrap();
    let scene = load(&imported).unwrap();
    let names: Vec<&str> = scene.zones.iter().map(|z| z.name.as_str()).collect();
    assert_eq!(names, ["work_plane", "plane", "facade"]);
    assert!(matches!(scene.zones[2].kind, ZoneKind::Points { .. }));
    // Runs of one direction: south twice, east, askew, north.
    assert_eq!(scene.zones[2].grid.as_ref().unwrap().pieces.len(), 4);

    let (a, b) = (solved(&toml), solved(&imported));
    // The work plane's grid, from the TOML room, against the imported grid at its points.
    let (want, got) = (grid_points(&a, "work_plane"), grid_points(&b, "plane"));
    assert_eq!(want.len(), got.len());
    for (k, (w, g)) in want.iter().zip(&got).enumerate() {
        assert!(g.1 > 0.0, "point {k}: daylight reaches it");
        for (x, y) in [(w.0, g.0), (w.1, g.1)] {
            assert!(close(x, y, SAME_POINTS), "point {k}: {x} vs {y}");
        }
    }
    let figures = |r: &Readout, zone: &str| {
        let g = r.grids.iter().find(|g| g.zone == zone).unwrap();
        [g.average[0], g.minimum[0], g.maximum[0], g.uniformity[0]]
    };
    for (x, y) in figures(&a, "work_plane").iter().zip(figures(&b, "plane")) {
        assert!(close(*x, y, SAME_POINTS), "figures: {x} vs {y}");
    }
    // The zone reads the mean of its points: the work-plane grid's E_avg.
    let mean = |v: &[(f64, f64)]| {
        let n = v.len() as f64;
        (
            v.iter().map(|p| p.0).sum::<f64>() / n,
            v.iter().map(|p| p.1).sum::<f64>() / n,
        )
    };
    let (zone, grid) = (reading(&b, "plane"), mean(&want));
    assert!(close(zone.0, grid.0, SAME_POINTS) && close(zone.1, grid.1, SAME_POINTS));
    assert!(close(zone.0, figures(&a, "work_plane")[0], SAME_POINTS));

    // The façade grid against sensors with the same normals, in the same scene.
    let points = grid_points(&b, "facade");
    for (k, p) in points.iter().enumerate() {
        let s = reading(&b, &format!("v{k}"));
        assert!(p.1 > 0.0, "façade point {k}: daylight reaches it");
        assert!(
            close(s.0, p.0, SAME_POINTS) && close(s.1, p.1, SAME_POINTS),
            "façade point {k}: {p:?} vs sensor {s:?}"
        );
    }
    let zone = reading(&b, "facade");
    let grid = mean(&points);
    assert!(close(zone.0, grid.0, SAME_POINTS) && close(zone.1, grid.1, SAME_POINTS));
    // Facing the south window and facing the west wall read differently: a vertical reading,
    // not the plane's.
    assert!(points[0].1 > 2.0 * points[4].1, "{points:?}");
    println!(
        "{} plane points and {} façade points as the TOML grid and sensors; façade E_v {:.1} \
         lux (daylight {:.1} lux) at the south window",
        got.len(),
        points.len(),
        points[0].0,
        points[0].1
    );
    std::fs::remove_dir_all(&dir).ok();
}

/// honeybee-schema's sample of two rooms (a house and a garage, 5 m × 10 m × 3 m side by
/// side) with a 0.5 m grid of 200 upward sensors in each, at 1 m.
#[test]
fn the_honeybee_sample_imports_with_its_grids_and_the_runtime_reads_them() {
    let dir = scratch("sample");
    let model = root().join("examples/import/honeybee/model_radiance_grid_views.hbjson");
    let text = format!(
        r#"[scene]
name = "tiny-house"
bands = "photopic"
unit = "m"
max_edge = 2.5

[materials]
wall = {{ reflectance = 0.5 }}
floor = {{ reflectance = 0.2 }}
ceiling = {{ reflectance = 0.7 }}

[[import]]
file = {:?}
materials = {{ Floor = "floor", Wall = "wall", RoofCeiling = "ceiling", Aperture = "wall" }}

[[channel]]
name = "ceilings"
surfaces = ["Tiny_House_Zone.ceiling", "Tiny_Garage.ceiling"]
flux = 5000
"#,
        model.display().to_string()
    );
    let path = dir.join("scene.toml");
    std::fs::write(&path, text).unwrap();
    let scene = load(&path).unwrap();
    assert!(scene.warnings.is_empty(), "{:?}", scene.warnings);
    let grids: Vec<(&str, usize, usize)> = scene
        .zones
        .iter()
        .map(|z| {
            let g = z.grid.as_ref().unwrap();
            (z.name.as_str(), g.len(), g.pieces.len())
        })
        .collect();
    assert_eq!(
        grids,
        [("Tiny_House_Zone", 200, 1), ("Tiny_Garage", 200, 1)]
    );
    let piece = &scene.zones[0].grid.as_ref().unwrap().pieces[0];
    assert_eq!((piece.counts, piece.spacing), ([200, 1], 0.5));

    let levels = LevelArgs {
        levels: Vec::new(),
        arcs: Vec::new(),
    };
    let exact = cli::solve(&path, &levels, false, &FormFactorOptions::default()).unwrap();
    let opts = BuildOptions {
        modes: ModeSelection::Count(scene.patches.len()),
        solver: Solver::Dense,
        ..BuildOptions::default()
    };
    let (bytes, report) = pipeline::build(&path, &opts).unwrap();
    assert_eq!(report.grids.len(), 2);
    let eval = cli::eval(&path, &bytes, &levels, false).unwrap();
    for (e, x) in eval.grids.iter().zip(&exact.grids) {
        assert_eq!((e.zone.as_str(), e.points.len()), (x.zone.as_str(), 200));
        for (p, q) in e.points.iter().zip(&x.points) {
            assert!(q.irradiance[0] > 0.0);
            assert!(close(p.irradiance[0], q.irradiance[0], RUNTIME_RTOL));
        }
        let f = |g: &cli::Readout, k: usize| -> [f64; 4] {
            let g = &g.grids[k];
            [g.average[0], g.minimum[0], g.maximum[0], g.uniformity[0]]
        };
        let k = exact.grids.iter().position(|g| g.zone == x.zone).unwrap();
        for (a, b) in f(&eval, k).iter().zip(f(&exact, k)) {
            assert!(close(*a, b, RUNTIME_RTOL), "{}: {a} vs {b}", x.zone);
        }
        // The zone reads its grid's mean.
        let zone = exact.zones.iter().find(|z| z.name == x.zone).unwrap();
        assert!(close(zone.irradiance[0], x.average[0], SAME_POINTS));
    }
    // Each zone's area: a 0.5 m cell per sensor, the 50 m² floor its grid covers.
    let info = cli::inspect(&path, &bytes).unwrap();
    for (name, area) in &info.zones {
        assert!((f64::from(*area) - 50.0).abs() < 1e-4, "{name}: {area} m²");
    }
    println!(
        "{}: E_avg {:.1} lux, U_o {:.3} (runtime {:.1} lux)",
        exact.grids[0].zone,
        exact.grids[0].average[0],
        exact.grids[0].uniformity[0],
        eval.grids[0].average[0]
    );
    std::fs::remove_dir_all(&dir).ok();
}

/// A bare scene importing the L-office's model with `grids`, and the scene's own `extra`
/// lines.
fn bare(name: &str, grids: serde_json::Value, extra: &str) -> (PathBuf, PathBuf) {
    let dir = scratch(name);
    let model = write_model(&dir, &model_with(grids));
    let scene = dir.join("scene.toml");
    std::fs::write(
        &scene,
        format!(
            "[scene]\nname = \"bad\"\nbands = \"photopic\"\nunit = \"m\"\nmax_edge = 2.0\n\n\
             [[import]]\nfile = \"model.hbjson\"\n{extra}"
        ),
    )
    .unwrap();
    (scene, model)
}

fn refused(name: &str, grids: serde_json::Value, extra: &str) -> (String, PathBuf) {
    let (scene, model) = bare(name, grids, extra);
    let e = load(&scene).expect_err("refused").to_string();
    println!("{name}: {e}");
    (e, model)
}

/// The 1-based line of `"identifier": "<id>"` in the model file at `path`.
fn line_of(path: &Path, id: &str) -> usize {
    let text = std::fs::read_to_string(path).unwrap();
    let needle = format!("\"identifier\": \"{id}\"");
    text[..text.find(&needle).unwrap()].matches('\n').count() + 1
}

fn desks(points: &[[f64; 3]]) -> serde_json::Value {
    let up: Vec<([f64; 3], [f64; 3])> = points.iter().map(|&p| (p, [0.0, 0.0, 1.0])).collect();
    serde_json::json!([{"type": "SensorGrid", "identifier": "desks",
        "room_identifier": "office", "sensors": sensors_json(&up)}])
}

#[test]
fn a_sensor_outside_its_room_is_refused_naming_the_grid_and_the_sensor() {
    // The third sensor in the L's notch: inside the bounding box, outside the room.
    let (e, model) = refused(
        "outside",
        desks(&[[1.0, 1.0, 0.8], [2.0, 1.0, 0.8], [10.0, 6.0, 0.8]]),
        "",
    );
    let at = format!("{}:{}", model.display(), line_of(&model, "desks"));
    for part in [
        &at[..],
        "sensor grid `desks`, sensor 2",
        "outside its room",
        "[10.0, 6.0, 0.8]",
    ] {
        assert!(e.contains(part), "{part}: {e}");
    }
    // Without a room_identifier: outside every room.
    let mut grids = desks(&[[1.0, 1.0, 0.8], [1.0, 1.0, 3.5]]);
    grids[0].as_object_mut().unwrap().remove("room_identifier");
    let (e, _) = refused("outside-every", grids, "");
    assert!(
        e.contains("sensor 1") && e.contains("outside every room"),
        "{e}"
    );
}

#[test]
fn a_grid_the_model_or_the_scene_cannot_place_is_refused() {
    let mut grids = desks(&[[1.0, 1.0, 0.8]]);
    grids[0]["room_identifier"] = "attic".into();
    let (e, _) = refused("unknown-room", grids, "");
    assert!(
        e.contains("room_identifier `attic`") && e.contains("office"),
        "{e}"
    );

    let (e, _) = refused(
        "unknown-name",
        desks(&[[1.0, 1.0, 0.8]]),
        "sensor_grids = [\"tables\"]\n",
    );
    assert!(e.contains("import.sensor_grids") && e.contains("unknown sensor grid `tables`"));
    assert!(e.contains("its sensor grids: desks"), "{e}");

    let mut grids = desks(&[[1.0, 1.0, 0.8], [2.0, 1.0, 0.8]]);
    grids[0]["sensors"][1]["dir"] = serde_json::json!([0, 0, 0]);
    let (e, model) = refused("zero-dir", grids, "");
    assert!(e.contains(&model.display().to_string()), "{e}");
    assert!(
        e.contains("sensor grid `desks`, sensor 1") && e.contains("`dir`"),
        "{e}"
    );

    let mut grids = desks(&[[1.0, 1.0, 0.8]]);
    grids[0]["sensors"][0]["pos"] = serde_json::json!([1, 1]);
    let (e, _) = refused("short-pos", grids, "");
    assert!(e.contains("sensor 0") && e.contains("`pos`"), "{e}");

    let (e, _) = refused(
        "duplicate",
        desks(&[[1.0, 1.0, 0.8]]),
        "\n[[zone]]\nname = \"desks\"\nsurfaces = [\"office.floor\"]\n",
    );
    assert!(e.contains("desks") && e.contains("model.hbjson"), "{e}");
}

#[test]
fn sensors_in_a_block_are_left_out_and_grids_can_be_turned_off() {
    let points = [[1.0, 1.0, 0.8], [3.5, 4.0, 0.8], [5.0, 1.0, 0.8]];
    let column = "\n[materials]\ncolumn = { reflectance = 0.6 }\n\n[[block]]\nname = \"column\"\n\
                  min = [3.3, 3.8, 0]\nmax = [3.7, 4.2, 3]\nmaterial = \"column\"\n\
                  bottom = false\ntop = false\n";
    let (scene, _) = bare("column", desks(&points), column);
    let scene = load(&scene).unwrap();
    let grid = scene.zones[0].grid.as_ref().unwrap();
    assert_eq!((grid.len(), grid.obstructed), (2, 1));

    let (scene, _) = bare("off", desks(&points), "sensor_grids = false\n");
    assert!(load(&scene).unwrap().zones.is_empty());
    let (scene, _) = bare("named", desks(&points), "sensor_grids = [\"desks\"]\n");
    assert_eq!(load(&scene).unwrap().zones.len(), 1);

    // A grid of a room the import leaves out: left out with a warning, or refused when named.
    let model = root().join("examples/import/honeybee/model_radiance_grid_views.hbjson");
    let dir = scratch("garage");
    let scene = dir.join("scene.toml");
    let write = |extra: &str| {
        std::fs::write(
            &scene,
            format!(
                "[scene]\nname = \"garage\"\nbands = \"photopic\"\nunit = \"m\"\n\
                 max_edge = 2.5\n\n[materials]\nwall = {{ reflectance = 0.5 }}\n\n\
                 [[import]]\nfile = {:?}\nspaces = [\"Tiny_Garage\"]\n\
                 materials = {{ Floor = \"wall\", Wall = \"wall\", RoofCeiling = \"wall\", \
                 Aperture = \"wall\" }}\n{extra}",
                model.display().to_string()
            ),
        )
        .unwrap();
    };
    write("");
    let s = load(&scene).unwrap();
    let zones: Vec<&str> = s.zones.iter().map(|z| z.name.as_str()).collect();
    assert_eq!(zones, ["Tiny_Garage"]);
    assert!(
        s.warnings
            .iter()
            .any(|w| w.contains("sensor grid `Tiny_House_Zone`") && w.contains("not imported")),
        "{:?}",
        s.warnings
    );
    write("sensor_grids = [\"Tiny_House_Zone\"]\n");
    let e = load(&scene).expect_err("refused").to_string();
    assert!(
        e.contains("Tiny_House_Zone") && e.contains("leaves out"),
        "{e}"
    );
    std::fs::remove_dir_all(&dir).ok();
}
