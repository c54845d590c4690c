//! The serialized basis, format version 5: the wire types a writer fills and the reader
//! decodes in place. `docs/format.md` is the normative description; this module is its
//! layout and header, the checks of the payload's sections are in `decode.rs`.
//!
//! A basis is a 20-byte header followed by a postcard-encoded [`Payload`]:
//!
//! | offset | size | field | meaning |
//! |---|---|---|---|
//! | 0 | 8 | magic | `EIGENRAD` |
//! | 8 | 2 | version | [`FORMAT_VERSION`], little-endian |
//! | 10 | 2 | reserved | 0 |
//! | 12 | 4 | payload length | bytes of payload, little-endian |
//! | 16 | 4 | checksum | CRC-32 (ISO-HDLC) of the payload, little-endian |
//!
//! Bulk tables inside the payload are borrowed byte slices of little-endian numbers, so that a
//! basis kept in flash is read where it lies: decoding copies nothing but a few slice headers.

use serde::{Deserialize, Serialize};

use crate::error::{Error, Result};

/// The eight bytes every basis starts with.
pub const MAGIC: [u8; 8] = *b"EIGENRAD";
/// The format version this runtime writes and reads.
pub const FORMAT_VERSION: u16 = 5;
/// Size of the fixed header in bytes.
pub const HEADER_LEN: usize = 20;
/// `patch_channel` value of a patch that belongs to no channel.
pub const NO_CHANNEL: u16 = u16::MAX;

/// How the interreflection operator is expanded in modes (see `docs/format.md` and
/// docs/math.md). Channels are stored exactly in either; the expansion serves exitance set
/// patch by patch at run time.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[repr(u8)]
pub enum Formulation {
    /// Default. `M = M0 + Σ c_k v_k (v_k · b∘M0)` with `c_k = μ_k/(1−μ_k)`: a patch's own
    /// exitance exact, the interreflection in modes; the stored eigenvalues are `μ_k`
    /// (eigenvalues of `R F`).
    #[default]
    Split = 0,
    /// The seed paper's expansion, corrected: `M = Σ (1/λ_k) v_k (v_k · b∘M0)` over the
    /// smallest eigenvalues `λ_k` of `S = A R⁻¹ (I − R F)`; kept for comparison.
    Seed = 1,
}

/// How the large tables (mode vectors, channel responses, view rows) are stored.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[repr(u8)]
pub enum Precision {
    /// IEEE binary32, 4 bytes a value.
    F32 = 0,
    /// IEEE binary16 times a per-column scale, 2 bytes a value.
    F16 = 1,
    /// Signed 16-bit integer times a per-column scale, 2 bytes a value.
    I16 = 2,
}

impl Formulation {
    /// The name used on the command line and in reports: `split` or `seed`.
    pub const fn name(self) -> &'static str {
        match self {
            Formulation::Split => "split",
            Formulation::Seed => "seed",
        }
    }
}

impl Precision {
    /// The name used on the command line and in reports: `f32`, `f16` or `i16`.
    pub const fn name(self) -> &'static str {
        match self {
            Precision::F32 => "f32",
            Precision::F16 => "f16",
            Precision::I16 => "i16",
        }
    }

    /// Bytes per stored value.
    pub const fn bytes(self) -> usize {
        match self {
            Precision::F32 => 4,
            Precision::F16 | Precision::I16 => 2,
        }
    }
}

/// What the numbers measure.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[repr(u8)]
pub enum Quantity {
    /// Radiometric: exitance and irradiance in W/m², luminance in W/(m²·sr).
    Radiometric = 0,
    /// Photometric, one photopic band: exitance (lm/m²) and illuminance in lux, luminance in
    /// cd/m².
    Photometric = 1,
}

/// A matrix stored row-major in the basis' [`Precision`], with one scale per column: the
/// value at `(row, col)` is `stored(row, col) × scale[col]` (`scale` is empty for `F32`).
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
    /// [`Quantity`] as its discriminant.
    pub quantity: u8,
    /// [`Formulation`] as its discriminant.
    pub formulation: u8,
    /// [`Precision`] as its discriminant.
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
    /// `G × D` matrix: each grid point's exact illuminance per unit of each daylight node.
    #[serde(borrow)]
    pub daylight_grid: MatrixBytes<'a>,
}

