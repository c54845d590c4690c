//! Calculation grids: where a zone's illuminance is evaluated point by point for its
//! average, minimum, maximum and uniformity (EN 12464-1:2021, 4.4; docs/scene.md, "Grids").
//!
//! The rule: the largest spacing is `p = 0.2 × 5^(log10 d)` m, `d` the longer side of the
//! area in m, `p ≤ 10` m; each side of length `s` gets `⌈s/p⌉` points at the centres of equal
//! cells, and a side is split further where needed to keep each cell's aspect ratio between
//! 0.5 and 2.
//!
//! A zone's grid is made of pieces, each such a lattice over a rectangle of a plane: one for a
//! work plane or a task area, up to four for the band around a task area, one per plane of a
//! surface zone. A piece keeps the cell centres that lie on its area (all of them, but for a
//! surface whose outline is not its rectangle: a wall's window, a triangle).

use crate::geometry::{Patch, Vec3};

/// Largest grid spacing the rule allows, m.
pub const MAX_SPACING: f64 = 10.0;
/// Most points a zone's grid may have: each point is a row of form factors over every patch.
pub const MAX_POINTS: usize = 10_000;

/// A zone's calculation grid: its pieces, in order; the zone's points are theirs, piece by
/// piece.
#[derive(Clone, Debug, PartialEq)]
pub struct Grid {
    /// The lattices the grid is made of (at least one).
    pub pieces: Vec<GridPiece>,
    /// Cell centres left out because they lie inside an obstacle (a block standing through
    /// the plane): no one works there, and a reading inside a solid is meaningless.
    pub obstructed: usize,
}

impl Grid {
    /// Number of points over all pieces.
    pub fn len(&self) -> usize {
        self.pieces.iter().map(|p| p.points.len()).sum()
    }

    /// Whether the grid has no point (a grid is never built so; for completeness).
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Every point with the normal it faces, piece by piece, m.
    pub fn points(&self) -> impl Iterator<Item = (Vec3, Vec3)> + '_ {
        self.pieces
            .iter()
            .flat_map(|p| p.points.iter().map(move |&x| (x, p.normal)))
    }
}

/// One lattice of a grid: point receivers at cell centres, all facing `normal`.
#[derive(Clone, Debug, PartialEq)]
pub struct GridPiece {
    /// Largest spacing used: the rule's `p` or the scene's `grid.spacing`, m.
    pub spacing: f64,
    /// Whether `spacing` was given in the scene rather than taken from the rule.
    pub explicit: bool,
    /// Band left out at the walls, m (the work plane's `margin`).
    pub border: f64,
    /// Cells along the first and second side of the piece's rectangle.
    pub counts: [usize; 2],
    /// Cell sides along the first and second side, m.
    pub cell: [f64; 2],
    /// Unit normal every point faces (up for a work plane).
    pub normal: Vec3,
    /// Positions of the cell centres kept, m, first side fastest.
    pub points: Vec<Vec3>,
}

/// A rectangle of a plane: corner `origin`, unit sides `u` and `v` (`u × v` the normal the
/// points face), side lengths `size` along them, m.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PlaneRect {
    /// The corner the lattice starts from, m.
    pub origin: Vec3,
    /// Unit direction of the first side.
    pub u: Vec3,
    /// Unit direction of the second side.
    pub v: Vec3,
    /// Lengths of the first and second side, m.
    pub size: [f64; 2],
}

/// The rule's largest spacing for an area whose longer side is `d` m:
/// `p = 0.2 × 5^(log10 d)`, at most [`MAX_SPACING`].
pub fn rule_spacing(d: f64) -> f64 {
    (0.2 * 5f64.powf(d.log10())).min(MAX_SPACING)
}

/// Points along the sides `a` and `b` (m) for the largest spacing `p` (m): `⌈a/p⌉` and
/// `⌈b/p⌉` (at least 1), then the side whose cells are more than twice as long as the
/// other's split further until they are not.
pub fn counts(a: f64, b: f64, p: f64) -> [usize; 2] {
    let along = |s: f64| ((s / p).ceil() as usize).max(1);
    let (mut na, mut nb) = (along(a), along(b));
    if a / na as f64 > 2.0 * (b / nb as f64) {
        na = (a / (2.0 * (b / nb as f64))).ceil() as usize;
    } else if b / nb as f64 > 2.0 * (a / na as f64) {
        nb = (b / (2.0 * (a / na as f64))).ceil() as usize;
    }
    [na, nb]
}

/// The lattice of the rule (or of `spacing`, m) over `rect`, every cell centre kept.
/// `border` is what was left out at the walls, m.
pub fn full_lattice(rect: &PlaneRect, spacing: Option<f64>, border: f64) -> GridPiece {
    let [a, b] = rect.size;
    let p = spacing.unwrap_or_else(|| rule_spacing(a.max(b)));
    let [na, nb] = counts(a, b, p);
    let cell = [a / na as f64, b / nb as f64];
    let mut points = Vec::with_capacity(na * nb);
    for j in 0..nb {
        for i in 0..na {
            points.push(
                rect.origin
                    + rect.u * ((i as f64 + 0.5) * cell[0])
                    + rect.v * ((j as f64 + 0.5) * cell[1]),
            );
        }
    }
    GridPiece {
        spacing: p,
        explicit: spacing.is_some(),
        border,
        counts: [na, nb],
        cell,
        normal: rect.u.cross(rect.v).normalized(),
        points,
    }
}

