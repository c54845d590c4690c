//! `eigenrad build`: a scene's basis, written atomically, and the build's report.

use std::io::IsTerminal;
use std::path::PathBuf;

use clap::{Args, ValueEnum};

use super::groups::{help, CacheArgs, JsonFlag};
use crate::cli::{self, atomic, guard};
use crate::flash::FlashBudget;
use crate::pipeline::{self, BuildOptions, ModeSelection, Narration, SkySelection};
use crate::radiosity::eigen::{Formulation, Solver};
use crate::scene;
use crate::sources::daylight::nodes::DEFAULT_SUN_STEP;
use crate::sources::daylight::reflection::DEFAULT_SKY_RANK_TOLERANCE;
use eigenrad_runtime::Precision;

/// The arguments of `eigenrad build`.
#[derive(Args)]
#[command(mut_arg("json", help("Print the report as one JSON document on stdout")))]
pub(super) struct BuildArgs {
    /// Scene file (TOML).
    scene: PathBuf,
    /// Output basis file; written atomically (a failed build leaves it untouched).
    #[arg(short, long)]
    output: PathBuf,
    /// Number of modes per band [default: 32, when --tolerance is not given].
    #[arg(long, conflicts_with = "tolerance")]
    modes: Option<usize>,
    /// Instead of --modes: the smallest mode count at which every case of the report
    /// (channels, level vectors, exitance set patch by patch) stays within this relative
    /// error of the exact solve: the area-weighted RMS of patch exitance, and every
    /// sensor and zone against its own exact value.
    #[arg(long, value_parser = positive_fraction)]
    tolerance: Option<f64>,
    /// Expansion to store.
    #[arg(long, value_enum, default_value = "split")]
    formulation: FormulationArg,
    /// Storage precision of mode vectors, first bounces and view rows.
    #[arg(long, value_enum, default_value = "f32")]
    precision: PrecisionArg,
    /// Eigensolver.
    #[arg(long, value_enum, default_value = "auto")]
    solver: SolverArg,
    /// Leave the zones' calculation grids out of the basis (smaller; each grid point
    /// costs about 4 bytes per patch in f32).
    #[arg(long)]
    no_grids: bool,
    /// Degrees between the sun grid's declinations and between its hour angles, for a
    /// scene with daylight: finer reads the sun more closely between nodes and takes more
    /// flash (the build reports both). Default 5.86,7.5.
    #[arg(long, value_name = "DECLINATION,HOUR", value_parser = sun_step)]
    sun_step: Option<[f64; 2]>,
    /// Sky patches a basis with daylight stores: Reinhart subdivision MF:n, 1 (Tregenza's
    /// 145 patches) to 8 (144 n² + 1 patches). Default 1.
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u8).range(1..=8), conflicts_with = "sky_tolerance")]
    mf: Option<u8>,
    /// Instead of --mf: the coarsest of MF:1, 2 and 4 whose direct daylight at the outputs
    /// under the reference skies is within this relative error of the next finer
    /// subdivision (docs/math.md, "Choosing the sky's patches"); the build reports it.
    #[arg(long, value_parser = positive_fraction)]
    sky_tolerance: Option<f64>,
    /// Relative error to which the sky's first reflection under daylight is stored (its
    /// rank is the smallest within it, area-weighted RMS over patches and sky nodes): lower
    /// draws the patches under daylight more closely and takes more flash (the build
    /// reports both). Default 0.1.
    #[arg(long, value_name = "FRACTION", value_parser = positive_fraction)]
    sky_rank_tolerance: Option<f64>,
    /// Store the patches the sun can light (their polygons) and every reading's response to
    /// each, so that the controller clips the sun patch at the sun's own direction and reads
    /// the sun between the grid's nodes within about 10⁻³ of each reading's largest sun
    /// response, where interpolating it misses by up to half (docs/accuracy.md, "The sun's
    /// first reflection on the controller"). It costs flash (131 KB on the example daylight
    /// office, 95 KB of it the responses, most of them its grid points') and about 5 M
    /// Cortex-M4F instructions a sun update.
    #[arg(long)]
    sun_first: bool,
    /// Flash the basis should fit, in bytes or with KiB, MiB, kB or MB (the build says
    /// before its form factors whether the basis will fit, and what would make it fit).
    #[arg(long, value_name = "SIZE", default_value_t = FlashBudget::DEFAULT)]
    flash: FlashBudget,
    #[command(flatten)]
    json: JsonFlag,
    #[command(flatten)]
    cache: CacheArgs,
}

