//! The hierarchical (H-matrix) form-factor operator: `G` stored as blocks over a cluster tree
//! of the patches, dense where clusters are close and low rank where they are well separated,
//! in single precision (docs/math.md, "The hierarchical operator").
//!
//! Like [`super::DenseF32`] it stores the symmetric `S = A^-½ G A^-½` (dimensionless) and
//! reports `G = D S D` with `D = diag(√A)`. Only one of each pair of blocks `(τ, σ)`, `(σ, τ)`
//! is stored, and diagonal blocks are filled from one value per pair, so the operator is
//! exactly symmetric: block Lanczos and conjugate gradients see a symmetric matrix.
//!
//! - `tree`: the cluster tree and the block partition;
//! - `aca`: the low-rank approximation of one block, its guard and its recompression;
//! - `block`: one block as numbers and its part of a product;
//! - `fill`: one block computed from the pair integrals (whole, low rank, or shaded);
//! - `census`: what the partition makes of a scene before any entry is read;
//! - `stored`: the operator as numbers, for the form-factor cache.
//!
//! Assembly reads entries through a function of two patch indices, so that the form factors'
//! pair integrals (`super::patch_form_factors_hierarchical`) and the tests' matrices fill it
//! the same way.

mod aca;
mod block;
mod census;
mod fill;
mod stored;
#[cfg(test)]
pub(in crate::formfactor) mod tests;
mod tree;

use std::ops::Range;

use faer::{MatMut, MatRef, Par};
use indicatif::ProgressBar;
use rayon::prelude::*;
use serde::Serialize;

use super::operator::FormFactorOperator;
use super::visibility::ClusterShares;
use super::PairStats;
use crate::geometry::{Patch, Vec3};
use block::{Block, Data};
pub use census::Census;
use fill::{fill, Filled, Outcome};
use tree::{BlockSpan, ClearBetween, ClusterTree, Kind, Seeing};

/// How the operator is built; `Default` gives the settings `--operator hierarchical` uses.
#[derive(Clone, Debug, PartialEq)]
pub struct Settings {
    /// Most patches in a leaf cluster. Default 32: blocks between leaves are small enough that
    /// computing them whole costs little, large enough that a block's bookkeeping is small
    /// against its entries.
    pub leaf: usize,
    /// Two clusters are well separated when the smaller box's diagonal is at most this
    /// multiple of the gap between the boxes (dimensionless). Default 1.
    pub admissibility: f64,
    /// Relative Frobenius error each low-rank block is approximated to (dimensionless).
    /// Default 1e-6.
    pub tolerance: f64,
    /// Classify each well-separated pair by what lies between its clusters before reading
    /// any entry (`tree` module docs): pairs facing away are 0 unread, pairs a blocker may
    /// cut are split further rather than approximated whole. Default true; false gives the
    /// partition by distance alone.
    pub split_by_sight: bool,
    /// Store each well-separated pair that a blocker may cut as its unoccluded entries times
    /// visible shares per patch from rays between the two clusters (`Occlusion::shade`)
    /// instead of splitting it down to blocks read whole: the pair integrals' shadows are left
    /// to close clusters, and the operator approximates the visibility of distant ones.
    /// Default false (exact).
    pub shade_mixed: bool,
    /// A shaded block whose rays stray from its visible shares by more than this (their
    /// misfit: the error they estimate in a patch's row over the other cluster, as a share
    /// of its output, dimensionless; docs/math.md) is split into its clusters' children and
    /// classified again, down to leaves read whole with their shadows. Default
    /// [`SHADE_MISFIT`]; infinity keeps every shaded block whole.
    pub shade_misfit: f64,
}

/// Version of the assembly: bumped whenever a change alters the operator built from the same
/// pair integrals and settings, so that the form-factor cache keys on it.
///
/// 2: blocks of clusters seen clear read their pairs one way, from the smaller patch;
/// shaded blocks split where their shares misfit ([`Settings::shade_misfit`]).
pub const ASSEMBLY_VERSION: usize = 2;

