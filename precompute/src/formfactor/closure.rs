//! Which faces of a scene enclose a cavity: the parts whose rows of exact form factors sum to
//! exactly 1, so that a row that misses 1 there is an error of the form factors rather than
//! light leaving through an opening.
//!
//! A part is a set of faces connected through shared stretches of edge. It is closed when
//! every edge of every face is covered, along its whole length, by edges of other faces of the
//! part running the other way (two faces seen from the same side meet with opposite edge
//! directions), and it is a cavity when its faces face inward: the signed volume
//! `(1/3) Σ_f A_f (c_f · n_f)` (divergence theorem) is negative. A closed block seen from
//! outside is closed but not a cavity.

use crate::geometry::{Face, Vec3};

/// Relative distance (of the scene's extent) within which two edges count as lying on one
/// line.
const COLLINEAR: f64 = 1e-7;

/// One directed edge of a face.
struct Edge {
    face: usize,
    a: Vec3,
    b: Vec3,
    /// Bounding interval in x, metres (for the sweep).
    x: (f64, f64),
}

/// Finds the closed cavities among `faces`: each as the list of its face indices, in
/// increasing order; cavities ordered by their first face.
pub(crate) fn cavities(faces: &[Face]) -> Vec<Vec<usize>> {
    let mut edges = Vec::new();
    let mut extent = 0.0_f64;
    let origin = faces
        .first()
        .and_then(|f| f.polygon.vertices.first().copied())
        .unwrap_or(Vec3::ZERO);
    for (f, face) in faces.iter().enumerate() {
        let v = &face.polygon.vertices;
        for (k, &a) in v.iter().enumerate() {
            let b = v[(k + 1) % v.len()];
            extent = extent.max((a - origin).length());
            edges.push(Edge {
                face: f,
                a,
                b,
                x: (a.x.min(b.x), a.x.max(b.x)),
            });
        }
    }
    if edges.is_empty() {
        return Vec::new();
    }
    let tol = COLLINEAR * extent.max(f64::MIN_POSITIVE);
    edges.sort_by(|p, q| p.x.0.total_cmp(&q.x.0));
    // Covered parameter intervals of every edge, and the faces that share a stretch.
    let mut covered: Vec<Vec<(f64, f64)>> = vec![Vec::new(); edges.len()];
    let mut parent: Vec<usize> = (0..faces.len()).collect();
    for i in 0..edges.len() {
        for j in i + 1..edges.len() {
            if edges[j].x.0 > edges[i].x.1 + tol {
                break;
            }
            if edges[i].face == edges[j].face {
                continue;
            }
            let (Some(ti), Some(tj)) = (
                overlap(&edges[i], &edges[j], tol),
                overlap(&edges[j], &edges[i], tol),
            ) else {
                continue;
            };
            covered[i].push(ti);
            covered[j].push(tj);
            union(&mut parent, edges[i].face, edges[j].face);
        }
    }
    let mut open = vec![false; faces.len()];
    for (e, c) in edges.iter().zip(&mut covered) {
        let length = (e.b - e.a).length().max(f64::MIN_POSITIVE);
        if !covers(c, tol / length) {
            open[e.face] = true;
        }
    }
    let mut parts: Vec<Vec<usize>> = Vec::new();
    let mut index_of_root = vec![usize::MAX; faces.len()];
    for f in 0..faces.len() {
        let root = find(&mut parent, f);
        if index_of_root[root] == usize::MAX {
            index_of_root[root] = parts.len();
            parts.push(Vec::new());
        }
        parts[index_of_root[root]].push(f);
    }
    parts
        .into_iter()
        .filter(|part| {
            let volume: f64 = part
                .iter()
                .map(|&f| {
                    let p = &faces[f].polygon;
                    p.area() * p.centroid().dot(p.normal())
                })
                .sum();
            !part.iter().any(|&f| open[f]) && volume < 0.0
        })
        .collect()
}

