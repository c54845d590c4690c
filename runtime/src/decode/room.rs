//! The sections every basis has, in payload order: names, eigenvalues, patch tables, modes,
//! black patches, channel tables, outputs, grids.

use super::tables::{bad_value, cols, f32_table, matrix, mul, u16_table, Allowed};
use crate::error::{Error, Result};
use crate::format::{Counts, Formulation, Payload, Precision, NO_CHANNEL};
use crate::storage::{f32_at, f32s, u16_at, u32_at};

/// Names: the surfaces', channels', sensors' and zones' as consecutive postcard strings,
/// nothing after them. Each is stepped over as bytes (a varint length and that many bytes);
/// whether a name is UTF-8 is checked when it is read (`Basis::channel_name` and the
/// others), so that decoding links no UTF-8 validation.
pub(super) fn names(raw: &Payload<'_>, c: &Counts) -> Result<()> {
    let count = c
        .surface_count
        .checked_add(c.channel_count)
        .and_then(|x| x.checked_add(c.output_count()?))
        .ok_or(Error::DecodeField {
            field: "names",
            value: u32::MAX,
        })?;
    let mut rest = raw.names;
    for _ in 0..count {
        let (_, tail) =
            postcard::take_from_bytes::<&[u8]>(rest).map_err(|_| Error::DecodePayload)?;
        rest = tail;
    }
    if !rest.is_empty() {
        return Err(Error::DecodeLength {
            field: "names",
            expected: raw.names.len() - rest.len(),
            found: raw.names.len(),
        });
    }
    Ok(())
}

/// Eigenvalues: `μ` within `±MAX_MU` (split) or `λ` positive (seed).
pub(super) fn eigenvalues(raw: &Payload<'_>, c: &Counts, formulation: Formulation) -> Result<()> {
    let count = cols(c.modes_cols())?;
    match formulation {
        Formulation::Split => f32_table("eigenvalues", raw.eigenvalues, count, Allowed::Mu),
        Formulation::Seed => f32_table("eigenvalues", raw.eigenvalues, count, Allowed::Lambda),
    }
}

/// Patch tables: `patch_area` to `patch_emission`.
pub(super) fn patch_tables(raw: &Payload<'_>, c: &Counts) -> Result<()> {
    let n = c.patch_count;
    let nb = mul(n, c.bands)?;
    f32_table("patch_area", raw.patch_area, n, Allowed::Positive)?;
    f32_table(
        "patch_centroid",
        raw.patch_centroid,
        mul(n, 3)?,
        Allowed::Bounded,
    )?;
    u16_table(
        "patch_surface",
        raw.patch_surface,
        n,
        c.surface_count,
        false,
    )?;
    u16_table("patch_channel", raw.patch_channel, n, c.channel_count, true)?;
    f32_table(
        "patch_reflectance",
        raw.patch_reflectance,
        nb,
        Allowed::Reflectance,
    )?;
    f32_table(
        "patch_emission",
        raw.patch_emission,
        nb,
        Allowed::NonNegative,
    )?;
    // Emission belongs to a channel: a patch outside every channel emits nothing.
    if let Some(index) = (0..nb).position(|k| {
        f32_at(raw.patch_emission, k) != 0.0 && u16_at(raw.patch_channel, k / c.bands) == NO_CHANNEL
    }) {
        return Err(bad_value("patch_emission", index));
    }
    Ok(())
}

/// Modes: the `n × (B·p)` matrix of mode vectors.
pub(super) fn modes(raw: &Payload<'_>, c: &Counts, precision: Precision) -> Result<()> {
    let cols = cols(c.modes_cols())?;
    matrix(
        "modes.data",
        "modes.scales",
        raw.modes,
        precision,
        c.patch_count,
        cols,
    )
}

