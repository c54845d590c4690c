//! `eigenrad sky`: the sun's position and a sky's figures for a site, a time and a weather
//! state, through the runtime's sky models (what a controller will compute).

use std::fmt::Write as _;

use eigenrad_runtime::sky::{cie::CieSky, efficacy, patches::SkyPatches, perez, RelativeSky};
use serde::Serialize;

use crate::daylight::{self, sun};
use crate::error::{Error, Result};

/// Which sky, and what drives it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum SkyInput {
    /// A CIE standard general sky type (1 to 15; 0 for the traditional overcast sky) scaled
    /// to a diffuse horizontal illuminance (lux), with an optional direct normal
    /// illuminance (lux) for the sun.
    Cie {
        /// The type, 1 to 15, or 0 for the traditional CIE overcast sky.
        sky_type: u8,
        /// Diffuse horizontal illuminance, lux.
        diffuse_horizontal: f64,
        /// Direct normal illuminance, lux (0 without the sun).
        direct_normal: f64,
    },
    /// The Perez sky from irradiances, W/m².
    PerezIrradiance {
        /// Direct normal irradiance, W/m².
        direct_normal: f64,
        /// Diffuse horizontal irradiance, W/m².
        diffuse_horizontal: f64,
    },
    /// The Perez sky from illuminances, lux.
    PerezIlluminance {
        /// Direct normal illuminance, lux.
        direct_normal: f64,
        /// Diffuse horizontal illuminance, lux.
        diffuse_horizontal: f64,
    },
}

/// What `eigenrad sky` is asked.
#[derive(Clone, Debug)]
pub struct SkyRequest {
    /// The site.
    pub site: sun::Site,
    /// The time, as given (with its UTC offset).
    pub time: String,
    /// Compass bearing of the scene's +y axis, degrees clockwise from true north.
    pub north: f64,
    /// The sky.
    pub input: SkyInput,
    /// Precipitable water, cm (Perez efficacies).
    pub water: f64,
    /// Reinhart subdivision MF (1: Tregenza's 145 patches).
    pub subdivision: u8,
}

/// One sky patch of the report.
#[derive(Clone, Debug, Serialize)]
pub struct PatchReport {
    /// Index, 0-based (Radiance's bin `index + 1`).
    pub index: usize,
    /// Altitude of the centre, degrees.
    pub altitude_deg: f64,
    /// Azimuth of the centre, degrees clockwise from true north.
    pub azimuth_deg: f64,
    /// Centre direction in the room's frame.
    pub direction_room: [f64; 3],
    /// Solid angle, sr.
    pub solid_angle_sr: f64,
    /// Luminance at the centre, cd/m².
    pub luminance_cd_m2: f64,
}

/// The state of a Perez sky and its efficacies.
#[derive(Clone, Debug, Serialize)]
pub struct PerezReport {
    /// Clearness ε.
    pub clearness: f64,
    /// Brightness Δ.
    pub brightness: f64,
    /// Coefficients a, b, c, d, e.
    pub coefficients: [f64; 5],
    /// Luminous efficacy of the diffuse irradiance, lm/W.
    pub diffuse_efficacy_lm_w: f64,
    /// Luminous efficacy of the direct irradiance, lm/W.
    pub direct_efficacy_lm_w: f64,
    /// Diffuse horizontal irradiance, W/m².
    pub diffuse_horizontal_w_m2: f64,
    /// Direct normal irradiance, W/m².
    pub direct_normal_w_m2: f64,
}

/// A sky built for the report: its relative luminance, the factor to cd/m², and its
/// illuminances (lux).
struct Built {
    model: String,
    sky: Box<dyn RelativeSky>,
    scale: f64,
    diffuse_lux: f64,
    direct_lux: f64,
    perez: Option<PerezReport>,
}

