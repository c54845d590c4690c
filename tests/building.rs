//! A building (docs/building.md): every controller's basis reads, to the bit, what its whole
//! room's basis, coupled through its ports, reads at the same outputs (channels, daylight,
//! grid points); the example
//! building gives the same bytes built on one machine and as three shards; bad manifests and
//! bad parts are errors naming the file, line and item, with nothing written.
//!
//! The example building is built once per run, in process (the test profile is optimised),
//! and shared by the tests that read it.

mod common;

use std::path::{Path, PathBuf};
use std::sync::OnceLock;

use eigenrad_precompute::building::{self, Manifest, Part};
use eigenrad_precompute::pipeline::BuildOptions;
use eigenrad_runtime::{Basis, ChannelEvaluator, DaylightEvaluator, Sun};

/// Most channels of a room of the example building.
const CHANNELS: usize = 8;

fn example() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/building/building.toml")
}

/// Builds every room of `manifest` (in the order of `shards`, one call each) into `out` and
/// merges; the form factors computed afresh.
fn build(manifest: &Manifest, shards: &[Vec<usize>], out: &Path) -> building::Merged {
    let parts = building::parts_dir(out);
    std::fs::create_dir_all(&parts).expect("parts folder");
    for rooms in shards {
        building::build_rooms(manifest, rooms, &BuildOptions::default(), &parts)
            .unwrap_or_else(|e| panic!("{e}"));
    }
    building::merge(manifest, &parts, out, manifest.flash).unwrap_or_else(|e| panic!("{e}"))
}

/// The example building, built on this machine (every room at once) into a scratch folder.
fn local_example() -> &'static (Manifest, PathBuf, building::Merged) {
    static LOCAL: OnceLock<(Manifest, PathBuf, building::Merged)> = OnceLock::new();
    LOCAL.get_or_init(|| {
        let manifest = Manifest::load(&example()).unwrap_or_else(|e| panic!("{e}"));
        let out = common::scratch("building-local");
        let all: Vec<usize> = (0..manifest.rooms.len()).collect();
        let merged = build(&manifest, &[all], &out);
        (manifest, out, merged)
    })
}

/// A reproducible sequence of numbers in [0, 1) (a 64-bit LCG, Knuth's MMIX constants).
struct Numbers(u64);

impl Numbers {
    fn next(&mut self) -> f32 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (self.0 >> 40) as f32 / (1u64 << 24) as f32
    }
}

/// Every reading of `controller` (its sensors, zones and grid points, by name) through
/// `basis` with the channels at `levels` (by name) and, for a basis with daylight, a sky:
/// as raw f32 bits, so that equality is to the bit.
fn readings(basis: &[u8], levels: &[(String, f32)], sky_seed: u64) -> Vec<(String, u32)> {
    let basis = Basis::from_bytes(basis).unwrap_or_else(|e| panic!("{e}"));
    let mut channels =
        ChannelEvaluator::<1, CHANNELS>::new(basis).unwrap_or_else(|e| panic!("{e}"));
    for c in 0..basis.channel_count() {
        let name = basis.channel_name(c).expect("channel");
        let level = levels
            .iter()
            .find(|(n, _)| n == name)
            .map(|(_, l)| *l)
            .expect("a level for every channel");
        channels.set_channel_level(c, level).expect("level");
    }
    let mut out = Vec::new();
    for s in 0..basis.sensor_count() {
        let name = basis.sensor_name(s).expect("sensor");
        let e = channels.sensor_irradiance(s).expect("sensor")[0];
        out.push((format!("sensor {name}"), e.to_bits()));
    }
    for z in 0..basis.zone_count() {
        let name = basis.zone_name(z).expect("zone");
        let e = channels.zone_irradiance(z).expect("zone")[0];
        out.push((format!("zone {name}"), e.to_bits()));
        for g in 0..basis.grid_points(z).expect("grid") {
            let e = channels.grid_point_irradiance(z, g).expect("point")[0];
            out.push((format!("zone {name} point {g}"), e.to_bits()));
        }
    }
    if basis.has_daylight() {
        let mut daylight =
            DaylightEvaluator::<'_, 145, 16, 0>::new(basis).unwrap_or_else(|e| panic!("{e}"));
        let mut numbers = Numbers(sky_seed);
        let patches = basis.sky_patches().expect("sky").count();
        let luminance: Vec<f32> = (0..patches)
            .map(|_| 2000.0 + 8000.0 * numbers.next())
            .collect();
        // The sun 35° high, 20° east of south, between the sun grid's nodes.
        let sun = Sun {
            direction: eigenrad_runtime::sky::direction(35f32.to_radians(), 160f32.to_radians()),
            direct_normal: 60_000.0,
        };
        daylight
            .set_sky(&luminance, 30_000.0, Some(sun))
            .unwrap_or_else(|e| panic!("{e}"));
        for s in 0..basis.sensor_count() {
            let name = basis.sensor_name(s).expect("sensor");
            let e = daylight.sensor_illuminance(s).expect("sensor");
            out.push((format!("daylight sensor {name}"), e.to_bits()));
        }
        for z in 0..basis.zone_count() {
            let name = basis.zone_name(z).expect("zone");
            let e = daylight.zone_illuminance(z).expect("zone");
            out.push((format!("daylight zone {name}"), e.to_bits()));
            for g in 0..basis.grid_points(z).expect("grid") {
                let e = daylight.grid_point_illuminance(z, g).expect("point");
                out.push((format!("daylight zone {name} point {g}"), e.to_bits()));
            }
        }
    }
    if basis.patch_count() > 0 {
        for i in 0..basis.patch_count() {
            let m = channels.exitance(i).expect("patch")[0];
            out.push((format!("patch {i}"), m.to_bits()));
        }
    }
    out
}

