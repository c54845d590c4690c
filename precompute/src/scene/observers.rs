//! Sensors and zones: where the results are read.

use toml::Spanned;

use super::context::{resolve_surfaces, unique, Ctx};
use super::error::SceneError;
use super::file::{BandDef, GridDef, SensorDef, WorkPlaneDef, ZoneDef};
use super::grid::{self, Grid};
use super::mesh::{estimate, mesh_face};
use super::openings::CONTACT_TOLERANCE;
use super::{Sensor, Surface, Zone, ZoneKind};
use crate::geometry::{Patch, Polygon, Vec3};
use crate::memory;

/// Reads and checks the sensors; `rooms` and `blocks` are (name, min, max) in metres.
pub(crate) fn sensors(
    ctx: &Ctx,
    defs: &[Spanned<SensorDef>],
    rooms: &[(String, Vec3, Vec3)],
    blocks: &[(String, Vec3, Vec3)],
    extent: Option<(Vec3, Vec3)>,
) -> Result<Vec<Sensor>, SceneError> {
    unique(
        "sensor",
        defs.iter().map(|s| (s.get_ref().name.as_str(), ctx.at(s))),
    )?;
    let mut sensors = Vec::with_capacity(defs.len());
    for def in defs {
        let s = def.get_ref();
        let what = format!("sensor `{}`", s.name);
        let position = ctx.point(&s.position, &format!("{what}.position"))?;
        let n = s.normal.get_ref();
        let normal = Vec3::new(n[0], n[1], n[2]);
        if !(normal.is_finite() && normal.length() > 0.0) {
            return Err(SceneError::Invalid {
                at: ctx.at(&s.normal),
                field: format!("{what}.normal"),
                message: format!("must be a finite, non-zero vector, found {n:?}"),
            });
        }
        let half_angle = match &s.half_angle {
            Some(a) if !(*a.get_ref() > 0.0 && *a.get_ref() <= 90.0) => {
                return Err(SceneError::OutOfRange {
                    at: ctx.at(a),
                    field: format!("{what}.half_angle"),
                    message: format!("must be in (0, 90] degrees, found {}", a.get_ref()),
                })
            }
            Some(a) => Some(a.get_ref().to_radians()),
            None => None,
        };
        let normal = normal.normalized();
        placement(ctx, s, &what, position, normal, rooms, blocks, extent)?;
        sensors.push(Sensor {
            name: s.name.clone(),
            position,
            normal,
            half_angle,
        });
    }

    Ok(sensors)
}

/// In a scene without rooms, how far a sensor may lie from the box around the faces, in
/// diagonals of that box.
const FAR_OUTSIDE: f64 = 10.0;

/// Face names of a box by axis and side (min, max): a room's, then a block's.
const ROOM_FACES: [[&str; 2]; 3] = [
    ["wall_xmin", "wall_xmax"],
    ["wall_ymin", "wall_ymax"],
    ["floor", "ceiling"],
];
const BLOCK_FACES: [[&str; 2]; 3] = [
    ["side_xmin", "side_xmax"],
    ["side_ymin", "side_ymax"],
    ["bottom", "top"],
];

