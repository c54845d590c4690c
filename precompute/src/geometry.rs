//! Points, vectors and planar convex polygons in metres.
//!
//! Everything geometric in the precompute is `f64`: form factors of adjacent patches lose
//! several digits near a shared edge, so single precision is not enough here.

use std::ops::{Add, AddAssign, Div, Mul, Neg, Sub};

/// A point or a vector in 3-D space, in metres when it is a position.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Vec3 {
    /// x coordinate.
    pub x: f64,
    /// y coordinate.
    pub y: f64,
    /// z coordinate.
    pub z: f64,
}

impl Vec3 {
    /// The zero vector.
    pub const ZERO: Vec3 = Vec3::new(0.0, 0.0, 0.0);

    /// A vector from its three coordinates.
    pub const fn new(x: f64, y: f64, z: f64) -> Self {
        Vec3 { x, y, z }
    }

    /// Dot product.
    pub fn dot(self, o: Vec3) -> f64 {
        self.x * o.x + self.y * o.y + self.z * o.z
    }

    /// Cross product (right-handed).
    pub fn cross(self, o: Vec3) -> Vec3 {
        Vec3::new(
            self.y * o.z - self.z * o.y,
            self.z * o.x - self.x * o.z,
            self.x * o.y - self.y * o.x,
        )
    }

    /// Euclidean length.
    pub fn length(self) -> f64 {
        self.dot(self).sqrt()
    }

    /// This vector scaled to unit length; the zero vector stays zero.
    pub fn normalized(self) -> Vec3 {
        let l = self.length();
        if l > 0.0 {
            self / l
        } else {
            self
        }
    }

    /// True when every coordinate is finite.
    pub fn is_finite(self) -> bool {
        self.x.is_finite() && self.y.is_finite() && self.z.is_finite()
    }

    /// Coordinates as an array.
    pub fn to_array(self) -> [f64; 3] {
        [self.x, self.y, self.z]
    }

    /// Coordinate by axis index (0 = x, 1 = y, 2 = z).
    pub fn axis(self, axis: usize) -> f64 {
        match axis {
            0 => self.x,
            1 => self.y,
            _ => self.z,
        }
    }
}

impl Add for Vec3 {
    type Output = Vec3;
    fn add(self, o: Vec3) -> Vec3 {
        Vec3::new(self.x + o.x, self.y + o.y, self.z + o.z)
    }
}

impl AddAssign for Vec3 {
    fn add_assign(&mut self, o: Vec3) {
        *self = *self + o;
    }
}

impl Sub for Vec3 {
    type Output = Vec3;
    fn sub(self, o: Vec3) -> Vec3 {
        Vec3::new(self.x - o.x, self.y - o.y, self.z - o.z)
    }
}

impl Mul<f64> for Vec3 {
    type Output = Vec3;
    fn mul(self, s: f64) -> Vec3 {
        Vec3::new(self.x * s, self.y * s, self.z * s)
    }
}

impl Div<f64> for Vec3 {
    type Output = Vec3;
    fn div(self, s: f64) -> Vec3 {
        Vec3::new(self.x / s, self.y / s, self.z / s)
    }
}

impl Neg for Vec3 {
    type Output = Vec3;
    fn neg(self) -> Vec3 {
        Vec3::new(-self.x, -self.y, -self.z)
    }
}

/// Axis-aligned bounding box, metres.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Aabb {
    /// Lowest corner.
    pub min: Vec3,
    /// Highest corner.
    pub max: Vec3,
}

impl Aabb {
    /// The box around nothing: growing it by a point gives that point.
    pub const EMPTY: Aabb = Aabb {
        min: Vec3::new(f64::INFINITY, f64::INFINITY, f64::INFINITY),
        max: Vec3::new(f64::NEG_INFINITY, f64::NEG_INFINITY, f64::NEG_INFINITY),
    };

    /// The box around `points` ([`Aabb::EMPTY`] for none).
    pub fn of(points: &[Vec3]) -> Aabb {
        let mut b = Aabb::EMPTY;
        for &p in points {
            b.grow(p);
        }
        b
    }

