//! IEEE binary16: the conversions of the `F16` storage, exact from binary16 to `f32`,
//! rounding to nearest even from `f32`.

/// Converts an IEEE binary16 bit pattern to `f32` (exact: every f16 is an f32). Infinities
/// and NaNs map to their `f32` counterparts.
pub fn f16_to_f32(bits: u16) -> f32 {
    if bits & 0x7C00 == 0x7C00 {
        let sign = u32::from(bits & 0x8000) << 16;
        let man = u32::from(bits & 0x3FF) << 13;
        let quiet = if man != 0 { 0x0040_0000 } else { 0 };
        return f32::from_bits(sign | 0x7F80_0000 | quiet | man);
    }
    f16_finite_to_f32(bits)
}

/// `2^112`: the difference between the exponent biases of `f32` (127) and binary16 (15).
const F16_TO_F32_SCALE: f32 = f32::from_bits((127 + 112) << 23);

/// Converts the bit pattern of a finite binary16 to `f32`, exactly, without a branch: the
/// sign, exponent and mantissa fields shifted into place form an `f32` of the value times
/// 2⁻¹¹² (a subnormal half becomes a subnormal single), and one multiplication by 2¹¹²
/// restores it. The decoder rejects infinities and NaNs in stored tables, so the evaluator
/// reads through this. (An FPU in flush-to-zero mode would read the few subnormal halves,
/// magnitudes below 2⁻¹⁴ of their column's scale, as 0.)
#[inline]
pub(crate) fn f16_finite_to_f32(bits: u16) -> f32 {
    let sign = u32::from(bits & 0x8000) << 16;
    let magnitude = u32::from(bits & 0x7FFF) << 13;
    f32::from_bits(sign | magnitude) * F16_TO_F32_SCALE
}

/// Converts `f32` to the nearest IEEE binary16 bit pattern (round to nearest even).
/// Writers use it; values beyond the f16 range become infinity, which the reader rejects.
pub fn f32_to_f16(value: f32) -> u16 {
    let x = value.to_bits();
    let sign = ((x >> 16) & 0x8000) as u16;
    let exp = ((x >> 23) & 0xFF) as i32;
    let man = x & 0x007F_FFFF;
    if exp == 0xFF {
        return sign | 0x7C00 | if man != 0 { 0x200 } else { 0 };
    }
    let e = exp - 127 + 15;
    if e >= 0x1F {
        return sign | 0x7C00;
    }
    if e <= 0 {
        if e < -10 {
            return sign;
        }
        let m = man | 0x0080_0000;
        let shift = (14 - e) as u32;
        let half = 1u32 << (shift - 1);
        let rest = m & ((1u32 << shift) - 1);
        let mut h = (m >> shift) as u16;
        if rest > half || (rest == half && (h & 1) == 1) {
            h += 1;
        }
        return sign | h;
    }
    let mut h = ((e as u32) << 10) as u16 | (man >> 13) as u16;
    let rest = man & 0x1FFF;
    if rest > 0x1000 || (rest == 0x1000 && (h & 1) == 1) {
        h += 1; // may carry into the exponent, which is the correct rounding
    }
    sign | h
}
