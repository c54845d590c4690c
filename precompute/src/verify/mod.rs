//! `eigenrad verify`: how the error of a truncated basis against the exact dense solve falls
//! with the mode count p, for both formulations, with the exact per-channel superposition as
//! the baseline (docs/math.md, "Be honest about the baseline").
//!
//! Cases: every channel alone at level 1; random channel mixes (every channel at a random
//! level in [0, 1]); random emitter patterns (see [`accuracy::standard_cases`]). Metrics, each
//! the worst spectral band:
//!
//! - patches: area-weighted RMS of the per-patch exitance error over the RMS exitance
//!   ([`metric::patch_error`]);
//! - zones, sensors: `|E − E_exact| / |E_exact|` per zone or sensor (irradiance, W/m² or lux;
//!   [`metric::reading_errors`]).
//!
//! The curves use the host model in f64 ([`Model::truncated`] arithmetic), so they show the
//! truncation alone; `eigenrad build` reports the same cases through the runtime's f32.

mod markdown;
mod plot;

use std::path::Path;

use eigenrad_runtime::Precision;
use serde::Serialize;

use crate::accuracy::rng::Rng;
use crate::accuracy::{self, metric, Case, ExactCases};
use crate::basis;
use crate::error::Result;
use crate::formfactor::FormFactorOptions;
use crate::pipeline::{self, Prepared};
use crate::radiosity::eigen::{Formulation, Solver};
use crate::radiosity::model::Model;

pub use markdown::markdown;
pub use plot::{svgs, PLOT_FLOOR};

/// Options of `eigenrad verify`.
#[derive(Clone, Debug)]
pub struct VerifyOptions {
    /// Random channel mixes (skipped when the scene has no channel).
    pub random_mixes: usize,
    /// Random emitter patterns.
    pub random_patterns: usize,
    /// Form-factor settings.
    pub form_factors: FormFactorOptions,
    /// Show the stages after the form factors (eigenmodes, curves, basis sizes per
    /// formulation) as an indicatif progress bar on stderr.
    pub progress: bool,
}

impl Default for VerifyOptions {
    fn default() -> Self {
        VerifyOptions {
            random_mixes: 4,
            random_patterns: 4,
            form_factors: FormFactorOptions::default(),
            progress: false,
        }
    }
}

/// What a case is made of.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum CaseKind {
    /// One channel at level 1, the others off.
    Channel,
    /// Every channel at a random level.
    ChannelMix,
    /// Random exitance on a random fifth of the patches; no channel.
    EmitterPattern,
}

impl CaseKind {
    /// All kinds, in table order.
    pub const ALL: [CaseKind; 3] = [
        CaseKind::Channel,
        CaseKind::ChannelMix,
        CaseKind::EmitterPattern,
    ];

    /// Name in tables and legends.
    pub fn label(self) -> &'static str {
        match self {
            CaseKind::Channel => "channel alone",
            CaseKind::ChannelMix => "channel mix",
            CaseKind::EmitterPattern => "emitter pattern",
        }
    }
}

/// Which reading an error is about.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Metric {
    /// Per-patch exitance (area-weighted RMS).
    Patches,
    /// Zone averages.
    Zones,
    /// Sensors.
    Sensors,
}

impl Metric {
    /// All metrics, in table order.
    pub const ALL: [Metric; 3] = [Metric::Patches, Metric::Zones, Metric::Sensors];

    /// Name in tables and file names.
    pub fn label(self) -> &'static str {
        match self {
            Metric::Patches => "patches",
            Metric::Zones => "zones",
            Metric::Sensors => "sensors",
        }
    }
}

/// Relative errors of one case, per tested p (index `t` of [`VerifyReport::modes`]).
#[derive(Clone, Debug, Serialize)]
pub struct CaseCurve {
    /// Case name (`channel lum1`, `channel mix 2`, `random pattern 3`).
    pub case: String,
    /// Its kind.
    pub kind: CaseKind,
    /// Patch exitance error at each p.
    pub patches: Vec<f64>,
    /// `zones[z][t]`: error of zone z at the t-th p.
    pub zones: Vec<Vec<f64>>,
    /// `sensors[s][t]`: error of sensor s at the t-th p.
    pub sensors: Vec<Vec<f64>>,
}