    /// Grows the box to hold `p`.
    pub fn grow(&mut self, p: Vec3) {
        self.min = Vec3::new(
            self.min.x.min(p.x),
            self.min.y.min(p.y),
            self.min.z.min(p.z),
        );
        self.max = Vec3::new(
            self.max.x.max(p.x),
            self.max.y.max(p.y),
            self.max.z.max(p.z),
        );
    }

    /// The box around both.
    pub fn union(self, o: Aabb) -> Aabb {
        let mut b = self;
        b.grow(o.min);
        b.grow(o.max);
        b
    }

    /// The box grown by `by` metres on every side.
    pub fn expanded(self, by: f64) -> Aabb {
        let d = Vec3::new(by, by, by);
        Aabb {
            min: self.min - d,
            max: self.max + d,
        }
    }

    /// Whether the two boxes share a point.
    pub fn overlaps(&self, o: &Aabb) -> bool {
        self.min.x <= o.max.x
            && o.min.x <= self.max.x
            && self.min.y <= o.max.y
            && o.min.y <= self.max.y
            && self.min.z <= o.max.z
            && o.min.z <= self.max.z
    }

    /// The centre.
    pub fn center(&self) -> Vec3 {
        (self.min + self.max) * 0.5
    }
}

/// A planar convex polygon (a triangle or a quadrilateral after meshing).
///
/// Twice the vector area of the polygon with corners `vertices` (Newell's method): its
/// direction is the normal, its length twice the area (m²; 0 for fewer than three corners).
/// Exact for planar polygons, robust for nearly degenerate ones.
pub fn doubled_vector_area(vertices: &[Vec3]) -> Vec3 {
    let n = vertices.len();
    let mut acc = Vec3::ZERO;
    for (i, &a) in vertices.iter().enumerate() {
        acc += a.cross(vertices[(i + 1) % n]);
    }
    acc
}

/// Vertices run counter-clockwise seen from the side the polygon faces, so the normal follows
/// the right-hand rule. One-sided: light leaves and arrives on the front only.
#[derive(Clone, Debug, PartialEq)]
pub struct Polygon {
    /// Corners in order, metres.
    pub vertices: Vec<Vec3>,
}

impl Polygon {
    /// A polygon from its corners (counter-clockwise seen from the front).
    pub fn new(vertices: Vec<Vec3>) -> Self {
        Polygon { vertices }
    }

    /// Twice the vector area ([`doubled_vector_area`]).
    fn doubled_vector_area(&self) -> Vec3 {
        doubled_vector_area(&self.vertices)
    }

    /// Unit normal (right-hand rule), or zero for a degenerate polygon.
    pub fn normal(&self) -> Vec3 {
        self.doubled_vector_area().normalized()
    }

    /// Area in m².
    pub fn area(&self) -> f64 {
        0.5 * self.doubled_vector_area().length()
    }

    /// Area-weighted centroid, metres.
    pub fn centroid(&self) -> Vec3 {
        let n = self.vertices.len();
        let Some(&origin) = self.vertices.first() else {
            return Vec3::ZERO;
        };
        let mut weighted = Vec3::ZERO;
        let mut total = 0.0;
        for i in 1..n.saturating_sub(1) {
            let a = self.vertices[i] - origin;
            let b = self.vertices[i + 1] - origin;
            let w = 0.5 * a.cross(b).length();
            weighted += (origin + self.vertices[i] + self.vertices[i + 1]) / 3.0 * w;
            total += w;
        }
        if total > 0.0 {
            weighted / total
        } else {
            origin
        }
    }
}

/// The narrowest rectangle around a convex planar polygon with a side along one of its edges
/// (of all rectangles around a convex polygon, the narrowest has a side along an edge).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Narrowest {
    /// Unit direction of the rectangle's long side (along the edge it rests on).
    pub along: Vec3,
    /// Extent of the polygon along `along`, m.
    pub length: f64,
    /// Extent across it, in the polygon's plane: the polygon's width, m.
    pub width: f64,
    /// Smallest `p · along` over the corners, m.
    pub start: f64,
}

