//! Settings and counts: the basis' typed settings and the dimensions every later table's
//! length follows from, grid points and daylight nodes included.

use super::tables::{bad_value, check_len, cols, mul, u32_sum};
use crate::error::{Error, Result};
use crate::format::{self, Counts, Formulation, Payload, Precision, Quantity, NO_CHANNEL};
use crate::storage::u32_at;

/// The settings section, typed.
pub(super) struct Settings {
    pub bands: usize,
    pub quantity: Quantity,
    pub formulation: Formulation,
    pub precision: Precision,
}

/// Settings: `bands`, `quantity`, `formulation`, `precision`.
pub(super) fn settings(raw: &Payload<'_>) -> Result<Settings> {
    let bands = match raw.bands {
        1 | 3 => usize::from(raw.bands),
        other => return Err(field_value("bands", other)),
    };
    let quantity = match raw.quantity {
        0 => Quantity::Radiometric,
        1 => Quantity::Photometric,
        other => return Err(field_value("quantity", other)),
    };
    if quantity == Quantity::Photometric && bands != 1 {
        return Err(field_value("quantity", raw.quantity));
    }
    let formulation = match raw.formulation {
        0 => Formulation::Split,
        1 => Formulation::Seed,
        other => return Err(field_value("formulation", other)),
    };
    let precision = match raw.precision {
        0 => Precision::F32,
        1 => Precision::F16,
        2 => Precision::I16,
        other => return Err(field_value("precision", other)),
    };
    Ok(Settings {
        bands,
        quantity,
        formulation,
        precision,
    })
}

/// Counts: `patch_count` to `zone_count`. Surface and channel indices are stored in 16 bits,
/// with `0xFFFF` meaning no channel.
pub(super) fn counts(raw: &Payload<'_>, bands: usize) -> Result<Counts> {
    let counts = Counts {
        bands,
        patch_count: raw.patch_count as usize,
        mode_count: raw.mode_count as usize,
        surface_count: raw.surface_count as usize,
        channel_count: raw.channel_count as usize,
        sensor_count: raw.sensor_count as usize,
        zone_count: raw.zone_count as usize,
        grid_piece_count: 0,
        grid_point_count: 0,
        daylight_node_count: 0,
        sun_node_count: 0,
        reflection_rank: None,
    };
    if counts.surface_count > usize::from(u16::MAX) {
        return Err(Error::DecodeField {
            field: "surface_count",
            value: raw.surface_count,
        });
    }
    if counts.channel_count >= usize::from(NO_CHANNEL) {
        return Err(Error::DecodeField {
            field: "channel_count",
            value: raw.channel_count,
        });
    }
    if counts.output_count().is_none() {
        return Err(Error::DecodeField {
            field: "zone_count",
            value: raw.zone_count,
        });
    }
    // The grid's pieces and lattices come before its tables: every later length follows
    // from `Q` and `G`.
    let pieces = u32_sum("grid_pieces", raw.grid_pieces, counts.zone_count)?;
    check_len("grid_lattice", raw.grid_lattice, mul(pieces, 3)?, 4)?;
    let mut points = 0usize;
    // Piece by piece, each piece's three numbers read once.
    for (q, piece) in raw.grid_lattice.chunks_exact(3 * 4).enumerate() {
        let at = |k: usize| u32_at(piece, k) as usize;
        let cells = mul(at(0), at(1))?;
        let kept = at(2);
        if kept == 0 || kept > cells {
            return Err(bad_value("grid_lattice", 3 * q + 2));
        }
        points = cols(points.checked_add(kept))?;
    }
    // The daylight's nodes: the sky's patches, the exterior, the sun nodes.
    if raw.sky_subdivision > crate::sky::patches::MAX_SUBDIVISION {
        return Err(field_value("sky_subdivision", raw.sky_subdivision));
    }
    if !raw.sun_nodes.len().is_multiple_of(4) {
        return Err(Error::DecodeLength {
            field: "sun_nodes",
            expected: raw.sun_nodes.len() / 4 * 4,
            found: raw.sun_nodes.len(),
        });
    }
    let daylight_nodes = cols(format::daylight_nodes(
        raw.sky_subdivision,
        raw.sun_nodes.len() / 4,
    ))?;
    // The rank of the sky's first reflection sizes that table and `daylight_modes`.
    let reflection_rank = match raw.reflection_rank.len() {
        0 => None,
        4 => Some(u32_at(raw.reflection_rank, 0) as usize),
        found => {
            return Err(Error::DecodeLength {
                field: "reflection_rank",
                expected: 4,
                found,
            })
        }
    };
    Ok(Counts {
        grid_piece_count: pieces,
        grid_point_count: points,
        daylight_node_count: daylight_nodes,
        sun_node_count: raw.sun_nodes.len() / 4,
        reflection_rank,
        ..counts
    })
}

/// The error of a setting with a value it cannot take.
pub(super) fn field_value(field: &'static str, value: u8) -> Error {
    Error::DecodeField {
        field,
        value: u32::from(value),
    }
}