/// The default [`Settings::shade_misfit`].
pub const SHADE_MISFIT: f64 = 1e-3;

impl Default for Settings {
    fn default() -> Self {
        Settings {
            leaf: 32,
            admissibility: 1.0,
            tolerance: 1e-6,
            split_by_sight: true,
            shade_mixed: false,
            shade_misfit: SHADE_MISFIT,
        }
    }
}

/// What the compression made of the matrix, for the build report.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct Compression {
    /// Blocks computed entry by entry (close clusters).
    pub near_blocks: usize,
    /// Well-separated blocks stored low rank.
    pub low_rank_blocks: usize,
    /// Well-separated blocks computed whole because the guard found the cross approximation
    /// wrong.
    pub guard_fallbacks: usize,
    /// Well-separated blocks computed whole because no rank smaller than the block's own
    /// saved memory.
    pub rank_fallbacks: usize,
    /// Well-separated blocks that a blocker may cut, stored as their unoccluded entries times
    /// the clusters' visible fraction ([`Settings::shade_mixed`]).
    pub shaded_blocks: usize,
    /// Shaded blocks split because their rays strayed from their visible shares
    /// ([`Settings::shade_misfit`]).
    pub shade_splits: usize,
    /// The misfit above which they were split ([`Settings::shade_misfit`], dimensionless).
    pub shade_misfit: f64,
    /// Largest rank of a low-rank block.
    pub max_rank: usize,
    /// Mean rank of the low-rank blocks.
    pub mean_rank: f64,
    /// Share of the matrix's entries that lie in low-rank blocks (dimensionless).
    pub low_rank_share: f64,
    /// Entries read from the pair integrals, over `n²` (dimensionless): the cost of assembly
    /// against a dense matrix's.
    pub entries_read: f64,
    /// The measured error: the largest `‖row_H − row‖₂ / ‖row‖₂` over [`ROWS_CHECKED`] rows
    /// of `S` spread over the patches, each computed whole from the pair integrals
    /// (dimensionless).
    pub row_error: f64,
}

/// Rows of `S` that [`Compression::row_error`] compares with the pair integrals.
pub const ROWS_CHECKED: usize = 8;

/// The hierarchical operator (module docs).
#[derive(Clone, Debug)]
pub struct Hierarchical {
    /// The tree's nodes: positions and children.
    nodes: Vec<(Range<usize>, Option<[usize; 2]>)>,
    /// `order[position]` = patch.
    order: Vec<usize>,
    /// `position[patch]`.
    position: Vec<usize>,
    /// `√A_i` by patch, m.
    root_area: Vec<f64>,
    blocks: Vec<Block>,
    /// Blocks by their row cluster, and off-diagonal blocks by their column cluster.
    by_row: Vec<Vec<usize>>,
    by_col: Vec<Vec<usize>>,
    compression: Compression,
}

/// What lies between two planar polygons (corners in metres), for the partition's sight of
/// well-separated clusters (`tree` module docs).
pub(super) struct Occlusion<'a> {
    /// `clear(a, a_normal, b, b_normal)`: no blocker can cut a segment from `a` to `b` (the
    /// normals: the unit normals of their lit sides).
    pub(super) clear: &'a ClearBetween<'a>,
    /// `hidden(a, b)`: one blocker, or one closed box of blockers, cuts every segment from `a`
    /// to `b`.
    pub(super) hidden: &'a (dyn Fn(&[Vec3], &[Vec3]) -> bool + Sync),
    /// `unoccluded(i, j, stats)`: `S_ij` of two well-separated patches as if nothing stood
    /// between them, for the blocks seen clear ([`Kind::Clear`]) and the shaded ones
    /// ([`Settings::shade_mixed`]); it may read the pair one way and record nothing in `stats`.
    pub(super) unoccluded: &'a (dyn Fn(usize, usize, &mut PairStats) -> f64 + Sync),
    /// `shade(a, b)`: the share of the light between the patches `a` and those of `b`
    /// (patch indices) that no blocker cuts, as factors `r` (rows) and `c` (columns) by
    /// patch, the pair `(i, j)`'s share being `r_i c_j`, with the rays' misfit; for
    /// [`Settings::shade_mixed`] (dimensionless).
    pub(super) shade: &'a Shade<'a>,
}

