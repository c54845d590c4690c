//! The exact differential-area-to-polygon form factor (the integrand of every patch form factor).
//!
//! Lambert's contour formula, as catalogued by Howell (*A Catalog of Radiation Heat Transfer
//! Configuration Factors*, 3rd ed., and Modest, *Radiative Heat Transfer*, eq. 4.36 / 4.37):
//!
//! ```text
//! F_dA→A = 1/(2π) Σ_edges γ_k  n · (r_{k+1} × r_k) / |r_{k+1} × r_k|
//! ```
//!
//! with `r_k` the vector from the differential element to corner k and `γ_k` the angle between
//! `r_k` and `r_{k+1}`. The formula only holds when the whole polygon lies in front of the
//! element's tangent plane, so the polygon is first clipped to that half-space.

use crate::geometry::Vec3;

/// Corners of a patch polygon clipped by one plane: a convex polygon of `c` corners clipped by
/// `k` planes has at most `c + k` corners, and patches have at most 4 (a few more are tolerated).
pub(crate) const PATCH_CLIPPED: usize = 8;

/// A convex polygon with a fixed capacity of `N` corners, so that clipping never allocates.
#[derive(Clone, Copy, Debug)]
pub(crate) struct SmallPolygon<const N: usize> {
    /// Corners, metres; only the first `len` are used.
    pub(crate) vertices: [Vec3; N],
    /// Number of corners in use.
    pub(crate) len: usize,
}

impl<const N: usize> SmallPolygon<N> {
    /// The polygon from a slice of corners (at most `N`; the rest is dropped).
    pub(crate) fn from_slice(corners: &[Vec3]) -> Self {
        let mut vertices = [Vec3::ZERO; N];
        let len = corners.len().min(N);
        vertices[..len].copy_from_slice(&corners[..len]);
        SmallPolygon { vertices, len }
    }

    /// The used corners.
    pub(crate) fn corners(&self) -> &[Vec3] {
        &self.vertices[..self.len]
    }

    /// Keeps the part of the polygon where `normal · (p − origin) ≥ 0` (Sutherland–Hodgman
    /// against one plane). Returns the clipped polygon; it may have fewer than 3 corners when
    /// nothing is left.
    pub(crate) fn clip(&self, origin: Vec3, normal: Vec3) -> SmallPolygon<N> {
        let mut out = SmallPolygon {
            vertices: [Vec3::ZERO; N],
            len: 0,
        };
        let n = self.len;
        if n == 0 {
            return out;
        }
        let push = |p: Vec3, out: &mut SmallPolygon<N>| {
            if out.len < N {
                out.vertices[out.len] = p;
                out.len += 1;
            }
        };
        for k in 0..n {
            let a = self.vertices[k];
            let b = self.vertices[(k + 1) % n];
            let da = normal.dot(a - origin);
            let db = normal.dot(b - origin);
            if da >= 0.0 {
                push(a, &mut out);
            }
            // The edge crosses the plane strictly: add the crossing point.
            if (da > 0.0 && db < 0.0) || (da < 0.0 && db > 0.0) {
                let t = da / (da - db);
                push(a + (b - a) * t, &mut out);
            }
        }
        out
    }
}

/// Form factor (dimensionless) from a differential area at `x` (metres) with unit normal
/// `normal` to the polygon `target` (corners counter-clockwise seen from its front, unit normal
/// `target_normal`).
///
/// One-sided on both ends: zero when `x` is not strictly in front of the target's plane, and only
/// the part of the target in front of the element's tangent plane counts (the polygon is
/// clipped). Exact up to rounding: Lambert's contour integral (module docs).
pub(crate) fn point_to_polygon(x: Vec3, normal: Vec3, target: &[Vec3], target_normal: Vec3) -> f64 {
    let Some(&first) = target.first() else {
        return 0.0;
    };
    if target_normal.dot(x - first) <= 0.0 {
        return 0.0;
    }
    // Usually the whole target is in front: no clipping (and no copy) needed.
    if target.iter().all(|&c| normal.dot(c - x) >= 0.0) {
        return contour_integral(x, normal, target);
    }
    let clipped = SmallPolygon::<PATCH_CLIPPED>::from_slice(target).clip(x, normal);
    contour_integral(x, normal, clipped.corners())
}

