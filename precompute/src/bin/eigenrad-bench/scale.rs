//! `eigenrad-bench scale`: the precompute's stage times and peak memory, one child process
//! per scene so that each peak is its own.

use std::hint::black_box;
use std::path::{Path, PathBuf};
use std::time::Instant;

use anyhow::{bail, Context as _, Result};
use clap::ValueEnum as _;
use eigenrad_precompute::formfactor::{hierarchical, FormFactorOptions, Visibility};
use eigenrad_precompute::pipeline::{self, BuildOptions};

use eigenrad_precompute::formfactor::OperatorChoice;

/// The table's columns.
const HEADER: &str = "| patches | operator | meshing s | BVH s | form factors s | sensors & zones s | light sources s | eigenbasis s | exact reference s | serialization s | verification s | total s | CPU s | peak MB |";

/// How each scene is built.
#[derive(clap::Args, Clone, Debug)]
pub(crate) struct Settings {
    /// How the form-factor operator is stored.
    #[arg(long, value_enum, default_value_t = OperatorChoice::Auto)]
    operator: OperatorChoice,
    /// Build with `--visibility clusters` (hierarchical operator).
    #[arg(long)]
    clusters: bool,
    /// With --clusters: the `--cluster-misfit` of the builds.
    #[arg(long, default_value_t = hierarchical::SHADE_MISFIT)]
    cluster_misfit: f64,
}

/// The value of `column` (a name of [`HEADER`]) in a row of the table.
fn cell(row: &str, column: &str) -> Option<f64> {
    let at = HEADER
        .trim_matches('|')
        .split('|')
        .position(|name| name.trim() == column)?;
    row.trim()
        .trim_matches('|')
        .split('|')
        .nth(at)
        .and_then(|t| t.trim().parse::<f64>().ok())
}

/// The slope of `ln y` against `ln x` by least squares: the exponent `k` of `y ∝ x^k`.
fn growth_exponent(points: &[(f64, f64)]) -> Option<f64> {
    let logs: Vec<(f64, f64)> = points
        .iter()
        .filter(|(x, y)| *x > 0.0 && *y > 0.0)
        .map(|(x, y)| (x.ln(), y.ln()))
        .collect();
    let n = logs.len() as f64;
    let (mx, my) = logs
        .iter()
        .fold((0.0, 0.0), |(a, b), (x, y)| (a + x / n, b + y / n));
    let (sxy, sxx) = logs.iter().fold((0.0, 0.0), |(a, b), (x, y)| {
        (a + (x - mx) * (y - my), b + (x - mx) * (x - mx))
    });
    (logs.len() >= 2 && sxx > 0.0).then(|| sxy / sxx)
}

/// Prints the table's header, then runs `eigenrad-bench scale-one` on each scene in a child
/// process, which prints its row. With more than one scene, each scene's total time is then
/// given against the first's (e.g. the office with photometric luminaires against the
/// Lambertian office, in one run), and the growth of the total time, the form factors, the
/// eigenbasis and the peak memory with the patches as exponents fitted over all of them.
pub(crate) fn run(scenes: &[PathBuf], settings: &Settings) -> Result<()> {
    println!("{HEADER}");
    println!("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|");
    let exe = std::env::current_exe()?;
    let mut rows = Vec::new();
    for s in scenes {
        let mut child = std::process::Command::new(&exe);
        child.arg("scale-one").arg(s).arg("--operator").arg(
            settings
                .operator
                .to_possible_value()
                .map_or("auto".into(), |v| v.get_name().to_owned()),
        );
        if settings.clusters {
            child
                .arg("--clusters")
                .arg("--cluster-misfit")
                .arg(settings.cluster_misfit.to_string());
        }
        let out = child.stderr(std::process::Stdio::inherit()).output()?;
        if !out.status.success() {
            bail!("{}: scale-one failed", s.display());
        }
        let row = String::from_utf8_lossy(&out.stdout).into_owned();
        print!("{row}");
        rows.push((s, row));
    }
    let totals: Vec<(&PathBuf, Option<f64>)> = rows
        .iter()
        .map(|(s, row)| (*s, cell(row, "total s")))
        .collect();
    if let [(first, Some(base)), rest @ ..] = totals.as_slice() {
        for (s, total) in rest {
            if let Some(t) = total {
                println!(
                    "\n{}: total {t:.1} s, {:.2}× the {base:.1} s of {}",
                    s.display(),
                    t / base,
                    first.display()
                );
            }
        }
    }
    let exponent = |column: &str| {
        let points: Vec<(f64, f64)> = rows
            .iter()
            .filter_map(|(_, row)| Some((cell(row, "patches")?, cell(row, column)?)))
            .collect();
        growth_exponent(&points).map_or("–".to_owned(), |k| format!("n^{k:.2}"))
    };
    if rows.len() >= 2 {
        println!(
            "\nGrowth with the patches over the {} scenes (least squares of the logarithms): total {}, form factors {}, eigenbasis {}, peak memory {}",
            rows.len(),
            exponent("total s"),
            exponent("form factors s"),
            exponent("eigenbasis s"),
            exponent("peak MB")
        );
    }
    Ok(())
}

