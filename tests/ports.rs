//! Rooms that share light through a port (docs/building.md, "Ports"; docs/math.md, "Rooms
//! coupled through ports"): two small rooms, `left` (3 m × 3 m) and `right` (2 m × 3 m), each
//! 2.5 m high, joined by an open door (1 m × 2 m) in the wall x = 3 m, each lit by an emitting
//! ceiling panel on a channel of its own.
//!
//! - Built apart and merged, they read what one dense solve of the two rooms together reads,
//!   its door a two-sided diffusing pass-through (written here from the rooms' form factors,
//!   independently of the merge's port system), within 1e-4 at every sensor, zone and grid
//!   point.
//! - Against the two rooms as one scene whose doorway is a real hole, the difference the
//!   diffuse port makes is measured and held to its stated bound, and a directional port
//!   (direction bins, docs/math.md "Directional ports") errs less.
//! - One machine or two shards give the same bytes; without the port the rooms are
//!   independent; bad ports are errors naming the manifest's line and item.

mod common;

use common::two_rooms::*;

use std::path::{Path, PathBuf};
use std::sync::OnceLock;

use eigenrad_precompute::accuracy::metric::patch_error;
use eigenrad_precompute::accuracy::runtime_eval::{evaluate_daylight, SkyState};
use eigenrad_precompute::building::{self, controller, port, Manifest, Part};
use eigenrad_precompute::formfactor::FormFactorOptions;
use eigenrad_precompute::pipeline::{self, BuildOptions, ModeSelection, Prepared};
use eigenrad_precompute::radiosity::{LightResponse, System};
use eigenrad_precompute::sources::daylight::nodes::room_sun;
use eigenrad_precompute::sources::daylight::{sky_response, sun_light, DaylightOptions};
use eigenrad_precompute::sources::ChannelLight;
use eigenrad_runtime::sky::patches::SkyPatches;
use eigenrad_runtime::writer::BasisTables;
use eigenrad_runtime::{Basis, ChannelEvaluator, Sun};

/// Relative agreement of the merge with the one-scene solve of the same model (the door a
/// diffusing pass-through): the figure. Both are exact solves of one linear system in
/// f64, the bases store f32 (relative rounding 6e-8): what remains is far below.
const COUPLING_TOLERANCE: f64 = 1e-4;

/// Area-weighted RMS difference of the daylight's patch exitance through every mode from the
/// one-scene solve: the modes are complete, what remains is `f32` rounding of `n` terms (as
/// tests/daylight_basis.rs for one room).
const FULL_MODES: f64 = 1e-4;

/// The diffuse port against the doorway as a real hole: a modelling error, measured here
/// (docs/accuracy.md, "Ports"). The light a room's own channel sends out through the door and
/// gets back is a small share of its readings, so its own channel barely moves.
const OWN_LIGHT_TOLERANCE: f64 = 0.01;
/// The light of the other room's channel: a diffusing door re-emits evenly over the
/// hemisphere what in the doorway keeps its direction (the light crossing it goes on straight
/// ahead), so points in front of the door get too little of it (half, here) and points to
/// its sides too much (up to 86 % here): within 100 %.
const THROUGH_DOOR_TOLERANCE: f64 = 1.0;
/// Both channels at level 1, what a controller reads: the neighbour's light is a tenth to a
/// third of a room's own here, so the port's error is at most 15 % of the reading (in front of
/// the door, measured); within 20 %.
const BOTH_TOLERANCE: f64 = 0.2;

/// The directional port of the test: a cone and four sectors (up, down and the two sides of
/// the door).
const TESTED_DIRECTIONS: usize = 5;
/// The other room's light through a door of [`TESTED_DIRECTIONS`] bins against the hole:
/// measured (docs/accuracy.md, "Ports") with a margin.
const DIRECTIONAL_THROUGH_DOOR_TOLERANCE: f64 = 1.0;
/// The other room's light at the sensors and zones through a door of [`TESTED_DIRECTIONS`]
/// bins against the hole: measured (41 %) with a margin; the diffuse port errs by 49 %.
const DIRECTIONAL_SENSORS_AND_ZONES_TOLERANCE: f64 = 0.45;
/// Both channels at level 1 through a door of [`TESTED_DIRECTIONS`] bins: measured with a
/// margin.
const DIRECTIONAL_BOTH_TOLERANCE: f64 = 0.15;

/// Builds every room of `manifest` (one call per shard) into `out` and merges.
fn build(manifest: &Manifest, shards: &[Vec<usize>], out: &Path) -> building::Merged {
    let parts = building::parts_dir(out);
    std::fs::create_dir_all(&parts).expect("parts folder");
    for rooms in shards {
        building::build_rooms(manifest, rooms, &BuildOptions::default(), &parts)
            .unwrap_or_else(|e| panic!("{e}"));
    }
    building::merge(manifest, &parts, out, manifest.flash).unwrap_or_else(|e| panic!("{e}"))
}

/// The two rooms with their door open, built on this machine and merged, shared by the tests.
fn door_open() -> &'static (Manifest, PathBuf) {
    static BUILT: OnceLock<(Manifest, PathBuf)> = OnceLock::new();
    BUILT.get_or_init(|| {
        let dir = common::scratch("ports-open");
        let manifest = Manifest::load(&two_rooms(&dir, PORT)).unwrap_or_else(|e| panic!("{e}"));
        let out = dir.join("out");
        build(&manifest, &[vec![0, 1]], &out);
        (manifest, out)
    })
}

