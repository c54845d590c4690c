//! A space as the room the typed room describes: one horizontal floor polygon, a ceiling over
//! all of it (flat at one height, or sloped: the lowest of its roof planes over each point),
//! and one vertical wall from the floor up to the ceiling on each edge of the floor (none
//! where the roof comes down to the floor). A space of another shape is an error naming the
//! face that breaks the rule.

use super::model::{ModelFace, ModelFaceKind, Space};
use super::ImportError;
use crate::geometry::{Polygon, Vec3};
use crate::scene::context::LARGEST_COORDINATE;
use crate::scene::room::ceiling::{lowest, CeilingPlane};
use crate::scene::room::{Plan, Point2};

/// A space read as a room on its floor plan.
pub(crate) struct Prism<'a> {
    /// The floor polygon, counter-clockwise seen from above, from its south-west-most corner
    /// (smallest y, then smallest x), metres; its edges are numbered from there.
    pub plan: Plan,
    /// The floor's and the ceiling's z, metres (a sloped ceiling's highest corner).
    pub floor: f64,
    pub ceiling: f64,
    /// A sloped ceiling's planes, each named after its first face (empty: flat).
    pub roof: Vec<CeilingPlane>,
    pub floor_face: &'a ModelFace,
    /// The ceiling's (or roof's) faces, and for a sloped ceiling the plane of each in `roof`.
    pub ceiling_faces: Vec<&'a ModelFace>,
    pub plane_of: Vec<usize>,
    /// The wall on each plan edge, in plan order (`None` where the roof meets the floor).
    pub walls: Vec<Option<&'a ModelFace>>,
}

/// An error about `face` of `space`.
fn face_error(space: &Space, face: &ModelFace, message: String) -> ImportError {
    ImportError {
        line: face.line,
        element: format!("space `{}`, face `{}`", space.id, face.id),
        message,
    }
}

/// The largest distance (m) of a corner of `polygon` from its mean plane (Newell's normal
/// through the centroid of the corners).
pub(crate) fn off_plane(polygon: &[Vec3]) -> f64 {
    let normal = Polygon::new(polygon.to_vec()).normal();
    let centre = polygon.iter().fold(Vec3::ZERO, |s, &p| s + p) / polygon.len() as f64;
    polygon
        .iter()
        .map(|&p| (p - centre).dot(normal).abs())
        .fold(0.0, f64::max)
}