/// The stretch of `e` (as parameters in [0, 1] from `e.a` to `e.b`) that `other` covers when
/// the two lie on one line (within `tol` metres) and run opposite ways; `None` otherwise or
/// when the stretch has no length.
fn overlap(e: &Edge, other: &Edge, tol: f64) -> Option<(f64, f64)> {
    let d = e.b - e.a;
    let len2 = d.dot(d);
    if len2 <= 0.0 || d.dot(other.b - other.a) >= 0.0 {
        return None;
    }
    let off_line = |p: Vec3| {
        let t = (p - e.a).dot(d) / len2;
        ((p - (e.a + d * t)).length(), t)
    };
    let (da, ta) = off_line(other.a);
    let (db, tb) = off_line(other.b);
    if da > tol || db > tol {
        return None;
    }
    let (s, t) = (ta.min(tb).max(0.0), ta.max(tb).min(1.0));
    (t - s > tol / len2.sqrt()).then_some((s, t))
}

/// Do the intervals cover [0, 1] (up to gaps of `slack`)?
fn covers(intervals: &mut [(f64, f64)], slack: f64) -> bool {
    intervals.sort_by(|p, q| p.0.total_cmp(&q.0));
    let mut reach = 0.0;
    for &(s, t) in intervals.iter() {
        if s > reach + slack {
            return false;
        }
        reach = f64::max(reach, t);
    }
    reach >= 1.0 - slack
}

fn find(parent: &mut [usize], mut x: usize) -> usize {
    while parent[x] != x {
        parent[x] = parent[parent[x]];
        x = parent[x];
    }
    x
}

fn union(parent: &mut [usize], a: usize, b: usize) {
    let (ra, rb) = (find(parent, a), find(parent, b));
    if ra != rb {
        parent[ra.max(rb)] = ra.min(rb);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::Polygon;

    /// The six faces of the unit cube, facing in (`inward`) or out.
    fn cube(inward: bool, lo: f64) -> Vec<Face> {
        let h = lo + 1.0;
        let v = |x: f64, y: f64, z: f64| Vec3::new(x, y, z);
        // Counter-clockwise seen from outside.
        let mut faces = vec![
            vec![v(lo, lo, lo), v(lo, h, lo), v(h, h, lo), v(h, lo, lo)],
            vec![v(lo, lo, h), v(h, lo, h), v(h, h, h), v(lo, h, h)],
            vec![v(lo, lo, lo), v(h, lo, lo), v(h, lo, h), v(lo, lo, h)],
            vec![v(lo, h, lo), v(lo, h, h), v(h, h, h), v(h, h, lo)],
            vec![v(lo, lo, lo), v(lo, lo, h), v(lo, h, h), v(lo, h, lo)],
            vec![v(h, lo, lo), v(h, h, lo), v(h, h, h), v(h, lo, h)],
        ];
        if inward {
            for f in &mut faces {
                f.reverse();
            }
        }
        faces
            .into_iter()
            .map(|c| Face {
                polygon: Polygon::new(c),
                patches: 0..0,
            })
            .collect()
    }

    #[test]
    fn a_room_is_a_cavity_a_block_and_an_open_box_are_not() {
        assert_eq!(cavities(&cube(true, 0.0)), vec![vec![0, 1, 2, 3, 4, 5]]);
        assert!(cavities(&cube(false, 0.0)).is_empty());
        let mut open = cube(true, 0.0);
        open.remove(1);
        assert!(cavities(&open).is_empty());
        // A room and a separate block: only the room.
        let mut both = cube(true, 0.0);
        both.extend(cube(false, 5.0));
        assert_eq!(cavities(&both), vec![vec![0, 1, 2, 3, 4, 5]]);
    }

    #[test]
    fn a_wall_split_in_two_still_closes_the_room() {
        // The floor cut into two halves along x = 0.5: its neighbours' edges are covered by two
        // edges each (a T-junction of faces).
        let mut faces = cube(true, 0.0);
        let floor = faces[0].polygon.vertices.clone();
        // Inward floor (reversed): (1,0,0) (1,1,0) (0,1,0) (0,0,0).
        let v = |x: f64, y: f64| Vec3::new(x, y, 0.0);
        assert_eq!(floor[0], v(1.0, 0.0));
        faces[0].polygon = Polygon::new(vec![v(1.0, 0.0), v(1.0, 1.0), v(0.5, 1.0), v(0.5, 0.0)]);
        faces.push(Face {
            polygon: Polygon::new(vec![v(0.5, 0.0), v(0.5, 1.0), v(0.0, 1.0), v(0.0, 0.0)]),
            patches: 0..0,
        });
        assert_eq!(cavities(&faces), vec![vec![0, 1, 2, 3, 4, 5, 6]]);
    }
}
