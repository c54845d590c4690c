//! Decoding a basis, one function per section of `docs/format.md`: header
//! ([`format::check_header`]), settings, counts, names, eigenvalues, patch tables, modes,
//! black patches, channel tables, outputs, grids, daylight.
//!
//! Each section checks its tables' lengths against the counts and every stored value against
//! its range, so that the evaluator reads the tables without checking them again.
//! [`Basis::from_bytes`], defined here, runs the sections in payload order and returns the
//! first failure.

// The checks of one table (length, values, indices, matrix), shared by every section.
mod tables;

use crate::basis::Basis;
use crate::error::{Error, Result};
use crate::format::{self, Counts, Formulation, Payload, Precision, Quantity, NO_CHANNEL};
use crate::storage::{f32_at, u16_at, u32_at};
use tables::{check_len, cols, f32_table, matrix, mul, u16_table, Allowed};

/// The settings section, typed.
struct Settings {
    bands: usize,
    quantity: Quantity,
    formulation: Formulation,
    precision: Precision,
}

impl<'a> Basis<'a> {
    /// Decodes and validates a basis in place.
    ///
    /// Checks the magic, the format version, the CRC-32 of the payload, every table length
    /// against the counts, and that every stored number is finite and in range, section by
    /// section of `docs/format.md`. Vector data stays where it is (flash): only slice
    /// headers are kept. Any byte string gives `Ok` or an `Err`; none panics.
    pub fn from_bytes(bytes: &'a [u8]) -> Result<Self> {
        let body = format::check_header(bytes)?;
        let raw = format::decode_payload(body)?;
        let Settings {
            bands,
            quantity,
            formulation,
            precision,
        } = settings(&raw)?;
        let counts = counts(&raw, bands)?;
        names(&raw, &counts)?;
        eigenvalues(&raw, &counts, formulation)?;
        patch_tables(&raw, &counts)?;
        modes(&raw, &counts, precision)?;
        black_patches(&raw, &counts)?;
        channel_tables(&raw, &counts, precision)?;
        outputs(&raw, &counts, precision)?;
        grids(&raw, &counts, precision)?;
        daylight(&raw, &counts, quantity, precision)?;
        Ok(Basis {
            quantity,
            formulation,
            precision,
            counts,
            byte_len: format::HEADER_LEN + body.len(),
            tables: raw,
        })
    }
}

