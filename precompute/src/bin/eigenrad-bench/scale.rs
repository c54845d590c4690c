//! `eigenrad-bench scale`: the precompute's stage times and peak memory, one child process
//! per scene so that each peak is its own.

use std::hint::black_box;
use std::path::{Path, PathBuf};
use std::time::Instant;

use anyhow::{bail, Context as _, Result};
use clap::ValueEnum as _;
use eigenrad_precompute::formfactor::FormFactorOptions;
use eigenrad_precompute::pipeline::{self, BuildOptions};

use eigenrad_precompute::formfactor::OperatorChoice;

/// The table's columns; the build's wall time is [`TOTAL_COLUMN`].
const HEADER: &str = "| patches | operator | meshing s | BVH s | form factors s | sensors & zones s | eigenbasis s | exact reference s | serialization s | verification s | total s | CPU s | peak MB |";

/// Index of `total s` among the columns of [`HEADER`].
const TOTAL_COLUMN: usize = 10;

/// Prints the table's header, then runs `eigenrad-bench scale-one` on each scene in a child
/// process, which prints its row. With more than one scene, each scene's total time is then
/// given against the first's (e.g. the office with photometric luminaires against the
/// Lambertian office, in one run).
pub(crate) fn run(scenes: &[PathBuf], operator: OperatorChoice) -> Result<()> {
    println!("{HEADER}");
    println!("|---|---|---|---|---|---|---|---|---|---|---|---|---|");
    let exe = std::env::current_exe()?;
    let mut totals = Vec::new();
    for s in scenes {
        let out = std::process::Command::new(&exe)
            .arg("scale-one")
            .arg(s)
            .arg("--operator")
            .arg(
                operator
                    .to_possible_value()
                    .map_or("auto".into(), |v| v.get_name().to_owned()),
            )
            .stderr(std::process::Stdio::inherit())
            .output()?;
        if !out.status.success() {
            bail!("{}: scale-one failed", s.display());
        }
        let row = String::from_utf8_lossy(&out.stdout);
        print!("{row}");
        let total = row
            .trim()
            .trim_matches('|')
            .split('|')
            .nth(TOTAL_COLUMN)
            .and_then(|t| t.trim().parse::<f64>().ok());
        totals.push((s, total));
    }
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
pub(crate) fn one(path: &Path, operator: OperatorChoice) -> Result<()> {
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
            operator,
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
        "| {} | {} | {:.2} | {:.3} | {:.1} | {:.1} | {:.1} | {:.1} | {:.2} | {:.2} | {:.1} | {:.1} | {:.0} |",
        report.patches,
        report.operator.storage,
        stage("scene"),
        bvh_s,
        stage("form factors"),
        stage("sensors"),
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
        "  {}: light sources {:.1} s; {} modes, row sums {:.4}..{:.4}, reciprocity {:.1e}, worst patch error {:.1e}, worst sensor/zone error {:.1e}",
        path.display(),
        stage("light sources"),
        report.modes,
        report.form_factors.row_sum_min,
        report.form_factors.row_sum_max,
        report.form_factors.reciprocity_mismatch,
        worst.0,
        worst.1
    );
    Ok(())
}
