//! Form factors between patches, from points (sensors) and from non-blocking receivers, with
//! occlusion.
//!
//! `F_ij` (dimensionless) is the fraction of patch i's diffuse output that lands on patch j:
//!
//! ```text
//! F_ij = (1/A_i) ∫_{A_i} F_{dA→A_j}(x) V_ij(x) dA
//! ```
//!
//! - `F_{dA→A_j}` is exact: Lambert's contour integral over j clipped to the front half-space of
//!   `x` (module `kernel`; Howell's catalogue, Modest eq. 4.36);
//! - the outer integral is a Gauss–Legendre rule on patch i (bilinear map for quadrilaterals,
//!   collapsed map for triangles) whose order falls with the distance between the patches
//!   ([`FormFactorOptions::quadrature_tolerance`]), rises for touching patches, is one common
//!   rule for all pairs a blocker may cut, and covers only the front part of i when j's plane
//!   cuts i;
//! - `V_ij(x)` restricts the kernel to the part of j that no blocker hides from `x`. It is exact:
//!   the shadows of the blockers that can cut the pair (shaft culling, [`Occluders`]) are cut
//!   out of j, and the contour integral runs over the visible pieces (module `shadow`). Only when
//!   a shaft holds more blockers, or the visible part more pieces, than fixed capacities does it
//!   fall back to a visible fraction estimated by rays refined at silhouettes (module
//!   `visibility`). Pairs that no blocker can cut cost no visibility work at all.
//!
//! Both `F_ij` and `F_ji` are computed, and `G = A F` is symmetrised (see `docs/math.md`).

mod bvh;
pub mod exchange;
mod health;
mod kernel;
pub mod outputs;
mod quadrature;
mod shadow;
#[cfg(test)]
mod tests;
mod visibility;

pub use bvh::Occluders;
use bvh::Shaft;
pub use health::{FormFactorHealth, CLOSED_TOLERANCE};

use crate::geometry::{Patch, Vec3};
use faer::Mat;
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use kernel::Cone;
use quadrature::SampleTable;
use rayon::prelude::*;

/// Options; `Default` gives the accurate defaults.
#[derive(Clone, Debug)]
pub struct FormFactorOptions {
    /// Gauss–Legendre points per side on the emitting patch for near pairs (the highest order
    /// used for patches that do not touch). Default 5: order 4 leaves about 1.2e-5 relative
    /// error on the close pairs of the unit-cube references (raw reciprocity mismatch 1.2e-5),
    /// order 5 about 1e-6.
    pub gauss_order: usize,
    /// Show an indicatif progress bar on stderr.
    pub progress: bool,
    /// Points per side on the emitting patch when the two patches touch (share an edge or a
    /// corner): the kernel is not smooth there, so more points are needed for the same
    /// accuracy. Default 6 (about 2e-6 relative on a shared edge).
    pub touching_order: usize,
    /// Target relative error of the outer quadrature for distant pairs (dimensionless). The order
    /// for a pair is the smallest m with `(ORDER_SCALE · r_i / d)^(2m) ≤ tolerance`, `r_i` the
    /// source patch's radius and `d` the gap to the target (metres), capped by `gauss_order`.
    /// Default 1e-6.
    pub quadrature_tolerance: f64,
    /// For the ray fallback of visibility only (a shaft with more than 64 blockers): how often
    /// a cell of the target may be split in four where the rays to its corners and centre
    /// disagree (a blocker's silhouette crosses it). Default 4: silhouettes are resolved
    /// to 1/16 of the target's side; a target entirely in view or in shadow costs 5 rays.
    pub visibility_depth: u32,
    /// For the ray fallback of visibility only: cells of a target whose unoccluded form factor
    /// from the point exceeds this share are split even when all their rays agree
    /// (dimensionless). Default 1e-3.
    pub visibility_cell_share: f64,
    /// Outer-quadrature order on the emitting patch for every pair that a blocker may cut
    /// (except touching pairs). All such pairs of a row share the rule: their summed kernel ×
    /// visibility is smooth over the source even where each term jumps at a shadow edge, so the
    /// row still sums to 1. Default 5.
    pub occluded_order: usize,
}

impl Default for FormFactorOptions {
    fn default() -> Self {
        FormFactorOptions {
            gauss_order: 5,
            progress: false,
            touching_order: 6,
            quadrature_tolerance: 1e-6,
            visibility_depth: 4,
            visibility_cell_share: 1e-3,
            occluded_order: 5,
        }
    }
}

/// Scale in the error model of the outer quadrature (see
/// [`FormFactorOptions::quadrature_tolerance`]). A conservative choice, not a fit: the empty
/// 412-patch test room keeps its row sums within 1e-5 with it.
const ORDER_SCALE: f64 = 0.5;

