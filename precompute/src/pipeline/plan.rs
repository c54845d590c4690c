//! What a build will do, said before the form factors: its expected time per stage (a time
//! model measured on the office builds, scaled by the share of pairs a blocker may cut), its expected peak memory ([`crate::memory`]) and the
//! size of the basis it will write, section by section, against the flash budget
//! (`--flash`). A build that would not fit says so here, with what would make it fit, before
//! the long stages rather than after them.

use std::fmt::Write as _;

use serde::Serialize;

use super::{time_model, BuildOptions, ModeSelection, SkySelection, TOLERANCE_MAX_MODES};
use crate::flash::FlashBudget;
use crate::formfactor::{outputs, Storage};
use crate::scene::Scene;
use crate::sources::daylight::nodes::{room_sun, sun_grid};

/// Expected wall-clock seconds of the stages after meshing.
#[derive(Clone, Debug, Serialize)]
pub struct StageSeconds {
    /// The form factors (assembly of the operator).
    pub form_factors: f64,
    /// The sensors', zones' and grid points' rows.
    pub outputs: f64,
    /// The modes (block Lanczos or the dense eigensolver).
    pub eigenbasis: f64,
    /// The channels' exact responses.
    pub exact_solves: f64,
    /// The report's exact cases.
    pub exact_cases: f64,
    /// Writing the basis.
    pub serialization: f64,
    /// The accuracy check through the runtime.
    pub verification: f64,
}

impl StageSeconds {
    /// Expected seconds of a build of `patches` patches whose operator is `storage` and holds
    /// `operator_bytes` bytes, with `blocking` between its patches ([`time_model`]), `modes`
    /// to find (per band times the bands).
    pub fn of(
        patches: f64,
        storage: Storage,
        operator_bytes: f64,
        blocking: Blocking,
        modes: usize,
    ) -> StageSeconds {
        use time_model::*;
        let scale = patches / REFERENCE_PATCHES;
        let share = blocking.share.clamp(0.0, 1.0);
        let dense = DENSE_FORM_FACTOR_SECONDS * scale.powf(DENSE_FORM_FACTOR_EXPONENT);
        // The pairs a blocker may cut are read whole by either operator (the hierarchical one
        // stores the blocks they fall in whole), at `OCCLUDED_PAIR_COST` times a clear pair's
        // work; only the clear rest compresses.
        let occluded = OCCLUDED_PAIR_COST * share * dense;
        let form_factors = match storage {
            Storage::F64 | Storage::F32 => (1.0 - share) * dense + occluded,
            Storage::Hierarchical => {
                let shadows = (1.0 - share)
                    * DENSE_FORM_FACTOR_SECONDS
                    * HIERARCHICAL_FORM_FACTOR_RATIO
                    * scale.powf(HIERARCHICAL_FORM_FACTOR_EXPONENT)
                    + occluded;
                // Without shadows between well-separated clusters the occluded pairs no longer
                // grow as n²: the open-plan floor's time a patch, unless the scene is quicker.
                if blocking.clusters {
                    shadows.min(CLUSTERS_FORM_FACTOR_SECONDS_PER_PATCH * patches)
                } else {
                    shadows
                }
            }
        };
        let after = StageSeconds::after_form_factors(storage, operator_bytes, modes);
        StageSeconds {
            form_factors,
            outputs: OUTPUT_SECONDS_PER_PATCH * patches,
            eigenbasis: after.eigenbasis,
            exact_solves: after.exact_solves,
            exact_cases: after.exact_cases,
            serialization: SERIALIZATION_SECONDS_PER_PATCH * patches,
            verification: VERIFICATION_SECONDS_PER_PATCH * patches,
        }
    }

