//! How close a truncated expansion is to the exact dense solve, as a function of the mode
//! count p: the figures behind `--tolerance`, the build report and `eigenrad verify`.

use serde::Serialize;

pub mod calibration;
pub mod daylight;
pub mod metric;
pub mod rng;
pub mod runtime_eval;
pub mod sky;
pub mod sun_parts;

use crate::radiosity::eigen::EigenError;
use crate::radiosity::model::Model;
use crate::radiosity::System;
use crate::scene::Scene;
use rng::Rng;

/// An emitter state to test: channel levels and per-patch exitance per band.
#[derive(Clone, Debug)]
pub struct Case {
    /// What it is (`channel NAME`, `random pattern K`).
    pub name: String,
    /// Relative level of every channel.
    pub levels: Vec<f64>,
    /// Per band, per patch exitance set directly (W/m² or lux).
    pub extra: Vec<Vec<f64>>,
}

/// Relative errors of one case at each tested p.
#[derive(Clone, Debug, Serialize)]
pub struct Curve {
    /// The case's name.
    pub case: String,
    /// Mode counts tested.
    pub modes: Vec<usize>,
    /// [`metric::patch_error`] at each p, worst band.
    pub patch_error: Vec<f64>,
    /// The worst [`metric::reading_errors`] over the sensors and zones at each p, worst band.
    pub reading_error: Vec<f64>,
}

/// Channel levels a random level vector draws from: off, dimmed and full, as a controller
/// sets them.
pub const RANDOM_LEVELS: [f64; 5] = [0.0, 0.1, 0.37, 0.8, 1.0];

/// The cases every build report lists: [`channel_cases`], `random` [`level_cases`],
/// `random` [`emitter_cases`] and `random` [`pattern_cases`].
pub fn standard_cases(scene: &Scene, random: usize) -> Vec<Case> {
    let mut cases = channel_cases(scene);
    cases.extend(level_cases(scene, random));
    cases.extend(emitter_cases(scene, random));
    cases.extend(pattern_cases(scene, random));
    cases
}

/// A case with channel levels `levels` and exitance set patch by patch `extra` (per band).
fn case(name: String, levels: Vec<f64>, extra: Vec<Vec<f64>>) -> Case {
    Case {
        name,
        levels,
        extra,
    }
}

/// No exitance set patch by patch: zero in every band.
fn no_extra(scene: &Scene) -> Vec<Vec<f64>> {
    vec![vec![0.0; scene.patches.len()]; scene.bands.count()]
}

/// Every channel alone at level 1.
pub fn channel_cases(scene: &Scene) -> Vec<Case> {
    let m = scene.channels.len();
    (0..m)
        .map(|c| {
            let mut levels = vec![0.0; m];
            levels[c] = 1.0;
            let name = format!("channel {}", scene.channels[c].name);
            case(name, levels, no_extra(scene))
        })
        .collect()
}

/// `count` level vectors, each channel at one of [`RANDOM_LEVELS`] (none without channels).
pub fn level_cases(scene: &Scene, count: usize) -> Vec<Case> {
    let m = scene.channels.len();
    let mut rng = Rng(0xD1B5_4A32_D192_ED03);
    (0..count * usize::from(m > 0))
        .map(|k| {
            let levels = (0..m)
                .map(|_| {
                    let pick = (rng.next_f64() * RANDOM_LEVELS.len() as f64) as usize;
                    RANDOM_LEVELS[pick.min(RANDOM_LEVELS.len() - 1)]
                })
                .collect();
            case(format!("random levels {}", k + 1), levels, no_extra(scene))
        })
        .collect()
}

/// `count` patterns of exitance set patch by patch on the patches that emit, each at a
/// random share of its own exitance at level 1, channels off (none when nothing emits).
pub fn emitter_cases(scene: &Scene, count: usize) -> Vec<Case> {
    let (n, bands, m) = (
        scene.patches.len(),
        scene.bands.count(),
        scene.channels.len(),
    );
    let emits = scene.emission.iter().flatten().any(|&e| e > 0.0);
    let mut rng = Rng(0x2545_F491_4F6C_DD1D);
    (0..count * usize::from(emits))
        .map(|k| {
            let shares: Vec<f64> = (0..n).map(|_| rng.next_f64()).collect();
            let extra = (0..bands)
                .map(|b| (0..n).map(|i| shares[i] * scene.emission[i][b]).collect())
                .collect();
            case(
                format!("emitters patch by patch {}", k + 1),
                vec![0.0; m],
                extra,
            )
        })
        .collect()
}

/// `count` patterns over the whole room, channels off: a random fifth of the patches each
/// emitting a random exitance up to the largest exitance a patch of the scene emits at level
/// 1, in any band (1 when nothing emits), same in every band.
pub fn pattern_cases(scene: &Scene, count: usize) -> Vec<Case> {
    let (n, bands, m) = (
        scene.patches.len(),
        scene.bands.count(),
        scene.channels.len(),
    );
    let peak = scene
        .emission
        .iter()
        .flatten()
        .copied()
        .fold(0.0f64, f64::max);
    let peak = if peak > 0.0 { peak } else { 1.0 };
    let mut rng = Rng(0x9E37_79B9_7F4A_7C15);
    (0..count)
        .map(|k| {
            let pattern: Vec<f64> = (0..n)
                .map(|_| {
                    if rng.next_f64() < 0.2 {
                        peak * rng.next_f64()
                    } else {
                        0.0
                    }
                })
                .collect();
            let name = format!("random pattern {}", k + 1);
            case(name, vec![0.0; m], vec![pattern; bands])
        })
        .collect()
}

