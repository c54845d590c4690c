//! The sun's position from a UTC date and time and a site, in `f32` and integer arithmetic
//! alone, for a controller that has nothing but the runtime: within 0.05° of NREL's SPA
//! (Reda and Andreas 2004, which the host uses) from 2000 to 2100; 0.0099° at most over
//! the 10 144 instants with the sun up that `tests/sun_position.rs` compares.
//!
//! The algorithm is the "low accuracy" solar position of J. Meeus, *Astronomical
//! Algorithms* (2nd ed., 1998), chapter 25 (the Sun's mean longitude and anomaly, the
//! equation of the centre, nutation and aberration in longitude, stated to 0.01°), with
//! the sidereal time of chapter 12 (eq. 12.4) and nutation's main term in it (chapter 22),
//! the Sun's parallax (8.794″ at 1 AU), and the refraction SPA applies (Reda and Andreas,
//! eq. 42, after Bennett), for a standard atmosphere of 1013.25 mbar and 15 °C, as the host
//! has it by default.
//!
//! **Single precision.** A day count from 2000 is 36 525 at 2100, where an `f32` resolves
//! 4 × 10⁻³ days (5.6 minutes, 1.4° of the sun's hour angle). So the angles that turn many
//! times in a century (the mean longitude, the mean anomaly, the sidereal time) are summed
//! as fractions of a turn in 64-bit fixed point, where wrapping is reduction modulo one turn
//! and the whole days multiply exactly; only the part within the day and the slow terms are
//! `f32`. The trigonometry is the sky's (`approx`), no `f64` anywhere.
//!
//! **ΔT** (TT − UT) is taken as 69 s, its value in the 2020s: the sun moves along the
//! ecliptic by 0.04° an hour, so ΔT's drift to about 200 s by 2100 moves it by less than
//! 0.002°.

use super::approx;
use crate::error::{Error, Result};

/// A moment in UTC: a calendar date (proleptic Gregorian) and the seconds after that date's
/// midnight, UTC. The seconds may be negative or beyond a day (by up to two days either
/// way), so that a local time converts by subtracting its UTC offset alone:
/// `seconds = local seconds after local midnight − offset minutes × 60`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Utc {
    /// Year, 1900 to 2200 (the algorithm's stated accuracy holds from 2000 to 2100).
    pub year: i32,
    /// Month, 1 to 12.
    pub month: u8,
    /// Day of the month, 1 to the month's length.
    pub day: u8,
    /// Seconds after the date's midnight UTC, s (−172 800 to 172 800).
    pub seconds: f32,
}

/// The sun as seen from a site.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Position {
    /// Apparent altitude above the horizon (refracted), degrees; negative below it.
    pub altitude: f32,
    /// Azimuth, degrees clockwise from true north, 0 to 360.
    pub azimuth: f32,
    /// Unit vector towards the sun in the site's frame (x east, y north, z up), as
    /// [`super::direction`] builds it from the altitude and azimuth: what the sky models and
    /// a [`Sun`](crate::Sun) take.
    pub direction: [f32; 3],
}

/// ΔT = TT − UT, s (see the module documentation).
const DELTA_T: f32 = 69.0;

/// Seconds in a day.
const DAY: f32 = 86_400.0;

/// Days in a Julian century.
const CENTURY: f32 = 36_525.0;

/// The fraction of a turn an angle advances in a day, in units of 2⁻⁶⁴ turn: multiplying
/// it by a whole number of days wraps exactly modulo one turn. Evaluated at compile time.
const fn turns_per_day(degrees_per_day: f64) -> u64 {
    let turns = degrees_per_day / 360.0;
    let fraction = turns - (turns as u64) as f64;
    (fraction * 18_446_744_073_709_551_616.0) as u64
}

/// An angle at 2000-01-01 00:00 (the day count's origin), in units of 2⁻⁶⁴ turn.
const fn turns_at_origin(degrees: f64, degrees_per_day: f64) -> u64 {
    // J2000.0 is half a day later than the origin.
    let turns = (degrees - 0.5 * degrees_per_day) / 360.0;
    let fraction = turns - (turns as i64) as f64;
    let fraction = if fraction < 0.0 {
        fraction + 1.0
    } else {
        fraction
    };
    (fraction * 18_446_744_073_709_551_616.0) as u64
}

