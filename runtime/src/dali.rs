//! DALI arc power levels (IEC 62386-102).

use crate::error::{Error, Result};

/// Relative light level (0 to 1) of a DALI arc power level, on the standard logarithmic
/// dimming curve `X(n) = 10^((n − 1)/(253/3) − 1) %` for `n` in 1..=254, and 0 (off) for
/// `n = 0`. Level 1 gives 0.1 %, 254 gives 100 %. 255 is MASK ("no change") and is an error.
///
/// Computed in `f32` only, within 3 × 10⁻⁷ of the curve (relative): libm's `exp10f` falls
/// back to a double-precision `exp2` outside a narrow range, which on a part without a
/// double-precision FPU links about 7 KB of soft-float code and tables.
pub fn arc_power_to_level(arc: u8) -> Result<f32> {
    match arc {
        0 => Ok(0.0),
        255 => Err(Error::DaliMask),
        n => {
            // The exponent 3(n − 1)/253 − 3 in decades, split exactly into whole decades
            // `decade` (0..=3) and a remainder `rest/253` of a decade, `rest` in 0..253.
            let steps = 3 * (u32::from(n) - 1);
            let (decade, rest) = (steps / 253, steps % 253);
            let fraction_of_decade =
                exp2_below_4(rest as f32 * (core::f32::consts::LOG2_10 / 253.0));
            let whole = match decade {
                0 => 1.0e-3,
                1 => 1.0e-2,
                2 => 1.0e-1,
                _ => 1.0,
            };
            Ok(whole * fraction_of_decade)
        }
    }
}

/// `2^t` for `t` in [0, 4), within 10⁻⁷ relative: the integer part exactly, the fractional
/// part by a degree-6 polynomial fitted to `2^f` on [0, 1] (relative error 2 × 10⁻⁹ in exact
/// arithmetic; Horner's rule in `f32` adds under 10⁻⁷).
fn exp2_below_4(t: f32) -> f32 {
    // Fitted (least squares, relative, on Chebyshev nodes); the linear term is close to but
    // not ln 2, which is what the fit wants with the terms after it.
    #[allow(clippy::approx_constant)]
    const C: [f32; 7] = [
        1.0,
        6.931_47e-1,
        2.402_298e-1,
        5.548_352_5e-2,
        9.678_473e-3,
        1.244_308_2e-3,
        2.169_061e-4,
    ];
    // `t as u32` truncates, which is the floor for t ≥ 0; the caller keeps t below 4.
    let whole = (t as u32).min(3);
    let f = t - whole as f32;
    let p = C.iter().rev().fold(0.0, |p, &c| p * f + c);
    p * (1u32 << whole) as f32
}
