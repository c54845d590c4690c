//! Rooms drawn as OBJ files (`[[obj]]` with `room`, docs/scene.md "OBJ rooms"):
//!
//! - an L-shaped room drawn in OBJ (its floor and ceiling in two quads each, meeting the long
//!   walls at a corner of the other quad) with a window in its south wall meshes into the
//!   same patches, in the same order, as the same L written as a `[[room]]` plan, and reads
//!   the same at a sensor, a zone and a work-plane grid (independent reference: the TOML
//!   plan room of `tests/rooms.rs`);
//! - the OBJ L is closed: uniform ρ, one emitting face, the area-weighted mean irradiance is
//!   `Φ / (S (1 − ρ))` within 1e-4 (docs/math.md, "Exact results": the closed-room identity);
//! - a work plane over the OBJ L has no grid point in the notch;
//! - each mistake is an error naming the OBJ file's line, the room and the face: a shell with
//!   a face missing, a wall wound out of the room, a room drawn as a solid seen from outside, a
//!   window drawn in the shell, a floor on two levels; and a sensor in the notch, a window
//!   facing out, a window over an uncut wall and `openings` without `room` are refused as in
//!   any room.
//!
//! Run with `cargo test --test obj_rooms -- --nocapture` to see the figures.

use std::path::{Path, PathBuf};

use eigenrad::precompute::cli;
use eigenrad::precompute::formfactor::FormFactorOptions;
use eigenrad::precompute::scene::{load, Scene};

#[path = "obj_rooms/refusals.rs"]
mod refusals;

/// The closed-room identity holds up to the form factors' closure (`tests/rooms.rs`).
const CLOSED_ROOM_TOLERANCE: f64 = 1e-4;