/// The Sun's geometric mean longitude (Meeus 25.2): 280.46646° + 36 000.76983° T.
const LONGITUDE_RATE: f64 = 36_000.769_83 / 36_525.0;
/// The Sun's mean anomaly (Meeus 25.3): 357.52911° + 35 999.05029° T.
const ANOMALY_RATE: f64 = 35_999.050_29 / 36_525.0;
/// Greenwich mean sidereal time (Meeus 12.4): 280.46061837° + 360.98564736629° a day.
const SIDEREAL_RATE: f64 = 360.985_647_366_29;

/// `angle(days)` in degrees, in [−180, 180): the angle at the origin plus `days` whole days
/// at `rate`, reduced exactly in fixed point.
fn whole_days(origin: u64, rate: u64, days: i64) -> f32 {
    let turns = origin.wrapping_add((days as u64).wrapping_mul(rate));
    // The top 32 bits as a signed fraction of a turn: 2.3 × 10⁻⁷° resolution.
    ((turns >> 32) as u32 as i32) as f32 * (360.0 / 4_294_967_296.0)
}

/// Days from 2000-01-01 to `year-month-day` (proleptic Gregorian; H. Hinnant's
/// `days_from_civil`), or `None` for a month or day that does not exist.
fn days_from_2000(year: i32, month: u8, day: u8) -> Option<i64> {
    let leap = (year % 4 == 0 && year % 100 != 0) || year % 400 == 0;
    let length = match month {
        1 | 3 | 5 | 7 | 8 | 10 | 12 => 31,
        4 | 6 | 9 | 11 => 30,
        2 if leap => 29,
        2 => 28,
        _ => return None,
    };
    if day == 0 || day > length {
        return None;
    }
    let (m, d) = (i64::from(month), i64::from(day));
    let y = i64::from(year) - i64::from(month <= 2);
    let era = y.div_euclid(400);
    let year_of_era = y - era * 400;
    let day_of_year = (153 * (m + if m > 2 { -3 } else { 9 }) + 2) / 5 + d - 1;
    let day_of_era = year_of_era * 365 + year_of_era / 4 - year_of_era / 100 + day_of_year;
    // 730 425: 2000-01-01 counted from 0000-03-01.
    Some(era * 146_097 + day_of_era - 730_425)
}

/// `x` reduced to [−180, 180) degrees.
fn wrap_degrees(x: f32) -> f32 {
    let turns = x * (1.0 / 360.0);
    let k = (turns + if turns < 0.0 { -0.5 } else { 0.5 }) as i32 as f32;
    x - 360.0 * k
}

/// `(sin, cos)` of an angle in degrees.
fn sin_cos_degrees(x: f32) -> (f32, f32) {
    approx::sin_cos(x.to_radians())
}

