//! An exact port (docs/building.md, "Ports"; docs/math.md, "Rooms seen through an exact
//! port"): the two rooms of tests/ports.rs joined by their open door with `model = "exact"`,
//! built apart and merged, against both rooms solved as one scene whose doorway is a real
//! hole.
//!
//! - The one scene is written from the same boxes and quads as the rooms' own scenes, so that
//!   it is meshed into the same patches (the doorway's two black quads left out of it): the
//!   comparison measures the port's model, not a different meshing. Its form factors are the
//!   dense matrix of all its patches, its solve the exact one of the whole system.
//! - A room whose neighbour returns no light (all black) reads its own channel exactly as
//!   built alone.
//! - The diffuse port misses the same one scene by far more.
//! - A luminaire with photometry lights the other room through the doorway as in the one
//!   scene.
//! - One machine or two shards give the same bytes; bad port models, and rooms built with
//!   other form-factor rules, are errors naming the manifest's line and item.
//! - Daylight through a window and then the doorway reads as in the one scene.

mod common;
mod ports_exact {
    pub mod daylight;
    pub mod three_rooms;
}

use std::path::{Path, PathBuf};
use std::sync::OnceLock;

use common::one_scene::with_the_hole;
use common::two_rooms::{
    left_luminaire, rooms_in_one_scene, two_rooms, two_rooms_with_luminaire, PORT,
};
use eigenrad_precompute::building::{self, Manifest, Part};
use eigenrad_precompute::formfactor::FormFactorOptions;
use eigenrad_precompute::pipeline::BuildOptions;
use eigenrad_runtime::{Basis, ChannelEvaluator};

/// Relative agreement of the merge with the one-scene solve of the two rooms with the doorway
/// a real hole, at every sensor, zone and grid point: the figure. Both are exact
/// solves of the same pair integrals in f64; the bases store f32 (relative rounding 6e-8).
const EXACT_TOLERANCE: f64 = 1e-4;

/// The port of the two rooms, exact.
fn exact_port() -> String {
    format!("{PORT}model = \"exact\"\n")
}

/// Builds every room of `manifest` (one call per shard) into `out` and merges.
fn build(manifest: &Manifest, shards: &[Vec<usize>], out: &Path) {
    build_with(manifest, shards, out, &BuildOptions::default());
}

/// [`build`] with the build's `options`.
fn build_with(manifest: &Manifest, shards: &[Vec<usize>], out: &Path, options: &BuildOptions) {
    let parts = building::parts_dir(out);
    std::fs::create_dir_all(&parts).expect("parts folder");
    for rooms in shards {
        building::build_rooms(manifest, rooms, options, &parts).unwrap_or_else(|e| panic!("{e}"));
    }
    building::merge(manifest, &parts, out, manifest.flash).unwrap_or_else(|e| panic!("{e}"));
}

/// The two rooms joined by the exact port, built on this machine and merged.
fn exact_door() -> &'static (Manifest, PathBuf) {
    static BUILT: OnceLock<(Manifest, PathBuf)> = OnceLock::new();
    BUILT.get_or_init(|| {
        let dir = common::scratch("ports-exact");
        let manifest =
            Manifest::load(&two_rooms(&dir, &exact_port())).unwrap_or_else(|e| panic!("{e}"));
        let out = dir.join("out");
        build(&manifest, &[vec![0, 1]], &out);
        (manifest, out)
    })
}

/// Every reading (sensors, zone averages, grid points; by name) of a basis with channel
/// `channel` (by name) alone at level 1.
fn readings(basis: &[u8], channel: &str) -> Vec<(String, f64)> {
    let basis = Basis::from_bytes(basis).unwrap_or_else(|e| panic!("{e}"));
    let mut eval = ChannelEvaluator::<1, 4>::new(basis).unwrap_or_else(|e| panic!("{e}"));
    let c = (0..basis.channel_count())
        .find(|&c| basis.channel_name(c).ok() == Some(channel))
        .unwrap_or_else(|| panic!("no channel {channel} in the basis"));
    eval.set_channel_level(c, 1.0).expect("level");
    let mut out = Vec::new();
    for s in 0..basis.sensor_count() {
        let name = basis.sensor_name(s).expect("sensor");
        let e = eval.sensor_irradiance(s).expect("sensor")[0];
        out.push((format!("sensor {name}"), f64::from(e)));
    }
    for z in 0..basis.zone_count() {
        let name = basis.zone_name(z).expect("zone");
        let e = eval.zone_irradiance(z).expect("zone")[0];
        out.push((format!("zone {name}"), f64::from(e)));
        for g in 0..basis.grid_points(z).expect("grid") {
            let e = eval.grid_point_irradiance(z, g).expect("point")[0];
            out.push((format!("zone {name} point {g}"), f64::from(e)));
        }
    }
    out
}

