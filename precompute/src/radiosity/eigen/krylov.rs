//! Extreme eigenpairs of `H = diag(s) G_rr diag(s)` without forming `H`
//! (docs/math.md, "Default formulation: split", large n).
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

use crate::formfactor::operator::FormFactorOperator;

/// `H = diag(s) G[r, r] diag(s)` applied on the fly: the only n×n matrix touched is `G`.
///
/// `r` lists the reflecting patches (indices into `G`), `s_i = sqrt(ρ_i / A_i)` on them.
#[derive(Debug)]
pub(crate) struct ScaledOp<'a> {
    g: &'a dyn FormFactorOperator,
    r: &'a [usize],
    s: &'a [f64],
}

impl<'a> ScaledOp<'a> {
    pub(crate) fn new(g: &'a dyn FormFactorOperator, r: &'a [usize], s: &'a [f64]) -> Self {
        debug_assert_eq!(r.len(), s.len());
        Self { g, r, s }
    }

    /// Dimension of the reflecting subsystem.
    pub(crate) fn dim(&self) -> usize {
        self.r.len()
    }

    /// `out = H rhs`; `rhs` and `out` are `n_r × k`.
    pub(crate) fn apply_to(&self, mut out: MatMut<'_, f64>, rhs: MatRef<'_, f64>, par: Par) {
        let n = self.g.len();
        let k = rhs.ncols();
        let mut scattered = Mat::<f64>::zeros(n, k);
        for j in 0..k {
            for (i, (&ri, &si)) in self.r.iter().zip(self.s).enumerate() {
                scattered[(ri, j)] = si * rhs[(i, j)];
            }
        }
        let mut full = Mat::<f64>::zeros(n, k);
        self.g.apply(full.as_mut(), scattered.as_ref(), par);
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
    /// What the solve took.
    pub work: super::LanczosWork,
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
///
/// The partial path now runs [`block_lanczos`]; this one-vector form is kept as its reference
/// in the tests.
#[cfg(test)]
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
    let mut st = LanczosState::new(n, m_cap);
    let mut best = f64::INFINITY;
    let mut restarts = 0;
    loop {
        let exhausted = st.expand(op, m_cap, par);
        let m = st.m;
        // Rayleigh–Ritz on T (m × m).
        let t = &st.t;
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
            let u = st.ritz_vectors(s, &sel, par);
            let values: Vec<f64> = sel.iter().map(|&i| vals[i]).collect();
            let res = residuals(op, &values, u.as_ref(), par);
            let max = res.iter().copied().fold(0.0, f64::max);
            if max <= settings.accept {
                return Ok(Eigenpairs {
                    values,
                    vectors: u,
                    residuals: res,
                    work: super::LanczosWork {
                        restarts,
                        columns: st.applied + k,
                    },
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
        let u = st.ritz_vectors(s, &keep, par);
        let next = st.basis.as_ref().col(m).to_owned();
        st.basis.as_mut().get_mut(.., 0..keep.len()).copy_from(&u);
        st.basis.as_mut().col_mut(keep.len()).copy_from(&next);
        st.t.fill(0.0);
        for (c, &i) in keep.iter().enumerate() {
            st.t[(c, c)] = vals[i];
            st.t[(keep.len(), c)] = beta * s[(m - 1, i)];
        }
        st.m = keep.len();
    }
}

/// The Lanczos basis of [`lanczos`] and its projected matrix between restarts.
#[cfg(test)]
struct LanczosState {
    /// `n × (m_cap + 1)`: columns `0..m` the basis, column `m` the next vector.
    basis: Mat<f64>,
    /// `T = Vᵀ H V`, lower triangle, with `β` below the last column.
    t: Mat<f64>,
    /// The vector being orthogonalised.
    w: Mat<f64>,
    /// Gram–Schmidt coefficients of one pass.
    h: Mat<f64>,
    /// Their sum over both passes.
    hsum: Vec<f64>,
    /// Current basis size.
    m: usize,
    /// Seed of the last start vector.
    seed: u64,
    /// Vectors the operator was applied to.
    applied: usize,
}

#[cfg(test)]
impl LanczosState {
    /// A basis holding the normalised first start vector.
    fn new(n: usize, m_cap: usize) -> Self {
        let mut basis = Mat::<f64>::zeros(n, m_cap + 1);
        let seed = 1u64;
        let q0 = start_vector(n, seed);
        let nrm = q0.norm_l2();
        for i in 0..n {
            basis[(i, 0)] = q0[i] / nrm;
        }
        LanczosState {
            basis,
            t: Mat::<f64>::zeros(m_cap + 1, m_cap + 1),
            w: Mat::<f64>::zeros(n, 1),
            h: Mat::<f64>::zeros(m_cap + 1, 1),
            hsum: vec![0.0; m_cap + 1],
            m: 0,
            seed,
            applied: 0,
        }
    }

    /// Expands the basis to `m_cap` columns; true if the space was exhausted first.
    fn expand(&mut self, op: &ScaledOp<'_>, m_cap: usize, par: Par) -> bool {
        let n = op.dim();
        while self.m < m_cap {
            let j = self.m;
            op.apply_to(self.w.as_mut(), self.basis.as_ref().get(.., j..j + 1), par);
            self.applied += 1;
            self.hsum[..=j].iter_mut().for_each(|x| *x = 0.0);
            for _ in 0..2 {
                let v = self.basis.as_ref().get(.., 0..j + 1);
                let mut hj = self.h.as_mut().get_mut(0..j + 1, ..);
                matmul(
                    hj.rb_mut(),
                    Accum::Replace,
                    v.transpose(),
                    self.w.as_ref(),
                    1.0,
                    par,
                );
                matmul(self.w.as_mut(), Accum::Add, v, hj.rb(), -1.0, par);
                for i in 0..=j {
                    self.hsum[i] += hj[(i, 0)];
                }
            }
            for i in 0..=j {
                self.t[(j, i)] = self.hsum[i];
            }
            self.m += 1;
            let m = self.m;
            let mut b = self.w.as_ref().col(0).norm_l2();
            if b <= 1e-12 {
                // Invariant subspace (‖H‖ < 1): continue from a fresh orthogonal vector.
                b = 0.0;
                self.seed += 1;
                let fresh = start_vector(n, self.seed);
                for i in 0..n {
                    self.w[(i, 0)] = fresh[i];
                }
                for _ in 0..2 {
                    let v = self.basis.as_ref().get(.., 0..m);
                    let mut hj = self.h.as_mut().get_mut(0..m, ..);
                    matmul(
                        hj.rb_mut(),
                        Accum::Replace,
                        v.transpose(),
                        self.w.as_ref(),
                        1.0,
                        par,
                    );
                    matmul(self.w.as_mut(), Accum::Add, v, hj.rb(), -1.0, par);
                }
            }
            self.t[(m, m - 1)] = b;
            let wn = self.w.as_ref().col(0).norm_l2();
            if m == n || wn <= 1e-10 {
                return true;
            }
            for i in 0..n {
                self.basis[(i, m)] = self.w[(i, 0)] / wn;
            }
        }
        false
    }

    /// The Ritz vectors `V y` for the columns `sel` of the eigenvectors `s` of `T`.
    fn ritz_vectors(&self, s: MatRef<'_, f64>, sel: &[usize], par: Par) -> Mat<f64> {
        let m = self.m;
        let y = Mat::<f64>::from_fn(m, sel.len(), |r, c| s[(r, sel[c])]);
        let mut u = Mat::<f64>::zeros(self.basis.nrows(), sel.len());
        matmul(
            u.as_mut(),
            Accum::Replace,
            self.basis.as_ref().get(.., 0..m),
            y.as_ref(),
            1.0,
            par,
        );
        u
    }
}

/// Restarts of [`lanczos`] before it gives up (each costs at most `m_cap − k_keep` operator
/// applications).
#[cfg(test)]
const MAX_RESTARTS: usize = 200;

/// Columns the block solver applies the operator to at once.
pub(crate) const BLOCK: usize = 16;

/// Restarts of [`block_lanczos`] before it gives up.
const MAX_BLOCK_RESTARTS: usize = 300;

/// Columns of the basis of [`block_lanczos`] per wanted pair, and blocks of extra Ritz pairs
/// a restart keeps beyond the wanted ones. The strongest modes of a large floor lie close
/// together, and a small basis restarts often: for 32 modes of a 9888-patch open-plan floor,
/// 3 columns a pair and one extra block took 34 restarts and 1760 operator columns, 6 and 3
/// take 6 restarts and 896 columns (docs/performance.md, "What changed for speed"). The basis
/// and its image cost `2 · 8 · n · 6k` bytes: 295 MB for 32 modes of 96 000 patches.
const BASIS_PER_WANTED: usize = 6;
const KEPT_BLOCKS: usize = 3;

/// Thick-restart block Lanczos with full reorthogonalisation: [`lanczos`] with the operator
/// applied to [`BLOCK`] vectors at once, so that `G` (the only n×n matrix) is streamed once per
/// block instead of once per vector, and the products are matrix–matrix (BLAS-3) work.
///
/// The basis `V` and its image `H V` are both kept, so the Rayleigh quotient `T = Vᵀ (H V)`
/// and every Ritz residual `H u − θ u = (H V) s − θ V s` are explicit. A cycle expands `V` by
/// blocks `H X` (orthogonalised twice against `V`, then within the block), up to
/// [`BASIS_PER_WANTED`]` · k` columns; a restart keeps the `k + KEPT_BLOCKS · BLOCK` best Ritz
/// pairs (`V ← V S`, `H V ← (H V) S`) and
/// continues from the residuals of the wanted pairs not yet converged, which span the same
/// space as the next block of the unrestarted iteration. Columns that vanish on
/// orthogonalisation (an invariant subspace, e.g. the rank-one sphere) are replaced by fresh
/// start vectors, so repeated eigenvalues are found too.
///
/// Returns the `k` Ritz pairs with the largest `key(θ)`, ordered by decreasing key, or
/// `Err(best max explicit residual)` after [`MAX_BLOCK_RESTARTS`] restarts.
pub(crate) fn block_lanczos(
    op: &ScaledOp<'_>,
    k: usize,
    key: fn(f64) -> f64,
    settings: KrylovSettings,
    par: Par,
) -> Result<Eigenpairs, f64> {
    let n = op.dim();
    let k = k.min(n);
    let b = BLOCK.min(n).max(1);
    let m_cap = (BASIS_PER_WANTED * k).max(k + 4 * b).min(n);
    let k_keep = (k + KEPT_BLOCKS * b)
        .min(m_cap.saturating_sub(b))
        .max(k.min(m_cap));
    let mut seed = 1u64;
    // The block to add next (not yet orthogonalised).
    let mut x = Mat::<f64>::from_fn(n, b, |_, _| 0.0);
    for c in 0..b {
        let s = start_vector(n, seed);
        seed += 1;
        for i in 0..n {
            x[(i, c)] = s[i];
        }
    }
    let mut m = 0usize;
    let mut restarts = 0usize;
    let mut columns = 0usize;
    let mut best = f64::INFINITY;
    let mut v = Mat::<f64>::zeros(n, m_cap);
    let mut hv = Mat::<f64>::zeros(n, m_cap);
    loop {
        // Expand by blocks until the basis is full.
        while m < m_cap {
            let width = x.ncols().min(m_cap - m);
            let mut block = x.as_ref().get(.., 0..width).to_owned();
            let added = orthonormalise(v.as_ref().get(.., 0..m), block.as_mut(), &mut seed, par);
            if added == 0 {
                break;
            }
            let block = block.as_ref().get(.., 0..added);
            v.as_mut().get_mut(.., m..m + added).copy_from(block);
            let mut hb = Mat::<f64>::zeros(n, added);
            op.apply_to(hb.as_mut(), block, par);
            columns += added;
            hv.as_mut().get_mut(.., m..m + added).copy_from(&hb);
            m += added;
            x = hb;
        }
        // Rayleigh–Ritz with T = Vᵀ (H V), symmetrised.
        let vm = v.as_ref().get(.., 0..m);
        let hvm = hv.as_ref().get(.., 0..m);
        let mut t = Mat::<f64>::zeros(m, m);
        matmul(t.as_mut(), Accum::Replace, vm.transpose(), hvm, 1.0, par);
        let ts = Mat::<f64>::from_fn(m, m, |i, j| 0.5 * (t[(i, j)] + t[(j, i)]));
        let evd = ts
            .self_adjoint_eigen(Side::Lower)
            .map_err(|_| f64::INFINITY)?;
        let vals: Vec<f64> = (0..m).map(|i| evd.S().column_vector()[i]).collect();
        let mut order: Vec<usize> = (0..m).collect();
        order.sort_by(|&a, &c| key(vals[c]).total_cmp(&key(vals[a])));
        let keep: Vec<usize> = order.iter().copied().take(k_keep.min(m)).collect();
        let s = Mat::<f64>::from_fn(m, keep.len(), |r, c| evd.U()[(r, keep[c])]);
        let mut u = Mat::<f64>::zeros(n, keep.len());
        let mut hu = Mat::<f64>::zeros(n, keep.len());
        matmul(u.as_mut(), Accum::Replace, vm, s.as_ref(), 1.0, par);
        matmul(hu.as_mut(), Accum::Replace, hvm, s.as_ref(), 1.0, par);
        let theta: Vec<f64> = keep.iter().map(|&i| vals[i]).collect();
        let mut r = hu.clone();
        let mut rnorm = vec![0.0; keep.len()];
        for c in 0..keep.len() {
            let mut acc = 0.0;
            for i in 0..n {
                let d = hu[(i, c)] - theta[c] * u[(i, c)];
                r[(i, c)] = d;
                acc += d * d;
            }
            rnorm[c] = acc.sqrt();
        }
        let wanted = k.min(keep.len());
        let est = rnorm.iter().take(wanted).copied().fold(0.0, f64::max);
        let exhausted = m >= n;
        if est <= settings.tol || exhausted || restarts >= MAX_BLOCK_RESTARTS {
            let values: Vec<f64> = theta.iter().copied().take(wanted).collect();
            let vectors = u.as_ref().get(.., 0..wanted).to_owned();
            let res = residuals(op, &values, vectors.as_ref(), par);
            let max = res.iter().copied().fold(0.0, f64::max);
            if max <= settings.accept {
                return Ok(Eigenpairs {
                    values,
                    vectors,
                    residuals: res,
                    work: super::LanczosWork {
                        restarts,
                        columns: columns + wanted,
                    },
                });
            }
            best = best.min(max);
            if exhausted || restarts >= MAX_BLOCK_RESTARTS {
                return Err(best);
            }
        }
        // Thick restart: keep the best Ritz pairs, continue from unconverged residuals.
        restarts += 1;
        let mut next: Vec<usize> = (0..wanted).filter(|&c| rnorm[c] > settings.tol).collect();
        next.extend((wanted..keep.len()).filter(|&c| rnorm[c] > settings.tol));
        next.truncate(b);
        x = Mat::<f64>::from_fn(n, next.len().max(1), |i, c| {
            next.get(c).map_or(0.0, |&col| r[(i, col)])
        });
        v.as_mut().get_mut(.., 0..keep.len()).copy_from(&u);
        hv.as_mut().get_mut(.., 0..keep.len()).copy_from(&hu);
        m = keep.len();
    }
}

/// Orthonormalises the columns of `x` against the orthonormal `v` (two classical Gram–Schmidt
/// passes) and among themselves (modified Gram–Schmidt, twice), compacting the surviving
/// columns to the front; a column that vanishes is replaced by a fresh start vector. Returns
/// how many columns are valid (0 only when `v` already spans the space).
fn orthonormalise(v: MatRef<'_, f64>, mut x: MatMut<'_, f64>, seed: &mut u64, par: Par) -> usize {
    let n = x.nrows();
    let width = x.ncols();
    if v.ncols() >= n {
        return 0;
    }
    let mut proj = Mat::<f64>::zeros(v.ncols(), width);
    for _ in 0..2 {
        if v.ncols() > 0 {
            matmul(
                proj.as_mut(),
                Accum::Replace,
                v.transpose(),
                x.rb(),
                1.0,
                par,
            );
            matmul(x.rb_mut(), Accum::Add, v, proj.as_ref(), -1.0, par);
        }
    }
    let mut good = 0usize;
    for c in 0..width {
        let mut attempts = 0;
        loop {
            let before = x.rb().col(c).norm_l2();
            for _ in 0..2 {
                for q in 0..good {
                    let d: f64 = (0..n).map(|i| x[(i, q)] * x[(i, c)]).sum();
                    for i in 0..n {
                        let xq = x[(i, q)];
                        x[(i, c)] -= d * xq;
                    }
                }
            }
            let after = x.rb().col(c).norm_l2();
            if after > 1e-8 * before.max(f64::MIN_POSITIVE) && after > 1e-300 {
                for i in 0..n {
                    let val = x[(i, c)] / after;
                    x[(i, good)] = val;
                }
                good += 1;
                break;
            }
            attempts += 1;
            if attempts > 3 || v.ncols() + good >= n {
                break;
            }
            // Vanished: a fresh generic direction, orthogonalised against v.
            let fresh = start_vector(n, *seed);
            *seed += 1;
            for i in 0..n {
                x[(i, c)] = fresh[i];
            }
            if v.ncols() > 0 {
                let mut pc = Mat::<f64>::zeros(v.ncols(), 1);
                for _ in 0..2 {
                    let xc = x.rb().get(.., c..c + 1).to_owned();
                    matmul(
                        pc.as_mut(),
                        Accum::Replace,
                        v.transpose(),
                        xc.as_ref(),
                        1.0,
                        par,
                    );
                    let mut xcm = x.rb_mut().get_mut(.., c..c + 1);
                    matmul(xcm.rb_mut(), Accum::Add, v, pc.as_ref(), -1.0, par);
                }
            }
        }
        if v.ncols() + good >= n {
            break;
        }
    }
    good
}
