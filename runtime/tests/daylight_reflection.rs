//! The daylight's first reflection (format version 7; docs/format.md, "First reflection"),
//! on the hand-made `common::tiny_daylight_reflection` basis: patch exitance summed by hand
//! from its tables, the capacity it needs, what the decoder refuses, and that no corruption
//! of its bytes makes the evaluator panic.
#![allow(
    clippy::unwrap_used,
    clippy::expect_used,
    clippy::indexing_slicing,
    clippy::panic
)]

mod common;

use common::{tiny_daylight, tiny_daylight_reflection, TREGENZA};
use eigenrad_runtime::sky::sun_grid::direction_of;
use eigenrad_runtime::writer::BasisTables;
use eigenrad_runtime::{Basis, DaylightEvaluator, Error, Sun};
use proptest::prelude::*;

/// Relative tolerance of an `f32` sum of a few hundred positive terms against the same sum
/// in `f64`.
const SUM_TOLERANCE: f64 = 1.0e-5;

/// Room for the tiny basis' one mode and its first reflection's two coefficients.
type Day<'a> = DaylightEvaluator<'a, 145, 2, 3>;

/// Luminances that differ patch by patch, cd/m².
fn luminances() -> Vec<f32> {
    (0..TREGENZA).map(|i| 1000.0 + 10.0 * i as f32).collect()
}

/// The coefficient `j` of the sky's first reflection for `sky` and `E_gh`, in `f64`.
fn coefficient(j: usize, sky: &[f32], global: f64) -> f64 {
    let weight = |d: usize| (j + 1) as f64 * 1e-3 * (d + 1) as f64;
    let patches: f64 = sky
        .iter()
        .enumerate()
        .map(|(d, &l)| weight(d) * f64::from(l))
        .sum();
    patches + weight(TREGENZA) * global / std::f64::consts::PI
}

fn close(got: f32, want: f64) -> bool {
    (f64::from(got) - want).abs() <= SUM_TOLERANCE * want.abs().max(1.0)
}

/// Under a sky and the sun at node 6 (declination 0°, hour angle −15°): the floor's exitance
/// is its first reflection (the sky's two coefficients through their patch values, the sun
/// node's listed 0.2) plus its mode (0.5) times the amplitude of what follows; the lamp,
/// black and listed nowhere, reads 0; with the sun at node 7, which lists nothing, the
/// floor's sun is in its mode alone.
#[test]
fn patch_exitance_is_the_first_reflection_plus_the_modes() {
    let bytes = tiny_daylight_reflection().to_bytes().unwrap();
    let basis = Basis::from_bytes(&bytes).unwrap();
    assert_eq!(basis.daylight_reflection_rank(), Some(2));
    assert_eq!(basis.daylight_exitance_state(), 3);
    let mut day = Day::new(basis).unwrap();
    let sky = luminances();
    let global = 20_000.0;
    let sun = |hour: f32| Sun {
        direction: direction_of(48.21, 0.0, hour),
        direct_normal: 80_000.0,
    };
    let z = [coefficient(0, &sky, global), coefficient(1, &sky, global)];
    let sky_first = 0.4 * z[0] + 0.5 * z[1];
    let sky_modes = 0.01 * z[0] + 0.02 * z[1];
    day.set_sky(&sky, global as f32, Some(sun(-15.0))).unwrap();
    let want = sky_first + 0.2 * 80_000.0 + 0.5 * (sky_modes + 0.03 * 80_000.0);
    assert!(close(day.exitance(0).unwrap(), want), "{want}");
    assert_eq!(day.exitance(1).unwrap(), 0.0);
    day.set_sky(&sky, global as f32, Some(sun(0.0))).unwrap();
    let want = sky_first + 0.5 * (sky_modes + 0.04 * 80_000.0);
    assert!(close(day.exitance(0).unwrap(), want), "{want}");
    // Without the sun, the sky alone; the outputs read as without a first reflection.
    day.set_sky(&sky, global as f32, None).unwrap();
    assert!(close(day.exitance(0).unwrap(), sky_first + 0.5 * sky_modes));
    let plain = tiny_daylight().to_bytes().unwrap();
    let mut old = DaylightEvaluator::<145, 2, 1>::new(Basis::from_bytes(&plain).unwrap()).unwrap();
    old.set_sky(&sky, global as f32, None).unwrap();
    assert_eq!(day.sensor_illuminance(0), old.sensor_illuminance(0));
    assert_eq!(day.zone_illuminance(0), old.zone_illuminance(0));
}

/// An evaluator keeping patch exitance needs room for the modes and the coefficients
/// together; one without reads the outputs and refuses patches.
#[test]
fn the_exitance_state_holds_modes_and_coefficients() {
    let bytes = tiny_daylight_reflection().to_bytes().unwrap();
    let basis = Basis::from_bytes(&bytes).unwrap();
    assert_eq!(
        DaylightEvaluator::<145, 2, 2>::new(basis).unwrap_err(),
        Error::Capacity {
            what: "modes and first reflection",
            needed: 3,
            capacity: 2
        }
    );
    let mut lean = DaylightEvaluator::<145, 2, 0>::new(basis).unwrap();
    lean.set_sky(&luminances(), 1000.0, None).unwrap();
    assert!(lean.sensor_illuminance(0).unwrap() > 0.0);
    assert!(matches!(lean.exitance(0), Err(Error::Capacity { .. })));
}

