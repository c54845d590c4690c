//! The checks a face passes before it is meshed: enough corners, finite, not degenerate,
//! planar and convex.

use crate::geometry::{Polygon, Vec3};

/// Why a face was rejected (the caller adds the surface and file).
#[derive(Debug, PartialEq)]
pub(crate) enum FaceProblem {
    /// Fewer than three corners.
    TooFewCorners(usize),
    /// A coordinate is NaN or infinite.
    NotFinite,
    /// Zero area or a zero-length edge (area in m², edge in m).
    Degenerate { area: f64, shortest_edge: f64 },
    /// A corner is further from the mean plane than the tolerance (distance in m, and as a
    /// fraction of the longest diagonal).
    NonPlanar { distance: f64, relative: f64 },
    /// The polygon is not convex.
    NonConvex,
}

impl std::fmt::Display for FaceProblem {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            FaceProblem::TooFewCorners(n) => {
                write!(f, "a face needs at least 3 corners, found {n}")
            }
            FaceProblem::NotFinite => write!(f, "a coordinate is not a finite number"),
            FaceProblem::Degenerate {
                area,
                shortest_edge,
            } => write!(
                f,
                "degenerate face (area {area:.3e} m², shortest edge {shortest_edge:.3e} m)"
            ),
            FaceProblem::NonPlanar { distance, relative } => write!(
                f,
                "non-planar face: a corner is {distance:.3e} m ({relative:.2e} of the diagonal) \
                 from the mean plane; fix the corners or set `triangulate = true` for this \
                 surface in [surfaces]"
            ),
            FaceProblem::NonConvex => write!(f, "face is not convex"),
        }
    }
}

/// Relative size below which an edge or area counts as zero.
const DEGENERATE: f64 = 1e-9;

/// Checks a face before meshing: finite, at least 3 corners, non-degenerate, planar within
/// `planarity` (fraction of the longest diagonal) and convex.
pub(crate) fn check_face(corners: &[Vec3], planarity: f64) -> Result<(), FaceProblem> {
    let n = corners.len();
    if n < 3 {
        return Err(FaceProblem::TooFewCorners(n));
    }
    if corners.iter().any(|c| !c.is_finite()) {
        return Err(FaceProblem::NotFinite);
    }
    let edges: Vec<Vec3> = (0..n).map(|i| corners[(i + 1) % n] - corners[i]).collect();
    let longest = edges.iter().map(|e| e.length()).fold(0.0, f64::max);
    let shortest = edges
        .iter()
        .map(|e| e.length())
        .fold(f64::INFINITY, f64::min);
    let polygon = Polygon::new(corners.to_vec());
    let area = polygon.area();
    if longest == 0.0 || shortest <= DEGENERATE * longest || area <= DEGENERATE * longest * longest
    {
        return Err(FaceProblem::Degenerate {
            area,
            shortest_edge: shortest,
        });
    }
    let normal = polygon.normal();
    let centre = corners.iter().fold(Vec3::ZERO, |a, &c| a + c) / n as f64;
    let distance = corners
        .iter()
        .map(|&c| (c - centre).dot(normal).abs())
        .fold(0.0, f64::max);
    let diagonal = (0..n)
        .flat_map(|i| (i + 1..n).map(move |j| (i, j)))
        .map(|(i, j)| (corners[j] - corners[i]).length())
        .fold(0.0, f64::max);
    let relative = distance / diagonal;
    if relative > planarity {
        return Err(FaceProblem::NonPlanar { distance, relative });
    }
    // Convex: every turn goes the same way as the normal.
    for i in 0..n {
        let turn = edges[i].cross(edges[(i + 1) % n]).dot(normal);
        if turn <= DEGENERATE * longest * longest {
            return Err(FaceProblem::NonConvex);
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::super::fixtures::unit_square;
    use super::*;

    #[test]
    fn scene_mesh_checks_reject_bad_faces() {
        let mut bent = unit_square();
        bent[2].z = 0.1;
        assert!(matches!(
            check_face(&bent, 1e-3),
            Err(FaceProblem::NonPlanar { .. })
        ));
        let mut flat = unit_square();
        flat[2] = flat[1];
        assert!(matches!(
            check_face(&flat, 1e-3),
            Err(FaceProblem::Degenerate { .. })
        ));
        let mut dart = unit_square();
        dart[2] = Vec3::new(0.2, 0.2, 0.0);
        assert_eq!(check_face(&dart, 1e-3), Err(FaceProblem::NonConvex));
        assert_eq!(check_face(&unit_square(), 1e-3), Ok(()));
    }
}
