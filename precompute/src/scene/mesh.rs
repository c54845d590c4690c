//! Checking faces and cutting them into patches no longer than a given edge, of bounded
//! aspect ratio where the face allows.
//!
//! Quadrilaterals become a regular grid of convex quads; triangles within [`ASPECT_BOUND`]
//! become m² similar triangles (each edge cut into m equal parts; m = 2 is midpoint
//! subdivision). Thinner triangles (slivers) and polygons of more than four corners are cut
//! by straight lines across their long side ([`cut`]), not fanned from a corner: a fan's
//! triangles all meet at one corner and run across the whole face, and a sliver's similar
//! triangles are as thin as the sliver. Everything depends only on the corners and the edge
//! length, so meshing is deterministic.
//!
//! The aspect ratio is [`geometry::aspect`](crate::geometry::aspect): the long side over the
//! short side of the narrowest rectangle around a patch. Away from a face's boundary the
//! pieces are about `max_edge` on each side (aspect under 2), and every piece at least
//! [`NARROW`] × `max_edge` wide is within [`ASPECT_BOUND`]; the small pieces left along a
//! slanted or curved outline may be thinner. A face narrower than
//! `max_edge` is cut across its length only, into pieces at most `max_edge` long: rounder
//! pieces would multiply the patch count by their aspect without resolving the exitance any
//! finer along the face, and the form-factor quadrature refines thin patches itself. A patch
//! holding a corner sharper than the bound allows is as thin as that corner.

use crate::geometry::{aspect, narrowest, Polygon, Vec3};

/// Aspect ratio ([`aspect`]) up to which a triangle is subdivided into similar triangles and
/// a polygon's pieces are cut down to quadrilaterals and triangles: a right isosceles
/// triangle has 2, a 2 × 1 rectangle 2.
pub(crate) const ASPECT_BOUND: f64 = 2.5;

/// Most corners a patch cut from a polygon keeps: a piece of more is halved across its long
/// side. The form-factor quadrature maps quadrilaterals and triangles directly but fans larger
/// polygons from a corner: a closed 32-sided prism's base rows missed 1 by 1.2e-2 with pieces
/// of up to eight corners, and miss it by under 7e-6 in quadrilaterals and triangles
/// (`c79_c109_closed_faceted_prisms_and_pyramids_close`).
pub(crate) const MAX_CORNERS: usize = 4;

/// A piece narrower than this share of `max_edge` is narrow: [`cut`] makes it no longer than
/// `max_edge` but no rounder (a wider one is cut to within [`ASPECT_BOUND`]).
pub(crate) const NARROW: f64 = 0.25;

/// How deep [`cut`] recurses at most (a guard: each level halves a piece or cuts it into
/// pieces no longer than `max_edge`, so real faces stop far earlier).
const MAX_DEPTH: usize = 64;

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

/// Cuts a checked convex face into convex patches whose edges are at most `max_edge`
/// (metres), with the face's winding.
///
/// A quad gives a grid of quads, a triangle within [`ASPECT_BOUND`] m² similar triangles;
/// a thinner triangle or a polygon of more than four corners is [`cut`] across its long side.
pub(crate) fn mesh_face(corners: &[Vec3], max_edge: f64, out: &mut Vec<Polygon>) {
    match corners {
        [a, b, c] if aspect(corners) <= ASPECT_BOUND => mesh_triangle(*a, *b, *c, max_edge, out),
        [a, b, c, d] => mesh_quad(*a, *b, *c, *d, max_edge, out),
        _ => cut(corners.to_vec(), max_edge, 0, out),
    }
}

