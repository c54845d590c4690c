//! From a [`Model`] to the runtime's [`BasisTables`]: what the basis stores, table by table.

use eigenrad_runtime::sky::direct::DirectSun;
use eigenrad_runtime::sky::sun_first::SunFirst;
use eigenrad_runtime::writer::BasisTables;
use eigenrad_runtime::{Precision, Quantity};

use crate::radiosity::eigen::Formulation;
use crate::radiosity::model::amplitude_weight;
use crate::radiosity::{LightResponse, Model};
use crate::scene::{Bands, Scene};
use crate::sources::daylight::direct::direct_sun_tables;
use crate::sources::daylight::nodes::DaylightNodes;
use crate::sources::daylight::reflection::first_reflection;
use crate::sources::daylight::sun_first::{
    culling_suns, sun_first_responses, sun_first_tables, zone_sun_tables,
};

/// Fills every table of the basis for the first `p` modes of `model`, section by section of
/// `docs/format.md`.
pub fn basis_tables(scene: &Scene, model: &Model, p: usize, precision: Precision) -> BasisTables {
    let p = model
        .bands
        .iter()
        .map(|b| b.mode_count())
        .max()
        .unwrap_or(0)
        .min(p);
    let quantity = match scene.bands {
        Bands::Photopic => Quantity::Photometric,
        Bands::Rgb => Quantity::Radiometric,
    };
    let mut t = BasisTables {
        surface_names: scene.surfaces.iter().map(|s| s.name.clone()).collect(),
        channel_names: scene.channels.iter().map(|c| c.name.clone()).collect(),
        sensor_names: scene.sensors.iter().map(|s| s.name.clone()).collect(),
        zone_names: scene.zones.iter().map(|z| z.name.clone()).collect(),
        ..BasisTables::new(quantity, model.formulation, precision, model.bands.len(), p)
    };
    let modes = Truncated { model, p };
    eigenvalues(&mut t, &modes);
    patch_tables(&mut t, scene, &modes);
    channel_tables(&mut t, model);
    output_tables(&mut t, scene, &modes);
    t
}

/// The first `p` modes of a model, padded with null modes where a band has fewer.
struct Truncated<'m> {
    model: &'m Model<'m>,
    p: usize,
}

impl Truncated<'_> {
    /// Entry `i` of mode `k` in band `b`; 0 for a padding mode.
    fn mode(&self, b: usize, i: usize, k: usize) -> f64 {
        let v = &self.model.bands[b].modes.vectors;
        if k < v.ncols() {
            v[(i, k)]
        } else {
            0.0
        }
    }
}

/// `eigenvalues`: a band with fewer reflecting patches than p is padded with null modes, zero
/// vectors with μ = 0 (split, c = 0) or λ = 1 (seed, positive as the format requires).
fn eigenvalues(t: &mut BasisTables, modes: &Truncated) {
    let pad = if modes.model.formulation == Formulation::Split {
        0.0
    } else {
        1.0
    };
    for band in &modes.model.bands {
        for k in 0..modes.p {
            t.eigenvalues
                .push(band.modes.values.get(k).copied().unwrap_or(pad));
        }
    }
}

/// Patch tables, the mode vectors and the black patches' projections.
fn patch_tables(t: &mut BasisTables, scene: &Scene, modes: &Truncated) {
    let (model, p) = (modes.model, modes.p);
    let bands = model.bands.len();
    for (i, patch) in scene.patches.iter().enumerate() {
        t.patch_area.push(patch.area);
        t.patch_centroid.push(patch.centroid.to_array());
        t.patch_surface.push(patch.surface as u16);
        t.patch_channel
            .push(scene.channel_of_patch[i].map(|c| c as u16));
        for b in 0..bands {
            t.patch_reflectance.push(model.reflectance(b)[i]);
            // The format gives a patch one channel: its emission is that channel's.
            t.patch_emission
                .push(scene.channel_of_patch[i].map_or(0.0, |c| model.emission(c, b)[i]));
        }
        for b in 0..bands {
            for k in 0..p {
                t.modes.push(modes.mode(b, i, k));
            }
        }
    }
    for j in 0..model.patch_count() {
        if (0..bands).any(|b| model.reflectance(b)[j] == 0.0) {
            for b in 0..bands {
                let mut projection = model.patch_projection(j, b);
                projection.resize(p, 0.0);
                t.black_projection.extend(projection);
            }
        }
    }
}

