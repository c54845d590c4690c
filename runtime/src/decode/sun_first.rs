//! The sun's first reflection (`docs/format.md`, "The sun's first reflection"), part of the
//! daylight section since format version 8: checked where the tables are used, with the rest
//! of the daylight's values ([`super::daylight::check_values`]).

use super::tables::{ascending_below, bad_value, check_len, cols, empty, f32_table, Allowed};
use crate::error::Result;
use crate::format::{Counts, Payload};
use crate::sky::sun_first::MAX_SAMPLES;
use crate::storage::{f32_at, u32_at};

/// Largest departure of a patch's stored normal from unit length (as a polygon's).
const NORMAL_TOLERANCE: f32 = 2.0e-3;

/// Bytes of the four tables: a basis without a sky has none.
pub(super) fn bytes(raw: &Payload<'_>) -> usize {
    raw.sun_first_patches.len()
        + raw.sun_first_sizes.len()
        + raw.sun_first_points.len()
        + raw.sun_node_power.len()
}

/// All four tables empty, or: the direct sun's geometry present (the sample points are lit
/// through its windows), the patches ascending below `n` and reflecting, each with 1 to
/// [`MAX_SAMPLES`] sample points, a unit normal (within [`NORMAL_TOLERANCE`]), finite
/// bounded positions and weights in `[0, 1]`, and one power `≥ 0` per sun node.
pub(super) fn check(raw: &Payload<'_>, c: &Counts) -> Result<()> {
    if raw.sun_node_power.is_empty() {
        return empty(&[
            ("sun_first_patches", raw.sun_first_patches),
            ("sun_first_sizes", raw.sun_first_sizes),
            ("sun_first_points", raw.sun_first_points),
        ]);
    }
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
        if size == 0 || size > MAX_SAMPLES || reflectance <= 0.0 {
            return Err(bad_value("sun_first_sizes", index));
        }
        values = cols(values.checked_add(3 + 4 * usize::from(size)))?;
    }
    f32_table(
        "sun_first_points",
        raw.sun_first_points,
        values,
        Allowed::Bounded,
    )?;
    let mut offset = 0usize;
    for &size in raw.sun_first_sizes {
        let at = |k: usize| f32_at(raw.sun_first_points, offset + k);
        let length = at(0) * at(0) + at(1) * at(1) + at(2) * at(2);
        if (length - 1.0).abs() > NORMAL_TOLERANCE {
            return Err(bad_value("sun_first_points", offset));
        }
        for k in 0..usize::from(size) {
            let weight = offset + 3 + 4 * k + 3;
            if !(0.0..=1.0).contains(&f32_at(raw.sun_first_points, weight)) {
                return Err(bad_value("sun_first_points", weight));
            }
        }
        offset += 3 + 4 * usize::from(size);
    }
    Ok(())
}
