//! Properties over corrupted bases: decoding never panics, and whatever decodes evaluates to
//! finite numbers (or a documented error) for any finite, non-negative input. The channel
//! evaluator reads finite numbers for every level in range: its sums cannot overflow.
#![allow(
    clippy::unwrap_used,
    clippy::expect_used,
    clippy::indexing_slicing,
    clippy::panic
)]

mod common;

use eigenrad_runtime::format::{FORMAT_VERSION, HEADER_LEN};
use eigenrad_runtime::{Basis, ChannelEvaluator, Error, Evaluator, Formulation, Precision};
use proptest::prelude::*;

/// Valid bases of every formulation, precision and band count.
fn seeds() -> Vec<Vec<u8>> {
    let mut out = vec![common::tiny().to_bytes().unwrap()];
    for f in [Formulation::Split, Formulation::Seed] {
        for p in [Precision::F32, Precision::F16, Precision::I16] {
            for bands in [1, 3] {
                out.push(common::random(13, f, p, bands).to_bytes().unwrap());
            }
        }
    }
    out
}

#[derive(Clone, Debug)]
enum Mutation {
    Flip { at: usize, mask: u8 },
    Set { at: usize, value: u8 },
    Truncate { len: usize },
    Insert { at: usize, value: u8 },
    Remove { at: usize },
}

fn mutation() -> impl Strategy<Value = Mutation> {
    prop_oneof![
        (any::<usize>(), 1..=255u8).prop_map(|(at, mask)| Mutation::Flip { at, mask }),
        (any::<usize>(), any::<u8>()).prop_map(|(at, value)| Mutation::Set { at, value }),
        any::<usize>().prop_map(|len| Mutation::Truncate { len }),
        (any::<usize>(), any::<u8>()).prop_map(|(at, value)| Mutation::Insert { at, value }),
        any::<usize>().prop_map(|at| Mutation::Remove { at }),
    ]
}

fn apply(bytes: &mut Vec<u8>, m: &Mutation) {
    let n = bytes.len().max(1);
    match *m {
        Mutation::Flip { at, mask } => {
            if let Some(b) = bytes.get_mut(at % n) {
                *b ^= mask;
            }
        }
        Mutation::Set { at, value } => {
            if let Some(b) = bytes.get_mut(at % n) {
                *b = value;
            }
        }
        Mutation::Truncate { len } => bytes.truncate(len % n),
        Mutation::Insert { at, value } => bytes.insert(at % (bytes.len() + 1), value),
        Mutation::Remove { at } => {
            if !bytes.is_empty() {
                bytes.remove(at % bytes.len());
            }
        }
    }
}

/// Evaluates everything the basis offers; every Ok value must be finite.
fn evaluate_all<const B: usize>(basis: Basis<'_>, levels: &[f32], exitance: f32) {
    let Ok(mut e) = Evaluator::<B, 64, 16, 8, 8>::new(basis) else {
        return;
    };
    let m = basis.channel_count();
    let lv: Vec<f32> = (0..m).map(|c| levels[c % levels.len()]).collect();
    match e.set_channel_levels(&lv) {
        Ok(()) | Err(Error::InvalidInput { .. }) => {}
        Err(other) => panic!("unexpected {other:?}"),
    }
    for c in 0..m {
        let _ = e.set_channel_level(c, levels[(c + 1) % levels.len()]);
        let _ = e.set_channel_arc_power(c, 200);
    }
    for i in 0..basis.patch_count() {
        let _ = e.set_patch_exitance(i, [exitance; B]);
    }
    let finite = |r: eigenrad_runtime::Result<[f32; B]>| {
        if let Ok(v) = r {
            assert!(v.iter().all(|x| x.is_finite()), "non-finite reading {v:?}");
        }
    };
    for i in 0..basis.patch_count() {
        finite(e.exitance(i));
        finite(e.irradiance(i));
        finite(e.luminance(i));
    }
    for s in 0..basis.sensor_count() {
        finite(e.sensor_irradiance(s));
    }
    for z in 0..basis.zone_count() {
        finite(e.zone_irradiance(z));
        let points = basis.grid_points(z).unwrap_or(0);
        for point in 0..=points {
            finite(e.grid_point_irradiance(z, point));
        }
        figures_finite(e.zone_figures(z));
    }
}