/// `channel_response`: channels are stored exactly, from the exact solve the model did at
/// build time; any combination of levels is then exact to the storage precision, and the
/// modes serve exitance set patch by patch only.
fn channel_tables(t: &mut BasisTables, model: &Model) {
    let (n, m, bands) = (
        model.patch_count(),
        model.channel_count(),
        model.bands.len(),
    );
    t.channel_response = vec![0.0; n * m * bands];
    for c in 0..m {
        for b in 0..bands {
            for (i, x) in model.channel_response(c, b).iter().enumerate() {
                t.channel_response[i * m * bands + c * bands + b] = *x;
            }
        }
    }
}

/// Sensor geometry, zone areas, and the outputs' modes, exact channel readings and view rows;
/// then the grids: their layout, and their points' positions, modes, readings and view rows.
/// The model's outputs are the sensors, the zones, then the grid points
/// ([`crate::formfactor::outputs`]); the basis keeps the first two in the output tables and
/// the points in the grid tables.
fn output_tables(t: &mut BasisTables, scene: &Scene, modes: &Truncated) {
    let model = modes.model;
    let (n, m, bands) = (
        model.patch_count(),
        model.channel_count(),
        model.bands.len(),
    );
    let outputs = crate::formfactor::outputs::grid_offset(scene);
    for s in &scene.sensors {
        // A response's view ends at its last row.
        let half = s
            .half_angle
            .or(s.response.as_ref().map(|r| r.view_edge()))
            .unwrap_or(std::f64::consts::PI);
        let (x, d) = (s.position, s.normal);
        t.sensor_geometry.push([x.x, x.y, x.z, d.x, d.y, d.z, half]);
    }
    for z in &scene.zones {
        t.zone_area
            .push(crate::formfactor::outputs::zone_area(scene, z));
        let pieces = z.grid.as_ref().map_or(&[][..], |g| &g.pieces);
        t.grid_pieces.push(pieces.len() as u32);
        for g in pieces {
            let kept = g.points.len();
            t.grid_lattice
                .push([g.counts[0] as u32, g.counts[1] as u32, kept as u32]);
            let d = g.normal;
            t.grid_layout
                .push([g.spacing, g.cell[0], g.cell[1], g.border, d.x, d.y, d.z]);
            t.grid_position
                .extend(g.points.iter().map(|p| [p.x, p.y, p.z]));
        }
    }
    let mut row_modes = Vec::new();
    for row in &model.system.output_rows {
        for b in 0..bands {
            for k in 0..modes.p {
                row_modes.push((0..n).map(|j| row[j] * modes.mode(b, j, k)).sum::<f64>());
            }
        }
    }
    let split = outputs * bands * modes.p;
    t.grid_modes = row_modes.split_off(split);
    t.output_modes = row_modes;
    // `O × B × m`: the exact readings of each channel alone at level 1.
    let readings: Vec<Vec<Vec<f64>>> = (0..m)
        .map(|c| (0..bands).map(|b| model.channel_readings(c, b)).collect())
        .collect();
    for o in 0..model.system.output_rows.len() {
        let table = if o < outputs {
            &mut t.output_channels
        } else {
            &mut t.grid_channels
        };
        for b in 0..bands {
            for channel in &readings {
                table.push(channel[b][o]);
            }
        }
    }
    t.output_view = vec![0.0; n * outputs];
    for (o, row) in model.system.output_rows.iter().take(outputs).enumerate() {
        for (j, &v) in row.iter().enumerate() {
            t.output_view[j * outputs + o] = v;
        }
    }
    t.grid_view = model.system.output_rows[outputs..].concat();
}

/// The daylight a basis carries: its nodes, and the room's exact response to each
/// ([`crate::radiosity::System::light_responses`]).
pub struct BasisDaylight {
    /// The nodes: sky patches, the exterior, the sun nodes.
    pub nodes: DaylightNodes,
    /// The exact response to each node alone, in the nodes' order.
    pub responses: Vec<LightResponse>,
    /// Each node's initial exitance, its first reflection (lux per unit of the node;
    /// [`crate::radiosity::System::initial_exitances`]), in the nodes' order.
    pub initial: Vec<Vec<f64>>,
    /// Per patch, whether the sun lights it at the centre of a cell of the sun grid
    /// ([`crate::sources::daylight::sun_first::lit_between_nodes`]); empty unless the basis
    /// stores the sun's first reflection for the controller.
    pub lit_between_nodes: Vec<bool>,
}

