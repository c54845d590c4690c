//! The sunlit part of a convex patch, as polygons in its plane (docs/math.md, "The sun
//! between the grid's nodes, part by part").
//!
//! A point `x` of a patch sees the sun through a window face when the ray `x + t s` passes
//! the face, meets no room occluder before it and no exterior occluder past it
//! ([`crate::sky::direct`]). Along a fixed direction `s` every polygon casts its shadow on
//! the patch's plane as its projection along `s`: the window's projection is where the sun
//! comes in, each occluder's where it is held back. So the sunlit part is the patch clipped
//! by the window's projection, less the occluders' projections: convex pieces, whose area
//! is exact where a sample point's test is a midpoint rule that misses up to a whole
//! sample's share of the patch along a shadow's edge.
//!
//! Only the part of a polygon on the sun's side of the patch's plane (`t > 0`) casts a
//! shadow, and only a room occluder's part on the room's side of the window's plane (hit
//! before the window) or an exterior occluder's part past it: each polygon is first clipped
//! by those planes in space, then projected. Every polygon is convex (a shadow of a
//! non-convex one, or more pieces than [`MAX_PIECES`], makes [`Pieces::subtract`] report
//! it, and the caller falls back to sample points).
//!
//! Fixed buffers, no allocation; any input gives a number or `None`, never a panic.

use super::direct::DirectSun;

/// Most vertices of a polygon clipped in space or in the plane: a patch of 16 corners
/// clipped by a window's four edges has at most 20.
pub const MAX_VERTICES: usize = 24;

/// Most convex pieces the sunlit part of one patch is kept in.
pub const MAX_PIECES: usize = 12;

/// Distance (m) within which a polygon is taken to lie in a patch's or a window's plane: the
/// face a patch lies on does not shade it, the wall around a window does not shade the
/// window. About 100 `f32` steps at 10 m.
const SURFACE_MARGIN: f32 = 1.0e-4;

/// A vector of the plane or of space.
type V2 = [f32; 2];
type V3 = [f32; 3];

/// A polygon of at most [`MAX_VERTICES`] vertices of `D` coordinates, clipped in place of
/// the plane (`D = 2`, [`Piece`]) or of space (`D = 3`).
#[derive(Clone, Copy, Debug)]
pub struct Polygon<const D: usize> {
    len: usize,
    v: [[f32; D]; MAX_VERTICES],
}

/// A convex polygon in the patch's plane, counter-clockwise seen from the patch's front.
pub type Piece = Polygon<2>;

/// A polygon of space being clipped.
type Space = Polygon<3>;

impl<const D: usize> Polygon<D> {
    /// No vertex.
    pub const EMPTY: Polygon<D> = Polygon {
        len: 0,
        v: [[0.0; D]; MAX_VERTICES],
    };

    /// The polygon of `vertices`, `None` past [`MAX_VERTICES`].
    pub fn from_vertices(vertices: &[[f32; D]]) -> Option<Polygon<D>> {
        let mut p = Polygon::EMPTY;
        for &x in vertices {
            p.push(x)?;
        }
        Some(p)
    }

    /// Its vertices.
    pub fn vertices(&self) -> &[[f32; D]] {
        self.v.get(..self.len).unwrap_or(&[])
    }

    fn push(&mut self, x: [f32; D]) -> Option<()> {
        *self.v.get_mut(self.len)? = x;
        self.len += 1;
        Some(())
    }

    /// The part where `side(x) ≥ 0` for an affine `side` (Sutherland–Hodgman on one edge or
    /// plane); `None` past [`MAX_VERTICES`].
    fn keep(&self, side: impl Fn([f32; D]) -> f32) -> Option<Polygon<D>> {
        let v = self.vertices();
        let mut out = Polygon::EMPTY;
        for (i, &p) in v.iter().enumerate() {
            let q = v.get(i + 1).or(v.first()).copied().unwrap_or(p);
            let (sp, sq) = (side(p), side(q));
            if sp >= 0.0 {
                out.push(p)?;
            }
            if (sp >= 0.0) != (sq >= 0.0) {
                let f = sp / (sp - sq);
                let mut x = p;
                for (xk, (pk, qk)) in x.iter_mut().zip(p.iter().zip(&q)) {
                    *xk = pk + f * (qk - pk);
                }
                out.push(x)?;
            }
        }
        Some(out)
    }
}

