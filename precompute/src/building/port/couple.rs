//! The merge's side of the ports: the small system of the exitances entering through every
//! port patch in every direction bin, solved per channel and daylight node of the building, and what it adds to each
//! room's tables (docs/math.md, "Rooms coupled through ports").

use eigenrad_runtime::writer::BasisTables;
use faer::linalg::solvers::Solve;
use faer::Mat;

use super::PortOpening;
use crate::building::error::BuildingError;
use crate::building::manifest::{Manifest, PortModel};
use crate::building::part::Part;
use crate::radiosity::model::amplitude_weight;

/// The two sides of one port patch may lie this far apart and still be one patch, in metres
/// (the openings' corners agree within `PORT_CORNER_TOLERANCE`; meshing them at one edge
/// length puts their patches' centroids together to rounding).
const PATCH_MATCH_TOLERANCE: f64 = 1e-6;

/// One unknown of the port system: the exitance entering room `rooms[side]` of port `port`
/// through its patch `patch` (numbered as in the port's first room) in direction bin `bin`.
#[derive(Clone, Copy, Debug)]
struct Entering {
    port: usize,
    side: usize,
    patch: usize,
    bin: usize,
}

/// What the merge made of the ports: every room's tables with the light its ports bring.
#[derive(Clone, Debug)]
pub struct Coupled {
    /// Per room of the manifest, its tables with every channel of the building whose light
    /// reaches it through ports (named `room/channel`, after the room's own), the responses
    /// of its own channels including the light that comes back through its ports.
    pub tables: Vec<BasisTables>,
}

/// The name a channel of room `room` takes in the tables of another room.
pub fn foreign_channel(room: &str, channel: &str) -> String {
    format!("{room}/{channel}")
}