/// The sun's apparent position at `time` from the site at `latitude` (degrees north, −90 to
/// 90) and `longitude` (degrees east, −180 to 180), refracted by a standard atmosphere.
/// Within 0.05° of SPA from 2000 to 2100 (the tests check many instants and sites); the
/// algorithm runs in `f32` and 64-bit integers. An input outside its range (a date that
/// does not exist included) is [`Error::OutOfRange`].
pub fn position(latitude: f32, longitude: f32, time: Utc) -> Result<Position> {
    super::check_range(latitude, "site latitude (°)", -90.0, 90.0, "from -90 to 90")?;
    super::check_range(
        longitude,
        "site longitude (°)",
        -180.0,
        180.0,
        "from -180 to 180",
    )?;
    if !(1900..=2200).contains(&time.year) {
        return Err(Error::OutOfRange {
            what: "year of the sun's position",
            range: "from 1900 to 2200",
        });
    }
    let days = days_from_2000(time.year, time.month, time.day).ok_or(Error::OutOfRange {
        what: "date of the sun's position",
        range: "a month from 1 to 12 and a day of that month",
    })?;
    super::check_range(
        time.seconds,
        "seconds after midnight UTC",
        -2.0 * DAY,
        2.0 * DAY,
        "from -172800 to 172800",
    )?;

    // The day's fraction in UT and in TT, and centuries of TT from J2000.0 (for the slow
    // terms only: f32 resolves them to 10⁻⁷ of a century).
    let day_ut = time.seconds / DAY;
    let day_tt = (time.seconds + DELTA_T) / DAY;
    let t = ((days as f32 - 0.5) + day_tt) / CENTURY;

    // Mean longitude and anomaly: whole days in fixed point, the rest in f32.
    let mean_longitude = whole_days(
        const { turns_at_origin(280.466_46, LONGITUDE_RATE) },
        const { turns_per_day(LONGITUDE_RATE) },
        days,
    ) + day_tt * LONGITUDE_RATE as f32
        + 0.000_303_2 * t * t;
    let anomaly = whole_days(
        const { turns_at_origin(357.529_11, ANOMALY_RATE) },
        const { turns_per_day(ANOMALY_RATE) },
        days,
    ) + day_tt * ANOMALY_RATE as f32
        - 0.000_153_7 * t * t;
    let (sin_m, cos_m) = sin_cos_degrees(anomaly);
    let (sin_2m, cos_2m) = (2.0 * sin_m * cos_m, cos_m * cos_m - sin_m * sin_m);
    let sin_3m = sin_2m * cos_m + cos_2m * sin_m;
    // Equation of the centre (Meeus 25, C).
    let centre = (1.914_602 - 0.004_817 * t - 0.000_014 * t * t) * sin_m
        + (0.019_993 - 0.000_101 * t) * sin_2m
        + 0.000_289 * sin_3m;
    // Longitude of the Moon's ascending node, for nutation (Meeus 25, Ω).
    let (sin_node, cos_node) = sin_cos_degrees(wrap_degrees(125.04 - 1934.136 * t));
    // Apparent longitude: aberration (−0.00569°) and nutation (−0.00478° sin Ω).
    let longitude_sun = wrap_degrees(mean_longitude + centre) - 0.005_69 - 0.004_78 * sin_node;
    // Obliquity of the ecliptic, mean (Meeus 22.2, first terms) plus nutation (Meeus 25.8).
    let obliquity = 23.439_291 - 0.013_004_2 * t + 0.002_56 * cos_node;
    let (sin_e, cos_e) = sin_cos_degrees(obliquity);
    let (sin_l, cos_l) = sin_cos_degrees(longitude_sun);
    let right_ascension = approx::atan2(cos_e * sin_l, cos_l).to_degrees();
    let sin_declination = sin_e * sin_l;
    let cos_declination = approx::sqrt(1.0 - sin_declination * sin_declination);

    // Apparent sidereal time: the mean (Meeus 12.4) plus the equation of the equinoxes,
    // nutation in longitude's main term times cos ε (Meeus 22, Δψ ≈ −17.20″ sin Ω).
    let sidereal = whole_days(
        const { turns_at_origin(280.460_618_37, SIDEREAL_RATE) },
        const { turns_per_day(SIDEREAL_RATE) },
        days,
    ) + wrap_degrees(day_ut * SIDEREAL_RATE as f32)
        + 0.000_387_933 * t * t
        - 0.004_78 * sin_node * cos_e;
    let hour = wrap_degrees(sidereal + longitude - right_ascension);

    // Horizontal coordinates, as `sun_grid::direction_of` has them.
    let (sin_phi, cos_phi) = sin_cos_degrees(latitude);
    let (sin_h, cos_h) = sin_cos_degrees(hour);
    let east = -cos_declination * sin_h;
    let north = cos_phi * sin_declination - sin_phi * cos_declination * cos_h;
    let up = sin_phi * sin_declination + cos_phi * cos_declination * cos_h;
    // atan2 rather than asin: asin is steep near the zenith, where f32 would lose 0.02°.
    let geometric = approx::atan2(up, approx::sqrt(east * east + north * north)).to_degrees();
    // The Sun's parallax at 1 AU (8.794″) lowers it; SPA works topocentrically too.
    let topocentric = geometric - 0.002_443 * sin_cos_degrees(geometric).1;
    let altitude = topocentric + refraction(topocentric);
    let mut azimuth = approx::atan2(east, north).to_degrees();
    if azimuth < 0.0 {
        azimuth += 360.0;
    }
    Ok(Position {
        altitude,
        azimuth,
        direction: super::direction(altitude.to_radians(), azimuth.to_radians()),
    })
}

