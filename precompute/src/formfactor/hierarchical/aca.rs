//! Low-rank approximation of one admissible block from its entries: adaptive cross
//! approximation with partial pivoting, a guard against its one failure, and a recompression
//! by a small SVD (docs/math.md, "The hierarchical operator").
//!
//! ACA reads whole rows and columns of the block, one pivot at a time, and stops when the
//! newest cross is small against the approximation so far. It only sees the rows and columns
//! it reads: where occlusion or orientation leaves most of a block dark and a small part lit,
//! it can stop on a wrong answer. The guard reads a few rows and columns ACA did not choose,
//! at places drawn from a fixed seed, and where they disagree with the approximation the
//! block is computed entry by entry instead.

use faer::linalg::matmul::matmul;
use faer::{Accum, Mat, Par};

/// Probes of a dark row (or column) in a row before ACA concludes the rest of the block is
/// dark too.
const DARK_PROBES: usize = 6;

/// Rows and columns the guard reads (each).
pub(super) const GUARD_LINES: usize = 2;

/// The guard fires when the error it measures exceeds this multiple of the tolerance (relative
/// to the block's Frobenius norm). ACA's stopping rule estimates the error from its newest
/// cross, so the true error is of the order of the tolerance; ten times it is a wrong
/// approximation, not a loose one.
pub(super) const GUARD_FACTOR: f64 = 10.0;

/// A block `≈ U Vᵀ` (m × r and n × r).
#[derive(Clone, Debug)]
pub(super) struct LowRank {
    pub(super) u: Mat<f64>,
    pub(super) v: Mat<f64>,
}

impl LowRank {
    pub(super) fn rank(&self) -> usize {
        self.u.ncols()
    }

    /// Entry `(i, j)` of `U Vᵀ`.
    fn at(&self, i: usize, j: usize) -> f64 {
        (0..self.rank())
            .map(|k| self.u[(i, k)] * self.v[(j, k)])
            .sum()
    }
}

/// What [`compress`] made of a block.
#[derive(Clone, Debug)]
pub(super) enum Compressed {
    /// Low rank, recompressed.
    LowRank(LowRank),
    /// Every entry: ACA did not compress the block, or the guard fired.
    Dense {
        /// `m × n`.
        entries: Mat<f64>,
        /// The guard fired (rather than ACA running out of rank).
        guarded: bool,
    },
}

/// The block's `m × n` entries through `entry(i, j)` (local indices), approximated to a
/// relative Frobenius error of about `tolerance`, or computed whole (module docs). `seed`
/// fixes where the guard looks.
pub(super) fn compress(
    m: usize,
    n: usize,
    entry: &dyn Fn(usize, usize) -> f64,
    tolerance: f64,
    seed: u64,
) -> Compressed {
    // Entries are read once: a block computed whole after ACA or the guard reuses what they
    // read (each entry is two pair integrals).
    let memo = Memo::new(m, n);
    let entry = &|i: usize, j: usize| memo.get(i, j, entry);
    // A rank at which U and V hold half as many numbers as the block itself is the last worth
    // storing; past it, the crosses read are kept for the whole block.
    let max_rank = (m * n) / (2 * (m + n)).max(1);
    let dense = |guarded| Compressed::Dense {
        entries: Mat::from_fn(m, n, entry),
        guarded,
    };
    let Some(cross) = aca(m, n, entry, tolerance, max_rank) else {
        return dense(false);
    };
    if cross.approximation.rank() == 0 {
        // Every row and column ACA probed was dark. Blocks of clusters that face away from
        // each other are, and their entries cost next to nothing (the pair integrals stop at
        // the orientation test); a block lit through a gap ACA missed is not. Read it whole:
        // all zeros keep rank 0, anything else is the guard's catch.
        let entries = Mat::from_fn(m, n, entry);
        if entries.col_iter().all(|c| c.iter().all(|&x| x == 0.0)) {
            return Compressed::LowRank(cross.approximation);
        }
        return Compressed::Dense {
            entries,
            guarded: true,
        };
    }
    if guard_fires(&cross, m, n, entry, tolerance, seed) {
        return dense(true);
    }
    Compressed::LowRank(recompress(cross.approximation, tolerance))
}

/// Blocks up to this many entries remember every entry read (8 bytes each, 32 MB at most
/// per block being assembled); larger ones read again what a fallback needs.
const MEMO_ENTRIES: usize = 1 << 22;

/// The entries of one block read so far (NaN: not yet).
struct Memo {
    n: usize,
    values: Option<std::cell::RefCell<Vec<f64>>>,
}

