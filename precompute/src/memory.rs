//! What a build of n patches holds in memory, the sizes at which its solvers change method
//! (and with it what they hold), and how much of the machine a build may take.
//!
//! The radiosity system is dense, so a build's memory is its n × n matrices: the
//! scene check (before meshing, from the estimated patch count) and the pipeline's check
//! (after meshing, before the form factors are allocated) both refuse a scene for which
//! [`build_bytes`] exceeds [`budget_bytes`]. The thresholds live here, not with the solvers
//! that use them, so that the scene stage can apply the model without depending on a later
//! stage.
//!
//! At its peak a build of `n` patches, `n_r` of them reflecting in a band, holds `G`
//! (`n²` entries of f64, or above [`AUTO_HIERARCHICAL_ABOVE`] patches the hierarchical
//! operator, [`hierarchical_bytes`]) and, one after the other:
//!
//! - while the modes are computed, for a band with `n_r ≤` [`AUTO_DENSE_MAX`] (the dense
//!   eigensolver): `5 n_r²`, namely the scaled matrix `H`, the eigenvectors `U` and faer's
//!   workspace, a copy reduced to tridiagonal form and the two matrices of divide and
//!   conquer (`faer::linalg::evd::self_adjoint_evd_scratch`). The partial (Lanczos)
//!   solver above it holds about `15 p + 150` vectors of length `n_r` (its basis of `6 p`
//!   vectors and their images, the Ritz pairs a restart keeps and their residuals), 0.5 GB
//!   for 32 modes of 100 000 patches, not counted: on the open-plan floor of 102 934 patches
//!   the build peaked at 2.16 GB elsewhere.
//! - while the exact reference is factorised, for `n ≤` [`EXACT_LU_MAX`]: one LU factor
//!   of `n²` per band, plus the matrix `I − R F` being factorised. Conjugate gradients
//!   above it hold a few vectors per case, not counted.
//!
//! Checked against `eigenrad-bench scale` and `eigen` (docs/performance.md): the model gives
//! 55, 184, 196 and 785 MB for the office at 1101, 2028, 4947 and 9905 patches in f64, whose
//! builds peaked at 77, 212, 278 and 875 MB (the rest is per-patch data and the program
//! itself); 392 MB at 9905 patches in f32 (`--operator dense-f32`), which peaked at 547 MB;
//! and 4.4 GB for the dense eigensolve at 9905 patches, which peaked at 4.1 GB.
//!
//! It is the model of `eigenrad build` with the default solver and the split formulation.
//! `--solver dense`, `--formulation seed` and `eigenrad verify` run the dense eigensolver at
//! any size: on scenes near the budget they need more.

use std::sync::OnceLock;

/// Largest patch count whose exact reference is an LU factorisation of `I − R F`
/// ([`crate::radiosity::exact::ExactSolver::auto`]: an `n²` f64 copy and `n³/3` flops per
/// band); above it the reference comes from conjugate gradients on `G` itself.
pub const EXACT_LU_MAX: usize = 3000;

/// Above this many reflecting patches [`crate::radiosity::eigen::Solver::Auto`] uses the
/// partial solver.
///
/// Measured by `eigenrad-bench eigen` (release, 2 idle cores, the office meshed finer,
/// p = 32; docs/performance.md): dense 0.2 s and partial 0.2 s at 1061 reflecting patches,
/// 0.7 s and 0.6 s at 1944, 14.7 s and 2.4 s at 4766. The crossover is near n = 2000.
pub const AUTO_DENSE_MAX: usize = 2000;

/// Above this many patches the form-factor operator's `auto` storage is the hierarchical
/// operator ([`crate::formfactor::OperatorChoice::Auto`]); at and below it the dense f64
/// matrix.
///
/// Measured by `eigenrad-bench compress --reference dense-f32` on the office at 1101, 2028
/// and 4947 patches (docs/performance.md, "The hierarchical operator"; one run on the 2-core
/// machine under a load of 5 to 9 from other builds, so times as ratios within a row): the
/// hierarchical operator holds 50 %, 50 % and 36 % of the dense f32 matrix, and its assembly
/// takes 1.16×, 0.65× and 0.98× the dense one's time; at 9905 patches it holds 24.5 % in
/// both runs and took 0.61× the time in one and 1.39× in the other, whose load doubled while
/// it ran. Memory favours it at every size, by a ratio that repeats between runs; the time
/// crossover is not resolved on the loaded machine (the times are of the same order: both
/// assemblies integrate about half of the entries at these sizes). Above this count, then,
/// dense f32 is never the better choice. Below this count the f64 matrix is kept all the same: it is exact where the
/// hierarchical operator is within about 1e-7, it fits an entry of the form-factor cache
/// (268 MB at this size), which makes a second run of the same scene fast, and the exact
/// reference up to [`EXACT_LU_MAX`] is an LU of it.
pub const AUTO_HIERARCHICAL_ABOVE: usize = 5792;

