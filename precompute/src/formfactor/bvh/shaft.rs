//! Shaft culling (Haines & Wallace 1994): the few occluders that can cut a segment between
//! two given polygons, so that rays between them are tested against those alone.

use super::{Aabb, Blocker, Occluders, STACK};
use crate::geometry::Vec3;

impl Occluders {
    /// The occluders (other than those in `ignore`) that may cut a segment from a point of
    /// polygon `a` to a point of polygon `b` (corners and the unit normal of the side that
    /// emits or receives; a point sensor is a one-corner polygon): those whose box meets the
    /// pair's bounding box, that lie in front of both polygons, straddle neither polygon's
    /// side of their plane and meet the convex hull of the two polygons (shaft culling,
    /// Haines & Wallace 1994). Rays between the two polygons then only need testing against
    /// these few ([`Occluders::visible_in`]).
    pub(crate) fn shaft(
        &self,
        a: &[Vec3],
        a_normal: Vec3,
        b: &[Vec3],
        b_normal: Vec3,
        ignore: &[usize],
    ) -> Shaft {
        let mut shaft = Shaft::default();
        self.visit_shaft(a, a_normal, b, b_normal, ignore, &mut |index| {
            shaft.push(index)
        });
        shaft
    }

    /// The outlines (corners in order, metres) of every occluder [`Occluders::shaft`] would
    /// list, however many: where the shadows themselves are wanted, not rays.
    pub(crate) fn shaft_outlines_all(
        &self,
        a: &[Vec3],
        a_normal: Vec3,
        b: &[Vec3],
        b_normal: Vec3,
        ignore: &[usize],
    ) -> Vec<&[Vec3]> {
        let mut outlines = Vec::new();
        self.visit_shaft(a, a_normal, b, b_normal, ignore, &mut |index| {
            let k = &self.blockers[index];
            outlines.push(&k.corners[..k.len]);
            true
        });
        outlines
    }

    /// Calls `found` with the index of each occluder of [`Occluders::shaft`] until it returns
    /// false.
    fn visit_shaft(
        &self,
        a: &[Vec3],
        a_normal: Vec3,
        b: &[Vec3],
        b_normal: Vec3,
        ignore: &[usize],
        found: &mut dyn FnMut(usize) -> bool,
    ) {
        if self.blockers.is_empty() || a.is_empty() || b.is_empty() {
            return;
        }
        let tol = self.tolerance;
        let bounds = Aabb::of(a).union(Aabb::of(b)).expanded(tol);
        // Segments leave `a` forwards and arrive at `b` from the front: an occluder entirely
        // behind either plane cannot meet them.
        let a_off = a_normal.dot(a[0]);
        let b_off = b_normal.dot(b[0]);
        let mut hull: Option<HullPlanes> = None;
        let mut stack = [0usize; STACK];
        let mut top = 1;
        while top > 0 {
            top -= 1;
            let node = self.nodes[stack[top]];
            if !node.bounds.overlaps(&bounds)
                || node.bounds.max_height(a_normal, a_off) <= tol
                || node.bounds.max_height(b_normal, b_off) <= tol
            {
                continue;
            }
            if node.count > 0 {
                for index in node.first..node.first + node.count {
                    let k = &self.blockers[index];
                    if self.ignores(ignore, k)
                        || !k.bounds.overlaps(&bounds)
                        || !straddles(k, a, b, tol)
                        || !in_front(&k.corners[..k.len], a_normal, a_off, tol)
                        || !in_front(&k.corners[..k.len], b_normal, b_off, tol)
                    {
                        continue;
                    }
                    let planes = hull.get_or_insert_with(|| HullPlanes::of(a, b, tol));
                    if planes.excludes(&k.corners[..k.len], tol) {
                        continue;
                    }
                    if !found(index) {
                        return;
                    }
                }
            } else if top + 2 <= STACK {
                stack[top] = node.first;
                stack[top + 1] = node.right;
                top += 2;
            }
        }
    }