/// Form factor from a differential area at `x` with unit normal `normal` to a polygon that lies
/// entirely in front of the element (already clipped) and is seen from its front, so that its
/// corners run clockwise seen from `x`. Lambert / Hottel contour formula (module docs).
pub(crate) fn contour_integral(x: Vec3, normal: Vec3, corners: &[Vec3]) -> f64 {
    let n = corners.len();
    if n < 3 {
        return 0.0;
    }
    let mut acc = 0.0;
    for k in 0..n {
        let a = corners[k] - x;
        let b = corners[(k + 1) % n] - x;
        let c = b.cross(a);
        let s = c.length();
        if s == 0.0 {
            // Collinear with the element (an edge seen end-on): contributes nothing.
            continue;
        }
        let gamma = s.atan2(a.dot(b));
        acc += gamma * normal.dot(c) / s;
    }
    (acc / (2.0 * std::f64::consts::PI)).max(0.0)
}

/// Sides of the pyramid that stands in for a field-of-view cone.
pub(crate) const CONE_SIDES: usize = 64;
/// Corners of a patch clipped by the tangent plane and the pyramid.
const CONE_CLIPPED: usize = CONE_SIDES + PATCH_CLIPPED;

/// A sensor's field of view: the directions within `half_angle` of its normal, approximated by
/// a regular pyramid of [`CONE_SIDES`] planes through the apex whose cross-section has the
/// cone's area. The error in the cosine-weighted solid angle is second order in the facet angle
/// (below 1e-5 relative for a plane filling the view, see the tests).
#[derive(Clone, Debug)]
pub(crate) struct Cone {
    /// Cosine of the half-angle: directions with a smaller cosine are outside.
    pub(crate) cos_half_angle: f64,
    /// Inward unit normals of the pyramid's faces.
    planes: [Vec3; CONE_SIDES],
}

impl Cone {
    /// The field of view around the unit `normal` with `half_angle` in radians; `None` when the
    /// cone covers the whole front hemisphere (half-angle ≥ π/2) so that no clipping is needed.
    pub(crate) fn new(normal: Vec3, half_angle: f64) -> Option<Cone> {
        // NaN as well as wide angles: no cone.
        if half_angle.partial_cmp(&std::f64::consts::FRAC_PI_2) != Some(std::cmp::Ordering::Less) {
            return None;
        }
        let half_angle = half_angle.max(0.0);
        let (u, v) = tangent_basis(normal);
        let k = CONE_SIDES as f64;
        let facet = std::f64::consts::PI / k;
        // Circumscribed pyramid with the cone's cross-section area: K tan²β tan(π/K) = π tan²α.
        let beta = (half_angle.tan() * (facet / facet.tan()).sqrt()).atan();
        let mut planes = [Vec3::ZERO; CONE_SIDES];
        for (i, plane) in planes.iter_mut().enumerate() {
            let phi = 2.0 * facet * i as f64;
            let w = u * phi.cos() + v * phi.sin();
            *plane = normal * beta.sin() - w * beta.cos();
        }
        Some(Cone {
            cos_half_angle: half_angle.cos(),
            planes,
        })
    }

    /// Is the direction `d` (any length) inside the cone around `normal`?
    pub(crate) fn contains(&self, normal: Vec3, d: Vec3) -> bool {
        normal.dot(d) >= self.cos_half_angle * d.length()
    }
}

/// Two unit vectors completing `n` to a right-handed orthonormal basis.
fn tangent_basis(n: Vec3) -> (Vec3, Vec3) {
    let a = if n.x.abs() < 0.6 {
        Vec3::new(1.0, 0.0, 0.0)
    } else {
        Vec3::new(0.0, 1.0, 0.0)
    };
    let u = n.cross(a).normalized();
    (u, n.cross(u))
}

