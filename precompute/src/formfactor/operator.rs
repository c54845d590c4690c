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

    /// True when the operator checked its entries finite and stores each pair once, so that
    /// the solvers' input check need not read all `n²` entries (which for a compressed
    /// operator costs far more than building it).
    fn checked_when_built(&self) -> bool {
        false
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

/// How the form-factor operator is stored (`--operator`; the help texts are the command
/// line's).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default, clap::ValueEnum)]
pub enum OperatorChoice {
    /// f64 up to [`crate::memory::AUTO_HIERARCHICAL_ABOVE`] patches, hierarchical above.
    #[default]
    #[value(
        help = "f64 up to 5792 patches (where the form-factor cache keeps it), hierarchical above (a quarter to a half of dense f32 there)"
    )]
    Auto,
    /// The dense f64 matrix, `8 n²` bytes.
    #[value(help = "The dense matrix in f64: 8 n² bytes")]
    Dense,
    /// The dense f32 matrix ([`DenseF32`]), `4 n²` bytes.
    #[value(
        help = "The dense matrix in f32: 4 n² bytes, entries within 2⁻²⁴ of the f64 ones (not cached)"
    )]
    DenseF32,
    /// The hierarchical operator ([`super::Hierarchical`]): blocks of close clusters whole,
    /// well-separated ones at low rank, in f32.
    #[value(
        help = "Compressed (H-matrix): close clusters whole, distant ones at low rank within 1e-6, in f32 (cached while its entry stays within 256 MiB, 8 bytes a stored number)"
    )]
    Hierarchical,
}

// The help names the threshold: keep them together.
const _: () = assert!(crate::memory::AUTO_HIERARCHICAL_ABOVE == 5792);

/// How an operator is stored.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Storage {
    /// Dense, f64.
    F64,
    /// Dense, f32.
    F32,
    /// Hierarchical, f32 ([`super::Hierarchical`]).
    Hierarchical,
}

impl OperatorChoice {
    /// The storage this choice takes for `patches` patches.
    pub fn storage(self, patches: usize) -> Storage {
        match self {
            OperatorChoice::Dense => Storage::F64,
            OperatorChoice::DenseF32 => Storage::F32,
            OperatorChoice::Hierarchical => Storage::Hierarchical,
            OperatorChoice::Auto if patches > crate::memory::AUTO_HIERARCHICAL_ABOVE => {
                Storage::Hierarchical
            }
            OperatorChoice::Auto => Storage::F64,
        }
    }

    /// Why this choice takes [`Self::storage`] for `patches` patches, as the build says it.
    pub fn reason(self, patches: usize) -> String {
        let above = crate::memory::AUTO_HIERARCHICAL_ABOVE;
        match self {
            OperatorChoice::Dense => "--operator dense".to_string(),
            OperatorChoice::DenseF32 => "--operator dense-f32".to_string(),
            OperatorChoice::Hierarchical => "--operator hierarchical".to_string(),
            OperatorChoice::Auto if patches > above => {
                format!("auto: {patches} patches, above {above}, where it holds a quarter to a half of a dense f32 matrix")
            }
            OperatorChoice::Auto => {
                format!("auto: {patches} patches, at most {above}, in f64 where the form-factor cache keeps it")
            }
        }
    }
}