/// Splits of a source cell toward a target it touches (`Context::integrate_toward`).
const TOUCHING_DEPTH: u32 = 4;

/// Share of the smaller patch's output below which a pair's reciprocity mismatch is measured
/// against that share instead of the pair's own exchange.
const RECIPROCITY_FLOOR: f64 = 1e-3;

/// Result for a set of patches that are both the emitters, receivers and occluders.
#[derive(Clone, Debug)]
pub struct FormFactors {
    /// F, n×n, row i = from patch i, after enforcing reciprocity: `A_i F_ij == A_j F_ji`
    /// (G = A F symmetrised by averaging G and Gᵀ). Dimensionless.
    pub matrix: Mat<f64>,
    /// Worst reciprocity mismatch of the raw matrix before symmetrising:
    /// max over pairs of `|A_i F_ij − A_j F_ji| / max(A_i F_ij, A_j F_ji, 10⁻³ min(A_i, A_j))`.
    /// The floor keeps pairs that exchange almost nothing (a sliver seen past a blocker) from
    /// dominating: their mismatch counts relative to 0.1 % of the smaller patch's output.
    /// Dimensionless.
    pub reciprocity_mismatch: f64,
    /// The same disagreement as a share of the patches' output: max over pairs of
    /// `|A_i F_ij − A_j F_ji| / min(A_i, A_j)`, the most light (as a fraction of the smaller
    /// patch's total output) that the two directions assign differently. This is what
    /// symmetrising moves, so it bounds how far it can shift a row sum by one pair.
    /// Dimensionless.
    pub reciprocity_share: f64,
    /// Row sums of the symmetrised matrix (1 for every patch of a closed scene).
    pub row_sums: Vec<f64>,
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
struct Prepared<'a> {
    patches: &'a [Patch],
    bounds: Vec<Bound>,
    samples: SampleTable,
}

impl<'a> Prepared<'a> {
    fn new(patches: &'a [Patch], max_order: usize) -> Self {
        Prepared {
            patches,
            bounds: patches.iter().map(Bound::of).collect(),
            samples: SampleTable::new(patches, max_order),
        }
    }
}

/// Gauss–Legendre rules of orders 1 to `max` on [0, 1].
fn gauss_rules(max: usize) -> Vec<Vec<(f64, f64)>> {
    (1..=max.max(1)).map(quadrature::gauss_legendre).collect()
}

/// The largest order any rule on a set of patches needs.
fn max_order(opts: &FormFactorOptions) -> usize {
    opts.gauss_order
        .max(opts.touching_order)
        .max(opts.occluded_order)
        .max(1)
}

/// Everything needed to evaluate form factors towards the scene patches.
struct Context<'a> {
    targets: &'a Prepared<'a>,
    /// Gauss–Legendre rules on [0, 1] of orders 1, 2, … (index = order − 1).
    gauss: Vec<Vec<(f64, f64)>>,
    occluders: &'a Occluders,
    opts: &'a FormFactorOptions,
}

