//! Exact results of a closed room of uniform reflectance (docs/math.md, "Exact results"
//! implementation must reproduce"), through the exact solve (`cli::solve`, the code behind
//! `eigenrad solve`) and through a basis with every mode kept (p = n) evaluated by the runtime
//! (`accuracy::runtime_eval`, the arithmetic firmware performs):
//!
//! - CIE 171:2006, test case 5.8 (a 4 m cube, all surfaces of one reflectance ρ, total flux
//!   Φ): the area-average irradiance over all surfaces is `Φ / (S (1 − ρ))`, S = 96 m²;
//! - the "white furnace": every patch emitting E gives `M = E / (1 − ρ)` everywhere;
//! - the all-ones vector is a mode of `R F` with `μ = ρ`.
//!
//! Run with `cargo test --test validation_closed_room -- --nocapture` to see the figures.

use std::path::{Path, PathBuf};

use eigenrad::precompute::accuracy::runtime_eval;
use eigenrad::precompute::cli;
use eigenrad::precompute::formfactor::FormFactorOptions;
use eigenrad::precompute::pipeline::{self, prepare, BuildOptions, ModeSelection};
use eigenrad::precompute::radiosity::eigen::{self, Formulation, Solver};

/// CIE 171:2006 test case 5.8 asks for the analytic average; the project's acceptance figure
/// is 0.2 % relative (project issue 5).
const CIE_TOLERANCE: f64 = 2e-3;

/// White furnace: 1e-4 relative (project issue 5). The f32 runtime keeps ~1e-6; the form
/// factors' row sums (closure) are the limit.
const FURNACE_TOLERANCE: f64 = 1e-4;