/// What `eigenrad sky` reports. Illuminances in lux, luminances in cd/m², angles in degrees.
#[derive(Clone, Debug, Serialize)]
pub struct SkyReport {
    /// The time, RFC 3339 with its offset.
    pub time: String,
    /// Latitude (degrees north), longitude (degrees east), elevation (m).
    pub site: [f64; 3],
    /// Compass bearing of the scene's +y axis, degrees.
    pub north_deg: f64,
    /// The sun (apparent altitude, standard-atmosphere refraction).
    pub sun: sun::SunPosition,
    /// The sun's direction in the room's frame (unit vector).
    pub sun_direction_room: [f64; 3],
    /// `CIE type N`, `CIE traditional overcast` or `Perez`.
    pub model: String,
    /// The Perez sky's state and efficacies (Perez skies only).
    pub perez: Option<PerezReport>,
    /// Zenith luminance, cd/m².
    pub zenith_luminance_cd_m2: f64,
    /// Diffuse horizontal illuminance of the unobstructed sky, lux.
    pub diffuse_horizontal_lux: f64,
    /// Direct normal illuminance of the sun, lux.
    pub direct_normal_lux: f64,
    /// Direct illuminance of the sun on a horizontal plane, lux.
    pub direct_horizontal_lux: f64,
    /// Global horizontal illuminance (diffuse + direct), lux.
    pub global_horizontal_lux: f64,
    /// The sky patches: `tregenza` (MF:1) or `reinhart MF:n`.
    pub patch_set: String,
    /// The diffuse horizontal illuminance of the patches' centre luminances, each times the
    /// patch's projected solid angle, lux: the sky discretised.
    pub patch_diffuse_horizontal_lux: f64,
    /// Every patch.
    pub patches: Vec<PatchReport>,
}

fn err(what: &str, reason: impl Into<String>) -> Error {
    Error::Daylight {
        what: what.to_owned(),
        reason: reason.into(),
    }
}

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

fn runtime_err(what: &str) -> impl Fn(eigenrad_runtime::Error) -> Error + '_ {
    move |e| err(what, e.to_string())
}

/// `eigenrad sky`.
pub fn sky(request: &SkyRequest) -> Result<SkyReport> {
    let site = request.site;
    check_request(request)?;
    let patches = SkyPatches::reinhart(request.subdivision).map_err(runtime_err("--mf"))?;
    let time = sun::parse_time(&request.time)?;
    let position = sun::position(&site, &time, &sun::SunOptions::default())?;
    if position.altitude < 0.0 {
        return Err(err(
            "--time",
            format!(
                "the sun is below the horizon then (altitude {:.2}°, azimuth {:.2}°): the sky models need it above",
                position.altitude, position.azimuth
            ),
        ));
    }
    let site_sun = daylight::room_direction(position.altitude, position.azimuth, 0.0);
    let sun_room = daylight::site_to_room(site_sun, request.north);
    let sin_alt = position.altitude.to_radians().sin();
    let sun_state = SunState {
        // The sky in the site's frame (the patches' frame), in f32 as the controller has it.
        direction: site_sun.map(|x| x as f32),
        zenith: (position.zenith.to_radians() as f32).min(core::f32::consts::FRAC_PI_2),
        day_of_year: sun::day_of_year(&time),
    };
    let Built {
        model,
        sky: relative,
        scale,
        diffuse_lux,
        direct_lux,
        perez,
    } = built_sky(request.input, &sun_state, request.water)?;
    let zenith_luminance = f64::from(relative.relative_luminance([0.0, 0.0, 1.0])) * scale;
    let (patch_reports, patch_sum) = patch_reports(&patches, &*relative, scale, request.north);
    Ok(SkyReport {
        time: time.to_rfc3339(),
        site: [site.latitude, site.longitude, site.elevation],
        north_deg: request.north,
        sun: position,
        sun_direction_room: sun_room,
        model,
        perez,
        zenith_luminance_cd_m2: zenith_luminance,
        diffuse_horizontal_lux: diffuse_lux,
        direct_normal_lux: direct_lux,
        direct_horizontal_lux: direct_lux * sin_alt,
        global_horizontal_lux: diffuse_lux + direct_lux * sin_alt,
        patch_set: if patches.subdivision() == 1 {
            "tregenza".to_owned()
        } else {
            format!("reinhart MF:{}", patches.subdivision())
        },
        patch_diffuse_horizontal_lux: patch_sum,
        patches: patch_reports,
    })
}

/// Checks the site, the room's bearing (`--north`) and the precipitable water (`--water`) of
/// `request`.
fn check_request(request: &SkyRequest) -> Result<()> {
    sun::check_site(&request.site)?;
    if !(request.north.is_finite() && request.north.abs() <= 360.0) {
        return Err(err(
            "--north",
            format!("{} is not an angle from −360° to 360°", request.north),
        ));
    }
    if !(request.water.is_finite() && (0.0..=10.0).contains(&request.water)) {
        return Err(err(
            "--water",
            format!("{} cm is outside 0 cm to 10 cm", request.water),
        ));
    }
    Ok(())
}

