//! Shared helpers: a small deterministic random generator and hand-built bases.
#![allow(
    dead_code,
    clippy::unwrap_used,
    clippy::expect_used,
    clippy::indexing_slicing,
    clippy::panic
)]

use eigenrad_runtime::writer::BasisTables;
use eigenrad_runtime::{Formulation, Precision, Quantity};

/// xorshift64*: deterministic, dependency-free.
pub struct Rng(pub u64);
impl Rng {
    pub fn next_f64(&mut self) -> f64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        (self.0.wrapping_mul(0x2545_F491_4F6C_DD1D) >> 11) as f64 / (1u64 << 53) as f64
    }
    pub fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.next_f64()
    }
}

/// The smallest meaningful basis: 2 patches, 1 mode, 1 band, 1 channel, 1 sensor, 1 zone.
/// Numbers are chosen by hand (not physically derived): the golden-bytes test freezes the
/// layout, not the physics.
pub fn tiny() -> BasisTables {
    BasisTables {
        quantity: Quantity::Photometric,
        formulation: Formulation::Split,
        precision: Precision::F32,
        bands: 1,
        mode_count: 1,
        surface_names: vec!["floor".into(), "lamp".into()],
        channel_names: vec!["main".into()],
        sensor_names: vec!["desk".into()],
        zone_names: vec!["plane".into()],
        eigenvalues: vec![0.5],
        patch_area: vec![2.0, 0.25],
        patch_centroid: vec![[1.0, 1.0, 0.0], [1.0, 1.0, 2.5]],
        patch_surface: vec![0, 1],
        patch_channel: vec![None, Some(0)],
        patch_reflectance: vec![0.5, 0.0],
        patch_emission: vec![0.0, 1000.0],
        modes: vec![0.5, 0.0],
        black_projection: vec![25.0],
        // The floor's exitance and the lamp's (its emission: it reflects nothing).
        channel_response: vec![75.0, 1000.0],
        sensor_geometry: vec![[1.0, 1.0, 0.8, 0.0, 0.0, 1.0, std::f64::consts::PI]],
        zone_area: vec![2.0],
        output_modes: vec![0.25, 0.5],
        output_channels: vec![100.0, 40.0],
        output_view: vec![0.0, 0.0, 0.1, 0.05],
        // The zone's grid: one piece of 2 × 1 points at 0.8 m, facing up.
        grid_pieces: vec![1],
        grid_lattice: vec![[2, 1, 2]],
        grid_layout: vec![[0.2, 1.0, 1.0, 0.5, 0.0, 0.0, 1.0]],
        grid_position: vec![[0.5, 1.0, 0.8], [1.5, 1.0, 0.8]],
        grid_modes: vec![0.25, 0.3],
        grid_channels: vec![110.0, 90.0],
        grid_view: vec![0.0, 0.12, 0.0, 0.08],
        // No daylight.
        ..BasisTables::new(
            Quantity::Photometric,
            Formulation::Split,
            Precision::F32,
            1,
            1,
        )
    }
}

/// Tregenza's sky patches.
pub const TREGENZA: usize = 145;

/// The tiny basis with daylight: Tregenza's sky, the exterior and a sun grid of 3
/// declinations by 5 hour angles (−30° to 30° by 15°) in Vienna, of which the nodes 6, 7 and
/// 8 (the middle row's three middle columns) light the room. Node `d` of the `D = 149`
/// gives output `o` the value `(o + 1) · (d + 1)` lux per unit (a sky patch's per cd/m²),
/// mode amplitude `0.01 · (d + 1)`, grid point `g` the value `(g + 2) · (d + 1)`: by hand,
/// so that the tests can sum what the evaluator must read.
pub fn tiny_daylight() -> BasisTables {
    let mut t = tiny();
    let d = TREGENZA + 1 + 3;
    t.sky_subdivision = 1;
    t.daylight_site = vec![48.21, 16.37, 170.0, 0.0, 60.0];
    t.sun_lattice = vec![3, 5];
    t.sun_spacing = vec![-10.0, 10.0, -30.0, 15.0];
    t.sun_nodes = vec![6, 7, 8];
    let node = |k: usize| (k + 1) as f64;
    t.daylight_outputs = (0..2)
        .flat_map(|o| (0..d).map(move |k| (o + 1) as f64 * node(k)))
        .collect();
    t.daylight_modes = (0..d).map(|k| 0.01 * node(k)).collect();
    t.daylight_grid = (0..2)
        .flat_map(|g| (0..d).map(move |k| (g + 2) as f64 * node(k)))
        .collect();
    t
}

