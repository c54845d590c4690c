//! Exact visibility from a point: the part of a target that no blocker hides, as convex pieces.
//!
//! Seen from a point `x` in front of the target's plane, a convex blocker hides the central
//! projection onto that plane of its part lying between `x` and the plane (the slab
//! `0 ≤ h < h(x)`, `h` the height above the target's plane): its *shadow*, a convex polygon.
//! Parts of a blocker outside the slab cannot cut a segment from `x` to the target. The target
//! minus one convex shadow is a union of convex pieces (the target clipped to the outside of one
//! shadow edge and the inside of the edges before it), so subtracting every shadow in turn
//! leaves the visible part as a short list of convex polygons. The exact kernel summed over them
//! is the visible form factor: no rays and no sampling error, so the visible parts of all
//! targets seen from one point tile its hemisphere exactly, as the blockers are themselves
//! targets.

use super::kernel::SmallPolygon;
use crate::geometry::Vec3;
use std::cell::RefCell;

/// Corners a piece may have: a quadrilateral target clipped by the edges of a few shadows.
const PIECE_CORNERS: usize = 12;
/// Pieces the visible part may consist of; more and the caller falls back to rays.
const MAX_PIECES: usize = 32;
/// Corners of a clipped blocker or its shadow (4 corners clipped by 2 planes).
const SHADOW_CORNERS: usize = 8;

type Piece = SmallPolygon<PIECE_CORNERS>;

thread_local! {
    /// Two piece lists per thread, reused by every query (the current one and the next).
    static SCRATCH: RefCell<(Vec<Piece>, Vec<Piece>)> = const { RefCell::new((Vec::new(), Vec::new())) };
}

/// Sum of `kernel` over the convex pieces of the part of the convex `target` (corners, unit
/// `normal`) visible from `x` past the convex `blockers` (corners in order; orientation does not
/// matter). The pieces run counter-clockwise seen from the target's front, like the target.
/// `None` when `x` is not strictly in front of the target or the visible part has more pieces
/// or corners than the fixed capacities: the caller then estimates visibility with rays.
pub(crate) fn visible_sum<'b>(
    x: Vec3,
    target: &[Vec3],
    normal: Vec3,
    blockers: impl Iterator<Item = &'b [Vec3]>,
    mut kernel: impl FnMut(&[Vec3]) -> f64,
) -> Option<f64> {
    let &origin = target.first()?;
    let height = normal.dot(x - origin);
    if height <= 0.0 || target.len() > PIECE_CORNERS {
        return None;
    }
    let scale = target
        .iter()
        .map(|&c| (c - origin).length())
        .fold(0.0, f64::max);
    // Pieces thinner than this (m²) are dropped: they hold no measurable light.
    let negligible = 1e-14 * scale * scale;
    let pyramid = Pyramid::new(x, target, 1e-9 * (scale + height));
    SCRATCH.with(|scratch| {
        let mut scratch = scratch.try_borrow_mut().ok()?;
        let (current, next) = &mut *scratch;
        current.clear();
        current.push(Piece::from_slice(target));
        for blocker in blockers {
            // Most blockers of a shaft miss the pyramid of any one point: the shaft holds what
            // may cut a segment from anywhere on the source, the pyramid only what may cut one
            // from `x`. Rejecting them here spares casting a shadow that falls beside the
            // target and the needless cuts of pieces along its edges.
            if pyramid.misses(blocker) {
                continue;
            }
            let shadow = match Shadow::cast(x, height, origin, normal, blocker, negligible) {
                Cast::Nothing => continue,
                Cast::Shadow(shadow) => shadow,
                Cast::TooComplex => return None,
            };
            next.clear();
            shadow.subtract(current, next, negligible)?;
            std::mem::swap(current, next);
            if current.is_empty() {
                break;
            }
        }
        Some(current.iter().map(|p| kernel(p.corners())).sum())
    })
}

