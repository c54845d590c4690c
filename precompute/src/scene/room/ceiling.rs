//! Sloped and pitched ceilings: a plan room's ceiling as the lowest of a few planes over each
//! point of its plan.
//!
//! The lowest of planes is a concave roof, which is what mono-pitch, gabled and hipped rooms
//! are (one plane; two meeting at the ridge; four), and a flat collar ceiling under a pitched
//! roof is one more, horizontal, plane. Each plane is the ceiling over a convex cell of the
//! plan's surroundings (where it lies below every other plane); the ceiling face of a plane is
//! the plan clipped to its cell. Over each wall the ceiling is a concave broken line, so every
//! wall is one convex polygon: a trapezoid under a single slope, a pentagon under a gable.

use crate::geometry::Vec3;

use super::plan::Point2;

/// One plane of a sloped ceiling, `z = z0 + slope · (x, y)` in metres, and where it is the
/// ceiling.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct CeilingPlane {
    /// Its face's name after the room's (`ceiling`, `ceiling_2` or the user's).
    pub suffix: String,
    /// Its height over the origin, m.
    pub z0: f64,
    /// Its rise per metre along x and along y (dimensionless).
    pub slope: [f64; 2],
    /// The convex cell (counter-clockwise, m) of the plan's surroundings where it is the
    /// lowest plane; the plan clipped to it is the plane's face.
    pub cell: Vec<Point2>,
}

impl CeilingPlane {
    /// The plane through three points (m), or `None` when they are on one line or the plane
    /// is vertical (it is then no ceiling over any area).
    pub fn through(suffix: String, p: [Vec3; 3]) -> Option<CeilingPlane> {
        let n = (p[1] - p[0]).cross(p[2] - p[0]);
        let scale = (p[1] - p[0]).length().max((p[2] - p[0]).length());
        // Three points on one line span no plane.
        if n.length() <= 1e-12 * scale * scale {
            return None;
        }
        CeilingPlane::square_to(suffix, p[0], n)
    }

    /// The plane through `point` (m) square to `normal`, or `None` when it is vertical (or
    /// within 1e-6 of it).
    pub fn square_to(suffix: String, point: Vec3, normal: Vec3) -> Option<CeilingPlane> {
        // A plane steeper than 1e6 : 1 is a wall, not a ceiling.
        if !normal.z.is_finite() || normal.z.abs() <= 1e-6 * normal.length() {
            return None;
        }
        let slope = [-normal.x / normal.z, -normal.y / normal.z];
        Some(CeilingPlane {
            suffix,
            z0: point.z - slope[0] * point.x - slope[1] * point.y,
            slope,
            cell: Vec::new(),
        })
    }

    /// Its height over the plan point `p` (m), m.
    pub fn z(&self, p: Point2) -> f64 {
        self.z0 + self.slope[0] * p[0] + self.slope[1] * p[1]
    }

    /// Whether `p` (m) lies in its cell: no other plane lower there by more than `tol` (m).
    pub fn holds(&self, planes: &[CeilingPlane], p: Point2, tol: f64) -> bool {
        self.z(p) <= lowest(planes, p) + tol
    }
}

/// The ceiling's height over the plan point `p` (m): the lowest of the `planes`, m.
pub(crate) fn lowest(planes: &[CeilingPlane], p: Point2) -> f64 {
    planes.iter().map(|c| c.z(p)).fold(f64::INFINITY, f64::min)
}

/// Sets each plane's cell: the rectangle `lo`..`hi` (m, around the plan) less where another
/// plane is lower. Of two planes equal over the whole rectangle the later keeps no cell.
pub(crate) fn set_cells(planes: &mut [CeilingPlane], lo: Point2, hi: Point2) {
    let rectangle = vec![lo, [hi[0], lo[1]], hi, [lo[0], hi[1]]];
    for k in 0..planes.len() {
        let mut cell = rectangle.clone();
        for j in 0..planes.len() {
            if j == k {
                continue;
            }
            let (pk, pj) = (&planes[k], &planes[j]);
            // Keep where z_k − z_j ≤ 0; of two equal planes the earlier one.
            let g = [
                pk.slope[0] - pj.slope[0],
                pk.slope[1] - pj.slope[1],
                pk.z0 - pj.z0,
            ];
            let identical = g.iter().all(|&v| v == 0.0);
            cell = if identical && j < k {
                Vec::new()
            } else {
                clip(&cell, g)
            };
        }
        planes[k].cell = cell;
    }
}

/// The convex polygon `polygon` (m) where `g[0] x + g[1] y + g[2] ≤ 0` (Sutherland–Hodgman).
fn clip(polygon: &[Point2], g: [f64; 3]) -> Vec<Point2> {
    let f = |p: Point2| g[0] * p[0] + g[1] * p[1] + g[2];
    let n = polygon.len();
    let mut out = Vec::with_capacity(n + 1);
    for i in 0..n {
        let (a, b) = (polygon[i], polygon[(i + 1) % n]);
        let (fa, fb) = (f(a), f(b));
        if fa <= 0.0 {
            out.push(a);
        }
        if (fa < 0.0 && fb > 0.0) || (fa > 0.0 && fb < 0.0) {
            let t = fa / (fa - fb);
            out.push([a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1])]);
        }
    }
    out
}

