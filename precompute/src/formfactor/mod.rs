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
//! - the outer integral (module `pair`) is a Gauss–Legendre rule on patch i (bilinear map for
//!   quadrilaterals, collapsed map for triangles) whose order falls with the distance between
//!   the patches ([`FormFactorOptions::quadrature_tolerance`]), is one common rule for all pairs
//!   a blocker may cut, and covers only the front part of i when j's plane cuts i. Where i
//!   touches j, comes closer to it than its own size or meets it in a T-junction, i is cut
//!   into cells refined toward j until each is further from j than its size (half of it next
//!   to a contact; module `near`: thin cells are first halved across their long side);
//! - `V_ij(x)` restricts the kernel to the part of j that no blocker hides from `x`. It is exact:
//!   the shadows of the blockers that can cut the pair (shaft culling, [`Occluders`]) are cut
//!   out of j, and the contour integral runs over the visible pieces (module `shadow`). Only when
//!   a shaft holds more blockers, or the visible part more pieces, than fixed capacities does it
//!   fall back to a visible fraction estimated by rays refined at silhouettes (module
//!   `visibility`). Pairs that no blocker can cut cost no visibility work at all. On request
//!   ([`Visibility::Sampled`], module `sampled`) a pair of patches that do not come close takes
//!   its unoccluded form factor times a visible fraction from a fixed grid of rays instead;
//!   with the hierarchical operator ([`Visibility::Clusters`]) a well-separated pair of
//!   clusters that a blocker may cut takes its unoccluded form factors times one visible
//!   share per patch from rays between the clusters (`visibility::between_clusters`).
//!
//! Both `F_ij` and `F_ji` are computed, and `G = A F` is symmetrised (see `docs/math.md`).

mod bvh;
mod closure;
pub(crate) use closure::cavities;
pub mod exchange;
mod health;
pub mod hierarchical;
mod kernel;
mod near;
pub mod operator;
pub mod outputs;
mod pair;
mod pairs;
mod quadrature;
mod rows;
mod sampled;
mod shadow;
#[cfg(test)]
mod tests;
mod visibility;

pub(crate) use bvh::Shaft;
pub use bvh::{Occluders, Solid};
pub use health::{
    CavityClosure, FormFactorHealth, PairDisagreement, RowMiss, CAVITY_TOLERANCE, CLOSED_TOLERANCE,
    WORST_ROWS,
};
pub use hierarchical::Hierarchical;
pub(crate) use kernel::point_to_polygon;
pub use operator::{DenseF32, FormFactorOperator, OperatorChoice, Storage};
pub use pairs::pair_exchanges;
pub use sampled::{Visibility, MAX_PER_SIDE};
// The patch rules and the exact visibility from a point, for the direct light of sources
// that are not patches (`crate::sources`).
pub use quadrature::gauss_legendre;
pub(crate) use quadrature::{for_each_on_cell, split_cell};
pub use rows::{point_form_factors, receiver_form_factors};
pub(crate) use shadow::visible_sum;

use crate::geometry::{Patch, Vec3};
use faer::Mat;
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use pair::{max_order, Context, Prepared};
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
    /// Folder of the form-factor cache ([`crate::cache`]) that [`crate::pipeline::prepare`]
    /// reads and fills; `None` (the default) computes the form factors every time.
    pub cache: Option<std::path::PathBuf>,
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
    /// How the visibility of a pair of patches that a blocker may cut is found
    /// (`--visibility`): exact shadows (the default) or a fixed grid of rays between the two
    /// patches ([`Visibility::Sampled`]; faster on scenes with many blockers, less accurate:
    /// `docs/performance.md`, "Sampled visibility"). Point sensors and grid points keep exact
    /// visibility.
    pub visibility: Visibility,
    /// With [`Visibility::Clusters`]: the misfit above which a shaded block is split
    /// (`--cluster-misfit`; [`hierarchical::Settings::shade_misfit`], dimensionless).
    pub cluster_misfit: f64,
    /// How the patch form factors are stored while the room is solved (`--operator`):
    /// f64, f32, or by size (the default). It does not enter the pair integrals.
    pub operator: OperatorChoice,
}