impl Piece {
    /// Signed area (positive counter-clockwise), m².
    pub fn area(&self) -> f32 {
        let v = self.vertices();
        let mut twice = 0.0;
        for (i, a) in v.iter().enumerate() {
            let b = v.get(i + 1).or(v.first()).copied().unwrap_or(*a);
            twice += a[0] * b[1] - a[1] * b[0];
        }
        0.5 * twice
    }

    /// The part left of the directed line `a → b` (Sutherland–Hodgman on one edge); `None`
    /// past [`MAX_VERTICES`].
    pub fn left_of(&self, a: V2, b: V2) -> Option<Piece> {
        self.keep(|x: V2| (b[0] - a[0]) * (x[1] - a[1]) - (b[1] - a[1]) * (x[0] - a[0]))
    }

    /// Bounds: least x, least y, largest x, largest y.
    fn bounds(&self) -> [f32; 4] {
        self.vertices().iter().fold(
            [
                f32::INFINITY,
                f32::INFINITY,
                f32::NEG_INFINITY,
                f32::NEG_INFINITY,
            ],
            |b, p| {
                [
                    b[0].min(p[0]),
                    b[1].min(p[1]),
                    b[2].max(p[0]),
                    b[3].max(p[1]),
                ]
            },
        )
    }

    /// Whether it is convex and counter-clockwise (every turn to the left or straight), with
    /// finite vertices: what a clip by its edges needs.
    pub fn is_convex(&self) -> bool {
        let v = self.vertices();
        let n = v.len();
        if n < 3 || v.iter().any(|p| !(p[0].is_finite() && p[1].is_finite())) {
            return false;
        }
        let at = |i: usize| v.get(i % n).copied().unwrap_or([0.0; 2]);
        (0..n).all(|i| {
            let (a, b, c) = (at(i), at(i + 1), at(i + 2));
            let turn = (b[0] - a[0]) * (c[1] - b[1]) - (b[1] - a[1]) * (c[0] - b[0]);
            // A relative tolerance: a straight corner of a clipped polygon turns by rounding.
            let scale = (b[0] - a[0]).abs()
                + (b[1] - a[1]).abs()
                + (c[0] - b[0]).abs()
                + (c[1] - b[1]).abs();
            turn >= -1e-5 * scale * scale
        })
    }

    /// The same polygon counter-clockwise.
    pub fn counter_clockwise(mut self) -> Piece {
        if self.area() < 0.0 {
            let n = self.len;
            self.v.get_mut(..n).map(<[V2]>::reverse);
        }
        self
    }
}

/// The sunlit part of a patch: convex pieces that do not overlap.
#[derive(Clone, Copy, Debug)]
pub struct Pieces {
    len: usize,
    items: [Piece; MAX_PIECES],
}

/// More pieces or vertices than the buffers hold, or a shadow that is not convex.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Overflow;

impl Pieces {
    /// The one piece `piece`.
    pub fn one(piece: Piece) -> Pieces {
        let mut items = [Piece::EMPTY; MAX_PIECES];
        items[0] = piece;
        Pieces { len: 1, items }
    }

    /// Total area, m².
    pub fn area(&self) -> f32 {
        self.items().iter().map(Piece::area).sum()
    }

    fn items(&self) -> &[Piece] {
        self.items.get(..self.len).unwrap_or(&[])
    }

    /// Takes the convex counter-clockwise `shadow` out of every piece: each piece it meets
    /// is replaced by its parts outside the shadow's edges, one part per edge (the part
    /// right of that edge and left of the edges before it), which do not overlap.
    pub fn subtract(&mut self, shadow: &Piece) -> Result<(), Overflow> {
        if !shadow.is_convex() {
            return Err(Overflow);
        }
        let s = shadow.bounds();
        let apart = |b: [f32; 4]| b[2] <= s[0] || s[2] <= b[0] || b[3] <= s[1] || s[3] <= b[1];
        // Most shadows miss every piece: nothing to copy then.
        if self.items().iter().all(|p| apart(p.bounds())) {
            return Ok(());
        }
        let edges = shadow.vertices();
        let mut out = Pieces {
            len: 0,
            items: [Piece::EMPTY; MAX_PIECES],
        };
        for piece in self.items() {
            if apart(piece.bounds()) {
                out.push(*piece)?;
                continue;
            }
            let mut rest = *piece;
            for (i, &a) in edges.iter().enumerate() {
                let next = edges.get(i + 1).or(edges.first()).copied().unwrap_or(a);
                let outside = rest.left_of(next, a).ok_or(Overflow)?;
                if outside.len >= 3 && outside.area() > 0.0 {
                    out.push(outside)?;
                }
                rest = rest.left_of(a, next).ok_or(Overflow)?;
                if rest.len < 3 {
                    break;
                }
            }
        }
        *self = out;
        Ok(())
    }