    /// Expected seconds of the stages that work through the operator once it is built and
    /// holds `operator_bytes` ([`StageSeconds::eigenbasis`], [`StageSeconds::exact_solves`],
    /// [`StageSeconds::exact_cases`]; the other fields 0): what a build says again when its
    /// operator's size is known. `modes` to find in all (per band times the bands).
    pub fn after_form_factors(storage: Storage, operator_bytes: f64, modes: usize) -> StageSeconds {
        use time_model::*;
        let byte_columns_per_second = match storage {
            Storage::F64 => DENSE_F64_BYTE_COLUMNS_PER_SECOND,
            Storage::F32 => DENSE_F32_BYTE_COLUMNS_PER_SECOND,
            Storage::Hierarchical => HIERARCHICAL_BYTE_COLUMNS_PER_SECOND,
        };
        let (solves, cases) = match storage {
            Storage::F64 | Storage::F32 => (
                SOLVE_OPERATOR_BYTES_PER_SECOND,
                SOLVE_OPERATOR_BYTES_PER_SECOND,
            ),
            Storage::Hierarchical => (
                HIERARCHICAL_SOLVE_BYTES_PER_SECOND,
                HIERARCHICAL_CASES_BYTES_PER_SECOND,
            ),
        };
        StageSeconds {
            form_factors: 0.0,
            outputs: 0.0,
            eigenbasis: EIGEN_COLUMNS_PER_MODE * modes as f64 * operator_bytes
                / byte_columns_per_second,
            exact_solves: operator_bytes / solves,
            exact_cases: operator_bytes / cases,
            serialization: 0.0,
            verification: 0.0,
        }
    }

    /// The whole build's expected seconds after meshing.
    pub fn total(&self) -> f64 {
        self.form_factors
            + self.outputs
            + self.eigenbasis
            + self.exact_solves
            + self.exact_cases
            + self.serialization
            + self.verification
    }
}

/// Serializes a storage by its name.
fn storage_name<S: serde::Serializer>(storage: &Storage, to: S) -> Result<S::Ok, S::Error> {
    to.serialize_str(storage.name())
}

/// What lies between the patches, as the time model counts it.
#[derive(Clone, Copy, Debug)]
pub struct Blocking {
    /// Share of the facing pairs with a blocker between them, sampled
    /// ([`crate::formfactor::occluded_share`]; dimensionless).
    pub share: f64,
    /// Whether well-separated clusters are read without shadows (`--visibility clusters`,
    /// hierarchical operator).
    pub clusters: bool,
}

/// Expected bytes of the basis, by section (docs/format.md). Matrices are counted at the
/// build's precision with their column scales, every other table as f32; the postcard
/// framing (a few bytes per table) and the names are left out.
#[derive(Clone, Debug, Default, Serialize)]
pub struct BasisSize {
    /// The patch tables: area, centroid, surface, channel, reflectance, emission.
    pub patches: f64,
    /// The modes: vectors, eigenvalues, black patches' projections, the outputs' and grid
    /// points' mode readings.
    pub modes: f64,
    /// The channels' exact responses on every patch, output and grid point.
    pub channels: f64,
    /// The sensors' and zones' view rows and geometry.
    pub outputs: f64,
    /// The calculation grids' view rows and layout.
    pub grids: f64,
    /// The daylight nodes' responses (an upper bound: sun nodes that light nothing are left
    /// out of the basis).
    pub daylight: f64,
}

/// The sizes a basis is made of (the counts of docs/format.md).
#[derive(Clone, Copy, Debug)]
struct Counts {
    patches: f64,
    bands: f64,
    modes: f64,
    channels: f64,
    outputs: f64,
    grid_points: f64,
    black: f64,
    daylight_nodes: f64,
    value_bytes: f64,
}

/// Bytes of an f32.
const F32: f64 = 4.0;

impl BasisSize {
    fn of(c: Counts) -> BasisSize {
        let Counts {
            patches: n,
            bands: b,
            modes: p,
            channels: m,
            outputs: o,
            grid_points: g,
            black: k,
            daylight_nodes: d,
            value_bytes: v,
        } = c;
        // A matrix of `rows × cols` values with one f32 scale per column.
        let matrix = |rows: f64, cols: f64| rows * cols * v + cols * F32;
        BasisSize {
            patches: n * (F32 + 3.0 * F32 + 2.0 + 2.0 + 2.0 * b * F32),
            modes: matrix(n, b * p) + b * p * F32 + k * (4.0 + b * p * F32) + (o + g) * b * p * F32,
            channels: matrix(n, m * b) + (o + g) * b * m * F32,
            outputs: matrix(n, o) + o * 7.0 * F32,
            grids: matrix(g, n) + g * 3.0 * F32,
            daylight: if d > 0.0 {
                o * d * F32 + p * d * F32 + matrix(g, d)
            } else {
                0.0
            },
        }
    }

