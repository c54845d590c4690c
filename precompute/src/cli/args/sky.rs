//! `eigenrad sky`: the sun's position and one sky for a site, a time and a weather state.

use clap::Args;

use super::daylight::{SkyStateArgs, GIVE_ONE_SKY};
use super::groups::{help, JsonFlag};
use crate::cli;
use crate::daylight::sun::Site;

/// `eigenrad sky`: the site, the time and one sky.
#[derive(Args)]
#[command(group(clap::ArgGroup::new("model").required(true).multiple(true).args(["cie", "dni", "dni_lux"])))]
#[command(mut_arg(
    "json",
    help("Print one JSON document on stdout, with every sky patch")
))]
pub(super) struct SkyArgs {
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
    #[command(flatten)]
    json: JsonFlag,
}

impl SkyArgs {
    /// Computes the sun and the sky and prints them.
    pub(super) fn run(self) -> anyhow::Result<()> {
        let report = cli::sky(&self.request()?)?;
        self.json.print(&report, cli::format_sky)
    }

    /// What `cli::sky` is asked.
    fn request(&self) -> anyhow::Result<cli::SkyRequest> {
        let Some(input) = self.sky.input()? else {
            anyhow::bail!(GIVE_ONE_SKY)
        };
        Ok(cli::SkyRequest {
            site: Site {
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