/// The [`Narrowest`] rectangle around convex planar `vertices` (the first edge of least
/// width wins a tie); `None` for fewer than three corners or no area.
pub fn narrowest(vertices: &[Vec3]) -> Option<Narrowest> {
    let n = vertices.len();
    let normal = doubled_vector_area(vertices).normalized();
    if n < 3 || normal.length() == 0.0 {
        return None;
    }
    let mut best: Option<Narrowest> = None;
    for i in 0..n {
        let edge = vertices[(i + 1) % n] - vertices[i];
        if edge.length() == 0.0 {
            continue;
        }
        let along = edge.normalized();
        let across = normal.cross(along);
        let range = |d: Vec3| {
            vertices
                .iter()
                .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), p| {
                    let x = p.dot(d);
                    (lo.min(x), hi.max(x))
                })
        };
        let (lo, hi) = range(along);
        let (wlo, whi) = range(across);
        let width = whi - wlo;
        if best.is_none_or(|b| width < b.width) {
            best = Some(Narrowest {
                along,
                length: hi - lo,
                width,
                start: lo,
            });
        }
    }
    best
}

/// Aspect ratio of a convex planar polygon: the long side over the short side of its
/// [`narrowest`] rectangle. A square has 1, an equilateral triangle 1.15, a right isosceles
/// triangle 2, an l × w rectangle l / w, a triangle its longest edge over the height onto it;
/// infinite for a polygon without area.
pub fn aspect(vertices: &[Vec3]) -> f64 {
    match narrowest(vertices) {
        Some(r) if r.width > 0.0 => r.length / r.width,
        _ => f64::INFINITY,
    }
}

/// The median and the worst [`aspect`] over a scene's patches (both 0 without patches).
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct AspectSummary {
    /// The median patch's aspect (the mean of the middle two for an even count).
    pub median: f64,
    /// The largest aspect of any patch.
    pub worst: f64,
}

/// The [`AspectSummary`] of `patches`.
pub fn aspect_summary(patches: &[Patch]) -> AspectSummary {
    let mut a: Vec<f64> = patches
        .iter()
        .map(|p| aspect(&p.polygon.vertices))
        .collect();
    a.sort_by(f64::total_cmp);
    let n = a.len();
    if n == 0 {
        return AspectSummary {
            median: 0.0,
            worst: 0.0,
        };
    }
    AspectSummary {
        median: 0.5 * (a[(n - 1) / 2] + a[n / 2]),
        worst: a[n - 1],
    }
}

/// A convex planar face of a surface as the scene gives it, before meshing. Its patches tile
/// it exactly, so for occlusion the face stands in for all of them: one blocker instead of
/// dozens, and no ray can slip through a seam between two of its patches.
#[derive(Clone, Debug, PartialEq)]
pub struct Face {
    /// The outline (convex, counter-clockwise seen from the front).
    pub polygon: Polygon,
    /// The patches it was cut into: consecutive indices into the scene's patch list.
    pub patches: std::ops::Range<usize>,
}

/// A meshed patch: the unit of the radiosity system.
#[derive(Clone, Debug, PartialEq)]
pub struct Patch {
    /// The patch outline (convex, counter-clockwise seen from the front; 3 or 4 corners, more
    /// where a contact cut leaves them).
    pub polygon: Polygon,
    /// Unit normal, pointing to the side that emits and receives light.
    pub normal: Vec3,
    /// Area, m².
    pub area: f64,
    /// Centroid, m.
    pub centroid: Vec3,
    /// Index of the named surface the patch was cut from.
    pub surface: usize,
}

