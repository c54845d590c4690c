//! The CIE standard general sky (ISO 15469:2004 / CIE S 011/E:2003) and the traditional CIE
//! overcast sky.
//!
//! A standard general sky's luminance relative to the zenith's is
//!
//! ```text
//! L(Z, χ) / L_z = f(χ) φ(Z) / (f(Z_s) φ(0))
//! φ(Z) = 1 + a exp(b / cos Z)            (gradation; φ(π/2) = 1)
//! f(χ) = 1 + c (exp(d χ) − exp(d π/2)) + e cos² χ   (indicatrix)
//! ```
//!
//! with Z the zenith angle of the sky element, Z_s the sun's and χ the angle between the
//! element and the sun. The 15 types combine six gradation groups (a, b) with six indicatrix
//! groups (c, d, e) as in the standard's Table 1; [`STANDARD_TYPES`] is that table, checked
//! against two public transcriptions (the CIE Lighting Toolbox's `ciesky.m`, F. Rudawski,
//! 2021, and Darula and Kittler, "CIE general sky standard defining luminance
//! distributions", eSim 2002).
//!
//! The traditional CIE overcast sky (CIE 1955, after Moon and Spencer 1942) is
//! `L(Z)/L_z = (1 + 2 cos Z)/3`: three times as bright at the zenith as at the horizon, and
//! `E_h = 7π/9 L_z` exactly. Type 1 is the standard general sky's version of it, with a
//! zenith-to-horizon ratio of `1 + 4 e^(−0.7) = 2.986`.

use super::{angle_between, approx, check_sun, RelativeSky};
use crate::error::{Error, Result};

/// The parameters of one standard sky type: gradation `a`, `b`, indicatrix `c`, `d`, `e`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Parameters {
    /// Gradation: `a`.
    pub a: f32,
    /// Gradation: `b`.
    pub b: f32,
    /// Indicatrix: `c`.
    pub c: f32,
    /// Indicatrix: `d` (1/rad).
    pub d: f32,
    /// Indicatrix: `e`.
    pub e: f32,
}

const fn p(a: f32, b: f32, c: f32, d: f32, e: f32) -> Parameters {
    Parameters { a, b, c, d, e }
}

/// ISO 15469:2004 Table 1: the 15 standard sky types, type `t` at index `t − 1`. Gradation
/// groups I–VI: (4, −0.7), (1.1, −0.8), (0, −1), (−1, −0.55), (−1, −0.32), (−1, −0.15);
/// indicatrix groups 1–6: (0, −1, 0), (2, −1.5, 0.15), (5, −2.5, 0.3), (10, −3, 0.45),
/// (16, −3, 0.3), (24, −2.8, 0.15).
pub const STANDARD_TYPES: [Parameters; 15] = [
    // 1: CIE standard overcast sky, steep gradation towards the zenith, azimuthal uniformity (I.1).
    p(4.0, -0.7, 0.0, -1.0, 0.0),
    // 2: overcast, steep gradation, slight brightening towards the sun (I.2).
    p(4.0, -0.7, 2.0, -1.5, 0.15),
    // 3: overcast, moderately graded, azimuthal uniformity (II.1).
    p(1.1, -0.8, 0.0, -1.0, 0.0),
    // 4: overcast, moderately graded, slight brightening towards the sun (II.2).
    p(1.1, -0.8, 2.0, -1.5, 0.15),
    // 5: sky of uniform luminance (III.1).
    p(0.0, -1.0, 0.0, -1.0, 0.0),
    // 6: partly cloudy, no gradation towards the zenith, slight brightening towards the sun (III.2).
    p(0.0, -1.0, 2.0, -1.5, 0.15),
    // 7: partly cloudy, no gradation, brighter circumsolar region (III.3).
    p(0.0, -1.0, 5.0, -2.5, 0.3),
    // 8: partly cloudy, no gradation, distinct solar corona (III.4).
    p(0.0, -1.0, 10.0, -3.0, 0.45),
    // 9: partly cloudy, obscured sun (IV.2).
    p(-1.0, -0.55, 2.0, -1.5, 0.15),
    // 10: partly cloudy, brighter circumsolar region (IV.3).
    p(-1.0, -0.55, 5.0, -2.5, 0.3),
    // 11: white-blue sky with distinct solar corona (IV.4).
    p(-1.0, -0.55, 10.0, -3.0, 0.45),
    // 12: CIE standard clear sky, low luminance turbidity (V.4).
    p(-1.0, -0.32, 10.0, -3.0, 0.45),
    // 13: CIE standard clear sky, polluted atmosphere (V.5).
    p(-1.0, -0.32, 16.0, -3.0, 0.3),
    // 14: cloudless turbid sky with broad solar corona (VI.5).
    p(-1.0, -0.15, 16.0, -3.0, 0.3),
    // 15: white-blue turbid sky with broad solar corona (VI.6).
    p(-1.0, -0.15, 24.0, -2.8, 0.15),
];

