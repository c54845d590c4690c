//! From form factors to irradiance: the exchange areas `G = A F` (m²), the irradiance a
//! pattern of exitance puts on every patch (`E = F M = A⁻¹ G M`) and on every output
//! (`E_o = Σ_j R_oj M_j`). The light sources and the radiosity model both go through these
//! functions, so a channel's direct light and the model's own propagation of its emission are
//! the same numbers.

use faer::Mat;

use crate::formfactor::operator::FormFactorOperator;

/// `G = A F` (m²) from the form factors `f` (n × n, symmetrised) and the patch areas (m²).
pub fn exchange_areas(mut f: Mat<f64>, area: &[f64]) -> Mat<f64> {
    // Column by column: contiguous in faer's layout.
    for j in 0..f.ncols() {
        for i in 0..f.nrows() {
            f[(i, j)] *= area[i];
        }
    }
    f
}

/// Irradiance on every patch, `E_i = (G M)_i / A_i` (W/m² or lux), from the exitance `M` of
/// every patch (same unit), `G` in m² and the areas in m².
pub fn patch_irradiance(g: &dyn FormFactorOperator, area: &[f64], exitance: &[f64]) -> Vec<f64> {
    let gm = g.apply_vector(exitance);
    (0..area.len()).map(|i| gm[i] / area[i]).collect()
}

/// Irradiance at every output (sensors, then zones), `E_o = Σ_j R_oj M_j` (W/m² or lux), from
/// the output rows `rows` (one per output, one value per patch) and the exitance of every
/// patch.
pub fn output_irradiance(rows: &[Vec<f64>], exitance: &[f64]) -> Vec<f64> {
    rows.iter()
        .map(|r| r.iter().zip(exitance).map(|(a, b)| a * b).sum())
        .collect()
}
