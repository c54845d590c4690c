//! Cutting by straight lines: slivers and polygons of more than four corners, across their
//! long side until every piece is short enough, round enough and has at most four corners.

use super::{parts, ASPECT_BOUND, MAX_CORNERS, NARROW};
use crate::geometry::{aspect, narrowest, Polygon, Vec3};

/// How deep [`cut`] recurses at most (a guard: each level halves a piece or cuts it into
/// pieces no longer than `max_edge`, so real faces stop far earlier).
const MAX_DEPTH: usize = 64;

/// Cuts convex `piece` by straight lines until every piece is at most `max_edge` long, every
/// edge at most `max_edge`, every piece within [`ASPECT_BOUND`] unless it is [`NARROW`], and
/// no piece has more than [`MAX_CORNERS`] corners.
///
/// Each cut is across the long side of the piece's narrowest rectangle (perpendicular to its
/// long side), so that the pieces get rounder, at a multiple of `1/k` of its length where `k`
/// pieces of at most `max_edge` fit: a rectangle is cut into the same grid as
/// [`mesh_quad`](super::regular::mesh_quad)'s.
pub(super) fn cut(piece: Vec<Vec3>, max_edge: f64, depth: usize, out: &mut Vec<Polygon>) {
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

#[cfg(test)]
mod tests {
    use super::super::fixtures::{assert_tiles, faces, regular};
    use super::super::mesh_face;
    use super::super::regular::mesh_triangle;
    use super::*;

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
}
