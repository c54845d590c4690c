//! `eigenrad-bench update`: the cost of turning new channel levels into (a) every sensor and
//! zone reading and (b) every patch exitance, for the eigenbasis through the runtime and for
//! the alternatives, with the accuracy each reaches against the exact solve; and the host
//! evaluation against a memory-bandwidth bound.

use std::hint::black_box;
use std::path::{Path, PathBuf};
use std::time::Instant;

use anyhow::{bail, Result};
use eigenrad_precompute::accuracy::metric::{patch_error, worst_reading};
use eigenrad_precompute::accuracy::rng::level_vector;
use eigenrad_precompute::basis;
use eigenrad_precompute::formfactor::FormFactorOptions;
use eigenrad_precompute::pipeline;
use eigenrad_precompute::radiosity::eigen::{Formulation, Solver};
use eigenrad_precompute::radiosity::exact::ExactSolver;
use eigenrad_precompute::radiosity::iterative::BandSystem;
use eigenrad_precompute::radiosity::model::Model;
use eigenrad_precompute::scene::Scene;
use eigenrad_runtime::format::MatrixBytes;
use eigenrad_runtime::{Basis, Evaluator, Precision};

use crate::REFERENCE_MODES;

/// Mode counts of the eigenbasis rows, ascending.
const MODE_COUNTS: [usize; 4] = [16, 32, 64, 128];

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

/// Prints the copy bandwidth, then one table per scene.
pub(crate) fn run(scenes: &[PathBuf], skip_lu: bool) -> Result<()> {
    println!(
        "plain copy of 256 MB: {:.2} GB/s (bytes copied per second, one thread)",
        copy_bandwidth() / 1e9
    );
    for s in scenes {
        update(s, skip_lu)?;
    }
    Ok(())
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

/// Patch exitances and sensor/zone readings for a level vector.
type Solution<'s> = dyn FnMut(&[f64]) -> (Vec<f64>, Vec<f64>) + 's;

/// One row of the update table.
struct Row {
    method: String,
    outputs_s: f64,
    patches_s: f64,
    /// (b) by a plain loop over the same bytes ([`plain_rows`]), for the eigenbasis rows.
    plain_s: Option<f64>,
    outputs_err: f64,
    patches_err: f64,
    bytes: usize,
}

/// The table of one scene.
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
    let model = Model::new(&prepared.system, Formulation::Split, MODES, Solver::Auto)?;
    println!(
        "\n## {}: {n} patches, {} channels, {} sensors and zones (prepared in {:.1} s)\n",
        path.display(),
        scene.channels.len(),
        model.system.output_count(),
        t.elapsed().as_secs_f64()
    );
    let bench = Bench::new(&model)?;
    let mut rows = Vec::new();
    for &p in &MODE_COUNTS {
        for precision in [Precision::F32, Precision::F16, Precision::I16] {
            rows.push(bench.eigenbasis(&scene, p, precision)?);
        }
    }
    rows.push(bench.superposition());
    rows.extend(bench.lu(skip_lu));
    rows.extend(bench.iterative());
    print_table(&rows);
    Ok(())
}

/// What every row of one scene is measured against: the model, its exact solver and the
/// exact solutions of the accuracy cases.
struct Bench<'m> {
    model: &'m Model<'m>,
    /// The LU factorisation of the one band.
    exact: ExactSolver,
    /// Patches.
    n: usize,
    /// Channels.
    m: usize,
    /// The accuracy cases' level vectors.
    cases: Vec<Vec<f64>>,
    /// Their exact patch exitances and readings.
    truth: Vec<(Vec<f64>, Vec<f64>)>,
}

impl<'m> Bench<'m> {
    fn new(model: &'m Model<'m>) -> Result<Self> {
        let exact = ExactSolver::new(model.system.operator(), model.area(), Self::rho(model))?;
        let m = model.channel_count();
        let mut bench = Bench {
            model,
            exact,
            n: model.patch_count(),
            m,
            cases: (0..ACCURACY_CASES)
                .map(|k| level_vector(1000 + k, m))
                .collect(),
            truth: Vec::new(),
        };
        bench.truth = bench
            .cases
            .iter()
            .map(|l| {
                let x = bench.exact.solve(&bench.m0(l));
                let o = model.readings(0, &x, l);
                (x, o)
            })
            .collect();
        Ok(bench)
    }