/// The dimensions every table's length follows from (`docs/format.md`, notation): the reader
/// takes them from the payload's settings and counts, the writer from its tables' lengths.
///
/// The rules for the matrices' columns live here, once, for both. They return `None` when a
/// product overflows `usize`, which only the untrusted counts of a corrupt basis can make
/// happen.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct Counts {
    /// `B`: the payload's `bands`.
    pub bands: usize,
    /// `n`: `patch_count`.
    pub patch_count: usize,
    /// `p`: `mode_count`.
    pub mode_count: usize,
    /// `surface_count`.
    pub surface_count: usize,
    /// `m`: `channel_count`.
    pub channel_count: usize,
    /// `S`: `sensor_count`.
    pub sensor_count: usize,
    /// `Z`: `zone_count`.
    pub zone_count: usize,
    /// `Q`: grid pieces, the sum of `grid_pieces`.
    pub grid_piece_count: usize,
    /// `G`: grid points, the sum of the pieces' kept points.
    pub grid_point_count: usize,
    /// `D`: daylight nodes (sky patches, the exterior, the sun nodes); 0 without daylight.
    pub daylight_node_count: usize,
}

impl Counts {
    /// `O = S + Z`: outputs, sensors first.
    pub fn output_count(&self) -> Option<usize> {
        self.sensor_count.checked_add(self.zone_count)
    }

    /// Columns of `modes`: `B·p`.
    pub fn modes_cols(&self) -> Option<usize> {
        self.bands.checked_mul(self.mode_count)
    }

    /// Columns of `channel_response`: `m·B`.
    pub fn channel_response_cols(&self) -> Option<usize> {
        self.channel_count.checked_mul(self.bands)
    }

    /// Columns of `output_view`: `O`.
    pub fn output_view_cols(&self) -> Option<usize> {
        self.output_count()
    }

    /// Columns of `grid_view`: `n`.
    pub fn grid_view_cols(&self) -> Option<usize> {
        Some(self.patch_count)
    }

    /// Columns of `daylight_grid`: `D`.
    pub fn daylight_grid_cols(&self) -> Option<usize> {
        Some(self.daylight_node_count)
    }
}

/// `D`, the daylight nodes of a basis whose sky is `sky_subdivision` and whose sun has
/// `sun_nodes` nodes: the sky's patches, the exterior and the sun nodes (0 without
/// daylight, `None` for a subdivision the sky patches do not have or an overflow).
pub(crate) fn daylight_nodes(sky_subdivision: u8, sun_nodes: usize) -> Option<usize> {
    if sky_subdivision == 0 {
        return Some(0);
    }
    let sky = crate::sky::patches::SkyPatches::reinhart(sky_subdivision).ok()?;
    sky.count().checked_add(1)?.checked_add(sun_nodes)
}

/// CRC-32/ISO-HDLC (the zlib/PNG CRC): reflected polynomial `0xEDB88320`, initial value and
/// final XOR `0xFFFF_FFFF`. A nibble table keeps it small for flash and fast enough to check
/// a basis at boot.
pub fn crc32(bytes: &[u8]) -> u32 {
    // Evaluated at compile time: an index out of bounds here fails the build, not the device.
    #[allow(clippy::indexing_slicing)]
    const fn table() -> [u32; 16] {
        let mut t = [0u32; 16];
        let mut i = 0;
        while i < 16 {
            let mut c = i as u32;
            let mut k = 0;
            while k < 4 {
                c = if c & 1 != 0 {
                    (c >> 1) ^ 0xEDB8_8320
                } else {
                    c >> 1
                };
                k += 1;
            }
            t[i] = c;
            i += 1;
        }
        t
    }
    const TABLE: [u32; 16] = table();
    let mut crc = !0u32;
    for &byte in bytes {
        crc ^= u32::from(byte);
        for _ in 0..2 {
            // `crc & 0xF` is below 16, so the lookup cannot fail; `unwrap_or` keeps it total.
            let t = TABLE.get((crc & 0xF) as usize).copied().unwrap_or(0);
            crc = (crc >> 4) ^ t;
        }
    }
    !crc
}

/// Bytes the encoding of `payload` takes, header included.
pub fn encoded_len(payload: &Payload<'_>) -> Result<usize> {
    let body = postcard::serialize_with_flavor(payload, postcard::ser_flavors::Size::default())
        .map_err(|_| Error::EncodePayload)?;
    Ok(HEADER_LEN + body)
}