/// `tiny_daylight` with a stored first reflection (format version 7): the sky's at rank 2,
/// coefficient `j` weighing sky node `d` by `(j + 1) · 10⁻³ · (d + 1)` and giving the floor
/// (patch 0) `0.4 + 0.1 j` lux and the lamp (patch 1, black) 0 per unit; the sun nodes list
/// the floor at 0.2 and 0.3 lux per lux (nodes 6 and 8) and nothing at node 7; the modes'
/// amplitudes of what follows, `0.01 · (c + 1)` for column `c` of the 2 + 3. By hand, so
/// that the tests can sum what the evaluator must read.
pub fn tiny_daylight_reflection() -> BasisTables {
    let mut t = tiny_daylight();
    let sky = TREGENZA + 1;
    t.reflection_rank = vec![2];
    t.sky_reflection_weights = (0..2)
        .flat_map(|j| (0..sky).map(move |d| (j + 1) as f64 * 1e-3 * (d + 1) as f64))
        .collect();
    t.sky_reflection = vec![0.4, 0.5, 0.0, 0.0];
    t.sun_reflection_counts = vec![1, 0, 1];
    t.sun_reflection_patches = vec![0, 0];
    t.sun_reflection = vec![0.2, 0.3];
    t.daylight_modes = (0..5).map(|c| 0.01 * (c + 1) as f64).collect();
    t
}

/// A random basis with consistent dimensions and plausible magnitudes.
pub fn random(
    seed: u64,
    formulation: Formulation,
    precision: Precision,
    bands: usize,
) -> BasisTables {
    let mut rng = Rng(seed | 1);
    let (n, p, m, sensors, zones) = (23, 7, 3, 2, 2);
    let outputs = sensors + zones;
    let quantity = if bands == 1 {
        Quantity::Photometric
    } else {
        Quantity::Radiometric
    };
    let mut t = BasisTables {
        surface_names: vec!["walls".into(), "lamps".into()],
        channel_names: (0..m).map(|c| format!("ch{c}")).collect(),
        sensor_names: (0..sensors).map(|s| format!("s{s}")).collect(),
        zone_names: (0..zones).map(|z| format!("z{z}")).collect(),
        ..BasisTables::new(quantity, formulation, precision, bands, p)
    };
    for _ in 0..bands * p {
        t.eigenvalues.push(match formulation {
            Formulation::Split => rng.range(-0.3, 0.9),
            Formulation::Seed => rng.range(0.5, 20.0),
        });
    }
    for i in 0..n {
        t.patch_area.push(rng.range(0.05, 1.5));
        t.patch_centroid.push([
            rng.range(0.0, 4.0),
            rng.range(0.0, 4.0),
            rng.range(0.0, 3.0),
        ]);
        let lamp = i % 7 == 3;
        t.patch_surface.push(u16::from(lamp));
        t.patch_channel.push(lamp.then_some((i % m) as u16));
        for _ in 0..bands {
            t.patch_reflectance.push(if lamp && i % 2 == 1 {
                0.0
            } else {
                rng.range(0.05, 0.9)
            });
            t.patch_emission
                .push(if lamp { rng.range(100.0, 3000.0) } else { 0.0 });
        }
    }
    let black = (0..n)
        .filter(|&i| (0..bands).any(|b| t.patch_reflectance[i * bands + b] == 0.0))
        .count();
    for i in 0..n {
        for b in 0..bands {
            for _ in 0..p {
                let black = t.patch_reflectance[i * bands + b] == 0.0;
                t.modes.push(if black { 0.0 } else { rng.range(-1.0, 1.0) });
            }
        }
    }
    t.black_projection = (0..black * bands * p)
        .map(|_| rng.range(-0.5, 0.5))
        .collect();
    // Each channel's exitance on every patch: some reflected light everywhere, plus the
    // emission on the channel's own lamps, as an exact response has it.
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
    t.sensor_geometry = (0..sensors)
        .map(|_| [1.0, 2.0, 0.8, 0.0, 0.0, 1.0, 1.2])
        .collect();
    t.zone_area = (0..zones).map(|_| rng.range(1.0, 10.0)).collect();
    t.output_modes = (0..outputs * bands * p)
        .map(|_| rng.range(-0.5, 0.5))
        .collect();
    t.output_channels = (0..outputs * bands * m)
        .map(|_| rng.range(0.0, 60.0))
        .collect();
    t.output_view = (0..n * outputs).map(|_| rng.range(0.0, 0.05)).collect();
    // The first zone has a grid of two pieces, a 3 × 2 lattice and a 2 × 2 one keeping 3 of
    // its cells (a band around a task area, say); the second zone has none.
    let g = 9;
    t.grid_pieces = vec![2, 0];
    t.grid_lattice = vec![[3, 2, 6], [2, 2, 3]];
    t.grid_layout = vec![
        [0.6, 0.5, 0.5, 0.5, 0.0, 0.0, 1.0],
        [0.6, 0.5, 0.5, 0.0, 0.0, 0.0, 1.0],
    ];
    t.grid_position = (0..g)
        .map(|k| {
            [
                0.75 + 0.5 * (k % 3) as f64,
                0.75 + 0.5 * (k / 3) as f64,
                0.8,
            ]
        })
        .collect();
    t.grid_modes = (0..g * bands * p).map(|_| rng.range(-0.5, 0.5)).collect();
    t.grid_channels = (0..g * bands * m).map(|_| rng.range(0.0, 60.0)).collect();
    t.grid_view = (0..g * n).map(|_| rng.range(0.0, 0.05)).collect();
    t
}

