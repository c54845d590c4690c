//! The cluster tree over the patches and the partition of `S` into blocks that it induces.
//!
//! The tree halves a cluster at the median of its patches along the coordinate in which they
//! spread most, down to [`Settings::leaf`] patches. The coordinates are the centroid's three
//! and the unit normal's three scaled by the scene's diagonal: patches facing different ways
//! are separated first (a cluster of the floor and a wall has a kernel with a kink where they
//! meet, and of much higher rank), then coplanar ones by position. A pair of clusters is *admissible*
//! (well separated, stored low rank) when the smaller of their boxes is no wider than
//! [`Settings::admissibility`] times the gap between the boxes; other pairs are split until
//! one side is a leaf, and stored dense there.
//!
//! Occlusion makes the kernel of a well-separated pair discontinuous wherever a blocker's
//! silhouette crosses it, and such a block is of high rank. So an admissible pair is first
//! classified by what lies between its clusters ([`Sight`]): *dark* when the clusters face
//! away from each other or one blocker, or one closed box of blockers (a desk), hides each
//! from the other (every entry is 0, nothing is read), *clear* when no blocker can cut a
//! segment between them (the kernel is smooth: low rank), and *mixed* otherwise, split
//! further like an inadmissible pair, so that only the parts a silhouette crosses are stored
//! dense and the rest of the block still compresses; or, with [`Settings::shade_mixed`],
//! kept whole as a *shaded* block (its unoccluded entries times visible shares from rays).
//!
//! Only the upper half of the symmetric partition is kept: diagonal blocks `(τ, τ)` and
//! blocks whose rows all come before their columns in the tree's order. Every stored
//! off-diagonal block stands for itself and its transpose.

use std::ops::Range;

use super::Settings;
use crate::geometry::{Patch, Vec3};

/// An axis-aligned box, metres.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct Bounds {
    pub(super) min: Vec3,
    pub(super) max: Vec3,
}

impl Bounds {
    const EMPTY: Bounds = Bounds {
        min: Vec3::new(f64::INFINITY, f64::INFINITY, f64::INFINITY),
        max: Vec3::new(f64::NEG_INFINITY, f64::NEG_INFINITY, f64::NEG_INFINITY),
    };

    fn add(&mut self, p: Vec3) {
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

    fn union(self, o: Bounds) -> Bounds {
        let mut b = self;
        b.add(o.min);
        b.add(o.max);
        b
    }

    /// The box's diagonal, metres.
    pub(super) fn diameter(&self) -> f64 {
        (self.max - self.min).length()
    }

    /// The gap between two boxes, metres (0 where they overlap or touch).
    pub(super) fn distance(&self, o: &Bounds) -> f64 {
        let gap = |lo1: f64, hi1: f64, lo2: f64, hi2: f64| (lo2 - hi1).max(lo1 - hi2).max(0.0);
        Vec3::new(
            gap(self.min.x, self.max.x, o.min.x, o.max.x),
            gap(self.min.y, self.max.y, o.min.y, o.max.y),
            gap(self.min.z, self.max.z, o.min.z, o.max.z),
        )
        .length()
    }
}

/// A cluster: the patches at positions `range` of the tree's order.
#[derive(Clone, Debug)]
pub(super) struct Node {
    /// Positions in the tree's order.
    pub(super) range: Range<usize>,
    /// The box of the cluster's patches (all their corners), metres.
    pub(super) bounds: Bounds,
    /// The two halves, or none for a leaf.
    pub(super) children: Option<[usize; 2]>,
    /// The plane the cluster's patches lie in, when they share one.
    pub(super) plate: Option<Plate>,
}

/// A cluster whose patches all lie in one plane and face the same way: the rectangle in that
/// plane that holds them, for the shaft between two clusters.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct Plate {
    /// Corners of the rectangle, in order, metres.
    pub(super) corners: [Vec3; 4],
    /// The patches' unit normal.
    pub(super) normal: Vec3,
}

impl Plate {
    /// Is every corner of `other` at most `tolerance` metres in front of this plate's plane?
    /// Then no patch of the other cluster is in front of a patch of this one.
    fn faces_away_from(&self, other: &Plate, tolerance: f64) -> bool {
        let offset = self.normal.dot(self.corners[0]);
        other
            .corners
            .iter()
            .all(|&c| self.normal.dot(c) - offset <= tolerance)
    }
}

/// What lies between two well-separated clusters (module docs).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Sight {
    /// The clusters face away from each other, or one blocker or one solid hides each from
    /// the other: every entry is 0.
    Dark,
    /// No blocker can cut a segment between them.
    Clear,
    /// A blocker may cut some of the segments between them, or the clusters are not planar.
    Mixed,
}

