//! A random basis of three bands written by the runtime's writer, for the firmware's
//! checks on a basis no build makes.

use std::path::PathBuf;

use super::*;

/// Dimensions of a random basis.
#[derive(Clone, Copy)]
struct Dims {
    patches: usize,
    modes: usize,
    bands: usize,
    channels: usize,
    sensors: usize,
    zones: usize,
}

/// A random split-formulation basis with consistent dimensions and plausible magnitudes: the
/// numbers are not a room's, but every table the evaluator reads is filled.
fn random_basis(seed: u64, d: Dims, precision: Precision) -> Vec<u8> {
    let mut rng = Rng(seed | 1);
    let (n, p, bands, m) = (d.patches, d.modes, d.bands, d.channels);
    let outputs = d.sensors + d.zones;
    let quantity = if bands == 1 {
        Quantity::Photometric
    } else {
        Quantity::Radiometric
    };
    let mut t = BasisTables {
        surface_names: vec!["walls".into(), "luminaires".into()],
        channel_names: (0..m).map(|c| format!("ch{c}")).collect(),
        sensor_names: (0..d.sensors).map(|s| format!("desk{s}")).collect(),
        zone_names: (0..d.zones).map(|z| format!("plane{z}")).collect(),
        ..BasisTables::new(quantity, Formulation::Split, precision, bands, p)
    };
    t.eigenvalues = (0..bands * p).map(|_| rng.range(-0.3, 0.9)).collect();
    for i in 0..n {
        t.patch_area.push(rng.range(0.05, 0.5));
        t.patch_centroid.push([
            rng.range(0.0, 6.0),
            rng.range(0.0, 4.0),
            rng.range(0.0, 3.0),
        ]);
        let lamp = i % 11 == 5;
        t.patch_surface.push(u16::from(lamp));
        t.patch_channel.push(lamp.then_some((i % m) as u16));
        for _ in 0..bands {
            // Every other luminaire patch is black (ρ = 0), so the black-patch tables are
            // exercised too.
            t.patch_reflectance.push(if lamp && i % 2 == 1 {
                0.0
            } else {
                rng.range(0.05, 0.9)
            });
            t.patch_emission
                .push(if lamp { rng.range(500.0, 5000.0) } else { 0.0 });
        }
    }
    let black = (0..n)
        .filter(|&i| (0..bands).any(|b| t.patch_reflectance[i * bands + b] == 0.0))
        .count();
    for i in 0..n {
        for b in 0..bands {
            let is_black = t.patch_reflectance[i * bands + b] == 0.0;
            for _ in 0..p {
                t.modes
                    .push(if is_black { 0.0 } else { rng.range(-1.0, 1.0) });
            }
        }
    }
    t.black_projection = (0..black * bands * p)
        .map(|_| rng.range(-0.5, 0.5))
        .collect();
    // Each channel's exitance on every patch: reflected light everywhere plus the emission
    // of the channel's own luminaires, as an exact response has it.
    for i in 0..n {
        for c in 0..m {
            for b in 0..bands {
                let own = t.patch_channel[i] == Some(c as u16);
                let emission = if own {
                    t.patch_emission[i * bands + b]
                } else {
                    0.0
                };
                t.channel_response.push(emission + rng.range(0.0, 80.0));
            }
        }
    }
    t.sensor_geometry = (0..d.sensors)
        .map(|_| [1.0, 2.0, 0.8, 0.0, 0.0, 1.0, 1.2])
        .collect();
    t.zone_area = (0..d.zones).map(|_| rng.range(5.0, 20.0)).collect();
    // Mostly positive, as the dominant modes of a room are: readings stay well away from 0.
    t.output_modes = (0..outputs * bands * p)
        .map(|_| rng.range(-0.1, 0.5))
        .collect();
    t.output_channels = (0..outputs * bands * m)
        .map(|_| rng.range(0.0, 60.0))
        .collect();
    t.output_view = (0..n * outputs).map(|_| rng.range(0.0, 0.05)).collect();
    t.to_bytes().expect("random tables encode")
}

/// Dimensions of the random RGB basis: 200 patches, 24 modes, 3 bands, 3 channels, 2
/// sensors, 1 zone.
const RGB: Dims = Dims {
    patches: 200,
    modes: 24,
    bands: 3,
    channels: 3,
    sensors: 2,
    zones: 1,
};

/// The random RGB basis, written next to the test's other bases.
pub(crate) fn rgb_basis() -> PathBuf {
    let path = work_dir().join("random-rgb.basis");
    std::fs::write(&path, random_basis(12, RGB, Precision::F32)).unwrap();
    path
}
