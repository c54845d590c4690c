//! The daylight of one room's clear windows through an exact port's opening: the illuminance
//! each daylight node puts on the other room's seen patches and at its outputs, straight from
//! the sky, the exterior and the sun through the window and then the hole, occluded by both
//! rooms' surfaces (docs/math.md, "Rooms seen through an exact port"). It is what the
//! one-scene build's daylight code gives those patches and outputs
//! ([`crate::sources::daylight`]), with the same rules, from the two rooms' patches as one
//! scene. The light of diffusing windows is their patches' emission, which the exchange
//! through the opening carries with every other patch's exitance.

use eigenrad_runtime::sky::patches::SkyPatches;
use eigenrad_runtime::sky::sun_grid::SunGrid;
use eigenrad_runtime::writer::BasisTables;
use rayon::prelude::*;

use super::cross::{Link, Side};
use crate::building::error::BuildingError;
use crate::building::manifest::Manifest;
use crate::building::part::Part;
use crate::building::port::couple::DaylightFrame;
use crate::formfactor::Occluders;
use crate::geometry::{Face, Patch};
use crate::radiosity::model::amplitude_weight;
use crate::scene::receivers::{receivers, Receiver};
use crate::scene::{Scene, ZoneKind};
use crate::sources::daylight::nodes::room_sun;
use crate::sources::daylight::{clear_sky_on, clear_sun_on, DaylightOptions};
use crate::sources::ChannelLight;

/// What one room's daylight puts directly on the other room of a port, per node at 1.
pub(super) struct Through {
    /// The sun grid's nodes (`row · columns + column`, ascending) whose sun reaches the
    /// other room through the opening; the nodes are the sky's patches and the exterior
    /// (`sky` of them, the room's own order), then these.
    pub sun_nodes: Vec<u32>,
    /// `seen[d][a]`: illuminance (lux) on the other room's seen patch `a` (its mean).
    pub seen: Vec<Vec<f64>>,
    /// `outputs[d][o]`: at the other room's output `o` (sensors, zones, then grid points).
    pub outputs: Vec<Vec<f64>>,
}

/// The whole scene of a port as the daylight code sees the light of side `from`: both
/// rooms' patches and faces as one scene (the openings left out; `index[s][k]` patch `k` of
/// side `s` in them), `from`'s windows, site and obstructions, and the other side's receivers.
pub(super) struct BothRooms<'a> {
    pub patches: &'a [Patch],
    pub faces: &'a [Face],
    pub index: &'a [Vec<Option<usize>>; 2],
    pub occluders: &'a Occluders,
}

/// The daylight of side `from`'s clear windows on side `1 − from` of a port, through its
/// opening, at every node of `from`'s daylight section as its part's `tables` hold it: the
/// sky's patches and the exterior, and every node of its sun grid above the horizon whose
/// sun reaches the other room. `None` when `from` has no daylight.
pub(super) fn through(sides: [&Side; 2], from: usize, both: &BothRooms) -> Option<Through> {
    let (lit, dark) = (sides[from], sides[1 - from]);
    let tables = lit.tables;
    let site = lit.scene.site.as_ref()?;
    if lit.scene.windows.is_empty() {
        return None;
    }
    let scene = seen_from(lit.scene, from, dark.scene, both);
    // The other room's seen patches and its surface zones' patches receive the light.
    let mut receiving = vec![false; both.patches.len()];
    let mut mark = |k: usize| {
        if let Some(at) = both.index[1 - from][k] {
            receiving[at] = true;
        }
    };
    for &k in dark.seen {
        mark(k);
    }
    for zone in &dark.scene.zones {
        if let ZoneKind::Surfaces(members) = &zone.kind {
            members.iter().for_each(|&k| mark(k));
        }
    }
    let opts = DaylightOptions::default();
    let sky = SkyPatches::reinhart(tables.sky_subdivision.max(1)).ok()?;
    let response = clear_sky_on(&scene, both.occluders, sky, &opts, &receiving);
    let grid = sun_grid(tables)?;
    let suns: Vec<(u32, ChannelLight)> = (0..grid.len())
        .into_par_iter()
        .filter_map(|node| {
            let sun = room_sun(site, grid.direction(node)?)?;
            let light = clear_sun_on(&scene, both.occluders, sun, &opts, &receiving);
            let reaches = light.patch_irradiance[0].iter().any(|&e| e != 0.0)
                || light.output_irradiance[0].iter().any(|&e| e != 0.0);
            reaches.then_some((node as u32, light))
        })
        .collect();
    let mut lights = response.sky;
    lights.push(response.exterior);
    let sun_nodes = suns.iter().map(|(node, _)| *node).collect();
    lights.extend(suns.into_iter().map(|(_, light)| light));
    let all: Vec<Receiver> = receivers(dark.scene).take(dark.outputs).collect();
    let at = |k: usize| both.index[1 - from][k];
    let mut seen = Vec::with_capacity(lights.len());
    let mut outputs = Vec::with_capacity(lights.len());
    for light in &lights {
        let on = &light.patch_irradiance[0];
        let on_patch = |k: usize| at(k).map_or(0.0, |i| on[i]);
        seen.push(dark.seen.iter().map(|&k| on_patch(k)).collect());
        // A surface zone's mean over all its patches, as its room's build takes it (an
        // opening's patch among them reads 0).
        let read: Vec<f64> = all
            .iter()
            .zip(&light.output_irradiance[0])
            .map(|(receiver, &e)| match *receiver {
                Receiver::Surfaces(members) => {
                    let area: f64 = members.iter().map(|&k| dark.scene.patches[k].area).sum();
                    let lumens: f64 = members
                        .iter()
                        .map(|&k| dark.scene.patches[k].area * on_patch(k))
                        .sum();
                    lumens / area
                }
                _ => e,
            })
            .collect();
        outputs.push(read);
    }
    Some(Through {
        sun_nodes,
        seen,
        outputs,
    })
}

