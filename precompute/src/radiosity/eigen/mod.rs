//! Radiosity eigenbasis of one spectral band (docs/math.md, "Default formulation: split" and
//! "Seed errata").
//!
//! Input: `G = A F` (n×n, symmetric, m²), patch areas `A_i` (m²) and reflectances `ρ_i ∈ [0, 1)`.
//! Patches with `ρ_i = 0` ("black", e.g. a luminaire's emitting face) take no part in the
//! eigenproblem: their rows of the mode vectors are zero and their emission reaches the room
//! through an exact first bounce (docs/math.md, "Zero reflectance"; see [`Modes::exitance`]).
//! Everything below works on the reflecting subsystem `r = {i : ρ_i > 0}` of size `n_r`.
//!
//! - [`Formulation::Split`] (default): `G v = μ B v`, `B = diag(A/ρ)`, computed as the ordinary
//!   symmetric problem `H u = μ u` with `H = diag(√w) G diag(√w)`, `w = ρ/A`, `v = √w ∘ u`.
//!   Then `(I − R F)⁻¹ = I + V diag(μ/(1−μ)) Vᵀ B` exactly, and the modes with the largest
//!   `|c_k| = |μ_k/(1−μ_k)|` are kept.
//! - [`Formulation::Seed`]: the seed paper's `S = A R⁻¹ (I − R F) = B − G`, corrected (errata 1
//!   and 2): `S⁻¹ = V diag(1/λ) Vᵀ`, keeping the smallest `λ`.

mod krylov;
#[cfg(test)]
mod tests;

use faer::linalg::matmul::matmul;
use faer::{Accum, Mat, MatRef, Par, Side};
use krylov::{block_lanczos, KrylovSettings, ScaledOp};

use crate::formfactor::operator::FormFactorOperator;

/// Which eigenproblem the basis diagonalises: the runtime's own type, so that the name a
/// basis records is the one the precompute used.
pub use eigenrad_runtime::Formulation;

/// Which eigensolver to run.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Solver {
    /// Dense for `n_r ≤` [`AUTO_DENSE_MAX`] (and always for [`Formulation::Seed`]), partial above.
    #[default]
    Auto,
    /// Full self-adjoint eigendecomposition (faer), `O(n_r³)`.
    Dense,
    /// Krylov solver for the wanted modes only, applying `H` as an operator.
    Partial,
}

/// Which algorithm actually produced the modes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Method {
    /// faer's dense self-adjoint eigendecomposition.
    Dense,
    /// Our thick-restart block Lanczos with full reorthogonalisation (bounded restarts), the
    /// operator applied to 16 vectors at once.
    Lanczos,
}

/// Above this many reflecting patches [`Solver::Auto`] uses the partial solver: defined with
/// the memory model of a build, which depends on it.
pub use crate::memory::AUTO_DENSE_MAX;

/// Relative asymmetry `max |G_ij − G_ji| / max |G|` accepted in the input.
pub const SYMMETRY_TOLERANCE: f64 = 1e-10;

/// Accepted explicit residual `‖H u − μ u‖₂` of a partial-solver eigenpair (`‖H‖ < 1`).
pub const RESIDUAL_TOLERANCE: f64 = 1e-9;

/// A truncated eigenbasis of one band.
#[derive(Debug, Clone)]
pub struct Modes {
    /// The formulation these modes belong to.
    pub formulation: Formulation,
    /// Split: `μ_k` (eigenvalues of `R F`, `|μ| < 1`), ordered by decreasing `|μ/(1−μ)|`.
    /// Seed: `λ_k` (eigenvalues of `S = B − G` on the reflecting subsystem, m²), increasing.
    pub values: Vec<f64>,
    /// `n × p`, zero rows for black patches. Split: `v = √w ∘ u`, so `Vᵀ B V = I` and
    /// `R F v = μ v`. Seed: orthonormal eigenvectors of `S`.
    pub vectors: Mat<f64>,
    /// The solver path that ran: [`Solver::Dense`] or [`Solver::Partial`], never `Auto`.
    pub solver_used: Solver,
    /// The algorithm that produced the result.
    pub method: Method,
    /// Largest `‖H u − μ u‖₂` over the kept modes (split: unit `u`, dimensionless;
    /// seed: `‖S v − λ v‖₂` in m²).
    pub max_residual: f64,
    /// What the partial solver took; `None` from the dense one.
    pub work: Option<LanczosWork>,
}