/// [`full_lattice`] keeping only the cell centres `keep` accepts; `None` when it accepts
/// none.
pub fn lattice(
    rect: &PlaneRect,
    spacing: Option<f64>,
    border: f64,
    keep: impl Fn(Vec3) -> bool,
) -> Option<GridPiece> {
    let mut piece = full_lattice(rect, spacing, border);
    piece.points.retain(|&x| keep(x));
    (!piece.points.is_empty()).then_some(piece)
}

/// A horizontal rectangle `[x0, x1] × [y0, y1]` at height `z` (m), sides along x and y,
/// facing up.
pub fn horizontal_rect((x0, y0): (f64, f64), (x1, y1): (f64, f64), z: f64) -> PlaneRect {
    PlaneRect {
        origin: Vec3::new(x0, y0, z),
        u: Vec3::new(1.0, 0.0, 0.0),
        v: Vec3::new(0.0, 1.0, 0.0),
        size: [x1 - x0, y1 - y0],
    }
}

/// A horizontal grid over `[x0, x1] × [y0, y1]` at height `z` (m), facing up, every cell
/// centre kept; `spacing` is the scene's override (m) or `None` for the rule, `border` what
/// was left out at the walls.
pub fn horizontal(
    lo: (f64, f64),
    hi: (f64, f64),
    z: f64,
    spacing: Option<f64>,
    border: f64,
) -> GridPiece {
    full_lattice(&horizontal_rect(lo, hi, z), spacing, border)
}

/// A rectangle of the floor plan, m: `[x0, y0, x1, y1]`.
pub type PlanRect = [f64; 4];

/// Sides shorter than this (m) are no rectangle: a band clipped to nothing at a wall.
const THINNEST_SIDE: f64 = 1e-9;

/// `outer` less `inner` (which lies inside it) as at most four rectangles: the strips below
/// and above `inner` over `outer`'s whole width, then those left and right of it between
/// them. Strips thinner than a nanometre (where `inner` meets `outer`'s side) are left out.
pub fn ring(inner: PlanRect, outer: PlanRect) -> Vec<PlanRect> {
    let [ix0, iy0, ix1, iy1] = inner;
    let [ox0, oy0, ox1, oy1] = outer;
    [
        [ox0, oy0, ox1, iy0],
        [ox0, iy1, ox1, oy1],
        [ox0, iy0, ix0, iy1],
        [ix1, iy0, ox1, iy1],
    ]
    .into_iter()
    .filter(|[x0, y0, x1, y1]| x1 - x0 > THINNEST_SIDE && y1 - y0 > THINNEST_SIDE)
    .collect()
}

/// Distance within which a point on a patch's plane counts as on the patch, m.
const ON_PATCH: f64 = 1e-9;

/// Whether `x`, in the plane of the convex `patch`, lies on it (edges included).
fn on_patch(patch: &Patch, x: Vec3) -> bool {
    let v = &patch.polygon.vertices;
    (0..v.len()).all(|k| {
        let (a, b) = (v[k], v[(k + 1) % v.len()]);
        let edge = b - a;
        edge.cross(x - a).dot(patch.normal) >= -ON_PATCH * edge.length()
    })
}

/// Normals closer than this (1 − cos of the angle) and offsets closer than this (m) are
/// one plane.
const SAME_PLANE: f64 = 1e-9;