/// The two rooms as one scene with the doorway a real hole, meshed as the rooms are
/// ([`rooms_in_one_scene`] without its two door quads): its exact readings of each channel
/// alone at level 1, by output name (as [`readings`] names them) and channel name. The form
/// factors are the dense matrix of every pair of its patches with occlusion by all of them,
/// the solve the exact one of the whole system (one dense LU).
fn one_scene_with_the_hole() -> &'static Vec<(String, String, f64)> {
    static SOLVED: OnceLock<Vec<(String, String, f64)>> = OnceLock::new();
    SOLVED.get_or_init(|| solve_with_the_hole("ports-exact-hole", &rooms_in_one_scene()))
}

/// The readings of the one scene `text` ([`rooms_in_one_scene`] with more in it) solved in
/// `scratch` as [`one_scene_with_the_hole`] solves it (tests/common/one_scene.rs).
fn solve_with_the_hole(scratch: &str, text: &str) -> Vec<(String, String, f64)> {
    with_the_hole(scratch, text).channel_readings()
}

/// The one scene's reading `name` of channel `channel` (a neighbour's channel named
/// `room/channel` in a room's basis is `channel` there).
fn in_one_scene(name: &str, channel: &str) -> f64 {
    read_in(one_scene_with_the_hole(), name, channel)
}

/// The reading `name` of channel `channel` among `solved` (as [`in_one_scene`]).
fn read_in(solved: &[(String, String, f64)], name: &str, channel: &str) -> f64 {
    let bare = channel.rsplit('/').next().unwrap_or(channel);
    solved
        .iter()
        .find(|(n, c, _)| n == name && c == bare)
        .map(|(_, _, v)| *v)
        .unwrap_or_else(|| panic!("no reading {name} of {bare} in the one scene"))
}

/// The relative error of `got`, what controller `controller`'s merged basis reads at output
/// `name` for `channel`, against `want`, the one scene's reading; fails unless the output
/// reads some light and the error is within [`EXACT_TOLERANCE`].
fn merged_error(controller: &str, name: &str, channel: &str, got: f64, want: f64) -> f64 {
    assert!(
        want > 0.0,
        "{controller}: {name} reads no light of {channel}"
    );
    let error = (got - want).abs() / want;
    assert!(
        error <= EXACT_TOLERANCE,
        "{controller}: {name} of channel {channel}: merged {got}, one scene {want} (relative {error:.2e})"
    );
    error
}

#[test]
fn built_apart_and_merged_equals_the_two_rooms_as_one_scene_with_the_doorway_open() {
    let (manifest, out) = exact_door();
    // The channels as each room's basis names them: its own, then the other's through the door.
    let names = [["left", "right/right"], ["left/left", "right"]];
    let mut worst: [f64; 2] = [0.0; 2];
    let mut count = 0;
    for side in 0..2 {
        let controller = &manifest.controllers[side];
        let basis = std::fs::read(building::basis_path(out, &controller.name)).expect("basis");
        for (column, channel) in names[side].iter().enumerate() {
            for (name, got) in readings(&basis, channel) {
                let want = in_one_scene(&name, channel);
                let error = merged_error(&controller.name, &name, channel, got, want);
                let own = usize::from(column != side);
                worst[own] = worst[own].max(error);
                count += 1;
            }
        }
    }
    eprintln!(
        "exact port against the two rooms as one scene with the doorway open, {count} readings: largest relative difference {:.2e} (own channel), {:.2e} (the other room's)",
        worst[0], worst[1]
    );
    let parts = building::parts_dir(out);
    for room in &manifest.rooms {
        let path = parts.join(format!("{}.part", room.name));
        let part = Part::read(&path).unwrap_or_else(|e| panic!("{e}"));
        let bytes = std::fs::metadata(&path).expect("part").len();
        eprintln!(
            "room {}: {} patches, {} seen patches, part {bytes} bytes",
            room.name,
            part.exact.patches,
            part.exact.seen.len()
        );
    }
}