/// The work of one block Lanczos solve: what its time is made of.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct LanczosWork {
    /// Thick restarts before every wanted pair converged.
    pub restarts: usize,
    /// Vectors the operator was applied to (columns of its products), the final check of
    /// the residuals included.
    pub columns: usize,
}

/// Failures of the eigen- and exact solves.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum EigenError {
    /// An input has the wrong length (`what` names it).
    #[error("{what}: expected {expected} entries, found {found}")]
    DimensionMismatch {
        /// Which input.
        what: &'static str,
        /// Expected length.
        expected: usize,
        /// Actual length.
        found: usize,
    },
    /// A patch area is not finite and positive.
    #[error("patch {patch}: area {value} m² is not finite and positive")]
    BadArea {
        /// Patch index.
        patch: usize,
        /// The area.
        value: f64,
    },
    /// A reflectance is outside `[0, 1)` (`ρ = 1` makes `I − R F` singular in a closed room).
    #[error("patch {patch}: reflectance {value} is outside [0, 1)")]
    BadReflectance {
        /// Patch index.
        patch: usize,
        /// The reflectance.
        value: f64,
    },
    /// `G` holds a NaN or infinity.
    #[error("G[{row}, {col}] is not finite")]
    NonFinite {
        /// Row.
        row: usize,
        /// Column.
        col: usize,
    },
    /// `G = A F` is not symmetric (reciprocity); symmetrise it first (docs/math.md, "Notation").
    #[error("G is not symmetric: |G[{row},{col}] − G[{col},{row}]| = {asymmetry:e} > {tolerance:e} (relative)")]
    NotSymmetric {
        /// Row of the worst pair.
        row: usize,
        /// Column of the worst pair.
        col: usize,
        /// Relative asymmetry found.
        asymmetry: f64,
        /// Relative asymmetry accepted.
        tolerance: f64,
    },
    /// faer's dense eigendecomposition did not converge.
    #[error("dense eigendecomposition did not converge")]
    DenseNoConvergence,
    /// The partial solver (thick-restart Lanczos) did not reach the residual tolerance within
    /// its restart bound.
    #[error("partial eigensolver: residual {residual:e} > {tolerance:e} for {wanted} modes")]
    NoConvergence {
        /// Modes wanted.
        wanted: usize,
        /// Best maximal residual reached.
        residual: f64,
        /// Residual accepted.
        tolerance: f64,
    },
    /// The requested combination is not implemented.
    #[error("not supported: {0}")]
    Unsupported(&'static str),
    /// The LU factorisation of `I − R F` found it singular.
    #[error("I − R F is singular (pivot {pivot})")]
    Singular {
        /// Index of the zero pivot.
        pivot: usize,
    },
}

/// Checks `g` (n×n, finite, symmetric), `area` (> 0) and `reflectance` (in `[0, 1)`).
pub(crate) fn check_inputs(
    g: &dyn FormFactorOperator,
    area: &[f64],
    reflectance: &[f64],
) -> Result<(), EigenError> {
    let n = g.len();
    if area.len() != n {
        return Err(EigenError::DimensionMismatch {
            what: "area",
            expected: n,
            found: area.len(),
        });
    }
    if reflectance.len() != n {
        return Err(EigenError::DimensionMismatch {
            what: "reflectance",
            expected: n,
            found: reflectance.len(),
        });
    }
    if let Some((patch, &value)) = area
        .iter()
        .enumerate()
        .find(|(_, a)| !(a.is_finite() && **a > 0.0))
    {
        return Err(EigenError::BadArea { patch, value });
    }
    if let Some((patch, &value)) = reflectance
        .iter()
        .enumerate()
        .find(|(_, r)| !(**r >= 0.0 && **r < 1.0))
    {
        return Err(EigenError::BadReflectance { patch, value });
    }
    if g.checked_when_built() {
        return Ok(());
    }
    let mut gmax = 0.0f64;
    for j in 0..n {
        for i in 0..n {
            let x = g.entry(i, j);
            if !x.is_finite() {
                return Err(EigenError::NonFinite { row: i, col: j });
            }
            gmax = gmax.max(x.abs());
        }
    }
    let mut worst = (0.0f64, 0, 0);
    for j in 0..n {
        for i in j + 1..n {
            let d = (g.entry(i, j) - g.entry(j, i)).abs();
            if d > worst.0 {
                worst = (d, i, j);
            }
        }
    }
    let asymmetry = if gmax > 0.0 { worst.0 / gmax } else { 0.0 };
    if asymmetry > SYMMETRY_TOLERANCE {
        return Err(EigenError::NotSymmetric {
            row: worst.1,
            col: worst.2,
            asymmetry,
            tolerance: SYMMETRY_TOLERANCE,
        });
    }
    Ok(())
}

