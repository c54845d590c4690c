//! Checking faces and cutting them into patches no longer than a given edge.
//!
//! Quadrilaterals become a regular grid of convex quads; triangles become m² similar triangles
//! (each edge cut into m equal parts; m = 2 is midpoint subdivision). Both depend only on the
//! corners and the edge length, so meshing is deterministic.

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

/// Cuts a checked convex face into patches whose edges are at most `max_edge` (metres).
///
/// A quad gives a grid of quads, a triangle m² triangles, a larger polygon a fan of triangles
/// from its first corner, each subdivided. The pieces keep the face's winding.
pub(crate) fn mesh_face(corners: &[Vec3], max_edge: f64, out: &mut Vec<Polygon>) {
    match corners {
        [a, b, c] => mesh_triangle(*a, *b, *c, max_edge, out),
        [a, b, c, d] => mesh_quad(*a, *b, *c, *d, max_edge, out),
        _ => {
            for i in 1..corners.len().saturating_sub(1) {
                mesh_triangle(corners[0], corners[i], corners[i + 1], max_edge, out);
            }
        }
    }
}

/// How many patches [`mesh_face`] would make of a face, without making them (f64, so that an
/// absurd count is a number rather than an overflow).
pub(crate) fn estimate(corners: &[Vec3], max_edge: f64) -> f64 {
    // As `parts` does, so that a side of exactly k × max_edge counts k.
    let count = |length: f64| (length / max_edge * (1.0 - 1e-12)).ceil().max(1.0);
    let triangle = |a: Vec3, b: Vec3, c: Vec3| {
        let m = count((b - a).length().max((c - b).length()).max((a - c).length()));
        m * m
    };
    match corners {
        [a, b, c] => triangle(*a, *b, *c),
        [a, b, c, d] => {
            count((*b - *a).length().max((*c - *d).length()))
                * count((*d - *a).length().max((*c - *b).length()))
        }
        _ => (1..corners.len().saturating_sub(1))
            .map(|i| triangle(corners[0], corners[i], corners[i + 1]))
            .sum(),
    }
}

/// Cuts a face into triangles: a quad along its shorter diagonal, other polygons as a fan.
pub(crate) fn triangulate(corners: &[Vec3]) -> Vec<Vec<Vec3>> {
    if let [a, b, c, d] = corners {
        if (*c - *a).length() <= (*d - *b).length() {
            return vec![vec![*a, *b, *c], vec![*a, *c, *d]];
        }
        return vec![vec![*a, *b, *d], vec![*b, *c, *d]];
    }
    (1..corners.len().saturating_sub(1))
        .map(|i| vec![corners[0], corners[i], corners[i + 1]])
        .collect()
}

/// How many equal parts make pieces of `length` no longer than `max_edge`.
fn parts(length: f64, max_edge: f64) -> usize {
    let k = (length / max_edge * (1.0 - 1e-12)).ceil();
    if k.is_finite() && k >= 1.0 {
        k as usize
    } else {
        1
    }
}

/// Bilinear grid of a convex quad a-b-c-d: u runs a→b (and d→c), v runs a→d (and b→c).
fn mesh_quad(a: Vec3, b: Vec3, c: Vec3, d: Vec3, max_edge: f64, out: &mut Vec<Polygon>) {
    let nu = parts((b - a).length().max((c - d).length()), max_edge);
    let nv = parts((d - a).length().max((c - b).length()), max_edge);
    let point = |i: usize, j: usize| {
        let u = i as f64 / nu as f64;
        let v = j as f64 / nv as f64;
        let bottom = a + (b - a) * u;
        let top = d + (c - d) * u;
        bottom + (top - bottom) * v
    };
    for j in 0..nv {
        for i in 0..nu {
            out.push(Polygon::new(vec![
                point(i, j),
                point(i + 1, j),
                point(i + 1, j + 1),
                point(i, j + 1),
            ]));
        }
    }
}

/// Regular subdivision of a triangle into m² similar triangles.
fn mesh_triangle(a: Vec3, b: Vec3, c: Vec3, max_edge: f64, out: &mut Vec<Polygon>) {
    let longest = (b - a).length().max((c - b).length()).max((a - c).length());
    let m = parts(longest, max_edge);
    let point =
        |i: usize, j: usize| a + (b - a) * (i as f64 / m as f64) + (c - a) * (j as f64 / m as f64);
    for j in 0..m {
        for i in 0..m - j {
            out.push(Polygon::new(vec![
                point(i, j),
                point(i + 1, j),
                point(i, j + 1),
            ]));
            if i + j + 1 < m {
                out.push(Polygon::new(vec![
                    point(i + 1, j),
                    point(i + 1, j + 1),
                    point(i, j + 1),
                ]));
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn unit_square() -> Vec<Vec3> {
        vec![
            Vec3::new(0.0, 0.0, 0.0),
            Vec3::new(1.0, 0.0, 0.0),
            Vec3::new(1.0, 1.0, 0.0),
            Vec3::new(0.0, 1.0, 0.0),
        ]
    }

    #[test]
    fn scene_mesh_unit_quad_at_quarter_metre_gives_16_patches() {
        let mut out = Vec::new();
        mesh_face(&unit_square(), 0.25, &mut out);
        assert_eq!(out.len(), 16);
        for p in &out {
            assert!((p.area() - 1.0 / 16.0).abs() < 1e-15);
            assert!((p.normal() - Vec3::new(0.0, 0.0, 1.0)).length() < 1e-15);
        }
    }

    #[test]
    fn scene_mesh_triangle_keeps_area_winding_and_edge_bound() {
        let (a, b, c) = (
            Vec3::new(0.0, 0.0, 0.0),
            Vec3::new(2.0, 0.0, 0.0),
            Vec3::new(0.0, 0.0, 1.0),
        );
        let whole = Polygon::new(vec![a, b, c]);
        let mut out = Vec::new();
        mesh_face(&[a, b, c], 0.3, &mut out);
        let m = 8; // ceil(sqrt(5) / 0.3)
        assert_eq!(out.len(), m * m);
        let total: f64 = out.iter().map(Polygon::area).sum();
        assert!((total - whole.area()).abs() < 1e-12);
        for p in &out {
            assert!((p.normal() - whole.normal()).length() < 1e-12);
            let n = p.vertices.len();
            for i in 0..n {
                assert!((p.vertices[(i + 1) % n] - p.vertices[i]).length() <= 0.3 + 1e-12);
            }
        }
    }

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
