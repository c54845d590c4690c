//! `eigenrad-bench rays`: sampled visibility (`--visibility sampled`, and with `--clusters`
//! `--visibility clusters`) against the exact
//! shadows on the same scene: form-factor time, and how far the row sums, the products `G x`
//! and every channel's reading at every output move. Each scene is prepared once with exact
//! visibility and once per grid size in this process, one after the other, with the same
//! operator and no cache.

use std::path::{Path, PathBuf};

use anyhow::{Context as _, Result};
use eigenrad_precompute::formfactor::{
    FormFactorOperator, FormFactorOptions, OperatorChoice, Visibility,
};
use eigenrad_precompute::pipeline::{self, Prepared};

use crate::scale::cpu_seconds;

/// A reading this far below the largest reading of its channel is compared against that
/// floor rather than its own value (dimensionless).
const READING_FLOOR: f64 = 1e-9;

/// Vectors the two operators' products are compared on.
const PROBES: usize = 4;

/// What one visibility gave on a scene.
struct Run {
    /// Process CPU seconds of the whole preparation (the other stages are the same work).
    cpu: f64,
    /// Wall seconds of the form-factor stage.
    form_factor_wall: f64,
    row_sums: Vec<f64>,
    /// `G x` for each probe.
    products: Vec<Vec<f64>>,
    /// `[channel][output]`, every channel at level 1 alone (band 0).
    readings: Vec<Vec<f64>>,
}

/// Probe `k`: all ones, then fixed patterns of signs and sizes.
fn probe(n: usize, k: usize) -> Vec<f64> {
    (0..n)
        .map(|i| {
            if k == 0 {
                1.0
            } else {
                (((i * 7 + k * 13) % 17) as f64 - 8.0) / 8.0
            }
        })
        .collect()
}

fn run_one(scene: &Path, operator: OperatorChoice, visibility: Visibility) -> Result<Run> {
    let options = FormFactorOptions {
        operator,
        visibility,
        ..FormFactorOptions::default()
    };
    let cpu = cpu_seconds();
    let prepared: Prepared =
        pipeline::prepare(scene, &options).with_context(|| format!("{}", scene.display()))?;
    let cpu = cpu_seconds() - cpu;
    let form_factor_wall = prepared
        .timings
        .iter()
        .filter(|s| s.stage == "form factors")
        .map(|s| s.seconds)
        .sum::<f64>();
    let system = &prepared.system;
    let g: &dyn FormFactorOperator = system.operator();
    let areas: Vec<f64> = prepared.scene.patches.iter().map(|p| p.area).collect();
    let n = areas.len();
    let channels = system.channel_count();
    let responses = system.channel_responses()?;
    let readings = (0..channels)
        .map(|c| {
            let mut levels = vec![0.0; channels];
            levels[c] = 1.0;
            system.readings(0, &responses[c][0], &levels)
        })
        .collect();
    Ok(Run {
        cpu,
        form_factor_wall,
        row_sums: g.form_factor_row_sums(&areas),
        products: (0..PROBES).map(|k| g.apply_vector(&probe(n, k))).collect(),
        readings,
    })
}

/// (largest, root-mean-square) of `|b − a| / scale(a)` over paired values.
fn errors<'a>(
    pairs: impl Iterator<Item = (&'a f64, &'a f64)>,
    scale: impl Fn(f64) -> f64,
) -> (f64, f64) {
    let (mut worst, mut sq, mut count) = (0.0f64, 0.0, 0usize);
    for (a, b) in pairs {
        let s = scale(*a);
        if s > 0.0 {
            let e = (b - a).abs() / s;
            worst = worst.max(e);
            sq += e * e;
            count += 1;
        }
    }
    (worst, (sq / count.max(1) as f64).sqrt())
}

/// Prints one row per scene and visibility: the sampled form factors against the exact ones.
pub(crate) fn run(
    scenes: &[PathBuf],
    operator: OperatorChoice,
    points: &[u32],
    clusters: bool,
) -> Result<()> {
    println!("| scene | patches | visibility | CPU s | form factors wall s | CPU ratio | row sums largest / RMS | G x largest / RMS | readings largest / RMS |");
    println!("|---|---|---|---|---|---|---|---|---|");
    for scene in scenes {
        let exact = run_one(scene, operator, Visibility::Exact)?;
        let n = exact.row_sums.len();
        println!(
            "| {} | {n} | exact | {:.1} | {:.1} | 1 | | | |",
            scene.display(),
            exact.cpu,
            exact.form_factor_wall
        );
        let variants = points
            .iter()
            .map(|&per_side| {
                (
                    format!("sampled {per_side}×{per_side}"),
                    Visibility::Sampled { per_side },
                )
            })
            .chain(clusters.then(|| ("clusters".to_string(), Visibility::Clusters)));
        for (label, visibility) in variants {
            let s = run_one(scene, operator, visibility)?;
            // Row sums are fractions of the patch's output: their differences are absolute.
            let rows = errors(exact.row_sums.iter().zip(&s.row_sums), |_| 1.0);
            let (mut gx, mut reading) = ((0.0f64, 0.0f64), (0.0f64, 0.0f64));
            for (a, b) in exact.products.iter().zip(&s.products) {
                // Entries of a product against its largest entry (a signed probe has zeros).
                let largest = a.iter().fold(0.0f64, |m, x| m.max(x.abs()));
                let e = errors(a.iter().zip(b), |_| largest);
                gx = (gx.0.max(e.0), gx.1.max(e.1));
            }
            for (a, b) in exact.readings.iter().zip(&s.readings) {
                let largest = a.iter().fold(0.0f64, |m, x| m.max(x.abs()));
                let e = errors(a.iter().zip(b), |x| x.abs().max(READING_FLOOR * largest));
                reading = (reading.0.max(e.0), reading.1.max(e.1));
            }
            println!(
                "| {} | {n} | {label} | {:.1} | {:.1} | {:.2} | {:.1e} / {:.1e} | {:.1e} / {:.1e} | {:.1e} / {:.1e} |",
                scene.display(),
                s.cpu,
                s.form_factor_wall,
                s.cpu / exact.cpu,
                rows.0,
                rows.1,
                gx.0,
                gx.1,
                reading.0,
                reading.1
            );
        }
    }
    Ok(())
}