/// One piece per plane of `patches` (a surface zone's): the rule's lattice (or `spacing`'s, m)
/// over the smallest rectangle holding that plane's patches, its first side along their
/// longest edge, keeping the cell centres on a patch, facing the patches' normal. Planes in
/// the order of their first patch. More than `limit` cells over all planes is refused before
/// they are laid out, with their number.
pub fn on_patches(
    patches: &[&Patch],
    spacing: Option<f64>,
    limit: usize,
) -> Result<Vec<GridPiece>, usize> {
    let mut planes: Vec<(Vec3, f64, Vec<&Patch>)> = Vec::new();
    for &patch in patches {
        let (n, d) = (patch.normal, patch.normal.dot(patch.centroid));
        match planes
            .iter_mut()
            .find(|(m, e, _)| 1.0 - m.dot(n) <= SAME_PLANE && (e - d).abs() <= SAME_PLANE.sqrt())
        {
            Some((_, _, members)) => members.push(patch),
            None => planes.push((n, d, vec![patch])),
        }
    }
    let mut frames = Vec::with_capacity(planes.len());
    for (normal, _, members) in planes {
        let corners = || {
            members
                .iter()
                .flat_map(|p| p.polygon.vertices.iter().copied())
        };
        let edges = members.iter().flat_map(|p| {
            let v = &p.polygon.vertices;
            (0..v.len()).map(move |k| v[(k + 1) % v.len()] - v[k])
        });
        let mut longest = Vec3::new(0.0, 0.0, 0.0);
        for e in edges {
            if e.length() > longest.length() {
                longest = e;
            }
        }
        let u = longest.normalized();
        let v = normal.cross(u);
        let start = members[0].polygon.vertices[0];
        let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
        for c in corners() {
            let at = [(c - start).dot(u), (c - start).dot(v)];
            for k in 0..2 {
                lo[k] = lo[k].min(at[k]);
                hi[k] = hi[k].max(at[k]);
            }
        }
        let rect = PlaneRect {
            origin: start + u * lo[0] + v * lo[1],
            u,
            v,
            size: [hi[0] - lo[0], hi[1] - lo[1]],
        };
        frames.push((rect, members));
    }
    let cells = frames
        .iter()
        .map(|(r, _)| {
            let [a, b] = r.size;
            let [na, nb] = counts(a, b, spacing.unwrap_or_else(|| rule_spacing(a.max(b))));
            na.saturating_mul(nb)
        })
        .fold(0usize, usize::saturating_add);
    if cells > limit {
        return Err(cells);
    }
    Ok(frames
        .iter()
        .filter_map(|(rect, members)| {
            let keep = |x: Vec3| members.iter().any(|p| on_patch(p, x));
            lattice(rect, spacing, 0.0, keep)
        })
        .collect())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Spacings worked by hand from `p = 0.2 × 5^(log10 d)`: `log10 5 = 0.69897`,
    /// `5^0.69897 = e^(0.69897 · ln 5) = e^1.12494 = 3.0800`; `log10 2 = 0.30103`,
    /// `5^0.30103 = e^0.48449 = 1.6234`; `5^1 = 5`; `5^2 = 25`, capped at 10 m. The same
    /// figures, rounded, are the rule's table (Fagerhult's summary of EN 12464-1: 2 m → 0.3 m,
    /// 5 m → 0.6 m, 10 m → 1 m).
    #[test]
    fn spacing_follows_the_rule() {
        let cases = [(1.0, 0.2), (2.0, 0.32468), (5.0, 0.61600), (10.0, 1.0)];
        for (d, p) in cases {
            assert!(
                (rule_spacing(d) - p).abs() < 1e-4,
                "d = {d}: {}",
                rule_spacing(d)
            );
        }
        assert_eq!(rule_spacing(100.0), 5.0);
        assert_eq!(rule_spacing(1000.0), MAX_SPACING);
    }

    /// Counts by hand. The office's work plane (6 m × 4 m less 0.5 m): 5 m × 3 m, p = 0.616,
    /// 5/0.616 = 8.12 → 9, 3/0.616 = 4.87 → 5. A 2 m × 1 m desk: p = 0.3247, 6.16 → 7,
    /// 3.08 → 4. A 4 m × 0.1 m strip: p = 0.2 × 5^0.60206 = 0.5271, 7.59 → 8 cells of 0.5 m
    /// against 0.1 m across, aspect 5: split to 0.2 m, 4/0.2 = 20 points.
    #[test]
    fn counts_follow_the_rule() {
        assert_eq!(counts(5.0, 3.0, rule_spacing(5.0)), [9, 5]);
        assert_eq!(counts(2.0, 1.0, rule_spacing(2.0)), [7, 4]);
        assert_eq!(counts(4.0, 0.1, rule_spacing(4.0)), [20, 1]);
        assert_eq!(counts(0.1, 4.0, rule_spacing(4.0)), [1, 20]);
        for (a, b) in [(5.0, 3.0), (2.0, 1.0), (4.0, 0.1), (30.0, 0.7), (0.3, 0.2)] {
            let [na, nb] = counts(a, b, rule_spacing(f64::max(a, b)));
            let aspect = (a / na as f64) / (b / nb as f64);
            assert!((0.5..=2.0).contains(&aspect), "{a} × {b}: aspect {aspect}");
        }
    }

    /// Points at cell centres: the first half a cell in from the corner, the last half a
    /// cell in from the opposite one, all at the plane's height.
    #[test]
    fn points_sit_at_cell_centres() {
        let g = horizontal((0.5, 0.5), (5.5, 3.5), 0.8, None, 0.5);
        assert_eq!(g.counts, [9, 5]);
        assert_eq!(g.points.len(), 45);
        let (first, last) = (g.points[0], g.points[44]);
        assert!((first.x - (0.5 + 5.0 / 18.0)).abs() < 1e-12);
        assert!((first.y - (0.5 + 3.0 / 10.0)).abs() < 1e-12);
        assert!((last.x - (5.5 - 5.0 / 18.0)).abs() < 1e-12);
        assert!((last.y - (3.5 - 3.0 / 10.0)).abs() < 1e-12);
        assert!(g.points.iter().all(|p| p.z == 0.8));
        let fixed = horizontal((0.0, 0.0), (1.0, 1.0), 0.0, Some(0.25), 0.0);
        assert_eq!((fixed.counts, fixed.explicit), ([4, 4], true));
    }
}
