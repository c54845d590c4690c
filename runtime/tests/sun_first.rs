//! The sun's first reflection on the controller (format versions 8 and 9; docs/format.md,
//! "The sun's first reflection"): the tiny daylight basis with a window, a wall outside and
//! one candidate patch, read at a sun node against sums by hand, a candidate's sunlit area
//! against its closed form, and each malformed table refused naming it.
#![allow(
    clippy::unwrap_used,
    clippy::expect_used,
    clippy::indexing_slicing,
    clippy::panic
)]

mod common;

use common::tiny_daylight_sun_first as with_first;
use eigenrad_runtime::sky::sun_grid::direction_of;
use eigenrad_runtime::writer::BasisTables;
use eigenrad_runtime::{Basis, DaylightEvaluator, Error, Sun};
use proptest::prelude::*;

type Day<'a> = DaylightEvaluator<'a, 145, 2, 0>;

/// Vienna's latitude in the tiny basis' site.
const LATITUDE: f32 = 48.21;

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
        day.set_sky(&[0.0; 145], 0.0, Some(noon(e_n as f32)))
            .unwrap();
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

/// With every reading's response to the candidate stored (format version 9), a reading is
/// the node's stored rest (weighed per unit of power, as before) plus its direct sun plus
/// its response times `M0`, the response taking the place of the view; with a zone polygon
/// (the same square as the candidate, fully lit), the zone adds its direct sun, `τ sin a`.
#[test]
fn responses_take_the_place_of_the_views_and_zones_get_their_direct_sun() {
    let a = (90.0f64 - f64::from(LATITUDE)).to_radians();
    let direct = 0.5 * a.sin();
    let m0 = 0.5 * direct;
    let e_n = 1000.0;
    let response = [0.7, 0.9, 0.4, 0.6];
    for zone_polygon in [false, true] {
        let mut t = with_first([1.0, 2.0 * m0, 1.0]);
        t.sun_first_response = response.to_vec();
        if zone_polygon {
            t.zone_sun_counts = vec![1];
            t.zone_sun_sizes = vec![4];
            t.zone_sun_polygons = t.sun_first_points.clone();
        }
        let bytes = t.to_bytes().unwrap();
        let basis = Basis::from_bytes(&bytes).unwrap();
        let mut day = Day::new(basis).unwrap();
        day.set_sky(&[0.0; 145], 0.0, Some(noon(e_n as f32)))
            .unwrap();
        let want = |rest: f64, direct: f64, o: usize| e_n * (rest + direct + response[o] * m0);
        let zone_direct = if zone_polygon { direct } else { 0.0 };
        let cases = [
            (day.sensor_illuminance(0).unwrap(), want(148.0, direct, 0)),
            (
                day.zone_illuminance(0).unwrap(),
                want(296.0, zone_direct, 1),
            ),
            (
                day.grid_point_illuminance(0, 0).unwrap(),
                want(296.0, direct, 2),
            ),
            (
                day.grid_point_illuminance(0, 1).unwrap(),
                want(444.0, direct, 3),
            ),
        ];
        for (got, want) in cases {
            assert!(
                (f64::from(got) - want).abs() <= 1e-5 * want,
                "{got} against {want} (zone polygon {zone_polygon})"
            );
        }
    }
}

