//! The cross terms of one exact port, from its two rooms' meshed scenes, or of two rooms
//! that see each other across a third: the exchange areas between the patches of one room and
//! of the other that see the opening, through it, and every output's view of the other
//! room's seen patches, occluded by the rooms' surfaces, and the direct light of each room's
//! luminaires and clear windows in the other (docs/math.md, "Rooms seen through an exact
//! port").

use std::ops::Range;

use eigenrad_runtime::writer::BasisTables;

use super::daylight::{self, BothRooms, Through};
use super::direct::{self, Direct};
use crate::formfactor::{self, FormFactorOptions, Occluders};
use crate::geometry::{Face, Patch};
use crate::scene::receivers::{mean_over_points, receivers, Receiver};
use crate::scene::FieldOfView;
use crate::scene::Scene;

/// One side of an exact port: a room's meshed scene, its opening's patches and its seen
/// patches (ascending indices into the scene's patches), its number of outputs and its
/// part's tables (for its daylight's nodes).
pub(super) struct Side<'a> {
    pub scene: &'a Scene,
    pub opening: Range<usize>,
    pub seen: &'a [usize],
    pub outputs: usize,
    pub tables: &'a BasisTables,
}

/// The cross terms of a port.
pub(super) struct Cross {
    /// `exchange[a][b]`: `G_ab` (m²) between seen patch `a` of the first room and seen patch
    /// `b` of the second, through the opening.
    pub exchange: Vec<Vec<f64>>,
    /// `rows[s][o][v]`: room `s`'s output `o` reads `rows[s][o][v] M_v` (dimensionless) of the
    /// exitance `M_v` of the other room's seen patch `v`.
    pub rows: [Vec<Vec<f64>>; 2],
    /// `direct[s]`: the direct light of side `s`'s luminaires with photometry on the other
    /// side, through the opening (`None` without luminaires).
    pub direct: [Option<Direct>; 2],
    /// `daylight[s]`: the direct daylight of side `s`'s clear windows on the other side,
    /// through the opening (`None` without daylight).
    pub daylight: [Option<Through>; 2],
}

/// The room between the two sides of a [`Link`] across it: its scene and the openings of its
/// ports to the two sides.
pub(super) struct Middle<'a> {
    pub scene: &'a Scene,
    pub openings: [Range<usize>; 2],
}

/// Two rooms that see each other through openings, the cross terms between them: joined by a
/// port, or across a third room joined to both (the light passing through both openings in
/// turn).
pub(super) struct Link {
    /// The two rooms (indices into the manifest's rooms), in the order of the terms' sides.
    pub rooms: [usize; 2],
    /// The share of the light passing: the port's, or the product of the two ports'.
    pub transmittance: f64,
    /// The cross terms.
    pub term: Cross,
}

