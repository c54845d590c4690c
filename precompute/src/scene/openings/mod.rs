//! Openings: polygons set flush into a room's face (a window, a door, a skylight, a recessed
//! luminaire). The face is meshed around them, so no part of the wall hides behind an opening
//! and every patch of a closed room exchanges light with the rest of it.
//!
//! Blocks standing on the floor without a bottom face are cut out of the floor the same way:
//! the floor under a desk sees only the inside of the desk, which is no surface at all.
//!
//! A face whose openings are all rectangles along its edges is cut into a grid at every
//! opening's edge coordinates; the cells an opening covers are dropped and every other cell
//! becomes a face of its own, meshed later at the face's `max_edge`. A face holding any other
//! convex polygon (a triangle, a trapezoid) is cut by a polygon difference instead
//! ([`polygon`]). The cut depends only on the corners, so it is deterministic.
//!
//! The floor and the ceiling of a room given by its plan are not rectangles: openings in them
//! (any convex quad) and the footprints of blocks standing on the floor are taken out of the
//! plan polygon instead, which is then cut into convex pieces ([`RoomShape::floor_faces`]).

// One room's faces: placing its openings in them and cutting each face around them.
mod faces;
mod frame;
mod polygon;

use std::ops::Range;

use toml::Spanned;

use super::context::{Ctx, RawSurface};
use super::error::{Location, SceneError};
use super::file::RoomDef;
use super::room::{overlap_area, FaceKind, Point2, Room as RoomShape};
use crate::geometry::Vec3;
use faces::Room;
use frame::Frame;

/// How far a point may lie from a room's or block's face and still count as on it (an
/// opening's corner, a sensor, another opening's edge line), as a fraction of the room's (or
/// block's) diagonal: 1 µm for a diagonal of 1 m. Coordinates written with a few decimals are
/// exact to far better than this; anything further off is a placement error, not rounding.
pub(crate) const CONTACT_TOLERANCE: f64 = 1e-6;

/// An opening placed in a face, in the face's parameters: `s` runs a→b, `t` runs a→d, both
/// in [0, 1].
struct Placed {
    /// Index of the opening in the raw surfaces; `None` for a block's footprint on the floor.
    surface: Option<usize>,
    /// Room face (0..6) it lies in.
    face: usize,
    s: [f64; 2],
    t: [f64; 2],
    /// Per corner, whether its `s` (then `t`) is the upper bound (a rectangle along the
    /// face's edges).
    upper: Vec<(bool, bool)>,
    /// Any other polygon's corners in the face's plane coordinates ([`Frame::to_plane`]);
    /// `s` and `t` are then the bounds of its box.
    outline: Option<Vec<Point2>>,
}

impl Placed {
    /// Its corners in the plane coordinates of `frame`, the face it lies in, in the order
    /// written (a footprint's counter-clockwise in `s`, `t`).
    fn in_plane(&self, frame: &Frame) -> Vec<Point2> {
        if let Some(outline) = &self.outline {
            return outline.clone();
        }
        let (ls, lt) = (frame.ab.length(), frame.ad.length());
        let corner = |us: bool, ut: bool| [self.s[us as usize] * ls, self.t[ut as usize] * lt];
        if self.upper.is_empty() {
            vec![
                corner(false, false),
                corner(true, false),
                corner(true, true),
                corner(false, true),
            ]
        } else {
            self.upper.iter().map(|&(us, ut)| corner(us, ut)).collect()
        }
    }

    /// Whether it and `other`, both in face `frame`, overlap by more than `tol` (m) across.
    fn overlaps(&self, other: &Placed, frame: &Frame, tol: f64) -> bool {
        let (ls, lt) = (frame.ab.length(), frame.ad.length());
        if self.outline.is_none() && other.outline.is_none() {
            let overlap_s = self.s[1].min(other.s[1]) - self.s[0].max(other.s[0]);
            let overlap_t = self.t[1].min(other.t[1]) - self.t[0].max(other.t[0]);
            return overlap_s > tol / ls && overlap_t > tol / lt;
        }
        // Polygons meeting along an edge share a sliver of at most `tol` across.
        overlap_area(&self.in_plane(frame), &other.in_plane(frame)) > tol * (ls + lt)
    }
}

