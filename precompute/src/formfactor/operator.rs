//! The form-factor operator `G = A F` (m², symmetric) as the solvers see it: a product with a
//! block of vectors, its diagonal, its rows, and, where the operator is a dense f64 matrix,
//! that matrix for a factorisation or a dense eigensolver.
//!
//! Block Lanczos, conjugate gradients and the receivers' rows go through
//! [`FormFactorOperator`] only, so that an operator stored another way (single precision, or
//! compressed) is one new implementation of this trait. The model to follow is faer's
//! matrix-free `LinOp`: a product with a block, the dimensions, nothing about storage.

use faer::linalg::matmul::matmul;
use faer::reborrow::ReborrowMut;
use faer::{Accum, Mat, MatMut, MatRef, Par};

/// `G = A F` (m²) of a meshed scene, symmetric, as an operator on patch vectors.
///
/// Every implementation must be symmetric to the accuracy it states: the eigensolvers and
/// conjugate gradients rely on it.
pub trait FormFactorOperator: Send + Sync + std::fmt::Debug {
    /// Number of patches `n` (the operator is n × n).
    fn len(&self) -> usize;

    /// True for an empty scene.
    fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// `out = G rhs` for a block of vectors (`rhs` and `out` are n × k; m² times the unit of
    /// `rhs`).
    fn apply(&self, out: MatMut<'_, f64>, rhs: MatRef<'_, f64>, par: Par);

    /// `G_ij`, m². One entry at a time is slow for every storage but a dense one: the
    /// validation of inputs and the dense paths use it, the iterative ones do not.
    fn entry(&self, i: usize, j: usize) -> f64;

    /// Row `i` of `G` (= column `i`), m², into `out` (n values).
    fn row(&self, i: usize, out: &mut [f64]) {
        for (j, x) in out.iter_mut().enumerate() {
            *x = self.entry(i, j);
        }
    }

    /// The diagonal `G_ii` (m²): non-zero on curved or concave patches that see themselves.
    fn diagonal(&self) -> Vec<f64> {
        (0..self.len()).map(|i| self.entry(i, i)).collect()
    }

    /// The matrix itself, where the operator is a dense f64 matrix: the LU factorisation and
    /// the dense eigensolvers read it without a copy. `None` for other storage.
    fn dense(&self) -> Option<MatRef<'_, f64>> {
        None
    }

    /// Bytes the operator holds.
    fn stored_bytes(&self) -> usize;

    /// How the operator is stored, for reports: `dense f64`, `dense f32`.
    fn storage(&self) -> &'static str;

    /// `G x` for one vector, m² times the unit of `x`.
    fn apply_vector(&self, x: &[f64]) -> Vec<f64> {
        let rhs = MatRef::from_column_major_slice(x, x.len(), 1);
        let mut out = Mat::<f64>::zeros(self.len(), 1);
        self.apply(out.as_mut(), rhs, faer::get_global_parallelism());
        (0..self.len()).map(|i| out[(i, 0)]).collect()
    }

    /// Row sums of `F`, `Σ_j G_ij / A_i`: 1 for a patch inside a closed room.
    fn form_factor_row_sums(&self, area: &[f64]) -> Vec<f64> {
        let ones = vec![1.0; self.len()];
        self.apply_vector(&ones)
            .iter()
            .zip(area)
            .map(|(g, a)| g / a)
            .collect()
    }
}

/// The dense f64 matrix: 8 n² bytes, every product a matrix product.
impl FormFactorOperator for Mat<f64> {
    fn len(&self) -> usize {
        self.nrows()
    }

    fn apply(&self, out: MatMut<'_, f64>, rhs: MatRef<'_, f64>, par: Par) {
        matmul(out, Accum::Replace, self.as_ref(), rhs, 1.0, par);
    }

    fn entry(&self, i: usize, j: usize) -> f64 {
        self[(i, j)]
    }

    fn row(&self, i: usize, out: &mut [f64]) {
        for (j, x) in out.iter_mut().enumerate() {
            *x = self[(i, j)];
        }
    }

    fn dense(&self) -> Option<MatRef<'_, f64>> {
        Some(self.as_ref())
    }

    fn stored_bytes(&self) -> usize {
        8 * self.nrows() * self.ncols()
    }

    fn storage(&self) -> &'static str {
        "dense f64"
    }

    fn apply_vector(&self, x: &[f64]) -> Vec<f64> {
        // faer's matrix-vector product, the one every light source and readout used before
        // the operator existed: the same bytes.
        let gx = self * faer::ColRef::from_slice(x);
        (0..self.nrows()).map(|i| gx[i]).collect()
    }
}