/// A point (or differential area) that looks at the targets.
#[derive(Clone, Copy)]
struct Viewer<'c> {
    point: Vec3,
    normal: Vec3,
    cone: Option<&'c Cone>,
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

    /// Integrates `f(point, weight in m²)` over the convex `cell` of a source, splitting cells
    /// that touch `target` (within `tol` metres) `depth` more times; cells clear of it take the
    /// near-pair rule (`gauss_order`), the finest touching cells `touching_order`.
    fn integrate_toward(
        &self,
        cell: &[Vec3],
        target: &[Vec3],
        tol: f64,
        depth: u32,
        f: &mut dyn FnMut(Vec3, f64),
    ) {
        let touching_cell = touching(cell, target, tol);
        if depth == 0 || !touching_cell {
            let order = if touching_cell {
                self.opts.touching_order
            } else {
                self.opts.gauss_order
            };
            quadrature::for_each_on_cell(cell, self.gauss_rule(order), &mut *f);
            return;
        }
        for sub in quadrature::split_cell(cell) {
            self.integrate_toward(&sub, target, tol, depth - 1, f);
        }
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
    fn pair(&self, sources: &Prepared, i: usize, j: usize, ignore: &[usize]) -> f64 {
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
        let shaft = self.occluders.shaft(sv, src.normal, tv, tgt.normal, ignore);
        let occluded = !shaft.is_clear();
        let touches = self.touches(src, sources.bounds[i], j);
        let mut order = self.source_order(sources.bounds[i], j, touches);
        if occluded && order <= self.opts.gauss_order {
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
                * if occluded {
                    self.visible_kernel(viewer, j, &shaft, ignore)
                } else {
                    self.kernel(viewer, j)
                };
        };
        let cut = any_in_front(sv, -tgt.normal, t0, tol) && src.area > 0.0;
        // The target's plane cuts the source: only the part in front sees the target, and the
        // integrand has a kink on the cut, so integrate over that part alone.
        let front = cut.then(|| {
            kernel::SmallPolygon::<{ kernel::PATCH_CLIPPED }>::from_slice(sv).clip(t0, tgt.normal)
        });
        let region = front.as_ref().map_or(sv.as_slice(), |f| f.corners());
        if src.area > 0.0 && touches {
            // The kernel is singular along the contact: cells that touch the target are split
            // down to 1/2^TOUCHING_DEPTH of the source's side, so that a contact along part of
            // an edge (a T-junction of the mesh) or at a corner is resolved as well as one
            // along a whole edge.
            self.integrate_toward(region, tv, tol, TOUCHING_DEPTH, &mut |p, w| {
                add(p, w / src.area)
            });
        } else if let Some(front) = front {
            let gl = self.gauss_rule(order);
            quadrature::for_each_on_polygon(front.corners(), gl, |p, w| add(p, w / src.area));
        } else {
            for s in sources.samples.rule(i, order) {
                add(s.point, s.weight);
            }
        }
        sum
    }

    /// The Gauss–Legendre rule of `order` on [0, 1] (clamped to the orders prepared).
    fn gauss_rule(&self, order: usize) -> &[(f64, f64)] {
        let k = order.clamp(1, self.gauss.len().max(1)) - 1;
        self.gauss.get(k).map_or(&[], Vec::as_slice)
    }

    /// Unoccluded differential form factor from the viewer to target `j` (exact).
    fn kernel(&self, v: Viewer, j: usize) -> f64 {
        let tgt = &self.targets.patches[j];
        self.kernel_on(v, &tgt.polygon.vertices, tgt.normal)
    }

    /// Differential form factor from the viewer to the part of target `j` that the shaft's
    /// occluders leave visible: exact ([`shadow`]), or the exact unoccluded kernel times a
    /// visible fraction estimated with rays when the shaft overflowed or the visible part is too
    /// fragmented for the fixed capacities.
    fn visible_kernel(&self, v: Viewer, j: usize, shaft: &Shaft, ignore: &[usize]) -> f64 {
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

/// A progress bar on stderr, or a hidden one.
fn progress_bar(len: usize, show: bool, what: &str) -> ProgressBar {
    if !show {
        return ProgressBar::hidden();
    }
    let bar = ProgressBar::with_draw_target(Some(len as u64), ProgressDrawTarget::stderr());
    if let Ok(style) =
        ProgressStyle::with_template("{msg} {bar:40} {pos}/{len} rows, {elapsed} (eta {eta})")
    {
        bar.set_style(style);
    }
    bar.set_message(what.to_string());
    bar
}

/// Form factors between all patches of a scene (emitters, receivers and occluders at once).
/// Builds the [`Occluders`] itself; see [`patch_form_factors_with`] to reuse them.
pub fn patch_form_factors(patches: &[Patch], opts: &FormFactorOptions) -> FormFactors {
    let occluders = Occluders::new(patches);
    patch_form_factors_with(patches, &occluders, opts)
}

/// [`patch_form_factors`] with occluders built beforehand from the same `patches`.
pub fn patch_form_factors_with(
    patches: &[Patch],
    occluders: &Occluders,
    opts: &FormFactorOptions,
) -> FormFactors {
    let n = patches.len();
    let prepared = Prepared::new(patches, max_order(opts));
    let ctx = Context {
        targets: &prepared,
        gauss: gauss_rules(max_order(opts)),
        occluders,
        opts,
    };
    let bar = progress_bar(n, opts.progress, "form factors");
    // Column i holds row i of the raw F, so that rows are filled in parallel contiguously.
    let mut m = Mat::<f64>::zeros(n, n);
    m.par_col_iter_mut().enumerate().for_each(|(i, mut col)| {
        for (j, x) in col.as_mut().iter_mut().enumerate() {
            *x = if i == j {
                0.0
            } else {
                ctx.pair(&prepared, i, j, &[i, j])
            };
        }
        bar.inc(1);
    });
    bar.finish_and_clear();
    let areas: Vec<f64> = patches.iter().map(|p| p.area).collect();
    let (reciprocity_mismatch, reciprocity_share) = symmetrise_transposed(&mut m, &areas);
    let row_sums = row_sums(&m);
    FormFactors {
        matrix: m,
        reciprocity_mismatch,
        reciprocity_share,
        row_sums,
    }
}

/// Turns `m` holding the raw Fᵀ (`m[(j, i)] = F_ij`) into the symmetrised F in place:
/// `G = A F`, `G_sym = (G + Gᵀ)/2`, `F = A⁻¹ G_sym` (docs/math.md). Returns the worst reciprocity
/// mismatch of the raw matrix, relative and as a share of the output
/// ([`FormFactors::reciprocity_mismatch`], [`FormFactors::reciprocity_share`]).
fn symmetrise_transposed(m: &mut Mat<f64>, areas: &[f64]) -> (f64, f64) {
    let n = areas.len();
    let mut worst = 0.0_f64;
    let mut worst_share = 0.0_f64;
    for j in 0..n {
        for i in 0..j {
            let (ai, aj) = (areas[i], areas[j]);
            let gij = ai * m[(j, i)];
            let gji = aj * m[(i, j)];
            let big = gij.max(gji).max(RECIPROCITY_FLOOR * ai.min(aj));
            if big > 0.0 {
                worst = worst.max((gij - gji).abs() / big);
                worst_share = worst_share.max((gij - gji).abs() / ai.min(aj));
            }
            let g = 0.5 * (gij + gji);
            m[(i, j)] = if ai > 0.0 { g / ai } else { 0.0 };
            m[(j, i)] = if aj > 0.0 { g / aj } else { 0.0 };
        }
    }
    (worst, worst_share)
}

/// Row sums of a square matrix, summed column by column (contiguous in faer's layout).
fn row_sums(m: &Mat<f64>) -> Vec<f64> {
    let mut sums = vec![0.0; m.nrows()];
    for j in 0..m.ncols() {
        for (i, s) in sums.iter_mut().enumerate() {
            *s += m[(i, j)];
        }
    }
    sums
}

/// Differential element (a point sensor at `point`, metres, facing the unit `normal`, optional
/// field-of-view half-angle in radians: only directions within that cone of the normal count)
/// to every patch: `F_sj` (dimensionless) such that irradiance `E = Σ_j F_sj M_j` (W/m² from
/// exitances in W/m², or lux from lm/m²). With occlusion by `occluders`.
pub fn point_form_factors(
    point: Vec3,
    normal: Vec3,
    half_angle: Option<f64>,
    patches: &[Patch],
    occluders: &Occluders,
) -> Vec<f64> {
    let opts = FormFactorOptions::default();
    let targets = Prepared::new(patches, max_order(&opts));
    let ctx = Context {
        targets: &targets,
        gauss: gauss_rules(max_order(&opts)),
        occluders,
        opts: &opts,
    };
    let normal = normal.normalized();
    let cone = half_angle.and_then(|a| Cone::new(normal, a));
    let viewer = Viewer {
        point,
        normal,
        cone: cone.as_ref(),
    };
    (0..patches.len())
        .into_par_iter()
        .map(|j| {
            let k = ctx.kernel(viewer, j);
            if k <= 0.0 {
                return 0.0;
            }
            let tgt = &patches[j];
            let shaft = occluders.shaft(&[point], normal, &tgt.polygon.vertices, tgt.normal, &[j]);
            if !shaft.is_clear() {
                ctx.visible_kernel(viewer, j, &shaft, &[j])
            } else {
                k
            }
        })
        .collect()
}

/// Receiving patches that do not block light (e.g. a work plane) to every scene patch, with
/// occlusion by the scene patches: rows = receivers, `F_rj` (dimensionless, fraction of the
/// receiver's hemispherical view, front side only), `n_receivers × n`.
pub fn receiver_form_factors(
    receivers: &[Patch],
    patches: &[Patch],
    occluders: &Occluders,
    opts: &FormFactorOptions,
) -> Mat<f64> {
    let targets = Prepared::new(patches, max_order(opts));
    let sources = Prepared::new(receivers, opts.gauss_order);
    let ctx = Context {
        targets: &targets,
        gauss: gauss_rules(max_order(opts)),
        occluders,
        opts,
    };
    let bar = progress_bar(receivers.len(), opts.progress, "receivers");
    let rows: Vec<Vec<f64>> = (0..receivers.len())
        .into_par_iter()
        .map(|r| {
            let row = (0..patches.len())
                .map(|j| ctx.pair(&sources, r, j, &[j]))
                .collect();
            bar.inc(1);
            row
        })
        .collect();
    bar.finish_and_clear();
    Mat::from_fn(receivers.len(), patches.len(), |r, j| rows[r][j])
}