/// The daylight section (docs/format.md, "Daylight") of a basis whose other tables `t` holds:
/// the site, the sky and the sun grid, then per node every output's and grid point's exact
/// reading, the first reflection (the sky's to `sky_rank_tolerance`) and the mode amplitudes
/// of what the room reflects after it; with `sun_first`, the patches the sun can light for
/// the controller's first reflection at the sun. Daylight is photopic: one band.
pub fn daylight_tables(
    t: &mut BasisTables,
    scene: &Scene,
    model: &Model,
    daylight: &BasisDaylight,
    (sky_rank_tolerance, sun_first): (f64, bool),
) -> crate::error::Result<()> {
    let Some(site) = &scene.site else {
        return Ok(());
    };
    let nodes = &daylight.nodes;
    let d = nodes.len();
    let outputs = crate::formfactor::outputs::grid_offset(scene);
    let grid = &nodes.sun_grid;
    t.sky_subdivision = nodes.patches.subdivision();
    t.daylight_site = vec![
        site.location.latitude,
        site.location.longitude,
        site.location.elevation,
        site.north,
        f64::from(site.utc_offset.unwrap_or(0)) / 60.0,
    ];
    t.sun_lattice = vec![grid.rows as u32, grid.columns as u32];
    t.sun_spacing = [
        grid.declination_first,
        grid.declination_step,
        grid.hour_first,
        grid.hour_step,
    ]
    .map(f64::from)
    .to_vec();
    t.sun_nodes.clone_from(&nodes.sun_nodes);
    let rows = daylight.responses.first().map_or(0, |r| r.readings.len());
    let column = |row: usize| daylight.responses.iter().map(move |r| r.readings[row]);
    t.daylight_outputs = (0..outputs).flat_map(column).collect();
    t.daylight_grid = (outputs..rows).flat_map(column).collect();
    let exact: Vec<Vec<f64>> = daylight
        .responses
        .iter()
        .map(|r| r.exitance.clone())
        .collect();
    let first_sun = nodes.patches.count() + 1;
    let first = first_reflection(
        model,
        &daylight.initial,
        &exact,
        first_sun,
        t.mode_count,
        sky_rank_tolerance,
    )?;
    t.reflection_rank = vec![first.rank as u32];
    t.sky_reflection_weights = first.sky_weights;
    t.sky_reflection = first.sky;
    t.sun_reflection_counts = first.sun_counts;
    t.sun_reflection_patches = first.sun_patches;
    t.sun_reflection = first.sun_values;
    t.daylight_modes = first.modes;
    debug_assert_eq!(t.daylight_outputs.len(), outputs * d);
    // The patches some stored sun node or the sun at a cell's centre lights directly and
    // that reflect: the candidates of the sun's first reflection on the controller.
    let bands = t.bands.max(1);
    let lit = |i: usize| {
        t.patch_reflectance.get(i * bands).is_some_and(|&r| r > 0.0)
            && (daylight.initial[first_sun..].iter().any(|m0| m0[i] > 0.0)
                || daylight.lit_between_nodes.get(i) == Some(&true))
    };
    let (first_tables, zone_tables) = if sun_first {
        (
            sun_first_tables(&scene.patches, lit),
            zone_sun_tables(scene),
        )
    } else {
        Default::default()
    };
    let patch_suns = culling_suns(site, grid, &nodes.sun_nodes);
    let culling: Vec<_> = [&first_tables.sample_points, &zone_tables.sample_points]
        .into_iter()
        .flatten()
        .copied()
        .collect();
    let direct = direct_sun_tables(scene, site, &culling, &patch_suns);
    t.sun_polygon_counts = direct.counts.to_vec();
    t.sun_polygon_sizes = direct.sizes;
    t.sun_polygons = direct.polygons;
    t.sun_glazing = direct.glazing;
    t.sensor_response_rows = direct.sensor_rows;
    t.sensor_response = direct.sensor_response;
    if !sun_first || t.sun_polygon_counts.is_empty() || nodes.sun_nodes.is_empty() {
        return Ok(split_direct_sun(t, nodes)?);
    }
    t.sun_first_patches = first_tables.patches;
    t.sun_first_sizes = first_tables.sizes;
    t.sun_first_points = first_tables.points;
    t.sun_node_power = vec![0.0; nodes.sun_nodes.len()];
    let readings = scene.sensors.len() + scene.zones.len() + t.grid_position.len();
    t.sun_first_response =
        sun_first_responses(scene, model.system, &t.sun_first_patches, readings)?;
    t.zone_sun_counts = zone_tables.counts;
    t.zone_sun_sizes = zone_tables.sizes;
    t.zone_sun_polygons = zone_tables.polygons;
    split_direct_sun(t, nodes)?;
    Ok(split_first_reflection(t, nodes)?)
}

