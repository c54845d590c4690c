//! The evaluators' contracts: capacities checked with both sizes, bad requests as errors
//! that leave the state alone, a tiny grid by hand, the DALI curve, RAM independent of the
//! basis, and grid means in f32.
#![allow(
    clippy::unwrap_used,
    clippy::expect_used,
    clippy::indexing_slicing,
    clippy::panic,
    clippy::needless_range_loop
)]

mod common;

use eigenrad_runtime::{
    dali, Basis, ChannelEvaluator, Error, Evaluator, Figures, Formulation, Precision,
};

/// The full evaluator at the capacities of these tests: 3 or 1 bands, 64 patches, 16 modes,
/// 8 channels, 8 outputs.
type Eval3<'a> = Evaluator<'a, 3, 64, 16, 8, 8>;
type Eval1<'a> = Evaluator<'a, 1, 64, 16, 8, 8>;

#[test]
fn capacities_are_checked_with_both_sizes() {
    let t = common::random(1, Formulation::Split, Precision::F32, 1);
    let bytes = t.to_bytes().unwrap();
    let basis = Basis::from_bytes(&bytes).unwrap();
    assert_eq!(
        Evaluator::<1, 22, 16, 8, 8>::new(basis).unwrap_err(),
        Error::Capacity {
            what: "patches",
            needed: 23,
            capacity: 22
        }
    );
    assert_eq!(
        Evaluator::<1, 64, 6, 8, 8>::new(basis).unwrap_err(),
        Error::Capacity {
            what: "modes",
            needed: 7,
            capacity: 6
        }
    );
    assert_eq!(
        Evaluator::<1, 64, 16, 2, 8>::new(basis).unwrap_err(),
        Error::Capacity {
            what: "channels",
            needed: 3,
            capacity: 2
        }
    );
    assert_eq!(
        Evaluator::<1, 64, 16, 8, 3>::new(basis).unwrap_err(),
        Error::Capacity {
            what: "outputs",
            needed: 4,
            capacity: 3
        }
    );
    assert_eq!(
        Evaluator::<3, 64, 16, 8, 8>::new(basis).unwrap_err(),
        Error::Capacity {
            what: "bands",
            needed: 1,
            capacity: 3
        }
    );
    assert!(Evaluator::<1, 23, 7, 3, 4>::new(basis).is_ok());
    assert_eq!(
        ChannelEvaluator::<1, 2>::new(basis).unwrap_err(),
        Error::Capacity {
            what: "channels",
            needed: 3,
            capacity: 2
        }
    );
    assert_eq!(
        ChannelEvaluator::<3, 8>::new(basis).unwrap_err(),
        Error::Capacity {
            what: "bands",
            needed: 1,
            capacity: 3
        }
    );
    assert!(ChannelEvaluator::<1, 3>::new(basis).is_ok());
}

