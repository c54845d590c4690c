//! The direct sun's geometry (`docs/format.md`, "Direct sun"), part of the daylight section
//! since format version 6: checked where the tables are used, with the rest of the daylight's
//! values ([`super::daylight::check_values`]).

use super::tables::{bad_value, check_len, cols, empty, f32_table, mul, u32_sum, Allowed};
use crate::error::Result;
use crate::format::{Counts, Payload};
use crate::sky::direct::{GLAZING_STEPS, MAX_POLYGON_VERTICES};
use crate::storage::{f32_at, u32_at};

/// Largest departure of a polygon's stored normal from unit length.
const NORMAL_TOLERANCE: f32 = 2.0e-3;

/// All six tables empty, or the polygons' counts, sizes, normals (unit within
/// [`NORMAL_TOLERANCE`]) and vertices, the glazing tables (within `[0, 1]`) and each
/// sensor's response (polar angles ascending within `[0, π]`, sensitivities `≥ 0`).
pub(super) fn check(raw: &Payload<'_>, c: &Counts) -> Result<()> {
    if raw.sun_polygon_counts.is_empty() {
        return empty(&[
            ("sun_polygon_sizes", raw.sun_polygon_sizes),
            ("sun_polygons", raw.sun_polygons),
            ("sun_glazing", raw.sun_glazing),
            ("sensor_response_rows", raw.sensor_response_rows),
            ("sensor_response", raw.sensor_response),
        ]);
    }
    let polygons = u32_sum("sun_polygon_counts", raw.sun_polygon_counts, 3)?;
    let windows = u32_at(raw.sun_polygon_counts, 0) as usize;
    check_len("sun_polygon_sizes", raw.sun_polygon_sizes, polygons, 1)?;
    let mut values = 0usize;
    for (index, &size) in raw.sun_polygon_sizes.iter().enumerate() {
        if !(3..=MAX_POLYGON_VERTICES).contains(&size) {
            return Err(bad_value("sun_polygon_sizes", index));
        }
        values = cols(values.checked_add(3 + 3 * usize::from(size)))?;
    }
    f32_table("sun_polygons", raw.sun_polygons, values, Allowed::Bounded)?;
    let mut offset = 0usize;
    for (index, &size) in raw.sun_polygon_sizes.iter().enumerate() {
        let n = |k: usize| f32_at(raw.sun_polygons, offset + k);
        let length = n(0) * n(0) + n(1) * n(1) + n(2) * n(2);
        if (length - 1.0).abs() > NORMAL_TOLERANCE {
            return Err(bad_value("sun_polygons", index));
        }
        offset += 3 + 3 * usize::from(size);
    }
    f32_table(
        "sun_glazing",
        raw.sun_glazing,
        mul(windows, GLAZING_STEPS + 1)?,
        Allowed::Fraction,
    )?;
    let pairs = u32_sum(
        "sensor_response_rows",
        raw.sensor_response_rows,
        c.sensor_count,
    )?;
    f32_table(
        "sensor_response",
        raw.sensor_response,
        mul(pairs, 2)?,
        Allowed::Bounded,
    )?;
    let mut first = 0usize;
    for s in 0..c.sensor_count {
        let rows = u32_at(raw.sensor_response_rows, s) as usize;
        let mut previous = -1.0f32;
        for k in first..first + rows {
            let angle = f32_at(raw.sensor_response, 2 * k);
            let value = f32_at(raw.sensor_response, 2 * k + 1);
            if !(angle > previous && (0.0..=core::f32::consts::PI).contains(&angle) && value >= 0.0)
            {
                return Err(bad_value("sensor_response", 2 * k));
            }
            previous = angle;
        }
        first += rows;
    }
    Ok(())
}