/// Takes out of every sun node's readings (sensors, zones, grid points) the first reflection
/// of the sun's candidate patches as the controller computes it
/// (`eigenrad_runtime::sky::sun_first`, on the stored tables), and stores each node's
/// first-reflection power `P_c` as it computes it: the node's column then holds the rest
/// `Q`, which the controller interpolates per unit of power and adds to its own first
/// reflection at the sun's direction. At a node `P(s) = P_c` to the bit, so the reading is
/// the exact one to `f32`.
fn split_first_reflection(
    t: &mut BasisTables,
    nodes: &DaylightNodes,
) -> std::result::Result<(), eigenrad_runtime::Error> {
    let bytes = t.to_bytes()?;
    let basis = eigenrad_runtime::Basis::from_bytes(&bytes)?;
    let Some(direct) = DirectSun::new(&basis)? else {
        return Ok(());
    };
    let Some(first) = SunFirst::new(&basis, direct) else {
        return Ok(());
    };
    let d = nodes.len();
    let first_sun = nodes.patches.count() + 1;
    let outputs = basis.sensor_count() + basis.zone_count();
    let points = t.grid_position.len();
    let mut power = Vec::with_capacity(nodes.sun_nodes.len());
    for (i, &node) in nodes.sun_nodes.iter().enumerate() {
        let Some(site) = nodes.sun_grid.direction(node as usize) else {
            power.push(0.0);
            continue;
        };
        let sun = direct.room_direction(site);
        let column = first_sun + i;
        let mut reflected = vec![0.0f32; outputs];
        power.push(f64::from(first.add_outputs(sun, 1.0, &mut reflected)));
        for (o, r) in reflected.iter().enumerate() {
            t.daylight_outputs[o * d + column] -= f64::from(*r);
        }
        for g in 0..points {
            t.daylight_grid[g * d + column] -= f64::from(first.at_grid_point(g, sun));
        }
    }
    t.sun_node_power = power;
    Ok(())
}

/// `t` with the sun's first reflection folded back into its sun nodes' readings: each
/// node's column its reading less the direct sun alone again (format version 7's), and the
/// candidates' tables emptied. For bases whose patches or daylight nodes change (a
/// controller without the room's patches, rooms joined through ports): their sun is then
/// interpolated whole between nodes. Nothing to do without the candidates.
pub fn fold_sun_first(t: &mut BasisTables) -> std::result::Result<(), eigenrad_runtime::Error> {
    if t.sun_node_power.is_empty() {
        return Ok(());
    }
    let bytes = t.to_bytes()?;
    let basis = eigenrad_runtime::Basis::from_bytes(&bytes)?;
    let (Some(direct), Some(grid)) = (DirectSun::new(&basis)?, basis.sun_grid()) else {
        return Ok(());
    };
    let Some(first) = SunFirst::new(&basis, direct) else {
        return Ok(());
    };
    let d = basis.daylight_node_count();
    let first_sun = d - basis.sun_node_count();
    let outputs = basis.sensor_count() + basis.zone_count();
    let points = t.grid_position.len();
    for (i, &node) in t.sun_nodes.clone().iter().enumerate() {
        let Some(site) = grid.direction(node as usize) else {
            continue;
        };
        let sun = direct.room_direction(site);
        let column = first_sun + i;
        let mut reflected = vec![0.0f32; outputs];
        first.add_outputs(sun, 1.0, &mut reflected);
        for (o, r) in reflected.iter().enumerate() {
            t.daylight_outputs[o * d + column] += f64::from(*r);
        }
        for g in 0..points {
            t.daylight_grid[g * d + column] += f64::from(first.at_grid_point(g, sun));
        }
    }
    t.sun_first_patches.clear();
    t.sun_first_sizes.clear();
    t.sun_first_points.clear();
    t.sun_node_power.clear();
    t.sun_first_response.clear();
    t.zone_sun_counts.clear();
    t.zone_sun_sizes.clear();
    t.zone_sun_polygons.clear();
    Ok(())
}

