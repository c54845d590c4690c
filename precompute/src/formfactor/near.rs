//! Geometry of the refinement of the outer integral where a source comes close to its target:
//! distances between convex polygons and the splitting of source cells into pieces of bounded
//! aspect ratio.
//!
//! The kernel `F_{dA→A_j}(x)` is analytic in `x` away from the target, and its nearest
//! singularity lies on the target: a Gauss rule on a source cell converges at a rate set by
//! the ratio of the cell's distance to the target to its size. So a cell is split until that
//! ratio is at least a stated multiple (module `pair`), whether the patches touch (distance 0:
//! the split stops at a depth), nearly touch (a gap of 1 mm at a 1 m patch) or meet in a
//! T-junction. Only the target's outline is singular ([`outline_distance`]). Thin cells are
//! first cut across their long side, so that the pieces the ratio is measured on are roughly
//! round.

use crate::geometry::Vec3;

/// Aspect ratio above which a cell is halved across its long side instead of being split in
/// four: quadrilaterals whose long side exceeds this multiple of the short one, triangles
/// whose longest edge exceeds this multiple of the height over it (an equilateral triangle has
/// 1.15, a right isosceles one 2).
pub(super) const ASPECT_BOUND: f64 = 2.5;

/// Largest distance between two corners of a convex cell (its diameter), metres.
pub(super) fn diameter(cell: &[Vec3]) -> f64 {
    let mut d = 0.0_f64;
    for (k, &p) in cell.iter().enumerate() {
        for &q in &cell[k + 1..] {
            d = d.max((q - p).length());
        }
    }
    d
}