/// The light of the left room's luminaire with photometry, straight through the door and
/// reflected on both sides, merged against the two rooms as one scene with the doorway open
/// and the same luminaire, whose direct light the build's luminaire code computes over the
/// whole scene.
#[test]
fn a_luminaire_with_photometry_lights_the_other_room_through_the_doorway_as_in_one_scene() {
    let dir = common::scratch("ports-exact-luminaire");
    let manifest = Manifest::load(&two_rooms_with_luminaire(&dir, &exact_port()))
        .unwrap_or_else(|e| panic!("{e}"));
    let out = dir.join("out");
    build(&manifest, &[vec![0, 1]], &out);
    let one = solve_with_the_hole(
        "ports-exact-luminaire-hole",
        &(rooms_in_one_scene() + &left_luminaire()),
    );
    let mut worst: [f64; 2] = [0.0; 2];
    let mut direct_share: f64 = 0.0;
    let mut count = 0;
    for (side, channel) in [(0, "lum_left"), (1, "left/lum_left")] {
        let controller = &manifest.controllers[side];
        let basis = std::fs::read(building::basis_path(&out, &controller.name)).expect("basis");
        for (name, got) in readings(&basis, channel) {
            let want = read_in(&one, &name, channel);
            let error = merged_error(&controller.name, &name, channel, got, want);
            worst[side] = worst[side].max(error);
            count += 1;
            if side == 1 {
                direct_share = direct_share.max(read_in(&one, &name, "direct lum_left") / want);
            }
        }
    }
    eprintln!(
        "exact port with a luminaire with photometry against the one scene, {count} readings: largest relative difference {:.2e} (its own room), {:.2e} (through the door); its direct light is up to {:.0} % of a reading in the other room",
        worst[0],
        worst[1],
        100.0 * direct_share
    );
    // Light straight from the luminaire through the door is much of what the other room
    // reads: a merge without it misses the one scene by far more than the tolerance.
    assert!(direct_share > 0.5, "{direct_share}");
}

/// The diffuse port's error against the same one scene: the doorway as a diffusing surface
/// misses what the exact port meets, so the comparison above can fail (and measures the hole).
const DIFFUSE_AT_LEAST: f64 = 0.1;

#[test]
fn the_diffuse_port_misses_the_one_scene_by_far_more() {
    let dir = common::scratch("ports-exact-diffuse");
    let manifest = Manifest::load(&two_rooms(&dir, PORT)).unwrap_or_else(|e| panic!("{e}"));
    let out = dir.join("out");
    build(&manifest, &[vec![0, 1]], &out);
    let basis = std::fs::read(building::basis_path(&out, "right")).expect("basis");
    let worst = readings(&basis, "left/left")
        .into_iter()
        .map(|(name, got)| {
            let want = in_one_scene(&name, "left");
            (got - want).abs() / want
        })
        .fold(0.0, f64::max);
    eprintln!("diffuse port against the same one scene: the other room's channel {worst:.2e}");
    assert!(worst > DIFFUSE_AT_LEAST, "{worst}");
}

#[test]
fn a_room_whose_neighbour_returns_no_light_reads_its_own_channel_as_built_alone() {
    let dir = common::scratch("ports-exact-black");
    let path = two_rooms(&dir, &exact_port());
    // The right room black: nothing of the left room's light comes back through the door.
    let right = std::fs::read_to_string(dir.join("right.toml")).expect("scene");
    let black = right
        .replace(
            "floor = { reflectance = 0.3 }",
            "floor = { reflectance = 0.0 }",
        )
        .replace(
            "wall = { reflectance = 0.6 }",
            "wall = { reflectance = 0.0 }",
        )
        .replace(
            "ceiling = { reflectance = 0.8 }",
            "ceiling = { reflectance = 0.0 }",
        );
    assert_ne!(black, right);
    std::fs::write(dir.join("right.toml"), black).expect("scene");
    let manifest = Manifest::load(&path).unwrap_or_else(|e| panic!("{e}"));
    let out = dir.join("out");
    build(&manifest, &[vec![0, 1]], &out);
    // The left room alone: the same manifest without the port.
    let apart = dir.join("apart");
    std::fs::create_dir_all(&apart).expect("folder");
    for file in ["left.toml", "right.toml"] {
        std::fs::copy(dir.join(file), apart.join(file)).expect("scene");
    }
    let closed = std::fs::read_to_string(&path)
        .expect("manifest")
        .replace(&exact_port(), "");
    std::fs::write(apart.join("building.toml"), closed).expect("manifest");
    let alone = Manifest::load(&apart.join("building.toml")).unwrap_or_else(|e| panic!("{e}"));
    assert!(alone.ports.is_empty());
    build(&alone, &[vec![0, 1]], &apart.join("out"));
    let read = |out: &Path| {
        let basis = std::fs::read(building::basis_path(out, "left")).expect("basis");
        readings(&basis, "left")
    };
    let (joined, apart) = (read(&out), read(&apart.join("out")));
    assert!(joined.len() > 10);
    assert_eq!(
        joined, apart,
        "the left room's own channel, its neighbour black"
    );
}

