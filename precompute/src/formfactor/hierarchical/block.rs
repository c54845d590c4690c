//! One block of the operator as numbers, and its part of a product.

use super::tree::BlockSpan;

/// How one block's numbers are stored (f32, column-major).
#[derive(Clone, Debug)]
pub(super) enum Data {
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
pub(super) struct Block {
    pub(super) span: BlockSpan,
    pub(super) data: Data,
}

impl Block {
    /// Entry `(a, b)` of the block (local indices).
    pub(super) fn at(&self, a: usize, b: usize) -> f64 {
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

    pub(super) fn bytes(&self) -> usize {
        4 * match &self.data {
            Data::Dense(d) => d.len(),
            Data::LowRank { u, v, .. } => u.len() + v.len(),
        }
    }

    /// `y[rows] += B x[cols]` and, off the diagonal, `y[cols] += Bᵀ x[rows]`, for `k` columns
    /// stored one after the other (`x` and `y` are `n × k`, column-major): the inner loops run
    /// along a block's column, the fastest way for a few columns.
    #[inline(always)]
    pub(super) fn product_by_columns(&self, n: usize, k: usize, x: &[f64], y: &mut [f64]) {
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

    /// `y[rows] += B x[cols]` and, off the diagonal, `y[cols] += Bᵀ x[rows]`, for `k` columns
    /// stored side by side (`x` and `y` are `n × k`, row-major: the `k` values of a row are
    /// adjacent): each stored number is read once for a chunk of columns, the inner loops run
    /// along the chunk's values, the fastest way for many columns. The columns go in chunks of
    /// 8, then 4, then one at a time, each of a width known when compiling, so that a chunk's
    /// sums stay in registers. Each column's sums run in the order of
    /// [`Block::product_by_columns`]: either gives the same bytes.
    #[inline(always)]
    pub(super) fn product_by_rows(&self, k: usize, x: &[f64], y: &mut [f64]) {
        let mut first = 0;
        while first < k {
            let left = k - first;
            if left >= 8 {
                self.chunk_by_rows::<8>(k, first, x, y);
                first += 8;
            } else if left >= 4 {
                self.chunk_by_rows::<4>(k, first, x, y);
                first += 4;
            } else {
                self.chunk_by_rows::<1>(k, first, x, y);
                first += 1;
            }
        }
    }

    /// [`Block::product_by_rows`] for the `W` columns from `first`.
    #[inline(always)]
    fn chunk_by_rows<const W: usize>(&self, k: usize, first: usize, x: &[f64], y: &mut [f64]) {
        let (rows, cols) = (self.span.rows.clone(), self.span.cols.clone());
        let mirror = !self.span.is_diagonal();
        let m = rows.len();
        let at = |p: usize| p * k + first;
        // One bounds check a row, none a value: the loops over `c` then vectorise.
        let load = |v: &[f64], p: usize| -> [f64; W] {
            let s = at(p);
            let mut row = [0.0; W];
            row.copy_from_slice(&v[s..s + W]);
            row
        };
        match &self.data {
            Data::Dense(d) => {
                for (b, column) in d.chunks_exact(m.max(1)).enumerate() {
                    let xb = load(x, cols.start + b);
                    let mut back = [0.0; W];
                    for (a, &e) in column.iter().enumerate() {
                        let e = f64::from(e);
                        let ya = at(rows.start + a);
                        if mirror {
                            let xa = load(x, rows.start + a);
                            for c in 0..W {
                                back[c] += e * xa[c];
                            }
                        }
                        let yr = &mut y[ya..ya + W];
                        for c in 0..W {
                            yr[c] += e * xb[c];
                        }
                    }
                    if mirror {
                        let yb = at(cols.start + b);
                        let yr = &mut y[yb..yb + W];
                        for c in 0..W {
                            yr[c] += back[c];
                        }
                    }
                }
            }
            Data::LowRank { rank, u, v } => {
                let nb = cols.len();
                for r in 0..*rank {
                    let (ur, vr) = (&u[r * m..(r + 1) * m], &v[r * nb..(r + 1) * nb]);
                    let mut t = [0.0; W];
                    let mut back = [0.0; W];
                    for (b, &e) in vr.iter().enumerate() {
                        let e = f64::from(e);
                        let xb = load(x, cols.start + b);
                        for c in 0..W {
                            t[c] += e * xb[c];
                        }
                    }
                    if mirror {
                        for (a, &e) in ur.iter().enumerate() {
                            let e = f64::from(e);
                            let xa = load(x, rows.start + a);
                            for c in 0..W {
                                back[c] += e * xa[c];
                            }
                        }
                    }
                    for (a, &e) in ur.iter().enumerate() {
                        let e = f64::from(e);
                        let ya = at(rows.start + a);
                        let yr = &mut y[ya..ya + W];
                        for c in 0..W {
                            yr[c] += e * t[c];
                        }
                    }
                    if mirror {
                        for (b, &e) in vr.iter().enumerate() {
                            let e = f64::from(e);
                            let yb = at(cols.start + b);
                            let yr = &mut y[yb..yb + W];
                            for c in 0..W {
                                yr[c] += e * back[c];
                            }
                        }
                    }
                }
            }
        }
    }
}
