//! An exact port carries daylight: the left room's window lights the right room through the
//! doorway as in the two rooms as one scene (tests/ports_exact.rs).

use eigenrad_precompute::accuracy::metric::patch_error;
use eigenrad_precompute::accuracy::runtime_eval::{evaluate_daylight, SkyState};
use eigenrad_precompute::building::{self, Manifest};
use eigenrad_precompute::pipeline::{BuildOptions, ModeSelection};
use eigenrad_precompute::scene::{self, Scene};
use eigenrad_precompute::sources::daylight::nodes::room_sun;
use eigenrad_precompute::sources::daylight::{sky_response, sun_light, DaylightOptions};
use eigenrad_precompute::sources::ChannelLight;
use eigenrad_runtime::sky::patches::SkyPatches;
use eigenrad_runtime::{Basis, Sun};

use crate::common;
use crate::common::one_scene::with_the_hole;
use crate::common::two_rooms::{
    both_keep_the_modes, daylit_left_scene, daylit_right_scene, daylit_rooms_in_one_scene,
    two_rooms,
};
use crate::{build_with, exact_port, merged_error};

/// Area-weighted RMS difference of the daylight's patch exitance through every mode from the
/// one scene's on each room's reflecting patches: the modes are complete, what remains is
/// `f32` rounding of `n` terms (as tests/daylight_basis.rs for one room).
const FULL_MODES: f64 = 1e-4;

/// The left room's daylight through its window and then the open door: built apart and
/// merged, both rooms read under a sky and under the sun at two nodes of the basis' sun grid
/// what the two rooms as one scene with the doorway open read, its daylight computed by the
/// daylight's own functions over the whole scene (sky patches, exterior, sun) and weighted
/// by the same sky, at every output and, through every mode, at every patch. One of the suns
/// shines through the window and the door onto the right room: a merge without the daylight
/// straight through the opening misses it by far more.
#[test]
fn daylight_through_the_window_and_the_doorway_reads_as_in_one_scene() {
    daylight_as_in_one_scene("ports-exact-daylit", false);
}

/// The same with a window in the right room too, under the same site: each room's daylight
/// reaches the other, the rooms' sun nodes joined.
#[test]
fn daylight_of_both_rooms_through_the_doorway_reads_as_in_one_scene() {
    daylight_as_in_one_scene("ports-exact-daylit-both", true);
}