    fn push(&mut self, piece: Piece) -> Result<(), Overflow> {
        let slot = self.items.get_mut(self.len).ok_or(Overflow)?;
        *slot = piece;
        self.len += 1;
        Ok(())
    }
}

/// A patch's plane and the sun's direction: where a point of space casts its shadow.
#[derive(Clone, Copy, Debug)]
pub struct Plane {
    origin: V3,
    normal: V3,
    u: V3,
    w: V3,
    sun: V3,
    /// `normal · sun`, > 0.
    facing: f32,
}

impl Plane {
    /// The plane through `origin` facing `normal` (unit), with `toward` (not along the
    /// normal) giving its first axis, lit along the unit `sun`; `None` when the sun is not
    /// in front of it or the axes are degenerate.
    pub fn new(origin: V3, normal: V3, toward: V3, sun: V3) -> Option<Plane> {
        let facing = dot(normal, sun);
        if facing.is_nan() || facing <= 0.0 {
            return None;
        }
        let along = sub(toward, scale(normal, dot(toward, normal)));
        let length = libm::sqrtf(dot(along, along));
        if length.is_nan() || length <= 0.0 {
            return None;
        }
        let u = scale(along, 1.0 / length);
        let w = cross(normal, u);
        Some(Plane {
            origin,
            normal,
            u,
            w,
            sun,
            facing,
        })
    }

    /// `x` in the plane's axes (m).
    pub fn local(&self, x: V3) -> V2 {
        let d = sub(x, self.origin);
        [dot(d, self.u), dot(d, self.w)]
    }

    /// Height of `x` over the plane, m.
    pub fn height(&self, x: V3) -> f32 {
        dot(sub(x, self.origin), self.normal)
    }

    /// The shadow on the plane of the polygon `vertices` (of space), its part in the
    /// half-spaces `keep` holds (each a point and a normal: `(x − p) · m ≥ 0`) and at least
    /// `margin` over the plane: projected along the sun and made counter-clockwise. `None`
    /// past [`MAX_VERTICES`]; an empty piece when nothing is left.
    pub fn shadow(&self, vertices: &[V3], keep: &[(V3, V3)], margin: f32) -> Option<Piece> {
        let mut space = Space::EMPTY;
        for &x in vertices {
            space.push(x)?;
        }
        let over = (self.origin, self.normal);
        for &(point, normal) in keep {
            space = space.clip(point, normal, 0.0)?;
        }
        space = space.clip(over.0, over.1, margin)?;
        let mut flat = Piece::EMPTY;
        for &x in space.vertices() {
            // Along the sun down to the plane: `x − (h / (n · s)) s`.
            let down = sub(x, scale(self.sun, self.height(x) / self.facing));
            flat.push(self.local(down))?;
        }
        Some(flat.counter_clockwise())
    }
}