/// Atmospheric refraction (degrees) at true altitude `altitude` (degrees), as SPA applies
/// it (Reda and Andreas 2004, eq. 42): `(P/1010)(283/(273 + T)) · 1.02 / (60 tan(e + 10.3 /
/// (e + 5.11)))` for P = 1013.25 mbar and T = 15 °C, and none with the sun's upper limb
/// below the horizon (e < −0.26667° − 0.5667°).
fn refraction(altitude: f32) -> f32 {
    if altitude < -(0.266_67 + 0.566_7) {
        return 0.0;
    }
    const ATMOSPHERE: f32 = (1013.25 / 1010.0) * (283.0 / (273.0 + 15.0));
    let (sin, cos) = sin_cos_degrees(altitude + 10.3 / (altitude + 5.11));
    ATMOSPHERE * 1.02 * cos / (60.0 * sin)
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, clippy::indexing_slicing)]
    use super::*;

    /// The day count against dates counted by hand: 2000-01-01 is day 0, 2000 is a leap year
    /// (366 days), 2100 is not; 1900-01-01 is 36 524 days before (24 leap years in 1900–1999).
    #[test]
    fn days_from_2000_by_hand() {
        assert_eq!(days_from_2000(2000, 1, 1), Some(0));
        assert_eq!(days_from_2000(2000, 3, 1), Some(31 + 29));
        assert_eq!(days_from_2000(2001, 1, 1), Some(366));
        assert_eq!(days_from_2000(2100, 3, 1), Some(36_525 + 31 + 28));
        assert_eq!(days_from_2000(1900, 1, 1), Some(-36_524));
        assert_eq!(days_from_2000(2100, 2, 29), None);
        assert_eq!(days_from_2000(2024, 2, 29), Some(8825));
        assert_eq!(days_from_2000(2024, 13, 1), None);
        assert_eq!(days_from_2000(2024, 4, 31), None);
        assert_eq!(days_from_2000(2024, 4, 0), None);
    }

    /// Meeus' example 25.a (1992 October 13.0 TD): apparent declination −7.78507°. At that
    /// moment, seen from the equator, the sun's direction's north component is sin δ
    /// whatever the hour angle; the sun is then far below the horizon at Greenwich (no
    /// refraction), and its parallax moves the direction by 0.0003° there. Within 0.001°:
    /// the f32 routine and that parallax.
    #[test]
    fn meeus_example_25a() {
        let time = Utc {
            year: 1992,
            month: 10,
            day: 13,
            seconds: -DELTA_T,
        };
        let p = position(0.0, 0.0, time).unwrap();
        assert!(p.altitude < -10.0, "altitude {}", p.altitude);
        let declination = libm::asinf(p.direction[1]).to_degrees();
        assert!(
            (declination - -7.785_07).abs() <= 1.0e-3,
            "declination {declination}"
        );
    }

    /// Bad inputs are errors, never a panic or a NaN.
    #[test]
    fn bad_inputs_are_refused() {
        let ok = Utc {
            year: 2026,
            month: 6,
            day: 21,
            seconds: 43_200.0,
        };
        assert!(position(48.2, 16.4, ok).is_ok());
        assert!(position(91.0, 0.0, ok).is_err());
        assert!(position(f32::NAN, 0.0, ok).is_err());
        assert!(position(0.0, 181.0, ok).is_err());
        for bad in [
            Utc { year: 1899, ..ok },
            Utc { year: 2201, ..ok },
            Utc { month: 0, ..ok },
            Utc { day: 31, ..ok },
            Utc {
                seconds: f32::NAN,
                ..ok
            },
            Utc {
                seconds: 3.0 * DAY,
                ..ok
            },
        ] {
            assert!(position(0.0, 0.0, bad).is_err(), "{bad:?}");
        }
    }
}
