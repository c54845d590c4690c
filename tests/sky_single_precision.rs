//! The controller's sky in single precision against the same sky in `f64`, on the daylight
//! office (`examples/office-daylight/scene.toml`, built as `eigenrad build` builds it).
//!
//! The runtime's sky models (`eigenrad_runtime::sky`) run in `f32` with polynomial sines,
//! cosines, arccosines and exponentials; the reference here evaluates the same models in
//! `f64` with `std`'s functions, written out in this file from the published formulas:
//! the patch centres from Tregenza's rows, the CIE standard general sky (ISO 15469 Table 1)
//! and the Perez all-weather sky (Perez, Seals and Michalsky 1993, Table 1, with the limits
//! `gendaylit` applies), each scaled to its diffuse horizontal illuminance by the same
//! quadrature the runtime documents (Gauss–Legendre of order 16 in the zenith angle, its
//! nodes computed here by Newton's method, times 32 midpoint steps on the half circle), so
//! that what differs is the precision and nothing of the discretisation. Both skies go
//! through the same `DaylightEvaluator` with the same sun, so every sensor's and zone's
//! daylight differs by what the single-precision sky changes: within [`TOLERANCE`] of the
//! `f64` sky's, at every moment.

use std::f64::consts::{FRAC_PI_2, PI};
use std::path::Path;
use std::sync::OnceLock;

use eigenrad_precompute::daylight::sun::{self as spa, Site, SunOptions};
use eigenrad_precompute::formfactor::FormFactorOptions;
use eigenrad_precompute::pipeline::{self, BuildOptions};
use eigenrad_runtime::sky::cie::{CieSky, STANDARD_TYPES};
use eigenrad_runtime::sky::patches::SkyPatches;
use eigenrad_runtime::sky::perez::{
    clearness_bin, extraterrestrial_irradiance, Conditions, PerezSky, COEFFICIENTS,
};
use eigenrad_runtime::sky::RelativeSky;
use eigenrad_runtime::{Basis, DaylightEvaluator, Sun};

/// Relative difference allowed between a reading under the `f32` sky and under the `f64`
/// one (floored at 1 lux), the target the runtime's sky is held to.
const TOLERANCE: f64 = 1e-4;

/// Direct normal illuminance of the sun at every moment, lux.
const DIRECT_NORMAL: f64 = 60_000.0;

type Evaluator<'a> = DaylightEvaluator<'a, 145, 8, 0>;

/// The daylight office's basis (f32 storage, default settings), built once per run, in
/// process (the code behind `eigenrad build`, optimised as tests are).
fn basis_bytes() -> &'static [u8] {
    static BYTES: OnceLock<Vec<u8>> = OnceLock::new();
    BYTES.get_or_init(|| {
        let scene =
            Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/office-daylight/scene.toml");
        let opts = BuildOptions {
            form_factors: FormFactorOptions {
                cache: None,
                ..FormFactorOptions::default()
            },
            ..BuildOptions::default()
        };
        let (bytes, report) = pipeline::build(&scene, &opts).expect("build");
        assert!(report.daylight.is_some(), "a daylight section");
        bytes
    })
}

/// Gauss–Legendre nodes and weights of order `n` on [−1, 1], by Newton's method on the
/// Legendre polynomial (to 10⁻¹⁵).
fn gauss_legendre(n: usize) -> Vec<(f64, f64)> {
    (1..=n)
        .map(|i| {
            let mut x = (PI * (i as f64 - 0.25) / (n as f64 + 0.5)).cos();
            loop {
                let (mut p0, mut p1) = (1.0, x);
                for k in 2..=n {
                    let k = k as f64;
                    (p0, p1) = (p1, ((2.0 * k - 1.0) * x * p1 - (k - 1.0) * p0) / k);
                }
                let derivative = n as f64 * (x * p1 - p0) / (x * x - 1.0);
                let step = p1 / derivative;
                x -= step;
                if step.abs() < 1e-15 {
                    let w = 2.0 / ((1.0 - x * x) * derivative * derivative);
                    return (x, w);
                }
            }
        })
        .collect()
}

/// `∫ L_rel cos Z dω` over the sky by the runtime's rule, in f64.
fn horizontal_integral(sun: [f64; 3], relative: &dyn Fn([f64; 3]) -> f64) -> f64 {
    let horizontal = sun[0].hypot(sun[1]);
    let (ux, uy) = if horizontal > 1e-6 {
        (sun[0] / horizontal, sun[1] / horizontal)
    } else {
        (0.0, 1.0)
    };
    let step = PI / 32.0;
    let mut total = 0.0;
    for (x, w) in gauss_legendre(16) {
        let zenith = FRAC_PI_2 / 2.0 * (1.0 + x);
        let (sz, cz) = zenith.sin_cos();
        let ring: f64 = (0..32)
            .map(|k| {
                let (sp, cp) = ((k as f64 + 0.5) * step).sin_cos();
                relative([sz * (cp * ux - sp * uy), sz * (cp * uy + sp * ux), cz])
            })
            .sum();
        total += w * FRAC_PI_2 / 2.0 * sz * cz * ring;
    }
    total * 2.0 * step
}