/// The two rooms with their door open and daylight through the left room's window, built
/// with every mode (so that the daylight's patch exitance through the modes is exact too),
/// both controllers keeping them, and merged.
fn door_open_daylit() -> (Manifest, PathBuf) {
    let dir = common::scratch("ports-daylit");
    let path = two_rooms(&dir, PORT);
    std::fs::write(dir.join("left.toml"), daylit_left_scene()).expect("scene");
    both_keep_the_modes(&path);
    let manifest = Manifest::load(&path).unwrap_or_else(|e| panic!("{e}"));
    assert!(manifest.controllers.iter().all(|c| c.modes));
    let out = dir.join("out");
    let parts = building::parts_dir(&out);
    std::fs::create_dir_all(&parts).expect("parts folder");
    let every_mode = BuildOptions {
        modes: ModeSelection::Count(usize::MAX),
        ..BuildOptions::default()
    };
    building::build_rooms(&manifest, &[0, 1], &every_mode, &parts)
        .unwrap_or_else(|e| panic!("{e}"));
    building::merge(&manifest, &parts, &out, manifest.flash).unwrap_or_else(|e| panic!("{e}"));
    (manifest, out)
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
        out.push((
            format!("sensor {name}"),
            f64::from(eval.sensor_irradiance(s).expect("sensor")[0]),
        ));
    }
    for z in 0..basis.zone_count() {
        let name = basis.zone_name(z).expect("zone");
        out.push((
            format!("zone {name}"),
            f64::from(eval.zone_irradiance(z).expect("zone")[0]),
        ));
        for g in 0..basis.grid_points(z).expect("grid") {
            let e = eval.grid_point_irradiance(z, g).expect("point")[0];
            out.push((format!("zone {name} point {g}"), f64::from(e)));
        }
    }
    out
}

/// Solves `a x = b` for every column of `b` (row-major, `n × n` and `n × k`) by Gaussian
/// elimination with partial pivoting.
fn solve(mut a: Vec<Vec<f64>>, mut b: Vec<Vec<f64>>) -> Vec<Vec<f64>> {
    let n = a.len();
    for col in 0..n {
        let pivot = (col..n)
            .max_by(|&i, &j| a[i][col].abs().total_cmp(&a[j][col].abs()))
            .expect("a row");
        a.swap(col, pivot);
        b.swap(col, pivot);
        assert!(a[col][col].abs() > 1e-12, "singular at {col}");
        for row in col + 1..n {
            let f = a[row][col] / a[col][col];
            if f != 0.0 {
                for k in col..n {
                    a[row][k] -= f * a[col][k];
                }
                for k in 0..b[row].len() {
                    b[row][k] -= f * b[col][k];
                }
            }
        }
    }
    for col in (0..n).rev() {
        for k in 0..b[col].len() {
            let s: f64 = (col + 1..n).map(|j| a[col][j] * b[j][k]).sum();
            b[col][k] = (b[col][k] - s) / a[col][col];
        }
    }
    b
}

/// The patches of surface `name` in a prepared room.
fn patches_of(room: &Prepared, name: &str) -> std::ops::Range<usize> {
    room.scene
        .surfaces
        .iter()
        .find(|s| s.name == name)
        .map(|s| s.patch_range.clone())
        .unwrap_or_else(|| panic!("no surface {name}"))
}

/// The two rooms solved as one system, the door a two-sided diffusing pass-through of
/// transmittance 1: every patch of either room obeys `M_i = M0_i + ρ_i (F M)_i` in its room,
/// except the door's patches, whose exitance into one room is the irradiance the matching
/// patch receives from the other, `M_i = (F M)_i' + E_ext,i'`. One dense elimination of the
/// whole system (both rooms' patches), a right-hand side per channel (left's, then right's); returns
/// each room's exitance and readings (sensors, zones, grid points) per channel. `systems` are the rooms'
/// systems with the lights to solve for as their channels.
fn one_system(rooms: [&Prepared; 2], systems: [&System; 2]) -> [Vec<LightResponse>; 2] {
    let n = [systems[0].patch_count(), systems[1].patch_count()];
    let offset = [0, n[0]];
    let total = n[0] + n[1];
    let door = [patches_of(rooms[0], "door"), patches_of(rooms[1], "door")];
    // The patch of the other room's door at the same place.
    let across = |side: usize, i: usize| -> usize {
        let c = rooms[side].scene.patches[i].centroid;
        door[1 - side]
            .clone()
            .find(|&k| {
                let d = rooms[1 - side].scene.patches[k].centroid;
                (c.x - d.x).abs() + (c.y - d.y).abs() + (c.z - d.z).abs() < 1e-9
            })
            .expect("the door's patches match")
    };
    let channels = [systems[0].channel_count(), systems[1].channel_count()];
    let columns = channels[0] + channels[1];
    let mut a: Vec<Vec<f64>> = (0..total)
        .map(|i| (0..total).map(|j| if i == j { 1.0 } else { 0.0 }).collect())
        .collect();
    let mut rhs = vec![vec![0.0; columns]; total];
    // The light of channel `column` alone, in room `side`: its levels there (all 0 when it
    // is the other room's).
    let levels = |side: usize, column: usize| -> Vec<f64> {
        (0..channels[side])
            .map(|c| {
                let own = if side == 0 { c } else { channels[0] + c };
                if own == column {
                    1.0
                } else {
                    0.0
                }
            })
            .collect()
    };
    for side in 0..2 {
        let s = systems[side];
        let g = s.operator();
        for i in 0..n[side] {
            let row = offset[side] + i;
            if door[side].contains(&i) {
                let (other, k) = (1 - side, across(side, i));
                let o = systems[other];
                for j in 0..n[other] {
                    a[row][offset[other] + j] -= o.operator().entry(k, j) / o.area[k];
                }
                for column in 0..columns {
                    // The other room's direct light on the door from beyond its patches.
                    let direct =
                        o.patch_irradiance(0, &vec![0.0; n[other]], &levels(other, column));
                    rhs[row][column] = direct[k];
                }
            } else {
                let rho = s.reflectance[0][i];
                for j in 0..n[side] {
                    a[row][offset[side] + j] -= rho * g.entry(i, j) / s.area[i];
                }
                for column in 0..columns {
                    rhs[row][column] = s.initial_exitance(0, &levels(side, column), &[])[i];
                }
            }
        }
    }
    let m = solve(a, rhs);
    std::array::from_fn(|side| {
        let s = systems[side];
        (0..columns)
            .map(|column| {
                let exitance: Vec<f64> =
                    (0..n[side]).map(|i| m[offset[side] + i][column]).collect();
                let readings = s.readings(0, &exitance, &levels(side, column));
                LightResponse { exitance, readings }
            })
            .collect()
    })
}

