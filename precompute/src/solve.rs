//! Exact reference solve of the radiosity equation for one band (math.md, "Notation"):
//! `M = M0 + R F M`, so `M = (I − R F)⁻¹ M0` (seed eq. 6–7), by LU with partial pivoting.
//!
//! This is the baseline every truncated basis is measured against, and the "exact per-channel
//! response" lighting practice uses when the emitter channels are fixed (math.md, "Sharper
//! still").

use crate::eigen::{check_inputs, EigenError};
use faer::linalg::solvers::{PartialPivLu, Solve};
use faer::{Mat, MatRef};

/// Factorisation of `I − R F` (`F = A⁻¹ G`) for one band; solves for any number of emission
/// patterns. Black patches (`ρ = 0`) are handled by the same equation: their row is the
/// identity, so `M_k = M0_k`.
#[derive(Debug)]
pub struct ExactSolver {
    n: usize,
    lu: PartialPivLu<f64>,
}

impl ExactSolver {
    /// Factorises `I − R F` with `(R F)_ij = ρ_i G_ij / A_i` (`G` in m², `A` in m²).
    ///
    /// Inputs are checked as for [`crate::eigen::modes`] (symmetric finite `G`, `A > 0`,
    /// `ρ ∈ [0, 1)`). `O(n³)`.
    pub fn new(g: MatRef<'_, f64>, area: &[f64], reflectance: &[f64]) -> Result<Self, EigenError> {
        check_inputs(g, area, reflectance)?;
        let n = g.nrows();
        let a = Mat::<f64>::from_fn(n, n, |i, j| {
            let id = if i == j { 1.0 } else { 0.0 };
            id - reflectance[i] / area[i] * g[(i, j)]
        });
        let lu = a.partial_piv_lu();
        // With ρ < 1 and row sums of F ≤ 1 the matrix is diagonally dominant; a zero pivot
        // means the inputs broke that (e.g. F rows summing far above 1).
        let u = lu.U();
        if let Some(pivot) = (0..n).find(|&i| !(u[(i, i)].abs() > 0.0 && u[(i, i)].is_finite())) {
            return Err(EigenError::Singular { pivot });
        }
        Ok(Self { n, lu })
    }

    /// Number of patches.
    pub fn len(&self) -> usize {
        self.n
    }

    /// True for an empty scene.
    pub fn is_empty(&self) -> bool {
        self.n == 0
    }

    /// `M = (I − R F)⁻¹ M0` for one emission pattern (`M0` in W/m² or lm/m²).
    #[track_caller]
    pub fn solve(&self, m0: &[f64]) -> Vec<f64> {
        assert!(
            m0.len() == self.n,
            "ExactSolver::solve: m0 has {} entries, expected {}",
            m0.len(),
            self.n
        );
        let rhs = Mat::<f64>::from_fn(self.n, 1, |i, _| m0[i]);
        let m = self.lu.solve(rhs);
        (0..self.n).map(|i| m[(i, 0)]).collect()
    }

    /// `M = (I − R F)⁻¹ M0` for every column of `m0` (n × channels).
    #[track_caller]
    pub fn solve_many(&self, m0: MatRef<'_, f64>) -> Mat<f64> {
        assert!(
            m0.nrows() == self.n,
            "ExactSolver::solve_many: m0 has {} rows, expected {}",
            m0.nrows(),
            self.n
        );
        self.lu.solve(m0)
    }
}
