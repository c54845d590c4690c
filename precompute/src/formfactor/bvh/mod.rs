//! Occlusion: a bounding-volume hierarchy over the patches that can block anything.
//!
//! A patch can only cut a segment between two scene points if the segment crosses its plane,
//! so a patch with the whole scene on or in front of its plane (every wall of a convex room)
//! never occludes and is left out of the tree. An empty room therefore costs no ray at all.
//!
//! Given the scene's faces ([`Occluders::with_faces`]), the blockers are the faces rather than
//! their patches: a desk top cut into a hundred patches is one blocker. That makes every ray
//! and every shaft far cheaper, and it is exact, because the patches of a face tile it.

mod shaft;
mod solid;

use crate::geometry::{Aabb, Face, Patch, Vec3};

pub(crate) use shaft::Shaft;
pub use solid::Solid;

/// What the hierarchy needs of a box besides [`Aabb`]'s own: planes and segments.
impl Aabb {
    /// Largest signed distance of a corner above the plane `normal · p = offset`.
    fn max_height(&self, normal: Vec3, offset: f64) -> f64 {
        let pick = |n: f64, lo: f64, hi: f64| if n >= 0.0 { hi } else { lo };
        let p = Vec3::new(
            pick(normal.x, self.min.x, self.max.x),
            pick(normal.y, self.min.y, self.max.y),
            pick(normal.z, self.min.z, self.max.z),
        );
        normal.dot(p) - offset
    }

    /// Does the segment `from + t d`, `t ∈ [t0, t1]`, meet the box? (slab test)
    fn hit_by(&self, from: Vec3, inv_d: Vec3, mut t0: f64, mut t1: f64) -> bool {
        for axis in 0..3 {
            let o = from.axis(axis);
            let inv = inv_d.axis(axis);
            let mut ta = (self.min.axis(axis) - o) * inv;
            let mut tb = (self.max.axis(axis) - o) * inv;
            if ta.is_nan() || tb.is_nan() {
                // Zero direction along this axis with the origin on a slab face.
                continue;
            }
            if ta > tb {
                std::mem::swap(&mut ta, &mut tb);
            }
            t0 = t0.max(ta);
            t1 = t1.min(tb);
            if t0 > t1 {
                return false;
            }
        }
        true
    }
}

/// A convex occluding polygon (at most 4 corners; larger patches are cut into triangles).
#[derive(Clone, Copy, Debug)]
struct Blocker {
    /// The face it comes from (see [`Occluders::face_of_patch`]).
    face: usize,
    corners: [Vec3; 4],
    /// In-plane inward normals of the edges (`normal × edge`).
    edge_normals: [Vec3; 4],
    len: usize,
    normal: Vec3,
    /// Plane offset `normal · corner`, metres.
    offset: f64,
    bounds: Aabb,
}

impl Blocker {
    fn new(face: usize, normal: Vec3, corners: &[Vec3]) -> Blocker {
        let len = corners.len().min(4);
        let mut c = [Vec3::ZERO; 4];
        c[..len].copy_from_slice(&corners[..len]);
        let mut e = [Vec3::ZERO; 4];
        for k in 0..len {
            e[k] = normal.cross(c[(k + 1) % len] - c[k]);
        }
        Blocker {
            face,
            corners: c,
            edge_normals: e,
            len,
            normal,
            offset: normal.dot(c[0]),
            bounds: Aabb::of(&c[..len]),
        }
    }

    /// Parameter `t` where the segment `from + t d` meets the polygon, if within `(t0, t1)`.
    fn hit(&self, from: Vec3, d: Vec3, t0: f64, t1: f64) -> bool {
        let denom = self.normal.dot(d);
        if denom == 0.0 {
            return false;
        }
        let t = (self.offset - self.normal.dot(from)) / denom;
        if !(t > t0 && t < t1) {
            return false;
        }
        let p = from + d * t;
        // Inside or on the boundary: rays through a shared edge must not leak.
        (0..self.len).all(|k| (p - self.corners[k]).dot(self.edge_normals[k]) >= -1e-12)
    }
}

/// A node of the hierarchy: either two children or a run of blockers.
#[derive(Clone, Copy, Debug)]
struct Node {
    bounds: Aabb,
    /// Leaf: first blocker; inner node: index of the left child (the right one follows it).
    first: usize,
    /// Leaf: number of blockers; inner node: 0.
    count: usize,
    /// Inner node: index of the right child.
    right: usize,
}

