//! A sky for a site, a time and a weather state: the sun's position, the illuminances and
//! every sky patch's luminance, through the runtime's sky models (what a controller will
//! compute). The request and the report here, the sky models in `models.rs`; `eigenrad sky`
//! prints the report, `solve --time` and `eval --time` light the room with it.

mod models;

use chrono::{DateTime, FixedOffset};
use eigenrad_runtime::sky::{patches::SkyPatches, RelativeSky};
use serde::Serialize;

use super::{self as daylight, error as err, sun, Result};
use models::{built_sky, Built, SunState};

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

/// What a sky is asked apart from its time: the same for every moment of a loop over time
/// ([`sky_at`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SkyParams {
    /// The site.
    pub site: sun::Site,
    /// Compass bearing of the scene's +y axis, degrees clockwise from true north.
    pub north: f64,
    /// The sky.
    pub input: SkyInput,
    /// Precipitable water, cm (Perez efficacies).
    pub water: f64,
    /// Reinhart subdivision MF (1: Tregenza's 145 patches).
    pub subdivision: u8,
}

/// What a sky is asked (`eigenrad sky`, `solve --time`, `eval --time`): [`SkyParams`] and a
/// time as text.
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

/// A sky as `eigenrad sky` reports it. Illuminances in lux, luminances in cd/m², angles in degrees.
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

/// The runtime's error about `what` (a flag, or the model it built) as a daylight error.
fn runtime_err(what: &str) -> impl Fn(eigenrad_runtime::Error) -> super::DaylightError + '_ {
    move |e| err(what, e.to_string())
}

impl SkyRequest {
    /// The request without its time.
    pub fn params(&self) -> SkyParams {
        SkyParams {
            site: self.site,
            north: self.north,
            input: self.input,
            water: self.water,
            subdivision: self.subdivision,
        }
    }
}

/// The sky of `request`: the sun's position at its time (parsed by [`sun::parse_time`]) and
/// the sky's figures and patches, as [`sky_at`] gives them.
pub fn sky(request: &SkyRequest) -> Result<SkyReport> {
    let params = request.params();
    // The site and the flags are checked before the time, so that a bad flag is named first.
    check_params(&params)?;
    let time = sun::parse_time(&request.time)?;
    sky_at(&params, &time)
}

/// The sky of `params` at `time`: the sun's position then and the sky's figures and patches.
/// The report's time is `time` in RFC 3339 with its offset.
pub fn sky_at(params: &SkyParams, time: &DateTime<FixedOffset>) -> Result<SkyReport> {
    let site = params.site;
    check_params(params)?;
    let patches = SkyPatches::reinhart(params.subdivision).map_err(runtime_err("--mf"))?;
    let position = sun::position(&site, time, &sun::SunOptions::default())?;
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
    let sun_room = daylight::site_to_room(site_sun, params.north);
    let sin_alt = position.altitude.to_radians().sin();
    let sun_state = SunState {
        // The sky in the site's frame (the patches' frame), in f32 as the controller has it.
        direction: site_sun.map(|x| x as f32),
        zenith: (position.zenith.to_radians() as f32).min(core::f32::consts::FRAC_PI_2),
        day_of_year: sun::day_of_year(time),
    };
    let Built {
        model,
        sky: relative,
        scale,
        diffuse_lux,
        direct_lux,
        perez,
    } = built_sky(params.input, &sun_state, params.water)?;
    let zenith_luminance = f64::from(relative.relative_luminance([0.0, 0.0, 1.0])) * scale;
    let (patch_reports, patch_sum) = patch_reports(&patches, &*relative, scale, params.north);
    Ok(SkyReport {
        time: time.to_rfc3339(),
        site: [site.latitude, site.longitude, site.elevation],
        north_deg: params.north,
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

/// Checks the site, the room's bearing (`--north`), the precipitable water (`--water`) and
/// the sky's patches (`--mf`) of `params`.
fn check_params(params: &SkyParams) -> Result<()> {
    sun::check_site(&params.site)?;
    if !(params.north.is_finite() && params.north.abs() <= 360.0) {
        return Err(err(
            "--north",
            format!("{} is not an angle from −360° to 360°", params.north),
        ));
    }
    if !(params.water.is_finite() && (0.0..=10.0).contains(&params.water)) {
        return Err(err(
            "--water",
            format!("{} cm is outside 0 cm to 10 cm", params.water),
        ));
    }
    SkyPatches::reinhart(params.subdivision).map_err(runtime_err("--mf"))?;
    Ok(())
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

    /// A loop over time asks [`sky_at`] with the time as a value; [`sky`] parses its text and
    /// gives the same report, to the byte of its JSON.
    #[test]
    fn sky_at_a_time_is_the_sky_of_its_text() {
        let r = request(SkyInput::PerezIrradiance {
            direct_normal: 650.0,
            diffuse_horizontal: 140.0,
        });
        let time = sun::parse_time(&r.time).unwrap();
        let a = serde_json::to_string(&sky(&r).unwrap()).unwrap();
        let b = serde_json::to_string(&sky_at(&r.params(), &time).unwrap()).unwrap();
        assert_eq!(a, b);
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