/// Checks that a sensor (position in metres, unit normal) can see the room: it is inside a
/// room (when the scene has rooms) or, in a scene without rooms (OBJ geometry, quads), within
/// [`FAR_OUTSIDE`] diagonals of the box around its faces (`extent`); not inside a block, and not lying on a room or block
/// face while facing into it.
#[allow(clippy::too_many_arguments)]
fn placement(
    ctx: &Ctx,
    s: &SensorDef,
    what: &str,
    p: Vec3,
    n: Vec3,
    rooms: &[(String, Vec3, Vec3)],
    blocks: &[(String, Vec3, Vec3)],
    extent: Option<(Vec3, Vec3)>,
) -> Result<(), SceneError> {
    let written = |v: Vec3| (v / ctx.unit).to_array();
    let position_error = |message: String| SceneError::OutOfRange {
        at: ctx.at(&s.position),
        field: format!("{what}.position"),
        message,
    };
    let facing_error = |face: String| SceneError::Invalid {
        at: ctx.at(&s.normal),
        field: format!("{what}.normal"),
        message: format!(
            "the sensor at {:?} lies on `{face}` and faces into it (normal {:?}): it would see \
             nothing; turn its normal away from that face or move it off the face",
            written(p),
            n.to_array()
        ),
    };
    if let (true, Some((lo, hi))) = (rooms.is_empty(), extent) {
        // Distance from the box around the faces; a sensor may look at a panel from a few of
        // its sizes away, but not from many: that is a unit or `translate` slip.
        let outside = Vec3::new(
            (lo.x - p.x).max(p.x - hi.x).max(0.0),
            (lo.y - p.y).max(p.y - hi.y).max(0.0),
            (lo.z - p.z).max(p.z - hi.z).max(0.0),
        )
        .length();
        let diagonal = (hi - lo).length();
        if outside > FAR_OUTSIDE * diagonal {
            return Err(position_error(format!(
                "{:?} is {:.3e} m from the scene, whose faces span {:?} to {:?}: more than \
                 {FAR_OUTSIDE} times the scene's size (a unit or `translate` mistake?)",
                written(p),
                outside,
                written(lo),
                written(hi)
            )));
        }
    }
    if !rooms.is_empty() {
        let within = |lo: &Vec3, hi: &Vec3, tol: f64| {
            (0..3).all(|k| p.axis(k) >= lo.axis(k) - tol && p.axis(k) <= hi.axis(k) + tol)
        };
        let Some((name, lo, hi)) = rooms
            .iter()
            .find(|(_, lo, hi)| within(lo, hi, CONTACT_TOLERANCE * (*hi - *lo).length()))
        else {
            return Err(position_error(format!(
                "{:?} is outside every room ({}); a sensor there would see nothing of the scene",
                written(p),
                rooms
                    .iter()
                    .map(|(r, lo, hi)| format!(
                        "`{r}` spans {:?} to {:?}",
                        written(*lo),
                        written(*hi)
                    ))
                    .collect::<Vec<_>>()
                    .join("; ")
            )));
        };
        let tol = CONTACT_TOLERANCE * (*hi - *lo).length();
        for k in 0..3 {
            // Room faces look into the room: +axis at the min side, −axis at the max side.
            for (side, plane, inward) in [(0, lo.axis(k), 1.0), (1, hi.axis(k), -1.0)] {
                if (p.axis(k) - plane).abs() <= tol && n.axis(k) * inward < 0.0 {
                    return Err(facing_error(format!("{name}.{}", ROOM_FACES[k][side])));
                }
            }
        }
    }
    for (name, lo, hi) in blocks {
        let tol = CONTACT_TOLERANCE * (*hi - *lo).length();
        let strictly = (0..3).all(|k| p.axis(k) > lo.axis(k) + tol && p.axis(k) < hi.axis(k) - tol);
        if strictly {
            return Err(position_error(format!(
                "{:?} is inside block `{name}` (from {:?} to {:?}): a sensor there would see \
                 nothing",
                written(p),
                written(*lo),
                written(*hi)
            )));
        }
        for k in 0..3 {
            let on_face_extent = (0..3)
                .filter(|&j| j != k)
                .all(|j| p.axis(j) >= lo.axis(j) - tol && p.axis(j) <= hi.axis(j) + tol);
            // Block faces look out of the block: −axis at the min side, +axis at the max side.
            for (side, plane, outward) in [(0, lo.axis(k), -1.0), (1, hi.axis(k), 1.0)] {
                if on_face_extent && (p.axis(k) - plane).abs() <= tol && n.axis(k) * outward < 0.0 {
                    return Err(facing_error(format!("{name}.{}", BLOCK_FACES[k][side])));
                }
            }
        }
    }
    Ok(())
}

