//! Extreme eigenpairs of `H = diag(s) G_rr diag(s)` without forming `H`
//! (math.md, "Default formulation: split", large n).
//!
//! The partial path is a Lanczos iteration with full reorthogonalisation written here, whose
//! loop bound we own, and every result is checked by its explicit residual `‖H u − μ u‖₂`.
//!
//! Why not faer's Krylov–Schur (`faer::matrix_free::eigen::partial_self_adjoint_eigen`)?
//! In faer 0.24 it can run forever (faer-rs issue 262). We reproduced that on a random
//! symmetric matrix with n = 1200 even with bounded `min_dim`/`max_dim`/`max_restarts`: the
//! process spins in the reorthogonalisation loop of `iterate_lanczos`
//! (`operator/self_adjoint_eigen/mod.rs`, line 47), which repeats until
//! `|vᵢ · w| < max(j, 8) ε ‖w‖` for every basis vector and never calls the operator. A
//! watchdog inside the operator (apply budget, deadline, abort by panic) therefore cannot end
//! it, and a watchdog thread could only abandon a thread that keeps spinning. The test
//! `eigen_faer_krylov_schur_issue_262` (ignored: it leaves that thread behind) shows the hang;
//! [`ScaledOp`] implements faer's `LinOp` for it, so switching back is a small change once
//! faer fixes the loop.

use faer::dyn_stack::{MemStack, StackReq};
use faer::linalg::matmul::matmul;
use faer::matrix_free::LinOp;
use faer::reborrow::{Reborrow, ReborrowMut};
use faer::{Accum, Col, Mat, MatMut, MatRef, Par, Side};

/// `H = diag(s) G[r, r] diag(s)` applied on the fly: the only n×n matrix touched is `G`.
///
/// `r` lists the reflecting patches (indices into `G`), `s_i = sqrt(ρ_i / A_i)` on them.
#[derive(Debug)]
pub(crate) struct ScaledOp<'a> {
    g: MatRef<'a, f64>,
    r: &'a [usize],
    s: &'a [f64],
}

impl<'a> ScaledOp<'a> {
    pub(crate) fn new(g: MatRef<'a, f64>, r: &'a [usize], s: &'a [f64]) -> Self {
        debug_assert_eq!(r.len(), s.len());
        Self { g, r, s }
    }

    /// Dimension of the reflecting subsystem.
    pub(crate) fn dim(&self) -> usize {
        self.r.len()
    }

    /// `out = H rhs`; `rhs` and `out` are `n_r × k`.
    pub(crate) fn apply_to(&self, mut out: MatMut<'_, f64>, rhs: MatRef<'_, f64>, par: Par) {
        let n = self.g.nrows();
        let k = rhs.ncols();
        let mut scattered = Mat::<f64>::zeros(n, k);
        for j in 0..k {
            for (i, (&ri, &si)) in self.r.iter().zip(self.s).enumerate() {
                scattered[(ri, j)] = si * rhs[(i, j)];
            }
        }
        let mut full = Mat::<f64>::zeros(n, k);
        matmul(
            full.as_mut(),
            Accum::Replace,
            self.g,
            scattered.as_ref(),
            1.0,
            par,
        );
        for j in 0..k {
            for (i, (&ri, &si)) in self.r.iter().zip(self.s).enumerate() {
                out[(i, j)] = si * full[(ri, j)];
            }
        }
    }
}

impl LinOp<f64> for ScaledOp<'_> {
    fn apply_scratch(&self, _rhs_ncols: usize, _par: Par) -> StackReq {
        StackReq::EMPTY
    }
    fn nrows(&self) -> usize {
        self.r.len()
    }
    fn ncols(&self) -> usize {
        self.r.len()
    }
    fn apply(&self, out: MatMut<'_, f64>, rhs: MatRef<'_, f64>, par: Par, _stack: &mut MemStack) {
        self.apply_to(out, rhs, par);
    }
    fn conj_apply(
        &self,
        out: MatMut<'_, f64>,
        rhs: MatRef<'_, f64>,
        par: Par,
        stack: &mut MemStack,
    ) {
        self.apply(out, rhs, par, stack);
    }
}