/// Every file under `dir`, sorted.
fn files(dir: &Path) -> Vec<PathBuf> {
    let mut out = Vec::new();
    for entry in std::fs::read_dir(dir).expect("folder") {
        let path = entry.expect("entry").path();
        if path.is_dir() {
            out.extend(files(&path));
        } else {
            out.push(path);
        }
    }
    out.sort();
    out
}

#[test]
fn one_machine_and_two_shards_give_the_same_bytes() {
    let (manifest, out) = exact_door();
    let dir = common::scratch("ports-exact-shards");
    let sharded = Manifest::load(&two_rooms(&dir, &exact_port())).unwrap_or_else(|e| panic!("{e}"));
    let out2 = dir.join("out");
    build(&sharded, &[vec![1], vec![0]], &out2);
    let ours = files(out);
    let theirs = files(&out2);
    assert_eq!(ours.len(), theirs.len());
    for (a, b) in ours.iter().zip(&theirs) {
        assert_eq!(a.file_name(), b.file_name());
        if a.extension().is_some_and(|e| e == "json") {
            continue; // names its folder
        }
        assert!(
            std::fs::read(a).expect("file") == std::fs::read(b).expect("file"),
            "{} differs between one machine and two shards",
            a.display()
        );
    }
    assert_eq!(manifest.ports[0].model, building::PortModel::Exact);
}

#[test]
fn rooms_built_with_other_form_factor_rules_are_refused_naming_the_port() {
    let dir = common::scratch("ports-exact-rules");
    let manifest =
        Manifest::load(&two_rooms(&dir, &exact_port())).unwrap_or_else(|e| panic!("{e}"));
    let parts = building::parts_dir(&dir.join("out"));
    std::fs::create_dir_all(&parts).expect("parts folder");
    let coarse = BuildOptions {
        form_factors: FormFactorOptions {
            gauss_order: 3,
            ..FormFactorOptions::default()
        },
        ..BuildOptions::default()
    };
    for (room, options) in [(0, BuildOptions::default()), (1, coarse)] {
        building::build_rooms(&manifest, &[room], &options, &parts)
            .unwrap_or_else(|e| panic!("{e}"));
    }
    let e = building::merge(&manifest, &parts, &dir.join("out"), manifest.flash)
        .expect_err("rooms built by other rules")
        .to_string();
    for x in [
        "building.toml:",
        "port door",
        "gauss_order: 3",
        "same form-factor options",
    ] {
        assert!(e.contains(x), "{x:?} not in: {e}");
    }
    assert!(!dir.join("out").join("building.json").exists());
}

#[test]
fn a_part_built_without_the_exitance_the_modes_need_is_refused_naming_it() {
    let dir = common::scratch("ports-exact-modes");
    let path = two_rooms(&dir, &exact_port());
    let manifest = Manifest::load(&path).unwrap_or_else(|e| panic!("{e}"));
    assert!(manifest.controllers.iter().all(|c| !c.modes));
    let parts = building::parts_dir(&dir.join("out"));
    std::fs::create_dir_all(&parts).expect("parts folder");
    building::build_rooms(&manifest, &[0, 1], &BuildOptions::default(), &parts)
        .unwrap_or_else(|e| panic!("{e}"));
    // Without modes the parts keep no patch's exitance: the left controller now asks for them.
    let text = std::fs::read_to_string(&path).expect("manifest");
    let drives = "drives = [\"left\"]";
    assert!(text.contains(drives));
    std::fs::write(
        &path,
        text.replace(drives, &format!("{drives}\nmodes = true")),
    )
    .expect("manifest");
    let with_modes = Manifest::load(&path).unwrap_or_else(|e| panic!("{e}"));
    let e = building::merge(&with_modes, &parts, &dir.join("out"), with_modes.flash)
        .expect_err("a part without the patches' exitance")
        .to_string();
    for x in [
        "left.part",
        "modes of controller left",
        "build room left again",
    ] {
        assert!(e.contains(x), "{x:?} not in: {e}");
    }
}

#[test]
fn bad_port_models_name_the_manifest_line_and_item() {
    let dir = common::scratch("ports-exact-bad");
    for (ports, expected) in [
        (
            format!("{PORT}model = \"hole\"\n"),
            vec![
                "building.toml:",
                "port door: model",
                "\"hole\" is not a port model",
            ],
        ),
        (
            format!("{PORT}model = \"exact\"\ndirections = 5\n"),
            vec!["port door: model", "no direction bins"],
        ),
    ] {
        let path = two_rooms(&dir, &ports);
        let e = Manifest::load(&path).expect_err("a bad model").to_string();
        for x in expected {
            assert!(e.contains(x), "{x:?} not in: {e}");
        }
    }
}