impl DirectSun<'_, '_> {
    /// Mean direct irradiance over the convex patch of `corners` (m, at most
    /// [`MAX_VERTICES`], in order) facing the unit `normal`, per lux of direct normal
    /// illuminance from the sun in the room-frame direction `sun`: for each window face, the
    /// patch's part inside the face's shadow less the occluders' shadows, times the glazing's
    /// `τ(θ_w)` and `cos θ`, over the patch's area. `None` where pieces overflow or a polygon
    /// is not convex (the caller samples points instead).
    pub fn on_patch(&self, corners: &[V3], normal: V3, sun: V3) -> Option<f32> {
        let cos = dot(normal, sun);
        // NaN compares false: a NaN direction lights nothing.
        if cos.is_nan() || cos <= 0.0 || sun[2].is_nan() || sun[2] < 0.0 {
            return Some(0.0);
        }
        let first = *corners.first()?;
        let plane = Plane::new(first, normal, sub(*corners.get(1)?, first), sun)?;
        let mut patch = Piece::EMPTY;
        for &c in corners {
            patch.push(plane.local(c))?;
        }
        let patch = patch.counter_clockwise();
        let area = patch.area();
        if !patch.is_convex() || area.is_nan() || area <= 0.0 {
            return None;
        }
        let [windows, room, exterior] = self.polygon_counts();
        let mut total = 0.0;
        for (w, (offset, size)) in self.polygons().take(windows).enumerate() {
            let window_normal = self.vector(offset);
            let cos_window = -dot(window_normal, sun);
            if cos_window.is_nan() || cos_window <= 0.0 {
                continue;
            }
            let mut corners = [[0.0f32; 3]; MAX_VERTICES];
            let corners = self.corners(offset, size, &mut corners);
            let light = plane.shadow(corners, &[], SURFACE_MARGIN)?;
            if light.len < 3 {
                continue;
            }
            if !light.is_convex() {
                return None;
            }
            let mut inside = patch;
            for (i, &a) in light.vertices().iter().enumerate() {
                let b = light
                    .vertices()
                    .get(i + 1)
                    .or(light.vertices().first())
                    .copied()?;
                inside = inside.left_of(a, b)?;
            }
            if inside.len < 3 {
                continue;
            }
            // The pieces are made when a shadow first falls on the lit part: most candidates
            // are lit whole or cut by no occluder, and the buffers are large to clear.
            let mut lit: Option<Pieces> = None;
            let bounds = inside.bounds();
            // A room occluder shades on the room's side of the window's plane, an exterior
            // one past it.
            let on_window = self.vector(offset + 3);
            let room_side = (
                add(on_window, scale(window_normal, SURFACE_MARGIN)),
                window_normal,
            );
            let outside = (
                sub(on_window, scale(window_normal, SURFACE_MARGIN)),
                scale(window_normal, -1.0),
            );
            let occluders = self
                .polygons()
                .skip(windows)
                .take(room.saturating_add(exterior));
            for (k, (offset, size)) in occluders.enumerate() {
                let keep = if k < room { room_side } else { outside };
                let mut corners = [[0.0f32; 3]; MAX_VERTICES];
                let corners = self.corners(offset, size, &mut corners);
                // Wholly behind the patch's plane or on the wrong side of the window's: no
                // shadow, and nothing to clip.
                let reaches = |point: V3, normal: V3, margin: f32| {
                    corners
                        .iter()
                        .any(|&c| dot(sub(c, point), normal) >= margin)
                };
                if !reaches(first, normal, SURFACE_MARGIN) || !reaches(keep.0, keep.1, 0.0) {
                    continue;
                }
                let shadow = plane.shadow(corners, &[keep], SURFACE_MARGIN)?;
                let s = shadow.bounds();
                let apart = bounds[2] <= s[0]
                    || s[2] <= bounds[0]
                    || bounds[3] <= s[1]
                    || s[3] <= bounds[1];
                if shadow.len >= 3 && shadow.area() > 0.0 && !apart {
                    lit.get_or_insert_with(|| Pieces::one(inside))
                        .subtract(&shadow)
                        .ok()?;
                }
            }
            let lit_area = lit.map_or_else(|| inside.area(), |p| p.area());
            total += self.transmittance(w, cos_window) * lit_area;
        }
        let irradiance = total * cos / area;
        irradiance.is_finite().then_some(irradiance)
    }

    /// The corners of the stored polygon at `offset` of `size` vertices, in `buffer` (at
    /// most [`MAX_VERTICES`] of them).
    fn corners<'c>(
        &self,
        offset: usize,
        size: usize,
        buffer: &'c mut [V3; MAX_VERTICES],
    ) -> &'c [V3] {
        let size = size.min(MAX_VERTICES);
        for (i, c) in buffer.iter_mut().enumerate().take(size) {
            *c = self.vector(offset + 3 + 3 * i);
        }
        buffer.get(..size).unwrap_or(&[])
    }
}

impl Space {
    /// The part where `(x − point) · normal ≥ margin`.
    fn clip(&self, point: V3, normal: V3, margin: f32) -> Option<Space> {
        self.keep(|x: V3| dot(sub(x, point), normal) - margin)
    }
}

