//! Channels are stored exactly (docs/format.md, version 2): a basis the precompute writes for
//! the example office at the default 32 modes reads, for any combination of channel levels,
//! the exact solve's patch exitance and sensor and zone readings, to f32 rounding, in both
//! formulations and through both evaluators of the runtime.

use std::path::Path;

use eigenrad::precompute::accuracy::runtime_eval;
use eigenrad::precompute::basis::basis_tables;
use eigenrad::precompute::formfactor::FormFactorOptions;
use eigenrad::precompute::pipeline::prepare;
use eigenrad::precompute::radiosity::eigen::{Formulation, Solver};
use eigenrad::precompute::radiosity::model::Model;
use eigenrad::runtime::{Basis, ChannelEvaluator, Precision};

/// The modes `eigenrad build` keeps by default.
const MODES: usize = 32;

/// The runtime's sum of `m` stored f32 products against the same sum in f64 of the model's
/// responses: each term is rounded once to f32 (2⁻²⁴ ≈ 6e-8), levels such as 0.1 too, and the
/// terms are non-negative, so the relative error of the sum stays near 1e-7.
const STORAGE_RTOL: f64 = 1e-6;

/// Against an independent exact solve of the same levels (another right-hand side of the
/// LU): the storage rounding plus the solve's own.
const EXACT_RTOL: f64 = 1e-5;

/// Levels a controller sets often: off, dimmed, odd, high, full.
const LEVELS: [f64; 5] = [0.0, 0.1, 0.37, 0.8, 1.0];

/// xorshift64*: deterministic, dependency-free.
struct Rng(u64);
impl Rng {
    fn below(&mut self, n: usize) -> usize {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        (self.0.wrapping_mul(0x2545_F491_4F6C_DD1D) >> 33) as usize % n
    }
}

/// `|got − want| / |want|`, 0 when both are 0.
fn relative(got: f64, want: f64) -> f64 {
    let gap = (got - want).abs();
    if gap == 0.0 {
        0.0
    } else {
        gap / want.abs()
    }
}

#[test]
fn office_channels_read_the_exact_solve_for_any_levels() {
    channels_read_the_exact_solve_for_any_levels("examples/office/scene.toml", 1000, 5);
}

/// The classroom's channels are luminaires with photometry: their light enters the model as
/// direct irradiance from beyond the patches, and the basis reads it as exactly.
#[test]
fn classroom_luminaire_channels_read_the_exact_solve_for_any_levels() {
    channels_read_the_exact_solve_for_any_levels("examples/classroom/scene.toml", 500, 2);
}

