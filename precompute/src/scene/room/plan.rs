//! A room's floor plan: a simple polygon in the x-y plane, checked, wound counter-clockwise
//! seen from above, and cut into convex pieces the mesher takes.
//!
//! The polygon operations are georust's `geo` (robust segment intersection, point in polygon,
//! the boolean difference that takes the footprints of obstacles out of a floor, and the
//! constrained Delaunay triangulation of spade); the triangles are then merged back into
//! convex pieces (Hertel and Mehlhorn's greedy removal of diagonals), which the mesher cuts
//! into patches far rounder than the triangles would be.

use geo::algorithm::line_intersection::{line_intersection, LineIntersection};
use geo::coordinate_position::CoordPos;
use geo::triangulate_delaunay::DelaunayTriangulationConfig;
use geo::{
    Area, BooleanOps, Buffer, Coord, CoordinatePosition, Line, LineString, MultiPolygon,
    Polygon as GeoPolygon, TriangulateDelaunay,
};

/// A corner of a plan, `[x, y]` in metres.
pub(crate) type Point2 = [f64; 2];

/// Why a plan was refused; corner and edge numbers are 1-based and as written (edge `k` runs
/// from corner `k` to corner `k + 1`, the last back to corner 1).
#[derive(Debug, Clone, PartialEq)]
pub(crate) enum PlanProblem {
    /// Fewer than three corners.
    TooFewCorners(usize),
    /// Two corners at the same point (within the tolerance); the second number is the later.
    RepeatedCorner(usize, usize),
    /// An edge of zero length (two consecutive corners at the same point).
    ZeroLengthEdge(usize),
    /// Two edges cross or overlap.
    SelfIntersecting(usize, usize),
    /// The polygon encloses no area.
    ZeroArea,
}

impl std::fmt::Display for PlanProblem {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            PlanProblem::TooFewCorners(n) => {
                write!(f, "a plan needs at least 3 corners, found {n}")
            }
            PlanProblem::RepeatedCorner(i, j) => {
                write!(
                    f,
                    "corners {i} and {j} are the same point: the room is not one polygon"
                )
            }
            PlanProblem::ZeroLengthEdge(k) => write!(
                f,
                "edge {k} (from corner {k} to the next) has zero length: drop the repeated corner"
            ),
            PlanProblem::SelfIntersecting(a, b) => write!(
                f,
                "edges {a} and {b} cross or overlap: the plan is not a simple polygon (list the \
                 corners in order around the room)"
            ),
            PlanProblem::ZeroArea => write!(f, "the plan encloses no area"),
        }
    }
}

/// A checked floor plan.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Plan {
    /// Corners counter-clockwise seen from above (z up), metres.
    pub corners: Vec<Point2>,
    /// For each edge `corners[i] → corners[i + 1]`, the 0-based index of the edge as written
    /// (a plan written clockwise is reversed, its edges keep their numbers).
    pub written_edge: Vec<usize>,
}

impl Plan {
    /// Checks `written` (metres) and winds it counter-clockwise. `tol` (m) is how close two
    /// corners may be and still count as one point.
    pub fn new(written: &[Point2], tol: f64) -> Result<Plan, PlanProblem> {
        let n = written.len();
        if n < 3 {
            return Err(PlanProblem::TooFewCorners(n));
        }
        let same = |a: Point2, b: Point2| (a[0] - b[0]).hypot(a[1] - b[1]) <= tol;
        for k in 0..n {
            if same(written[k], written[(k + 1) % n]) {
                return Err(PlanProblem::ZeroLengthEdge(k + 1));
            }
        }
        for i in 0..n {
            for j in i + 1..n {
                if same(written[i], written[j]) {
                    return Err(PlanProblem::RepeatedCorner(i + 1, j + 1));
                }
            }
        }
        let line = |k: usize| {
            let (a, b) = (written[k], written[(k + 1) % n]);
            Line::new(Coord { x: a[0], y: a[1] }, Coord { x: b[0], y: b[1] })
        };
        for i in 0..n {
            for j in i + 1..n {
                let adjacent = j == i + 1 || (i == 0 && j == n - 1);
                match line_intersection(line(i), line(j)) {
                    None => {}
                    // Neighbours meet at their shared corner, and only there.
                    Some(LineIntersection::SinglePoint { .. }) if adjacent => {}
                    Some(_) => return Err(PlanProblem::SelfIntersecting(i + 1, j + 1)),
                }
            }
        }
        let area = signed_area(written);
        let scale = bounding_diagonal(written);
        if area.abs() <= 1e-12 * scale * scale {
            return Err(PlanProblem::ZeroArea);
        }
        Ok(if area > 0.0 {
            Plan {
                corners: written.to_vec(),
                written_edge: (0..n).collect(),
            }
        } else {
            // Reversed: corner i is written corner n − 1 − i, and the edge from it to the next
            // is written edge n − 2 − i, run backwards.
            Plan {
                corners: written.iter().rev().copied().collect(),
                written_edge: (0..n).map(|i| (2 * n - 2 - i) % n).collect(),
            }
        })
    }

