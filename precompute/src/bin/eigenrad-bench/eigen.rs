//! `eigenrad-bench eigen`: the dense against the partial eigensolve on the same form
//! factors, and the partial one again on `G` rounded to f32.

use std::path::{Path, PathBuf};
use std::time::Instant;

use anyhow::{Context, Result};
use eigenrad_precompute::formfactor::{DenseF32, FormFactorOptions};
use eigenrad_precompute::pipeline;
use eigenrad_precompute::radiosity::eigen::{self, Formulation, Solver};

use crate::REFERENCE_MODES;

/// Prints the table's header and one row per scene; the dense solve runs up to `dense_max`
/// reflecting patches.
pub(crate) fn run(scenes: &[PathBuf], dense_max: usize) -> Result<()> {
    println!(
        "| patches | reflecting | partial (Lanczos) s | dense s | max |Δμ| dense vs partial | max |Δμ| with G stored in f32 | G in f64 MB | G in f32 MB |"
    );
    println!("|---|---|---|---|---|---|---|---|");
    for s in scenes {
        compare(s, dense_max)?;
    }
    Ok(())
}

/// One row: both eigensolves of the scene at `path`.
fn compare(path: &Path, dense_max: usize) -> Result<()> {
    let prepared = pipeline::prepare(path, &FormFactorOptions::default())?;
    let rho: Vec<f64> = prepared.scene.reflectance.iter().map(|r| r[0]).collect();
    let nr = rho.iter().filter(|&&r| r > 0.0).count();
    let g = prepared.system.operator();
    let area = &prepared.system.area;
    let t = Instant::now();
    let partial = eigen::modes(
        g,
        area,
        &rho,
        Formulation::Split,
        REFERENCE_MODES,
        Solver::Partial,
    )?;
    let partial_s = t.elapsed().as_secs_f64();
    let (dense_s, diff) = if nr <= dense_max {
        let t = Instant::now();
        let dense = eigen::modes(
            g,
            area,
            &rho,
            Formulation::Split,
            REFERENCE_MODES,
            Solver::Dense,
        )?;
        let s = t.elapsed().as_secs_f64();
        let d = dense
            .values
            .iter()
            .zip(&partial.values)
            .fold(0.0f64, |w, (a, b)| w.max((a - b).abs()));
        (format!("{s:.1}"), format!("{d:.1e}"))
    } else {
        ("not run".into(), "–".into())
    };
    // The same partial eigensolve on G rounded to f32: what storing G in single precision
    // would cost in accuracy (the eigenvalues μ are dimensionless, in (0, 1]).
    let n = rho.len();
    let dense = g.dense().context("the benchmark's operator is dense f64")?;
    let g32 = DenseF32::from_f64(dense, area);
    let rounded = eigen::modes(
        &g32,
        area,
        &rho,
        Formulation::Split,
        REFERENCE_MODES,
        Solver::Partial,
    )?;
    let f32_shift = rounded
        .values
        .iter()
        .zip(&partial.values)
        .fold(0.0f64, |w, (a, b)| w.max((a - b).abs()));
    let mb = |bytes: usize| (n * n * bytes) as f64 / 1e6;
    println!(
        "| {n} | {nr} | {partial_s:.1} | {dense_s} | {diff} | {f32_shift:.1e} | {:.0} | {:.0} |",
        mb(8),
        mb(4)
    );
    Ok(())
}