    /// The whole basis.
    pub fn total(&self) -> f64 {
        self.patches + self.modes + self.channels + self.outputs + self.grids + self.daylight
    }

    /// The sections as `(name, bytes)`, in the order the warning names them.
    fn sections(&self) -> [(&'static str, f64); 6] {
        [
            ("modes", self.modes),
            ("channels", self.channels),
            ("daylight", self.daylight),
            ("grids", self.grids),
            ("sensors and zones", self.outputs),
            ("patch tables", self.patches),
        ]
    }
}

/// What a build will do, known once the scene is meshed.
#[derive(Clone, Debug, Serialize)]
pub struct Plan {
    /// Patches.
    pub patches: usize,
    /// The operator's storage (by name in the JSON report, as `operator`).
    #[serde(rename = "operator", serialize_with = "storage_name")]
    pub storage: Storage,
    /// Why that operator (the `--operator` choice and the size rule that applied).
    pub operator_reason: String,
    /// Expected peak memory of the build, bytes ([`crate::memory`]).
    pub memory_bytes: f64,
    /// Expected seconds per stage.
    pub seconds: StageSeconds,
    /// Modes the basis will keep per band (the most the search may keep under `--tolerance`).
    pub modes: usize,
    /// Expected basis size by section, bytes.
    pub basis: BasisSize,
    /// The flash budget the basis is measured against.
    pub flash_bytes: u64,
    /// Bytes one more mode per band adds to the basis.
    pub bytes_per_mode: f64,
    /// Share of the facing pairs with a blocker between them, sampled
    /// ([`crate::formfactor::occluded_share`]; dimensionless).
    pub occluded_share: f64,
    /// Expected seconds of the same build with `--visibility clusters`, where the operator is
    /// hierarchical and the build reads every pair's shadows; `None` otherwise.
    pub seconds_with_clusters: Option<f64>,
}

/// A build expected to take longer than this, seconds, and more than
/// [`CLUSTERS_HINT_RATIO`] times as long as with `--visibility clusters`, is told so before
/// its form factors.
const CLUSTERS_HINT_ABOVE: f64 = 600.0;
/// See [`CLUSTERS_HINT_ABOVE`] (dimensionless).
const CLUSTERS_HINT_RATIO: f64 = 2.0;

/// The line that points a long build with exact shadows to `--visibility clusters`, where
/// it is expected to take `total` seconds and `with_clusters` seconds with it.
fn clusters_note(total: f64, with_clusters: Option<f64>) -> Option<String> {
    let clusters = with_clusters?;
    (total > CLUSTERS_HINT_ABOVE && total > CLUSTERS_HINT_RATIO * clusters).then(|| {
        format!(
            "note: the pairs a blocker may cut are read with their shadows, whose cost grows as the square of the patches; with --visibility clusters, which reads well-separated ones without shadows (readings within about 1e-2; docs/performance.md, \"Visibility between clusters\"), expected about {}",
            super::stages::seconds(clusters)
        )
    })
}

impl Plan {
    /// The plan of building `scene` (meshed) with `opts`, its operator `storage` holding about
    /// `operator_bytes`, the build expected to peak at `memory_bytes`, with `blocking` between
    /// its patches.
    pub(crate) fn of(
        scene: &Scene,
        opts: &BuildOptions,
        storage: Storage,
        operator_reason: String,
        operator_bytes: f64,
        memory_bytes: f64,
        blocking: Blocking,
    ) -> Plan {
        let n = scene.patches.len();
        let modes = match opts.modes {
            ModeSelection::Count(p) => p.min(n),
            ModeSelection::Tolerance(_) => n.min(TOLERANCE_MAX_MODES),
        };
        let counts = |modes: usize| Counts {
            patches: n as f64,
            bands: scene.bands.count() as f64,
            modes: modes as f64,
            channels: scene.channels.len() as f64,
            outputs: outputs::grid_offset(scene) as f64,
            grid_points: if opts.grids {
                outputs::grid_points(scene).count() as f64
            } else {
                0.0
            },
            black: scene
                .reflectance
                .iter()
                .filter(|r| r.contains(&0.0))
                .count() as f64,
            daylight_nodes: daylight_nodes(scene, opts.sun_step, opts.sky) as f64,
            value_bytes: opts.precision.bytes() as f64,
        };
        let basis = BasisSize::of(counts(modes));
        let bytes_per_mode = BasisSize::of(counts(modes + 1)).total() - basis.total();
        let seconds = |blocking| {
            StageSeconds::of(
                n as f64,
                storage,
                operator_bytes,
                blocking,
                modes * scene.bands.count(),
            )
        };
        let seconds_with_clusters =
            (storage == Storage::Hierarchical && !blocking.clusters).then(|| {
                seconds(Blocking {
                    clusters: true,
                    ..blocking
                })
                .total()
            });
        Plan {
            patches: n,
            storage,
            operator_reason,
            memory_bytes,
            seconds: seconds(blocking),
            seconds_with_clusters,
            modes,
            basis,
            flash_bytes: opts.flash.bytes,
            bytes_per_mode,
            occluded_share: blocking.share,
        }
    }

