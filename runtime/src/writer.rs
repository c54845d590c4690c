//! Writing a basis from owned tables (feature `alloc`; host tools and tests).
//!
//! The precompute fills a [`BasisTables`] in `f64` and calls [`BasisTables::to_bytes`]; the
//! quantisation to the storage precision and the byte layout live here, next to the reader,
//! so the two cannot drift apart.

use alloc::string::String;
use alloc::vec;
use alloc::vec::Vec;

use crate::error::{Error, Result};
use crate::format::{
    self, f32_to_f16, Counts, Formulation, MatrixBytes, Payload, Precision, Quantity, NO_CHANNEL,
};

/// Every table of a basis, owned, in `f64`, with the counts implied by the lengths.
///
/// Fields carry the names of `docs/format.md`'s payload. Notation as there: `n` patches, `p`
/// modes, `B` bands, `m` channels, `O` outputs (sensors, then zones), `G` grid points. Matrices are row-major.
/// Three things of the payload have an owned form of their own: the counts are the lengths
/// of the name lists and of `patch_area`, `names` is written from the four name lists, and
/// `black_patches` is derived from `patch_reflectance`, so that they cannot disagree.
///
/// The writer does not check the tables against each other: [`Basis::from_bytes`] does, and
/// tests rely on writing malformed bases.
///
/// The tables (de)serialize with serde, so host tools can keep them between stages (the
/// precompute's building parts) with every `f64` exact.
///
/// [`Basis::from_bytes`]: crate::Basis::from_bytes
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct BasisTables {
    /// What the numbers measure: W/m² or lux.
    pub quantity: Quantity,
    /// Expansion used.
    pub formulation: Formulation,
    /// Storage of the three matrices (`modes`, `channel_response`, `output_view`).
    pub precision: Precision,
    /// `B`: 1 or 3.
    pub bands: usize,
    /// `p`: modes per band.
    pub mode_count: usize,
    /// Surface names.
    pub surface_names: Vec<String>,
    /// Channel names (`m`).
    pub channel_names: Vec<String>,
    /// Sensor names (`S`).
    pub sensor_names: Vec<String>,
    /// Zone names (`Z`).
    pub zone_names: Vec<String>,
    /// `B × p`: `μ` (split) or `λ` (seed).
    pub eigenvalues: Vec<f64>,
    /// `n`, m².
    pub patch_area: Vec<f64>,
    /// `n`, m.
    pub patch_centroid: Vec<[f64; 3]>,
    /// `n` surface indices.
    pub patch_surface: Vec<u16>,
    /// `n`: the channel driving the patch's emission, if any (written as [`NO_CHANNEL`]
    /// when none).
    pub patch_channel: Vec<Option<u16>>,
    /// `n × B`: reflectance ρ, 0 (black) or in `[10⁻⁶, 1)`.
    pub patch_reflectance: Vec<f64>,
    /// `n × B`: exitance at channel level 1, W/m² or lux.
    pub patch_emission: Vec<f64>,
    /// `n × (B·p)`: mode vectors, patch-major.
    pub modes: Vec<f64>,
    /// `K × B × p`, black patches in ascending order (those with ρ = 0 in some band).
    pub black_projection: Vec<f64>,
    /// `n × (m·B)`: each channel's exact exitance per patch at level 1, column `c·B + b`.
    pub channel_response: Vec<f64>,
    /// Per sensor: position (m), unit normal, half-angle (rad).
    pub sensor_geometry: Vec<[f64; 7]>,
    /// Per zone, m².
    pub zone_area: Vec<f64>,
    /// `O × B × p`.
    pub output_modes: Vec<f64>,
    /// `O × B × m`.
    pub output_channels: Vec<f64>,
    /// `n × O`.
    pub output_view: Vec<f64>,
    /// Per zone: the pieces of its grid (0 without a grid). Left empty, no zone has a grid
    /// (written as a 0 per zone).
    pub grid_pieces: Vec<u32>,
    /// Per piece: cells along its first and second side, points kept.
    pub grid_lattice: Vec<[u32; 3]>,
    /// Per piece: spacing `p` (m), cell sides (m), border (m), unit normal.
    pub grid_layout: Vec<[f64; 7]>,
    /// `G` grid point positions, m.
    pub grid_position: Vec<[f64; 3]>,
    /// `G × B × p`.
    pub grid_modes: Vec<f64>,
    /// `G × B × m`.
    pub grid_channels: Vec<f64>,
    /// `G × n`.
    pub grid_view: Vec<f64>,
    /// The daylight's sky: 0 without daylight (every daylight table empty), 1 Tregenza, `n`
    /// Reinhart MF:n.
    pub sky_subdivision: u8,
    /// Empty, or latitude (°), longitude (°), elevation (m), north (°), UTC offset (minutes).
    pub daylight_site: Vec<f64>,
    /// Empty, or the sun grid's declinations and hour angles.
    pub sun_lattice: Vec<u32>,
    /// Empty, or the first declination, its step, the first hour angle, its step (°).
    pub sun_spacing: Vec<f64>,
    /// Ascending indices of the sun grid's nodes that light the room.
    pub sun_nodes: Vec<u32>,
    /// `O × D`: each output's illuminance per unit of each daylight node.
    pub daylight_outputs: Vec<f64>,
    /// `p × D`: each daylight node's mode amplitudes.
    pub daylight_modes: Vec<f64>,
    /// `G × D`: each grid point's illuminance per unit of each daylight node.
    pub daylight_grid: Vec<f64>,
    /// Empty, or the direct sun's window faces, room occluders and exterior occluders.
    pub sun_polygon_counts: Vec<u32>,
    /// Each polygon's vertex count, windows first.
    pub sun_polygon_sizes: Vec<u8>,
    /// Per polygon: unit normal, then vertices (m).
    pub sun_polygons: Vec<f64>,
    /// `W × 65`: each window face's transmittance at incidence cosines `k / 64`.
    pub sun_glazing: Vec<f64>,
    /// Rows of each sensor's angular response (0: read by its half-angle).
    pub sensor_response_rows: Vec<u32>,
    /// Polar angle (rad) and relative sensitivity pairs, sensor by sensor.
    pub sensor_response: Vec<f64>,
    /// Empty (no first reflection stored), or `r`, the rank of the sky's first reflection.
    pub reflection_rank: Vec<u32>,
    /// `r × (S_k + 1)`: each coefficient's weights of the sky's patches and the exterior.
    pub sky_reflection_weights: Vec<f64>,
    /// `n × r`: each patch's first reflection per unit of each coefficient (lux).
    pub sky_reflection: Vec<f64>,
    /// Per sun node: the patches its first reflection lists.
    pub sun_reflection_counts: Vec<u32>,
    /// The listed patches, sun node by sun node, ascending within a node.
    pub sun_reflection_patches: Vec<u32>,
    /// Each listed patch's first reflection, lux per lux of direct normal illuminance.
    pub sun_reflection: Vec<f64>,
    /// Empty, or the patches the sun can light directly, ascending.
    pub sun_first_patches: Vec<u32>,
    /// Each such patch's corners.
    pub sun_first_sizes: Vec<u8>,
    /// Per such patch: unit normal, then its corners in order (m).
    pub sun_first_points: Vec<f64>,
    /// Empty, or per sun node the controller's first-reflection power, lm per lux.
    pub sun_node_power: Vec<f64>,
    /// Empty, or per candidate every reading's response to a unit of its first reflection
    /// (sensors, zones, grid points; lux per lux).
    pub sun_first_response: Vec<f64>,
    /// Empty, or per zone the polygons its direct sun is computed on.
    pub zone_sun_counts: Vec<u32>,
    /// Each such polygon's corners.
    pub zone_sun_sizes: Vec<u8>,
    /// Per such polygon: unit normal, then its corners in order (m).
    pub zone_sun_polygons: Vec<f64>,
}

