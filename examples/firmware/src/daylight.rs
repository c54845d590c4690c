//! The firmware through days of daylight, on a basis that carries it (built only then: see
//! `build.rs`).
//!
//! For each date of [`DATES`], at the basis' site and in its local standard time (the
//! basis' UTC offset), every [`STEP_MINUTES`] minutes from midnight on, the loop
//!
//! 1. computes the sun's position with the `solar-positioning` crate (NREL's SPA, the crate
//!    and the settings `eigenrad` uses on the host: ΔT estimated from the year and month,
//!    refraction in a standard atmosphere of 1013.25 mbar and 15 °C, the site's elevation),
//!    in `f64`, which the Cortex-M4F does in software; steps with the sun at or below the
//!    horizon are skipped, so the day runs from the first step after sunrise to the last
//!    before sunset;
//! 2. builds the sky of that moment in the runtime, all in `f32`: the sun's direction from
//!    its altitude and azimuth (`sky::direction`), the CIE standard general sky type 12
//!    (clear, [`SKY_TYPE`]) for that sun, scaled to a fixed diffuse horizontal illuminance
//!    [`DIFFUSE_HORIZONTAL`] (`CieSky::zenith_luminance_for`), with a sun of a fixed direct
//!    normal illuminance [`DIRECT_NORMAL`]: one weather state all day, the sky's shape and
//!    the sun moving with the sun's position, as
//!    `eigenrad eval --cie 12 --dhi-lux 10000 --dni-lux 60000` has it;
//! 3. fills every sky patch's luminance (`SkyPatches::luminances_at`, from the patches'
//!    centres computed once before the loop), takes the global
//!    horizontal illuminance `E_dh + E_n sin(altitude)` and calls `set_sky` on a
//!    `DaylightEvaluator` without modes (`MODES` = 0, the state a controller that reads
//!    sensors, zones and grids needs) and on one with modes (patch exitance); the two must
//!    read the same sensors and zones to the bit, else the firmware stops with an error;
//! 4. prints every sensor's and zone's daylight illuminance and the daylight figures of
//!    every zone's calculation grid.
//!
//! At each step it also computes the sun's position with the runtime alone
//! (`sky::sun::position`, single precision) and prints it beside SPA's. Then it times a
//! daylight update plus the read of every output on both evaluators, the sky and its patch
//! luminances, both suns' positions, and a whole sky update as a controller without SPA
//! makes it.
//!
//! Output, after the records of `main.rs` and `control.rs`:
//!
//! ```text
//! daylight setup sky cie <type> diffuse_horizontal <lux> direct_normal <lux> sky_patches <n> nodes <D> sun_nodes <s>
//! daylight site latitude <deg> longitude <deg> elevation <m> utc_offset_minutes <min>
//! daylight_evaluator size_of <bytes> ram_bytes <bytes> capacity <sky> <outputs> <modes>
//! daylight zone work_plane <z>                         the zone a controller keeps
//! daylight step <k> time <YYYY-MM-DDTHH:MM+HH:MM> altitude <deg> azimuth <deg> global_horizontal <lux>
//! daylight sun_runtime <k> altitude <deg> azimuth <deg>  the runtime's own sun position (f32)
//! daylight reading <k> sensor <name> <lux>
//! daylight reading <k> zone <name> <lux>
//! daylight figures <k> average <lux> minimum <lux> maximum <lux> uniformity <u> zone <name>
//! timing <what> reps <r> ticks <t> baseline_ticks <t0>
//! instructions <what> <per call>                       see `measure`
//! ```
//!
//! `daylight_evaluator` is printed twice, without modes (capacity `... 0`) and with. The
//! altitude (apparent, degrees above the horizon) and azimuth (degrees clockwise from north)
//! are the sun's as SPA gives them, in `f64` (`{:e}` reads back to the same `f64`); the time
//! is the step's local time with the site's UTC offset, the form `eigenrad eval --time`
//! reads. `daylight zone work_plane` is the zone named `work_plane`, else zone 0 (absent
//! without zones). Readings are of daylight alone, lux: a controller adds the electric
//! light of its channel evaluator.

use core::hint::black_box;

