//! Contacts: where an OBJ object stands on a face (a box on a floor, a cabinet against a
//! wall), the face's patches are cut along the object's footprint, so that no patch lies
//! partly under the object, hidden from the room, and partly in the room. A patch that
//! straddles a footprint has one exitance for two regions that see very different light; the
//! object's faces next to it read that average too.
//!
//! `[[block]]`s without a bottom face get the same treatment in [`super::openings`], where
//! the footprint is a rectangle on the room's grid. An OBJ object's footprint on a face is a
//! closed loop of its faces' edges lying in the face's plane, each edge belonging to a face
//! that is not parallel to it (the sides of a box, the legs of a table: one loop per leg).
//! Convex loops are used; a concave footprint is left as it is (its patches may straddle).
//!
//! The region inside a footprint is kept: whether it sees anything depends on whether the
//! object is closed above it, and a dark patch there costs nothing but a patch.

use super::context::RawSurface;
use crate::geometry::{doubled_vector_area, Aabb, Polygon, Vec3};

/// A piece smaller than this fraction of its patch is not cut off: the patch stays whole
/// (the straddled part is then at most this fraction of it), rather than leaving a sliver
/// whose form factors would be poor.
pub(crate) const SMALLEST_PIECE: f64 = 0.05;

/// The convex footprint of an object on one face of a surface.
#[derive(Debug, Clone)]
pub(crate) struct Footprint {
    /// The surface and face it lies on (indices into the raw surfaces and their faces).
    pub surface: usize,
    pub face: usize,
    /// Its corners, metres, counter-clockwise about the face's normal, in the face's plane.
    pub corners: Vec<Vec3>,
}

/// The footprints of the faces of `objects` (indices of the OBJ surfaces in `raw`) on every
/// face of every surface. `tol` (m) is how far a point may be from a plane or from another
/// point and still count as on it.
pub(crate) fn footprints(raw: &[RawSurface], objects: &[usize], tol: f64) -> Vec<Footprint> {
    let mut out = Vec::new();
    for (s, host) in raw.iter().enumerate() {
        for (f, face) in host.faces.iter().enumerate() {
            if face.len() < 3 {
                continue;
            }
            let plane = Polygon::new(face.clone());
            let normal = plane.normal();
            let origin = face[0];
            let on_plane = |p: Vec3| (p - origin).dot(normal).abs() <= tol;
            let inside = |p: Vec3| inside_convex(face, normal, p, tol);
            let host_box = Aabb::of(face).expanded(tol);
            let mut edges: Vec<(Vec3, Vec3)> = Vec::new();
            for &o in objects.iter().filter(|&&o| o != s) {
                for g in &raw[o].faces {
                    if g.len() < 3 || !host_box.overlaps(&Aabb::of(g)) {
                        continue;
                    }
                    let n = Polygon::new(g.clone()).normal();
                    if n.dot(normal).abs() > 1.0 - 1e-6 {
                        continue; // parallel to the face: not a side standing on it
                    }
                    for k in 0..g.len() {
                        let (p, q) = (g[k], g[(k + 1) % g.len()]);
                        if on_plane(p) && on_plane(q) && inside(p) && inside(q) {
                            edges.push((p, q));
                        }
                    }
                }
            }
            for corners in loops(&edges, tol) {
                if let Some(corners) = convex_ccw(corners, normal, tol) {
                    out.push(Footprint {
                        surface: s,
                        face: f,
                        corners,
                    });
                }
            }
        }
    }
    out
}