#[test]
fn every_controller_reads_what_its_whole_room_reads_to_the_bit() {
    let (manifest, out, merged) = local_example();
    assert_eq!(merged.controllers.len(), 7);
    let mut numbers = Numbers(29);
    // The rooms' tables as the merge couples them through their ports (the office and the
    // corridor: each also holds the other's channels through their door).
    let parts_dir = building::parts_dir(out);
    let parts: Vec<Part> = manifest
        .rooms
        .iter()
        .map(|room| Part::read_checked(&parts_dir, room).unwrap_or_else(|e| panic!("{e}")))
        .collect();
    let coupled =
        building::port::couple(manifest, &parts, &parts_dir).unwrap_or_else(|e| panic!("{e}"));
    for (controller, written) in manifest.controllers.iter().zip(&merged.controllers) {
        let room = &manifest.rooms[controller.room];
        let tables = &coupled.tables[controller.room];
        let whole = tables.to_bytes().expect("the room's basis");
        let own = std::fs::read(building::basis_path(out, &controller.name)).expect("basis");
        assert_eq!(written.controller, controller.name);
        assert_eq!(
            written.bytes,
            own.len(),
            "{}: the size building.json states",
            controller.name
        );
        assert!(own.len() <= manifest.flash.bytes as usize);
        assert!(
            own.len() < whole.len() || controller.modes,
            "{}: its basis is no smaller than the room's",
            controller.name
        );
        for trial in 0..3 {
            let levels: Vec<(String, f32)> = tables
                .channel_names
                .iter()
                .map(|n| (n.clone(), numbers.next()))
                .collect();
            let theirs = readings(&whole, &levels, trial);
            let mine = readings(&own, &levels, trial);
            assert!(!mine.is_empty());
            // Every reading of the controller, found among the room's under its name.
            for (name, bits) in &mine {
                let (_, room_bits) = theirs.iter().find(|(n, _)| n == name).unwrap_or_else(|| {
                    panic!(
                        "{}: {name} is not among the room's readings",
                        controller.name
                    )
                });
                assert_eq!(
                    bits,
                    room_bits,
                    "{}: {name} reads {} through its basis and {} through the room's",
                    controller.name,
                    f32::from_bits(*bits),
                    f32::from_bits(*room_bits)
                );
            }
            // Not vacuous: the controller's own light reaches what it reads.
            assert!(
                mine.iter().any(|(_, b)| f32::from_bits(*b) > 0.0),
                "{}: reads nothing but zeros",
                controller.name
            );
            let grids = mine.iter().filter(|(n, _)| n.contains(" point ")).count();
            assert_eq!(
                grids > 0,
                !controller.grids.is_empty(),
                "{}: grid points",
                controller.name
            );
            let daylight = mine.iter().any(|(n, _)| n.starts_with("daylight"));
            // The office's daylight, and the corridor's through the open door.
            assert_eq!(
                daylight,
                room.name == "office" || room.name == "corridor",
                "{}: daylight rows",
                controller.name
            );
        }
    }
    // The open floor's controllers keep their neighbours: told or bounded, as the manifest says.
    let sw = merged
        .controllers
        .iter()
        .find(|c| c.controller == "open-sw")
        .expect("open-sw");
    assert_eq!(sw.channels, ["sw", "se", "nw", "ne"]);
    assert_eq!(sw.neighbours.inputs, ["se", "nw"]);
    assert_eq!(sw.neighbours.bounds, [("ne".to_string(), 1.0)]);
    // Through the open door the office and the corridor are told each other's levels.
    let of = |name: &str| {
        merged
            .controllers
            .iter()
            .find(|c| c.controller == name)
            .expect("controller")
    };
    assert_eq!(
        of("office").neighbours.inputs,
        ["corridor/west", "corridor/east"]
    );
    assert_eq!(
        of("corridor").neighbours.inputs,
        ["office/lum1", "office/lum2", "office/lum3", "office/lum4"]
    );
    assert_eq!(of("meeting").channels, ["table", "walls"]);
}