use cortex_m_semihosting::hprintln;
use eigenrad_runtime::sky;
use eigenrad_runtime::sky::cie::CieSky;
use eigenrad_runtime::sky::patches::SkyPatches;
use eigenrad_runtime::{Basis, DaylightEvaluator, Error, Sun};
use solar_positioning::time::JulianDate;
use solar_positioning::{delta_t, Location, RefractionCorrection, SolarPositions};

use crate::timing::{Calibration, Ticks};
use crate::OUTPUTS;

/// The dates of the day loop, local: the summer and the winter solstice of 2026.
pub const DATES: [(i32, u32, u32); 2] = [(2026, 6, 21), (2026, 12, 21)];
/// Minutes between the steps of a day.
pub const STEP_MINUTES: u32 = 30;
/// The CIE standard general sky type: 12, the clear sky (CIE S 011/E:2003).
pub const SKY_TYPE: u8 = 12;
/// Diffuse horizontal illuminance of the sky, lux.
pub const DIFFUSE_HORIZONTAL: f32 = 10_000.0;
/// Direct normal illuminance of the sun, lux.
pub const DIRECT_NORMAL: f32 = 60_000.0;
/// Sky patches the evaluators hold: Tregenza's 145 (a basis built with a finer sky, MF:2 or
/// more, is refused with a capacity error).
pub const SKY: usize = 145;
/// Modes of the evaluator with patch exitance: as the channel firmware's `Evaluator`.
pub const MODES: usize = crate::MODES;
/// Standard atmosphere for the refraction correction, as the host's: mbar, °C.
const PRESSURE: f64 = 1013.25;
const TEMPERATURE: f64 = 15.0;
/// Repetitions of the timed daylight updates (cheap) and of the sky and the sun (dearer).
const REPS: u32 = 1000;
const REPS_SKY: u32 = 100;
const REPS_SUN: u32 = 20;
/// The two moments the timed updates alternate between: hours after local midnight of the
/// first date, morning and afternoon sun.
const TIMED_HOURS: [u32; 2] = [10, 14];

/// Why the day stopped.
pub enum Fail {
    /// The runtime refused the basis or an input.
    Runtime(Error),
    /// The sun's position could not be computed.
    Sun(solar_positioning::Error),
    /// The two evaluators read different values at a step.
    Disagree(usize),
}

impl From<Error> for Fail {
    fn from(e: Error) -> Self {
        Fail::Runtime(e)
    }
}

impl From<solar_positioning::Error> for Fail {
    fn from(e: solar_positioning::Error) -> Self {
        Fail::Sun(e)
    }
}

impl core::fmt::Display for Fail {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            Fail::Runtime(e) => write!(f, "runtime: {e}"),
            Fail::Sun(e) => write!(f, "sun position: {e}"),
            Fail::Disagree(step) => write!(
                f,
                "step {step}: the evaluator with modes reads otherwise than the one without"
            ),
        }
    }
}

type Plain<'a> = DaylightEvaluator<'a, SKY, OUTPUTS, 0>;
type Modal<'a> = DaylightEvaluator<'a, SKY, OUTPUTS, MODES>;

/// A local date and time at the site.
#[derive(Clone, Copy)]
pub struct Moment {
    pub year: i32,
    pub month: u32,
    pub day: u32,
    /// Minutes after local midnight.
    pub minute: u32,
    /// Local time minus UTC, minutes.
    pub offset: i32,
}

impl core::fmt::Display for Moment {
    /// `2026-06-21T12:30+01:00`.
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        let sign = if self.offset < 0 { '-' } else { '+' };
        let offset = self.offset.unsigned_abs();
        write!(
            f,
            "{:04}-{:02}-{:02}T{:02}:{:02}{}{:02}:{:02}",
            self.year,
            self.month,
            self.day,
            self.minute / 60,
            self.minute % 60,
            sign,
            offset / 60,
            offset % 60
        )
    }
}

/// The sun at a moment: SPA's apparent altitude and azimuth, degrees.
#[derive(Clone, Copy)]
struct Position {
    altitude: f64,
    azimuth: f64,
}