impl Default for FormFactorOptions {
    fn default() -> Self {
        FormFactorOptions {
            gauss_order: 5,
            progress: false,
            cache: None,
            touching_order: 6,
            quadrature_tolerance: 1e-6,
            visibility_depth: 4,
            visibility_cell_share: 1e-3,
            occluded_order: 5,
            visibility: Visibility::Exact,
            cluster_misfit: hierarchical::SHADE_MISFIT,
            operator: OperatorChoice::Auto,
        }
    }
}

/// Share of the smaller patch's output below which a pair's reciprocity mismatch is measured
/// against that share instead of the pair's own exchange.
const RECIPROCITY_FLOOR: f64 = 1e-3;

/// Result for a set of patches that are both the emitters, receivers and occluders.
#[derive(Clone, Debug)]
pub struct FormFactors<M = Mat<f64>> {
    /// F, n×n, row i = from patch i, after enforcing reciprocity: `A_i F_ij == A_j F_ji`
    /// (G = A F symmetrised by averaging G and Gᵀ). Dimensionless. In single precision
    /// ([`patch_form_factors_f32`]), `G` itself as its operator ([`DenseF32`]).
    pub matrix: M,
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
    /// The pairs whose two directions disagree most before symmetrising, worst first, at most
    /// [`WORST_PAIRS`]: `(i, j, share)` with `i < j` and the share as in
    /// [`FormFactors::reciprocity_share`]. Pairs that agree exactly are not listed.
    pub worst_pairs: Vec<(usize, usize, f64)>,
}

/// How many of the worst pairs [`FormFactors::worst_pairs`] keeps.
pub const WORST_PAIRS: usize = 5;

/// Version of the form-factor algorithm: bumped whenever a change alters the numbers
/// [`patch_form_factors`], [`receiver_form_factors`] or [`point_form_factors`] return for the
/// same patches and options, so that a cache of form factors can key on it.
///
/// 2: the outer integral is refined toward the outline of targets that come close without
/// touching, and toward thin targets; thin source cells are halved across their long side.
pub const ALGORITHM_VERSION: u32 = 2;

