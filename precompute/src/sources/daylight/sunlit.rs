//! The sunlit part of a polygon, exactly: the shadows of everything between it and the sun
//! projected along the sun onto its plane, united and taken out of it by polygon Booleans
//! (`geo`). The host's reference for the sun patch: a quadrature of the lit area misses a
//! sliver of sun that none of its points sees, whatever its order.

use geo::orient::{Direction, Orient};
use geo::{Area, BooleanOps, Coord, LineString, MultiPolygon, Polygon};

use super::outside::clip;
use crate::geometry::{doubled_vector_area, Vec3};

/// The point where the line through `y` along `s` meets the plane through `origin` with
/// normal `normal` (m); `normal · s` must not vanish.
pub(super) fn along_sun(y: Vec3, origin: Vec3, normal: Vec3, s: Vec3) -> Vec3 {
    y - s * (normal.dot(y - origin) / normal.dot(s))
}

/// The shadow cast along the sun `s` onto the plane (`origin`, `normal`) by the part of the
/// polygon `corners` on the kept side of every plane in `keep` (each `(origin, normal)`, kept
/// where `normal · (y − origin) ≥ 0`): its corners on the plane, or `None` when nothing of it
/// is kept.
pub(super) fn shadow(
    corners: &[Vec3],
    keep: &[(Vec3, Vec3)],
    origin: Vec3,
    normal: Vec3,
    s: Vec3,
) -> Option<Vec<Vec3>> {
    let mut part = corners.to_vec();
    for &(o, n) in keep {
        part = clip(&part, o, n);
        if part.len() < 3 {
            return None;
        }
    }
    Some(
        part.iter()
            .map(|&y| along_sun(y, origin, normal, s))
            .collect(),
    )
}

/// Area (m²) of the convex polygon `part` (in the plane of unit `normal`) less the union of
/// the `shadows` (polygons in the same plane, either orientation, overlapping or not).
///
/// `geo`'s Booleans snap coordinates to an integer grid over the operands' extent: each
/// shadow is first cut to `part` (whose edges bound what matters), so that a shadow reaching
/// far past the patch does not coarsen the grid; the area is then exact to about 10⁻⁹ of the
/// part's (a shadow that covers it whole leaves 1.1 × 10⁻⁹ of it), and within [`SNAPPING`]
/// of none or all of it is read as none or all.
pub(super) fn area_outside(part: &[Vec3], normal: Vec3, shadows: &[Vec<Vec3>]) -> f64 {
    if part.len() < 3 {
        return 0.0;
    }
    let mut part = part.to_vec();
    if doubled_vector_area(&part).dot(normal) < 0.0 {
        part.reverse();
    }
    let origin = part[0];
    let Some(u) = part[1..]
        .iter()
        .map(|&c| c - origin)
        .find(|d| d.length() > 0.0)
        .map(|d| d / d.length())
    else {
        return 0.0;
    };
    let v = normal.cross(u);
    let flat = |corners: &[Vec3]| -> Polygon<f64> {
        let ring: Vec<Coord<f64>> = corners
            .iter()
            .map(|&c| Coord {
                x: u.dot(c - origin),
                y: v.dot(c - origin),
            })
            .collect();
        Polygon::new(LineString::new(ring), vec![]).orient(Direction::Default)
    };
    let whole = flat(&part);
    let whole_area = whole.unsigned_area();
    let n = part.len();
    let within = |shadow: &Vec<Vec3>| {
        let mut cut = shadow.clone();
        for k in 0..n {
            let (a, b) = (part[k], part[(k + 1) % n]);
            cut = clip(&cut, a, normal.cross(b - a));
            if cut.len() < 3 {
                break;
            }
        }
        cut
    };
    // A shadow seen edge-on (the sun in its plane) has no area and only confuses the
    // Booleans.
    let dark: Vec<Polygon<f64>> = shadows
        .iter()
        .map(within)
        .filter(|c| c.len() >= 3)
        .map(|c| flat(&c))
        .filter(|p| p.unsigned_area() > 1e-12 * whole_area)
        .collect();
    if dark.is_empty() {
        return whole_area;
    }
    let union: MultiPolygon<f64> = geo::unary_union(&dark);
    let lit = whole.difference(&union).unsigned_area();
    if lit <= SNAPPING * whole_area {
        0.0
    } else if lit >= (1.0 - SNAPPING) * whole_area {
        whole_area
    } else {
        lit
    }
}

/// What the Booleans' snapping to their grid can leave of a polygon's area, relative to it.
const SNAPPING: f64 = 1e-8;

#[cfg(test)]
mod tests {
    use super::*;

    fn square(x0: f64, y0: f64, x1: f64, y1: f64, z: f64) -> Vec<Vec3> {
        vec![
            Vec3::new(x0, y0, z),
            Vec3::new(x1, y0, z),
            Vec3::new(x1, y1, z),
            Vec3::new(x0, y1, z),
        ]
    }

    #[test]
    fn overlapping_shadows_are_counted_once() {
        let part = square(0.0, 0.0, 1.0, 1.0, 0.0);
        let up = Vec3::new(0.0, 0.0, 1.0);
        // Two shadows of 0.5 × 1 overlapping by 0.25 × 1, one of them clockwise.
        let mut b = square(0.25, 0.0, 0.75, 1.0, 0.0);
        b.reverse();
        let shadows = vec![square(0.0, 0.0, 0.5, 1.0, 0.0), b];
        let lit = area_outside(&part, up, &shadows);
        assert!((lit - 0.25).abs() < 1e-9, "{lit}");
    }

    #[test]
    fn a_sliver_between_shadows_is_lit() {
        // The strip 0.499 < x < 0.501 stays lit: what a quadrature whose points all fall in
        // the shadows reads as dark.
        let part = square(0.0, 0.0, 1.0, 1.0, 0.0);
        let up = Vec3::new(0.0, 0.0, 1.0);
        let shadows = vec![
            square(-1.0, -1.0, 0.499, 2.0, 0.0),
            square(0.501, -1.0, 2.0, 2.0, 0.0),
        ];
        let lit = area_outside(&part, up, &shadows);
        assert!((lit - 0.002).abs() < 1e-9, "{lit}");
    }

    #[test]
    fn a_bar_casts_its_shadow_along_an_oblique_sun() {
        // A 0.2 m wide bar 1 m above the floor, the sun at 45° in the x–z plane: its shadow is
        // the bar shifted 1 m in x, whatever part of the bar lies beyond the kept planes
        // left out.
        let floor = Vec3::ZERO;
        let up = Vec3::new(0.0, 0.0, 1.0);
        let s = Vec3::new(1.0, 0.0, 1.0) / 2f64.sqrt();
        let bar = square(-0.6, -1.0, -0.4, 1.0, 1.0);
        let keep = [(floor, up)];
        let Some(dark) = shadow(&bar, &keep, floor, up, s) else {
            panic!("the bar is above the floor");
        };
        for (c, d) in bar.iter().zip(&dark) {
            assert!((d.x - (c.x - 1.0)).abs() < 1e-12 && d.y == c.y && d.z.abs() < 1e-12);
        }
        let part = square(-2.0, -0.5, 0.0, 0.5, 0.0);
        let lit = area_outside(&part, up, &[dark]);
        assert!((lit - (2.0 - 0.2)).abs() < 1e-9, "{lit}");
        // Below the floor nothing is kept.
        let under = square(-0.6, -1.0, -0.4, 1.0, -0.5);
        assert!(shadow(&under, &keep, floor, up, s).is_none());
    }
}