impl Position {
    /// The sun as the daylight evaluator takes it: its direction in the site's frame, built
    /// in `f32` from the angles as the host builds it.
    fn sun(&self) -> Sun {
        Sun {
            direction: sky::direction(
                self.altitude.to_radians() as f32,
                self.azimuth.to_radians() as f32,
            ),
            direct_normal: DIRECT_NORMAL,
        }
    }

    /// `E_dh + E_n sin(altitude)`, lux: the unobstructed sky and sun on the ground, in `f64`
    /// as the host sums it.
    fn global_horizontal(&self) -> f32 {
        let sin = libm::sin(self.altitude.to_radians());
        (f64::from(DIFFUSE_HORIZONTAL) + f64::from(DIRECT_NORMAL) * sin) as f32
    }
}

/// Days from 1970-01-01 to the proleptic Gregorian date `(year, month, day)` (H. Hinnant's
/// `days_from_civil`).
fn days_from_civil(year: i32, month: u32, day: u32) -> i64 {
    let y = i64::from(year) - i64::from(month <= 2);
    let era = y.div_euclid(400);
    let yoe = y - era * 400;
    let m = i64::from(month);
    let doy = (153 * (if m > 2 { m - 3 } else { m + 9 }) + 2) / 5 + i64::from(day) - 1;
    let doe = yoe * 365 + yoe / 4 - yoe / 100 + doy;
    era * 146_097 + doe - 719_468
}

/// The sun's position at `moment` from `site`: the Julian date from the Unix time, as the
/// host's `chrono` path forms it, ΔT from the local year and month.
fn position(site: &eigenrad_runtime::Site, moment: Moment) -> Result<Position, Fail> {
    let seconds = days_from_civil(moment.year, moment.month, moment.day) * 86_400
        + i64::from(moment.minute) * 60
        - i64::from(moment.offset) * 60;
    let dt = delta_t::estimate_from_date(moment.year, moment.month)?;
    let time = JulianDate::new(2_440_587.5 + seconds as f64 / 86_400.0, dt)?;
    let location = Location {
        latitude: f64::from(site.latitude),
        longitude: f64::from(site.longitude),
    };
    let refraction = RefractionCorrection::new(PRESSURE, TEMPERATURE)?;
    let p = SolarPositions::new().at_from_julian(
        time,
        location,
        f64::from(site.elevation),
        Some(refraction),
    )?;
    Ok(Position {
        altitude: p.elevation_angle(),
        azimuth: p.azimuth(),
    })
}

/// The clear sky of the sun in `direction` and every patch's luminance (cd/m²) into `out`,
/// from the patches' centres computed once (`SkyPatches::centres`).
fn sky_luminances(
    patches: SkyPatches,
    centres: &[[f32; 3]],
    direction: [f32; 3],
    out: &mut [f32],
) -> Result<(), Error> {
    let sky = CieSky::standard(SKY_TYPE, direction)?;
    let zenith = sky.zenith_luminance_for(DIFFUSE_HORIZONTAL)?;
    patches.luminances_at(centres, &sky, zenith, out)
}

/// The sun's position at `moment` from `site` by the runtime alone
/// (`eigenrad_runtime::sky::sun`, `f32`): the controller's way, without SPA.
pub fn runtime_position(
    site: &eigenrad_runtime::Site,
    moment: Moment,
) -> Result<sky::sun::Position, Error> {
    sky::sun::position(
        site.latitude,
        site.longitude,
        sky::sun::Utc {
            year: moment.year,
            month: moment.month as u8,
            day: moment.day as u8,
            seconds: ((moment.minute as i32 - moment.offset) * 60) as f32,
        },
    )
}