/// Encodes `payload` with its header into `out`, returning the bytes written.
///
/// `out` must hold [`encoded_len`] bytes ([`Error::EncodeBuffer`] otherwise). Host tools
/// allocate that; the runtime itself never encodes.
pub fn encode<'o>(payload: &Payload<'_>, out: &'o mut [u8]) -> Result<&'o mut [u8]> {
    let total = encoded_len(payload)?;
    let too_small = Error::EncodeBuffer {
        needed: total,
        found: out.len(),
    };
    let out = out.get_mut(..total).ok_or(too_small)?;
    let (header, body) = out.split_at_mut_checked(HEADER_LEN).ok_or(too_small)?;
    let len = postcard::to_slice(payload, body)
        .map_err(|_| Error::EncodePayload)?
        .len();
    let crc = crc32(body.get(..len).unwrap_or(&[]));
    let len32 = u32::try_from(len).map_err(|_| Error::EncodeOverflow {
        field: "payload length",
    })?;
    let fields: [&[u8]; 5] = [
        &MAGIC,
        &FORMAT_VERSION.to_le_bytes(),
        &0u16.to_le_bytes(),
        &len32.to_le_bytes(),
        &crc.to_le_bytes(),
    ];
    for (slot, &b) in header.iter_mut().zip(fields.into_iter().flatten()) {
        *slot = b;
    }
    Ok(out)
}

/// Checks the header and checksum of `bytes` and decodes the payload, borrowing from `bytes`.
///
/// Trailing bytes after the payload (e.g. erased flash padding) are ignored. This checks the
/// header section only; [`Basis::from_bytes`](crate::Basis::from_bytes) checks the rest.
pub fn decode(bytes: &[u8]) -> Result<Payload<'_>> {
    decode_payload(check_header(bytes)?)
}

/// The header section of `docs/format.md`: checks magic, version, reserved, that the
/// payload is present, and the checksum, in that order, and returns the payload's bytes.
pub(crate) fn check_header(bytes: &[u8]) -> Result<&[u8]> {
    let header = bytes.get(..HEADER_LEN).ok_or(Error::DecodeTruncated {
        needed: HEADER_LEN,
        found: bytes.len(),
    })?;
    if header.get(..8) != Some(&MAGIC[..]) {
        return Err(Error::DecodeBadMagic);
    }
    let version = u16::from_le_bytes([byte(header, 8), byte(header, 9)]);
    if version != FORMAT_VERSION {
        return Err(Error::DecodeVersion {
            found: version,
            supported: FORMAT_VERSION,
        });
    }
    let reserved = u16::from_le_bytes([byte(header, 10), byte(header, 11)]);
    if reserved != 0 {
        return Err(Error::DecodeField {
            field: "reserved",
            value: u32::from(reserved),
        });
    }
    let len = u32::from_le_bytes([
        byte(header, 12),
        byte(header, 13),
        byte(header, 14),
        byte(header, 15),
    ]);
    let expected = u32::from_le_bytes([
        byte(header, 16),
        byte(header, 17),
        byte(header, 18),
        byte(header, 19),
    ]);
    let needed = HEADER_LEN.saturating_add(len as usize);
    let body = bytes
        .get(HEADER_LEN..needed)
        .ok_or(Error::DecodeTruncated {
            needed,
            found: bytes.len(),
        })?;
    let found = crc32(body);
    if found != expected {
        return Err(Error::DecodeChecksum { expected, found });
    }
    Ok(body)
}

/// Decodes the postcard payload that fills `body` exactly, borrowing its tables.
///
/// The payload is postcard's encoding of [`Payload`]: its fields in order, each `u8` as a
/// byte, each `u32` as a varint, each table as a varint length and its bytes. They are read
/// here in three loops (settings, counts, tables) rather than through `Payload`'s derived
/// `Deserialize`, whose code per field is several times larger in flash; the bytes read are
/// the same (`decode_payload_reads_what_postcard_derives` in the tests).
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
    let mut tables: [&[u8]; 28] = [&[]; 28];
    for slot in &mut tables {
        *slot = take(&mut rest)?;
    }
    let sky_subdivision: u8 = take(&mut rest)?;
    let mut daylight: [&[u8]; 8] = [&[]; 8];
    for slot in &mut daylight {
        *slot = take(&mut rest)?;
    }
    if !rest.is_empty() {
        return Err(Error::DecodeLength {
            field: "payload length",
            expected: body.len() - rest.len(),
            found: body.len(),
        });
    }
    let [bands, quantity, formulation, precision] = settings;
    let [patch_count, mode_count, surface_count, channel_count, sensor_count, zone_count] = counts;
    let matrix = |scales, data| MatrixBytes { scales, data };
    let [names, eigenvalues, patch_area, patch_centroid, patch_surface, patch_channel, patch_reflectance, patch_emission, modes_scales, modes_data, black_patches, black_projection, response_scales, response_data, sensor_geometry, zone_area, output_modes, output_channels, view_scales, view_data, grid_pieces, grid_lattice, grid_layout, grid_position, grid_modes, grid_channels, grid_view_scales, grid_view_data] =
        tables;
    let [daylight_site, sun_lattice, sun_spacing, sun_nodes, daylight_outputs, daylight_modes, daylight_grid_scales, daylight_grid_data] =
        daylight;
    Ok(Payload {
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
        names,
        eigenvalues,
        patch_area,
        patch_centroid,
        patch_surface,
        patch_channel,
        patch_reflectance,
        patch_emission,
        modes: matrix(modes_scales, modes_data),
        black_patches,
        black_projection,
        channel_response: matrix(response_scales, response_data),
        sensor_geometry,
        zone_area,
        output_modes,
        output_channels,
        output_view: matrix(view_scales, view_data),
        grid_pieces,
        grid_lattice,
        grid_layout,
        grid_position,
        grid_modes,
        grid_channels,
        grid_view: matrix(grid_view_scales, grid_view_data),
        sky_subdivision,
        daylight_site,
        sun_lattice,
        sun_spacing,
        sun_nodes,
        daylight_outputs,
        daylight_modes,
        daylight_grid: matrix(daylight_grid_scales, daylight_grid_data),
    })
}

