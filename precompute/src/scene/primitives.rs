//! Built-in geometry: `quad`, `block` (a box seen from outside) and the faces of a box, which
//! rooms (`super::room`) are laid out from. z is up.

use toml::Spanned;

use super::context::{Ctx, RawSurface};
use super::error::SceneError;
use super::file::{BlockDef, PolygonDef, QuadDef, Xyz};
use super::room::Room;
use crate::geometry::Vec3;

/// The six faces of an axis-aligned box, each wound so that its normal points *into* the box:
/// (room suffix, block suffix, corners).
pub(crate) fn box_faces(lo: Vec3, hi: Vec3) -> [(&'static str, &'static str, [Vec3; 4]); 6] {
    let (x0, y0, z0, x1, y1, z1) = (lo.x, lo.y, lo.z, hi.x, hi.y, hi.z);
    let p = Vec3::new;
    [
        (
            "floor",
            "bottom",
            [p(x0, y0, z0), p(x1, y0, z0), p(x1, y1, z0), p(x0, y1, z0)],
        ),
        (
            "ceiling",
            "top",
            [p(x0, y0, z1), p(x0, y1, z1), p(x1, y1, z1), p(x1, y0, z1)],
        ),
        (
            "wall_xmin",
            "side_xmin",
            [p(x0, y0, z0), p(x0, y1, z0), p(x0, y1, z1), p(x0, y0, z1)],
        ),
        (
            "wall_xmax",
            "side_xmax",
            [p(x1, y0, z0), p(x1, y0, z1), p(x1, y1, z1), p(x1, y1, z0)],
        ),
        (
            "wall_ymin",
            "side_ymin",
            [p(x0, y0, z0), p(x0, y0, z1), p(x1, y0, z1), p(x1, y0, z0)],
        ),
        (
            "wall_ymax",
            "side_ymax",
            [p(x0, y1, z0), p(x1, y1, z0), p(x1, y1, z1), p(x0, y1, z1)],
        ),
    ]
}

/// Reads and checks a box's `min` and `max` corners (metres), `min < max` on every axis.
pub(crate) fn box_corners(
    ctx: &Ctx,
    what: &str,
    min: &Spanned<Xyz>,
    max: &Spanned<Xyz>,
) -> Result<(Vec3, Vec3), SceneError> {
    let lo = ctx.point(min, &format!("{what}.min"))?;
    let hi = ctx.point(max, &format!("{what}.max"))?;
    for axis in 0..3 {
        if lo.axis(axis) >= hi.axis(axis) {
            return Err(SceneError::OutOfRange {
                at: ctx.at(max),
                field: format!("{what}.max"),
                message: format!(
                    "every coordinate of `max` must exceed that of `min` ({} is not above {})",
                    hi.axis(axis) / ctx.unit,
                    lo.axis(axis) / ctx.unit
                ),
            });
        }
    }
    Ok((lo, hi))
}

/// A block: faces named `<block>.top`, `.bottom`, `.side_xmin` ... `.side_ymax`, facing
/// outwards; `bottom = false` leaves out the bottom, `top = false` the top.
pub(crate) fn block(ctx: &Ctx, def: &Spanned<BlockDef>) -> Result<Vec<RawSurface>, SceneError> {
    let b = def.get_ref();
    let what = format!("block `{}`", b.name);
    let (lo, hi) = box_corners(ctx, &what, &b.min, &b.max)?;
    let max_edge = ctx.optional_length(b.max_edge.as_ref(), &format!("{what}.max_edge"))?;
    Ok(box_faces(lo, hi)
        .into_iter()
        .filter(|(_, suffix, _)| (b.bottom || *suffix != "bottom") && (b.top || *suffix != "top"))
        .map(|(_, suffix, mut corners)| {
            corners.reverse();
            RawSurface {
                name: format!("{}.{suffix}", b.name),
                material: b.material.get_ref().clone(),
                material_at: ctx.at(&b.material),
                faces: vec![corners.to_vec()],
                max_edge,
                at: ctx.at(def),
                exterior: b.exterior,
            }
        })
        .collect())
}

