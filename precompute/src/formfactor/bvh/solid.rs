//! Solids: closed boxes (a desk, a storage tower) whose faces block together. A segment that
//! passes through a solid's inside must cross one of its faces on the way in or out, so a pair
//! of polygons every segment between which runs through a solid is hidden whole, even where
//! no single face hides it (a floor patch behind a desk is hidden by its side and its top
//! together). Deciding that once, from the polygons' corners, saves casting the shadow of
//! every face at every quadrature point of the pair, or reading a block of clusters at all.

use super::Occluders;
use crate::geometry::{Aabb, Vec3};

/// A closed axis-aligned box among the occluders: its faces are all patches of the scene,
/// except perhaps the bottom or the top, where it stands on a floor or reaches a ceiling
/// (`open_below`, `open_above`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Solid {
    /// The box, metres.
    pub bounds: Aabb,
    /// The box has no bottom face (it stands on a floor).
    pub open_below: bool,
    /// The box has no top face (it reaches the ceiling).
    pub open_above: bool,
}

/// Where, along each axis, [`Solid::hides`] tries a plane across the box: shares of its
/// width. A segment through the box crosses each such plane inside it, so one of them holds
/// every crossing of the pairs a solid hides unless the segments pass it at very different
/// places; five per axis catch the floor's desks and towers.
const CROSSINGS: [f64; 5] = [0.125, 0.25, 0.5, 0.75, 0.875];

impl Solid {
    /// Does every segment from a point of `a` to a point of `b` (convex polygons, corners in
    /// metres) pass through the inside of the box, so that some face of it (not one of `a` or
    /// `b`, which lie outside it or on it) cuts each of them?
    ///
    /// True when, for one plane across the box perpendicular to an axis, `a` lies strictly on
    /// one side and `b` on the other, and every segment between their corners crosses the
    /// plane strictly inside the box: the crossings of all segments from `a` to `b` are the
    /// convex hull of those (the section of the hull of `a ∪ b` by the plane), and a convex
    /// hull of points inside the box is inside it. Such a segment goes in and out of the box;
    /// it leaves through a face unless it ends on the box, and at least one of `a` and `b` is
    /// required to lie strictly outside it. Where a face is missing, both polygons must lie on
    /// the box's side of its plane, so that no segment passes through the gap. "Strictly" is
    /// by `margin` metres.
    pub(crate) fn hides(&self, a: &[Vec3], b: &[Vec3], margin: f64) -> bool {
        let (lo, hi) = (self.bounds.min, self.bounds.max);
        let above_floor = |p: &[Vec3]| p.iter().all(|c| c.z >= lo.z - margin);
        let below_top = |p: &[Vec3]| p.iter().all(|c| c.z <= hi.z + margin);
        if self.open_below && !(above_floor(a) && above_floor(b))
            || self.open_above && !(below_top(a) && below_top(b))
        {
            return false;
        }
        let outside = |p: &[Vec3]| {
            (0..3).any(|k| {
                p.iter().all(|c| c.axis(k) < lo.axis(k) - margin)
                    || p.iter().all(|c| c.axis(k) > hi.axis(k) + margin)
            })
        };
        if !(outside(a) || outside(b)) {
            return false;
        }
        let inside = |x: Vec3, skip: usize| {
            (0..3).all(|k| {
                k == skip || (x.axis(k) > lo.axis(k) + margin && x.axis(k) < hi.axis(k) - margin)
            })
        };
        (0..3).any(|k| {
            CROSSINGS.iter().any(|&share| {
                let c = lo.axis(k) + share * (hi.axis(k) - lo.axis(k));
                let before = |p: &[Vec3]| p.iter().all(|v| v.axis(k) < c - margin);
                let after = |p: &[Vec3]| p.iter().all(|v| v.axis(k) > c + margin);
                (before(a) && after(b) || after(a) && before(b))
                    && a.iter().all(|&p| {
                        b.iter().all(|&q| {
                            let t = (c - p.axis(k)) / (q.axis(k) - p.axis(k));
                            inside(p + (q - p) * t, k)
                        })
                    })
            })
        })
    }
}

impl Occluders {
    /// The same occluders with `solids` added: boxes among them whose faces are all patches
    /// of the scene but the open ones ([`Solid`]). They change no segment's visibility, only
    /// how quickly a pair hidden by several of a box's faces together is found so.
    pub fn with_solids(mut self, solids: &[Solid]) -> Self {
        self.solids = solids.to_vec();
        self
    }