/// The ceiling over the plan edge `a` → `b` (m): its corners from `a` to `b` as plan points
/// and heights (m), the ends and every point where another plane becomes the lowest (the
/// lowest of lines along the edge bends only there). `tol` (m): breaks closer to straight
/// than this are dropped.
pub(crate) fn over_edge(
    planes: &[CeilingPlane],
    a: Point2,
    b: Point2,
    tol: f64,
) -> Vec<(Point2, f64)> {
    let at = |t: f64| [a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1])];
    let mut ts = vec![0.0, 1.0];
    for k in 0..planes.len() {
        for j in k + 1..planes.len() {
            let d0 = planes[k].z(a) - planes[j].z(a);
            let d1 = planes[k].z(b) - planes[j].z(b);
            if (d0 < 0.0 && d1 > 0.0) || (d0 > 0.0 && d1 < 0.0) {
                ts.push(d0 / (d0 - d1));
            }
        }
    }
    ts.sort_by(f64::total_cmp);
    ts.dedup();
    let points: Vec<(Point2, f64)> = ts
        .iter()
        .map(|&t| {
            let p = at(t);
            (p, lowest(planes, p))
        })
        .collect();
    // Keep the ends and the bends: a point off the line from the last kept one to the next.
    let mut kept = vec![points[0]];
    for i in 1..points.len() - 1 {
        let (p, z) = points[i];
        let (q, zq) = kept[kept.len() - 1];
        let (r, zr) = points[i + 1];
        let along = |u: Point2| (u[0] - q[0]).hypot(u[1] - q[1]);
        let straight = zq + (zr - zq) * along(p) / along(r);
        if (z - straight).abs() > tol {
            kept.push((p, z));
        }
    }
    kept.push(points[points.len() - 1]);
    kept
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A gable over 0 ≤ y ≤ 6: eaves at 2.8 m along y = 0 and y = 6, ridge at 4.3 m along
    /// y = 3.
    fn gable() -> Vec<CeilingPlane> {
        let south = CeilingPlane::through(
            "ceiling_1".into(),
            [
                Vec3::new(0.0, 0.0, 2.8),
                Vec3::new(10.0, 0.0, 2.8),
                Vec3::new(0.0, 3.0, 4.3),
            ],
        )
        .unwrap();
        let north = CeilingPlane::through(
            "ceiling_2".into(),
            [
                Vec3::new(0.0, 6.0, 2.8),
                Vec3::new(0.0, 3.0, 4.3),
                Vec3::new(10.0, 6.0, 2.8),
            ],
        )
        .unwrap();
        let mut planes = vec![south, north];
        set_cells(&mut planes, [-1.0, -1.0], [11.0, 7.0]);
        planes
    }

    #[test]
    fn a_gable_is_the_lowest_of_its_two_planes() {
        let planes = gable();
        for (y, want) in [(0.0, 2.8), (1.5, 3.55), (3.0, 4.3), (4.5, 3.55), (6.0, 2.8)] {
            let got = lowest(&planes, [4.0, y]);
            assert!((got - want).abs() < 1e-12, "y = {y}: {got} vs {want}");
        }
        // Each plane's cell ends at the ridge.
        for c in &planes[0].cell {
            assert!(c[1] <= 3.0 + 1e-12, "{c:?}");
        }
        for c in &planes[1].cell {
            assert!(c[1] >= 3.0 - 1e-12, "{c:?}");
        }
    }

    #[test]
    fn a_gable_wall_is_a_pentagon_and_an_eaves_wall_a_rectangle() {
        let planes = gable();
        let end = over_edge(&planes, [0.0, 6.0], [0.0, 0.0], 1e-9);
        let heights: Vec<f64> = end.iter().map(|c| c.1).collect();
        assert_eq!(end.len(), 3, "{end:?}");
        assert!((heights[1] - 4.3).abs() < 1e-12 && (end[1].0[1] - 3.0).abs() < 1e-12);
        let eaves = over_edge(&planes, [0.0, 0.0], [10.0, 0.0], 1e-9);
        assert_eq!(eaves.len(), 2, "{eaves:?}");
    }

    #[test]
    fn vertical_and_degenerate_planes_are_no_ceiling() {
        let vertical = [
            Vec3::new(0.0, 0.0, 0.0),
            Vec3::new(1.0, 0.0, 0.0),
            Vec3::new(0.0, 0.0, 1.0),
        ];
        assert!(CeilingPlane::through("c".into(), vertical).is_none());
        let collinear = [
            Vec3::new(0.0, 0.0, 2.0),
            Vec3::new(1.0, 1.0, 2.0),
            Vec3::new(2.0, 2.0, 2.0),
        ];
        assert!(CeilingPlane::through("c".into(), collinear).is_none());
    }
}