/// Reads and checks the zones; `rooms` are (name, min, max) in metres, `patch_list` the
/// scene's patches (the surfaces' `patch_range`s index it), `max_edge` (m) the scene's default.
pub(crate) fn zones(
    ctx: &Ctx,
    defs: &[Spanned<ZoneDef>],
    rooms: &[(String, Vec3, Vec3)],
    surfaces: &[Surface],
    patch_list: &[Patch],
    max_edge: f64,
) -> Result<Vec<Zone>, SceneError> {
    unique(
        "zone",
        defs.iter().map(|z| (z.get_ref().name.as_str(), ctx.at(z))),
    )?;
    let mut zones = Vec::with_capacity(defs.len());
    for def in defs {
        let z = def.get_ref();
        let what = format!("zone `{}`", z.name);
        let (kind, grid) = match (&z.surfaces, &z.work_plane) {
            (Some(refs), None) => {
                let members = resolve_surfaces(ctx, surfaces, refs, &format!("{what}.surfaces"))?;
                if members.is_empty() {
                    return Err(SceneError::Invalid {
                        at: ctx.at(refs),
                        field: format!("{what}.surfaces"),
                        message: "names no surface: a zone averages over at least one".into(),
                    });
                }
                let patches: Vec<usize> = members
                    .iter()
                    .flat_map(|&i| surfaces[i].patch_range.clone())
                    .collect();
                let grid = match &z.grid {
                    Some(g) => Some(surface_grid(ctx, &what, g, &patches, patch_list)?),
                    None => None,
                };
                (ZoneKind::Surfaces(patches), grid)
            }
            (None, Some(wp)) => {
                if let Some(g) = &z.grid {
                    return Err(SceneError::Invalid {
                        at: ctx.at(g),
                        field: format!("{what}.grid"),
                        message: "a work plane's grid is set as `work_plane.grid`".into(),
                    });
                }
                let (kind, grid) = work_plane(ctx, &what, wp, rooms, surfaces, max_edge)?;
                (kind, Some(grid))
            }
            _ => {
                return Err(SceneError::Invalid {
                    at: ctx.at(def),
                    field: what,
                    message: "give exactly one of `surfaces` and `work_plane`".into(),
                })
            }
        };
        zones.push(Zone {
            name: z.name.clone(),
            kind,
            grid,
        });
    }

    Ok(zones)
}

/// Default band left out at the walls, m (EN 12464-1:2021, 4.4: 0.5 m).
pub(crate) const DEFAULT_MARGIN: f64 = 0.5;

