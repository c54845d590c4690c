//! The payload's wire type, [`Payload`], with [`MatrixBytes`], and its reader: postcard's
//! encoding of the struct, read field by field in the struct's order.

use serde::{Deserialize, Serialize};

use crate::error::{Error, Result};

/// `patch_channel` value of a patch that belongs to no channel.
pub const NO_CHANNEL: u16 = u16::MAX;

/// A matrix stored row-major in the basis' [`Precision`], with one scale per column: the
/// value at `(row, col)` is `stored(row, col) × scale[col]` (`scale` is empty for `F32`).
///
/// [`Precision`]: super::Precision
#[derive(Serialize, Deserialize, Clone, Copy, Debug, Default, PartialEq)]
pub struct MatrixBytes<'a> {
    /// One little-endian `f32` per column (empty for `F32` storage).
    #[serde(borrow)]
    pub scales: &'a [u8],
    /// `rows × cols` values, row-major.
    #[serde(borrow)]
    pub data: &'a [u8],
}

/// The payload: settings, counts, names, then tables of little-endian numbers, in the order
/// and with the names of `docs/format.md`'s payload table.
///
/// `n` patches, `p` modes, `B` bands (1 or 3), `m` channels, `S` sensors, `Z` zones,
/// `O = S + Z` outputs (sensors first, then zones), and `G` grid points (every zone's, zone
/// by zone, piece by piece: the sum of `grid_lattice`'s kept points). Lengths are in values; see
/// `docs/format.md` for the byte layout and the meaning of every table. A decoded payload is
/// only parsed; [`Basis::from_bytes`](crate::Basis::from_bytes) is what checks its tables.
#[derive(Serialize, Deserialize, Clone, Copy, Debug, Default, PartialEq)]
pub struct Payload<'a> {
    /// `B`: 1 (photopic) or 3 (RGB).
    pub bands: u8,
    /// [`Quantity`](super::Quantity) as its discriminant.
    pub quantity: u8,
    /// [`Formulation`](super::Formulation) as its discriminant.
    pub formulation: u8,
    /// [`Precision`](super::Precision) as its discriminant.
    pub precision: u8,
    /// `n`.
    pub patch_count: u32,
    /// `p`.
    pub mode_count: u32,
    /// Number of named surfaces.
    pub surface_count: u32,
    /// `m`.
    pub channel_count: u32,
    /// `S`.
    pub sensor_count: u32,
    /// `Z`.
    pub zone_count: u32,
    /// Postcard strings, one after the other: surfaces, channels, sensors, zones.
    #[serde(borrow)]
    pub names: &'a [u8],
    /// `B × p` `f32`: per band, `μ_k` (split) or `λ_k` (seed).
    #[serde(borrow)]
    pub eigenvalues: &'a [u8],
    /// `n` `f32`: patch area, m².
    #[serde(borrow)]
    pub patch_area: &'a [u8],
    /// `n × 3` `f32`: patch centroid, m.
    #[serde(borrow)]
    pub patch_centroid: &'a [u8],
    /// `n` `u16`: index of the surface the patch belongs to.
    #[serde(borrow)]
    pub patch_surface: &'a [u8],
    /// `n` `u16`: channel driving the patch's emission, or [`NO_CHANNEL`].
    #[serde(borrow)]
    pub patch_channel: &'a [u8],
    /// `n × B` `f32`: reflectance ρ, 0 or in `[1e-6, 1)`.
    #[serde(borrow)]
    pub patch_reflectance: &'a [u8],
    /// `n × B` `f32`: exitance emitted at channel level 1 (W/m² or lux).
    #[serde(borrow)]
    pub patch_emission: &'a [u8],
    /// `n × (B·p)` matrix: mode vectors, patch-major; column `b·p + k` is mode `k` of band `b`.
    #[serde(borrow)]
    pub modes: MatrixBytes<'a>,
    /// Ascending `u32` patch indices whose reflectance is 0 in at least one band.
    #[serde(borrow)]
    pub black_patches: &'a [u8],
    /// `black × B × p` `f32`: mode-space response to unit exitance of each black patch, with
    /// the mode coefficient included (split `v_k·G e_j/(1−μ_k)`, seed `v_k·G e_j/λ_k`).
    #[serde(borrow)]
    pub black_projection: &'a [u8],
    /// `n × (m·B)` matrix: each channel's exact exitance on every patch at level 1,
    /// emission included (W/m² or lux), from the exact solve at build time. Column `c·B + b`.
    #[serde(borrow)]
    pub channel_response: MatrixBytes<'a>,
    /// `S × 7` `f32`: sensor position (m), unit normal, field-of-view half-angle (rad, π for
    /// a full hemisphere).
    #[serde(borrow)]
    pub sensor_geometry: &'a [u8],
    /// `Z` `f32`: zone area, m².
    #[serde(borrow)]
    pub zone_area: &'a [u8],
    /// `O × B × p` `f32`: each output's irradiance per unit mode amplitude.
    #[serde(borrow)]
    pub output_modes: &'a [u8],
    /// `O × B × m` `f32`: each output's exact irradiance from each channel alone at level 1
    /// (W/m² or lux).
    #[serde(borrow)]
    pub output_channels: &'a [u8],
    /// `n × O` matrix: view factor from each output to each patch (a zone's is
    /// area-averaged), for direct light from exitance set patch by patch.
    #[serde(borrow)]
    pub output_view: MatrixBytes<'a>,
    /// `Z` `u32`: the pieces of each zone's calculation grid (0: the zone has none). `Q` is
    /// their sum.
    #[serde(borrow)]
    pub grid_pieces: &'a [u8],
    /// `Q × 3` `u32`: each piece's lattice, cells along its first and second side, and the
    /// points it keeps (the cell centres on the piece's area, at most the product).
    #[serde(borrow)]
    pub grid_lattice: &'a [u8],
    /// `Q × 7` `f32`: each piece's layout: largest spacing `p` (m), cell sides (m), band
    /// left out at the walls (m), the unit normal its points face.
    #[serde(borrow)]
    pub grid_layout: &'a [u8],
    /// `G × 3` `f32`: grid point positions, m.
    #[serde(borrow)]
    pub grid_position: &'a [u8],
    /// `G × B × p` `f32`: each grid point's irradiance per unit mode amplitude.
    #[serde(borrow)]
    pub grid_modes: &'a [u8],
    /// `G × B × m` `f32`: each grid point's exact irradiance from each channel alone at
    /// level 1 (W/m² or lux).
    #[serde(borrow)]
    pub grid_channels: &'a [u8],
    /// `G × n` matrix: view factor from each grid point to each patch, for direct light from
    /// exitance set patch by patch.
    #[serde(borrow)]
    pub grid_view: MatrixBytes<'a>,
    /// The daylight's sky: 0 when the basis carries no daylight, 1 for Tregenza's 145
    /// patches, `n` for Reinhart's subdivision MF:n ([`crate::sky::patches::SkyPatches`]).
    /// With daylight, `D` = the sky's patches + 1 (the exterior) + the sun nodes is the
    /// number of daylight nodes; without, every daylight table is empty.
    pub sky_subdivision: u8,
    /// Empty, or 5 `f32`: latitude (° north), longitude (° east), elevation (m), the compass
    /// bearing of the scene's +y axis (°, clockwise from true north) and the site's UTC
    /// offset (minutes).
    #[serde(borrow)]
    pub daylight_site: &'a [u8],
    /// Empty, or 2 `u32`: the sun grid's declinations and hour angles (rows and columns).
    #[serde(borrow)]
    pub sun_lattice: &'a [u8],
    /// Empty, or 4 `f32`, degrees: the first declination, the step between declinations,
    /// the first hour angle, the step between hour angles.
    #[serde(borrow)]
    pub sun_spacing: &'a [u8],
    /// Ascending `u32` indices `row · columns + column` of the sun grid's nodes that light
    /// the room; the others light nothing.
    #[serde(borrow)]
    pub sun_nodes: &'a [u8],
    /// `O × D` `f32`: each output's exact illuminance (lux) per unit of each daylight node:
    /// per cd/m² of a sky patch, per cd/m² of `E_gh/π` of the exterior, per lux of direct
    /// normal illuminance of the sun at a node.
    #[serde(borrow)]
    pub daylight_outputs: &'a [u8],
    /// `p × D` `f32`: the mode amplitudes of each daylight node's exact exitance.
    #[serde(borrow)]
    pub daylight_modes: &'a [u8],
    /// `G × D` matrix: each grid point's exact illuminance per unit of each daylight node;
    /// with the direct sun's geometry, a sun node's column holds only what the device does
    /// not compute itself (docs/format.md, "Direct sun").
    #[serde(borrow)]
    pub daylight_grid: MatrixBytes<'a>,
    /// Empty (the device computes no direct sun), or 3 `u32`: the polygons of the direct
    /// sun's geometry, `W` window faces, `K_r` room occluders, `K_e` exterior occluders.
    #[serde(borrow)]
    pub sun_polygon_counts: &'a [u8],
    /// `W + K_r + K_e` bytes: each polygon's vertex count (3 to
    /// [`crate::sky::direct::MAX_POLYGON_VERTICES`]), windows first.
    #[serde(borrow)]
    pub sun_polygon_sizes: &'a [u8],
    /// `f32`, per polygon in order: its unit normal (a window's into the room), then its
    /// vertices (m), 3 each.
    #[serde(borrow)]
    pub sun_polygons: &'a [u8],
    /// `W × 65` `f32`: each window face's glazing transmittance at incidence cosines
    /// `k / 64`, `k = 0 … 64`, in `[0, 1]`.
    #[serde(borrow)]
    pub sun_glazing: &'a [u8],
    /// `S` `u32` (with the direct sun's geometry): rows of each sensor's angular response,
    /// 0 for a cone or hemisphere read by its half-angle.
    #[serde(borrow)]
    pub sensor_response_rows: &'a [u8],
    /// `f32` pairs, sensor by sensor: polar angle (rad, ascending within `[0, π]`) and
    /// relative sensitivity (`≥ 0`).
    #[serde(borrow)]
    pub sensor_response: &'a [u8],
    /// Empty (patch exitance under daylight through the modes alone), or 1 `u32`: `r`, the
    /// rank of the sky's stored first reflection (docs/format.md, "First reflection").
    #[serde(borrow)]
    pub reflection_rank: &'a [u8],
    /// `r × (S_k + 1)` `f32`: the sky's and the exterior's weight in each of the `r`
    /// coefficients of the first reflection (the right singular vectors).
    #[serde(borrow)]
    pub sky_reflection_weights: &'a [u8],
    /// `n × r` matrix: each patch's first reflection per unit of each coefficient (lux).
    #[serde(borrow)]
    pub sky_reflection: MatrixBytes<'a>,
    /// One `u32` per stored sun node: the patches its first reflection lists.
    #[serde(borrow)]
    pub sun_reflection_counts: &'a [u8],
    /// `u32` patch indices, sun node by sun node, ascending within a node.
    #[serde(borrow)]
    pub sun_reflection_patches: &'a [u8],
    /// `f32`, one per listed patch: its first reflection, lux per lux of direct normal
    /// illuminance.
    #[serde(borrow)]
    pub sun_reflection: &'a [u8],
    /// Empty (each sun node's whole reflected sun interpolated), or `C` `u32`: the patches
    /// the sun can light directly, ascending (docs/format.md, "The sun's first reflection").
    #[serde(borrow)]
    pub sun_first_patches: &'a [u8],
    /// `C` `u8`: each such patch's corners, 3 to 16.
    #[serde(borrow)]
    pub sun_first_sizes: &'a [u8],
    /// `f32`, patch by patch: its unit normal, then its corners in order (m), a convex
    /// polygon.
    #[serde(borrow)]
    pub sun_first_points: &'a [u8],
    /// One `f32` per stored sun node: the power of its first reflection as the controller
    /// computes it, `P = Σ_j A_j ρ_j E_j` (lm per lux of direct normal illuminance).
    #[serde(borrow)]
    pub sun_node_power: &'a [u8],
    /// Empty (what the room reflects after the first reflection is interpolated per unit of
    /// its power), or `C × (S + Z + G)` `f32`, candidate by candidate: each reading's response
    /// to a unit of that candidate's first reflection (lux per lux), the direct sun on a
    /// surface zone's own candidates included.
    #[serde(borrow)]
    pub sun_first_response: &'a [u8],
    /// Empty, or with the candidates one `u32` per zone: the polygons its direct sun is
    /// computed on at the sun (a work plane's receivers; 0 for a zone whose direct sun is
    /// in its candidates' responses or interpolated).
    #[serde(borrow)]
    pub zone_sun_counts: &'a [u8],
    /// One `u8` per such polygon: its corners, 3 to 16.
    #[serde(borrow)]
    pub zone_sun_sizes: &'a [u8],
    /// `f32`, polygon by polygon: its unit normal, then its corners in order (m), convex.
    #[serde(borrow)]
    pub zone_sun_polygons: &'a [u8],
}

