//! The daylight's first reflection as a basis stores it (docs/math.md, "Daylight's first
//! reflection"; docs/format.md, "First reflection"): the sky's part as a low-rank product,
//! the sun's as each node's list of the patches it reaches, and the mode amplitudes of what
//! the room reflects after it.
//!
//! A daylight node's initial exitance `M0_d` (its emission plus the first reflection of its
//! direct light, `ρ ∘ E_ext`) is local: the patches under a window, a sun patch. Through `p`
//! modes it is poor (docs/math.md, "Daylight in the basis"); stored apart, patch exitance
//! under daylight is `M0 + (M − M0)`, the first exact and only the smooth rest through the
//! modes, as the channels' first bounce was before their exact responses.

use faer::Mat;

use crate::radiosity::eigen::EigenError;
use crate::radiosity::model::Model;

/// Default of `eigenrad build --sky-rank-tolerance`: the sky's first reflection is kept to
/// this relative error in the area-weighted Frobenius norm (the RMS over patches and sky
/// nodes, each patch weighed by its area, of the dropped part against the whole). On the
/// example daylight office (p = 32) the patches' error under the overcast sky is 4.9 % at
/// 10⁻¹ (rank 18, 85 KB) and 4.7 % at 10⁻² (rank 43, 153 KB): what the modes carry after
/// the first reflection dominates, and 10⁻¹ keeps the office's f16 basis and its firmware
/// within 512 KiB of flash (docs/accuracy.md, "Daylight in the basis").
pub const DEFAULT_SKY_RANK_TOLERANCE: f64 = 1e-1;

/// A sun node's entries of its initial exitance smaller than this share of its largest are
/// not listed: what a diffusing window's quadratures leave on every patch (below 10⁻⁴ of
/// the direct light, docs/math.md, "Daylight through windows"). They stay in the exitance
/// the modes carry, so nothing is lost.
pub const SUN_LIST_FLOOR: f64 = 1e-6;

/// The tables of the first reflection, in the format's layout.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct FirstReflection {
    /// `r`.
    pub rank: usize,
    /// `r × (S_k + 1)`: each coefficient's weights of the sky's patches and the exterior.
    pub sky_weights: Vec<f64>,
    /// `n × r`, patch-major: each patch's first reflection per unit of each coefficient.
    pub sky: Vec<f64>,
    /// Relative error of the rank-`r` sky in the area-weighted Frobenius norm.
    pub sky_error: f64,
    /// Per sun node: its listed patches.
    pub sun_counts: Vec<u32>,
    /// The listed patches, node by node, ascending.
    pub sun_patches: Vec<u32>,
    /// Their first reflection, lux per lux of direct normal illuminance.
    pub sun_values: Vec<f64>,
    /// `p × (r + sun nodes)`: the mode amplitudes of the exitance that follows each
    /// coefficient's first reflection, then of each sun node's exitance less its listed
    /// entries.
    pub modes: Vec<f64>,
}

/// The first reflection of the daylight whose nodes' initial exitances are `initial` (sky
/// patches and the exterior first, `sky_nodes` of them, then the sun nodes) and whose exact
/// exitances are `exact`, in `model`'s room with `p` modes; the sky's rank the smallest within
/// `tolerance` ([`DEFAULT_SKY_RANK_TOLERANCE`]).
pub fn first_reflection(
    model: &Model,
    initial: &[Vec<f64>],
    exact: &[Vec<f64>],
    sky_nodes: usize,
    p: usize,
    tolerance: f64,
) -> Result<FirstReflection, EigenError> {
    let n = model.patch_count();
    let area = model.area();
    let (rank, sky, sky_weights, sky_error) = sky_factors(&initial[..sky_nodes], area, tolerance);
    // What follows each coefficient's first reflection: (I − R F)⁻¹ y_j − y_j.
    let mut columns = Mat::<f64>::zeros(n, rank);
    for i in 0..n {
        for j in 0..rank {
            columns[(i, j)] = sky[i * rank + j];
        }
    }
    let solved = model.system.solver(0)?.solve_many(columns.as_ref());
    let mut amplitudes: Vec<Vec<f64>> = (0..rank)
        .map(|j| {
            let rest: Vec<f64> = (0..n).map(|i| solved[(i, j)] - columns[(i, j)]).collect();
            model.mode_amplitudes(0, &rest, p)
        })
        .collect();
    let (mut sun_counts, mut sun_patches, mut sun_values) = (Vec::new(), Vec::new(), Vec::new());
    for (m0, m) in initial[sky_nodes..].iter().zip(&exact[sky_nodes..]) {
        let peak = m0.iter().fold(0.0f64, |a, x| a.max(x.abs()));
        let mut rest = m.clone();
        let mut count = 0u32;
        for (i, &x) in m0.iter().enumerate() {
            if x != 0.0 && x.abs() >= SUN_LIST_FLOOR * peak {
                sun_patches.push(i as u32);
                sun_values.push(x);
                rest[i] -= x;
                count += 1;
            }
        }
        sun_counts.push(count);
        amplitudes.push(model.mode_amplitudes(0, &rest, p));
    }
    let modes = (0..p)
        .flat_map(|k| amplitudes.iter().map(move |a| a[k]))
        .collect();
    Ok(FirstReflection {
        rank,
        sky_weights,
        sky,
        sky_error,
        sun_counts,
        sun_patches,
        sun_values,
        modes,
    })
}