/// A quad: one face, corners counter-clockwise seen from the front.
pub(crate) fn quad(ctx: &Ctx, def: &Spanned<QuadDef>) -> Result<RawSurface, SceneError> {
    let q = def.get_ref();
    let what = format!("quad `{}`", q.name);
    if q.corners.get_ref().len() != 4 {
        return Err(SceneError::Invalid {
            at: ctx.at(&q.corners),
            field: format!("{what}.corners"),
            message: format!(
                "a quad has 4 corners, found {}; write other polygons as a [[polygon]]",
                q.corners.get_ref().len()
            ),
        });
    }
    let mut corners = Vec::with_capacity(4);
    for c in q.corners.get_ref() {
        corners.push(ctx.coordinates(**c, &q.corners, &format!("{what}.corners"))?);
    }
    Ok(RawSurface {
        name: q.name.clone(),
        material: q.material.get_ref().clone(),
        material_at: ctx.at(&q.material),
        faces: vec![corners],
        max_edge: ctx.optional_length(q.max_edge.as_ref(), &format!("{what}.max_edge"))?,
        at: ctx.at(&q.corners),
        exterior: q.exterior,
    })
}

/// A polygon: one face of three or more corners, counter-clockwise seen from the front
/// (checked planar and convex with every other face before meshing, and as an opening where
/// it is one).
pub(crate) fn polygon(ctx: &Ctx, def: &Spanned<PolygonDef>) -> Result<RawSurface, SceneError> {
    let p = def.get_ref();
    let field = format!("polygon `{}`.vertices", p.name);
    let written = p.vertices.get_ref();
    if written.len() < 3 {
        return Err(SceneError::Invalid {
            at: ctx.at(&p.vertices),
            field,
            message: format!("a polygon has at least 3 vertices, found {}", written.len()),
        });
    }
    let mut corners = Vec::with_capacity(written.len());
    for c in written {
        corners.push(ctx.coordinates(**c, &p.vertices, &field)?);
    }
    Ok(RawSurface {
        name: p.name.clone(),
        material: p.material.get_ref().clone(),
        material_at: ctx.at(&p.material),
        faces: vec![corners],
        max_edge: ctx.optional_length(
            p.max_edge.as_ref(),
            &format!("polygon `{}`.max_edge", p.name),
        )?,
        at: ctx.at(&p.vertices),
        exterior: p.exterior,
    })
}

/// Checks that a block (`lo`..`hi`, metres) stands inside one of the rooms, if the scene has
/// any: a block reaching through a wall would put faces outside the room, facing away from it.
pub(crate) fn check_inside_rooms(
    ctx: &Ctx,
    def: &Spanned<BlockDef>,
    lo: Vec3,
    hi: Vec3,
    rooms: &[Room],
) -> Result<(), SceneError> {
    let b = def.get_ref();
    if let Some(room) = rooms.iter().find(|r| r.holds_box(lo, hi)) {
        let flush = [[lo.x, lo.y], [hi.x, lo.y], [hi.x, hi.y], [lo.x, hi.y]]
            .iter()
            .all(|&c| (hi.z - room.ceiling_at(c)).abs() <= room.tolerance());
        if !b.top && !flush {
            return Err(SceneError::Invalid {
                at: ctx.at(&b.max),
                field: format!("block `{}`.top", b.name),
                message: format!(
                    "`top = false` leaves the block open above, but it stops at z = {} below \
                     the ceiling of room `{}` (z = {} over its centre): make it reach the \
                     ceiling (a level part of it) or keep its top",
                    hi.z / ctx.unit,
                    room.name,
                    room.ceiling_at([0.5 * (lo.x + hi.x), 0.5 * (lo.y + hi.y)]) / ctx.unit
                ),
            });
        }
        return Ok(());
    }
    if rooms.is_empty() {
        return Ok(());
    }
    Err(SceneError::OutOfRange {
        at: ctx.at(&b.max),
        field: format!("block `{}`.min/max", b.name),
        message: format!(
            "the block is not inside any room ({}): it would reach through a wall, with faces \
             outside the room facing away from it",
            rooms
                .iter()
                .map(|r| r.describe(ctx.unit))
                .collect::<Vec<_>>()
                .join("; ")
        ),
    })
}
