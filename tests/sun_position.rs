//! The runtime's single-precision sun position (`eigenrad_runtime::sky::sun`) against the
//! host's NREL SPA (`eigenrad_precompute::daylight::sun`, `solar-positioning` in `f64`,
//! ±0.0003°), both refracted by the same standard atmosphere (1013.25 mbar, 15 °C), over
//! 2000 to 2100.

use eigenrad_precompute::daylight::sun::{self as spa, Site, SunOptions};
use eigenrad_runtime::sky::sun::{position, Utc};

/// The bound the runtime's documentation states, degrees.
const BOUND: f64 = 0.05;

/// Angle between two directions given by altitude and azimuth (degrees), degrees: the error
/// that matters for a sky, free of the azimuth's blow-up near the zenith.
fn separation(alt_a: f64, az_a: f64, alt_b: f64, az_b: f64) -> f64 {
    let (a1, z1, a2, z2) = (
        alt_a.to_radians(),
        az_a.to_radians(),
        alt_b.to_radians(),
        az_b.to_radians(),
    );
    let cos = a1.sin() * a2.sin() + a1.cos() * a2.cos() * (z1 - z2).cos();
    cos.clamp(-1.0, 1.0).acos().to_degrees()
}

/// A small deterministic generator (SplitMix64) for the instants: the test needs no
/// dependency and gives the same instants on every run.
struct SplitMix(u64);

impl SplitMix {
    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^ (z >> 31)
    }
    /// Uniform in [0, 1).
    fn unit(&mut self) -> f64 {
        (self.next() >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// 20 000 instants spread at random over 2000-01-01 to 2100-12-31 (any second of the day),
/// each at a random site (latitude −66° to 70°, any longitude): wherever SPA's sun is above
/// −0.5° (daylight and the horizon, where refraction is steep), the runtime's direction is
/// within 0.05° of SPA's and its altitude too. Prints the largest separation and altitude
/// error seen, and how many instants were compared.
#[test]
fn within_bound_of_spa_2000_to_2100() {
    let mut rng = SplitMix(0x5eed_2000_2100);
    let (mut worst, mut worst_altitude, mut compared) = (0.0f64, 0.0f64, 0);
    for _ in 0..20_000 {
        let year = 2000 + (rng.next() % 101) as i32;
        let month = 1 + (rng.next() % 12) as u8;
        let day = 1 + (rng.next() % 28) as u8;
        let second = (rng.next() % 86_400) as u32;
        let latitude = -66.0 + 136.0 * rng.unit();
        let longitude = -180.0 + 360.0 * rng.unit();
        let text = format!(
            "{year:04}-{month:02}-{day:02}T{:02}:{:02}:{:02}Z",
            second / 3600,
            second / 60 % 60,
            second % 60
        );
        let site = Site {
            latitude,
            longitude,
            elevation: 0.0,
        };
        let reference = spa::position(
            &site,
            &spa::parse_time(&text).unwrap(),
            &SunOptions::default(),
        )
        .unwrap();
        if reference.altitude < -0.5 {
            continue;
        }
        let ours = position(
            latitude as f32,
            longitude as f32,
            Utc {
                year,
                month,
                day,
                seconds: second as f32,
            },
        )
        .unwrap();
        let (alt, az) = (f64::from(ours.altitude), f64::from(ours.azimuth));
        let gap = separation(alt, az, reference.altitude, reference.azimuth);
        let altitude_gap = (alt - reference.altitude).abs();
        assert!(
            gap <= BOUND && altitude_gap <= BOUND,
            "{text} at ({latitude:.3}, {longitude:.3}): ours {alt:.4}° {az:.4}°, SPA {:.4}° {:.4}° ({gap:.4}°)",
            reference.altitude,
            reference.azimuth
        );
        // The direction is the altitude and azimuth's.
        let d = ours.direction;
        let (x, y, z) = (f64::from(d[0]), f64::from(d[1]), f64::from(d[2]));
        let d_alt = z.atan2(x.hypot(y)).to_degrees();
        let d_az = x.atan2(y).to_degrees().rem_euclid(360.0);
        assert!(
            separation(d_alt, d_az, alt, az) <= 1.0e-4,
            "{text}: direction {d:?}"
        );
        worst = worst.max(gap);
        worst_altitude = worst_altitude.max(altitude_gap);
        compared += 1;
    }
    println!(
        "runtime sun position against SPA, 2000-2100: {compared} instants, largest separation \
         {worst:.5}°, largest altitude error {worst_altitude:.5}°"
    );
    assert!(compared > 8000, "only {compared} instants with the sun up");
}

/// Local time converts by the UTC offset alone: noon in Vienna at UTC+1 is 11:00 UTC, and
/// the runtime gives the same sun for the date with seconds 12 h − 1 h and for the day
/// before with 36 h − 1 h; both against SPA at 2026-06-21T12:00+01:00.
#[test]
fn local_time_through_the_offset() {
    let site = Site {
        latitude: 48.21,
        longitude: 16.37,
        elevation: 0.0,
    };
    let reference = spa::position(
        &site,
        &spa::parse_time("2026-06-21T12:00+01:00").unwrap(),
        &SunOptions::default(),
    )
    .unwrap();
    for (day, hours) in [(21u8, 11.0f32), (20, 35.0)] {
        let p = position(
            48.21,
            16.37,
            Utc {
                year: 2026,
                month: 6,
                day,
                seconds: hours * 3600.0,
            },
        )
        .unwrap();
        let gap = separation(
            f64::from(p.altitude),
            f64::from(p.azimuth),
            reference.altitude,
            reference.azimuth,
        );
        assert!(gap <= BOUND, "day {day}: {gap}°");
    }
}