/// Which CIE sky.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Kind {
    /// A standard general sky with these parameters (one of [`STANDARD_TYPES`] for types 1 to 15).
    General(Parameters),
    /// The traditional CIE overcast sky, `(1 + 2 cos Z)/3`, which ignores the sun.
    TraditionalOvercast,
}

/// A CIE sky for one sun position: luminance relative to the zenith's.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CieSky {
    kind: Kind,
    sun: [f32; 3],
    /// `1 / (f(Z_s) φ(0))` for a general sky.
    scale: f32,
    /// `exp(d π/2)` of the indicatrix, the same for every direction (0 for the traditional
    /// overcast sky, which has no indicatrix).
    horizon_term: f32,
}

impl CieSky {
    /// Standard general sky type `sky_type` (1 to 15) with the sun in direction `sun` (unit
    /// vector, z up, at or above the horizon).
    pub fn standard(sky_type: u8, sun: [f32; 3]) -> Result<Self> {
        let index = usize::from(sky_type).wrapping_sub(1);
        let parameters = *STANDARD_TYPES.get(index).ok_or(Error::OutOfRange {
            what: "CIE standard sky type",
            range: "from 1 to 15",
        })?;
        Self::general(parameters, sun)
    }

    /// A general sky with any parameters (for a fitted or interpolated sky). The parameters
    /// must give a positive zenith luminance: `φ(0) = 1 + a e^b > 0` and `f(Z_s) > 0`.
    pub fn general(parameters: Parameters, sun: [f32; 3]) -> Result<Self> {
        let sun = check_sun(sun)?;
        let Parameters { a, b, c, d, e } = parameters;
        if ![a, b, c, d, e].iter().all(|x| x.is_finite()) {
            return Err(Error::OutOfRange {
                what: "CIE sky parameter",
                range: "finite",
            });
        }
        let cos_zenith_sun = sun[2].clamp(-1.0, 1.0);
        let horizon_term = approx::exp(d * core::f32::consts::FRAC_PI_2);
        let norm = indicatrix(
            &parameters,
            horizon_term,
            approx::acos(cos_zenith_sun),
            cos_zenith_sun,
        ) * gradation(&parameters, 1.0);
        if !(norm > 0.0 && norm.is_finite()) {
            return Err(Error::OutOfRange {
                what: "CIE sky zenith luminance f(Z_s) φ(0)",
                range: "above 0",
            });
        }
        Ok(Self {
            kind: Kind::General(parameters),
            sun,
            scale: 1.0 / norm,
            horizon_term,
        })
    }

    /// The traditional CIE overcast sky; `sun` only sets the azimuth the quadrature starts
    /// from (the sky does not depend on it).
    pub fn traditional_overcast(sun: [f32; 3]) -> Result<Self> {
        Ok(Self {
            kind: Kind::TraditionalOvercast,
            sun: check_sun(sun)?,
            scale: 1.0,
            horizon_term: 0.0,
        })
    }

    /// Which sky this is.
    pub fn kind(&self) -> Kind {
        self.kind
    }