/// Cuts convex `patch` (a polygon in the plane of `footprint`) along the footprint: the
/// pieces outside it and the piece inside, each convex and with the patch's winding, or the
/// patch itself when it does not straddle the footprint or a piece would be smaller than
/// [`SMALLEST_PIECE`] of it.
pub(crate) fn cut(patch: &[Vec3], footprint: &Footprint, normal: Vec3) -> Vec<Vec<Vec3>> {
    let area = Polygon::new(patch.to_vec()).area();
    // Counter-clockwise about `normal` (a flipped surface's patches face the other way).
    let mut corners = footprint.corners.clone();
    if Polygon::new(corners.clone()).normal().dot(normal) < 0.0 {
        corners.reverse();
    }
    let mut pieces = Vec::new();
    let mut rest = patch.to_vec();
    for k in 0..corners.len() {
        let (u, v) = (corners[k], corners[(k + 1) % corners.len()]);
        // Inside the footprint: to the left of u → v about the normal.
        let side = |x: Vec3| (v - u).cross(x - u).dot(normal);
        let outside = clip(&rest, |x| -side(x));
        rest = clip(&rest, side);
        if polygon_area(&outside) > 0.0 {
            pieces.push(outside);
        }
        if rest.len() < 3 {
            break;
        }
    }
    if rest.len() >= 3 {
        pieces.push(rest);
    }
    let smallest = pieces
        .iter()
        .map(|p| polygon_area(p))
        .fold(f64::INFINITY, f64::min);
    if pieces.len() < 2 || smallest < SMALLEST_PIECE * area {
        return vec![patch.to_vec()];
    }
    pieces
}

/// The part of convex `polygon` where `side(x) ≥ 0` (Sutherland–Hodgman with one plane),
/// with the polygon's winding; fewer than three corners when nothing is left.
fn clip(polygon: &[Vec3], side: impl Fn(Vec3) -> f64) -> Vec<Vec3> {
    let mut out = Vec::with_capacity(polygon.len() + 1);
    for k in 0..polygon.len() {
        let (a, b) = (polygon[k], polygon[(k + 1) % polygon.len()]);
        let (sa, sb) = (side(a), side(b));
        if sa >= 0.0 {
            out.push(a);
        }
        if (sa > 0.0 && sb < 0.0) || (sa < 0.0 && sb > 0.0) {
            out.push(a + (b - a) * (sa / (sa - sb)));
        }
    }
    dedup(out)
}

/// Drops corners that repeat the previous one (within 1e-12 m): a clip line through a corner
/// gives it twice.
fn dedup(points: Vec<Vec3>) -> Vec<Vec3> {
    let mut out: Vec<Vec3> = Vec::with_capacity(points.len());
    for p in points {
        if out.last().is_none_or(|&q| (p - q).length() > 1e-12) {
            out.push(p);
        }
    }
    while out.len() > 1 && (out[0] - out[out.len() - 1]).length() <= 1e-12 {
        out.pop();
    }
    out
}

/// Area of a planar polygon (m²); 0 for fewer than three corners.
fn polygon_area(p: &[Vec3]) -> f64 {
    0.5 * doubled_vector_area(p).length()
}

/// Whether `p` lies in convex `face` (within `tol` of its edges), in the face's plane.
fn inside_convex(face: &[Vec3], normal: Vec3, p: Vec3, tol: f64) -> bool {
    (0..face.len()).all(|k| {
        let (a, b) = (face[k], face[(k + 1) % face.len()]);
        let edge = b - a;
        // Signed distance of p to the edge line, positive inside for a counter-clockwise face.
        edge.cross(p - a).dot(normal) >= -tol * edge.length()
    })
}

