//! `eigenrad simulate`: the controller's year on a basis and a weather file.

use std::path::PathBuf;

use clap::{Args, ValueEnum};

use super::groups::{help, JsonFlag};
use super::{note_written, read};
use crate::cli::{self, atomic, guard, HeatMapQuantity};
use crate::picture::Format;
use crate::simulate::{Recipe, SkySource};

/// The arguments of `eigenrad simulate`.
#[derive(Args)]
#[command(mut_arg(
    "json",
    help("Print the summary as one JSON document (with every grid point's daylight autonomy)")
))]
pub(super) struct SimulateArgs {
    /// Basis file (built from a scene with daylight: a `[site]` and glazed windows).
    basis: PathBuf,
    /// Weather file: EPW, or TMY3 CSV, with a record an hour.
    #[arg(long, value_name = "FILE", required_unless_present = "sky", conflicts_with_all = ["sky", "from", "to", "linke"])]
    weather: Option<PathBuf>,
    /// Instead of a weather file, the same sky every day: `overcast` (CIE standard sky 1 at
    /// 300 + 21 000 sin(altitude) lux) or `clear` (the Perez sky of Ineichen–Perez clear-sky
    /// irradiances), from --from to --to.
    #[arg(long, value_enum, requires_all = ["from", "to"])]
    sky: Option<RecipeArg>,
    /// With --sky: the first day, YYYY-MM-DD (the basis' standard time).
    #[arg(long, value_name = "DATE", value_parser = date)]
    from: Option<chrono::NaiveDate>,
    /// With --sky: the last day, YYYY-MM-DD, included.
    #[arg(long, value_name = "DATE", value_parser = date)]
    to: Option<chrono::NaiveDate>,
    /// With --sky clear: the Linke turbidity (2 very clear, 3 a clean mid-latitude
    /// atmosphere, 4–5 hazy).
    #[arg(long, requires = "sky")]
    linke: Option<f64>,
    /// Controller file (TOML): photosensor, targets, each channel's power, occupancy,
    /// strategy (docs/simulate.md).
    #[arg(long, value_name = "FILE")]
    controller: PathBuf,
    /// Write the hourly CSV of the controller's strategy to this file, atomically.
    #[arg(long, value_name = "FILE")]
    hourly: Option<PathBuf>,
    /// Write the lighting fraction hour by hour, an EnergyPlus `Schedule:File` CSV, to this
    /// file, atomically.
    #[arg(long, value_name = "FILE")]
    schedule: Option<PathBuf>,
    /// Draw the year as a day × hour heat map of --heatmap-of (days along, the hours of the
    /// day up, the false-colour scale of `render`) to this .png or .svg file, atomically.
    #[arg(long, value_name = "FILE")]
    heatmap: Option<PathBuf>,
    /// What the heat map colours each hour by: `power` (the controller's strategy, W, summed
    /// over its channels) or `daylight:ZONE` (that zone's daylight, lux).
    #[arg(
        long,
        value_name = "QUANTITY",
        default_value = "power",
        requires = "heatmap",
        value_parser = parse_quantity
    )]
    heatmap_of: HeatMapQuantity,
    /// The calendar year the records' dates fall in (weekdays, the sun); default: the first
    /// record's, or the latest year before it with as many days as the file.
    #[arg(long)]
    year: Option<i32>,
    /// Which weather fields drive the sky: `illuminance` (when the file has them, else the
    /// irradiances) or `irradiance` (through the Perez efficacies, as Radiance's gendaymtx).
    #[arg(long, value_enum, default_value = "illuminance")]
    sky_from: SkyFrom,
    #[command(flatten)]
    json: JsonFlag,
}

fn parse_quantity(s: &str) -> Result<HeatMapQuantity, String> {
    s.parse()
}

#[derive(Clone, Copy, ValueEnum)]
enum RecipeArg {
    Overcast,
    Clear,
}

/// `YYYY-MM-DD`.
fn date(text: &str) -> Result<chrono::NaiveDate, String> {
    chrono::NaiveDate::parse_from_str(text.trim(), "%Y-%m-%d")
        .map_err(|e| format!("`{text}` is not a date YYYY-MM-DD: {e}"))
}

#[derive(Clone, Copy, ValueEnum)]
enum SkyFrom {
    Illuminance,
    Irradiance,
}

impl SimulateArgs {
    /// Runs the year and prints its summary; writes the hourly CSV, the schedule and the
    /// heat map.
    pub(super) fn run(self) -> anyhow::Result<()> {
        let outputs: Vec<PathBuf> = [&self.hourly, &self.schedule, &self.heatmap]
            .into_iter()
            .flatten()
            .cloned()
            .collect();
        if let Some(path) = &self.heatmap {
            if Format::of(path).is_none() {
                anyhow::bail!(
                    "{}: a heat map is written as .png or .svg, by its extension",
                    path.display()
                );
            }
        }
        for (k, out) in outputs.iter().enumerate() {
            guard::check_file_output(out)?;
            if outputs[..k].contains(out) {
                anyhow::bail!(
                    "{}: named twice; give each output its own file",
                    out.display()
                );
            }
        }
        let mut inputs = vec![self.basis.clone(), self.controller.clone()];
        inputs.extend(self.weather.clone());
        guard::check_outputs(&outputs, &inputs)?;
        let bytes = read(&self.basis)?;
        let skies = match (&self.weather, self.sky, self.from, self.to) {
            (Some(weather), _, _, _) => cli::Skies::Weather {
                path: weather,
                year: self.year,
                source: match self.sky_from {
                    SkyFrom::Illuminance => SkySource::Illuminance,
                    SkyFrom::Irradiance => SkySource::Irradiance,
                },
            },
            (None, Some(recipe), Some(from), Some(to)) => cli::Skies::Recipe {
                recipe: match recipe {
                    RecipeArg::Overcast => Recipe::Overcast,
                    RecipeArg::Clear => Recipe::Clear {
                        linke: self
                            .linke
                            .unwrap_or(crate::daylight::clear_sky::LINKE_DEFAULT),
                    },
                },
                from,
                to,
            },
            _ => anyhow::bail!("give --weather FILE, or --sky overcast|clear with --from and --to"),
        };
        if self.linke.is_some() && !matches!(self.sky, Some(RecipeArg::Clear)) {
            anyhow::bail!("--linke is the clear sky's: give it with --sky clear");
        }
        let request = cli::SimulateRequest {
            basis: &self.basis,
            skies,
            controller: &self.controller,
            heatmap: self.heatmap.is_some().then_some(&self.heatmap_of),
        };
        let outcome = cli::simulate(&request, &bytes)?;
        if let Some(path) = &self.hourly {
            atomic::write(path, outcome.hourly_csv.as_bytes())?;
            note_written(path);
        }
        if let Some(path) = &self.schedule {
            atomic::write(path, outcome.schedule_csv.as_bytes())?;
            note_written(path);
        }
        if let (Some(path), Some(map)) = (&self.heatmap, &outcome.heatmap) {
            let format = Format::of(path).unwrap_or(Format::Png);
            let bytes = map.file(format).map_err(|reason| {
                anyhow::anyhow!("{}: drawing the heat map: {reason}", path.display())
            })?;
            atomic::write(path, &bytes)?;
            note_written(path);
        }
        self.json
            .print(&outcome.summary, crate::simulate::format_summary)
    }
}
