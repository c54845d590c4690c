//! Calculation grids: where a zone's illuminance is evaluated point by point for its
//! average, minimum, maximum and uniformity (EN 12464-1:2021, 4.4; docs/scene.md, "Grids").
//!
//! The rule: the largest spacing is `p = 0.2 × 5^(log10 d)` m, `d` the longer side of the
//! area in m, `p ≤ 10` m; each side of length `s` gets `⌈s/p⌉` points at the centres of equal
//! cells, and a side is split further where needed to keep each cell's aspect ratio between
//! 0.5 and 2.

use crate::geometry::Vec3;

/// Largest grid spacing the rule allows, m.
pub const MAX_SPACING: f64 = 10.0;
/// Most points a zone's grid may have: each point is a row of form factors over every patch.
pub const MAX_POINTS: usize = 10_000;

/// A zone's calculation grid: point receivers at cell centres, all facing `normal`.
#[derive(Clone, Debug, PartialEq)]
pub struct Grid {
    /// Largest spacing used: the rule's `p` or the scene's `grid.spacing`, m.
    pub spacing: f64,
    /// Whether `spacing` was given in the scene rather than taken from the rule.
    pub explicit: bool,
    /// Band left out at the walls, m (the work plane's `margin`).
    pub border: f64,
    /// Points along the first (x) and second (y) side of the area.
    pub counts: [usize; 2],
    /// Cell sides along x and y, m.
    pub cell: [f64; 2],
    /// Unit normal every point faces (up for a work plane).
    pub normal: Vec3,
    /// Point positions, m, x fastest.
    pub points: Vec<Vec3>,
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

/// A horizontal grid over `[x0, x1] × [y0, y1]` at height `z` (m), facing up; `spacing` is
/// the scene's override (m) or `None` for the rule, `border` what was left out at the walls.
pub fn horizontal(
    (x0, y0): (f64, f64),
    (x1, y1): (f64, f64),
    z: f64,
    spacing: Option<f64>,
    border: f64,
) -> Grid {
    let (a, b) = (x1 - x0, y1 - y0);
    let p = spacing.unwrap_or_else(|| rule_spacing(a.max(b)));
    let [na, nb] = counts(a, b, p);
    let cell = [a / na as f64, b / nb as f64];
    let mut points = Vec::with_capacity(na * nb);
    for j in 0..nb {
        for i in 0..na {
            points.push(Vec3::new(
                x0 + (i as f64 + 0.5) * cell[0],
                y0 + (j as f64 + 0.5) * cell[1],
                z,
            ));
        }
    }
    Grid {
        spacing: p,
        explicit: spacing.is_some(),
        border,
        counts: [na, nb],
        cell,
        normal: Vec3::new(0.0, 0.0, 1.0),
        points,
    }
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