/// Cuts convex `piece` by straight lines until every piece is at most `max_edge` long, every
/// edge at most `max_edge`, every piece within [`ASPECT_BOUND`] unless it is [`NARROW`], and
/// no piece has more than [`MAX_CORNERS`] corners.
///
/// Each cut is across the long side of the piece's narrowest rectangle (perpendicular to its
/// long side), so that the pieces get rounder, at a multiple of `1/k` of its length where `k`
/// pieces of at most `max_edge` fit: a rectangle is cut into the same grid as [`mesh_quad`]'s.
fn cut(piece: Vec<Vec3>, max_edge: f64, depth: usize, out: &mut Vec<Polygon>) {
    if piece.len() < 3 {
        return;
    }
    let Some(frame) = narrowest(&piece) else {
        out.push(Polygon::new(piece));
        return;
    };
    if depth >= MAX_DEPTH {
        out.push(Polygon::new(piece));
        return;
    }
    let n = piece.len();
    // Across the long side while the piece is longer than max_edge.
    let k = parts(frame.length, max_edge);
    if k > 1 {
        let at = frame.start + frame.length * (k / 2) as f64 / k as f64;
        return cut_at(&piece, frame.along, at, frame.length, max_edge, depth, out);
    }
    // A slanted edge longer than max_edge on a piece that is not: across that edge.
    let longest = (0..n)
        .map(|i| piece[(i + 1) % n] - piece[i])
        .fold(
            Vec3::ZERO,
            |a, e| if e.length() > a.length() { e } else { a },
        );
    if parts(longest.length(), max_edge) > 1 {
        let along = longest.normalized();
        let (lo, hi) = extent(&piece, along);
        let k = parts(hi - lo, max_edge);
        let at = lo + (hi - lo) * (k / 2) as f64 / k as f64;
        return cut_at(&piece, along, at, hi - lo, max_edge, depth, out);
    }
    // Thinner than the bound but not narrow: halved across its long side.
    if frame.length > ASPECT_BOUND * frame.width && frame.width >= NARROW * max_edge {
        let at = frame.start + 0.5 * frame.length;
        return cut_at(&piece, frame.along, at, frame.length, max_edge, depth, out);
    }
    // Too many corners: halved across the long side where both halves have fewer corners,
    // else cut along the diagonal whose worse part is roundest (a diagonal always leaves
    // fewer corners on both sides).
    if n > MAX_CORNERS {
        let at = frame.start + 0.5 * frame.length;
        let halves = halves(&piece, frame.along, at, tolerance(frame.length));
        let [a, b] = if halves.iter().all(|h| h.len() >= 3 && h.len() < n) {
            halves
        } else {
            best_diagonal(&piece)
        };
        cut(a, max_edge, depth + 1, out);
        cut(b, max_edge, depth + 1, out);
        return;
    }
    out.push(Polygon::new(piece));
}

/// The two parts of convex `piece` (more than three corners) along the diagonal between two
/// of its corners whose larger [`aspect`] of the two parts is least (the first such).
fn best_diagonal(piece: &[Vec3]) -> [Vec<Vec3>; 2] {
    let n = piece.len();
    let part = |i: usize, j: usize| -> Vec<Vec3> { (i..=j).map(|k| piece[k % n]).collect() };
    let mut best: Option<(f64, [Vec<Vec3>; 2])> = None;
    for i in 0..n {
        for j in i + 2..n {
            if i == 0 && j == n - 1 {
                continue; // an edge, not a diagonal
            }
            let (a, b) = (part(i, j), part(j, n + i));
            let score = aspect(&a).max(aspect(&b));
            if best.as_ref().is_none_or(|(s, _)| score < *s) {
                best = Some((score, [a, b]));
            }
        }
    }
    best.map_or_else(|| [piece.to_vec(), Vec::new()], |(_, parts)| parts)
}

/// Cuts `piece` at `p · along = at` and cuts both halves further ([`cut`]); `length` (m) is
/// the piece's extent along `along`, which scales the tolerance.
fn cut_at(
    piece: &[Vec3],
    along: Vec3,
    at: f64,
    length: f64,
    max_edge: f64,
    depth: usize,
    out: &mut Vec<Polygon>,
) {
    for h in halves(piece, along, at, tolerance(length)) {
        cut(h, max_edge, depth + 1, out);
    }
}

/// How far (m) a corner may be from a cut line and count as on it, for a piece `length` long:
/// closer corners are not cut off into an edge of rounding size.
fn tolerance(length: f64) -> f64 {
    1e-9 * length
}

/// Smallest and largest `p · along` over the corners, m.
fn extent(piece: &[Vec3], along: Vec3) -> (f64, f64) {
    piece
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), p| {
            let x = p.dot(along);
            (lo.min(x), hi.max(x))
        })
}

/// The two parts of convex `piece` where `p · along ≤ at` and `≥ at`, each with the piece's
/// winding (Sutherland–Hodgman against one line, both sides at once; a crossing point is
/// computed once and shared). A corner within `tol` of the line belongs to both parts.
fn halves(piece: &[Vec3], along: Vec3, at: f64, tol: f64) -> [Vec<Vec3>; 2] {
    let side = |p: Vec3| {
        let s = p.dot(along) - at;
        if s.abs() <= tol {
            0.0
        } else {
            s
        }
    };
    let (mut below, mut above) = (Vec::new(), Vec::new());
    let n = piece.len();
    for k in 0..n {
        let (a, b) = (piece[k], piece[(k + 1) % n]);
        let (sa, sb) = (side(a), side(b));
        if sa <= 0.0 {
            below.push(a);
        }
        if sa >= 0.0 {
            above.push(a);
        }
        if (sa < 0.0 && sb > 0.0) || (sa > 0.0 && sb < 0.0) {
            let x = a + (b - a) * (sa / (sa - sb));
            below.push(x);
            above.push(x);
        }
    }
    [below, above]
}

