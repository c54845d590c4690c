//! Scene tests: the two example scenes, and one test per validation error checking that the
//! message names the file and the field or line.

use std::path::{Path, PathBuf};

use super::*;

fn example(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../examples")
        .join(name)
        .join("scene.toml")
}

fn surface<'s>(scene: &'s Scene, name: &str) -> &'s Surface {
    scene
        .surfaces
        .iter()
        .find(|s| s.name == name)
        .unwrap_or_else(|| panic!("no surface {name}"))
}

fn patches<'s>(scene: &'s Scene, name: &str) -> &'s [Patch] {
    &scene.patches[surface(scene, name).patch_range.clone()]
}

fn area(scene: &Scene, name: &str) -> f64 {
    patches(scene, name).iter().map(|p| p.area).sum()
}

#[test]
fn scene_office_example() {
    let scene = load(&example("office")).expect("office scene loads");
    assert_eq!(scene.bands, Bands::Photopic);
    let n = scene.patches.len();
    eprintln!("office: {n} patches");
    assert!((800..=1500).contains(&n), "office has {n} patches");
    assert_eq!(scene.reflectance.len(), n);
    assert_eq!(scene.emission.len(), n);
    assert_eq!(scene.channel_of_patch.len(), n);

    // Room 6 x 4 x 2.8 (its four 0.6 m luminaires and its 2 x 1.4 window flush in its
    // faces), two desks without bottoms.
    let room = 2.0 * (6.0 * 4.0 + 6.0 * 2.8 + 4.0 * 2.8);
    let desk = 1.6 * 0.8 + 2.0 * (1.6 * 0.75 + 0.8 * 0.75);
    // The floor under the desks (no bottom faces) is cut out: it would see nothing.
    let expected = room - 2.0 * 1.28 + 2.0 * desk;
    let total: f64 = scene.patches.iter().map(|p| p.area).sum();
    assert!(
        ((total - expected) / expected).abs() < 1e-9,
        "area {total} vs {expected}"
    );
    assert!((area(&scene, "room.floor") - (24.0 - 2.0 * 1.28)).abs() < 1e-12);
    assert!((area(&scene, "room.ceiling") - (24.0 - 4.0 * 0.36)).abs() < 1e-12);
    assert!((area(&scene, "room.wall_ymin") - (6.0 * 2.8 - 2.0 * 1.4)).abs() < 1e-12);

    // Room faces look into the room, desk faces out of the desk, luminaires down.
    let centre = Vec3::new(3.0, 2.0, 1.4);
    for face in [
        "floor",
        "ceiling",
        "wall_xmin",
        "wall_xmax",
        "wall_ymin",
        "wall_ymax",
    ] {
        for p in patches(&scene, &format!("room.{face}")) {
            assert!(
                p.normal.dot(centre - p.centroid) > 0.0,
                "room.{face} faces out"
            );
        }
    }
    let desk_centre = Vec3::new(2.0, 2.0, 0.375);
    for face in ["top", "side_xmin", "side_xmax", "side_ymin", "side_ymax"] {
        for p in patches(&scene, &format!("desk1.{face}")) {
            assert!(
                p.normal.dot(p.centroid - desk_centre) > 0.0,
                "desk1.{face} faces in"
            );
        }
    }
    assert!(scene.surfaces.iter().all(|s| s.name != "desk1.bottom"));
    for p in patches(&scene, "lum1") {
        assert!((p.normal - Vec3::new(0.0, 0.0, -1.0)).length() < 1e-12);
    }
    for p in patches(&scene, "window") {
        assert!((p.normal - Vec3::new(0.0, 1.0, 0.0)).length() < 1e-12);
    }

    // Channels: four luminaires at 3400 lm over 0.36 m², and the window at 3000 lux.
    let names: Vec<&str> = scene.channels.iter().map(|c| c.name.as_str()).collect();
    assert_eq!(names, ["lum1", "lum2", "lum3", "lum4", "window"]);
    assert!((scene.channels[0].exitance[0] - 3400.0 / 0.36).abs() < 1e-9);
    assert_eq!(scene.channels[4].exitance, vec![3000.0]);
    for (i, p) in scene.patches.iter().enumerate() {
        let name = &scene.surfaces[p.surface].name;
        match scene.channel_of_patch[i] {
            Some(k) => {
                assert_eq!(&scene.channels[k].name, name);
                assert_eq!(scene.emission[i], scene.channels[k].exitance);
                assert_eq!(scene.reflectance[i], vec![0.0]);
            }
            None => assert_eq!(scene.emission[i], vec![0.0]),
        }
    }
    let lum1 = surface(&scene, "lum1");
    let flux: f64 = scene.patches[lum1.patch_range.clone()]
        .iter()
        .zip(&scene.emission[lum1.patch_range.clone()])
        .map(|(p, e)| p.area * e[0])
        .sum();
    assert!((flux - 3400.0).abs() < 1e-9);

    // Sensors and zones.
    assert_eq!(scene.sensors[0].position, Vec3::new(2.0, 2.0, 0.75));
    assert_eq!(scene.sensors[0].half_angle, None);
    let half = scene.sensors[1]
        .half_angle
        .expect("ceiling sensor has a field of view");
    assert!((half - std::f64::consts::FRAC_PI_3).abs() < 1e-15);
    let ZoneKind::WorkPlane { height, receivers } = &scene.zones[0].kind else {
        panic!("first zone is the work plane")
    };
    assert_eq!(*height, 0.8);
    let covered: f64 = receivers.iter().map(|p| p.area).sum();
    assert!((covered - 5.0 * 3.0).abs() < 1e-12);
    assert_eq!(receivers.len(), 10 * 6);
    for p in receivers {
        assert!((p.normal - Vec3::new(0.0, 0.0, 1.0)).length() < 1e-12);
        assert!((p.centroid.z - 0.8).abs() < 1e-12);
    }
    let ZoneKind::Surfaces(desks) = &scene.zones[1].kind else {
        panic!("second zone: desks")
    };
    let top: f64 = desks.iter().map(|&i| scene.patches[i].area).sum();
    assert!((top - 2.0 * 1.28).abs() < 1e-12);
}

