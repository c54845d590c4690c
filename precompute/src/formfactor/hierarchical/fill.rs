//! Computing one block of the partition from the pair integrals: whole, by cross
//! approximation, or shaded.

use faer::{Mat, MatRef};

use super::aca::{self, Compressed};
use super::block::{Block, Data};
use super::tree::{BlockSpan, Kind};
use super::{Occlusion, Settings};
use crate::formfactor::PairStats;

/// How one block's assembly went.
pub(super) struct Outcome {
    /// Entries read through the pair integrals.
    pub(super) read: usize,
    /// The guard fired.
    pub(super) guarded: bool,
    /// A pair whose entry was not finite.
    pub(super) non_finite: Option<[usize; 2]>,
}

/// What became of one block of the partition.
pub(super) enum Filled {
    /// The block, computed.
    Block(Block, PairStats, Outcome),
    /// A shaded block whose rays stray from its visible shares by more than
    /// [`Settings::shade_misfit`]: nothing read, to be split into its clusters' children.
    Split(BlockSpan),
}

/// Computes one block of the partition: whole if near, compressed if far, and if shaded
/// ([`Settings::shade_mixed`]) its unoccluded entries compressed, each times its pair's
/// visible share `r_i c_j` ([`Occlusion::shade`]), unless the shares' misfit sends it back
/// to be split.
pub(super) fn fill(
    span: BlockSpan,
    order: &[usize],
    settings: &Settings,
    scaled: &(dyn Fn(usize, usize, &mut PairStats) -> f64 + Sync),
    occlusion: Option<&Occlusion>,
    seed: u64,
) -> Filled {
    let (rows, cols) = (span.rows.clone(), span.cols.clone());
    let shares = match (span.kind, occlusion) {
        (Kind::Shaded, Some(o)) => Some((o.shade)(&order[rows.clone()], &order[cols.clone()])),
        _ => None,
    };
    if shares
        .as_ref()
        .is_some_and(|s| s.misfit > settings.shade_misfit)
    {
        return Filled::Split(span);
    }
    let shares = shares.map(|s| (s.rows, s.cols));
    let source = match (span.kind, occlusion) {
        (Kind::Shaded | Kind::Clear, Some(o)) => o.unoccluded,
        _ => scaled,
    };
    let stats = std::cell::RefCell::new(PairStats::default());
    let read = std::cell::Cell::new(0usize);
    let non_finite = std::cell::Cell::new(None);
    let entry = |a: usize, b: usize| -> f64 {
        let (i, j) = (order[rows.start + a], order[cols.start + b]);
        if i == j {
            return 0.0;
        }
        read.set(read.get() + 1);
        let s = source(i, j, &mut stats.borrow_mut());
        if !s.is_finite() {
            non_finite.set(Some([i.min(j), i.max(j)]));
            return 0.0;
        }
        s
    };
    let (m, n) = (rows.len(), cols.len());
    let unlit = Data::LowRank {
        rank: 0,
        u: Vec::new(),
        v: Vec::new(),
    };
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
        Kind::Dark => unlit,
        // No ray gets through: nothing to read.
        Kind::Shaded
            if shares
                .as_ref()
                .is_some_and(|(r, _)| r.iter().all(|&x| x == 0.0)) =>
        {
            unlit
        }
        Kind::Far | Kind::Clear | Kind::Shaded => {
            let shares = shares.as_ref().map(|(r, c)| (r.as_slice(), c.as_slice()));
            let (data, g) = compressed(m, n, &entry, settings.tolerance, seed, shares);
            guarded = g;
            data
        }
    };
    let outcome = Outcome {
        read: read.get(),
        guarded,
        non_finite: non_finite.get(),
    };
    Filled::Block(Block { span, data }, stats.into_inner(), outcome)
}

/// A far block from its entries through the cross approximation, entry `(a, b)` times
/// `r_a c_b` where `scales` gives `(r, c)`; and whether the guard fired.
fn compressed(
    m: usize,
    n: usize,
    entry: &dyn Fn(usize, usize) -> f64,
    tolerance: f64,
    seed: u64,
    scales: Option<(&[f64], &[f64])>,
) -> (Data, bool) {
    let (r, c) = scales.unwrap_or((&[], &[]));
    let scale = |factors: &[f64], k: usize| factors.get(k).copied().unwrap_or(1.0);
    match aca::compress(m, n, entry, tolerance, seed) {
        Compressed::LowRank(approximation) => {
            let u = Mat::from_fn(m, approximation.rank(), |a, k| {
                approximation.u[(a, k)] * scale(r, a)
            });
            let v = Mat::from_fn(n, approximation.rank(), |b, k| {
                approximation.v[(b, k)] * scale(c, b)
            });
            (
                Data::LowRank {
                    rank: approximation.rank(),
                    u: column_major_f32(u.as_ref()),
                    v: column_major_f32(v.as_ref()),
                },
                false,
            )
        }
        Compressed::Dense { entries, guarded } => {
            let scaled = Mat::from_fn(m, n, |a, b| entries[(a, b)] * scale(r, a) * scale(c, b));
            (Data::Dense(column_major_f32(scaled.as_ref())), guarded)
        }
    }
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
