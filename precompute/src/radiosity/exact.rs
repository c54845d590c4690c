//! Exact reference solve of the radiosity equation for one band (docs/math.md, "Notation"):
//! `M = M0 + R F M`, so `M = (I − R F)⁻¹ M0` (seed eq. 6–7), by LU with partial pivoting.
//!
//! This is the baseline every truncated basis is measured against, and the "exact per-channel
//! response" lighting practice uses when the emitter channels are fixed (docs/math.md, "Be
//! honest about the baseline").

use std::sync::Arc;

use crate::formfactor::operator::FormFactorOperator;
use crate::radiosity::eigen::{check_inputs, EigenError};
use faer::linalg::solvers::{PartialPivLu, Solve};
use faer::{Mat, MatRef};

/// Largest patch count [`ExactSolver::auto`] factorises by LU: defined with the memory model
/// of a build, which depends on it.
pub use crate::memory::EXACT_LU_MAX;

/// Relative residual the conjugate-gradient reference stops at: `‖r‖₂ ≤ CG_TOLERANCE ‖b‖₂` on
/// the symmetric system `(B − G) M = B M0` (Jacobi-preconditioned, condition number at most
/// `(1 + ρmax)/(1 − ρmax)` after preconditioning, so the error stays near this figure).
pub const CG_TOLERANCE: f64 = 1e-12;

/// Iterations after which conjugate gradients stop whatever the residual (about 60 are needed
/// at ρmax = 0.9 for [`CG_TOLERANCE`]).
const CG_MAX_ITERATIONS: usize = 2000;

/// Solver of `I − R F` (`F = A⁻¹ G`) for one band; solves for any number of emission
/// patterns. Black patches (`ρ = 0`) are handled by the same equation: their row is the
/// identity, so `M_k = M0_k`.
///
/// Two ways: an LU factorisation with partial pivoting ([`ExactSolver::new`]), or conjugate
/// gradients on the symmetric positive definite reflecting subsystem
/// `(B_r − G_rr) M_r = B_r M0_r + G_rk M0_k` (`B = A/ρ`, docs/math.md "Zero reflectance";
/// [`ExactSolver::iterative`]), which shares the form-factor operator and needs no n×n copy.
#[derive(Debug)]
pub struct ExactSolver {
    n: usize,
    kind: Kind,
}

#[derive(Debug)]
enum Kind {
    Lu(PartialPivLu<f64>),
    Cg {
        g: Arc<dyn FormFactorOperator>,
        area: Vec<f64>,
        reflectance: Vec<f64>,
    },
}

impl ExactSolver {
    /// Factorises `I − R F` with `(R F)_ij = ρ_i G_ij / A_i` (`G` in m², `A` in m²).
    ///
    /// Inputs are checked as for [`crate::radiosity::eigen::modes`] (symmetric finite `G`, `A > 0`,
    /// `ρ ∈ [0, 1)`). `O(n³)`.
    pub fn new(
        g: &dyn FormFactorOperator,
        area: &[f64],
        reflectance: &[f64],
    ) -> Result<Self, EigenError> {
        check_inputs(g, area, reflectance)?;
        let n = g.len();
        let dense = g.dense();
        let entry = |i: usize, j: usize| match dense {
            Some(dense) => dense[(i, j)],
            None => g.entry(i, j),
        };
        let a = Mat::<f64>::from_fn(n, n, |i, j| {
            let id = if i == j { 1.0 } else { 0.0 };
            id - reflectance[i] / area[i] * entry(i, j)
        });
        let lu = a.partial_piv_lu();
        // With ρ < 1 and row sums of F ≤ 1 the matrix is diagonally dominant; a zero pivot
        // means the inputs broke that (e.g. F rows summing far above 1).
        let u = lu.U();
        if let Some(pivot) = (0..n).find(|&i| !(u[(i, i)].abs() > 0.0 && u[(i, i)].is_finite())) {
            return Err(EigenError::Singular { pivot });
        }
        Ok(Self {
            n,
            kind: Kind::Lu(lu),
        })
    }

    /// Conjugate gradients on the operator `G` (shared), to [`CG_TOLERANCE`]: one product
    /// with `G` per iteration and no n×n allocation. Inputs are checked as for
    /// [`ExactSolver::new`].
    pub fn iterative(
        g: Arc<dyn FormFactorOperator>,
        area: &[f64],
        reflectance: &[f64],
    ) -> Result<Self, EigenError> {
        check_inputs(g.as_ref(), area, reflectance)?;
        Ok(Self {
            n: g.len(),
            kind: Kind::Cg {
                g,
                area: area.to_vec(),
                reflectance: reflectance.to_vec(),
            },
        })
    }

    /// LU up to [`EXACT_LU_MAX`] patches of a dense f64 operator, conjugate gradients above
    /// and on every other operator.
    pub fn auto(
        g: &Arc<dyn FormFactorOperator>,
        area: &[f64],
        reflectance: &[f64],
    ) -> Result<Self, EigenError> {
        if g.len() <= EXACT_LU_MAX && g.dense().is_some() {
            Self::new(g.as_ref(), area, reflectance)
        } else {
            Self::iterative(Arc::clone(g), area, reflectance)
        }
    }

    /// `"LU"` or `"conjugate gradients"`.
    pub fn method(&self) -> &'static str {
        match self.kind {
            Kind::Lu(_) => "LU",
            Kind::Cg { .. } => "conjugate gradients",
        }
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
        let m = self.solve_many(rhs.as_ref());
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
        match &self.kind {
            Kind::Lu(lu) => lu.solve(m0),
            Kind::Cg {
                g,
                area,
                reflectance,
            } => cg(g.as_ref(), area, reflectance, m0),
        }
    }
}

