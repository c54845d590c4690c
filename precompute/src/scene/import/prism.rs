//! A space as the prism the typed room describes: one horizontal floor polygon, a flat
//! ceiling over all of it, and one vertical wall from floor to ceiling on each edge of the
//! floor. A space of another shape is an error naming the face that breaks the rule.

use super::model::{ModelFace, ModelFaceKind, Space};
use super::ImportError;
use crate::geometry::{Polygon, Vec3};
use crate::scene::context::LARGEST_COORDINATE;
use crate::scene::room::{Plan, Point2};

/// A space read as a prism.
pub(crate) struct Prism<'a> {
    /// The floor polygon, counter-clockwise seen from above, from its south-west-most corner
    /// (smallest y, then smallest x), metres; its edges are numbered from there.
    pub plan: Plan,
    /// The floor's and the ceiling's z, metres.
    pub floor: f64,
    pub ceiling: f64,
    pub floor_face: &'a ModelFace,
    pub ceiling_faces: Vec<&'a ModelFace>,
    /// The wall on each plan edge, in plan order.
    pub walls: Vec<&'a ModelFace>,
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
        if f.kind == ModelFaceKind::Wall {
            footprint(f, tol).map_err(|m| face_error(space, f, m))?;
        }
    }
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

    let ceiling_faces: Vec<&ModelFace> = of(ModelFaceKind::Ceiling).collect();
    let Some(first) = ceiling_faces.first() else {
        return Err(ImportError {
            line: space.line,
            element: format!("space `{}`", space.id),
            message: "missing geometry: the space has no ceiling or roof face".into(),
        });
    };
    let ceiling = first.polygon[0].z;
    for c in &ceiling_faces {
        if c.polygon.iter().any(|p| (p.z - ceiling).abs() > tol) {
            return Err(face_error(
                space,
                c,
                format!(
                    "the ceiling is not flat at one height (z = {ceiling} m): sloped ceilings \
                     are not supported yet"
                ),
            ));
        }
    }
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
    let perimeter: f64 = (0..plan.len())
        .map(|k| {
            let (a, b) = plan.edge(k);
            (b[0] - a[0]).hypot(b[1] - a[1])
        })
        .sum();
    if (covered - plan_area).abs() > tol * perimeter {
        return Err(face_error(
            space,
            first,
            format!(
                "the ceiling faces cover {covered:.4} m², the floor {plan_area:.4} m²: the \
                 ceiling must be flat over the whole floor (other shapes are not supported yet)"
            ),
        ));
    }

    let mut walls: Vec<Option<&ModelFace>> = vec![None; plan.len()];
    for w in of(ModelFaceKind::Wall) {
        let edge = wall_edge(w, &plan, floor, ceiling, tol).map_err(|m| face_error(space, w, m))?;
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
    let walls = walls
        .into_iter()
        .enumerate()
        .map(|(k, w)| {
            w.ok_or_else(|| {
                let (a, b) = plan.edge(k);
                ImportError {
                    line: space.line,
                    element: format!("space `{}`", space.id),
                    message: format!(
                        "missing geometry: no wall stands on the floor's edge from {a:?} to \
                         {b:?} (m); the space is not closed"
                    ),
                }
            })
        })
        .collect::<Result<_, _>>()?;
    Ok(Prism {
        plan,
        floor,
        ceiling,
        floor_face,
        ceiling_faces,
        walls,
    })
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
/// `floor`) to the ceiling and end at the edge's two corners.
fn wall_edge(
    w: &ModelFace,
    plan: &Plan,
    floor: f64,
    ceiling: f64,
    tol: f64,
) -> Result<usize, String> {
    let (p, q) = footprint(w, tol)?;
    let distance = |a: Point2, b: Point2| (a[0] - b[0]).hypot(a[1] - b[1]);
    let at_floor = |c: &Vec3| (c.z - floor).abs() <= tol;
    let at_ceiling = |c: &Vec3| (c.z - ceiling).abs() <= tol;
    if !w.polygon.iter().all(|c| at_floor(c) || at_ceiling(c))
        || !w.polygon.iter().any(at_floor)
        || !w.polygon.iter().any(at_ceiling)
    {
        return Err(format!(
            "the wall does not run from the floor (z = {floor} m) to the ceiling (z = \
             {ceiling} m); walls split along their height are not supported yet"
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