#[test]
fn built_apart_and_merged_equals_one_solve_of_both_rooms_with_a_diffusing_door() {
    let (manifest, out) = door_open();
    let options = FormFactorOptions::default();
    let rooms: Vec<Prepared> = manifest
        .rooms
        .iter()
        .map(|r| pipeline::prepare(&r.scene, &options).unwrap_or_else(|e| panic!("{e}")))
        .collect();
    let reference = one_system([&rooms[0], &rooms[1]], [&rooms[0].system, &rooms[1].system]);
    // The channels as each room's basis names them: its own, then the other's through the door.
    let names = [["left", "right/right"], ["left/left", "right"]];
    let mut worst: f64 = 0.0;
    let mut through_door = 0;
    for side in 0..2 {
        let controller = &manifest.controllers[side];
        let basis = std::fs::read(building::basis_path(out, &controller.name)).expect("basis");
        for (column, channel) in names[side].iter().enumerate() {
            let merged = readings(&basis, channel);
            let exact = &reference[side][column].readings;
            assert_eq!(merged.len(), exact.len(), "{}: outputs", controller.name);
            for ((name, got), want) in merged.iter().zip(exact) {
                assert!(
                    *want > 0.0,
                    "{}: {name} reads no light of {channel}",
                    controller.name
                );
                let error = (got - want).abs() / want;
                assert!(
                    error <= COUPLING_TOLERANCE,
                    "{}: {name} of channel {channel}: merged {got}, one solve {want} (relative {error:.2e})",
                    controller.name
                );
                worst = worst.max(error);
            }
            through_door += usize::from(column != side);
        }
    }
    assert_eq!(through_door, 2, "each room reads the other's channel");
    eprintln!("merged against one solve of both rooms: largest relative difference {worst:.2e}");
}

/// `Σ_k w_k light_k`: one light of the photopic band.
fn weighted(lights: &[(&ChannelLight, f64)]) -> ChannelLight {
    let sum = |field: fn(&ChannelLight) -> &Vec<f64>| -> Vec<f64> {
        let mut out = vec![0.0; field(lights[0].0).len()];
        for (light, w) in lights {
            for (o, x) in out.iter_mut().zip(field(light)) {
                *o += w * x;
            }
        }
        out
    };
    ChannelLight {
        emission: vec![sum(|l| &l.emission[0])],
        patch_irradiance: vec![sum(|l| &l.patch_irradiance[0])],
        output_irradiance: vec![sum(|l| &l.output_irradiance[0])],
    }
}