/// The closed loops that `edges` form, each as its corners in order: points within `tol` are
/// the same point, and a loop is kept only where every corner joins exactly two edges.
fn loops(edges: &[(Vec3, Vec3)], tol: f64) -> Vec<Vec<Vec3>> {
    let mut points: Vec<Vec3> = Vec::new();
    let mut index = |p: Vec3| -> usize {
        match points.iter().position(|&q| (p - q).length() <= tol) {
            Some(i) => i,
            None => {
                points.push(p);
                points.len() - 1
            }
        }
    };
    let mut links: Vec<(usize, usize)> = Vec::new();
    for &(p, q) in edges {
        let (i, j) = (index(p), index(q));
        if i != j
            && !links
                .iter()
                .any(|&(a, b)| (a, b) == (i, j) || (a, b) == (j, i))
        {
            links.push((i, j));
        }
    }
    let mut neighbours = vec![Vec::new(); points.len()];
    for &(i, j) in &links {
        neighbours[i].push(j);
        neighbours[j].push(i);
    }
    let mut seen = vec![false; points.len()];
    let mut out = Vec::new();
    for start in 0..points.len() {
        if seen[start] || neighbours[start].len() != 2 {
            continue;
        }
        let mut chain = vec![start];
        seen[start] = true;
        let (mut previous, mut current) = (start, neighbours[start][0]);
        let closed = loop {
            if current == start {
                break true;
            }
            if seen[current] || neighbours[current].len() != 2 {
                break false;
            }
            seen[current] = true;
            chain.push(current);
            let next = if neighbours[current][0] == previous {
                neighbours[current][1]
            } else {
                neighbours[current][0]
            };
            (previous, current) = (current, next);
        };
        if closed && chain.len() >= 3 {
            out.push(chain.into_iter().map(|i| points[i]).collect());
        }
    }
    out
}