/// The best rank-`r` approximation of the sky nodes' initial exitances `columns` (one per
/// node, `n` each) in the area-weighted Frobenius norm, `r` the smallest whose dropped part
/// is within `tolerance` of the whole: the thin SVD of `A^½ M0 = U Σ Wᵀ`, truncated, gives
/// the patch factor `A^-½ U_r Σ_r` (`n × r`, patch-major) and the weights `W_rᵀ`
/// (`r × nodes`, row-major). Each coefficient's sign makes its largest patch entry
/// positive, so that the bytes do not depend on the SVD's choice. Returns the rank, the two
/// factors and the relative error of the truncation.
fn sky_factors(
    columns: &[Vec<f64>],
    area: &[f64],
    tolerance: f64,
) -> (usize, Vec<f64>, Vec<f64>, f64) {
    let (n, nodes) = (area.len(), columns.len());
    if n == 0 || nodes == 0 {
        return (0, Vec::new(), Vec::new(), 0.0);
    }
    let root: Vec<f64> = area.iter().map(|a| a.sqrt()).collect();
    let weighted = Mat::<f64>::from_fn(n, nodes, |i, d| root[i] * columns[d][i]);
    let Ok(svd) = weighted.thin_svd() else {
        // faer's SVD converges for finite input, which every node's light is.
        return (0, Vec::new(), Vec::new(), 1.0);
    };
    let sigma: Vec<f64> = svd.S().column_vector().iter().copied().collect();
    let total: f64 = sigma.iter().map(|s| s * s).sum();
    let mut tail = total;
    let mut rank = 0;
    while rank < sigma.len() && tail > tolerance * tolerance * total {
        tail -= sigma[rank] * sigma[rank];
        rank += 1;
    }
    let (u, w) = (svd.U(), svd.V());
    let mut sky = vec![0.0; n * rank];
    let mut weights = vec![0.0; rank * nodes];
    for j in 0..rank {
        let largest = (0..n).fold(0.0f64, |m, i| {
            let x = u[(i, j)];
            if x.abs() > m.abs() {
                x
            } else {
                m
            }
        });
        let sign = if largest < 0.0 { -1.0 } else { 1.0 };
        for i in 0..n {
            sky[i * rank + j] = sign * u[(i, j)] * sigma[j] / root[i];
        }
        for d in 0..nodes {
            weights[j * nodes + d] = sign * w[(d, j)];
        }
    }
    let error = if total > 0.0 {
        (tail.max(0.0) / total).sqrt()
    } else {
        0.0
    };
    (rank, sky, weights, error)
}

/// The relative error, in the area-weighted Frobenius norm, of the best rank-`rank`
/// approximation of the sky nodes' initial exitances `columns` (as the build factors them): what the
/// build reports of the rank it stored.
pub fn sky_truncation_error(columns: &[Vec<f64>], area: &[f64], rank: usize) -> f64 {
    let (n, nodes) = (area.len(), columns.len());
    if n == 0 || nodes == 0 {
        return 0.0;
    }
    let weighted = Mat::<f64>::from_fn(n, nodes, |i, d| area[i].sqrt() * columns[d][i]);
    let Ok(svd) = weighted.thin_svd() else {
        return 1.0;
    };
    let sigma: Vec<f64> = svd.S().column_vector().iter().copied().collect();
    let total: f64 = sigma.iter().map(|s| s * s).sum();
    let tail: f64 = sigma.iter().skip(rank).map(|s| s * s).sum();
    if total > 0.0 {
        (tail / total).sqrt()
    } else {
        0.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A matrix of known rank 2 (area-weighted) is found to have rank 2 at any tolerance
    /// above rounding, and its factors give it back; a tolerance of 1 keeps nothing.
    #[test]
    fn a_rank_two_sky_is_recovered_from_its_factors() {
        let area = [0.5, 1.0, 2.0, 0.25, 1.5];
        let a = [1.0, 0.0, 2.0, 3.0, 1.0];
        let b = [0.0, 1.0, 1.0, -1.0, 2.0];
        let columns: Vec<Vec<f64>> = (0..4)
            .map(|d| {
                let (x, y) = (d as f64 + 1.0, (d * d) as f64 - 1.0);
                (0..5).map(|i| x * a[i] + y * b[i]).collect()
            })
            .collect();
        let (rank, sky, weights, error) = sky_factors(&columns, &area, 1e-9);
        assert_eq!(rank, 2);
        assert!(error <= 1e-9, "{error}");
        for (d, column) in columns.iter().enumerate() {
            for (i, &x) in column.iter().enumerate() {
                let back: f64 = (0..rank)
                    .map(|j| sky[i * rank + j] * weights[j * 4 + d])
                    .sum();
                assert!(
                    (back - x).abs() <= 1e-12 * 10.0,
                    "({i}, {d}): {back} vs {x}"
                );
            }
        }
        let (rank, _, _, error) = sky_factors(&columns, &area, 1.0);
        assert_eq!(rank, 0);
        assert!((error - 1.0).abs() < 1e-12);
    }
}