/// `values` rounded to `f32`, little-endian.
fn f32_bytes(values: &[f64]) -> Vec<u8> {
    values
        .iter()
        .flat_map(|&v| (v as f32).to_le_bytes())
        .collect()
}

/// A matrix table's bytes, owned.
struct Quantised {
    scales: Vec<u8>,
    data: Vec<u8>,
}

impl Quantised {
    /// The table as the payload borrows it.
    fn bytes(&self) -> MatrixBytes<'_> {
        MatrixBytes {
            scales: &self.scales,
            data: &self.data,
        }
    }
}

/// A row-major `rows × cols` matrix in `precision` (`docs/format.md`, "Matrices").
fn quantise(values: &[f64], cols: usize, precision: Precision) -> Quantised {
    if precision == Precision::F32 || cols == 0 {
        return Quantised {
            scales: Vec::new(),
            data: f32_bytes(values),
        };
    }
    let mut max = vec![0.0f64; cols];
    for (i, &v) in values.iter().enumerate() {
        if let Some(slot) = max.get_mut(i % cols) {
            *slot = slot.max(v.abs());
        }
    }
    // f16 keeps its largest value at 2^14, well inside its range (65504) yet far above its
    // subnormals, so small entries of a column keep their 11-bit precision.
    let top = match precision {
        Precision::I16 => 32767.0,
        _ => 16384.0,
    };
    let scales: Vec<f64> = max
        .iter()
        .map(|&m| if m > 0.0 { m / top } else { 0.0 })
        .collect();
    let mut data = Vec::with_capacity(values.len() * 2);
    for (i, &v) in values.iter().enumerate() {
        let s = scales.get(i % cols).copied().unwrap_or(0.0);
        let x = if s > 0.0 {
            v / f64::from(s as f32)
        } else {
            0.0
        };
        let bits = match precision {
            Precision::I16 => (libm::round(x).clamp(-32767.0, 32767.0) as i16).to_le_bytes(),
            _ => f32_to_f16(x as f32).to_le_bytes(),
        };
        data.extend_from_slice(&bits);
    }
    Quantised {
        scales: f32_bytes(&scales),
        data,
    }
}