fn dot(a: V3, b: V3) -> f32 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn sub(a: V3, b: V3) -> V3 {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn add(a: V3, b: V3) -> V3 {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}

fn scale(a: V3, k: f32) -> V3 {
    [a[0] * k, a[1] * k, a[2] * k]
}

fn cross(a: V3, b: V3) -> V3 {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, clippy::indexing_slicing)]
    use super::*;

    fn square(x0: f32, y0: f32, size: f32) -> Piece {
        Piece::from_vertices(&[
            [x0, y0],
            [x0 + size, y0],
            [x0 + size, y0 + size],
            [x0, y0 + size],
        ])
        .unwrap()
    }

    /// A unit square less a square of side 0.5 over its corner keeps 0.75 m²; less one
    /// inside it, 1 − 0.04; less one outside it, all of it; less one over the whole of it,
    /// nothing; the pieces do not overlap (their areas add to the closed form).
    #[test]
    fn subtracting_squares_leaves_the_closed_form_area() {
        let cases = [
            (square(0.5, 0.5, 1.0), 0.75),
            (square(0.4, 0.4, 0.2), 0.96),
            (square(2.0, 2.0, 1.0), 1.0),
            (square(-1.0, -1.0, 3.0), 0.0),
            (square(-0.5, 0.25, 1.0), 0.625),
        ];
        for (shadow, want) in cases {
            let mut lit = Pieces::one(square(0.0, 0.0, 1.0));
            lit.subtract(&shadow).unwrap();
            assert!((lit.area() - want).abs() < 1e-6, "{} vs {want}", lit.area());
        }
        // Two shadows that overlap each other take their union: 1 − (0.25 + 0.25 − 0.0625).
        let mut lit = Pieces::one(square(0.0, 0.0, 1.0));
        lit.subtract(&square(0.5, 0.5, 1.0)).unwrap();
        lit.subtract(&square(0.25, 0.25, 0.5)).unwrap();
        assert!((lit.area() - (1.0 - 0.4375)).abs() < 1e-6, "{}", lit.area());
    }

    /// A triangle's shadow over a square: the square less a right triangle of legs 0.5.
    #[test]
    fn a_triangle_shadow() {
        let tri = Piece::from_vertices(&[[0.5, 0.5], [1.5, 0.5], [0.5, 1.5]]).unwrap();
        let mut lit = Pieces::one(square(0.0, 0.0, 1.0));
        lit.subtract(&tri).unwrap();
        assert!(
            (lit.area() - (1.0 - 0.125 - 0.125)).abs() < 1e-6,
            "{}",
            lit.area()
        );
    }

    /// A shadow that is not convex is reported, as is a clockwise one turned first.
    #[test]
    fn a_shadow_not_convex_is_reported() {
        let l = Piece::from_vertices(&[
            [0.0, 0.0],
            [2.0, 0.0],
            [2.0, 1.0],
            [1.0, 1.0],
            [1.0, 2.0],
            [0.0, 2.0],
        ])
        .unwrap();
        assert!(!l.is_convex());
        let mut lit = Pieces::one(square(0.0, 0.0, 1.0));
        assert_eq!(lit.subtract(&l), Err(Overflow));
        let clockwise =
            Piece::from_vertices(&[[0.0, 0.0], [0.0, 1.0], [1.0, 1.0], [1.0, 0.0]]).unwrap();
        assert!(clockwise.area() < 0.0);
        assert!(clockwise.counter_clockwise().is_convex());
    }

    /// A unit square window 1 m above a floor plane, the sun at 45° in the x–z plane: its
    /// shadow is the unit square shifted by 1 m along −x; the part of a polygon under the
    /// plane casts none.
    #[test]
    fn a_window_projects_along_the_sun() {
        let r = core::f32::consts::FRAC_1_SQRT_2;
        let plane = Plane::new([0.0; 3], [0.0, 0.0, 1.0], [1.0, 0.0, 0.0], [r, 0.0, r]).unwrap();
        let window = [
            [0.0, 0.0, 1.0],
            [1.0, 0.0, 1.0],
            [1.0, 1.0, 1.0],
            [0.0, 1.0, 1.0],
        ];
        let shadow = plane.shadow(&window[..], &[], 1e-6).unwrap();
        assert!((shadow.area() - 1.0).abs() < 1e-5, "{}", shadow.area());
        let b = shadow.bounds();
        assert!((b[0] + 1.0).abs() < 1e-5 && b[2].abs() < 1e-5, "{b:?}");
        // A vertical square from z = −1 to 1: only its upper half casts a shadow.
        let wall = [
            [0.0, 0.0, -1.0],
            [0.0, 1.0, -1.0],
            [0.0, 1.0, 1.0],
            [0.0, 0.0, 1.0],
        ];
        let shadow = plane.shadow(&wall[..], &[], 1e-6).unwrap();
        assert!((shadow.area() - 1.0).abs() < 1e-4, "{}", shadow.area());
        // Kept to x ≥ 0.5 only (a half-space), the window's shadow halves.
        let half = plane
            .shadow(&window[..], &[([0.5, 0.0, 0.0], [1.0, 0.0, 0.0])], 1e-6)
            .unwrap();
        assert!((half.area() - 0.5).abs() < 1e-5, "{}", half.area());
        // The sun behind the plane lights nothing.
        assert!(Plane::new([0.0; 3], [0.0, 0.0, 1.0], [1.0, 0.0, 0.0], [r, 0.0, -r]).is_none());
    }
}
