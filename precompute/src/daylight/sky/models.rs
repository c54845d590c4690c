//! The sky models of a sky report, the runtime's (what a controller will compute): a CIE
//! standard general sky scaled to a diffuse horizontal illuminance, or the Perez all-weather
//! sky from irradiances or illuminances with its efficacies; every flag checked against what
//! daylight can give. A diffuse horizontal of 0 is a dark sky ([`Dark`]) in every model.

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

/// The most diffuse horizontal illuminance daylight gives, lux (the flags' bound).
const DHI_LUX_MAX: f64 = 2.0e5;
/// The most direct normal illuminance daylight gives, lux.
const DNI_LUX_MAX: f64 = 1.5e5;
/// The most diffuse horizontal irradiance daylight gives, W/m².
const DHI_W_MAX: f64 = 1000.0;
/// The most direct normal irradiance daylight gives, W/m².
const DNI_W_MAX: f64 = 1400.0;

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

/// `input` without its sun, for a sun below the horizon: its direct normal checked as ever,
/// then 0; and the direct normal given, with its unit, when it was above 0 (for the report's
/// note).
pub(super) fn without_direct(input: SkyInput) -> Result<(SkyInput, Option<String>)> {
    let (input, given) = match input {
        SkyInput::Cie {
            sky_type,
            diffuse_horizontal,
            direct_normal,
        } => (
            SkyInput::Cie {
                sky_type,
                diffuse_horizontal,
                direct_normal: 0.0,
            },
            (direct_normal, "--dni-lux", "lux", DNI_LUX_MAX),
        ),
        SkyInput::PerezIrradiance {
            direct_normal,
            diffuse_horizontal,
        } => (
            SkyInput::PerezIrradiance {
                direct_normal: 0.0,
                diffuse_horizontal,
            },
            (direct_normal, "--dni", "W/m²", DNI_W_MAX),
        ),
        SkyInput::PerezIlluminance {
            direct_normal,
            diffuse_horizontal,
        } => (
            SkyInput::PerezIlluminance {
                direct_normal: 0.0,
                diffuse_horizontal,
            },
            (direct_normal, "--dni-lux", "lux", DNI_LUX_MAX),
        ),
        SkyInput::PerezMeasured {
            diffuse_horizontal,
            diffuse_horizontal_lux,
            direct_normal_lux,
            ..
        } => (
            SkyInput::PerezMeasured {
                direct_normal: 0.0,
                diffuse_horizontal,
                direct_normal_lux: 0.0,
                diffuse_horizontal_lux,
            },
            (
                direct_normal_lux,
                "direct normal illuminance",
                "lux",
                DNI_LUX_MAX,
            ),
        ),
    };
    let (value, flag, unit, max) = given;
    check_flag(value, flag, unit, max)?;
    let dropped = (value > 0.0).then(|| {
        let quantity = if unit == "lux" {
            "illuminance"
        } else {
            "irradiance"
        };
        format!("{quantity} of {value} {unit}")
    });
    Ok((input, dropped))
}

/// A sky without light (a diffuse horizontal of 0: the night, or a weather record without
/// diffuse light): 0 in every direction, whatever the model would have shaped.
struct Dark {
    sun: [f32; 3],
}

impl RelativeSky for Dark {
    fn relative_luminance(&self, _dir: [f32; 3]) -> f32 {
        0.0
    }

