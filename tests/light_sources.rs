//! The light-source seam (docs/math.md, "Light sources: emission and direct irradiance").
//!
//! 1. Emitting surfaces hand the model their emission and, as direct irradiance, exactly what
//!    that emission sends through the form factors: checked against an independent sum over
//!    the form factors and against flux conservation in a closed room.
//! 2. The same light handed over as direct irradiance from beyond the patches (no patch
//!    emission, as a luminaire's photometry or daylight will be) gives the same room: the
//!    exact solve, the readings, and the basis evaluated through the runtime agree with the
//!    emitting-surface model, up to the emitters' own exitance.

mod common;

use std::path::{Path, PathBuf};

use eigenrad::precompute::accuracy::runtime_eval;
use eigenrad::precompute::basis::basis_tables;
use eigenrad::precompute::formfactor::FormFactorOptions;
use eigenrad::precompute::pipeline::{prepare, Prepared};
use eigenrad::precompute::radiosity::eigen::{Formulation, Solver};
use eigenrad::precompute::radiosity::model::Model;
use eigenrad::precompute::sources::ChannelLight;
use eigenrad::runtime::Precision;

/// `common::two_channel_room` (a black ceiling lamp and a reflecting wall panel, a desk that
/// shadows part of the floor) with a sensor, a surface zone and a work plane.
fn scene_text() -> String {
    common::two_channel_room("sources", 0.8)
        + r#"
[[sensor]]
name = "desk"
position = [1.4, 1.0, 0.7]
normal = [0, 0, 1]

[[zone]]
name = "floor"
surfaces = ["room.floor"]

[[zone]]
name = "work_plane"
work_plane = { room = "room", height = 0.8, margin = 0.3, max_edge = 0.5 }
"#
}

/// Sums of a few hundred f64 terms taken in another order: 1e-12 relative.
const F64_TOLERANCE: f64 = 1e-12;

/// Everything kept (p = n), f64 LU against f64 modes: 1e-9 relative to the largest value.
const FULL_BASIS_TOLERANCE: f64 = 1e-9;

/// f32 runtime arithmetic over ~100 terms: 1e-5 relative to the largest value.
const RUNTIME_TOLERANCE: f64 = 1e-5;

/// Closure of the symmetrised form factors of this room (row sums within ~1e-4 of 1) bounds
/// how well the direct flux matches the emitted flux.
const CLOSURE_TOLERANCE: f64 = 1e-3;