/// The daylight of the left room crosses the door: built apart and merged, both rooms read
/// under a sky, and under the sun at a node of the basis' sun grid, what one dense solve of the
/// two rooms with a diffusing door reads, the left room's daylight computed afresh by the
/// daylight's own functions (sky patches, exterior, sun) and weighted by the same sky.
#[test]
fn daylight_crosses_the_door_as_one_solve_of_both_rooms_reads_it() {
    let (manifest, out) = &door_open_daylit();
    let rooms: Vec<Prepared> = manifest
        .rooms
        .iter()
        .map(|r| {
            pipeline::prepare(&r.scene, &FormFactorOptions::default())
                .unwrap_or_else(|e| panic!("{e}"))
        })
        .collect();
    let left = &rooms[0];
    let site = left.scene.site.clone().expect("the left room's site");
    let right_basis = std::fs::read(building::basis_path(out, "right")).expect("basis");
    let left_basis = std::fs::read(building::basis_path(out, "left")).expect("basis");
    let grid = {
        let b = Basis::from_bytes(&right_basis).unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(
            b.sky_patches().map(|p| p.count()),
            Some(145),
            "the right room reads the left room's sky"
        );
        b.sun_grid()
            .expect("the right room's basis has the left room's sun grid")
    };
    // A stored sun node near noon at the equinox: the sun through the window.
    let node = (0..grid.len())
        .filter(|&k| {
            let (d, h) = grid.angles(k).expect("node");
            d.abs() < 6.0 && h.abs() < 16.0
        })
        .find(|&k| grid.direction(k).and_then(|d| room_sun(&site, d)).is_some())
        .expect("a node near noon at the equinox");
    let direction = grid.direction(node).expect("node");
    let options = DaylightOptions::default();
    let sky = sky_response(&left.scene, &left.occluders, SkyPatches::TREGENZA, &options);
    // A sky of uneven luminances (cd/m²) and its global horizontal illuminance (lux).
    let luminance: Vec<f32> = (0..145)
        .map(|k| 1000.0 * (1.0 + (k % 5) as f32 / 4.0))
        .collect();
    let global_horizontal = 10_000.0f32;
    let direct_normal = 1000.0f32;
    let mut sky_lights: Vec<(&ChannelLight, f64)> = sky
        .sky
        .iter()
        .zip(&luminance)
        .map(|(l, &w)| (l, f64::from(w)))
        .collect();
    sky_lights.push((
        &sky.exterior,
        f64::from(global_horizontal) / std::f64::consts::PI,
    ));
    let sun = sun_light(
        &left.scene,
        &left.occluders,
        room_sun(&site, direction).expect("above the horizon"),
        &options,
    );
    let lights = vec![
        weighted(&sky_lights),
        weighted(&[(&sun, f64::from(direct_normal))]),
    ];
    let systems = [
        left.system.with_lights(lights),
        rooms[1].system.with_lights(Vec::new()),
    ];
    let reference = one_system([&rooms[0], &rooms[1]], [&systems[0], &systems[1]]);
    let states = [
        SkyState {
            sky_luminance: luminance.clone(),
            global_horizontal,
            sun: None,
        },
        SkyState {
            sky_luminance: vec![0.0; 145],
            global_horizontal: 0.0,
            sun: Some(Sun {
                direction,
                direct_normal,
            }),
        },
    ];
    let mut worst: f64 = 0.0;
    let mut worst_patches: f64 = 0.0;
    for (side, basis) in [&left_basis, &right_basis].into_iter().enumerate() {
        for (case, state) in states.iter().enumerate() {
            let read = evaluate_daylight(basis, state, &[0.0, 0.0], true)
                .unwrap_or_else(|e| panic!("{e}"));
            // The patches' exitance through every mode, the neighbour's daylight included, on
            // the reflecting patches the modes span (a black patch's exitance, the door's, is
            // what enters through it, not a mode's).
            let exact = &reference[side][case].exitance;
            let system = &rooms[side].system;
            let area: Vec<f64> = (0..system.patch_count())
                .map(|j| {
                    if system.reflectance[0][j] > 0.0 {
                        system.area[j]
                    } else {
                        0.0
                    }
                })
                .collect();
            let error = patch_error(&area, &read.exitance, exact);
            assert!(
                error <= FULL_MODES,
                "room {side}, case {case}: daylight's patch exitance through every mode {error:.2e}"
            );
            worst_patches = worst_patches.max(error);
            let merged = read.outputs();
            let exact = &reference[side][case].readings;
            assert_eq!(merged.len(), exact.len());
            assert!(merged.len() > 10, "sensors, zone and grid points");
            for (o, (got, want)) in merged.iter().zip(exact).enumerate() {
                assert!(
                    *want > 0.0,
                    "room {side}, case {case}, output {o}: no daylight"
                );
                let error = (got - want).abs() / want;
                assert!(
                    error <= COUPLING_TOLERANCE,
                    "room {side}, case {case} (0 sky, 1 sun), output {o}: merged {got}, one solve {want} (relative {error:.2e})"
                );
                worst = worst.max(error);
            }
        }
    }
    eprintln!("daylight through the door, merged against one solve of both rooms: largest relative difference {worst:.2e} at the outputs, patch exitance through every mode {worst_patches:.2e} (area-weighted RMS)");

    // The right room with daylight of its own under another site: refused, naming the room.
    let parts_dir = building::parts_dir(out);
    let mut parts: Vec<Part> = manifest
        .rooms
        .iter()
        .map(|r| Part::read_checked(&parts_dir, r).unwrap_or_else(|e| panic!("{e}")))
        .collect();
    let (lit, dark) = (parts[0].clone(), &mut parts[1]);
    dark.tables.sky_subdivision = lit.tables.sky_subdivision;
    dark.tables.daylight_site = lit.tables.daylight_site.clone();
    dark.tables.daylight_site[0] += 1.0;
    dark.tables.sun_lattice = lit.tables.sun_lattice.clone();
    dark.tables.sun_spacing = lit.tables.sun_spacing.clone();
    dark.ports.daylight = vec![vec![0.0; dark.ports.openings[0].area.len()]; 146];
    let e = port::couple(manifest, &parts, &parts_dir)
        .expect_err("two sites")
        .to_string();
    for expected in [
        "building.toml:",
        "room right",
        "differs from room left's",
        "[site]",
    ] {
        assert!(e.contains(expected), "{expected:?} not in: {e}");
    }
}

/// The two rooms as one scene with the doorway open, its tables built once for the tests.
fn one_scene_tables() -> &'static BasisTables {
    static BUILT: OnceLock<BasisTables> = OnceLock::new();
    BUILT.get_or_init(|| {
        let dir = common::scratch("ports-hole");
        let path = dir.join("both.toml");
        std::fs::write(&path, one_scene()).expect("scene");
        pipeline::build_tables(&path, &BuildOptions::default())
            .unwrap_or_else(|e| panic!("{e}"))
            .tables
    })
}