    /// The plan of an axis-aligned rectangle (metres), counter-clockwise from its smallest
    /// corner.
    pub fn rectangle(lo: Point2, hi: Point2) -> Plan {
        Plan {
            corners: vec![lo, [hi[0], lo[1]], hi, [lo[0], hi[1]]],
            written_edge: vec![0, 1, 2, 3],
        }
    }

    /// Number of corners (and edges).
    pub fn len(&self) -> usize {
        self.corners.len()
    }

    /// The edge `i` (counter-clockwise numbering) as its two ends.
    pub fn edge(&self, i: usize) -> (Point2, Point2) {
        (self.corners[i], self.corners[(i + 1) % self.len()])
    }

    /// The smallest and largest corner of its bounding rectangle, metres.
    pub fn bounds(&self) -> (Point2, Point2) {
        let mut lo = [f64::INFINITY; 2];
        let mut hi = [f64::NEG_INFINITY; 2];
        for c in &self.corners {
            for k in 0..2 {
                lo[k] = lo[k].min(c[k]);
                hi[k] = hi[k].max(c[k]);
            }
        }
        (lo, hi)
    }

    /// Whether it is an axis-aligned rectangle.
    pub fn is_rectangle(&self) -> bool {
        let (lo, hi) = self.bounds();
        self.len() == 4
            && self
                .corners
                .iter()
                .all(|c| (c[0] == lo[0] || c[0] == hi[0]) && (c[1] == lo[1] || c[1] == hi[1]))
    }

    fn polygon(&self) -> GeoPolygon<f64> {
        GeoPolygon::new(line_string(&self.corners), Vec::new())
    }

    /// Where `p` lies: inside, on the boundary (within `tol`, m) or outside.
    pub fn position(&self, p: Point2, tol: f64) -> CoordPos {
        if self.distance_to_boundary(p) <= tol {
            return CoordPos::OnBoundary;
        }
        self.polygon()
            .coordinate_position(&Coord { x: p[0], y: p[1] })
    }

    /// Whether `p` lies inside or on the boundary, within `tol` (m).
    pub fn holds(&self, p: Point2, tol: f64) -> bool {
        self.position(p, tol) != CoordPos::Outside
    }

    /// Distance from `p` to the nearest edge, m.
    pub fn distance_to_boundary(&self, p: Point2) -> f64 {
        (0..self.len())
            .map(|i| {
                let (a, b) = self.edge(i);
                segment_distance(p, a, b)
            })
            .fold(f64::INFINITY, f64::min)
    }

    /// Whether the rectangle `lo`..`hi` (m) lies inside the plan (its boundary may touch the
    /// plan's within `tol`, m): every corner inside and no plan corner strictly inside it.
    pub fn holds_rectangle(&self, lo: Point2, hi: Point2, tol: f64) -> bool {
        let corners = [lo, [hi[0], lo[1]], hi, [lo[0], hi[1]]];
        corners.iter().all(|&c| self.holds(c, tol))
            && !self.corners.iter().any(|c| {
                c[0] > lo[0] + tol && c[0] < hi[0] - tol && c[1] > lo[1] + tol && c[1] < hi[1] - tol
            })
            && self.holds([0.5 * (lo[0] + hi[0]), 0.5 * (lo[1] + hi[1])], tol)
    }