/// Peak resident memory of this process so far (`VmHWM`), bytes.
fn peak_rss() -> f64 {
    std::fs::read_to_string("/proc/self/status")
        .ok()
        .and_then(|s| {
            s.lines().find(|l| l.starts_with("VmHWM:")).and_then(|l| {
                l.split_whitespace()
                    .nth(1)
                    .and_then(|kb| kb.parse::<f64>().ok())
            })
        })
        .map_or(f64::NAN, |kb| kb * 1024.0)
}

/// CPU seconds (user + system) of this process so far, from `/proc/self/stat`.
pub(crate) fn cpu_seconds() -> f64 {
    let stat = std::fs::read_to_string("/proc/self/stat").unwrap_or_default();
    // Fields after the command name (which is in parentheses): utime is field 14, stime 15.
    let rest = stat.rsplit(')').next().unwrap_or("");
    let f: Vec<&str> = rest.split_whitespace().collect();
    let ticks = |k: usize| {
        f.get(k)
            .and_then(|v| v.parse::<f64>().ok())
            .unwrap_or(f64::NAN)
    };
    // rest starts at field 3; utime (14) is index 11, stime (15) index 12; 100 ticks/s.
    (ticks(11) + ticks(12)) / 100.0
}

/// One row of the table: builds the scene at `path` with the default options in this process.
pub(crate) fn one(path: &Path, settings: &Settings) -> Result<()> {
    let start = Instant::now();
    let scene =
        eigenrad_precompute::scene::load(path).with_context(|| format!("{}", path.display()))?;
    let t = Instant::now();
    let occ = eigenrad_precompute::formfactor::Occluders::with_faces(&scene.patches, &scene.faces);
    let bvh_s = t.elapsed().as_secs_f64();
    black_box(occ.len());
    drop(occ);
    drop(scene);
    let options = BuildOptions {
        form_factors: FormFactorOptions {
            operator: settings.operator,
            visibility: if settings.clusters {
                Visibility::Clusters
            } else {
                Visibility::Exact
            },
            cluster_misfit: settings.cluster_misfit,
            ..FormFactorOptions::default()
        },
        ..BuildOptions::default()
    };
    let (_bytes, report) = pipeline::build(path, &options)?;
    let total = start.elapsed().as_secs_f64();
    let stage = |name: &str| {
        report
            .timings
            .iter()
            .filter(|s| s.stage.starts_with(name))
            .map(|s| s.seconds)
            .sum::<f64>()
    };
    println!(
        "| {} | {} | {:.2} | {:.3} | {:.1} | {:.1} | {:.1} | {:.1} | {:.1} | {:.2} | {:.2} | {:.1} | {:.1} | {:.0} |",
        report.patches,
        report.operator.storage,
        stage("scene"),
        bvh_s,
        stage("form factors"),
        stage("sensors"),
        stage("light sources"),
        stage("eigenbasis"),
        stage("exact"),
        stage("serialization"),
        stage("verification"),
        total,
        cpu_seconds(),
        peak_rss() / 1e6
    );
    let worst = report.accuracy.iter().fold((0.0f64, 0.0f64), |w, c| {
        (w.0.max(c.patch_error), w.1.max(c.worst_reading.error))
    });
    eprintln!(
        "  {}: {} modes, row sums {:.4}..{:.4}, reciprocity {:.1e}, operator's measured row error {}, worst patch error {:.1e}, worst sensor/zone error {:.1e} (against the exact solves of the same operator)",
        path.display(),
        report.modes,
        report.form_factors.row_sum_min,
        report.form_factors.row_sum_max,
        report.form_factors.reciprocity_mismatch,
        report
            .operator
            .compression
            .as_ref()
            .map_or("–".to_owned(), |c| format!("{:.1e}", c.row_error)),
        worst.0,
        worst.1
    );
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn growth_exponent_of_a_power_law() {
        // y = 3 x^1.5 exactly: the fit gives 1.5 to rounding.
        let points: Vec<(f64, f64)> = [1e4, 2e4, 5e4, 1e5]
            .iter()
            .map(|&x: &f64| (x, 3.0 * x.powf(1.5)))
            .collect();
        let k = growth_exponent(&points).expect("four points");
        assert!((k - 1.5).abs() < 1e-12, "{k}");
        assert_eq!(growth_exponent(&points[..1]), None);
    }

    #[test]
    fn cells_by_column_name() {
        let row = "| 9888 | hierarchical f32 | 0.01 | 0.002 | 40.5 | 3.6 | 1.0 | 2.7 | 2.0 | 0.22 | 0.67 | 51.2 | 95.1 | 211 |";
        assert_eq!(cell(row, "patches"), Some(9888.0));
        assert_eq!(cell(row, "form factors s"), Some(40.5));
        assert_eq!(cell(row, "total s"), Some(51.2));
        assert_eq!(cell(row, "peak MB"), Some(211.0));
        assert_eq!(cell(row, "operator"), None);
    }
}
