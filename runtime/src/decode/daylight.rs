//! The daylight section (`docs/format.md`, "Daylight"): its shape when the basis is decoded,
//! its values when daylight is used.
//!
//! [`shape`] runs in [`Basis::from_bytes`](crate::Basis::from_bytes): without a sky every
//! table of the section is empty; with one the basis is photometric and every table has the
//! length the counts give it, so that every later read stays inside its table.
//! [`check_values`] runs when daylight is used ([`crate::Basis::check_daylight`], called by
//! [`DirectSun::new`](crate::sky::direct::DirectSun::new) and so by every
//! [`DaylightEvaluator`](crate::DaylightEvaluator)): the site, the sun grid and its nodes
//! in range, every node table finite and bounded, then the direct sun's geometry. A firmware
//! that reads no daylight links the shape's few length checks and none of the rest.

use super::dimensions::field_value;
use super::tables::{
    ascending_below, bad_value, check_f32, check_len, cols, empty, matrix_len, matrix_values, mul,
    Allowed,
};
use crate::error::Result;
use crate::format::{Counts, Payload, Precision, Quantity};
use crate::storage::{f32_at, u32_at};

/// Most nodes of a sun grid: its node indices are read as `u32`, and a grid this fine is far
/// finer than the sun's own disc (0.53°) would ever need.
const MAX_SUN_GRID: usize = 1 << 20;

/// Largest magnitudes of the site's five values, in their order: latitude and longitude
/// (°), elevation (m), north (°), UTC offset (minutes).
const SITE_LIMITS: [f32; 5] = [90.0, 180.0, 1.0e4, 360.0, 18.0 * 60.0];

/// The section's shape, at decode: nothing without a sky (`sky_subdivision` 0); with one, a
/// photometric basis of one band, 5 values of site, 2 of lattice, 4 of spacing, and the node
/// tables `O × D`, `p × D` and the `G × D` grid matrix. (`sky_subdivision` and the length of
/// `sun_nodes` were checked with the counts, since `D` follows from them.)
pub(super) fn shape(
    raw: &Payload<'_>,
    c: &Counts,
    quantity: Quantity,
    precision: Precision,
) -> Result<()> {
    if raw.sky_subdivision == 0 {
        return empty(&[
            ("daylight_site", raw.daylight_site),
            ("sun_lattice", raw.sun_lattice),
            ("sun_spacing", raw.sun_spacing),
            ("sun_nodes", raw.sun_nodes),
            ("daylight_outputs", raw.daylight_outputs),
            ("daylight_modes", raw.daylight_modes),
            ("daylight_grid.scales", raw.daylight_grid.scales),
            ("daylight_grid.data", raw.daylight_grid.data),
            ("sun_polygon_counts", raw.sun_polygon_counts),
            ("sun_polygon_sizes", raw.sun_polygon_sizes),
            ("sun_polygons", raw.sun_polygons),
            ("sun_glazing", raw.sun_glazing),
            ("sensor_response_rows", raw.sensor_response_rows),
            ("sensor_response", raw.sensor_response),
        ]);
    }
    // Daylight is photopic: its tables are in lux.
    if quantity != Quantity::Photometric {
        return Err(field_value("sky_subdivision", raw.sky_subdivision));
    }
    let d = c.daylight_node_count;
    check_len("daylight_site", raw.daylight_site, 5, 4)?;
    check_len("sun_lattice", raw.sun_lattice, 2, 4)?;
    check_len("sun_spacing", raw.sun_spacing, 4, 4)?;
    check_len(
        "daylight_outputs",
        raw.daylight_outputs,
        mul(cols(c.output_count())?, d)?,
        4,
    )?;
    check_len(
        "daylight_modes",
        raw.daylight_modes,
        mul(cols(c.modes_cols())?, d)?,
        4,
    )?;
    matrix_len(
        "daylight_grid.data",
        "daylight_grid.scales",
        raw.daylight_grid,
        precision,
        c.grid_point_count,
        cols(c.daylight_grid_cols())?,
    )
}

/// The section's values, where daylight is used: the site within [`SITE_LIMITS`], a sun
/// grid of at most [`MAX_SUN_GRID`] nodes with declinations within ±90° and hour angles
/// within ±360°, stepping forward, its stored nodes ascending inside it, every node table
/// finite and bounded; then the direct sun's tables ([`super::direct_sun::check`]). Nothing
/// to check without a sky. The shape was checked by [`shape`] when the basis was decoded.
pub(crate) fn check_values(raw: &Payload<'_>, c: &Counts, precision: Precision) -> Result<()> {
    if raw.sky_subdivision == 0 {
        return Ok(());
    }
    check_f32("daylight_site", raw.daylight_site, Allowed::Bounded)?;
    for (k, limit) in SITE_LIMITS.into_iter().enumerate() {
        if f32_at(raw.daylight_site, k).abs() > limit {
            return Err(bad_value("daylight_site", k));
        }
    }
    let rows = u32_at(raw.sun_lattice, 0) as usize;
    let columns = u32_at(raw.sun_lattice, 1) as usize;
    let grid = mul(rows, columns)?;
    if rows == 0 || columns == 0 || grid > MAX_SUN_GRID {
        return Err(bad_value("sun_lattice", 0));
    }
    check_f32("sun_spacing", raw.sun_spacing, Allowed::Bounded)?;
    let spacing = |k: usize| f32_at(raw.sun_spacing, k);
    let last = |first: f32, step: f32, count: usize| first + step * (count - 1) as f32;
    let ok = spacing(1) > 0.0
        && spacing(3) > 0.0
        && spacing(0) >= -90.0
        && last(spacing(0), spacing(1), rows) <= 90.0
        && spacing(2) >= -360.0
        && last(spacing(2), spacing(3), columns) <= 360.0;
    if !ok {
        return Err(bad_value("sun_spacing", 0));
    }
    ascending_below("sun_nodes", raw.sun_nodes, grid)?;
    check_f32("daylight_outputs", raw.daylight_outputs, Allowed::Bounded)?;
    check_f32("daylight_modes", raw.daylight_modes, Allowed::Bounded)?;
    matrix_values(
        "daylight_grid.data",
        "daylight_grid.scales",
        raw.daylight_grid,
        precision,
    )?;
    super::direct_sun::check(raw, c)
}