impl Patch {
    /// A patch from its outline; normal, area and centroid follow from it.
    pub fn new(polygon: Polygon, surface: usize) -> Self {
        let normal = polygon.normal();
        let area = polygon.area();
        let centroid = polygon.centroid();
        Patch {
            polygon,
            normal,
            area,
            centroid,
            surface,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn unit_square_area_normal_centroid() {
        let p = Polygon::new(vec![
            Vec3::new(0.0, 0.0, 0.0),
            Vec3::new(1.0, 0.0, 0.0),
            Vec3::new(1.0, 1.0, 0.0),
            Vec3::new(0.0, 1.0, 0.0),
        ]);
        assert!((p.area() - 1.0).abs() < 1e-15);
        assert!((p.normal() - Vec3::new(0.0, 0.0, 1.0)).length() < 1e-15);
        assert!((p.centroid() - Vec3::new(0.5, 0.5, 0.0)).length() < 1e-15);
    }

    #[test]
    fn triangle_centroid_is_vertex_mean() {
        let p = Polygon::new(vec![
            Vec3::new(0.0, 0.0, 1.0),
            Vec3::new(3.0, 0.0, 1.0),
            Vec3::new(0.0, 3.0, 1.0),
        ]);
        assert!((p.area() - 4.5).abs() < 1e-12);
        assert!((p.centroid() - Vec3::new(1.0, 1.0, 1.0)).length() < 1e-12);
    }

    #[test]
    fn aspect_of_hand_checked_shapes() {
        let v = |x: f64, y: f64| Vec3::new(x, y, 0.5);
        let s3 = 3.0_f64.sqrt();
        // By hand: square 1; equilateral triangle side / height = 2/√3; right isosceles
        // triangle hypotenuse √2 over the height onto it 1/√2 = 2; 3 × 0.5 rectangle 6 (turned
        // by 30°, so the rectangle is not along an axis); a triangle with longest edge 2 and
        // height 0.1 onto it: 20; a trapezoid 1 m high with parallel sides 1 and 3 m: 3.
        let (c, s) = (s3 / 2.0, 0.5);
        let turned = |x: f64, y: f64| v(c * x - s * y, s * x + c * y);
        let cases: [(Vec<Vec3>, f64); 6] = [
            (
                vec![v(0.0, 0.0), v(1.0, 0.0), v(1.0, 1.0), v(0.0, 1.0)],
                1.0,
            ),
            (vec![v(0.0, 0.0), v(1.0, 0.0), v(0.5, s3 / 2.0)], 2.0 / s3),
            (vec![v(0.0, 0.0), v(1.0, 0.0), v(0.0, 1.0)], 2.0),
            (
                vec![
                    turned(0.0, 0.0),
                    turned(3.0, 0.0),
                    turned(3.0, 0.5),
                    turned(0.0, 0.5),
                ],
                6.0,
            ),
            (vec![v(0.0, 0.0), v(2.0, 0.0), v(0.5, 0.1)], 20.0),
            (
                vec![v(0.0, 0.0), v(3.0, 0.0), v(2.0, 1.0), v(1.0, 1.0)],
                3.0,
            ),
        ];
        for (corners, want) in cases {
            let got = aspect(&corners);
            assert!(
                (got - want).abs() < 1e-12 * want,
                "{corners:?}: {got} vs {want}"
            );
        }
        assert_eq!(
            aspect(&[v(0.0, 0.0), v(1.0, 0.0), v(2.0, 0.0)]),
            f64::INFINITY
        );
    }

    #[test]
    fn aspect_summary_takes_the_middle_and_the_worst() {
        let v = |x: f64, y: f64| Vec3::new(x, y, 0.0);
        let rectangle = |l: f64| {
            Patch::new(
                Polygon::new(vec![v(0.0, 0.0), v(l, 0.0), v(l, 1.0), v(0.0, 1.0)]),
                0,
            )
        };
        let patches: Vec<Patch> = [4.0, 1.0, 2.0, 3.0].map(rectangle).into();
        let s = aspect_summary(&patches);
        assert!((s.median - 2.5).abs() < 1e-12 && (s.worst - 4.0).abs() < 1e-12);
        let s = aspect_summary(&patches[..3]);
        assert!((s.median - 2.0).abs() < 1e-12);
        assert_eq!(aspect_summary(&[]).worst, 0.0);
    }
}