#[test]
fn the_example_gives_the_same_bytes_on_one_machine_and_as_three_shards() {
    let (manifest, local, _) = local_example();
    let sharded = common::scratch("building-shards");
    let shards: Vec<Vec<usize>> = (0..3)
        .map(|i| manifest.shard(&format!("{i}/3")).expect("shard"))
        .collect();
    assert_eq!(shards, [vec![0, 3], vec![1], vec![2]]);
    build(manifest, &shards, &sharded);
    let files = |dir: &Path| {
        let mut names: Vec<PathBuf> = std::fs::read_dir(dir)
            .expect("folder")
            .flatten()
            .map(|e| e.path())
            .filter(|p| p.is_file())
            .collect();
        names.sort();
        names
    };
    let mut compared = 0;
    for sub in [PathBuf::new(), PathBuf::from("parts")] {
        let (a, b) = (files(&local.join(&sub)), files(&sharded.join(&sub)));
        let names = |f: &[PathBuf]| {
            f.iter()
                .map(|p| p.file_name().map(|n| n.to_owned()))
                .collect::<Vec<_>>()
        };
        assert_eq!(names(&a), names(&b));
        for (a, b) in a.iter().zip(&b) {
            if a.file_name().is_some_and(|n| n == "building.json") {
                continue; // names the folder it was written to
            }
            let (x, y) = (
                std::fs::read(a).expect("file"),
                std::fs::read(b).expect("file"),
            );
            assert!(
                x == y,
                "{}: differs between one machine and three shards",
                a.display()
            );
            compared += 1;
        }
    }
    assert_eq!(compared, 7 + 4, "seven bases and four parts");
    let _ = std::fs::remove_dir_all(&sharded);
}