/// The sun grid a part's daylight section holds.
pub(super) fn sun_grid(t: &BasisTables) -> Option<SunGrid> {
    let (&[rows, columns], &[declination_first, declination_step, hour_first, hour_step]) =
        (t.sun_lattice.as_slice(), t.sun_spacing.as_slice())
    else {
        return None;
    };
    Some(SunGrid {
        latitude: *t.daylight_site.first()? as f32,
        declination_first: declination_first as f32,
        declination_step: declination_step as f32,
        rows: rows as usize,
        hour_first: hour_first as f32,
        hour_step: hour_step as f32,
        columns: columns as usize,
    })
}

/// The scene `lit` (side `from` of a port) with both rooms' patches and faces in place of its
/// own and the receivers of `dark`, the other side: its windows, site and obstructions light
/// the other room's patches and outputs through the opening.
fn seen_from(lit: &Scene, from: usize, dark: &Scene, both: &BothRooms) -> Scene {
    let n = both.patches.len();
    let bands = lit.bands.count();
    let mut scene = lit.clone();
    scene.patches = both.patches.to_vec();
    scene.faces = both.faces.to_vec();
    scene.reflectance = vec![vec![0.0; bands]; n];
    scene.emission = vec![vec![0.0; bands]; n];
    scene.channel_of_patch = vec![None; n];
    scene.channels.clear();
    scene.luminaires.clear();
    scene.solids.clear();
    // The lit room's surfaces where their patches are now (an opening's is empty).
    for surface in &mut scene.surfaces {
        let range = surface.patch_range.clone();
        let start = range
            .clone()
            .next()
            .and_then(|k| both.index[from][k])
            .unwrap_or(0);
        let len = if range.clone().all(|k| both.index[from][k].is_some()) {
            range.len()
        } else {
            0
        };
        surface.patch_range = start..start + len;
    }
    scene.sensors = dark.sensors.clone();
    scene.zones = dark.zones.clone();
    for zone in &mut scene.zones {
        if let ZoneKind::Surfaces(members) = &mut zone.kind {
            *members = members
                .iter()
                .filter_map(|&k| both.index[1 - from][k])
                .collect();
        }
    }
    scene
}

/// The daylight nodes of a group of rooms joined through exact ports, as columns of the
/// coupled system's right-hand sides (after the building's channels).
#[derive(Clone, Debug)]
pub(super) struct Columns {
    /// The group's first column.
    pub first: usize,
    /// The sky's patches and the exterior: the same nodes in every room of the group.
    pub sky: usize,
    /// Every sun node of the group, ascending: each room's own and those whose sun reaches
    /// a room through an opening.
    pub sun_nodes: Vec<u32>,
    /// The room whose daylight frame (site, sky, sun grid) the group's rooms share.
    pub frame: usize,
}

impl Columns {
    /// The group's number of nodes.
    pub fn len(&self) -> usize {
        self.sky + self.sun_nodes.len()
    }

    /// The column of node `d` of a list of nodes whose sun nodes are `suns` (the sky's and
    /// the exterior's first, as in every room).
    pub fn column(&self, suns: &[u32], d: usize) -> usize {
        if d < self.sky {
            self.first + d
        } else {
            let node = suns[d - self.sky];
            self.first + self.sky + self.sun_nodes.partition_point(|&x| x < node)
        }
    }
}