/// The cross terms between the two sides of a port, or of two rooms across the room `middle`
/// joined to both (whose surfaces then occlude, its two openings left out), with the
/// accuracy of `opts`.
pub(super) fn cross(sides: [&Side; 2], middle: Option<&Middle>, opts: &FormFactorOptions) -> Cross {
    // The rooms' patches as one scene, the openings left out (a hole blocks nothing);
    // `index[s][k]`: patch `k` of side `s` in it (the middle room's last, `index[2]`).
    let mut patches: Vec<Patch> = Vec::new();
    let mut index: [Vec<Option<usize>>; 2] = [Vec::new(), Vec::new()];
    let mut middle_index: Vec<Option<usize>> = Vec::new();
    let mut add = |scene: &Scene, open: &dyn Fn(usize) -> bool, index: &mut Vec<Option<usize>>| {
        for (k, p) in scene.patches.iter().enumerate() {
            if open(k) {
                index.push(None);
            } else {
                index.push(Some(patches.len()));
                patches.push(p.clone());
            }
        }
    };
    for (s, side) in sides.iter().enumerate() {
        add(side.scene, &|k| side.opening.contains(&k), &mut index[s]);
    }
    if let Some(m) = middle {
        add(
            m.scene,
            &|k| m.openings.iter().any(|o| o.contains(&k)),
            &mut middle_index,
        );
    }
    let mut faces: Vec<Face> = Vec::new();
    let scenes = sides
        .iter()
        .zip(&index)
        .map(|(side, index)| (side.scene, index))
        .chain(middle.map(|m| (m.scene, &middle_index)));
    for (scene, index) in scenes {
        for face in &scene.faces {
            let mapped: Vec<usize> = face.patches.clone().filter_map(|k| index[k]).collect();
            // A face is the opening's or none of it: the opening is a surface of its own.
            if let (Some(&first), true) = (mapped.first(), mapped.len() == face.patches.len()) {
                faces.push(Face {
                    polygon: face.polygon.clone(),
                    patches: first..first + mapped.len(),
                });
            }
        }
    }
    let occluders = Occluders::with_faces(&patches, &faces);
    let at = |s: usize, k: usize| index[s][k].expect("a seen patch is no opening's");
    let pairs: Vec<(usize, usize)> = sides[0]
        .seen
        .iter()
        .flat_map(|&a| sides[1].seen.iter().map(move |&b| (a, b)))
        .map(|(a, b)| (at(0, a), at(1, b)))
        .collect();
    let g = formfactor::pair_exchanges(&patches, &occluders, opts, &pairs);
    let width = sides[1].seen.len();
    let exchange: Vec<Vec<f64>> = if width == 0 {
        vec![Vec::new(); sides[0].seen.len()]
    } else {
        g.chunks(width).map(<[f64]>::to_vec).collect()
    };
    let rows = std::array::from_fn(|s| {
        let (own, other) = (sides[s], sides[1 - s]);
        let columns: Vec<usize> = other.seen.iter().map(|&v| at(1 - s, v)).collect();
        // `G` between this side's seen patch `k` and the other's seen patch `v`.
        let between = |k: usize, v: usize| -> f64 {
            own.seen.binary_search(&k).map_or(0.0, |a| {
                if s == 0 {
                    exchange[a][v]
                } else {
                    exchange[v][a]
                }
            })
        };
        receivers(own.scene)
            .take(own.outputs)
            .map(|receiver| match receiver {
                Receiver::Point {
                    position,
                    normal,
                    field,
                } => {
                    let f = formfactor::point_form_factors(
                        position, normal, field, &patches, &occluders,
                    );
                    columns.iter().map(|&u| f[u]).collect()
                }
                Receiver::Surfaces(zone) => {
                    // Σ_k G_kv / Σ_k A_k over the zone's patches, as in one room.
                    let total: f64 = zone.iter().map(|&k| own.scene.patches[k].area).sum();
                    (0..columns.len())
                        .map(|v| zone.iter().map(|&k| between(k, v)).sum::<f64>() / total)
                        .collect()
                }
                Receiver::Points(points) => {
                    // The mean over the points of each one's row, as in one room.
                    let mean = mean_over_points(points, patches.len(), |position, normal| {
                        formfactor::point_form_factors(
                            position,
                            normal,
                            FieldOfView::HEMISPHERE,
                            &patches,
                            &occluders,
                        )
                    });
                    columns.iter().map(|&u| mean[u]).collect()
                }
                Receiver::Plane(cells) => {
                    let f = formfactor::receiver_form_factors(cells, &patches, &occluders, opts);
                    let total: f64 = cells.iter().map(|c| c.area).sum();
                    columns
                        .iter()
                        .map(|&u| {
                            cells
                                .iter()
                                .enumerate()
                                .map(|(r, c)| c.area * f[(r, u)])
                                .sum::<f64>()
                                / total
                        })
                        .collect()
                }
            })
            .collect()
    });
    let direct = std::array::from_fn(|s| {
        direct::through(
            sides[s].scene,
            sides[1 - s],
            &index[1 - s],
            &patches,
            &occluders,
        )
    });
    let both = BothRooms {
        patches: &patches,
        faces: &faces,
        index: &index,
        occluders: &occluders,
    };
    let daylight = std::array::from_fn(|s| daylight::through(sides, s, &both));
    Cross {
        exchange,
        rows,
        direct,
        daylight,
    }
}