/// Curves of one formulation.
#[derive(Clone, Debug, Serialize)]
pub struct FormulationReport {
    /// `split` or `seed`.
    pub formulation: &'static str,
    /// Size of the f32 basis at each tested p, bytes.
    pub basis_bytes: Vec<usize>,
    /// One curve per case.
    pub cases: Vec<CaseCurve>,
}

/// The exact per-channel superposition: `(I − R F)⁻¹ e_c` stored for each channel.
#[derive(Clone, Debug, Serialize)]
pub struct Baseline {
    /// Worst error of the superposition over the channel-only cases (alone and mixes) per
    /// metric: rounding only, by construction. `None` without channels.
    pub channel_error: Option<[f64; 3]>,
    /// Bytes of the responses in f32: per-patch exitance and every sensor and zone, for each
    /// channel and band: `4 (n + outputs) m bands`.
    pub bytes: usize,
    /// Bytes when only sensors and zones are needed: `4 · outputs · m · bands`.
    pub output_bytes: usize,
}

/// The whole report.
#[derive(Clone, Debug, Serialize)]
pub struct VerifyReport {
    /// Scene file as given.
    pub path: String,
    /// Scene name.
    pub scene: String,
    /// Number of patches.
    pub patches: usize,
    /// Number of bands.
    pub bands: usize,
    /// Unit of exitance and irradiance.
    pub unit: &'static str,
    /// Channel names.
    pub channels: Vec<String>,
    /// Sensor names.
    pub sensors: Vec<String>,
    /// Zone names.
    pub zones: Vec<String>,
    /// Tested mode counts, ascending ([`accuracy::mode_ladder`] up to every mode).
    pub modes: Vec<usize>,
    /// `split`, then `seed`.
    pub formulations: Vec<FormulationReport>,
    /// The per-channel baseline.
    pub baseline: Baseline,
}

fn cases(prepared: &Prepared, opts: &VerifyOptions) -> Vec<(CaseKind, Case)> {
    let scene = &prepared.scene;
    let m = scene.channels.len();
    let n = scene.patches.len();
    let mut out: Vec<(CaseKind, Case)> = accuracy::channel_cases(scene)
        .into_iter()
        .map(|c| (CaseKind::Channel, c))
        .collect();
    let patterns: Vec<(CaseKind, Case)> = accuracy::pattern_cases(scene, opts.random_patterns)
        .into_iter()
        .map(|c| (CaseKind::EmitterPattern, c))
        .collect();
    if m > 0 {
        let mut rng = Rng(0xD1B5_4A32_D192_ED03);
        for k in 0..opts.random_mixes {
            out.push((
                CaseKind::ChannelMix,
                Case {
                    name: format!("channel mix {}", k + 1),
                    levels: (0..m).map(|_| rng.next_f64()).collect(),
                    extra: vec![vec![0.0; n]; scene.bands.count()],
                },
            ));
        }
    }
    out.extend(patterns);
    out
}

/// Errors of every metric of `case` at each p of `modes` for `model`.
fn case_curve(
    model: &Model,
    kind: CaseKind,
    case: &Case,
    exact: (&ExactCases, usize),
    modes: &[usize],
    sensors: usize,
    outputs: usize,
) -> CaseCurve {
    let mut curve = CaseCurve {
        case: case.name.clone(),
        kind,
        patches: vec![0.0; modes.len()],
        zones: vec![vec![0.0; modes.len()]; outputs - sensors],
        sensors: vec![vec![0.0; modes.len()]; sensors],
    };
    accuracy::sweep(model, case, exact, modes, |pt| {
        let t = pt.step;
        let e = metric::patch_error(model.area(), pt.exitance, pt.exact);
        curve.patches[t] = curve.patches[t].max(e);
        // Sensors and zones; grid points (past them) are not among the metrics.
        let readings = metric::reading_errors(&pt.outputs[..outputs], &pt.exact_outputs[..outputs]);
        for (o, r) in readings.into_iter().enumerate() {
            let slot = if o < sensors {
                &mut curve.sensors[o][t]
            } else {
                &mut curve.zones[o - sensors][t]
            };
            *slot = slot.max(r);
        }
    });
    curve
}