/// [`Occlusion::shade`].
pub(super) type Shade<'a> = dyn Fn(&[usize], &[usize]) -> ClusterShares + Sync + 'a;

/// A non-finite entry met during assembly: the patches of the pair.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct NonFiniteEntry {
    /// The two patches.
    pub patches: [usize; 2],
}

/// Most columns of a product that one task carries through every block, in order. Each
/// column's sum runs over the blocks in one fixed order whatever the threads and the grouping,
/// so products are the same bytes on any machine; wider groups read the stored numbers fewer
/// times.
const MAX_COLUMNS_PER_TASK: usize = 32;

/// Groups of at least this many columns are multiplied with their values side by side
/// (`Block::product_by_rows`), smaller ones column after column: measured on a 5643-patch
/// floor, 8 columns a group (the eigensolve) take 0.63 of the time side by side, 3 columns (the
/// exact responses of 5 channels) 1.65 times as long (docs/performance.md, "What changed for
/// speed").
const ROW_MAJOR_FROM: usize = 4;

impl Hierarchical {
    /// Assembles the operator over `patches` from `scaled(i, j, stats)`, the entry `S_ij` of
    /// patches `i` and `j` (called with `i ≠ j` only; the diagonal is 0, as for flat
    /// patches), which records the pair's reciprocity in `stats`. `occlusion` says what lies
    /// between two planar polygons (`None` where nothing occludes). `progress` counts the
    /// blocks. Returns the reciprocity figures of the pairs read, merged in the partition's
    /// order.
    pub(super) fn assemble(
        patches: &[Patch],
        settings: &Settings,
        scaled: &(dyn Fn(usize, usize, &mut PairStats) -> f64 + Sync),
        occlusion: Option<&Occlusion>,
        progress: &ProgressBar,
    ) -> Result<(Hierarchical, PairStats), NonFiniteEntry> {
        let n = patches.len();
        let (tree, mut spans, half) = partitioned(patches, settings, occlusion);
        let seeing = seeing(occlusion, half);
        progress.set_length(spans.len() as u64);
        let order = &tree.order;
        // Round after round: the shaded blocks whose shares misfit come back unread and are
        // split once more, their children filled in the next round. Seeds count the blocks
        // over the rounds, in order: the same scene gives the same operator.
        let mut built: Vec<(Block, PairStats, Outcome)> = Vec::with_capacity(spans.len());
        let mut shade_splits = 0usize;
        while !spans.is_empty() {
            let first = built.len() + shade_splits;
            let round: Vec<Filled> = spans
                .into_par_iter()
                .enumerate()
                .map(|(index, span)| {
                    let seed = (first + index) as u64;
                    let out = fill(span, order, settings, scaled, occlusion, seed);
                    progress.inc(1);
                    out
                })
                .collect();
            spans = Vec::new();
            for filled in round {
                match filled {
                    Filled::Block(block, stats, outcome) => built.push((block, stats, outcome)),
                    Filled::Split(span) => {
                        shade_splits += 1;
                        spans.extend(tree::split_once(&tree, settings, Some(&seeing), &span));
                    }
                }
            }
            progress.inc_length(spans.len() as u64);
        }
        let mut stats = PairStats::default();
        let mut compression = Compression {
            shade_splits,
            shade_misfit: settings.shade_misfit,
            ..Compression::default()
        };
        let mut blocks = Vec::with_capacity(built.len());
        let (mut rank_sum, mut low_rank_entries, mut read) = (0usize, 0usize, 0usize);
        for (block, block_stats, outcome) in built {
            stats.merge(block_stats);
            read += outcome.read;
            let entries = block.span.rows.len() * block.span.cols.len();
            if block.span.kind == Kind::Shaded {
                compression.shaded_blocks += 1;
            }
            match (block.span.kind, &block.data) {
                (Kind::Near, _) => compression.near_blocks += 1,
                (
                    Kind::Far | Kind::Clear | Kind::Dark | Kind::Shaded,
                    Data::LowRank { rank, .. },
                ) => {
                    compression.low_rank_blocks += 1;
                    compression.max_rank = compression.max_rank.max(*rank);
                    rank_sum += rank;
                    low_rank_entries += entries * if block.span.is_diagonal() { 1 } else { 2 };
                }
                (Kind::Far | Kind::Clear | Kind::Dark | Kind::Shaded, Data::Dense(_))
                    if outcome.guarded =>
                {
                    compression.guard_fallbacks += 1
                }
                (Kind::Far | Kind::Clear | Kind::Dark | Kind::Shaded, Data::Dense(_)) => {
                    compression.rank_fallbacks += 1
                }
            }
            if let Some(pair) = outcome.non_finite {
                return Err(NonFiniteEntry { patches: pair });
            }
            blocks.push(block);
        }
        let total = (n * n).max(1) as f64;
        compression.mean_rank = if compression.low_rank_blocks > 0 {
            rank_sum as f64 / compression.low_rank_blocks as f64
        } else {
            0.0
        };
        compression.low_rank_share = low_rank_entries as f64 / total;
        compression.entries_read = read as f64 / total;
        let mut by_row = vec![Vec::new(); tree.nodes.len()];
        let mut by_col = vec![Vec::new(); tree.nodes.len()];
        for (b, block) in blocks.iter().enumerate() {
            by_row[block.span.row_node].push(b);
            if !block.span.is_diagonal() {
                by_col[block.span.col_node].push(b);
            }
        }
        let position = tree.positions();
        let mut h = Hierarchical {
            nodes: tree
                .nodes
                .into_iter()
                .map(|node| (node.range, node.children))
                .collect(),
            order: tree.order,
            position,
            root_area: patches.iter().map(|p| p.area.sqrt()).collect(),
            blocks,
            by_row,
            by_col,
            compression,
        };
        h.compression.row_error = h.row_error(scaled);
        Ok((h, stats))
    }