/// The plate of the patches `members`: `None` unless their planes lie within `tolerance`
/// metres of each other and their normals within `tolerance / extent` (`extent` metres, the
/// scene's size: over it the normals' difference moves a height by at most `tolerance`).
/// The rectangle lies in the lowest of their planes, so that whatever is in front of a patch
/// is in front of it.
fn plate_of(patches: &[Patch], members: &[usize], tolerance: f64, extent: f64) -> Option<Plate> {
    let first = patches.get(*members.first()?)?;
    let normal = first.normal;
    let (mut low, mut high) = (f64::INFINITY, f64::NEG_INFINITY);
    for &i in members {
        let p = &patches[i];
        let turned = (p.normal - normal).length() * extent;
        if turned.is_nan() || turned > tolerance {
            return None;
        }
        for &c in &p.polygon.vertices {
            let h = normal.dot(c);
            low = low.min(h);
            high = high.max(h);
        }
    }
    let spread = high - low;
    if spread.is_nan() || spread > tolerance {
        return None;
    }
    // Two unit vectors in the plane: across the normal's smallest component, then the third.
    let axis = (0..3).fold(0, |best, k| {
        if normal.axis(k).abs() < normal.axis(best).abs() {
            k
        } else {
            best
        }
    });
    let e = [
        Vec3::new(1.0, 0.0, 0.0),
        Vec3::new(0.0, 1.0, 0.0),
        Vec3::new(0.0, 0.0, 1.0),
    ][axis];
    let u = normal.cross(e).normalized();
    let v = normal.cross(u);
    let (mut s0, mut s1, mut t0, mut t1) = (
        f64::INFINITY,
        f64::NEG_INFINITY,
        f64::INFINITY,
        f64::NEG_INFINITY,
    );
    for &i in members {
        for &c in &patches[i].polygon.vertices {
            let (s, t) = (u.dot(c), v.dot(c));
            (s0, s1, t0, t1) = (s0.min(s), s1.max(s), t0.min(t), t1.max(t));
        }
    }
    let at = |s: f64, t: f64| normal * low + u * s + v * t;
    Some(Plate {
        corners: [at(s0, t0), at(s1, t0), at(s1, t1), at(s0, t1)],
        normal,
    })
}

/// The cluster tree: nodes (the root first) and the order it puts the patches in.
#[derive(Clone, Debug)]
pub(super) struct ClusterTree {
    pub(super) nodes: Vec<Node>,
    /// `order[position]` = patch index.
    pub(super) order: Vec<usize>,
}

impl ClusterTree {
    /// The tree over `patches`, with leaves of at most `leaf` patches; a cluster whose
    /// patches' planes lie within `flat` metres of each other across the scene has a
    /// [`Plate`].
    pub(super) fn new(patches: &[Patch], leaf: usize, flat: f64) -> ClusterTree {
        let leaf = leaf.max(1);
        let mut order: Vec<usize> = (0..patches.len()).collect();
        let mut nodes = Vec::new();
        let bounds: Vec<Bounds> = patches
            .iter()
            .map(|p| {
                let mut b = Bounds::EMPTY;
                for &v in &p.polygon.vertices {
                    b.add(v);
                }
                b.add(p.centroid);
                b
            })
            .collect();
        let scene = order.iter().fold(Bounds::EMPTY, |b, &i| b.union(bounds[i]));
        let orientation_scale = if patches.is_empty() {
            0.0
        } else {
            scene.diameter()
        };
        let keys: Vec<[f64; 6]> = patches
            .iter()
            .map(|p| {
                let (c, n) = (p.centroid, p.normal * orientation_scale);
                [c.x, c.y, c.z, n.x, n.y, n.z]
            })
            .collect();
        split(&keys, &bounds, &mut order, 0, leaf, &mut nodes);
        for node in &mut nodes {
            node.plate = plate_of(patches, &order[node.range.clone()], flat, orientation_scale);
        }
        ClusterTree { nodes, order }
    }

    /// The position of each patch in the tree's order (the inverse of `order`).
    pub(super) fn positions(&self) -> Vec<usize> {
        let mut position = vec![0; self.order.len()];
        for (p, &i) in self.order.iter().enumerate() {
            position[i] = p;
        }
        position
    }
}