/// Receivers of a work plane: upward quads over the room's footprint less the margin (or
/// over its task area), and its calculation grid.
fn work_plane(
    ctx: &Ctx,
    what: &str,
    def: &Spanned<WorkPlaneDef>,
    rooms: &[(String, Vec3, Vec3)],
    surfaces: &[Surface],
    default_edge: f64,
) -> Result<(ZoneKind, Grid), SceneError> {
    let wp = def.get_ref();
    let field = format!("{what}.work_plane.room");
    let room = match &wp.room {
        Some(name) => rooms
            .iter()
            .find(|r| &r.0 == name.get_ref())
            .ok_or_else(|| SceneError::Unknown {
                at: ctx.at(name),
                field: field.clone(),
                kind: "room",
                name: name.get_ref().clone(),
            })?,
        None if rooms.len() == 1 => &rooms[0],
        None => {
            return Err(SceneError::Invalid {
                at: ctx.at(def),
                field,
                message: format!("name the room (the scene has {} rooms)", rooms.len()),
            })
        }
    };
    let (name, lo, hi) = room;
    let height = ctx.length(&wp.height, &format!("{what}.work_plane.height"))?;
    if height >= hi.z - lo.z {
        return Err(SceneError::OutOfRange {
            at: ctx.at(&wp.height),
            field: format!("{what}.work_plane.height"),
            message: format!("must be below the ceiling of room `{name}`"),
        });
    }
    let margin = match &wp.margin {
        Some(m) if !(m.get_ref().is_finite() && *m.get_ref() >= 0.0) => {
            return Err(SceneError::OutOfRange {
                at: ctx.at(m),
                field: format!("{what}.work_plane.margin"),
                message: format!("must be finite and non-negative, found {}", m.get_ref()),
            })
        }
        Some(m) => *m.get_ref() * ctx.unit,
        None => DEFAULT_MARGIN,
    };
    if 2.0 * margin >= (hi.x - lo.x).min(hi.y - lo.y) {
        return Err(SceneError::OutOfRange {
            at: wp
                .margin
                .as_ref()
                .map_or_else(|| ctx.at(def), |m| ctx.at(m)),
            field: format!("{what}.work_plane.margin"),
            message: format!("leaves nothing of room `{name}`"),
        });
    }
    let edge = ctx.optional_length(wp.max_edge.as_ref(), &format!("{what}.work_plane.max_edge"))?;
    let floor = surfaces
        .iter()
        .position(|s| s.name == format!("{name}.floor"))
        .unwrap_or(0);
    let z = lo.z + height;
    let (mut x0, mut y0, mut x1, mut y1) =
        (lo.x + margin, lo.y + margin, hi.x - margin, hi.y - margin);
    let mut border = margin;
    if let Some(area) = &wp.area {
        let field = format!("{what}.work_plane.area");
        let a = area.get_ref();
        let corner = |c: &Spanned<Vec<f64>>, end: &str| match c.get_ref()[..] {
            [x, y] => ctx.coordinates([x, y, 0.0], c, &format!("{field}.{end}")),
            _ => Err(SceneError::BandCount {
                at: ctx.at(c),
                field: format!("{field}.{end}"),
                expected: 2,
                found: c.get_ref().len(),
            }),
        };
        let (min, max) = (corner(&a.min, "min")?, corner(&a.max, "max")?);
        let inside = lo.x <= min.x && lo.y <= min.y && max.x <= hi.x && max.y <= hi.y;
        if !(min.x < max.x && min.y < max.y && inside) {
            return Err(SceneError::OutOfRange {
                at: ctx.at(area),
                field,
                message: format!(
                    "must be a rectangle (min below max) inside room `{name}`'s footprint \
                     {:?} to {:?}, found {:?} to {:?}",
                    [lo.x / ctx.unit, lo.y / ctx.unit],
                    [hi.x / ctx.unit, hi.y / ctx.unit],
                    a.min.get_ref(),
                    a.max.get_ref()
                ),
            });
        }
        // A task area is the area itself: no band is left out of it.
        (x0, y0, x1, y1) = (min.x, min.y, max.x, max.y);
        border = 0.0;
    }
    let spacing = explicit_spacing(ctx, what, "work_plane.grid", wp.grid.as_ref())?;
    // The plane's rectangles: the area (or the room less its margin), or the band around it.
    let rects = match &wp.band {
        None => vec![[x0, y0, x1, y1]],
        Some(band) => {
            let field = format!("{what}.work_plane.band");
            if wp.area.is_none() {
                return Err(SceneError::Invalid {
                    at: ctx.at(band),
                    field,
                    message: "a band surrounds a task area: give `area` too".into(),
                });
            }
            let [from, to] = band_widths(ctx, band, &field)?;
            let grown = |by: f64| {
                [
                    (x0 - by).max(lo.x),
                    (y0 - by).max(lo.y),
                    (x1 + by).min(hi.x),
                    (y1 + by).min(hi.y),
                ]
            };
            let rects = grid::ring(grown(from), grown(to));
            if rects.is_empty() {
                return Err(SceneError::OutOfRange {
                    at: ctx.at(band),
                    field,
                    message: format!("leaves nothing inside room `{name}`'s walls"),
                });
            }
            rects
        }
    };
    let rule = |[x0, y0, x1, y1]: [f64; 4]| {
        let p = spacing.unwrap_or_else(|| grid::rule_spacing((x1 - x0).max(y1 - y0)));
        let [na, nb] = grid::counts(x1 - x0, y1 - y0, p);
        na.saturating_mul(nb)
    };
    let cells = rects
        .iter()
        .map(|&r| rule(r))
        .fold(0usize, usize::saturating_add);
    if cells > grid::MAX_POINTS {
        let g = wp.grid.as_ref();
        return Err(too_many_points(
            ctx,
            what,
            "work_plane.grid",
            g,
            ctx.at(def),
            cells,
        ));
    }
    let grid = Grid {
        pieces: rects
            .iter()
            .map(|&[x0, y0, x1, y1]| grid::horizontal((x0, y0), (x1, y1), z, spacing, border))
            .collect(),
    };
    let edge_used = edge.unwrap_or(default_edge);
    let corners = |[x0, y0, x1, y1]: [f64; 4]| {
        [
            Vec3::new(x0, y0, z),
            Vec3::new(x1, y0, z),
            Vec3::new(x1, y1, z),
            Vec3::new(x0, y1, z),
        ]
    };
    let receivers = rects
        .iter()
        .map(|&r| estimate(&corners(r), edge_used))
        .sum();
    check_receivers(ctx, what, def, receivers, surfaces)?;
    let mut polygons: Vec<Polygon> = Vec::new();
    for &r in &rects {
        mesh_face(&corners(r), edge_used, &mut polygons);
    }
    let kind = ZoneKind::WorkPlane {
        height,
        receivers: polygons.into_iter().map(|p| Patch::new(p, floor)).collect(),
    };
    Ok((kind, grid))
}

