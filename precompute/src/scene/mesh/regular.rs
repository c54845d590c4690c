//! Regular subdivision: a quadrilateral into a grid of quads, a triangle into similar
//! triangles.

use super::parts;
use crate::geometry::{Polygon, Vec3};

/// Bilinear grid of a convex quad a-b-c-d: u runs a→b (and d→c), v runs a→d (and b→c).
pub(super) fn mesh_quad(a: Vec3, b: Vec3, c: Vec3, d: Vec3, max_edge: f64, out: &mut Vec<Polygon>) {
    let nu = parts((b - a).length().max((c - d).length()), max_edge);
    let nv = parts((d - a).length().max((c - b).length()), max_edge);
    let point = |i: usize, j: usize| {
        let u = i as f64 / nu as f64;
        let v = j as f64 / nv as f64;
        let bottom = a + (b - a) * u;
        let top = d + (c - d) * u;
        bottom + (top - bottom) * v
    };
    for j in 0..nv {
        for i in 0..nu {
            out.push(Polygon::new(vec![
                point(i, j),
                point(i + 1, j),
                point(i + 1, j + 1),
                point(i, j + 1),
            ]));
        }
    }
}

/// Regular subdivision of a triangle into m² similar triangles.
pub(super) fn mesh_triangle(a: Vec3, b: Vec3, c: Vec3, max_edge: f64, out: &mut Vec<Polygon>) {
    let longest = (b - a).length().max((c - b).length()).max((a - c).length());
    let m = parts(longest, max_edge);
    let point =
        |i: usize, j: usize| a + (b - a) * (i as f64 / m as f64) + (c - a) * (j as f64 / m as f64);
    for j in 0..m {
        for i in 0..m - j {
            out.push(Polygon::new(vec![
                point(i, j),
                point(i + 1, j),
                point(i, j + 1),
            ]));
            if i + j + 1 < m {
                out.push(Polygon::new(vec![
                    point(i + 1, j),
                    point(i + 1, j + 1),
                    point(i, j + 1),
                ]));
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::super::fixtures::{assert_tiles, tilted, unit_square};
    use super::super::mesh_face;
    use super::*;
    use crate::geometry::aspect;

    #[test]
    fn scene_mesh_unit_quad_at_quarter_metre_gives_16_patches() {
        let mut out = Vec::new();
        mesh_face(&unit_square(), 0.25, &mut out);
        assert_eq!(out.len(), 16);
        for p in &out {
            assert!((p.area() - 1.0 / 16.0).abs() < 1e-15);
            assert!((p.normal() - Vec3::new(0.0, 0.0, 1.0)).length() < 1e-15);
        }
    }

    #[test]
    fn scene_mesh_triangle_keeps_area_winding_and_edge_bound() {
        let (a, b, c) = (
            Vec3::new(0.0, 0.0, 0.0),
            Vec3::new(2.0, 0.0, 0.0),
            Vec3::new(0.0, 0.0, 1.0),
        );
        let whole = Polygon::new(vec![a, b, c]);
        let mut out = Vec::new();
        mesh_face(&[a, b, c], 0.3, &mut out);
        let m = 8; // ceil(sqrt(5) / 0.3)
        assert_eq!(out.len(), m * m);
        let total: f64 = out.iter().map(Polygon::area).sum();
        assert!((total - whole.area()).abs() < 1e-12);
        for p in &out {
            assert!((p.normal() - whole.normal()).length() < 1e-12);
            let n = p.vertices.len();
            for i in 0..n {
                assert!((p.vertices[(i + 1) % n] - p.vertices[i]).length() <= 0.3 + 1e-12);
            }
        }
    }

    #[test]
    fn scene_mesh_thin_strip_is_cut_across_its_length_only() {
        // A 0.025 × 2 m strip at 0.25 m: 8 patches of 0.25 × 0.025 m (aspect 10), as the
        // grid always gave; see the module docs for why not 80 square ones.
        let strip = [
            tilted(0.0, 0.0),
            tilted(2.0, 0.0),
            tilted(2.0, 0.025),
            tilted(0.0, 0.025),
        ];
        let mut out = Vec::new();
        mesh_face(&strip, 0.25, &mut out);
        assert_eq!(out.len(), 8);
        for p in &out {
            assert!((aspect(&p.vertices) - 10.0).abs() < 1e-9);
        }
        assert_tiles("strip", &strip, &out, 0.25);
    }
}
