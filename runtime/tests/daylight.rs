//! The daylight section of a basis and its evaluator, on the hand-made `common::tiny_daylight`
//! basis: what the decoder accepts and refuses, and readings summed by hand from its tables
//! (node `d` gives output `o` the value `(o + 1)(d + 1)` per unit, grid point `g` the value
//! `(g + 2)(d + 1)`, mode amplitude `0.01 (d + 1)`).
#![allow(
    clippy::unwrap_used,
    clippy::expect_used,
    clippy::indexing_slicing,
    clippy::panic
)]

mod common;

use common::{tiny, tiny_daylight, TREGENZA};
use eigenrad_runtime::sky::sun_grid::direction_of;
use eigenrad_runtime::{Basis, ChannelEvaluator, DaylightEvaluator, Error, Quantity, Sun};

/// Relative tolerance of an `f32` sum of a few hundred positive terms against the same sum
/// in `f64`.
const SUM_TOLERANCE: f64 = 1.0e-5;

type Day<'a> = DaylightEvaluator<'a, 145, 2, 1>;

/// Luminances that differ patch by patch, cd/m².
fn luminances() -> Vec<f32> {
    (0..TREGENZA).map(|i| 1000.0 + 10.0 * i as f32).collect()
}

/// What output `o` (grid point `g` with `scale = g + 2`) reads for `luminances`, `E_gh`
/// and `sun` as (node, weight × E_n) pairs: the sum over nodes, in `f64`.
fn by_hand(scale: f64, sky: &[f32], global: f64, sun: &[(usize, f64)]) -> f64 {
    let node = |d: usize| scale * (d + 1) as f64;
    let mut sum: f64 = sky
        .iter()
        .enumerate()
        .map(|(d, &l)| node(d) * f64::from(l))
        .sum();
    sum += node(TREGENZA) * global / std::f64::consts::PI;
    for &(column, w) in sun {
        sum += node(column) * w;
    }
    sum
}

fn close(got: f32, want: f64) -> bool {
    (f64::from(got) - want).abs() <= SUM_TOLERANCE * want.abs().max(1.0)
}

#[test]
fn decoded_daylight_section() {
    let bytes = tiny_daylight().to_bytes().unwrap();
    let basis = Basis::from_bytes(&bytes).unwrap();
    assert!(basis.has_daylight());
    assert_eq!(basis.sky_patches().unwrap().count(), TREGENZA);
    assert_eq!(basis.sun_node_count(), 3);
    assert_eq!(basis.daylight_node_count(), TREGENZA + 1 + 3);
    let site = basis.site().unwrap();
    assert_eq!(site.utc_offset_minutes, 60.0);
    assert!((site.latitude - 48.21).abs() < 1e-5);
    let grid = basis.sun_grid().unwrap();
    assert_eq!((grid.rows, grid.columns), (3, 5));
    // Without daylight: nothing, and the evaluator says why.
    let plain = tiny().to_bytes().unwrap();
    let plain = Basis::from_bytes(&plain).unwrap();
    assert!(!plain.has_daylight() && plain.site().is_none() && plain.sun_grid().is_none());
    assert_eq!(Day::new(plain).unwrap_err(), Error::NoDaylight);
}