/// The day loop and the timings, on a one-band basis that carries daylight.
#[inline(never)]
pub fn run(basis: Basis<'_>, ticks: &mut Ticks, calibration: Calibration) -> Result<(), Fail> {
    let (Some(site), Some(patches)) = (basis.site(), basis.sky_patches()) else {
        return Ok(());
    };
    let mut plain = Plain::new(basis)?;
    let mut modal = Modal::new(basis)?;
    hprintln!(
        "daylight setup sky cie {} diffuse_horizontal {:e} direct_normal {:e} sky_patches {} \
         nodes {} sun_nodes {}",
        SKY_TYPE,
        DIFFUSE_HORIZONTAL,
        DIRECT_NORMAL,
        patches.count(),
        basis.daylight_node_count(),
        basis.sun_node_count()
    );
    hprintln!(
        "daylight site latitude {:e} longitude {:e} elevation {:e} utc_offset_minutes {:e}",
        site.latitude,
        site.longitude,
        site.elevation,
        site.utc_offset_minutes
    );
    hprintln!(
        "daylight_evaluator size_of {} ram_bytes {} capacity {} {} 0",
        core::mem::size_of_val(&plain),
        Plain::RAM_BYTES,
        SKY,
        OUTPUTS
    );
    hprintln!(
        "daylight_evaluator size_of {} ram_bytes {} capacity {} {} {}",
        core::mem::size_of_val(&modal),
        Modal::RAM_BYTES,
        SKY,
        OUTPUTS,
        MODES
    );
    let work_plane = basis.find_zone("work_plane").unwrap_or(0);
    if work_plane < basis.zone_count() {
        hprintln!("daylight zone work_plane {}", work_plane);
    }

    let offset = libm::roundf(site.utc_offset_minutes) as i32;
    // The patches' geometry, once for the basis.
    let mut centres = [[0.0f32; 3]; SKY];
    let centres = centres.get_mut(..patches.count()).ok_or(Error::Capacity {
        what: "sky patches",
        needed: patches.count(),
        capacity: SKY,
    })?;
    patches.centres(centres)?;
    let centres = &*centres;
    let mut luminance = [0.0f32; SKY];
    let luminance = luminance
        .get_mut(..patches.count())
        .ok_or(Error::Capacity {
            what: "sky patches",
            needed: patches.count(),
            capacity: SKY,
        })?;
    let mut step = 0usize;
    for (year, month, day) in DATES {
        for minute in (0..24 * 60).step_by(STEP_MINUTES as usize) {
            let moment = Moment {
                year,
                month,
                day,
                minute,
                offset,
            };
            let sun = position(&site, moment)?;
            if sun.altitude <= 0.0 {
                continue;
            }
            sky_luminances(patches, centres, sun.sun().direction, luminance)?;
            let global = sun.global_horizontal();
            plain.set_sky(luminance, global, Some(sun.sun()))?;
            modal.set_sky(luminance, global, Some(sun.sun()))?;
            hprintln!(
                "daylight step {} time {} altitude {:e} azimuth {:e} global_horizontal {:e}",
                step,
                moment,
                sun.altitude,
                sun.azimuth,
                global
            );
            let ours = runtime_position(&site, moment)?;
            hprintln!(
                "daylight sun_runtime {} altitude {:e} azimuth {:e}",
                step,
                ours.altitude,
                ours.azimuth
            );
            report(&plain, &modal, step)?;
            step += 1;
        }
    }
    measure(
        &site,
        patches,
        centres,
        &mut plain,
        &mut modal,
        ticks,
        calibration,
        offset,
    )
}

/// Prints every sensor's and zone's daylight and every grid's figures after step `step`,
/// and checks that the evaluator with modes reads the same outputs.
fn report(plain: &Plain<'_>, modal: &Modal<'_>, step: usize) -> Result<(), Fail> {
    let basis = *plain.basis();
    let mut same = true;
    for s in 0..basis.sensor_count() {
        let e = plain.sensor_illuminance(s)?;
        same &= e == modal.sensor_illuminance(s)?;
        hprintln!(
            "daylight reading {} sensor {} {:e}",
            step,
            basis.sensor_name(s)?,
            e
        );
    }
    for z in 0..basis.zone_count() {
        let e = plain.zone_illuminance(z)?;
        same &= e == modal.zone_illuminance(z)?;
        hprintln!(
            "daylight reading {} zone {} {:e}",
            step,
            basis.zone_name(z)?,
            e
        );
    }
    for z in 0..basis.zone_count() {
        if basis.grid_points(z)? == 0 {
            continue;
        }
        let f = plain.zone_figures(z)?;
        hprintln!(
            "daylight figures {} average {:e} minimum {:e} maximum {:e} uniformity {:e} zone {}",
            step,
            f.average,
            f.minimum,
            f.maximum,
            f.uniformity,
            basis.zone_name(z)?
        );
    }
    if same {
        Ok(())
    } else {
        Err(Fail::Disagree(step))
    }
}