/// Couples the rooms' `parts` (in the manifest's order of rooms) through the manifest's
/// ports (docs/math.md, "Rooms coupled through ports").
/// `dir` is the folder of the parts, for the errors to name them.
pub fn couple(
    manifest: &Manifest,
    parts: &[Part],
    dir: &std::path::Path,
) -> Result<Coupled, BuildingError> {
    let mut coupled = Coupled {
        tables: parts.iter().map(|p| p.tables.clone()).collect(),
    };
    if manifest.ports.is_empty() {
        return Ok(coupled);
    }
    // A building's ports are all exact or all diffusing (the manifest checks it).
    if manifest.ports[0].model == PortModel::Exact {
        return super::exact::couple(manifest, parts, dir);
    }
    // Each part must answer for exactly the manifest's ports of its room.
    for (r, part) in parts.iter().enumerate() {
        let wanted: Vec<(String, String, usize)> = manifest
            .ports
            .iter()
            .filter_map(|p| Some((p.name.clone(), p.opening_in(r)?.to_string(), p.directions)))
            .collect();
        let held: Vec<(String, String, usize)> = part
            .ports
            .openings
            .iter()
            .map(|o| (o.port.clone(), o.surface.clone(), o.directions))
            .collect();
        if wanted != held {
            let list = |l: &[(String, String, usize)]| {
                if l.is_empty() {
                    "none".to_string()
                } else {
                    l.iter()
                        .map(|(p, s, d)| {
                            let bins = if *d == 1 { "direction" } else { "directions" };
                            format!("{p} ({s}, {d} {bins})")
                        })
                        .collect::<Vec<_>>()
                        .join(", ")
                }
            };
            return Err(BuildingError::Part {
                path: crate::building::part::path(dir, &part.room),
                message: format!(
                    "built with the ports {}, but the manifest gives room {} the ports {}: build room {} again",
                    list(&held),
                    part.room,
                    list(&wanted),
                    part.room
                ),
            });
        }
    }
    // Each part holds its room's openings in the manifest's order of ports (checked above):
    // port `p`'s opening on `side` is the room's opening `slot[p][side]`.
    let slot: Vec<[usize; 2]> = manifest
        .ports
        .iter()
        .enumerate()
        .map(|(p, port)| {
            port.rooms.map(|r| {
                manifest.ports[..p]
                    .iter()
                    .filter(|q| q.rooms.contains(&r))
                    .count()
            })
        })
        .collect();
    let opening = |p: usize, side: usize| -> &PortOpening {
        &parts[manifest.ports[p].rooms[side]].ports.openings[slot[p][side]]
    };
    // Each port's patches in its second room, matched to its first room's.
    let mut matched: Vec<Vec<usize>> = Vec::new();
    for (p, port) in manifest.ports.iter().enumerate() {
        let [x, y] = port.rooms.map(|r| &parts[r].tables);
        if x.bands != y.bands {
            return Err(BuildingError::Manifest {
                at: port.at.clone(),
                item: format!("port {}", port.name),
                message: format!(
                    "joins room {} ({} bands) and room {} ({} bands): rooms that share light are solved band by band, so give their scenes the same `bands`",
                    manifest.rooms[port.rooms[0]].name,
                    x.bands,
                    manifest.rooms[port.rooms[1]].name,
                    y.bands
                ),
            });
        }
        let opening = |side: usize| opening(p, side);
        let (a, b) = (opening(0), opening(1));
        let fail = || {
            BuildingError::Manifest {
            at: port.at.clone(),
            item: format!("port {}", port.name),
            message: format!(
                "its opening is meshed differently in room {} ({} patches) and room {} ({} patches): give the quads {} and {} the same `max_edge` in both scenes, so that each patch of the opening is one patch of both rooms",
                manifest.rooms[port.rooms[0]].name,
                a.area.len(),
                manifest.rooms[port.rooms[1]].name,
                b.area.len(),
                a.surface,
                b.surface
            ),
        }
        };
        if a.area.len() != b.area.len() {
            return Err(fail());
        }
        let mut order = Vec::with_capacity(a.area.len());
        for (j, ca) in a.centroid.iter().enumerate() {
            let near =
                |cb: &[f64; 3]| (0..3).all(|x| (ca[x] - cb[x]).abs() <= PATCH_MATCH_TOLERANCE);
            let k = b.centroid.iter().position(near).ok_or_else(fail)?;
            if (a.area[j] - b.area[k]).abs() > 1e-9 * a.area[j] {
                return Err(fail());
            }
            order.push(k);
        }
        matched.push(order);
    }
    // Where bin `bin` of patch `j` of port `p` (numbered as in its first room) lies among the
    // slots of its room on `side`.
    let local = |p: usize, side: usize, j: usize, bin: usize| -> usize {
        let ports = &parts[manifest.ports[p].rooms[side]].ports;
        let patch = if side == 0 { j } else { matched[p][j] };
        ports.first_slot(slot[p][side]) + patch * manifest.ports[p].directions + bin
    };
    let unknowns: Vec<Entering> = manifest
        .ports
        .iter()
        .enumerate()
        .flat_map(|(p, _)| {
            let patches = matched[p].len();
            let bins = manifest.ports[p].directions;
            (0..2).flat_map(move |side| {
                (0..patches).flat_map(move |patch| {
                    (0..bins).map(move |bin| Entering {
                        port: p,
                        side,
                        patch,
                        bin,
                    })
                })
            })
        })
        .collect();
    let rooms = parts.len();
    let group = super::groups(rooms, manifest.ports.iter().map(|p| p.rooms));
    let first_channel: Vec<usize> = parts
        .iter()
        .scan(0, |next, part| {
            let first = *next;
            *next += part.tables.channel_names.len();
            Some(first)
        })
        .collect();
    let channels: usize = parts.iter().map(|p| p.tables.channel_names.len()).sum();
    // Each room's daylight nodes are right-hand sides too, after the building's channels.
    let first_node: Vec<usize> = parts
        .iter()
        .scan(channels, |next, part| {
            let first = *next;
            *next += part.ports.daylight.len();
            Some(first)
        })
        .collect();
    let sources = channels + parts.iter().map(|p| p.ports.daylight.len()).sum::<usize>();
    let bands = parts.iter().map(|p| p.tables.bands).max().unwrap_or(1);
    let u_count = unknowns.len();
    // `entering[b]`: u × sources, the exitance entering through each slot per channel
    // of the building at level 1 (and, in the photopic band, per daylight node at 1).
    let mut entering = Vec::with_capacity(bands);
    for b in 0..bands {
        let mut system = Mat::<f64>::identity(u_count, u_count);
        let mut rhs = Mat::<f64>::zeros(u_count, sources);
        for (row, u) in unknowns.iter().enumerate() {
            let port = &manifest.ports[u.port];
            let from_side = 1 - u.side;
            let from = port.rooms[from_side];
            if b >= parts[from].tables.bands {
                // A band the rooms of this port do not have (joined rooms share their bands):
                // nothing enters.
                continue;
            }
            let ports = &parts[from].ports;
            // Light keeps its direction through the opening: bin `u.bin` of what leaves the
            // other room is bin `u.bin` of what enters this one.
            let j = local(u.port, from_side, u.patch, u.bin);
            let factor = port.transmittance / opening(u.port, 0).area[u.patch];
            for c in 0..parts[from].tables.channel_names.len() {
                rhs[(row, first_channel[from] + c)] = factor * ports.leaving[b][c][j];
            }
            if b == 0 {
                for (d, flux) in ports.daylight.iter().enumerate() {
                    rhs[(row, first_node[from] + d)] = factor * flux[j];
                }
            }
            for (col, v) in unknowns.iter().enumerate() {
                if manifest.ports[v.port].rooms[v.side] == from {
                    let i = local(v.port, v.side, v.patch, v.bin);
                    system[(row, col)] -= factor * ports.returned[b][i][j];
                }
            }
        }
        entering.push(system.partial_piv_lu().solve(rhs.as_ref()));
    }
    for (r, part) in parts.iter().enumerate() {
        let into: Vec<(usize, usize)> = unknowns
            .iter()
            .enumerate()
            .filter(|(_, u)| manifest.ports[u.port].rooms[u.side] == r)
            .map(|(row, u)| (row, local(u.port, u.side, u.patch, u.bin)))
            .collect();
        if into.is_empty() {
            continue;
        }
        // The room's channels, then every other joined room's, in the manifest's order.
        let mut kept: Vec<(usize, String)> = (0..part.tables.channel_names.len())
            .map(|c| (first_channel[r] + c, part.tables.channel_names[c].clone()))
            .collect();
        for (q, other) in parts.iter().enumerate() {
            if q != r && group[q] == group[r] {
                for (c, name) in other.tables.channel_names.iter().enumerate() {
                    let foreign = foreign_channel(&other.room, name);
                    if part.tables.channel_names.contains(&foreign) {
                        return Err(BuildingError::Manifest {
                            at: manifest.rooms[r].at.clone(),
                            item: format!("room {}: channel {foreign}", part.room),
                            message: format!(
                                "is also the name channel {name} of room {}, joined to this room through ports, takes here: rename one of them",
                                other.room
                            ),
                        });
                    }
                    kept.push((first_channel[q] + c, foreign));
                }
            }
        }
        // The joined rooms' daylight nodes are added here to this room's: its patches'
        // daylight then comes through the modes alone (its first reflection folded in).
        let mut folded = part.tables.clone();
        crate::basis::fold_daylight_reflection(&mut folded);
        // Its sun nodes' readings whole again: the neighbours' nodes have no candidates.
        crate::basis::fold_sun_first(&mut folded).map_err(|e| BuildingError::Manifest {
            at: manifest.rooms[r].at.clone(),
            item: format!("room {}", part.room),
            message: format!("its sun's first reflection cannot be folded: {e}"),
        })?;
        let t = &folded;
        let bands = t.bands;
        let own = t.channel_names.len();
        let outputs = t.sensor_names.len() + t.zone_names.len();
        let points = t.grid_position.len();
        let n = t.patch_area.len();
        let ports = &part.ports;
        // What the exitance entering through the room's slots for source `g` (a column of
        // `entering`) adds in band `b` where the room's response to unit exitance entering
        // through its slot `i` (a port patch, in one direction bin) is `through(i)`.
        let through_ports = |b: usize, g: usize, through: &dyn Fn(usize) -> f64| -> f64 {
            into.iter()
                .map(|&(row, i)| through(i) * entering[b][(row, g)])
                .sum()
        };
        // Column `kc` of `kept` at one output or patch in band `b`: the room's own response
        // there (`own_value`, 0 for another room's channel) plus what the channel's light
        // entering through the ports gives.
        let value = |own_value: f64, b: usize, kc: usize, through: &dyn Fn(usize) -> f64| -> f64 {
            own_value + through_ports(b, kept[kc].0, through)
        };
        let table = |rows: usize, offset: usize, old: &[f64]| -> Vec<f64> {
            let mut out = Vec::with_capacity(rows * bands * kept.len());
            for o in 0..rows {
                for b in 0..bands {
                    for kc in 0..kept.len() {
                        let own_value = if kc < own {
                            old[(o * bands + b) * own + kc]
                        } else {
                            0.0
                        };
                        out.push(value(own_value, b, kc, &|i| {
                            ports.readings[b][i][offset + o]
                        }));
                    }
                }
            }
            out
        };
        let mut tables = t.clone();
        tables.output_channels = table(outputs, 0, &t.output_channels);
        tables.grid_channels = table(points, outputs, &t.grid_channels);
        if !t.channel_response.is_empty() {
            let mut response = Vec::with_capacity(n * kept.len() * bands);
            for k in 0..n {
                for kc in 0..kept.len() {
                    for b in 0..bands {
                        let own_value = if kc < own {
                            t.channel_response[k * own * bands + kc * bands + b]
                        } else {
                            0.0
                        };
                        response.push(value(own_value, b, kc, &|i| ports.exitance[b][i][k]));
                    }
                }
            }
            tables.channel_response = response;
        }
        tables.channel_names = kept.into_iter().map(|(_, name)| name).collect();
        // The daylight of every joined room that has daylight, this room's own included
        // (what leaves through a port and comes back).
        let lit: Vec<usize> = (0..rooms)
            .filter(|&q| group[q] == group[r] && !parts[q].ports.daylight.is_empty())
            .collect();
        if let Some(&first) = lit.first() {
            DaylightFrame::check(manifest, parts, &lit)?;
            // The sky's patches and the exterior, the same nodes in every joined room.
            let sky_nodes = parts[first].ports.daylight.len() - parts[first].tables.sun_nodes.len();
            // Every joined room's sun nodes: a neighbour's sun lights this room through the
            // ports at nodes where it reaches none of this room's own surfaces.
            let mut sun_nodes: Vec<u32> = lit
                .iter()
                .flat_map(|&q| parts[q].tables.sun_nodes.iter().copied())
                .collect();
            sun_nodes.sort_unstable();
            sun_nodes.dedup();
            let d_all = sky_nodes + sun_nodes.len();
            // Column of node `d` of room `q`'s daylight among the joined nodes.
            let column = |q: usize, d: usize| -> usize {
                if d < sky_nodes {
                    d
                } else {
                    let node = parts[q].tables.sun_nodes[d - sky_nodes];
                    sky_nodes + sun_nodes.partition_point(|&x| x < node)
                }
            };
            let own_nodes = ports.daylight.len();
            // `rows × D` of this room's own daylight (`old`, empty without) with every joined
            // room's daylight entering through the ports added, where row `o`'s response to
            // unit exitance entering through slot `i` is `response(i, o)`.
            let daylight = |rows: usize, old: &[f64], response: &dyn Fn(usize, usize) -> f64| {
                let mut out = vec![0.0; rows * d_all];
                for o in 0..rows {
                    for d in 0..own_nodes {
                        out[o * d_all + column(r, d)] = old[o * own_nodes + d];
                    }
                    for &q in &lit {
                        for d in 0..parts[q].ports.daylight.len() {
                            out[o * d_all + column(q, d)] +=
                                through_ports(0, first_node[q] + d, &|i| response(i, o));
                        }
                    }
                }
                out
            };
            let reading =
                |offset: usize| move |i: usize, o: usize| ports.readings[0][i][offset + o];
            tables.daylight_outputs = daylight(outputs, &t.daylight_outputs, &reading(0));
            tables.daylight_grid = daylight(points, &t.daylight_grid, &reading(outputs));
            // The daylight's mode amplitudes (photopic: one band, `n × p` modes), with those
            // of the exitance the daylight entering through the ports gives: the amplitudes of
            // each port patch's response `N` (as `Model::mode_amplitudes` takes them).
            let p = t.mode_count;
            let entering_amplitudes: Vec<Vec<f64>> = (0..ports.exitance[0].len())
                .map(|i| {
                    (0..p)
                        .map(|k| {
                            (0..n)
                                .map(|j| {
                                    amplitude_weight(
                                        t.formulation,
                                        t.patch_area[j],
                                        t.patch_reflectance[j],
                                    ) * t.modes[j * p + k]
                                        * ports.exitance[0][i][j]
                                })
                                .sum()
                        })
                        .collect()
                })
                .collect();
            tables.daylight_modes =
                daylight(p, &t.daylight_modes, &|i, k| entering_amplitudes[i][k]);
            let from = &parts[first].tables;
            tables.sky_subdivision = from.sky_subdivision;
            tables.daylight_site.clone_from(&from.daylight_site);
            tables.sun_lattice.clone_from(&from.sun_lattice);
            tables.sun_spacing.clone_from(&from.sun_spacing);
            tables.sun_nodes = sun_nodes;
        }
        coupled.tables[r] = tables;
    }
    Ok(coupled)
}