/// Side of the CIE 171 test cube, m.
const SIDE: f64 = 4.0;
/// Its total surface, m².
const SURFACE: f64 = 6.0 * SIDE * SIDE;

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("eigenrad-val-{}-{name}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// The 4 m cube with every face of reflectance `rho`, meshed at 1 m (96 patches), a zone
/// `all` over every surface, and the channel `channel` (a TOML table body).
fn cube(dir: &Path, rho: f64, channel: &str) -> PathBuf {
    let text = format!(
        r#"
[scene]
name = "cie171-5.8"
bands = "photopic"
unit = "m"
max_edge = 1.0

[materials]
surface = {{ reflectance = {rho} }}

[[room]]
name = "room"
min = [0, 0, 0]
max = [{SIDE}, {SIDE}, {SIDE}]
material = "surface"

[[channel]]
{channel}

[[zone]]
name = "all"
surfaces = ["room*"]
"#
    );
    let path = dir.join(format!("cube-{rho}.toml"));
    std::fs::write(&path, text).unwrap();
    path
}

/// A basis with every mode kept (p = n), dense eigensolver.
fn full_basis(path: &Path) -> Vec<u8> {
    let opts = BuildOptions {
        modes: ModeSelection::Count(usize::MAX),
        solver: Solver::Dense,
        ..BuildOptions::default()
    };
    pipeline::build(path, &opts).unwrap().0
}

#[test]
fn cie_171_case_5_8_average_irradiance_in_a_cube() {
    let dir = scratch("cie171");
    // The whole ceiling emits Φ (lm).
    let flux = 10_000.0;
    println!("CIE 171:2006 case 5.8, 4 m cube, Φ = {flux} lm from the ceiling:");
    println!("    ρ   reference lux   solve lux   rel. err   basis lux   rel. err");
    for rho in [0.0, 0.2, 0.5, 0.8] {
        let channel = format!("name = \"ceiling\"\nsurfaces = [\"room.ceiling\"]\nflux = {flux}");
        let path = cube(&dir, rho, &channel);
        let want = flux / (SURFACE * (1.0 - rho));

        let solved = cli::solve(
            &path,
            &cli::LevelArgs::default(),
            false,
            &FormFactorOptions::default(),
        )
        .unwrap()
        .zones[0]
            .irradiance[0];
        let basis = full_basis(&path);
        let evaluated = runtime_eval::evaluate(&basis, &[1.0], &[], false)
            .unwrap()
            .zones[0][0];
        let (e1, e2) = (
            (solved - want).abs() / want,
            (evaluated - want).abs() / want,
        );
        println!("  {rho:.1} {want:15.4} {solved:11.4} {e1:10.2e} {evaluated:11.4} {e2:10.2e}");
        assert!(e1 <= CIE_TOLERANCE, "solve, ρ = {rho}: {solved} vs {want}");
        assert!(
            e2 <= CIE_TOLERANCE,
            "basis, ρ = {rho}: {evaluated} vs {want}"
        );
    }
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn white_furnace() {
    let dir = scratch("furnace");
    let e = 100.0;
    println!("White furnace, every patch emitting {e} lux:");
    println!("    ρ   E/(1-ρ) lux   worst rel. err solve   worst rel. err basis (p = n)");
    for rho in [0.2, 0.5, 0.8] {
        let channel = format!("name = \"all\"\nsurfaces = [\"room*\"]\nexitance = {e}");
        let path = cube(&dir, rho, &channel);
        let want = e / (1.0 - rho);

        let solved = cli::solve(
            &path,
            &cli::LevelArgs::default(),
            true,
            &FormFactorOptions::default(),
        )
        .unwrap();
        let patches = solved.patches.unwrap();
        let worst_solve = patches
            .iter()
            .map(|p| (p.exitance[0] - want).abs() / want)
            .fold(0.0, f64::max);

        let basis = full_basis(&path);
        let got = runtime_eval::evaluate(&basis, &[1.0], &[], true).unwrap();
        assert_eq!(got.exitance.len(), patches.len());
        let worst_basis = got
            .exitance
            .iter()
            .map(|m| (m[0] - want).abs() / want)
            .fold(0.0, f64::max);
        println!("  {rho:.1} {want:13.4} {worst_solve:22.2e} {worst_basis:22.2e}");
        assert!(worst_solve <= FURNACE_TOLERANCE, "solve, ρ = {rho}");
        assert!(worst_basis <= FURNACE_TOLERANCE, "basis, ρ = {rho}");
    }
    std::fs::remove_dir_all(&dir).ok();
}

/// `μ_top = ρ` up to the closure of the form factors (row sums within ~1e-5 of 1 on this
/// cube): 1e-4 relative; the mode's shape is as close to constant.
const MODE_TOLERANCE: f64 = 1e-4;

#[test]
fn the_constant_vector_is_the_top_mode_with_mu_equal_to_rho() {
    let dir = scratch("modes");
    for rho in [0.2, 0.5, 0.8] {
        let channel = "name = \"all\"\nsurfaces = [\"room*\"]\nexitance = 1";
        let path = cube(&dir, rho, channel);
        let prepared = prepare(&path, &FormFactorOptions::default()).unwrap();
        let n = prepared.system.area.len();
        let reflectance = vec![rho; n];
        let modes = eigen::modes(
            prepared.system.operator(),
            &prepared.system.area,
            &reflectance,
            Formulation::Split,
            4,
            Solver::Dense,
        )
        .unwrap();
        let mu = modes.values[0];
        // Vᵀ B V = I with B = diag(A/ρ): the constant mode is 1/√(Σ A/ρ) = √(ρ/S).
        let constant = (rho / SURFACE).sqrt();
        let v = modes.vectors.col(0);
        let sign = v[0].signum();
        let worst_shape = (0..n)
            .map(|i| (sign * v[i] - constant).abs() / constant)
            .fold(0.0, f64::max);
        println!(
            "ρ = {rho}: top μ = {mu:.8}, rel. error {:.2e}; mode shape vs constant {worst_shape:.2e}; next μ = {:.6}",
            (mu - rho).abs() / rho,
            modes.values[1]
        );
        assert!(
            (mu - rho).abs() <= MODE_TOLERANCE * rho,
            "μ = {mu}, ρ = {rho}"
        );
        assert!(worst_shape <= MODE_TOLERANCE, "shape {worst_shape:e}");
        assert!(
            modes.values[1].abs() < mu,
            "the constant mode is the strongest"
        );
    }
    std::fs::remove_dir_all(&dir).ok();
}