/// Counts instructions per call, set against an empty loop of the same shape:
///
/// - `daylight_update_read_outputs`: `set_sky` on the evaluator without modes, then every
///   sensor's and zone's daylight; `daylight_update_read_outputs_modes`: the same on the
///   evaluator with modes (the basis' `p` amplitudes summed too). The updates alternate
///   between two skies ([`TIMED_HOURS`]) that differ in every patch and in the sun;
/// - `daylight_sky`: the clear sky for a sun (`CieSky::standard`) and its zenith luminance
///   for the diffuse horizontal illuminance (`zenith_luminance_for`, a 512-point
///   quadrature); `daylight_sky_luminances`: every patch's luminance from the centres
///   computed once (`SkyPatches::luminances_at`);
/// - `daylight_sun_position`: the Julian date, ΔT and SPA's position of one moment (`f64`
///   in software); `daylight_sun_position_runtime`: the runtime's own (`sky::sun::position`,
///   `f32`);
/// - `daylight_sky_update`: all a controller without SPA does for a new sky state: the
///   runtime's sun position, the clear sky, its patch luminances, `set_sky` and the read of
///   every sensor and zone (on the evaluator without modes).
#[allow(clippy::too_many_arguments)]
fn measure(
    site: &eigenrad_runtime::Site,
    patches: SkyPatches,
    centres: &[[f32; 3]],
    plain: &mut Plain<'_>,
    modal: &mut Modal<'_>,
    ticks: &mut Ticks,
    calibration: Calibration,
    offset: i32,
) -> Result<(), Fail> {
    let basis = *plain.basis();
    let (year, month, day) = DATES[0];
    let moment = |hour: u32| Moment {
        year,
        month,
        day,
        minute: hour * 60,
        offset,
    };
    let moments = TIMED_HOURS.map(moment);
    let mut suns = [Position {
        altitude: 0.0,
        azimuth: 0.0,
    }; 2];
    let mut luminances = [[0.0f32; SKY]; 2];
    for ((sun, lum), &m) in suns.iter_mut().zip(&mut luminances).zip(&moments) {
        *sun = position(site, m)?;
        let lum = lum.get_mut(..patches.count()).unwrap_or(&mut []);
        sky_luminances(patches, centres, sun.sun().direction, lum)?;
    }
    let lum = |i: u32| -> &[f32] {
        let k = (i % 2) as usize;
        luminances
            .get(k)
            .and_then(|l| l.get(..patches.count()))
            .unwrap_or(&[])
    };
    let sun = |i: u32| suns.get((i % 2) as usize).copied().unwrap_or(suns[0]);
    // The update's inputs, computed beforehand: the timed call is `set_sky` and the reads.
    let inputs = |i: u32| (sun(i).global_horizontal(), Some(sun(i).sun()));
    let prepared = [inputs(0), inputs(1)];
    let input = |i: u32| {
        prepared
            .get((i % 2) as usize)
            .copied()
            .unwrap_or(prepared[0])
    };

    let baseline = ticks.count(REPS, |i| {
        black_box(i);
        Ok::<(), Error>(())
    })?;
    let update_plain = ticks.count(REPS, |i| {
        let (global, s) = input(i);
        plain.set_sky(lum(i), global, s)?;
        for o in 0..basis.sensor_count() {
            black_box(plain.sensor_illuminance(o)?);
        }
        for z in 0..basis.zone_count() {
            black_box(plain.zone_illuminance(z)?);
        }
        Ok::<(), Error>(())
    })?;
    let update_modal = ticks.count(REPS, |i| {
        let (global, s) = input(i);
        modal.set_sky(lum(i), global, s)?;
        for o in 0..basis.sensor_count() {
            black_box(modal.sensor_illuminance(o)?);
        }
        for z in 0..basis.zone_count() {
            black_box(modal.zone_illuminance(z)?);
        }
        Ok::<(), Error>(())
    })?;
    let baseline_sky = ticks.count(REPS_SKY, |i| {
        black_box(i);
        Ok::<(), Error>(())
    })?;
    let sky_model = ticks.count(REPS_SKY, |i| {
        let sky = CieSky::standard(SKY_TYPE, black_box(sun(i)).sun().direction)?;
        black_box(sky.zenith_luminance_for(black_box(DIFFUSE_HORIZONTAL))?);
        Ok::<(), Error>(())
    })?;
    let sky = CieSky::standard(SKY_TYPE, sun(0).sun().direction)?;
    let other = CieSky::standard(SKY_TYPE, sun(1).sun().direction)?;
    let zenith = sky.zenith_luminance_for(DIFFUSE_HORIZONTAL)?;
    let mut out = [0.0f32; SKY];
    let out = out.get_mut(..patches.count()).unwrap_or(&mut []);
    let sky_patches = ticks.count(REPS_SKY, |i| {
        let s = if i % 2 == 0 { &sky } else { &other };
        black_box(patches).luminances_at(
            black_box(centres),
            black_box(s),
            black_box(zenith),
            out,
        )?;
        black_box(&*out);
        Ok::<(), Error>(())
    })?;
    let baseline_sun = ticks.count(REPS_SUN, |i| {
        black_box(i);
        Ok::<(), Fail>(())
    })?;
    let sun_position = ticks.count(REPS_SUN, |i| {
        let m = moments.get((i % 2) as usize).copied().unwrap_or(moments[0]);
        black_box(position(black_box(site), black_box(m))?);
        Ok::<(), Fail>(())
    })?;
    let sun_runtime = ticks.count(REPS_SKY, |i| {
        let m = moments.get((i % 2) as usize).copied().unwrap_or(moments[0]);
        black_box(runtime_position(black_box(site), black_box(m))?);
        Ok::<(), Error>(())
    })?;
    // A whole sky update as a controller without SPA makes it: the runtime's sun position,
    // the clear sky and its zenith luminance, the patch luminances, `set_sky` and every
    // sensor's and zone's daylight.
    let mut scratch = [0.0f32; SKY];
    let scratch = scratch.get_mut(..patches.count()).unwrap_or(&mut []);
    let sky_update = ticks.count(REPS_SKY, |i| {
        let m = moments.get((i % 2) as usize).copied().unwrap_or(moments[0]);
        let p = runtime_position(black_box(site), black_box(m))?;
        sky_luminances(patches, centres, p.direction, scratch)?;
        let global = DIFFUSE_HORIZONTAL + DIRECT_NORMAL * p.direction[2].max(0.0);
        let s = Sun {
            direction: p.direction,
            direct_normal: DIRECT_NORMAL,
        };
        plain.set_sky(scratch, global, Some(s))?;
        for o in 0..basis.sensor_count() {
            black_box(plain.sensor_illuminance(o)?);
        }
        for z in 0..basis.zone_count() {
            black_box(plain.zone_illuminance(z)?);
        }
        Ok::<(), Error>(())
    })?;

    for (what, reps, t, base) in [
        ("daylight_update_read_outputs", REPS, update_plain, baseline),
        (
            "daylight_update_read_outputs_modes",
            REPS,
            update_modal,
            baseline,
        ),
        ("daylight_sky", REPS_SKY, sky_model, baseline_sky),
        (
            "daylight_sky_luminances",
            REPS_SKY,
            sky_patches,
            baseline_sky,
        ),
        (
            "daylight_sun_position",
            REPS_SUN,
            sun_position,
            baseline_sun,
        ),
        (
            "daylight_sun_position_runtime",
            REPS_SKY,
            sun_runtime,
            baseline_sky,
        ),
        ("daylight_sky_update", REPS_SKY, sky_update, baseline_sky),
    ] {
        hprintln!(
            "timing {} reps {} ticks {} baseline_ticks {}",
            what,
            reps,
            t,
            base
        );
        let per_call = calibration.instructions_for(t.saturating_sub(base)) / u64::from(reps);
        hprintln!("instructions {} {}", what, per_call);
    }
    Ok(())
}