#[test]
fn bad_manifests_name_the_file_line_and_item() {
    let dir = common::scratch("building-manifests");
    let out = dir.join("out");
    let o = out.to_str().expect("utf-8");
    let case = |controllers: &str| common::small_building(&dir, 1.0, Some(controllers));
    let path = |p: &Path| p.to_str().expect("utf-8").to_string();

    let m = path(&case(
        "[[controller]]\nname = \"a\"\nroom = \"cube-c\"\nsensors = [\"floor\"]\n",
    ));
    common::refused(
        &["building", &m, "--out", o],
        &out,
        &[
            "building.toml:14:",
            "controller a",
            "unknown room `cube-c`",
            "cube-a, cube-b",
        ],
    );

    let m = path(&case("[[controller]]\nname = \"a\"\nroom = \"cube-a\"\ndrives = [\"lamp\", \"lmap\"]\nsensors = [\"floor\"]\n"));
    common::refused(
        &["building", &m, "--out", o],
        &out,
        &[
            "building.toml:15:",
            "controller a: channel lmap",
            "room cube-a has no channel of this name",
            "cube-a.toml",
        ],
    );

    let m = path(&case(
        "[[controller]]\nname = \"a\"\nroom = \"cube-a\"\ndrives = [\"lamp\"]\n",
    ));
    common::refused(
        &["merge", &m, "--out", o],
        &out,
        &["building.toml:13:", "controller a", "reads nothing"],
    );

    let m = path(&case("[[controller]]\nname = \"a\"\nroom = \"cube-a\"\nsensors = [\"floor\"]\nbounds = { lamp = 2000 }\n"));
    common::refused(
        &["building", &m, "--out", o],
        &out,
        &[
            "building.toml:16:",
            "controller a: bounds.lamp",
            "not a channel level from 0 to 1000",
        ],
    );

    let m = path(&case(
        "[[controller]]\nname = \"a\"\nroom = \"cube-a\"\nsensors = [\"floor\"]\ncolour = 3\n",
    ));
    common::refused(
        &["building", &m, "--out", o],
        &out,
        &["building.toml:16:", "unknown field `colour`"],
    );

    let m = path(&common::small_building(&dir, 1.0, None));
    common::refused(
        &["building", &m, "--out", o, "--shard", "2/2"],
        &out,
        &["building.toml", "--shard 2/2", "out of range", "0 to 1"],
    );
    common::refused(
        &["building", &m, "--out", o, "--shard", "0/3"],
        &out,
        &["--shard 0/3", "3 shards for 2 rooms"],
    );
    common::refused(
        &["building", &m, "--out", o, "--shard", "x"],
        &out,
        &["--shard x", "not a shard I/N"],
    );
    common::refused(
        &["building", &m, "--out", o, "--room", "cube-c"],
        &out,
        &["--room cube-c", "no room of that name", "cube-a, cube-b"],
    );
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn merge_refuses_missing_parts_and_parts_of_other_scenes_or_versions() {
    let dir = common::scratch("building-parts");
    let out = dir.join("out");
    let o = out.to_str().expect("utf-8").to_string();
    let manifest = common::small_building(&dir, 1.0, None);
    let m = manifest.to_str().expect("utf-8").to_string();
    let built = common::run(&["building", &m, "--out", &o, "--room", "cube-a"]);
    assert!(built.status.success(), "{}", common::stderr(&built));
    let parts = building::parts_dir(&out);
    assert!(parts.join("cube-a.part").is_file() && !parts.join("cube-b.part").exists());

    // A part missing: the room, its line and the part looked for are named.
    common::refused(
        &["merge", &m, "--out", &o],
        &out,
        &[
            "cube-b.part",
            "room cube-b (",
            "building.toml:9",
            "has no part here",
        ],
    );

    let built = common::run(&["building", &m, "--out", &o, "--shard", "1/2"]);
    assert!(built.status.success(), "{}", common::stderr(&built));
    let merged = common::run(&["merge", &m, "--out", &o]);
    assert!(merged.status.success(), "{}", common::stderr(&merged));
    let basis_a = std::fs::read(out.join("a.basis")).expect("a.basis");
    for f in ["a.basis", "b.basis", "building.json"] {
        std::fs::remove_file(out.join(f)).expect("remove output");
    }

    // A part of another version of the program.
    let part_path = parts.join("cube-b.part");
    let good = std::fs::read(&part_path).expect("part");
    let mut part = Part::read(&part_path).unwrap_or_else(|e| panic!("{e}"));
    part.program = "eigenrad 0.0.9 (basis format 4)".into();
    part.write(&part_path).unwrap_or_else(|e| panic!("{e}"));
    common::refused(
        &["merge", &m, "--out", &o],
        &out,
        &[
            "cube-b.part",
            "built by eigenrad 0.0.9 (basis format 4)",
            "build room cube-b again",
        ],
    );

    // A damaged part.
    let mut damaged = good.clone();
    let middle = damaged.len() / 2;
    damaged[middle] ^= 1;
    std::fs::write(&part_path, &damaged).expect("part");
    common::refused(
        &["merge", &m, "--out", &o],
        &out,
        &["cube-b.part", "damaged"],
    );

    // Another room's part under this room's name.
    std::fs::copy(parts.join("cube-a.part"), &part_path).expect("copy part");
    common::refused(
        &["merge", &m, "--out", &o],
        &out,
        &["cube-b.part", "holds room cube-a, not room cube-b"],
    );

    // The scene changed since its part was built.
    std::fs::write(&part_path, &good).expect("part");
    let scene = dir.join("cube-b.toml");
    let edited = common::scene(1.0).replace("flux = 1000", "flux = 1200");
    std::fs::write(&scene, edited).expect("scene");
    common::refused(
        &["merge", &m, "--out", &o],
        &out,
        &[
            "cube-b.part",
            "built from another version of",
            "cube-b.toml",
            "build room cube-b again",
        ],
    );

    // The same room built again merges, and the untouched room's basis is the same bytes.
    let built = common::run(&["building", &m, "--out", &o, "--room", "cube-b"]);
    assert!(built.status.success(), "{}", common::stderr(&built));
    let merged = common::run(&["merge", &m, "--out", &o]);
    assert!(merged.status.success(), "{}", common::stderr(&merged));
    assert_eq!(
        std::fs::read(out.join("a.basis")).expect("a.basis"),
        basis_a
    );
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_basis_over_its_flash_names_the_controller_and_its_sections() {
    let dir = common::scratch("building-flash");
    let out = dir.join("out");
    let o = out.to_str().expect("utf-8").to_string();
    let manifest = common::small_building(
        &dir,
        1.0,
        Some("[[controller]]\nname = \"a\"\nroom = \"cube-a\"\ndrives = [\"lamp\"]\nsensors = [\"floor\"]\nmodes = true\n"),
    );
    let m = manifest.to_str().expect("utf-8").to_string();
    common::refused(
        &["building", &m, "--out", &o, "--flash", "1KiB"],
        &out,
        &[
            "building.toml:13:",
            "controller a",
            "more than the 1 KiB of flash",
            "by section: patches and modes",
            "outputs",
        ],
    );
    // The parts are there: a larger budget merges them.
    let merged = common::run(&["merge", &m, "--out", &o, "--flash", "64KiB"]);
    assert!(merged.status.success(), "{}", common::stderr(&merged));
    assert!(out.join("a.basis").is_file());
    let _ = std::fs::remove_dir_all(&dir);
}