/// Distance from `p` to the segment `a`–`b`, metres.
fn point_segment(p: Vec3, a: Vec3, b: Vec3) -> f64 {
    let d = b - a;
    let len2 = d.dot(d);
    let t = if len2 > 0.0 {
        ((p - a).dot(d) / len2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    (p - (a + d * t)).length()
}

/// Distance between the segments `p1`–`q1` and `p2`–`q2`, metres (Ericson, *Real-Time
/// Collision Detection*, §5.1.9).
fn segment_segment(p1: Vec3, q1: Vec3, p2: Vec3, q2: Vec3) -> f64 {
    let (d1, d2, r) = (q1 - p1, q2 - p2, p1 - p2);
    let (a, e, f) = (d1.dot(d1), d2.dot(d2), d2.dot(r));
    if a <= 0.0 || e <= 0.0 {
        return if a <= 0.0 {
            point_segment(p1, p2, q2)
        } else {
            point_segment(p2, p1, q1)
        };
    }
    let c = d1.dot(r);
    let b = d1.dot(d2);
    let denom = a * e - b * b;
    let mut s = if denom > 0.0 {
        ((b * f - c * e) / denom).clamp(0.0, 1.0)
    } else {
        0.0
    };
    let mut t = (b * s + f) / e;
    if t < 0.0 {
        t = 0.0;
        s = (-c / a).clamp(0.0, 1.0);
    } else if t > 1.0 {
        t = 1.0;
        s = ((b - c) / a).clamp(0.0, 1.0);
    }
    ((p1 + d1 * s) - (p2 + d2 * t)).length()
}

/// Unit normal of a convex polygon (Newell's method); zero for a degenerate one.
fn normal_of(poly: &[Vec3]) -> Vec3 {
    let mut n = Vec3::ZERO;
    for (k, &a) in poly.iter().enumerate() {
        let b = poly[(k + 1) % poly.len()];
        n += a.cross(b);
    }
    let len = n.length();
    if len > 0.0 {
        n / len
    } else {
        Vec3::ZERO
    }
}

/// Is the projection of `p` on the plane of the convex `poly` (unit normal `n`) inside it?
fn projects_inside(p: Vec3, poly: &[Vec3], n: Vec3) -> bool {
    let len = poly.len();
    len >= 3
        && (0..len).all(|k| {
            let (a, b) = (poly[k], poly[(k + 1) % len]);
            (b - a).cross(p - a).dot(n) >= 0.0
        })
}

/// Distance from the convex planar polygon `cell` to the outline (the edges) of the convex
/// polygon `outline`, metres: 0 when an edge of the outline touches or crosses the cell.
///
/// This is the distance that sets how smooth the kernel toward `outline` is over the cell:
/// Lambert's contour integral is analytic in the viewing point except on the target's edges,
/// so a cell that faces the middle of a parallel target a millimetre away is smooth, and only
/// cells near the target's edges need refining.
pub(super) fn outline_distance(cell: &[Vec3], outline: &[Vec3]) -> f64 {
    let n = normal_of(cell);
    let Some(&o) = cell.first() else {
        return f64::INFINITY;
    };
    let mut d = f64::INFINITY;
    for (k, &p) in outline.iter().enumerate() {
        if projects_inside(p, cell, n) {
            d = d.min(n.dot(p - o).abs());
        }
        // An edge of the outline that crosses the cell's interior.
        let q = outline[(k + 1) % outline.len()];
        let (sp, sq) = (n.dot(p - o), n.dot(q - o));
        if (sp > 0.0 && sq < 0.0) || (sp < 0.0 && sq > 0.0) {
            let x = p + (q - p) * (sp / (sp - sq));
            if projects_inside(x, cell, n) {
                return 0.0;
            }
        }
        for (i, &p1) in cell.iter().enumerate() {
            d = d.min(segment_segment(p1, cell[(i + 1) % cell.len()], p, q));
        }
    }
    d
}

/// How a cell is split: in two across its long side (a thin cell) or in four.
pub(super) enum Split {
    /// Two halves: the cell was thin; the halves are closer to round.
    Halves([Vec<Vec3>; 2]),
    /// Four cells at the edge midpoints ([`super::quadrature::split_cell`]), or the triangles
    /// of the fan of a polygon of more than four corners.
    Cells(Vec<Vec<Vec3>>),
}

/// Splits a convex cell: a quadrilateral whose long side exceeds [`ASPECT_BOUND`] times its
/// short side is halved across the long side, a triangle whose longest edge exceeds
/// [`ASPECT_BOUND`] times its height over that edge is halved by [`split_thin_triangle`];
/// other cells are split in four.
pub(super) fn split(cell: &[Vec3]) -> Split {
    let mid = |p: Vec3, q: Vec3| (p + q) * 0.5;
    match *cell {
        [a, b, c, d] => {
            let lu = (b - a).length().max((c - d).length());
            let lv = (d - a).length().max((c - b).length());
            if lu > ASPECT_BOUND * lv {
                let (ab, dc) = (mid(a, b), mid(d, c));
                return Split::Halves([vec![a, ab, dc, d], vec![ab, b, c, dc]]);
            }
            if lv > ASPECT_BOUND * lu {
                let (ad, bc) = (mid(a, d), mid(b, c));
                return Split::Halves([vec![a, b, bc, ad], vec![ad, bc, c, d]]);
            }
        }
        [a, b, c] => {
            let twice_area = (b - a).cross(c - a).length();
            let longest = (b - a).length().max((c - b).length()).max((a - c).length());
            if twice_area > 0.0 && longest * longest > ASPECT_BOUND * twice_area {
                return Split::Halves(split_thin_triangle(a, b, c));
            }
        }
        _ => {}
    }
    Split::Cells(super::quadrature::split_cell(cell))
}

/// Cosine of the largest angle above which a thin triangle counts as flat (a cap, angle above
/// 120°) rather than pointed (a needle).
const CAP_COSINE: f64 = -0.5;

/// Halves a thin triangle so that the pieces get rounder: a flat one (a cap) from its obtuse
/// corner to the midpoint of the opposite edge, giving two pointed ones; a pointed one (a
/// needle) across its length at the midpoints of its two long edges, giving the half-size
/// needle at its tip and a trapezoid (a quadrilateral, halved across its long side next).
/// Halving a needle's longest edge instead would give needles and caps again.
fn split_thin_triangle(a: Vec3, b: Vec3, c: Vec3) -> [Vec<Vec3>; 2] {
    let mid = |p: Vec3, q: Vec3| (p + q) * 0.5;
    // Rotations of the corners (same winding): (corner, next, previous).
    let turns = [(a, b, c), (b, c, a), (c, a, b)];
    let cosine = |(p, q, r): (Vec3, Vec3, Vec3)| {
        let (u, v) = (q - p, r - p);
        u.dot(v) / (u.length() * v.length()).max(f64::MIN_POSITIVE)
    };
    let (mut widest, mut sharpest) = (turns[0], turns[0]);
    for t in turns {
        if cosine(t) < cosine(widest) {
            widest = t;
        }
        if cosine(t) > cosine(sharpest) {
            sharpest = t;
        }
    }
    if cosine(widest) < CAP_COSINE {
        let (p, q, r) = widest;
        let m = mid(q, r);
        return [vec![p, q, m], vec![p, m, r]];
    }
    let (tip, q, r) = sharpest;
    let (mq, mr) = (mid(tip, q), mid(tip, r));
    [vec![tip, mq, mr], vec![mq, q, r, mr]]
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Distance between two convex planar polygons (0 when they touch or cross): the nearer of
    /// each one's distance to the other's outline.
    fn polygon_distance(a: &[Vec3], b: &[Vec3]) -> f64 {
        outline_distance(a, b).min(outline_distance(b, a))
    }

    fn square(z: f64, x0: f64) -> Vec<Vec3> {
        vec![
            Vec3::new(x0, 0.0, z),
            Vec3::new(x0 + 1.0, 0.0, z),
            Vec3::new(x0 + 1.0, 1.0, z),
            Vec3::new(x0, 1.0, z),
        ]
    }

    #[test]
    fn distances_between_polygons_match_hand_checked_cases() {
        // Parallel unit squares 0.01 m apart, face to face: the gap.
        assert!((polygon_distance(&square(0.0, 0.0), &square(0.01, 0.0)) - 0.01).abs() < 1e-15);
        // Coplanar, 0.5 m apart edge to edge.
        assert!((polygon_distance(&square(0.0, 0.0), &square(0.0, 1.5)) - 0.5).abs() < 1e-15);
        // A wall (plane y = 0.5, x from 0 to 1) standing 1 mm above the floor square: the
        // floor's edge-free interior is 1 mm below the wall's bottom edge.
        let wall = vec![
            Vec3::new(0.0, 0.5, 0.001),
            Vec3::new(0.0, 0.5, 1.0),
            Vec3::new(1.0, 0.5, 1.0),
            Vec3::new(1.0, 0.5, 0.001),
        ];
        assert!((polygon_distance(&square(0.0, 0.0), &wall) - 0.001).abs() < 1e-15);
        // The same wall down to the floor crosses it: 0.
        let mut touching = wall.clone();
        touching[0].z = -0.2;
        touching[3].z = -0.2;
        assert_eq!(polygon_distance(&square(0.0, 0.0), &touching), 0.0);
        // Skew edges: the corner (1, 1, 0) and the segment from (2, 2, 1) to (2, 2, -1).
        let far = vec![
            Vec3::new(2.0, 2.0, -1.0),
            Vec3::new(3.0, 2.0, 1.0),
            Vec3::new(2.0, 2.0, 1.0),
        ];
        let want = 2.0_f64.sqrt();
        assert!((polygon_distance(&square(0.0, 0.0), &far) - want).abs() < 1e-12);
        // A quarter square facing the middle of a parallel unit square 1 mm away: 1 mm to the
        // square, 0.25 m (in the plane) and 1 mm (across) to its outline.
        let small = vec![
            Vec3::new(0.25, 0.25, 0.0),
            Vec3::new(0.75, 0.25, 0.0),
            Vec3::new(0.75, 0.75, 0.0),
            Vec3::new(0.25, 0.75, 0.0),
        ];
        let top = square(0.001, 0.0);
        assert!((polygon_distance(&small, &top) - 0.001).abs() < 1e-15);
        let want = (0.25_f64 * 0.25 + 0.001 * 0.001).sqrt();
        assert!((outline_distance(&small, &top) - want).abs() < 1e-15);
        // The outline of a wall crossing the cell.
        assert_eq!(outline_distance(&square(0.0, 0.0), &touching), 0.0);
    }

    #[test]
    fn thin_cells_are_halved_across_their_long_side() {
        let strip = vec![
            Vec3::new(0.0, 0.0, 0.0),
            Vec3::new(2.0, 0.0, 0.0),
            Vec3::new(2.0, 0.025, 0.0),
            Vec3::new(0.0, 0.025, 0.0),
        ];
        let Split::Halves([a, b]) = split(&strip) else {
            panic!("a 80:1 strip must be halved");
        };
        assert!((diameter(&a) - diameter(&b)).abs() < 1e-12);
        assert!(diameter(&a) < 0.6 * diameter(&strip));
        let needle = vec![
            Vec3::new(0.0, 0.0, 0.0),
            Vec3::new(1.0, 0.0, 0.0),
            Vec3::new(1.0, 0.05, 0.0),
        ];
        let Split::Halves([tip, trapezoid]) = split(&needle) else {
            panic!("a 20:1 needle must be halved");
        };
        assert_eq!((tip.len(), trapezoid.len()), (3, 4));
        let flat = vec![
            Vec3::new(0.0, 0.0, 0.0),
            Vec3::new(1.0, 0.0, 0.0),
            Vec3::new(0.5, 0.02, 0.0),
        ];
        let Split::Halves([left, right]) = split(&flat) else {
            panic!("a flat triangle must be halved");
        };
        assert_eq!((left.len(), right.len()), (3, 3));
        let area = |t: &[Vec3]| 0.5 * (t[1] - t[0]).cross(t[2] - t[0]).length();
        assert!((area(&left) + area(&right) - area(&flat)).abs() < 1e-15);
        assert!(matches!(split(&square(0.0, 0.0)), Split::Cells(c) if c.len() == 4));
    }
}