/// The 145 Tregenza patch centres in f64 (rows of 12° from the horizon with 30, 30, 24, 24,
/// 18, 12 and 6 patches from due north eastwards, and the zenith).
fn centres() -> Vec<[f64; 3]> {
    let mut out = Vec::new();
    for (row, n) in [30, 30, 24, 24, 18, 12, 6].into_iter().enumerate() {
        let altitude = (6.0 + 12.0 * row as f64).to_radians();
        for k in 0..n {
            let azimuth = 2.0 * PI * k as f64 / n as f64;
            out.push([
                azimuth.sin() * altitude.cos(),
                azimuth.cos() * altitude.cos(),
                altitude.sin(),
            ]);
        }
    }
    out.push([0.0, 0.0, 1.0]);
    out
}

fn angle(a: [f64; 3], b: [f64; 3]) -> f64 {
    (a[0] * b[0] + a[1] * b[1] + a[2] * b[2])
        .clamp(-1.0, 1.0)
        .acos()
}

/// A CIE standard general sky of type `t`, relative to the zenith, in f64.
fn cie(t: u8, sun: [f64; 3]) -> impl Fn([f64; 3]) -> f64 {
    let p = STANDARD_TYPES[usize::from(t) - 1];
    let [a, b, c, d, e] = [p.a, p.b, p.c, p.d, p.e].map(f64::from);
    let gradation = move |cos_z: f64| {
        if cos_z <= 0.0 {
            1.0
        } else {
            1.0 + a * (b / cos_z).exp()
        }
    };
    let indicatrix =
        move |chi: f64| 1.0 + c * ((d * chi).exp() - (d * FRAC_PI_2).exp()) + e * chi.cos().powi(2);
    let norm = indicatrix(sun[2].acos()) * gradation(1.0);
    move |dir: [f64; 3]| {
        if dir[2] < 0.0 {
            0.0
        } else {
            (indicatrix(angle(dir, sun)) * gradation(dir[2]) / norm).max(0.0)
        }
    }
}

/// The Perez sky of diffuse horizontal and direct normal irradiance (W/m²) for a sun at
/// `sun` on day `day`, relative luminance `l(ζ, γ)`, in f64.
fn perez(dhi: f64, dni: f64, sun: [f64; 3], day: u16) -> impl Fn([f64; 3]) -> f64 {
    let z = sun[2].acos();
    let z3 = 1.041 * z.powi(3);
    let clearness = ((dhi + dni) / dhi + z3) / (1.0 + z3);
    let degrees = z.to_degrees();
    let air_mass = 1.0 / (z.cos() + 0.15 * (93.885 - degrees).powf(-1.253));
    // The eccentricity correction in f64, as the runtime documents it (Spencer 1971).
    let g = 2.0 * PI * (f64::from(day) - 1.0) / 365.0;
    let e0 = 1367.0
        * (1.00011
            + 0.034221 * g.cos()
            + 0.00128 * g.sin()
            + 0.000719 * (2.0 * g).cos()
            + 0.000077 * (2.0 * g).sin());
    assert!((e0 - f64::from(extraterrestrial_irradiance(day))).abs() < 1e-3 * e0);
    let brightness = dhi * air_mass / e0;
    let eps = clearness.clamp(1.0, 12.0);
    let mut delta = brightness.clamp(0.01, 0.6);
    if eps > 1.065 && eps < 2.8 {
        delta = delta.max(0.2);
    }
    let bin = clearness_bin(eps as f32);
    let rows = COEFFICIENTS[bin].map(|r| r.map(f64::from));
    let linear = |x: [f64; 4]| x[0] + x[1] * z + delta * (x[2] + x[3] * z);
    let (c, d) = if bin == 0 {
        let (rc, rd) = (rows[2], rows[3]);
        (
            (delta * (rc[0] + rc[1] * z)).powf(rc[2]).exp() - rc[3],
            -(delta * (rd[0] + rd[1] * z)).exp() + rd[2] + delta * rd[3],
        )
    } else {
        (linear(rows[2]), linear(rows[3]))
    };
    let (a, b, e) = (linear(rows[0]), linear(rows[1]), linear(rows[4]));
    move |dir: [f64; 3]| {
        if dir[2] < 0.0 {
            return 0.0;
        }
        let gradation = if dir[2] > 0.0 {
            1.0 + a * (b / dir[2]).exp()
        } else {
            1.0
        };
        let gamma = angle(dir, sun);
        ((gradation) * (1.0 + c * (d * gamma).exp() + e * gamma.cos().powi(2))).max(0.0)
    }
}

/// Which sky a moment has.
#[derive(Clone, Copy, Debug)]
enum Sky {
    /// CIE standard general sky of this type, diffuse horizontal illuminance (lux).
    Cie(u8, f64),
    /// Perez from diffuse horizontal and direct normal irradiance (W/m²), scaled to this
    /// diffuse horizontal illuminance (lux).
    Perez(f64, f64, f64),
}

