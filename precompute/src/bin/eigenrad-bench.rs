//! `eigenrad-bench`: the figures of `docs/performance.md`.
//!
//! - `eigenrad-bench update SCENE...`: cost of turning new channel levels into (a) every sensor
//!   and zone reading and (b) every patch exitance, for the eigenbasis through the runtime and
//!   for the alternatives (exact per-channel superposition, dense LU, Southwell shooting,
//!   Gauss–Seidel), with the accuracy each reaches against the exact solve; and the host
//!   evaluation against a memory-bandwidth bound.
//! - `eigenrad-bench scale SCENE...`: precompute stage times and peak memory, one child
//!   process per scene (so that each peak is its own).
//! - `eigenrad-bench eigen SCENE...`: dense against partial eigensolve on the same matrix.
//!
//! Run in release: `cargo run --release -p eigenrad-precompute --bin eigenrad-bench -- …`.

use std::hint::black_box;
use std::path::{Path, PathBuf};
use std::time::Instant;

use anyhow::{bail, Context as _, Result};
use clap::{Parser, Subcommand};
use eigenrad_precompute::accuracy::metric::{output_error, patch_error};
use eigenrad_precompute::accuracy::rng::level_vector;
use eigenrad_precompute::basis;
use eigenrad_precompute::formfactor::FormFactorOptions;
use eigenrad_precompute::pipeline::{self, BuildOptions};
use eigenrad_precompute::radiosity::eigen::{self, Formulation, Solver};
use eigenrad_precompute::radiosity::exact::ExactSolver;
use eigenrad_precompute::radiosity::iterative::System;
use eigenrad_precompute::radiosity::model::Model;
use eigenrad_runtime::{Basis, Evaluator, Precision};

/// Mode counts of the eigenbasis rows, ascending.
const MODE_COUNTS: [usize; 4] = [16, 32, 64, 128];
/// The eigenbasis row every ratio is relative to: the default build (p = 32, f32).
const REFERENCE_MODES: usize = pipeline::DEFAULT_MODES;

/// Capacities of the benchmark's evaluator (one band); modes: the largest row.
const PATCHES: usize = 16_384;
const MODES: usize = MODE_COUNTS[MODE_COUNTS.len() - 1];
const CHANNELS: usize = 64;
const OUTPUTS: usize = 64;
type Eval<'a> = Evaluator<'a, 1, PATCHES, MODES, CHANNELS, OUTPUTS>;
/// Relative residual the iterative solvers stop at (the figure).
const ITERATIVE_TOLERANCE: f64 = 1e-3;
/// Wall-clock seconds each timing loop runs at least.
const MIN_SECONDS: f64 = 0.3;
/// Level vectors the accuracy of each method is measured on.
const ACCURACY_CASES: usize = 4;

#[derive(Parser)]
#[command(about = "Benchmarks of eigenrad (docs/performance.md)")]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Per-update cost and accuracy of every method on each scene (one band).
    Update {
        /// Scene files.
        scenes: Vec<PathBuf>,
        /// Skip the LU factorisation per update (seconds per update at n = 5000).
        #[arg(long)]
        skip_lu: bool,
    },
    /// Precompute stage times and peak memory, one child process per scene.
    Scale {
        /// Scene files.
        scenes: Vec<PathBuf>,
    },
    /// (internal) One row of `scale`, in this process.
    ScaleOne {
        /// Scene file.
        scene: PathBuf,
    },
    /// Dense against partial eigensolve (p = 32) on each scene's form factors.
    Eigen {
        /// Scene files.
        scenes: Vec<PathBuf>,
        /// Largest reflecting-patch count for which the dense solve is run.
        #[arg(long, default_value_t = 5000)]
        dense_max: usize,
    },
}