#[test]
fn bad_requests_are_errors_and_leave_the_state_alone() {
    let t = common::random(2, Formulation::Split, Precision::F32, 1);
    let bytes = t.to_bytes().unwrap();
    let basis = Basis::from_bytes(&bytes).unwrap();
    let mut e = Eval1::new(basis).unwrap();
    e.set_channel_levels(&[0.5, 0.5, 0.5]).unwrap();
    e.set_patch_exitance(4, [80.0]).unwrap();
    let before: Vec<_> = (0..23).map(|i| e.exitance(i).unwrap()).collect();
    let sensors = [
        e.sensor_irradiance(0).unwrap(),
        e.zone_irradiance(1).unwrap(),
    ];
    for bad in [f32::NAN, -0.1, f32::INFINITY, 1e4] {
        assert_eq!(
            e.set_channel_level(0, bad).unwrap_err(),
            Error::InvalidInput { what: "level" }
        );
        assert_eq!(
            e.set_channel_levels(&[0.1, bad, 0.2]).unwrap_err(),
            Error::InvalidInput { what: "level" }
        );
        assert_eq!(
            e.set_patch_exitance(0, [bad * 1e6]).unwrap_err(),
            Error::InvalidInput { what: "exitance" }
        );
    }
    assert!(matches!(
        e.set_channel_levels(&[0.5]),
        Err(Error::LengthMismatch { .. })
    ));
    assert!(matches!(
        e.set_channel_level(3, 0.5),
        Err(Error::IndexOutOfRange {
            what: "channel",
            ..
        })
    ));
    assert!(matches!(
        e.set_patch_exitance(23, [1.0]),
        Err(Error::IndexOutOfRange { what: "patch", .. })
    ));
    assert!(matches!(
        e.sensor_irradiance(2),
        Err(Error::IndexOutOfRange { what: "sensor", .. })
    ));
    assert!(matches!(
        e.zone_irradiance(2),
        Err(Error::IndexOutOfRange { what: "zone", .. })
    ));
    assert!(matches!(
        e.exitance(23),
        Err(Error::IndexOutOfRange { what: "patch", .. })
    ));
    assert!(matches!(
        e.exitance_all(&mut [[0.0]; 3]),
        Err(Error::LengthMismatch { .. })
    ));
    assert_eq!(
        e.set_channel_arc_power(0, 255).unwrap_err(),
        Error::DaliMask
    );
    let after: Vec<_> = (0..23).map(|i| e.exitance(i).unwrap()).collect();
    assert_eq!(after, before);
    assert_eq!(
        [
            e.sensor_irradiance(0).unwrap(),
            e.zone_irradiance(1).unwrap()
        ],
        sensors
    );
    for c in 0..3 {
        assert_eq!(e.channel_level(c).unwrap(), 0.5);
    }

    // The channel evaluator refuses the same requests the same way.
    let mut c = ChannelEvaluator::<1, 8>::new(basis).unwrap();
    c.set_channel_levels(&[0.5, 0.5, 0.5]).unwrap();
    let before: Vec<_> = (0..23).map(|i| c.exitance(i).unwrap()).collect();
    for bad in [f32::NAN, -0.1, f32::INFINITY, 1e4] {
        assert_eq!(
            c.set_channel_level(0, bad).unwrap_err(),
            Error::InvalidInput { what: "level" }
        );
        assert_eq!(
            c.set_channel_levels(&[bad, 0.1, 0.2]).unwrap_err(),
            Error::InvalidInput { what: "level" }
        );
    }
    assert!(matches!(
        c.set_channel_levels(&[0.5; 4]),
        Err(Error::LengthMismatch { .. })
    ));
    assert!(matches!(
        c.set_channel_level(3, 0.5),
        Err(Error::IndexOutOfRange { .. })
    ));
    assert!(matches!(
        c.channel_level(3),
        Err(Error::IndexOutOfRange { .. })
    ));
    assert!(matches!(
        c.exitance(23),
        Err(Error::IndexOutOfRange { what: "patch", .. })
    ));
    assert!(matches!(
        c.sensor_irradiance(2),
        Err(Error::IndexOutOfRange { what: "sensor", .. })
    ));
    assert!(matches!(
        c.zone_irradiance(2),
        Err(Error::IndexOutOfRange { what: "zone", .. })
    ));
    assert!(matches!(
        c.exitance_all(&mut [[0.0]; 24]),
        Err(Error::LengthMismatch { .. })
    ));
    assert_eq!(
        c.set_channel_arc_power(1, 255).unwrap_err(),
        Error::DaliMask
    );
    let after: Vec<_> = (0..23).map(|i| c.exitance(i).unwrap()).collect();
    assert_eq!(after, before);
    // A black patch has no irradiance to read back.
    assert_eq!(c.irradiance(3).unwrap_err(), Error::BlackPatch { patch: 3 });
}

/// The tiny basis' grid by hand (`common::tiny`): two points, channel readings 110 and 90
/// lux at level 1; exitance δ on the floor (ρ 0.5, 2 m², v = 0.5, μ = 0.5 so c = 1) gives the
/// mode amplitude δ·A/ρ·v·c = δ·2/0.5·0.5·1 = 2δ, and the points 0.25·2δ and 0.3·2δ (the floor is not in
/// their view); on the black lamp (projection 25) 0.25·25δ + 0.12δ and 0.3·25δ + 0.08δ.
#[test]
fn tiny_grid_by_hand() {
    let bytes = common::tiny().to_bytes().unwrap();
    let basis = Basis::from_bytes(&bytes).unwrap();
    assert_eq!(basis.grid_piece_count(0).unwrap(), 1);
    let grid = basis.grid_piece(0, 0).unwrap();
    assert_eq!((grid.points, grid.counts, grid.border), (2, [2, 1], 0.5));
    assert_eq!(basis.grid_point(0, 1).unwrap(), [1.5, 1.0, 0.8]);
    let mut c = ChannelEvaluator::<1, 1>::new(basis).unwrap();
    c.set_channel_level(0, 0.5).unwrap();
    assert_eq!(c.grid_point_irradiance(0, 0).unwrap(), [55.0]);
    let f = c.zone_figures(0).unwrap()[0];
    assert_eq!((f.average, f.minimum, f.maximum), (50.0, 45.0, 55.0));
    assert!((f.uniformity - 0.9).abs() < 1e-6);
    let mut e = Evaluator::<1, 2, 1, 1, 2>::new(basis).unwrap();
    e.set_patch_exitance(0, [10.0]).unwrap();
    let at = |e: &Evaluator<'_, 1, 2, 1, 1, 2>, p| e.grid_point_irradiance(0, p).unwrap()[0];
    assert!((at(&e, 0) - 5.0).abs() < 1e-5 && (at(&e, 1) - 6.0).abs() < 1e-5);
    e.set_patch_exitance(0, [0.0]).unwrap();
    e.set_patch_exitance(1, [10.0]).unwrap();
    assert!((at(&e, 0) - 63.7).abs() < 1e-4, "{}", at(&e, 0));
    assert!((at(&e, 1) - 75.8).abs() < 1e-4, "{}", at(&e, 1));
    let f = e.zone_figures(0).unwrap()[0];
    assert!((f.average - 69.75).abs() < 1e-4 && f.minimum == at(&e, 0));
    // Unlit: no uniformity.
    let dark = ChannelEvaluator::<1, 1>::new(basis).unwrap();
    assert_eq!(dark.zone_figures(0).unwrap()[0].uniformity, 0.0);
}