fn byte(bytes: &[u8], at: usize) -> u8 {
    bytes.get(at).copied().unwrap_or(0)
}

/// Converts an IEEE binary16 bit pattern to `f32` (exact: every f16 is an f32). Infinities
/// and NaNs map to their `f32` counterparts.
pub fn f16_to_f32(bits: u16) -> f32 {
    if bits & 0x7C00 == 0x7C00 {
        let sign = u32::from(bits & 0x8000) << 16;
        let man = u32::from(bits & 0x3FF) << 13;
        let quiet = if man != 0 { 0x0040_0000 } else { 0 };
        return f32::from_bits(sign | 0x7F80_0000 | quiet | man);
    }
    f16_finite_to_f32(bits)
}

/// `2^112`: the difference between the exponent biases of `f32` (127) and binary16 (15).
const F16_TO_F32_SCALE: f32 = f32::from_bits((127 + 112) << 23);

/// Converts the bit pattern of a finite binary16 to `f32`, exactly, without a branch: the
/// sign, exponent and mantissa fields shifted into place form an `f32` of the value times
/// 2⁻¹¹² (a subnormal half becomes a subnormal single), and one multiplication by 2¹¹²
/// restores it. The decoder rejects infinities and NaNs in stored tables, so the evaluator
/// reads through this. (An FPU in flush-to-zero mode would read the few subnormal halves,
/// magnitudes below 2⁻¹⁴ of their column's scale, as 0.)
#[inline]
pub(crate) fn f16_finite_to_f32(bits: u16) -> f32 {
    let sign = u32::from(bits & 0x8000) << 16;
    let magnitude = u32::from(bits & 0x7FFF) << 13;
    f32::from_bits(sign | magnitude) * F16_TO_F32_SCALE
}

/// Converts `f32` to the nearest IEEE binary16 bit pattern (round to nearest even).
/// Writers use it; values beyond the f16 range become infinity, which the reader rejects.
pub fn f32_to_f16(value: f32) -> u16 {
    let x = value.to_bits();
    let sign = ((x >> 16) & 0x8000) as u16;
    let exp = ((x >> 23) & 0xFF) as i32;
    let man = x & 0x007F_FFFF;
    if exp == 0xFF {
        return sign | 0x7C00 | if man != 0 { 0x200 } else { 0 };
    }
    let e = exp - 127 + 15;
    if e >= 0x1F {
        return sign | 0x7C00;
    }
    if e <= 0 {
        if e < -10 {
            return sign;
        }
        let m = man | 0x0080_0000;
        let shift = (14 - e) as u32;
        let half = 1u32 << (shift - 1);
        let rest = m & ((1u32 << shift) - 1);
        let mut h = (m >> shift) as u16;
        if rest > half || (rest == half && (h & 1) == 1) {
            h += 1;
        }
        return sign | h;
    }
    let mut h = ((e as u32) << 10) as u16 | (man >> 13) as u16;
    let rest = man & 0x1FFF;
    if rest > 0x1000 || (rest == 0x1000 && (h & 1) == 1) {
        h += 1; // may carry into the exponent, which is the correct rounding
    }
    sign | h
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
        let store: alloc::vec::Vec<alloc::vec::Vec<u8>> = (0..36u8)
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
        };
        let mut buffer = [0u8; 1024];
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