#[test]
fn scene_cornell_box_example() {
    let scene = load(&example("cornell-box")).expect("Cornell box loads");
    assert_eq!(scene.bands, Bands::Rgb);
    assert!(!scene.patches.is_empty());
    eprintln!("Cornell box: {} patches", scene.patches.len());
    let mut names: Vec<&str> = scene.surfaces.iter().map(|s| s.name.as_str()).collect();
    names.sort_unstable();
    assert_eq!(
        names,
        [
            "backWall",
            "ceiling",
            "floor",
            "leftWall",
            "light",
            "rightWall",
            "shortBox",
            "tallBox"
        ]
    );
    // Duplicated "bottom" faces dropped: the top and four sides of the short box remain
    // (sides are 0.6 high; the top's area is half the cross product of its diagonals).
    let short_top = 0.5
        * Vec3::new(-0.40, 0.0, -0.75)
            .cross(Vec3::new(-0.75, 0.0, 0.40))
            .length();
    let short_sides: f64 = [(0.18, 0.57), (0.58, 0.18), (0.17, 0.58), (0.57, 0.17)]
        .iter()
        .map(|(a, b): &(f64, f64)| a.hypot(*b) * 0.6)
        .sum();
    assert!((area(&scene, "shortBox") - (short_top + short_sides)).abs() < 1e-9);

    // The box is about 2 m across, z up after `up = "y"`: walls, floor, ceiling and light
    // face into the box; the blocks' faces face out of them.
    let centre = Vec3::new(0.0, 0.0, 1.0);
    for name in [
        "floor",
        "ceiling",
        "backWall",
        "leftWall",
        "rightWall",
        "light",
    ] {
        for p in patches(&scene, name) {
            assert!(
                p.normal.dot(centre - p.centroid) > 0.0,
                "{name} faces out of the box"
            );
        }
    }
    for (name, c) in [
        ("shortBox", Vec3::new(0.33, -0.37, 0.3)),
        ("tallBox", Vec3::new(-0.33, 0.29, 0.6)),
    ] {
        for p in patches(&scene, name) {
            assert!(p.normal.dot(p.centroid - c) > 0.0, "{name} faces inwards");
        }
    }
    for p in patches(&scene, "floor") {
        assert!(p.centroid.z.abs() < 1e-12 && p.normal.z > 0.999);
    }

    // Channel `light` from Ke (17, 12, 4).
    assert_eq!(scene.channels.len(), 1);
    assert_eq!(scene.channels[0].name, "light");
    assert_eq!(
        scene.channels[0].surfaces,
        vec![scene
            .surfaces
            .iter()
            .position(|s| s.name == "light")
            .unwrap_or(usize::MAX)]
    );
    for (e, want) in scene.channels[0].exitance.iter().zip([17.0, 12.0, 4.0]) {
        assert!((e - want).abs() < 1e-12);
    }
    let light = surface(&scene, "light");
    assert!((light.reflectance[0] - 0.78).abs() < 1e-12);
    assert_eq!(scene.sensors[0].normal, Vec3::new(0.0, 0.0, 1.0));
    assert!(
        matches!(&scene.zones[0].kind, ZoneKind::Surfaces(p) if p.len() == patches(&scene, "floor").len())
    );
}