/// A candidate the window's shadow edge crosses: a 2 m square on the floor plane at
/// height 0.8 from y = 0.3 to 2.3, under the noon sun at the node (altitude `a`). A point at
/// depth `y` sees the sun through the window while `0.8 + y tan a ≤ 2.5`, so the lit part
/// is `y ≤ 1.7 / tan a`, and between x = 0 and 2 (the window's width, the sun due south):
/// the power is `ρ τ sin a` times that area, the closed form, where four sample points
/// (the rule before format 9) would give 0.5 or 0.75 of the whole.
#[test]
fn a_partly_lit_candidate_reads_its_lit_area() {
    let a = (90.0f64 - f64::from(LATITUDE)).to_radians();
    let mut t = with_first([1.0, 1.0, 1.0]);
    t.sun_first_points = vec![
        0.0, 0.0, 1.0, //
        0.0, 0.3, 0.8, 2.0, 0.3, 0.8, 2.0, 2.3, 0.8, 0.0, 2.3, 0.8,
    ];
    let bytes = t.to_bytes().unwrap();
    let basis = Basis::from_bytes(&bytes).unwrap();
    let direct = eigenrad_runtime::sky::direct::DirectSun::new(&basis)
        .unwrap()
        .unwrap();
    let first = eigenrad_runtime::sky::sun_first::SunFirst::new(&basis, direct).unwrap();
    let sun = direct.room_direction(noon(1.0).direction);
    let power = first.each_lit(sun, |_, _, _| {});
    let lit_depth = 1.7 / a.tan() - 0.3;
    assert!(lit_depth > 0.0 && lit_depth < 2.0, "{lit_depth}");
    // ρ τ sin a E over the lit area, per unit of the patch's area, times the stored area
    // (patch 0's, 2 m²).
    let want = 0.5 * 0.5 * a.sin() * (2.0 * lit_depth) / 4.0 * 2.0;
    assert!(
        (f64::from(power) - want).abs() <= 1e-4 * want,
        "{power} against {want}"
    );
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

/// A malformed table: what it is, the edit that makes it, the error that names it.
type Case = (&'static str, fn(&mut BasisTables), Error);

/// Each malformed table of the sun's first reflection is refused by name when daylight is
/// used; without a sky they must be empty at decode.
#[test]
fn malformed_tables_are_refused_naming_them() {
    let value = |field: &'static str, index: usize| Error::DecodeValue { field, index };
    let cases: [Case; 12] = [
        (
            "a power per sun node",
            |t| t.sun_node_power.pop().map(drop).unwrap_or(()),
            Error::DecodeLength {
                field: "sun_node_power",
                expected: 12,
                found: 8,
            },
        ),
        (
            "a negative power",
            |t| t.sun_node_power[1] = -1.0,
            value("sun_node_power", 1),
        ),
        (
            "a black candidate",
            |t| {
                t.sun_first_patches = vec![1];
            },
            value("sun_first_sizes", 0),
        ),
        (
            "two corners",
            |t| {
                t.sun_first_sizes = vec![2];
                t.sun_first_points.truncate(9);
            },
            value("sun_first_sizes", 0),
        ),
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
        (
            "a corner too far away",
            |t| t.sun_first_points[6] = 1.0e30,
            value("sun_first_points", 6),
        ),
        (
            "a response too many",
            |t| t.sun_first_response = vec![0.1; 5],
            Error::DecodeLength {
                field: "sun_first_response",
                expected: 16,
                found: 20,
            },
        ),
        (
            "a negative response",
            |t| {
                t.sun_first_response = vec![0.1; 4];
                t.sun_first_response[3] = -0.1;
            },
            value("sun_first_response", 3),
        ),
        (
            "a zone's polygon of two corners",
            |t| {
                t.zone_sun_counts = vec![1];
                t.zone_sun_sizes = vec![2];
                t.zone_sun_polygons = vec![0.0, 0.0, 1.0, 0.0, 0.0, 0.8, 1.0, 0.0, 0.8];
            },
            value("zone_sun_sizes", 0),
        ),
        (
            "a zone's polygon with a normal not of unit length",
            |t| {
                t.zone_sun_counts = vec![1];
                t.zone_sun_sizes = vec![3];
                t.zone_sun_polygons =
                    vec![0.0, 0.0, 2.0, 0.0, 0.0, 0.8, 1.0, 0.0, 0.8, 0.0, 1.0, 0.8];
            },
            value("zone_sun_polygons", 0),
        ),
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

/// A stored power made subnormal (its high byte zeroed, as the fuzzing below once found) is
/// in range, but dividing a node's rest by it overflows: the sky update refuses the basis
/// naming the table rather than reading an infinite illuminance.
#[test]
fn a_power_near_zero_is_refused_rather_than_read_as_infinite() {
    let mut t = with_first([0.3, 0.2, 0.1]);
    t.sun_node_power[1] = f64::from(f32::from_bits(0x004C_CCCD));
    let bytes = t.to_bytes().unwrap();
    let basis = Basis::from_bytes(&bytes).unwrap();
    let mut day = Day::new(basis).unwrap();
    let sun = Sun {
        direction: direction_of(LATITUDE, 0.0, 4.862789),
        direct_normal: 50_000.0,
    };
    let got = day.set_sky(&[1000.0; 145], 10_000.0, Some(sun));
    assert!(
        matches!(
            got,
            Err(Error::DecodeValue {
                field: "daylight_outputs",
                ..
            })
        ),
        "{got:?}"
    );
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    /// Bytes of the basis with the sun's first reflection, some set at random (half of them
    /// in its tables at the payload's end) and the checksum made right again: decoding,
    /// making an evaluator, a sky update with the sun and reading every output give values
    /// or errors, never a panic, and every value read is finite.
    #[test]
    fn corrupted_sun_first_tables_never_panic(
        edits in prop::collection::vec((any::<usize>(), any::<u8>()), 1..6),
        declination in -12.0f32..12.0,
        hour in -40.0f32..40.0,
    ) {
        let mut bytes = with_first([0.3, 0.2, 0.1]).to_bytes().unwrap();
        let n = bytes.len();
        for (at, value) in edits {
            let at = if at % 2 == 0 { n - 1 - at % 120.min(n - 1) } else { at % n };
            bytes[at] = value;
        }
        common::reseal_length_and_checksum(&mut bytes);
        let Ok(basis) = Basis::from_bytes(&bytes) else { return Ok(()) };
        let Ok(mut day) = Day::new(basis) else { return Ok(()) };
        let sun = Sun {
            direction: direction_of(LATITUDE, declination, hour),
            direct_normal: 50_000.0,
        };
        if day.set_sky(&[1000.0; 145], 10_000.0, Some(sun)).is_ok() {
            prop_assert!(day.sensor_illuminance(0).unwrap().is_finite());
            prop_assert!(day.zone_illuminance(0).unwrap().is_finite());
            for point in 0..2 {
                if let Ok(x) = day.grid_point_illuminance(0, point) {
                    prop_assert!(x.is_finite());
                }
            }
        }
    }
}
