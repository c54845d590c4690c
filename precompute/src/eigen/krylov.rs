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

/// Thick-restart Lanczos with full reorthogonalisation (two classical Gram–Schmidt passes per
/// step), i.e. a symmetric Krylov–Schur method whose every loop is bounded here.
///
/// The projected matrix `T = Vᵀ H V` is kept explicitly (lower triangle, from the
/// Gram–Schmidt coefficients), so a restart is just: keep the `k_keep` best Ritz vectors
/// `Y = V S`, `T ← diag(θ)` plus the arrow row `β s_{m,i}`, continue from the last Lanczos
/// vector (Wu & Simon 2000; Stewart's Krylov–Schur). The relation `H V = V T + β q eₘᵀ` holds
/// throughout, so `|β s_{m,i}|` is the residual of Ritz pair `i`.
///
/// On an invariant subspace (`β ≈ 0`, e.g. the rank-one sphere) the iteration continues with a
/// fresh start vector orthogonal to the basis, so repeated eigenvalues are found too.
///
/// Returns the `k` Ritz pairs with the largest `key(θ)` (e.g. `|θ/(1−θ)|`), ordered by
/// decreasing key, or `Err(max explicit residual)` after `max_restarts` restarts. Lanczos
/// converges the ends of the spectrum first, where both `|μ|` and `|μ/(1−μ)|` are largest.
pub(crate) fn lanczos(
    op: &ScaledOp<'_>,
    k: usize,
    key: fn(f64) -> f64,
    settings: KrylovSettings,
    par: Par,
) -> Result<Eigenpairs, f64> {
    let n = op.dim();
    let k = k.min(n);
    // Basis size and how many Ritz vectors survive a restart.
    let m_cap = (3 * k).max(k + 60).min(n);
    let k_keep = (k + (m_cap - k) / 3)
        .min(m_cap.saturating_sub(1))
        .max(k.min(m_cap.saturating_sub(1)));
    let mut basis = Mat::<f64>::zeros(n, m_cap + 1);
    let mut t = Mat::<f64>::zeros(m_cap + 1, m_cap + 1);
    let mut seed = 1u64;
    let q0 = start_vector(n, seed);
    let nrm = q0.norm_l2();
    for i in 0..n {
        basis[(i, 0)] = q0[i] / nrm;
    }
    let mut w = Mat::<f64>::zeros(n, 1);
    let mut h = Mat::<f64>::zeros(m_cap + 1, 1);
    let mut hsum = vec![0.0; m_cap + 1];
    let mut best = f64::INFINITY;
    let mut m = 0; // current basis size (columns 0..m hold the basis, column m the next vector)
    let mut restarts = 0;
    loop {
        // Expand to m_cap (or until the space is exhausted).
        let mut exhausted = false;
        while m < m_cap {
            let j = m;
            op.apply_to(w.as_mut(), basis.as_ref().get(.., j..j + 1), par);
            hsum[..=j].iter_mut().for_each(|x| *x = 0.0);
            for _ in 0..2 {
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
                for i in 0..=j {
                    hsum[i] += hj[(i, 0)];
                }
            }
            for i in 0..=j {
                t[(j, i)] = hsum[i];
            }
            m += 1;
            let mut b = w.as_ref().col(0).norm_l2();
            if b <= 1e-12 {
                // Invariant subspace (‖H‖ < 1): continue from a fresh orthogonal vector.
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
            t[(m, m - 1)] = b;
            let wn = w.as_ref().col(0).norm_l2();
            if m == n || wn <= 1e-10 {
                exhausted = true;
                break;
            }
            for i in 0..n {
                basis[(i, m)] = w[(i, 0)] / wn;
            }
        }
        // Rayleigh–Ritz on T (m × m).
        let tm = Mat::<f64>::from_fn(m, m, |i, j| if i >= j { t[(i, j)] } else { t[(j, i)] });
        let evd = tm
            .self_adjoint_eigen(Side::Lower)
            .map_err(|_| f64::INFINITY)?;
        let vals: Vec<f64> = (0..m).map(|i| evd.S().column_vector()[i]).collect();
        let s = evd.U();
        let mut order: Vec<usize> = (0..m).collect();
        order.sort_by(|&a, &b| key(vals[b]).total_cmp(&key(vals[a])));
        let beta = if exhausted { 0.0 } else { t[(m, m - 1)] };
        let est = order
            .iter()
            .take(k)
            .map(|&i| (beta * s[(m - 1, i)]).abs())
            .fold(0.0, f64::max);
        let done = est <= settings.tol || exhausted || restarts >= MAX_RESTARTS;
        if done {
            let sel: Vec<usize> = order.iter().copied().take(k).collect();
            let y = Mat::<f64>::from_fn(m, sel.len(), |r, c| s[(r, sel[c])]);
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
            best = best.min(max);
            if exhausted || restarts >= MAX_RESTARTS {
                return Err(best);
            }
        }
        // Thick restart: keep the k_keep best Ritz vectors and the next Lanczos vector.
        restarts += 1;
        let keep: Vec<usize> = order.iter().copied().take(k_keep).collect();
        let y = Mat::<f64>::from_fn(m, keep.len(), |r, c| s[(r, keep[c])]);
        let mut u = Mat::<f64>::zeros(n, keep.len());
        matmul(
            u.as_mut(),
            Accum::Replace,
            basis.as_ref().get(.., 0..m),
            y.as_ref(),
            1.0,
            par,
        );
        let next = basis.as_ref().col(m).to_owned();
        basis.as_mut().get_mut(.., 0..keep.len()).copy_from(&u);
        basis.as_mut().col_mut(keep.len()).copy_from(&next);
        t.fill(0.0);
        for (c, &i) in keep.iter().enumerate() {
            t[(c, c)] = vals[i];
            t[(keep.len(), c)] = beta * s[(m - 1, i)];
        }
        m = keep.len();
    }
}

/// Restarts of [`lanczos`] before it gives up (each costs at most `m_cap − k_keep` operator
/// applications).
const MAX_RESTARTS: usize = 200;
