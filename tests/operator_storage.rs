//! The form-factor operator in single precision (`--operator dense-f32`) against the f64 one
//! on the Lambertian example office (about 1100 patches, ρmax = 0.8): the same form-factor
//! health, eigenvalues and exact readings within the bounds docs/math.md derives for entries
//! rounded to f32 ("One room, one system, the operator behind it"), and a build through it.
//!
//! Reference: the same scene's f64 operator, the project's validated path (its exact solve
//! is an LU factorisation; the f32 and hierarchical ones are solved by conjugate gradients on
//! the operator). The hierarchical operator (`--operator hierarchical`) is held to the bounds
//! of its block tolerance ("The hierarchical operator").

use std::path::{Path, PathBuf};

use eigenrad::precompute::formfactor::{FormFactorOptions, OperatorChoice};
use eigenrad::precompute::pipeline::{self, prepare, BuildOptions, Prepared};
use eigenrad::precompute::radiosity::eigen::{Formulation, Solver};
use eigenrad::precompute::radiosity::model::Model;

/// f32 unit roundoff, 2⁻²⁴.
const U: f64 = 5.960_464_477_539_063e-8;

/// The largest reflectance of the scene.
const RHO_MAX: f64 = 0.8;

/// Each stored entry is a raw form factor rounded to f32, symmetrised in f64 and rounded
/// again: within `2u` of the f64 entry (plus f64 rounding). Eigenvalues of `H` then move by at
/// most `2u ρmax`; a factor 2 of margin.
const EIGENVALUE_TOLERANCE: f64 = 4.0 * U * RHO_MAX;

/// Exact readings move by about `2u ρmax / (1 − ρmax)` relative; conjugate gradients stop at
/// a 1e-12 relative residual. A factor 2 of margin.
const READING_RTOL: f64 = 4.0 * U * RHO_MAX / (1.0 - RHO_MAX);

/// Row sums `Σ_j F_ij` of order 1 from entries within `2u`: a factor 4 of margin.
const ROW_SUM_TOLERANCE: f64 = 8.0 * U;

fn scene() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/office-lambertian/scene.toml")
}

fn prepared(operator: OperatorChoice) -> Prepared {
    let opts = FormFactorOptions {
        operator,
        ..FormFactorOptions::default()
    };
    prepare(&scene(), &opts).unwrap_or_else(|e| panic!("{e}"))
}

#[test]
fn single_precision_reads_what_double_precision_reads() {
    let f64_room = prepared(OperatorChoice::Dense);
    let f32_room = prepared(OperatorChoice::DenseF32);
    let n = f64_room.scene.patches.len();
    assert!(n > 1000, "{n} patches");
    let (a, b) = (f64_room.system.operator(), f32_room.system.operator());
    assert_eq!((a.storage(), b.storage()), ("dense f64", "dense f32"));
    assert_eq!(b.stored_bytes(), 4 * n * n + 8 * n);

    // Form-factor health: row sums and reciprocity of the same pair integrals.
    let (ha, hb) = (&f64_room.form_factor_health, &f32_room.form_factor_health);
    for (x, y) in [
        (ha.row_sum_min, hb.row_sum_min),
        (ha.row_sum_max, hb.row_sum_max),
    ] {
        assert!((x - y).abs() <= ROW_SUM_TOLERANCE, "row sums {x} and {y}");
    }
    assert!((ha.reciprocity_mismatch - hb.reciprocity_mismatch).abs() < 1e-4);

    // The strongest modes.
    fn modes(room: &Prepared) -> Model<'_> {
        Model::new(&room.system, Formulation::Split, 16, Solver::Dense)
            .unwrap_or_else(|e| panic!("{e}"))
    }
    let (ma, mb) = (modes(&f64_room), modes(&f32_room));
    let worst_mu = ma.bands[0]
        .modes
        .values
        .iter()
        .zip(&mb.bands[0].modes.values)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max);
    assert!(
        worst_mu <= EIGENVALUE_TOLERANCE,
        "eigenvalues moved by {worst_mu:e} > {EIGENVALUE_TOLERANCE:e}"
    );

    // Every channel's exact readings at every sensor and zone, each against its own value.
    let mut worst = 0.0f64;
    for c in 0..f64_room.system.channel_count() {
        let (x, y) = (ma.channel_readings(c, 0), mb.channel_readings(c, 0));
        for (p, q) in x.iter().zip(&y) {
            if p.abs() > 0.0 {
                worst = worst.max((p - q).abs() / p.abs());
            }
        }
    }
    assert!(
        worst <= READING_RTOL,
        "readings moved by {worst:e} > {READING_RTOL:e}"
    );
    println!(
        "f32 operator: eigenvalues within {worst_mu:.1e} (bound {EIGENVALUE_TOLERANCE:.1e}), readings within {worst:.1e} (bound {READING_RTOL:.1e})"
    );
}