    /// The expected seconds per stage again once the operator is built and holds
    /// `operator_bytes`, `modes` to find (per band times the bands): the stages that work
    /// through it from its actual size ([`StageSeconds::after_form_factors`]), the others
    /// as planned.
    pub fn seconds_once_built(&self, operator_bytes: usize, modes: usize) -> StageSeconds {
        StageSeconds {
            form_factors: self.seconds.form_factors,
            outputs: self.seconds.outputs,
            serialization: self.seconds.serialization,
            verification: self.seconds.verification,
            ..StageSeconds::after_form_factors(self.storage, operator_bytes as f64, modes)
        }
    }

    /// Whether the expected basis fits the flash budget.
    pub fn fits(&self) -> bool {
        self.basis.total() <= self.flash_bytes as f64
    }

    /// The lines a build prints before its form factors: time, memory, operator, basis size
    /// and, when over budget, the warning and what would bring the basis under it.
    pub fn lines(&self) -> Vec<String> {
        let mut lines = vec![
            format!(
                "{} patches, operator {} ({}); expected about {} and {:.2} GB at the peak (time model of the office builds on 2 cores, with {:.0} % of the pairs a blocker may cut, docs/performance.md)",
                self.patches,
                self.storage.name(),
                self.operator_reason,
                super::stages::seconds(self.seconds.total()),
                self.memory_bytes / 1e9,
                100.0 * self.occluded_share
            ),
            format!(
                "basis about {} ({}), flash budget {}",
                binary_bytes(self.basis.total()),
                self.section_list(),
                FlashBudget {
                    bytes: self.flash_bytes
                }
            ),
        ];
        lines.extend(clusters_note(
            self.seconds.total(),
            self.seconds_with_clusters,
        ));
        if !self.fits() {
            lines.push(format!(
                "warning: the basis would take about {}, more than the flash budget of {} (--flash); {}",
                binary_bytes(self.basis.total()),
                FlashBudget {
                    bytes: self.flash_bytes
                },
                self.remedies()
            ));
        }
        lines
    }

    /// The non-empty sections with their sizes, largest first.
    fn section_list(&self) -> String {
        let mut sections: Vec<_> = self
            .basis
            .sections()
            .into_iter()
            .filter(|(_, b)| *b > 0.0)
            .collect();
        sections.sort_by(|a, b| b.1.total_cmp(&a.1));
        let mut s = String::new();
        for (k, (name, bytes)) in sections.iter().enumerate() {
            let _ = write!(
                s,
                "{}{name} {}",
                if k == 0 { "" } else { ", " },
                binary_bytes(*bytes)
            );
        }
        s
    }