    /// Does one blocker cut every segment from the convex polygon `a` to the convex polygon
    /// `b` (corners, metres), so that no light passes between any of their points? True when
    /// a blocker's plane has `a` strictly on one side and `b`
    /// strictly on the other, and the points where the segments between their corners cross
    /// that plane all lie strictly inside the blocker. Those points span every crossing: a
    /// point of the plane on a segment from `a` to `b` lies in the convex hull of `a ∪ b`,
    /// whose section by the plane is the hull of the corner segments' crossings. "Strictly"
    /// is by ten times the hierarchy's tolerance, so that the shadow of the blocker from any
    /// point of `a` covers all of `b` with room to spare for rounding.
    pub(crate) fn one_blocker_hides(&self, a: &[Vec3], b: &[Vec3]) -> bool {
        if self.blockers.is_empty() || a.is_empty() || b.is_empty() {
            return false;
        }
        let margin = 10.0 * self.tolerance;
        let bounds = Aabb::of(a).union(Aabb::of(b));
        let mut stack = [0usize; STACK];
        let mut top = 1;
        while top > 0 {
            top -= 1;
            let node = self.nodes[stack[top]];
            if !node.bounds.overlaps(&bounds) {
                continue;
            }
            if node.count > 0 {
                let run = &self.blockers[node.first..node.first + node.count];
                if run.iter().any(|k| k.hides(a, b, margin)) {
                    return true;
                }
            } else if top + 2 <= STACK {
                stack[top] = node.first;
                stack[top + 1] = node.right;
                top += 2;
            }
        }
        false
    }

    /// [`Occluders::visible`] for a segment between the two polygons `shaft` was built for:
    /// only the shaft's occluders are tested (all of them when it overflowed).
    pub(crate) fn visible_in(&self, shaft: &Shaft, from: Vec3, to: Vec3, ignore: &[usize]) -> bool {
        if shaft.overflow {
            return self.visible(from, to, ignore);
        }
        let d = to - from;
        let (t0, t1) = (1e-7, 1.0 - 1e-7);
        !shaft.ids[..shaft.len].iter().any(|&k| {
            self.blockers
                .get(k as usize)
                .is_some_and(|b| !self.ignores(ignore, b) && b.hit(from, d, t0, t1))
        })
    }
    /// The outlines of the occluders a shaft lists (corners in order, metres), or `None` when it
    /// overflowed and only rays through the whole hierarchy can tell.
    pub(crate) fn shaft_outlines<'s>(
        &'s self,
        shaft: &'s Shaft,
    ) -> Option<impl Iterator<Item = &'s [Vec3]> + 's> {
        (!shaft.overflow).then(|| {
            shaft.ids[..shaft.len]
                .iter()
                .filter_map(|&k| self.blockers.get(k as usize))
                .map(|b| &b.corners[..b.len])
        })
    }
}

impl Blocker {
    /// [`Occluders::one_blocker_hides`] for this blocker.
    fn hides(&self, a: &[Vec3], b: &[Vec3], margin: f64) -> bool {
        let height = |p: Vec3| self.normal.dot(p) - self.offset;
        let above = |side: &[Vec3]| side.iter().all(|&p| height(p) > margin);
        let below = |side: &[Vec3]| side.iter().all(|&p| height(p) < -margin);
        if !(above(a) && below(b) || below(a) && above(b)) {
            return false;
        }
        let inside = |x: Vec3| {
            (0..self.len).all(|k| {
                let m = self.edge_normals[k];
                (x - self.corners[k]).dot(m) > margin * m.length()
            })
        };
        a.iter().all(|&p| {
            b.iter().all(|&q| {
                let (hp, hq) = (height(p), height(q));
                inside(p + (q - p) * (hp / (hp - hq)))
            })
        })
    }
}

/// Most occluders a [`Shaft`] lists; beyond that rays traverse the whole hierarchy.
const SHAFT_MAX: usize = 64;

/// The occluders that may cut segments between two polygons ([`Occluders::shaft`]).
#[derive(Clone, Debug)]
pub(crate) struct Shaft {
    ids: [u32; SHAFT_MAX],
    len: usize,
    /// More than [`SHAFT_MAX`] candidates: test rays against every occluder.
    overflow: bool,
}

