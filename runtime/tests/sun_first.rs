//! The sun's first reflection on the controller (format version 8; docs/format.md, "The
//! sun's first reflection"): the tiny daylight basis with a window, a wall outside and one
//! candidate patch, read at a sun node against sums by hand, and each malformed table
//! refused naming it.
#![allow(
    clippy::unwrap_used,
    clippy::expect_used,
    clippy::indexing_slicing,
    clippy::panic
)]

mod common;

use common::tiny_daylight;
use eigenrad_runtime::sky::sun_grid::direction_of;
use eigenrad_runtime::writer::BasisTables;
use eigenrad_runtime::{Basis, DaylightEvaluator, Error, Sun};

type Day<'a> = DaylightEvaluator<'a, 145, 2, 0>;

/// Vienna's latitude in the tiny basis' site.
const LATITUDE: f32 = 48.21;

/// `tiny_daylight` with a 2 m × 1.5 m window face in the wall y = 0 (x 0 to 2, z 1 to 2.5,
/// τ = 0.5), a wall outside at y = −2 up to z = 2.5, and the floor (patch 0, ρ 0.5, 2 m²)
/// as the one candidate, sampled at (1, 1, 0.8) facing up (a desk's height, so that the
/// sun through the window reaches it) with weight 1. The floor's view from the sensor and
/// the zone is 0.2 and 0.3, from the grid points 0.25 and 0.35. `power` per sun node.
fn with_first(power: [f64; 3]) -> BasisTables {
    let mut t = tiny_daylight();
    t.sun_polygon_counts = vec![1, 0, 1];
    t.sun_polygon_sizes = vec![4, 4];
    t.sun_polygons = vec![
        0.0, 1.0, 0.0, // the window's normal, into the room
        0.0, 0.0, 1.0, 2.0, 0.0, 1.0, 2.0, 0.0, 2.5, 0.0, 0.0, 2.5, //
        0.0, 1.0, 0.0, // the exterior wall
        -5.0, -2.0, 0.0, 5.0, -2.0, 0.0, 5.0, -2.0, 2.5, -5.0, -2.0, 2.5,
    ];
    t.sun_glazing = vec![0.5; 65];
    t.sensor_response_rows = vec![0];
    t.output_view = vec![0.2, 0.3, 0.1, 0.05];
    t.grid_view = vec![0.25, 0.12, 0.35, 0.08];
    t.sun_first_patches = vec![0];
    t.sun_first_sizes = vec![1];
    t.sun_first_points = vec![0.0, 0.0, 1.0, 1.0, 1.0, 0.8, 1.0];
    t.sun_node_power = power.to_vec();
    t
}

/// The sun at the middle node (declination 0, noon: due south at 90° − 48.21° altitude).
fn noon(direct_normal: f32) -> Sun {
    Sun {
        direction: direction_of(LATITUDE, 0.0, 0.0),
        direct_normal,
    }
}

/// At the node, due south at altitude `a` = 41.79°, the ray from (1, 1, 0.8) meets the window
/// at z = 0.8 + tan a = 1.69 (inside 1 to 2.5) and the wall outside at z = 0.8 + 3 tan a = 3.48
/// (over 2.5): the candidate's irradiance is τ sin a, its first reflection `M0 = 0.5 τ sin
/// a` and its power `P = 2 M0`. With the node's stored power equal to it, a reading is the
/// node's stored rest, plus its direct sun (τ sin a at the sensor and the grid points, which
/// face up from the same height), plus its view of the floor times `M0`, all times `E_n`;
/// with a stored power twice as large, the rest is read at half its value.
#[test]
fn a_node_reads_its_rest_its_direct_sun_and_its_first_reflection() {
    let a = (90.0f64 - f64::from(LATITUDE)).to_radians();
    let direct = 0.5 * a.sin();
    let m0 = 0.5 * direct;
    let power = 2.0 * m0;
    let e_n = 1000.0;
    // The middle node's column is 145 + 1 + 1 = 147: `(o + 1) · 148` at output `o`,
    // `(g + 2) · 148` at grid point `g`.
    for (stored, share) in [(power, 1.0), (2.0 * power, 0.5)] {
        let bytes = with_first([1.0, stored, 1.0]).to_bytes().unwrap();
        let basis = Basis::from_bytes(&bytes).unwrap();
        let mut day = Day::new(basis).unwrap();
        day.set_sky(&[0.0; 145], 0.0, Some(noon(e_n as f32))).unwrap();
        let want = |rest: f64, direct: f64, view: f64| e_n * (share * rest + direct + view * m0);
        let cases = [
            (day.sensor_illuminance(0).unwrap(), want(148.0, direct, 0.2)),
            (day.zone_illuminance(0).unwrap(), want(296.0, 0.0, 0.3)),
            (
                day.grid_point_illuminance(0, 0).unwrap(),
                want(296.0, direct, 0.25),
            ),
            (
                day.grid_point_illuminance(0, 1).unwrap(),
                want(444.0, direct, 0.35),
            ),
        ];
        for (got, want) in cases {
            assert!(
                (f64::from(got) - want).abs() <= 1e-5 * want,
                "{got} against {want}"
            );
        }
    }
}

