//! Rooms: the typed description of a closed room seen from inside, between the file formats
//! and the meshing.
//!
//! A `[[room]]` is read into a [`Room`] whether it is written as a box (`min`, `max`) or as a
//! floor plan (`plan`, `height`): a plan polygon, a floor and a ceiling level, and its faces,
//! each facing into the room and knowing what it is (floor, ceiling, the wall on a plan
//! edge). Meshing, openings, obstacles, sensors, luminaires and work planes read the room
//! from here, never from the file. A plan that is an axis-aligned rectangle is the box: its
//! faces come in the box's order with the box's corners, so both spellings give the same
//! patches and the same basis bytes (walls keep the names the plan gives them).
//!
//! A plan room may have a sloped or pitched ceiling instead of a height (`ceiling_planes`):
//! the lowest of a few planes over each point of the plan ([`ceiling`]). Its ceiling is then
//! one face per plane, each the plan clipped to where that plane is the lowest, and each wall
//! the polygon under the ceiling's broken line over its edge (a trapezoid under a single
//! slope, a pentagon under a gable).

pub(crate) mod ceiling;
mod flat;
mod plan;
mod sloped;

use geo::coordinate_position::CoordPos;
use toml::Spanned;

use super::context::{Ctx, RawSurface};
use super::error::{Location, SceneError};
use super::file::RoomDef;
use super::openings::CONTACT_TOLERANCE;
use super::primitives::box_corners;
use crate::geometry::Vec3;

pub(crate) use ceiling::CeilingPlane;
pub(crate) use plan::{is_convex, overlap_area, Plan, PlanProblem, Point2};

/// What a room face is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum FaceKind {
    /// The floor, facing up.
    Floor,
    /// The ceiling, facing down.
    Ceiling,
    /// The part of a sloped ceiling under plane `index` of [`Room::roof`], facing down.
    CeilingPlane {
        /// Index of the plane in [`Room::roof`].
        index: usize,
    },
    /// The wall standing on edge `edge` of the plan (counter-clockwise numbering).
    Wall {
        /// Index of the edge in [`Plan::corners`] order.
        edge: usize,
    },
}

/// One face of a room.
#[derive(Clone, Debug)]
pub(crate) struct RoomFace {
    /// Its name after the room's: `floor`, `ceiling`, `wall_xmin` (box), `wall_3` or the
    /// user's name (plan).
    pub suffix: String,
    /// What it is.
    pub kind: FaceKind,
    /// Its material's name, and where that was written.
    pub material: String,
    pub material_at: Location,
    /// Its outline, metres, wound so that its normal points into the room (the floor and the
    /// ceiling of a plan room: the plan itself, which may be concave; a sloped ceiling's
    /// face: the first of its convex pieces).
    pub outline: Vec<Vec3>,
}

impl RoomFace {
    /// A face that is no wall (a floor, a ceiling or a ceiling plane's part) named `suffix`,
    /// of the material `end` names (with where it was named), around `outline` (m).
    fn end(kind: FaceKind, suffix: &str, end: &(String, Location), outline: Vec<Vec3>) -> Self {
        RoomFace {
            suffix: suffix.to_owned(),
            kind,
            material: end.0.clone(),
            material_at: end.1.clone(),
            outline,
        }
    }
}

/// A closed room: a prism on a floor plan (under a flat or a sloped ceiling), seen from
/// inside.
#[derive(Clone, Debug)]
pub(crate) struct Room {
    /// Its name; its faces are `<name>.<suffix>`.
    pub name: String,
    /// Where it was written.
    pub at: Location,
    /// Its floor plan, counter-clockwise seen from above, metres.
    pub plan: Plan,
    /// The floor's and the ceiling's z, metres (a sloped ceiling's highest point).
    pub floor: f64,
    pub ceiling: f64,
    /// The planes of a sloped ceiling (empty: the ceiling is flat at `ceiling`).
    pub roof: Vec<CeilingPlane>,
    /// Its bounding box, metres.
    pub lo: Vec3,
    pub hi: Vec3,
    /// Whether the plan is an axis-aligned rectangle: the room is then meshed, cut by its
    /// openings and by the blocks standing on it as a box.
    pub is_box: bool,
    /// Floor, ceiling (one face per plane of a sloped ceiling), then the walls (in the box's
    /// order for a box, in plan order else).
    pub faces: Vec<RoomFace>,
    /// Longest patch edge of its faces, metres (`None`: the scene's).
    pub max_edge: Option<f64>,
}