#[test]
fn sky_and_exterior_read_as_summed_by_hand() {
    let bytes = tiny_daylight().to_bytes().unwrap();
    let basis = Basis::from_bytes(&bytes).unwrap();
    let mut day = Day::new(basis).unwrap();
    // Dark until a sky is set.
    assert_eq!(day.sensor_illuminance(0).unwrap(), 0.0);
    let sky = luminances();
    day.set_sky(&sky, 20_000.0, None).unwrap();
    assert!(close(
        day.sensor_illuminance(0).unwrap(),
        by_hand(1.0, &sky, 20_000.0, &[])
    ));
    assert!(close(
        day.zone_illuminance(0).unwrap(),
        by_hand(2.0, &sky, 20_000.0, &[])
    ));
    for g in 0..2 {
        assert!(close(
            day.grid_point_illuminance(0, g).unwrap(),
            by_hand((g + 2) as f64, &sky, 20_000.0, &[])
        ));
    }
    let f = day.zone_figures(0).unwrap();
    assert!(close(f.minimum, by_hand(2.0, &sky, 20_000.0, &[])));
    assert!(close(f.maximum, by_hand(3.0, &sky, 20_000.0, &[])));
    // With the electric light of the same basis (its channel at level 1: grid points 110
    // and 90 lux), point by point.
    let mut electric = ChannelEvaluator::<1, 1>::new(basis).unwrap();
    electric.set_channel_level(0, 1.0).unwrap();
    let both = day.zone_figures_with(0, &electric).unwrap();
    let points = [
        by_hand(2.0, &sky, 20_000.0, &[]) + 110.0,
        by_hand(3.0, &sky, 20_000.0, &[]) + 90.0,
    ];
    assert!(close(both.minimum, points[0].min(points[1])));
    assert!(close(both.average, 0.5 * (points[0] + points[1])));
    // Patch exitance through the one mode (0.5 on patch 0).
    let amplitude = by_hand(0.01, &sky, 20_000.0, &[]);
    assert!(close(day.exitance(0).unwrap(), 0.5 * amplitude));
    assert!(close(
        day.luminance(0).unwrap(),
        0.5 * amplitude / std::f64::consts::PI
    ));
}

#[test]
fn sun_at_a_node_between_nodes_and_where_it_lights_nothing() {
    let bytes = tiny_daylight().to_bytes().unwrap();
    let basis = Basis::from_bytes(&bytes).unwrap();
    let mut day = Day::new(basis).unwrap();
    let dark = vec![0.0; TREGENZA];
    // The stored nodes 6, 7, 8 are the daylight's columns 146, 147, 148.
    let column = |node: usize| TREGENZA + 1 + (node - 6);
    let sun = |declination: f32, hour: f32| Sun {
        direction: direction_of(48.21, declination, hour),
        direct_normal: 80_000.0,
    };
    // Node 7: declination 0°, hour angle 0°.
    day.set_sky(&dark, 0.0, Some(sun(0.0, 0.0))).unwrap();
    let want = by_hand(1.0, &dark, 0.0, &[(column(7), 80_000.0)]);
    assert!(close(day.sensor_illuminance(0).unwrap(), want), "{want}");
    // Halfway between nodes 7 and 8 (hour angles 0° and 15°).
    day.set_sky(&dark, 0.0, Some(sun(0.0, 7.5))).unwrap();
    let want = by_hand(
        1.0,
        &dark,
        0.0,
        &[(column(7), 40_000.0), (column(8), 40_000.0)],
    );
    assert!(
        (f64::from(day.sensor_illuminance(0).unwrap()) - want).abs() <= 1e-3 * want,
        "{want}"
    );
    // Halfway between node 7 and node 12 (declination 10°), which lights nothing: half of
    // node 7.
    day.set_sky(&dark, 0.0, Some(sun(5.0, 0.0))).unwrap();
    let want = by_hand(1.0, &dark, 0.0, &[(column(7), 40_000.0)]);
    assert!((f64::from(day.sensor_illuminance(0).unwrap()) - want).abs() <= 1e-3 * want);
    // Below the horizon (midnight): nothing.
    day.set_sky(&dark, 0.0, Some(sun(0.0, 180.0))).unwrap();
    assert_eq!(day.sensor_illuminance(0).unwrap(), 0.0);
}

