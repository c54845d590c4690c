//! How far computed form factors are from the identities exact ones satisfy: reciprocity
//! (`A_i F_ij = A_j F_ji`) and closure (every row of a closed room sums to 1).

use serde::Serialize;

use super::FormFactors;

/// Health of a scene's form-factor matrix: reciprocity before symmetrising and closure (row
/// sums) after, the figures `eigenrad build` reports.
#[derive(Clone, Debug, Serialize)]
pub struct FormFactorHealth {
    /// Worst reciprocity mismatch before symmetrising, relative to the pair's own exchange
    /// (or to 0.1 % of the smaller patch's output, whichever is larger).
    pub reciprocity_mismatch: f64,
    /// Worst reciprocity mismatch before symmetrising as a share of the smaller patch's
    /// output (`FormFactors::reciprocity_share`).
    pub reciprocity_share: f64,
    /// Smallest row sum of F after symmetrising.
    pub row_sum_min: f64,
    /// Largest row sum of F after symmetrising.
    pub row_sum_max: f64,
    /// Share of the light leaving the patches that leaves the scene: `Σ A_i (1 − Σ_j F_ij) /
    /// Σ A_i` (0 for a closed room; an open window or a missing ceiling raise it).
    pub escaping: f64,
    /// Whether every row sums to 1 within [`CLOSED_TOLERANCE`]: a closed scene. Otherwise the
    /// deficit is light leaving through openings.
    pub closed: bool,
}

/// Row-sum deviation up to which a scene counts as closed. With occlusion the symmetrised
/// form factors are accurate to a few 10⁻⁴ per row (the fixed outer quadrature where a shadow
/// edge crosses a source patch), so a much tighter bound would call closed rooms open; an opening that matters takes far more than
/// 1 % of the view of the patches facing it.
pub const CLOSED_TOLERANCE: f64 = 1e-2;

impl FormFactorHealth {
    /// The health of `ff`, whose patches have areas `area` (m²).
    pub fn of(ff: &FormFactors, area: &[f64]) -> FormFactorHealth {
        let row_sum_min = ff.row_sums.iter().copied().fold(f64::INFINITY, f64::min);
        let row_sum_max = ff
            .row_sums
            .iter()
            .copied()
            .fold(f64::NEG_INFINITY, f64::max);
        FormFactorHealth {
            reciprocity_mismatch: ff.reciprocity_mismatch,
            reciprocity_share: ff.reciprocity_share,
            row_sum_min,
            row_sum_max,
            escaping: ff
                .row_sums
                .iter()
                .zip(area)
                .map(|(s, a)| a * (1.0 - s))
                .sum::<f64>()
                / area.iter().sum::<f64>(),
            closed: (row_sum_min - 1.0).abs() <= CLOSED_TOLERANCE
                && (row_sum_max - 1.0).abs() <= CLOSED_TOLERANCE,
        }
    }
}