    /// [`Compression::row_error`]: rows `k n / ROWS_CHECKED` read whole, in parallel.
    fn row_error(&self, scaled: &(dyn Fn(usize, usize, &mut PairStats) -> f64 + Sync)) -> f64 {
        let n = self.len();
        let rows: Vec<usize> = (0..ROWS_CHECKED.min(n))
            .map(|k| k * n / ROWS_CHECKED)
            .collect();
        rows.par_iter()
            .map(|&i| {
                let mut stats = PairStats::default();
                let (mut err2, mut norm2) = (0.0, 0.0);
                for j in (0..n).filter(|&j| j != i) {
                    let exact = scaled(i, j, &mut stats);
                    err2 += (self.scaled_entry(i, j) - exact).powi(2);
                    norm2 += exact * exact;
                }
                if norm2 > 0.0 {
                    (err2 / norm2).sqrt()
                } else {
                    err2.sqrt()
                }
            })
            .collect::<Vec<f64>>()
            .into_iter()
            .fold(0.0, f64::max)
    }

    /// What the compression made of the matrix.
    pub fn compression(&self) -> &Compression {
        &self.compression
    }

    /// `S_ij` (dimensionless): the block holding the pair, found from the root down.
    fn scaled_entry(&self, i: usize, j: usize) -> f64 {
        let (a, b) = {
            let (p, q) = (self.position[i], self.position[j]);
            (p.min(q), p.max(q))
        };
        let mut node = 0;
        loop {
            for &k in &self.by_row[node] {
                let block = &self.blocks[k];
                if block.span.cols.contains(&b) {
                    return block.at(a - block.span.rows.start, b - block.span.cols.start);
                }
            }
            match self.nodes[node].1 {
                Some([l, r]) => node = if self.nodes[l].0.contains(&a) { l } else { r },
                None => return 0.0,
            }
        }
    }