#[test]
fn bad_requests_are_errors_and_change_nothing() {
    let bytes = tiny_daylight().to_bytes().unwrap();
    let basis = Basis::from_bytes(&bytes).unwrap();
    let mut day = Day::new(basis).unwrap();
    let sky = luminances();
    day.set_sky(&sky, 10_000.0, None).unwrap();
    let before = day.sensor_illuminance(0).unwrap();
    assert!(matches!(
        day.set_sky(&sky[1..], 10_000.0, None),
        Err(Error::LengthMismatch { .. })
    ));
    let mut negative = sky.clone();
    negative[3] = -1.0;
    assert!(matches!(
        day.set_sky(&negative, 10_000.0, None),
        Err(Error::InvalidInput { .. })
    ));
    assert!(day.set_sky(&sky, f32::NAN, None).is_err());
    let not_unit = Sun {
        direction: [0.0, 0.0, 2.0],
        direct_normal: 1.0,
    };
    assert!(day.set_sky(&sky, 10_000.0, Some(not_unit)).is_err());
    let infinite = Sun {
        direction: [0.0, 0.0, 1.0],
        direct_normal: f32::INFINITY,
    };
    assert!(day.set_sky(&sky, 10_000.0, Some(infinite)).is_err());
    assert_eq!(day.sensor_illuminance(0).unwrap(), before);
    assert!(matches!(
        day.sensor_illuminance(1),
        Err(Error::IndexOutOfRange { .. })
    ));
    // Capacities.
    assert!(matches!(
        DaylightEvaluator::<144, 2, 0>::new(basis),
        Err(Error::Capacity { .. })
    ));
    assert!(matches!(
        DaylightEvaluator::<145, 1, 0>::new(basis),
        Err(Error::Capacity { .. })
    ));
    // Without modes: no patch exitance, the rest as before.
    let mut lean = DaylightEvaluator::<145, 2, 0>::new(basis).unwrap();
    lean.set_sky(&sky, 10_000.0, None).unwrap();
    assert_eq!(lean.sensor_illuminance(0).unwrap(), before);
    assert!(matches!(lean.exitance(0), Err(Error::Capacity { .. })));
}

/// Where a bad daylight section is refused: its shape (a sky or none, a photometric basis,
/// its tables' bytes together) by `Basis::from_bytes`, the tables one by one when daylight
/// is used (`Basis::check_daylight`, which `DaylightEvaluator::new` calls), each with the
/// table named; the channels read a basis whose daylight is corrupt as before.
#[test]
fn decoder_refuses_bad_daylight_sections() {
    let named = |err: Error| match err {
        Error::DecodeField { field, .. }
        | Error::DecodeLength { field, .. }
        | Error::DecodeValue { field, .. } => field,
        other => panic!("{other:?}"),
    };
    let at_decode = |edit: &dyn Fn(&mut eigenrad_runtime::writer::BasisTables), field: &str| {
        let mut t = tiny_daylight();
        edit(&mut t);
        let bytes = t.to_bytes().unwrap();
        assert_eq!(named(Basis::from_bytes(&bytes).unwrap_err()), field);
    };
    let at_use = |edit: &dyn Fn(&mut eigenrad_runtime::writer::BasisTables), field: &str| {
        let mut t = tiny_daylight();
        edit(&mut t);
        let bytes = t.to_bytes().unwrap();
        let basis = Basis::from_bytes(&bytes).expect("the shape is sound");
        assert_eq!(named(basis.check_daylight().unwrap_err()), field);
        let err = Day::new(basis).unwrap_err();
        assert_eq!(named(err), field);
        // The electric light does not read the daylight section.
        let mut lights = ChannelEvaluator::<1, 4>::new(basis).unwrap();
        lights.set_channel_level(0, 1.0).unwrap();
        assert!(lights.sensor_irradiance(0).unwrap()[0].is_finite());
    };
    at_decode(&|t| t.sky_subdivision = 9, "sky_subdivision");
    at_decode(&|t| t.quantity = Quantity::Radiometric, "sky_subdivision");
    at_decode(&|t| t.sun_nodes.pop().map(drop).unwrap(), "daylight");
    at_decode(&|t| t.daylight_site.pop().map(drop).unwrap(), "daylight");
    at_decode(&|t| t.sun_lattice.push(1), "daylight");
    at_decode(&|t| t.sun_spacing.pop().map(drop).unwrap(), "daylight");
    at_decode(&|t| t.daylight_outputs.truncate(10), "daylight");
    at_decode(&|t| t.daylight_modes.push(0.0), "daylight");
    at_decode(&|t| t.daylight_grid.push(1.0), "daylight");
    // Daylight tables without a sky.
    at_decode(&|t| t.sky_subdivision = 0, "daylight");
    at_decode(
        &|t| {
            t.sky_subdivision = 0;
            t.quantity = Quantity::Radiometric;
        },
        "daylight",
    );
    // Lengths that make up the right total between them: the table is named at use.
    at_use(
        &|t| {
            t.daylight_outputs.pop();
            t.daylight_modes.push(0.0);
        },
        "daylight_outputs",
    );
    at_use(
        &|t| {
            t.sun_spacing.pop();
            t.daylight_site.push(0.0);
        },
        "daylight_site",
    );
    at_use(&|t| t.daylight_site[0] = 91.0, "daylight_site");
    at_use(&|t| t.daylight_site[4] = f64::NAN, "daylight_site");
    at_use(&|t| t.sun_lattice[0] = 0, "sun_lattice");
    at_use(&|t| t.sun_spacing[1] = 0.0, "sun_spacing");
    at_use(&|t| t.sun_spacing[0] = 80.0, "sun_spacing");
    at_use(&|t| t.sun_nodes = vec![7, 6, 8], "sun_nodes");
    at_use(&|t| t.sun_nodes = vec![6, 7, 15], "sun_nodes");
    at_use(
        &|t| t.daylight_outputs[3] = f64::INFINITY,
        "daylight_outputs",
    );
    at_use(&|t| t.daylight_modes[0] = f64::NAN, "daylight_modes");
    at_use(&|t| t.daylight_grid[5] = 2.0e9, "daylight_grid.data");
    // The sound section passes both.
    let bytes = tiny_daylight().to_bytes().unwrap();
    let basis = Basis::from_bytes(&bytes).unwrap();
    basis.check_daylight().unwrap();
    // Without daylight there is nothing to check.
    let bytes = tiny().to_bytes().unwrap();
    Basis::from_bytes(&bytes).unwrap().check_daylight().unwrap();
}

