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
    /// adjacent): each stored number is read once for all `k` columns, the inner loops run
    /// along the `k` values, the fastest way for many columns. Each column's sums run in the
    /// order of [`Block::product_by_columns`]: either gives the same bytes.
    pub(super) fn product_by_rows(&self, k: usize, x: &[f64], y: &mut [f64]) {
        let (rows, cols) = (self.span.rows.clone(), self.span.cols.clone());
        let mirror = !self.span.is_diagonal();
        let m = rows.len();
        let row_of = |p: usize| p * k..(p + 1) * k;
        let mut back = vec![0.0; k];
        match &self.data {
            Data::Dense(d) => {
                for (b, column) in d.chunks_exact(m.max(1)).enumerate() {
                    back.fill(0.0);
                    let xb = row_of(cols.start + b);
                    for (a, &e) in column.iter().enumerate() {
                        let e = f64::from(e);
                        let ya = row_of(rows.start + a);
                        if mirror {
                            for (s, &xa) in back.iter_mut().zip(&x[ya.clone()]) {
                                *s += e * xa;
                            }
                        }
                        let (yr, xr) = (&mut y[ya], &x[xb.clone()]);
                        for (yi, &xi) in yr.iter_mut().zip(xr) {
                            *yi += e * xi;
                        }
                    }
                    if mirror {
                        for (yi, &s) in y[xb].iter_mut().zip(&back) {
                            *yi += s;
                        }
                    }
                }
            }
            Data::LowRank { rank, u, v } => {
                let nb = cols.len();
                let mut t = vec![0.0; k];
                for r in 0..*rank {
                    let (ur, vr) = (&u[r * m..(r + 1) * m], &v[r * nb..(r + 1) * nb]);
                    t.fill(0.0);
                    back.fill(0.0);
                    for (b, &e) in vr.iter().enumerate() {
                        let e = f64::from(e);
                        for (s, &xi) in t.iter_mut().zip(&x[row_of(cols.start + b)]) {
                            *s += e * xi;
                        }
                    }
                    if mirror {
                        for (a, &e) in ur.iter().enumerate() {
                            let e = f64::from(e);
                            for (s, &xi) in back.iter_mut().zip(&x[row_of(rows.start + a)]) {
                                *s += e * xi;
                            }
                        }
                    }
                    for (a, &e) in ur.iter().enumerate() {
                        let e = f64::from(e);
                        for (yi, &s) in y[row_of(rows.start + a)].iter_mut().zip(&t) {
                            *yi += e * s;
                        }
                    }
                    if mirror {
                        for (b, &e) in vr.iter().enumerate() {
                            let e = f64::from(e);
                            for (yi, &s) in y[row_of(cols.start + b)].iter_mut().zip(&back) {
                                *yi += e * s;
                            }
                        }
                    }
                }
            }
        }
    }
}