/// The reflecting subsystem `r = {i : ρ_i > 0}` (docs/math.md, "Zero reflectance").
fn reflecting(reflectance: &[f64]) -> Vec<usize> {
    (0..reflectance.len())
        .filter(|&i| reflectance[i] > 0.0)
        .collect()
}

/// `c = μ / (1 − μ)`, the weight of a split mode in `(I − R F)⁻¹ − I` (docs/math.md).
pub fn split_weight(mu: f64) -> f64 {
    mu / (1.0 - mu)
}

/// Computes `p` modes of one band (docs/math.md, "Default formulation: split"; "Seed errata").
///
/// If `p > n_r` (the number of reflecting patches), `n_r` modes are returned: no padding, so
/// `values.len() == vectors.ncols() == min(p, n_r)`.
///
/// Solver choice: [`Solver::Auto`] runs the dense path for `n_r ≤` [`AUTO_DENSE_MAX`] and for
/// every seed problem. [`Solver::Partial`] falls back to dense when `2p + 16 ≥ n_r` (tiny
/// problems, where a Krylov basis would be as large as the matrix; `solver_used` tells).
/// [`Solver::Partial`] with [`Formulation::Seed`] is [`EigenError::Unsupported`]: the seed needs
/// the *smallest* eigenvalues of `S`, which need a shift-invert the project has no use for
/// beyond comparison.
///
/// Split, partial: thick-restart block Lanczos (module `krylov`, `G` applied to a block of
/// vectors at once) selects the Ritz pairs by `|c|`
/// directly; Lanczos converges the ends of the spectrum first, where `|c|` is largest. Not
/// faer's Krylov–Schur: it hangs in faer 0.24 (issue 262; see `krylov`). Every returned pair
/// has an explicit residual `‖H u − μ u‖₂ ≤` [`RESIDUAL_TOLERANCE`], else
/// [`EigenError::NoConvergence`].
pub fn modes(
    g: &dyn FormFactorOperator,
    area: &[f64],
    reflectance: &[f64],
    formulation: Formulation,
    p: usize,
    solver: Solver,
) -> Result<Modes, EigenError> {
    check_inputs(g, area, reflectance)?;
    let r = reflecting(reflectance);
    let p = p.min(r.len());
    if p == 0 {
        // All patches black (or p = 0): no interreflection modes (faer's EVD rejects n = 0).
        return Ok(Modes {
            formulation,
            values: Vec::new(),
            vectors: Mat::zeros(g.len(), 0),
            solver_used: if solver == Solver::Partial {
                Solver::Partial
            } else {
                Solver::Dense
            },
            method: Method::Dense,
            max_residual: 0.0,
            work: None,
        });
    }
    match formulation {
        Formulation::Split => {
            let s: Vec<f64> = r
                .iter()
                .map(|&i| (reflectance[i] / area[i]).sqrt())
                .collect();
            let partial = match solver {
                Solver::Dense => false,
                Solver::Partial => true,
                Solver::Auto => r.len() > AUTO_DENSE_MAX,
            };
            if partial {
                if let Some(m) = split_partial(g, &r, &s, p)? {
                    return Ok(m);
                }
            }
            split_dense(g, &r, &s, p)
        }
        Formulation::Seed => match solver {
            Solver::Partial => Err(EigenError::Unsupported(
                "partial solver for the seed formulation",
            )),
            Solver::Dense | Solver::Auto => seed_dense(g, area, reflectance, &r, p),
        },
    }
}

fn par() -> Par {
    faer::get_global_parallelism()
}

/// Scatters `u` (n_r × p, columns `cols`) into `n × p` with rows scaled by `scale`.
fn scatter(n: usize, r: &[usize], scale: &[f64], u: MatRef<'_, f64>, cols: &[usize]) -> Mat<f64> {
    let mut v = Mat::<f64>::zeros(n, cols.len());
    for (c, &k) in cols.iter().enumerate() {
        for (i, &ri) in r.iter().enumerate() {
            v[(ri, c)] = scale[i] * u[(i, k)];
        }
    }
    v
}