/// The sky's patch luminances are the sky's relative luminance at each centre times the scale
/// (the cap's centre is the zenith, where the CIE overcast sky is 3 times its horizon): to
/// the bit at the centres `SkyPatches::centres` computes in f32 alone, and within 10⁻⁶ at
/// the geometric centres of `SkyPatches::patch` (those are within 2 × 10⁻⁷ of each other);
/// a wrong length is an error.
#[test]
fn patch_luminances_of_a_sky() {
    use eigenrad_runtime::sky::cie::CieSky;
    use eigenrad_runtime::sky::patches::SkyPatches;
    use eigenrad_runtime::sky::RelativeSky;
    let sky = CieSky::traditional_overcast([0.0, -0.6, 0.8]).unwrap();
    let patches = SkyPatches::TREGENZA;
    let mut out = vec![0.0f32; TREGENZA];
    patches.luminances(&sky, 2000.0, &mut out).unwrap();
    let mut centres = vec![[0.0f32; 3]; TREGENZA];
    patches.centres(&mut centres).unwrap();
    for (i, &l) in out.iter().enumerate() {
        assert_eq!(l, sky.relative_luminance(centres[i]) * 2000.0);
        let geometric = sky.relative_luminance(patches.patch(i).unwrap().direction) * 2000.0;
        assert!((l - geometric).abs() <= 1e-6 * geometric, "patch {i}");
    }
    let zenith = out[TREGENZA - 1];
    assert_eq!(zenith, sky.relative_luminance([0.0, 0.0, 1.0]) * 2000.0);
    // The lowest row's centre is 6° up: (1 + 2 sin 6°)/3 of the zenith (Moon and Spencer).
    let low = (1.0 + 2.0 * 6f32.to_radians().sin()) / 3.0;
    assert!((out[0] / zenith - low).abs() < 1e-5, "{}", out[0] / zenith);
    assert!(patches.luminances(&sky, 1.0, &mut out[1..]).is_err());
    assert!(patches.luminances(&sky, f32::NAN, &mut out).is_err());
}