fn main() -> Result<()> {
    match Cli::parse().command {
        Command::Update { scenes, skip_lu } => {
            machine();
            bandwidth();
            for s in &scenes {
                update(s, skip_lu)?;
            }
        }
        Command::Scale { scenes } => {
            machine();
            println!(
                "| patches | meshing s | BVH s | form factors s | sensors & zones s | eigenbasis s | exact reference s | serialization s | verification s | total s | CPU s | peak MB |"
            );
            println!("|---|---|---|---|---|---|---|---|---|---|---|---|");
            let exe = std::env::current_exe()?;
            for s in &scenes {
                let status = std::process::Command::new(&exe)
                    .arg("scale-one")
                    .arg(s)
                    .status()?;
                if !status.success() {
                    bail!("{}: scale-one failed", s.display());
                }
            }
        }
        Command::ScaleOne { scene } => scale_one(&scene)?,
        Command::Eigen { scenes, dense_max } => {
            machine();
            println!(
                "| patches | reflecting | partial (Lanczos) s | dense s | max |Δμ| dense vs partial | max |Δμ| with G stored in f32 | G in f64 MB | G in f32 MB |"
            );
            println!("|---|---|---|---|---|---|---|---|");
            for s in &scenes {
                eigen_compare(s, dense_max)?;
            }
        }
    }
    Ok(())
}

/// Prints the CPU model and core count (`lscpu`).
fn machine() {
    let out = std::process::Command::new("lscpu")
        .output()
        .map(|o| String::from_utf8_lossy(&o.stdout).into_owned())
        .unwrap_or_default();
    let field = |name: &str| {
        out.lines()
            .find(|l| l.starts_with(name))
            .and_then(|l| l.split(':').nth(1))
            .map_or("?".to_string(), |v| v.trim().to_string())
    };
    println!(
        "machine: {} ({} CPUs), rayon threads {}",
        field("Model name"),
        field("CPU(s)"),
        rayon::current_num_threads()
    );
}

/// Seconds per call of `f`, looping until [`MIN_SECONDS`] have passed (one warm-up call).
fn per_call(mut f: impl FnMut()) -> f64 {
    f();
    let mut reps = 1usize;
    loop {
        let t = Instant::now();
        for _ in 0..reps {
            f();
        }
        let e = t.elapsed().as_secs_f64();
        if e >= MIN_SECONDS {
            return e / reps as f64;
        }
        reps = (reps * 2).max((reps as f64 * MIN_SECONDS / e.max(1e-9) * 1.2) as usize);
    }
}

/// Bandwidth of a plain copy of a 256 MB buffer, bytes per second (bytes copied / time).
fn copy_bandwidth() -> f64 {
    let len = 32 << 20; // 32 Mi f64 = 256 MB
    let src: Vec<f64> = (0..len).map(|i| i as f64).collect();
    let mut dst = vec![0.0f64; len];
    let secs = per_call(|| {
        dst.copy_from_slice(black_box(&src));
        black_box(&mut dst);
    });
    (len * 8) as f64 / secs
}

fn bandwidth() {
    println!(
        "plain copy of 256 MB: {:.2} GB/s (bytes copied per second, one thread)",
        copy_bandwidth() / 1e9
    );
}

/// Patch exitances and sensor/zone readings for a level vector.
type Solution<'s> = dyn FnMut(&[f64]) -> (Vec<f64>, Vec<f64>) + 's;

/// One row of the update table.
struct Row {
    method: String,
    outputs_s: f64,
    patches_s: f64,
    outputs_err: f64,
    patches_err: f64,
    bytes: usize,
}