/// Reads `space` as a prism; `tol` (m) is how far a corner may be from where the rule puts it.
pub(crate) fn prism(space: &Space, tol: f64) -> Result<Prism<'_>, ImportError> {
    let of = |kind| space.faces.iter().filter(move |f| f.kind == kind);
    for f in &space.faces {
        let mut corners = f
            .polygon
            .iter()
            .chain(f.openings.iter().flat_map(|o| &o.polygon));
        if let Some(p) = corners.find(|p| p.to_array().iter().any(|c| c.abs() > LARGEST_COORDINATE))
        {
            return Err(face_error(
                space,
                f,
                format!(
                    "a corner {:?} (m) lies beyond the ±{LARGEST_COORDINATE:.0e} m a scene may \
                     span (a unit mistake?)",
                    p.to_array()
                ),
            ));
        }
        let off = off_plane(&f.polygon);
        if off > tol || Polygon::new(f.polygon.clone()).area() <= tol * tol {
            return Err(face_error(
                space,
                f,
                if off > tol {
                    format!("the polygon is not planar: a corner lies {off:.3e} m off its plane (tolerance {tol:.1e} m)")
                } else {
                    "the polygon encloses no area".into()
                },
            ));
        }
    }
    // A face typed as a wall that is not vertical is part of the roof (Honeybee types steep
    // roof slopes as walls) if it is a ceiling at all; the rules below say whether it is.
    let vertical = |f: &ModelFace| footprint(f, tol).is_ok();
    let floors: Vec<&ModelFace> = of(ModelFaceKind::Floor).collect();
    let floor_face = match floors.as_slice() {
        [one] => *one,
        [] => {
            return Err(ImportError {
                line: space.line,
                element: format!("space `{}`", space.id),
                message: "missing geometry: the space has no floor face".into(),
            })
        }
        [_, second, ..] => {
            return Err(face_error(
                space,
                second,
                format!(
                    "the space has {} floor faces; a space with one floor polygon is supported \
                     yet",
                    floors.len()
                ),
            ))
        }
    };
    let floor = floor_face.polygon[0].z;
    if floor_face.polygon.iter().any(|p| (p.z - floor).abs() > tol) {
        return Err(face_error(
            space,
            floor_face,
            "the floor is not horizontal: sloped floors are not supported yet".into(),
        ));
    }
    let plan = floor_plan(&floor_face.polygon, tol)
        .map_err(|problem| face_error(space, floor_face, format!("the floor: {problem}")))?;

    let ceiling_faces: Vec<&ModelFace> = space
        .faces
        .iter()
        .filter(|f| {
            f.kind == ModelFaceKind::Ceiling || (f.kind == ModelFaceKind::Wall && !vertical(f))
        })
        .collect();
    let Some(first) = ceiling_faces.first() else {
        return Err(ImportError {
            line: space.line,
            element: format!("space `{}`", space.id),
            message: "missing geometry: the space has no ceiling or roof face".into(),
        });
    };
    let level = first.polygon[0].z;
    let flat = ceiling_faces
        .iter()
        .all(|c| c.polygon.iter().all(|p| (p.z - level).abs() <= tol));
    if !flat {
        return sloped(space, plan, floor, floor_face, ceiling_faces, tol);
    }
    let ceiling = level;
    if ceiling - floor <= tol {
        return Err(face_error(
            space,
            first,
            format!("the ceiling (z = {ceiling} m) is not above the floor (z = {floor} m)"),
        ));
    }
    let plan_area = plan_area(&plan.corners);
    let covered: f64 = ceiling_faces
        .iter()
        .map(|c| Polygon::new(c.polygon.clone()).area())
        .sum();
    if (covered - plan_area).abs() > tol * perimeter(&plan) {
        return Err(face_error(
            space,
            first,
            format!(
                "the ceiling faces cover {covered:.4} m², the floor {plan_area:.4} m²: the \
                 ceiling must be flat over the whole floor (other shapes are not supported yet)"
            ),
        ));
    }

    let walls = walls_on_edges(space, &plan, floor, &|_| ceiling, tol)?;
    let walls = walls
        .into_iter()
        .enumerate()
        .map(|(k, w)| w.map(Some).ok_or_else(|| missing_wall(space, &plan, k)))
        .collect::<Result<_, _>>()?;
    Ok(Prism {
        plan,
        floor,
        ceiling,
        roof: Vec::new(),
        floor_face,
        plane_of: Vec::new(),
        ceiling_faces,
        walls,
    })
}

/// The error for the floor edge `k` of `space` on which no wall stands.
fn missing_wall(space: &Space, plan: &Plan, k: usize) -> ImportError {
    let (a, b) = plan.edge(k);
    ImportError {
        line: space.line,
        element: format!("space `{}`", space.id),
        message: format!(
            "missing geometry: no wall stands on the floor's edge from {a:?} to {b:?} (m); the \
             space is not closed"
        ),
    }
}