/// `values` as little-endian `u16`.
fn u16_bytes(values: impl Iterator<Item = u16>) -> Vec<u8> {
    values.flat_map(u16::to_le_bytes).collect()
}

/// `values` as little-endian `u32`.
fn u32_bytes(values: &[u32]) -> Vec<u8> {
    values.iter().flat_map(|v| v.to_le_bytes()).collect()
}

/// Channel indices as `u16`, [`NO_CHANNEL`] for none.
fn channel_bytes(channels: &[Option<u16>]) -> Vec<u8> {
    u16_bytes(channels.iter().map(|c| c.unwrap_or(NO_CHANNEL)))
}

/// A count as the format's `u32`.
fn count(field: &'static str, value: usize) -> Result<u32> {
    u32::try_from(value).map_err(|_| Error::EncodeOverflow { field })
}

/// A column count of [`Counts`]; `None` means the tables are too large to address.
fn cols(value: Option<usize>) -> Result<usize> {
    value.ok_or(Error::EncodeOverflow {
        field: "dimensions",
    })
}

impl BasisTables {
    /// Tables for a basis of `bands` bands and `mode_count` modes with the given settings,
    /// every table and name list empty; fill them in before [`to_bytes`](Self::to_bytes).
    pub fn new(
        quantity: Quantity,
        formulation: Formulation,
        precision: Precision,
        bands: usize,
        mode_count: usize,
    ) -> Self {
        BasisTables {
            quantity,
            formulation,
            precision,
            bands,
            mode_count,
            surface_names: Vec::new(),
            channel_names: Vec::new(),
            sensor_names: Vec::new(),
            zone_names: Vec::new(),
            eigenvalues: Vec::new(),
            patch_area: Vec::new(),
            patch_centroid: Vec::new(),
            patch_surface: Vec::new(),
            patch_channel: Vec::new(),
            patch_reflectance: Vec::new(),
            patch_emission: Vec::new(),
            modes: Vec::new(),
            black_projection: Vec::new(),
            channel_response: Vec::new(),
            sensor_geometry: Vec::new(),
            zone_area: Vec::new(),
            output_modes: Vec::new(),
            output_channels: Vec::new(),
            output_view: Vec::new(),
            grid_pieces: Vec::new(),
            grid_lattice: Vec::new(),
            grid_layout: Vec::new(),
            grid_position: Vec::new(),
            grid_modes: Vec::new(),
            grid_channels: Vec::new(),
            grid_view: Vec::new(),
            sky_subdivision: 0,
            daylight_site: Vec::new(),
            sun_lattice: Vec::new(),
            sun_spacing: Vec::new(),
            sun_nodes: Vec::new(),
            daylight_outputs: Vec::new(),
            daylight_modes: Vec::new(),
            daylight_grid: Vec::new(),
            sun_polygon_counts: Vec::new(),
            sun_polygon_sizes: Vec::new(),
            sun_polygons: Vec::new(),
            sun_glazing: Vec::new(),
            sensor_response_rows: Vec::new(),
            sensor_response: Vec::new(),
            reflection_rank: Vec::new(),
            sky_reflection_weights: Vec::new(),
            sky_reflection: Vec::new(),
            sun_reflection_counts: Vec::new(),
            sun_reflection_patches: Vec::new(),
            sun_reflection: Vec::new(),
            sun_first_patches: Vec::new(),
            sun_first_sizes: Vec::new(),
            sun_first_points: Vec::new(),
            sun_node_power: Vec::new(),
            sun_first_response: Vec::new(),
            zone_sun_counts: Vec::new(),
            zone_sun_sizes: Vec::new(),
            zone_sun_polygons: Vec::new(),
        }
    }

