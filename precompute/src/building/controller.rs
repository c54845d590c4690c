//! A controller's basis, cut from its room's tables: only its outputs (its sensors, its
//! zones, its zones' grid points), the channels that reach them, their daylight rows, and
//! the room's modes only when the manifest asks for them.
//!
//! Every value is copied from the room's tables, in the room's order, so the controller's
//! basis reads, to the bit, what the whole room's basis reads at the same outputs: the
//! runtime sums each reading over the channels in order, and a channel left out reads exactly
//! 0 there (docs/building.md, "A basis per controller").

use eigenrad_runtime::writer::BasisTables;
use serde::Serialize;

use super::manifest::Controller;

/// What a controller's basis holds, as indices into its room's tables.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Selection {
    /// The room's channels it keeps, ascending.
    pub channels: Vec<usize>,
    /// The room's sensors it reads, ascending.
    pub sensors: Vec<usize>,
    /// The room's zones it reads, ascending, each with whether its grid is kept.
    pub zones: Vec<(usize, bool)>,
    /// Whether the modes (and with them every patch) are kept.
    pub modes: bool,
}

/// How the channels that reach a controller's outputs stand to it.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct Neighbours {
    /// Neighbours' channels whose levels the controller must be told.
    pub inputs: Vec<String>,
    /// Neighbours' channels it is not told, each with the highest level it assumes.
    pub bounds: Vec<(String, f64)>,
    /// Channels the manifest bounds that do not reach its outputs (left out of its basis).
    pub unreached: Vec<String>,
}

/// Where each zone's grid points lie among the room's: `(first point, points)` per zone.
fn grid_points_per_zone(t: &BasisTables) -> Vec<(usize, usize)> {
    let mut piece = 0;
    let mut point = 0;
    (0..t.zone_names.len())
        .map(|z| {
            let pieces = t.grid_pieces.get(z).copied().unwrap_or(0) as usize;
            let points: usize = t.grid_lattice[piece..piece + pieces]
                .iter()
                .map(|l| l[2] as usize)
                .sum();
            let range = (point, points);
            piece += pieces;
            point += points;
            range
        })
        .collect()
}

/// Where each zone's grid pieces lie among the room's: `(first piece, pieces)` per zone.
fn grid_pieces_per_zone(t: &BasisTables) -> Vec<(usize, usize)> {
    let mut piece = 0;
    (0..t.zone_names.len())
        .map(|z| {
            let pieces = t.grid_pieces.get(z).copied().unwrap_or(0) as usize;
            let range = (piece, pieces);
            piece += pieces;
            range
        })
        .collect()
}

/// The indices of `names` among `all`, ascending (the manifest's names were checked against
/// the room's scene when it was loaded).
fn indices(all: &[String], names: &[String]) -> Vec<usize> {
    (0..all.len())
        .filter(|&i| names.contains(&all[i]))
        .collect()
}

/// The room's outputs (sensors, then zones) and grid points a selection reads.
fn kept_rows(
    room: &BasisTables,
    sensors: &[usize],
    zones: &[(usize, bool)],
) -> (Vec<usize>, Vec<usize>) {
    let s = room.sensor_names.len();
    let outputs = sensors
        .iter()
        .copied()
        .chain(zones.iter().map(|&(z, _)| s + z))
        .collect();
    let per_zone = grid_points_per_zone(room);
    let points = zones
        .iter()
        .filter(|&&(_, grid)| grid)
        .flat_map(|&(z, _)| {
            let (first, count) = per_zone[z];
            first..first + count
        })
        .collect();
    (outputs, points)
}

/// The selection of `controller` in `room`, and how its neighbours' channels stand: the
/// channels it drives and every other channel whose exact reading at one of its outputs or
/// grid points is not 0; with modes, every channel of the room (the patch tables name them).
pub fn select(room: &BasisTables, controller: &Controller) -> (Selection, Neighbours) {
    let sensors = indices(&room.sensor_names, &controller.sensors);
    let zones: Vec<(usize, bool)> = (0..room.zone_names.len())
        .filter_map(|z| {
            let name = &room.zone_names[z];
            let grid = controller.grids.contains(name);
            (grid || controller.zones.contains(name)).then_some((z, grid))
        })
        .collect();
    let (outputs, points) = kept_rows(room, &sensors, &zones);
    let (m, bands) = (room.channel_names.len(), room.bands);
    let reaches = |c: usize| {
        let read =
            |table: &[f64], row: usize| (0..bands).any(|b| table[(row * bands + b) * m + c] != 0.0);
        outputs.iter().any(|&o| read(&room.output_channels, o))
            || points.iter().any(|&g| read(&room.grid_channels, g))
    };
    let drives = |c: usize| controller.drives.contains(&room.channel_names[c]);
    let channels: Vec<usize> = (0..m)
        .filter(|&c| controller.modes || drives(c) || reaches(c))
        .collect();
    let mut neighbours = Neighbours::default();
    for &c in &channels {
        let name = &room.channel_names[c];
        if drives(c) {
            continue;
        }
        match controller.bounds.iter().find(|(b, _)| b == name) {
            Some(bound) => neighbours.bounds.push(bound.clone()),
            None => neighbours.inputs.push(name.clone()),
        }
    }
    neighbours.unreached = controller
        .bounds
        .iter()
        .filter(|(b, _)| !channels.iter().any(|&c| &room.channel_names[c] == b))
        .map(|(b, _)| b.clone())
        .collect();
    let selection = Selection {
        channels,
        sensors,
        zones,
        modes: controller.modes,
    };
    (selection, neighbours)
}

