//! What the command-line tests share: the `eigenrad` binary of the test's profile (built once
//! per run), scratch folders, a small scene and ways to run the command.
//!
//! The binary is built once per test run (`cargo build -p eigenrad-precompute --bin
//! eigenrad`, a no-op when it is up to date) next to the test's own profile folder.
// Each test crate uses its own part of these.
#![allow(dead_code)]

pub mod l_office;
pub mod one_scene;
pub mod radiance;
pub mod three_rooms;
pub mod two_rooms;

use std::path::{Path, PathBuf};
use std::process::{Command, Output};
use std::sync::OnceLock;

/// The `eigenrad` binary of this test's profile, built if needed.
pub fn eigenrad() -> &'static Path {
    static BINARY: OnceLock<PathBuf> = OnceLock::new();
    BINARY.get_or_init(|| {
        // target/<profile>/deps/cli_files-<hash> → target/<profile>/eigenrad
        let exe = std::env::current_exe().expect("test executable path");
        let profile_dir = exe
            .parent()
            .and_then(Path::parent)
            .expect("target/<profile>/deps")
            .to_path_buf();
        let mut build = Command::new(std::env::var("CARGO").unwrap_or_else(|_| "cargo".into()));
        build
            .args(["build", "-p", "eigenrad-precompute", "--bin", "eigenrad"])
            .current_dir(env!("CARGO_MANIFEST_DIR"));
        if profile_dir.file_name().is_some_and(|n| n == "release") {
            build.arg("--release");
        }
        let status = build.status().expect("run cargo build");
        assert!(status.success(), "cargo build of eigenrad failed");
        let binary = profile_dir.join(format!("eigenrad{}", std::env::consts::EXE_SUFFIX));
        assert!(binary.is_file(), "no binary at {}", binary.display());
        binary
    })
}