/// The pyramid of segments from a point to a convex target: the planes through the point and
/// each edge of the target, as inward unit normals. A segment from the point to the target lies
/// inside every plane, so a blocker entirely outside one of them cannot cut it.
struct Pyramid {
    apex: Vec3,
    inward: [Vec3; PIECE_CORNERS],
    len: usize,
    /// Distance outside a plane that counts as outside, metres: corners within it of a plane
    /// are kept, so that rounding never rejects a blocker that touches the pyramid.
    margin: f64,
}

impl Pyramid {
    /// The pyramid from `apex` over `target` (at most [`PIECE_CORNERS`] corners; more, and
    /// the rest are not used: the pyramid is then only larger, never wrong).
    fn new(apex: Vec3, target: &[Vec3], margin: f64) -> Pyramid {
        let mut pyramid = Pyramid {
            apex,
            inward: [Vec3::ZERO; PIECE_CORNERS],
            len: 0,
            margin,
        };
        let count = target.len().min(PIECE_CORNERS);
        if count < 3 {
            return pyramid;
        }
        let centre = target[..count].iter().fold(Vec3::ZERO, |a, &c| a + c) / count as f64;
        for k in 0..count {
            let (a, b) = (target[k], target[(k + 1) % count]);
            let m = (a - apex).cross(b - apex);
            let length = m.length();
            if length.is_nan() || length <= 0.0 {
                // An edge seen end-on: its plane is undefined, and leaving it out only widens
                // the pyramid.
                continue;
            }
            let mut m = m / length;
            let side = m.dot(centre - apex);
            if side == 0.0 {
                // A target of no area: no side to call inward, and leaving the plane out only
                // widens the pyramid.
                continue;
            }
            if side < 0.0 {
                m = -m;
            }
            pyramid.inward[pyramid.len] = m;
            pyramid.len += 1;
        }
        pyramid
    }

    /// Is every corner of `blocker` outside one of the pyramid's planes?
    fn misses(&self, blocker: &[Vec3]) -> bool {
        self.inward[..self.len]
            .iter()
            .any(|&m| blocker.iter().all(|&c| m.dot(c - self.apex) < -self.margin))
    }
}

/// A convex shadow in the target's plane, as the half-planes of its edges: a point on each
/// edge and the in-plane normal pointing into the shadow.
struct Shadow {
    corners: [Vec3; SHADOW_CORNERS],
    inward: [Vec3; SHADOW_CORNERS],
    len: usize,
}

/// What one blocker does to the target.
// A short-lived value on the stack, once per blocker and point: boxing the shadow would put an
// allocation in the innermost loop of the form factors.
#[allow(clippy::large_enum_variant)]
enum Cast {
    /// It hides nothing (outside the slab, or seen edge-on).
    Nothing,
    /// It hides this shadow.
    Shadow(Shadow),
    /// More corners than the fixed capacity: the caller must fall back to rays.
    TooComplex,
}

impl Shadow {
    /// The shadow of `blocker` seen from `x` (at `height` m above the target's plane through
    /// `origin` with unit `normal`).
    fn cast(
        x: Vec3,
        height: f64,
        origin: Vec3,
        normal: Vec3,
        blocker: &[Vec3],
        negligible: f64,
    ) -> Cast {
        if blocker.len() > SHADOW_CORNERS - 2 {
            return Cast::TooComplex;
        }
        // The slab between the target's plane and (just below) the point's height.
        let top = x - normal * (height * 1e-9);
        let mut slab = SmallPolygon::<SHADOW_CORNERS>::from_slice(blocker);
        // Most blockers lie within the slab: clip only those that do not.
        if blocker.iter().any(|&c| normal.dot(c - origin) < 0.0) {
            slab = slab.clip(origin, normal);
        }
        if blocker.iter().any(|&c| normal.dot(c - top) > 0.0) {
            slab = slab.clip(top, -normal);
        }
        if slab.len < 3 {
            return Cast::Nothing;
        }
        let mut projected = [Vec3::ZERO; SHADOW_CORNERS];
        for (s, &p) in projected.iter_mut().zip(slab.corners()) {
            let h = normal.dot(p - origin);
            *s = x + (p - x) * (height / (height - h));
        }
        let corners = &projected[..slab.len];
        let centre = corners.iter().fold(Vec3::ZERO, |a, &c| a + c) / slab.len as f64;
        let extent = corners
            .iter()
            .map(|&c| (c - centre).length())
            .fold(0.0, f64::max);
        let mut shadow = Shadow {
            corners: [Vec3::ZERO; SHADOW_CORNERS],
            inward: [Vec3::ZERO; SHADOW_CORNERS],
            len: 0,
        };
        let mut twice_area = Vec3::ZERO;
        for k in 0..slab.len {
            let (a, b) = (corners[k], corners[(k + 1) % slab.len]);
            twice_area += (a - centre).cross(b - centre);
            // A clipped corner can leave an edge of rounding length, whose direction (and so
            // half-plane) is noise: the neighbouring edges bound the shadow there.
            if (b - a).length() <= 1e-12 * extent {
                continue;
            }
            let mut m = normal.cross(b - a);
            if m.dot(centre - a) < 0.0 {
                m = -m;
            }
            shadow.corners[shadow.len] = a;
            shadow.inward[shadow.len] = m;
            shadow.len += 1;
        }
        if 0.5 * twice_area.length() > negligible && shadow.len >= 3 {
            Cast::Shadow(shadow)
        } else {
            Cast::Nothing
        }
    }