/// The space under a sloped ceiling: `roofs` (its ceiling faces and its walls that are not
/// vertical) each in a plane, the ceiling the lowest of those planes over every point of the
/// floor, covering it once.
fn sloped<'a>(
    space: &'a Space,
    plan: Plan,
    floor: f64,
    floor_face: &'a ModelFace,
    roofs: Vec<&'a ModelFace>,
    tol: f64,
) -> Result<Prism<'a>, ImportError> {
    let mut roof: Vec<CeilingPlane> = Vec::new();
    let mut plane_of = Vec::with_capacity(roofs.len());
    for f in &roofs {
        let polygon = Polygon::new(f.polygon.clone());
        let on = |plane: &CeilingPlane| {
            f.polygon
                .iter()
                .all(|p| (plane.z([p.x, p.y]) - p.z).abs() <= tol)
        };
        if let Some(k) = roof.iter().position(on) {
            plane_of.push(k);
            continue;
        }
        let Some(plane) = CeilingPlane::square_to(f.name.clone(), f.polygon[0], polygon.normal())
        else {
            return Err(face_error(
                space,
                f,
                "the roof face is vertical: a ceiling face must slope, not stand".into(),
            ));
        };
        plane_of.push(roof.len());
        roof.push(plane);
    }
    for f in &roofs {
        if let Some(p) = f
            .polygon
            .iter()
            .find(|p| p.z > lowest(&roof, [p.x, p.y]) + tol || p.z < floor - tol)
        {
            return Err(face_error(
                space,
                f,
                format!(
                    "the roof face's corner {:?} (m) lies above another roof plane of the space \
                     (or below its floor): a ceiling that is not the lowest of its planes over \
                     each point (a valley, an overhang) is not supported yet",
                    p.to_array()
                ),
            ));
        }
    }
    let covered: f64 = roofs
        .iter()
        .map(|c| {
            let p = Polygon::new(c.polygon.clone());
            p.area() * p.normal().z.abs()
        })
        .sum();
    let plan_area = plan_area(&plan.corners);
    if (covered - plan_area).abs() > tol * perimeter(&plan) {
        return Err(face_error(
            space,
            roofs[0],
            format!(
                "the ceiling faces cover {covered:.4} m² of the floor's {plan_area:.4} m² seen \
                 from above: the ceiling must cover the whole floor once (other shapes are not \
                 supported yet)"
            ),
        ));
    }
    let ceiling_at = |p: Point2| lowest(&roof, p);
    let walls = walls_on_edges(space, &plan, floor, &ceiling_at, tol)?;
    for (k, w) in walls.iter().enumerate() {
        let (a, b) = plan.edge(k);
        let middle = [0.5 * (a[0] + b[0]), 0.5 * (a[1] + b[1])];
        // The ceiling is concave: down at both ends and the middle, it is down all along.
        let down = [a, middle, b].iter().all(|&p| ceiling_at(p) <= floor + tol);
        if w.is_none() && !down {
            return Err(missing_wall(space, &plan, k));
        }
    }
    let ceiling = roofs
        .iter()
        .flat_map(|f| &f.polygon)
        .map(|p| p.z)
        .fold(floor, f64::max);
    Ok(Prism {
        plan,
        floor,
        ceiling,
        roof,
        floor_face,
        ceiling_faces: roofs,
        plane_of,
        walls,
    })
}

/// The length of the plan's outline, m.
fn perimeter(plan: &Plan) -> f64 {
    (0..plan.len())
        .map(|k| {
            let (a, b) = plan.edge(k);
            (b[0] - a[0]).hypot(b[1] - a[1])
        })
        .sum()
}

/// The vertical wall of `space` standing on each plan edge, if any: each runs from the floor
/// (z = `floor`, m) up to the ceiling over it (`ceiling_at`, m).
fn walls_on_edges<'a>(
    space: &'a Space,
    plan: &Plan,
    floor: f64,
    ceiling_at: &dyn Fn(Point2) -> f64,
    tol: f64,
) -> Result<Vec<Option<&'a ModelFace>>, ImportError> {
    let mut walls: Vec<Option<&ModelFace>> = vec![None; plan.len()];
    let standing = space
        .faces
        .iter()
        .filter(|f| f.kind == ModelFaceKind::Wall && footprint(f, tol).is_ok());
    for w in standing {
        let edge =
            wall_edge(w, plan, floor, ceiling_at, tol).map_err(|m| face_error(space, w, m))?;
        if let Some(other) = walls[edge] {
            return Err(face_error(
                space,
                w,
                format!(
                    "walls `{}` and `{}` both stand on the floor's edge {}: one wall per edge \
                     is supported yet",
                    other.id,
                    w.id,
                    edge + 1
                ),
            ));
        }
        walls[edge] = Some(w);
    }
    Ok(walls)
}