impl Memo {
    fn new(m: usize, n: usize) -> Memo {
        let size = m.saturating_mul(n);
        Memo {
            n,
            values: (size <= MEMO_ENTRIES).then(|| std::cell::RefCell::new(vec![f64::NAN; size])),
        }
    }

    fn get(&self, i: usize, j: usize, entry: &dyn Fn(usize, usize) -> f64) -> f64 {
        let Some(values) = &self.values else {
            return entry(i, j);
        };
        let known = values.borrow()[i * self.n + j];
        if !known.is_nan() {
            return known;
        }
        let x = entry(i, j);
        values.borrow_mut()[i * self.n + j] = x;
        x
    }
}

/// ACA's result: the crosses and the squared Frobenius norm of their sum.
pub(super) struct Cross {
    pub(super) approximation: LowRank,
    norm2: f64,
}

/// Adaptive cross approximation with partial pivoting, to relative `tolerance` (stopping rule
/// `‖u_k‖ ‖v_k‖ ≤ tolerance ‖Σ u_l v_lᵀ‖_F`); `None` when it needs `max_rank` crosses.
pub(super) fn aca(
    m: usize,
    n: usize,
    entry: &dyn Fn(usize, usize) -> f64,
    tolerance: f64,
    max_rank: usize,
) -> Option<Cross> {
    let mut us: Vec<Vec<f64>> = Vec::new();
    let mut vs: Vec<Vec<f64>> = Vec::new();
    let mut used_row = vec![false; m];
    let mut used_col = vec![false; n];
    let mut norm2 = 0.0f64;
    let residual_row = |us: &[Vec<f64>], vs: &[Vec<f64>], i: usize| -> Vec<f64> {
        (0..n)
            .map(|j| entry(i, j) - us.iter().zip(vs).map(|(u, v)| u[i] * v[j]).sum::<f64>())
            .collect()
    };
    let residual_col = |us: &[Vec<f64>], vs: &[Vec<f64>], j: usize| -> Vec<f64> {
        (0..m)
            .map(|i| entry(i, j) - us.iter().zip(vs).map(|(u, v)| u[i] * v[j]).sum::<f64>())
            .collect()
    };
    let mut next_row = Some(0);
    let mut probe_col = 0usize;
    while let Some(mut i) = next_row {
        // A pivot row whose residual is not dark: the row asked for, else rows found through
        // columns (a dark row says nothing about the others).
        let mut pivot = None;
        for _ in 0..DARK_PROBES {
            used_row[i] = true;
            let row = residual_row(&us, &vs, i);
            if let Some(j) = largest(&row, &used_col).filter(|&j| !dark(row[j], norm2, m, n)) {
                pivot = Some((row, j));
                break;
            }
            // Through the next column not yet used: its largest residual names a lit row.
            let Some(j) = (0..n).map(|k| (probe_col + k) % n).find(|&k| !used_col[k]) else {
                break;
            };
            probe_col = (j + 1) % n.max(1);
            let col = residual_col(&us, &vs, j);
            match largest(&col, &used_row).filter(|&r| !dark(col[r], norm2, m, n)) {
                Some(r) => i = r,
                None => {
                    // The column is dark too: try the next row not yet used.
                    match (0..m).find(|&r| !used_row[r]) {
                        Some(r) => i = r,
                        None => break,
                    }
                }
            }
        }
        let Some((row, j)) = pivot else { break };
        used_col[j] = true;
        let v: Vec<f64> = row.iter().map(|x| x / row[j]).collect();
        let u = residual_col(&us, &vs, j);
        let (uu, vv) = (dot(&u, &u), dot(&v, &v));
        let cross: f64 = us
            .iter()
            .zip(&vs)
            .map(|(ul, vl)| dot(&u, ul) * dot(&v, vl))
            .sum();
        norm2 = (norm2 + uu * vv + 2.0 * cross).max(0.0);
        let converged = (uu * vv).sqrt() <= tolerance * norm2.sqrt();
        next_row = largest(&u, &used_row);
        us.push(u);
        vs.push(v);
        if converged {
            break;
        }
        if us.len() >= max_rank {
            return None;
        }
    }
    let r = us.len();
    Some(Cross {
        approximation: LowRank {
            u: Mat::from_fn(m, r, |i, k| us[k][i]),
            v: Mat::from_fn(n, r, |j, k| vs[k][j]),
        },
        norm2,
    })
}

/// A residual this small is rounding, not light: below 10⁻⁹ of the typical entry of the
/// approximation so far, or exactly zero before anything is found.
fn dark(x: f64, norm2: f64, m: usize, n: usize) -> bool {
    let typical = (norm2 / (m * n).max(1) as f64).sqrt();
    x.abs() <= 1e-9 * typical || x == 0.0
}

fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

/// The index of the largest magnitude among those not `used` (the first of equals).
fn largest(x: &[f64], used: &[bool]) -> Option<usize> {
    let mut best: Option<usize> = None;
    for (k, v) in x.iter().enumerate() {
        if !used[k] && best.is_none_or(|b| v.abs() > x[b].abs()) {
            best = Some(k);
        }
    }
    best
}

/// Reads [`GUARD_LINES`] rows and columns at positions drawn from `seed` and compares them
/// with the approximation: true when the block's error, estimated from them, exceeds
/// [`GUARD_FACTOR`] × `tolerance` × the block's norm.
pub(super) fn guard_fires(
    cross: &Cross,
    m: usize,
    n: usize,
    entry: &dyn Fn(usize, usize) -> f64,
    tolerance: f64,
    seed: u64,
) -> bool {
    let mut state = seed ^ 0x9E37_79B9_7F4A_7C15;
    let mut draw = |len: usize| {
        // splitmix64: a fixed sequence for a fixed seed.
        state = state.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = state;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        ((z ^ (z >> 31)) % len.max(1) as u64) as usize
    };
    let approx = &cross.approximation;
    let (mut err_rows, mut norm_rows, mut err_cols, mut norm_cols) = (0.0, 0.0, 0.0, 0.0);
    for _ in 0..GUARD_LINES {
        let i = draw(m);
        for j in 0..n {
            let e = entry(i, j);
            err_rows += (e - approx.at(i, j)).powi(2);
            norm_rows += e * e;
        }
        let j = draw(n);
        for i in 0..m {
            let e = entry(i, j);
            err_cols += (e - approx.at(i, j)).powi(2);
            norm_cols += e * e;
        }
    }
    // Each sample of lines stands for the whole block.
    let lines = GUARD_LINES as f64;
    let err2 = (err_rows * m as f64 / lines).max(err_cols * n as f64 / lines);
    let norm2 = cross
        .norm2
        .max(norm_rows * m as f64 / lines)
        .max(norm_cols * n as f64 / lines);
    err2.sqrt() > GUARD_FACTOR * tolerance * norm2.sqrt()
}

/// `U Vᵀ` brought to its smallest rank within relative Frobenius error `tolerance`: QR of
/// both factors, an SVD of the small core `R_U R_Vᵀ`, and the singular values whose tail is
/// below the tolerance dropped.
pub(super) fn recompress(lr: LowRank, tolerance: f64) -> LowRank {
    let k = lr.rank();
    if k == 0 {
        return lr;
    }
    let (qu, ru) = {
        let qr = lr.u.qr();
        (qr.compute_thin_Q(), qr.thin_R().to_owned())
    };
    let (qv, rv) = {
        let qr = lr.v.qr();
        (qr.compute_thin_Q(), qr.thin_R().to_owned())
    };
    let mut core = Mat::<f64>::zeros(ru.nrows(), rv.nrows());
    matmul(
        core.as_mut(),
        Accum::Replace,
        ru.as_ref(),
        rv.transpose(),
        1.0,
        Par::Seq,
    );
    let Ok(svd) = core.thin_svd() else {
        // The SVD did not converge (it does for finite input): keep the crosses as they are.
        return lr;
    };
    let sigma: Vec<f64> = svd.S().column_vector().iter().copied().collect();
    let total: f64 = sigma.iter().map(|s| s * s).sum();
    // Smallest r whose dropped tail Σ_{l ≥ r} σ_l² is within tolerance² of the total.
    let mut tail = total;
    let mut r = 0;
    while r < sigma.len() && tail > tolerance * tolerance * total {
        tail -= sigma[r] * sigma[r];
        r += 1;
    }
    let (w, z) = (svd.U(), svd.V());
    let mut u = Mat::<f64>::zeros(qu.nrows(), r);
    let mut v = Mat::<f64>::zeros(qv.nrows(), r);
    let ws = Mat::<f64>::from_fn(w.nrows(), r, |a, c| w[(a, c)] * sigma[c]);
    let zs = Mat::<f64>::from_fn(z.nrows(), r, |a, c| z[(a, c)]);
    matmul(
        u.as_mut(),
        Accum::Replace,
        qu.as_ref(),
        ws.as_ref(),
        1.0,
        Par::Seq,
    );
    matmul(
        v.as_mut(),
        Accum::Replace,
        qv.as_ref(),
        zs.as_ref(),
        1.0,
        Par::Seq,
    );
    LowRank { u, v }
}