    /// `y = S x` in the tree's order, `k` columns (`n × k`, row-major when `by_rows`, else
    /// column-major), the blocks in their one order.
    ///
    /// The loops are compiled once per vector width and run at the widest the machine has
    /// (`pulp::Arch`): the same additions and multiplications in the same order at every
    /// width (Rust never fuses a multiply and an add unasked), so the bytes do not depend on
    /// the machine.
    fn scaled_product(&self, k: usize, by_rows: bool, x: &[f64], y: &mut [f64]) {
        pulp::Arch::new().dispatch(ScaledProduct {
            operator: self,
            k,
            by_rows,
            x,
            y,
        });
    }
}

/// [`Hierarchical::scaled_product`]'s loops, compiled for each vector width: `with_simd` is
/// inlined into a function built for the width `S`, and so is everything it calls.
struct ScaledProduct<'a> {
    operator: &'a Hierarchical,
    k: usize,
    by_rows: bool,
    x: &'a [f64],
    y: &'a mut [f64],
}

impl pulp::WithSimd for ScaledProduct<'_> {
    type Output = ();

    #[inline(always)]
    fn with_simd<S: pulp::Simd>(self, _: S) {
        let ScaledProduct {
            operator,
            k,
            by_rows,
            x,
            y,
        } = self;
        let n = operator.order.len();
        for block in &operator.blocks {
            if by_rows {
                block.product_by_rows(k, x, y);
            } else {
                block.product_by_columns(n, k, x, y);
            }
        }
    }
}

/// The cluster tree over `patches` and the partition of its `S` into blocks, seen through
/// `occlusion` (module `tree`).
/// The cluster tree of `patches`, its partition, and the tolerance of its plates and of the
/// partition's sight ([`seeing`]), metres.
fn partitioned(
    patches: &[Patch],
    settings: &Settings,
    occlusion: Option<&Occlusion>,
) -> (ClusterTree, Vec<BlockSpan>, f64) {
    // A pair integral counts a corner as in front of the source beyond 1e-9 of the sum of
    // the two patches' radii. Half of 1e-9 of the smallest radius is the most a cluster's
    // planes may spread, the most its normals may turn a height across the scene, and the
    // most a corner may stand in front of a dark pair's plane: together 1.5e-9 of that
    // radius, below every pair's own tolerance, so that a block called dark is one whose pair
    // integrals all return 0.
    let half = 0.5e-9
        * patches
            .iter()
            .map(smallest_radius)
            .fold(f64::INFINITY, f64::min);
    let tree = ClusterTree::new(patches, settings.leaf, half);
    let spans = tree::partition(&tree, settings, Some(&seeing(occlusion, half)));
    (tree, spans, half)
}

/// What the partition sees between clusters: `occlusion`'s tests, or nothing in the way
/// where it is `None`; corners within `half` metres of a plane count as in it.
fn seeing<'a>(occlusion: Option<&'a Occlusion<'a>>, half: f64) -> Seeing<'a> {
    fn nothing_between(_: &[Vec3], _: Vec3, _: &[Vec3], _: Vec3) -> bool {
        true
    }
    fn nothing_hides(_: &[Vec3], _: &[Vec3]) -> bool {
        false
    }
    Seeing {
        clear: occlusion.map_or(&nothing_between, |o| o.clear),
        hidden: occlusion.map_or(&nothing_hides, |o| o.hidden),
        dark_tolerance: half,
    }
}