impl Storage {
    /// The name the report gives it, as [`FormFactorOperator::storage`] does.
    pub fn name(self) -> &'static str {
        match self {
            Storage::F64 => "dense f64",
            Storage::F32 => "dense f32",
            Storage::Hierarchical => "hierarchical f32",
        }
    }

    /// Bytes the operator of `patches` patches is expected to hold (the memory model's figure,
    /// [`crate::memory`]).
    pub fn operator_bytes(self, patches: f64) -> f64 {
        match self {
            Storage::F64 => 8.0 * patches * patches,
            Storage::F32 => 4.0 * patches * patches,
            Storage::Hierarchical => crate::memory::hierarchical_bytes(patches),
        }
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

/// The dense matrix in single precision: half the memory of f64 (`4 n²` bytes). It stores
/// the symmetric `S = A^-½ G A^-½` (dimensionless, each pair rounded once from its one
/// symmetrised value), so that every entry `G_ij = S_ij √(A_i A_j)` it reports is exactly
/// symmetric and within `2⁻²⁴` relative of the f64 value. Products accumulate in f64.
#[derive(Debug, Clone)]
pub struct DenseF32 {
    /// `S`, n × n, f32.
    scaled: Mat<f32>,
    /// `√A_i`, m.
    root_area: Vec<f64>,
}

impl DenseF32 {
    /// Columns of `S` converted to f64 a panel at a time, so that a product with a block
    /// runs as f64 matrix products over a bounded workspace.
    const PANEL: usize = 256;

    /// The operator of `S` (symmetric, n × n) and `√A` (m, n values).
    #[track_caller]
    pub fn from_scaled(scaled: Mat<f32>, root_area: Vec<f64>) -> DenseF32 {
        assert!(
            scaled.nrows() == root_area.len() && scaled.ncols() == root_area.len(),
            "DenseF32: S is {} × {}, √A has {} values",
            scaled.nrows(),
            scaled.ncols(),
            root_area.len()
        );
        DenseF32 { scaled, root_area }
    }

    /// `g` (n × n, symmetric, m²) rounded to single precision, over patches of areas `area`
    /// (m²). Pairs are read from the upper triangle, so the result is symmetric even where
    /// `g` is only symmetric to rounding.
    pub fn from_f64(g: MatRef<'_, f64>, area: &[f64]) -> DenseF32 {
        let root: Vec<f64> = area.iter().map(|a| a.sqrt()).collect();
        let scaled = Mat::from_fn(g.nrows(), g.ncols(), |i, j| {
            let (a, b) = (i.min(j), i.max(j));
            (g[(a, b)] / (root[a] * root[b])) as f32
        });
        DenseF32::from_scaled(scaled, root)
    }
}

impl FormFactorOperator for DenseF32 {
    fn len(&self) -> usize {
        self.scaled.nrows()
    }

    fn apply(&self, mut out: MatMut<'_, f64>, rhs: MatRef<'_, f64>, par: Par) {
        // G x = D S D x with D = diag(√A).
        let n = self.len();
        let root = &self.root_area;
        let scaled_rhs = Mat::<f64>::from_fn(n, rhs.ncols(), |i, c| root[i] * rhs[(i, c)]);
        out.fill(0.0);
        let mut panel = Mat::<f64>::zeros(n, Self::PANEL.min(n.max(1)));
        let mut start = 0;
        while start < n {
            let width = Self::PANEL.min(n - start);
            for j in 0..width {
                for i in 0..n {
                    panel[(i, j)] = f64::from(self.scaled[(i, start + j)]);
                }
            }
            matmul(
                out.rb_mut(),
                Accum::Add,
                panel.as_ref().get(.., 0..width),
                scaled_rhs.as_ref().get(start..start + width, ..),
                1.0,
                par,
            );
            start += width;
        }
        for c in 0..out.ncols() {
            for i in 0..n {
                out[(i, c)] *= root[i];
            }
        }
    }

    fn entry(&self, i: usize, j: usize) -> f64 {
        // The product of the roots is commutative, so entry(i, j) == entry(j, i) exactly.
        f64::from(self.scaled[(i, j)]) * (self.root_area[i] * self.root_area[j])
    }

    fn stored_bytes(&self) -> usize {
        4 * self.scaled.nrows() * self.scaled.ncols() + 8 * self.root_area.len()
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

    fn areas(n: usize) -> Vec<f64> {
        (0..n).map(|i| 0.5 + ((i * 7) % 5) as f64 * 0.3).collect()
    }

    /// Each entry of the f32 operator is the f64 entry within f32 rounding (2⁻²⁴ relative,
    /// twice: S rounded, then scaled back), exactly symmetric, and its product equals the f64
    /// product of its own entries (to 1e-13 relative) over more columns than one panel.
    #[test]
    fn f32_entries_and_products() {
        let n = 300;
        let g = symmetric(n);
        let area = areas(n);
        let op = DenseF32::from_f64(g.as_ref(), &area);
        for i in 0..n {
            for j in 0..n {
                let e = op.entry(i, j);
                assert_eq!(e.to_bits(), op.entry(j, i).to_bits(), "({i}, {j})");
                assert!(
                    (e - g[(i, j)]).abs() <= g[(i, j)].abs() * 1.2e-7,
                    "({i}, {j})"
                );
            }
        }
        let own = Mat::<f64>::from_fn(n, n, |i, j| op.entry(i, j));
        let x = Mat::<f64>::from_fn(n, 3, |i, c| ((i * (c + 2)) % 13) as f64 - 6.0);
        let mut want = Mat::<f64>::zeros(n, 3);
        own.apply(want.as_mut(), x.as_ref(), Par::Seq);
        let mut got = Mat::<f64>::zeros(n, 3);
        op.apply(got.as_mut(), x.as_ref(), Par::Seq);
        let scale = (0..n).fold(0.0f64, |s, i| s.max(want[(i, 0)].abs()));
        for c in 0..3 {
            for i in 0..n {
                let d = (got[(i, c)] - want[(i, c)]).abs() / scale;
                assert!(d < 1e-13, "({i}, {c}): {d:e}");
            }
        }
        assert_eq!(op.stored_bytes(), g.stored_bytes() / 2 + 8 * n);
        assert_eq!(op.storage(), "dense f32");
    }

    /// The default row, diagonal, vector product and row sums agree with the dense matrix's
    /// own to f32 rounding.
    #[test]
    fn default_methods_agree_with_dense() {
        let n = 40;
        let g = symmetric(n);
        let area = areas(n);
        let op = DenseF32::from_f64(g.as_ref(), &area);
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
            assert!((p - q).abs() <= 2.4e-7 * p.abs());
        }
        let sums = g.form_factor_row_sums(&area);
        let want: f64 = (0..n).map(|j| g[(5, j)]).sum::<f64>() / area[5];
        assert!((sums[5] - want).abs() < 1e-12 * want);
        let sums32 = op.form_factor_row_sums(&area);
        assert!((sums32[5] - want).abs() < 2.4e-7 * want);
    }
}