/// Up to how many cells of a grid over its narrowest rectangle [`estimate`] counts a
/// polygon's or sliver's pieces by cutting it (a few milliseconds); beyond, the grid is the
/// estimate.
const EXACT_UP_TO: f64 = 1e5;

/// How many patches [`mesh_face`] would make of a face, without making them (f64, so that an
/// absurd count is a number rather than an overflow); exact unless a polygon or sliver would
/// have more than about [`EXACT_UP_TO`] pieces.
pub(crate) fn estimate(corners: &[Vec3], max_edge: f64) -> f64 {
    // As `parts` does, so that a side of exactly k × max_edge counts k.
    let count = |length: f64| (length / max_edge * (1.0 - 1e-12)).ceil().max(1.0);
    let triangle = |a: Vec3, b: Vec3, c: Vec3| {
        let m = count((b - a).length().max((c - b).length()).max((a - c).length()));
        m * m
    };
    match corners {
        [a, b, c, d] => {
            count((*b - *a).length().max((*c - *d).length()))
                * count((*d - *a).length().max((*c - *b).length()))
        }
        [_, _, _] if aspect(corners) <= ASPECT_BOUND => {
            triangle(corners[0], corners[1], corners[2])
        }
        // What [`cut`] makes: counted by cutting, unless a grid over the narrowest rectangle
        // already has more than EXACT_UP_TO cells (the count is then that grid, more or less
        // the pieces cut off along a slanted or curved boundary).
        _ => narrowest(corners).map_or(1.0, |r| {
            let grid = count(r.length) * count(r.width);
            if grid > EXACT_UP_TO {
                return grid;
            }
            let mut out = Vec::new();
            cut(corners.to_vec(), max_edge, 0, &mut out);
            out.len() as f64
        }),
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

    /// A point of a tilted plane (so that no test relies on a face lying in z = 0): `(x, y)`
    /// in its own orthonormal frame.
    fn tilted(x: f64, y: f64) -> Vec3 {
        let e1 = Vec3::new(1.0, 2.0, 2.0) / 3.0;
        let e2 = Vec3::new(2.0, 1.0, -2.0) / 3.0;
        Vec3::new(0.3, -0.2, 1.1) + e1 * x + e2 * y
    }

    /// A regular `n`-gon of circumradius `r` (m), counter-clockwise in the tilted plane.
    fn regular(n: usize, r: f64) -> Vec<Vec3> {
        (0..n)
            .map(|k| {
                let t = 2.0 * std::f64::consts::PI * k as f64 / n as f64;
                tilted(r * t.cos(), r * t.sin())
            })
            .collect()
    }

    /// Convex faces of more than four corners and thin triangles, in the tilted plane.
    fn faces() -> Vec<(&'static str, Vec<Vec3>)> {
        let irregular = [
            (0.0, 0.0),
            (1.3, -0.2),
            (2.1, 0.4),
            (2.2, 1.1),
            (1.6, 1.7),
            (0.4, 1.5),
            (-0.3, 0.8),
        ];
        vec![
            ("pentagon", regular(5, 0.5)),
            ("hexagon", regular(6, 0.5)),
            ("octagon", regular(8, 0.5)),
            ("32-gon", regular(32, 0.5)),
            ("128-gon", regular(128, 0.5)),
            ("128-gon of 3 m", regular(128, 3.0)),
            (
                "irregular heptagon",
                irregular.iter().map(|&(x, y)| tilted(x, y)).collect(),
            ),
            // A needle 2 m long, 0.05 m wide at its base.
            (
                "needle",
                vec![tilted(0.0, 0.0), tilted(2.0, 0.0), tilted(2.0, 0.05)],
            ),
            // A cap: 2 m long, 0.04 m high over its long edge at 0.7 m.
            (
                "cap",
                vec![tilted(0.0, 0.0), tilted(2.0, 0.0), tilted(0.7, 0.04)],
            ),
        ]
    }

    /// Whether `p` is strictly inside convex `patch` (normal `n`), and its distance (m) to the
    /// nearest line through an edge.
    fn inside(patch: &[Vec3], n: Vec3, p: Vec3) -> (bool, f64) {
        let mut inside = true;
        let mut nearest = f64::INFINITY;
        for k in 0..patch.len() {
            let (a, b) = (patch[k], patch[(k + 1) % patch.len()]);
            let side = (b - a).cross(p - a).dot(n) / (b - a).length();
            inside &= side > 0.0;
            nearest = nearest.min(side.abs());
        }
        (inside, nearest)
    }

    /// The patches tile `face`: their areas sum to its area (1e-12 relative), each has its
    /// normal (1e-9) and is convex, no edge is longer than `max_edge`, and each of a grid of
    /// points inside the face lies inside exactly one patch (points within 1e-9 m of an edge
    /// line are skipped: on a seam, "inside" depends on rounding).
    fn assert_tiles(name: &str, face: &[Vec3], patches: &[Polygon], max_edge: f64) {
        let whole = Polygon::new(face.to_vec());
        let n = whole.normal();
        let total: f64 = patches.iter().map(Polygon::area).sum();
        assert!(
            (total - whole.area()).abs() <= 1e-12 * whole.area(),
            "{name} at {max_edge} m: area {total} of {}",
            whole.area()
        );
        for p in patches {
            let v = &p.vertices;
            assert!(
                v.len() >= 3 && v.len() <= MAX_CORNERS,
                "{name}: {} corners",
                v.len()
            );
            assert!(
                (p.normal() - n).length() < 1e-9,
                "{name}: normal {:?}",
                p.normal()
            );
            for k in 0..v.len() {
                let (a, b, c) = (v[k], v[(k + 1) % v.len()], v[(k + 2) % v.len()]);
                assert!(
                    (b - a).length() <= max_edge * (1.0 + 1e-9),
                    "{name}: long edge"
                );
                let turn = (b - a).cross(c - b).dot(n);
                assert!(turn >= -1e-12 * max_edge * max_edge, "{name}: not convex");
            }
        }
        let frame = narrowest(face).unwrap();
        let across = n.cross(frame.along);
        let origin = face[0];
        let (lo, hi) = face
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), p| {
                let y = (*p - origin).dot(across);
                (l.min(y), h.max(y))
            });
        let mut tested = 0;
        for i in 0..60 {
            for j in 0..60 {
                let x =
                    frame.start - origin.dot(frame.along) + frame.length * (i as f64 + 0.5) / 60.0;
                let y = lo + (hi - lo) * (j as f64 + 0.37) / 60.0;
                let p = origin + frame.along * x + across * y;
                if !inside(face, n, p).0 {
                    continue;
                }
                let hits: Vec<(bool, f64)> =
                    patches.iter().map(|q| inside(&q.vertices, n, p)).collect();
                if hits.iter().any(|&(_, d)| d < 1e-9) {
                    continue;
                }
                let count = hits.iter().filter(|h| h.0).count();
                assert_eq!(count, 1, "{name} at {max_edge} m: {p:?} in {count} patches");
                tested += 1;
            }
        }
        assert!(tested > 100, "{name}: only {tested} points tested");
    }

    #[test]
    fn scene_mesh_polygons_and_slivers_tile_their_face() {
        for (name, face) in faces() {
            for max_edge in [5.0, 0.4, 0.25, 0.1] {
                let mut out = Vec::new();
                mesh_face(&face, max_edge, &mut out);
                assert_tiles(name, &face, &out, max_edge);
            }
        }
    }

    /// The old mesh of a polygon: a fan of triangles from its first corner, each subdivided.
    fn fan(face: &[Vec3], max_edge: f64) -> Vec<Polygon> {
        let mut out = Vec::new();
        for i in 1..face.len() - 1 {
            mesh_triangle(face[0], face[i], face[i + 1], max_edge, &mut out);
        }
        out
    }

    fn worst_aspect(patches: &[Polygon]) -> f64 {
        patches
            .iter()
            .map(|p| aspect(&p.vertices))
            .fold(0.0, f64::max)
    }

    #[test]
    fn scene_mesh_polygons_are_cut_into_pieces_within_the_aspect_bound() {
        // Reference: the bound itself, and the fan the mesher replaced (its worst piece).
        for (name, face) in faces().into_iter().take(7) {
            for max_edge in [5.0, 0.4, 0.25, 0.1] {
                let mut out = Vec::new();
                mesh_face(&face, max_edge, &mut out);
                let old = fan(&face, max_edge);
                let (worst, fan) = (worst_aspect(&out), worst_aspect(&old));
                let narrow =
                    |p: &Polygon| narrowest(&p.vertices).unwrap().width < NARROW * max_edge;
                let worst_wide = worst_aspect(
                    &out.iter()
                        .filter(|p| !narrow(p))
                        .cloned()
                        .collect::<Vec<_>>(),
                );
                println!("{name} at {max_edge} m: {} patches, worst aspect {worst:.2}, of the pieces not narrow {worst_wide:.2} (fan: {} patches, {fan:.2})", out.len(), old.len());
                assert!(
                    worst_wide <= ASPECT_BOUND,
                    "{name} at {max_edge} m: worst aspect {worst_wide:.2} (fan {fan:.2})"
                );
            }
        }
        // Smaller than max_edge: a pentagon is cut in two quadrilaterals through a corner; a
        // hexagon's halves across its long side are pentagons, each cut in two again.
        for (face, corners) in [(regular(5, 0.5), vec![4, 4]), (regular(6, 0.5), vec![4; 4])] {
            let mut out = Vec::new();
            mesh_face(&face, 5.0, &mut out);
            let got: Vec<usize> = out.iter().map(|p| p.vertices.len()).collect();
            assert_eq!(got, corners);
        }
    }

    #[test]
    fn scene_mesh_slivers_are_cut_across_their_length() {
        // A sliver narrower than max_edge is cut into pieces no longer than max_edge across
        // its length: ⌈2 m / 0.25 m⌉ = 8 of them (9 for the needle), where similar subdivision gave 8² = 64 as
        // thin as the sliver. No piece is thinner than the sliver itself, and the median
        // piece is at most max_edge over the sliver's widest (0.05 m for the needle,
        // 0.04 m for the cap) — a quarter of the sliver's own aspect or less.
        for (name, face) in faces().into_iter().skip(7) {
            let mut out = Vec::new();
            mesh_face(&face, 0.25, &mut out);
            // The needle's long side is its hypotenuse, √(2² + 0.05²) m: 9 slabs. A slab's own
            // slanted edge may still exceed max_edge by a little and be cut once more, and the
            // slab holding the cap's apex has five corners and is cut in two: at most four more.
            let k = parts(narrowest(&face).unwrap().length, 0.25);
            assert_eq!(k, if name == "needle" { 9 } else { 8 });
            assert!(
                out.len() >= k && out.len() <= k + 4,
                "{name}: {}",
                out.len()
            );
            let whole = aspect(&face);
            let mut a: Vec<f64> = out.iter().map(|p| aspect(&p.vertices)).collect();
            a.sort_by(f64::total_cmp);
            assert!(a[7] <= whole * (1.0 + 1e-9), "{name}: {a:?} vs {whole}");
            assert!(a[3] <= 0.25 * whole, "{name}: median {} vs {whole}", a[3]);
            let mut old = Vec::new();
            let [p, q, r] = face[..] else { unreachable!() };
            mesh_triangle(p, q, r, 0.25, &mut old);
            assert_eq!(old.len(), k * k);
        }
        // Within max_edge, a sliver stays one patch: nothing asks for more.
        let (_, needle) = &faces()[7];
        let mut out = Vec::new();
        mesh_face(needle, 5.0, &mut out);
        assert_eq!(out.len(), 1);
    }

    #[test]
    fn scene_mesh_thin_strip_is_cut_across_its_length_only() {
        // A 0.025 × 2 m strip at 0.25 m: 8 patches of 0.25 × 0.025 m (aspect 10), as the
        // grid always gave; see the module docs for why not 80 square ones.
        let strip = [
            tilted(0.0, 0.0),
            tilted(2.0, 0.0),
            tilted(2.0, 0.025),
            tilted(0.0, 0.025),
        ];
        let mut out = Vec::new();
        mesh_face(&strip, 0.25, &mut out);
        assert_eq!(out.len(), 8);
        for p in &out {
            assert!((aspect(&p.vertices) - 10.0).abs() < 1e-9);
        }
        assert_tiles("strip", &strip, &out, 0.25);
    }

    #[test]
    fn scene_mesh_estimate_is_the_count() {
        for (name, face) in faces() {
            for max_edge in [5.0, 0.4, 0.25, 0.1] {
                let mut out = Vec::new();
                mesh_face(&face, max_edge, &mut out);
                assert_eq!(
                    estimate(&face, max_edge),
                    out.len() as f64,
                    "{name} at {max_edge}"
                );
            }
        }
        // An absurd edge is a number, not a meshing.
        let e = estimate(&regular(7, 100.0), 1e-6);
        assert!(e > 1e15 && e.is_finite(), "{e}");
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