/// The distance from a patch's centroid to its farthest corner, metres (what the pair
/// integrals call its radius).
fn smallest_radius(p: &Patch) -> f64 {
    p.polygon
        .vertices
        .iter()
        .map(|&v| (v - p.centroid).length())
        .fold(0.0, f64::max)
}

impl FormFactorOperator for Hierarchical {
    fn len(&self) -> usize {
        self.order.len()
    }

    fn apply(&self, mut out: MatMut<'_, f64>, rhs: MatRef<'_, f64>, par: Par) {
        let n = self.len();
        let k = rhs.ncols();
        // One task per thread, each streaming the blocks once for its columns; the grouping
        // does not change the bytes (Block::product).
        let tasks = match par {
            Par::Seq => 1,
            _ => rayon::current_num_threads().max(1),
        };
        let width = k.div_ceil(tasks).clamp(1, MAX_COLUMNS_PER_TASK);
        let groups: Vec<Range<usize>> = (0..k)
            .step_by(width)
            .map(|c| c..(c + width).min(k))
            .collect();
        // Side by side from ROW_MAJOR_FROM columns a group (the same bytes either way).
        let by_rows = width >= ROW_MAJOR_FROM;
        let at = |p: usize, c: usize, w: usize| if by_rows { p * w + c } else { c * n + p };
        let one = |cols: &Range<usize>| -> Vec<f64> {
            // D x in the tree's order.
            let w = cols.len();
            let mut x = vec![0.0; n * w];
            for (c, col) in cols.clone().enumerate() {
                for (p, &i) in self.order.iter().enumerate() {
                    x[at(p, c, w)] = self.root_area[i] * rhs[(i, col)];
                }
            }
            let mut y = vec![0.0; n * w];
            self.scaled_product(w, by_rows, &x, &mut y);
            y
        };
        let results: Vec<Vec<f64>> = match par {
            Par::Seq => groups.iter().map(one).collect(),
            _ => groups.par_iter().map(one).collect(),
        };
        for (cols, y) in groups.iter().zip(&results) {
            let w = cols.len();
            for (c, col) in cols.clone().enumerate() {
                for (p, &i) in self.order.iter().enumerate() {
                    out[(i, col)] = self.root_area[i] * y[at(p, c, w)];
                }
            }
        }
    }

    fn entry(&self, i: usize, j: usize) -> f64 {
        // The product of the roots is commutative and S is stored once per pair: entry(i, j)
        // == entry(j, i) exactly.
        self.scaled_entry(i, j) * (self.root_area[i] * self.root_area[j])
    }

    fn row(&self, i: usize, out: &mut [f64]) {
        out.fill(0.0);
        let p = self.position[i];
        let mut node = Some(0);
        while let Some(t) = node {
            for &k in &self.by_row[t] {
                let block = &self.blocks[k];
                let a = p - block.span.rows.start;
                for (b, q) in block.span.cols.clone().enumerate() {
                    out[self.order[q]] = block.at(a, b);
                }
            }
            for &k in &self.by_col[t] {
                let block = &self.blocks[k];
                let b = p - block.span.cols.start;
                for (a, q) in block.span.rows.clone().enumerate() {
                    out[self.order[q]] = block.at(a, b);
                }
            }
            node = self.nodes[t]
                .1
                .map(|[l, r]| if self.nodes[l].0.contains(&p) { l } else { r });
        }
        for (j, x) in out.iter_mut().enumerate() {
            *x *= self.root_area[i] * self.root_area[j];
        }
    }

    fn stored_bytes(&self) -> usize {
        self.blocks.iter().map(Block::bytes).sum::<usize>()
            + 8 * (self.root_area.len() + self.order.len() + self.position.len())
    }

    fn storage(&self) -> &'static str {
        "hierarchical f32"
    }

    fn checked_when_built(&self) -> bool {
        true
    }
}