    /// The counts the tables' lengths imply.
    fn counts(&self) -> Counts {
        Counts {
            bands: self.bands,
            patch_count: self.patch_area.len(),
            mode_count: self.mode_count,
            surface_count: self.surface_names.len(),
            channel_count: self.channel_names.len(),
            sensor_count: self.sensor_names.len(),
            zone_count: self.zone_names.len(),
            grid_piece_count: self.grid_lattice.len(),
            grid_point_count: self.grid_position.len(),
            daylight_node_count: format::daylight_nodes(self.sky_subdivision, self.sun_nodes.len())
                .unwrap_or(0),
            sun_node_count: self.sun_nodes.len(),
            reflection_rank: self.reflection_rank.first().map(|&r| r as usize),
        }
    }

    /// The `names` table: every name as a postcard string, surfaces, channels, sensors, zones.
    fn names(&self) -> Result<Vec<u8>> {
        let mut names = Vec::new();
        for name in self
            .surface_names
            .iter()
            .chain(&self.channel_names)
            .chain(&self.sensor_names)
            .chain(&self.zone_names)
        {
            // Room for the name and its varint length.
            let mut buf = vec![0u8; name.len() + 8];
            let used = postcard::to_slice(name.as_str(), &mut buf)
                .map_err(|_| Error::EncodePayload)?
                .len();
            names.extend_from_slice(buf.get(..used).unwrap_or(&[]));
        }
        Ok(names)
    }

    /// `grid_pieces` as written: as given, or a 0 for every zone when empty (no zone has a
    /// grid).
    fn grid_pieces(&self) -> Vec<u32> {
        if self.grid_pieces.is_empty() {
            return vec![0; self.zone_names.len()];
        }
        self.grid_pieces.clone()
    }

    /// The `black_patches` table: ascending indices of the patches with ρ = 0 in some band.
    fn black_patches(&self) -> Vec<u8> {
        let bands = self.bands;
        (0..self.patch_area.len())
            .filter(|&i| {
                (0..bands).any(|b| self.patch_reflectance.get(i * bands + b) == Some(&0.0))
            })
            .flat_map(|i| (i as u32).to_le_bytes())
            .collect()
    }