fn split_dense(
    g: &dyn FormFactorOperator,
    r: &[usize],
    s: &[f64],
    p: usize,
) -> Result<Modes, EigenError> {
    let nr = r.len();
    let h = Mat::<f64>::from_fn(nr, nr, |i, j| s[i] * g.entry(r[i], r[j]) * s[j]);
    let evd = h
        .self_adjoint_eigen(Side::Lower)
        .map_err(|_| EigenError::DenseNoConvergence)?;
    let mu: Vec<f64> = (0..nr).map(|i| evd.S().column_vector()[i]).collect();
    let mut order: Vec<usize> = (0..nr).collect();
    order.sort_by(|&a, &b| {
        split_weight(mu[b])
            .abs()
            .total_cmp(&split_weight(mu[a]).abs())
    });
    order.truncate(p);
    let u = evd.U();
    // Residual of the kept pairs, for the record.
    let up = Mat::<f64>::from_fn(nr, p, |i, c| u[(i, order[c])]);
    let mut hu = Mat::<f64>::zeros(nr, p);
    matmul(
        hu.as_mut(),
        Accum::Replace,
        h.as_ref(),
        up.as_ref(),
        1.0,
        par(),
    );
    let max_residual = (0..p)
        .map(|c| {
            (0..nr)
                .map(|i| (hu[(i, c)] - mu[order[c]] * up[(i, c)]).powi(2))
                .sum::<f64>()
                .sqrt()
        })
        .fold(0.0, f64::max);
    Ok(Modes {
        formulation: Formulation::Split,
        values: order.iter().map(|&k| mu[k]).collect(),
        vectors: scatter(g.len(), r, s, u, &order),
        solver_used: Solver::Dense,
        method: Method::Dense,
        max_residual,
        work: None,
    })
}

/// Settings of the partial path (absolute tolerances: `‖H‖ ≤ ρmax < 1`).
fn krylov_settings() -> KrylovSettings {
    KrylovSettings {
        tol: RESIDUAL_TOLERANCE / 10.0,
        accept: RESIDUAL_TOLERANCE,
    }
}

/// Key by which split modes are kept: `|c| = |μ/(1−μ)|`.
fn split_key(mu: f64) -> f64 {
    split_weight(mu).abs()
}

/// Split modes from the partial solver (block Lanczos with full reorthogonalisation, see
/// [`krylov`]); `Ok(None)` when the problem is too small for a Krylov method to pay off.
fn split_partial(
    g: &dyn FormFactorOperator,
    r: &[usize],
    s: &[f64],
    p: usize,
) -> Result<Option<Modes>, EigenError> {
    let nr = r.len();
    if p == 0 || 2 * p + 16 >= nr {
        return Ok(None);
    }
    let op = ScaledOp::new(g, r, s);
    let settings = krylov_settings();
    let pairs = block_lanczos(&op, p, split_key, settings, par()).map_err(|residual| {
        EigenError::NoConvergence {
            wanted: p,
            residual,
            tolerance: settings.accept,
        }
    })?;
    let max_residual = pairs.residuals.iter().copied().fold(0.0, f64::max);
    let order: Vec<usize> = (0..p).collect();
    Ok(Some(Modes {
        formulation: Formulation::Split,
        vectors: scatter(g.len(), r, s, pairs.vectors.as_ref(), &order),
        values: pairs.values,
        solver_used: Solver::Partial,
        method: Method::Lanczos,
        max_residual,
        work: Some(pairs.work),
    }))
}

