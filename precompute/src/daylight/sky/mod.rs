//! A sky for a site, a time and a weather state: the sun's position, the illuminances and
//! every sky patch's luminance, through the runtime's sky models (what a controller will
//! compute). The request and the report here, the sky models in `models.rs`; `eigenrad sky`
//! prints the report, `solve --time` and `eval --time` light the room with it.
//!
//! **The sun below the horizon** (apparent altitude below 0: dawn, dusk, night) is not an
//! error. The sky is then its diffuse light alone: the model's shape with the sun placed on
//! the horizon at its azimuth (altitude 0, zenith angle 90°), scaled to the diffuse
//! horizontal illuminance given, and no sun (direct normal 0; one given above 0 is dropped,
//! and the report's `notes` say so). A Perez sky's state is then that of its diffuse
//! irradiance alone (ε = 1, the overcast bin). A diffuse horizontal of 0 is a dark sky,
//! every patch 0 cd/m², whatever the model and wherever the sun.
//!
//! Radiance's `gendaymtx` (2.38, `src/gen/gendaymtx.c`, the annual sky matrices of a weather
//! file, what `epw2wea` passes every record to unchanged) does the same with the sky: a record
//! whose direct and diffuse add up to at most 10⁻⁴ is a black sky (`main`, "effectively
//! nighttime?"), and any other has its Perez sky computed with the sun's zenith angle held at
//! 90° when the altitude is at or below 0 (`ComputeSky`: "don't let it dip below horizon"),
//! scaled to the record's diffuse. It differs in the direct light: it keeps the record's
//! direct normal in the clearness ε and still spreads it over the four sky patches nearest
//! the sun below the horizon (`AddDirect` has no altitude test; the ground gets none), with
//! a warning ("unusually bright") only above 20 W/m². eigenrad drops it: a sun below the
//! horizon sends no direct light into a room, and a direct normal in a record then is the
//! hour's average over a sunrise or a measurement's artefact. `gendaylit` (one sky at a time)
//! instead refuses such a moment with an "error sky" of zero luminance, diffuse or not.

mod models;

use chrono::{DateTime, FixedOffset};
use eigenrad_runtime::sky::{patches::SkyPatches, RelativeSky};
use serde::Serialize;

use crate::daylight::{self, error as err, sun, Result};
use models::{built_sky, Built, SunState};

/// Which sky, and what drives it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum SkyInput {
    /// A CIE standard general sky type (1 to 15; 0 for the traditional overcast sky) scaled
    /// to a diffuse horizontal illuminance (lux), with a direct normal illuminance (lux) for
    /// the sun. The commands take the sun of types 6 to 15 (partly cloudy and clear) only
    /// as given (`--dni-lux`), that of the overcast types as 0 unless given.
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
    /// The Perez sky of a weather record that gives both irradiances and illuminances: its
    /// state (clearness, brightness) from the irradiances, the quantities the model was
    /// fitted to, its luminance and its sun scaled to the illuminances. Turning
    /// illuminances back into irradiances through the efficacies is ill-conditioned for a
    /// low sun, whose direct efficacy falls towards 0 (700 lux direct normal at 0.9° of
    /// altitude came back as 307 W/m² where the record measured 17 W/m²).
    PerezMeasured {
        /// Direct normal irradiance, W/m².
        direct_normal: f64,
        /// Diffuse horizontal irradiance, W/m².
        diffuse_horizontal: f64,
        /// Direct normal illuminance, lux.
        direct_normal_lux: f64,
        /// Diffuse horizontal illuminance, lux.
        diffuse_horizontal_lux: f64,
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

/// The state of a Perez sky and its efficacies. A dark sky (no diffuse light) has no state
/// (ε and Δ divide by and take the logarithm of its diffuse light): it reports the limits
/// its efficacies were taken at, those of Radiance's `gendaymtx` (ε 11.9 with a sun, else 1;
/// Δ 0.01).
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
    /// The sun's direction in the room's frame (unit vector; below the horizon where the sun
    /// is, not where the sky's shape takes it).
    pub sun_direction_room: [f64; 3],
    /// The sun is below the horizon (apparent altitude below 0): the sky is its diffuse light
    /// alone, shaped with the sun on the horizon at its azimuth, and there is no direct light.
    pub sun_below_horizon: bool,
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
    /// What the sky made of its input that its figures alone do not say: a direct light
    /// given for a sun below the horizon and dropped. Empty as a rule.
    pub notes: Vec<String>,
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
    // Below the horizon the sky's shape takes the sun on the horizon at its azimuth, and the
    // sun sends no direct light (the module's documentation).
    let below = position.altitude < 0.0;
    let (input, notes) = if below {
        let (input, dropped) = models::without_direct(params.input)?;
        let notes = dropped.map(|given| {
            format!(
                "the sun is below the horizon (altitude {:.2}°): the direct normal {given} given is dropped, the sky is its diffuse light alone",
                position.altitude
            )
        });
        (input, notes.into_iter().collect())
    } else {
        (params.input, Vec::new())
    };
    let site_sun = daylight::room_direction(position.altitude, position.azimuth, 0.0);
    let sun_room = daylight::site_to_room(site_sun, params.north);
    let sun_state = if below {
        SunState {
            direction: daylight::room_direction(0.0, position.azimuth, 0.0).map(|x| x as f32),
            zenith: core::f32::consts::FRAC_PI_2,
            day_of_year: sun::day_of_year(time),
        }
    } else {
        SunState {
            // The sky in the site's frame (the patches' frame), in f32 as the controller has it.
            direction: site_sun.map(|x| x as f32),
            zenith: (position.zenith.to_radians() as f32).min(core::f32::consts::FRAC_PI_2),
            day_of_year: sun::day_of_year(time),
        }
    };
    let Built {
        model,
        sky: relative,
        scale,
        diffuse_lux,
        direct_lux,
        perez,
    } = built_sky(input, &sun_state, params.water)?;
    // No direct light below the horizon (and no −0 from 0 times a negative sine).
    let direct_horizontal = if below {
        0.0
    } else {
        direct_lux * position.altitude.to_radians().sin()
    };
    let zenith_luminance = f64::from(relative.relative_luminance([0.0, 0.0, 1.0])) * scale;
    let (patch_reports, patch_sum) = patch_reports(&patches, &*relative, scale, params.north);
    Ok(SkyReport {
        time: time.to_rfc3339(),
        site: [site.latitude, site.longitude, site.elevation],
        north_deg: params.north,
        sun: position,
        sun_direction_room: sun_room,
        sun_below_horizon: below,
        model,
        perez,
        zenith_luminance_cd_m2: zenith_luminance,
        diffuse_horizontal_lux: diffuse_lux,
        direct_normal_lux: direct_lux,
        direct_horizontal_lux: direct_horizontal,
        global_horizontal_lux: diffuse_lux + direct_horizontal,
        patch_set: if patches.subdivision() == 1 {
            "tregenza".to_owned()
        } else {
            format!("reinhart MF:{}", patches.subdivision())
        },
        patch_diffuse_horizontal_lux: patch_sum,
        notes,
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
mod tests;
