//! One pair's form factor: the outer quadrature on the source patch, the exact kernel toward
//! the target and its visible part, with the quadrature order chosen per pair.

use super::bvh::Shaft;
use super::kernel::{self, Cone};
use super::quadrature::{self, SampleTable};
use super::{near, sampled, shadow, visibility, FormFactorOptions, Occluders, Visibility};
use crate::geometry::{Patch, Vec3};

/// Scale in the error model of the outer quadrature (see
/// [`FormFactorOptions::quadrature_tolerance`]). A conservative choice, not a fit: the empty
/// 412-patch test room keeps its row sums within 1e-5 with it.
const ORDER_SCALE: f64 = 0.5;

/// Four-way splits of a source cell toward a target it touches (`Context::integrate_near`):
/// the finest cells have 1/16 of the side of the (round) source.
const TOUCHING_DEPTH: u32 = 4;

/// Four-way splits of a source cell toward a target it comes close to without touching:
/// enough for a gap of 1e-5 of the source's size to be resolved.
const NEAR_DEPTH: u32 = 18;

/// Halvings of a thin source cell across its long side on one branch of the refinement
/// (aspect ratios up to 2^16 are brought down to [`near::ASPECT_BOUND`]).
const MAX_HALVINGS: u32 = 16;

/// In a pair that touches, a source cell closer to the target than this multiple of its
/// diameter is split (dimensionless). Below 1/√2 so that, next to a contact, the cells one row
/// away from it in a square grid (at a distance of their side) are left whole: they are
/// integrated accurately by the near-pair rule, and touching pairs of round patches are
/// integrated as they always were.
const TOUCHING_RATIO: f64 = 0.5;

/// In a pair that does not touch, a source closer to the target than this multiple of its
/// diameter is refined, and its cells are split until each is at least this multiple of its
/// diameter away from the target (dimensionless); further pairs keep the distance-based rule.
/// At 1 the near-pair rule (order 5) leaves below 1e-6 relative on a cell; at 0.5 up to 2e-5
/// (the needles of a 64-sided pyramid's base).
const GAP_RATIO: f64 = 1.0;

/// How a source is refined toward one target (`Context::integrate_near`).
struct Refinement<'t> {
    /// The corners of the part of the target in front of the source's plane, metres: its
    /// outline is where the kernel is singular.
    target: &'t [Vec3],
    /// Distance up to which a cell touches the target, metres.
    tol: f64,
    /// Touching cells are split beyond `TOUCHING_DEPTH` while larger than this, metres.
    touching_size: f64,
    /// Cells closer to the target than this multiple of their diameter are split.
    ratio: f64,
}

/// Per-patch data the pair loop needs, computed once.
#[derive(Clone, Copy, Debug)]
struct Bound {
    /// Centroid, metres.
    centre: Vec3,
    /// Largest distance from the centroid to a corner, metres.
    radius: f64,
}

impl Bound {
    fn of(p: &Patch) -> Bound {
        let radius = p
            .polygon
            .vertices
            .iter()
            .map(|&v| (v - p.centroid).length())
            .fold(0.0, f64::max);
        Bound {
            centre: p.centroid,
            radius,
        }
    }
}

/// A set of patches with their quadrature rules: sources (outer integral) or targets (ray ends).
pub(super) struct Prepared<'a> {
    patches: &'a [Patch],
    bounds: Vec<Bound>,
    samples: SampleTable,
}

impl<'a> Prepared<'a> {
    pub(super) fn new(patches: &'a [Patch], max_order: usize) -> Self {
        Prepared {
            patches,
            bounds: patches.iter().map(Bound::of).collect(),
            samples: SampleTable::new(patches, max_order),
        }
    }

    /// Patches only looked at (the targets of a [`Context`]): the exact kernel needs their
    /// outlines and bounds, never a quadrature rule on them, so only the rule of order 1 is
    /// made: the rules of every order up to 6 are 91 points a patch, 9.4 million for 103 000
    /// patches, and a point's row would otherwise make them all again.
    pub(super) fn targets(patches: &'a [Patch]) -> Self {
        Prepared::new(patches, 1)
    }

    /// The largest distance from patch `i`'s centroid to a corner, metres.
    pub(super) fn radius(&self, i: usize) -> f64 {
        self.bounds[i].radius
    }
}

/// Gauss–Legendre rules of orders 1 to `max` on [0, 1].
pub(super) fn gauss_rules(max: usize) -> Vec<Vec<(f64, f64)>> {
    (1..=max.max(1)).map(quadrature::gauss_legendre).collect()
}

/// The largest order any rule on a set of patches needs.
pub(super) fn max_order(opts: &FormFactorOptions) -> usize {
    opts.gauss_order
        .max(opts.touching_order)
        .max(opts.occluded_order)
        .max(1)
}