#[test]
fn scene_faces_are_tiled_by_their_patches() {
    // Reference: meshing cuts each convex face into patches that tile it, so occlusion may use
    // the face in their place. Every patch is in exactly one face, in the face's plane and
    // facing its way, and the patch areas add up to the face area (1e-9 relative).
    for name in ["office", "cornell-box"] {
        let scene = load(&example(name)).expect("example loads");
        let mut covered = 0;
        for face in &scene.faces {
            assert_eq!(face.patches.start, covered, "{name}: faces in patch order");
            covered = face.patches.end;
            let (normal, face_area) = (face.polygon.normal(), face.polygon.area());
            let origin = face.polygon.vertices[0];
            let mut sum = 0.0;
            for p in &scene.patches[face.patches.clone()] {
                assert!(
                    p.normal.dot(normal) > 1.0 - 1e-12,
                    "{name}: patch faces its face's way"
                );
                for &c in &p.polygon.vertices {
                    assert!(
                        normal.dot(c - origin).abs() < 1e-9,
                        "{name}: patch off its face"
                    );
                }
                sum += p.area;
            }
            assert!(
                (sum - face_area).abs() <= 1e-9 * face_area,
                "{name}: {sum} vs {face_area}"
            );
        }
        assert_eq!(
            covered,
            scene.patches.len(),
            "{name}: every patch in a face"
        );
    }
}

#[test]
fn scene_meshing_is_deterministic() {
    let a = load(&example("office")).expect("loads");
    let b = load(&example("office")).expect("loads");
    assert_eq!(a, b);
}

// ---- validation errors ----------------------------------------------------------------------

const BASE: &str = r#"[scene]
name = "t"
bands = "photopic"
unit = "m"
max_edge = 0.5

[materials]
white = { reflectance = 0.5 }
lamp = { reflectance = 0.0, emission = 100 }

[[quad]]
name = "a"
material = "white"
corners = [[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]]
"#;

const FILE: &str = "/somewhere/test-scene.toml";

fn error(extra: &str) -> String {
    error_in(&format!("{BASE}{extra}"))
}

fn error_in(text: &str) -> String {
    match parse(text, Path::new(FILE)) {
        Ok(_) => panic!("scene should be rejected:\n{text}"),
        Err(e) => e.to_string(),
    }
}

/// The 1-based line, in `BASE` followed by `extra`, of the first line of `extra` holding
/// `needle`.
fn line_of(extra: &str, needle: &str) -> usize {
    let found = extra
        .lines()
        .position(|l| l.contains(needle))
        .map_or(0, |i| i + 1);
    BASE.lines().count() + found
}

fn assert_names(message: &str, parts: &[&str]) {
    assert!(message.contains("test-scene.toml"), "no file in: {message}");
    for p in parts {
        assert!(message.contains(p), "`{p}` missing from: {message}");
    }
}