/// Appends the node over `order[start..]` (the slice given) and its descendants; returns its
/// index.
fn split(
    keys: &[[f64; 6]],
    bounds: &[Bounds],
    order: &mut [usize],
    start: usize,
    leaf: usize,
    nodes: &mut Vec<Node>,
) -> usize {
    let own = order.iter().fold(Bounds::EMPTY, |b, &i| b.union(bounds[i]));
    let index = nodes.len();
    nodes.push(Node {
        range: start..start + order.len(),
        bounds: own,
        children: None,
        plate: None,
    });
    if order.len() <= leaf {
        return index;
    }
    let spread = |k: usize| {
        let (lo, hi) = order
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &i| {
                (lo.min(keys[i][k]), hi.max(keys[i][k]))
            });
        hi - lo
    };
    // The first of equal spreads: deterministic.
    let axis = (0..6).fold(0, |best, k| if spread(k) > spread(best) { k } else { best });
    let half = order.len() / 2;
    // Ties broken by patch index: the tree, and with it every byte, is deterministic.
    order.select_nth_unstable_by(half, |&a, &b| {
        keys[a][axis].total_cmp(&keys[b][axis]).then(a.cmp(&b))
    });
    let (low, high) = order.split_at_mut(half);
    // Each half in patch order within itself, so that the split does not depend on how the
    // selection left it.
    low.sort_unstable();
    high.sort_unstable();
    let a = split(keys, bounds, low, start, leaf, nodes);
    let b = split(keys, bounds, high, start + half, leaf, nodes);
    nodes[index].children = Some([a, b]);
    index
}

/// How a block is stored.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Kind {
    /// Every entry computed.
    Near,
    /// Admissible, with no sight known (the partition by distance alone): approximated at low
    /// rank from the pair integrals with their shadows.
    Far,
    /// Admissible and clear ([`Sight::Clear`]): no blocker cuts a pair, so the low-rank
    /// approximation reads the unoccluded entries, one way (`Occlusion::unoccluded`).
    Clear,
    /// Admissible and dark ([`Sight::Dark`]): every entry is 0, stored at rank 0 unread.
    Dark,
    /// Admissible and mixed, with [`Settings::shade_mixed`]: the unoccluded entries, at low
    /// rank, times each pair's visible share (one factor per patch).
    Shaded,
}

/// A block of the partition: rows of cluster `row_node`, columns of `col_node`.
#[derive(Clone, Debug)]
pub(super) struct BlockSpan {
    pub(super) row_node: usize,
    pub(super) col_node: usize,
    pub(super) rows: Range<usize>,
    pub(super) cols: Range<usize>,
    pub(super) kind: Kind,
    /// The admissible pair of clusters `(row_node, col_node)` that sight split this block
    /// from ([`Sight::Mixed`]), if any: its ancestor in the partition, for the census.
    pub(super) split_from: Option<(usize, usize)>,
}

impl BlockSpan {
    /// A diagonal block `(τ, τ)`, stored whole (symmetric).
    pub(super) fn is_diagonal(&self) -> bool {
        self.row_node == self.col_node
    }
}

/// `clear(a, a_normal, b, b_normal)`: no blocker can cut a segment between the planar
/// polygons `a` and `b` (corners, metres; the unit normals of their lit sides).
pub(super) type ClearBetween<'a> = dyn Fn(&[Vec3], Vec3, &[Vec3], Vec3) -> bool + Sync + 'a;

/// What decides a well-separated pair's [`Sight`]: `clear(a, a_normal, b, b_normal)` says
/// whether no blocker can cut a segment between the planar polygons `a` and `b` (corners,
/// metres, and the unit normals of the sides that emit and receive); `dark_tolerance` is the
/// height in metres up to which a corner counts as in a plane (below every pair integral's own
/// tolerance, so that a block called dark is one whose pair integrals all return 0);
/// `hidden(a, b)` says whether one blocker, or one closed box of blockers, cuts every segment
/// between the polygons.
pub(super) struct Seeing<'a> {
    pub(super) clear: &'a ClearBetween<'a>,
    pub(super) hidden: &'a (dyn Fn(&[Vec3], &[Vec3]) -> bool + Sync),
    pub(super) dark_tolerance: f64,
}

impl Seeing<'_> {
    fn sight(&self, a: Option<&Plate>, b: Option<&Plate>) -> Sight {
        let (Some(a), Some(b)) = (a, b) else {
            return Sight::Mixed;
        };
        if a.faces_away_from(b, self.dark_tolerance) || b.faces_away_from(a, self.dark_tolerance) {
            Sight::Dark
        } else if (self.clear)(&a.corners, a.normal, &b.corners, b.normal) {
            Sight::Clear
        } else if (self.hidden)(&a.corners, &b.corners) {
            Sight::Dark
        } else {
            Sight::Mixed
        }
    }
}

