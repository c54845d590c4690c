//! The firmware as a daylight-harvesting controller, on a basis that carries daylight (built
//! only then: see `build.rs`).
//!
//! One day at the basis' site ([`DATE`], local standard time, every [`STEP_MINUTES`] from
//! [`FIRST_MINUTE`] to [`LAST_MINUTE`]) under an overcast sky. At each step the runtime alone
//! builds the sky: the sun's position (`sky::sun::position`), the CIE standard general sky
//! type 1 (overcast, [`SKY_TYPE`]) scaled to the diffuse horizontal illuminance of an
//! overcast sky at that sun's altitude ([`overcast_diffuse_horizontal`]), its patch
//! luminances, and `set_sky` on a `DaylightEvaluator` without modes. The photosensor (the
//! sensor named `ceiling`, else sensor 0) reads `DaylightEvaluator::sensor_total`: its
//! daylight plus the electric light of the luminaires at their current levels, both weighted
//! by the sensor's angular response as the basis stores it. Two controllers, each with its
//! own luminaires (a `ChannelEvaluator`), keep the work plane (the zone named `work_plane`,
//! else zone 0) at [`TARGET`], the dimmed channels and their power those of `control.rs`:
//!
//! - **the model's**: reads its photosensor, takes its daylight as the reading less the
//!   electric light the basis predicts there, turns it into the work plane's daylight by the
//!   ratio of the two under the sky of the moment (`zone_illuminance / sensor_illuminance` of
//!   the daylight evaluator), and sets the least-power levels that give the work plane at
//!   least the target with it (`LevelProblem`);
//! - **the conventional one**: all luminaires at one level, its photosensor commissioned at
//!   night. With every luminaire at 1 and no daylight the sensor reads `S₁` and the work
//!   plane `W₁`; the controller keeps the ratio `r = S₁/W₁` and from then on drives its
//!   level so that the sensor reads the set point `r × target`. Its step is
//!   `level + (set point − reading)/S₁`, clamped to [0, 1]: the reading is linear in the
//!   level with slope `S₁`, so this is where an integral controller of any gain settles, in
//!   one step. By day the sensor sees daylight in another ratio to the work plane than
//!   electric light, and the work plane misses the target by
//!   `(E_wp,day − E_s,day/r)/target` while the level is within [0, 1].
//!
//! Levels are continuous (`set_channel_level`), so that the work plane's error is the
//! controller's and not the DALI curve's rounding. Each step prints the sky, the daylight at
//! the sensor and on the work plane, and for each controller its reading, its levels, their
//! power and the work plane's illuminance and relative error with them:
//!
//! ```text
//! harvest setup date <YYYY-MM-DD> sky cie <type> target <lux> sensor <s> zone <z>
//! harvest night sensor <lux> zone <lux> ratio <S₁/W₁> setpoint <lux>
//! harvest step <k> time <YYYY-MM-DDTHH:MM±HH:MM> altitude <deg> azimuth <deg> diffuse_horizontal <lux> sensor_daylight <lux> zone_daylight <lux>
//! harvest model <k> reading <lux> estimate <lux> ambient <lux> levels <l...> power <W> work_plane <lux> error <e>
//! harvest closed <k> reading <lux> level <l> power <W> work_plane <lux> error <e>
//! ```
//!
//! `altitude` and `azimuth` are the runtime's (`f32`, degrees); `estimate` the model's
//! daylight at the sensor and `ambient` its daylight on the work plane; `error` is
//! `work_plane / target − 1`; a controller's `reading` is its photosensor's before it sets
//! that step's levels. The `harvest closed` reading settles at the set point while the level
//! is within (0, 1).

use cortex_m_semihosting::hprintln;
use eigenrad_runtime::sky::cie::CieSky;
use eigenrad_runtime::{Basis, ChannelEvaluator, DaylightEvaluator, Error, LevelProblem, Output};

use crate::control::{self, TARGET, WATTS};
use crate::daylight::{runtime_position, Moment};
use crate::{Fail, Line, CHANNELS, OUTPUTS};

/// The day, local: the March equinox of 2026, when the sun's noon altitude is the site's
/// colatitude.
pub const DATE: (i32, u32, u32) = (2026, 3, 20);
/// The first and the last step, minutes after local midnight, and the minutes between steps:
/// office hours, 08:00 to 16:00, hourly.
pub const FIRST_MINUTE: u32 = 8 * 60;
pub const LAST_MINUTE: u32 = 16 * 60;
pub const STEP_MINUTES: u32 = 60;
/// The CIE standard general sky type: 1, overcast with a steep gradation and no sun
/// (CIE S 011/E:2003); its luminance does not depend on the sun's azimuth.
pub const SKY_TYPE: u8 = 1;
/// Sky patches the evaluator holds: Tregenza's 145.
const SKY: usize = crate::daylight::SKY;

/// The diffuse horizontal illuminance of an overcast sky with the sun in direction `sun` (a
/// unit vector, z up), lux: `300 + 21 000 sin(altitude)` (J. Krochmann and M. Seidl,
/// "Quantitative data on daylight for illuminating engineering", Lighting Research and
/// Technology 6(3), 1974, the mean of measured overcast skies that DIN 5034-2 adopts); 300
/// lux with the sun at the horizon, 21 300 at the zenith.
pub fn overcast_diffuse_horizontal(sun: [f32; 3]) -> f32 {
    300.0 + 21_000.0 * sun[2].max(0.0)
}