/// Block conjugate gradients (independent scalars per column, one `G` product per iteration
/// for all columns) on `(B_r − G_rr) M_r = B_r M0_r + G_rk M0_k`, Jacobi-preconditioned;
/// black rows keep `M0`.
fn cg(g: &dyn FormFactorOperator, area: &[f64], rho: &[f64], m0: MatRef<'_, f64>) -> Mat<f64> {
    let n = g.len();
    let c = m0.ncols();
    let par = faer::get_global_parallelism();
    let reflecting = |i: usize| rho[i] > 0.0;
    let b: Vec<f64> = (0..n)
        .map(|i| if reflecting(i) { area[i] / rho[i] } else { 0.0 })
        .collect();
    // Right-hand side: B M0 on reflecting rows plus G times the black emission.
    let black = Mat::<f64>::from_fn(n, c, |i, j| if reflecting(i) { 0.0 } else { m0[(i, j)] });
    let mut rhs = Mat::<f64>::zeros(n, c);
    g.apply(rhs.as_mut(), black.as_ref(), par);
    for j in 0..c {
        for i in 0..n {
            rhs[(i, j)] = if reflecting(i) {
                rhs[(i, j)] + b[i] * m0[(i, j)]
            } else {
                0.0
            };
        }
    }
    let g_diagonal = g.diagonal();
    let diag: Vec<f64> = (0..n)
        .map(|i| {
            if reflecting(i) {
                b[i] - g_diagonal[i]
            } else {
                1.0
            }
        })
        .collect();
    // S x = B x − G x on reflecting rows (x is zero on black rows).
    let apply = |x: MatRef<'_, f64>, out: &mut Mat<f64>| {
        g.apply(out.as_mut(), x, par);
        for j in 0..c {
            for i in 0..n {
                out[(i, j)] = if reflecting(i) {
                    b[i] * x[(i, j)] - out[(i, j)]
                } else {
                    0.0
                };
            }
        }
    };
    let dot = |a: &Mat<f64>, b: &Mat<f64>, j: usize| -> f64 {
        (0..n).map(|i| a[(i, j)] * b[(i, j)]).sum()
    };
    let mut x = Mat::<f64>::zeros(n, c);
    let mut r = rhs.clone();
    let mut z = Mat::<f64>::from_fn(n, c, |i, j| r[(i, j)] / diag[i]);
    let mut p = z.clone();
    let mut q = Mat::<f64>::zeros(n, c);
    let mut rz: Vec<f64> = (0..c).map(|j| dot(&r, &z, j)).collect();
    let target: Vec<f64> = (0..c)
        .map(|j| CG_TOLERANCE * dot(&rhs, &rhs, j).sqrt())
        .collect();
    for _ in 0..CG_MAX_ITERATIONS {
        if (0..c).all(|j| dot(&r, &r, j).sqrt() <= target[j]) {
            break;
        }
        apply(p.as_ref(), &mut q);
        for j in 0..c {
            let pq = dot(&p, &q, j);
            let alpha = if pq > 0.0 { rz[j] / pq } else { 0.0 };
            for i in 0..n {
                x[(i, j)] += alpha * p[(i, j)];
                r[(i, j)] -= alpha * q[(i, j)];
                z[(i, j)] = r[(i, j)] / diag[i];
            }
            let rz_new = dot(&r, &z, j);
            let beta = if rz[j] > 0.0 { rz_new / rz[j] } else { 0.0 };
            rz[j] = rz_new;
            for i in 0..n {
                p[(i, j)] = z[(i, j)] + beta * p[(i, j)];
            }
        }
    }
    for j in 0..c {
        for i in 0..n {
            if !reflecting(i) {
                x[(i, j)] = m0[(i, j)];
            }
        }
    }
    x
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

    /// White furnace (docs/math.md "Exact results"): closed room, uniform ρ, every patch emitting E:
    /// `M = E / (1 − ρ)` everywhere, to 1e-12 relative.
    #[test]
    fn solve_white_furnace() {
        let n = 50;
        let (g, area) = closed_room(n);
        for rho in [0.2, 0.5, 0.9] {
            let s = ExactSolver::new(&g, &area, &vec![rho; n]).expect("lu");
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
        let s = ExactSolver::new(&g, &area, &rho).expect("lu");
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

    /// Conjugate gradients agree with the LU factorisation on the closed room with black
    /// patches (1e-10 relative to max |M|: CG stops at a 1e-12 relative residual on a system
    /// whose preconditioned condition number is below (1 + 0.9)/(1 − 0.9) = 19).
    #[test]
    fn conjugate_gradients_match_lu() {
        let n = 60;
        let (g, area) = closed_room(n);
        let rho: Vec<f64> = (0..n)
            .map(|i| {
                if i % 9 == 0 {
                    0.0
                } else {
                    0.05 + 0.85 * ((i * 13 % 17) as f64) / 17.0
                }
            })
            .collect();
        let lu = ExactSolver::new(&g, &area, &rho).expect("lu");
        let cg = ExactSolver::iterative(Arc::new(g.clone()), &area, &rho).expect("cg");
        assert_eq!(cg.method(), "conjugate gradients");
        let m0 = Mat::<f64>::from_fn(n, 4, |i, c| ((i * (c + 5) + 3 * c) % 11) as f64);
        let a = lu.solve_many(m0.as_ref());
        let b = cg.solve_many(m0.as_ref());
        for c in 0..4 {
            let scale = (0..n).fold(0.0f64, |s, i| s.max(a[(i, c)].abs()));
            let err = (0..n).fold(0.0f64, |s, i| s.max((a[(i, c)] - b[(i, c)]).abs())) / scale;
            assert!(err < 1e-10, "column {c}: CG vs LU {err:e}");
        }
    }
}
