//! Rooms imported from a building model (`[[import]]`, docs/scene.md "Importing a building
//! model"):
//!
//! - the L-shaped office of `examples/l-office/` written as a Honeybee model
//!   (`examples/import/l-office.hbjson`) gives the same room as its TOML: the same patches,
//!   and the same sensor, zone and grid readings under luminaires and an overcast sky
//!   (within [`SAME_ROOM`]), its imported windows passing daylight;
//! - the model's own materials are read (Radiance plastic and glass), a shipped sample of
//!   honeybee-schema imports with its adjacency and warnings;
//! - every mistake in a model is an error naming the file, the element and its line.
//!
//! Run with `cargo test --test import -- --nocapture` to see the figures.

mod common;

use std::path::{Path, PathBuf};

use common::l_office::{self, root};

use eigenrad_precompute::cli::{self, DaylightArgs, LevelArgs, SkyInput};
use eigenrad_precompute::formfactor::FormFactorOptions;
use eigenrad_precompute::scene::{load, Scene};

/// The same mesh in another surface order: the solve sums in another order, nothing else.
const SAME_ROOM: f64 = 1e-9;

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("eigenrad-import-{}-{name}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn import_of(model: &Path) -> String {
    format!("[[import]]\nfile = {:?}\n", model.display().to_string())
}