/// Bytes the form-factor operator of `patches` patches holds under the `auto` storage:
/// the f64 matrix up to [`AUTO_HIERARCHICAL_ABOVE`], the hierarchical operator above.
pub fn auto_operator_bytes(patches: f64) -> f64 {
    if patches > AUTO_HIERARCHICAL_ABOVE as f64 {
        hierarchical_bytes(patches)
    } else {
        matrix_bytes(patches)
    }
}

/// Bytes per patch and per level of the cluster tree that the hierarchical operator holds
/// ([`hierarchical_bytes`]). Measured by `eigenrad-bench compress` on the office
/// (docs/performance.md, "The hierarchical operator"): 675, 968 and 1173 at 2028, 4947 and
/// 9905 patches, still growing; 1500 leaves a margin above the largest.
pub const HIERARCHICAL_BYTES_PER_PATCH_LEVEL: f64 = 1500.0;

/// Bytes the hierarchical operator of `patches` patches is expected to hold: every patch
/// holds its near blocks and a share of the low-rank blocks of each level of the cluster tree
/// (`log₂(n / 32)` levels with leaves of 32 patches), a few hundred f32 values per level.
pub fn hierarchical_bytes(patches: f64) -> f64 {
    let levels = (patches / 32.0).max(2.0).log2();
    HIERARCHICAL_BYTES_PER_PATCH_LEVEL * patches * levels
}

/// Peak bytes of `eigenrad build` whose form-factor operator holds `operator_bytes`: as
/// [`build_bytes_stored`], with the LU reference counted only where it is made
/// (`lu_reference`: a dense f64 operator, up to [`EXACT_LU_MAX`] patches).
pub fn build_bytes_of(
    patches: f64,
    reflecting: &[f64],
    operator_bytes: f64,
    lu_reference: bool,
) -> f64 {
    let eigen = reflecting
        .iter()
        .filter(|&&r| r <= AUTO_DENSE_MAX as f64)
        .map(|&r| dense_eigen_bytes(r))
        .fold(0.0, f64::max);
    let reference = if lu_reference && patches <= EXACT_LU_MAX as f64 {
        (reflecting.len() as f64 + 1.0) * matrix_bytes(patches)
    } else {
        0.0
    };
    operator_bytes + eigen.max(reference)
}

/// Share of physical memory a build may plan to use: the rest is left to the per-patch data
/// the model does not count, the program and the rest of the machine.
pub const BUDGET_SHARE: f64 = 0.8;

/// Physical memory assumed when the platform does not tell, bytes.
const ASSUMED_MEMORY: f64 = 8e9;

/// Bytes of one entry of a dense matrix (f64).
const ENTRY_BYTES: f64 = 8.0;

/// Matrices of `n_r²` entries the dense eigensolver holds for one band: `H`, `U` and
/// faer's three of workspace.
const DENSE_EIGEN_MATRICES: f64 = 5.0;

/// Bytes of a dense `n × n` matrix of f64 (`n` may be an estimate, hence f64).
pub fn matrix_bytes(n: f64) -> f64 {
    n * n * ENTRY_BYTES
}

/// Bytes the dense eigensolver holds for one band of `reflecting` reflecting patches, on top
/// of `G`.
pub fn dense_eigen_bytes(reflecting: f64) -> f64 {
    DENSE_EIGEN_MATRICES * matrix_bytes(reflecting)
}

/// Peak bytes of `eigenrad build` (default solver, split formulation, `auto` operator) for
/// `patches` patches with `reflecting[b]` reflecting patches in band `b` (one entry per
/// band). Counts may be estimates.
pub fn build_bytes(patches: f64, reflecting: &[f64]) -> f64 {
    let dense = patches <= AUTO_HIERARCHICAL_ABOVE as f64;
    build_bytes_of(patches, reflecting, auto_operator_bytes(patches), dense)
}

/// [`build_bytes`] with the form-factor operator stored at `entry_bytes` bytes an entry (8 for
/// f64, 4 for f32).
pub fn build_bytes_stored(patches: f64, reflecting: &[f64], entry_bytes: f64) -> f64 {
    build_bytes_of(patches, reflecting, patches * patches * entry_bytes, true)
}