/// [`point_to_polygon`] restricted to a field of view: only the part of the target inside
/// `cone` counts (the target is clipped to the cone's pyramid as well).
pub(crate) fn point_to_polygon_in_cone(
    x: Vec3,
    normal: Vec3,
    cone: &Cone,
    target: &[Vec3],
    target_normal: Vec3,
) -> f64 {
    let Some(&first) = target.first() else {
        return 0.0;
    };
    if target_normal.dot(x - first) <= 0.0 {
        return 0.0;
    }
    let mut clipped = SmallPolygon::<CONE_CLIPPED>::from_slice(target).clip(x, normal);
    for &plane in &cone.planes {
        if clipped.len < 3 {
            return 0.0;
        }
        clipped = clipped.clip(x, plane);
    }
    contour_integral(x, normal, clipped.corners())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Howell B-3: element to a parallel rectangle with one corner above the element.
    fn howell_b3(a: f64, b: f64, c: f64) -> f64 {
        let (x, y) = (a / c, b / c);
        let sx = (1.0 + x * x).sqrt();
        let sy = (1.0 + y * y).sqrt();
        (x / sx * (y / sx).atan() + y / sy * (x / sy).atan()) / (2.0 * std::f64::consts::PI)
    }

    fn ceiling(a: f64, b: f64, c: f64) -> [Vec3; 4] {
        // Facing down (normal −z): counter-clockwise seen from below.
        [
            Vec3::new(0.0, 0.0, c),
            Vec3::new(0.0, b, c),
            Vec3::new(a, b, c),
            Vec3::new(a, 0.0, c),
        ]
    }

    #[test]
    fn element_to_parallel_rectangle_matches_howell_b3() {
        // Reference: Howell B-3 closed form; tolerance 1e-12 relative (both exact).
        for &(a, b, c) in &[(1.0, 1.0, 1.0), (2.0, 0.5, 0.7), (0.1, 3.0, 2.0)] {
            let f = point_to_polygon(
                Vec3::ZERO,
                Vec3::new(0.0, 0.0, 1.0),
                &ceiling(a, b, c),
                Vec3::new(0.0, 0.0, -1.0),
            );
            let exact = howell_b3(a, b, c);
            assert!((f - exact).abs() <= 1e-12 * exact, "{f} vs {exact}");
        }
    }

    #[test]
    fn cone_over_large_plane_gives_sin_squared() {
        // Reference: a cone of half-angle α under an infinite parallel plane sees a disk of
        // radius h tan α, F = R² / (h² + R²) = sin² α (Howell B-13, element to coaxial disk).
        // Tolerance 2e-5 relative: the pyramid approximation of the cone.
        let n = Vec3::new(0.0, 0.0, 1.0);
        let big = [
            Vec3::new(-100.0, -100.0, 1.0),
            Vec3::new(-100.0, 100.0, 1.0),
            Vec3::new(100.0, 100.0, 1.0),
            Vec3::new(100.0, -100.0, 1.0),
        ];
        for deg in [5.0_f64, 30.0, 60.0, 80.0] {
            let alpha = deg.to_radians();
            let Some(cone) = Cone::new(n, alpha) else {
                panic!("cone of {deg} degrees must clip");
            };
            let f = point_to_polygon_in_cone(Vec3::ZERO, n, &cone, &big, -n);
            let exact = alpha.sin().powi(2);
            let rel = (f - exact).abs() / exact;
            println!("cone {deg}°: F = {f:.8}, exact {exact:.8}, rel. error {rel:.2e}");
            assert!(rel < 2e-5);
        }
    }

    #[test]
    fn back_face_and_behind_are_zero() {
        let up = Vec3::new(0.0, 0.0, 1.0);
        // Target facing away from the element.
        let f = point_to_polygon(Vec3::ZERO, up, &ceiling(1.0, 1.0, 1.0), up);
        assert_eq!(f, 0.0);
    }

    #[test]
    fn clipping_half_plane_gives_half_of_symmetric_target() {
        // A vertical square straddling the element's tangent plane symmetrically: the part
        // below must not count. Compare with the part above computed directly.
        let x = Vec3::ZERO;
        let n = Vec3::new(0.0, 0.0, 1.0);
        // Square in plane y = 1, facing −y, from z = −1 to 1.
        let full = [
            Vec3::new(-1.0, 1.0, -1.0),
            Vec3::new(1.0, 1.0, -1.0),
            Vec3::new(1.0, 1.0, 1.0),
            Vec3::new(-1.0, 1.0, 1.0),
        ];
        let upper = [
            Vec3::new(-1.0, 1.0, 0.0),
            Vec3::new(1.0, 1.0, 0.0),
            Vec3::new(1.0, 1.0, 1.0),
            Vec3::new(-1.0, 1.0, 1.0),
        ];
        let normal = Vec3::new(0.0, -1.0, 0.0);
        let f_full = point_to_polygon(x, n, &full, normal);
        let f_upper = point_to_polygon(x, n, &upper, normal);
        assert!(f_upper > 0.0);
        assert!((f_full - f_upper).abs() < 1e-15);
    }
}
