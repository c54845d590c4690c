//! Work planes: upward receivers at a height above a room's floor, over its footprint less a
//! margin, over a task area or over the band around one, and their calculation grid.

use toml::Spanned;

use super::zones::{explicit_spacing, too_many_points};
use crate::geometry::{Patch, Polygon, Vec3};
use crate::memory;
use crate::scene::context::Ctx;
use crate::scene::error::SceneError;
use crate::scene::file::{BandDef, WorkPlaneDef};
use crate::scene::grid::{self, Grid};
use crate::scene::mesh::{estimate, mesh_face};
use crate::scene::{Surface, ZoneKind};

/// Default band left out at the walls, m (EN 12464-1:2021, 4.4: 0.5 m).
pub(crate) const DEFAULT_MARGIN: f64 = 0.5;

/// Receivers of a work plane: upward quads over the room's footprint less the margin (or
/// over its task area), and its calculation grid.
pub(super) fn work_plane(
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
