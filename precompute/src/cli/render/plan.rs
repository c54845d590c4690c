//! The plan of `eigenrad render --plan`: the work-plane zones it is of (those named, on one
//! floor, or the scene's only one), and their grids' readings drawn over the rooms' walls and
//! openings, the blocks, the luminaires and the sensors seen from above.

use std::path::Path;

use crate::error::Result;
use crate::geometry::Vec3;
use crate::picture::{Footprint, Plan, PlanGrid, PlanInput};
use crate::pipeline::GridReadout;
use crate::scene::layout::RoomPlan;
use crate::scene::{self, Scene, ZoneKind};

use super::{render_error, total, Readout};

/// The work-plane zones the plan is of: those `asked` (each once, on one floor), or the
/// scene's only zone with a grid.
pub(super) fn plan_zones<'s>(
    scene: &'s Scene,
    path: &Path,
    asked: &[String],
) -> Result<Vec<&'s scene::Zone>> {
    // An imported sensor grid's points face their own ways, in no lattice: not a plan's.
    let planar = |z: &scene::Zone| z.grid.is_some() && !matches!(z.kind, ZoneKind::Points { .. });
    let grids: Vec<&scene::Zone> = scene.zones.iter().filter(|z| planar(z)).collect();
    let names = || {
        grids
            .iter()
            .map(|z| z.name.as_str())
            .collect::<Vec<_>>()
            .join(", ")
    };
    if asked.is_empty() {
        return match grids.as_slice() {
            [one] => Ok(vec![*one]),
            [] => Err(render_error(
                path,
                "no work-plane zone: a plan needs a zone with `work_plane = { ... }` and its calculation grid (docs/scene.md, \"Zones\"); leave out --plan to draw the surfaces only".into(),
            )),
            _ => Err(render_error(
                path,
                format!("{} work-plane zones ({}): name the plan's with --zone (repeatable: zones of one floor are drawn together)", grids.len(), names()),
            )),
        };
    }
    let mut zones: Vec<&scene::Zone> = Vec::new();
    for name in asked {
        let zone = match scene.zones.iter().find(|z| &z.name == name) {
            Some(z) if planar(z) => z,
            Some(z) if z.grid.is_some() => return Err(render_error(
                path,
                format!(
                    "--zone {name}: zone `{name}` is an imported sensor grid, its points in no lattice; a plan needs a work-plane zone ({})",
                    if grids.is_empty() { "the scene has none".into() } else { names() }
                ),
            )),
            Some(_) => return Err(render_error(
                path,
                format!(
                    "--zone {name}: zone `{name}` is a surface zone, without a calculation grid; a plan needs a work-plane zone ({})",
                    if grids.is_empty() { "the scene has none".into() } else { names() }
                ),
            )),
            None => return Err(render_error(
                path,
                format!("--zone {name}: no zone named `{name}` (zones with a grid: {})", if grids.is_empty() { "none".into() } else { names() }),
            )),
        };
        if zones.iter().any(|z| z.name == zone.name) {
            return Err(render_error(path, format!("--zone {name} is named twice")));
        }
        zones.push(zone);
    }
    // One floor: every zone's plane at one height above the floors of rooms at one level.
    let level = |z: &scene::Zone| plane_level(z);
    if let Some(first) = zones.first() {
        for z in &zones[1..] {
            if (level(z) - level(first)).abs() > 1e-6 {
                return Err(render_error(
                    path,
                    format!(
                        "--zone {} and --zone {}: their work planes lie at z = {:.3} m and {:.3} m; a plan draws zones of one floor at one height (draw them apart)",
                        first.name, z.name, level(first), level(z)
                    ),
                ));
            }
        }
    }
    Ok(zones)
}