/// Makes the header's length and checksum agree with the (mutated, perhaps truncated or
/// grown) payload, so that a mutation reaches the payload decoder instead of stopping at the
/// checksum. Bytes shorter than a header are left as they are.
pub fn reseal_length_and_checksum(bytes: &mut [u8]) {
    use eigenrad_runtime::format::{crc32, HEADER_LEN};
    if bytes.len() >= HEADER_LEN {
        let len = (bytes.len() - HEADER_LEN) as u32;
        bytes[12..16].copy_from_slice(&len.to_le_bytes());
        let crc = crc32(&bytes[HEADER_LEN..]);
        bytes[16..20].copy_from_slice(&crc.to_le_bytes());
    }
}

/// Recomputes the header checksum after a payload edit, so that a test reaches the check
/// it is about rather than stopping at the checksum.
pub fn reseal(bytes: &mut [u8]) {
    let crc = eigenrad_runtime::format::crc32(&bytes[eigenrad_runtime::format::HEADER_LEN..]);
    bytes[16..20].copy_from_slice(&crc.to_le_bytes());
}

/// `tiny_daylight` with the sun's first reflection (format version 8): a 2 m × 1.5 m window face in the wall y = 0 (x 0 to 2, z 1 to 2.5,
/// τ = 0.5), a wall outside at y = −2 up to z = 2.5, and the floor (patch 0, ρ 0.5, 2 m²)
/// as the one candidate, its polygon the 0.2 m square about (1, 1, 0.8) facing up (a
/// desk's height, so that the sun through the window reaches it). The floor's view from the sensor and
/// the zone is 0.2 and 0.3, from the grid points 0.25 and 0.35. `power` per sun node.
pub fn tiny_daylight_sun_first(power: [f64; 3]) -> BasisTables {
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
    t.sun_first_sizes = vec![4];
    t.sun_first_points = vec![
        0.0, 0.0, 1.0, // facing up
        0.9, 0.9, 0.8, 1.1, 0.9, 0.8, 1.1, 1.1, 0.8, 0.9, 1.1, 0.8,
    ];
    t.sun_node_power = power.to_vec();
    t
}