/// The two rooms joined by the door with `directions` direction bins, built on this machine
/// into a scratch folder named after `test` and merged.
fn door_with_directions(test: &str, directions: usize) -> (Manifest, PathBuf) {
    let dir = common::scratch(test);
    let port = format!("{PORT}directions = {directions}\n");
    let manifest = Manifest::load(&two_rooms(&dir, &port)).unwrap_or_else(|e| panic!("{e}"));
    let out = dir.join("out");
    build(&manifest, &[vec![0, 1]], &out);
    (manifest, out)
}

/// The port's model against the doorway as a real hole: per reading of either room, each
/// channel's merged and one-scene value (the room's own channel first).
struct AgainstTheHole {
    rows: Vec<(String, Vec<f64>, Vec<f64>)>,
}

impl AgainstTheHole {
    /// The merged rooms' readings (coupled tables) of the building built into `out` against
    /// the two rooms as one scene with the doorway open: sensors and zones by name, grid
    /// points by position, each channel by name.
    fn measure(manifest: &Manifest, out: &Path) -> AgainstTheHole {
        let whole = one_scene_tables();
        let parts_dir = building::parts_dir(out);
        let parts: Vec<Part> = manifest
            .rooms
            .iter()
            .map(|r| Part::read_checked(&parts_dir, r).unwrap_or_else(|e| panic!("{e}")))
            .collect();
        let coupled = port::couple(manifest, &parts, &parts_dir).unwrap_or_else(|e| panic!("{e}"));
        let channel_in_whole = |name: &str| -> usize {
            let bare = name.rsplit('/').next().unwrap_or(name);
            whole
                .channel_names
                .iter()
                .position(|c| c == bare)
                .expect("channel")
        };
        let mut rows: Vec<(String, Vec<f64>, Vec<f64>)> = Vec::new();
        for (r, t) in coupled.tables.iter().enumerate() {
            let room = &manifest.rooms[r].name;
            let (m, wm) = (t.channel_names.len(), whole.channel_names.len());
            assert_eq!(m, 2, "room {room}: its channel and the other room's");
            let columns: Vec<usize> = t
                .channel_names
                .iter()
                .map(|n| channel_in_whole(n))
                .collect();
            let mut row = |name: String, k: usize, w: usize, table: &[f64], whole_table: &[f64]| {
                let got = (0..m).map(|c| table[k * m + c]).collect();
                let want = columns.iter().map(|&wc| whole_table[w * wm + wc]).collect();
                rows.push((name, got, want));
            };
            for (k, s) in t.sensor_names.iter().enumerate() {
                let w = whole
                    .sensor_names
                    .iter()
                    .position(|x| x == s)
                    .expect("sensor");
                row(
                    format!("{room}: sensor {s}"),
                    k,
                    w,
                    &t.output_channels,
                    &whole.output_channels,
                );
            }
            for (z, name) in t.zone_names.iter().enumerate() {
                let k = t.sensor_names.len() + z;
                let w = whole.sensor_names.len()
                    + whole
                        .zone_names
                        .iter()
                        .position(|x| x == name)
                        .expect("zone");
                row(
                    format!("{room}: zone {name}"),
                    k,
                    w,
                    &t.output_channels,
                    &whole.output_channels,
                );
            }
            for (g, p) in t.grid_position.iter().enumerate() {
                let w = whole
                    .grid_position
                    .iter()
                    .position(|q| (0..3).all(|x| (p[x] - q[x]).abs() < 1e-9))
                    .unwrap_or_else(|| panic!("{room}: grid point {p:?} not in the one scene"));
                row(
                    format!("{room}: point {p:?}"),
                    g,
                    w,
                    &t.grid_channels,
                    &whole.grid_channels,
                );
            }
        }
        if std::env::var_os("PORTS_DETAIL").is_some() {
            for (name, got, want) in &rows {
                eprintln!("{name}: merged {got:.3?}, one scene {want:.3?}");
            }
        }
        assert!(rows.len() > 40);
        AgainstTheHole { rows }
    }

    /// The largest of `f(merged, one scene)` over the readings.
    fn worst(&self, f: &dyn Fn(&[f64], &[f64]) -> f64) -> f64 {
        self.rows
            .iter()
            .map(|(_, got, want)| f(got, want))
            .fold(0.0, f64::max)
    }

    /// Largest relative difference of the room's own channel.
    fn own(&self) -> f64 {
        self.worst(&|g, w| relative(g[0], w[0]))
    }

    /// Largest relative difference of the other room's channel (its light through the door).
    fn neighbour(&self) -> f64 {
        self.worst(&|g, w| relative(g[1], w[1]))
    }

    /// Largest relative difference of the other room's channel at the sensors and zones (the
    /// grid points left out): what a controller's photocell and its zone figures read.
    fn neighbour_at_sensors_and_zones(&self) -> f64 {
        self.rows
            .iter()
            .filter(|(name, _, _)| name.contains(": sensor ") || name.contains(": zone "))
            .map(|(_, got, want)| relative(got[1], want[1]))
            .fold(0.0, f64::max)
    }