/// Runs the whole report for the scene at `path`.
pub fn verify(path: &Path, opts: &VerifyOptions) -> Result<VerifyReport> {
    let prepared = pipeline::prepare(path, &opts.form_factors)?;
    let scene = &prepared.scene;
    let n = scene.patches.len();
    let bands = scene.bands.count();
    let m = scene.channels.len();
    let sensors = scene.sensors.len();
    // Sensors and zones: the outputs the tables report (grid points come after them).
    let outputs = crate::formfactor::outputs::grid_offset(scene);
    let cases = cases(&prepared, opts);
    // Solved once: both formulations and the baseline are measured against the same solutions.
    let plain: Vec<Case> = cases.iter().map(|(_, c)| c.clone()).collect();
    let exact = ExactCases::solve(&prepared.system, &plain)?;

    let mut formulations = Vec::new();
    let mut modes = Vec::new();
    let mut baseline_error: Option<[f64; 3]> = None;
    let formulation_list = [Formulation::Split, Formulation::Seed];
    let bar = stage_bar(opts.progress, 3 * formulation_list.len());
    for formulation in formulation_list {
        bar.set_message(format!("verify, {}: eigenmodes", formulation.name()));
        let model = Model::new(&prepared.system, formulation, n, Solver::Dense)?;
        if modes.is_empty() {
            modes = accuracy::mode_ladder(accuracy::modes_held(&model).max(1));
            if m > 0 {
                baseline_error = Some(superposition_error(
                    &model, &cases, &exact, sensors, outputs,
                ));
            }
        }
        bar.inc(1);
        bar.set_message(format!("verify, {}: error curves", formulation.name()));
        let curves = cases
            .iter()
            .enumerate()
            .map(|(k, (kind, case))| {
                case_curve(&model, *kind, case, (&exact, k), &modes, sensors, outputs)
            })
            .collect();
        bar.inc(1);
        bar.set_message(format!("verify, {}: basis sizes", formulation.name()));
        let mut basis_bytes = Vec::with_capacity(modes.len());
        for &p in &modes {
            let bytes = basis::basis_tables(scene, &model, p, Precision::F32).to_bytes()?;
            basis_bytes.push(bytes.len());
        }
        bar.inc(1);
        formulations.push(FormulationReport {
            formulation: formulation.name(),
            basis_bytes,
            cases: curves,
        });
    }
    bar.finish_and_clear();
    Ok(VerifyReport {
        path: path.display().to_string(),
        scene: scene.name.clone(),
        patches: n,
        bands,
        unit: scene.bands.unit(),
        channels: scene.channels.iter().map(|c| c.name.clone()).collect(),
        sensors: scene.sensors.iter().map(|s| s.name.clone()).collect(),
        zones: scene.zones.iter().map(|z| z.name.clone()).collect(),
        modes,
        formulations,
        baseline: Baseline {
            channel_error: baseline_error,
            bytes: 4 * (n + outputs) * m * bands,
            output_bytes: 4 * outputs * m * bands,
        },
    })
}

/// A bar of `steps` stages on stderr, or a hidden one.
fn stage_bar(show: bool, steps: usize) -> indicatif::ProgressBar {
    use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
    if !show {
        return ProgressBar::hidden();
    }
    let bar = ProgressBar::with_draw_target(Some(steps as u64), ProgressDrawTarget::stderr());
    if let Ok(style) = ProgressStyle::with_template("{msg} {bar:40} {pos}/{len} stages, {elapsed}")
    {
        bar.set_style(style);
    }
    bar
}