/// Mode counts tested for the tolerance search and reports: 1, 2, 3, 4, 6, 8, 12, 16, …
/// (about √2 apart) up to and including `max`.
pub fn mode_ladder(max: usize) -> Vec<usize> {
    let mut out = Vec::new();
    let mut p = 1usize;
    let mut step_half = false;
    while p < max {
        out.push(p);
        p = if p < 4 {
            p + 1
        } else if step_half {
            step_half = false;
            p / 3 * 4
        } else {
            step_half = true;
            p / 2 * 3
        };
    }
    out.push(max);
    out.dedup();
    out
}

/// Modes `model` holds: the most of any band (a band with fewer reflecting patches has fewer).
pub fn modes_held(model: &Model) -> usize {
    model
        .bands
        .iter()
        .map(|b| b.mode_count())
        .max()
        .unwrap_or(0)
}

/// One point of a truncation sweep (one band, one mode count): the index into the mode
/// ladder, and the truncated and exact solutions (patch exitance and output readings) there.
pub struct SweepPoint<'s> {
    /// Index of the mode count in the ladder.
    pub step: usize,
    /// Truncated exitance of every patch.
    pub exitance: &'s [f64],
    /// Exact exitance of every patch.
    pub exact: &'s [f64],
    /// Truncated readings of every output (sensors, then zones).
    pub outputs: &'s [f64],
    /// Exact readings of every output.
    pub exact_outputs: &'s [f64],
}

/// The exact solutions of a set of cases, solved once and shared by every figure that is
/// measured against them (the tolerance search, the build report, both formulations of
/// `eigenrad verify`).
pub struct ExactCases {
    /// `by_band[b][k]`: exitance of every patch for case `k` in band `b`, W/m² or lux.
    by_band: Vec<Vec<Vec<f64>>>,
}

impl ExactCases {
    /// Every case of `cases` solved exactly by `system`, one solve per band with a right-hand
    /// side per case.
    pub fn solve(system: &System, cases: &[Case]) -> Result<ExactCases, EigenError> {
        let by_band = (0..system.band_count())
            .map(|b| {
                let inputs: Vec<(&[f64], &[f64])> = cases
                    .iter()
                    .map(|c| (c.levels.as_slice(), c.extra[b].as_slice()))
                    .collect();
                system.exact_many(b, &inputs)
            })
            .collect::<Result<Vec<_>, _>>()?;
        Ok(ExactCases { by_band })
    }

    /// Exact exitance of case `k` (in the order solved) in band `b`.
    pub fn exitance(&self, k: usize, b: usize) -> &[f64] {
        &self.by_band[b][k]
    }
}

/// Evaluates `case` (number `k` of `exact`) with the first p modes for every p of `modes`
/// (ascending), adding one mode's contribution at a time, and shows each point to `visit`
/// together with the exact solve. Shared by `--tolerance`, the build report and
/// `eigenrad verify`.
pub fn sweep(
    model: &Model,
    case: &Case,
    exact: (&ExactCases, usize),
    modes: &[usize],
    mut visit: impl FnMut(SweepPoint<'_>),
) {
    let (solutions, k) = exact;
    for b in 0..model.bands.len() {
        let exact = solutions.exitance(k, b);
        let exact_outputs = model.readings(b, exact, &case.levels);
        let (mut m, amplitude) = model.expansion(b, &case.levels, &case.extra[b]);
        let v = &model.bands[b].modes.vectors;
        let mut done = 0;
        for (t, &p) in modes.iter().enumerate() {
            let p = p.min(amplitude.len());
            for (k, a) in amplitude.iter().enumerate().take(p).skip(done) {
                for (i, x) in m.iter_mut().enumerate() {
                    *x += v[(i, k)] * a;
                }
            }
            done = done.max(p);
            let outputs = model.readings(b, &m, &case.levels);
            visit(SweepPoint {
                step: t,
                exitance: &m,
                exact,
                outputs: &outputs,
                exact_outputs: &exact_outputs,
            });
        }
    }
}

/// Error curves of `case` for every p in `modes` (ascending), against the exact solve.
pub fn curve(model: &Model, case: &Case, exact: (&ExactCases, usize), modes: &[usize]) -> Curve {
    let mut patch_error = vec![0.0f64; modes.len()];
    let mut reading_error = vec![0.0f64; modes.len()];
    sweep(model, case, exact, modes, |pt| {
        let t = pt.step;
        let patches = metric::patch_error(model.area(), pt.exitance, pt.exact);
        patch_error[t] = patch_error[t].max(patches);
        let readings = metric::worst_reading(pt.outputs, pt.exact_outputs);
        reading_error[t] = reading_error[t].max(readings.error);
    });
    Curve {
        case: case.name.clone(),
        modes: modes.to_vec(),
        patch_error,
        reading_error,
    }
}

/// The smallest p at which, for every curve, the patch error and every sensor's and zone's
/// reading error are at or under `tolerance`, if any.
pub fn smallest_p(curves: &[Curve], tolerance: f64) -> Option<usize> {
    let modes = &curves.first()?.modes;
    (0..modes.len())
        .find(|&t| {
            curves
                .iter()
                .all(|c| c.patch_error[t] <= tolerance && c.reading_error[t] <= tolerance)
        })
        .map(|t| modes[t])
}

#[cfg(test)]
mod tests {
    use super::mode_ladder;

    #[test]
    fn ladder_is_ascending_and_ends_at_max() {
        assert_eq!(mode_ladder(1), vec![1]);
        assert_eq!(mode_ladder(20), vec![1, 2, 3, 4, 6, 8, 12, 16, 20]);
        let l = mode_ladder(600);
        assert!(l.windows(2).all(|w| w[0] < w[1]));
        assert_eq!(*l.last().unwrap_or(&0), 600);
    }
}