/// The widths `[from, to]` of `zone.work_plane.band` in m: a number `w` is `[0, w]`, two
/// numbers the distances from the task area's edges between which the band lies.
fn band_widths(ctx: &Ctx, band: &Spanned<BandDef>, field: &str) -> Result<[f64; 2], SceneError> {
    let [from, to] = match band.get_ref() {
        BandDef::Width(w) => [0.0, *w],
        BandDef::Between(v) => match v[..] {
            [a, b] => [a, b],
            _ => {
                return Err(SceneError::BandCount {
                    at: ctx.at(band),
                    field: field.into(),
                    expected: 2,
                    found: v.len(),
                })
            }
        },
    };
    if !(from.is_finite() && to.is_finite() && 0.0 <= from && from < to) {
        return Err(SceneError::OutOfRange {
            at: ctx.at(band),
            field: field.into(),
            message: format!(
                "must be a width > 0 or two distances 0 ≤ from < to, found {from} to {to}"
            ),
        });
    }
    Ok([from * ctx.unit, to * ctx.unit])
}

/// The spacing a grid's settings `grid` give (`field` under the zone), m, checked; `None`
/// for the rule.
fn explicit_spacing(
    ctx: &Ctx,
    what: &str,
    field: &str,
    grid: Option<&Spanned<GridDef>>,
) -> Result<Option<f64>, SceneError> {
    let Some(s) = grid.and_then(|g| g.get_ref().spacing.as_ref()) else {
        return Ok(None);
    };
    let field = format!("{what}.{field}.spacing");
    let value = ctx.length(s, &field)?;
    if !(value > 0.0 && value <= grid::MAX_SPACING) {
        return Err(SceneError::OutOfRange {
            at: ctx.at(s),
            field,
            message: format!(
                "must be positive and at most {} m, found {}",
                grid::MAX_SPACING,
                s.get_ref()
            ),
        });
    }
    Ok(Some(value))
}

/// The error for a grid of more than [`grid::MAX_POINTS`] cells (`field` under the zone: its
/// settings `grid`), at its spacing if the scene gave one, else at the settings or `fallback`.
fn too_many_points(
    ctx: &Ctx,
    what: &str,
    field: &str,
    grid: Option<&Spanned<GridDef>>,
    fallback: crate::scene::error::Location,
    cells: usize,
) -> SceneError {
    let spacing = grid.and_then(|g| g.get_ref().spacing.as_ref());
    let (at, field) = match (spacing, grid) {
        (Some(s), _) => (ctx.at(s), format!("{what}.{field}.spacing")),
        (None, Some(g)) => (ctx.at(g), format!("{what}.{field}")),
        (None, None) => (fallback, format!("{what}.{field}")),
    };
    SceneError::OutOfRange {
        at,
        field,
        message: format!(
            "gives {cells} points, more than {} a zone may have",
            grid::MAX_POINTS
        ),
    }
}

/// A surface zone's grid (`zone.grid`): one piece per plane of its `patches` (indices into
/// `patch_list`), no border.
fn surface_grid(
    ctx: &Ctx,
    what: &str,
    def: &Spanned<GridDef>,
    patches: &[usize],
    patch_list: &[Patch],
) -> Result<Grid, SceneError> {
    let spacing = explicit_spacing(ctx, what, "grid", Some(def))?;
    let members: Vec<&Patch> = patches.iter().map(|&i| &patch_list[i]).collect();
    let pieces = grid::on_patches(&members, spacing, grid::MAX_POINTS)
        .map_err(|cells| too_many_points(ctx, what, "grid", Some(def), ctx.at(def), cells))?;
    if pieces.is_empty() {
        return Err(SceneError::Invalid {
            at: ctx.at(def),
            field: format!("{what}.grid"),
            message: "no cell centre of the grid lies on the zone's surfaces".into(),
        });
    }
    Ok(Grid { pieces })
}

/// Refuses a work plane whose `receivers` (an estimate) would not fit in memory next to the
/// build of the scene's patches, before it is meshed; names its `max_edge`.
fn check_receivers(
    ctx: &Ctx,
    what: &str,
    def: &Spanned<WorkPlaneDef>,
    receivers: f64,
    surfaces: &[Surface],
) -> Result<(), SceneError> {
    let patches = surfaces.iter().map(|s| s.patch_range.len()).sum::<usize>() as f64;
    let needed = memory::build_bytes(patches, &vec![patches; ctx.bands])
        + memory::receiver_bytes(receivers, patches);
    let available = memory::budget_bytes();
    if needed <= available {
        return Ok(());
    }
    let wp = def.get_ref();
    let (at, field) = match &wp.max_edge {
        Some(e) => (ctx.at(e), format!("{what}.work_plane.max_edge")),
        None => (ctx.at(def), "scene.max_edge".to_string()),
    };
    Err(SceneError::TooManyReceivers {
        at,
        field,
        receivers,
        needed,
        available,
    })
}
