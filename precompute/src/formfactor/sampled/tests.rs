//! Sampled visibility against the exact shadows on a closed room with many blockers.

use faer::Mat;

use super::Visibility;
use crate::formfactor::hierarchical::tests::open_plan_in_small;
use crate::formfactor::{patch_form_factors_with, FormFactorOptions, Occluders};

/// Points per side of the grids the test samples with: the command line's default.
const PER_SIDE: u32 = Visibility::DEFAULT_PER_SIDE;

/// Reflectance of every patch in the radiosity solve (dimensionless).
const REFLECTANCE: f64 = 0.7;

/// `B = E + ρ F B` by Jacobi iteration (ρ = [`REFLECTANCE`] < 1 and row sums near 1, so it
/// converges; 200 sweeps leave 0.7^200 of the first).
fn radiosity(f: &Mat<f64>, emission: &[f64]) -> Vec<f64> {
    let n = emission.len();
    let mut b = emission.to_vec();
    for _ in 0..200 {
        b = (0..n)
            .map(|i| emission[i] + REFLECTANCE * (0..n).map(|j| f[(i, j)] * b[j]).sum::<f64>())
            .collect();
    }
    b
}

/// Largest and root-mean-square of `|b − a| / scale`.
fn errors(a: &[f64], b: &[f64], scale: f64) -> (f64, f64) {
    let sq = a
        .iter()
        .zip(b)
        .map(|(x, y)| ((y - x) / scale).powi(2))
        .sum::<f64>();
    let worst = a
        .iter()
        .zip(b)
        .map(|(x, y)| (y - x).abs() / scale)
        .fold(0.0, f64::max);
    (worst, (sq / a.len() as f64).sqrt())
}

/// Reference: the exact shadows (the default visibility, itself checked against closed forms
/// in `formfactor::tests`) on the same patches of a closed 12 × 6 × 2.7 m room with six desks
/// and two columns (`open_plan_in_small`, most pairs with several blockers between them).
/// Tolerances, from this test's own run at 3 × 3 points (docs/performance.md, "Sampled
/// visibility", gives the figures): row sums within [`ROW_TOLERANCE`] of the exact ones,
/// the radiosity of a room lit from its ceiling within [`RADIOSITY_TOLERANCE`] of its
/// largest value, and the raw reciprocity no worse than the exact shadows' own (the two
/// directions of a sampled pair share one visible fraction). The
/// sampled matrix must differ from the exact one (the option is in use) and be the same bytes
/// when built again (a fixed pattern).
#[test]
fn sampled_visibility_stays_near_the_exact_shadows() {
    let (patches, _) = open_plan_in_small(0.9);
    let n = patches.len();
    let occluders = Occluders::new(&patches);
    let exact = patch_form_factors_with(&patches, &occluders, &FormFactorOptions::default());
    let opts = FormFactorOptions {
        visibility: Visibility::Sampled { per_side: PER_SIDE },
        ..FormFactorOptions::default()
    };
    let sampled = patch_form_factors_with(&patches, &occluders, &opts);

    let rows = errors(&exact.row_sums, &sampled.row_sums, 1.0);
    // Light from the ceiling (the patches facing down from z = 2.7 m), 1 W/m² each.
    let emission: Vec<f64> = patches
        .iter()
        .map(|p| f64::from(p.normal.z < -0.5 && p.centroid.z > 2.6))
        .collect();
    assert!(emission.iter().sum::<f64>() > 10.0);
    let (a, b) = (
        radiosity(&exact.matrix, &emission),
        radiosity(&sampled.matrix, &emission),
    );
    let largest = a.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    let light = errors(&a, &b, largest);
    let changed = (0..n)
        .flat_map(|i| (0..n).map(move |j| (i, j)))
        .filter(|&(i, j)| exact.matrix[(i, j)] != sampled.matrix[(i, j)])
        .count();
    eprintln!(
        "{n} patches, {changed} entries changed; row sums {:.1e} / {:.1e} (largest / RMS), radiosity {:.1e} / {:.1e}, reciprocity exact {:.1e} sampled {:.1e}",
        rows.0, rows.1, light.0, light.1, exact.reciprocity_mismatch, sampled.reciprocity_mismatch
    );
    assert!(changed > n, "only {changed} entries changed");
    assert!(rows.0 <= ROW_TOLERANCE, "row sums moved by {:.1e}", rows.0);
    assert!(
        light.0 <= RADIOSITY_TOLERANCE,
        "radiosity moved by {:.1e}",
        light.0
    );
    assert!(
        sampled.reciprocity_mismatch <= exact.reciprocity_mismatch,
        "reciprocity {:.1e} against {:.1e} exact",
        sampled.reciprocity_mismatch,
        exact.reciprocity_mismatch
    );
    let again = patch_form_factors_with(&patches, &occluders, &opts);
    assert!(
        (0..n)
            .all(|i| (0..n)
                .all(|j| again.matrix[(i, j)].to_bits() == sampled.matrix[(i, j)].to_bits())),
        "sampled visibility is not deterministic"
    );
}

/// Largest difference of a row sum, sampled against exact (dimensionless): 3.0e-2 measured
/// (RMS 4.1e-3, 390 patches, 46 576 entries changed).
const ROW_TOLERANCE: f64 = 5e-2;
/// Largest difference of a patch's radiosity, against the largest radiosity (dimensionless):
/// 1.2e-2 measured (RMS 2.0e-3).
const RADIOSITY_TOLERANCE: f64 = 2e-2;
