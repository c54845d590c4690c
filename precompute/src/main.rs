//! The `eigenrad` command: a thin layer over `eigenrad_precompute` that parses arguments and
//! prints. Every number printed carries its unit.

use std::io::{IsTerminal, Write as _};
use std::path::{Path, PathBuf};
use std::process::ExitCode;

use anyhow::Context;
use clap::{Args, Parser, Subcommand, ValueEnum};
use eigenrad_precompute::cli::{self, atomic, guard};
use eigenrad_precompute::formfactor::FormFactorOptions;
use eigenrad_precompute::pipeline::{self, BuildOptions, ModeSelection};
use eigenrad_precompute::radiosity::eigen::{Formulation, Solver};
use eigenrad_precompute::{cache, picture, scene, verify, Error};
use eigenrad_runtime::Precision;

/// Real-time radiosity for lighting controllers: precompute a room's eigenbasis, evaluate it
/// like the firmware does, and check it against the exact solution.
#[derive(Parser)]
#[command(name = "eigenrad", version, about, long_about = None)]
struct Cli {
    #[command(subcommand)]
    command: Command,
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

#[derive(Clone, Copy, ValueEnum)]
enum QuantityArg {
    /// Irradiance E arriving at each patch (lux or fc; W/m²).
    Illuminance,
    /// Luminance L = M/π leaving each patch (cd/m²; W/(m²·sr)).
    Luminance,
}

#[derive(Clone, Copy, ValueEnum)]
enum UnitsArg {
    /// Lux for a photometric basis or scene (W/m² for a radiometric one, whatever is asked).
    Lux,
    /// Footcandles: 1 fc = 1 lm/ft² = 10.7639 lx (photometric only).
    Fc,
}

impl From<UnitsArg> for cli::Units {
    fn from(u: UnitsArg) -> Self {
        match u {
            UnitsArg::Lux => cli::Units::Native,
            UnitsArg::Fc => cli::Units::Footcandles,
        }
    }
}

/// The form-factor cache of the commands that compute form factors.
#[derive(Args)]
struct CacheArgs {
    /// Compute the form factors without reading or writing the form-factor cache
    /// ($EIGENRAD_CACHE_DIR, else $XDG_CACHE_HOME/eigenrad, else ~/.cache/eigenrad).
    #[arg(long)]
    no_cache: bool,
}

impl CacheArgs {
    /// Form-factor settings for a command: the defaults, a progress bar only where someone
    /// watches (never in logs, pipes or tests), and the cache unless `--no-cache`.
    fn form_factors(&self) -> FormFactorOptions {
        FormFactorOptions {
            progress: std::io::stderr().is_terminal(),
            cache: if self.no_cache {
                None
            } else {
                cache::default_dir()
            },
            ..FormFactorOptions::default()
        }
    }
}

#[derive(Subcommand)]
enum Command {
    /// Build a basis from a scene and report patches, modes, size, form-factor health,
    /// accuracy per channel and time per stage.
    Build {
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
        /// Print the report as one JSON document on stdout.
        #[arg(long)]
        json: bool,
        #[command(flatten)]
        cache: CacheArgs,
    },
    /// Exact dense solve of a scene (LU), for reference.
    Solve {
        /// Scene file (TOML).
        scene: PathBuf,
        /// Channel level, relative (1 = as in the scene); repeatable. Channels default to 1.
        #[arg(long = "level", value_name = "NAME=VALUE")]
        levels: Vec<String>,
        /// Channel level as a DALI arc power level, 0 (off) to 254 (100 %) on the IEC 62386-102
        /// curve, as the firmware converts it; repeatable. Not with --level for one channel.
        #[arg(long = "arc", value_name = "NAME=ARC")]
        arcs: Vec<String>,
        /// Also print every patch.
        #[arg(long)]
        patches: bool,
        /// Unit of illuminance (and exitance) printed.
        #[arg(long, value_enum, default_value = "lux")]
        units: UnitsArg,
        /// Print one JSON document on stdout.
        #[arg(long)]
        json: bool,
        /// Write every calculation grid point (zone, position in m, irradiance per band) to
        /// this CSV file, atomically.
        #[arg(long, value_name = "FILE")]
        csv: Option<PathBuf>,
        /// Daylight at this date and time (with its UTC offset, or the scene's
        /// `site.utc_offset`), through the scene's windows from the sky the sky flags give;
        /// readings then show daylight and electric light apart and together.
        #[arg(long)]
        time: Option<String>,
        #[command(flatten)]
        sky: SkyStateArgs,
        #[command(flatten)]
        cache: CacheArgs,
    },
    /// Evaluate a basis through the runtime crate: exactly what firmware computes.
    Eval {
        /// Basis file.
        basis: PathBuf,
        /// Channel level, relative (1 = as built); repeatable. Channels default to 1.
        #[arg(long = "level", value_name = "NAME=VALUE")]
        levels: Vec<String>,
        /// Channel level as a DALI arc power level, 0 (off) to 254 (100 %) on the IEC 62386-102
        /// curve, through the runtime's conversion; repeatable. Not with --level for one channel.
        #[arg(long = "arc", value_name = "NAME=ARC")]
        arcs: Vec<String>,
        /// Also print every patch.
        #[arg(long)]
        patches: bool,
        /// Unit of illuminance (and exitance) printed.
        #[arg(long, value_enum, default_value = "lux")]
        units: UnitsArg,
        /// Print one JSON document on stdout.
        #[arg(long)]
        json: bool,
        /// Write every calculation grid point (zone, position in m, irradiance per band) to
        /// this CSV file, atomically.
        #[arg(long, value_name = "FILE")]
        csv: Option<PathBuf>,
        /// Daylight at this date and time (with its UTC offset, or the site's), from the sky
        /// the sky flags give, through the daylight the basis carries (a basis built from a
        /// scene with a `[site]` and glazed windows); readings then show daylight and
        /// electric light apart and together.
        #[arg(long)]
        time: Option<String>,
        #[command(flatten)]
        sky: SkyStateArgs,
    },
    /// False-colour pictures (PNG or SVG, by the file's extension): the plan of a work plane
    /// with isolux lines, and the room's surfaces unfolded; from the exact solve of the scene,
    /// or with --basis from a basis built from it, evaluated as the firmware does.
    Render {
        /// Scene file (TOML): the geometry, and what is solved without --basis.
        scene: PathBuf,
        /// Evaluate this basis (built from the scene) through the runtime instead of solving
        /// the scene: what the controller would see.
        #[arg(long)]
        basis: Option<PathBuf>,
        /// Channel level, relative (1 = as built); repeatable. Channels default to 1.
        #[arg(long = "level", value_name = "NAME=VALUE")]
        levels: Vec<String>,
        /// Channel level as a DALI arc power level, 0 (off) to 254 (100 %) on the IEC 62386-102
        /// curve, as the firmware converts it; repeatable. Not with --level for one channel.
        #[arg(long = "arc", value_name = "NAME=ARC")]
        arcs: Vec<String>,
        /// Write the plan of the work plane (its calculation grid in false colour, isolux
        /// lines, a scale in lux or fc) to this .png or .svg file, atomically; repeatable.
        #[arg(long, value_name = "FILE")]
        plan: Vec<PathBuf>,
        /// Write the room's surfaces unfolded (floor in the middle, walls folded out, ceiling
        /// beside) to this .png or .svg file, atomically; repeatable.
        #[arg(long, value_name = "FILE")]
        surfaces: Vec<PathBuf>,
        /// The work-plane zone of the plan [default: the scene's only one].
        #[arg(long, value_name = "NAME")]
        zone: Option<String>,
        /// What colours the surfaces.
        #[arg(long, value_enum, default_value = "illuminance")]
        quantity: QuantityArg,
        /// Unit of illuminance (luminance is in cd/m² either way).
        #[arg(long, value_enum, default_value = "lux")]
        units: UnitsArg,
        /// Daylight at this date and time through the scene's windows, under the sky the sky
        /// flags give, as `solve --time` (not with --basis).
        #[arg(long)]
        time: Option<String>,
        #[command(flatten)]
        sky: SkyStateArgs,
        #[command(flatten)]
        cache: CacheArgs,
    },
    /// Surface-to-surface form factors, area-weighted over each surface's patches.
    FormFactors {
        /// Scene file (TOML).
        scene: PathBuf,
        /// Print `{factors: [{from, to, value}], health: {...}}` as JSON on stdout.
        #[arg(long)]
        json: bool,
        #[command(flatten)]
        cache: CacheArgs,
    },
    /// Describe a basis: dimensions, names, sizes; or, with --gains, what every sensor and
    /// zone reads per channel.
    Inspect {
        /// Basis file.
        basis: PathBuf,
        /// Instead: for every sensor and zone, its reading per channel at level 1 with the
        /// other channels off (lux, fc or W/m² per band), through the runtime.
        #[arg(long)]
        gains: bool,
        /// With --gains: also write the gains as CSV to this file (atomically).
        #[arg(long, value_name = "FILE", requires = "gains")]
        csv: Option<PathBuf>,
        /// With --gains: unit of illuminance.
        #[arg(long, value_enum, default_value = "lux", requires = "gains")]
        units: UnitsArg,
        /// Print one JSON document on stdout.
        #[arg(long)]
        json: bool,
    },
    /// The sun's position and a sky (CIE standard general sky or Perez all-weather sky) for a
    /// site, a time and a weather state: sun altitude and azimuth, efficacies, zenith
    /// luminance, horizontal illuminances, and with --json every sky patch's luminance.
    Sky(SkyArgs),
    /// Accuracy report: relative error against the exact solve as the mode count grows, for
    /// both formulations and the per-channel baseline, as markdown tables and SVG curves.
    Verify {
        /// Scene file (TOML).
        scene: PathBuf,
        /// Write `<scene>.md` and `<scene>-{patches,zones,sensors}.svg` into this folder.
        #[arg(long)]
        out: Option<PathBuf>,
        /// Print the report as one JSON document on stdout instead of the tables.
        #[arg(long)]
        json: bool,
        #[command(flatten)]
        cache: CacheArgs,
    },
}

/// `eigenrad sky`: the site, the time and one sky.
#[derive(Args)]
#[command(group(clap::ArgGroup::new("model").required(true).multiple(true).args(["cie", "dni", "dni_lux"])))]
struct SkyArgs {
    /// Latitude, degrees north (−90 to 90).
    #[arg(long, allow_hyphen_values = true)]
    lat: f64,
    /// Longitude, degrees east (−180 to 180).
    #[arg(long, allow_hyphen_values = true)]
    lon: f64,
    /// Height above sea level, m.
    #[arg(long, default_value_t = 0.0, allow_hyphen_values = true)]
    elevation: f64,
    /// Date and time with its UTC offset, e.g. 2026-06-21T12:00+02:00 or 2026-06-21T10:00Z.
    #[arg(long)]
    time: String,
    /// Compass bearing of the scene's +y axis, degrees clockwise from true north.
    #[arg(long, default_value_t = 0.0, allow_hyphen_values = true)]
    north: f64,
    #[command(flatten)]
    sky: SkyStateArgs,
    /// Print one JSON document on stdout, with every sky patch.
    #[arg(long)]
    json: bool,
}

/// A sky and what drives it: the flags `sky` and `solve` share.
#[derive(Args)]
struct SkyStateArgs {
    /// CIE standard general sky type 1 to 15, or `overcast` for the traditional CIE
    /// overcast sky; needs --dhi-lux (and takes --dni-lux for the sun).
    #[arg(long, value_name = "TYPE", value_parser = cie_type)]
    cie: Option<u8>,
    /// Perez sky: direct normal irradiance, W/m² (with --dhi).
    #[arg(long, requires = "dhi", conflicts_with_all = ["cie", "dni_lux", "dhi_lux"], allow_hyphen_values = true)]
    dni: Option<f64>,
    /// Perez sky: diffuse horizontal irradiance, W/m² (with --dni).
    #[arg(long, requires = "dni", allow_hyphen_values = true)]
    dhi: Option<f64>,
    /// Direct normal illuminance, lux: the Perez sky with --dhi-lux, or the sun of a CIE sky.
    #[arg(long, allow_hyphen_values = true)]
    dni_lux: Option<f64>,
    /// Diffuse horizontal illuminance, lux (a CIE sky, or the Perez sky with --dni-lux).
    #[arg(long, allow_hyphen_values = true)]
    dhi_lux: Option<f64>,
    /// Atmospheric precipitable water, cm, for the Perez efficacies.
    #[arg(long, default_value_t = 2.0, allow_hyphen_values = true)]
    water: f64,
    /// Sky patches: Reinhart subdivision MF:n, 1 (Tregenza, 145 patches) to 8.
    #[arg(long, default_value_t = 1)]
    mf: u8,
}

impl SkyStateArgs {
    /// The sky the flags give, or `None` when they give none.
    fn input(&self) -> anyhow::Result<Option<cli::SkyInput>> {
        Ok(Some(
            match (self.cie, self.dni, self.dhi, self.dni_lux, self.dhi_lux) {
                (None, None, None, None, None) => return Ok(None),
                (Some(sky_type), None, None, dni, Some(dhi)) => cli::SkyInput::Cie {
                    sky_type,
                    diffuse_horizontal: dhi,
                    direct_normal: dni.unwrap_or(0.0),
                },
                (Some(_), _, _, _, None) => anyhow::bail!("--cie needs --dhi-lux (lux)"),
                (None, Some(dni), Some(dhi), None, None) => cli::SkyInput::PerezIrradiance {
                    direct_normal: dni,
                    diffuse_horizontal: dhi,
                },
                (None, None, None, Some(dni), Some(dhi)) => cli::SkyInput::PerezIlluminance {
                    direct_normal: dni,
                    diffuse_horizontal: dhi,
                },
                (None, None, None, Some(_), None) => {
                    anyhow::bail!("--dni-lux needs --dhi-lux (the Perez sky from illuminances)")
                }
                _ => anyhow::bail!(
                    "give one sky: --cie TYPE --dhi-lux LUX, --dni W/m² --dhi W/m², or --dni-lux LUX --dhi-lux LUX"
                ),
            },
        ))
    }
}

impl SkyArgs {
    fn request(&self) -> anyhow::Result<cli::SkyRequest> {
        let Some(input) = self.sky.input()? else {
            anyhow::bail!(
                "give one sky: --cie TYPE --dhi-lux LUX, --dni W/m² --dhi W/m², or --dni-lux LUX --dhi-lux LUX"
            )
        };
        Ok(cli::SkyRequest {
            site: eigenrad_precompute::daylight::sun::Site {
                latitude: self.lat,
                longitude: self.lon,
                elevation: self.elevation,
            },
            time: self.time.clone(),
            north: self.north,
            input,
            water: self.sky.water,
            subdivision: self.sky.mf,
        })
    }
}

/// `solve --time ... <sky>`: the daylight asked for, or `None` without a time and a sky.
fn daylight_args(
    time: Option<String>,
    sky: &SkyStateArgs,
) -> anyhow::Result<Option<cli::DaylightArgs>> {
    match (time, sky.input()?) {
        (None, None) => Ok(None),
        (Some(time), Some(input)) => Ok(Some(cli::DaylightArgs {
            time,
            input,
            water: sky.water,
            subdivision: sky.mf,
        })),
        (Some(_), None) => anyhow::bail!(
            "--time needs a sky: --cie TYPE --dhi-lux LUX, --dni W/m² --dhi W/m², or --dni-lux LUX --dhi-lux LUX"
        ),
        (None, Some(_)) => {
            anyhow::bail!("a sky needs --time (the date and time, for the sun's position)")
        }
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

/// `--cie`: 1 to 15, or `overcast` (the traditional CIE overcast sky, 0 here).
fn cie_type(text: &str) -> Result<u8, String> {
    match text.trim() {
        "overcast" => Ok(0),
        t => match t.parse::<u8>() {
            Ok(n) if (1..=15).contains(&n) => Ok(n),
            _ => Err(format!(
                "`{text}` is not a CIE standard sky type: 1 to 15, or `overcast`"
            )),
        },
    }
}

/// A relative error a build can aim for: a number in (0, 1].
fn positive_fraction(text: &str) -> Result<f64, String> {
    match text.trim().parse::<f64>() {
        Ok(x) if x > 0.0 && x <= 1.0 => Ok(x),
        Ok(x) => Err(format!("{x} is not a relative error in (0, 1]")),
        Err(_) => Err(format!("`{text}` is not a number")),
    }
}

/// What `solve` and `eval` end with: the readings in the asked units, their grid points to
/// `csv` (checked against the inputs beforehand) and the readout on standard output.
fn show_readout(
    readout: cli::Readout,
    units: cli::units::Units,
    csv: Option<&std::path::Path>,
    json: bool,
) -> anyhow::Result<()> {
    let readout = cli::units::readout_in(readout, units)?;
    if let Some(csv) = csv {
        atomic::write(csv, cli::grids_csv(&readout).as_bytes())?;
    }
    cli::print(&if json {
        cli::json(&readout)?
    } else {
        cli::format_readout(&readout)
    })?;
    Ok(())
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    match run(cli) {
        Ok(()) => ExitCode::SUCCESS,
        // The reader went away (`| head`): stop quietly, with the status a shell reports for
        // tools that SIGPIPE ends (128 + 13).
        Err(e) if matches!(e.downcast_ref::<Error>(), Some(Error::ClosedPipe)) => {
            ExitCode::from(141)
        }
        Err(e) => {
            // Nothing left to report to if standard error is closed too.
            let _ = writeln!(std::io::stderr(), "error: {e:#}");
            ExitCode::FAILURE
        }
    }
}

/// Tells on standard error what was written; a closed standard error is no reason to fail.
fn note_written(path: &Path) {
    let _ = writeln!(std::io::stderr(), "wrote {}", path.display());
}

fn read(path: &Path) -> anyhow::Result<Vec<u8>> {
    std::fs::read(path).map_err(|reason| {
        Error::Io {
            path: path.to_path_buf(),
            reason,
        }
        .into()
    })
}

fn run(cli: Cli) -> anyhow::Result<()> {
    match cli.command {
        Command::Build {
            scene,
            output,
            modes,
            tolerance,
            formulation,
            precision,
            solver,
            no_grids,
            sun_step,
            json,
            cache,
        } => {
            let opts = BuildOptions {
                grids: !no_grids,
                sun_step: sun_step
                    .unwrap_or(eigenrad_precompute::sources::daylight::nodes::DEFAULT_SUN_STEP),
                modes: match (modes, tolerance) {
                    (Some(p), _) => ModeSelection::Count(p),
                    (None, Some(t)) => ModeSelection::Tolerance(t),
                    (None, None) => ModeSelection::Count(pipeline::DEFAULT_MODES),
                },
                formulation: match formulation {
                    FormulationArg::Split => Formulation::Split,
                    FormulationArg::Seed => Formulation::Seed,
                },
                precision: match precision {
                    PrecisionArg::F32 => Precision::F32,
                    PrecisionArg::F16 => Precision::F16,
                    PrecisionArg::I16 => Precision::I16,
                },
                solver: match solver {
                    SolverArg::Auto => Solver::Auto,
                    SolverArg::Dense => Solver::Dense,
                    SolverArg::Partial => Solver::Partial,
                },
                form_factors: cache.form_factors(),
                ..BuildOptions::default()
            };
            // Before any work: the basis must be writable and must not replace the scene or a
            // file it reads.
            guard::check_file_output(&output)?;
            guard::check_outputs(std::slice::from_ref(&output), &scene::inputs(&scene)?.files)?;
            let (bytes, report) = pipeline::build(&scene, &opts)?;
            atomic::write(&output, &bytes)?;
            cli::print(&if json {
                cli::json(&report)?
            } else {
                cli::format_build_report(&report, &output)
            })?;
        }
        Command::Solve {
            scene,
            levels,
            arcs,
            patches,
            units,
            json,
            csv,
            time,
            sky,
            cache,
        } => {
            let daylight = daylight_args(time, &sky)?;
            if let Some(csv) = &csv {
                guard::check_file_output(csv)?;
                guard::check_outputs(std::slice::from_ref(csv), &scene::inputs(&scene)?.files)?;
            }
            let levels = cli::LevelArgs { levels, arcs };
            let readout = cli::solve_with_daylight(
                &scene,
                &levels,
                daylight.as_ref(),
                patches,
                &cache.form_factors(),
            )?;
            show_readout(readout, units.into(), csv.as_deref(), json)?;
        }
        Command::Eval {
            basis,
            levels,
            arcs,
            patches,
            units,
            json,
            csv,
            time,
            sky,
        } => {
            let daylight = daylight_args(time, &sky)?;
            if let Some(csv) = &csv {
                guard::check_file_output(csv)?;
                guard::check_outputs(std::slice::from_ref(csv), std::slice::from_ref(&basis))?;
            }
            let bytes = read(&basis)?;
            let levels = cli::LevelArgs { levels, arcs };
            let readout =
                cli::eval_with_daylight(&basis, &bytes, &levels, daylight.as_ref(), patches)
                    .with_context(|| format!("evaluating {}", basis.display()))?;
            show_readout(readout, units.into(), csv.as_deref(), json)?;
        }
        Command::Render {
            scene,
            basis,
            levels,
            arcs,
            plan,
            surfaces,
            zone,
            quantity,
            units,
            time,
            sky,
            cache,
        } => {
            let daylight = daylight_args(time, &sky)?;
            if plan.is_empty() && surfaces.is_empty() {
                anyhow::bail!("render: nothing to draw; name a --plan FILE, a --surfaces FILE or both (.png or .svg)");
            }
            // Before any work: every output a .png or .svg that can be written, none an input.
            let outputs: Vec<PathBuf> = plan.iter().chain(&surfaces).cloned().collect();
            for path in &outputs {
                if picture::Format::of(path).is_none() {
                    anyhow::bail!(
                        "{}: a picture is written as .png or .svg, by its extension",
                        path.display()
                    );
                }
                guard::check_file_output(path)?;
            }
            for (k, path) in outputs.iter().enumerate() {
                if outputs[..k].contains(path) {
                    anyhow::bail!(
                        "{}: named twice; give each picture its own file",
                        path.display()
                    );
                }
            }
            let mut inputs = scene::inputs(&scene)?.files;
            inputs.extend(basis.iter().cloned());
            guard::check_outputs(&outputs, &inputs)?;
            let bytes = basis.as_deref().map(read).transpose()?;
            let levels = cli::LevelArgs { levels, arcs };
            let pictures = cli::render(&cli::RenderRequest {
                scene: &scene,
                basis: basis.as_deref().zip(bytes.as_deref()),
                levels: &levels,
                units: units.into(),
                zone: zone.as_deref(),
                plan: !plan.is_empty(),
                surfaces: (!surfaces.is_empty()).then_some(match quantity {
                    QuantityArg::Illuminance => cli::SurfaceQuantity::Illuminance,
                    QuantityArg::Luminance => cli::SurfaceQuantity::Luminance,
                }),
                form_factors: &cache.form_factors(),
                daylight: daylight.as_ref(),
            })?;
            let files = plan
                .iter()
                .map(|p| (p, true))
                .chain(surfaces.iter().map(|p| (p, false)));
            for (path, is_plan) in files {
                let Some(format) = picture::Format::of(path) else {
                    continue;
                };
                let drawn = if is_plan {
                    pictures.plan_file(format)
                } else {
                    pictures.surfaces_file(format)
                };
                if let Some(drawn) = drawn {
                    let bytes = drawn.map_err(|reason| Error::Render {
                        scene: scene.clone(),
                        reason: format!("drawing {}: {reason}", path.display()),
                    })?;
                    atomic::write(path, &bytes)?;
                    note_written(path);
                }
            }
        }
        Command::FormFactors { scene, json, cache } => {
            let table = cli::form_factor_table(&scene, &cache.form_factors())?;
            cli::print(&if json {
                cli::json(&table)?
            } else {
                cli::format_surface_form_factors(&table)
            })?;
        }
        Command::Inspect {
            basis,
            gains: true,
            csv,
            units,
            json,
        } => {
            if let Some(csv) = &csv {
                guard::check_file_output(csv)?;
                guard::check_outputs(std::slice::from_ref(csv), std::slice::from_ref(&basis))?;
            }
            let bytes = read(&basis)?;
            let gains = cli::gains(&basis, &bytes, units.into())?;
            if let Some(csv) = csv {
                atomic::write(&csv, cli::gains_csv(&gains).as_bytes())?;
                note_written(&csv);
            }
            cli::print(&if json {
                cli::json(&gains)?
            } else {
                cli::format_gains(&gains)
            })?;
        }
        Command::Inspect {
            basis,
            gains: false,
            json,
            ..
        } => {
            let bytes = read(&basis)?;
            let info = cli::inspect(&basis, &bytes)?;
            cli::print(&if json {
                cli::json(&info)?
            } else {
                cli::format_inspect(&info)
            })?;
        }
        Command::Sky(args) => {
            let report = cli::sky(&args.request()?)?;
            cli::print(&if args.json {
                cli::json(&report)?
            } else {
                cli::format_sky(&report)
            })?;
        }
        Command::Verify {
            scene,
            out,
            json,
            cache,
        } => {
            if let Some(dir) = &out {
                let inputs = scene::inputs(&scene)?;
                guard::check_outputs(&cli::verify_outputs(dir, &inputs.name), &inputs.files)?;
            }
            let opts = verify::VerifyOptions {
                form_factors: cache.form_factors(),
                progress: std::io::stderr().is_terminal(),
                ..verify::VerifyOptions::default()
            };
            let report = verify::verify(&scene, &opts)?;
            let tables = verify::markdown(&report);
            if let Some(dir) = out {
                for path in cli::write_svgs(&report, &dir)? {
                    note_written(&path);
                }
                let path = dir.join(format!("{}.md", report.scene));
                atomic::write(&path, tables.as_bytes())?;
                note_written(&path);
            }
            cli::print(&if json { cli::json(&report)? } else { tables })?;
        }
    }
    Ok(())
}