/// The scene at `scene` (relative to the repository), of more than `patches` patches and
/// `channels` channels, read through the runtime for many level vectors.
fn channels_read_the_exact_solve_for_any_levels(scene: &str, patches: usize, channels: usize) {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join(scene);
    let prepared = prepare(&path, &FormFactorOptions::default()).unwrap();
    let scene = &prepared.scene;
    let n = scene.patches.len();
    let m = scene.channels.len();
    assert!(n > patches && m == channels, "{n} patches, {m} channels");
    let mut rng = Rng(0x5eed);
    // Every channel alone at full, all on, all off, and random combinations.
    let mut cases: Vec<Vec<f64>> = (0..m)
        .map(|c| (0..m).map(|d| if d == c { 1.0 } else { 0.0 }).collect())
        .collect();
    cases.push(vec![1.0; m]);
    cases.push(vec![0.0; m]);
    for _ in 0..8 {
        cases.push((0..m).map(|_| LEVELS[rng.below(LEVELS.len())]).collect());
    }

    for formulation in [Formulation::Split, Formulation::Seed] {
        let model = Model::new(&prepared.system, formulation, MODES, Solver::Auto).unwrap();
        let bytes = basis_tables(scene, &model, MODES, Precision::F32)
            .to_bytes()
            .unwrap();
        let basis = Basis::from_bytes(&bytes).unwrap();
        assert_eq!(basis.mode_count(), MODES);
        let mut evaluator = ChannelEvaluator::<1, 8>::new(basis).unwrap();
        let (mut worst_storage, mut worst_exact) = (0.0f64, 0.0f64);

        for levels in &cases {
            let levels32: Vec<f32> = levels.iter().map(|&l| l as f32).collect();
            // The levels as the runtime holds them, for the f64 combinations.
            let held: Vec<f64> = levels32.iter().map(|&l| f64::from(l)).collect();
            let got = runtime_eval::evaluate(&bytes, &levels32, &[], true).unwrap();
            evaluator.set_channel_levels(&levels32).unwrap();

            // The model's exact per-channel responses and readings, combined in f64.
            let combined: Vec<f64> = (0..n)
                .map(|i| {
                    (0..m)
                        .map(|c| held[c] * model.channel_response(c, 0)[i])
                        .sum()
                })
                .collect();
            let readings: Vec<Vec<f64>> = (0..m).map(|c| model.channel_readings(c, 0)).collect();
            let outputs = readings[0].len();
            let combined_out: Vec<f64> = (0..outputs)
                .map(|o| (0..m).map(|c| held[c] * readings[c][o]).sum())
                .collect();
            // An independent exact solve of the same state.
            let exact = model.system.exact(0, levels, &[]).unwrap();
            let exact_out = model.readings(0, &exact, levels);

            for i in 0..n {
                let runtime = got.exitance[i][0];
                assert_eq!(
                    evaluator.exitance(i).unwrap()[0] as f64,
                    runtime,
                    "patch {i}"
                );
                let s = relative(runtime, combined[i]);
                let e = relative(runtime, exact[i]);
                assert!(
                    s <= STORAGE_RTOL,
                    "{formulation:?} {levels:?}: patch {i} exitance {runtime:e}, \
                     responses {:e} ({s:e})",
                    combined[i]
                );
                assert!(
                    e <= EXACT_RTOL,
                    "{formulation:?} {levels:?}: patch {i} exitance {runtime:e}, \
                     exact {:e} ({e:e})",
                    exact[i]
                );
                worst_storage = worst_storage.max(s);
                worst_exact = worst_exact.max(e);
            }
            let sensors = got.sensors.len();
            let zones = got.zones.len();
            // Sensors, zones, then every zone's grid points: the model's outputs.
            let runtime_out: Vec<f64> = got
                .sensors
                .iter()
                .chain(&got.zones)
                .chain(&got.grid)
                .map(|r| r[0])
                .collect();
            assert_eq!(runtime_out.len(), outputs);
            let points: Vec<(usize, usize)> = (0..zones)
                .flat_map(|z| (0..basis.grid_points(z).unwrap()).map(move |i| (z, i)))
                .collect();
            for (o, &runtime) in runtime_out.iter().enumerate() {
                let direct = if o < sensors {
                    evaluator.sensor_irradiance(o)
                } else if o < sensors + zones {
                    evaluator.zone_irradiance(o - sensors)
                } else {
                    let (z, i) = points[o - sensors - zones];
                    evaluator.grid_point_irradiance(z, i)
                };
                assert_eq!(direct.unwrap()[0] as f64, runtime, "output {o}");
                let s = relative(runtime, combined_out[o]);
                let e = relative(runtime, exact_out[o]);
                assert!(
                    s <= STORAGE_RTOL,
                    "{formulation:?} {levels:?}: output {o} {runtime:e}, responses {:e} ({s:e})",
                    combined_out[o]
                );
                assert!(
                    e <= EXACT_RTOL,
                    "{formulation:?} {levels:?}: output {o} {runtime:e}, exact {:e} ({e:e})",
                    exact_out[o]
                );
                worst_storage = worst_storage.max(s);
                worst_exact = worst_exact.max(e);
            }
        }
        eprintln!(
            "{formulation:?}, p = {MODES}: {} level vectors, largest relative difference \
             {worst_storage:.1e} from the responses, {worst_exact:.1e} from the exact solve",
            cases.len()
        );
    }
}
