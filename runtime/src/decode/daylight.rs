//! The daylight section (`docs/format.md`, "Daylight"): its shape when the basis is decoded,
//! its tables one by one when daylight is used.
//!
//! [`shape`] runs in [`Basis::from_bytes`](crate::Basis::from_bytes) and costs a few
//! dozen bytes of flash: without a sky every table of the section is empty; with one the
//! basis is photometric and the tables the counts size (36 to 42) hold the bytes the counts
//! give them, together. [`check_values`] runs when daylight is used
//! ([`crate::Basis::check_daylight`], called by
//! [`DirectSun::new`](crate::sky::direct::DirectSun::new) and so by every
//! [`DaylightEvaluator`](crate::DaylightEvaluator)): each table's length, named, the site,
//! the sun grid and its nodes in range, every node table finite and bounded, then the
//! direct sun's geometry, the first reflection ([`super::reflection`]) and the sun's
//! ([`super::sun_first`]). A firmware that
//! reads no daylight links the shape alone.

use super::dimensions::field_value;
use super::tables::{ascending_below, bad_value, check_len, cols, f32_table, matrix, mul, Allowed};
use crate::error::{Error, Result};
use crate::format::{Counts, Payload, Precision, Quantity};
use crate::storage::{f32_at, u32_at};

/// Most nodes of a sun grid: its node indices are read as `u32`, and a grid this fine is far
/// finer than the sun's own disc (0.53°) would ever need.
const MAX_SUN_GRID: usize = 1 << 20;

/// Largest magnitudes of the site's five values, in their order: latitude and longitude
/// (°), elevation (m), north (°), UTC offset (minutes).
const SITE_LIMITS: [f32; 5] = [90.0, 180.0, 1.0e4, 360.0, 18.0 * 60.0];

/// Bytes of the site (5 `f32`), the sun lattice (2 `u32`) and the sun spacing (4 `f32`).
const SETTINGS_BYTES: usize = 4 * (5 + 2 + 4);

/// The section's shape, at decode, as the sum of its tables' lengths: nothing without a sky
/// (`sky_subdivision` 0), all twenty-five tables empty; with one, a photometric basis of one
/// band whose site, sun lattice and spacing, `O × D` output table, `p × D` (or, with a first
/// reflection, `p × (r + sun nodes)`) mode table and `G × D` grid matrix (with a scale per
/// node in 16 bits) take the bytes the counts give them together. A wrong total is
/// [`Error::DecodeLength`] for the field `daylight`; [`check_values`] names the table.
/// (`sky_subdivision`, the length of `sun_nodes` and `reflection_rank` were checked with the
/// counts, since `D` and `r` follow from them; the direct sun's tables, sized by their own
/// counts, and the first reflection's are checked with the values.)
pub(super) fn shape(
    raw: &Payload<'_>,
    c: &Counts,
    quantity: Quantity,
    precision: Precision,
) -> Result<()> {
    let sized = raw.daylight_site.len()
        + raw.sun_lattice.len()
        + raw.sun_spacing.len()
        + raw.daylight_outputs.len()
        + raw.daylight_modes.len()
        + raw.daylight_grid.scales.len()
        + raw.daylight_grid.data.len();
    let direct = raw.sun_polygon_counts.len()
        + raw.sun_polygon_sizes.len()
        + raw.sun_polygons.len()
        + raw.sun_glazing.len()
        + raw.sensor_response_rows.len()
        + raw.sensor_response.len();
    let reflection = super::reflection::sized_bytes(raw);
    let listed = raw.sun_reflection_patches.len() + raw.sun_reflection.len();
    if raw.sky_subdivision == 0 {
        let all = sized + direct + reflection + listed + raw.reflection_rank.len();
        let all = all + super::sun_first::bytes(raw);
        return total("daylight", 0, all + raw.sun_nodes.len());
    }
    // Daylight is photopic: its tables are in lux.
    if quantity != Quantity::Photometric {
        return Err(field_value("sky_subdivision", raw.sky_subdivision));
    }
    // Per node: its value for every output (4 bytes each), its grid column, and its grid
    // scale in 16 bits; per mode, a value per column of `daylight_modes`.
    let outputs = cols(c.output_count())?;
    let grid = mul(c.grid_point_count, precision.bytes())?;
    let scale = match precision {
        Precision::F32 => 0,
        Precision::F16 | Precision::I16 => 4,
    };
    let per_node = cols(mul(outputs, 4)?.checked_add(grid))?;
    let per_node = cols(per_node.checked_add(scale))?;
    let modes = mul(mul(c.mode_count, cols(c.daylight_modes_cols())?)?, 4)?;
    let expected = cols(mul(c.daylight_node_count, per_node)?.checked_add(SETTINGS_BYTES))?;
    // The first reflection's tables are sized by its rank and its sun lists by their
    // counts: [`super::reflection::check`] checks them where daylight is used, so that a
    // firmware reading no daylight links none of it.
    total("daylight", cols(expected.checked_add(modes))?, sized)
}

/// [`Error::DecodeLength`] for `field` unless the tables it names hold `expected` bytes.
pub(super) fn total(field: &'static str, expected: usize, found: usize) -> Result<()> {
    if expected == found {
        Ok(())
    } else {
        Err(Error::DecodeLength {
            field,
            expected,
            found,
        })
    }
}

/// The section's tables, where daylight is used: each of the length the counts give it
/// (named), the site within [`SITE_LIMITS`], a sun grid of at most [`MAX_SUN_GRID`] nodes
/// with declinations within ±90° and hour angles within ±360°, stepping forward, its stored
/// nodes ascending inside it, every node table finite and bounded; then the direct sun's
/// tables ([`super::direct_sun::check`]). Nothing to check without a sky ([`shape`] found
/// every table empty).
pub(crate) fn check_values(raw: &Payload<'_>, c: &Counts, precision: Precision) -> Result<()> {
    if raw.sky_subdivision == 0 {
        return Ok(());
    }
    f32_table("daylight_site", raw.daylight_site, 5, Allowed::Bounded)?;
    for (k, limit) in SITE_LIMITS.into_iter().enumerate() {
        if f32_at(raw.daylight_site, k).abs() > limit {
            return Err(bad_value("daylight_site", k));
        }
    }
    check_len("sun_lattice", raw.sun_lattice, 2, 4)?;
    let rows = u32_at(raw.sun_lattice, 0) as usize;
    let columns = u32_at(raw.sun_lattice, 1) as usize;
    let grid = mul(rows, columns)?;
    if rows == 0 || columns == 0 || grid > MAX_SUN_GRID {
        return Err(bad_value("sun_lattice", 0));
    }
    f32_table("sun_spacing", raw.sun_spacing, 4, Allowed::Bounded)?;
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
    let d = c.daylight_node_count;
    f32_table(
        "daylight_outputs",
        raw.daylight_outputs,
        mul(cols(c.output_count())?, d)?,
        Allowed::Bounded,
    )?;
    f32_table(
        "daylight_modes",
        raw.daylight_modes,
        mul(cols(c.modes_cols())?, cols(c.daylight_modes_cols())?)?,
        Allowed::Bounded,
    )?;
    matrix(
        "daylight_grid.data",
        "daylight_grid.scales",
        raw.daylight_grid,
        precision,
        c.grid_point_count,
        cols(c.daylight_grid_cols())?,
    )?;
    super::direct_sun::check(raw, c)?;
    super::reflection::check(raw, c, precision)?;
    super::sun_first::check(raw, c)
}