/// Where a bad first reflection is refused: what sizes the daylight section (the rank, the
/// modes' table) by `Basis::from_bytes`, its own tables and values when daylight is used,
/// each with the table named.
#[test]
fn decoder_refuses_bad_first_reflections() {
    let named = |err: Error| match err {
        Error::DecodeField { field, .. }
        | Error::DecodeLength { field, .. }
        | Error::DecodeValue { field, .. } => field,
        other => panic!("{other:?}"),
    };
    let bytes_of = |edit: &dyn Fn(&mut BasisTables)| {
        let mut t = tiny_daylight_reflection();
        edit(&mut t);
        t.to_bytes().unwrap()
    };
    let at_decode = |edit: &dyn Fn(&mut BasisTables), field: &str| {
        let bytes = bytes_of(edit);
        assert_eq!(named(Basis::from_bytes(&bytes).unwrap_err()), field);
    };
    let at_use = |edit: &dyn Fn(&mut BasisTables), field: &str| {
        let bytes = bytes_of(edit);
        let basis = Basis::from_bytes(&bytes).expect("the shape is sound");
        assert_eq!(named(basis.check_daylight().unwrap_err()), field);
        assert_eq!(named(Day::new(basis).unwrap_err()), field);
    };
    at_decode(&|t| t.reflection_rank.push(2), "reflection_rank");
    // The modes' table is `p × (r + sun nodes)` with a rank, `p × D` without.
    at_decode(&|t| t.daylight_modes = vec![0.0; TREGENZA + 4], "daylight");
    at_decode(&|t| t.reflection_rank.clear(), "daylight");
    // A first reflection without a sky.
    at_decode(&|t| t.sky_subdivision = 0, "daylight");
    // The first reflection's own tables, sized by its rank and counts, at use (a firmware
    // that reads no daylight links none of their checks).
    at_use(
        &|t| t.sky_reflection_weights.push(0.0),
        "sky_reflection_weights",
    );
    at_use(
        &|t| t.sky_reflection.pop().map(drop).unwrap(),
        "sky_reflection.data",
    );
    at_use(
        &|t| t.sun_reflection_counts.push(0),
        "sun_reflection_counts",
    );
    // A first reflection without a rank.
    at_use(
        &|t| {
            *t = tiny_daylight();
            t.sun_reflection_patches.push(0);
        },
        "reflection",
    );
    // Values, at use.
    at_use(
        &|t| {
            t.reflection_rank = vec![3];
            t.sky_reflection_weights = vec![0.0; 3 * (TREGENZA + 1)];
            t.sky_reflection = vec![0.0; 6];
            t.daylight_modes = vec![0.0; 6];
        },
        "reflection_rank",
    );
    at_use(
        &|t| t.sky_reflection_weights[7] = f64::NAN,
        "sky_reflection_weights",
    );
    at_use(
        &|t| t.sky_reflection[1] = f64::INFINITY,
        "sky_reflection.data",
    );
    at_use(
        &|t| t.sun_reflection_patches[1] = 2,
        "sun_reflection_patches",
    );
    at_use(
        &|t| {
            t.sun_reflection_counts = vec![2, 0, 0];
            t.sun_reflection_patches = vec![0, 0];
        },
        "sun_reflection_patches",
    );
    at_use(
        &|t| t.sun_reflection_counts[1] = 1,
        "sun_reflection_patches",
    );
    at_use(&|t| t.sun_reflection[0] = 2.0e9, "sun_reflection");
    // The sound table passes both.
    let bytes = tiny_daylight_reflection().to_bytes().unwrap();
    Basis::from_bytes(&bytes).unwrap().check_daylight().unwrap();
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    /// Bytes of the first reflection's basis with some set at random and the checksum
    /// made right again: decoding, making an evaluator, a sky update and reading every
    /// patch give values or errors, never a panic, and every value read is finite.
    #[test]
    fn corrupted_first_reflections_never_panic(
        edits in prop::collection::vec((any::<usize>(), any::<u8>()), 1..6),
        hour in -60.0f32..60.0,
    ) {
        let mut bytes = tiny_daylight_reflection().to_bytes().unwrap();
        let n = bytes.len();
        for (at, value) in edits {
            // The tables are at the payload's end: aim half the edits there.
            let at = if at % 2 == 0 { n - 1 - at % 200.min(n - 1) } else { at % n };
            bytes[at] = value;
        }
        common::reseal_length_and_checksum(&mut bytes);
        let Ok(basis) = Basis::from_bytes(&bytes) else { return Ok(()) };
        let Ok(mut day) = DaylightEvaluator::<145, 4, 16>::new(basis) else { return Ok(()) };
        let sun = Sun { direction: direction_of(48.21, 0.0, hour), direct_normal: 50_000.0 };
        if day.set_sky(&luminances(), 10_000.0, Some(sun)).is_ok() {
            for i in 0..basis.patch_count().min(64) {
                if let Ok(x) = day.exitance(i) {
                    prop_assert!(x.is_finite());
                }
            }
        }
    }
}