/// The floor's corners as a plan, counter-clockwise from the south-west-most corner: the same
/// floor gives the same plan however the file winds it and wherever it starts.
fn floor_plan(polygon: &[Vec3], tol: f64) -> Result<Plan, crate::scene::room::PlanProblem> {
    let mut corners: Vec<Point2> = polygon.iter().map(|p| [p.x, p.y]).collect();
    if plan_area(&corners) < 0.0 {
        corners.reverse();
    }
    let start = (0..corners.len())
        .min_by(|&i, &j| {
            let (a, b) = (corners[i], corners[j]);
            a[1].total_cmp(&b[1]).then(a[0].total_cmp(&b[0]))
        })
        .unwrap_or(0);
    corners.rotate_left(start);
    Plan::new(&corners, tol)
}

/// The signed area of a plan polygon, m² (positive counter-clockwise).
fn plan_area(corners: &[Point2]) -> f64 {
    let n = corners.len();
    0.5 * (0..n)
        .map(|i| {
            let (a, b) = (corners[i], corners[(i + 1) % n]);
            a[0] * b[1] - b[0] * a[1]
        })
        .sum::<f64>()
}

/// The two ends (m) of the footprint in plan of the wall `w`, which must be vertical: every
/// corner within `tol` of the line through its two corners farthest apart in plan.
fn footprint(w: &ModelFace, tol: f64) -> Result<(Point2, Point2), String> {
    let xy = |p: &Vec3| [p.x, p.y];
    let distance = |a: Point2, b: Point2| (a[0] - b[0]).hypot(a[1] - b[1]);
    let mut ends = (xy(&w.polygon[0]), xy(&w.polygon[0]));
    for p in &w.polygon {
        for q in &w.polygon {
            if distance(xy(p), xy(q)) > distance(ends.0, ends.1) {
                ends = (xy(p), xy(q));
            }
        }
    }
    let (p, q) = ends;
    let length = distance(p, q);
    let off_line =
        |c: Point2| ((q[0] - p[0]) * (c[1] - p[1]) - (q[1] - p[1]) * (c[0] - p[0])).abs() / length;
    if length <= tol || w.polygon.iter().any(|c| off_line(xy(c)) > tol) {
        return Err("the wall is not vertical: sloped walls are not supported yet".into());
    }
    Ok(ends)
}

/// The plan edge the wall `w` stands on: it must be vertical, run from the floor (z =
/// `floor`) up to the ceiling (`ceiling_at` over each point, m) and end at the edge's two
/// corners.
fn wall_edge(
    w: &ModelFace,
    plan: &Plan,
    floor: f64,
    ceiling_at: &dyn Fn(Point2) -> f64,
    tol: f64,
) -> Result<usize, String> {
    let (p, q) = footprint(w, tol)?;
    let distance = |a: Point2, b: Point2| (a[0] - b[0]).hypot(a[1] - b[1]);
    let at_floor = |c: &Vec3| (c.z - floor).abs() <= tol;
    let at_ceiling = |c: &Vec3| (c.z - ceiling_at([c.x, c.y])).abs() <= tol;
    let astray = w.polygon.iter().find(|c| !(at_floor(c) || at_ceiling(c)));
    if astray.is_some() || !w.polygon.iter().any(at_floor) || !w.polygon.iter().any(at_ceiling) {
        let c = astray.unwrap_or(&w.polygon[0]);
        return Err(format!(
            "the wall does not run from the floor (z = {floor} m) to the ceiling: its corner \
             {:?} (m) is at neither (the ceiling is at z = {} m there); walls split along their \
             height are not supported yet",
            c.to_array(),
            ceiling_at([c.x, c.y])
        ));
    }
    (0..plan.len())
        .find(|&k| {
            let (a, b) = plan.edge(k);
            (distance(a, p) <= tol && distance(b, q) <= tol)
                || (distance(a, q) <= tol && distance(b, p) <= tol)
        })
        .ok_or_else(|| {
            format!(
                "the wall from {p:?} to {q:?} (m, in plan) does not stand on one edge of the \
                 floor polygon"
            )
        })
}
