//! DALI arc power levels (IEC 62386-102).

use crate::error::{Error, Result};

/// Relative light level (0 to 1) of a DALI arc power level, on the standard logarithmic
/// dimming curve `X(n) = 10^((n − 1)/(253/3) − 1) %` for `n` in 1..=254, and 0 (off) for
/// `n = 0`. Level 1 gives 0.1 %, 254 gives 100 %. 255 is MASK ("no change") and is an error.
pub fn arc_power_to_level(arc: u8) -> Result<f32> {
    match arc {
        0 => Ok(0.0),
        255 => Err(Error::DaliMask),
        n => {
            // (n − 1)/(253/3) − 1 is the exponent in percent; −2 more converts % to a fraction.
            let exponent = (f32::from(n) - 1.0) * 3.0 / 253.0 - 3.0;
            Ok(libm::exp10f(exponent))
        }
    }
}