#[test]
fn scene_base_is_valid() {
    let scene = parse(BASE, Path::new(FILE)).expect("base scene is valid");
    assert_eq!(scene.patches.len(), 4);
}

#[test]
fn scene_error_unknown_field_names_line() {
    let extra =
        "\n[[sensor]]\nname = \"s\"\nposition = [0, 0, 1]\nnormal = [0, 0, 1]\nhalf_angel = 30\n";
    let m = error(extra);
    assert_names(
        &m,
        &[&format!(":{}:", line_of(extra, "half_angel")), "half_angel"],
    );
}

#[test]
fn scene_error_reflectance_out_of_range() {
    let m = error_in(&BASE.replace(
        "white = { reflectance = 0.5 }",
        "white = { reflectance = 1.0 }",
    ));
    assert_names(&m, &["materials.white.reflectance", ":8:"]);
    let m = error_in(&BASE.replace(
        "white = { reflectance = 0.5 }",
        "white = { reflectance = -0.1 }",
    ));
    assert_names(&m, &["materials.white.reflectance"]);
}

#[test]
fn scene_error_band_count() {
    let m = error_in(&BASE.replace("reflectance = 0.5", "reflectance = [0.5, 0.5, 0.5]"));
    assert_names(
        &m,
        &[
            "materials.white.reflectance",
            "expected 1 value(s), found 3",
        ],
    );
}

#[test]
fn scene_error_negative_or_nonfinite_exitance() {
    let m = error_in(&BASE.replace("emission = 100", "emission = -5"));
    assert_names(&m, &["materials.lamp.emission", ":9:"]);
    let extra = "\n[[channel]]\nname = \"c\"\nsurfaces = [\"a\"]\nexitance = nan\n";
    let m = error(extra);
    assert_names(
        &m,
        &[
            "channel `c`.exitance",
            &format!(":{}:", line_of(extra, "nan")),
        ],
    );
    let extra = "\n[[channel]]\nname = \"c\"\nsurfaces = [\"a\"]\nflux = -3\n";
    assert_names(&error(extra), &["channel `c`.flux"]);
}

#[test]
fn scene_error_nonfinite_coordinates() {
    let extra = "\n[[quad]]\nname = \"b\"\nmaterial = \"white\"\ncorners = [[0, 0, 0], [inf, 0, 0], [1, 1, 0], [0, 1, 0]]\n";
    let m = error(extra);
    assert_names(
        &m,
        &["quad `b`.corners", &format!(":{}:", line_of(extra, "inf"))],
    );
}

#[test]
fn scene_error_degenerate_face() {
    let extra = "\n[[quad]]\nname = \"b\"\nmaterial = \"white\"\ncorners = [[0, 0, 0], [1, 0, 0], [1, 0, 0], [0, 1, 0]]\n";
    let m = error(extra);
    assert_names(
        &m,
        &[
            "surface `b`",
            "degenerate",
            &format!(":{}:", line_of(extra, "corners")),
        ],
    );
    let extra = "\n[[quad]]\nname = \"b\"\nmaterial = \"white\"\ncorners = [[0, 0, 0], [1, 0, 0], [2, 0, 0], [3, 0, 0]]\n";
    assert_names(&error(extra), &["surface `b`", "degenerate"]);
}

#[test]
fn scene_error_nonplanar_quad() {
    let extra = "\n[[quad]]\nname = \"b\"\nmaterial = \"white\"\ncorners = [[0, 0, 0], [1, 0, 0], [1, 1, 0.1], [0, 1, 0]]\n";
    let m = error(extra);
    assert_names(
        &m,
        &[
            "surface `b`",
            "non-planar",
            &format!(":{}:", line_of(extra, "corners")),
        ],
    );
    // Within a looser tolerance, or triangulated, it is accepted.
    let loose = format!("{BASE}{extra}").replace(
        "max_edge = 0.5",
        "max_edge = 0.5\nplanarity_tolerance = 0.1",
    );
    assert!(parse(&loose, Path::new(FILE)).is_ok());
    let split = format!("{BASE}{extra}\n[surfaces.b]\ntriangulate = true\n");
    assert!(parse(&split, Path::new(FILE)).is_ok());
}