/// The sun as the sky models take it, in f32 as the controller has it.
struct SunState {
    /// Direction in the site's frame (the sky patches' frame), unit vector.
    direction: [f32; 3],
    /// Zenith angle, radians, at most π/2.
    zenith: f32,
    /// Day of the year, 1 to 366 (the Perez sky's extraterrestrial irradiance).
    day_of_year: u16,
}

/// The sky `input` asks for under `sun`, with `water` cm of precipitable water for the Perez
/// efficacies; each flag checked against what daylight can give.
fn built_sky(input: SkyInput, sun: &SunState, water: f64) -> Result<Built> {
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

/// Every patch of `patches` under `relative` times `scale` (cd/m²), directions turned into
/// the room's axes by `north` (degrees); and the diffuse horizontal illuminance of their
/// centre luminances, lux.
fn patch_reports(
    patches: &SkyPatches,
    relative: &dyn RelativeSky,
    scale: f64,
    north: f64,
) -> (Vec<PatchReport>, f64) {
    let mut patch_reports = Vec::with_capacity(patches.count());
    let mut patch_sum = 0.0f64;
    for i in 0..patches.count() {
        let Some(p) = patches.patch(i) else { break };
        let luminance = f64::from(relative.relative_luminance(p.direction)) * scale;
        patch_sum += luminance * f64::from(p.projected_solid_angle);
        let dir = p.direction.map(f64::from);
        let altitude = 0.5 * (f64::from(p.altitude[0]) + f64::from(p.altitude[1]));
        patch_reports.push(PatchReport {
            index: i,
            altitude_deg: if i + 1 == patches.count() {
                90.0
            } else {
                altitude.to_degrees()
            },
            azimuth_deg: f64::from(p.azimuth).to_degrees(),
            direction_room: daylight::site_to_room(dir, north),
            solid_angle_sr: f64::from(p.solid_angle),
            luminance_cd_m2: luminance,
        });
    }
    (patch_reports, patch_sum)
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

/// The report as text: one quantity a line, each with its unit.
pub fn format_sky(r: &SkyReport) -> String {
    let mut s = String::new();
    let _ = writeln!(s, "time                         {}", r.time);
    let _ = writeln!(
        s,
        "site                         {:.4}° N, {:.4}° E, {:.1} m; scene +y at {:.1}° from true north",
        r.site[0], r.site[1], r.site[2], r.north_deg
    );
    let _ = writeln!(
        s,
        "sun                          altitude {:.3}°, azimuth {:.3}° (clockwise from north), zenith {:.3}°",
        r.sun.altitude, r.sun.azimuth, r.sun.zenith
    );
    let d = r.sun_direction_room;
    let _ = writeln!(
        s,
        "sun direction (scene axes)   ({:.4}, {:.4}, {:.4})",
        d[0], d[1], d[2]
    );
    let _ = writeln!(s, "sky                          {}", r.model);
    if let Some(p) = &r.perez {
        let _ = writeln!(
            s,
            "clearness ε, brightness Δ    {:.4}, {:.4}",
            p.clearness, p.brightness
        );
        let c = p.coefficients;
        let _ = writeln!(
            s,
            "Perez a, b, c, d, e          {:.4}, {:.4}, {:.4}, {:.4}, {:.4}",
            c[0], c[1], c[2], c[3], c[4]
        );
        let _ = writeln!(
            s,
            "efficacy                     diffuse {:.2} lm/W, direct {:.2} lm/W",
            p.diffuse_efficacy_lm_w, p.direct_efficacy_lm_w
        );
        let _ = writeln!(
            s,
            "irradiance                   diffuse horizontal {:.1} W/m², direct normal {:.1} W/m²",
            p.diffuse_horizontal_w_m2, p.direct_normal_w_m2
        );
    }
    let _ = writeln!(
        s,
        "zenith luminance             {:.1} cd/m²",
        r.zenith_luminance_cd_m2
    );
    let _ = writeln!(
        s,
        "diffuse horizontal           {:.1} lux",
        r.diffuse_horizontal_lux
    );
    let _ = writeln!(
        s,
        "direct                       {:.1} lux normal, {:.1} lux horizontal",
        r.direct_normal_lux, r.direct_horizontal_lux
    );
    let _ = writeln!(
        s,
        "global horizontal            {:.1} lux",
        r.global_horizontal_lux
    );
    let rel = if r.diffuse_horizontal_lux > 0.0 {
        100.0 * (r.patch_diffuse_horizontal_lux / r.diffuse_horizontal_lux - 1.0)
    } else {
        0.0
    };
    let _ = writeln!(
        s,
        "{:<28} {} patches: diffuse horizontal {:.1} lux from centre luminances ({rel:+.2} %)",
        r.patch_set,
        r.patches.len(),
        r.patch_diffuse_horizontal_lux
    );
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    fn request(input: SkyInput) -> SkyRequest {
        SkyRequest {
            site: sun::Site {
                latitude: 48.2,
                longitude: 16.4,
                elevation: 0.0,
            },
            time: "2026-06-21T12:00+02:00".to_owned(),
            north: 0.0,
            input,
            water: 2.0,
            subdivision: 1,
        }
    }

    /// A CIE overcast sky scaled to 15 000 lux: its patches' centre luminances times their
    /// projected solid angles come back to the illuminance within the discretisation error
    /// of the traditional overcast sky, whose patch sum has the closed form
    /// Σ (1 + 2 sin h_i)/3 L_z Ω⊥_i (here within 1 %: it is smooth), and the zenith luminance
    /// is 9/(7π) E_h exactly (to the quadrature's 10⁻⁶).
    #[test]
    fn traditional_overcast_report() {
        let r = sky(&request(SkyInput::Cie {
            sky_type: 0,
            diffuse_horizontal: 15_000.0,
            direct_normal: 0.0,
        }))
        .unwrap();
        let lz = 9.0 / (7.0 * std::f64::consts::PI) * 15_000.0;
        assert!((r.zenith_luminance_cd_m2 - lz).abs() <= 1.0e-5 * lz);
        assert_eq!(r.patches.len(), 145);
        let omega: f64 = r.patches.iter().map(|p| p.solid_angle_sr).sum();
        assert!((omega - 2.0 * std::f64::consts::PI).abs() < 1e-4);
        assert!((r.patch_diffuse_horizontal_lux / 15_000.0 - 1.0).abs() < 0.01);
        assert!(r.perez.is_none());
    }

    #[test]
    fn perez_from_irradiance_and_illuminance_agree() {
        let w = sky(&request(SkyInput::PerezIrradiance {
            direct_normal: 700.0,
            diffuse_horizontal: 120.0,
        }))
        .unwrap();
        let wp = w.perez.as_ref().unwrap();
        let (kd, kb) = (wp.diffuse_efficacy_lm_w, wp.direct_efficacy_lm_w);
        assert!((w.diffuse_horizontal_lux - 120.0 * kd).abs() < 1e-6 * w.diffuse_horizontal_lux);
        let l = sky(&request(SkyInput::PerezIlluminance {
            direct_normal: 700.0 * kb,
            diffuse_horizontal: 120.0 * kd,
        }))
        .unwrap();
        // The illuminance route finds the irradiances back to the iteration's 10⁻⁴.
        let lp = l.perez.as_ref().unwrap();
        assert!((lp.diffuse_horizontal_w_m2 - 120.0).abs() < 0.05);
        assert!((lp.direct_normal_w_m2 - 700.0).abs() < 0.3);
        assert!((l.zenith_luminance_cd_m2 / w.zenith_luminance_cd_m2 - 1.0).abs() < 1e-3);
    }

    #[test]
    fn bad_requests_name_the_flag() {
        let mut r = request(SkyInput::Cie {
            sky_type: 16,
            diffuse_horizontal: 1000.0,
            direct_normal: 0.0,
        });
        assert!(sky(&r).unwrap_err().to_string().contains("--cie"));
        r.input = SkyInput::PerezIrradiance {
            direct_normal: 700.0,
            diffuse_horizontal: -3.0,
        };
        assert!(sky(&r).unwrap_err().to_string().contains("--dhi"));
        r.input = SkyInput::PerezIrradiance {
            direct_normal: f64::NAN,
            diffuse_horizontal: 100.0,
        };
        assert!(sky(&r).unwrap_err().to_string().contains("--dni"));
        r.site.latitude = -95.0;
        assert!(sky(&r).unwrap_err().to_string().contains("--lat"));
        r.site.latitude = 48.2;
        r.time = "2026-06-21T23:00+02:00".to_owned();
        r.input = SkyInput::PerezIrradiance {
            direct_normal: 0.0,
            diffuse_horizontal: 100.0,
        };
        let e = sky(&r).unwrap_err().to_string();
        assert!(
            e.contains("--time") && e.contains("below the horizon"),
            "{e}"
        );
        r.time = "tomorrow".to_owned();
        assert!(sky(&r).unwrap_err().to_string().contains("--time"));
    }
}