/// Every figure of an `Ok` is finite; a zone without a grid (or with a reading that is not
/// finite) is [`Error::NoGrid`].
fn figures_finite<const B: usize>(r: eigenrad_runtime::Result<[eigenrad_runtime::Figures; B]>) {
    match r {
        Ok(f) => assert!(
            f.iter()
                .all(|x| [x.average, x.minimum, x.maximum, x.uniformity]
                    .iter()
                    .all(|v| v.is_finite())),
            "non-finite figures {f:?}"
        ),
        Err(Error::NoGrid { .. } | Error::InvalidInput { .. }) => {}
        Err(other) => panic!("unexpected {other:?}"),
    }
}

/// The same for the channel evaluator: levels only.
fn evaluate_channels<const B: usize>(basis: Basis<'_>, levels: &[f32]) {
    let Ok(mut e) = ChannelEvaluator::<B, 8>::new(basis) else {
        return;
    };
    let m = basis.channel_count();
    let lv: Vec<f32> = (0..m).map(|c| levels[c % levels.len()]).collect();
    e.set_channel_levels(&lv).unwrap();
    for c in 0..m {
        e.set_channel_level(c, levels[(c + 1) % levels.len()])
            .unwrap();
        e.set_channel_arc_power(c, 200).unwrap();
    }
    let finite = |r: eigenrad_runtime::Result<[f32; B]>| match r {
        Ok(v) => assert!(v.iter().all(|x| x.is_finite()), "non-finite reading {v:?}"),
        Err(Error::BlackPatch { .. }) => {}
        Err(other) => panic!("unexpected {other:?}"),
    };
    for i in 0..basis.patch_count() {
        finite(e.exitance(i));
        finite(e.irradiance(i));
        finite(e.luminance(i));
    }
    for s in 0..basis.sensor_count() {
        finite(e.sensor_irradiance(s));
    }
    for z in 0..basis.zone_count() {
        finite(e.zone_irradiance(z));
        let points = basis.grid_points(z).unwrap_or(0);
        for point in 0..points {
            finite(e.grid_point_irradiance(z, point));
        }
        assert!(matches!(
            e.grid_point_irradiance(z, points),
            Err(Error::IndexOutOfRange { .. })
        ));
        figures_finite(e.zone_figures(z));
    }
}

fn exercise(bytes: &[u8], levels: &[f32], exitance: f32) {
    if let Ok(basis) = Basis::from_bytes(bytes) {
        match basis.bands() {
            1 => {
                evaluate_all::<1>(basis, levels, exitance);
                evaluate_channels::<1>(basis, levels);
            }
            _ => {
                evaluate_all::<3>(basis, levels, exitance);
                evaluate_channels::<3>(basis, levels);
            }
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 2000, ..ProptestConfig::default() })]

    #[test]
    fn mutated_bases_decode_or_fail_cleanly(
        seed in 0..13usize,
        mutations in prop::collection::vec(mutation(), 1..6),
        resealed in any::<bool>(),
        levels in prop::collection::vec(0.0f32..=1000.0, 1..4),
        exitance in 0.0f32..=1.0e9,
    ) {
        let mut bytes = seeds()[seed % 13].clone();
        for m in &mutations {
            apply(&mut bytes, m);
        }
        if resealed {
            common::reseal_length_and_checksum(&mut bytes);
        }
        exercise(&bytes, &levels, exitance);
    }

    #[test]
    fn arbitrary_bytes_never_panic(bytes in prop::collection::vec(any::<u8>(), 0..512), resealed in any::<bool>()) {
        let mut bytes = bytes;
        if resealed && bytes.len() >= 8 {
            bytes[..8].copy_from_slice(b"EIGENRAD");
            if bytes.len() >= HEADER_LEN {
                bytes[8..10].copy_from_slice(&FORMAT_VERSION.to_le_bytes());
                bytes[10..12].copy_from_slice(&[0, 0]);
            }
            common::reseal_length_and_checksum(&mut bytes);
        }
        exercise(&bytes, &[1.0], 1.0);
    }

    #[test]
    fn accepted_bases_give_finite_readings(
        seed in 0..13usize,
        levels in prop::collection::vec(0.0f32..=1000.0, 1..4),
        exitance in 0.0f32..=1.0e9,
    ) {
        let bytes = seeds()[seed % 13].clone();
        prop_assert!(Basis::from_bytes(&bytes).is_ok());
        exercise(&bytes, &levels, exitance);
    }
}