#[test]
fn scene_error_duplicate_names() {
    let extra = "\n[[quad]]\nname = \"a\"\nmaterial = \"white\"\ncorners = [[0, 0, 1], [1, 0, 1], [1, 1, 1], [0, 1, 1]]\n";
    assert_names(
        &error(extra),
        &[
            "duplicate surface name `a`",
            &format!(":{}:", line_of(extra, "corners")),
        ],
    );
    let lamp = "\n[[quad]]\nname = \"l\"\nmaterial = \"lamp\"\ncorners = [[0, 0, 1], [0, 1, 1], [1, 1, 1], [1, 0, 1]]\n";
    let extra = format!("{lamp}\n[[channel]]\nname = \"c\"\nsurfaces = [\"l\"]\n\n[[channel]]\nname = \"c\"\nsurfaces = [\"l\"]\n");
    assert_names(&error(&extra), &["duplicate channel name `c`"]);
    let sensor = "\n[[sensor]]\nname = \"s\"\nposition = [0, 0, 1]\nnormal = [0, 0, 1]\n";
    assert_names(
        &error(&format!("{sensor}{sensor}")),
        &["duplicate sensor name `s`"],
    );
    let zone = "\n[[zone]]\nname = \"z\"\nsurfaces = [\"a\"]\n";
    assert_names(
        &error(&format!("{zone}{zone}")),
        &["duplicate zone name `z`"],
    );
    // A duplicate key in TOML itself: the parser names the line.
    let extra = "\n[materials.white]\nreflectance = 0.3\n";
    assert_names(
        &error(extra),
        &["duplicate key", &format!(":{}:", line_of(extra, "white"))],
    );
}

#[test]
fn scene_error_channel_without_emitter() {
    let extra = "\n[[channel]]\nname = \"c\"\nsurfaces = [\"a\"]\n";
    assert_names(
        &error(extra),
        &[
            "channel `c`",
            "none of its surfaces emits",
            &format!(":{}:", line_of(extra, "[[channel]]")),
        ],
    );
    let extra = "\n[[channel]]\nname = \"c\"\n";
    assert_names(&error(extra), &["channel `c`", "names no surface"]);
}

#[test]
fn scene_error_emitter_outside_channels() {
    let extra = "\n[[quad]]\nname = \"l\"\nmaterial = \"lamp\"\ncorners = [[0, 0, 1], [0, 1, 1], [1, 1, 1], [1, 0, 1]]\n";
    assert_names(
        &error(extra),
        &[
            "surface `l`",
            "no channel drives it",
            &format!(":{}:", line_of(extra, "\"lamp\"")),
        ],
    );
}

#[test]
fn scene_error_unknown_references() {
    let extra = "\n[[channel]]\nname = \"c\"\nsurfaces = [\"nope\"]\nexitance = 10\n";
    assert_names(
        &error(extra),
        &[
            "channel `c`.surfaces",
            "unknown surface `nope`",
            &format!(":{}:", line_of(extra, "nope")),
        ],
    );
    let extra = "\n[[quad]]\nname = \"b\"\nmaterial = \"whit\"\ncorners = [[0, 0, 1], [1, 0, 1], [1, 1, 1], [0, 1, 1]]\n";
    assert_names(
        &error(extra),
        &[
            "unknown material `whit`",
            &format!(":{}:", line_of(extra, "whit")),
        ],
    );
    let extra = "\n[surfaces.nope]\nflip = true\n";
    assert_names(&error(extra), &["unknown surface `nope`"]);
    let extra = "\n[[zone]]\nname = \"z\"\nwork_plane = { room = \"hall\", height = 0.8 }\n";
    assert_names(
        &error(extra),
        &[
            "unknown room `hall`",
            &format!(":{}:", line_of(extra, "hall")),
        ],
    );
    let extra = "\n[[channel]]\nname = \"c\"\nmaterials = [\"neon\"]\n";
    assert_names(&error(extra), &["channel `c`.materials", "`neon`"]);
}