/// The blocks open at one end, which cut the room face they end on: (name, min, max),
/// metres.
pub(crate) struct OpenBlocks<'a> {
    /// Blocks without a bottom face, standing on the floor.
    pub standing: &'a [(String, Vec3, Vec3)],
    /// Blocks without a top face, reaching the ceiling.
    pub hanging: &'a [(String, Vec3, Vec3)],
}

/// Cuts the openings of one room, and the footprints of the blocks standing on its floor
/// without a bottom face, out of its faces.
///
/// `list` names the openings; `faces` are the room's surfaces in `raw`, in the order of `shape.faces` (a box's: floor,
/// ceiling, wall_xmin, wall_xmax, wall_ymin, wall_ymax); `flip` says which surfaces will have their winding reversed;
/// `claimed` marks surfaces already used as an opening (by this or an earlier room);
/// `open` are the blocks without a bottom or a top face. The openings'
/// corners are snapped onto the face plane and the shared grid lines.
#[allow(clippy::too_many_arguments)]
pub(crate) fn cut(
    list: &OpeningList,
    shape: &RoomShape,
    faces: Range<usize>,
    raw: &mut [RawSurface],
    flip: &[bool],
    claimed: &mut [bool],
    open: &OpenBlocks,
) -> Result<(), SceneError> {
    let (standing, hanging) = (open.standing, open.hanging);
    // The rectangles cut on a grid: every face of a box, the walls of a plan room.
    let hosts: Vec<usize> = shape
        .faces
        .iter()
        .enumerate()
        .filter(|(_, f)| shape.is_box || matches!(f.kind, FaceKind::Wall { .. }))
        .map(|(k, _)| faces.start + k)
        .collect();
    let frames: Vec<Frame> = hosts
        .iter()
        .map(|&f| Frame::new(&raw[f].faces[0]))
        .collect();
    let diagonal = (shape.hi - shape.lo).length();
    let room = Room {
        at: list.at.clone(),
        field: list.field.clone(),
        faces,
        hosts,
        frames,
        tol: CONTACT_TOLERANCE * diagonal,
    };
    let mut placed: Vec<Placed> = Vec::new();
    // A plan room's openings in its floor and ceiling, as plan polygons.
    let mut floor_holes: Vec<Vec<Point2>> = Vec::new();
    let mut ceiling_holes: Vec<Vec<Point2>> = Vec::new();
    // A sloped ceiling's, per plane.
    let mut plane_holes: Vec<Vec<Vec<Point2>>> = vec![Vec::new(); shape.roof.len()];
    // Every opening in a floor or a ceiling so far: its name, face and plan polygon.
    let mut in_plan: Vec<(&str, FaceKind, Vec<Point2>)> = Vec::new();
    for name in list.names {
        if !shape.is_box {
            if let Some((kind, hole)) = room.in_plan_face(shape, name, raw, flip, claimed)? {
                // Openings meeting along an edge share a sliver of at most the tolerance.
                let slack = room.tol * (shape.hi - shape.lo).length();
                if let Some((other, _, _)) = in_plan
                    .iter()
                    .find(|(_, k, h)| *k == kind && overlap_area(h, &hole) > slack)
                {
                    return Err(room.invalid(format!(
                        "openings `{other}` and `{name}` overlap in face `{}.{}`",
                        shape.name,
                        shape
                            .faces
                            .iter()
                            .find(|f| f.kind == kind)
                            .map_or("?", |f| &f.suffix)
                    )));
                }
                in_plan.push((name, kind, hole.clone()));
                match kind {
                    FaceKind::Floor => floor_holes.push(hole),
                    FaceKind::CeilingPlane { index } => plane_holes[index].push(hole),
                    _ => ceiling_holes.push(hole),
                }
                continue;
            }
        }
        let opening = room.place(name, raw, flip, claimed, &placed)?;
        placed.push(opening);
    }
    if shape.is_box {
        room.place_footprints(standing, 0, raw, &mut placed)?;
        room.place_footprints(hanging, 1, raw, &mut placed)?;
    } else {
        floor_holes.extend(ends_at(shape, standing, shape.floor, |lo, _| lo.z));
        if shape.roof.is_empty() {
            ceiling_holes.extend(ends_at(shape, hanging, shape.ceiling, |_, hi| hi.z));
        } else {
            for (index, hole) in under_ceiling_planes(shape, hanging) {
                plane_holes[index].push(hole);
            }
        }
        for (k, f) in shape.faces.iter().enumerate() {
            let index = room.faces.start + k;
            match f.kind {
                FaceKind::Floor if !floor_holes.is_empty() => {
                    raw[index].faces = shape.floor_faces(&floor_holes)
                }
                FaceKind::Ceiling if !ceiling_holes.is_empty() => {
                    raw[index].faces = shape.ceiling_faces(&ceiling_holes)
                }
                FaceKind::CeilingPlane { index: plane } if !plane_holes[plane].is_empty() => {
                    raw[index].faces = shape.plane_faces(plane, &plane_holes[plane])
                }
                _ => continue,
            }
            if raw[index].faces.is_empty() {
                return Err(room.invalid(format!(
                    "the openings (or blocks standing on it) cover the whole face `{}`",
                    raw[index].name
                )));
            }
        }
    }
    for k in 0..room.frames.len() {
        room.cut_face(k, raw, &mut placed)?;
    }
    Ok(())
}

