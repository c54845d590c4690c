//! Visible fraction of a target patch seen from a point, by rays refined at silhouettes.
//!
//! The target is parametrised over the unit square (bilinear for a quadrilateral, collapsed for
//! a triangle). A cell whose corners and centre are all visible counts as visible, all blocked
//! as blocked (exact when the shadow on the cell is convex, as behind one convex blocker);
//! otherwise it is split in four, down to a depth limit, where the five rays vote. Cells are
//! weighted by the point-to-point kernel `cos θ_x cos θ_y / r²` times their area, so the result
//! is the kernel-weighted visible fraction that multiplies the exact unoccluded form factor.

use super::bvh::{Occluders, Shaft};
use super::kernel::Cone;
use crate::geometry::{Patch, Vec3};

/// A target patch as a map from the unit square.
#[derive(Clone, Copy, Debug)]
pub(crate) enum Param {
    /// Bilinear map of a quadrilateral's corners.
    Quad([Vec3; 4]),
    /// Collapsed map `a + u (b − a) + u v (c − b)` of a triangle.
    Tri([Vec3; 3]),
}

impl Param {
    /// The parametrisation of a 3- or 4-cornered patch; `None` for other polygons.
    pub(crate) fn of(p: &Patch) -> Option<Param> {
        match *p.polygon.vertices.as_slice() {
            [a, b, c] => Some(Param::Tri([a, b, c])),
            [a, b, c, d] => Some(Param::Quad([a, b, c, d])),
            _ => None,
        }
    }

    /// Point at parameters (u, v), metres.
    pub(super) fn point(&self, u: f64, v: f64) -> Vec3 {
        match *self {
            Param::Quad(c) => {
                c[0] * ((1.0 - u) * (1.0 - v))
                    + c[1] * (u * (1.0 - v))
                    + c[2] * (u * v)
                    + c[3] * ((1.0 - u) * v)
            }
            Param::Tri([a, b, c]) => a + (b - a) * u + (c - b) * (u * v),
        }
    }

    /// Area density |∂p/∂u × ∂p/∂v| at (u, v), m².
    pub(super) fn jacobian(&self, u: f64, v: f64) -> f64 {
        match *self {
            Param::Quad(c) => {
                let du = (c[1] - c[0]) * (1.0 - v) + (c[2] - c[3]) * v;
                let dv = (c[3] - c[0]) * (1.0 - u) + (c[2] - c[1]) * u;
                du.cross(dv).length()
            }
            Param::Tri([a, b, c]) => u * (b - a).cross(c - b).length(),
        }
    }
}

/// One visibility query: from `point` (normal `normal`, optional field of view) to a target.
pub(crate) struct Query<'a> {
    pub(crate) occluders: &'a Occluders,
    /// The occluders that can cut a ray of this query ([`Occluders::shaft`]).
    pub(crate) shaft: &'a Shaft,
    pub(crate) point: Vec3,
    pub(crate) normal: Vec3,
    pub(crate) cone: Option<&'a Cone>,
    pub(crate) target: Param,
    pub(crate) target_normal: Vec3,
    pub(crate) ignore: &'a [usize],
    /// Largest number of splits of a cell (the finest cells are 2^-depth of the patch's side).
    pub(crate) depth: u32,
    /// A cell whose unoccluded form factor (dimensionless) exceeds this is split even when its
    /// rays agree, so that shadows smaller than a large, close cell are not missed.
    pub(crate) max_cell_share: f64,
}

/// Parameter inset from the patch boundary, so that rays end inside the target.
const INSET: f64 = 1e-6;

impl Query<'_> {
    /// Kernel-weighted visible fraction in [0, 1] (module docs). `None` when no cell centre of the
    /// target is in view of the point (a sliver at grazing incidence): the caller decides.
    pub(crate) fn visible_fraction(&self) -> Option<f64> {
        let (lo, hi) = (INSET, 1.0 - INSET);
        let corners = [
            self.ray(lo, lo),
            self.ray(hi, lo),
            self.ray(hi, hi),
            self.ray(lo, hi),
        ];
        let (seen, total) = self.cell(lo, hi, lo, hi, corners, 0);
        (total > 0.0).then(|| (seen / total).clamp(0.0, 1.0))
    }

    fn ray(&self, u: f64, v: f64) -> bool {
        self.occluders
            .visible_in(self.shaft, self.point, self.target.point(u, v), self.ignore)
    }

    /// Kernel weight of the cell `[u0, u1] × [v0, v1]` from its centre (midpoint rule):
    /// π times its unoccluded form factor from the point (dimensionless).
    fn weight(&self, u0: f64, u1: f64, v0: f64, v1: f64) -> f64 {
        let (u, v) = (0.5 * (u0 + u1), 0.5 * (v0 + v1));
        let d = self.target.point(u, v) - self.point;
        let (cx, cy) = (self.normal.dot(d), -self.target_normal.dot(d));
        if cx <= 0.0 || cy <= 0.0 || self.cone.is_some_and(|c| !c.contains(self.normal, d)) {
            return 0.0;
        }
        let r2 = d.dot(d);
        self.target.jacobian(u, v) * (u1 - u0) * (v1 - v0) * cx * cy / (r2 * r2)
    }

    /// (visible weight, total weight) of a cell whose corner rays are known, corners in the
    /// order (u0, v0), (u1, v0), (u1, v1), (u0, v1).
    fn cell(
        &self,
        u0: f64,
        u1: f64,
        v0: f64,
        v1: f64,
        corners: [bool; 4],
        depth: u32,
    ) -> (f64, f64) {
        let (um, vm) = (0.5 * (u0 + u1), 0.5 * (v0 + v1));
        let centre = self.ray(um, vm);
        let agree = corners.iter().all(|&c| c == centre);
        let w = self.weight(u0, u1, v0, v1);
        let small = w <= std::f64::consts::PI * self.max_cell_share;
        if (agree && small) || depth >= self.depth {
            let votes = corners.iter().filter(|&&c| c).count() + usize::from(centre);
            return (w * votes as f64 / 5.0, w);
        }
        let bottom = self.ray(um, v0);
        let right = self.ray(u1, vm);
        let top = self.ray(um, v1);
        let left = self.ray(u0, vm);
        let [c00, c10, c11, c01] = corners;
        let d = depth + 1;
        let parts = [
            self.cell(u0, um, v0, vm, [c00, bottom, centre, left], d),
            self.cell(um, u1, v0, vm, [bottom, c10, right, centre], d),
            self.cell(um, u1, vm, v1, [centre, right, c11, top], d),
            self.cell(u0, um, vm, v1, [left, centre, top, c01], d),
        ];
        parts
            .iter()
            .fold((0.0, 0.0), |acc, p| (acc.0 + p.0, acc.1 + p.1))
    }
}