/// Every sensor's and zone's daylight under the sky of `luminance` (cd/m², f32), with the
/// global horizontal `global` (lux) and the sun.
fn readings(basis: Basis<'_>, luminance: &[f32], global: f64, sun: Sun) -> Vec<f64> {
    let mut e = Evaluator::new(basis).unwrap();
    e.set_sky(luminance, global as f32, Some(sun)).unwrap();
    let sensors = (0..basis.sensor_count()).map(|s| e.sensor_illuminance(s).unwrap());
    let zones = (0..basis.zone_count()).map(|z| e.zone_illuminance(z).unwrap());
    sensors.chain(zones).map(f64::from).collect()
}

/// At five moments of 2026 in Vienna (the office's site), overcast, clear and Perez skies:
/// every reading under the runtime's f32 sky within 10⁻⁴ of the same under the f64 sky.
#[test]
fn single_precision_sky_reads_as_the_f64_sky() {
    let bytes = basis_bytes();
    let basis = Basis::from_bytes(bytes).unwrap();
    let site = basis.site().unwrap();
    let patches = basis.sky_patches().unwrap();
    assert_eq!(patches, SkyPatches::TREGENZA);
    let mut centres32 = vec![[0.0f32; 3]; patches.count()];
    patches.centres(&mut centres32).unwrap();
    let centres64 = centres();

    let moments = [
        ("2026-12-21T12:00+01:00", Sky::Cie(1, 8_000.0)),
        ("2026-06-21T10:00+01:00", Sky::Cie(12, 10_000.0)),
        ("2026-03-20T16:30+01:00", Sky::Cie(12, 10_000.0)),
        ("2026-06-21T14:00+01:00", Sky::Perez(180.0, 550.0, 20_000.0)),
        ("2026-10-15T09:00+02:00", Sky::Perez(120.0, 0.0, 14_000.0)),
    ];
    let mut worst = 0.0f64;
    for (time, kind) in moments {
        let position = spa::position(
            &Site {
                latitude: f64::from(site.latitude),
                longitude: f64::from(site.longitude),
                elevation: f64::from(site.elevation),
            },
            &spa::parse_time(time).unwrap(),
            &SunOptions::default(),
        )
        .unwrap();
        let (alt, az) = (
            position.altitude.to_radians(),
            position.azimuth.to_radians(),
        );
        let sun64 = [az.sin() * alt.cos(), az.cos() * alt.cos(), alt.sin()];
        let sun32 = sun64.map(|x| x as f32);
        let day = spa::day_of_year(&spa::parse_time(time).unwrap());

        // The runtime's sky, f32, as a controller computes it.
        let mut lum32 = vec![0.0f32; patches.count()];
        let diffuse = match kind {
            Sky::Cie(t, dhi) => {
                let sky = CieSky::standard(t, sun32).unwrap();
                let zenith = sky.zenith_luminance_for(dhi as f32).unwrap();
                patches
                    .luminances_at(&centres32, &sky, zenith, &mut lum32)
                    .unwrap();
                dhi
            }
            Sky::Perez(dhi_w, dni_w, dhi) => {
                let c = Conditions::from_irradiance(
                    dhi_w as f32,
                    dni_w as f32,
                    (FRAC_PI_2 - alt) as f32,
                    day,
                )
                .unwrap();
                let sky = PerezSky::new(&c, sun32).unwrap();
                let scale = sky.luminance_scale(dhi as f32).unwrap();
                patches
                    .luminances_at(&centres32, &sky, scale, &mut lum32)
                    .unwrap();
                assert!(sky.relative_luminance(sun32) > 0.0);
                dhi
            }
        };

        // The same sky in f64.
        let relative: Box<dyn Fn([f64; 3]) -> f64> = match kind {
            Sky::Cie(t, _) => Box::new(cie(t, sun64)),
            Sky::Perez(dhi_w, dni_w, _) => Box::new(perez(dhi_w, dni_w, sun64, day)),
        };
        let scale = diffuse / horizontal_integral(sun64, &*relative);
        let lum64: Vec<f32> = centres64
            .iter()
            .map(|&c| (relative(c) * scale) as f32)
            .collect();
        for (i, (a, b)) in lum32.iter().zip(&lum64).enumerate() {
            let rel = (f64::from(*a) - f64::from(*b)).abs() / f64::from(*b).max(1.0);
            assert!(
                rel <= TOLERANCE,
                "{time} {kind:?}: patch {i}: {a} against {b}"
            );
        }

        let global = diffuse + DIRECT_NORMAL * alt.sin();
        let sun = Sun {
            direction: sun32,
            direct_normal: DIRECT_NORMAL as f32,
        };
        let ours = readings(basis, &lum32, global, sun);
        let reference = readings(basis, &lum64, global, sun);
        assert!(!ours.is_empty());
        for (k, (a, b)) in ours.iter().zip(&reference).enumerate() {
            assert!(*b > 0.0, "{time}: output {k} has no daylight");
            let rel = (a - b).abs() / b.max(1.0);
            assert!(
                rel <= TOLERANCE,
                "{time} {kind:?}: output {k}: {a} lux against {b} lux ({rel:.1e})"
            );
            worst = worst.max(rel);
        }
    }
    println!(
        "f32 sky against the f64 sky, daylight office: largest relative difference {worst:.2e}"
    );
}