    /// Diffuse horizontal illuminance (lux) of the unobstructed sky whose zenith luminance
    /// is `zenith_luminance` (cd/m²): `L_z ∫ (L/L_z) cos Z dω`, the integral by
    /// [`super::horizontal_illuminance`]. `Err` for a negative or non-finite luminance.
    pub fn diffuse_horizontal_for(&self, zenith_luminance: f32) -> Result<f32> {
        if !(zenith_luminance.is_finite() && zenith_luminance >= 0.0) {
            return Err(Error::OutOfRange {
                what: "zenith luminance (cd/m²)",
                range: "finite and at least 0",
            });
        }
        Ok(zenith_luminance * super::horizontal_illuminance(self))
    }

    /// Zenith luminance (cd/m²) that gives the unobstructed sky the diffuse horizontal
    /// illuminance `diffuse_horizontal` (lux): `E_dh / ∫ (L/L_z) cos Z dω`, the integral by
    /// [`super::horizontal_illuminance`]. `Err` for a negative or non-finite illuminance.
    pub fn zenith_luminance_for(&self, diffuse_horizontal: f32) -> Result<f32> {
        if !(diffuse_horizontal.is_finite() && diffuse_horizontal >= 0.0) {
            return Err(Error::OutOfRange {
                what: "diffuse horizontal illuminance (lux)",
                range: "finite and at least 0",
            });
        }
        Ok(diffuse_horizontal / super::horizontal_illuminance(self))
    }
}

/// `φ(Z)` from `cos Z`: 1 at and below the horizon (where `b / cos Z → −∞`).
fn gradation(p: &Parameters, cos_zenith: f32) -> f32 {
    if cos_zenith <= 0.0 {
        1.0
    } else {
        1.0 + p.a * approx::exp(p.b / cos_zenith)
    }
}

/// `f(χ)` from χ (rad) and `cos χ`, with `exp(d π/2)` given (`horizon_term`, computed once
/// per sky).
fn indicatrix(p: &Parameters, horizon_term: f32, chi: f32, cos_chi: f32) -> f32 {
    1.0 + p.c * (approx::exp(p.d * chi) - horizon_term) + p.e * cos_chi * cos_chi
}

impl RelativeSky for CieSky {
    /// `L / L_z` in direction `dir`; 0 below the horizon.
    fn relative_luminance(&self, dir: [f32; 3]) -> f32 {
        let cos_zenith = dir[2];
        if cos_zenith.is_nan() || cos_zenith < 0.0 {
            return 0.0;
        }
        let value = match self.kind {
            Kind::TraditionalOvercast => (1.0 + 2.0 * cos_zenith) / 3.0,
            Kind::General(p) => {
                let (chi, cos_chi) = angle_between(dir, self.sun);
                indicatrix(&p, self.horizon_term, chi, cos_chi)
                    * gradation(&p, cos_zenith)
                    * self.scale
            }
        };
        value.max(0.0)
    }