    /// Appends `pieces` minus this shadow to `out`; `None` beyond [`MAX_PIECES`] pieces or
    /// [`PIECE_CORNERS`] corners.
    fn subtract(&self, pieces: &[Piece], out: &mut Vec<Piece>, negligible: f64) -> Option<()> {
        let mut push = |p: Piece| -> Option<()> {
            if area(p.corners()) > negligible {
                if out.len() >= MAX_PIECES {
                    return None;
                }
                out.push(p);
            }
            Some(())
        };
        let edges = self.corners[..self.len]
            .iter()
            .zip(&self.inward[..self.len]);
        for piece in pieces {
            // Entirely outside one edge: untouched (no needless cuts).
            let clear = edges
                .clone()
                .any(|(&a, &m)| piece.corners().iter().all(|&c| m.dot(c - a) <= 0.0));
            if clear {
                push(*piece)?;
                continue;
            }
            let mut rest = *piece;
            for (&a, &m) in edges.clone() {
                // Only an edge that crosses what is left cuts a piece off it.
                if rest.corners().iter().all(|&c| m.dot(c - a) >= 0.0) {
                    continue;
                }
                if rest.len + 1 > PIECE_CORNERS {
                    return None;
                }
                push(rest.clip(a, -m))?;
                rest = rest.clip(a, m);
                if rest.len < 3 {
                    break;
                }
            }
            // What is left of `rest` lies inside the shadow.
        }
        Some(())
    }
}