/// The dense matrix in single precision: half the memory of f64, each entry rounded to
/// about 6e-8 relative. Products accumulate in f64.
#[derive(Debug, Clone)]
pub struct DenseF32 {
    g: Mat<f32>,
}

impl DenseF32 {
    /// `g` rounded to f32.
    pub fn from_f64(g: MatRef<'_, f64>) -> DenseF32 {
        DenseF32 {
            g: Mat::from_fn(g.nrows(), g.ncols(), |i, j| g[(i, j)] as f32),
        }
    }

    /// Columns of `G` converted to f64 a panel at a time, so that a product with a block
    /// runs as f64 matrix products over a bounded workspace.
    const PANEL: usize = 256;
}

impl FormFactorOperator for DenseF32 {
    fn len(&self) -> usize {
        self.g.nrows()
    }

    fn apply(&self, mut out: MatMut<'_, f64>, rhs: MatRef<'_, f64>, par: Par) {
        let n = self.g.nrows();
        out.fill(0.0);
        let mut panel = Mat::<f64>::zeros(n, Self::PANEL.min(n.max(1)));
        let mut start = 0;
        while start < n {
            let width = Self::PANEL.min(n - start);
            for j in 0..width {
                for i in 0..n {
                    panel[(i, j)] = f64::from(self.g[(i, start + j)]);
                }
            }
            matmul(
                out.rb_mut(),
                Accum::Add,
                panel.as_ref().get(.., 0..width),
                rhs.get(start..start + width, ..),
                1.0,
                par,
            );
            start += width;
        }
    }

    fn entry(&self, i: usize, j: usize) -> f64 {
        f64::from(self.g[(i, j)])
    }

    fn stored_bytes(&self) -> usize {
        4 * self.g.nrows() * self.g.ncols()
    }

    fn storage(&self) -> &'static str {
        "dense f32"
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn symmetric(n: usize) -> Mat<f64> {
        Mat::from_fn(n, n, |i, j| {
            let (a, b) = (i.min(j) as f64, i.max(j) as f64);
            0.01 + (a * 0.37 + b * 1.1).sin().abs()
        })
    }

    /// The f32 operator's product equals the f64 product of its own rounded entries (to f64
    /// rounding, 1e-13 relative), over more columns than one panel.
    #[test]
    fn f32_product_matches_rounded_matrix() {
        let n = 300;
        let g = symmetric(n);
        let op = DenseF32::from_f64(g.as_ref());
        let rounded = Mat::<f64>::from_fn(n, n, |i, j| op.entry(i, j));
        let x = Mat::<f64>::from_fn(n, 3, |i, c| ((i * (c + 2)) % 13) as f64 - 6.0);
        let mut want = Mat::<f64>::zeros(n, 3);
        rounded.apply(want.as_mut(), x.as_ref(), Par::Seq);
        let mut got = Mat::<f64>::zeros(n, 3);
        op.apply(got.as_mut(), x.as_ref(), Par::Seq);
        let scale = (0..n).fold(0.0f64, |s, i| s.max(want[(i, 0)].abs()));
        for c in 0..3 {
            for i in 0..n {
                let d = (got[(i, c)] - want[(i, c)]).abs() / scale;
                assert!(d < 1e-13, "({i}, {c}): {d:e}");
            }
        }
        // And each entry is the f64 entry to f32 rounding (2^-24 relative).
        for i in 0..n {
            for j in 0..n {
                assert!((op.entry(i, j) - g[(i, j)]).abs() <= g[(i, j)].abs() * 6.0e-8);
            }
        }
        assert_eq!(op.stored_bytes() * 2, g.stored_bytes());
    }

    /// The default row, diagonal and vector product agree with the dense matrix's own.
    #[test]
    fn default_methods_agree_with_dense() {
        let n = 40;
        let g = symmetric(n);
        let op = DenseF32::from_f64(g.as_ref());
        let mut row = vec![0.0; n];
        op.row(7, &mut row);
        for (j, x) in row.iter().enumerate() {
            assert_eq!(*x, op.entry(7, j));
        }
        let diag = op.diagonal();
        assert_eq!(diag[3], op.entry(3, 3));
        let x: Vec<f64> = (0..n).map(|i| i as f64).collect();
        let a = g.apply_vector(&x);
        let b = op.apply_vector(&x);
        for (p, q) in a.iter().zip(&b) {
            assert!((p - q).abs() <= 1e-6 * p.abs());
        }
        let area = vec![2.0; n];
        let sums = g.form_factor_row_sums(&area);
        let want: f64 = (0..n).map(|j| g[(5, j)]).sum::<f64>() / 2.0;
        assert!((sums[5] - want).abs() < 1e-12 * want);
    }
}