/// Builds the two rooms with the left room's window (and with `right_window`, the right
/// room's) in `scratch`, merges, and compares with the one scene as the tests above say.
fn daylight_as_in_one_scene(scratch: &str, right_window: bool) {
    let dir = common::scratch(scratch);
    let path = two_rooms(&dir, &exact_port());
    std::fs::write(dir.join("left.toml"), daylit_left_scene()).expect("scene");
    if right_window {
        std::fs::write(dir.join("right.toml"), daylit_right_scene()).expect("scene");
    }
    // Both controllers keep every mode, so that the patches' exitance through them is exact.
    both_keep_the_modes(&path);
    let manifest = Manifest::load(&path).unwrap_or_else(|e| panic!("{e}"));
    assert!(manifest.controllers.iter().all(|c| c.modes));
    let out = dir.join("out");
    let every_mode = BuildOptions {
        modes: ModeSelection::Count(usize::MAX),
        ..BuildOptions::default()
    };
    build_with(&manifest, &[vec![0, 1]], &out, &every_mode);
    let one = with_the_hole(
        &format!("{scratch}-hole"),
        &daylit_rooms_in_one_scene(right_window),
    );
    let site = one.scene.site.clone().expect("the one scene's site");
    let bases: Vec<Vec<u8>> = ["left", "right"]
        .iter()
        .map(|c| std::fs::read(building::basis_path(&out, c)).expect("basis"))
        .collect();
    let right = Basis::from_bytes(&bases[1]).unwrap_or_else(|e| panic!("{e}"));
    let grid = right
        .sun_grid()
        .expect("the right room reads the left room's sun grid");
    let options = DaylightOptions::default();
    let patches = SkyPatches::TREGENZA;
    // The one scene's patches of the right room: those east of the door's wall.
    let in_right: Vec<bool> = one
        .scene
        .patches
        .iter()
        .map(|p| p.centroid.x > 3.0)
        .collect();
    // The sun grid's node whose sun puts most light straight on the right room's patches
    // (through the window and the door), and a node near noon at the equinox.
    let sun_at = |node: usize| {
        let direction = grid.direction(node).expect("node");
        let sun = room_sun(&site, direction).expect("a node above the horizon");
        (
            direction,
            sun_light(&one.scene, &one.occluders, sun, &options),
        )
    };
    // Whether node `node`'s sun is up and on the side `south` (the left room's window's) or
    // the other (the right room's).
    let up = |node: usize, south: bool| {
        grid.direction(node)
            .and_then(|d| room_sun(&site, d))
            .is_some_and(|sun| (sun.y < 0.0) == south)
    };
    // The lumens a light puts on the patches of the right room (`right`) or the left one.
    let on = |light: &ChannelLight, right: bool| -> f64 {
        (0..one.scene.patches.len())
            .filter(|&k| in_right[k] == right)
            .map(|k| one.scene.patches[k].area * light.patch_irradiance[0][k])
            .sum()
    };
    // The southern sun putting most light on the right room: through the left room's window
    // and the door (the right room's window faces north).
    let most_on = |south: bool, right: bool| {
        (0..grid.len())
            .filter(|&node| up(node, south))
            .map(|node| (node, on(&sun_at(node).1, right)))
            .max_by(|a, b| a.1.total_cmp(&b.1))
            .expect("sun nodes")
    };
    let through_door = most_on(true, true);
    assert!(
        through_door.1 > 0.0,
        "no sun of the grid reaches the right room"
    );
    let noon = (0..grid.len())
        .filter(|&k| {
            let (d, h) = grid.angles(k).expect("node");
            d.abs() < 6.0 && h.abs() < 16.0
        })
        .find(|&k| up(k, true))
        .expect("a node near noon at the equinox");
    let mut nodes = vec![through_door.0, noon];
    if right_window {
        // A northern sun through the right room's window and the door onto the left room.
        let back = most_on(false, false);
        assert!(back.1 > 0.0, "no northern sun reaches the left room");
        nodes.push(back.0);
    }
    // A sky of uneven luminances (cd/m²) and its global horizontal illuminance (lux).
    let luminance: Vec<f32> = (0..patches.count())
        .map(|k| 1000.0 * (1.0 + (k % 5) as f32 / 4.0))
        .collect();
    let global_horizontal = 10_000.0f32;
    let direct_normal = 1000.0f32;
    // The sky's light through the windows of `scene`.
    let sky_through = |scene: &Scene| {
        let sky = sky_response(scene, &one.occluders, patches, &options);
        let mut light = sky
            .exterior
            .scaled(f64::from(global_horizontal) / std::f64::consts::PI);
        for (response, &l) in sky.sky.iter().zip(&luminance) {
            light.add_scaled(response, f64::from(l));
        }
        light
    };
    // Window by window, summed: a receiving patch's cells are refined for the windows the
    // quadrature is given (their distance and light), so each window's light is integrated
    // as its own room's build integrates it. Both windows in one call integrate the same
    // light on other cells: the difference is the quadrature's own error, reported below.
    let mut sky_light = ChannelLight {
        emission: vec![vec![0.0; one.scene.patches.len()]],
        patch_irradiance: vec![vec![0.0; one.scene.patches.len()]],
        output_irradiance: vec![vec![0.0; one.names.len()]],
    };
    for window in &one.scene.windows {
        let mut alone = one.scene.clone();
        alone.windows = vec![window.clone()];
        sky_light.add_scaled(&sky_through(&alone), 1.0);
    }
    if right_window {
        let together = sky_through(&one.scene);
        let patch = |l: &ChannelLight| l.patch_irradiance[0].clone();
        let largest = patch(&sky_light).iter().fold(0.0f64, |m, x| m.max(x.abs()));
        let moved = patch(&together)
            .iter()
            .zip(&patch(&sky_light))
            .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
        eprintln!(
            "the sky through both windows integrated together against window by window: patch irradiance moves by up to {:.1e} of its largest value",
            moved / largest
        );
    }
    let mut lights = vec![sky_light];
    let mut states = vec![SkyState {
        sky_luminance: luminance,
        global_horizontal,
        sun: None,
    }];
    for &node in &nodes {
        let (direction, sun) = sun_at(node);
        lights.push(sun.scaled(f64::from(direct_normal)));
        states.push(SkyState {
            sky_luminance: vec![0.0; patches.count()],
            global_horizontal: 0.0,
            sun: Some(Sun {
                direction,
                direct_normal,
            }),
        });
    }
    let reference = one
        .system
        .with_lights(lights.clone())
        .light_responses(0, &lights)
        .unwrap_or_else(|e| panic!("{e}"));
    let mut worst: (f64, String) = (0.0, String::new());
    let mut worst_patches: f64 = 0.0;
    let mut direct_share: f64 = 0.0;
    let mut count = 0;
    for (controller, bytes) in manifest.controllers.iter().zip(&bases) {
        let basis = Basis::from_bytes(bytes).unwrap_or_else(|e| panic!("{e}"));
        let names = output_names(&basis);
        let room =
            scene::load(&manifest.rooms[controller.room].scene).unwrap_or_else(|e| panic!("{e}"));
        // Each of the room's patches in the one scene: the same quad, meshed alike.
        let same: Vec<usize> = room
            .patches
            .iter()
            .map(|p| {
                one.scene
                    .patches
                    .iter()
                    .position(|q| {
                        (q.centroid - p.centroid).length() < 1e-9 && q.normal.dot(p.normal) > 0.999
                    })
                    .unwrap_or(usize::MAX)
            })
            .collect();
        // The reflecting patches the modes span (the door's, black, is what leaves).
        let area: Vec<f64> = room
            .patches
            .iter()
            .zip(&room.reflectance)
            .map(|(p, r)| if r[0] > 0.0 { p.area } else { 0.0 })
            .collect();
        for (case, state) in states.iter().enumerate() {
            let readout = evaluate_daylight(bytes, state, &[0.0, 0.0], true)
                .unwrap_or_else(|e| panic!("{e}"));
            let exact: Vec<f64> = same
                .iter()
                .zip(&area)
                .map(|(&k, &a)| {
                    assert!(
                        a == 0.0 || k != usize::MAX,
                        "a reflecting patch not in the one scene"
                    );
                    reference[case].exitance.get(k).copied().unwrap_or(0.0)
                })
                .collect();
            let error = patch_error(&area, &readout.exitance, &exact);
            assert!(
                error <= FULL_MODES,
                "{}, case {case}: daylight's patch exitance through every mode {error:.2e}",
                controller.name
            );
            worst_patches = worst_patches.max(error);
            let read = readout.outputs();
            assert_eq!(read.len(), names.len());
            for (name, got) in names.iter().zip(read) {
                let o = one.names.iter().position(|n| n == name).expect("output");
                let want = reference[case].readings[o];
                let error = merged_error(
                    &controller.name,
                    name,
                    &format!("daylight case {case}"),
                    got,
                    want,
                );
                if error > worst.0 {
                    worst = (error, format!("{}: {name}, case {case}", controller.name));
                }
                count += 1;
                if case == 1 && controller.room == 1 {
                    let direct = lights[1].output_irradiance[0][o];
                    direct_share = direct_share.max(direct / want);
                }
            }
        }
    }
    eprintln!(
        "daylight through an exact port against the one scene{}, {count} readings (a sky, the sun at nodes {nodes:?}): largest relative difference {:.2e} ({}), patch exitance through every mode {worst_patches:.2e} (area-weighted RMS); the sun straight through the left window and the door is up to {:.0} % of a reading in the right room",
        if right_window { ", a window in each room" } else { "" },
        worst.0,
        worst.1,
        100.0 * direct_share
    );
    assert!(direct_share > 0.5, "{direct_share}");
}

/// Every output's name of a basis in the order the runtime reads them (sensors, zones, then
/// each zone's grid points), as [`readings`] names them.
fn output_names(basis: &Basis) -> Vec<String> {
    let mut names: Vec<String> = (0..basis.sensor_count())
        .map(|s| format!("sensor {}", basis.sensor_name(s).expect("sensor")))
        .collect();
    let zones: Vec<&str> = (0..basis.zone_count())
        .map(|z| basis.zone_name(z).expect("zone"))
        .collect();
    names.extend(zones.iter().map(|z| format!("zone {z}")));
    for (z, name) in zones.iter().enumerate() {
        for g in 0..basis.grid_points(z).expect("grid") {
            names.push(format!("zone {name} point {g}"));
        }
    }
    names
}