/// Decodes the postcard payload that fills `body` exactly, borrowing its tables.
///
/// The payload is postcard's encoding of [`Payload`]: its fields in order, each `u8` as a
/// byte, each `u32` as a varint, each table as a varint length and its bytes. They are read
/// here in three loops (settings, counts, tables) rather than through `Payload`'s derived
/// `Deserialize`, whose code per field is several times larger in flash; the bytes read are
/// the same (`decode_payload_reads_what_postcard_derives` in the tests). The tables' loops
/// write through references to their fields of the payload returned, so that no table is
/// moved after it is read: gathering the tables in arrays and then moving them into the
/// fields took about 800 bytes of loads and stores. Not inlined, so that the payload is built once,
/// in place, and moved whole.
#[inline(never)]
pub(crate) fn decode_payload(body: &[u8]) -> Result<Payload<'_>> {
    fn take<'a, T: Deserialize<'a>>(rest: &mut &'a [u8]) -> Result<T> {
        let (value, tail) =
            postcard::take_from_bytes::<T>(rest).map_err(|_| Error::DecodePayload)?;
        *rest = tail;
        Ok(value)
    }
    let mut rest = body;
    let mut settings = [0u8; 4];
    for slot in &mut settings {
        *slot = take(&mut rest)?;
    }
    let mut counts = [0u32; 6];
    for slot in &mut counts {
        *slot = take(&mut rest)?;
    }
    let [bands, quantity, formulation, precision] = settings;
    let [patch_count, mode_count, surface_count, channel_count, sensor_count, zone_count] = counts;
    // The settings and counts first and the tables' defaults then: no default is written
    // twice.
    let mut p = Payload {
        bands,
        quantity,
        formulation,
        precision,
        patch_count,
        mode_count,
        surface_count,
        channel_count,
        sensor_count,
        zone_count,
        ..Payload::default()
    };
    for slot in [
        &mut p.names,
        &mut p.eigenvalues,
        &mut p.patch_area,
        &mut p.patch_centroid,
        &mut p.patch_surface,
        &mut p.patch_channel,
        &mut p.patch_reflectance,
        &mut p.patch_emission,
        &mut p.modes.scales,
        &mut p.modes.data,
        &mut p.black_patches,
        &mut p.black_projection,
        &mut p.channel_response.scales,
        &mut p.channel_response.data,
        &mut p.sensor_geometry,
        &mut p.zone_area,
        &mut p.output_modes,
        &mut p.output_channels,
        &mut p.output_view.scales,
        &mut p.output_view.data,
        &mut p.grid_pieces,
        &mut p.grid_lattice,
        &mut p.grid_layout,
        &mut p.grid_position,
        &mut p.grid_modes,
        &mut p.grid_channels,
        &mut p.grid_view.scales,
        &mut p.grid_view.data,
    ] {
        *slot = take(&mut rest)?;
    }
    p.sky_subdivision = take(&mut rest)?;
    for slot in [
        &mut p.daylight_site,
        &mut p.sun_lattice,
        &mut p.sun_spacing,
        &mut p.sun_nodes,
        &mut p.daylight_outputs,
        &mut p.daylight_modes,
        &mut p.daylight_grid.scales,
        &mut p.daylight_grid.data,
        &mut p.sun_polygon_counts,
        &mut p.sun_polygon_sizes,
        &mut p.sun_polygons,
        &mut p.sun_glazing,
        &mut p.sensor_response_rows,
        &mut p.sensor_response,
        &mut p.reflection_rank,
        &mut p.sky_reflection_weights,
        &mut p.sky_reflection.scales,
        &mut p.sky_reflection.data,
        &mut p.sun_reflection_counts,
        &mut p.sun_reflection_patches,
        &mut p.sun_reflection,
        &mut p.sun_first_patches,
        &mut p.sun_first_sizes,
        &mut p.sun_first_points,
        &mut p.sun_node_power,
        &mut p.sun_first_response,
        &mut p.zone_sun_counts,
        &mut p.zone_sun_sizes,
        &mut p.zone_sun_polygons,
    ] {
        *slot = take(&mut rest)?;
    }
    if !rest.is_empty() {
        return Err(Error::DecodeLength {
            field: "payload length",
            expected: body.len() - rest.len(),
            found: body.len(),
        });
    }
    Ok(p)
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, clippy::indexing_slicing)]
    use super::*;

    /// Every field set to a value of its own (tables of distinct lengths and contents, counts
    /// that need multi-byte varints), encoded by postcard from the struct, reads back equal
    /// through `decode_payload`, and equal to what `Payload`'s derived `Deserialize` reads:
    /// the three loops take the fields in the struct's order.
    #[test]
    fn decode_payload_reads_what_postcard_derives() {
        let store: alloc::vec::Vec<alloc::vec::Vec<u8>> = (0..57u8)
            .map(|k| {
                (0..=k)
                    .map(|i| k.wrapping_mul(31).wrapping_add(i))
                    .collect()
            })
            .collect();
        let t = |k: usize| store[k].as_slice();
        let m = |k: usize| MatrixBytes {
            scales: t(k),
            data: t(k + 1),
        };
        let payload = Payload {
            bands: 3,
            quantity: 1,
            formulation: 2,
            precision: 7,
            patch_count: 1,
            mode_count: 300,
            surface_count: 70_000,
            channel_count: 5,
            sensor_count: u32::MAX,
            zone_count: 129,
            names: t(0),
            eigenvalues: t(1),
            patch_area: t(2),
            patch_centroid: t(3),
            patch_surface: t(4),
            patch_channel: t(5),
            patch_reflectance: t(6),
            patch_emission: t(7),
            modes: m(8),
            black_patches: t(10),
            black_projection: t(11),
            channel_response: m(12),
            sensor_geometry: t(14),
            zone_area: t(15),
            output_modes: t(16),
            output_channels: t(17),
            output_view: m(18),
            grid_pieces: t(20),
            grid_lattice: t(21),
            grid_layout: t(22),
            grid_position: t(23),
            grid_modes: t(24),
            grid_channels: t(25),
            grid_view: m(26),
            sky_subdivision: 9,
            daylight_site: t(28),
            sun_lattice: t(29),
            sun_spacing: t(30),
            sun_nodes: t(31),
            daylight_outputs: t(32),
            daylight_modes: t(33),
            daylight_grid: m(34),
            sun_polygon_counts: t(36),
            sun_polygon_sizes: t(37),
            sun_polygons: t(38),
            sun_glazing: t(39),
            sensor_response_rows: t(40),
            sensor_response: t(41),
            reflection_rank: t(42),
            sky_reflection_weights: t(43),
            sky_reflection: m(44),
            sun_reflection_counts: t(46),
            sun_reflection_patches: t(47),
            sun_reflection: t(48),
            sun_first_patches: t(49),
            sun_first_sizes: t(50),
            sun_first_points: t(51),
            sun_node_power: t(52),
            sun_first_response: t(53),
            zone_sun_counts: t(54),
            zone_sun_sizes: t(55),
            zone_sun_polygons: t(56),
        };
        let mut buffer = [0u8; 2048];
        let body = postcard::to_slice(&payload, &mut buffer).unwrap();
        assert_eq!(decode_payload(body).unwrap(), payload);
        assert_eq!(postcard::from_bytes::<Payload<'_>>(body).unwrap(), payload);
        // One byte short or one byte over is an error, as before.
        let len = body.len();
        assert_eq!(
            decode_payload(&body[..len - 1]).unwrap_err(),
            Error::DecodePayload
        );
        let mut longer = buffer;
        longer[len] = 0;
        assert!(matches!(
            decode_payload(&longer[..len + 1]),
            Err(Error::DecodeLength { .. })
        ));
    }
}