/// The upper half of the block partition of the tree's `S` (module docs), in a fixed order.
/// Without `seeing` (or with [`Settings::split_by_sight`] off) every admissible pair is one
/// far block, as if nothing could occlude.
pub(super) fn partition(
    tree: &ClusterTree,
    settings: &Settings,
    seeing: Option<&Seeing>,
) -> Vec<BlockSpan> {
    let mut blocks = Vec::new();
    if !tree.nodes.is_empty() {
        Walk::new(tree, settings, seeing).visit(0, 0, None, &mut blocks);
    }
    blocks
}

/// The blocks that replace `span`, a well-separated pair of clusters split once more: its
/// clusters' children paired and classified again ([`Settings::shade_misfit`]), down to leaves
/// stored whole.
pub(super) fn split_once(
    tree: &ClusterTree,
    settings: &Settings,
    seeing: Option<&Seeing>,
    span: &BlockSpan,
) -> Vec<BlockSpan> {
    let mut blocks = Vec::new();
    let from = span.split_from.or(Some((span.row_node, span.col_node)));
    Walk::new(tree, settings, seeing).children(span.row_node, span.col_node, from, &mut blocks);
    blocks
}

/// The partition's recursion and what it reads.
struct Walk<'a> {
    tree: &'a ClusterTree,
    settings: &'a Settings,
    seeing: Option<&'a Seeing<'a>>,
}

impl<'a> Walk<'a> {
    /// A walk of `tree` that sees between clusters only with [`Settings::split_by_sight`].
    fn new(tree: &'a ClusterTree, settings: &'a Settings, seeing: Option<&'a Seeing<'a>>) -> Self {
        Walk {
            tree,
            settings,
            seeing: seeing.filter(|_| settings.split_by_sight),
        }
    }

    /// Appends the blocks of the pair `(t, s)`; `split_from`: the mixed admissible pair it
    /// descends from.
    fn visit(
        &self,
        t: usize,
        s: usize,
        split_from: Option<(usize, usize)>,
        out: &mut Vec<BlockSpan>,
    ) {
        let (tn, sn) = (&self.tree.nodes[t], &self.tree.nodes[s]);
        let span = |kind| self.span(t, s, kind, split_from);
        if t == s {
            match tn.children {
                None => out.push(span(Kind::Near)),
                Some([a, b]) => {
                    self.visit(a, a, split_from, out);
                    self.visit(a, b, split_from, out);
                    self.visit(b, b, split_from, out);
                }
            }
            return;
        }
        let gap = tn.bounds.distance(&sn.bounds);
        let small = tn.bounds.diameter().min(sn.bounds.diameter());
        let mut split_from = split_from;
        if gap > 0.0 && small <= self.settings.admissibility * gap {
            let sight = self
                .seeing
                .map(|seeing| seeing.sight(tn.plate.as_ref(), sn.plate.as_ref()));
            match sight {
                None => return out.push(span(Kind::Far)),
                Some(Sight::Clear) => return out.push(span(Kind::Clear)),
                Some(Sight::Dark) => return out.push(span(Kind::Dark)),
                Some(Sight::Mixed) if self.settings.shade_mixed => {
                    return out.push(span(Kind::Shaded))
                }
                // Split like a close pair: the parts no silhouette crosses compress.
                Some(Sight::Mixed) => split_from = split_from.or(Some((t, s))),
            }
        }
        self.children(t, s, split_from, out);
    }

    /// The block of clusters `t` (rows) and `s` (columns).
    fn span(
        &self,
        t: usize,
        s: usize,
        kind: Kind,
        split_from: Option<(usize, usize)>,
    ) -> BlockSpan {
        BlockSpan {
            row_node: t,
            col_node: s,
            rows: self.tree.nodes[t].range.clone(),
            cols: self.tree.nodes[s].range.clone(),
            kind,
            split_from,
        }
    }

    /// Appends the blocks of the pair `(t, s)` of distinct clusters split once: the pairs of
    /// their children (a leaf stands for itself), or the pair whole where both are leaves.
    fn children(
        &self,
        t: usize,
        s: usize,
        split_from: Option<(usize, usize)>,
        out: &mut Vec<BlockSpan>,
    ) {
        let (tn, sn) = (&self.tree.nodes[t], &self.tree.nodes[s]);
        match (tn.children, sn.children) {
            (None, None) => out.push(self.span(t, s, Kind::Near, split_from)),
            (None, Some([c, d])) => {
                self.visit(t, c, split_from, out);
                self.visit(t, d, split_from, out);
            }
            (Some([a, b]), None) => {
                self.visit(a, s, split_from, out);
                self.visit(b, s, split_from, out);
            }
            (Some([a, b]), Some([c, d])) => {
                for (x, y) in [(a, c), (a, d), (b, c), (b, d)] {
                    self.visit(x, y, split_from, out);
                }
            }
        }
    }
}