impl Room {
    /// Reads and checks a `[[room]]`.
    pub fn read(ctx: &Ctx, def: &Spanned<RoomDef>) -> Result<Room, SceneError> {
        let r = def.get_ref();
        let what = format!("room `{}`", r.name);
        let max_edge = ctx.optional_length(r.max_edge.as_ref(), &format!("{what}.max_edge"))?;
        let invalid = |at: Location, field: &str, message: String| SceneError::Invalid {
            at,
            field: format!("{what}.{field}"),
            message,
        };
        let base = RoomBase {
            name: r.name.clone(),
            at: ctx.at(def),
            max_edge,
        };
        match (&r.min, &r.max, &r.plan) {
            (Some(min), Some(max), None) => {
                for (field, given) in [
                    ("height", r.height.as_ref().map(|h| ctx.at(h))),
                    (
                        "ceiling_planes",
                        r.ceiling_planes.as_ref().map(|h| ctx.at(h)),
                    ),
                    ("level", r.level.as_ref().map(|h| ctx.at(h))),
                    ("wall_names", r.wall_names.as_ref().map(|h| ctx.at(h))),
                    (
                        "wall_materials",
                        r.wall_materials.as_ref().map(|h| ctx.at(h)),
                    ),
                ] {
                    if let Some(at) = given {
                        return Err(invalid(
                            at,
                            field,
                            "belongs to a room given by its `plan`; a box room has `min` and `max`"
                                .into(),
                        ));
                    }
                }
                let (lo, hi) = box_corners(ctx, &what, min, max)?;
                let walls = r.walls.as_ref().unwrap_or(&r.material);
                let plan = Plan::rectangle([lo.x, lo.y], [hi.x, hi.y]);
                let label = |suffix: &str, _edge: usize| {
                    (suffix.to_owned(), walls.get_ref().clone(), ctx.at(walls))
                };
                Ok(base.boxed(plan, lo.z, hi.z, &ends(ctx, r), label))
            }
            (None, None, Some(plan)) => {
                let (plan, floor, height) = read_plan(ctx, &what, def, plan)?;
                let n = plan.len();
                let names = per_edge(ctx, &what, "wall_names", r.wall_names.as_ref(), n)?;
                let materials =
                    per_edge(ctx, &what, "wall_materials", r.wall_materials.as_ref(), n)?;
                let walls = r.walls.as_ref().unwrap_or(&r.material);
                let written = plan.written_edge.clone();
                let label = |_: &str, edge: usize| {
                    let w = written[edge];
                    let name = names.map_or_else(|| format!("wall_{}", w + 1), |l| l[w].clone());
                    let material = materials.map_or(walls, |l| &l[w]);
                    (name, material.get_ref().clone(), ctx.at(material))
                };
                match (height, &r.ceiling_planes) {
                    (Some(height), _) => {
                        Ok(base.laid_out(plan, floor, floor + height, &ends(ctx, r), label))
                    }
                    (None, Some(list)) => {
                        let planes = sloped::read_ceiling_planes(ctx, &what, list)?;
                        let at = ctx.at(list);
                        let field = format!("{what}.ceiling_planes");
                        base.sloped(plan, floor, planes, &ends(ctx, r), label)
                            .map_err(|message| SceneError::Invalid { at, field, message })
                    }
                    // `read_plan` refuses a plan with neither.
                    (None, None) => Err(invalid(
                        ctx.at(def),
                        "height",
                        "a room given by its `plan` needs its `height`".into(),
                    )),
                }
            }
            _ => Err(invalid(
                ctx.at(def),
                "min/max/plan",
                "give either `min` and `max` (a box) or `plan` and `height` (a floor plan)".into(),
            )),
        }
    }