#[test]
fn a_build_through_the_single_precision_operator_reports_it() {
    let options = BuildOptions {
        form_factors: FormFactorOptions {
            operator: OperatorChoice::DenseF32,
            ..FormFactorOptions::default()
        },
        ..BuildOptions::default()
    };
    let (bytes, report) = pipeline::build(&scene(), &options).unwrap_or_else(|e| panic!("{e}"));
    assert!(!bytes.is_empty());
    assert_eq!(report.operator.storage, "dense f32");
    assert_eq!(
        report.operator.bytes,
        4 * report.patches * report.patches + 8 * report.patches
    );
    // Its own accuracy report, through the runtime against its own exact solve: channels
    // exact to f32 storage.
    for case in report
        .accuracy
        .iter()
        .filter(|c| c.case.starts_with("channel"))
    {
        assert!(
            case.worst_reading.error < 1e-5,
            "{}: {:e}",
            case.case,
            case.worst_reading.error
        );
    }
    // And auto keeps f64 at this size, where the cache holds it.
    let (_, auto) =
        pipeline::build(&scene(), &BuildOptions::default()).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(auto.operator.storage, "dense f64");
}

/// Each low-rank block of the hierarchical operator is within this of its own norm
/// (`hierarchical::Settings::default().tolerance`).
const BLOCK_TOLERANCE: f64 = 1e-6;

/// `‖S_H − S‖_F ≤ ε ‖S‖_F` moves eigenvalues of `H` by at most about `ε ρmax` and exact
/// readings by about `ε ρmax / (1 − ρmax)` relative (docs/math.md, "The hierarchical
/// operator"), on top of the f32 storage's own; a factor 2 of margin on each.
const HIERARCHICAL_EIGENVALUE_TOLERANCE: f64 = 2.0 * (BLOCK_TOLERANCE + 2.0 * U) * RHO_MAX;
const HIERARCHICAL_READING_RTOL: f64 =
    2.0 * (BLOCK_TOLERANCE + 2.0 * U) * RHO_MAX / (1.0 - RHO_MAX);

/// The hierarchical operator (`--operator hierarchical`) against the f64 one on the same
/// office: eigenvalues and every channel's exact readings within the bounds above, exactly
/// symmetric, and a build through it reports its compression.
#[test]
fn the_hierarchical_operator_reads_what_the_dense_one_reads() {
    let f64_room = prepared(OperatorChoice::Dense);
    let h_room = prepared(OperatorChoice::Hierarchical);
    let n = f64_room.scene.patches.len();
    let h = h_room.system.operator();
    assert_eq!(h.storage(), "hierarchical f32");
    assert!(h.stored_bytes() < 4 * n * n, "{} bytes", h.stored_bytes());
    for (i, j) in [(0, n - 1), (17, 503), (n / 2, n / 3)] {
        assert_eq!(h.entry(i, j).to_bits(), h.entry(j, i).to_bits());
    }
    let compression = h_room.compression.as_ref().expect("a compressed operator");
    assert!(
        compression.row_error < 10.0 * BLOCK_TOLERANCE,
        "{compression:?}"
    );

    let modes = |room: &Prepared| -> Vec<f64> {
        let m = Model::new(&room.system, Formulation::Split, 16, Solver::Partial)
            .unwrap_or_else(|e| panic!("{e}"));
        m.bands[0].modes.values.clone()
    };
    let (ma, mb) = (modes(&f64_room), modes(&h_room));
    let worst_mu = ma
        .iter()
        .zip(&mb)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max);
    assert!(
        worst_mu <= HIERARCHICAL_EIGENVALUE_TOLERANCE,
        "eigenvalues moved by {worst_mu:e} > {HIERARCHICAL_EIGENVALUE_TOLERANCE:e}"
    );
    let (ra, rb) = (
        f64_room.system.channel_responses().expect("solves"),
        h_room.system.channel_responses().expect("solves"),
    );
    let channels = f64_room.system.channel_count();
    let mut worst = 0.0f64;
    for c in 0..channels {
        let mut levels = vec![0.0; channels];
        levels[c] = 1.0;
        let x = f64_room.system.readings(0, &ra[c][0], &levels);
        let y = h_room.system.readings(0, &rb[c][0], &levels);
        for (p, q) in x.iter().zip(&y) {
            if p.abs() > 0.0 {
                worst = worst.max((p - q).abs() / p.abs());
            }
        }
    }
    assert!(
        worst <= HIERARCHICAL_READING_RTOL,
        "readings moved by {worst:e} > {HIERARCHICAL_READING_RTOL:e}"
    );
    println!(
        "hierarchical operator ({:.0} % of f32 dense): eigenvalues within {worst_mu:.1e} (bound {HIERARCHICAL_EIGENVALUE_TOLERANCE:.1e}), readings within {worst:.1e} (bound {HIERARCHICAL_READING_RTOL:.1e})",
        100.0 * h.stored_bytes() as f64 / (4 * n * n) as f64
    );
}