#[test]
fn scene_error_sensor_zero_normal() {
    let extra = "\n[[sensor]]\nname = \"s\"\nposition = [0, 0, 1]\nnormal = [0, 0, 0]\n";
    assert_names(
        &error(extra),
        &[
            "sensor `s`.normal",
            &format!(":{}:", line_of(extra, "normal")),
        ],
    );
    let extra =
        "\n[[sensor]]\nname = \"s\"\nposition = [0, 0, 1]\nnormal = [0, 0, 1]\nhalf_angle = 120\n";
    assert_names(&error(extra), &["sensor `s`.half_angle"]);
}

/// A scratch folder for OBJ tests, unique to this process and test.
fn scratch(test: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("eigenrad-scene-{}-{test}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    dir
}

const OBJ_SCENE: &str = "[scene]\nname = \"o\"\nbands = \"rgb\"\nunit = \"cm\"\nmax_edge = 50\n\n[[obj]]\nfile = \"model.obj\"\n";

#[test]
fn scene_error_missing_obj_names_path() {
    let dir = scratch("missing-obj");
    let m = match parse(OBJ_SCENE, &dir.join("test-scene.toml")) {
        Ok(_) => panic!("missing OBJ accepted"),
        Err(e) => e.to_string(),
    };
    assert_names(&m, &["obj.file", "model.obj", ":8:", "not found"]);
}

#[test]
fn scene_error_missing_mtl_names_path() {
    let dir = scratch("missing-mtl");
    std::fs::write(
        dir.join("model.obj"),
        "mtllib gone.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\ng t\nusemtl x\nf 1 2 3\n",
    )
    .expect("write obj");
    let m = match parse(OBJ_SCENE, &dir.join("test-scene.toml")) {
        Ok(_) => panic!("missing MTL accepted"),
        Err(e) => e.to_string(),
    };
    assert_names(&m, &["gone.mtl", "not found"]);
}

#[test]
fn scene_obj_units_transform_and_photopic_reduction() {
    let dir = scratch("obj-ok");
    std::fs::write(
        dir.join("model.obj"),
        "mtllib m.mtl\nv 0 0 0\nv 100 0 0\nv 100 100 0\nv 0 100 0\ng sheet\nusemtl grey\nf 1 2 3 4\n",
    )
    .expect("write obj");
    std::fs::write(dir.join("m.mtl"), "newmtl grey\nKd 0.2 0.4 0.6\nKe 0 0 0\n")
        .expect("write mtl");
    let text = format!("{OBJ_SCENE}translate = [0, 0, 250]\n").replace("\"rgb\"", "\"photopic\"");
    let scene = parse(&text, &dir.join("test-scene.toml")).expect("OBJ scene loads");
    assert_eq!(scene.surfaces[0].name, "sheet");
    assert_eq!(scene.patches.len(), 4); // 1 m square at 0.5 m edges
    let total: f64 = scene.patches.iter().map(|p| p.area).sum();
    assert!((total - 1.0).abs() < 1e-12);
    assert!(scene
        .patches
        .iter()
        .all(|p| (p.centroid.z - 2.5).abs() < 1e-12));
    let y = 0.2126 * 0.2 + 0.7152 * 0.4 + 0.0722 * 0.6;
    assert!((scene.reflectance[0][0] - y).abs() < 1e-15);

    // A bad Kd names the MTL file and the material.
    std::fs::write(dir.join("m.mtl"), "newmtl grey\nKd 1.2 0.4 0.6\n").expect("write mtl");
    let m = match parse(&text, &dir.join("test-scene.toml")) {
        Ok(_) => panic!("Kd above 1 accepted"),
        Err(e) => e.to_string(),
    };
    assert!(m.contains("m.mtl") && m.contains("`grey` Kd"), "{m}");
    std::fs::write(dir.join("m.mtl"), "newmtl grey\nKd 0.2 0.4 0.6\n").expect("write mtl");

    // A bad face in the OBJ names the OBJ file and the surface.
    std::fs::write(
        dir.join("model.obj"),
        "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 2 0 0\ng line\nusemtl grey\nf 1 2 3\n",
    )
    .expect("write obj");
    let m = match parse(&text, &dir.join("test-scene.toml")) {
        Ok(_) => panic!("degenerate OBJ face accepted"),
        Err(e) => e.to_string(),
    };
    assert!(
        m.contains("model.obj") && m.contains("surface `line`") && m.contains("face 1"),
        "{m}"
    );
}

#[test]
fn scene_flip_reverses_normals() {
    let text = format!("{BASE}\n[surfaces.a]\nflip = true\n");
    let scene = parse(&text, Path::new(FILE)).expect("valid");
    assert!(scene
        .patches
        .iter()
        .all(|p| (p.normal - Vec3::new(0.0, 0.0, -1.0)).length() < 1e-15));
}

#[test]
fn scene_docs_example_loads() {
    let docs = include_str!("../../../docs/scene.md");
    let start = docs.find("```toml\n").map_or(0, |i| i + 8);
    let end = docs[start..].find("```").map_or(docs.len(), |i| start + i);
    let example = &docs[start..end];
    // The OBJ part names a file that is not in the repository: it must be reported as missing,
    // and the rest must load.
    let m = match parse(example, Path::new("docs/scene.toml")) {
        Ok(_) => panic!("chair.obj does not exist"),
        Err(e) => e.to_string(),
    };
    assert!(m.contains("chair.obj") && m.contains("not found"), "{m}");
    let obj = example.find("[[obj]]").unwrap_or(0);
    let channel = example.find("[[channel]]").unwrap_or(0);
    let without_obj = format!("{}{}", &example[..obj], &example[channel..]);
    let scene = parse(&without_obj, Path::new("docs/scene.toml")).expect("docs example loads");
    assert_eq!(scene.channels.len(), 2);
    assert_eq!(scene.zones.len(), 2);
}

#[test]
fn scene_error_wrong_type_or_variant_names_line() {
    let m = error_in(&BASE.replace("reflectance = 0.5", "reflectance = \"high\""));
    assert_names(&m, &[":8:", "expected a number, or a list of numbers"]);
    let m = error_in(&BASE.replace("unit = \"m\"", "unit = \"yd\""));
    assert_names(&m, &[":4:", "unknown variant `yd`"]);
    let m = error("\n[[sensor]]\nname = \"s\"\nposition = [0, 0, 1]\n");
    assert_names(&m, &["missing field `normal`"]);
}

#[test]
fn scene_error_surface_in_two_channels() {
    let lamp = "\n[[quad]]\nname = \"l\"\nmaterial = \"lamp\"\ncorners = [[0, 0, 1], [0, 1, 1], [1, 1, 1], [1, 0, 1]]\n";
    let extra = format!(
        "{lamp}\n[[channel]]\nname = \"c1\"\nsurfaces = [\"l\"]\n\n[[channel]]\nname = \"c2\"\nmaterials = [\"lamp\"]\n"
    );
    assert_names(
        &error(&extra),
        &[
            "surface `l`",
            "`c1`",
            "`c2`",
            &format!(":{}:", line_of(&extra, "c2") - 1),
        ],
    );
}

#[test]
fn scene_error_missing_scene_file_names_path() {
    let path = scratch("missing-scene").join("nothing-here.toml");
    let m = match load(&path) {
        Ok(_) => panic!("missing scene accepted"),
        Err(e) => e.to_string(),
    };
    assert!(
        m.contains("nothing-here.toml") && m.contains("cannot read"),
        "{m}"
    );
}

// ---- openings -------------------------------------------------------------------------------

/// A closed 3 m × 2 m × 2.5 m room with four openings: one in the ceiling, two sharing an edge
/// in the wall y = 0 (one touching the floor), one covering a corner of the wall x = 3.
const OPENINGS: &str = r#"[scene]
name = "openings"
bands = "photopic"
unit = "m"
max_edge = 0.4

[materials]
white = { reflectance = 0.5 }
black = { reflectance = 0.0 }

[[room]]
name = "room"
min = [0, 0, 0]
max = [3, 2, 2.5]
material = "white"
openings = ["lamp", "left", "right", "corner"]

[[quad]]
name = "lamp"
material = "black"
corners = [[1.0, 0.7, 2.5], [1.0, 1.3, 2.5], [1.6, 1.3, 2.5], [1.6, 0.7, 2.5]]

[[quad]]
name = "left"
material = "black"
corners = [[0.5, 0, 0], [0.5, 0, 1.2], [1.5, 0, 1.2], [1.5, 0, 0]]

[[quad]]
name = "right"
material = "black"
corners = [[1.5, 0, 0.3], [1.5, 0, 1.0], [2.25, 0, 1.0], [2.25, 0, 0.3]]

[[quad]]
name = "corner"
material = "black"
corners = [[3, 1.5, 2.0], [3, 1.5, 2.5], [3, 2, 2.5], [3, 2, 2.0]]
"#;

/// The part of a patch's bounding box shared with an opening's, in the plane they share
/// (m²); zero when they only touch along an edge.
fn shared_area(a: &Patch, b: &Patch) -> f64 {
    let bounds = |p: &Patch, k: usize| {
        let v = p.polygon.vertices.iter().map(|c| c.axis(k));
        (
            v.clone().fold(f64::INFINITY, f64::min),
            v.fold(f64::NEG_INFINITY, f64::max),
        )
    };
    let mut area = 1.0;
    for k in 0..3 {
        let (a0, a1) = bounds(a, k);
        let (b0, b1) = bounds(b, k);
        if a1 - a0 < 1e-12 && b1 - b0 < 1e-12 {
            // The axis normal to both: they must share the plane.
            if (a0 - b0).abs() > 1e-12 {
                return 0.0;
            }
            continue;
        }
        area *= (a1.min(b1) - a0.max(b0)).max(0.0);
    }
    area
}

#[test]
fn scene_openings_account_for_every_area_and_leave_no_patch_behind() {
    let scene = parse(OPENINGS, Path::new(FILE)).expect("room with openings loads");
    // Every patch is a room face or an opening: the box's surface area exactly (to rounding).
    let total: f64 = scene.patches.iter().map(|p| p.area).sum();
    let box_area = 2.0 * (3.0 * 2.0 + 3.0 * 2.5 + 2.0 * 2.5);
    assert!(
        (total - box_area).abs() < 1e-12 * box_area,
        "{total} m² vs {box_area} m²"
    );
    assert!((area(&scene, "room.ceiling") - (6.0 - 0.36)).abs() < 1e-12);
    assert!((area(&scene, "room.wall_ymin") - (7.5 - 1.2 - 0.525)).abs() < 1e-12);
    assert!((area(&scene, "room.wall_xmax") - (5.0 - 0.25)).abs() < 1e-12);
    // No room patch overlaps an opening's patch, and every opening faces into the room.
    let centre = Vec3::new(1.5, 1.0, 1.25);
    for opening in ["lamp", "left", "right", "corner"] {
        for o in patches(&scene, opening) {
            assert!(
                o.normal.dot(centre - o.centroid) > 0.0,
                "{opening} faces out"
            );
            for face in [
                "floor",
                "ceiling",
                "wall_xmin",
                "wall_xmax",
                "wall_ymin",
                "wall_ymax",
            ] {
                for p in patches(&scene, &format!("room.{face}")) {
                    let shared = shared_area(p, o);
                    assert!(
                        shared < 1e-12,
                        "room.{face} overlaps {opening} by {shared} m²"
                    );
                }
            }
        }
    }
    // Patches keep within max_edge (cells are meshed at the face's max_edge).
    for p in &scene.patches {
        let v = &p.polygon.vertices;
        for i in 0..v.len() {
            assert!((v[(i + 1) % v.len()] - v[i]).length() <= 0.4 + 1e-12);
        }
    }
    let again = parse(OPENINGS, Path::new(FILE)).expect("loads again");
    assert_eq!(scene.patches, again.patches);
}