/// The z of a work-plane zone's plane, m (its grid's first point), NaN without one.
fn plane_level(z: &scene::Zone) -> f64 {
    z.grid
        .as_ref()
        .and_then(|g| g.points().next())
        .map_or(f64::NAN, |(p, _)| p.z)
}
/// The plan of the `zones`' work planes (one floor) from the readings of their calculation
/// grids (one piece each), with the rooms' walls and openings, the blocks standing in them,
/// the luminaires and the sensors seen from above.
pub(super) fn plan_picture(
    scene: &Scene,
    path: &Path,
    zones: &[&scene::Zone],
    readout: &Readout,
    notes: Vec<String>,
) -> Result<Plan> {
    let mut grids = Vec::new();
    let mut floors = Vec::new();
    let mut heights = Vec::new();
    for zone in zones {
        let grid = readout
            .grids
            .iter()
            .find(|g| g.zone == zone.name)
            .ok_or_else(|| {
                render_error(path, format!("zone `{}` has no grid readings", zone.name))
            })?;
        let [piece] = grid.pieces[..] else {
            return Err(render_error(
                path,
                format!(
                    "zone `{}`'s grid has {} pieces (the band around a task area): a plan \
                     draws a grid of one piece, a work plane or a task area",
                    zone.name,
                    grid.pieces.len()
                ),
            ));
        };
        let values: Vec<f64> = grid.points.iter().map(|p| total(&p.irradiance)).collect();
        if let ZoneKind::WorkPlane { height, receivers } = &zone.kind {
            heights.push((zone.name.as_str(), *height));
            floors.extend(receivers.first().map(|r| r.surface));
        }
        grids.push(PlanGrid {
            zone: zone.name.clone(),
            figures: plan_figures(grid, &values, readout.bands.len()),
            counts: piece.counts,
            cell: piece.cell_m,
            border: piece.border_m,
            points: grid
                .points
                .iter()
                .map(|p| [p.position_m[0], p.position_m[1]])
                .collect(),
            values,
        });
    }
    floors.dedup();
    let rooms: Vec<&RoomPlan> = scene
        .layout
        .rooms
        .iter()
        .filter(|r| {
            floors
                .iter()
                .any(|&f| scene.surfaces[f].name == format!("{}.floor", r.name))
        })
        .collect();
    let plane = zones.first().map_or(f64::NAN, |z| plane_level(z));
    let extent = plan_extent(&rooms, &grids);
    let within = |p: [f64; 2]| {
        let pad = 1e-6 + 1e-9 * (extent[1][0] - extent[0][0]).abs();
        p[0] >= extent[0][0] - pad
            && p[0] <= extent[1][0] + pad
            && p[1] >= extent[0][1] - pad
            && p[1] <= extent[1][1] + pad
    };
    let (windows, doors) = wall_openings(scene, &within);
    Ok(Plan::new(PlanInput {
        title: plan_title(scene, &heights, readout.unit),
        notes,
        unit: readout.unit,
        grids,
        room: extent,
        floor: floors
            .iter()
            .flat_map(|&f| floor_patches(scene, f))
            .collect(),
        walls: rooms.iter().map(|r| r.corners.clone()).collect(),
        windows,
        doors,
        blocks: scene
            .layout
            .blocks
            .iter()
            .filter(|b| within([b.min.x, b.min.y]) && within([b.max.x, b.max.y]))
            .map(|b| Footprint {
                corners: [[b.min.x, b.min.y], [b.max.x, b.max.y]],
                through: b.min.z < plane && b.max.z > plane,
            })
            .collect(),
        luminaires: luminaire_outlines(scene),
        luminaire_points: scene
            .luminaires
            .iter()
            .map(|l| [l.position.x, l.position.y])
            .filter(|&p| within(p))
            .collect(),
        sensors: scene
            .sensors
            .iter()
            .map(|s| [s.position.x, s.position.y])
            .filter(|&p| within(p))
            .collect(),
    }))
}

/// The plan's title: the scene, each zone and its plane's height above the floor (left out
/// where it is not a finite number), and what is shown.
fn plan_title(scene: &Scene, heights: &[(&str, f64)], unit: &str) -> String {
    let zones: Vec<String> = heights
        .iter()
        .map(|&(zone, h)| {
            if h.is_finite() {
                format!("{zone} at {h:.2} m above the floor")
            } else {
                zone.to_owned()
            }
        })
        .collect();
    format!("{}: {}, illuminance ({unit})", scene.name, zones.join(", "))
}

/// The drawn extent: the rooms' plans, or the grids' points without rooms (an OBJ floor).
fn plan_extent(rooms: &[&RoomPlan], grids: &[PlanGrid]) -> Extent {
    let mut extent = EMPTY;
    for c in rooms.iter().flat_map(|r| &r.corners) {
        grow(Vec3::new(c[0], c[1], 0.0), &mut extent);
    }
    if extent[0][0] > extent[1][0] {
        for p in grids.iter().flat_map(|g| &g.points) {
            grow(Vec3::new(p[0], p[1], 0.0), &mut extent);
        }
    }
    extent
}