#[derive(Clone, Copy, ValueEnum)]
enum FormulationArg {
    /// Exact emission and first bounce, interreflections from the modes (default).
    Split,
    /// The seed paper's expansion (corrected), for comparison.
    Seed,
}

#[derive(Clone, Copy, ValueEnum)]
enum PrecisionArg {
    /// 4 bytes per value.
    F32,
    /// IEEE half precision with a per-column scale, 2 bytes per value.
    F16,
    /// 16-bit integers with a per-column scale, 2 bytes per value.
    I16,
}

#[derive(Clone, Copy, ValueEnum)]
enum SolverArg {
    /// Dense for small scenes, partial (Krylov–Schur) for large ones.
    Auto,
    /// Full self-adjoint eigendecomposition.
    Dense,
    /// Partial eigensolver for the strongest modes only.
    Partial,
}

impl BuildArgs {
    /// The build the flags ask for.
    fn options(&self) -> BuildOptions {
        BuildOptions {
            grids: !self.no_grids,
            sun_step: self.sun_step.unwrap_or(DEFAULT_SUN_STEP),
            sky: match (self.mf, self.sky_tolerance) {
                (_, Some(t)) => SkySelection::Tolerance(t),
                (n, None) => SkySelection::Subdivision(n.unwrap_or(1)),
            },
            sky_rank_tolerance: self
                .sky_rank_tolerance
                .unwrap_or(DEFAULT_SKY_RANK_TOLERANCE),
            sun_first: self.sun_first,
            modes: match (self.modes, self.tolerance) {
                (Some(p), _) => ModeSelection::Count(p),
                (None, Some(t)) => ModeSelection::Tolerance(t),
                (None, None) => ModeSelection::Count(pipeline::DEFAULT_MODES),
            },
            formulation: match self.formulation {
                FormulationArg::Split => Formulation::Split,
                FormulationArg::Seed => Formulation::Seed,
            },
            precision: match self.precision {
                PrecisionArg::F32 => Precision::F32,
                PrecisionArg::F16 => Precision::F16,
                PrecisionArg::I16 => Precision::I16,
            },
            solver: match self.solver {
                SolverArg::Auto => Solver::Auto,
                SolverArg::Dense => Solver::Dense,
                SolverArg::Partial => Solver::Partial,
            },
            form_factors: self.cache.form_factors(),
            flash: self.flash,
            // Progress bars where someone watches, a line per stage in logs and pipes.
            narration: if std::io::stderr().is_terminal() {
                Narration::Terminal
            } else {
                Narration::Log
            },
            ..BuildOptions::default()
        }
    }

    /// Builds the basis, writes it and prints the report.
    pub(super) fn run(self) -> anyhow::Result<()> {
        let opts = self.options();
        // Before any work: the basis must be writable and must not replace the scene or a
        // file it reads.
        guard::check_file_output(&self.output)?;
        guard::check_outputs(
            std::slice::from_ref(&self.output),
            &scene::inputs(&self.scene)?.files,
        )?;
        let (bytes, report) = pipeline::build(&self.scene, &opts)?;
        atomic::write(&self.output, &bytes)?;
        self.json.print(&report, |report| {
            cli::format_build_report(report, &self.output)
        })
    }
}

/// `--sun-step`: two steps in degrees, of declination (0.1° to 46.88°, the whole span) and of
/// hour angle (0.25° to 180°).
fn sun_step(text: &str) -> Result<[f64; 2], String> {
    let parts: Vec<&str> = text.split(',').map(str::trim).collect();
    let [declination, hour] = parts.as_slice() else {
        return Err(format!(
            "`{text}` is not two steps in degrees, DECLINATION,HOUR (e.g. 5.86,7.5)"
        ));
    };
    let number = |t: &str, what: &str, range: std::ops::RangeInclusive<f64>| match t.parse::<f64>()
    {
        Ok(x) if range.contains(&x) => Ok(x),
        _ => Err(format!(
            "the {what} step `{t}` is not a number of degrees from {} to {}",
            range.start(),
            range.end()
        )),
    };
    Ok([
        number(declination, "declination", 0.1..=46.88)?,
        number(hour, "hour-angle", 0.25..=180.0)?,
    ])
}

/// A relative error a build can aim for: a number in (0, 1].
fn positive_fraction(text: &str) -> Result<f64, String> {
    match text.trim().parse::<f64>() {
        Ok(x) if x > 0.0 && x <= 1.0 => Ok(x),
        Ok(x) => Err(format!("{x} is not a relative error in (0, 1]")),
        Err(_) => Err(format!("`{text}` is not a number")),
    }
}