fn seed_dense(
    g: &dyn FormFactorOperator,
    area: &[f64],
    reflectance: &[f64],
    r: &[usize],
    p: usize,
) -> Result<Modes, EigenError> {
    let nr = r.len();
    let smat = Mat::<f64>::from_fn(nr, nr, |i, j| {
        let b = if i == j {
            area[r[i]] / reflectance[r[i]]
        } else {
            0.0
        };
        b - g.entry(r[i], r[j])
    });
    let evd = smat
        .self_adjoint_eigen(Side::Lower)
        .map_err(|_| EigenError::DenseNoConvergence)?;
    // faer returns eigenvalues in nondecreasing order: the smallest λ are the first p.
    let order: Vec<usize> = (0..p).collect();
    let lambda: Vec<f64> = (0..p).map(|i| evd.S().column_vector()[i]).collect();
    let u = evd.U();
    let up = u.get(.., 0..p);
    let mut su = Mat::<f64>::zeros(nr, p);
    matmul(su.as_mut(), Accum::Replace, smat.as_ref(), up, 1.0, par());
    let max_residual = (0..p)
        .map(|c| {
            (0..nr)
                .map(|i| (su[(i, c)] - lambda[c] * up[(i, c)]).powi(2))
                .sum::<f64>()
                .sqrt()
        })
        .fold(0.0, f64::max);
    Ok(Modes {
        formulation: Formulation::Seed,
        values: lambda,
        vectors: scatter(g.len(), r, &vec![1.0; nr], u, &order),
        solver_used: Solver::Dense,
        method: Method::Dense,
        max_residual,
        work: None,
    })
}

impl Modes {
    /// Number of modes kept.
    pub fn len(&self) -> usize {
        self.values.len()
    }

    /// True if no mode was kept.
    pub fn is_empty(&self) -> bool {
        self.values.is_empty()
    }

    /// Final exitance `M` (W/m² or lm/m², as `m0`) from initial exitance `m0` with these modes.
    ///
    /// Black patches (`ρ_k = 0`) keep `M_k = M0_k`; their emission enters the reflecting
    /// subsystem through its exact first bounce `y_r = R F_rk M0_k = B_r⁻¹ G_rk M0_k`
    /// (docs/math.md, "Zero reflectance"; from `M_r = M0_r + R F_rr M_r + R F_rk M0_k`):
    ///
    /// - split: `M_r = M0_r + y_r + V diag(c) Vᵀ (b ∘ M0_r + G_rk M0_k)`, `c = μ/(1−μ)`.
    ///   With all `n_r` modes `y_r = V Vᵀ B y_r`, so the black part equals
    ///   `V diag(1/(1−μ)) Vᵀ (G_rk M0_k)`; under truncation the form above keeps the first
    ///   bounce of black emitters exact.
    /// - seed: `M_r = S⁻¹ (B M0_r + G_rk M0_k) ≈ V diag(1/λ) Vᵀ (b ∘ M0_r + G_rk M0_k)`.
    ///
    /// Exact (to rounding) when all `n_r` modes are kept (docs/math.md, "Exact results").
    #[track_caller]
    pub fn exitance(
        &self,
        g: &dyn FormFactorOperator,
        area: &[f64],
        reflectance: &[f64],
        m0: &[f64],
    ) -> Vec<f64> {
        let n = g.len();
        assert!(
            area.len() == n && reflectance.len() == n && m0.len() == n && self.vectors.nrows() == n,
            "Modes::exitance: dimensions disagree"
        );
        // source_r = b ∘ M0_r + G_rk M0_k (zero on black rows)
        let black: Vec<usize> = (0..n).filter(|&k| reflectance[k] == 0.0).collect();
        let mut source = vec![0.0; n];
        for i in 0..n {
            if reflectance[i] > 0.0 {
                let gk: f64 = black.iter().map(|&k| g.entry(i, k) * m0[k]).sum();
                source[i] = area[i] / reflectance[i] * m0[i] + gk;
            }
        }
        let p = self.len();
        let mut m = match self.formulation {
            Formulation::Split => {
                let mut m = m0.to_vec();
                for i in 0..n {
                    if reflectance[i] > 0.0 && !black.is_empty() {
                        let gk: f64 = black.iter().map(|&k| g.entry(i, k) * m0[k]).sum();
                        m[i] += reflectance[i] / area[i] * gk;
                    }
                }
                m
            }
            Formulation::Seed => {
                let mut m = vec![0.0; n];
                for &k in &black {
                    m[k] = m0[k];
                }
                m
            }
        };
        for k in 0..p {
            let v = self.vectors.col(k);
            let proj: f64 = (0..n).map(|i| v[i] * source[i]).sum();
            let weight = match self.formulation {
                Formulation::Split => split_weight(self.values[k]),
                Formulation::Seed => 1.0 / self.values[k],
            };
            for i in 0..n {
                m[i] += weight * proj * v[i];
            }
        }
        m
    }
}