/// Eigenpairs of `H` on the reflecting subsystem, ordered by decreasing `|μ|`.
#[derive(Debug)]
pub(crate) struct Eigenpairs {
    pub values: Vec<f64>,
    /// `nr × k`, orthonormal columns.
    pub vectors: Mat<f64>,
    /// `‖H u_k − μ_k u_k‖₂` per pair.
    pub residuals: Vec<f64>,
}

/// Deterministic, generic start vector (a symmetric start would miss antisymmetric modes of
/// symmetric scenes entirely).
pub(crate) fn start_vector(n: usize, seed: u64) -> Col<f64> {
    let mut state = seed ^ 0x9E37_79B9_7F4A_7C15;
    Col::from_fn(n, |_| {
        // splitmix64
        state = state.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = state;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^= z >> 31;
        (z >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0 + 0.25
    })
}

/// Explicit residuals `‖H u_j − μ_j u_j‖₂`.
pub(crate) fn residuals(
    op: &ScaledOp<'_>,
    values: &[f64],
    vectors: MatRef<'_, f64>,
    par: Par,
) -> Vec<f64> {
    let mut hv = Mat::<f64>::zeros(vectors.nrows(), vectors.ncols());
    op.apply_to(hv.as_mut(), vectors, par);
    (0..vectors.ncols())
        .map(|j| {
            let mut acc = 0.0;
            for i in 0..vectors.nrows() {
                let d = hv[(i, j)] - values[j] * vectors[(i, j)];
                acc += d * d;
            }
            acc.sqrt()
        })
        .collect()
}

/// Convergence settings of one partial solve.
#[derive(Debug, Clone, Copy)]
pub(crate) struct KrylovSettings {
    /// Convergence tolerance on the Ritz residual estimate (absolute; `‖H‖ ≤ ρmax < 1`).
    pub tol: f64,
    /// Accept a result only if every explicit residual is at most this.
    pub accept: f64,
}

/// Lanczos with full reorthogonalisation (two classical Gram–Schmidt passes per step) and
/// Rayleigh–Ritz on the tridiagonal `T`; no restarts, at most `max_steps` operator
/// applications. On an invariant subspace (`β ≈ 0`, e.g. the rank-one sphere) it continues
/// with a fresh start vector orthogonal to the basis, so the multiplicity of repeated
/// eigenvalues is found too.
///
/// Returns the `k` Ritz pairs with the largest `key(θ)` (e.g. `|θ/(1−θ)|`), ordered by
/// decreasing key, or `Err(max explicit residual)`. Lanczos converges the extreme eigenvalues
/// first, and both `|μ|` and `|μ/(1−μ)|` are largest at the ends of the spectrum.
pub(crate) fn lanczos(
    op: &ScaledOp<'_>,
    k: usize,
    key: fn(f64) -> f64,
    max_steps: usize,
    settings: KrylovSettings,
    par: Par,
) -> Result<Eigenpairs, f64> {
    let n = op.dim();
    let m_cap = max_steps.min(n).max(k.min(n));
    let mut basis = Mat::<f64>::zeros(n, m_cap + 1);
    let mut alpha = Vec::with_capacity(m_cap);
    let mut beta: Vec<f64> = Vec::with_capacity(m_cap);
    let mut seed = 1u64;
    let q0 = start_vector(n, seed);
    let nrm = q0.norm_l2();
    for i in 0..n {
        basis[(i, 0)] = q0[i] / nrm;
    }
    let mut w = Mat::<f64>::zeros(n, 1);
    let mut h = Mat::<f64>::zeros(m_cap + 1, 1);
    let check_every = 25usize;
    let mut best: Option<(Vec<f64>, Mat<f64>, Vec<f64>)> = None;
    let mut m = 0;
    while m < m_cap {
        let j = m;
        op.apply_to(w.as_mut(), basis.as_ref().get(.., j..j + 1), par);
        let mut a_j = 0.0;
        for pass in 0..2 {
            let v = basis.as_ref().get(.., 0..j + 1);
            let mut hj = h.as_mut().get_mut(0..j + 1, ..);
            matmul(
                hj.rb_mut(),
                Accum::Replace,
                v.transpose(),
                w.as_ref(),
                1.0,
                par,
            );
            matmul(w.as_mut(), Accum::Add, v, hj.rb(), -1.0, par);
            a_j += hj[(j, 0)];
            let _ = pass;
        }
        alpha.push(a_j);
        m += 1;
        let mut b = w.as_ref().col(0).norm_l2();
        let scale = alpha
            .iter()
            .chain(beta.iter())
            .fold(0.0f64, |acc, x| acc.max(x.abs()));
        if b <= 1e-12 * scale.max(f64::MIN_POSITIVE) {
            // Invariant subspace: restart from a fresh vector orthogonal to the basis.
            b = 0.0;
            seed += 1;
            let fresh = start_vector(n, seed);
            for i in 0..n {
                w[(i, 0)] = fresh[i];
            }
            for _ in 0..2 {
                let v = basis.as_ref().get(.., 0..m);
                let mut hj = h.as_mut().get_mut(0..m, ..);
                matmul(
                    hj.rb_mut(),
                    Accum::Replace,
                    v.transpose(),
                    w.as_ref(),
                    1.0,
                    par,
                );
                matmul(w.as_mut(), Accum::Add, v, hj.rb(), -1.0, par);
            }
        }
        let wn = w.as_ref().col(0).norm_l2();
        beta.push(b);
        let exhausted = m == n || wn <= 1e-10 * (n as f64).sqrt();
        if !exhausted {
            for i in 0..n {
                basis[(i, m)] = w[(i, 0)] / wn;
            }
        }
        if (m >= k && (m % check_every == 0 || m == m_cap)) || exhausted {
            let (vals, s) = ritz(&alpha, &beta)?;
            // Ritz residual estimate |β_m s_{m,i}| on the k Ritz values of largest key.
            let mut order: Vec<usize> = (0..vals.len()).collect();
            order.sort_by(|&a, &b| key(vals[b]).total_cmp(&key(vals[a])));
            let sel: Vec<usize> = order.into_iter().take(k).collect();
            let last = beta[m - 1];
            let est = sel
                .iter()
                .map(|&i| (last * s[(m - 1, i)]).abs())
                .fold(0.0, f64::max);
            if est <= settings.tol || exhausted || m == m_cap {
                let mut y = Mat::<f64>::zeros(m, sel.len());
                for (c, &i) in sel.iter().enumerate() {
                    for r in 0..m {
                        y[(r, c)] = s[(r, i)];
                    }
                }
                let mut u = Mat::<f64>::zeros(n, sel.len());
                matmul(
                    u.as_mut(),
                    Accum::Replace,
                    basis.as_ref().get(.., 0..m),
                    y.as_ref(),
                    1.0,
                    par,
                );
                let values: Vec<f64> = sel.iter().map(|&i| vals[i]).collect();
                let res = residuals(op, &values, u.as_ref(), par);
                let max = res.iter().copied().fold(0.0, f64::max);
                if max <= settings.accept {
                    return Ok(Eigenpairs {
                        values,
                        vectors: u,
                        residuals: res,
                    });
                }
                best = Some((values, u, res));
                if exhausted || m == m_cap {
                    break;
                }
            }
        }
        if exhausted {
            break;
        }
    }
    Err(best
        .map(|(_, _, r)| r.iter().copied().fold(0.0, f64::max))
        .unwrap_or(f64::INFINITY))
}

/// Eigen-decomposition of the symmetric tridiagonal `T` (`alpha` diagonal, `beta` off-diagonal).
fn ritz(alpha: &[f64], beta: &[f64]) -> Result<(Vec<f64>, Mat<f64>), f64> {
    let m = alpha.len();
    let t = Mat::<f64>::from_fn(m, m, |i, j| {
        if i == j {
            alpha[i]
        } else if i == j + 1 {
            beta[j]
        } else if j == i + 1 {
            beta[i]
        } else {
            0.0
        }
    });
    let evd = t
        .self_adjoint_eigen(Side::Lower)
        .map_err(|_| f64::INFINITY)?;
    let vals: Vec<f64> = (0..m).map(|i| evd.S().column_vector()[i]).collect();
    Ok((vals, evd.U().to_owned()))
}