/// Every sensor's, zone's and grid point's reading and daylight part under the west wing at
/// full level, the east at half and the CIE overcast sky of 10 klx.
fn readings(scene: &Path) -> Vec<(String, f64, f64)> {
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
    let r = cli::solve_with_daylight(scene, &levels, Some(&sky), false, &no_cache)
        .unwrap_or_else(|e| panic!("{}: {e:#}", scene.display()));
    let mut out: Vec<(String, f64, f64)> = r
        .sensors
        .iter()
        .chain(&r.zones)
        .map(|x| {
            (
                x.name.clone(),
                x.irradiance[0],
                x.daylight.as_ref().unwrap()[0],
            )
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
    (a - b).abs() <= tolerance * a.abs().max(b.abs())
}

/// The patches of a scene as sorted corner lists, to compare meshes whatever their order.
fn mesh(scene: &Scene) -> Vec<Vec<[u64; 3]>> {
    let mut out: Vec<Vec<[u64; 3]>> = scene
        .patches
        .iter()
        .map(|p| {
            p.polygon
                .vertices
                .iter()
                .map(|v| v.to_array().map(f64::to_bits))
                .collect()
        })
        .collect();
    out.sort();
    out
}

/// The same room from its TOML and from the three descriptions: the same mesh, the same
/// readings; its imported windows pass daylight.
fn same_room_as_toml(model: &Path, dir: &Path) {
    let toml = dir.join("toml.toml");
    std::fs::write(&toml, l_office::scene(None)).unwrap();
    let imported = dir.join("imported.toml");
    std::fs::write(&imported, l_office::scene(Some(&import_of(model)))).unwrap();
    let (a, b) = (load(&toml).unwrap(), load(&imported).unwrap());
    assert_eq!(a.patches.len(), b.patches.len());
    assert!(mesh(&a) == mesh(&b), "the meshes differ");
    assert_eq!(b.windows.len(), 3, "three imported windows");
    let (want, got) = (readings(&toml), readings(&imported));
    assert_eq!(want.len(), got.len());
    let mut worst: f64 = 0.0;
    for (w, g) in want.iter().zip(&got) {
        assert_eq!(w.0, g.0);
        assert!(
            g.2 > 0.0,
            "{}: daylight reaches it through the windows",
            g.0
        );
        for (x, y) in [(w.1, g.1), (w.2, g.2)] {
            assert!(close(x, y, SAME_ROOM), "{}: {x} vs {y}", g.0);
            worst = worst.max((x - y).abs() / x.abs());
        }
    }
    let desk = &got[0];
    println!(
        "{}: {} patches, {} readings; desk {:.3} lux, daylight factor {:.4} %; worst relative \
         difference from the TOML {worst:.1e}",
        model.display(),
        b.patches.len(),
        got.len(),
        desk.1,
        100.0 * desk.2 / 10_000.0
    );
}

#[test]
fn the_l_office_from_hbjson_reads_as_from_toml() {
    let dir = scratch("hbjson-same");
    same_room_as_toml(&root().join("examples/import/l-office.hbjson"), &dir);
    std::fs::remove_dir_all(&dir).ok();
}

/// The example scene takes its materials from the model: Radiance plastic's reflectance, and
/// glass of transmissivity 0.96 (n = 1.52), whose transmittance the Radiance reference manual
/// gives as 0.88 ("Glass": the transmissivity 0.96 of a transmittance of 0.88).
#[test]
fn the_hbjson_example_takes_the_models_materials() {
    let scene = load(&root().join("examples/import/l-office-hbjson.toml")).unwrap();
    let reflectance = |name: &str| {
        scene
            .surfaces
            .iter()
            .find(|s| s.name == name)
            .unwrap_or_else(|| panic!("no surface {name}"))
            .reflectance[0]
    };
    // Photopic: the luminance-weighted sum of equal red, green and blue.
    assert!((reflectance("office.floor") - 0.2).abs() < 1e-12);
    assert!((reflectance("office.south") - 0.5).abs() < 1e-12);
    assert!((reflectance("office.ceiling") - 0.8).abs() < 1e-12);
    assert_eq!(scene.windows.len(), 3);
    let tau = f64::from(scene.windows[0].glazing.normal_transmittance());
    println!(
        "imported glass: transmittance {tau:.5}, reflectance {:.5}",
        reflectance("office.window_s1")
    );
    // The manual rounds to two decimals.
    assert!((tau - 0.88).abs() < 0.005, "{tau}");
    assert!(scene.warnings.is_empty(), "{:?}", scene.warnings);
}

/// honeybee-schema's `model_complete_multiroom_radiance.hbjson` (examples/import/PROVENANCE.md):
/// two storeys of 10 m × 10 m × 3 m, one over the other, under a gabled attic. The storeys
/// import, their faces without modifiers mapped by kind, the first floor's windows glazed by
/// the model's own glass; the ceiling and floor they share are recorded from each side. The
/// gabled attic, its roof slopes typed as walls coming down to its floor, imports as a room
/// under two ceiling planes with two triangular gable walls.
#[test]
fn a_honeybee_sample_imports_with_its_adjacency() {
    let dir = scratch("sample");
    let model = root().join("examples/import/honeybee/model_complete_multiroom_radiance.hbjson");
    let scene_text = |spaces: &str| {
        format!(
            r#"[scene]
name = "sample"
bands = "photopic"
unit = "m"
max_edge = 2.5

[materials]
wall = {{ reflectance = 0.5 }}
floor = {{ reflectance = 0.2 }}
ceiling = {{ reflectance = 0.8 }}
glass = {{ reflectance = 0.08, transmittance = 0.6 }}

{}{spaces}materials = {{ Wall = "wall", Floor = "floor", RoofCeiling = "ceiling", Aperture = "glass" }}
"#,
            import_of(&model)
        )
    };
    let path = dir.join("sample.toml");
    std::fs::write(
        &path,
        scene_text("spaces = [\"First_Floor\", \"Second_Floor\"]\n"),
    )
    .unwrap();
    let scene = load(&path).unwrap_or_else(|e| panic!("{e}"));
    let floors: Vec<&str> = scene
        .surfaces
        .iter()
        .filter(|s| s.name.ends_with(".floor"))
        .map(|s| s.name.as_str())
        .collect();
    println!("rooms: {floors:?}; adjacency {:?}", scene.adjacency);
    assert_eq!(floors, ["First_Floor.floor", "Second_Floor.floor"]);
    assert_eq!(scene.windows.len(), 8);
    let glazing = |name: &str| {
        let w = scene
            .windows
            .iter()
            .find(|w| scene.surfaces[w.surface].name == name)
            .unwrap();
        f64::from(w.glazing.normal_transmittance())
    };
    // `Triple_Pane_0.35`: Radiance glass of 0.35 transmittance, as its name says.
    assert!((glazing("First_Floor.First_Floor_Front_Glz0") - 0.35).abs() < 1e-4);
    assert!((glazing("Second_Floor.Second_Floor_Front_Glz0") - 0.6).abs() < 1e-6);
    let pairs: Vec<(&str, &str)> = scene
        .adjacency
        .iter()
        .map(|a| (a.surface.as_str(), a.space.as_str()))
        .collect();
    assert_eq!(
        pairs,
        [
            ("First_Floor.ceiling", "Second_Floor"),
            ("Second_Floor.floor", "First_Floor"),
            ("Second_Floor.ceiling", "Attic"),
        ]
    );
    std::fs::write(&path, scene_text("")).unwrap();
    let scene = load(&path).unwrap_or_else(|e| panic!("{e}"));
    let area = |name: &str| -> f64 {
        scene
            .surface_area(name)
            .unwrap_or_else(|| panic!("no surface `{name}`"))
    };
    let attic: Vec<(&str, f64)> = scene
        .surfaces
        .iter()
        .filter(|s| s.name.starts_with("Attic."))
        .map(|s| (s.name.as_str(), area(&s.name)))
        .collect();
    println!("attic: {attic:?}");
    // 10 m × 10 m at z = 6 m, the ridge at 9 m along x = 5: two slopes of 10 m × √(5² + 3²),
    // two gable triangles of 10 m × 3 m / 2, no wall along the eaves.
    let slope = 10.0 * 34f64.sqrt();
    let want = [
        ("Attic.floor", 100.0),
        ("Attic.AtticFace2", slope),
        ("Attic.AtticFace3", slope),
        ("Attic.AtticFace4", 15.0),
        ("Attic.AtticFace5", 15.0),
    ];
    assert_eq!(attic.len(), want.len(), "{attic:?}");
    for (name, a) in want {
        let got = area(name);
        assert!((got - a).abs() < 1e-9 * a, "{name}: {got} m² vs {a} m²");
    }
    std::fs::remove_dir_all(&dir).ok();
}

/// What the import cannot map is listed, each naming the file: a shade, a view, an orphaned
/// shade, a modifier of another type.
#[test]
fn what_cannot_be_mapped_is_reported() {
    let dir = scratch("warnings");
    let text = std::fs::read_to_string(root().join("examples/import/l-office.hbjson")).unwrap();
    let mut model: serde_json::Value = serde_json::from_str(&text).unwrap();
    let shade = serde_json::json!({"type": "Shade", "identifier": "fin",
        "geometry": {"type": "Face3D", "boundary": [[0, 0, 3], [1, 0, 3], [1, -1, 3]]}});
    model["rooms"][0]["outdoor_shades"] = serde_json::json!([shade.clone()]);
    model["orphaned_shades"] = serde_json::json!([{"type": "Shade", "identifier": "tree"}]);
    let radiance = &mut model["properties"]["radiance"];
    radiance["views"] = serde_json::json!([{"type": "View", "identifier": "camera",
        "position": [1, 1, 1.5], "direction": [1, 0, 0], "up_vector": [0, 0, 1]}]);
    radiance["modifiers"]
        .as_array_mut()
        .unwrap()
        .push(serde_json::json!({"type": "Trans", "identifier": "curtain"}));
    let path = dir.join("model.hbjson");
    std::fs::write(&path, serde_json::to_string_pretty(&model).unwrap()).unwrap();
    let scene = dir.join("scene.toml");
    std::fs::write(&scene, l_office::scene(Some(&import_of(&path)))).unwrap();
    let warnings = load(&scene).unwrap().warnings;
    for w in &warnings {
        println!("warning: {w}");
    }
    for part in [
        "shade `fin`",
        "view `camera`",
        "orphaned shade `tree`",
        "modifier `curtain` of type `Trans`",
    ] {
        assert!(
            warnings
                .iter()
                .any(|w| w.contains(part) && w.contains("model.hbjson")),
            "no warning of {part}"
        );
    }
    assert_eq!(warnings.len(), 4);
    std::fs::remove_dir_all(&dir).ok();
}

/// The L-office model, changed by `edit`, imported into a bare scene (with the scene's own
/// `extra` lines): the error's message.
fn refused(name: &str, edit: impl Fn(&mut serde_json::Value), extra: &str) -> (String, PathBuf) {
    let dir = scratch(name);
    let text = std::fs::read_to_string(root().join("examples/import/l-office.hbjson")).unwrap();
    let mut model: serde_json::Value = serde_json::from_str(&text).unwrap();
    edit(&mut model);
    let path = dir.join("model.hbjson");
    std::fs::write(&path, serde_json::to_string_pretty(&model).unwrap()).unwrap();
    let scene = dir.join("scene.toml");
    std::fs::write(
        &scene,
        format!(
            "[scene]\nname = \"bad\"\nbands = \"photopic\"\nunit = \"m\"\nmax_edge = 1.0\n\n\
             [[import]]\nfile = \"model.hbjson\"\n{extra}"
        ),
    )
    .unwrap();
    let e = load(&scene).expect_err("refused").to_string();
    println!("{name}: {e}");
    (e, path)
}

/// The 1-based line of `"identifier": "<id>"` in the model file at `path`.
fn line_of(path: &Path, id: &str) -> usize {
    let text = std::fs::read_to_string(path).unwrap();
    let needle = format!("\"identifier\": \"{id}\"");
    text[..text.find(&needle).unwrap()].matches('\n').count() + 1
}

fn face<'a>(model: &'a mut serde_json::Value, id: &str) -> &'a mut serde_json::Value {
    model["rooms"][0]["faces"]
        .as_array_mut()
        .unwrap()
        .iter_mut()
        .find(|f| f["identifier"] == id)
        .unwrap()
}