/// The per-channel superposition `Σ_c l_c (I − R F)⁻¹ e_c` against the direct solve of each
/// channel-only case: worst error per metric.
fn superposition_error(
    model: &Model,
    cases: &[(CaseKind, Case)],
    exact: &ExactCases,
    sensors: usize,
    outputs: usize,
) -> [f64; 3] {
    let m = model.channel_count();
    let mut worst = [0.0f64; 3];
    for b in 0..model.bands.len() {
        // The model's exact per-channel responses, as the basis stores them.
        let responses: Vec<&[f64]> = (0..m).map(|c| model.channel_response(c, b)).collect();
        for (k, (kind, case)) in cases.iter().enumerate() {
            if *kind == CaseKind::EmitterPattern {
                continue;
            }
            let exact = exact.exitance(k, b);
            let mut sum = vec![0.0; exact.len()];
            for (c, l) in case.levels.iter().enumerate() {
                for (s, r) in sum.iter_mut().zip(responses[c]) {
                    *s += l * r;
                }
            }
            worst[0] = worst[0].max(metric::patch_error(model.area(), &sum, exact));
            let (got, want) = (
                model.readings(b, &sum, &case.levels),
                model.readings(b, exact, &case.levels),
            );
            let (got, want) = (&got[..outputs], &want[..outputs]);
            for (o, r) in metric::reading_errors(got, want).into_iter().enumerate() {
                let slot = if o < sensors { 2 } else { 1 };
                worst[slot] = worst[slot].max(r);
            }
        }
    }
    worst
}

impl FormulationReport {
    /// Worst error of `metric` over the cases of `kind` at the t-th p (`None`: no such case,
    /// or no zone/sensor).
    pub fn worst(&self, kind: Option<CaseKind>, metric: Metric, t: usize) -> Option<f64> {
        let mut out: Option<f64> = None;
        for c in self
            .cases
            .iter()
            .filter(|c| kind.is_none_or(|k| c.kind == k))
        {
            let values: Vec<f64> = match metric {
                Metric::Patches => vec![c.patches[t]],
                Metric::Zones => c.zones.iter().map(|z| z[t]).collect(),
                Metric::Sensors => c.sensors.iter().map(|s| s[t]).collect(),
            };
            for v in values {
                out = Some(out.map_or(v, |o| o.max(v)));
            }
        }
        out
    }

    /// Worst error of zone (`zone = true`) or sensor `index` over every case at the t-th p.
    pub fn worst_output(&self, zone: bool, index: usize, t: usize) -> f64 {
        self.cases
            .iter()
            .map(|c| {
                if zone {
                    c.zones[index][t]
                } else {
                    c.sensors[index][t]
                }
            })
            .fold(0.0, f64::max)
    }
}

impl VerifyReport {
    /// The smallest tested p at which `f(t)` is at most `tolerance`, and stays so for every
    /// larger tested p.
    pub fn smallest_p(&self, tolerance: f64, f: impl Fn(usize) -> f64) -> Option<usize> {
        let ok: Vec<bool> = (0..self.modes.len()).map(|t| f(t) <= tolerance).collect();
        let last_bad = ok.iter().rposition(|&x| !x);
        match last_bad {
            None => self.modes.first().copied(),
            Some(t) => self.modes.get(t + 1).copied(),
        }
    }

    /// The smallest p at which zone `name` is within `tolerance` in every case, per
    /// formulation (`split`, `seed`).
    pub fn zone_p(&self, name: &str, tolerance: f64) -> Vec<(&'static str, Option<usize>)> {
        let Some(z) = self.zones.iter().position(|x| x == name) else {
            return Vec::new();
        };
        self.formulations
            .iter()
            .map(|f| {
                (
                    f.formulation,
                    self.smallest_p(tolerance, |t| f.worst_output(true, z, t)),
                )
            })
            .collect()
    }
}