    /// Reflectance of the one band.
    fn rho<'a>(model: &'a Model<'_>) -> &'a [f64] {
        model.reflectance(0)
    }

    /// Initial exitance of every patch for channel levels `l`.
    fn m0(&self, l: &[f64]) -> Vec<f64> {
        self.model.system.initial_exitance(0, l, &[])
    }

    /// Level vector number `k` in f32, as firmware receives it.
    fn levels32(&self, k: usize) -> Vec<f32> {
        level_vector(k, self.m).iter().map(|&x| x as f32).collect()
    }

    /// Worst (a) sensor or zone reading error (each against its own exact value) and (b)
    /// patch error of `solve` over the accuracy cases.
    fn errors(&self, solve: &mut Solution<'_>) -> (f64, f64) {
        let (mut ep, mut eo) = (0.0f64, 0.0f64);
        for (l, (x, o)) in self.cases.iter().zip(&self.truth) {
            let (gx, go) = solve(l);
            ep = ep.max(patch_error(self.model.area(), &gx, x));
            eo = eo.max(worst_reading(&go, o).error);
        }
        (eo, ep)
    }

    /// (1) The eigenbasis with `p` modes in `precision`, through the runtime.
    fn eigenbasis(&self, scene: &Scene, p: usize, precision: Precision) -> Result<Row> {
        let (n, m) = (self.n, self.m);
        let bytes = basis::basis_tables(scene, self.model, p, precision).to_bytes()?;
        let basis = Basis::from_bytes(&bytes)?;
        let mut eval = Box::new(Eval::new(basis)?);
        let sensors = basis.sensor_count();
        let zones = basis.zone_count();
        let mut out = vec![[0.0f32; 1]; n];
        let mut k = 0usize;
        let outputs_s = per_call(|| {
            k += 1;
            let l = self.levels32(k);
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
            k += 1;
            let l = self.levels32(k);
            if eval.set_channel_levels(&l).is_ok() {
                let _ = eval.exitance_all(&mut out);
            }
            black_box(&out);
        });
        let raw = eigenrad_runtime::format::decode(&bytes)?;
        let mut plain = vec![0.0f32; n];
        let plain_s = per_call(|| {
            k += 1;
            let l = self.levels32(k);
            plain_rows(raw.channel_response, precision, &l, &mut plain);
            black_box(&plain);
        });
        // The plain loop is a reference for the time only if it computes the same sums.
        let l = self.levels32(1);
        if eval.set_channel_levels(&l).is_ok() && eval.exitance_all(&mut out).is_ok() {
            plain_rows(raw.channel_response, precision, &l, &mut plain);
            if out
                .iter()
                .zip(&plain)
                .any(|(a, b)| a[0].to_bits() != b.to_bits())
            {
                bail!(
                    "the plain loop and exitance_all disagree ({})",
                    precision.name()
                );
            }
        }
        let (outputs_err, patches_err) = self.errors(&mut |l| {
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
        Ok(Row {
            method: format!("eigenbasis p = {p}, {}", precision.name()),
            outputs_s,
            patches_s,
            plain_s: Some(plain_s),
            outputs_err,
            patches_err,
            // Bytes read by (b): every patch's row of channel responses (format v2: channel
            // levels do not touch the modes).
            bytes: n * m * precision.bytes(),
        })
    }

    /// (2) Exact per-channel superposition, f32 tables as firmware would hold them.
    fn superposition(&self) -> Row {
        let (n, m) = (self.n, self.m);
        let outputs = self.model.system.output_count();
        let patch_table: Vec<Vec<f32>> = (0..m)
            .map(|c| {
                let r = self.model.channel_response(c, 0);
                r.iter().map(|&x| x as f32).collect()
            })
            .collect();
        let output_table: Vec<Vec<f32>> = (0..m)
            .map(|c| {
                let r = self.model.channel_readings(c, 0);
                r.iter().map(|&x| x as f32).collect()
            })
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
            superpose(&self.levels32(k), &output_table, &mut out_o);
            black_box(&out_o);
        });
        let patches_s = per_call(|| {
            k += 1;
            superpose(&self.levels32(k), &patch_table, &mut out_p);
            black_box(&out_p);
        });
        let (outputs_err, patches_err) = self.errors(&mut |l| {
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
        Row {
            method: "exact per-channel superposition (f32)".into(),
            outputs_s,
            patches_s,
            plain_s: None,
            outputs_err,
            patches_err,
            bytes: n * m * 4,
        }
    }

    /// (3) Dense LU: factorised per update (unless `skip_lu`), and the factorisation reused.
    fn lu(&self, skip_lu: bool) -> Vec<Row> {
        let (n, m, model) = (self.n, self.m, self.model);
        let mut rows = Vec::new();
        let mut k = 0usize;
        let solve_reused = |l: &[f64]| {
            let x = self.exact.solve(&self.m0(l));
            let o = model.readings(0, &x, l);
            (x, o)
        };
        let reused_s = per_call(|| {
            k += 1;
            black_box(solve_reused(&level_vector(k, m)));
        });
        let (outputs_err, patches_err) = self.errors(&mut |l| solve_reused(l));
        if !skip_lu {
            let per_update_s = per_call(|| {
                k += 1;
                if let Ok(lu) =
                    ExactSolver::new(model.system.operator(), model.area(), Self::rho(model))
                {
                    let l = level_vector(k, m);
                    let x = lu.solve(&self.m0(&l));
                    black_box(model.readings(0, &x, &l));
                }
            });
            rows.push(Row {
                method: "dense LU per update (faer)".into(),
                outputs_s: per_update_s,
                patches_s: per_update_s,
                plain_s: None,
                outputs_err,
                patches_err,
                bytes: n * n * 8,
            });
        }
        rows.push(Row {
            method: "LU factorisation reused (substitution)".into(),
            outputs_s: reused_s,
            patches_s: reused_s,
            plain_s: None,
            outputs_err,
            patches_err,
            bytes: n * n * 8,
        });
        rows
    }

    /// (4) Iterative: Southwell shooting and Gauss–Seidel, to a 1e-3 relative residual.
    fn iterative(&self) -> Vec<Row> {
        let (n, m, model) = (self.n, self.m, self.model);
        let g_rows: Vec<f64> = (0..n)
            .flat_map(|i| (0..n).map(move |j| (i, j)))
            .map(|(i, j)| model.system.operator().entry(j, i))
            .collect();
        let sys = BandSystem::new(&g_rows, model.area(), Self::rho(model));
        let mut k = 0usize;
        let mut counts = (0usize, 0usize);
        let sw_s = per_call(|| {
            k += 1;
            let l = level_vector(k, m);
            let (x, shots) = sys.southwell(&self.m0(&l), ITERATIVE_TOLERANCE);
            counts.0 = shots;
            black_box(model.readings(0, &x, &l));
        });
        let (sw_o, sw_p) = self.errors(&mut |l| {
            let (x, _) = sys.southwell(&self.m0(l), ITERATIVE_TOLERANCE);
            let o = model.readings(0, &x, l);
            (x, o)
        });
        let gs_s = per_call(|| {
            k += 1;
            let l = level_vector(k, m);
            let (x, sweeps) = sys.gauss_seidel(&self.m0(&l), ITERATIVE_TOLERANCE);
            counts.1 = sweeps;
            black_box(model.readings(0, &x, &l));
        });
        let (gs_o, gs_p) = self.errors(&mut |l| {
            let (x, _) = sys.gauss_seidel(&self.m0(l), ITERATIVE_TOLERANCE);
            let o = model.readings(0, &x, l);
            (x, o)
        });
        let (x, _) = sys.southwell(&self.m0(&level_vector(1, m)), ITERATIVE_TOLERANCE);
        let sw_residual = sys.residual(&self.m0(&level_vector(1, m)), &x);
        vec![
            Row {
                method: format!(
                    "Southwell shooting to 1e-3 unshot ({} shots, true residual {sw_residual:.1e})",
                    counts.0
                ),
                outputs_s: sw_s,
                patches_s: sw_s,
                plain_s: None,
                outputs_err: sw_o,
                patches_err: sw_p,
                bytes: n * n * 8,
            },
            Row {
                method: format!("Gauss–Seidel to 1e-3 residual ({} sweeps)", counts.1),
                outputs_s: gs_s,
                patches_s: gs_s,
                plain_s: None,
                outputs_err: gs_o,
                patches_err: gs_p,
                bytes: n * n * 8,
            },
        ]
    }
}

/// A plain loop over the bytes `exitance_all` reads: row after row of the `m` stored channel
/// responses of a patch (`n × m`, one band), each value (a 16-bit one times its column's
/// scale, a half converted as the runtime does) times its channel's level, summed in order.
/// No evaluator, no checks beyond the slices': the speed the row-major table allows.
fn plain_rows(raw: MatrixBytes<'_>, precision: Precision, levels: &[f32], out: &mut [f32]) {
    let m = levels.len();
    if m == 0 {
        out.fill(0.0);
        return;
    }
    let scales: Vec<f32> = raw
        .scales
        .chunks_exact(4)
        .map(|b| f32::from_le_bytes([b[0], b[1], b[2], b[3]]))
        .collect();
    match precision {
        Precision::F32 => {
            for (row, o) in raw.data.chunks_exact(4 * m).zip(out) {
                *o = row
                    .chunks_exact(4)
                    .zip(levels)
                    .map(|(b, &l)| f32::from_le_bytes([b[0], b[1], b[2], b[3]]) * l)
                    .sum();
            }
        }
        Precision::F16 => {
            // Sign, exponent and mantissa shifted into an f32, times 2^112: exact for every
            // finite half.
            let half = |b: &[u8]| {
                let bits = u32::from(u16::from_le_bytes([b[0], b[1]]));
                f32::from_bits(((bits & 0x8000) << 16) | ((bits & 0x7FFF) << 13))
                    * f32::from_bits((127 + 112) << 23)
            };
            for (row, o) in raw.data.chunks_exact(2 * m).zip(out) {
                *o = row
                    .chunks_exact(2)
                    .zip(&scales)
                    .zip(levels)
                    .map(|((b, &s), &l)| half(b) * s * l)
                    .sum();
            }
        }
        _ => {
            for (row, o) in raw.data.chunks_exact(2 * m).zip(out) {
                *o = row
                    .chunks_exact(2)
                    .zip(&scales)
                    .zip(levels)
                    .map(|((b, &s), &l)| f32::from(i16::from_le_bytes([b[0], b[1]])) * s * l)
                    .sum();
            }
        }
    }
}

/// The table, with every time also as a ratio to the reference eigenbasis row, the
/// eigenbasis' (b) against a plain loop over the same bytes, and the reference row against
/// the copy bandwidth.
fn print_table(rows: &[Row]) {
    let reference_row = rows
        .iter()
        .find(|r| r.method == format!("eigenbasis p = {REFERENCE_MODES}, f32"));
    let reference = reference_row.map_or((1.0, 1.0), |r| (r.outputs_s, r.patches_s));
    let reference_bytes = reference_row.map_or(0, |r| r.bytes);
    println!("Times per update; ratios are to the eigenbasis at p = {REFERENCE_MODES}, f32, measured in the same run; (b) against a plain loop over the same bytes for the eigenbasis rows. Errors are relative to the exact (LU) solve, worst of {ACCURACY_CASES} level vectors.\n");
    println!("| method | (a) sensors & zones µs | ratio | (b) all patches µs | ratio | (b) plain loop µs | (b) / plain loop | (a) error | (b) error | table bytes |");
    println!("|---|---|---|---|---|---|---|---|---|---|");
    for r in rows {
        let (plain, against) = r.plain_s.map_or(("–".to_owned(), "–".to_owned()), |p| {
            (format!("{:.1}", p * 1e6), format!("{:.2}", r.patches_s / p))
        });
        println!(
            "| {} | {:.3} | {:.3} | {:.1} | {:.3} | {plain} | {against} | {:.1e} | {:.1e} | {} |",
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
}