fn update(path: &Path, skip_lu: bool) -> Result<()> {
    let t = Instant::now();
    let prepared = pipeline::prepare(path, &FormFactorOptions::default())?;
    let scene = prepared.scene;
    let n = scene.patches.len();
    if scene.bands.count() != 1 {
        bail!(
            "{}: the update benchmark takes one-band scenes",
            path.display()
        );
    }
    if n > PATCHES {
        bail!(
            "{}: {n} patches, the benchmark holds {PATCHES}",
            path.display()
        );
    }
    let model = Model::new(
        &scene,
        prepared.g,
        prepared.output_rows,
        Formulation::Split,
        MODES,
        Solver::Auto,
    )?;
    let m = scene.channels.len();
    let outputs = model.output_rows.len();
    println!(
        "\n## {}: {n} patches, {m} channels, {outputs} sensors and zones (prepared in {:.1} s)\n",
        path.display(),
        t.elapsed().as_secs_f64()
    );
    let area = model.area.clone();
    let rho = model.bands[0].reflectance.clone();
    let exact = ExactSolver::new(model.g.as_ref(), &area, &rho)?;

    // Exact responses: per channel (the superposition tables) and per accuracy case.
    let responses: Vec<Vec<f64>> = (0..m).map(|c| exact.solve(&model.emission[c][0])).collect();
    let cases: Vec<Vec<f64>> = (0..ACCURACY_CASES)
        .map(|k| level_vector(1000 + k, m))
        .collect();
    let m0_of = |l: &[f64]| -> Vec<f64> {
        let mut m0 = vec![0.0; n];
        for (c, &lc) in l.iter().enumerate() {
            for (x, e) in m0.iter_mut().zip(&model.emission[c][0]) {
                *x += lc * e;
            }
        }
        m0
    };
    let truth: Vec<(Vec<f64>, Vec<f64>)> = cases
        .iter()
        .map(|l| {
            let x = exact.solve(&m0_of(l));
            let o = model.outputs(&x);
            (x, o)
        })
        .collect();
    let errors = |solve: &mut Solution<'_>| -> (f64, f64) {
        let (mut ep, mut eo) = (0.0f64, 0.0f64);
        for (l, (x, o)) in cases.iter().zip(&truth) {
            let (gx, go) = solve(l);
            ep = ep.max(patch_error(&area, &gx, x));
            eo = eo.max(output_error(&go, o));
        }
        (eo, ep)
    };

    let mut rows: Vec<Row> = Vec::new();
    let mut reference_bytes = 0usize;
    // (1) The eigenbasis through the runtime.
    for &p in &MODE_COUNTS {
        for precision in [Precision::F32, Precision::F16, Precision::I16] {
            let bytes = basis::basis_tables(&scene, &model, p, precision).to_bytes()?;
            let basis = Basis::from_bytes(&bytes)?;
            let mut eval = Box::new(Eval::new(basis)?);
            let sensors = basis.sensor_count();
            let zones = basis.zone_count();
            let mut out = vec![[0.0f32; 1]; n];
            let mut k = 0usize;
            let next = |k: &mut usize| -> Vec<f32> {
                *k += 1;
                level_vector(*k, m).iter().map(|&x| x as f32).collect()
            };
            let outputs_s = per_call(|| {
                let l = next(&mut k);
                let mut acc = 0.0f32;
                if eval.set_channel_levels(&l).is_ok() {
                    for s in 0..sensors {
                        acc += eval.sensor_irradiance(s).map_or(0.0, |v| v[0]);
                    }
                    for z in 0..zones {
                        acc += eval.zone_irradiance(z).map_or(0.0, |v| v[0]);
                    }
                }
                black_box(acc);
            });
            let patches_s = per_call(|| {
                let l = next(&mut k);
                if eval.set_channel_levels(&l).is_ok() {
                    let _ = eval.exitance_all(&mut out);
                }
                black_box(&out);
            });
            let (outputs_err, patches_err) = errors(&mut |l| {
                let lf: Vec<f32> = l.iter().map(|&x| x as f32).collect();
                let mut o = vec![[0.0f32; 1]; n];
                let mut readings = Vec::new();
                if eval.set_channel_levels(&lf).is_ok() {
                    let _ = eval.exitance_all(&mut o);
                    for s in 0..sensors {
                        readings.push(
                            eval.sensor_irradiance(s)
                                .map_or(f64::NAN, |v| f64::from(v[0])),
                        );
                    }
                    for z in 0..zones {
                        readings.push(
                            eval.zone_irradiance(z)
                                .map_or(f64::NAN, |v| f64::from(v[0])),
                        );
                    }
                }
                (o.iter().map(|v| f64::from(v[0])).collect(), readings)
            });
            let name = precision.name();
            // Bytes read by (b): the mode vectors and first-bounce rows of every patch.
            let read = n * (p + m) * precision.bytes();
            if p == REFERENCE_MODES && precision == Precision::F32 {
                reference_bytes = read;
            }
            rows.push(Row {
                method: format!("eigenbasis p = {p}, {name}"),
                outputs_s,
                patches_s,
                outputs_err,
                patches_err,
                bytes: read,
            });
        }
    }

    // (2) Exact per-channel superposition, f32 tables as firmware would hold them.
    {
        let patch_table: Vec<Vec<f32>> = responses
            .iter()
            .map(|r| r.iter().map(|&x| x as f32).collect())
            .collect();
        let output_table: Vec<Vec<f32>> = responses
            .iter()
            .map(|r| model.outputs(r).iter().map(|&x| x as f32).collect())
            .collect();
        let mut k = 0usize;
        let mut out_o = vec![0.0f32; outputs];
        let mut out_p = vec![0.0f32; n];
        let superpose = |l: &[f32], table: &[Vec<f32>], out: &mut [f32]| {
            out.iter_mut().for_each(|x| *x = 0.0);
            for (lc, row) in l.iter().zip(table) {
                for (o, r) in out.iter_mut().zip(row) {
                    *o += lc * r;
                }
            }
        };
        let outputs_s = per_call(|| {
            k += 1;
            let l: Vec<f32> = level_vector(k, m).iter().map(|&x| x as f32).collect();
            superpose(&l, &output_table, &mut out_o);
            black_box(&out_o);
        });
        let patches_s = per_call(|| {
            k += 1;
            let l: Vec<f32> = level_vector(k, m).iter().map(|&x| x as f32).collect();
            superpose(&l, &patch_table, &mut out_p);
            black_box(&out_p);
        });
        let (outputs_err, patches_err) = errors(&mut |l| {
            let lf: Vec<f32> = l.iter().map(|&x| x as f32).collect();
            let mut o = vec![0.0f32; outputs];
            let mut x = vec![0.0f32; n];
            superpose(&lf, &output_table, &mut o);
            superpose(&lf, &patch_table, &mut x);
            (
                x.iter().map(|&v| f64::from(v)).collect(),
                o.iter().map(|&v| f64::from(v)).collect(),
            )
        });
        rows.push(Row {
            method: "exact per-channel superposition (f32)".into(),
            outputs_s,
            patches_s,
            outputs_err,
            patches_err,
            bytes: n * m * 4,
        });
    }

    // (3) Dense LU: factorised per update, and factorisation reused.
    {
        let mut k = 0usize;
        let solve_reused = |l: &[f64]| {
            let x = exact.solve(&m0_of(l));
            let o = model.outputs(&x);
            (x, o)
        };
        let reused_s = per_call(|| {
            k += 1;
            black_box(solve_reused(&level_vector(k, m)));
        });
        let (outputs_err, patches_err) = errors(&mut |l| solve_reused(l));
        if !skip_lu {
            let per_update_s = per_call(|| {
                k += 1;
                if let Ok(lu) = ExactSolver::new(model.g.as_ref(), &area, &rho) {
                    let x = lu.solve(&m0_of(&level_vector(k, m)));
                    black_box(model.outputs(&x));
                }
            });
            rows.push(Row {
                method: "dense LU per update (faer)".into(),
                outputs_s: per_update_s,
                patches_s: per_update_s,
                outputs_err,
                patches_err,
                bytes: n * n * 8,
            });
        }
        rows.push(Row {
            method: "LU factorisation reused (substitution)".into(),
            outputs_s: reused_s,
            patches_s: reused_s,
            outputs_err,
            patches_err,
            bytes: n * n * 8,
        });
    }

    // (4) Iterative: Southwell shooting and Gauss–Seidel, to a 1e-3 relative residual.
    {
        let g_rows: Vec<f64> = (0..n)
            .flat_map(|i| (0..n).map(move |j| (i, j)))
            .map(|(i, j)| model.g[(j, i)])
            .collect();
        let sys = System::new(&g_rows, &area, &rho);
        let mut k = 0usize;
        let mut counts = (0usize, 0usize);
        let sw_s = per_call(|| {
            k += 1;
            let (x, shots) = sys.southwell(&m0_of(&level_vector(k, m)), ITERATIVE_TOLERANCE);
            counts.0 = shots;
            black_box(model.outputs(&x));
        });
        let (sw_o, sw_p) = errors(&mut |l| {
            let (x, _) = sys.southwell(&m0_of(l), ITERATIVE_TOLERANCE);
            let o = model.outputs(&x);
            (x, o)
        });
        let gs_s = per_call(|| {
            k += 1;
            let (x, sweeps) = sys.gauss_seidel(&m0_of(&level_vector(k, m)), ITERATIVE_TOLERANCE);
            counts.1 = sweeps;
            black_box(model.outputs(&x));
        });
        let (gs_o, gs_p) = errors(&mut |l| {
            let (x, _) = sys.gauss_seidel(&m0_of(l), ITERATIVE_TOLERANCE);
            let o = model.outputs(&x);
            (x, o)
        });
        let (x, _) = sys.southwell(&m0_of(&level_vector(1, m)), ITERATIVE_TOLERANCE);
        let sw_residual = sys.residual(&m0_of(&level_vector(1, m)), &x);
        rows.push(Row {
            method: format!(
                "Southwell shooting to 1e-3 unshot ({} shots, true residual {sw_residual:.1e})",
                counts.0
            ),
            outputs_s: sw_s,
            patches_s: sw_s,
            outputs_err: sw_o,
            patches_err: sw_p,
            bytes: n * n * 8,
        });
        rows.push(Row {
            method: format!("Gauss–Seidel to 1e-3 residual ({} sweeps)", counts.1),
            outputs_s: gs_s,
            patches_s: gs_s,
            outputs_err: gs_o,
            patches_err: gs_p,
            bytes: n * n * 8,
        });
    }

    let reference = rows
        .iter()
        .find(|r| r.method == format!("eigenbasis p = {REFERENCE_MODES}, f32"))
        .map_or((1.0, 1.0), |r| (r.outputs_s, r.patches_s));
    println!("Times per update; ratios are to the eigenbasis at p = {REFERENCE_MODES}, f32, measured in the same run. Errors are relative to the exact (LU) solve, worst of {ACCURACY_CASES} level vectors.\n");
    println!("| method | (a) sensors & zones µs | ratio | (b) all patches µs | ratio | (a) error | (b) error | table bytes |");
    println!("|---|---|---|---|---|---|---|---|");
    for r in &rows {
        println!(
            "| {} | {:.3} | {:.3} | {:.1} | {:.3} | {:.1e} | {:.1e} | {} |",
            r.method,
            r.outputs_s * 1e6,
            r.outputs_s / reference.0,
            r.patches_s * 1e6,
            r.patches_s / reference.1,
            r.outputs_err,
            r.patches_err,
            r.bytes
        );
    }
    let bw = copy_bandwidth();
    println!(
        "\nhost evaluation (b), p = {REFERENCE_MODES} f32: {reference_bytes} bytes of basis per update; at the copy bandwidth {:.2} GB/s the bound is {:.1} µs, measured {:.1} µs ({:.0} % of the bound)",
        bw / 1e9,
        reference_bytes as f64 / bw * 1e6,
        reference.1 * 1e6,
        100.0 * (reference_bytes as f64 / bw) / reference.1
    );
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
fn cpu_seconds() -> f64 {
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

fn scale_one(path: &Path) -> Result<()> {
    let start = Instant::now();
    let scene =
        eigenrad_precompute::scene::load(path).with_context(|| format!("{}", path.display()))?;
    let t = Instant::now();
    let occ = eigenrad_precompute::formfactor::Occluders::with_faces(&scene.patches, &scene.faces);
    let bvh_s = t.elapsed().as_secs_f64();
    black_box(occ.len());
    drop(occ);
    drop(scene);
    let (_bytes, report) = pipeline::build(path, &BuildOptions::default())?;
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
        "| {} | {:.2} | {:.3} | {:.1} | {:.1} | {:.1} | {:.1} | {:.2} | {:.2} | {:.1} | {:.1} | {:.0} |",
        report.patches,
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
        (w.0.max(c.patch_error), w.1.max(c.output_error))
    });
    eprintln!(
        "  {}: {} modes, row sums {:.4}..{:.4}, reciprocity {:.1e}, worst patch error {:.1e}, worst sensor/zone error {:.1e}",
        path.display(),
        report.modes,
        report.form_factors.row_sum_min,
        report.form_factors.row_sum_max,
        report.form_factors.reciprocity_mismatch,
        worst.0,
        worst.1
    );
    Ok(())
}

fn eigen_compare(path: &Path, dense_max: usize) -> Result<()> {
    let prepared = pipeline::prepare(path, &FormFactorOptions::default())?;
    let rho: Vec<f64> = prepared.scene.reflectance.iter().map(|r| r[0]).collect();
    let nr = rho.iter().filter(|&&r| r > 0.0).count();
    let g = prepared.g.as_ref();
    let t = Instant::now();
    let partial = eigen::modes(
        g,
        &prepared.area,
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
            &prepared.area,
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
    let g32 = faer::Mat::<f64>::from_fn(n, n, |i, j| f64::from(g[(i, j)] as f32));
    let rounded = eigen::modes(
        g32.as_ref(),
        &prepared.area,
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
