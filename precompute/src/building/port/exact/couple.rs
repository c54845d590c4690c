//! The merge's side of the exact ports: the cross terms from the rooms' scenes, the coupled
//! system over every room's seen patches, solved per band with a right-hand side per channel
//! of the building, and what it adds to each room's tables (docs/math.md, "Rooms seen through
//! an exact port").

use eigenrad_runtime::sky::patches::SkyPatches;
use eigenrad_runtime::writer::BasisTables;
use faer::linalg::solvers::Solve;
use faer::Mat;

use super::cross::{cross, Link, Middle, Side};
use super::daylight::{self, daylight_columns};
use super::tables::{coupled_tables, without_patches_unless};
use super::{opening_patches, ExactOpening};
use crate::building::error::BuildingError;
use crate::building::manifest::{Manifest, PortModel};
use crate::building::part::{self, Part};
use crate::building::port::{foreign_channel, Coupled};
use crate::scene::Scene;

/// Couples the rooms' `parts` (in the manifest's order of rooms) through the manifest's
/// exact ports, meshing the rooms' scenes again for the cross terms. `dir` is the folder of
/// the parts, for the errors to name them.
pub fn couple(
    manifest: &Manifest,
    parts: &[Part],
    dir: &std::path::Path,
) -> Result<Coupled, BuildingError> {
    let mut coupled = Coupled {
        tables: parts.iter().map(|p| p.tables.clone()).collect(),
    };
    let ports: Vec<usize> = (0..manifest.ports.len())
        .filter(|&p| manifest.ports[p].model == PortModel::Exact)
        .collect();
    if ports.is_empty() {
        return Ok(coupled);
    }
    let rooms = parts.len();
    let part_error = |r: usize, message: String| BuildingError::Part {
        path: part::path(dir, &parts[r].room),
        message,
    };
    // Each part must answer for exactly the manifest's exact ports of its room.
    let wanted = |r: usize| -> Vec<ExactOpening> {
        ports
            .iter()
            .filter_map(|&p| {
                let port = &manifest.ports[p];
                Some(ExactOpening {
                    port: port.name.clone(),
                    surface: port.opening_in(r)?.to_string(),
                })
            })
            .collect()
    };
    let mut scenes: Vec<Option<Scene>> = Vec::with_capacity(rooms);
    for (r, part) in parts.iter().enumerate() {
        let want = wanted(r);
        let held = &part.exact;
        if want != held.openings {
            let list = |l: &[ExactOpening]| {
                if l.is_empty() {
                    "none".to_string()
                } else {
                    l.iter()
                        .map(|o| format!("{} ({})", o.port, o.surface))
                        .collect::<Vec<_>>()
                        .join(", ")
                }
            };
            return Err(part_error(
                r,
                format!(
                    "built with the exact ports {}, but the manifest gives room {} the exact ports {}: build room {} again",
                    list(&held.openings),
                    part.room,
                    list(&want),
                    part.room
                ),
            ));
        }
        if want.is_empty() {
            scenes.push(None);
            continue;
        }
        let room = &manifest.rooms[r];
        let room_error = |reason: crate::Error| BuildingError::Room {
            at: room.at.clone(),
            room: room.name.clone(),
            reason: Box::new(reason),
        };
        // The part's scene hash was checked against the file: the same scene, meshed again.
        let scene = crate::scene::load(&room.scene).map_err(|e| room_error(e.into()))?;
        check_shapes(&scene, part).map_err(|m| part_error(r, m))?;
        if let Some(c) = manifest
            .controllers
            .iter()
            .find(|c| c.room == r && c.modes)
            .filter(|_| part.exact.exitance.is_empty())
        {
            return Err(part_error(
                r,
                format!(
                    "built without the patches' exitance for light entering through its exact ports, which the modes of controller {} need: build room {} again",
                    c.name, part.room
                ),
            ));
        }
        scenes.push(Some(scene));
    }
    let bands = parts[manifest.ports[ports[0]].rooms[0]].tables.bands;
    for &p in &ports {
        let port = &manifest.ports[p];
        for r in port.rooms {
            if parts[r].tables.bands != bands {
                return Err(BuildingError::Manifest {
                    at: port.at.clone(),
                    item: format!("port {}", port.name),
                    message: format!(
                        "joins room {} ({} bands) to rooms of {bands} bands: rooms that share light are solved band by band, so give their scenes the same `bands`",
                        parts[r].room, parts[r].tables.bands
                    ),
                });
            }
        }
    }
    // The cross terms of each port, from its rooms' scenes, by its rooms' rules, and of each
    // two rooms that see each other across a third joined to both.
    let mut links: Vec<Link> = Vec::with_capacity(ports.len());
    let scene_of = |r: usize| {
        scenes[r]
            .as_ref()
            .ok_or_else(|| part_error(r, "has no exact ports".into()))
    };
    // The patches of port `p`'s opening in its room on side `side`.
    let opening_of = |p: usize, side: usize| -> Result<std::ops::Range<usize>, BuildingError> {
        let port = &manifest.ports[p];
        let r = port.rooms[side];
        opening_patches(scene_of(r)?, &port.name, &port.openings[side]).map_err(|e| {
            BuildingError::Room {
                at: manifest.rooms[r].at.clone(),
                room: manifest.rooms[r].name.clone(),
                reason: Box::new(e),
            }
        })
    };
    let side_of = |p: usize, side: usize| -> Result<Side, BuildingError> {
        let r = manifest.ports[p].rooms[side];
        Ok(Side {
            scene: scene_of(r)?,
            opening: opening_of(p, side)?,
            seen: &parts[r].exact.seen,
            outputs: outputs(&parts[r].tables),
            tables: &parts[r].tables,
        })
    };
    for &p in &ports {
        let port = &manifest.ports[p];
        let [a, b] = port.rooms;
        let rules = &parts[a].exact.rules;
        if *rules != parts[b].exact.rules {
            return Err(BuildingError::Manifest {
                at: port.at.clone(),
                item: format!("port {}", port.name),
                message: format!(
                    "joins room {} (its form factors by {rules:?}) to room {} (by {:?}): the light crossing an exact port is integrated as in one room, so build both rooms with the same form-factor options",
                    parts[a].room, parts[b].room, parts[b].exact.rules
                ),
            });
        }
        let sides = [side_of(p, 0)?, side_of(p, 1)?];
        links.push(Link {
            rooms: port.rooms,
            transmittance: port.transmittance,
            term: cross([&sides[0], &sides[1]], None, &rules.options()),
        });
    }
    // Two rooms joined to a third by two ports, and not to each other: what passes through
    // both openings in turn, across the third room.
    for (i, &p) in ports.iter().enumerate() {
        for &q in &ports[i + 1..] {
            let (pr, qr) = (manifest.ports[p].rooms, manifest.ports[q].rooms);
            let Some((sp, sq)) = (0..2)
                .flat_map(|sp| (0..2).map(move |sq| (sp, sq)))
                .find(|&(sp, sq)| pr[sp] == qr[sq])
            else {
                continue;
            };
            let (x, z) = (pr[1 - sp], qr[1 - sq]);
            let joined = |a: usize, b: usize| {
                ports.iter().any(|&k| {
                    let rooms = manifest.ports[k].rooms;
                    rooms == [a, b] || rooms == [b, a]
                })
            };
            if x == z || joined(x, z) {
                continue;
            }
            let sides = [side_of(p, 1 - sp)?, side_of(q, 1 - sq)?];
            let middle = Middle {
                scene: scene_of(pr[sp])?,
                openings: [opening_of(p, sp)?, opening_of(q, sq)?],
            };
            let rules = &parts[x].exact.rules;
            links.push(Link {
                rooms: [x, z],
                transmittance: manifest.ports[p].transmittance * manifest.ports[q].transmittance,
                term: cross([&sides[0], &sides[1]], Some(&middle), &rules.options()),
            });
        }
    }
    // The unknowns: every seen patch's exitance, room by room.
    let offset: Vec<usize> = parts
        .iter()
        .scan(0, |next, part| {
            let first = *next;
            *next += part.exact.seen.len();
            Some(first)
        })
        .collect();
    let unknowns: usize = parts.iter().map(|p| p.exact.seen.len()).sum();
    let first_channel: Vec<usize> = parts
        .iter()
        .scan(0, |next, part| {
            let first = *next;
            *next += part.tables.channel_names.len();
            Some(first)
        })
        .collect();
    let channels: usize = parts.iter().map(|p| p.tables.channel_names.len()).sum();
    let group = super::super::groups(rooms, ports.iter().map(|&p| manifest.ports[p].rooms));
    // Each group's daylight nodes are right-hand sides too, after the building's channels.
    let columns = daylight_columns(manifest, parts, &group, &links, channels)?;
    let sources = columns
        .iter()
        .flatten()
        .map(|c| c.first + c.len())
        .max()
        .unwrap_or(channels)
        .max(channels);
    // The direct light of the luminaires with photometry and the clear windows of each room in
    // the rooms it sees through openings: `lit[r]` on room r's seen patches (seen × sources)
    // and at its outputs (outputs × sources), `None` where none reaches it.
    let mut lit: Vec<Option<(Mat<f64>, Mat<f64>)>> = vec![None; rooms];
    for link in &links {
        for (side, direct) in link.term.direct.iter().enumerate() {
            let Some(direct) = direct else { continue };
            let (from, r) = (link.rooms[side], link.rooms[1 - side]);
            let (seen, read) = lit[r].get_or_insert_with(|| {
                (
                    Mat::zeros(parts[r].exact.seen.len(), sources),
                    Mat::zeros(outputs(&parts[r].tables), sources),
                )
            });
            for (c, (on_seen, at_outputs)) in direct.seen.iter().zip(&direct.outputs).enumerate() {
                let g = first_channel[from] + c;
                for (a, e) in on_seen.iter().enumerate() {
                    seen[(a, g)] += link.transmittance * e;
                }
                for (o, e) in at_outputs.iter().enumerate() {
                    read[(o, g)] += link.transmittance * e;
                }
            }
        }
        // And the daylight of each room's clear windows, node by node.
        for (side, through) in link.term.daylight.iter().enumerate() {
            let r = link.rooms[1 - side];
            let (Some(through), Some(columns)) = (through, &columns[r]) else {
                continue;
            };
            let (seen, read) = lit[r].get_or_insert_with(|| {
                (
                    Mat::zeros(parts[r].exact.seen.len(), sources),
                    Mat::zeros(outputs(&parts[r].tables), sources),
                )
            });
            for (d, (on_seen, at_outputs)) in through.seen.iter().zip(&through.outputs).enumerate()
            {
                let g = columns.column(&through.sun_nodes, d);
                for (a, e) in on_seen.iter().enumerate() {
                    seen[(a, g)] += link.transmittance * e;
                }
                for (o, e) in at_outputs.iter().enumerate() {
                    read[(o, g)] += link.transmittance * e;
                }
            }
        }
    }
    // `coupling(k, r)`: irradiance arriving at room r's seen patch a from the other room of
    // link k per unit exitance of its seen patch v, `τ G_av / A_a`, as a matrix.
    let coupling = |k: usize, r: usize| -> Mat<f64> {
        let link = &links[k];
        let side = usize::from(link.rooms[1] == r);
        let other = link.rooms[1 - side];
        let area = |a: usize| scenes[r].as_ref().map_or(1.0, |s| s.patches[a].area);
        let seen = &parts[r].exact.seen;
        let g = &link.term.exchange;
        Mat::from_fn(seen.len(), parts[other].exact.seen.len(), |a, v| {
            let gav = if side == 0 { g[a][v] } else { g[v][a] };
            link.transmittance * gav / area(seen[a])
        })
    };
    // Per band: the seen patches' exitance `m` (unknowns × sources) and the irradiance each
    // room's seen patches get from outside, `e[r]` (seen × sources).
    let mut exitance: Vec<Mat<f64>> = Vec::with_capacity(bands);
    let mut arriving: Vec<Vec<Mat<f64>>> = Vec::with_capacity(bands);
    for b in 0..bands {
        let mut system = Mat::<f64>::identity(unknowns, unknowns);
        let mut rhs = Mat::<f64>::zeros(unknowns, sources);
        for (r, part) in parts.iter().enumerate() {
            let x = &part.exact;
            for (c, on_seen) in x.channels.get(b).into_iter().flatten().enumerate() {
                for (v, m) in on_seen.iter().enumerate() {
                    rhs[(offset[r] + v, first_channel[r] + c)] = *m;
                }
            }
            // Daylight is photopic: one band.
            if let (0, Some(columns)) = (b, &columns[r]) {
                for (d, on_seen) in x.daylight.iter().enumerate() {
                    let g = columns.column(&part.tables.sun_nodes, d);
                    for (v, m) in on_seen.iter().enumerate() {
                        rhs[(offset[r] + v, g)] = *m;
                    }
                }
            }
        }
        // `H_r[v][i]`: the exitance of room r's seen patch v for irradiance 1 at its seen patch i.
        let response = |r: usize| -> Mat<f64> {
            let x = &parts[r].exact;
            Mat::from_fn(x.seen.len(), x.seen.len(), |v, i| x.seen_exitance[b][i][v])
        };
        // Light arriving straight from another room's luminaires: `H_r E_d` more in `a_r`.
        for (r, lit) in lit.iter().enumerate() {
            if let Some((on_seen, _)) = lit {
                let add = response(r) * on_seen;
                for v in 0..add.nrows() {
                    for g in 0..sources {
                        rhs[(offset[r] + v, g)] += add[(v, g)];
                    }
                }
            }
        }
        for (k, link) in links.iter().enumerate() {
            for r in link.rooms {
                let other = link.rooms[usize::from(link.rooms[0] == r)];
                let x = &parts[r].exact;
                // `m_r − H_r C m_other = a_r`.
                let h = response(r);
                let block = h.as_ref() * coupling(k, r).as_ref();
                for v in 0..x.seen.len() {
                    for w in 0..parts[other].exact.seen.len() {
                        system[(offset[r] + v, offset[other] + w)] -= block[(v, w)];
                    }
                }
            }
        }
        let m = system.partial_piv_lu().solve(rhs.as_ref());
        let mut e: Vec<Mat<f64>> = parts
            .iter()
            .zip(&lit)
            .map(|(p, lit)| match lit {
                Some((on_seen, _)) => on_seen.clone(),
                None => Mat::zeros(p.exact.seen.len(), sources),
            })
            .collect();
        for (k, link) in links.iter().enumerate() {
            for r in link.rooms {
                let other = link.rooms[usize::from(link.rooms[0] == r)];
                let rows = offset[other]..offset[other] + parts[other].exact.seen.len();
                let add = coupling(k, r).as_ref() * m.subrows(rows.start, rows.len());
                for a in 0..add.nrows() {
                    for g in 0..sources {
                        e[r][(a, g)] += add[(a, g)];
                    }
                }
            }
        }
        exitance.push(m);
        arriving.push(e);
    }
    for (r, part) in parts.iter().enumerate() {
        if part.exact.openings.is_empty() {
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
        // The other rooms' seen patches this room's outputs see through its openings.
        let views: Vec<(usize, &Vec<Vec<f64>>, f64)> = links
            .iter()
            .filter_map(|link| {
                let side = link.rooms.iter().position(|&x| x == r)?;
                let other = link.rooms[1 - side];
                Some((other, &link.term.rows[side], link.transmittance))
            })
            .collect();
        let x = &part.exact;
        // What source `g` adds in band `b` at output `o` (sensors, zones, grid points).
        let reading = |b: usize, g: usize, o: usize| -> f64 {
            let reflected: f64 = (0..x.seen.len())
                .map(|a| x.readings[b][a][o] * arriving[b][r][(a, g)])
                .sum();
            let seen_through: f64 = views
                .iter()
                .map(|(other, rows, tau)| {
                    (0..parts[*other].exact.seen.len())
                        .map(|v| tau * rows[o][v] * exitance[b][(offset[*other] + v, g)])
                        .sum::<f64>()
                })
                .sum();
            match &lit[r] {
                Some((_, direct)) => reflected + seen_through + direct[(o, g)],
                None => reflected + seen_through,
            }
        };
        let patch = |b: usize, g: usize, k: usize| -> f64 {
            (0..x.seen.len())
                .map(|a| x.exitance[b][a][k] * arriving[b][r][(a, g)])
                .sum()
        };
        let patch: Option<&dyn Fn(usize, usize, usize) -> f64> =
            (!x.exitance.is_empty()).then_some(&patch);
        let Some(columns) = &columns[r] else {
            let tables = coupled_tables(&part.tables, &kept, &reading, patch);
            coupled.tables[r] = without_patches_unless(patch.is_some(), tables);
            continue;
        };
        // The room's daylight, its own first reflections folded into its modes and readings
        // (the group's nodes have none of this room's first-reflection tables).
        let mut own = part.tables.clone();
        crate::basis::fold_daylight_reflection(&mut own);
        crate::basis::fold_sun_first(&mut own).map_err(|e| BuildingError::Manifest {
            at: manifest.rooms[r].at.clone(),
            item: format!("room {}", part.room),
            message: format!("its sun's first reflection cannot be folded: {e}"),
        })?;
        let mut tables = coupled_tables(&own, &kept, &reading, patch);
        let patch_daylight = |g: usize, k: usize| patch.map_or(0.0, |p| p(0, g, k));
        daylight::coupled(
            &mut tables,
            &own,
            &parts[columns.frame].tables,
            columns,
            &|g, o| reading(0, g, o),
            patch.map(|_| &patch_daylight as &dyn Fn(usize, usize) -> f64),
        );
        coupled.tables[r] = without_patches_unless(patch.is_some(), tables);
    }
    Ok(coupled)
}

/// Rows of outputs of a room's tables: sensors, zones, then grid points.
fn outputs(t: &BasisTables) -> usize {
    t.sensor_names.len() + t.zone_names.len() + t.grid_position.len()
}

/// Whether a part's exact responses fit its scene as meshed again, and its tables: a message
/// for the part's error if not.
fn check_shapes(scene: &Scene, part: &Part) -> Result<(), String> {
    let x = &part.exact;
    let n = scene.patches.len();
    let t = &part.tables;
    let seen_ok = x.seen.windows(2).all(|w| w[0] < w[1]) && x.seen.iter().all(|&k| k < n);
    let bands_ok = [x.channels.len(), x.seen_exitance.len(), x.readings.len()]
        .iter()
        .all(|&l| l == t.bands)
        && (x.exitance.is_empty() || x.exitance.len() == t.bands);
    let s = x.seen.len();
    let sizes_ok = bands_ok
        && (0..t.bands).all(|b| {
            x.channels[b].len() == t.channel_names.len()
                && x.channels[b].iter().all(|c| c.len() == s)
                && x.seen_exitance[b].len() == s
                && x.seen_exitance[b].iter().all(|r| r.len() == s)
                && x.readings[b].len() == s
                && x.readings[b].iter().all(|r| r.len() == outputs(t))
                && x.exitance
                    .get(b)
                    .is_none_or(|e| e.len() == s && e.iter().all(|r| r.len() == n))
        });
    let opening_free = x.openings.iter().all(|o| {
        scene
            .surfaces
            .iter()
            .find(|f| f.name == o.surface)
            .is_some_and(|f| !x.seen.iter().any(|k| f.patch_range.contains(k)))
    });
    // The seen patches' exitance under every daylight node, when the room has daylight.
    let nodes = if scene.site.is_some() && !scene.windows.is_empty() {
        SkyPatches::reinhart(t.sky_subdivision).map_or(usize::MAX, |sky| sky.count() + 1)
            + t.sun_nodes.len()
    } else {
        0
    };
    let daylight_ok = x.daylight.len() == nodes && x.daylight.iter().all(|d| d.len() == s);
    if x.patches != n || !seen_ok || !sizes_ok || !opening_free || !daylight_ok {
        return Err(format!(
            "its responses at its exact ports do not fit its scene as meshed now ({n} patches, the part {}): build room {} again",
            x.patches, part.room
        ));
    }
    Ok(())
}