/// `t` with its daylight's first reflection folded into the modes: `daylight_modes` made
/// `p × D` again, each node's amplitudes of its whole exitance (the stored first reflection's
/// projection added to what followed it), and the first reflection's tables emptied. For
/// bases whose daylight nodes change (a building's rooms joined through ports, which add
/// their neighbours' nodes): their patches' daylight then comes through the modes alone, as
/// in format version 6. Nothing to do without a first reflection.
pub fn fold_daylight_reflection(t: &mut BasisTables) {
    let Some(&rank) = t.reflection_rank.first() else {
        return;
    };
    let rank = rank as usize;
    let (n, p) = (t.patch_area.len(), t.mode_count);
    let suns = t.sun_nodes.len();
    let sky = t
        .sky_reflection_weights
        .len()
        .checked_div(rank)
        .unwrap_or(0);
    let d = sky + suns;
    let columns = rank + suns;
    // Daylight is photopic: band 0's modes, `n × p`.
    let weight =
        |j: usize| amplitude_weight(t.formulation, t.patch_area[j], t.patch_reflectance[j]);
    let project = |x: &dyn Fn(usize) -> f64, k: usize| -> f64 {
        (0..n).map(|j| weight(j) * t.modes[j * p + k] * x(j)).sum()
    };
    let mut modes = vec![0.0; p * d];
    let mut first_sun = 0usize;
    let mut sun_starts = Vec::with_capacity(suns);
    for &c in &t.sun_reflection_counts {
        sun_starts.push(first_sun);
        first_sun += c as usize;
    }
    for k in 0..p {
        // Each coefficient's first reflection and what followed it, on mode k.
        let per_coefficient: Vec<f64> = (0..rank)
            .map(|j| {
                project(&|i| t.sky_reflection[i * rank + j], k) + t.daylight_modes[k * columns + j]
            })
            .collect();
        for node in 0..sky {
            modes[k * d + node] = (0..rank)
                .map(|j| per_coefficient[j] * t.sky_reflection_weights[j * sky + node])
                .sum();
        }
        for s in 0..suns {
            let start = sun_starts[s];
            let listed: f64 = (start..start + t.sun_reflection_counts[s] as usize)
                .map(|e| {
                    let i = t.sun_reflection_patches[e] as usize;
                    weight(i) * t.modes[i * p + k] * t.sun_reflection[e]
                })
                .sum();
            modes[k * d + sky + s] = t.daylight_modes[k * columns + rank + s] + listed;
        }
    }
    t.daylight_modes = modes;
    t.reflection_rank.clear();
    t.sky_reflection_weights.clear();
    t.sky_reflection.clear();
    t.sun_reflection_counts.clear();
    t.sun_reflection_patches.clear();
    t.sun_reflection.clear();
}

/// Takes out of every sun node's readings at the sensors and grid points the direct sun the
/// controller computes itself (`eigenrad_runtime::sky::direct`, from the geometry `t`
/// holds), leaving the light the room reflects, which is smooth between nodes: at a node
/// the controller's reading is the exact one to `f32`, and between nodes only the reflected
/// part is interpolated. The direct part is the runtime's own `f32` rule on the stored
/// geometry, so that the host subtracts exactly what the device adds. Zones (area means)
/// keep their whole sun.
fn split_direct_sun(
    t: &mut BasisTables,
    nodes: &DaylightNodes,
) -> std::result::Result<(), eigenrad_runtime::Error> {
    let bytes = t.to_bytes()?;
    let basis = eigenrad_runtime::Basis::from_bytes(&bytes)?;
    let Some(direct) = DirectSun::new(&basis)? else {
        return Ok(());
    };
    let d = nodes.len();
    let first_sun = nodes.patches.count() + 1;
    let (sensors, points) = (basis.sensor_count(), t.grid_position.len());
    for (i, &node) in nodes.sun_nodes.iter().enumerate() {
        let Some(site) = nodes.sun_grid.direction(node as usize) else {
            continue;
        };
        let sun = direct.room_direction(site);
        let column = first_sun + i;
        for s in 0..sensors {
            t.daylight_outputs[s * d + column] -= f64::from(direct.at_sensor(s, sun));
        }
        for g in 0..points {
            t.daylight_grid[g * d + column] -= f64::from(direct.at_grid_point(g, sun));
        }
    }
    Ok(())
}