    fn sun(&self) -> [f32; 3] {
        self.sun
    }
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
        SkyInput::PerezMeasured {
            direct_normal,
            diffuse_horizontal,
            direct_normal_lux,
            diffuse_horizontal_lux,
        } => {
            check_flag(
                direct_normal_lux,
                "direct normal illuminance",
                "lux",
                DNI_LUX_MAX,
            )?;
            check_flag(
                diffuse_horizontal_lux,
                "diffuse horizontal illuminance",
                "lux",
                DHI_LUX_MAX,
            )?;
            let mut built = perez_from_irradiance(direct_normal, diffuse_horizontal, sun, water)?;
            // The state's shape, the record's own illuminances.
            if built.diffuse_lux > 0.0 {
                built.scale *= diffuse_horizontal_lux / built.diffuse_lux;
            }
            built.diffuse_lux = diffuse_horizontal_lux;
            built.direct_lux = direct_normal_lux;
            Ok(built)
        }
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
    let dhi = check_flag(diffuse_horizontal, "--dhi-lux", "lux", DHI_LUX_MAX)?;
    check_flag(direct_normal, "--dni-lux", "lux", DNI_LUX_MAX)?;
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
    let dni = check_flag(direct_normal, "--dni", "W/m²", DNI_W_MAX)?;
    let dhi = check_flag(diffuse_horizontal, "--dhi", "W/m²", DHI_W_MAX)?;
    if dhi == 0.0 {
        let (c, kd, kb) = dark_perez_state(dni, sun, water)?;
        let direct_lux = f64::from(dni) * f64::from(kb);
        return Ok(dark_perez(&c, kd, kb, direct_lux, f64::from(dni), sun));
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
    let dni = check_flag(direct_normal, "--dni-lux", "lux", DNI_LUX_MAX)?;
    let dhi = check_flag(diffuse_horizontal, "--dhi-lux", "lux", DHI_LUX_MAX)?;
    if dhi == 0.0 {
        let (c, kd, kb) = dark_perez_state(dni, sun, water)?;
        // The irradiance of the direct illuminance given, as the runtime's
        // `Conditions::from_illuminance` finds it (none through an efficacy below 0.1 lm/W).
        let dni_w = if kb < 0.1 {
            0.0
        } else {
            f64::from(dni) / f64::from(kb)
        };
        return Ok(dark_perez(&c, kd, kb, direct_normal, dni_w, sun));
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
    if eigenrad_runtime::sky::horizontal_illuminance(&sky) <= 0.0 {
        return overcast_in_place_of_perez(c, sun32, kd, kb, diffuse_lux, direct_lux, dhi_w, dni_w);
    }
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

/// The sky of a Perez state whose luminance is nowhere positive, so that no scale gives it
/// its diffuse light: the overcast bin with a bright Δ and the sun at or near the horizon
/// (dusk through a weather year's bright overcast records). The sky is then the CIE
/// traditional overcast sky of the same diffuse horizontal illuminance, and its model says
/// so; its direct light and the Perez figures stay the state's.
#[allow(clippy::too_many_arguments)]
fn overcast_in_place_of_perez(
    c: &perez::Conditions,
    sun32: [f32; 3],
    kd: f32,
    kb: f32,
    diffuse_lux: f64,
    direct_lux: f64,
    dhi_w: f64,
    dni_w: f64,
) -> Result<Built> {
    let overcast = CieSky::traditional_overcast(sun32).map_err(runtime_err("overcast sky"))?;
    let scale = overcast
        .zenith_luminance_for(diffuse_lux as f32)
        .map_err(runtime_err("overcast sky"))?;
    let coefficients = perez::PerezSky::new(c, sun32)
        .map_err(runtime_err("Perez sky"))?
        .coefficients();
    Ok(Built {
        model: "CIE traditional overcast (the Perez state's luminance is nowhere positive)"
            .to_owned(),
        sky: Box::new(overcast),
        scale: f64::from(scale),
        diffuse_lux,
        direct_lux,
        perez: Some(PerezReport {
            clearness: f64::from(c.clearness),
            brightness: f64::from(c.brightness),
            coefficients: coefficients.map(f64::from),
            diffuse_efficacy_lm_w: f64::from(kd),
            direct_efficacy_lm_w: f64::from(kb),
            diffuse_horizontal_w_m2: dhi_w,
            direct_normal_w_m2: dni_w,
        }),
    })
}

/// The state a Perez sky without diffuse light takes its efficacies from, and the diffuse
/// and direct efficacies (lm/W). Without diffuse light ε (which divides by it) and Δ (whose
/// logarithm the diffuse efficacy takes) are undefined; the state is Radiance `gendaymtx`'s
/// limits (`ComputeSky`: ε at most 11.9, Δ at least 0.01): with a sun (`direct_normal` above
/// 0 W/m² or lux) ε = 11.9, the clear bin its limit reaches, else ε = 1.
fn dark_perez_state(
    direct_normal: f32,
    sun: &SunState,
    water: f64,
) -> Result<(perez::Conditions, f32, f32)> {
    let c = perez::Conditions {
        clearness: if direct_normal > 0.0 { 11.9 } else { 1.0 },
        brightness: 0.01,
        zenith: sun.zenith,
    };
    let kd = efficacy::diffuse(&c, water as f32).map_err(runtime_err("--water"))?;
    let kb = efficacy::direct(&c, water as f32).map_err(runtime_err("--water"))?;
    Ok((c, kd, kb))
}

/// A dark Perez sky ([`Dark`]) of the state `c` with efficacies `kd`, `kb` (lm/W), the sun's
/// direct normal illuminance `direct_lux` (lux) and irradiance `dni_w` (W/m²).
fn dark_perez(
    c: &perez::Conditions,
    kd: f32,
    kb: f32,
    direct_lux: f64,
    dni_w: f64,
    sun: &SunState,
) -> Built {
    let perez = PerezReport {
        clearness: f64::from(c.clearness),
        brightness: f64::from(c.brightness),
        coefficients: c.coefficients().map(f64::from),
        diffuse_efficacy_lm_w: f64::from(kd),
        direct_efficacy_lm_w: f64::from(kb),
        diffuse_horizontal_w_m2: 0.0,
        direct_normal_w_m2: dni_w,
    };
    Built {
        model: "Perez".to_owned(),
        sky: Box::new(Dark { sun: sun.direction }),
        scale: 0.0,
        diffuse_lux: 0.0,
        direct_lux,
        perez: Some(perez),
    }
}
