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

/// The lowest DALI arc power level whose light level (on the curve of
/// [`arc_power_to_level`]) is at least `level`: the inverse of that curve rounded up, so that
/// a level the controller needs is met. 0 gives 0 (off); anything above 0 and up to 0.1 %
/// gives 1; 1 gives 254. `level` must be finite and in [0, 1], else
/// [`Error::InvalidInput`] (`"level"`).
pub fn level_to_arc_power(level: f32) -> Result<u8> {
    if !(level.is_finite() && (0.0..=1.0).contains(&level)) {
        return Err(Error::InvalidInput { what: "level" });
    }
    if level == 0.0 {
        return Ok(0);
    }
    // The curve's inverse, n = 1 + (log10(level) + 3)·253/3, rounded up, then checked against
    // the curve itself so that f32 rounding of either cannot give a level below `level`.
    let estimate = 1.0 + (libm::log10f(level) + 3.0) * 253.0 / 3.0;
    let mut n = libm::ceilf(estimate).clamp(1.0, 254.0) as u8;
    let at = |n: u8| arc_power_to_level(n).unwrap_or(0.0);
    while n < 254 && at(n) < level {
        n += 1;
    }
    while n > 1 && at(n - 1) >= level {
        n -= 1;
    }
    Ok(n)
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, clippy::indexing_slicing)]
    use super::*;

    #[test]
    fn every_arc_level_round_trips() {
        for n in 0..=254u8 {
            let level = arc_power_to_level(n).unwrap();
            assert_eq!(
                level_to_arc_power(level).unwrap(),
                n,
                "arc {n} (level {level:e})"
            );
        }
    }

    /// Between two arc levels, the higher one is chosen: the level is met, by the least arc
    /// level that meets it.
    #[test]
    fn levels_between_arc_levels_round_up() {
        for n in 1..254u8 {
            let (a, b) = (
                arc_power_to_level(n).unwrap(),
                arc_power_to_level(n + 1).unwrap(),
            );
            for t in [0.001f32, 0.25, 0.5, 0.75, 0.999] {
                let level = a + (b - a) * t;
                if level <= a || level > b {
                    continue;
                }
                let arc = level_to_arc_power(level).unwrap();
                assert_eq!(arc, n + 1, "level {level:e} between arcs {n} and {}", n + 1);
                assert!(arc_power_to_level(arc).unwrap() >= level);
            }
        }
        assert_eq!(level_to_arc_power(1.0e-9).unwrap(), 1);
        assert_eq!(level_to_arc_power(0.001).unwrap(), 1);
        assert_eq!(level_to_arc_power(1.0).unwrap(), 254);
    }

    #[test]
    fn levels_outside_zero_to_one_are_refused() {
        for bad in [-0.1f32, 1.01, f32::NAN, f32::INFINITY] {
            assert_eq!(
                level_to_arc_power(bad),
                Err(Error::InvalidInput { what: "level" })
            );
        }
    }
}