    /// Encodes the tables as a basis (header, checksum, payload).
    ///
    /// Fails with [`Error::EncodeOverflow`] when a count does not fit the format; it does
    /// not check the tables' lengths (see [`BasisTables`]).
    pub fn to_bytes(&self) -> Result<Vec<u8>> {
        let c = self.counts();
        let precision = self.precision;
        let matrix = |values: &[f64], cols: Option<usize>| -> Result<Quantised> {
            Ok(quantise(values, self::cols(cols)?, precision))
        };
        // Temporaries live to the end of the statement: the payload borrows them while it is
        // encoded, so each table is converted on the line that names its payload field.
        encode(&Payload {
            bands: u8::try_from(self.bands)
                .map_err(|_| Error::EncodeOverflow { field: "bands" })?,
            quantity: self.quantity as u8,
            formulation: self.formulation as u8,
            precision: precision as u8,
            patch_count: count("patch_count", c.patch_count)?,
            mode_count: count("mode_count", c.mode_count)?,
            surface_count: count("surface_count", c.surface_count)?,
            channel_count: count("channel_count", c.channel_count)?,
            sensor_count: count("sensor_count", c.sensor_count)?,
            zone_count: count("zone_count", c.zone_count)?,
            names: &self.names()?,
            eigenvalues: &f32_bytes(&self.eigenvalues),
            patch_area: &f32_bytes(&self.patch_area),
            patch_centroid: &f32_bytes(self.patch_centroid.as_flattened()),
            patch_surface: &u16_bytes(self.patch_surface.iter().copied()),
            patch_channel: &channel_bytes(&self.patch_channel),
            patch_reflectance: &f32_bytes(&self.patch_reflectance),
            patch_emission: &f32_bytes(&self.patch_emission),
            modes: matrix(&self.modes, c.modes_cols())?.bytes(),
            black_patches: &self.black_patches(),
            black_projection: &f32_bytes(&self.black_projection),
            channel_response: matrix(&self.channel_response, c.channel_response_cols())?.bytes(),
            sensor_geometry: &f32_bytes(self.sensor_geometry.as_flattened()),
            zone_area: &f32_bytes(&self.zone_area),
            output_modes: &f32_bytes(&self.output_modes),
            output_channels: &f32_bytes(&self.output_channels),
            output_view: matrix(&self.output_view, c.output_view_cols())?.bytes(),
            grid_pieces: &u32_bytes(&self.grid_pieces()),
            grid_lattice: &u32_bytes(self.grid_lattice.as_flattened()),
            grid_layout: &f32_bytes(self.grid_layout.as_flattened()),
            grid_position: &f32_bytes(self.grid_position.as_flattened()),
            grid_modes: &f32_bytes(&self.grid_modes),
            grid_channels: &f32_bytes(&self.grid_channels),
            grid_view: matrix(&self.grid_view, c.grid_view_cols())?.bytes(),
            sky_subdivision: self.sky_subdivision,
            daylight_site: &f32_bytes(&self.daylight_site),
            sun_lattice: &u32_bytes(&self.sun_lattice),
            sun_spacing: &f32_bytes(&self.sun_spacing),
            sun_nodes: &u32_bytes(&self.sun_nodes),
            daylight_outputs: &f32_bytes(&self.daylight_outputs),
            daylight_modes: &f32_bytes(&self.daylight_modes),
            daylight_grid: matrix(&self.daylight_grid, c.daylight_grid_cols())?.bytes(),
            sun_polygon_counts: &u32_bytes(&self.sun_polygon_counts),
            sun_polygon_sizes: &self.sun_polygon_sizes,
            sun_polygons: &f32_bytes(&self.sun_polygons),
            sun_glazing: &f32_bytes(&self.sun_glazing),
            sensor_response_rows: &u32_bytes(&self.sensor_response_rows),
            sensor_response: &f32_bytes(&self.sensor_response),
            reflection_rank: &u32_bytes(&self.reflection_rank),
            sky_reflection_weights: &f32_bytes(&self.sky_reflection_weights),
            sky_reflection: matrix(&self.sky_reflection, Some(c.reflection_rank.unwrap_or(0)))?
                .bytes(),
            sun_reflection_counts: &u32_bytes(&self.sun_reflection_counts),
            sun_reflection_patches: &u32_bytes(&self.sun_reflection_patches),
            sun_reflection: &f32_bytes(&self.sun_reflection),
            sun_first_patches: &u32_bytes(&self.sun_first_patches),
            sun_first_sizes: &self.sun_first_sizes,
            sun_first_points: &f32_bytes(&self.sun_first_points),
            sun_node_power: &f32_bytes(&self.sun_node_power),
            sun_first_response: &f32_bytes(&self.sun_first_response),
            zone_sun_counts: &u32_bytes(&self.zone_sun_counts),
            zone_sun_sizes: &self.zone_sun_sizes,
            zone_sun_polygons: &f32_bytes(&self.zone_sun_polygons),
        })
    }
}

/// `payload` encoded with its header, in a vector of exactly its length.
fn encode(payload: &Payload<'_>) -> Result<Vec<u8>> {
    let mut out = vec![0u8; format::encoded_len(payload)?];
    let used = format::encode(payload, &mut out)?.len();
    out.truncate(used);
    Ok(out)
}
