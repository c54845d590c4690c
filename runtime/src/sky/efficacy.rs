//! Luminous efficacy of daylight (R. Perez, P. Ineichen, R. Seals, J. Michalsky and
//! R. Stewart, "Modeling daylight availability and irradiance components from direct and
//! global irradiance", Solar Energy 44(5), 271–289, 1990), lm/W: what turns the irradiances
//! of a weather file into the illuminances a sky is scaled to.
//!
//! In each clearness bin of [`perez::clearness_bin`](super::perez::clearness_bin), with W
//! the atmospheric precipitable water (cm), Z the sun's zenith angle (rad) and Δ the sky
//! brightness (Table 4 of the paper):
//!
//! ```text
//! global  K_g = a + b W + c cos Z + d ln Δ
//! diffuse K_d = a + b W + c cos Z + d ln Δ
//! direct  K_b = max(0, a + b W + c exp(5.73 Z − 5) + d Δ)
//! ```
//!
//! Two public transcriptions of Table 4 differ in one digit (the direct `c` of bin 7, −1.26
//! or −1.25); this is −1.26, as in Radiance's `gendaylit.c` and DOE-2's daylighting code; the
//! difference is below 0.03 lm/W at any sun height.

use super::approx;
use super::conditions::{clearness_bin, Conditions};
use crate::error::{Error, Result};

/// Precipitable water (cm) when none is known: 2 cm, Radiance `gendaylit`'s default (its
/// dew point of 10.97 °C through Perez's `W = exp(0.07 T_d − 0.075)`).
pub const DEFAULT_WATER: f32 = 2.0;

/// `[a, b, c, d]` per clearness bin: global, diffuse, direct (Perez et al. 1990, Table 4).
const GLOBAL: [[f32; 4]; 8] = [
    [96.63, -0.47, 11.50, -9.16],
    [107.54, 0.79, 1.79, -1.19],
    [98.73, 0.70, 4.40, -6.95],
    [92.72, 0.56, 8.36, -8.31],
    [86.73, 0.98, 7.10, -10.94],
    [88.34, 1.39, 6.06, -7.60],
    [78.63, 1.47, 4.93, -11.37],
    [99.65, 1.86, -4.46, -3.15],
];
const DIFFUSE: [[f32; 4]; 8] = [
    [97.24, -0.46, 12.00, -8.91],
    [107.22, 1.15, 0.59, -3.95],
    [104.97, 2.96, -5.53, -8.77],
    [102.39, 5.59, -13.95, -13.90],
    [100.71, 5.94, -22.75, -23.74],
    [106.42, 3.83, -36.15, -28.83],
    [141.88, 1.90, -53.24, -14.03],
    [152.23, 0.35, -45.27, -7.98],
];
const DIRECT: [[f32; 4]; 8] = [
    [57.20, -4.55, -2.98, 117.12],
    [98.99, -3.46, -1.21, 12.38],
    [109.83, -4.90, -1.71, -8.81],
    [110.34, -5.84, -1.99, -4.56],
    [106.36, -3.97, -1.75, -6.16],
    [107.19, -1.25, -1.51, -26.73],
    [105.75, 0.77, -1.26, -34.44],
    [101.18, 1.58, -1.10, -8.29],
];

/// The row of `table` for these conditions, and checks of W and Δ.
fn row(table: &[[f32; 4]; 8], conditions: &Conditions, water: f32) -> Result<[f32; 4]> {
    if !(water.is_finite() && (0.0..=10.0).contains(&water)) {
        return Err(Error::OutOfRange {
            what: "precipitable water (cm)",
            range: "from 0 to 10",
        });
    }
    if !(conditions.zenith.is_finite()
        && (0.0..=core::f32::consts::FRAC_PI_2).contains(&conditions.zenith))
    {
        return Err(Error::OutOfRange {
            what: "sun zenith angle (rad)",
            range: "from 0 to π/2",
        });
    }
    if !(conditions.brightness > 0.0 && conditions.brightness.is_finite()) {
        return Err(Error::OutOfRange {
            what: "sky brightness Δ",
            range: "finite and above 0",
        });
    }
    // `clearness_bin` is at most 7; the fallback is never taken.
    Ok(*table
        .get(clearness_bin(conditions.clearness))
        .unwrap_or(&table[7]))
}

/// Efficacy of the global horizontal irradiance, lm/W.
pub fn global(conditions: &Conditions, water: f32) -> Result<f32> {
    let [a, b, c, d] = row(&GLOBAL, conditions, water)?;
    Ok(a + b * water
        + c * approx::sin_cos(conditions.zenith).1
        + d * libm::logf(conditions.brightness))
}

/// Efficacy of the diffuse horizontal irradiance, lm/W.
pub fn diffuse(conditions: &Conditions, water: f32) -> Result<f32> {
    let [a, b, c, d] = row(&DIFFUSE, conditions, water)?;
    Ok(a + b * water
        + c * approx::sin_cos(conditions.zenith).1
        + d * libm::logf(conditions.brightness))
}

/// Efficacy of the direct normal irradiance, lm/W (never negative: the fit can dip below 0
/// for a sun on the horizon).
pub fn direct(conditions: &Conditions, water: f32) -> Result<f32> {
    let [a, b, c, d] = row(&DIRECT, conditions, water)?;
    Ok((a
        + b * water
        + c * approx::exp(5.73 * conditions.zenith - 5.0)
        + d * conditions.brightness)
        .max(0.0))
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, clippy::indexing_slicing)]
    // The f64 references use std's float functions.
    extern crate std;
    use super::*;

    /// A hand evaluation of Table 4 (f64, in the test) for an intermediate sky: ε = 3.0
    /// (bin 6), Δ = 0.2, Z = 40°, W = 1.5 cm: K_d = 106.42 + 3.83·1.5 − 36.15 cos 40° −
    /// 28.83 ln 0.2, K_b = 107.19 − 1.25·1.5 − 1.51 e^(5.73·0.69813 − 5) − 26.73·0.2,
    /// K_g = 88.34 + 1.39·1.5 + 6.06 cos 40° − 7.60 ln 0.2. Tolerance 10⁻⁵ relative (f32).
    #[test]
    fn hand_evaluation_of_table_4() {
        let z = 40f64.to_radians();
        let c = Conditions {
            clearness: 3.0,
            brightness: 0.2,
            zenith: z as f32,
        };
        let kd = 106.42 + 3.83 * 1.5 - 36.15 * z.cos() - 28.83 * 0.2f64.ln();
        let kb = 107.19 - 1.25 * 1.5 - 1.51 * (5.73 * z - 5.0).exp() - 26.73 * 0.2;
        let kg = 88.34 + 1.39 * 1.5 + 6.06 * z.cos() - 7.60 * 0.2f64.ln();
        for (ours, want) in [
            (diffuse(&c, 1.5).unwrap(), kd),
            (direct(&c, 1.5).unwrap(), kb),
            (global(&c, 1.5).unwrap(), kg),
        ] {
            assert!(
                (f64::from(ours) - want).abs() <= 1.0e-5 * want,
                "{ours} against {want}"
            );
        }
    }

    #[test]
    fn bad_inputs_are_refused() {
        let c = Conditions {
            clearness: 3.0,
            brightness: 0.2,
            zenith: 0.5,
        };
        assert!(diffuse(&c, -1.0).is_err());
        assert!(direct(&c, f32::NAN).is_err());
        let dark = Conditions {
            brightness: 0.0,
            ..c
        };
        assert!(global(&dark, 2.0).is_err());
    }
}
