//! A face's frame: the rectangle around a face in which openings are placed by two
//! parameters, and the grid of cut positions along each.

use crate::geometry::{Polygon, Vec3};
use crate::scene::room::Point2;

/// A face rectangle a-b-c-d and its parameterisation `a + (b − a) s + (d − a) t`; for a
/// face that is not a parallelogram (a wall under a sloped ceiling), the rectangle around it
/// whose cells are clipped to the face.
pub(super) struct Frame {
    pub(super) a: Vec3,
    pub(super) ab: Vec3,
    pub(super) ad: Vec3,
    /// Inward unit normal of the face.
    pub(super) normal: Vec3,
    /// The face's outline when the rectangle is larger than the face, else `None`.
    pub(super) outline: Option<Vec<Vec3>>,
}

impl Frame {
    /// The frame of a face wound from `a` up its first side to `b` and back along its last
    /// side to `d`; of any other convex face, the rectangle on its last side `a`–`d` that
    /// holds it.
    pub(super) fn new(corners: &[Vec3]) -> Self {
        let normal = Polygon::new(corners.to_vec()).normal();
        let n = corners.len();
        let (a, ad) = (corners[0], corners[n - 1] - corners[0]);
        if let [a, b, c, d] = corners {
            let skew = (*c - (*b + *d - *a)).length();
            if skew <= 1e-12 * (*c - *a).length() {
                return Frame {
                    a: *a,
                    ab: *b - *a,
                    ad: *d - *a,
                    normal,
                    outline: None,
                };
            }
        }
        // Square to the last side, towards the face's first corner after `a` (up a wall),
        // as far as the face reaches.
        let mut up = normal.cross(ad).normalized();
        if (corners[1] - a).dot(up) < 0.0 {
            up = up * -1.0;
        }
        let reach = corners.iter().map(|&p| (p - a).dot(up)).fold(0.0, f64::max);
        Frame {
            a,
            ab: up * reach,
            ad,
            normal,
            outline: Some(corners.to_vec()),
        }
    }

    /// Whether `p` (m, in the face's plane) lies in the face, within `tol` (m).
    pub(super) fn holds(&self, p: Vec3, tol: f64) -> bool {
        let Some(outline) = &self.outline else {
            let (s, t) = self.params(p);
            let (ts, tt) = (tol / self.ab.length(), tol / self.ad.length());
            return s >= -ts && s <= 1.0 + ts && t >= -tt && t <= 1.0 + tt;
        };
        let n = outline.len();
        (0..n).all(|i| {
            let (u, v) = (outline[i], outline[(i + 1) % n]);
            let inward = self.normal.cross(v - u).normalized();
            (p - u).dot(inward) >= -tol
        })
    }

    /// The convex cell `cell` (m, in the face's plane) clipped to the face
    /// (Sutherland–Hodgman, one edge at a time); empty when nothing wider than `tol` (m) is
    /// left.
    pub(super) fn clip(&self, cell: Vec<Vec3>, tol: f64) -> Vec<Vec3> {
        let Some(outline) = &self.outline else {
            return cell;
        };
        let mut out = cell;
        let n = outline.len();
        for i in 0..n {
            let (u, v) = (outline[i], outline[(i + 1) % n]);
            let inward = self.normal.cross(v - u).normalized();
            let f = |p: Vec3| (p - u).dot(inward);
            let input = std::mem::take(&mut out);
            for k in 0..input.len() {
                let (p, q) = (input[k], input[(k + 1) % input.len()]);
                let (fp, fq) = (f(p), f(q));
                if fp >= -tol {
                    out.push(p);
                }
                if (fp < -tol && fq > tol) || (fp > tol && fq < -tol) {
                    out.push(p + (q - p) * (fp / (fp - fq)));
                }
            }
        }
        // Corners left within `tol` of each other are one.
        let mut kept: Vec<Vec3> = Vec::with_capacity(out.len());
        for p in out {
            if kept.last().is_none_or(|&l: &Vec3| (p - l).length() > tol) {
                kept.push(p);
            }
        }
        while kept.len() > 1 && (kept[0] - kept[kept.len() - 1]).length() <= tol {
            kept.pop();
        }
        let big_enough = kept.len() >= 3 && Polygon::new(kept.clone()).area() > tol * tol;
        if big_enough {
            kept
        } else {
            Vec::new()
        }
    }

    /// `p` (m, in the face's plane) in the plane's coordinates: metres along `ab`, then along
    /// `ad` (square to each other: a rectangle's sides, or a wall's foot and its rise).
    pub(super) fn to_plane(&self, p: Vec3) -> Point2 {
        let (s, t) = self.params(p);
        [s * self.ab.length(), t * self.ad.length()]
    }

    /// The point of the face's plane at plane coordinates `q` ([`Frame::to_plane`]), m.
    pub(super) fn point_in_plane(&self, q: Point2) -> Vec3 {
        self.point(q[0] / self.ab.length(), q[1] / self.ad.length())
    }

    /// The face's outline in the plane's coordinates ([`Frame::to_plane`]).
    pub(super) fn outline_in_plane(&self) -> Vec<Point2> {
        match &self.outline {
            Some(outline) => outline.iter().map(|&p| self.to_plane(p)).collect(),
            None => {
                let (s, t) = (self.ab.length(), self.ad.length());
                vec![[0.0, 0.0], [s, 0.0], [s, t], [0.0, t]]
            }
        }
    }

    pub(super) fn point(&self, s: f64, t: f64) -> Vec3 {
        self.a + self.ab * s + self.ad * t
    }

    pub(super) fn params(&self, p: Vec3) -> (f64, f64) {
        let d = p - self.a;
        (
            d.dot(self.ab) / self.ab.dot(self.ab),
            d.dot(self.ad) / self.ad.dot(self.ad),
        )
    }
}

/// The sorted cut positions in [0, 1]: both ends and every opening edge, positions closer
/// than `tol` merged into the first.
pub(super) fn grid(edges: impl Iterator<Item = f64>, tol: f64) -> Vec<f64> {
    let mut all: Vec<f64> = edges.chain([0.0, 1.0]).collect();
    all.sort_by(f64::total_cmp);
    let mut out: Vec<f64> = Vec::with_capacity(all.len());
    for x in all {
        match out.last() {
            Some(&last) if x - last <= tol => {}
            _ => out.push(x),
        }
    }
    // The far end is exactly 1 even if an opening edge within `tol` of it came first.
    if let Some(last) = out.last_mut() {
        *last = 1.0;
    }
    out
}

/// The grid position nearest to `x`.
pub(super) fn snap(grid: &[f64], x: f64) -> f64 {
    grid.iter()
        .copied()
        .min_by(|a, b| (a - x).abs().total_cmp(&(b - x).abs()))
        .unwrap_or(x)
}
