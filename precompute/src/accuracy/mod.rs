//! How close a truncated expansion is to the exact dense solve, as a function of the mode
//! count p: the figures behind `--tolerance`, the build report and `eigenrad verify`.

use serde::Serialize;

pub mod metric;
pub mod rng;
pub mod runtime_eval;

use crate::radiosity::exact::ExactSolver;
use crate::radiosity::model::Model;
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
    /// [`metric::output_error`] at each p, worst band.
    pub output_error: Vec<f64>,
}

/// Every channel alone at level 1, then `random` emitter patterns: a random fifth of the
/// patches each emitting a random exitance up to the largest exitance a patch of the scene
/// emits at level 1, in any band (the brightest channel's when its surfaces emit alike; 1
/// when nothing emits), same in every band.
pub fn standard_cases(scene: &Scene, random: usize) -> Vec<Case> {
    let n = scene.patches.len();
    let bands = scene.bands.count();
    let m = scene.channels.len();
    let mut cases: Vec<Case> = (0..m)
        .map(|c| {
            let mut levels = vec![0.0; m];
            levels[c] = 1.0;
            Case {
                name: format!("channel {}", scene.channels[c].name),
                levels,
                extra: vec![vec![0.0; n]; bands],
            }
        })
        .collect();
    let peak = scene
        .emission
        .iter()
        .flatten()
        .copied()
        .fold(0.0f64, f64::max);
    let peak = if peak > 0.0 { peak } else { 1.0 };
    let mut rng = Rng(0x9E37_79B9_7F4A_7C15);
    for k in 0..random {
        let pattern: Vec<f64> = (0..n)
            .map(|_| {
                if rng.next_f64() < 0.2 {
                    peak * rng.next_f64()
                } else {
                    0.0
                }
            })
            .collect();
        cases.push(Case {
            name: format!("random pattern {}", k + 1),
            levels: vec![0.0; m],
            extra: vec![pattern; bands],
        });
    }
    cases
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

/// Evaluates `case` with the first p modes for every p of `modes` (ascending), adding one
/// mode's contribution at a time, and shows each point to `visit` together with the exact
/// solve. Shared by `--tolerance`, the build report and `eigenrad verify`.
pub fn sweep(
    model: &Model,
    solvers: &[ExactSolver],
    case: &Case,
    modes: &[usize],
    mut visit: impl FnMut(SweepPoint<'_>),
) {
    for (b, solver) in solvers.iter().enumerate() {
        let exact = model.exact(solver, b, &case.levels, &case.extra[b]);
        let exact_outputs = model.readings(b, &exact, &case.levels);
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
                exact: &exact,
                outputs: &outputs,
                exact_outputs: &exact_outputs,
            });
        }
    }
}

/// Error curves of `case` for every p in `modes` (ascending), against the exact solve.
pub fn curve(model: &Model, solvers: &[ExactSolver], case: &Case, modes: &[usize]) -> Curve {
    let mut patch_error = vec![0.0f64; modes.len()];
    let mut output_error = vec![0.0f64; modes.len()];
    sweep(model, solvers, case, modes, |pt| {
        let t = pt.step;
        let patches = metric::patch_error(&model.area, pt.exitance, pt.exact);
        patch_error[t] = patch_error[t].max(patches);
        let outputs = metric::output_error(pt.outputs, pt.exact_outputs);
        output_error[t] = output_error[t].max(outputs);
    });
    Curve {
        case: case.name.clone(),
        modes: modes.to_vec(),
        patch_error,
        output_error,
    }
}

/// The smallest p whose patch error stays at or under `tolerance` for every curve, if any.
pub fn smallest_p(curves: &[Curve], tolerance: f64) -> Option<usize> {
    let modes = &curves.first()?.modes;
    (0..modes.len())
        .find(|&t| curves.iter().all(|c| c.patch_error[t] <= tolerance))
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
