//! Scene tests: the example scenes (the Lambertian office, the Cornell box; the offices and
//! classroom with photometry in `luminaires`) and the documentation's example here; one test per
//! validation error checking that the message names the file and the field or line
//! (`errors`, `obj`); openings cut out of room faces (`openings`); the site, windows and
//! exterior obstructions (`daylight`).

use std::path::{Path, PathBuf};

use super::*;

mod daylight;
mod errors;
mod luminaires;
mod obj;
mod openings;

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
    scene.surface_area(name).expect("surface in scene")
}

#[test]
fn scene_lambertian_office_example() {
    let scene = load(&example("office-lambertian")).expect("office scene loads");
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

    // Channel `light` from Ke (17, 12, 4), a radiance: exitance π·Ke.
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
    for (e, ke) in scene.channels[0].exitance.iter().zip([17.0, 12.0, 4.0]) {
        assert!((e - std::f64::consts::PI * ke).abs() < 1e-12);
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
    for name in [
        "office",
        "office-lambertian",
        "office-daylight",
        "cornell-box",
    ] {
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
    let a = load(&example("office-lambertian")).expect("loads");
    let b = load(&example("office-lambertian")).expect("loads");
    assert_eq!(a, b);
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

// ---- scene texts and helpers of the validation tests -------------------------------------

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

/// A scratch folder for OBJ tests, unique to this process and test.
fn scratch(test: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("eigenrad-scene-{}-{test}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    dir
}

#[test]
fn scene_base_is_valid() {
    let scene = parse(BASE, Path::new(FILE)).expect("base scene is valid");
    assert_eq!(scene.patches.len(), 4);
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

/// Reference: the file itself. The open-plan floor's blocks are its solids, in file order,
/// open below (`bottom = false`: they stand on the floor) and closed above, with the corners
/// the file gives (the first desk's and the last tower's).
#[test]
fn blocks_inside_the_rooms_are_solids() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../examples/scaling/open-plan-10k.toml");
    let scene = load(&path).expect("the open-plan floor loads");
    assert_eq!(scene.solids.len(), 51);
    assert_eq!(scene.solids.len(), scene.layout.blocks.len());
    assert!(scene.solids.iter().all(|s| s.open_below && !s.open_above));
    let (first, last) = (scene.solids[0].bounds, scene.solids[50].bounds);
    assert_eq!(
        (first.min, first.max),
        (Vec3::new(1.5, 3.0, 0.0), Vec3::new(3.1, 3.8, 0.75))
    );
    assert_eq!(last.max.z, 2.0);
}
