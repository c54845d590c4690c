//! The sky models of a sky report, the runtime's (what a controller will compute): a CIE
//! standard general sky scaled to a diffuse horizontal illuminance, or the Perez all-weather
//! sky from irradiances or illuminances with its efficacies; every flag checked against what
//! daylight can give.

use eigenrad_runtime::sky::{cie::CieSky, efficacy, perez, RelativeSky};

use super::{err, runtime_err, PerezReport, SkyInput};
use crate::daylight::Result;

/// A sky built for the report: its relative luminance, the factor to cd/m², and its
/// illuminances (lux).
pub(super) struct Built {
    pub(super) model: String,
    pub(super) sky: Box<dyn RelativeSky>,
    pub(super) scale: f64,
    pub(super) diffuse_lux: f64,
    pub(super) direct_lux: f64,
    pub(super) perez: Option<PerezReport>,
}

/// `value` of `flag` in `unit` as f32, if it is a number from 0 to `max`, what daylight can give.
fn check_flag(value: f64, flag: &str, unit: &str, max: f64) -> Result<f32> {
    if !value.is_finite() {
        return Err(err(flag, format!("{value} is not a number of {unit}")));
    }
    if value < 0.0 {
        return Err(err(flag, format!("{value} {unit} is negative")));
    }
    if value > max {
        return Err(err(
            flag,
            format!("{value} {unit} is above {max} {unit}, more than daylight gives"),
        ));
    }
    Ok(value as f32)
}

/// The sun as the sky models take it, in f32 as the controller has it.
pub(super) struct SunState {
    /// Direction in the site's frame (the sky patches' frame), unit vector.
    pub(super) direction: [f32; 3],
    /// Zenith angle, radians, at most π/2.
    pub(super) zenith: f32,
    /// Day of the year, 1 to 366 (the Perez sky's extraterrestrial irradiance).
    pub(super) day_of_year: u16,
}

/// The sky `input` asks for under `sun`, with `water` cm of precipitable water for the Perez
/// efficacies; each flag checked against what daylight can give.
pub(super) fn built_sky(input: SkyInput, sun: &SunState, water: f64) -> Result<Built> {
    match input {
        SkyInput::Cie {
            sky_type,
            diffuse_horizontal,
            direct_normal,
        } => cie_sky(sky_type, diffuse_horizontal, direct_normal, sun),
        SkyInput::PerezIrradiance {
            direct_normal,
            diffuse_horizontal,
        } => perez_from_irradiance(direct_normal, diffuse_horizontal, sun, water),
        SkyInput::PerezIlluminance {
            direct_normal,
            diffuse_horizontal,
        } => perez_from_illuminance(direct_normal, diffuse_horizontal, sun, water),
    }
}

/// A CIE sky of `sky_type` (0: the traditional overcast sky) scaled to `diffuse_horizontal`
/// lux, with a sun of `direct_normal` lux.
fn cie_sky(
    sky_type: u8,
    diffuse_horizontal: f64,
    direct_normal: f64,
    sun: &SunState,
) -> Result<Built> {
    let dhi = check_flag(diffuse_horizontal, "--dhi-lux", "lux", 2.0e5)?;
    check_flag(direct_normal, "--dni-lux", "lux", 1.5e5)?;
    let sky = if sky_type == 0 {
        CieSky::traditional_overcast(sun.direction)
    } else {
        CieSky::standard(sky_type, sun.direction)
    }
    .map_err(runtime_err("--cie"))?;
    let lz = sky
        .zenith_luminance_for(dhi)
        .map_err(runtime_err("--dhi-lux"))?;
    let name = if sky_type == 0 {
        "CIE traditional overcast".to_owned()
    } else {
        format!("CIE type {sky_type}")
    };
    Ok(Built {
        model: name,
        sky: Box::new(sky),
        scale: f64::from(lz),
        diffuse_lux: diffuse_horizontal,
        direct_lux: direct_normal,
        perez: None,
    })
}

/// The Perez sky of a direct normal and a diffuse horizontal irradiance, W/m².
fn perez_from_irradiance(
    direct_normal: f64,
    diffuse_horizontal: f64,
    sun: &SunState,
    water: f64,
) -> Result<Built> {
    let dni = check_flag(direct_normal, "--dni", "W/m²", 1400.0)?;
    let dhi = check_flag(diffuse_horizontal, "--dhi", "W/m²", 1000.0)?;
    if dhi <= 0.0 {
        return Err(err(
            "--dhi",
            "the Perez sky needs a diffuse horizontal irradiance above 0 W/m²",
        ));
    }
    let c = perez::Conditions::from_irradiance(dhi, dni, sun.zenith, sun.day_of_year)
        .map_err(runtime_err("--dni/--dhi"))?;
    perez_parts(
        &c,
        sun.direction,
        water as f32,
        f64::from(dhi),
        f64::from(dni),
    )
}

/// The Perez sky of a direct normal and a diffuse horizontal illuminance, lux.
fn perez_from_illuminance(
    direct_normal: f64,
    diffuse_horizontal: f64,
    sun: &SunState,
    water: f64,
) -> Result<Built> {
    let dni = check_flag(direct_normal, "--dni-lux", "lux", 1.5e5)?;
    let dhi = check_flag(diffuse_horizontal, "--dhi-lux", "lux", 2.0e5)?;
    if dhi <= 0.0 {
        return Err(err(
            "--dhi-lux",
            "the Perez sky needs a diffuse horizontal illuminance above 0 lux",
        ));
    }
    let (c, dhi_w, dni_w) =
        perez::Conditions::from_illuminance(dhi, dni, sun.zenith, sun.day_of_year, water as f32)
            .map_err(runtime_err("--dni-lux/--dhi-lux"))?;
    let mut built = perez_parts(
        &c,
        sun.direction,
        water as f32,
        f64::from(dhi_w),
        f64::from(dni_w),
    )?;
    // Scaled to the illuminances given, not to their round trip through the
    // efficacies.
    built.scale *= diffuse_horizontal / built.diffuse_lux;
    built.diffuse_lux = diffuse_horizontal;
    built.direct_lux = direct_normal;
    Ok(built)
}

/// The Perez sky of `c` with its figures.
fn perez_parts(
    c: &perez::Conditions,
    sun32: [f32; 3],
    water: f32,
    dhi_w: f64,
    dni_w: f64,
) -> Result<Built> {
    let sky = perez::PerezSky::new(c, sun32).map_err(runtime_err("Perez sky"))?;
    let kd = efficacy::diffuse(c, water).map_err(runtime_err("--water"))?;
    let kb = efficacy::direct(c, water).map_err(runtime_err("--water"))?;
    let diffuse_lux = dhi_w * f64::from(kd);
    let direct_lux = dni_w * f64::from(kb);
    let scale = f64::from(
        sky.luminance_scale(diffuse_lux as f32)
            .map_err(runtime_err("Perez sky"))?,
    );
    let perez = PerezReport {
        clearness: f64::from(c.clearness),
        brightness: f64::from(c.brightness),
        coefficients: sky.coefficients().map(f64::from),
        diffuse_efficacy_lm_w: f64::from(kd),
        direct_efficacy_lm_w: f64::from(kb),
        diffuse_horizontal_w_m2: dhi_w,
        direct_normal_w_m2: dni_w,
    };
    Ok(Built {
        model: "Perez".to_owned(),
        sky: Box::new(sky),
        scale,
        diffuse_lux,
        direct_lux,
        perez: Some(perez),
    })
}