/// Black patches: `black_patches` lists, ascending, exactly the patches with a zero
/// reflectance in some band, and `black_projection` has a row per band for each.
pub(super) fn black_patches(raw: &Payload<'_>, c: &Counts) -> Result<()> {
    if !raw.black_patches.len().is_multiple_of(4) {
        return Err(Error::DecodeLength {
            field: "black_patches",
            expected: raw.black_patches.len() / 4 * 4,
            found: raw.black_patches.len(),
        });
    }
    let black = raw.black_patches.len() / 4;
    let mut next = 0usize;
    for i in 0..c.patch_count {
        let is_black = (0..c.bands).any(|b| f32_at(raw.patch_reflectance, i * c.bands + b) == 0.0);
        let listed = next < black && u32_at(raw.black_patches, next) as usize == i;
        if is_black != listed {
            return Err(bad_value("black_patches", next));
        }
        if listed {
            next += 1;
        }
    }
    if next != black {
        return Err(bad_value("black_patches", next));
    }
    let count = mul(black, cols(c.modes_cols())?)?;
    f32_table(
        "black_projection",
        raw.black_projection,
        count,
        Allowed::Bounded,
    )
}

/// Channel tables: the `channel_response` matrix, `n × (m·B)` in both formulations.
pub(super) fn channel_tables(raw: &Payload<'_>, c: &Counts, precision: Precision) -> Result<()> {
    matrix(
        "channel_response.data",
        "channel_response.scales",
        raw.channel_response,
        precision,
        c.patch_count,
        cols(c.channel_response_cols())?,
    )
}

/// Outputs: `sensor_geometry` to the `output_view` matrix.
pub(super) fn outputs(raw: &Payload<'_>, c: &Counts, precision: Precision) -> Result<()> {
    let o = cols(c.output_count())?;
    let bp = cols(c.modes_cols())?;
    let sensors = mul(c.sensor_count, 7)?;
    f32_table(
        "sensor_geometry",
        raw.sensor_geometry,
        sensors,
        Allowed::Bounded,
    )?;
    f32_table("zone_area", raw.zone_area, c.zone_count, Allowed::Positive)?;
    f32_table(
        "output_modes",
        raw.output_modes,
        mul(o, bp)?,
        Allowed::Bounded,
    )?;
    let count = mul(mul(o, c.bands)?, c.channel_count)?;
    f32_table(
        "output_channels",
        raw.output_channels,
        count,
        Allowed::Bounded,
    )?;
    let cols = cols(c.output_view_cols())?;
    matrix(
        "output_view.data",
        "output_view.scales",
        raw.output_view,
        precision,
        c.patch_count,
        cols,
    )
}

/// Grids: `grid_layout` to the `grid_view` matrix (`grid_pieces` and `grid_lattice` were
/// checked with the counts). Every piece has points, so a positive spacing and cells and a
/// unit normal.
pub(super) fn grids(raw: &Payload<'_>, c: &Counts, precision: Precision) -> Result<()> {
    let g = c.grid_point_count;
    f32_table(
        "grid_layout",
        raw.grid_layout,
        mul(c.grid_piece_count, 7)?,
        Allowed::NotBelowMinusOne,
    )?;
    // Piece by piece (the length is checked above), each piece's seven values read once.
    for (q, piece) in raw.grid_layout.chunks_exact(7 * 4).enumerate() {
        let mut at = [0.0f32; 7];
        at.iter_mut()
            .zip(f32s(piece))
            .for_each(|(slot, v)| *slot = v);
        let [spacing, cell_first, cell_second, border, nx, ny, nz] = at;
        let norm = nx * nx + ny * ny + nz * nz;
        let ok = spacing > 0.0
            && cell_first > 0.0
            && cell_second > 0.0
            && border >= 0.0
            && (norm - 1.0).abs() <= 1.0e-3;
        if !ok {
            return Err(bad_value("grid_layout", 7 * q));
        }
    }
    f32_table(
        "grid_position",
        raw.grid_position,
        mul(g, 3)?,
        Allowed::Bounded,
    )?;
    let bp = cols(c.modes_cols())?;
    f32_table("grid_modes", raw.grid_modes, mul(g, bp)?, Allowed::Bounded)?;
    let count = mul(mul(g, c.bands)?, c.channel_count)?;
    f32_table("grid_channels", raw.grid_channels, count, Allowed::Bounded)?;
    matrix(
        "grid_view.data",
        "grid_view.scales",
        raw.grid_view,
        precision,
        g,
        cols(c.grid_view_cols())?,
    )
}