/// What `arc_power_to_level` promises (relative to the curve evaluated in `f64`).
const DALI_CURVE_TOLERANCE: f64 = 3e-7;

#[test]
fn dali_curve() {
    // IEC 62386-102: X(n) = 10^((n−1)/(253/3) − 1) %.
    assert_eq!(dali::arc_power_to_level(0).unwrap(), 0.0);
    assert!((dali::arc_power_to_level(1).unwrap() - 0.001).abs() < 1e-9);
    assert!((dali::arc_power_to_level(254).unwrap() - 1.0).abs() < 1e-6);
    for n in 1..=254u8 {
        let want = 10f64.powf((f64::from(n) - 1.0) / (253.0 / 3.0) - 1.0) / 100.0;
        let got = f64::from(dali::arc_power_to_level(n).unwrap());
        assert!(
            (got - want).abs() <= DALI_CURVE_TOLERANCE * want,
            "arc {n}: {got} vs {want}"
        );
    }
    for n in 1..254u8 {
        assert!(dali::arc_power_to_level(n + 1).unwrap() > dali::arc_power_to_level(n).unwrap());
    }
    assert_eq!(dali::arc_power_to_level(255), Err(Error::DaliMask));
}

#[test]
fn ram_does_not_depend_on_the_basis() {
    // The evaluator's size is fixed by its capacities; the basis stays in the byte slice.
    // Besides the state it holds the basis view: one slice header per table (56 of them, 16
    // bytes each on a 64-bit host), the counts and the settings.
    const VIEW: usize = 1100;
    let size = core::mem::size_of::<Eval3<'_>>();
    assert!(
        (Eval3::RAM_BYTES..=Eval3::RAM_BYTES + VIEW).contains(&size),
        "{size} vs {}",
        Eval3::RAM_BYTES
    );
    type Channels3<'a> = ChannelEvaluator<'a, 3, 8>;
    let channel_size = core::mem::size_of::<Channels3<'_>>();
    assert!(
        (Channels3::RAM_BYTES..=Channels3::RAM_BYTES + VIEW).contains(&channel_size),
        "{channel_size} vs {}",
        Channels3::RAM_BYTES
    );
    // The channel evaluator carries no per-patch, per-mode or per-output state.
    assert_eq!(Channels3::RAM_BYTES, 4 * 8);
    assert_eq!(
        Eval3::RAM_BYTES,
        Channels3::RAM_BYTES + 4 * 3 * (16 + 64 + 8)
    );
    for seed in [1, 2] {
        let small = common::random(seed, Formulation::Split, Precision::F32, 3);
        let bytes = small.to_bytes().unwrap();
        let basis = Basis::from_bytes(&bytes).unwrap();
        let e = Eval3::new(basis).unwrap();
        assert_eq!(core::mem::size_of_val(&e), size);
        let c = Channels3::new(basis).unwrap();
        assert_eq!(core::mem::size_of_val(&c), channel_size);
    }
}

/// The figures' mean is summed with compensation in the readings' own precision: a million
/// `f32` points of 0.1 (a plain `f32` sum drifts by about 1 % there) average to 0.1 within one
/// rounding, and small readings after a large one are not lost.
#[test]
fn grid_mean_keeps_its_digits_in_f32() {
    let f = Figures::of((0..1_000_000).map(|_| 0.1f32)).unwrap();
    assert!(
        (f.average - 0.1).abs() <= 0.1 * f32::EPSILON,
        "{}",
        f.average
    );
    let mut values = vec![1.0e8f32];
    values.extend(std::iter::repeat_n(1.0f32, 10_000));
    let f = Figures::of(values.iter().copied()).unwrap();
    let want = (1.0e8 + 1.0e4) / 10_001.0;
    assert!(
        (f64::from(f.average) - want).abs() <= want * 1e-7,
        "{}",
        f.average
    );
    assert_eq!((f.minimum, f.maximum, f.points), (1.0, 1.0e8, 10_001));
}