    /// Largest relative difference of the other room's channel over its largest reading in
    /// the room: the error in lux at a point, as a share of what the door brings at its
    /// brightest, which does not grow where the neighbour's light is faint.
    fn neighbour_of_brightest(&self) -> f64 {
        let mut brightest = std::collections::BTreeMap::new();
        for (name, _, want) in &self.rows {
            let room = name.split(':').next().unwrap_or("");
            let b = brightest.entry(room).or_insert(0.0_f64);
            *b = b.max(want[1]);
        }
        self.rows
            .iter()
            .map(|(name, got, want)| {
                let room = name.split(':').next().unwrap_or("");
                (got[1] - want[1]).abs() / brightest[room]
            })
            .fold(0.0, f64::max)
    }

    /// Largest relative difference with both channels at level 1.
    fn total(&self) -> f64 {
        self.worst(&|g, w| relative(g[0] + g[1], w[0] + w[1]))
    }
}

/// `|got − want| / want` of a reading the one scene says is lit.
fn relative(got: f64, want: f64) -> f64 {
    assert!(want > 0.0);
    (got - want).abs() / want
}

#[test]
fn the_diffuse_port_against_the_open_doorway() {
    let (manifest, out) = door_open();
    let hole = AgainstTheHole::measure(manifest, out);
    let (own, neighbour, total) = (hole.own(), hole.neighbour(), hole.total());
    eprintln!(
        "diffuse port against the open doorway, largest relative difference over {} readings: the room's own channel {:.2} %, the other room's {:.1} %, both channels at level 1 {:.2} %",
        hole.rows.len(),
        100.0 * own,
        100.0 * neighbour,
        100.0 * total
    );
    assert!(own <= OWN_LIGHT_TOLERANCE, "own light: {own:.3e}");
    assert!(
        neighbour <= THROUGH_DOOR_TOLERANCE,
        "light through the door: {neighbour:.3e}"
    );
    assert!(total <= BOTH_TOLERANCE, "both channels: {total:.3e}");
}

/// A directional port (docs/math.md, "Directional ports") against the same hole: the light
/// through the door keeps its direction bin, so the neighbour's light errs less than through
/// the diffuse port, measured on the same readings.
#[test]
fn a_directional_port_against_the_open_doorway() {
    let (manifest, out) = door_with_directions("ports-directional", TESTED_DIRECTIONS);
    let directional = AgainstTheHole::measure(&manifest, &out);
    let (diffuse_manifest, diffuse_out) = door_open();
    let diffuse = AgainstTheHole::measure(diffuse_manifest, diffuse_out);
    let figures = |h: &AgainstTheHole| {
        [
            h.own(),
            h.neighbour(),
            h.neighbour_at_sensors_and_zones(),
            h.neighbour_of_brightest(),
            h.total(),
        ]
        .map(|x| 100.0 * x)
    };
    eprintln!(
        "against the open doorway, largest relative difference (own channel, other room's, other room's at sensors and zones, other room's over its brightest reading, both), %: diffuse {:.2?}, {TESTED_DIRECTIONS} directions {:.2?}",
        figures(&diffuse),
        figures(&directional)
    );
    assert!(directional.own() <= OWN_LIGHT_TOLERANCE);
    assert!(
        directional.neighbour() <= DIRECTIONAL_THROUGH_DOOR_TOLERANCE,
        "light through the door: {:.3e}",
        directional.neighbour()
    );
    assert!(
        directional.neighbour_at_sensors_and_zones() <= DIRECTIONAL_SENSORS_AND_ZONES_TOLERANCE,
        "light through the door at the sensors and zones: {:.3e}",
        directional.neighbour_at_sensors_and_zones()
    );
    assert!(
        directional.neighbour_at_sensors_and_zones() < diffuse.neighbour_at_sensors_and_zones()
            && directional.neighbour_of_brightest() < diffuse.neighbour_of_brightest(),
        "the directional port errs more than the diffuse one"
    );
    assert!(directional.total() <= DIRECTIONAL_BOTH_TOLERANCE);
    let _ = std::fs::remove_dir_all(out.parent().expect("folder"));
}

/// The error against the hole as a function of the number of direction bins: the table of
/// docs/accuracy.md ("Ports"). Ignored by default (one build of both rooms per row):
/// `cargo test --test ports -- --ignored --nocapture doorway_error_by_directions`.
#[test]
#[ignore]
fn doorway_error_by_directions() {
    println!("| directions | own channel | other room's channel | other room's at sensors and zones | other room's, over its brightest reading | both channels |");
    println!("|---|---|---|---|---|---|");
    for directions in [1, 2, 3, 5, 9, 17, 33] {
        let (manifest, out) = door_with_directions("ports-by-directions", directions);
        let hole = AgainstTheHole::measure(&manifest, &out);
        println!(
            "| {directions} | {:.2} % | {:.1} % | {:.1} % | {:.1} % | {:.2} % |",
            100.0 * hole.own(),
            100.0 * hole.neighbour(),
            100.0 * hole.neighbour_at_sensors_and_zones(),
            100.0 * hole.neighbour_of_brightest(),
            100.0 * hole.total()
        );
        let _ = std::fs::remove_dir_all(out.parent().expect("folder"));
    }
}