/// Sets the daylight section of `tables`, a room's coupled tables, to the group's nodes
/// `columns`: the room's own daylight (`own`, its part's tables with the first reflection
/// and the sun's first reflection folded in; none when it has no daylight of its own) at
/// its nodes' columns plus what each column adds through the ports, `reading(g, o)` at output
/// `o` (sensors, zones, then grid points) and `patch(g, k)` to the exitance of patch `k`
/// (`None` when no controller of the room keeps the modes: nothing reads the patches),
/// projected on the modes. The frame (site, sky, sun grid) is `frame`'s.
pub(super) fn coupled(
    tables: &mut BasisTables,
    own: &BasisTables,
    frame: &BasisTables,
    columns: &Columns,
    reading: &dyn Fn(usize, usize) -> f64,
    patch: Option<&dyn Fn(usize, usize) -> f64>,
) {
    let d_all = columns.len();
    let own_nodes = if own.daylight_site.is_empty() {
        0
    } else {
        columns.sky + own.sun_nodes.len()
    };
    // `rows × D` of the room's own daylight (`old`, `rows × own_nodes`) at its columns, with
    // what each column adds at row `o`, `extra(g, o)`.
    let table = |rows: usize, old: &[f64], extra: &dyn Fn(usize, usize) -> f64| {
        let mut out = vec![0.0; rows * d_all];
        for o in 0..rows {
            for d in 0..own_nodes {
                out[o * d_all + columns.column(&own.sun_nodes, d) - columns.first] =
                    old[o * own_nodes + d];
            }
            for c in 0..d_all {
                out[o * d_all + c] += extra(columns.first + c, o);
            }
        }
        out
    };
    let outputs = own.sensor_names.len() + own.zone_names.len();
    let points = own.grid_position.len();
    tables.daylight_outputs = table(outputs, &own.daylight_outputs, &|g, o| reading(g, o));
    tables.daylight_grid = table(points, &own.daylight_grid, &|g, o| reading(g, outputs + o));
    // The modes' amplitudes of each column's exitance entering through the ports (photopic:
    // one band, `n × p` modes), as `Model::mode_amplitudes` takes them.
    let p = own.mode_count;
    let n = own.patch_area.len();
    let amplitudes: Vec<Vec<f64>> = match patch {
        Some(patch) if p > 0 => (0..d_all)
            .map(|c| {
                let m: Vec<f64> = (0..n).map(|k| patch(columns.first + c, k)).collect();
                (0..p)
                    .map(|mode| {
                        (0..n)
                            .map(|j| {
                                amplitude_weight(
                                    own.formulation,
                                    own.patch_area[j],
                                    own.patch_reflectance[j],
                                ) * own.modes[j * p + mode]
                                    * m[j]
                            })
                            .sum()
                    })
                    .collect()
            })
            .collect(),
        _ => Vec::new(),
    };
    // Without a controller keeping the modes nothing reads the patches: the amplitudes of
    // what enters are not computed (`patch` is `None`), the table keeps its shape.
    if p > 0 {
        let old = if own.daylight_modes.is_empty() {
            vec![0.0; p * own_nodes]
        } else {
            own.daylight_modes.clone()
        };
        tables.daylight_modes = table(p, &old, &|g, mode| {
            amplitudes.get(g - columns.first).map_or(0.0, |a| a[mode])
        });
    }
    tables.sky_subdivision = frame.sky_subdivision;
    tables.daylight_site.clone_from(&frame.daylight_site);
    tables.sun_lattice.clone_from(&frame.sun_lattice);
    tables.sun_spacing.clone_from(&frame.sun_spacing);
    tables.sun_nodes.clone_from(&columns.sun_nodes);
}

/// The daylight nodes of each group of rooms joined through exact ports (`group[r]`: the
/// lowest room of room r's group) as columns after the building's `channels`, for every room
/// of a group where some room has daylight: its rooms' own nodes and those whose sun reaches a
/// room through openings (`links`, the cross terms of rooms that see each other). The rooms
/// of a group must share their daylight's frame.
pub(super) fn daylight_columns(
    manifest: &Manifest,
    parts: &[Part],
    group: &[usize],
    links: &[Link],
    channels: usize,
) -> Result<Vec<Option<Columns>>, BuildingError> {
    let rooms = parts.len();
    let mut columns: Vec<Option<Columns>> = vec![None; rooms];
    let mut next = channels;
    for g in (0..rooms).filter(|&r| group[r] == r) {
        let joined = |q: usize| group[q] == g && !parts[q].exact.openings.is_empty();
        let lit: Vec<usize> = (0..rooms)
            .filter(|&q| joined(q) && !parts[q].exact.daylight.is_empty())
            .collect();
        let Some(&first) = lit.first() else {
            continue;
        };
        DaylightFrame::check(manifest, parts, &lit)?;
        let sky = parts[first].exact.daylight.len() - parts[first].tables.sun_nodes.len();
        let mut sun_nodes: Vec<u32> = lit
            .iter()
            .flat_map(|&q| parts[q].tables.sun_nodes.iter().copied())
            .chain(
                links
                    .iter()
                    .filter(|link| joined(link.rooms[0]))
                    .flat_map(|link| link.term.daylight.iter().flatten())
                    .flat_map(|through| through.sun_nodes.iter().copied()),
            )
            .collect();
        sun_nodes.sort_unstable();
        sun_nodes.dedup();
        let group_columns = Columns {
            first: next,
            sky,
            sun_nodes,
            frame: first,
        };
        next += group_columns.len();
        for q in (0..rooms).filter(|&q| joined(q)) {
            columns[q] = Some(group_columns.clone());
        }
    }
    Ok(columns)
}
