//! Work planes: upward receivers at a height above a room's floor, over its footprint less a
//! margin, over a task area or over the band around one, and their calculation grid.

use toml::Spanned;

use super::zones::{explicit_spacing, too_many_points};
use crate::geometry::{Patch, Polygon, Vec3};
use crate::memory;
use crate::scene::context::Ctx;
use crate::scene::error::SceneError;
use crate::scene::file::{AreaDef, BandDef, WorkPlaneDef};
use crate::scene::grid::{self, Grid, PlanRect};
use crate::scene::mesh::{estimate, mesh_face};
use crate::scene::openings::CONTACT_TOLERANCE;
use crate::scene::room::Room;
use crate::scene::{Surface, ZoneKind};

/// Whether the grid point `x` (m) lies strictly inside one of `obstacles` (name, min, max in
/// metres), by more than [`CONTACT_TOLERANCE`] of its diagonal: such points are left out of a
/// grid and counted.
pub(super) fn inside_obstacle(x: Vec3, obstacles: &[(String, Vec3, Vec3)]) -> bool {
    obstacles.iter().any(|(_, lo, hi)| {
        let tol = CONTACT_TOLERANCE * (*hi - *lo).length();
        (0..3).all(|k| x.axis(k) > lo.axis(k) + tol && x.axis(k) < hi.axis(k) - tol)
    })
}

/// Default band left out at the walls, m (EN 12464-1:2021, 4.4: 0.5 m).
pub(crate) const DEFAULT_MARGIN: f64 = 0.5;

/// Receivers of a work plane: upward quads over the room's footprint less the margin (or
/// over its task area), and its calculation grid. Grid points inside one of `obstacles`
/// (name, min, max in metres) are left out and counted.
pub(super) fn work_plane(
    ctx: &Ctx,
    what: &str,
    def: &Spanned<WorkPlaneDef>,
    rooms: &[Room],
    obstacles: &[(String, Vec3, Vec3)],
    surfaces: &[Surface],
    default_edge: f64,
) -> Result<(ZoneKind, Grid), SceneError> {
    let wp = def.get_ref();
    let room = plane_room(ctx, what, def, rooms)?;
    let (lo, hi) = (room.lo, room.hi);
    let height = plane_height(ctx, what, wp, room)?;
    let margin = plane_margin(ctx, what, def, room)?;
    let edge = ctx.optional_length(wp.max_edge.as_ref(), &format!("{what}.work_plane.max_edge"))?;
    let floor = surfaces
        .iter()
        .position(|s| s.name == format!("{}.floor", room.name))
        .unwrap_or(0);
    let z = room.floor + height;
    // A task area is the area itself: no band is left out of it.
    let (inner, border) = match &wp.area {
        Some(area) => (task_area(ctx, what, area, room)?, 0.0),
        None => (
            [lo.x + margin, lo.y + margin, hi.x - margin, hi.y - margin],
            margin,
        ),
    };
    let spacing = explicit_spacing(ctx, what, "work_plane.grid", wp.grid.as_ref())?;
    let rects = plane_rects(ctx, what, wp, room, inner)?;
    check_grid_size(ctx, what, def, &rects, spacing)?;
    // In a plan room the rectangles are the plan's bounding box: only the points inside the
    // plan, `border` or more from its walls, are the plane's.
    let tol = room.tolerance();
    let on_plane = |x: Vec3| {
        room.is_box
            || (room.plan.holds([x.x, x.y], tol)
                && room.plan.distance_to_boundary([x.x, x.y]) >= border - tol)
    };
    let obstructed = |x: Vec3| inside_obstacle(x, obstacles);
    let mut left_out = 0;
    let mut pieces = Vec::new();
    for &[x0, y0, x1, y1] in &rects {
        let rect = grid::horizontal_rect((x0, y0), (x1, y1), z);
        let mut piece = grid::full_lattice(&rect, spacing, border);
        piece.points.retain(|&x| on_plane(x));
        let before = piece.points.len();
        piece.points.retain(|&x| !obstructed(x));
        left_out += before - piece.points.len();
        if !piece.points.is_empty() {
            pieces.push(piece);
        }
    }
    if pieces.is_empty() {
        return Err(SceneError::OutOfRange {
            at: ctx.at(def),
            field: format!("{what}.work_plane"),
            message: format!(
                "no grid point of the plane lies in room `{}` outside its obstacles",
                room.name
            ),
        });
    }
    let grid = Grid {
        pieces,
        obstructed: left_out,
    };
    let edge_used = edge.unwrap_or(default_edge);
    let outlines: Vec<Vec<Vec3>> = if room.is_box || wp.area.is_some() {
        rects.iter().map(|&r| corners(r, z).to_vec()).collect()
    } else {
        inset_pieces(room, margin, z)
    };
    if outlines.is_empty() {
        return Err(SceneError::OutOfRange {
            at: ctx.at(def),
            field: format!("{what}.work_plane.margin"),
            message: format!("leaves nothing of room `{}`", room.name),
        });
    }
    let receivers = outlines.iter().map(|o| estimate(o, edge_used)).sum();
    check_receivers(ctx, what, def, receivers, surfaces)?;
    let kind = ZoneKind::WorkPlane {
        height,
        receivers: mesh_receivers(&outlines, edge_used, floor),
    };
    Ok((kind, grid))
}