/// A room's openings: the surfaces named, and where and under which field the list was
/// written (for the messages).
pub(crate) struct OpeningList<'a> {
    /// The openings' surface names.
    pub names: &'a [String],
    /// Where the list was written (the room's entry when it has none).
    pub at: Location,
    /// The list's field, e.g. ``room `office`.openings``.
    pub field: String,
}

impl<'a> OpeningList<'a> {
    /// The `openings` of a `[[room]]`.
    pub fn of(ctx: &Ctx, def: &'a Spanned<RoomDef>) -> Self {
        let r = def.get_ref();
        OpeningList {
            names: r.openings.as_ref().map_or(&[], |l| l.get_ref().as_slice()),
            at: r
                .openings
                .as_ref()
                .map_or_else(|| ctx.at(def), |l| ctx.at(l)),
            field: format!("room `{}`.openings", r.name),
        }
    }
}

/// The footprints (plan rectangles, m) of the `blocks` whose end (`end(min, max)`, m) is at
/// the level `z` (m) of the floor or the ceiling of `shape`.
fn ends_at(
    shape: &RoomShape,
    blocks: &[(String, Vec3, Vec3)],
    z: f64,
    end: impl Fn(Vec3, Vec3) -> f64,
) -> Vec<Vec<Point2>> {
    let tol = shape.tolerance();
    blocks
        .iter()
        .filter(|(_, lo, hi)| (end(*lo, *hi) - z).abs() <= tol)
        .map(|(_, lo, hi)| vec![[lo.x, lo.y], [hi.x, lo.y], [hi.x, hi.y], [lo.x, hi.y]])
        .collect()
}

/// The footprints (plan rectangles, m) of the `blocks` whose tops meet a sloped ceiling of
/// `shape` flush, with the plane they meet: the plane is level over the whole top there.
fn under_ceiling_planes(
    shape: &RoomShape,
    blocks: &[(String, Vec3, Vec3)],
) -> Vec<(usize, Vec<Point2>)> {
    let tol = shape.tolerance();
    blocks
        .iter()
        .filter_map(|(_, lo, hi)| {
            let footprint = vec![[lo.x, lo.y], [hi.x, lo.y], [hi.x, hi.y], [lo.x, hi.y]];
            let centre = [0.5 * (lo.x + hi.x), 0.5 * (lo.y + hi.y)];
            let index = shape.roof.iter().position(|plane| {
                plane.holds(&shape.roof, centre, tol)
                    && footprint.iter().all(|&c| (plane.z(c) - hi.z).abs() <= tol)
            })?;
            Some((index, footprint))
        })
        .collect()
}