/// `corners` without collinear points, counter-clockwise about `normal`, if they form a
/// convex polygon of non-zero area.
fn convex_ccw(corners: Vec<Vec3>, normal: Vec3, tol: f64) -> Option<Vec<Vec3>> {
    let n = corners.len();
    let turn = |k: usize| {
        let (a, b, c) = (corners[(k + n - 1) % n], corners[k], corners[(k + 1) % n]);
        (b - a).cross(c - b).dot(normal) / ((b - a).length() * (c - b).length()).max(1e-300)
    };
    // Corners where the loop goes straight on are not corners.
    let kept: Vec<usize> = (0..n).filter(|&k| turn(k).abs() > 1e-9).collect();
    let signs: Vec<f64> = kept.iter().map(|&k| turn(k).signum()).collect();
    if kept.len() < 3 || signs.iter().any(|&s| s != signs[0]) {
        return None;
    }
    let mut out: Vec<Vec3> = kept.iter().map(|&k| corners[k]).collect();
    if signs[0] < 0.0 {
        out.reverse();
    }
    (polygon_area(&out) > tol * tol).then_some(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn v(x: f64, y: f64, z: f64) -> Vec3 {
        Vec3::new(x, y, z)
    }

    /// A 2 m × 2 m floor at z = 0, facing up.
    fn floor_2m() -> RawSurface {
        surface(
            "floor",
            vec![vec![
                v(0., 0., 0.),
                v(2., 0., 0.),
                v(2., 2., 0.),
                v(0., 2., 0.),
            ]],
        )
    }

    fn surface(name: &str, faces: Vec<Vec<Vec3>>) -> RawSurface {
        RawSurface {
            name: name.into(),
            material: "m".into(),
            material_at: super::super::error::Location::file(std::path::Path::new("t")),
            faces,
            max_edge: None,
            at: super::super::error::Location::file(std::path::Path::new("t")),
            exterior: false,
        }
    }

    /// The four side faces of a box of half-size `h` turned by `angle` about z, standing on
    /// z = 0 around (cx, cy), facing out.
    fn box_sides(cx: f64, cy: f64, h: f64, angle: f64, height: f64) -> Vec<Vec<Vec3>> {
        let (c, s) = (angle.cos(), angle.sin());
        let corner = |x: f64, y: f64| v(cx + c * x - s * y, cy + s * x + c * y, 0.0);
        let base = [corner(-h, -h), corner(h, -h), corner(h, h), corner(-h, h)];
        (0..4)
            .map(|k| {
                let (a, b) = (base[k], base[(k + 1) % 4]);
                let up = v(0.0, 0.0, height);
                vec![a, b, b + up, a + up]
            })
            .collect()
    }

    #[test]
    fn a_turned_box_on_a_floor_has_its_square_footprint() {
        let floor = floor_2m();
        let angle = 0.3f64;
        let block = surface("box", box_sides(1.0, 1.0, 0.3, angle, 0.5));
        let found = footprints(&[floor, block], &[1], 1e-6);
        assert_eq!(found.len(), 1, "{found:?}");
        let f = &found[0];
        assert_eq!((f.surface, f.face), (0, 0));
        assert_eq!(f.corners.len(), 4);
        assert!((polygon_area(&f.corners) - 0.36).abs() < 1e-12);
        // Counter-clockwise about the floor's normal (+z).
        let n = Polygon::new(f.corners.clone()).normal();
        assert!(n.z > 0.999, "{n:?}");
    }

    #[test]
    fn legs_give_one_footprint_each_and_open_chains_none() {
        let floor = floor_2m();
        let mut legs = box_sides(0.5, 0.5, 0.05, 0.0, 0.7);
        legs.extend(box_sides(1.5, 1.5, 0.05, 0.0, 0.7));
        // A free-standing panel: one edge on the floor, no loop.
        legs.push(vec![
            v(0.2, 1.5, 0.),
            v(0.8, 1.5, 0.),
            v(0.8, 1.5, 1.),
            v(0.2, 1.5, 1.),
        ]);
        let found = footprints(&[floor, surface("table", legs)], &[1], 1e-6);
        assert_eq!(found.len(), 2, "{found:?}");
        for f in &found {
            assert!((polygon_area(&f.corners) - 0.01).abs() < 1e-12);
        }
    }

    /// Cutting keeps the area exactly, leaves every piece on one side of the footprint, keeps
    /// the winding, and leaves alone patches that do not straddle or would lose a sliver.
    #[test]
    fn cutting_a_patch_keeps_its_area_and_sides() {
        let footprint = Footprint {
            surface: 0,
            face: 0,
            corners: vec![
                v(0.3, 0.2, 0.),
                v(0.9, 0.35, 0.),
                v(0.75, 0.95, 0.),
                v(0.15, 0.8, 0.),
            ],
        };
        let up = v(0.0, 0.0, 1.0);
        let patch = vec![
            v(0., 0., 0.),
            v(0.5, 0., 0.),
            v(0.5, 0.5, 0.),
            v(0., 0.5, 0.),
        ];
        let pieces = cut(&patch, &footprint, up);
        assert!(pieces.len() >= 2, "{pieces:?}");
        let total: f64 = pieces.iter().map(|p| polygon_area(p)).sum();
        assert!((total - 0.25).abs() < 1e-15, "{total}");
        let inside = |x: Vec3| inside_convex(&footprint.corners, up, x, 0.0);
        for p in &pieces {
            let c = Polygon::new(p.clone()).centroid();
            // Every corner on the same side as the centroid (or on the footprint's edge).
            let on_edge = |x: Vec3| {
                inside_convex(&footprint.corners, up, x, 1e-12)
                    && !inside_convex(&footprint.corners, up, x, -1e-12)
            };
            assert!(
                p.iter().all(|&x| on_edge(x) || inside(x) == inside(c)),
                "{p:?}"
            );
            assert!(Polygon::new(p.clone()).normal().z > 0.999);
        }
        // Wholly outside, and straddling by a sliver under SMALLEST_PIECE: unchanged.
        let away = vec![v(2., 2., 0.), v(3., 2., 0.), v(3., 3., 0.), v(2., 3., 0.)];
        assert_eq!(cut(&away, &footprint, up), vec![away.clone()]);
        let sliver = vec![
            v(0.89, 0.0, 0.),
            v(1.5, 0., 0.),
            v(1.5, 0.6, 0.),
            v(0.89, 0.6, 0.),
        ];
        assert_eq!(cut(&sliver, &footprint, up), vec![sliver.clone()]);
    }
}