/// Area of a planar polygon, m².
fn area(corners: &[Vec3]) -> f64 {
    let Some(&o) = corners.first() else {
        return 0.0;
    };
    let mut twice = Vec3::ZERO;
    for w in corners.windows(2) {
        twice += (w[0] - o).cross(w[1] - o);
    }
    0.5 * twice.length()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn v(x: f64, y: f64, z: f64) -> Vec3 {
        Vec3::new(x, y, z)
    }

    /// Visible area, m².
    fn visible_area(x: Vec3, blockers: &[&[Vec3]]) -> Option<f64> {
        visible_sum(x, &FLOOR, UP, blockers.iter().copied(), area)
    }

    /// Unit square on the floor z = 0, facing up.
    const FLOOR: [Vec3; 4] = [
        Vec3::new(0.0, 0.0, 0.0),
        Vec3::new(1.0, 0.0, 0.0),
        Vec3::new(1.0, 1.0, 0.0),
        Vec3::new(0.0, 1.0, 0.0),
    ];
    const UP: Vec3 = Vec3::new(0.0, 0.0, 1.0);

    #[test]
    fn shadow_of_a_square_halfway_is_twice_its_size() {
        // Reference: similar triangles. From (0.5, 0.5, 2) a 0.2 m square at height 1 casts a
        // 0.4 m square shadow centred under the point: visible area 1 − 0.16 m².
        let blocker = [
            v(0.4, 0.4, 1.0),
            v(0.6, 0.4, 1.0),
            v(0.6, 0.6, 1.0),
            v(0.4, 0.6, 1.0),
        ];
        let seen = visible_area(v(0.5, 0.5, 2.0), &[&blocker]).expect("within capacity");
        assert!((seen - 0.84).abs() < 1e-12, "{seen}");
    }

    #[test]
    fn overlapping_shadows_are_not_subtracted_twice() {
        // Reference: inclusion–exclusion by hand. Two squares at height 1 seen from height 2
        // cast shadows [0.1, 0.5]² and [0.3, 0.7]², overlapping in [0.3, 0.5]²:
        // hidden 0.16 + 0.16 − 0.04 m².
        let s = |lo: f64, hi: f64| {
            [
                v(lo, lo, 1.0),
                v(hi, lo, 1.0),
                v(hi, hi, 1.0),
                v(lo, hi, 1.0),
            ]
        };
        let (a, b) = (s(0.3, 0.5), s(0.4, 0.6));
        let x = v(0.5, 0.5, 2.0);
        let seen = visible_area(x, &[&a, &b]).expect("within capacity");
        assert!((seen - (1.0 - 0.28)).abs() < 1e-12, "{seen}");
    }

    #[test]
    fn blocker_parts_outside_the_slab_hide_nothing() {
        // A blocker above the point, and one below the target's plane: nothing hidden. A vertical
        // blocker crossing the point's height only hides through its lower part.
        let above = [
            v(0.4, 0.4, 3.0),
            v(0.6, 0.4, 3.0),
            v(0.6, 0.6, 3.0),
            v(0.4, 0.6, 3.0),
        ];
        let below = [
            v(0.0, 0.0, -1.0),
            v(1.0, 0.0, -1.0),
            v(1.0, 1.0, -1.0),
            v(0.0, 1.0, -1.0),
        ];
        let x = v(0.5, 0.5, 2.0);
        let seen = visible_area(x, &[&above, &below]).expect("within capacity");
        assert!((seen - 1.0).abs() < 1e-12, "{seen}");
        // A wall x = 0.75 from z = 0 to 3, seen from (0.5, 0.5, 2): it hides x > 0.75 entirely.
        let wall = [
            v(0.75, -1.0, 0.0),
            v(0.75, 2.0, 0.0),
            v(0.75, 2.0, 3.0),
            v(0.75, -1.0, 3.0),
        ];
        let seen = visible_area(x, &[&wall]).expect("within capacity");
        assert!((seen - 0.75).abs() < 1e-9, "{seen}");
    }

    #[test]
    fn blockers_beside_the_pyramid_hide_nothing_and_the_rest_still_count() {
        // Reference: similar triangles, as above. From (0.5, 0.5, 2) the target's pyramid at
        // height 1 is the square [0.25, 0.75]², and a blocker there casts a shadow twice its
        // size about (0.5, 0.5). Squares just outside the pyramid (x from 0.76, x up to 0.24)
        // hide nothing; x from 0.7 to 0.9 and y from 0.3 to 0.6 casts x from 0.9 to 1.3 and
        // y from 0.1 to 0.7, hiding 0.1 × 0.6 m² of the target.
        let x = v(0.5, 0.5, 2.0);
        let square = |x0: f64, x1: f64, y0: f64, y1: f64| {
            [
                v(x0, y0, 1.0),
                v(x1, y0, 1.0),
                v(x1, y1, 1.0),
                v(x0, y1, 1.0),
            ]
        };
        let beside = square(0.76, 0.9, 0.3, 0.6);
        let behind = square(-0.3, 0.24, 0.3, 0.6);
        let seen = visible_area(x, &[&beside, &behind]).expect("within capacity");
        assert!((seen - 1.0).abs() < 1e-12, "{seen}");
        let across = square(0.7, 0.9, 0.3, 0.6);
        let seen = visible_area(x, &[&beside, &across, &behind]).expect("within capacity");
        assert!((seen - (1.0 - 0.1 * 0.6)).abs() < 1e-12, "{seen}");
    }

    #[test]
    fn point_behind_the_target_is_refused() {
        assert!(visible_area(v(0.5, 0.5, -1.0), &[]).is_none());
    }
}