/// Most blockers in a leaf.
const LEAF_SIZE: usize = 4;
/// Depth of the traversal stack; the median split keeps the tree depth near log2(n).
const STACK: usize = 96;

/// Acceleration structure over the occluding patches of a scene (all scene patches are
/// candidates; only those that can cut a segment between two scene points are kept), reusable
/// for patch, point and receiver form factors.
#[derive(Clone, Debug)]
pub struct Occluders {
    blockers: Vec<Blocker>,
    /// The face each patch belongs to. A patch lying on a face never has a segment that
    /// starts or ends on it (from its front) cut by that face, so ignoring a patch ignores
    /// its whole face.
    face_of_patch: Vec<usize>,
    nodes: Vec<Node>,
    /// Geometric tolerance, metres (1e-9 of the scene's bounding-box diagonal).
    tolerance: f64,
    /// Closed boxes among the blockers ([`Occluders::with_solids`]).
    solids: Vec<Solid>,
}

impl Occluders {
    /// Builds the hierarchy with every patch of a scene as its own blocker. Patch indices in
    /// `ignore` lists refer to positions in `patches`.
    pub fn new(patches: &[Patch]) -> Self {
        let faces: Vec<Face> = patches
            .iter()
            .enumerate()
            .map(|(i, p)| Face {
                polygon: p.polygon.clone(),
                patches: i..i + 1,
            })
            .collect();
        Occluders::with_faces(patches, &faces)
    }

    /// Builds the hierarchy over the faces the `patches` were cut from (each face's patches
    /// tile it: [`Face::patches`]). Patches outside every face block on their own. Patch
    /// indices in `ignore` lists refer to positions in `patches`.
    pub fn with_faces(patches: &[Patch], faces: &[Face]) -> Self {
        let all: Vec<Vec3> = patches
            .iter()
            .flat_map(|p| p.polygon.vertices.iter().copied())
            .collect();
        let scene = Aabb::of(&all);
        let diagonal = if all.is_empty() {
            0.0
        } else {
            (scene.max - scene.min).length()
        };
        let tolerance = 1e-9 * diagonal.max(1e-300);
        // Each patch's face: its own unless a face lists it.
        let mut face_of_patch: Vec<usize> = (faces.len()..faces.len() + patches.len()).collect();
        let mut outlines: Vec<(usize, Vec3, &[Vec3])> = Vec::with_capacity(faces.len());
        for (index, face) in faces.iter().enumerate() {
            let Some(first) = face.patches.clone().next().and_then(|p| patches.get(p)) else {
                continue;
            };
            for p in face.patches.clone() {
                if let Some(slot) = face_of_patch.get_mut(p) {
                    *slot = index;
                }
            }
            // The face's normal is its patches' (the same plane and winding).
            outlines.push((index, first.normal, &face.polygon.vertices));
        }
        for (p, patch) in patches.iter().enumerate() {
            if face_of_patch[p] >= faces.len() {
                outlines.push((faces.len() + p, patch.normal, &patch.polygon.vertices));
            }
        }
        let mut blockers = Vec::new();
        for (face, normal, v) in outlines {
            if v.len() < 3 || !can_occlude(normal, v, &scene, &all, tolerance) {
                continue;
            }
            if v.len() <= 4 {
                blockers.push(Blocker::new(face, normal, v));
            } else {
                for k in 1..v.len() - 1 {
                    blockers.push(Blocker::new(face, normal, &[v[0], v[k], v[k + 1]]));
                }
            }
        }
        let mut occluders = Occluders {
            blockers,
            face_of_patch,
            nodes: Vec::new(),
            tolerance,
            solids: Vec::new(),
        };
        if !occluders.blockers.is_empty() {
            let n = occluders.blockers.len();
            occluders.build(0, n);
        }
        occluders
    }

    /// Is the blocker's face that of a patch in `ignore`?
    fn ignores(&self, ignore: &[usize], blocker: &Blocker) -> bool {
        ignore
            .iter()
            .any(|&p| self.face_of_patch.get(p) == Some(&blocker.face))
    }

    /// Number of occluding polygons kept (0 for a convex room without furniture).
    pub fn len(&self) -> usize {
        self.blockers.len()
    }

    /// True when nothing in the scene can occlude anything.
    pub fn is_empty(&self) -> bool {
        self.blockers.is_empty()
    }