/// Segments seen from above, m.
type Segments = Vec<[[f64; 2]; 2]>;

/// The openings in walls seen from above as segments, m: the windows, and the other openings
/// (doors, wall panels); those `within` the plan only. An opening in a floor or a ceiling
/// (a skylight, a flush luminaire) is not a segment and is left out.
fn wall_openings(scene: &Scene, within: &dyn Fn([f64; 2]) -> bool) -> (Segments, Segments) {
    let segments = |surface: usize| -> Segments {
        scene.patches[scene.surfaces[surface].patch_range.clone()]
            .iter()
            .filter(|p| p.normal.z.abs() < 1e-6)
            .filter_map(|p| {
                // Along the wall: the horizontal direction in the patch's plane.
                let along = Vec3::new(-p.normal.y, p.normal.x, 0.0);
                let key = |v: &&Vec3| along.dot(**v);
                let lo = p
                    .polygon
                    .vertices
                    .iter()
                    .min_by(|a, b| key(a).total_cmp(&key(b)))?;
                let hi = p
                    .polygon
                    .vertices
                    .iter()
                    .max_by(|a, b| key(a).total_cmp(&key(b)))?;
                Some([[lo.x, lo.y], [hi.x, hi.y]])
            })
            .filter(|&[a, b]| within(a) && within(b))
            .collect()
    };
    let glazed: Vec<usize> = scene.windows.iter().map(|w| w.surface).collect();
    let windows = glazed.iter().flat_map(|&s| segments(s)).collect();
    let doors = scene
        .layout
        .openings
        .iter()
        .filter(|s| !glazed.contains(s))
        .filter(|&&s| {
            let range = scene.surfaces[s].patch_range.clone();
            !scene.emission[range].iter().flatten().any(|&e| e > 0.0)
        })
        .flat_map(|&s| segments(s))
        .collect();
    (windows, doors)
}

/// `E_avg`, `E_min`, `E_max` and `U_o` of a plan's `values`: the grid's own for one band, of
/// the bands' sums for several.
fn plan_figures(grid: &GridReadout, values: &[f64], bands: usize) -> [f64; 4] {
    if bands == 1 {
        [
            grid.average[0],
            grid.minimum[0],
            grid.maximum[0],
            grid.uniformity[0],
        ]
    } else {
        match eigenrad_runtime::Figures::of(values.iter().copied()) {
            Some(f) => [f.average, f.minimum, f.maximum, f.uniformity],
            None => [f64::NAN; 4],
        }
    }
}

/// A rectangle in plan, `[[x_min, y_min], [x_max, y_max]]` (m); empty while `x_min > x_max`.
type Extent = [[f64; 2]; 2];

/// No rectangle yet: any point grows it.
const EMPTY: Extent = [[f64::INFINITY; 2], [f64::NEG_INFINITY; 2]];

/// `extent` grown to hold `p` seen from above.
fn grow(p: Vec3, extent: &mut Extent) {
    extent[0] = [extent[0][0].min(p.x), extent[0][1].min(p.y)];
    extent[1] = [extent[1][0].max(p.x), extent[1][1].max(p.y)];
}

/// The patches of the floor surface `floor` seen from above, m.
fn floor_patches(scene: &Scene, floor: usize) -> Vec<Vec<[f64; 2]>> {
    scene.patches[scene.surfaces[floor].patch_range.clone()]
        .iter()
        .map(|p| p.polygon.vertices.iter().map(|v| [v.x, v.y]).collect())
        .collect()
}

/// Luminaires: each emitting surface's patches that face down, seen from above.
fn luminaire_outlines(scene: &Scene) -> Vec<Extent> {
    let mut luminaires = Vec::new();
    for channel in &scene.channels {
        for &s in &channel.surfaces {
            let mut r = EMPTY;
            for p in &scene.patches[scene.surfaces[s].patch_range.clone()] {
                if p.normal.z < -0.5 {
                    for &v in &p.polygon.vertices {
                        grow(v, &mut r);
                    }
                }
            }
            if r[0][0] <= r[1][0] {
                luminaires.push(r);
            }
        }
    }
    luminaires
}
