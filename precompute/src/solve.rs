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

#[cfg(test)]
mod tests {
    use super::*;

    /// Closed room with exact row sums (`G_ii = A_i − Σ_{j≠i} G_ij`), kernel from a hash.
    fn closed_room(n: usize) -> (Mat<f64>, Vec<f64>) {
        let k = Mat::<f64>::from_fn(n, n, |i, j| {
            if i == j {
                0.0
            } else {
                let (a, b) = (i.min(j) as f64, i.max(j) as f64);
                1.0 + (a * 1.3 + b * 0.7).sin().abs()
            }
        });
        let rows: Vec<f64> = (0..n).map(|i| (0..n).map(|j| k[(i, j)]).sum()).collect();
        let area: Vec<f64> = rows
            .iter()
            .enumerate()
            .map(|(i, r)| r * (1.05 + 0.1 * ((i % 3) as f64)))
            .collect();
        let g = Mat::from_fn(
            n,
            n,
            |i, j| if i == j { area[i] - rows[i] } else { k[(i, j)] },
        );
        (g, area)
    }

    /// White furnace (math.md "Exact results"): closed room, uniform ρ, every patch emitting E:
    /// `M = E / (1 − ρ)` everywhere, to 1e-12 relative.
    #[test]
    fn solve_white_furnace() {
        let n = 50;
        let (g, area) = closed_room(n);
        for rho in [0.2, 0.5, 0.9] {
            let s = ExactSolver::new(g.as_ref(), &area, &vec![rho; n]).expect("lu");
            let e = 300.0;
            let m = s.solve(&vec![e; n]);
            let want = e / (1.0 - rho);
            let err = m.iter().map(|x| (x - want).abs()).fold(0.0, f64::max) / want;
            assert!(err < 1e-12, "ρ = {rho}: white furnace error {err:e}");
        }
    }

    /// `solve_many` equals column-wise `solve` (bitwise up to 1e-14), and satisfies the
    /// radiosity equation `M = M0 + R F M` (residual 1e-12 relative); black patches keep M0.
    #[test]
    fn solve_many_and_residual() {
        let n = 30;
        let (g, area) = closed_room(n);
        let rho: Vec<f64> = (0..n)
            .map(|i| {
                if i % 7 == 0 {
                    0.0
                } else {
                    0.1 + 0.8 * ((i * 37 % 11) as f64) / 11.0
                }
            })
            .collect();
        let s = ExactSolver::new(g.as_ref(), &area, &rho).expect("lu");
        let m0 = Mat::<f64>::from_fn(n, 3, |i, c| ((i * (c + 3) + c) % 7) as f64);
        let mm = s.solve_many(m0.as_ref());
        for c in 0..3 {
            let col: Vec<f64> = (0..n).map(|i| m0[(i, c)]).collect();
            let m = s.solve(&col);
            let scale = m.iter().fold(0.0f64, |a, x| a.max(x.abs()));
            for i in 0..n {
                assert!((m[i] - mm[(i, c)]).abs() <= 1e-14 * scale);
                let rfm: f64 = rho[i] / area[i] * (0..n).map(|j| g[(i, j)] * m[j]).sum::<f64>();
                let r = (m[i] - col[i] - rfm).abs() / scale;
                assert!(r < 1e-12, "radiosity residual {r:e} at {i}, ρ = {}", rho[i]);
                if rho[i] == 0.0 {
                    assert_eq!(m[i], col[i]);
                }
            }
        }
    }
}
