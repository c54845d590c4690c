//! `eigenrad-bench compress`: the hierarchical operator against a dense one on the same
//! scene: memory, form-factor time, every channel's reading at every output and the strongest
//! eigenvalues, each scene prepared once with each operator in this process (one after the
//! other, so each holds its own operator alone).

use std::path::PathBuf;
use std::time::Instant;

use anyhow::{Context as _, Result};
use eigenrad_precompute::formfactor::{FormFactorOptions, OperatorChoice};
use eigenrad_precompute::pipeline::{self, Prepared};
use eigenrad_precompute::radiosity::eigen::{Formulation, Solver};
use eigenrad_precompute::radiosity::Model;

use crate::REFERENCE_MODES;

/// A reading this far below the largest reading of its channel is compared against that
/// floor rather than its own value (dimensionless).
const READING_FLOOR: f64 = 1e-9;

/// What one operator gave on a scene.
struct Run {
    storage: &'static str,
    bytes: usize,
    form_factor_seconds: f64,
    /// `[channel][output]`, every channel at level 1 alone (band 0).
    readings: Vec<Vec<f64>>,
    /// The strongest split eigenvalues of band 0.
    values: Vec<f64>,
    row_error: Option<f64>,
}

fn run_one(scene: &std::path::Path, operator: OperatorChoice) -> Result<Run> {
    let options = FormFactorOptions {
        operator,
        ..FormFactorOptions::default()
    };
    let start = Instant::now();
    let prepared: Prepared =
        pipeline::prepare(scene, &options).with_context(|| format!("{}", scene.display()))?;
    let form_factor_seconds = prepared
        .timings
        .iter()
        .filter(|s| s.stage == "form factors")
        .map(|s| s.seconds)
        .sum::<f64>();
    let system = &prepared.system;
    let channels = system.channel_count();
    let responses = system.channel_responses()?;
    let readings = (0..channels)
        .map(|c| {
            let mut levels = vec![0.0; channels];
            levels[c] = 1.0;
            system.readings(0, &responses[c][0], &levels)
        })
        .collect();
    let bands = Model::modes(system, Formulation::Split, REFERENCE_MODES, Solver::Auto)?;
    let values = bands
        .first()
        .map(|b| b.modes.values.clone())
        .unwrap_or_default();
    eprintln!(
        "  {} with {}: {:.1} s",
        scene.display(),
        system.operator().storage(),
        start.elapsed().as_secs_f64()
    );
    Ok(Run {
        storage: system.operator().storage(),
        bytes: system.operator().stored_bytes(),
        form_factor_seconds,
        readings,
        values,
        row_error: prepared.compression.as_ref().map(|c| c.row_error),
    })
}

/// Prints one row per scene: the hierarchical operator against `reference`.
pub(crate) fn run(scenes: &[PathBuf], reference: OperatorChoice) -> Result<()> {
    println!("| patches | reference | reference MB | hierarchical MB | memory ratio | reference form factors s | hierarchical form factors s | time ratio | worst reading difference | worst eigenvalue difference | measured row error |");
    println!("|---|---|---|---|---|---|---|---|---|---|---|");
    for scene in scenes {
        let patches = eigenrad_precompute::scene::load(scene)
            .with_context(|| format!("{}", scene.display()))?
            .patches
            .len();
        let dense = run_one(scene, reference)?;
        let compressed = run_one(scene, OperatorChoice::Hierarchical)?;
        let mut worst_reading = 0.0f64;
        for (a, b) in dense.readings.iter().zip(&compressed.readings) {
            let largest = a.iter().fold(0.0f64, |m, x| m.max(x.abs()));
            for (x, y) in a.iter().zip(b) {
                let scale = x.abs().max(READING_FLOOR * largest);
                if scale > 0.0 {
                    worst_reading = worst_reading.max((x - y).abs() / scale);
                }
            }
        }
        let worst_value = dense
            .values
            .iter()
            .zip(&compressed.values)
            .map(|(a, b)| (a - b).abs())
            .fold(0.0f64, f64::max);
        println!(
            "| {patches} | {} | {:.1} | {:.1} | {:.3} | {:.1} | {:.1} | {:.2} | {:.1e} | {:.1e} | {:.1e} |",
            dense.storage,
            dense.bytes as f64 / 1e6,
            compressed.bytes as f64 / 1e6,
            compressed.bytes as f64 / dense.bytes as f64,
            dense.form_factor_seconds,
            compressed.form_factor_seconds,
            compressed.form_factor_seconds / dense.form_factor_seconds,
            worst_reading,
            worst_value,
            compressed.row_error.unwrap_or(f64::NAN),
        );
    }
    Ok(())
}
