//! The sun's first reflection (`docs/format.md`, "The sun's first reflection"), part of the
//! daylight section since format version 8: checked where the tables are used, with the rest
//! of the daylight's values ([`super::daylight::check_values`]).

use super::tables::{
    ascending_below, bad_value, check_len, cols, empty, f32_table, u32_sum, Allowed,
};
use crate::error::Result;
use crate::format::{Counts, Payload};
use crate::sky::sun_first::MAX_CORNERS;
use crate::storage::{f32_at, u32_at};

/// Largest departure of a patch's stored normal from unit length (as a polygon's).
const NORMAL_TOLERANCE: f32 = 2.0e-3;

/// Bytes of the eight tables: a basis without a sky has none.
pub(super) fn bytes(raw: &Payload<'_>) -> usize {
    raw.sun_first_patches.len()
        + raw.sun_first_sizes.len()
        + raw.sun_first_points.len()
        + raw.sun_node_power.len()
        + raw.sun_first_response.len()
        + raw.zone_sun_counts.len()
        + raw.zone_sun_sizes.len()
        + raw.zone_sun_polygons.len()
}

/// All eight tables empty, or: the direct sun's geometry present (the patches are lit
/// through its windows), the patches ascending below `n` and reflecting, each with 3 to
/// [`MAX_CORNERS`] corners, a unit normal (within [`NORMAL_TOLERANCE`]), finite bounded
/// positions, one power `≥ 0` per sun node, and either no responses or one finite value
/// `≥ 0` per candidate and reading (sensors, zones, grid points); the zones' polygons as
/// [`check_zones`] says.
pub(super) fn check(raw: &Payload<'_>, c: &Counts) -> Result<()> {
    if raw.sun_node_power.is_empty() {
        return empty(&[
            ("sun_first_patches", raw.sun_first_patches),
            ("sun_first_sizes", raw.sun_first_sizes),
            ("sun_first_points", raw.sun_first_points),
            ("sun_first_response", raw.sun_first_response),
            ("zone_sun_counts", raw.zone_sun_counts),
            ("zone_sun_sizes", raw.zone_sun_sizes),
            ("zone_sun_polygons", raw.zone_sun_polygons),
        ]);
    }
    check_zones(raw, c)?;
    if raw.sun_polygon_counts.is_empty() {
        return Err(bad_value("sun_node_power", 0));
    }
    f32_table(
        "sun_node_power",
        raw.sun_node_power,
        c.sun_node_count,
        Allowed::NonNegative,
    )?;
    ascending_below("sun_first_patches", raw.sun_first_patches, c.patch_count)?;
    let patches = raw.sun_first_patches.len() / 4;
    check_len("sun_first_patches", raw.sun_first_patches, patches, 4)?;
    check_len("sun_first_sizes", raw.sun_first_sizes, patches, 1)?;
    let mut values = 0usize;
    for (index, &size) in raw.sun_first_sizes.iter().enumerate() {
        let patch = u32_at(raw.sun_first_patches, index) as usize;
        // A candidate reflects: its first reflection is `ρ E`. Band 0 is the photopic one.
        let reflectance = f32_at(raw.patch_reflectance, patch.saturating_mul(c.bands));
        if !(3..=MAX_CORNERS).contains(&size) || reflectance <= 0.0 {
            return Err(bad_value("sun_first_sizes", index));
        }
        values = cols(values.checked_add(3 + 3 * usize::from(size)))?;
    }
    f32_table(
        "sun_first_points",
        raw.sun_first_points,
        values,
        Allowed::Bounded,
    )?;
    if !raw.sun_first_response.is_empty() {
        let readings = c
            .sensor_count
            .checked_add(c.zone_count)
            .and_then(|o| o.checked_add(c.grid_point_count));
        f32_table(
            "sun_first_response",
            raw.sun_first_response,
            cols(readings.and_then(|r| r.checked_mul(patches)))?,
            Allowed::NonNegative,
        )?;
    }
    unit_normals(
        "sun_first_points",
        raw.sun_first_points,
        raw.sun_first_sizes,
    )
}

/// The zones' polygons: none, or one count per zone, one size of 3 to [`MAX_CORNERS`] per
/// polygon, and per polygon a unit normal (within [`NORMAL_TOLERANCE`]) and finite bounded
/// corners.
fn check_zones(raw: &Payload<'_>, c: &Counts) -> Result<()> {
    if raw.zone_sun_counts.is_empty() {
        return empty(&[
            ("zone_sun_sizes", raw.zone_sun_sizes),
            ("zone_sun_polygons", raw.zone_sun_polygons),
        ]);
    }
    let polygons = u32_sum("zone_sun_counts", raw.zone_sun_counts, c.zone_count)?;
    check_len("zone_sun_sizes", raw.zone_sun_sizes, polygons, 1)?;
    let mut values = 0usize;
    for (index, &size) in raw.zone_sun_sizes.iter().enumerate() {
        if !(3..=MAX_CORNERS).contains(&size) {
            return Err(bad_value("zone_sun_sizes", index));
        }
        values = cols(values.checked_add(3 + 3 * usize::from(size)))?;
    }
    f32_table(
        "zone_sun_polygons",
        raw.zone_sun_polygons,
        values,
        Allowed::Bounded,
    )?;
    unit_normals(
        "zone_sun_polygons",
        raw.zone_sun_polygons,
        raw.zone_sun_sizes,
    )
}

/// Each polygon of `table` (its normal, then `sizes[k]` corners) has a unit normal, within
/// [`NORMAL_TOLERANCE`]; the error names `field` and the normal's place.
fn unit_normals(field: &'static str, table: &[u8], sizes: &[u8]) -> Result<()> {
    let mut offset = 0usize;
    for &size in sizes {
        let at = |k: usize| f32_at(table, offset + k);
        let length = at(0) * at(0) + at(1) * at(1) + at(2) * at(2);
        if (length - 1.0).abs() > NORMAL_TOLERANCE {
            return Err(bad_value(field, offset));
        }
        offset += 3 + 3 * usize::from(size);
    }
    Ok(())
}