/// The committed `tiny-daylight.basis` (the README's daylight example reads it) is the
/// encoding of `common::tiny_daylight`.
#[test]
fn tiny_daylight_file_is_the_tiny_daylight_basis() {
    let bytes = tiny_daylight().to_bytes().unwrap();
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/data/tiny-daylight.basis"
    );
    if std::env::var_os("EIGENRAD_WRITE_GOLDEN").is_some() {
        std::fs::write(path, &bytes).unwrap();
    }
    assert_eq!(
        std::fs::read(path).unwrap(),
        bytes,
        "EIGENRAD_WRITE_GOLDEN=1 rewrites it"
    );
}

/// `tiny_daylight` with the direct sun's geometry: a 2 m × 1.5 m window face in the wall
/// y = 0 (x from 0 to 2, z from 1 to 2.5, facing +y into the room) glazed at a constant
/// τ = 0.5, no room occluder, and outside a wall at y = −2 up to z = 2.5 (x from −5 to 5).
/// The sensor (1, 1, 0.8) faces up with the hemisphere, or with `response` rows.
fn with_direct_sun(response: &[(f64, f64)]) -> eigenrad_runtime::writer::BasisTables {
    let mut t = tiny_daylight();
    t.sun_polygon_counts = vec![1, 0, 1];
    t.sun_polygon_sizes = vec![4, 4];
    t.sun_polygons = vec![
        0.0, 1.0, 0.0, // the window's normal, into the room
        0.0, 0.0, 1.0, 2.0, 0.0, 1.0, 2.0, 0.0, 2.5, 0.0, 0.0, 2.5, 0.0, 1.0,
        0.0, // the exterior wall
        -5.0, -2.0, 0.0, 5.0, -2.0, 0.0, 5.0, -2.0, 2.5, -5.0, -2.0, 2.5,
    ];
    t.sun_glazing = vec![0.5; 65];
    t.sensor_response_rows = vec![response.len() as u32];
    t.sensor_response = response.iter().flat_map(|&(a, s)| [a, s]).collect();
    t
}

/// The direct sun by hand, for the sun due south (north = 0: the room's −y) at altitude
/// `h`: from the sensor (1, 1, 0.8) the ray reaches the window at z = 0.8 + tan h and the
/// wall outside (3 m away horizontally) at z = 0.8 + 3 tan h. At 45° it passes both (1.8 in
/// 1 to 2.5, 3.8 over 2.5) and reads τ cos θ = 0.5 sin 45°; at 25° the wall hides it (2.2
/// below 2.5). The evaluator adds `E_n` times it to the interpolated node readings at the
/// sensor and at the grid points (which face up too), and nothing at the zone; with a
/// response table, the table at θ = 45° in place of cos θ.
#[test]
fn the_direct_sun_is_added_at_sensors_and_grid_points() {
    let south = |degrees: f32| {
        let h = degrees.to_radians();
        Sun {
            direction: [0.0, -h.cos(), h.sin()],
            direct_normal: 50_000.0,
        }
    };
    let plain_bytes = tiny_daylight().to_bytes().unwrap();
    let plain = Basis::from_bytes(&plain_bytes).unwrap();
    let cases: [(&[(f64, f64)], f64); 2] = [
        (&[], std::f64::consts::FRAC_1_SQRT_2),
        // Linear in the polar angle: 1 + (0.5 − 1)(π/4)/(π/3) = 0.625.
        (
            &[(0.0, 1.0), (std::f64::consts::FRAC_PI_3, 0.5), (1.4, 0.0)],
            0.625,
        ),
    ];
    for (response, weight) in cases {
        let bytes = with_direct_sun(response).to_bytes().unwrap();
        let basis = Basis::from_bytes(&bytes).unwrap();
        let direct = eigenrad_runtime::sky::direct::DirectSun::new(&basis)
            .unwrap()
            .unwrap();
        assert!(eigenrad_runtime::sky::direct::DirectSun::new(&plain)
            .unwrap()
            .is_none());
        let dark = vec![0.0; TREGENZA];
        for (altitude, want) in [(45.0, 0.5 * weight), (25.0, 0.0)] {
            let sun = south(altitude);
            let room = direct.room_direction(sun.direction);
            let at = direct.at_sensor(0, room);
            assert!(
                (f64::from(at) - want).abs() <= 1e-6,
                "{altitude}°: {at} vs {want}"
            );
            let mut with = Day::new(basis).unwrap();
            let mut without = Day::new(plain).unwrap();
            with.set_sky(&dark, 0.0, Some(sun)).unwrap();
            without.set_sky(&dark, 0.0, Some(sun)).unwrap();
            let added =
                with.sensor_illuminance(0).unwrap() - without.sensor_illuminance(0).unwrap();
            let expected = 50_000.0 * want;
            assert!(
                (f64::from(added) - expected).abs() <= 1e-5 * 50_000.0,
                "{altitude}°: sensor {added} vs {expected}"
            );
            assert_eq!(with.zone_illuminance(0), without.zone_illuminance(0));
            for point in 0..2 {
                let grid = with.grid_point_illuminance(0, point).unwrap()
                    - without.grid_point_illuminance(0, point).unwrap();
                let want = 50_000.0
                    * if altitude > 30.0 {
                        0.5 * std::f64::consts::FRAC_1_SQRT_2
                    } else {
                        0.0
                    };
                assert!(
                    (f64::from(grid) - want).abs() <= 1e-5 * 50_000.0,
                    "{altitude}°: point {point} {grid} vs {want}"
                );
            }
        }
    }
}