/// The scene prepared from its own folder (`test` names it: tests run in parallel).
fn prepared(test: &str) -> Prepared {
    let dir = std::env::temp_dir().join(format!("eigenrad-{test}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path: PathBuf = dir.join("scene.toml");
    std::fs::write(&path, scene_text()).unwrap();
    let prepared = prepare(Path::new(&path), &FormFactorOptions::default());
    std::fs::remove_dir_all(&dir).ok();
    prepared.unwrap_or_else(|e| panic!("{e}"))
}

fn largest(x: &[f64]) -> f64 {
    x.iter().fold(0.0f64, |a, v| a.max(v.abs()))
}

/// Worst |a − b| over the largest |b|.
fn relative_gap(a: &[f64], b: &[f64]) -> f64 {
    assert_eq!(a.len(), b.len());
    let worst = a
        .iter()
        .zip(b)
        .fold(0.0f64, |w, (x, y)| w.max((x - y).abs()));
    worst / largest(b).max(f64::MIN_POSITIVE)
}

/// The same light with no patch emission: all of it arrives as direct irradiance.
fn as_light_from_beyond(lights: &[ChannelLight]) -> Vec<ChannelLight> {
    lights
        .iter()
        .map(|l| ChannelLight {
            emission: l.emission.iter().map(|e| vec![0.0; e.len()]).collect(),
            patch_irradiance: l.patch_irradiance.clone(),
            output_irradiance: l.output_irradiance.clone(),
        })
        .collect()
}

#[test]
fn emitting_surfaces_send_their_emission_through_the_form_factors() {
    let p = prepared("surfaces");
    let n = p.scene.patches.len();
    assert_eq!(p.system.lights.len(), 2);
    for (c, light) in p.system.lights.iter().enumerate() {
        let e = &light.emission[0];
        // Emission: the channel's patches at the scene's exitance, nothing elsewhere.
        for i in 0..n {
            let want = if p.scene.channel_of_patch[i] == Some(c) {
                p.scene.emission[i][0]
            } else {
                0.0
            };
            assert_eq!(e[i], want, "channel {c} patch {i}");
        }
        // Direct irradiance: Σ_j G_ij e_j / A_i, summed here independently.
        let by_hand: Vec<f64> = (0..n)
            .map(|i| {
                (0..n)
                    .map(|j| p.system.operator().entry(i, j) * e[j])
                    .sum::<f64>()
                    / p.system.area[i]
            })
            .collect();
        let gap = relative_gap(&light.patch_irradiance[0], &by_hand);
        assert!(
            gap <= F64_TOLERANCE,
            "channel {c}: patch irradiance {gap:.2e}"
        );
        let readings: Vec<f64> = p
            .system
            .output_rows
            .iter()
            .map(|r| (0..n).map(|j| r[j] * e[j]).sum())
            .collect();
        let gap = relative_gap(&light.output_irradiance[0], &readings);
        assert!(gap <= F64_TOLERANCE, "channel {c}: outputs {gap:.2e}");
        // A closed room receives all the flux its emitters send out.
        let emitted: f64 = (0..n).map(|i| p.system.area[i] * e[i]).sum();
        let received: f64 = (0..n)
            .map(|i| p.system.area[i] * light.patch_irradiance[0][i])
            .sum();
        assert!(
            (received / emitted - 1.0).abs() <= CLOSURE_TOLERANCE,
            "channel {c}: received {received} lm of {emitted} lm"
        );
        // Nothing is left beyond the patches: the model carries it all as emission.
        let external = light.external(p.system.operator(), &p.system.area, &p.system.output_rows);
        assert!(external.patches.iter().all(Option::is_none), "channel {c}");
        assert!(external.outputs.iter().all(Option::is_none), "channel {c}");
    }
}

#[test]
fn light_from_beyond_the_patches_lights_the_room_as_the_surfaces_do() {
    let p = prepared("beyond");
    let n = p.scene.patches.len();
    let beyond = as_light_from_beyond(&p.system.lights);
    let levels = [0.7, 0.4];
    let levels32 = [0.7f32, 0.4];
    // The emitters' own exitance at these levels, which only the surface model contains.
    let emitted: Vec<f64> = (0..n)
        .map(|i| {
            levels
                .iter()
                .zip(&p.system.lights)
                .map(|(l, light)| l * light.emission[0][i])
                .sum()
        })
        .collect();
    for formulation in [Formulation::Split, Formulation::Seed] {
        let surfaces_system = p.system.with_lights(p.system.lights.clone());
        let external_system = p.system.with_lights(beyond.clone());
        let model = |system| Model::new(system, formulation, n, Solver::Dense).unwrap();
        let surfaces = model(&surfaces_system);
        let external = model(&external_system);
        assert!(external
            .system
            .external
            .iter()
            .all(|x| x.patches[0].is_some()));

        // Exact solve and readings.
        let m_surfaces = surfaces.system.exact(0, &levels, &[]).unwrap();
        let m_external = external.system.exact(0, &levels, &[]).unwrap();
        let reflected: Vec<f64> = m_surfaces
            .iter()
            .zip(&emitted)
            .map(|(m, e)| m - e)
            .collect();
        let gap = relative_gap(&m_external, &reflected);
        assert!(
            gap <= F64_TOLERANCE * 1e3,
            "{formulation:?} exact exitance {gap:.2e}"
        );
        let want = surfaces.readings(0, &m_surfaces, &levels);
        let got = external.readings(0, &m_external, &levels);
        let gap = relative_gap(&got, &want);
        assert!(
            gap <= F64_TOLERANCE * 1e3,
            "{formulation:?} exact readings {gap:.2e}"
        );

        // Every mode kept: the expansions equal the exact solve.
        let truncated = external.truncated(0, n, &levels, &[]);
        let gap = relative_gap(&truncated, &m_external);
        assert!(
            gap <= FULL_BASIS_TOLERANCE,
            "{formulation:?} p = n {gap:.2e}"
        );

        // Through the runtime: same readings, exitance less the emitters' own.
        let evaluate = |m: &Model| {
            let bytes = basis_tables(&p.scene, m, n, Precision::F32)
                .to_bytes()
                .unwrap();
            runtime_eval::evaluate(&bytes, &levels32, &[], true).unwrap()
        };
        let (a, b) = (evaluate(&surfaces), evaluate(&external));
        let outputs = |r: &runtime_eval::Readout| -> Vec<f64> {
            r.sensors.iter().chain(&r.zones).map(|v| v[0]).collect()
        };
        let gap = relative_gap(&outputs(&b), &outputs(&a));
        assert!(
            gap <= RUNTIME_TOLERANCE,
            "{formulation:?} runtime readings {gap:.2e}"
        );
        let a_reflected: Vec<f64> = (0..n).map(|i| a.exitance[i][0] - emitted[i]).collect();
        let b_exitance: Vec<f64> = (0..n).map(|i| b.exitance[i][0]).collect();
        let gap = relative_gap(&b_exitance, &a_reflected);
        assert!(
            gap <= RUNTIME_TOLERANCE,
            "{formulation:?} runtime exitance {gap:.2e}"
        );
    }
}

#[test]
fn short_expansions_read_both_kinds_of_light_alike() {
    // Channels are carried by their exact responses whichever way the light comes, so even a
    // short expansion differs between the two only by the emitters' own exitance.
    let p = prepared("truncated");
    let n = p.scene.patches.len();
    let levels = [1.0, 1.0];
    let surfaces_system = p.system.with_lights(p.system.lights.clone());
    let external_system = p.system.with_lights(as_light_from_beyond(&p.system.lights));
    let make = |system| Model::new(system, Formulation::Split, 8, Solver::Dense).unwrap();
    let surfaces = make(&surfaces_system);
    let external = make(&external_system);
    for modes in [0, 1, 4, 8] {
        let a = surfaces.truncated(0, modes, &levels, &[]);
        let b = external.truncated(0, modes, &levels, &[]);
        let emitted: Vec<f64> = (0..n)
            .map(|i| p.system.lights.iter().map(|l| l.emission[0][i]).sum())
            .collect();
        let reflected: Vec<f64> = a.iter().zip(&emitted).map(|(m, e)| m - e).collect();
        let gap = relative_gap(&b, &reflected);
        assert!(gap <= F64_TOLERANCE * 1e3, "p = {modes}: {gap:.2e}");
    }
}