    /// The plan less the `holes` (convex polygons, metres, either winding) cut into convex
    /// pieces, counter-clockwise seen from above. Corners of the result within `tol` (m) of a
    /// corner of the plan or a hole are that corner exactly, so that the pieces meet the walls
    /// and the obstacles' sides edge to edge.
    pub fn convex_pieces(&self, holes: &[Vec<Point2>], tol: f64) -> Vec<Vec<Point2>> {
        let region = if holes.is_empty() {
            MultiPolygon::new(vec![self.polygon()])
        } else {
            let cut = MultiPolygon::new(
                holes
                    .iter()
                    .map(|h| GeoPolygon::new(line_string(h), Vec::new()))
                    .collect(),
            );
            let mut snapped = self.polygon().difference(&cut);
            let known: Vec<Point2> = self
                .corners
                .iter()
                .chain(holes.iter().flatten())
                .copied()
                .collect();
            snap(&mut snapped, &known, tol);
            snapped
        };
        pieces_of(&region)
    }

    /// The part of the plan inside the convex polygon `cell` (m, counter-clockwise) less the
    /// `holes`, in convex pieces as [`Plan::convex_pieces`]; corners within `tol` (m) of a
    /// corner of the plan, the cell or a hole are that corner exactly.
    pub fn convex_pieces_within(
        &self,
        cell: &[Point2],
        holes: &[Vec<Point2>],
        tol: f64,
    ) -> Vec<Vec<Point2>> {
        if cell.len() < 3 {
            return Vec::new();
        }
        let clip = GeoPolygon::new(line_string(cell), Vec::new());
        let mut region = self.polygon().intersection(&clip);
        if !holes.is_empty() {
            let cut = MultiPolygon::new(
                holes
                    .iter()
                    .map(|h| GeoPolygon::new(line_string(h), Vec::new()))
                    .collect(),
            );
            region = region.difference(&cut);
        }
        let known: Vec<Point2> = self
            .corners
            .iter()
            .chain(cell)
            .chain(holes.iter().flatten())
            .copied()
            .collect();
        snap(&mut region, &known, tol);
        pieces_of(&region)
    }

    /// The plan less a band of `margin` (m) along its edges, in convex pieces as
    /// [`Plan::convex_pieces`]: geo's inward buffer (round at the plan's reflex corners,
    /// where the points `margin` from the walls lie on a quarter circle).
    pub fn inset(&self, margin: f64, tol: f64) -> Vec<Vec<Point2>> {
        if margin <= 0.0 {
            return self.convex_pieces(&[], tol);
        }
        pieces_of(&self.polygon().buffer(-margin))
    }
}

/// The polygons of `region` (with holes) in convex pieces, counter-clockwise: constrained
/// Delaunay triangles merged while convex.
fn pieces_of(region: &MultiPolygon<f64>) -> Vec<Vec<Point2>> {
    let mut pieces = Vec::new();
    for polygon in region {
        let triangles = polygon
            .constrained_triangulation(DelaunayTriangulationConfig::default())
            .unwrap_or_default();
        let triangles = triangles
            .into_iter()
            .map(|t| {
                let mut c: Vec<Point2> = t.to_array().iter().map(|c| [c.x, c.y]).collect();
                if signed_area(&c) < 0.0 {
                    c.reverse();
                }
                c
            })
            .filter(|c| signed_area(c) > 0.0)
            .collect();
        pieces.extend(merge_convex(triangles));
    }
    pieces
}

/// A closed geo ring through `corners`.
fn line_string(corners: &[Point2]) -> LineString<f64> {
    LineString::from(corners.iter().map(|c| (c[0], c[1])).collect::<Vec<_>>())
}

/// Moves every coordinate of `region` within `tol` of one of `known` onto it.
fn snap(region: &mut MultiPolygon<f64>, known: &[Point2], tol: f64) {
    use geo::MapCoordsInPlace;
    region.map_coords_in_place(|c| {
        known
            .iter()
            .find(|k| (k[0] - c.x).hypot(k[1] - c.y) <= tol)
            .map_or(c, |k| Coord { x: k[0], y: k[1] })
    });
}

/// The signed area of a polygon (shoelace), m², positive counter-clockwise.
fn signed_area(c: &[Point2]) -> f64 {
    let n = c.len();
    0.5 * (0..n)
        .map(|i| {
            let (a, b) = (c[i], c[(i + 1) % n]);
            a[0] * b[1] - b[0] * a[1]
        })
        .sum::<f64>()
}

/// The diagonal of the box around `c`, m.
fn bounding_diagonal(c: &[Point2]) -> f64 {
    let (lo, hi) = Plan {
        corners: c.to_vec(),
        written_edge: Vec::new(),
    }
    .bounds();
    (hi[0] - lo[0]).hypot(hi[1] - lo[1])
}