    /// A room built by an importer: the prism on `plan` from `floor` to `ceiling` (m), its
    /// floor's and ceiling's materials in `ends`, `wall(edge)` naming the wall on each plan
    /// edge (counter-clockwise numbering) and giving its material. A rectangular plan is laid
    /// out as the box, as a `[[room]]` with that plan would be.
    pub fn from_plan(
        name: String,
        at: Location,
        plan: Plan,
        (floor, ceiling): (f64, f64),
        ends: &Ends,
        wall: impl Fn(usize) -> (String, String, Location),
    ) -> Room {
        let base = RoomBase {
            name,
            at,
            max_edge: None,
        };
        base.laid_out(plan, floor, ceiling, ends, |_, edge| wall(edge))
    }

    /// A room built by an importer under a sloped ceiling: as [`Room::from_plan`], the
    /// ceiling the lowest of `planes` over each point. An error (a message) names the plane or
    /// corner at fault.
    pub fn from_sloped_plan(
        name: String,
        at: Location,
        plan: Plan,
        floor: f64,
        planes: Vec<CeilingPlane>,
        ends: &Ends,
        wall: impl Fn(usize) -> (String, String, Location),
    ) -> Result<Room, String> {
        let base = RoomBase {
            name,
            at,
            max_edge: None,
        };
        base.sloped(plan, floor, planes, ends, |_, edge| wall(edge))
    }

    /// [`CONTACT_TOLERANCE`] of its diagonal, metres.
    pub fn tolerance(&self) -> f64 {
        CONTACT_TOLERANCE * (self.hi - self.lo).length()
    }

    /// Its faces as surfaces to mesh: a box's faces and every wall whole, a plan room's floor
    /// and ceiling in convex pieces.
    pub fn surfaces(&self) -> Vec<RawSurface> {
        self.faces
            .iter()
            .map(|f| RawSurface {
                name: format!("{}.{}", self.name, f.suffix),
                material: f.material.clone(),
                material_at: f.material_at.clone(),
                faces: match (self.is_box, f.kind) {
                    (false, FaceKind::Floor) => self.floor_faces(&[]),
                    (false, FaceKind::Ceiling) => self.ceiling_faces(&[]),
                    (_, FaceKind::CeilingPlane { index }) => self.plane_faces(index, &[]),
                    _ => vec![f.outline.clone()],
                },
                max_edge: self.max_edge,
                at: self.at.clone(),
                exterior: false,
            })
            .collect()
    }

    /// The floor less `holes` (convex, plan coordinates in metres) in convex pieces, facing up.
    pub fn floor_faces(&self, holes: &[Vec<Point2>]) -> Vec<Vec<Vec3>> {
        self.plan
            .convex_pieces(holes, self.tolerance())
            .into_iter()
            .map(|p| {
                p.iter()
                    .map(|c| Vec3::new(c[0], c[1], self.floor))
                    .collect()
            })
            .collect()
    }

    /// The ceiling less `holes` in convex pieces, facing down.
    pub fn ceiling_faces(&self, holes: &[Vec<Point2>]) -> Vec<Vec<Vec3>> {
        self.plan
            .convex_pieces(holes, self.tolerance())
            .into_iter()
            .map(|p| {
                p.iter()
                    .rev()
                    .map(|c| Vec3::new(c[0], c[1], self.ceiling))
                    .collect()
            })
            .collect()
    }

    /// The part of a sloped ceiling under plane `index` of [`Room::roof`] less `holes`
    /// (convex, plan coordinates in metres) in convex pieces, facing down.
    pub fn plane_faces(&self, index: usize, holes: &[Vec<Point2>]) -> Vec<Vec<Vec3>> {
        let plane = &self.roof[index];
        self.plan
            .convex_pieces_within(&plane.cell, holes, self.tolerance())
            .into_iter()
            .map(|p| {
                p.iter()
                    .rev()
                    .map(|&c| Vec3::new(c[0], c[1], plane.z(c)))
                    .collect()
            })
            .collect()
    }

    /// The ceiling's z over the plan point `p` (m), m.
    pub fn ceiling_at(&self, p: Point2) -> f64 {
        if self.roof.is_empty() {
            self.ceiling
        } else {
            ceiling::lowest(&self.roof, p)
        }
    }

