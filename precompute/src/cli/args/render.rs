//! `eigenrad render`: false-colour pictures of a scene, from its exact solve or from a basis
//! built from it.

use std::path::PathBuf;

use clap::{Args, ValueEnum};

use super::daylight::DaylightFlags;
use super::groups::{help, CacheArgs, ChannelLevels, UnitsFlag};
use super::{note_written, read};
use crate::cli::{self, atomic, guard};
use crate::error::Error;
use crate::{picture, scene};

/// The arguments of `eigenrad render`. Its illuminance is the only quantity in the units
/// asked for, and its daylight comes from the scene's windows or, with `--basis`, from what
/// the basis carries.
#[derive(Args)]
#[command(
    mut_arg(
        "units",
        help("Unit of illuminance (luminance is in cd/m² either way)")
    ),
    mut_arg(
        "time",
        help(
            "Daylight at this date and time through the scene's windows, under the sky the sky \
             flags give, as `solve --time`; with --basis, from the daylight the basis carries, \
             as `eval --time` (the plan only: the surfaces need the exact solve)"
        )
    )
)]
pub(super) struct RenderArgs {
    /// Scene file (TOML): the geometry, and what is solved without --basis.
    scene: PathBuf,
    /// Evaluate this basis (built from the scene) through the runtime instead of solving
    /// the scene: what the controller would see.
    #[arg(long)]
    basis: Option<PathBuf>,
    #[command(flatten)]
    levels: ChannelLevels,
    /// Write the plan of the work plane (its calculation grid in false colour, isolux
    /// lines, a scale in lux or fc) to this .png or .svg file, atomically; repeatable.
    #[arg(long, value_name = "FILE")]
    plan: Vec<PathBuf>,
    /// Write the room's surfaces unfolded (floor in the middle, walls folded out, ceiling
    /// beside) to this .png or .svg file, atomically; repeatable.
    #[arg(long, value_name = "FILE")]
    surfaces: Vec<PathBuf>,
    /// The work-plane zone of the plan [default: the scene's only one]; repeatable: zones of
    /// one floor (planes at one height) are drawn together on one colour scale.
    #[arg(long, value_name = "NAME")]
    zone: Vec<String>,
    /// What colours the surfaces.
    #[arg(long, value_enum, default_value = "illuminance")]
    quantity: QuantityArg,
    #[command(flatten)]
    units: UnitsFlag,
    #[command(flatten)]
    daylight: DaylightFlags,
    #[command(flatten)]
    cache: CacheArgs,
}

#[derive(Clone, Copy, ValueEnum)]
enum QuantityArg {
    /// Irradiance E arriving at each patch (lux or fc; W/m²).
    Illuminance,
    /// Luminance L = M/π leaving each patch (cd/m²; W/(m²·sr)).
    Luminance,
}

impl RenderArgs {
    /// Computes the readings, draws the pictures asked for and writes each to its file.
    pub(super) fn run(self) -> anyhow::Result<()> {
        let daylight = self.daylight.daylight()?;
        if self.plan.is_empty() && self.surfaces.is_empty() {
            anyhow::bail!("render: nothing to draw; name a --plan FILE, a --surfaces FILE or both (.png or .svg)");
        }
        self.check_outputs()?;
        let bytes = self.basis.as_deref().map(read).transpose()?;
        let pictures = cli::render(&cli::RenderRequest {
            scene: &self.scene,
            basis: self.basis.as_deref().zip(bytes.as_deref()),
            levels: &self.levels.level_args(),
            units: self.units.units(),
            zones: &self.zone,
            plan: !self.plan.is_empty(),
            surfaces: (!self.surfaces.is_empty()).then_some(match self.quantity {
                QuantityArg::Illuminance => cli::SurfaceQuantity::Illuminance,
                QuantityArg::Luminance => cli::SurfaceQuantity::Luminance,
            }),
            form_factors: &self.cache.form_factors(),
            daylight: daylight.as_ref(),
        })?;
        self.write(&pictures)
    }

    /// Before any work: every output a .png or .svg that can be written, named once, none an
    /// input.
    fn check_outputs(&self) -> anyhow::Result<()> {
        let outputs: Vec<PathBuf> = self.plan.iter().chain(&self.surfaces).cloned().collect();
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
        let mut inputs = scene::inputs(&self.scene)?.files;
        inputs.extend(self.basis.iter().cloned());
        guard::check_outputs(&outputs, &inputs)?;
        Ok(())
    }

    /// Every picture asked for, drawn in its file's format and written atomically.
    fn write(&self, pictures: &cli::Pictures) -> anyhow::Result<()> {
        let files = self
            .plan
            .iter()
            .map(|p| (p, true))
            .chain(self.surfaces.iter().map(|p| (p, false)));
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
                    scene: self.scene.clone(),
                    reason: format!("drawing {}: {reason}", path.display()),
                })?;
                atomic::write(path, &bytes)?;
                note_written(path);
            }
        }
        Ok(())
    }
}