    /// Builds the subtree over `blockers[start..end]` and returns its node index.
    fn build(&mut self, start: usize, end: usize) -> usize {
        let bounds = self.blockers[start..end]
            .iter()
            .fold(Aabb::EMPTY, |b, o| b.union(o.bounds));
        let index = self.nodes.len();
        self.nodes.push(Node {
            bounds,
            first: start,
            count: end - start,
            right: 0,
        });
        if end - start <= LEAF_SIZE {
            return index;
        }
        // Median split along the longest axis of the centres.
        let centres = self.blockers[start..end]
            .iter()
            .fold(Aabb::EMPTY, |mut b, o| {
                b.grow(o.bounds.center());
                b
            });
        let extent = centres.max - centres.min;
        let axis = if extent.x >= extent.y && extent.x >= extent.z {
            0
        } else if extent.y >= extent.z {
            1
        } else {
            2
        };
        let mid = start + (end - start) / 2;
        self.blockers[start..end].select_nth_unstable_by(mid - start, |a, b| {
            a.bounds
                .center()
                .axis(axis)
                .total_cmp(&b.bounds.center().axis(axis))
        });
        let left = self.build(start, mid);
        let right = self.build(mid, end);
        self.nodes[index] = Node {
            bounds,
            first: left,
            count: 0,
            right,
        };
        index
    }

    /// True when the open segment from `from` to `to` (metres) meets no occluder, apart from the
    /// patches listed in `ignore` (typically the source and target patch). The ends are trimmed
    /// by a relative 1e-7 so that points on patches do not hit their neighbours.
    pub fn visible(&self, from: Vec3, to: Vec3, ignore: &[usize]) -> bool {
        if self.blockers.is_empty() {
            return true;
        }
        let d = to - from;
        let inv_d = Vec3::new(1.0 / d.x, 1.0 / d.y, 1.0 / d.z);
        let (t0, t1) = (1e-7, 1.0 - 1e-7);
        let mut stack = [0usize; STACK];
        let mut top = 1;
        while top > 0 {
            top -= 1;
            let node = self.nodes[stack[top]];
            if !node.bounds.hit_by(from, inv_d, t0, t1) {
                continue;
            }
            if node.count > 0 {
                let run = &self.blockers[node.first..node.first + node.count];
                if run
                    .iter()
                    .any(|b| !self.ignores(ignore, b) && b.hit(from, d, t0, t1))
                {
                    return false;
                }
            } else if top + 2 <= STACK {
                stack[top] = node.first;
                stack[top + 1] = node.right;
                top += 2;
            }
        }
        true
    }
}

/// Is some scene corner strictly behind the plane of a polygon (unit `normal`, `corners`)? Only
/// then can the polygon cut a segment between two scene points. The scene box's corners answer
/// most cases without the full scan.
fn can_occlude(n: Vec3, corners: &[Vec3], scene: &Aabb, all: &[Vec3], tol: f64) -> bool {
    let Some(&origin) = corners.first() else {
        return false;
    };
    let offset = n.dot(origin);
    // Lowest corner of the scene box relative to the plane.
    let lowest = -scene.max_height(-n, -offset);
    if lowest >= -tol {
        return false;
    }
    all.iter().any(|&p| n.dot(p) - offset < -tol)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::Polygon;

    fn square(z: f64, up: bool) -> Patch {
        let mut v = vec![
            Vec3::new(0.0, 0.0, z),
            Vec3::new(1.0, 0.0, z),
            Vec3::new(1.0, 1.0, z),
            Vec3::new(0.0, 1.0, z),
        ];
        if !up {
            v.reverse();
        }
        Patch::new(Polygon::new(v), 0)
    }

    #[test]
    fn segment_through_blocker_is_occluded() {
        let patches = [square(0.0, true), square(0.5, true), square(1.0, false)];
        let occ = Occluders::new(&patches);
        // Only the middle square has scene points behind it.
        assert_eq!(occ.len(), 1);
        let from = Vec3::new(0.5, 0.5, 0.0);
        let to = Vec3::new(0.5, 0.5, 1.0);
        assert!(!occ.visible(from, to, &[]));
        assert!(occ.visible(from, to, &[1]));
        assert!(occ.visible(from, Vec3::new(2.5, 0.5, 1.0), &[]));
    }
}