    /// The ceiling's lowest z over the plan, m: over one of its corners (the lowest of planes
    /// is concave).
    pub fn lowest_ceiling(&self) -> f64 {
        self.plan
            .corners
            .iter()
            .map(|&c| self.ceiling_at(c))
            .fold(self.ceiling, f64::min)
    }

    /// Whether `p` (m) is inside the room or on its faces, within [`Room::tolerance`].
    pub fn contains(&self, p: Vec3) -> bool {
        let tol = self.tolerance();
        p.z >= self.floor - tol
            && p.z <= self.ceiling_at([p.x, p.y]) + tol
            && self.plan.holds([p.x, p.y], tol)
    }

    /// Whether `p` (m) is strictly inside: inside and farther than the tolerance from every
    /// face.
    pub fn strictly_contains(&self, p: Vec3) -> bool {
        let tol = self.tolerance();
        p.z > self.floor + tol
            && p.z < self.ceiling_at([p.x, p.y]) - tol
            && self.plan.position([p.x, p.y], tol) == CoordPos::Inside
    }

    /// Whether the box `lo`..`hi` (m) is inside the room (it may touch its faces).
    pub fn holds_box(&self, lo: Vec3, hi: Vec3) -> bool {
        let tol = self.tolerance();
        // The lowest of planes is concave: over a rectangle it is lowest at a corner.
        let under = [[lo.x, lo.y], [hi.x, lo.y], [hi.x, hi.y], [lo.x, hi.y]]
            .iter()
            .all(|&c| hi.z <= self.ceiling_at(c) + tol);
        lo.z >= self.floor - tol
            && under
            && self.plan.holds_rectangle([lo.x, lo.y], [hi.x, hi.y], tol)
    }

    /// Whether `p` (m) lies on face `f`, within the tolerance.
    pub fn on_face(&self, f: &RoomFace, p: Vec3) -> bool {
        let tol = self.tolerance();
        match f.kind {
            FaceKind::Floor | FaceKind::Ceiling => {
                let z = if f.kind == FaceKind::Floor {
                    self.floor
                } else {
                    self.ceiling
                };
                (p.z - z).abs() <= tol && self.plan.holds([p.x, p.y], tol)
            }
            FaceKind::CeilingPlane { index } => {
                let plane = &self.roof[index];
                let q = [p.x, p.y];
                (p.z - plane.z(q)).abs() <= tol
                    && plane.holds(&self.roof, q, tol)
                    && self.plan.holds(q, tol)
            }
            FaceKind::Wall { edge } => {
                let (a, b) = self.plan.edge(edge);
                let along = Vec3::new(b[0] - a[0], b[1] - a[1], 0.0);
                let length = along.length();
                let d = Vec3::new(p.x - a[0], p.y - a[1], 0.0);
                let s = d.dot(along) / length;
                let off = along.cross(d).z / length;
                off.abs() <= tol
                    && s >= -tol
                    && s <= length + tol
                    && p.z >= self.floor - tol
                    && p.z <= self.ceiling_at([p.x, p.y]) + tol
            }
        }
    }

    /// The face holding every one of `corners` (m), if any.
    pub fn face_holding(&self, corners: &[Vec3]) -> Option<&RoomFace> {
        if corners.is_empty() {
            return None;
        }
        self.faces
            .iter()
            .find(|f| corners.iter().all(|&p| self.on_face(f, p)))
    }

    /// The inward unit normal of face `f`.
    pub fn inward(&self, f: &RoomFace) -> Vec3 {
        crate::geometry::Polygon::new(f.outline.clone()).normal()
    }

    /// Where its corners run, for messages: the box's corners, or the plan's, in the scene's
    /// unit.
    pub fn describe(&self, unit: f64) -> String {
        if self.is_box {
            format!(
                "`{}` spans {:?} to {:?}",
                self.name,
                (self.lo / unit).to_array(),
                (self.hi / unit).to_array()
            )
        } else {
            let corners: Vec<[f64; 2]> = self
                .plan
                .corners
                .iter()
                .map(|c| [c[0] / unit, c[1] / unit])
                .collect();
            let top = if self.roof.is_empty() {
                format!("{}", self.ceiling / unit)
            } else {
                format!(
                    "its sloped ceiling (highest at z = {})",
                    self.ceiling / unit
                )
            };
            format!(
                "`{}` has the plan {corners:?} from z = {} to {top}",
                self.name,
                self.floor / unit,
            )
        }
    }
}

