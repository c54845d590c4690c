//! A time and a sky: the flags of `solve`, `eval` and `render` that add a moment's daylight,
//! and the sky flags they share with `sky`.

use clap::Args;

use crate::cli;

/// The sky flags' error when no sky (or no whole sky) is given.
pub(super) const GIVE_ONE_SKY: &str =
    "give one sky: --cie TYPE --dhi-lux LUX [--dni-lux LUX], --dni W/m² --dhi W/m², or --dni-lux LUX --dhi-lux LUX";

/// The first CIE standard general sky type with a sun: types 1 to 5 are overcast (and
/// uniform), 6 to 10 partly cloudy, 11 to 15 clear (CIE S 011/E:2003, ISO 15469:2004,
/// Table 1). A sky with a sun needs its direct light given: without `--dni-lux` it would be
/// lit by its sky alone, a tenth of its daylight.
const FIRST_SUNNY_CIE_TYPE: u8 = 6;

/// A sky and what drives it: the flags `sky` and `solve` share.
#[derive(Args)]
pub(super) struct SkyStateArgs {
    /// CIE standard general sky type 1 to 15, or `overcast` for the traditional CIE
    /// overcast sky; needs --dhi-lux, and types 6 to 15 (partly cloudy and clear, with a
    /// sun) --dni-lux for the sun (0 for the sky without it).
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
    pub(super) water: f64,
    /// Sky patches: Reinhart subdivision MF:n, 1 (Tregenza, 145 patches) to 8.
    #[arg(long, default_value_t = 1)]
    pub(super) mf: u8,
}

impl SkyStateArgs {
    /// The sky the flags give, or `None` when they give none.
    pub(super) fn input(&self) -> anyhow::Result<Option<cli::SkyInput>> {
        Ok(Some(
            match (self.cie, self.dni, self.dhi, self.dni_lux, self.dhi_lux) {
                (None, None, None, None, None) => return Ok(None),
                (Some(sky_type), None, None, dni, Some(dhi)) => cli::SkyInput::Cie {
                    sky_type,
                    diffuse_horizontal: dhi,
                    direct_normal: match dni {
                        Some(dni) => dni,
                        None if sky_type >= FIRST_SUNNY_CIE_TYPE => anyhow::bail!(
                            "--cie {sky_type} is a sky with a sun (CIE types 6 to 10 partly cloudy, 11 to 15 clear): give the sun's direct normal illuminance, --dni-lux LUX (0 for the sky without its sun)"
                        ),
                        None => 0.0,
                    },
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
                _ => anyhow::bail!(GIVE_ONE_SKY),
            },
        ))
    }
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

/// A moment's daylight through the room's windows: `--time` and the sky flags, for `solve`,
/// `eval` and `render`.
#[derive(Args)]
pub(super) struct DaylightFlags {
    /// Daylight at this date and time (with its UTC offset, or the scene's
    /// `site.utc_offset`), through the scene's windows from the sky the sky flags give;
    /// readings then show daylight and electric light apart and together.
    #[arg(long)]
    time: Option<String>,
    #[command(flatten)]
    sky: SkyStateArgs,
}

impl DaylightFlags {
    /// The daylight asked for, or `None` without a time and a sky; a time without a sky, or
    /// a sky without a time, is an error.
    pub(super) fn daylight(&self) -> anyhow::Result<Option<cli::DaylightArgs>> {
        match (&self.time, self.sky.input()?) {
            (None, None) => Ok(None),
            (Some(time), Some(input)) => Ok(Some(cli::DaylightArgs {
                time: time.clone(),
                input,
                water: self.sky.water,
                subdivision: self.sky.mf,
            })),
            (Some(_), None) => anyhow::bail!(
                "--time needs a sky: --cie TYPE --dhi-lux LUX [--dni-lux LUX], --dni W/m² --dhi W/m², or --dni-lux LUX --dhi-lux LUX"
            ),
            (None, Some(_)) => {
                anyhow::bail!("a sky needs --time (the date and time, for the sun's position)")
            }
        }
    }
}