/// A progress bar on stderr, or a hidden one.
fn progress_bar(len: usize, show: bool, what: &str, unit: &str) -> ProgressBar {
    if !show {
        return ProgressBar::hidden();
    }
    let bar = ProgressBar::with_draw_target(Some(len as u64), ProgressDrawTarget::stderr());
    if let Ok(style) = ProgressStyle::with_template(&format!(
        "{{msg}} {{bar:40}} {{pos}}/{{len}} {unit}, {{elapsed}} (eta {{eta}})"
    )) {
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
    let mut m = raw_transposed::<f64>(patches, occluders, opts);
    let areas: Vec<f64> = patches.iter().map(|p| p.area).collect();
    let mut stats = PairStats::default();
    for j in 0..areas.len() {
        for i in 0..j {
            let (ai, aj) = (areas[i], areas[j]);
            let g = stats.add(i, j, ai * m[(j, i)], aj * m[(i, j)], ai, aj);
            m[(i, j)] = if ai > 0.0 { g / ai } else { 0.0 };
            m[(j, i)] = if aj > 0.0 { g / aj } else { 0.0 };
        }
    }
    let row_sums = row_sums(&m);
    FormFactors {
        matrix: m,
        reciprocity_mismatch: stats.worst,
        reciprocity_share: stats.worst_share,
        row_sums,
        worst_pairs: stats.worst_pairs,
    }
}

/// [`patch_form_factors_with`] stored in single precision as the operator itself
/// ([`DenseF32`]: `4 n²` bytes at every stage, the raw form factors included): the same pair
/// integrals, each raw value rounded to f32, symmetrised in f64 and rounded once more.
pub fn patch_form_factors_f32(
    patches: &[Patch],
    occluders: &Occluders,
    opts: &FormFactorOptions,
) -> FormFactors<DenseF32> {
    let mut m = raw_transposed::<f32>(patches, occluders, opts);
    let areas: Vec<f64> = patches.iter().map(|p| p.area).collect();
    let root: Vec<f64> = areas.iter().map(|a| a.sqrt()).collect();
    let mut stats = PairStats::default();
    for j in 0..areas.len() {
        for i in 0..j {
            let (ai, aj) = (areas[i], areas[j]);
            let gij = ai * f64::from(m[(j, i)]);
            let gji = aj * f64::from(m[(i, j)]);
            let g = stats.add(i, j, gij, gji, ai, aj);
            // Both halves of the pair from the one value: the stored matrix is symmetric.
            let scaled = (g / (root[i] * root[j])) as f32;
            m[(i, j)] = scaled;
            m[(j, i)] = scaled;
        }
    }
    let operator = DenseF32::from_scaled(m, root);
    let row_sums = operator.form_factor_row_sums(&areas);
    FormFactors {
        matrix: operator,
        reciprocity_mismatch: stats.worst,
        reciprocity_share: stats.worst_share,
        row_sums,
        worst_pairs: stats.worst_pairs,
    }
}

/// [`patch_form_factors_with`] stored as a hierarchical operator ([`Hierarchical`]): the same
/// pair integrals, but only for the pairs of close clusters and the rows and columns that the
/// low-rank approximation of well-separated clusters reads (`hierarchical::Settings`). Pairs
/// a blocker may cut are read both ways and symmetrised as in the dense matrix; pairs of
/// well-separated clusters that see each other clear one way, from the smaller patch. The
/// reciprocity figures are those of the pairs read both ways.
pub fn patch_form_factors_hierarchical(
    patches: &[Patch],
    occluders: &Occluders,
    opts: &FormFactorOptions,
    settings: &hierarchical::Settings,
) -> Result<FormFactors<Hierarchical>, hierarchical::NonFiniteEntry> {
    let shade = |a: &[usize], b: &[usize]| visibility::between_clusters(occluders, patches, a, b);
    hierarchical_shaded_by(patches, occluders, opts, settings, &shade)
}

/// [`patch_form_factors_hierarchical`] with the visible shares of shaded blocks from `shade`
/// (patch indices of the two clusters; `hierarchical::Occlusion::shade`).
fn hierarchical_shaded_by(
    patches: &[Patch],
    occluders: &Occluders,
    opts: &FormFactorOptions,
    settings: &hierarchical::Settings,
    shade: &hierarchical::Shade,
) -> Result<FormFactors<Hierarchical>, hierarchical::NonFiniteEntry> {
    let prepared = Prepared::new(patches, max_order(opts));
    let ctx = Context::new(&prepared, occluders, opts, true);
    let areas: Vec<f64> = patches.iter().map(|p| p.area).collect();
    let scaled = |i: usize, j: usize, stats: &mut PairStats| -> f64 {
        let (a, b) = (i.min(j), i.max(j));
        let gab = areas[a] * ctx.pair(&prepared, a, b, &[a, b]);
        let gba = areas[b] * ctx.pair(&prepared, b, a, &[a, b]);
        let g = stats.add(a, b, gab, gba, areas[a], areas[b]);
        g / (areas[a] * areas[b]).sqrt()
    };
    // Well-separated pairs only (the blocks of clusters seen clear, and the shaded ones): one
    // direction, from the patch of the smaller radius, whose outer quadrature is the more
    // accurate of the two (its error falls as a power of the source's size over the distance)
    // and the cheaper; the reciprocity figures are those of the pairs read both ways.
    let unoccluded = |i: usize, j: usize, _: &mut PairStats| -> f64 {
        let (a, b) = (i.min(j), i.max(j));
        let (from, to) = if prepared.radius(b) < prepared.radius(a) {
            (b, a)
        } else {
            (a, b)
        };
        let g = areas[from] * ctx.pair_unoccluded(&prepared, from, to);
        g / (areas[a] * areas[b]).sqrt()
    };
    let bar = progress_bar(0, opts.progress, "form factors", "blocks");
    let (operator, stats) = seen_through(occluders, &unoccluded, shade, |occlusion| {
        Hierarchical::assemble(patches, settings, &scaled, Some(occlusion), &bar)
    })?;
    bar.finish_and_clear();
    let row_sums = operator.form_factor_row_sums(&areas);
    Ok(FormFactors {
        matrix: operator,
        reciprocity_mismatch: stats.worst,
        reciprocity_share: stats.worst_share,
        row_sums,
        worst_pairs: stats.worst_pairs,
    })
}

/// `then` called with what lies between two clusters' rectangles among `occluders`, for the
/// hierarchical partition.
fn seen_through<R>(
    occluders: &Occluders,
    unoccluded: &(dyn Fn(usize, usize, &mut PairStats) -> f64 + Sync),
    shade: &hierarchical::Shade,
    then: impl FnOnce(&hierarchical::Occlusion) -> R,
) -> R {
    // The shaft between two clusters' rectangles, with nothing ignored: it holds every
    // blocker of every pair between them, so a clear one leaves all their pairs unoccluded.
    let clear = |a: &[Vec3], a_normal: Vec3, b: &[Vec3], b_normal: Vec3| {
        occluders.shaft(a, a_normal, b, b_normal, &[]).is_clear()
    };
    let hidden =
        |a: &[Vec3], b: &[Vec3]| occluders.one_blocker_hides(a, b) || occluders.solid_hides(a, b);
    then(&hierarchical::Occlusion {
        clear: &clear,
        hidden: &hidden,
        unoccluded,
        shade,
    })
}

/// How the hierarchical partition of `patches` among `occluders` divides the entries, before
/// any is read ([`hierarchical::Census`]).
pub fn partition_census(
    patches: &[Patch],
    occluders: &Occluders,
    settings: &hierarchical::Settings,
) -> hierarchical::Census {
    // The census reads no entry.
    let unread = |_: usize, _: usize, _: &mut PairStats| 0.0;
    let unseen = |_: &[usize], _: &[usize]| visibility::ClusterShares {
        rows: Vec::new(),
        cols: Vec::new(),
        misfit: 0.0,
    };
    seen_through(occluders, &unread, &unseen, |occlusion| {
        Hierarchical::census(patches, settings, Some(occlusion))
    })
}

/// Pairs [`occluded_share`] samples.
pub const SAMPLED_PAIRS: usize = 4096;

/// The share of the pairs of patches facing each other that have a blocker in their shaft
/// and are not hidden whole by a solid ([`Solid`], 0 at once) (dimensionless): [`SAMPLED_PAIRS`] pairs drawn from a fixed sequence, so that the same
/// scene gives the same figure. Such a pair's integral runs the exact visibility at every
/// quadrature point, about ten times a clear pair's work
/// ([`crate::pipeline::time_model::OCCLUDED_PAIR_COST`]).
pub fn occluded_share(patches: &[Patch], occluders: &Occluders) -> f64 {
    let n = patches.len() as u64;
    if n < 2 || occluders.is_empty() {
        return 0.0;
    }
    let mut state = 0x2545_F491_4F6C_DD1Du64;
    let mut draw = || {
        // splitmix64: a fixed sequence.
        state = state.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = state;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        ((z ^ (z >> 31)) % n) as usize
    };
    let in_front = |of: &Patch, corners: &[Vec3]| {
        let origin = of.polygon.vertices.first().copied().unwrap_or(of.centroid);
        corners.iter().any(|&c| of.normal.dot(c - origin) > 0.0)
    };
    let (mut facing, mut occluded) = (0usize, 0usize);
    for _ in 0..4 * SAMPLED_PAIRS {
        if facing == SAMPLED_PAIRS {
            break;
        }
        let (i, j) = (draw(), draw());
        let (a, b) = (&patches[i], &patches[j]);
        let (av, bv) = (&a.polygon.vertices, &b.polygon.vertices);
        if i == j || !in_front(a, bv) || !in_front(b, av) {
            continue;
        }
        facing += 1;
        if !occluders
            .shaft(av, a.normal, bv, b.normal, &[i, j])
            .is_clear()
            && !occluders.solid_hides(av, bv)
        {
            occluded += 1;
        }
    }
    if facing == 0 {
        0.0
    } else {
        occluded as f64 / facing as f64
    }
}

/// The raw form factors, transposed: `m[(j, i)] = F_ij` (the diagonal 0), column `i` holding
/// row `i` of F so that rows are filled in parallel contiguously.
fn raw_transposed<T: faer::traits::ComplexField + From<f32> + Send + Sync>(
    patches: &[Patch],
    occluders: &Occluders,
    opts: &FormFactorOptions,
) -> Mat<T>
where
    f64: StoreAs<T>,
{
    let n = patches.len();
    let prepared = Prepared::new(patches, max_order(opts));
    let ctx = Context::new(&prepared, occluders, opts, true);
    let bar = progress_bar(n, opts.progress, "form factors", "rows");
    let mut m = Mat::<T>::zeros(n, n);
    m.par_col_iter_mut().enumerate().for_each(|(i, mut col)| {
        for (j, x) in col.as_mut().iter_mut().enumerate() {
            *x = if i == j {
                T::from(0.0f32)
            } else {
                ctx.pair(&prepared, i, j, &[i, j]).store()
            };
        }
        bar.inc(1);
    });
    bar.finish_and_clear();
    m
}

/// A form factor (f64) stored as the matrix's entry type.
trait StoreAs<T> {
    fn store(self) -> T;
}

impl StoreAs<f64> for f64 {
    fn store(self) -> f64 {
        self
    }
}

impl StoreAs<f32> for f64 {
    fn store(self) -> f32 {
        self as f32
    }
}

/// The reciprocity figures of the raw pairs, gathered while they are symmetrised
/// ([`FormFactors::reciprocity_mismatch`], [`FormFactors::reciprocity_share`],
/// [`FormFactors::worst_pairs`]).
#[derive(Default)]
struct PairStats {
    worst: f64,
    worst_share: f64,
    worst_pairs: Vec<(usize, usize, f64)>,
}

impl PairStats {
    /// Records the pair `i < j` with raw exchange areas `gij = A_i F_ij` and `gji = A_j F_ji`
    /// (m²) and areas `ai`, `aj`; returns the symmetrised `G_ij = (gij + gji)/2` (docs/math.md).
    fn add(&mut self, i: usize, j: usize, gij: f64, gji: f64, ai: f64, aj: f64) -> f64 {
        let big = gij.max(gji).max(RECIPROCITY_FLOOR * ai.min(aj));
        if big > 0.0 {
            self.worst = self.worst.max((gij - gji).abs() / big);
            let share = (gij - gji).abs() / ai.min(aj);
            self.worst_share = self.worst_share.max(share);
            let last = self.worst_pairs.last().map_or(0.0, |w| w.2);
            let listed = self.worst_pairs.iter().any(|w| (w.0, w.1) == (i, j));
            if share > 0.0 && !listed && (self.worst_pairs.len() < WORST_PAIRS || share > last) {
                // Kept sorted, worst first; ties keep the earlier pair (deterministic).
                let at = self.worst_pairs.partition_point(|w| w.2 >= share);
                self.worst_pairs.insert(at, (i, j, share));
                self.worst_pairs.truncate(WORST_PAIRS);
            }
        }
        0.5 * (gij + gji)
    }

    /// Adds the figures of `other`, gathered over other pairs (or the same pairs again).
    fn merge(&mut self, other: PairStats) {
        self.worst = self.worst.max(other.worst);
        self.worst_share = self.worst_share.max(other.worst_share);
        for (i, j, share) in other.worst_pairs {
            let last = self.worst_pairs.last().map_or(0.0, |w| w.2);
            let listed = self.worst_pairs.iter().any(|w| (w.0, w.1) == (i, j));
            if !listed && (self.worst_pairs.len() < WORST_PAIRS || share > last) {
                let at = self.worst_pairs.partition_point(|w| w.2 >= share);
                self.worst_pairs.insert(at, (i, j, share));
                self.worst_pairs.truncate(WORST_PAIRS);
            }
        }
    }
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