/// Distance from `p` to the segment `a`–`b`, m.
fn segment_distance(p: Point2, a: Point2, b: Point2) -> f64 {
    let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
    let length2 = dx * dx + dy * dy;
    let t = if length2 > 0.0 {
        (((p[0] - a[0]) * dx + (p[1] - a[1]) * dy) / length2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    (p[0] - a[0] - t * dx).hypot(p[1] - a[1] - t * dy)
}

/// The turn at `b` from `a` to `c`: positive to the left (a convex corner of a
/// counter-clockwise polygon), zero straight on.
fn turn(a: Point2, b: Point2, c: Point2) -> f64 {
    (b[0] - a[0]) * (c[1] - b[1]) - (b[1] - a[1]) * (c[0] - b[0])
}

/// The area two simple polygons (m, either winding) have in common, m² (geo's boolean
/// intersection).
pub(crate) fn overlap_area(a: &[Point2], b: &[Point2]) -> f64 {
    let a = GeoPolygon::new(line_string(a), Vec::new());
    let b = GeoPolygon::new(line_string(b), Vec::new());
    a.intersection(&b).unsigned_area()
}

/// Whether the counter-clockwise polygon `c` is convex, allowing straight corners.
pub(crate) fn is_convex(c: &[Point2]) -> bool {
    let n = c.len();
    (0..n).all(|i| turn(c[(i + n - 1) % n], c[i], c[(i + 1) % n]) >= 0.0)
}

/// `c` without its straight corners (a corner on the line through its neighbours, within a
/// relative 1e-12).
fn without_straight_corners(c: Vec<Point2>) -> Vec<Point2> {
    let n = c.len();
    let keep: Vec<bool> = (0..n)
        .map(|i| {
            let (a, b, d) = (c[(i + n - 1) % n], c[i], c[(i + 1) % n]);
            let scale = (b[0] - a[0]).hypot(b[1] - a[1]) * (d[0] - b[0]).hypot(d[1] - b[1]);
            turn(a, b, d).abs() > 1e-12 * scale
        })
        .collect();
    c.into_iter()
        .zip(keep)
        .filter_map(|(p, k)| k.then_some(p))
        .collect()
}

/// Hertel–Mehlhorn: counter-clockwise triangles of a triangulation merged across their shared
/// edges while the union stays convex, in a fixed order (the result is deterministic).
fn merge_convex(mut pieces: Vec<Vec<Point2>>) -> Vec<Vec<Point2>> {
    'again: loop {
        for i in 0..pieces.len() {
            for j in i + 1..pieces.len() {
                if let Some(merged) = merge(&pieces[i], &pieces[j]) {
                    if is_convex(&merged) {
                        pieces[i] = merged;
                        pieces.remove(j);
                        continue 'again;
                    }
                }
            }
        }
        break;
    }
    pieces.into_iter().map(without_straight_corners).collect()
}

/// The union of two counter-clockwise polygons sharing an edge (`p → q` in `a`, `q → p` in
/// `b`), or `None` when they share none.
fn merge(a: &[Point2], b: &[Point2]) -> Option<Vec<Point2>> {
    let (na, nb) = (a.len(), b.len());
    for i in 0..na {
        let (p, q) = (a[i], a[(i + 1) % na]);
        for j in 0..nb {
            if b[j] == q && b[(j + 1) % nb] == p {
                // a from q round to p, then b's corners strictly between p and q.
                let mut out: Vec<Point2> = (1..=na).map(|k| a[(i + k) % na]).collect();
                out.extend((2..nb).map(|k| b[(j + k) % nb]));
                return Some(out);
            }
        }
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;

    const L: [Point2; 6] = [
        [0.0, 0.0],
        [12.0, 0.0],
        [12.0, 4.0],
        [7.0, 4.0],
        [7.0, 8.0],
        [0.0, 8.0],
    ];

    fn area(pieces: &[Vec<Point2>]) -> f64 {
        pieces.iter().map(|p| signed_area(p)).sum()
    }

    #[test]
    fn scene_plan_l_shape_is_cut_into_convex_pieces_of_its_area() {
        let plan = Plan::new(&L, 1e-9).unwrap();
        let pieces = plan.convex_pieces(&[], 1e-9);
        // One reflex corner: two convex pieces suffice and the greedy merge finds them.
        assert_eq!(pieces.len(), 2, "{pieces:?}");
        assert!(pieces.iter().all(|p| is_convex(p)));
        // 12 × 8 less the 5 × 4 notch = 76 m², exactly representable.
        assert_eq!(area(&pieces), 76.0);
        assert_eq!(signed_area(&plan.corners), 76.0);
    }

    #[test]
    fn scene_plan_holes_are_taken_out_exactly() {
        let plan = Plan::new(&L, 1e-9).unwrap();
        // A column against the south wall and one free-standing.
        let holes = vec![
            vec![[3.0, 0.0], [3.4, 0.0], [3.4, 0.4], [3.0, 0.4]],
            vec![[2.0, 5.0], [2.5, 5.0], [2.5, 5.5], [2.0, 5.5]],
        ];
        // The difference is computed on an integer grid; corners within 1 µm of a corner of
        // the plan or a hole are snapped back onto it.
        let pieces = plan.convex_pieces(&holes, 1e-6);
        assert!(pieces.iter().all(|p| is_convex(p)));
        let want = 76.0 - 0.16 - 0.25;
        assert!((area(&pieces) - want).abs() < 1e-12, "{}", area(&pieces));
        // No piece reaches into a hole: every centroid lies outside both.
        for p in &pieces {
            let c = p.iter().fold([0.0, 0.0], |s, q| [s[0] + q[0], s[1] + q[1]]);
            let c = [c[0] / p.len() as f64, c[1] / p.len() as f64];
            assert!(!(c[0] > 2.0 && c[0] < 2.5 && c[1] > 5.0 && c[1] < 5.5));
        }
    }

    #[test]
    fn scene_plan_clockwise_is_reversed_keeping_edge_numbers() {
        let cw: Vec<Point2> = L.iter().rev().copied().collect();
        let plan = Plan::new(&cw, 1e-9).unwrap();
        assert_eq!(plan.corners, L.to_vec());
        // Counter-clockwise edge 0 (0,0)→(12,0) is written edge 4: from cw[4] = (12,0)... to
        // cw[5] = (0,0), run backwards.
        assert_eq!(plan.written_edge, vec![4, 3, 2, 1, 0, 5]);
        for (i, &w) in plan.written_edge.iter().enumerate() {
            let (a, b) = plan.edge(i);
            assert_eq!((cw[(w + 1) % 6], cw[w]), (a, b));
        }
    }

    #[test]
    fn scene_plan_problems_name_corners_and_edges() {
        let bowtie = [[0.0, 0.0], [4.0, 4.0], [4.0, 0.0], [0.0, 4.0]];
        assert_eq!(
            Plan::new(&bowtie, 1e-9),
            Err(PlanProblem::SelfIntersecting(1, 3))
        );
        let repeated = [[0.0, 0.0], [4.0, 0.0], [4.0, 4.0], [4.0, 0.0], [0.0, 4.0]];
        assert_eq!(
            Plan::new(&repeated, 1e-9),
            Err(PlanProblem::RepeatedCorner(2, 4))
        );
        let zero = [[0.0, 0.0], [4.0, 0.0], [4.0, 0.0], [0.0, 4.0]];
        assert_eq!(Plan::new(&zero, 1e-9), Err(PlanProblem::ZeroLengthEdge(2)));
        let flat = [[0.0, 0.0], [4.0, 0.0], [8.0, 0.0]];
        assert!(Plan::new(&flat, 1e-9).is_err());
        assert_eq!(
            Plan::new(&[[0.0, 0.0], [1.0, 0.0]], 1e-9),
            Err(PlanProblem::TooFewCorners(2))
        );
    }

    #[test]
    fn scene_plan_point_positions() {
        let plan = Plan::new(&L, 1e-9).unwrap();
        assert_eq!(plan.position([1.0, 1.0], 1e-9), CoordPos::Inside);
        assert_eq!(plan.position([10.0, 6.0], 1e-9), CoordPos::Outside); // the notch
        assert_eq!(plan.position([7.0, 6.0], 1e-9), CoordPos::OnBoundary);
        assert!(plan.holds_rectangle([1.0, 1.0], [2.0, 2.0], 1e-9));
        assert!(!plan.holds_rectangle([6.0, 3.0], [8.0, 5.0], 1e-9));
        assert!((plan.distance_to_boundary([6.0, 6.0]) - 1.0).abs() < 1e-15);
    }
}
