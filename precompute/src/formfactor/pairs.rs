//! The exchange areas of chosen pairs of patches only, not of every pair: what joins two rooms
//! built apart through an opening (`crate::building::port`).

use rayon::prelude::*;

use super::pair::{max_order, Context, Prepared};
use super::{FormFactorOptions, Occluders};
use crate::geometry::Patch;

/// `G_ab = (A_a F_ab + A_b F_ba) / 2` (m²) of each pair `(a, b)` of `pairs` among `patches`,
/// occluded by `occluders` (built from the same `patches`): the same pair integrals, and the
/// same symmetrisation, as [`super::patch_form_factors_with`] gives those entries of the whole
/// matrix. Deterministic: each pair is its own integral.
pub fn pair_exchanges(
    patches: &[Patch],
    occluders: &Occluders,
    opts: &FormFactorOptions,
    pairs: &[(usize, usize)],
) -> Vec<f64> {
    let prepared = Prepared::new(patches, max_order(opts));
    let ctx = Context::new(&prepared, occluders, opts, true);
    pairs
        .par_iter()
        .map(|&(a, b)| {
            if a == b {
                return 0.0;
            }
            // The matrix computes each pair with its lower index first: the same here.
            let (i, j) = (a.min(b), a.max(b));
            let gij = patches[i].area * ctx.pair(&prepared, i, j, &[i, j]);
            let gji = patches[j].area * ctx.pair(&prepared, j, i, &[i, j]);
            0.5 * (gij + gji)
        })
        .collect()
}