/// Everything needed to evaluate form factors towards the scene patches.
pub(super) struct Context<'a> {
    pub(super) targets: &'a Prepared<'a>,
    /// Gauss–Legendre rules on [0, 1] of orders 1, 2, … (index = order − 1).
    pub(super) gauss: Vec<Vec<(f64, f64)>>,
    pub(super) occluders: &'a Occluders,
    pub(super) opts: &'a FormFactorOptions,
    /// Refine the outer integral toward targets that come close without touching
    /// ([`GAP_RATIO`]); touching targets are refined regardless.
    pub(super) refine_gaps: bool,
}

/// A point (or differential area) that looks at the targets.
#[derive(Clone, Copy)]
pub(super) struct Viewer<'c> {
    pub(super) point: Vec3,
    pub(super) normal: Vec3,
    pub(super) cone: Option<&'c Cone>,
}

impl<'a> Context<'a> {
    /// A context looking at `targets`, with the Gauss rules up to the order `opts` needs.
    pub(super) fn new(
        targets: &'a Prepared<'a>,
        occluders: &'a Occluders,
        opts: &'a FormFactorOptions,
        refine_gaps: bool,
    ) -> Self {
        Context {
            targets,
            gauss: gauss_rules(max_order(opts)),
            occluders,
            opts,
            refine_gaps,
        }
    }
}