/// The bins of a port: each holds `1/N` of the hemisphere's projected solid angle (`π`),
/// integrated here over a fine polar grid in a frame of the test's own, independently of the
/// sampled shares; and their sectors start from the opening's "up" on either side.
#[test]
fn direction_bins_hold_equal_projected_solid_angles_and_start_from_up() {
    use eigenrad_precompute::building::port::directions::Bins;
    use eigenrad_precompute::geometry::Vec3;
    // Midpoint rule in θ and φ, 4000 × 320 cells: the sectors' edges fall on cell edges, the
    // cone's edge within a cell of 0.02° (an error below 1e-4).
    const PROJECTED_SOLID_ANGLE: f64 = 1e-3;
    for normal in [
        Vec3::new(-1.0, 0.0, 0.0),
        Vec3::new(0.0, 0.6, 0.8),
        Vec3::new(0.0, 0.0, 1.0),
    ] {
        for count in [1, 2, 3, 5, 9, 17] {
            let bins = Bins::new(count, normal);
            let up = if normal.z.abs() > 0.9 {
                Vec3::new(1.0, 0.0, 0.0)
            } else {
                Vec3::new(0.0, 0.0, 1.0).cross(normal).normalized()
            };
            let other = normal.cross(up);
            let (nt, np) = (4000, 320);
            let mut held = vec![0.0; count];
            for a in 0..nt {
                let theta = (a as f64 + 0.5) / nt as f64 * std::f64::consts::FRAC_PI_2;
                for b in 0..np {
                    let phi = (b as f64 + 0.5) / np as f64 * std::f64::consts::TAU;
                    let d = normal * theta.cos()
                        + up * (theta.sin() * phi.cos())
                        + other * (theta.sin() * phi.sin());
                    let cell = theta.sin()
                        * (std::f64::consts::FRAC_PI_2 / nt as f64)
                        * (std::f64::consts::TAU / np as f64);
                    held[bins.of(d)] += theta.cos() * cell / std::f64::consts::PI;
                }
            }
            // Light climbing steeply through the opening is in sector 0 ("up") whichever
            // way it crosses, so both rooms of a port share the sectors' frame.
            if count > 2 && normal.z.abs() <= 0.9 {
                let z = Vec3::new(0.0, 0.0, 1.0);
                let up = (z - normal * normal.dot(z)).normalized();
                for into in [normal, -normal] {
                    let climbing = into * 0.2 + up;
                    assert_eq!(Bins::new(count, into).of(climbing), 1, "{into:?}");
                }
            }
            for (bin, share) in held.iter().enumerate() {
                assert!(
                    (share - bins.weight()).abs() <= PROJECTED_SOLID_ANGLE,
                    "normal {normal:?}, {count} bins: bin {bin} holds {share}, not {}",
                    bins.weight()
                );
            }
        }
    }
}

/// Rooms joined through a port are solved band by band: a photopic room and an RGB one are
/// refused at the merge, naming the manifest's line, the port and both rooms' bands, and
/// nothing is written.
#[test]
fn rooms_of_different_bands_are_not_joined() {
    let dir = common::scratch("ports-bands");
    let path = two_rooms(&dir, PORT);
    let rgb = right_scene(0.5).replace("bands = \"photopic\"", "bands = \"rgb\"");
    std::fs::write(dir.join("right.toml"), rgb).expect("scene");
    let manifest = Manifest::load(&path).unwrap_or_else(|e| panic!("{e}"));
    let out = dir.join("out");
    let parts = building::parts_dir(&out);
    std::fs::create_dir_all(&parts).expect("parts folder");
    building::build_rooms(&manifest, &[0, 1], &BuildOptions::default(), &parts)
        .unwrap_or_else(|e| panic!("{e}"));
    let e = building::merge(&manifest, &parts, &out, manifest.flash)
        .expect_err("bands differ")
        .to_string();
    for expected in [
        "building.toml:27:",
        "port door",
        "room left (1 bands)",
        "room right (3 bands)",
        "same `bands`",
    ] {
        assert!(e.contains(expected), "{expected:?} not in: {e}");
    }
    assert!(!out.join("building.json").exists());
    assert!(!building::basis_path(&out, "left").exists());
    let _ = std::fs::remove_dir_all(&dir);
}

/// Every file of `dir` (not its folders), sorted.
fn files(dir: &Path) -> Vec<PathBuf> {
    let mut names: Vec<PathBuf> = std::fs::read_dir(dir)
        .expect("folder")
        .flatten()
        .map(|e| e.path())
        .filter(|p| p.is_file())
        .collect();
    names.sort();
    names
}