impl Default for Shaft {
    fn default() -> Self {
        Shaft {
            ids: [0; SHAFT_MAX],
            len: 0,
            overflow: false,
        }
    }
}

impl Shaft {
    /// No occluder can cut a segment between the two polygons: no ray is needed.
    pub(crate) fn is_clear(&self) -> bool {
        self.len == 0 && !self.overflow
    }

    /// Adds a blocker; false (and `overflow`) when full.
    fn push(&mut self, index: usize) -> bool {
        match (self.ids.get_mut(self.len), u32::try_from(index)) {
            (Some(slot), Ok(id)) => {
                *slot = id;
                self.len += 1;
                true
            }
            _ => {
                self.overflow = true;
                false
            }
        }
    }
}

/// Most planes of a [`HullPlanes`]: two quadrilaterals give 2 × 4 × 4 candidates.
const HULL_MAX: usize = 2 * PATCH_CORNERS * PATCH_CORNERS;
/// Corners of a polygon taken into account for the hull planes.
const PATCH_CORNERS: usize = 4;

/// Planes through an edge of one polygon and a corner of the other that have both polygons
/// on their inner side: faces of the convex hull of the pair (the shaft's sides). A point
/// strictly outside one of them is outside the hull.
struct HullPlanes {
    /// Outward unit normal and offset (`normal · x = offset` on the plane), metres.
    planes: [(Vec3, f64); HULL_MAX],
    len: usize,
}

impl HullPlanes {
    fn of(a: &[Vec3], b: &[Vec3], tol: f64) -> HullPlanes {
        let mut out = HullPlanes {
            planes: [(Vec3::ZERO, 0.0); HULL_MAX],
            len: 0,
        };
        // Polygons with more corners than a quadrilateral contribute no side planes (the hull
        // test is then only looser, never wrong).
        if a.len() > PATCH_CORNERS || b.len() > PATCH_CORNERS {
            return out;
        }
        for (p, q) in [(a, b), (b, a)] {
            if p.len() < 2 {
                continue;
            }
            for k in 0..p.len() {
                let (s, e) = (p[k], p[(k + 1) % p.len()]);
                for &v in q {
                    let n = (e - s).cross(v - s);
                    let len = n.length();
                    if len <= 1e-12 * (e - s).length().max(1e-300) * (v - s).length() {
                        continue;
                    }
                    let n = n / len;
                    let off = n.dot(s);
                    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
                    for &x in a.iter().chain(b) {
                        let h = n.dot(x) - off;
                        lo = lo.min(h);
                        hi = hi.max(h);
                    }
                    let plane = if hi <= tol {
                        (n, off)
                    } else if lo >= -tol {
                        (-n, -off)
                    } else {
                        continue;
                    };
                    if let Some(slot) = out.planes.get_mut(out.len) {
                        *slot = plane;
                        out.len += 1;
                    }
                }
            }
        }
        out
    }

    /// Are all `corners` strictly outside one of the planes (so the polygon misses the hull)?
    fn excludes(&self, corners: &[Vec3], tol: f64) -> bool {
        self.planes[..self.len]
            .iter()
            .any(|&(n, off)| corners.iter().all(|&c| n.dot(c) - off > tol))
    }
}

/// Some corner strictly in front of the plane `normal · p = offset`.
fn in_front(corners: &[Vec3], normal: Vec3, offset: f64, tol: f64) -> bool {
    corners.iter().any(|&c| normal.dot(c) - offset > tol)
}

/// Corners of `a` and `b` on both sides of the blocker's plane (else no segment crosses it).
fn straddles(k: &Blocker, a: &[Vec3], b: &[Vec3], tol: f64) -> bool {
    let (mut above, mut below) = (false, false);
    for &p in a.iter().chain(b) {
        let h = k.normal.dot(p) - k.offset;
        above |= h > tol;
        below |= h < -tol;
    }
    above && below
}