/// Rows `rows` of a row-major table of `width` values a row.
fn rows_of(table: &[f64], width: usize, rows: &[usize]) -> Vec<f64> {
    rows.iter()
        .flat_map(|&r| table[r * width..(r + 1) * width].iter().copied())
        .collect()
}

/// Of every row of a row-major table of `width` values a row, the columns `columns`.
fn columns_of(table: &[f64], width: usize, columns: &[usize]) -> Vec<f64> {
    if width == 0 {
        return Vec::new();
    }
    table
        .chunks_exact(width)
        .flat_map(|row| columns.iter().map(move |&c| row[c]))
        .collect()
}

/// The tables of the basis holding what `selection` keeps of `room`.
pub fn cut(room: &BasisTables, selection: &Selection) -> BasisTables {
    let Selection {
        channels,
        sensors,
        zones,
        modes,
    } = selection;
    let (bands, m) = (room.bands, room.channel_names.len());
    let (outputs, points) = kept_rows(room, sensors, zones);
    let p = if *modes { room.mode_count } else { 0 };
    let n = room.patch_area.len();
    let o = room.sensor_names.len() + room.zone_names.len();
    let d = room.daylight_outputs.len().checked_div(o).unwrap_or(0);
    let pieces = grid_pieces_per_zone(room);
    let kept_pieces: Vec<usize> = zones
        .iter()
        .filter(|&&(_, grid)| grid)
        .flat_map(|&(z, _)| pieces[z].0..pieces[z].0 + pieces[z].1)
        .collect();
    // The channel columns `c·B + b`... of a table `rows × (B × m)` read band-major per row
    // (`output_channels`, `grid_channels`: row, band, then channel).
    let channel_readings = |table: &[f64], rows: &[usize]| -> Vec<f64> {
        rows.iter()
            .flat_map(|&r| {
                (0..bands).flat_map(move |b| {
                    channels
                        .iter()
                        .map(move |&c| table[(r * bands + b) * m + c])
                })
            })
            .collect()
    };
    let when_modes = |table: &Vec<f64>| if *modes { table.clone() } else { Vec::new() };
    let when_rows = |table: &Vec<u32>| if *modes { table.clone() } else { Vec::new() };
    let mut t = BasisTables {
        quantity: room.quantity,
        formulation: room.formulation,
        precision: room.precision,
        bands,
        mode_count: p,
        surface_names: if *modes {
            room.surface_names.clone()
        } else {
            Vec::new()
        },
        channel_names: channels
            .iter()
            .map(|&c| room.channel_names[c].clone())
            .collect(),
        sensor_names: sensors
            .iter()
            .map(|&s| room.sensor_names[s].clone())
            .collect(),
        zone_names: zones
            .iter()
            .map(|&(z, _)| room.zone_names[z].clone())
            .collect(),
        eigenvalues: when_modes(&room.eigenvalues),
        patch_area: when_modes(&room.patch_area),
        patch_centroid: if *modes {
            room.patch_centroid.clone()
        } else {
            Vec::new()
        },
        patch_surface: if *modes {
            room.patch_surface.clone()
        } else {
            Vec::new()
        },
        patch_channel: if *modes {
            room.patch_channel.clone()
        } else {
            Vec::new()
        },
        patch_reflectance: when_modes(&room.patch_reflectance),
        patch_emission: when_modes(&room.patch_emission),
        modes: when_modes(&room.modes),
        black_projection: when_modes(&room.black_projection),
        channel_response: when_modes(&room.channel_response),
        sensor_geometry: sensors.iter().map(|&s| room.sensor_geometry[s]).collect(),
        zone_area: zones.iter().map(|&(z, _)| room.zone_area[z]).collect(),
        output_modes: rows_of(&room.output_modes, bands * p, &outputs),
        output_channels: channel_readings(&room.output_channels, &outputs),
        output_view: if *modes {
            columns_of(&room.output_view, o, &outputs)
        } else {
            Vec::new()
        },
        grid_pieces: zones
            .iter()
            .map(|&(z, grid)| if grid { pieces[z].1 as u32 } else { 0 })
            .collect(),
        grid_lattice: kept_pieces.iter().map(|&q| room.grid_lattice[q]).collect(),
        grid_layout: kept_pieces.iter().map(|&q| room.grid_layout[q]).collect(),
        grid_position: points.iter().map(|&g| room.grid_position[g]).collect(),
        grid_modes: rows_of(&room.grid_modes, bands * p, &points),
        grid_channels: channel_readings(&room.grid_channels, &points),
        grid_view: if *modes {
            rows_of(&room.grid_view, n, &points)
        } else {
            Vec::new()
        },
        sky_subdivision: room.sky_subdivision,
        daylight_site: room.daylight_site.clone(),
        sun_lattice: room.sun_lattice.clone(),
        sun_spacing: room.sun_spacing.clone(),
        sun_nodes: room.sun_nodes.clone(),
        daylight_outputs: rows_of(&room.daylight_outputs, d, &outputs),
        daylight_modes: when_modes(&room.daylight_modes),
        daylight_grid: rows_of(&room.daylight_grid, d, &points),
        sun_polygon_counts: room.sun_polygon_counts.clone(),
        sun_polygon_sizes: room.sun_polygon_sizes.clone(),
        sun_polygons: room.sun_polygons.clone(),
        sun_glazing: room.sun_glazing.clone(),
        sensor_response_rows: if room.sensor_response_rows.is_empty() {
            Vec::new()
        } else {
            sensors
                .iter()
                .map(|&s| room.sensor_response_rows[s])
                .collect()
        },
        sensor_response: sensor_response_of(room, sensors),
        // The daylight's first reflection is per patch, as the modes: kept with them.
        reflection_rank: when_rows(&room.reflection_rank),
        sky_reflection_weights: when_modes(&room.sky_reflection_weights),
        sky_reflection: when_modes(&room.sky_reflection),
        sun_reflection_counts: when_rows(&room.sun_reflection_counts),
        sun_reflection_patches: when_rows(&room.sun_reflection_patches),
        sun_reflection: when_modes(&room.sun_reflection),
        // Folded into the readings before a controller's basis is cut
        // (`basis::fold_sun_first`).
        sun_first_patches: Vec::new(),
        sun_first_sizes: Vec::new(),
        sun_first_points: Vec::new(),
        sun_node_power: Vec::new(),
        sun_first_response: Vec::new(),
        zone_sun_counts: Vec::new(),
        zone_sun_sizes: Vec::new(),
        zone_sun_polygons: Vec::new(),
    };
    if room.grid_pieces.is_empty() {
        // The room has no grid at all: written as it writes it.
        t.grid_pieces.clear();
    }
    t
}