/// Bytes of a receiver form-factor matrix (`receivers × patches` f64): what a work plane of
/// `receivers` points holds while its row is computed, on top of a build.
pub fn receiver_bytes(receivers: f64, patches: f64) -> f64 {
    receivers * patches * ENTRY_BYTES
}

/// Bytes of the output rows (`outputs × patches` f64): one row per sensor, zone and grid
/// point, held from the form factors to the basis.
pub fn output_bytes(outputs: f64, patches: f64) -> f64 {
    outputs * patches * ENTRY_BYTES
}

/// Physical memory in bytes, read once (Linux `/proc/meminfo`; 8 GB assumed elsewhere).
pub fn physical_bytes() -> f64 {
    static PHYSICAL: OnceLock<f64> = OnceLock::new();
    *PHYSICAL.get_or_init(|| {
        std::fs::read_to_string("/proc/meminfo")
            .ok()
            .and_then(|s| {
                s.lines()
                    .find(|l| l.starts_with("MemTotal:"))
                    .and_then(|l| l.split_whitespace().nth(1))
                    .and_then(|kb| kb.parse::<f64>().ok())
            })
            .map_or(ASSUMED_MEMORY, |kb| kb * 1024.0)
    })
}

/// Bytes a build may plan to use: [`BUDGET_SHARE`] of [`physical_bytes`].
pub fn budget_bytes() -> f64 {
    BUDGET_SHARE * physical_bytes()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The model against the peaks `eigenrad-bench` measured on the office
    /// (docs/performance.md, "Precompute scaling" and "The operator in f32"; one band): it
    /// accounts for at least 70 % of each build's peak and overestimates none by more than
    /// 10 %.
    #[test]
    fn model_accounts_for_the_measured_peaks() {
        // (patches, reflecting, measured peak in MB, bytes per operator entry, dense
        // eigensolve forced)
        let measured = [
            (1101.0, 1061.0, 77.0, 8.0, false),
            (2028.0, 1944.0, 212.0, 8.0, false),
            (4947.0, 4766.0, 278.0, 8.0, false),
            (9905.0, 9514.0, 875.0, 8.0, false),
            (9905.0, 9514.0, 547.0, 4.0, false),
            (9905.0, 9514.0, 4100.0, 8.0, true),
        ];
        for (n, nr, peak, entry, dense) in measured {
            let model = if dense {
                matrix_bytes(n) + dense_eigen_bytes(nr)
            } else {
                build_bytes_stored(n, &[nr], entry)
            } / 1e6;
            let share = model / peak;
            assert!(
                (0.7..=1.1).contains(&share),
                "{n} patches, {entry} bytes an entry: model {model:.0} MB against a peak of {peak} MB"
            );
        }
        // The 9905-patch office is stored hierarchically by default.
        assert_eq!(
            build_bytes(9905.0, &[9514.0]),
            build_bytes_of(9905.0, &[9514.0], hierarchical_bytes(9905.0), false)
        );
    }

    /// The scene of `tests/scenes/too_many_patches.toml` (8.8e7 patches) needs 2.8e12 bytes
    /// for the hierarchical operator (the `auto` storage at that size), 6.2e16 for the f64
    /// matrix: beyond any ordinary machine either way.
    #[test]
    fn huge_scenes_need_the_form_factors_alone() {
        let n = 8.8e7;
        assert_eq!(build_bytes(n, &[n]), hierarchical_bytes(n));
        assert_eq!(build_bytes_stored(n, &[n], 8.0), matrix_bytes(n));
        assert!(build_bytes(n, &[n]) > 1e12);
    }

    /// `auto` keeps f64 up to its threshold and the compressed operator above it, which the
    /// office measured at 12 % of the f64 matrix at 9905 patches and the model counts at 22 %.
    #[test]
    fn auto_storage_compresses_the_operator_above_its_threshold() {
        let at = AUTO_HIERARCHICAL_ABOVE as f64;
        assert_eq!(auto_operator_bytes(at), matrix_bytes(at));
        assert_eq!(auto_operator_bytes(at + 1.0), hierarchical_bytes(at + 1.0));
        assert!(auto_operator_bytes(9905.0) < 0.25 * matrix_bytes(9905.0));
        // At and below the threshold the f64 matrix fits an entry of the form-factor cache.
        assert!(matrix_bytes(at) <= (256u64 << 20) as f64);
        assert!(matrix_bytes(at + 1.0) > (256u64 << 20) as f64);
    }
}