/// Where the wall outside hides the sun from the candidate (raised to 4 m; every stored
/// corner's power positive), the rest is read per unit of a power of 0: the reading is its
/// direct sun and first reflection alone, both 0, where format 7 interpolated the corners'
/// whole sunlight.
#[test]
fn a_hidden_sun_patch_takes_the_rest_with_it() {
    let mut t = with_first([0.3, 0.3, 0.3]);
    for z in [26, 29] {
        t.sun_polygons[z] = 4.0;
    }
    let bytes = t.to_bytes().unwrap();
    let basis = Basis::from_bytes(&bytes).unwrap();
    let mut day = Day::new(basis).unwrap();
    // Between the nodes 1, 2, 6 and 7 (6 and 7 stored).
    let sun = Sun {
        direction: direction_of(LATITUDE, -5.0, 7.5),
        direct_normal: 1000.0,
    };
    // The ray from (1, 1, 0.8) meets the wall 3 m south below its top.
    let [_, y, z] = sun.direction;
    let height = 0.8 + 3.0 * z / -y;
    assert!(height < 4.0, "{height}");
    day.set_sky(&[0.0; 145], 0.0, Some(sun)).unwrap();
    assert_eq!(day.sensor_illuminance(0).unwrap(), 0.0);
    assert_eq!(day.zone_illuminance(0).unwrap(), 0.0);
    assert_eq!(day.grid_point_illuminance(0, 1).unwrap(), 0.0);
}

/// Each malformed table of the sun's first reflection is refused by name when daylight is
/// used; without a sky they must be empty at decode.
#[test]
fn malformed_tables_are_refused_naming_them() {
    let value = |field: &'static str, index: usize| Error::DecodeValue { field, index };
    let cases: [(&str, fn(&mut BasisTables), Error); 8] = [
        (
            "a power per sun node",
            |t| t.sun_node_power.pop().map(drop).unwrap_or(()),
            Error::DecodeLength {
                field: "sun_node_power",
                expected: 12,
                found: 8,
            },
        ),
        ("a negative power", |t| t.sun_node_power[1] = -1.0, value("sun_node_power", 1)),
        (
            "a black candidate",
            |t| {
                t.sun_first_patches = vec![1];
            },
            value("sun_first_sizes", 0),
        ),
        ("no sample point", |t| t.sun_first_sizes = vec![0], value("sun_first_sizes", 0)),
        (
            "a patch out of range",
            |t| t.sun_first_patches = vec![2],
            value("sun_first_patches", 0),
        ),
        (
            "a normal not of unit length",
            |t| t.sun_first_points[2] = 0.5,
            value("sun_first_points", 0),
        ),
        ("a weight above 1", |t| t.sun_first_points[6] = 1.5, value("sun_first_points", 6)),
        (
            "candidates without the direct sun's geometry",
            |t| t.sun_polygon_counts.clear(),
            value("sun_node_power", 0),
        ),
    ];
    for (what, edit, want) in cases {
        let mut t = with_first([1.0, 1.0, 1.0]);
        edit(&mut t);
        if what == "candidates without the direct sun's geometry" {
            t.sun_polygon_sizes.clear();
            t.sun_polygons.clear();
            t.sun_glazing.clear();
            t.sensor_response_rows.clear();
        }
        let bytes = t.to_bytes().unwrap();
        let basis = Basis::from_bytes(&bytes).unwrap();
        let got = Day::new(basis).map(drop).unwrap_err();
        assert_eq!(got, want, "{what}");
    }
    // Without a sky every table of the daylight section is empty.
    let mut t = common::tiny();
    t.sun_node_power = vec![1.0];
    let bytes = t.to_bytes().unwrap();
    assert!(matches!(
        Basis::from_bytes(&bytes),
        Err(Error::DecodeLength {
            field: "daylight",
            ..
        })
    ));
}
