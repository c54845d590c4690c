//! Built-in geometry: `quad`, `room` (a box seen from inside) and `block` (a box seen from
//! outside). z is up.

use toml::Spanned;

use super::context::{Ctx, RawSurface};
use super::error::SceneError;
use super::file::{BlockDef, QuadDef, RoomDef, Xyz};
use super::openings::CONTACT_TOLERANCE;
use crate::geometry::Vec3;

/// The six faces of an axis-aligned box, each wound so that its normal points *into* the box:
/// (room suffix, block suffix, corners).
fn box_faces(lo: Vec3, hi: Vec3) -> [(&'static str, &'static str, [Vec3; 4]); 6] {
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

/// A room: six faces named `<room>.floor`, `.ceiling`, `.wall_xmin` ... `.wall_ymax`, facing
/// inwards.
pub(crate) fn room(ctx: &Ctx, def: &Spanned<RoomDef>) -> Result<Vec<RawSurface>, SceneError> {
    let r = def.get_ref();
    let what = format!("room `{}`", r.name);
    let (lo, hi) = box_corners(ctx, &what, &r.min, &r.max)?;
    let max_edge = ctx.optional_length(r.max_edge.as_ref(), &format!("{what}.max_edge"))?;
    Ok(box_faces(lo, hi)
        .into_iter()
        .map(|(suffix, _, corners)| {
            let material = match suffix {
                "floor" => r.floor.as_ref(),
                "ceiling" => r.ceiling.as_ref(),
                _ => r.walls.as_ref(),
            }
            .unwrap_or(&r.material);
            RawSurface {
                name: format!("{}.{suffix}", r.name),
                material: material.get_ref().clone(),
                material_at: ctx.at(material),
                faces: vec![corners.to_vec()],
                max_edge,
                at: ctx.at(def),
                exterior: false,
            }
        })
        .collect())
}

/// A block: faces named `<block>.top`, `.bottom`, `.side_xmin` ... `.side_ymax`, facing
/// outwards; `bottom = false` leaves out the bottom.
pub(crate) fn block(ctx: &Ctx, def: &Spanned<BlockDef>) -> Result<Vec<RawSurface>, SceneError> {
    let b = def.get_ref();
    let what = format!("block `{}`", b.name);
    let (lo, hi) = box_corners(ctx, &what, &b.min, &b.max)?;
    let max_edge = ctx.optional_length(b.max_edge.as_ref(), &format!("{what}.max_edge"))?;
    Ok(box_faces(lo, hi)
        .into_iter()
        .filter(|(_, suffix, _)| b.bottom || *suffix != "bottom")
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
                "a quad has 4 corners, found {}; use an OBJ file for other polygons",
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

/// Checks that a block (`lo`..`hi`, metres) stands inside one of the rooms, if the scene has
/// any: a block reaching through a wall would put faces outside the room, facing away from it.
pub(crate) fn check_inside_rooms(
    ctx: &Ctx,
    def: &Spanned<BlockDef>,
    lo: Vec3,
    hi: Vec3,
    rooms: &[(String, Vec3, Vec3)],
) -> Result<(), SceneError> {
    if rooms.is_empty() {
        return Ok(());
    }
    let inside = rooms.iter().any(|(_, rlo, rhi)| {
        let tol = CONTACT_TOLERANCE * (*rhi - *rlo).length();
        (0..3).all(|k| lo.axis(k) >= rlo.axis(k) - tol && hi.axis(k) <= rhi.axis(k) + tol)
    });
    if inside {
        return Ok(());
    }
    let b = def.get_ref();
    Err(SceneError::OutOfRange {
        at: ctx.at(&b.max),
        field: format!("block `{}`.min/max", b.name),
        message: format!(
            "the block is not inside any room ({}): it would reach through a wall, with faces \
             outside the room facing away from it",
            rooms
                .iter()
                .map(|(n, l, h)| format!(
                    "`{n}` spans {:?} to {:?}",
                    (*l / ctx.unit).to_array(),
                    (*h / ctx.unit).to_array()
                ))
                .collect::<Vec<_>>()
                .join("; ")
        ),
    })
}