    /// What would bring an over-budget basis under its budget, each measured on the plan.
    fn remedies(&self) -> String {
        let budget = self.flash_bytes as f64;
        let total = self.basis.total();
        let mut fixes = Vec::new();
        // Fewer modes: each mode takes `bytes_per_mode`.
        let without_modes = total - self.modes as f64 * self.bytes_per_mode;
        if self.bytes_per_mode > 0.0 && self.modes > 0 && without_modes <= budget {
            let fit = ((budget - without_modes) / self.bytes_per_mode).floor() as usize;
            if fit >= 1 {
                fixes.push(format!(
                    "--modes {fit} (each mode takes {})",
                    binary_bytes(self.bytes_per_mode)
                ));
            }
        }
        if self.basis.grids > 0.0 && total - self.basis.grids <= budget {
            fixes.push(format!(
                "--no-grids (the grids take {})",
                binary_bytes(self.basis.grids)
            ));
        }
        // The matrices (modes, channels, view rows) in two bytes instead of four.
        let halved = total - 0.5 * (self.basis.modes + self.basis.channels + self.basis.grids);
        if halved <= budget {
            fixes.push("--precision f16 or i16 (two bytes a value)".to_string());
        }
        if self.basis.daylight > 0.0 && total - self.basis.daylight <= budget {
            fixes.push(format!(
                "a coarser --sun-step (daylight takes at most {})",
                binary_bytes(self.basis.daylight)
            ));
        }
        let coarser = "a coarser `max_edge` (every section grows with the patches)";
        if fixes.is_empty() {
            format!(
                "no single flag brings it under: {coarser}, or a larger --flash if the part has it"
            )
        } else {
            format!("it would fit with {}; or {coarser}", fixes.join(", or "))
        }
    }
}

/// Nodes of the daylight the basis will carry: the sky's patches (of `--mf`; the coarsest
/// candidate for `--sky-tolerance`, whose choice is made later), the exterior, and the sun
/// grid's nodes above the horizon (those that light nothing are dropped later, so this
/// part is an upper bound); 0 without a site and windows.
fn daylight_nodes(scene: &Scene, sun_step: [f64; 2], sky: SkySelection) -> usize {
    let Some(site) = scene.site.as_ref() else {
        return 0;
    };
    if scene.windows.is_empty() {
        return 0;
    }
    let grid = sun_grid(site, sun_step);
    let suns = (0..grid.len())
        .filter(|&node| {
            grid.direction(node)
                .and_then(|d| room_sun(site, d))
                .is_some()
        })
        .count();
    let subdivision = match sky {
        SkySelection::Subdivision(n) => n,
        SkySelection::Tolerance(_) => crate::accuracy::sky::CANDIDATES[0],
    };
    let patches =
        eigenrad_runtime::sky::patches::SkyPatches::reinhart(subdivision).map_or(0, |p| p.count());
    patches + 1 + suns
}

/// Bytes in the binary unit a part's flash is sold in, as the budget prints: `96 KiB`,
/// `7.3 MiB`.
fn binary_bytes(bytes: f64) -> String {
    const KIB: f64 = 1024.0;
    if bytes >= KIB * KIB {
        format!("{:.1} MiB", bytes / (KIB * KIB))
    } else {
        format!("{:.0} KiB", bytes / KIB)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The open-plan floor of docs/performance.md ("Scenes at scale"): 102 934 patches, 49 %
    /// of the facing pairs a blocker may cut, a hierarchical operator of 1.4 % of the dense
    /// f64 matrix. Its build with exact shadows is expected to take hours (it is not run) and
    /// with `--visibility clusters` minutes (measured 8.3): the note is given. The office's
    /// 9905 patches with its two desks (5 % of the pairs) get none.
    #[test]
    fn long_builds_with_shadows_are_pointed_to_clusters() {
        let expected = |patches: f64, share: f64, clusters: bool| {
            let bytes = 0.014 * 8.0 * patches * patches;
            StageSeconds::of(
                patches,
                Storage::Hierarchical,
                bytes,
                Blocking { share, clusters },
                32,
            )
            .total()
        };
        let (exact, clusters) = (
            expected(102_934.0, 0.49, false),
            expected(102_934.0, 0.49, true),
        );
        println!("open-plan-100k: {exact:.0} s exact, {clusters:.0} s with clusters");
        let note = clusters_note(exact, Some(clusters)).expect("a note");
        assert!(note.contains("--visibility clusters"), "{note}");
        assert!(clusters < 900.0, "{clusters}");
        let office = expected(9905.0, 0.05, false);
        let office_clusters = expected(9905.0, 0.05, true);
        assert_eq!(clusters_note(office, Some(office_clusters)), None);
        assert_eq!(clusters_note(exact, None), None);
    }
}