/// The identifier in the first ``face `<id>` `` of `message`.
fn face_named(message: &str) -> &str {
    let start = message.find("face `").expect("a face named") + "face `".len();
    let len = message[start..].find('`').unwrap();
    &message[start..start + len]
}

/// An aperture's true polygon is cut out of its wall, not its bounding rectangle: the
/// east window made a trapezoid (2 m at the sill, 1 m at the head, 1.5 m high: 2.25 m²) in the
/// 4 m × 3 m east wall, and a triangle in the south wall.
#[test]
fn an_aperture_of_any_convex_polygon_is_cut_out_of_its_wall() {
    let dir = scratch("polygon-aperture");
    let text = std::fs::read_to_string(root().join("examples/import/l-office.hbjson")).unwrap();
    let mut model: serde_json::Value = serde_json::from_str(&text).unwrap();
    face(&mut model, "office_east")["apertures"][0]["geometry"]["boundary"] =
        serde_json::json!([[12, 1, 0.9], [12, 3, 0.9], [12, 2.5, 2.4], [12, 1.5, 2.4]]);
    face(&mut model, "office_south")["apertures"][0]["geometry"]["boundary"] =
        serde_json::json!([[1.5, 0, 0.9], [4.5, 0, 0.9], [3, 0, 2.4]]);
    std::fs::write(
        dir.join("model.hbjson"),
        serde_json::to_string_pretty(&model).unwrap(),
    )
    .unwrap();
    let scene = dir.join("scene.toml");
    std::fs::write(
        &scene,
        "[scene]\nname = \"polygon\"\nbands = \"photopic\"\nunit = \"m\"\nmax_edge = 1.0\n\n\
         [[import]]\nfile = \"model.hbjson\"\n",
    )
    .unwrap();
    let scene = load(&scene).unwrap();
    let area = |name: &str| scene.surface_area(name).unwrap();
    let close = |got: f64, want: f64| (got - want).abs() <= 1e-9 * want;
    for (name, want) in [
        ("office.window_e", 2.25),
        ("office.east", 4.0 * 3.0 - 2.25),
        ("office.window_s1", 0.5 * 3.0 * 1.5),
        // The south wall's other window is still the 3 m × 1.5 m rectangle.
        ("office.south", 12.0 * 3.0 - 2.25 - 4.5),
    ] {
        println!("{name}: {:.12} m² (want {want})", area(name));
        assert!(close(area(name), want), "{name}: {} vs {want}", area(name));
    }
    assert_eq!(scene.windows.len(), 3);
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn a_sloped_ceiling_over_walls_that_stop_short_is_refused_naming_the_wall() {
    let (e, path) = refused(
        "sloped",
        |m| {
            // A plane rising 0.1 m per metre northwards: flat, and not level.
            for c in face(m, "office_ceiling")["geometry"]["boundary"]
                .as_array_mut()
                .unwrap()
            {
                let y = c[1].as_f64().unwrap();
                c[2] = (3.0 + 0.1 * y).into();
            }
        },
        "",
    );
    // The ceiling alone may slope, but the walls still stop at 3 m: the first wall whose top
    // is not the ceiling is named.
    let wall = face_named(&e);
    assert!(
        wall.starts_with("office_") && wall != "office_ceiling",
        "{e}"
    );
    let at = format!("model.hbjson:{}", line_of(&path, wall));
    for part in [
        at.as_str(),
        "space `office`",
        "the wall does not run from the floor",
    ] {
        assert!(e.contains(part), "{e}\nlacks {part}");
    }
}

#[test]
fn a_non_planar_wall_is_refused() {
    let (e, path) = refused(
        "non-planar",
        |m| face(m, "office_north")["geometry"]["boundary"][2][1] = 8.3.into(),
        "",
    );
    let at = format!("model.hbjson:{}", line_of(&path, "office_north"));
    for part in [at.as_str(), "face `office_north`", "not planar"] {
        assert!(e.contains(part), "{e}\nlacks {part}");
    }
}

#[test]
fn an_opening_off_its_face_is_refused() {
    let (e, path) = refused(
        "off-face",
        |m| {
            let east = face(m, "office_east");
            for c in east["apertures"][0]["geometry"]["boundary"]
                .as_array_mut()
                .unwrap()
            {
                c[0] = 12.2.into();
            }
        },
        "",
    );
    let at = format!("model.hbjson:{}", line_of(&path, "window_e"));
    for part in [
        at.as_str(),
        "opening `window_e`",
        "does not lie in its face `office.east`",
    ] {
        assert!(e.contains(part), "{e}\nlacks {part}");
    }
}

#[test]
fn units_not_understood_are_refused() {
    let (e, _) = refused("units", |m| m["units"] = "Furlongs".into(), "");
    assert!(
        e.contains("model.hbjson:1: Model.units: units `Furlongs` are not understood"),
        "{e}"
    );
}

#[test]
fn a_face_without_geometry_is_refused() {
    let (e, path) = refused(
        "geometry",
        |m| {
            face(m, "office_west")["geometry"]["boundary"] =
                serde_json::json!([[0, 0, 0], [0, 8, 0]])
        },
        "",
    );
    let at = format!("model.hbjson:{}", line_of(&path, "office_west"));
    for part in [at.as_str(), "face `office_west`", "missing geometry"] {
        assert!(e.contains(part), "{e}\nlacks {part}");
    }
}

#[test]
fn an_unknown_space_is_refused_listing_the_spaces() {
    let (e, _) = refused("space", |_| {}, "spaces = [\"Office 9\"]\n");
    for part in [
        "scene.toml:9",
        "import.spaces",
        "unknown space `Office 9`",
        "its spaces: office",
    ] {
        assert!(e.contains(part), "{e}\nlacks {part}");
    }
}

#[test]
fn a_face_without_a_reflectance_is_refused_suggesting_the_override() {
    let (e, path) = refused(
        "material",
        |m| face(m, "office_north")["properties"]["radiance"]["modifier"] = serde_json::Value::Null,
        "",
    );
    let at = format!("model.hbjson:{}", line_of(&path, "office_north"));
    for part in [
        at.as_str(),
        "`office_north` (surface `office.north`)",
        "no material",
        "materials = { Wall = \"wall\" }",
    ] {
        assert!(e.contains(part), "{e}\nlacks {part}");
    }
}

#[test]
fn a_malformed_model_is_refused_naming_its_line() {
    let dir = scratch("malformed");
    let text = std::fs::read_to_string(root().join("examples/import/l-office.hbjson")).unwrap();
    // Cut off in the middle of its rooms.
    let cut: String = text.lines().take(40).collect::<Vec<_>>().join("\n");
    std::fs::write(dir.join("model.hbjson"), cut).unwrap();
    let scene = dir.join("scene.toml");
    std::fs::write(
        &scene,
        "[scene]\nname = \"bad\"\nbands = \"photopic\"\nunit = \"m\"\nmax_edge = 1.0\n\n\
         [[import]]\nfile = \"model.hbjson\"\n",
    )
    .unwrap();
    let e = load(&scene).expect_err("refused").to_string();
    println!("{e}");
    assert!(
        e.contains("model.hbjson:40: Model: not a Honeybee model"),
        "{e}"
    );
}

#[test]
fn the_l_office_from_gbxml_reads_as_from_toml() {
    let dir = scratch("gbxml-same");
    same_room_as_toml(&root().join("examples/import/l-office.xml"), &dir);
    std::fs::remove_dir_all(&dir).ok();
}

/// The gbXML example's materials are the model's: the constructions' visible reflectance (the
/// ceiling's through its layer's material) and the window type's, the values
/// `examples/l-office/scene.toml` gives its materials.
#[test]
fn the_gbxml_example_takes_the_models_materials() {
    let toml = load(&root().join("examples/l-office/scene.toml")).unwrap();
    let scene = load(&root().join("examples/import/l-office-gbxml.toml")).unwrap();
    let reflectance = |scene: &Scene, name: &str| {
        scene
            .surfaces
            .iter()
            .find(|s| s.name == name)
            .unwrap_or_else(|| panic!("no surface {name}"))
            .reflectance
            .clone()
    };
    for (imported, written) in [
        ("office.floor", "office.floor"),
        ("office.south", "office.south"),
        ("office.ceiling", "office.ceiling"),
        ("office.window_e", "window_e"),
    ] {
        assert_eq!(
            reflectance(&scene, imported),
            reflectance(&toml, written),
            "{imported}"
        );
    }
    assert_eq!(scene.windows.len(), 3);
    assert_eq!(scene.windows[0].glazing, toml.windows[0].glazing);
    assert!(scene.warnings.is_empty(), "{:?}", scene.warnings);
}

/// OpenStudio's `3997_WindowScaling_bug.xml` (examples/import/PROVENANCE.md): one space on a
/// trapezoidal plan, in feet, 15 ft high, one window. Its floor, by hand from the file's
/// corners: a trapezoid of parallel sides 316 ft and 236 ft, 40 ft apart, 11 040 ft² (the
/// file's own `Area`), 1025.66 m².
#[test]
fn an_openstudio_sample_in_feet_imports() {
    let dir = scratch("openstudio");
    let model = root().join("examples/import/openstudio/3997_WindowScaling_bug.xml");
    let path = dir.join("sample.toml");
    std::fs::write(
        &path,
        format!(
            "[scene]\nname = \"sample\"\nbands = \"photopic\"\nunit = \"m\"\nmax_edge = 4.0\n\n\
             [materials]\nsurface = {{ reflectance = 0.5 }}\n\
             glass = {{ reflectance = 0.08, transmittance = 0.6 }}\n\n{}\
             materials = {{ Wall = \"surface\", Floor = \"surface\", RoofCeiling = \"surface\", \
             Aperture = \"glass\" }}\n",
            import_of(&model)
        ),
    )
    .unwrap();
    let scene = load(&path).unwrap_or_else(|e| panic!("{e}"));
    let area = |name: &str| -> f64 {
        let s = scene.surfaces.iter().find(|s| s.name == name).unwrap();
        scene.patches[s.patch_range.clone()]
            .iter()
            .map(|p| p.area)
            .sum()
    };
    let foot = 0.3048;
    let floor = 11_040.0 * foot * foot;
    println!(
        "storey-1-space-1: floor {:.4} m² (by hand {floor:.4}), window {:.4} m²",
        area("storey-1-space-1.floor"),
        area("storey-1-space-1.opening-1")
    );
    assert!((area("storey-1-space-1.floor") - floor).abs() < 1e-9 * floor);
    // The window: 41.579 ft × 11.4 ft.
    let window = (139.2895 - 97.7105) * (13.2 - 1.8) * foot * foot;
    assert!((area("storey-1-space-1.opening-1") - window).abs() < 1e-9 * window);
    assert_eq!(scene.windows.len(), 1);
    std::fs::remove_dir_all(&dir).ok();
}

/// The gbXML office with each `(from, to)` of `edits` replaced once, imported into a bare
/// scene: the error's message.
fn refused_xml(name: &str, edits: &[(String, String)]) -> (String, PathBuf) {
    let dir = scratch(name);
    let mut text = std::fs::read_to_string(root().join("examples/import/l-office.xml")).unwrap();
    for (from, to) in edits {
        assert!(text.contains(from.as_str()), "{from}");
        text = text.replacen(from.as_str(), to, 1);
    }
    let path = dir.join("model.xml");
    std::fs::write(&path, text).unwrap();
    let scene = dir.join("scene.toml");
    std::fs::write(
        &scene,
        "[scene]\nname = \"bad\"\nbands = \"photopic\"\nunit = \"m\"\nmax_edge = 1.0\n\n\
         [[import]]\nfile = \"model.xml\"\n",
    )
    .unwrap();
    let e = load(&scene).expect_err("refused").to_string();
    println!("{name}: {e}");
    (e, path)
}

/// A gbXML corner as `l-office.xml` writes it.
fn point(x: &str, y: &str, z: &str) -> String {
    format!("<CartesianPoint><Coordinate>{x}</Coordinate><Coordinate>{y}</Coordinate><Coordinate>{z}</Coordinate></CartesianPoint>")
}

/// The L's ceiling loop with each corner at `z(y)`.
fn ceiling_loop(z: impl Fn(f64) -> String) -> String {
    [
        ("0", 0.0),
        ("12", 0.0),
        ("12", 4.0),
        ("7", 4.0),
        ("7", 8.0),
        ("0", 8.0),
    ]
    .iter()
    .map(|(x, y)| point(x, &y.to_string(), &z(*y)))
    .collect::<Vec<_>>()
    .join("\n          ")
}

/// The 1-based line of the first occurrence of `needle` in the file at `path`.
fn line_with(path: &Path, needle: &str) -> usize {
    let text = std::fs::read_to_string(path).unwrap();
    text[..text.find(needle).unwrap()].matches('\n').count() + 1
}

#[test]
fn gbxml_mistakes_are_refused_naming_the_element_and_line() {
    // A sloped roof: the ceiling rising 0.1 m per metre northwards, flat and not level.
    let level = ceiling_loop(|_| "3".into());
    let sloped = ceiling_loop(|y| (3.0 + 0.1 * y).to_string());
    let (e, path) = refused_xml("xml-sloped", &[(level, sloped)]);
    // Its walls still stop at 3 m: the first whose top is not the ceiling is named.
    let wall = face_named(&e);
    let at = format!(
        "model.xml:{}",
        line_with(&path, &format!("<Surface id=\"{wall}\""))
    );
    for part in [
        at.as_str(),
        "space `office-space`, face `",
        "the wall does not run from the floor",
    ] {
        assert!(e.contains(part), "{e}\nlacks {part}");
    }
    // Units.
    let edit = |from: &str, to: &str| vec![(from.to_owned(), to.to_owned())];
    let (e, path) = refused_xml(
        "xml-units",
        &edit("lengthUnit=\"Meters\"", "lengthUnit=\"Cubits\""),
    );
    let at = format!("model.xml:{}", line_with(&path, "<gbXML"));
    for part in [at.as_str(), "units `Cubits` are not understood"] {
        assert!(e.contains(part), "{e}\nlacks {part}");
    }
    // Not well-formed.
    let (e, _) = refused_xml("xml-malformed", &edit("</Building>", "</Buildin>"));
    assert!(
        e.contains("model.xml:12: gbXML: not well-formed XML"),
        "{e}"
    );
    // The east window 0.2 m outside its wall.
    let moved: Vec<(String, String)> = [("1", "0.9"), ("3", "0.9"), ("3", "2.4"), ("1", "2.4")]
        .iter()
        .map(|(y, z)| (point("12", y, z), point("12.2", y, z)))
        .collect();
    let (e, path) = refused_xml("xml-off-face", &moved);
    let at = format!("model.xml:{}", line_with(&path, "<Opening id=\"window_e\""));
    for part in [
        at.as_str(),
        "opening `window_e`",
        "does not lie in its face `office.east`",
    ] {
        assert!(e.contains(part), "{e}\nlacks {part}");
    }
    // A surface naming a space that is not there.
    let (e, _) = refused_xml(
        "xml-space",
        &edit(
            "<AdjacentSpaceId spaceIdRef=\"office-space\"/>",
            "<AdjacentSpaceId spaceIdRef=\"office-9\"/>",
        ),
    );
    assert!(
        e.contains("Surface `office-floor`: its AdjacentSpaceId names no space: `office-9`"),
        "{e}"
    );
}