fn scratch(name: &str) -> PathBuf {
    let dir =
        std::env::temp_dir().join(format!("eigenrad-obj-rooms-{}-{name}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn write(dir: &Path, name: &str, text: &str) -> PathBuf {
    let path = dir.join(name);
    std::fs::write(&path, text).unwrap();
    path
}

/// The L's plan, counter-clockwise from its south-west corner: 6 m × 4 m less a
/// 2.5 m × 2 m notch in the north-east.
const PLAN: [[f64; 2]; 6] = [
    [0.0, 0.0],
    [6.0, 0.0],
    [6.0, 2.0],
    [3.5, 2.0],
    [3.5, 4.0],
    [0.0, 4.0],
];
const HEIGHT: f64 = 2.5;
/// The walls on the plan's edges, in order.
const WALLS: [&str; 6] = [
    "south",
    "east",
    "notch_south",
    "notch_west",
    "north",
    "west",
];

/// An OBJ face: its group, material and corners (m).
type ObjFace = (&'static str, &'static str, Vec<[f64; 3]>);

/// The L's faces wound into the room: the floor and the ceiling in two convex quads each
/// (split along y = 2, so the long quad's edge holds the short one's corner), a wall quad on
/// every plan edge.
fn l_faces() -> Vec<ObjFace> {
    let h = HEIGHT;
    let mut faces: Vec<ObjFace> = vec![
        (
            "floor",
            "floor",
            vec![
                [0.0, 0.0, 0.0],
                [6.0, 0.0, 0.0],
                [6.0, 2.0, 0.0],
                [0.0, 2.0, 0.0],
            ],
        ),
        (
            "floor",
            "floor",
            vec![
                [0.0, 2.0, 0.0],
                [3.5, 2.0, 0.0],
                [3.5, 4.0, 0.0],
                [0.0, 4.0, 0.0],
            ],
        ),
        (
            "ceiling",
            "ceiling",
            vec![[0.0, 0.0, h], [0.0, 2.0, h], [6.0, 2.0, h], [6.0, 0.0, h]],
        ),
        (
            "ceiling",
            "ceiling",
            vec![[0.0, 2.0, h], [0.0, 4.0, h], [3.5, 4.0, h], [3.5, 2.0, h]],
        ),
    ];
    for (k, name) in WALLS.iter().enumerate() {
        let (a, b) = (PLAN[k], PLAN[(k + 1) % 6]);
        // Counter-clockwise plan: the room is on the left of a → b; up a's side, the wall
        // faces left.
        faces.push((
            name,
            "wall",
            vec![
                [a[0], a[1], 0.0],
                [a[0], a[1], h],
                [b[0], b[1], h],
                [b[0], b[1], 0.0],
            ],
        ));
    }
    faces
}

/// `faces` as an OBJ file using `room.mtl`.
fn obj(faces: &[ObjFace]) -> String {
    let mut text = String::from("mtllib room.mtl\n");
    let mut n = 0;
    for (group, material, corners) in faces {
        text.push_str(&format!("g {group}\nusemtl {material}\n"));
        for c in corners {
            text.push_str(&format!("v {} {} {}\n", c[0], c[1], c[2]));
        }
        let indices: Vec<String> = (n + 1..=n + corners.len()).map(|i| i.to_string()).collect();
        text.push_str(&format!("f {}\n", indices.join(" ")));
        n += corners.len();
    }
    text
}

/// The MTL file: the scene's materials of the same names set the reflectances.
const MTL: &str = "newmtl floor\nKd 0.5 0.5 0.5\nnewmtl wall\nKd 0.5 0.5 0.5\n\
                   newmtl ceiling\nKd 0.5 0.5 0.5\nnewmtl glass\nKd 0.1 0.1 0.1\n";

/// The scene's header and materials: floor, walls and ceiling of reflectance `rho`.
fn header(rho: f64) -> String {
    format!(
        r#"[scene]
name = "l-room"
bands = "photopic"
unit = "m"
max_edge = 0.8

[materials]
floor = {{ reflectance = {rho} }}
wall = {{ reflectance = {rho} }}
ceiling = {{ reflectance = {rho} }}
glass = {{ reflectance = 0.08, transmittance = 0.7 }}
"#
    )
}

/// The window in the south wall (y = 0), facing into the room (+y).
const WINDOW: &str = r#"
[[quad]]
name = "window"
material = "glass"
corners = [[3, 0, 1], [1, 0, 1], [1, 0, 2], [3, 0, 2]]
"#;

/// The outputs: the ceiling lit, a desk sensor, a zone over every face, a work plane.
const OUTPUTS: &str = r#"
[[channel]]
name = "ceiling"
surfaces = ["office.ceiling"]
flux = 10000

[[sensor]]
name = "desk"
position = [1.5, 3, 0.75]
normal = [0, 0, 1]

[[zone]]
name = "all"
surfaces = ["office*"]

[[zone]]
name = "work_plane"
work_plane = { room = "office", height = 0.8, margin = 0.5 }
"#;

/// The L as an OBJ room, with the window as its opening if `window`.
fn obj_scene(dir: &Path, rho: f64, faces: &[ObjFace], window: bool) -> PathBuf {
    write(dir, "room.mtl", MTL);
    write(dir, "room.obj", &obj(faces));
    let openings = if window {
        "openings = [\"window\"]\n"
    } else {
        ""
    };
    let extra = if window { WINDOW } else { "" };
    write(
        dir,
        "obj.toml",
        &format!(
            "{}\n[[obj]]\nfile = \"room.obj\"\nroom = \"office\"\n{openings}{extra}{OUTPUTS}",
            header(rho)
        ),
    )
}

/// The same L as a `[[room]]` plan with the walls named as the OBJ's groups.
fn plan_scene(dir: &Path, rho: f64, window: bool) -> PathBuf {
    let plan: Vec<String> = PLAN
        .iter()
        .map(|c| format!("[{}, {}]", c[0], c[1]))
        .collect();
    let names: Vec<String> = WALLS.iter().map(|w| format!("\"{w}\"")).collect();
    let openings = if window {
        "openings = [\"window\"]\n"
    } else {
        ""
    };
    let extra = if window { WINDOW } else { "" };
    write(
        dir,
        "plan.toml",
        &format!(
            "{}\n[[room]]\nname = \"office\"\nplan = [{}]\nheight = {HEIGHT}\n\
             wall_names = [{}]\nmaterial = \"wall\"\nfloor = \"floor\"\nceiling = \"ceiling\"\n\
             {openings}{extra}{OUTPUTS}",
            header(rho),
            plan.join(", "),
            names.join(", ")
        ),
    )
}

fn loaded(path: &Path) -> Scene {
    load(path).unwrap_or_else(|e| panic!("{e}"))
}

#[test]
fn an_obj_l_room_with_a_window_is_the_plan_room() {
    let dir = scratch("same");
    let from_obj = obj_scene(&dir, 0.5, &l_faces(), true);
    let from_plan = plan_scene(&dir, 0.5, true);
    let (a, b) = (loaded(&from_obj), loaded(&from_plan));
    let names = |s: &Scene| -> Vec<String> { s.surfaces.iter().map(|x| x.name.clone()).collect() };
    assert_eq!(names(&a), names(&b));
    assert_eq!(a.patches.len(), b.patches.len());
    for (p, q) in a.patches.iter().zip(&b.patches) {
        assert_eq!(p.polygon.vertices, q.polygon.vertices);
        assert_eq!(p.surface, q.surface);
    }
    assert_eq!(a.windows.len(), 1, "the window lets daylight in");
    // The window's area is cut out of the south wall: faces add up to the room's surface.
    let area: f64 = a.patches.iter().map(|p| p.area).sum();
    let surface = 2.0 * 19.0 + 20.0 * HEIGHT;
    assert!((area - surface).abs() < 1e-9 * surface, "area {area}");

    let solve = |path: &Path| {
        cli::solve(
            path,
            &cli::LevelArgs::default(),
            false,
            &FormFactorOptions::default(),
        )
        .unwrap_or_else(|e| panic!("{e}"))
    };
    let (ra, rb) = (solve(&from_obj), solve(&from_plan));
    let readings = |r: &cli::Readout| -> Vec<f64> {
        let grid = r
            .grids
            .iter()
            .flat_map(|g| g.points.iter().map(|p| p.irradiance[0]));
        r.sensors
            .iter()
            .chain(&r.zones)
            .map(|x| x.irradiance[0])
            .chain(grid)
            .collect()
    };
    let (x, y) = (readings(&ra), readings(&rb));
    println!("OBJ room: {x:?}\nplan room: {y:?}");
    assert_eq!(x.len(), y.len());
    assert!(x.len() > 3, "a grid was laid out");
    for (u, v) in x.iter().zip(&y) {
        assert!(u.is_finite() && *u > 0.0);
        assert!((u - v).abs() <= 1e-12 * v.abs(), "{u} vs {v}");
    }
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn an_obj_l_room_meets_the_closed_room_identity() {
    let dir = scratch("identity");
    let flux = 10_000.0;
    let surface = 2.0 * 19.0 + 20.0 * HEIGHT;
    for rho in [0.2, 0.8] {
        let path = obj_scene(&dir, rho, &l_faces(), false);
        let want = flux / (surface * (1.0 - rho));
        let readout = cli::solve(
            &path,
            &cli::LevelArgs::default(),
            false,
            &FormFactorOptions::default(),
        )
        .unwrap_or_else(|e| panic!("{e}"));
        let got = readout.zones[0].irradiance[0];
        let err = (got - want).abs() / want;
        println!("ρ = {rho}: Φ/(S(1−ρ)) = {want:.4} lux, solve {got:.4} lux, rel. err {err:.2e}");
        assert!(err <= CLOSED_ROOM_TOLERANCE, "ρ = {rho}: {got} vs {want}");
    }
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn a_work_plane_over_an_obj_l_room_skips_the_notch() {
    let dir = scratch("grid");
    let scene = loaded(&obj_scene(&dir, 0.5, &l_faces(), false));
    let zone = scene.zones.iter().find(|z| z.name == "work_plane").unwrap();
    let grid = zone.grid.as_ref().expect("grid");
    let mut points = 0;
    for (p, _) in grid.points() {
        points += 1;
        assert!(!(p.x > 3.5 && p.y > 2.0), "{p:?} in the notch");
        assert!(
            p.x >= 0.5 && p.y >= 0.5 && p.x <= 5.5 && p.y <= 3.5,
            "{p:?} in the margin"
        );
    }
    assert!(points > 0);
    std::fs::remove_dir_all(&dir).ok();
}

/// The patches of two scenes, compared corner by corner within `tol` (m), with their
/// surfaces' names.
fn same_patches(a: &Scene, b: &Scene, tol: f64) {
    let names = |s: &Scene| -> Vec<String> { s.surfaces.iter().map(|x| x.name.clone()).collect() };
    assert_eq!(names(a), names(b));
    assert_eq!(a.patches.len(), b.patches.len());
    for (p, q) in a.patches.iter().zip(&b.patches) {
        assert_eq!(p.surface, q.surface);
        assert_eq!(p.polygon.vertices.len(), q.polygon.vertices.len());
        for (u, v) in p.polygon.vertices.iter().zip(&q.polygon.vertices) {
            assert!((*u - *v).length() <= tol, "{u:?} vs {v:?}");
        }
    }
}

#[test]
fn a_triangulated_obj_l_room_is_the_plan_room() {
    // Every quad of the L cut along a diagonal, as many exporters write it.
    let triangles: Vec<ObjFace> = l_faces()
        .into_iter()
        .flat_map(|(group, material, c)| {
            [
                (group, material, vec![c[0], c[1], c[2]]),
                (group, material, vec![c[0], c[2], c[3]]),
            ]
        })
        .collect();
    let dir = scratch("triangles");
    let a = loaded(&obj_scene(&dir, 0.5, &triangles, true));
    let b = loaded(&plan_scene(&dir, 0.5, true));
    same_patches(&a, &b, 0.0);
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn a_gabled_obj_room_is_the_room_with_those_ceiling_planes() {
    // 6 m × 4 m, eaves at 2.5 m along y = 0 and y = 4, the ridge at 3.7 m along y = 2.
    let (e, r) = (2.5, 3.7);
    let faces: Vec<ObjFace> = vec![
        (
            "floor",
            "floor",
            vec![
                [0.0, 0.0, 0.0],
                [6.0, 0.0, 0.0],
                [6.0, 4.0, 0.0],
                [0.0, 4.0, 0.0],
            ],
        ),
        (
            "roof",
            "ceiling",
            vec![[0.0, 0.0, e], [0.0, 2.0, r], [6.0, 2.0, r], [6.0, 0.0, e]],
        ),
        (
            "roof",
            "ceiling",
            vec![[0.0, 2.0, r], [0.0, 4.0, e], [6.0, 4.0, e], [6.0, 2.0, r]],
        ),
        (
            "south",
            "wall",
            vec![
                [0.0, 0.0, 0.0],
                [0.0, 0.0, e],
                [6.0, 0.0, e],
                [6.0, 0.0, 0.0],
            ],
        ),
        (
            "east",
            "wall",
            vec![
                [6.0, 0.0, 0.0],
                [6.0, 0.0, e],
                [6.0, 2.0, r],
                [6.0, 4.0, e],
                [6.0, 4.0, 0.0],
            ],
        ),
        (
            "north",
            "wall",
            vec![
                [6.0, 4.0, 0.0],
                [6.0, 4.0, e],
                [0.0, 4.0, e],
                [0.0, 4.0, 0.0],
            ],
        ),
        (
            "west",
            "wall",
            vec![
                [0.0, 4.0, 0.0],
                [0.0, 4.0, e],
                [0.0, 2.0, r],
                [0.0, 0.0, e],
                [0.0, 0.0, 0.0],
            ],
        ),
    ];
    let dir = scratch("gable");
    write(&dir, "room.mtl", MTL);
    write(&dir, "room.obj", &obj(&faces));
    let common = "\n[[zone]]\nname = \"all\"\nsurfaces = [\"attic*\"]\n";
    let from_obj = write(
        &dir,
        "obj.toml",
        &format!(
            "{}\n[[obj]]\nfile = \"room.obj\"\nroom = \"attic\"\n{common}",
            header(0.5)
        ),
    );
    let from_plan = write(
        &dir,
        "plan.toml",
        &format!(
            "{}\n[[room]]\nname = \"attic\"\nplan = [[0, 0], [6, 0], [6, 4], [0, 4]]\n\
             ceiling_planes = [\n  {{ through = [[0, 0, 2.5], [6, 0, 2.5], [0, 2, 3.7]] }},\n  \
             {{ through = [[0, 4, 2.5], [0, 2, 3.7], [6, 4, 2.5]] }},\n]\n\
             wall_names = [\"south\", \"east\", \"north\", \"west\"]\n\
             material = \"wall\"\nfloor = \"floor\"\nceiling = \"ceiling\"\n{common}",
            header(0.5)
        ),
    );
    let (a, b) = (loaded(&from_obj), loaded(&from_plan));
    // The planes come from three points in one file and a face's normal in the other: the
    // same within rounding, which may turn a tie in how a gable end's pentagon is cut, so the
    // patches are compared as sets, each surface's by its centroids (within 1e-9 m).
    let names = |s: &Scene| -> Vec<String> { s.surfaces.iter().map(|x| x.name.clone()).collect() };
    assert_eq!(names(&a), names(&b));
    for (x, y) in a.surfaces.iter().zip(&b.surfaces) {
        let (pa, pb) = (
            &a.patches[x.patch_range.clone()],
            &b.patches[y.patch_range.clone()],
        );
        assert_eq!(pa.len(), pb.len(), "{}", x.name);
        for p in pa {
            assert!(
                pb.iter()
                    .any(|q| (p.centroid - q.centroid).length() < 1e-9
                        && (p.area - q.area).abs() < 1e-9),
                "{}: no patch at {:?} in the plan room",
                x.name,
                p.centroid
            );
        }
    }
    let area: f64 = a.patches.iter().map(|p| p.area).sum();
    // Floor 24, two slopes 6 × √(2² + 1.2²) each, the long walls 6 × 2.5 each, the gable
    // ends 4 × 2.5 + 4 × 1.2 / 2 each.
    let slope = 6.0 * (4.0f64 + 1.44).sqrt();
    let surface = 24.0 + 2.0 * slope + 2.0 * 15.0 + 2.0 * (10.0 + 2.4);
    assert!(
        (area - surface).abs() < 1e-9 * surface,
        "area {area} vs {surface}"
    );
    std::fs::remove_dir_all(&dir).ok();
}