/// The plan of `room` less a band of `margin` (m) along its walls, in convex pieces at height
/// `z` (m), facing up: geo's inward buffer (its corners round at the plan's reflex corners,
/// where the band is a quarter circle) cut as the floor is.
fn inset_pieces(room: &Room, margin: f64, z: f64) -> Vec<Vec<Vec3>> {
    room.plan
        .inset(margin, room.tolerance())
        .into_iter()
        .map(|p| p.iter().map(|c| Vec3::new(c[0], c[1], z)).collect())
        .collect()
}

/// The room a work plane lies in: the one it names, or the scene's only room.
fn plane_room<'r>(
    ctx: &Ctx,
    what: &str,
    def: &Spanned<WorkPlaneDef>,
    rooms: &'r [Room],
) -> Result<&'r Room, SceneError> {
    let field = format!("{what}.work_plane.room");
    match &def.get_ref().room {
        Some(name) => rooms
            .iter()
            .find(|r| &r.name == name.get_ref())
            .ok_or_else(|| SceneError::Unknown {
                at: ctx.at(name),
                field: field.clone(),
                kind: "room",
                name: name.get_ref().clone(),
            }),
        None if rooms.len() == 1 => Ok(&rooms[0]),
        None => Err(SceneError::Invalid {
            at: ctx.at(def),
            field,
            message: format!("name the room (the scene has {} rooms)", rooms.len()),
        }),
    }
}

/// The plane's height above the floor of `room`, m: below its ceiling.
fn plane_height(ctx: &Ctx, what: &str, wp: &WorkPlaneDef, room: &Room) -> Result<f64, SceneError> {
    let height = ctx.length(&wp.height, &format!("{what}.work_plane.height"))?;
    if height >= room.lowest_ceiling() - room.floor {
        return Err(SceneError::OutOfRange {
            at: ctx.at(&wp.height),
            field: format!("{what}.work_plane.height"),
            message: format!("must be below the ceiling of room `{}`", room.name),
        });
    }
    Ok(height)
}

/// The band left out at the walls of `room`, m: the plane's `margin` or [`DEFAULT_MARGIN`],
/// leaving something of the room's footprint.
fn plane_margin(
    ctx: &Ctx,
    what: &str,
    def: &Spanned<WorkPlaneDef>,
    room: &Room,
) -> Result<f64, SceneError> {
    let (lo, hi) = (room.lo, room.hi);
    let wp = def.get_ref();
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
            message: format!("leaves nothing of room `{}`", room.name),
        });
    }
    Ok(margin)
}