/// The daylight evaluator refuses malformed direct-sun tables, naming each.
#[test]
fn evaluator_refuses_bad_direct_sun_tables() {
    let check = |edit: &dyn Fn(&mut eigenrad_runtime::writer::BasisTables), field: &str| {
        let mut t = with_direct_sun(&[(0.0, 1.0), (1.0, 0.5)]);
        Day::new(Basis::from_bytes(&t.to_bytes().unwrap()).unwrap()).unwrap();
        edit(&mut t);
        // The decoder leaves these tables to the daylight evaluator, which checks them.
        let bytes = t.to_bytes().unwrap();
        let basis = Basis::from_bytes(&bytes).unwrap();
        let err = Day::new(basis).unwrap_err();
        let named = match err {
            Error::DecodeField { field, .. }
            | Error::DecodeLength { field, .. }
            | Error::DecodeValue { field, .. } => field,
            other => panic!("{field}: {other:?}"),
        };
        assert_eq!(named, field, "{err:?}");
    };
    check(
        &|t| t.sun_polygon_counts.pop().map(drop).unwrap(),
        "sun_polygon_counts",
    );
    check(&|t| t.sun_polygon_counts[2] = 2, "sun_polygon_sizes");
    check(&|t| t.sun_polygon_sizes[1] = 2, "sun_polygon_sizes");
    check(&|t| t.sun_polygon_sizes[1] = 65, "sun_polygon_sizes");
    check(&|t| t.sun_polygons.truncate(20), "sun_polygons");
    check(&|t| t.sun_polygons[1] = 0.5, "sun_polygons");
    check(&|t| t.sun_polygons[4] = f64::NAN, "sun_polygons");
    check(&|t| t.sun_glazing[3] = 1.5, "sun_glazing");
    check(&|t| t.sun_glazing.truncate(64), "sun_glazing");
    check(&|t| t.sensor_response_rows.push(0), "sensor_response_rows");
    check(&|t| t.sensor_response[2] = -0.1, "sensor_response");
    check(&|t| t.sensor_response[3] = -0.5, "sensor_response");
    check(&|t| t.sensor_response[0] = 4.0, "sensor_response");
    check(&|t| t.sensor_response.push(1.0), "sensor_response");
    // Geometry without its counts.
    check(&|t| t.sun_polygon_counts.clear(), "sun_polygon_sizes");
}