/// Settings: `bands`, `quantity`, `formulation`, `precision`.
fn settings(raw: &Payload<'_>) -> Result<Settings> {
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
fn counts(raw: &Payload<'_>, bands: usize) -> Result<Counts> {
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
    check_len("grid_pieces", raw.grid_pieces, counts.zone_count, 4)?;
    let mut pieces = 0usize;
    for z in 0..counts.zone_count {
        pieces = cols(pieces.checked_add(u32_at(raw.grid_pieces, z) as usize))?;
    }
    check_len("grid_lattice", raw.grid_lattice, mul(pieces, 3)?, 4)?;
    let mut points = 0usize;
    for q in 0..pieces {
        let cells = mul(
            u32_at(raw.grid_lattice, 3 * q) as usize,
            u32_at(raw.grid_lattice, 3 * q + 1) as usize,
        )?;
        let kept = u32_at(raw.grid_lattice, 3 * q + 2) as usize;
        if kept == 0 || kept > cells {
            return Err(Error::DecodeValue {
                field: "grid_lattice",
                index: 3 * q + 2,
            });
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
    Ok(Counts {
        grid_piece_count: pieces,
        grid_point_count: points,
        daylight_node_count: daylight_nodes,
        ..counts
    })
}

/// Names: the surfaces', channels', sensors' and zones' as consecutive postcard strings,
/// nothing after them.
fn names(raw: &Payload<'_>, c: &Counts) -> Result<()> {
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
            postcard::take_from_bytes::<&str>(rest).map_err(|_| Error::DecodePayload)?;
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
fn eigenvalues(raw: &Payload<'_>, c: &Counts, formulation: Formulation) -> Result<()> {
    let count = cols(c.modes_cols())?;
    match formulation {
        Formulation::Split => f32_table("eigenvalues", raw.eigenvalues, count, Allowed::Mu),
        Formulation::Seed => f32_table("eigenvalues", raw.eigenvalues, count, Allowed::Lambda),
    }
}

/// Patch tables: `patch_area` to `patch_emission`.
fn patch_tables(raw: &Payload<'_>, c: &Counts) -> Result<()> {
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
        return Err(Error::DecodeValue {
            field: "patch_emission",
            index,
        });
    }
    Ok(())
}

/// Modes: the `n × (B·p)` matrix of mode vectors.
fn modes(raw: &Payload<'_>, c: &Counts, precision: Precision) -> Result<()> {
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
fn black_patches(raw: &Payload<'_>, c: &Counts) -> Result<()> {
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
            return Err(Error::DecodeValue {
                field: "black_patches",
                index: next,
            });
        }
        if listed {
            next += 1;
        }
    }
    if next != black {
        return Err(Error::DecodeValue {
            field: "black_patches",
            index: next,
        });
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
fn channel_tables(raw: &Payload<'_>, c: &Counts, precision: Precision) -> Result<()> {
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
fn outputs(raw: &Payload<'_>, c: &Counts, precision: Precision) -> Result<()> {
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
fn grids(raw: &Payload<'_>, c: &Counts, precision: Precision) -> Result<()> {
    let g = c.grid_point_count;
    f32_table(
        "grid_layout",
        raw.grid_layout,
        mul(c.grid_piece_count, 7)?,
        Allowed::NotBelowMinusOne,
    )?;
    for q in 0..c.grid_piece_count {
        let at = |k: usize| f32_at(raw.grid_layout, 7 * q + k);
        let norm = at(4) * at(4) + at(5) * at(5) + at(6) * at(6);
        let ok = at(0) > 0.0
            && at(1) > 0.0
            && at(2) > 0.0
            && at(3) >= 0.0
            && (norm - 1.0).abs() <= 1.0e-3;
        if !ok {
            return Err(Error::DecodeValue {
                field: "grid_layout",
                index: 7 * q,
            });
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

/// Most nodes of a sun grid: its node indices are read as `u32`, and a grid this fine is far
/// finer than the sun's own disc (0.53°) would ever need.
const MAX_SUN_GRID: usize = 1 << 20;

/// Daylight: nothing without a sky (`sky_subdivision` 0); with one, a photometric basis of
/// one band, the site, the sun grid and its nodes, and the node tables.
fn daylight(raw: &Payload<'_>, c: &Counts, quantity: Quantity, precision: Precision) -> Result<()> {
    if raw.sky_subdivision == 0 {
        for (field, table) in [
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
        ] {
            check_len(field, table, 0, 1)?;
        }
        return Ok(());
    }
    // Daylight is photopic: its tables are in lux.
    if quantity != Quantity::Photometric {
        return Err(field_value("sky_subdivision", raw.sky_subdivision));
    }
    f32_table("daylight_site", raw.daylight_site, 5, Allowed::Bounded)?;
    let site = |k: usize| f32_at(raw.daylight_site, k);
    let limits = [90.0, 180.0, 1.0e4, 360.0, 18.0 * 60.0];
    for (k, limit) in limits.into_iter().enumerate() {
        if site(k).abs() > limit {
            return Err(Error::DecodeValue {
                field: "daylight_site",
                index: k,
            });
        }
    }
    check_len("sun_lattice", raw.sun_lattice, 2, 4)?;
    let rows = u32_at(raw.sun_lattice, 0) as usize;
    let columns = u32_at(raw.sun_lattice, 1) as usize;
    let grid = mul(rows, columns)?;
    if rows == 0 || columns == 0 || grid > MAX_SUN_GRID {
        return Err(Error::DecodeValue {
            field: "sun_lattice",
            index: 0,
        });
    }
    f32_table("sun_spacing", raw.sun_spacing, 4, Allowed::Bounded)?;
    let spacing = |k: usize| f32_at(raw.sun_spacing, k);
    // Declinations within ±90°, hour angles within ±360°, and steps that move.
    let last = |first: f32, step: f32, count: usize| first + step * (count - 1) as f32;
    let ok = spacing(1) > 0.0
        && spacing(3) > 0.0
        && spacing(0) >= -90.0
        && last(spacing(0), spacing(1), rows) <= 90.0
        && spacing(2) >= -360.0
        && last(spacing(2), spacing(3), columns) <= 360.0;
    if !ok {
        return Err(Error::DecodeValue {
            field: "sun_spacing",
            index: 0,
        });
    }
    let mut previous: Option<u32> = None;
    for i in 0..raw.sun_nodes.len() / 4 {
        let node = u32_at(raw.sun_nodes, i);
        if node as usize >= grid || previous.is_some_and(|p| p >= node) {
            return Err(Error::DecodeValue {
                field: "sun_nodes",
                index: i,
            });
        }
        previous = Some(node);
    }
    let d = c.daylight_node_count;
    let o = cols(c.output_count())?;
    f32_table(
        "daylight_outputs",
        raw.daylight_outputs,
        mul(o, d)?,
        Allowed::Bounded,
    )?;
    f32_table(
        "daylight_modes",
        raw.daylight_modes,
        mul(cols(c.modes_cols())?, d)?,
        Allowed::Bounded,
    )?;
    matrix(
        "daylight_grid.data",
        "daylight_grid.scales",
        raw.daylight_grid,
        precision,
        c.grid_point_count,
        cols(c.daylight_grid_cols())?,
    )
}

/// The direct sun's geometry (docs/format.md, "Direct sun"): all six tables empty, or the
/// polygons' counts, sizes, normals (unit, within 10⁻³) and vertices, the glazing tables
/// (within `[0, 1]`) and each sensor's response (polar angles ascending within `[0, π]`,
/// sensitivities `≥ 0`). Checked where the tables are used, when a daylight evaluator is
/// made ([`crate::sky::direct::DirectSun::new`]), rather than by [`Basis::from_bytes`]: a
/// firmware that reads no daylight then links none of it.
pub(crate) fn direct_sun(raw: &Payload<'_>, c: &Counts) -> Result<()> {
    if raw.sun_polygon_counts.is_empty() {
        for (field, table) in [
            ("sun_polygon_sizes", raw.sun_polygon_sizes),
            ("sun_polygons", raw.sun_polygons),
            ("sun_glazing", raw.sun_glazing),
            ("sensor_response_rows", raw.sensor_response_rows),
            ("sensor_response", raw.sensor_response),
        ] {
            check_len(field, table, 0, 1)?;
        }
        return Ok(());
    }
    check_len("sun_polygon_counts", raw.sun_polygon_counts, 3, 4)?;
    let count = |k: usize| u32_at(raw.sun_polygon_counts, k) as usize;
    let windows = count(0);
    let polygons = cols(
        windows
            .checked_add(count(1))
            .and_then(|n| n.checked_add(count(2))),
    )?;
    check_len("sun_polygon_sizes", raw.sun_polygon_sizes, polygons, 1)?;
    let mut values = 0usize;
    for (index, &size) in raw.sun_polygon_sizes.iter().enumerate() {
        if !(3..=crate::sky::direct::MAX_POLYGON_VERTICES).contains(&size) {
            return Err(Error::DecodeValue {
                field: "sun_polygon_sizes",
                index,
            });
        }
        values = cols(values.checked_add(3 + 3 * usize::from(size)))?;
    }
    f32_table("sun_polygons", raw.sun_polygons, values, Allowed::Bounded)?;
    let mut offset = 0usize;
    for (index, &size) in raw.sun_polygon_sizes.iter().enumerate() {
        let n = |k: usize| f32_at(raw.sun_polygons, offset + k);
        let length = n(0) * n(0) + n(1) * n(1) + n(2) * n(2);
        if (length - 1.0).abs() > 2.0e-3 {
            return Err(Error::DecodeValue {
                field: "sun_polygons",
                index,
            });
        }
        offset += 3 + 3 * usize::from(size);
    }
    let steps = crate::sky::direct::GLAZING_STEPS + 1;
    f32_table(
        "sun_glazing",
        raw.sun_glazing,
        mul(windows, steps)?,
        Allowed::Bounded,
    )?;
    if let Some(index) =
        (0..windows * steps).find(|&k| !(0.0..=1.0).contains(&f32_at(raw.sun_glazing, k)))
    {
        return Err(Error::DecodeValue {
            field: "sun_glazing",
            index,
        });
    }
    check_len(
        "sensor_response_rows",
        raw.sensor_response_rows,
        c.sensor_count,
        4,
    )?;
    let mut pairs = 0usize;
    for s in 0..c.sensor_count {
        pairs = cols(pairs.checked_add(u32_at(raw.sensor_response_rows, s) as usize))?;
    }
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
            let (angle, value) = (
                f32_at(raw.sensor_response, 2 * k),
                f32_at(raw.sensor_response, 2 * k + 1),
            );
            if !(angle > previous && (0.0..=core::f32::consts::PI).contains(&angle) && value >= 0.0)
            {
                return Err(Error::DecodeValue {
                    field: "sensor_response",
                    index: 2 * k,
                });
            }
            previous = angle;
        }
        first += rows;
    }
    Ok(())
}

fn field_value(field: &'static str, value: u8) -> Error {
    Error::DecodeField {
        field,
        value: u32::from(value),
    }
}