/// A fresh folder for one test.
pub fn scratch(test: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("eigenrad-cli-{}-{test}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("scratch folder");
    dir
}

/// A closed 2 m cube with one flush ceiling luminaire (channel `lamp`) and a floor sensor;
/// `max_edge` in metres sets its size (1 m: 28 patches).
pub fn scene(max_edge: f64) -> String {
    format!(
        r#"[scene]
name = "cube"
bands = "photopic"
unit = "m"
max_edge = {max_edge}

[materials]
wall = {{ reflectance = 0.5 }}
lamp = {{ reflectance = 0.0 }}

[[room]]
name = "room"
min = [0, 0, 0]
max = [2, 2, 2]
material = "wall"
openings = ["lamp"]

[[quad]]
name = "lamp"
material = "lamp"
corners = [[0.7, 0.7, 2], [0.7, 1.3, 2], [1.3, 1.3, 2], [1.3, 0.7, 2]]

[[channel]]
name = "lamp"
surfaces = ["lamp"]
flux = 1000

[[sensor]]
name = "floor"
position = [1, 1, 0]
normal = [0, 0, 1]
"#
    )
}

/// The form-factor cache of this test run: a folder of its own under the temporary folder,
/// so that tests neither read nor fill the user's cache.
pub fn cache_dir() -> PathBuf {
    std::env::temp_dir().join(format!("eigenrad-cli-cache-{}", std::process::id()))
}

/// The `eigenrad` command, with its form-factor cache in [`cache_dir`].
pub fn command() -> Command {
    let mut command = Command::new(eigenrad());
    command.env("EIGENRAD_CACHE_DIR", cache_dir());
    command
}

pub fn run(args: &[&str]) -> Output {
    command().args(args).output().expect("run eigenrad")
}

pub fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// Builds `scene` (text) in `dir` into `out`; returns the command's output.
pub fn build(dir: &Path, scene_text: &str, out: &str, extra: &[&str]) -> Output {
    let scene = dir.join("scene.toml");
    std::fs::write(&scene, scene_text).expect("write scene");
    let out = dir.join(out);
    let mut args = vec![
        "build",
        scene.to_str().expect("utf-8 path"),
        "-o",
        out.to_str().expect("utf-8 path"),
        "--modes",
        "4",
    ];
    args.extend_from_slice(extra);
    run(&args)
}

/// A good basis of the small cube, built in `dir` as `good.basis`.
pub fn good_basis(dir: &Path) -> PathBuf {
    let o = build(dir, &scene(1.0), "good.basis", &[]);
    assert!(o.status.success(), "build failed: {}", stderr(&o));
    dir.join("good.basis")
}

/// The names of the files in `dir`, sorted.
pub fn listing(dir: &Path) -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(dir)
        .expect("list folder")
        .map(|e| e.expect("entry").file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    names
}

/// Runs `eigenrad` with `args`; it must fail (exit code 1), say every one of `expected` on
/// stderr, and leave no basis, building index nor temporary file in `out`.
pub fn refused(args: &[&str], out: &Path, expected: &[&str]) {
    let o = run(args);
    let err = stderr(&o);
    assert_eq!(o.status.code(), Some(1), "{args:?}: {err}");
    for e in expected {
        assert!(err.contains(e), "{args:?}: {e:?} not in:\n{err}");
    }
    let written: Vec<String> = std::fs::read_dir(out)
        .into_iter()
        .flatten()
        .flatten()
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .filter(|n| n.ends_with(".basis") || n == "building.json" || n.ends_with(".tmp"))
        .collect();
    assert!(written.is_empty(), "{args:?} wrote {written:?}");
}

/// A 3 m × 2 m × 2.5 m room (walls ρ 0.5, floor 0.25) with a desk (ρ 0.4, no bottom face)
/// that shades part of the floor, and two channels: a black ceiling lamp (ρ 0, 3000 lm) and a
/// reflecting wall panel (ρ 0.3, 800 lm), both flush openings. `name` and `max_edge` (m) are
/// the scene's; callers append their sensors and zones.
pub fn two_channel_room(name: &str, max_edge: f64) -> String {
    format!(
        r#"
[scene]
name = "{name}"
bands = "photopic"
unit = "m"
max_edge = {max_edge}

[materials]
wall = {{ reflectance = 0.5 }}
floor = {{ reflectance = 0.25 }}
desk = {{ reflectance = 0.4 }}
lamp = {{ reflectance = 0.0 }}
panel = {{ reflectance = 0.3 }}

[[room]]
name = "room"
min = [0, 0, 0]
max = [3, 2, 2.5]
material = "wall"
floor = "floor"
openings = ["lamp", "panel"]

[[block]]
name = "desk"
min = [0.8, 0.6, 0]
max = [2.0, 1.4, 0.7]
material = "desk"
bottom = false

[[quad]]
name = "lamp"
material = "lamp"
corners = [[1.2, 0.7, 2.5], [1.2, 1.3, 2.5], [1.8, 1.3, 2.5], [1.8, 0.7, 2.5]]

[[quad]]
name = "panel"
material = "panel"
corners = [[0, 1.5, 0.8], [0, 1.5, 1.8], [0, 0.5, 1.8], [0, 0.5, 0.8]]

[[channel]]
name = "lamp"
surfaces = ["lamp"]
flux = 3000

[[channel]]
name = "panel"
surfaces = ["panel"]
flux = 800
"#
    )
}

/// The white furnace of docs/math.md, "Exact results": a closed 4 m cube whose every surface
/// has reflectance `rho` and emits `e` (one channel, `all`), with a work plane (`plane`) at
/// 0.8 m. Every patch's exitance is `e / (1 − rho)`, and every upward point inside sees it.
pub fn white_furnace(rho: f64, e: f64) -> String {
    format!(
        r#"
[scene]
name = "furnace"
bands = "photopic"
unit = "m"
max_edge = 1.0

[materials]
surface = {{ reflectance = {rho} }}

[[room]]
name = "room"
min = [0, 0, 0]
max = [4, 4, 4]
material = "surface"

[[channel]]
name = "all"
surfaces = ["room*"]
exitance = {e}

[[zone]]
name = "plane"
work_plane = {{ height = 0.8 }}
"#
    )
}

/// A 4 × 3 × 2.8 m room with a 2 × 1.3 m clear window in its y = 0 wall (facing south at
/// `north = 0`), a flush ceiling lamp (channel `lamp`), a desk sensor, a ceiling photocell and
/// a work plane; meshed coarsely (0.7 m) so that each solve takes a fraction of a second.
/// `site` is its `[site]` table, or nothing.
pub fn daylit_room(site: &str) -> String {
    format!(
        r#"[scene]
name = "daylit"
bands = "photopic"
unit = "m"
max_edge = 0.7

{site}

[materials]
floor = {{ reflectance = 0.2 }}
wall = {{ reflectance = 0.5 }}
ceiling = {{ reflectance = 0.7 }}
glass = {{ reflectance = 0.0, transmittance = 0.7 }}
lamp = {{ reflectance = 0.0 }}

[[room]]
name = "room"
min = [0, 0, 0]
max = [4, 3, 2.8]
material = "wall"
floor = "floor"
ceiling = "ceiling"
openings = ["window", "lamp"]

[[quad]]
name = "window"
material = "glass"
corners = [[1, 0, 0.9], [1, 0, 2.2], [3, 0, 2.2], [3, 0, 0.9]]

[[quad]]
name = "lamp"
material = "lamp"
corners = [[1.7, 1.2, 2.8], [1.7, 1.8, 2.8], [2.3, 1.8, 2.8], [2.3, 1.2, 2.8]]

[[channel]]
name = "lamp"
surfaces = ["lamp"]
flux = 2000

[[sensor]]
name = "desk"
position = [2, 1.5, 0.8]
normal = [0, 0, 1]

[[sensor]]
name = "photocell"
position = [2, 2.5, 2.79]
normal = [0, 0, -1]
half_angle = 45

[[zone]]
name = "work_plane"
work_plane = {{ room = "room", height = 0.8, margin = 0.5, max_edge = 0.7 }}
"#
    )
}

/// A `[site]` in Vienna with the window facing south and the offset of CET.
pub const VIENNA: &str = r#"[site]
latitude = 48.21
longitude = 16.37
north = 0
ground_reflectance = 0.2
utc_offset = "+01:00""#;

/// A small building of two cubes ([`scene`] at `max_edge`, m) in `dir`: `cube-a` with
/// controller `a`, `cube-b` with controller `b`; `controllers` replaces the controllers when
/// given. Returns the manifest's path.
pub fn small_building(dir: &Path, max_edge: f64, controllers: Option<&str>) -> PathBuf {
    for room in ["cube-a", "cube-b"] {
        std::fs::write(dir.join(format!("{room}.toml")), scene(max_edge)).expect("scene");
    }
    let default = "[[controller]]\nname = \"a\"\nroom = \"cube-a\"\ndrives = [\"lamp\"]\nsensors = [\"floor\"]\n\n\
                   [[controller]]\nname = \"b\"\nroom = \"cube-b\"\ndrives = [\"lamp\"]\nsensors = [\"floor\"]\n";
    let text = format!(
        "[building]\nname = \"cubes\"\n\n[[room]]\nname = \"cube-a\"\nscene = \"cube-a.toml\"\n\n\
         [[room]]\nname = \"cube-b\"\nscene = \"cube-b.toml\"\n\n{}",
        controllers.unwrap_or(default)
    );
    let path = dir.join("building.toml");
    std::fs::write(&path, text).expect("manifest");
    path
}
