//! With every mode kept (p = n), a basis must reproduce the dense solve of (I − R F) M = M0
//! (docs/math.md: "Any truncation p = n reproduces the dense solve to rounding"), for both
//! formulations, through the runtime's f32 arithmetic — with random reflectances, a black
//! (ρ = 0) luminaire, channels and arbitrary per-patch exitance.

use std::path::Path;

use eigenrad::precompute::accuracy::runtime_eval;
use eigenrad::precompute::basis::basis_tables;
use eigenrad::precompute::formfactor::FormFactorOptions;
use eigenrad::precompute::pipeline::prepare;
use eigenrad::precompute::radiosity::eigen::{Formulation, Solver};
use eigenrad::precompute::radiosity::model::Model;
use eigenrad::runtime::Precision;

/// f32 evaluation of sums of up to ~100 terms against an f64 LU solve: 1e-5 relative,
/// norm-wise (the issue's figure).
const RTOL: f64 = 1e-5;

/// A 3 m × 2 m × 2.5 m room with a desk and a black ceiling luminaire; reflectances drawn
/// from a fixed-seed generator.
fn scene_text(seed: u64) -> String {
    let mut state = seed;
    let mut next = move || {
        state = state
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        0.05 + 0.85 * ((state >> 11) as f64 / (1u64 << 53) as f64)
    };
    format!(
        r#"
[scene]
name = "dense"
bands = "photopic"
unit = "m"
max_edge = 0.9

[materials]
floor = {{ reflectance = {:.3} }}
ceiling = {{ reflectance = {:.3} }}
walls = {{ reflectance = {:.3} }}
desk = {{ reflectance = {:.3} }}
lamp = {{ reflectance = 0.0 }}

[[room]]
name = "room"
min = [0, 0, 0]
max = [3, 2, 2.5]
material = "walls"
floor = "floor"
ceiling = "ceiling"

[[block]]
name = "desk"
min = [0.8, 0.6, 0]
max = [2.0, 1.4, 0.7]
material = "desk"
bottom = false

[[quad]]
name = "lamp"
material = "lamp"
corners = [[1.2, 0.7, 2.45], [1.2, 1.3, 2.45], [1.8, 1.3, 2.45], [1.8, 0.7, 2.45]]

[[channel]]
name = "lamp"
surfaces = ["lamp"]
flux = 3000

[[sensor]]
name = "desk"
position = [1.4, 1.0, 0.7]
normal = [0, 0, 1]

[[zone]]
name = "floor"
surfaces = ["room.floor"]
"#,
        next(),
        next(),
        next(),
        next()
    )
}

#[test]
fn full_basis_equals_the_dense_solve_for_both_formulations() {
    let dir = std::env::temp_dir().join(format!("eigenrad-dense-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("scene.toml");
    std::fs::write(&path, scene_text(7)).unwrap();
    let prepared = prepare(Path::new(&path), &FormFactorOptions::default()).unwrap();
    let scene = &prepared.scene;
    let n = scene.patches.len();
    assert!(n > 40, "{n} patches");

    // A general emitter state: the lamp channel at 0.7 and arbitrary exitance on a few
    // reflecting patches and on the black lamp itself.
    let levels = vec![0.7];
    let lamp_patch = (0..n).find(|&i| scene.reflectance[i][0] == 0.0).unwrap();
    let mut extra = vec![0.0; n];
    extra[3] = 120.0;
    extra[n / 2] = 40.0;
    extra[lamp_patch] = 500.0;

    for formulation in [Formulation::Split, Formulation::Seed] {
        let model = Model::new(&prepared.system, formulation, n, Solver::Dense).unwrap();
        let exact = model.system.exact(0, &levels, &extra).unwrap();
        let exact_out = model.system.outputs(&exact);

        let bytes = basis_tables(scene, &model, n, Precision::F32)
            .to_bytes()
            .unwrap();
        let levels32: Vec<f32> = levels.iter().map(|&l| l as f32).collect();
        let got = runtime_eval::evaluate(&bytes, &levels32, &[extra.clone()], true).unwrap();

        let scale = exact.iter().fold(0.0f64, |a, v| a.max(v.abs()));
        let worst = (0..n)
            .map(|i| (got.exitance[i][0] - exact[i]).abs())
            .fold(0.0, f64::max);
        assert!(
            worst <= RTOL * scale,
            "{formulation:?}: exitance error {worst:e} of {scale:e}"
        );

        let out_scale = exact_out.iter().fold(0.0f64, |a, v| a.max(v.abs()));
        let readings: Vec<f64> = got.sensors.iter().chain(&got.zones).map(|r| r[0]).collect();
        for (o, (a, e)) in readings.iter().zip(&exact_out).enumerate() {
            assert!(
                (a - e).abs() <= RTOL * out_scale,
                "{formulation:?}: output {o}: {a} vs {e}"
            );
        }
        // The f64 truncated expansion itself, before f32 storage: exact to rounding.
        let f64_full = model.truncated(0, n, &levels, &extra);
        let worst64 = (0..n)
            .map(|i| (f64_full[i] - exact[i]).abs())
            .fold(0.0, f64::max);
        assert!(
            worst64 <= 1e-9 * scale,
            "{formulation:?}: f64 expansion error {worst64:e}"
        );
    }
    std::fs::remove_dir_all(&dir).ok();
}
