//! Faces the meshing tests share, and the check that patches tile their face.

use super::MAX_CORNERS;
use crate::geometry::{narrowest, Polygon, Vec3};

/// The unit square in z = 0, facing up (+z).
pub(super) fn unit_square() -> Vec<Vec3> {
    vec![
        Vec3::new(0.0, 0.0, 0.0),
        Vec3::new(1.0, 0.0, 0.0),
        Vec3::new(1.0, 1.0, 0.0),
        Vec3::new(0.0, 1.0, 0.0),
    ]
}

/// A point of a tilted plane (so that no test relies on a face lying in z = 0): `(x, y)`
/// in its own orthonormal frame.
pub(super) fn tilted(x: f64, y: f64) -> Vec3 {
    let e1 = Vec3::new(1.0, 2.0, 2.0) / 3.0;
    let e2 = Vec3::new(2.0, 1.0, -2.0) / 3.0;
    Vec3::new(0.3, -0.2, 1.1) + e1 * x + e2 * y
}

/// A regular `n`-gon of circumradius `r` (m), counter-clockwise in the tilted plane.
pub(super) fn regular(n: usize, r: f64) -> Vec<Vec3> {
    (0..n)
        .map(|k| {
            let t = 2.0 * std::f64::consts::PI * k as f64 / n as f64;
            tilted(r * t.cos(), r * t.sin())
        })
        .collect()
}

/// Convex faces of more than four corners and thin triangles, in the tilted plane.
pub(super) fn faces() -> Vec<(&'static str, Vec<Vec3>)> {
    let irregular = [
        (0.0, 0.0),
        (1.3, -0.2),
        (2.1, 0.4),
        (2.2, 1.1),
        (1.6, 1.7),
        (0.4, 1.5),
        (-0.3, 0.8),
    ];
    vec![
        ("pentagon", regular(5, 0.5)),
        ("hexagon", regular(6, 0.5)),
        ("octagon", regular(8, 0.5)),
        ("32-gon", regular(32, 0.5)),
        ("128-gon", regular(128, 0.5)),
        ("128-gon of 3 m", regular(128, 3.0)),
        (
            "irregular heptagon",
            irregular.iter().map(|&(x, y)| tilted(x, y)).collect(),
        ),
        // A needle 2 m long, 0.05 m wide at its base.
        (
            "needle",
            vec![tilted(0.0, 0.0), tilted(2.0, 0.0), tilted(2.0, 0.05)],
        ),
        // A cap: 2 m long, 0.04 m high over its long edge at 0.7 m.
        (
            "cap",
            vec![tilted(0.0, 0.0), tilted(2.0, 0.0), tilted(0.7, 0.04)],
        ),
    ]
}

/// Whether `p` is strictly inside convex `patch` (normal `n`), and its distance (m) to the
/// nearest line through an edge.
fn inside(patch: &[Vec3], n: Vec3, p: Vec3) -> (bool, f64) {
    let mut inside = true;
    let mut nearest = f64::INFINITY;
    for k in 0..patch.len() {
        let (a, b) = (patch[k], patch[(k + 1) % patch.len()]);
        let side = (b - a).cross(p - a).dot(n) / (b - a).length();
        inside &= side > 0.0;
        nearest = nearest.min(side.abs());
    }
    (inside, nearest)
}

/// The patches tile `face`: their areas sum to its area (1e-12 relative), each has its
/// normal (1e-9) and is convex, no edge is longer than `max_edge`, and each of a grid of
/// points inside the face lies inside exactly one patch (points within 1e-9 m of an edge
/// line are skipped: on a seam, "inside" depends on rounding).
pub(super) fn assert_tiles(name: &str, face: &[Vec3], patches: &[Polygon], max_edge: f64) {
    let whole = Polygon::new(face.to_vec());
    let n = whole.normal();
    let total: f64 = patches.iter().map(Polygon::area).sum();
    assert!(
        (total - whole.area()).abs() <= 1e-12 * whole.area(),
        "{name} at {max_edge} m: area {total} of {}",
        whole.area()
    );
    for p in patches {
        let v = &p.vertices;
        assert!(
            v.len() >= 3 && v.len() <= MAX_CORNERS,
            "{name}: {} corners",
            v.len()
        );
        assert!(
            (p.normal() - n).length() < 1e-9,
            "{name}: normal {:?}",
            p.normal()
        );
        for k in 0..v.len() {
            let (a, b, c) = (v[k], v[(k + 1) % v.len()], v[(k + 2) % v.len()]);
            assert!(
                (b - a).length() <= max_edge * (1.0 + 1e-9),
                "{name}: long edge"
            );
            let turn = (b - a).cross(c - b).dot(n);
            assert!(turn >= -1e-12 * max_edge * max_edge, "{name}: not convex");
        }
    }
    let frame = narrowest(face).unwrap();
    let across = n.cross(frame.along);
    let origin = face[0];
    let (lo, hi) = face
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), p| {
            let y = (*p - origin).dot(across);
            (l.min(y), h.max(y))
        });
    let mut tested = 0;
    for i in 0..60 {
        for j in 0..60 {
            let x = frame.start - origin.dot(frame.along) + frame.length * (i as f64 + 0.5) / 60.0;
            let y = lo + (hi - lo) * (j as f64 + 0.37) / 60.0;
            let p = origin + frame.along * x + across * y;
            if !inside(face, n, p).0 {
                continue;
            }
            let hits: Vec<(bool, f64)> =
                patches.iter().map(|q| inside(&q.vertices, n, p)).collect();
            if hits.iter().any(|&(_, d)| d < 1e-9) {
                continue;
            }
            let count = hits.iter().filter(|h| h.0).count();
            assert_eq!(count, 1, "{name} at {max_edge} m: {p:?} in {count} patches");
            tested += 1;
        }
    }
    assert!(tested > 100, "{name}: only {tested} points tested");
}
