//! Openings of any convex polygon (a triangle, a trapezoid, a rectangle set askew), not only
//! rectangles along their face's edges. Each is checked as a polygon (planar, simple,
//! convex); a face holding one is cut by geo's boolean difference of the face less all its
//! openings, and what is left is cut into convex pieces as a floor plan is
//! ([`Plan::convex_pieces`]: spade's constrained Delaunay triangles merged while convex).

use super::frame::Frame;
use crate::geometry::{Polygon, Vec3};
use crate::scene::room::{is_convex, Plan, PlanProblem, Point2};

/// Why the polygon `corners` (m) cannot be the opening `name`, if it cannot: fewer than three
/// corners, a corner farther than `tol` (m) from the polygon's mean plane, edges crossing,
/// corners repeated, or a reflex corner (the opening's patches and the cut around it are
/// convex pieces; a concave opening is written as convex ones side by side).
pub(super) fn problem(name: &str, corners: &[Vec3], tol: f64) -> Option<String> {
    let n = corners.len();
    if n < 3 {
        return Some(format!(
            "opening `{name}` has {n} corners; a polygon needs at least 3"
        ));
    }
    let Some(normal) = plane_normal(corners) else {
        return Some(format!(
            "opening `{name}` encloses no area: its corners lie on one line"
        ));
    };
    let centre = corners.iter().fold(Vec3::ZERO, |a, &c| a + c) / n as f64;
    let off = corners
        .iter()
        .map(|&c| (c - centre).dot(normal).abs())
        .fold(0.0, f64::max);
    if off > tol {
        return Some(format!(
            "opening `{name}` is not planar: a corner lies {off:.3e} m off the polygon's mean \
             plane (tolerance {tol:.1e} m)"
        ));
    }
    let u = (corners[1] - corners[0]).normalized();
    let v = normal.cross(u);
    let flat: Vec<Point2> = corners
        .iter()
        .map(|&c| [(c - corners[0]).dot(u), (c - corners[0]).dot(v)])
        .collect();
    match Plan::new(&flat, tol) {
        Err(problem) => Some(format!(
            "opening `{name}` is not a simple polygon: {}",
            describe(&problem)
        )),
        Ok(plan) if !is_convex(&plan.corners) => Some(format!(
            "opening `{name}` is not convex: write it as convex openings side by side"
        )),
        Ok(_) => None,
    }
}

/// The unit normal of the plane through `corners` (Newell's, or, when the polygon's signed
/// area vanishes as a bow-tie's does, that of its first three corners not on one line).
fn plane_normal(corners: &[Vec3]) -> Option<Vec3> {
    let newell = Polygon::new(corners.to_vec()).normal();
    if newell.length() > 0.5 {
        return Some(newell);
    }
    let a = corners[0];
    corners
        .iter()
        .zip(corners.iter().skip(1))
        .map(|(&b, &c)| (b - a).cross(c - a))
        .find(|n| n.length() > 0.0)
        .map(Vec3::normalized)
}

/// A plan problem in the words of an opening's corners and edges (1-based, as written; edge
/// `k` runs from corner `k` to the next).
fn describe(problem: &PlanProblem) -> String {
    match problem {
        PlanProblem::TooFewCorners(n) => format!("it has {n} corners"),
        PlanProblem::RepeatedCorner(i, j) => format!("corners {i} and {j} are the same point"),
        PlanProblem::ZeroLengthEdge(k) => {
            format!("edge {k} has zero length (corner {k} is repeated)")
        }
        PlanProblem::SelfIntersecting(a, b) => {
            format!("edges {a} and {b} cross (list the corners in order around the opening)")
        }
        PlanProblem::ZeroArea => "it encloses no area".into(),
    }
}

/// The face of `frame` less the `holes` (in the face's plane coordinates, [`Frame::to_plane`],
/// any winding) in convex pieces wound as the face, corners in metres. Corners of the pieces
/// within `tol` (m) of a corner of the face or a hole are that corner exactly, so that the
/// pieces meet the openings edge to edge.
pub(super) fn cut_around(
    frame: &Frame,
    holes: &[Vec<Point2>],
    tol: f64,
) -> Result<Vec<Vec<Vec3>>, PlanProblem> {
    let face = Plan::new(&frame.outline_in_plane(), tol)?;
    // The plane coordinates run counter-clockwise about ab × ad; the face may face the other
    // way.
    let reversed = frame.ab.cross(frame.ad).dot(frame.normal) < 0.0;
    Ok(face
        .convex_pieces(holes, tol)
        .into_iter()
        .map(|piece| {
            let mut corners: Vec<Vec3> = piece.iter().map(|&q| frame.point_in_plane(q)).collect();
            if reversed {
                corners.reverse();
            }
            corners
        })
        .collect())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn v(x: f64, y: f64, z: f64) -> Vec3 {
        Vec3::new(x, y, z)
    }

    #[test]
    fn scene_opening_polygon_problems_are_named() {
        let triangle = [v(1.0, 0.0, 1.0), v(2.0, 0.0, 1.0), v(1.5, 0.0, 2.0)];
        assert_eq!(problem("w", &triangle, 1e-6), None);
        let bent = [
            v(1.0, 0.0, 1.0),
            v(2.0, 0.0, 1.0),
            v(2.0, 0.1, 2.0),
            v(1.0, 0.0, 2.0),
        ];
        let m = problem("w", &bent, 1e-6).unwrap();
        assert!(m.contains("`w` is not planar"), "{m}");
        let bowtie = [
            v(0.0, 0.0, 0.0),
            v(1.0, 0.0, 1.0),
            v(1.0, 0.0, 0.0),
            v(0.0, 0.0, 1.0),
        ];
        let m = problem("w", &bowtie, 1e-6).unwrap();
        assert!(
            m.contains("not a simple polygon: edges 1 and 3 cross"),
            "{m}"
        );
        let arrow = [
            v(0.0, 0.0, 0.0),
            v(2.0, 0.0, 0.0),
            v(1.0, 0.0, 0.5),
            v(1.0, 0.0, 2.0),
        ];
        let m = problem("w", &arrow, 1e-6).unwrap();
        assert!(m.contains("`w` is not convex"), "{m}");
        let line = [v(0.0, 0.0, 0.0), v(1.0, 0.0, 0.0), v(2.0, 0.0, 0.0)];
        let m = problem("w", &line, 1e-6).unwrap();
        assert!(m.contains("encloses no area"), "{m}");
    }
}