/// The task area `zone.work_plane.area` (m): a rectangle inside the footprint of `room`.
fn task_area(
    ctx: &Ctx,
    what: &str,
    area: &Spanned<AreaDef>,
    room: &Room,
) -> Result<PlanRect, SceneError> {
    let (name, lo, hi) = (&room.name, room.lo, room.hi);
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
    let inside = lo.x <= min.x
        && lo.y <= min.y
        && max.x <= hi.x
        && max.y <= hi.y
        && room
            .plan
            .holds_rectangle([min.x, min.y], [max.x, max.y], room.tolerance());
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
    Ok([min.x, min.y, max.x, max.y])
}

/// The plane's rectangles: `inner` (the task area, or the room less its margin), or with a
/// `band` the band around it, within the walls of `room`.
fn plane_rects(
    ctx: &Ctx,
    what: &str,
    wp: &WorkPlaneDef,
    room: &Room,
    inner: PlanRect,
) -> Result<Vec<PlanRect>, SceneError> {
    let (name, lo, hi) = (&room.name, room.lo, room.hi);
    let Some(band) = &wp.band else {
        return Ok(vec![inner]);
    };
    let field = format!("{what}.work_plane.band");
    if wp.area.is_none() {
        return Err(SceneError::Invalid {
            at: ctx.at(band),
            field,
            message: "a band surrounds a task area: give `area` too".into(),
        });
    }
    if !room.is_box {
        return Err(SceneError::Invalid {
            at: ctx.at(band),
            field,
            message: format!(
                "a band around a task area is available in box rooms only; room `{name}` is \
                 given by its plan"
            ),
        });
    }
    let [from, to] = band_widths(ctx, band, &field)?;
    let [x0, y0, x1, y1] = inner;
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
    Ok(rects)
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

/// Refuses a plane whose grid over `rects`, at `spacing` or the rule's, would have more than
/// [`grid::MAX_POINTS`] points.
fn check_grid_size(
    ctx: &Ctx,
    what: &str,
    def: &Spanned<WorkPlaneDef>,
    rects: &[PlanRect],
    spacing: Option<f64>,
) -> Result<(), SceneError> {
    let rule = |[x0, y0, x1, y1]: PlanRect| {
        let p = spacing.unwrap_or_else(|| grid::rule_spacing((x1 - x0).max(y1 - y0)));
        let [na, nb] = grid::counts(x1 - x0, y1 - y0, p);
        na.saturating_mul(nb)
    };
    let cells = rects
        .iter()
        .map(|&r| rule(r))
        .fold(0usize, usize::saturating_add);
    if cells > grid::MAX_POINTS {
        let g = def.get_ref().grid.as_ref();
        return Err(too_many_points(
            ctx,
            what,
            "work_plane.grid",
            g,
            ctx.at(def),
            cells,
        ));
    }
    Ok(())
}

/// The corners of a floor-plan rectangle at height `z` (m), counter-clockwise seen from
/// above: facing up.
fn corners([x0, y0, x1, y1]: PlanRect, z: f64) -> [Vec3; 4] {
    [
        Vec3::new(x0, y0, z),
        Vec3::new(x1, y0, z),
        Vec3::new(x1, y1, z),
        Vec3::new(x0, y1, z),
    ]
}

/// The receivers: the convex `outlines` (m, facing up) meshed no longer than `max_edge` (m),
/// each patch counted as lying above the floor surface `floor`.
fn mesh_receivers(outlines: &[Vec<Vec3>], max_edge: f64, floor: usize) -> Vec<Patch> {
    let mut polygons: Vec<Polygon> = Vec::new();
    for o in outlines {
        mesh_face(o, max_edge, &mut polygons);
    }
    polygons.into_iter().map(|p| Patch::new(p, floor)).collect()
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