/// Patches of a cluster whose centroids each patch of the other cluster casts rays to (at
/// most), in [`between_clusters`].
pub(crate) const CLUSTER_RAY_ENDS: usize = 16;

/// How much of the light between the patches `a` and the patches `b` (indices into
/// `patches`) the occluders let through, as one factor per patch: the block of a pair's
/// entries is approximated by `V_ij = r_i c_j`, with `r` and `c` returned (dimensionless).
///
/// Each patch `i` of `a` casts rays from its centroid to the centroids of up to
/// [`CLUSTER_RAY_ENDS`] patches of `b` spread evenly over the list, each weighted by the
/// point-to-point kernel `A_j cos θ_i cos θ_j / r²`; `f_i`, the weighted share of them that no
/// blocker cuts, is its own view of `b`; likewise `g_j` for each patch of `b`. With `v̄` the
/// kernel-weighted mean of all those rays, `V_ij = f_i g_j / v̄`, so that `r_i = f_i / √v̄` and
/// `c_j = g_j / √v̄`: exact where the blockers that matter stand next to one cluster (a desk
/// over part of the floor, seen from the ceiling), and the block's mean either way. A patch
/// none of whose rays face the other cluster takes `v̄`. All zeros when no ray gets through;
/// all ones where no ray faces (nothing to say the light is cut). Deterministic: the same
/// lists give the same rays.
pub(crate) fn between_clusters(
    occluders: &Occluders,
    patches: &[Patch],
    a: &[usize],
    b: &[usize],
) -> (Vec<f64>, Vec<f64>) {
    let spread = |list: &[usize]| -> Vec<usize> {
        let k = list.len().min(CLUSTER_RAY_ENDS);
        (0..k)
            .map(|s| list[(2 * s + 1) * list.len() / (2 * k)])
            .collect()
    };
    // (seen, total) kernel weights of the rays from each patch of `from` to `to`'s ends.
    let views = |from: &[usize], to: &[usize]| -> Vec<(f64, f64)> {
        let ends = spread(to);
        from.iter()
            .map(|&i| {
                let p = &patches[i];
                let (mut seen, mut total) = (0.0, 0.0);
                for &j in &ends {
                    let q = &patches[j];
                    let d = q.centroid - p.centroid;
                    let (cp, cq) = (p.normal.dot(d), -q.normal.dot(d));
                    if i == j || cp <= 0.0 || cq <= 0.0 {
                        continue;
                    }
                    let r2 = d.dot(d);
                    let w = q.area * cp * cq / (r2 * r2);
                    total += w;
                    // The same segment whichever patch casts it.
                    let (from, to) = if i < j {
                        (p.centroid, q.centroid)
                    } else {
                        (q.centroid, p.centroid)
                    };
                    if occluders.visible(from, to, &[i, j]) {
                        seen += w;
                    }
                }
                (seen, total)
            })
            .collect()
    };
    let (rows, cols) = (views(a, b), views(b, a));
    // Each side summed on its own, then added: the same bits whichever list comes first.
    let sum = |views: &[(f64, f64)]| {
        views
            .iter()
            .fold((0.0, 0.0), |(s, t), &(si, ti)| (s + si, t + ti))
    };
    let ((seen_a, total_a), (seen_b, total_b)) = (sum(&rows), sum(&cols));
    let (seen, total) = (seen_a + seen_b, total_a + total_b);
    if !(total > 0.0 && total.is_finite()) {
        return (vec![1.0; a.len()], vec![1.0; b.len()]);
    }
    let mean = (seen / total).clamp(0.0, 1.0);
    if mean == 0.0 {
        return (vec![0.0; a.len()], vec![0.0; b.len()]);
    }
    let root = mean.sqrt();
    let factor = |&(s, t): &(f64, f64)| {
        let own = if t > 0.0 && t.is_finite() {
            (s / t).clamp(0.0, 1.0)
        } else {
            mean
        };
        own / root
    };
    (
        rows.iter().map(factor).collect(),
        cols.iter().map(factor).collect(),
    )
}

#[cfg(test)]
mod tests;