    fn sun(&self) -> [f32; 3] {
        self.sun
    }
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, clippy::indexing_slicing)]
    // The f64 references use std's float functions.
    extern crate std;
    use super::super::{direction, horizontal_illuminance};
    use super::*;
    use core::f32::consts::{FRAC_PI_2, PI};

    const ZENITH: [f32; 3] = [0.0, 0.0, 1.0];

    /// The definition normalises every type to 1 at the zenith, wherever the sun is.
    #[test]
    fn every_type_is_one_at_the_zenith() {
        for t in 1..=15u8 {
            for alt in [0.0f32, 10.0, 35.0, 60.0, 89.0] {
                let sky = CieSky::standard(t, direction(alt.to_radians(), 2.0)).unwrap();
                let l = sky.relative_luminance(ZENITH);
                assert!((l - 1.0).abs() <= 1.0e-6, "type {t} sun {alt}°: {l}");
            }
        }
    }

    /// Type 1's zenith-to-horizon ratio is φ(0)/φ(π/2) = 1 + 4 e^(−0.7) = 2.98634 (ISO 15469
    /// Table 1, closed form), the "3:1" of the overcast sky to 0.5 %; the traditional overcast
    /// sky's is exactly 3.
    #[test]
    fn overcast_zenith_to_horizon_ratio() {
        let sun = direction(0.7, 0.0);
        let horizon = direction(0.0, 1.3);
        let ratio_1 = 1.0
            / CieSky::standard(1, sun)
                .unwrap()
                .relative_luminance(horizon);
        let closed = 1.0 + 4.0 * (-0.7f64).exp();
        assert!((f64::from(ratio_1) - closed).abs() <= 1.0e-5 * closed);
        assert!((ratio_1 - 3.0).abs() / 3.0 < 0.005);
        let traditional = CieSky::traditional_overcast(sun).unwrap();
        let ratio = 1.0 / traditional.relative_luminance(horizon);
        assert!((ratio - 3.0).abs() <= 1.0e-6);
    }

    /// Horizontal illuminance by the quadrature against closed forms: type 5 (uniform) gives
    /// π L_z; the traditional overcast sky 7π/9 L_z (∫ (1 + 2 cos Z)/3 cos Z sin Z dZ dφ);
    /// type 1 has no azimuth dependence, so its integral is one-dimensional:
    /// 2π ∫ φ(Z)/φ(0) cos Z sin Z dZ, here by a 200 000-step midpoint rule in f64.
    /// Tolerance 2 × 10⁻⁶ relative (f32 sums of 512 terms; the rule is exact to 10⁻⁷ on
    /// these smooth skies).
    #[test]
    fn horizontal_illuminance_closed_forms() {
        let sun = direction(0.4, 2.5);
        let uniform = horizontal_illuminance(&CieSky::standard(5, sun).unwrap());
        assert!((uniform - PI).abs() <= 2.0e-6 * PI, "{uniform}");
        let traditional = CieSky::traditional_overcast(sun).unwrap();
        let overcast = horizontal_illuminance(&traditional);
        let seven_ninths = 7.0 * PI / 9.0;
        assert!((overcast - seven_ninths).abs() <= 2.0e-6 * seven_ninths);
        // Both ways of scaling: E_h = 7π/9 L_z, and back.
        let e = traditional.diffuse_horizontal_for(9000.0).unwrap();
        assert!((e - 7000.0 * PI).abs() <= 2.0e-6 * e);
        let lz = traditional.zenith_luminance_for(7000.0 * PI).unwrap();
        assert!((lz - 9000.0).abs() <= 2.0e-6 * 9000.0);
        assert!(traditional.diffuse_horizontal_for(-1.0).is_err());

        let n = 200_000;
        let phi0 = 1.0 + 4.0 * (-0.7f64).exp();
        let h = std::f64::consts::FRAC_PI_2 / f64::from(n);
        let type1: f64 = (0..n)
            .map(|i| {
                let z = (f64::from(i) + 0.5) * h;
                (1.0 + 4.0 * (-0.7f64 / z.cos()).exp()) / phi0 * z.cos() * z.sin() * h
            })
            .sum::<f64>()
            * 2.0
            * std::f64::consts::PI;
        let quad = f64::from(horizontal_illuminance(&CieSky::standard(1, sun).unwrap()));
        assert!(
            (quad - type1).abs() <= 2.0e-6 * type1,
            "{quad} against {type1}"
        );
    }

    /// The quadrature on the peaked clear skies against a fine midpoint rule in f64
    /// (800 zenith × 1600 azimuth steps over the whole hemisphere, an independent rule of
    /// the same luminance), for all 15 types and sun altitudes 5° to 85°: within the
    /// 2 × 10⁻⁴ the rule's documentation states.
    #[test]
    fn horizontal_illuminance_of_all_types_within_stated_error() {
        let (nz, nphi) = (800u32, 1600u32);
        for t in 1..=15u8 {
            for alt in [5.0f32, 30.0, 60.0, 85.0] {
                let sky = CieSky::standard(t, direction(alt.to_radians(), 0.8)).unwrap();
                let (hz, hp) = (
                    std::f64::consts::FRAC_PI_2 / f64::from(nz),
                    2.0 * std::f64::consts::PI / f64::from(nphi),
                );
                let mut reference = 0.0f64;
                for i in 0..nz {
                    let z = (f64::from(i) + 0.5) * hz;
                    let mut ring = 0.0f64;
                    for j in 0..nphi {
                        let a = (f64::from(j) + 0.5) * hp;
                        let d = direction((FRAC_PI_2 as f64 - z) as f32, a as f32);
                        ring += f64::from(sky.relative_luminance(d));
                    }
                    reference += ring * hp * z.cos() * z.sin() * hz;
                }
                let quad = f64::from(horizontal_illuminance(&sky));
                let rel = (quad - reference).abs() / reference;
                assert!(
                    rel <= 2.0e-4,
                    "type {t} sun {alt}°: {quad} against {reference} ({rel:.1e})"
                );
            }
        }
    }

    /// Type 12 is the CIE clear sky of 1973 (Kittler; Radiance's `gensky +s`):
    /// `(0.91 + 10 e^(−3χ) + 0.45 cos² χ)(1 − e^(−0.32/cos Z)) /
    /// ((0.91 + 10 e^(−3 Z_s) + 0.45 cos² Z_s)(1 − e^(−0.32)))`, up to its constant 0.91
    /// where ISO 15469 has `1 − 10 e^(−3π/2) = 0.91017`: within 10⁻³ relative.
    #[test]
    fn type_12_is_the_1973_clear_sky() {
        let zs = 0.9f64;
        let sun = direction((std::f64::consts::FRAC_PI_2 - zs) as f32, 0.0);
        let sky = CieSky::standard(12, sun).unwrap();
        let f = |chi: f64| 0.91 + 10.0 * (-3.0 * chi).exp() + 0.45 * chi.cos().powi(2);
        for (alt, az) in [(0.1f64, 0.3f64), (0.5, 2.0), (1.2, 3.1), (0.02, 0.0)] {
            let dir = direction(alt as f32, az as f32);
            let z = std::f64::consts::FRAC_PI_2 - alt;
            let chi = f64::from(angle_between(dir, sun).0);
            let kittler =
                f(chi) * (1.0 - (-0.32 / z.cos()).exp()) / (f(zs) * (1.0 - (-0.32f64).exp()));
            let ours = f64::from(sky.relative_luminance(dir));
            assert!(
                (ours - kittler).abs() <= 1.0e-3 * kittler,
                "{ours} against {kittler}"
            );
        }
    }

    /// The absolute scaling against Radiance's `gensky -ang ALT 0 -s -B 100` (the CIE clear
    /// sky without sun for a diffuse horizontal irradiance of 100 W/m²; Radiance 6.0a in the
    /// `pyradiance` 1.3.1 wheel), whose zenith radiance is 13.80, 15.67 and 31.33 W/(m² sr)
    /// at sun altitudes 10°, 30° and 60°: `gensky` takes `E_h/L_z` from a polynomial fit
    /// (`normsc`), and its sky has the constant 0.91 where type 12 has 0.91017, so within
    /// 0.5 % (we find 0.24 %, 0.20 %, 0.04 %).
    #[test]
    fn type_12_zenith_against_gensky() {
        for (alt, gensky) in [(10.0f32, 13.80f32), (30.0, 15.67), (60.0, 31.33)] {
            let sky = CieSky::standard(12, direction(alt.to_radians(), 0.0)).unwrap();
            let lz = sky.zenith_luminance_for(100.0).unwrap();
            assert!(
                (lz - gensky).abs() <= 5.0e-3 * gensky,
                "sun {alt}°: {lz} against {gensky}"
            );
        }
    }

    #[test]
    fn bad_inputs_are_refused() {
        let sun = direction(0.5, 0.0);
        assert!(CieSky::standard(0, sun).is_err());
        assert!(CieSky::standard(16, sun).is_err());
        assert!(CieSky::standard(12, [0.0, 0.0, -1.0]).is_err());
        assert!(CieSky::standard(12, [f32::NAN, 0.0, 1.0]).is_err());
        assert!(CieSky::standard(12, [0.0, 0.0, 2.0]).is_err());
        let sky = CieSky::standard(12, sun).unwrap();
        assert!(sky.zenith_luminance_for(-1.0).is_err());
        assert!(sky.zenith_luminance_for(f32::NAN).is_err());
        assert_eq!(sky.relative_luminance([0.0, 1.0, -0.1]), 0.0);
        assert_eq!(sky.relative_luminance([f32::NAN; 3]), 0.0);
    }
}