#[test]
fn one_machine_and_two_shards_give_the_same_bytes_and_a_closed_door_leaves_the_rooms_apart() {
    let (manifest, local) = door_open();
    let sharded = local.with_file_name("shards");
    build(manifest, &[vec![0], vec![1]], &sharded);
    let mut compared = 0;
    for sub in ["", "parts"] {
        let (a, b) = (files(&local.join(sub)), files(&sharded.join(sub)));
        assert_eq!(a.len(), b.len());
        for (a, b) in a.iter().zip(&b) {
            assert_eq!(a.file_name(), b.file_name());
            if a.file_name().is_some_and(|n| n == "building.json") {
                continue; // names the folder it was written to
            }
            assert!(
                std::fs::read(a).expect("file") == std::fs::read(b).expect("file"),
                "{}: differs between one machine and two shards",
                a.display()
            );
            compared += 1;
        }
    }
    assert_eq!(compared, 2 + 2, "two bases and two parts");

    // The door closed: no port in the manifest. Each controller's basis is cut from its own
    // room's tables alone, as for rooms that share no light, and holds its room's channel only.
    let dir = common::scratch("ports-closed");
    let closed = Manifest::load(&two_rooms(&dir, "")).unwrap_or_else(|e| panic!("{e}"));
    assert!(closed.ports.is_empty());
    let out = dir.join("out");
    let merged = build(&closed, &[vec![0, 1]], &out);
    for (c, written) in closed.controllers.iter().zip(&merged.controllers) {
        let part = Part::read(&building::part::path(
            &building::parts_dir(&out),
            &closed.rooms[c.room].name,
        ))
        .unwrap_or_else(|e| panic!("{e}"));
        assert!(part.ports.openings.is_empty());
        let (selection, _) = controller::select(&part.tables, c);
        let alone = controller::cut(&part.tables, &selection)
            .to_bytes()
            .expect("basis");
        let basis = std::fs::read(building::basis_path(&out, &c.name)).expect("basis");
        assert!(basis == alone, "{}: not its room's own basis", c.name);
        assert_eq!(written.channels, [c.drives[0].clone()]);
        // With the door open the same controller also reads the other room's channel.
        let open = std::fs::read(building::basis_path(local, &c.name)).expect("basis");
        let open = Basis::from_bytes(&open).unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(open.channel_count(), 2, "{}", c.name);
    }
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn bad_ports_name_the_manifest_line_and_item() {
    let dir = common::scratch("ports-bad");
    let out = dir.join("out");
    let o = out.to_str().expect("utf-8").to_string();
    let with = |ports: &str| two_rooms(&dir, ports).to_str().expect("utf-8").to_string();

    let m = with("[[port]]\nname = \"door\"\nrooms = [\"left\", \"hall\"]\n");
    common::refused(
        &["building", &m, "--out", &o],
        &out,
        &[
            "building.toml:28:",
            "port door: room hall",
            "not a room of this building",
            "left, right",
        ],
    );

    let m = with("[[port]]\nname = \"door\"\nrooms = [\"left\", \"right\"]\nopenings = [\"door\", \"doorway\"]\n");
    common::refused(
        &["building", &m, "--out", &o],
        &out,
        &[
            "building.toml:29:",
            "port door: opening doorway in room right",
            "no [[quad]] of this name",
            "right.toml",
        ],
    );

    let m = with("[[port]]\nname = \"door\"\nrooms = [\"left\", \"left\"]\n");
    common::refused(
        &["building", &m, "--out", &o],
        &out,
        &["building.toml:28:", "port door", "joins a room to itself"],
    );

    // The door moved 10 cm in the left room only.
    let m = with(PORT);
    let moved = DOOR.map(|[x, y, z]| [x, y + 0.1, z]);
    std::fs::write(dir.join("left.toml"), left_scene(&moved)).expect("scene");
    common::refused(
        &["building", &m, "--out", &o],
        &out,
        &[
            "building.toml:27:",
            "port door",
            "its openings differ",
            "door in room left",
            "door in room right",
        ],
    );

    // The door's material reflects in the left room.
    let m = with(PORT);
    let grey = left_scene(&DOOR).replace("material = \"door\"", "material = \"wall\"");
    std::fs::write(dir.join("left.toml"), grey).expect("scene");
    common::refused(
        &["building", &m, "--out", &o],
        &out,
        &[
            "building.toml:27:",
            "port door: opening door in room left",
            "a port's opening is black",
        ],
    );

    // The door meshed finer in the right room: refused at the merge, nothing written.
    let m = with(PORT);
    std::fs::write(dir.join("right.toml"), right_scene(0.25)).expect("scene");
    common::refused(
        &["building", &m, "--out", &o],
        &out,
        &[
            "building.toml:27:",
            "port door",
            "meshed differently",
            "room left (8 patches)",
            "room right (32 patches)",
            "same `max_edge`",
        ],
    );

    // Parts built without the port, merged with it.
    let m = with("");
    let built = common::run(&["building", &m, "--out", &o]);
    assert!(built.status.success(), "{}", common::stderr(&built));
    for f in ["left.basis", "right.basis", "building.json"] {
        std::fs::remove_file(out.join(f)).expect("remove output");
    }
    let m = with(PORT);
    common::refused(
        &["merge", &m, "--out", &o],
        &out,
        &[
            "left.part",
            "built with the ports none",
            "door (door, 1 direction)",
            "build room left again",
        ],
    );

    // Parts built with the diffuse door, merged with a directional one.
    let m = with(PORT);
    let built = common::run(&["building", &m, "--out", &o]);
    assert!(built.status.success(), "{}", common::stderr(&built));
    for f in ["left.basis", "right.basis", "building.json"] {
        std::fs::remove_file(out.join(f)).expect("remove output");
    }
    let m = with(&format!("{PORT}directions = 5\n"));
    common::refused(
        &["merge", &m, "--out", &o],
        &out,
        &[
            "left.part",
            "built with the ports door (door, 1 direction)",
            "door (door, 5 directions)",
            "build room left again",
        ],
    );

    for bad in ["0", "65", "-1", "2.5"] {
        let m = with(&format!("{PORT}directions = {bad}\n"));
        let o2 = dir.join("out-directions");
        let expected = [
            "building.toml:29:",
            "port door: directions",
            "not a number of direction bins from 1 (diffuse) to 64",
        ];
        common::refused(
            &["building", &m, "--out", o2.to_str().expect("utf-8")],
            &o2,
            &expected,
        );
    }
    let _ = std::fs::remove_dir_all(&dir);
}