    /// Does one solid hide every point of the convex polygon `b` from every point of `a`
    /// (corners, metres)? Then the form factors between them are 0 both ways ([`Solid::hides`];
    /// strictly by ten times the hierarchy's tolerance).
    pub(crate) fn solid_hides(&self, a: &[Vec3], b: &[Vec3]) -> bool {
        if self.solids.is_empty() || a.is_empty() || b.is_empty() {
            return false;
        }
        let margin = 10.0 * self.tolerance;
        let pair = Aabb::of(a).union(Aabb::of(b));
        self.solids
            .iter()
            .any(|s| s.bounds.overlaps(&pair) && s.hides(a, b, margin))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::{Patch, Polygon};

    fn v(x: f64, y: f64, z: f64) -> Vec3 {
        Vec3::new(x, y, z)
    }

    /// A horizontal square over `[x0, x0 + 0.6] × [0.2, 0.8]` at height `z`.
    fn square(x0: f64, z: f64) -> Vec<Vec3> {
        vec![
            v(x0, 0.2, z),
            v(x0 + 0.6, 0.2, z),
            v(x0 + 0.6, 0.8, z),
            v(x0, 0.8, z),
        ]
    }

    /// Reference: rays through the faces themselves ([`Occluders::visible`]). A 1 m cube's
    /// four sides, as patches: a square below it and one above see each other straight
    /// through it when it has neither bottom nor top (a chimney), so a solid open below and
    /// above must not hide them, while the closed cube does. A square low beside the cube
    /// and one just above its far half are hidden (every corner segment goes in through the
    /// side and out through the top); one far above it is not.
    #[test]
    fn a_solid_hides_only_what_its_faces_hide() {
        let cube = Aabb {
            min: v(0.0, 0.0, 0.0),
            max: v(1.0, 1.0, 1.0),
        };
        let sides: Vec<Patch> = [
            [v(0., 0., 0.), v(0., 0., 1.), v(0., 1., 1.), v(0., 1., 0.)],
            [v(1., 0., 0.), v(1., 1., 0.), v(1., 1., 1.), v(1., 0., 1.)],
            [v(0., 0., 0.), v(1., 0., 0.), v(1., 0., 1.), v(0., 0., 1.)],
            [v(0., 1., 0.), v(0., 1., 1.), v(1., 1., 1.), v(1., 1., 0.)],
        ]
        .iter()
        .map(|c| Patch::new(Polygon::new(c.to_vec()), 0))
        .collect();
        let chimney = Occluders::new(&sides);
        let (below, above) = (square(0.2, -0.5), square(0.2, 1.5));
        assert!(chimney.visible(v(0.5, 0.5, -0.5), v(0.5, 0.5, 1.5), &[]));
        let margin = 1e-9;
        let closed = Solid {
            bounds: cube,
            open_below: false,
            open_above: false,
        };
        let open = Solid {
            open_below: true,
            open_above: true,
            ..closed
        };
        assert!(closed.hides(&below, &above, margin));
        assert!(!open.hides(&below, &above, margin));
        assert!(!open.hides(&above, &below, margin));
        // Beside the cube, low, and above the far half of it: through the side, out the top.
        let beside: Vec<Vec3> = vec![
            v(-0.3, 0.3, 0.1),
            v(-0.3, 0.7, 0.1),
            v(-0.3, 0.7, 0.3),
            v(-0.3, 0.3, 0.3),
        ];
        let over_far_half = vec![
            v(0.6, 0.2, 1.05),
            v(0.9, 0.2, 1.05),
            v(0.9, 0.8, 1.05),
            v(0.6, 0.8, 1.05),
        ];
        assert!(closed.hides(&beside, &over_far_half, margin));
        assert!(closed.hides(&over_far_half, &beside, margin));
        let far_above = square(-0.5, 3.0);
        assert!(!closed.hides(&beside, &far_above, margin));
        // What the faces say of the corners' segments of the hidden pair: every one is cut.
        let cube_faces = Occluders::new(
            &sides
                .iter()
                .cloned()
                .chain([Patch::new(
                    Polygon::new(vec![
                        v(0., 0., 1.),
                        v(1., 0., 1.),
                        v(1., 1., 1.),
                        v(0., 1., 1.),
                    ]),
                    0,
                )])
                .collect::<Vec<_>>(),
        );
        for &p in &beside {
            for &q in &over_far_half {
                assert!(!cube_faces.visible(p, q, &[]), "{p:?} to {q:?}");
            }
        }
    }
}