impl Context<'_> {
    /// Does source patch `src` touch target `j` (share an edge, part of one, or a corner)?
    fn touches(&self, src: &Patch, bound: Bound, j: usize) -> bool {
        let tgt = self.targets.bounds[j];
        let gap = (bound.centre - tgt.centre).length() - tgt.radius;
        let tol = 1e-9 * (bound.radius + tgt.radius);
        gap <= bound.radius + tol
            && touching(
                &src.polygon.vertices,
                &self.targets.patches[j].polygon.vertices,
                tol,
            )
    }

    /// Integrates `f(point, weight in m²)` over the convex `cell` of a source near the target
    /// of `r`: a cell closer to the target than `r.ratio` times its diameter is split (thin
    /// cells halved across their long side first, [`near::split`]) until it is not, down to
    /// `TOUCHING_DEPTH` four-way splits for cells that touch the target (further while they are
    /// larger than `r.touching_size`) and `NEAR_DEPTH` for cells that do not. Cells clear of
    /// the target take the near-pair rule (`gauss_order`), the finest touching cells
    /// `touching_order`.
    fn integrate_near(
        &self,
        cell: &[Vec3],
        r: &Refinement,
        depth: u32,
        halvings: u32,
        f: &mut dyn FnMut(Vec3, f64),
    ) {
        let distance = near::outline_distance(cell, r.target);
        let touching_cell = distance <= r.tol;
        let diameter = near::diameter(cell);
        if distance < r.ratio * diameter {
            let limit = if !touching_cell {
                NEAR_DEPTH
            } else if diameter > r.touching_size {
                // Next to a thin target the kernel varies on the scale of the target's width:
                // the contact is resolved to a fraction of that width, not of the source's.
                NEAR_DEPTH.min(depth + 1)
            } else {
                TOUCHING_DEPTH
            };
            match near::split(cell) {
                near::Split::Halves(halves) if halvings < MAX_HALVINGS => {
                    for sub in halves {
                        self.integrate_near(&sub, r, depth, halvings + 1, f);
                    }
                    return;
                }
                near::Split::Cells(cells) if depth < limit => {
                    for sub in cells {
                        self.integrate_near(&sub, r, depth + 1, halvings, f);
                    }
                    return;
                }
                _ => {}
            }
        }
        let order = if touching_cell {
            self.opts.touching_order
        } else {
            self.opts.gauss_order
        };
        quadrature::for_each_on_cell(cell, self.gauss_rule(order), &mut *f);
    }

    /// Outer-quadrature order for a source patch (`bound`) towards target `j` (module docs).
    /// `touches`: [`Context::touches`] for the pair.
    fn source_order(&self, bound: Bound, j: usize, touches: bool) -> usize {
        let max = self.opts.gauss_order.max(1);
        let tgt = self.targets.bounds[j];
        let gap = (bound.centre - tgt.centre).length() - tgt.radius;
        if bound.radius <= 0.0 {
            return 1;
        }
        if touches {
            return max.max(self.opts.touching_order);
        }
        if gap <= 0.0 {
            return max;
        }
        let src = bound;
        let ratio = ORDER_SCALE * src.radius / gap;
        if ratio >= 1.0 {
            return max;
        }
        let tol = self.opts.quadrature_tolerance.clamp(1e-300, 1.0);
        // Smallest m with ratio^(2m) ≤ tol.
        let m = (tol.ln() / (2.0 * ratio.ln())).ceil();
        if m.is_finite() && m >= 1.0 {
            (m as usize).min(max)
        } else {
            1
        }
    }

    /// Form factor (dimensionless, fraction of the source's output) from source patch `i` of
    /// `sources` to target `j`. `ignore` lists scene patches that must not block (the source
    /// and target themselves).
    pub(super) fn pair(&self, sources: &Prepared, i: usize, j: usize, ignore: &[usize]) -> f64 {
        self.pair_seen(sources, i, j, ignore, true)
    }

    /// [`Context::pair`] as if no blocker stood between the two patches.
    pub(super) fn pair_unoccluded(&self, sources: &Prepared, i: usize, j: usize) -> f64 {
        self.pair_seen(sources, i, j, &[], false)
    }

    fn pair_seen(
        &self,
        sources: &Prepared,
        i: usize,
        j: usize,
        ignore: &[usize],
        blockers: bool,
    ) -> f64 {
        let src = &sources.patches[i];
        let tgt = &self.targets.patches[j];
        let (sv, tv) = (&src.polygon.vertices, &tgt.polygon.vertices);
        let (Some(&s0), Some(&t0)) = (sv.first(), tv.first()) else {
            return 0.0;
        };
        // One-sided patches: nothing to do unless each is partly in front of the other.
        let tol = 1e-9 * (sources.bounds[i].radius + self.targets.bounds[j].radius);
        if !any_in_front(tv, src.normal, s0, tol) || !any_in_front(sv, tgt.normal, t0, tol) {
            return 0.0;
        }
        let shaft = blockers.then(|| self.occluders.shaft(sv, src.normal, tv, tgt.normal, ignore));
        let shaft = shaft.as_ref().filter(|shaft| !shaft.is_clear());
        let occluded = shaft.is_some();
        // A closed box that every segment between the two runs through hides the pair whole
        // (`bvh::Solid`): no shadow is cast at any point.
        if occluded && self.occluders.solid_hides(sv, tv) {
            return 0.0;
        }
        let touches = self.touches(src, sources.bounds[i], j);
        let cut = any_in_front(sv, -tgt.normal, t0, tol) && src.area > 0.0;
        // The target's plane cuts the source: only the part in front sees the target, and the
        // integrand has a kink on the cut, so integrate over that part alone.
        let front = cut.then(|| {
            kernel::SmallPolygon::<{ kernel::PATCH_CLIPPED }>::from_slice(sv).clip(t0, tgt.normal)
        });
        let region = front.as_ref().map_or(sv.as_slice(), |f| f.corners());
        // Touching, nearly touching or meeting in a T-junction: the kernel is singular on the
        // contact or varies on the scale of the gap, so the source is refined toward the target
        // until every cell is further from it than a multiple of its own size.
        // The part of the target in front of the source: the kernel clips the target there, so
        // that the clipping line is part of the outline it is singular on.
        let seen =
            kernel::SmallPolygon::<{ kernel::PATCH_CLIPPED }>::from_slice(tv).clip(s0, src.normal);
        let close = touches
            || self.refine_gaps
                && (sources.bounds[i].centre - self.targets.bounds[j].centre).length()
                    - self.targets.bounds[j].radius
                    - sources.bounds[i].radius
                    < 2.0 * GAP_RATIO * sources.bounds[i].radius
                && near::outline_distance(region, seen.corners())
                    < GAP_RATIO * near::diameter(region);
        // Sampled visibility: the unoccluded integral times one visible fraction for the pair
        // (module `sampled`); close pairs keep the shadows, whose edges they resolve.
        let fraction = match (self.opts.visibility, shaft) {
            (Visibility::Sampled { per_side }, Some(shaft)) if !close => {
                sampled::visible_fraction(self.occluders, shaft, src, tgt, per_side, ignore)
            }
            _ => None,
        };
        if fraction == Some(0.0) {
            return 0.0;
        }
        let shadows = shaft.filter(|_| fraction.is_none());
        let mut order = self.source_order(sources.bounds[i], j, touches);
        if shadows.is_some() && order <= self.opts.gauss_order {
            // One rule for every pair a blocker may cut (touching pairs keep their own).
            order = self.opts.occluded_order;
        }
        let mut sum = 0.0;
        let mut add = |point: Vec3, weight: f64| {
            let viewer = Viewer {
                point,
                normal: src.normal,
                cone: None,
            };
            sum += weight
                * match shadows {
                    Some(shaft) => self.visible_kernel(viewer, j, shaft, ignore),
                    None => self.kernel(viewer, j),
                };
        };
        if src.area > 0.0 && close {
            // A target's width: twice its area over its diameter (√2 × the side of a square).
            let width = 2.0 * tgt.area / near::diameter(tv).max(f64::MIN_POSITIVE);
            let refinement = Refinement {
                target: seen.corners(),
                tol,
                touching_size: width / f64::from(1u32 << (TOUCHING_DEPTH - 1)),
                ratio: if touches { TOUCHING_RATIO } else { GAP_RATIO },
            };
            self.integrate_near(region, &refinement, 0, 0, &mut |p, w| add(p, w / src.area));
        } else if let Some(front) = front {
            let gl = self.gauss_rule(order);
            quadrature::for_each_on_polygon(front.corners(), gl, |p, w| add(p, w / src.area));
        } else {
            for s in sources.samples.rule(i, order) {
                add(s.point, s.weight);
            }
        }
        sum * fraction.unwrap_or(1.0)
    }

    /// The Gauss–Legendre rule of `order` on [0, 1] (clamped to the orders prepared).
    fn gauss_rule(&self, order: usize) -> &[(f64, f64)] {
        let k = order.clamp(1, self.gauss.len().max(1)) - 1;
        self.gauss.get(k).map_or(&[], Vec::as_slice)
    }

    /// Unoccluded differential form factor from the viewer to target `j` (exact).
    pub(super) fn kernel(&self, v: Viewer, j: usize) -> f64 {
        let tgt = &self.targets.patches[j];
        self.kernel_on(v, &tgt.polygon.vertices, tgt.normal)
    }

    /// Differential form factor from the viewer to the part of target `j` that the shaft's
    /// occluders leave visible: exact ([`shadow`]), or the exact unoccluded kernel times a
    /// visible fraction estimated with rays when the shaft overflowed or the visible part is too
    /// fragmented for the fixed capacities.
    pub(super) fn visible_kernel(
        &self,
        v: Viewer,
        j: usize,
        shaft: &Shaft,
        ignore: &[usize],
    ) -> f64 {
        let tgt = &self.targets.patches[j];
        let exact = self.occluders.shaft_outlines(shaft).and_then(|outlines| {
            shadow::visible_sum(
                v.point,
                &tgt.polygon.vertices,
                tgt.normal,
                outlines,
                |piece| self.kernel_on(v, piece, tgt.normal),
            )
        });
        if let Some(k) = exact {
            return k;
        }
        let k = self.kernel(v, j);
        if k > 0.0 {
            k * self.visible_fraction(v, j, shaft, ignore)
        } else {
            0.0
        }
    }

    /// Unoccluded differential form factor from the viewer to a polygon (exact).
    fn kernel_on(&self, v: Viewer, corners: &[Vec3], normal: Vec3) -> f64 {
        match v.cone {
            None => kernel::point_to_polygon(v.point, v.normal, corners, normal),
            Some(cone) => {
                kernel::point_to_polygon_in_cone(v.point, v.normal, cone, corners, normal)
            }
        }
    }

    /// Fraction of target `j`'s contribution seen from the viewer that is not blocked, by rays
    /// refined at silhouettes ([`visibility`]).
    fn visible_fraction(&self, v: Viewer, j: usize, shaft: &Shaft, ignore: &[usize]) -> f64 {
        let tgt = &self.targets.patches[j];
        let fraction = visibility::Param::of(tgt).and_then(|target| {
            visibility::Query {
                occluders: self.occluders,
                shaft,
                point: v.point,
                normal: v.normal,
                cone: v.cone,
                target,
                target_normal: tgt.normal,
                ignore,
                depth: self.opts.visibility_depth,
                max_cell_share: self.opts.visibility_cell_share,
            }
            .visible_fraction()
        });
        // Other polygons, or only a grazing sliver in view: one ray to the centroid.
        fraction.unwrap_or_else(|| {
            if self
                .occluders
                .visible_in(shaft, v.point, tgt.centroid, ignore)
            {
                1.0
            } else {
                0.0
            }
        })
    }
}

/// Do the polygons touch: a corner of one within `tol` metres of an edge of the other?
fn touching(a: &[Vec3], b: &[Vec3], tol: f64) -> bool {
    let near_edge = |p: Vec3, poly: &[Vec3]| {
        (0..poly.len()).any(|k| {
            let (s, e) = (poly[k], poly[(k + 1) % poly.len()]);
            let d = e - s;
            let len2 = d.dot(d);
            let t = if len2 > 0.0 {
                ((p - s).dot(d) / len2).clamp(0.0, 1.0)
            } else {
                0.0
            };
            (p - (s + d * t)).length() <= tol
        })
    };
    a.iter().any(|&p| near_edge(p, b)) || b.iter().any(|&p| near_edge(p, a))
}

/// Is some corner strictly (more than `tol` metres) in front of the plane through `origin` with
/// unit normal `normal`?
fn any_in_front(corners: &[Vec3], normal: Vec3, origin: Vec3, tol: f64) -> bool {
    corners.iter().any(|&c| normal.dot(c - origin) > tol)
}