/// The day of both controllers; nothing for a basis without a sensor, a zone or a dimmed
/// channel.
#[inline(never)]
pub fn run(basis: Basis<'_>) -> Result<(), Fail> {
    let (Some(site), Some(patches), Some(plant)) =
        (basis.site(), basis.sky_patches(), control::plant(&basis))
    else {
        return Ok(());
    };
    let dimmed = plant.dimmed();
    let weights = WATTS
        .get(..dimmed.len())
        .ok_or(Fail::Board("too many channels"))?;
    let mut problem = LevelProblem::new(weights)?;
    let mut day = DaylightEvaluator::<SKY, OUTPUTS, 0>::new(basis)?;
    let mut model = ChannelEvaluator::<1, CHANNELS>::new(basis)?;
    let mut closed = ChannelEvaluator::<1, CHANNELS>::new(basis)?;
    let (year, month, date) = DATE;
    hprintln!(
        "harvest setup date {:04}-{:02}-{:02} sky cie {} target {:e} sensor {} zone {}",
        year,
        month,
        date,
        SKY_TYPE,
        TARGET,
        plant.sensor,
        plant.zone
    );

    // Commissioning at night: every luminaire at 1, no daylight (the daylight evaluator is
    // dark until its first sky).
    for &c in dimmed {
        model.set_channel_level(c, 1.0)?;
        closed.set_channel_level(c, 1.0)?;
    }
    let night_sensor = day.sensor_total(plant.sensor, &closed)?;
    let night_zone = day.zone_total(plant.zone, &closed)?;
    if !(night_sensor > 0.0 && night_zone > 0.0) {
        return Err(Fail::Board(
            "the luminaires light neither the sensor nor the work plane",
        ));
    }
    let ratio = night_sensor / night_zone;
    let setpoint = ratio * TARGET;
    hprintln!(
        "harvest night sensor {:e} zone {:e} ratio {:e} setpoint {:e}",
        night_sensor,
        night_zone,
        ratio,
        setpoint
    );

    let mut centres = [[0.0f32; 3]; SKY];
    let mut luminance = [0.0f32; SKY];
    let count = patches.count();
    let capacity = Fail::Runtime(Error::Capacity {
        what: "sky patches",
        needed: count,
        capacity: SKY,
    });
    let (Some(centres), Some(luminance)) = (centres.get_mut(..count), luminance.get_mut(..count))
    else {
        return Err(capacity);
    };
    patches.centres(centres)?;
    let offset = libm::roundf(site.utc_offset_minutes) as i32;
    let mut level = 1.0f32;
    let mut levels = [0.0f32; CHANNELS];
    let levels = levels.get_mut(..dimmed.len()).unwrap_or(&mut []);
    for (k, minute) in (FIRST_MINUTE..=LAST_MINUTE)
        .step_by(STEP_MINUTES as usize)
        .enumerate()
    {
        // The sky of the moment, by the runtime alone.
        let moment = Moment {
            year,
            month,
            day: date,
            minute,
            offset,
        };
        let sun = runtime_position(&site, moment)?;
        let diffuse = overcast_diffuse_horizontal(sun.direction);
        let overcast = CieSky::standard(SKY_TYPE, sun.direction)?;
        let zenith = overcast.zenith_luminance_for(diffuse)?;
        patches.luminances_at(centres, &overcast, zenith, luminance)?;
        day.set_sky(luminance, diffuse, None)?;
        let sensor_daylight = day.sensor_illuminance(plant.sensor)?;
        let zone_daylight = day.zone_illuminance(plant.zone)?;
        hprintln!(
            "harvest step {} time {} altitude {:e} azimuth {:e} diffuse_horizontal {:e} \
             sensor_daylight {:e} zone_daylight {:e}",
            k,
            moment,
            sun.altitude,
            sun.azimuth,
            diffuse,
            sensor_daylight,
            zone_daylight
        );

        // The model's controller: its sensor's daylight, carried to the work plane by the
        // sky's own ratio.
        let reading = day.sensor_total(plant.sensor, &model)?;
        let [electric] = model.sensor_irradiance(plant.sensor)?;
        let estimate = reading - electric;
        let ambient = if sensor_daylight > 0.0 {
            estimate * (zone_daylight / sensor_daylight)
        } else {
            zone_daylight
        };
        problem.clear_bounds();
        problem.add_output_bound(
            &basis,
            dimmed,
            Output::Zone(plant.zone),
            ambient,
            TARGET,
            f32::INFINITY,
        )?;
        match problem.solve(levels) {
            // Short of the target even at full: the closest levels, printed as they are.
            Ok(_) | Err(Error::BoundUnmet { .. }) => {}
            Err(e) => return Err(e.into()),
        }
        for (&c, &l) in dimmed.iter().zip(levels.iter()) {
            model.set_channel_level(c, l)?;
        }
        let plane = day.zone_total(plant.zone, &model)?;
        hprintln!(
            "harvest model {} reading {:e} estimate {:e} ambient {:e} levels{} power {:e} \
             work_plane {:e} error {:e}",
            k,
            reading,
            estimate,
            ambient,
            Line::of(levels),
            problem.power(levels)?,
            plane,
            plane / TARGET - 1.0
        );

        // The conventional controller: its sensor to the night's set point.
        let reading = day.sensor_total(plant.sensor, &closed)?;
        level = (level + (setpoint - reading) / night_sensor).clamp(0.0, 1.0);
        for &c in dimmed {
            closed.set_channel_level(c, level)?;
        }
        let plane = day.zone_total(plant.zone, &closed)?;
        let power: f32 = weights.iter().map(|w| w * level).sum();
        hprintln!(
            "harvest closed {} reading {:e} level {:e} power {:e} work_plane {:e} error {:e}",
            k,
            reading,
            level,
            power,
            plane,
            plane / TARGET - 1.0
        );
    }
    Ok(())
}
