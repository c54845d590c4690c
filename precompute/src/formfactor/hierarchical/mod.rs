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
//! - `stored`: the operator as numbers, for the form-factor cache.
//!
//! Assembly reads entries through a function of two patch indices, so that the form factors'
//! pair integrals (`super::patch_form_factors_hierarchical`) and the tests' matrices fill it
//! the same way.

mod aca;
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
use super::PairStats;
use crate::geometry::{Patch, Vec3};
use aca::Compressed;
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
}

impl Default for Settings {
    fn default() -> Self {
        Settings {
            leaf: 32,
            admissibility: 1.0,
            tolerance: 1e-6,
            split_by_sight: true,
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

/// How one block's numbers are stored (f32, column-major).
#[derive(Clone, Debug)]
enum Data {
    /// `m × n` entries.
    Dense(Vec<f32>),
    /// `U` (m × r) and `V` (n × r): the block is `U Vᵀ`.
    LowRank {
        rank: usize,
        u: Vec<f32>,
        v: Vec<f32>,
    },
}

#[derive(Clone, Debug)]
struct Block {
    span: BlockSpan,
    data: Data,
}

impl Block {
    /// Entry `(a, b)` of the block (local indices).
    fn at(&self, a: usize, b: usize) -> f64 {
        let m = self.span.rows.len();
        match &self.data {
            Data::Dense(d) => f64::from(d[b * m + a]),
            Data::LowRank { rank, u, v } => {
                let n = self.span.cols.len();
                (0..*rank)
                    .map(|k| f64::from(u[k * m + a]) * f64::from(v[k * n + b]))
                    .sum()
            }
        }
    }

    fn bytes(&self) -> usize {
        4 * match &self.data {
            Data::Dense(d) => d.len(),
            Data::LowRank { u, v, .. } => u.len() + v.len(),
        }
    }

    /// `y[rows] += B x[cols]` and, off the diagonal, `y[cols] += Bᵀ x[rows]`, for `k` columns
    /// stored one after the other (`x` and `y` are `n × k`, column-major).
    fn product(&self, n: usize, k: usize, x: &[f64], y: &mut [f64]) {
        let (rows, cols) = (self.span.rows.clone(), self.span.cols.clone());
        let mirror = !self.span.is_diagonal();
        let m = rows.len();
        for c in 0..k {
            let (xc, yc) = (&x[c * n..(c + 1) * n], &mut y[c * n..(c + 1) * n]);
            match &self.data {
                Data::Dense(d) => {
                    for (b, column) in d.chunks_exact(m.max(1)).enumerate() {
                        let xb = xc[cols.start + b];
                        let mut back = 0.0;
                        for (a, &e) in column.iter().enumerate() {
                            let e = f64::from(e);
                            yc[rows.start + a] += e * xb;
                            back += e * xc[rows.start + a];
                        }
                        if mirror {
                            yc[cols.start + b] += back;
                        }
                    }
                }
                Data::LowRank { rank, u, v } => {
                    let nb = cols.len();
                    for r in 0..*rank {
                        let (ur, vr) = (&u[r * m..(r + 1) * m], &v[r * nb..(r + 1) * nb]);
                        let t: f64 = vr
                            .iter()
                            .zip(&xc[cols.clone()])
                            .map(|(&e, x)| f64::from(e) * x)
                            .sum();
                        let s: f64 = ur
                            .iter()
                            .zip(&xc[rows.clone()])
                            .map(|(&e, x)| f64::from(e) * x)
                            .sum();
                        for (yi, &e) in yc[rows.clone()].iter_mut().zip(ur) {
                            *yi += f64::from(e) * t;
                        }
                        if mirror {
                            for (yj, &e) in yc[cols.clone()].iter_mut().zip(vr) {
                                *yj += f64::from(e) * s;
                            }
                        }
                    }
                }
            }
        }
    }
}

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
}

/// A non-finite entry met during assembly: the patches of the pair.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct NonFiniteEntry {
    /// The two patches.
    pub patches: [usize; 2],
}

/// Columns of a product that one task carries through every block, in order: each column's
/// sum runs over the blocks in one fixed order whatever the threads, so products are the same
/// bytes on any machine.
const COLUMNS_PER_TASK: usize = 4;

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
        // A pair integral counts a corner as in front of the source beyond 1e-9 of the sum of
        // the two patches' radii. Half of 1e-9 of the smallest radius is the most a cluster's
        // planes may spread, the most its normals may turn a height across the scene, and
        // the most a corner may stand in front of a dark pair's plane: together 1.5e-9 of
        // that radius, below every pair's own tolerance, so that a block called dark is one
        // whose pair integrals all return 0.
        let half = 0.5e-9
            * patches
                .iter()
                .map(smallest_radius)
                .fold(f64::INFINITY, f64::min);
        let tree = ClusterTree::new(patches, settings.leaf, half);
        let nothing_between = |_: &[Vec3], _: Vec3, _: &[Vec3], _: Vec3| true;
        let nothing_hides = |_: &[Vec3], _: &[Vec3]| false;
        let seeing = Seeing {
            clear: occlusion.map_or(&nothing_between, |o| o.clear),
            hidden: occlusion.map_or(&nothing_hides, |o| o.hidden),
            dark_tolerance: half,
        };
        let spans = tree::partition(&tree, settings, Some(&seeing));
        progress.set_length(spans.len() as u64);
        let order = &tree.order;
        let built: Vec<(Block, PairStats, Outcome)> = spans
            .into_par_iter()
            .enumerate()
            .map(|(index, span)| {
                let out = fill(span, order, settings, scaled, index as u64);
                progress.inc(1);
                out
            })
            .collect();
        let mut stats = PairStats::default();
        let mut compression = Compression::default();
        let mut blocks = Vec::with_capacity(built.len());
        let (mut rank_sum, mut low_rank_entries, mut read) = (0usize, 0usize, 0usize);
        for (block, block_stats, outcome) in built {
            stats.merge(block_stats);
            read += outcome.read;
            let entries = block.span.rows.len() * block.span.cols.len();
            match (block.span.kind, &block.data) {
                (Kind::Near, _) => compression.near_blocks += 1,
                (Kind::Far | Kind::Dark, Data::LowRank { rank, .. }) => {
                    compression.low_rank_blocks += 1;
                    compression.max_rank = compression.max_rank.max(*rank);
                    rank_sum += rank;
                    low_rank_entries += entries * if block.span.is_diagonal() { 1 } else { 2 };
                }
                (Kind::Far | Kind::Dark, Data::Dense(_)) if outcome.guarded => {
                    compression.guard_fallbacks += 1
                }
                (Kind::Far | Kind::Dark, Data::Dense(_)) => compression.rank_fallbacks += 1,
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

    /// `y = S x` in the tree's order, `k` columns (column-major, `n × k`), the blocks in their
    /// one order.
    fn scaled_product(&self, k: usize, x: &[f64], y: &mut [f64]) {
        let n = self.order.len();
        for block in &self.blocks {
            block.product(n, k, x, y);
        }
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

/// How one block's assembly went.
struct Outcome {
    /// Entries read through the pair integrals.
    read: usize,
    /// The guard fired.
    guarded: bool,
    /// A pair whose entry was not finite.
    non_finite: Option<[usize; 2]>,
}

/// Computes one block of the partition: whole if near, compressed if far.
fn fill(
    span: BlockSpan,
    order: &[usize],
    settings: &Settings,
    scaled: &(dyn Fn(usize, usize, &mut PairStats) -> f64 + Sync),
    seed: u64,
) -> (Block, PairStats, Outcome) {
    let stats = std::cell::RefCell::new(PairStats::default());
    let read = std::cell::Cell::new(0usize);
    let non_finite = std::cell::Cell::new(None);
    let (rows, cols) = (span.rows.clone(), span.cols.clone());
    let entry = |a: usize, b: usize| -> f64 {
        let (i, j) = (order[rows.start + a], order[cols.start + b]);
        if i == j {
            return 0.0;
        }
        read.set(read.get() + 1);
        let s = scaled(i, j, &mut stats.borrow_mut());
        if !s.is_finite() {
            non_finite.set(Some([i.min(j), i.max(j)]));
            return 0.0;
        }
        s
    };
    let (m, n) = (rows.len(), cols.len());
    let mut guarded = false;
    let data = match span.kind {
        Kind::Near if span.is_diagonal() => {
            // One value per pair, mirrored: the diagonal block is exactly symmetric.
            let mut d = vec![0.0f32; m * m];
            for b in 0..m {
                for a in 0..b {
                    let s = entry(a, b) as f32;
                    d[b * m + a] = s;
                    d[a * m + b] = s;
                }
            }
            Data::Dense(d)
        }
        Kind::Near => Data::Dense(dense_f32(m, n, &entry)),
        Kind::Dark => Data::LowRank {
            rank: 0,
            u: Vec::new(),
            v: Vec::new(),
        },
        Kind::Far => match aca::compress(m, n, &entry, settings.tolerance, seed) {
            Compressed::LowRank(approximation) => Data::LowRank {
                rank: approximation.rank(),
                u: column_major_f32(approximation.u.as_ref()),
                v: column_major_f32(approximation.v.as_ref()),
            },
            Compressed::Dense {
                entries,
                guarded: g,
            } => {
                guarded = g;
                Data::Dense(column_major_f32(entries.as_ref()))
            }
        },
    };
    let outcome = Outcome {
        read: read.get(),
        guarded,
        non_finite: non_finite.get(),
    };
    (Block { span, data }, stats.into_inner(), outcome)
}

/// A matrix's entries in f32, column after column.
fn column_major_f32(m: MatRef<'_, f64>) -> Vec<f32> {
    let mut out = Vec::with_capacity(m.nrows() * m.ncols());
    for j in 0..m.ncols() {
        for i in 0..m.nrows() {
            out.push(m[(i, j)] as f32);
        }
    }
    out
}

fn dense_f32(m: usize, n: usize, entry: &dyn Fn(usize, usize) -> f64) -> Vec<f32> {
    let mut d = Vec::with_capacity(m * n);
    for b in 0..n {
        for a in 0..m {
            d.push(entry(a, b) as f32);
        }
    }
    d
}

impl FormFactorOperator for Hierarchical {
    fn len(&self) -> usize {
        self.order.len()
    }

    fn apply(&self, mut out: MatMut<'_, f64>, rhs: MatRef<'_, f64>, par: Par) {
        let n = self.len();
        let k = rhs.ncols();
        let groups: Vec<Range<usize>> = (0..k)
            .step_by(COLUMNS_PER_TASK)
            .map(|c| c..(c + COLUMNS_PER_TASK).min(k))
            .collect();
        let one = |cols: &Range<usize>| -> Vec<f64> {
            // D x in the tree's order.
            let mut x = vec![0.0; n * cols.len()];
            for (c, col) in cols.clone().enumerate() {
                for (p, &i) in self.order.iter().enumerate() {
                    x[c * n + p] = self.root_area[i] * rhs[(i, col)];
                }
            }
            let mut y = vec![0.0; n * cols.len()];
            self.scaled_product(cols.len(), &x, &mut y);
            y
        };
        let results: Vec<Vec<f64>> = match par {
            Par::Seq => groups.iter().map(one).collect(),
            _ => groups.par_iter().map(one).collect(),
        };
        for (cols, y) in groups.iter().zip(&results) {
            for (c, col) in cols.clone().enumerate() {
                for (p, &i) in self.order.iter().enumerate() {
                    out[(i, col)] = self.root_area[i] * y[c * n + p];
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