/// The materials of a room's floor and ceiling, and where each was named.
pub(crate) struct Ends {
    pub floor: (String, Location),
    pub ceiling: (String, Location),
}

/// A `[[room]]`'s floor and ceiling materials: their own, or the room's `material`.
fn ends(ctx: &Ctx, r: &RoomDef) -> Ends {
    let own = |m: Option<&Spanned<String>>| {
        let m = m.unwrap_or(&r.material);
        (m.get_ref().clone(), ctx.at(m))
    };
    Ends {
        floor: own(r.floor.as_ref()),
        ceiling: own(r.ceiling.as_ref()),
    }
}

/// What every room has before its faces are laid out.
struct RoomBase {
    name: String,
    at: Location,
    max_edge: Option<f64>,
}

/// Reads and checks `room.plan` with `room.height` (or `room.ceiling_planes`) and
/// `room.level`: the plan (metres, wound counter-clockwise), the floor's z and the height
/// (m; `None` under ceiling planes).
fn read_plan(
    ctx: &Ctx,
    what: &str,
    def: &Spanned<RoomDef>,
    plan: &Spanned<Vec<Vec<f64>>>,
) -> Result<(Plan, f64, Option<f64>), SceneError> {
    let r = def.get_ref();
    let field = format!("{what}.plan");
    let mut corners = Vec::with_capacity(plan.get_ref().len());
    for (k, c) in plan.get_ref().iter().enumerate() {
        let [x, y] = c[..] else {
            return Err(SceneError::Invalid {
                at: ctx.at(plan),
                field: field.clone(),
                message: format!(
                    "corner {} has {} numbers; each corner is [x, y]",
                    k + 1,
                    c.len()
                ),
            });
        };
        let p = ctx.coordinates([x, y, 0.0], plan, &field)?;
        corners.push([p.x, p.y]);
    }
    let height = match (&r.height, &r.ceiling_planes) {
        (Some(height), None) => Some(ctx.length(height, &format!("{what}.height"))?),
        (None, Some(_)) => None,
        (Some(height), Some(_)) => {
            return Err(SceneError::Invalid {
                at: ctx.at(height),
                field: format!("{what}.height"),
                message: "give either `height` (a flat ceiling) or `ceiling_planes` (a sloped \
                 one), not both"
                    .into(),
            })
        }
        (None, None) => {
            return Err(SceneError::Invalid {
                at: ctx.at(def),
                field: format!("{what}.height"),
                message: "a room given by its `plan` needs its `height` (floor to ceiling) or \
                 its `ceiling_planes`"
                    .into(),
            })
        }
    };
    let floor = match &r.level {
        Some(l) => {
            ctx.coordinates([0.0, 0.0, *l.get_ref()], l, &format!("{what}.level"))?
                .z
        }
        None => 0.0,
    };
    let (lo, hi) = Plan {
        corners: corners.clone(),
        written_edge: Vec::new(),
    }
    .bounds();
    let diagonal = Vec3::new(hi[0] - lo[0], hi[1] - lo[1], height.unwrap_or(0.0)).length();
    let plan = Plan::new(&corners, CONTACT_TOLERANCE * diagonal).map_err(|problem| {
        SceneError::Invalid {
            at: ctx.at(plan),
            field,
            message: problem.to_string(),
        }
    })?;
    Ok((plan, floor, height))
}

/// A per-edge list (`wall_names` or `wall_materials`) checked to have one entry per plan edge.
fn per_edge<'a, T>(
    ctx: &Ctx,
    what: &str,
    field: &str,
    list: Option<&'a Spanned<Vec<T>>>,
    edges: usize,
) -> Result<Option<&'a [T]>, SceneError> {
    let Some(list) = list else {
        return Ok(None);
    };
    if list.get_ref().len() != edges {
        return Err(SceneError::Invalid {
            at: ctx.at(list),
            field: format!("{what}.{field}"),
            message: format!(
                "gives {} entries for the plan's {edges} edges: one per edge, in the plan's order",
                list.get_ref().len()
            ),
        });
    }
    Ok(Some(list.get_ref().as_slice()))
}