/// What a room's daylight nodes are: its site, its sky's patches and its sun grid. Rooms
/// joined through ports must agree on it for their daylight to be added node by node.
#[derive(PartialEq)]
pub(super) struct DaylightFrame<'a> {
    sky_subdivision: u8,
    site: &'a [f64],
    sun_lattice: &'a [u32],
    sun_spacing: &'a [f64],
}

impl DaylightFrame<'_> {
    /// Whether the rooms `lit` (indices into `parts`, the first their reference) share one
    /// frame: an error naming the first room that does not.
    pub(super) fn check(
        manifest: &Manifest,
        parts: &[Part],
        lit: &[usize],
    ) -> Result<(), BuildingError> {
        let Some(&first) = lit.first() else {
            return Ok(());
        };
        let frame = DaylightFrame::of(&parts[first]);
        match lit.iter().find(|&&q| DaylightFrame::of(&parts[q]) != frame) {
            None => Ok(()),
            Some(&q) => Err(BuildingError::Manifest {
                at: manifest.rooms[q].at.clone(),
                item: format!("room {}", parts[q].room),
                message: format!(
                    "its daylight (the site, the sky's patches or the sun grid) differs from room {}'s, which ports join to it: daylight crossing a port is read under one sky, so give the rooms' scenes the same [site] and build them with the same sun grid",
                    parts[first].room
                ),
            }),
        }
    }
}

impl<'a> DaylightFrame<'a> {
    /// The frame of `part`'s daylight.
    pub(super) fn of(part: &'a Part) -> Self {
        let t = &part.tables;
        DaylightFrame {
            sky_subdivision: t.sky_subdivision,
            site: &t.daylight_site,
            sun_lattice: &t.sun_lattice,
            sun_spacing: &t.sun_spacing,
        }
    }
}