/// The response pairs of `sensors` (indices into the room's), in their order.
fn sensor_response_of(room: &BasisTables, sensors: &[usize]) -> Vec<f64> {
    let rows = &room.sensor_response_rows;
    let first = |s: usize| rows[..s].iter().map(|&r| r as usize).sum::<usize>();
    sensors
        .iter()
        .filter(|&&s| s < rows.len())
        .flat_map(|&s| {
            let start = 2 * first(s);
            room.sensor_response[start..start + 2 * rows[s] as usize].to_vec()
        })
        .collect()
}

/// Bytes each part of a basis takes, by section (docs/format.md): what leaving the section's
/// tables out of `t` saves.
pub fn section_bytes(
    t: &BasisTables,
) -> Result<Vec<(&'static str, usize)>, eigenrad_runtime::Error> {
    let total = t.to_bytes()?.len();
    let without = |clear: fn(&mut BasisTables)| -> Result<usize, eigenrad_runtime::Error> {
        let mut less = t.clone();
        clear(&mut less);
        Ok(total - less.to_bytes()?.len().min(total))
    };
    let mut sections = vec![
        (
            "names",
            without(|t| {
                t.surface_names.clear();
                t.channel_names.clear();
                t.sensor_names.clear();
                t.zone_names.clear();
            })?,
        ),
        (
            "patches and modes",
            without(|t| {
                t.eigenvalues.clear();
                t.patch_area.clear();
                t.patch_centroid.clear();
                t.patch_surface.clear();
                t.patch_channel.clear();
                t.patch_reflectance.clear();
                t.patch_emission.clear();
                t.modes.clear();
                t.black_projection.clear();
                t.channel_response.clear();
                t.output_modes.clear();
                t.output_view.clear();
                t.grid_modes.clear();
                t.grid_view.clear();
                t.daylight_modes.clear();
            })?,
        ),
        (
            "outputs",
            without(|t| {
                t.sensor_geometry.clear();
                t.zone_area.clear();
                t.output_channels.clear();
            })?,
        ),
        (
            "grids",
            without(|t| {
                t.grid_lattice.clear();
                t.grid_layout.clear();
                t.grid_position.clear();
                t.grid_channels.clear();
            })?,
        ),
        (
            "daylight",
            without(|t| {
                t.daylight_site.clear();
                t.sun_lattice.clear();
                t.sun_spacing.clear();
                t.sun_nodes.clear();
                t.daylight_outputs.clear();
                t.daylight_grid.clear();
                t.sun_polygon_counts.clear();
                t.sun_polygon_sizes.clear();
                t.sun_polygons.clear();
                t.sun_glazing.clear();
                t.sensor_response_rows.clear();
                t.sensor_response.clear();
                t.sun_first_patches.clear();
                t.sun_first_sizes.clear();
                t.sun_first_points.clear();
                t.sun_node_power.clear();
            })?,
        ),
    ];
    sections.sort_by(|a, b| b.1.cmp(&a.1).then(a.0.cmp(b.0)));
    Ok(sections)
}
