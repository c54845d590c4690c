//! Sine, cosine, arcsine, arccosine, arctangent, exponential and square root in `f32`
//! arithmetic alone, for the sky models and the sun's position on the controller.
//!
//! `libm`'s single-precision sine and cosine reduce and evaluate their arguments in `f64`,
//! and its `asinf` takes an `f64` square root; on a Cortex-M4F (single-precision FPU only)
//! that is software floating point, about 2 000 instructions a call and several KB of code.
//! Here each function is a short polynomial after an exact or Cody–Waite range reduction,
//! in the manner of Cephes' single-precision library (S. L. Moshier, *Methods and Programs
//! for Mathematical Functions*, 1989; its `sinf`, `cosf`, `asinf`, `atanf` and `expf`
//! minimax coefficients), which `micromath` also follows for speed. Every product and sum is
//! `f32`; nothing links `f64` code.
//!
//! Each function's error bound is stated in its documentation over its whole domain and is
//! checked by this module's tests against `f64` (`std`) on dense samples of that domain
//! (several million points each, and the domain's ends). The bounds are a few units in the
//! last place of `f32`: the sky models' coefficients have four or five significant digits,
//! so these functions add nothing measurable to the models' own error.

use core::f32::consts::{FRAC_PI_2, FRAC_PI_4, PI};

/// The largest argument of [`sin_cos`] for which its stated bound holds, rad (fewer than
/// 2¹³ quarter turns): beyond it `k` times the reduction's second part of `π/2` is no longer
/// exact.
pub const SIN_COS_DOMAIN: f32 = 8192.0;

/// `(sin x, cos x)`, x in rad. Absolute error at most 1.2 × 10⁻⁷ for |x| ≤
/// [`SIN_COS_DOMAIN`]; `(0, 1)` for an argument beyond it or not finite (the runtime's
/// callers reduce their angles first or check them).
///
/// x is reduced to `r = x − k π/2` in [−π/4, π/4] with `π/2` in three parts (Cody and
/// Waite): the first two have few enough bits that `k` times them is exact for k < 2¹³.
/// Then Cephes' minimax polynomials for sine and cosine on [−π/4, π/4], and the quadrant
/// `k mod 4` swaps and signs them.
pub fn sin_cos(x: f32) -> (f32, f32) {
    if x.is_nan() || x.abs() > SIN_COS_DOMAIN {
        return (0.0, 1.0);
    }
    // π/2 = A + B + C (Cephes' parts of π/4, doubled): A has 8 significant bits and B 11,
    // so k·A and k·B are exact for every k below 2¹³.
    const A: f32 = 1.570_312_5;
    const B: f32 = 4.837_513e-4;
    const C: f32 = 7.549_79e-8;
    let k = round(x * (2.0 / PI));
    let r = ((x - k * A) - k * B) - k * C;
    let z = r * r;
    let s = r + r * z * ((-1.951_529_6e-4 * z + 8.332_161e-3) * z - 1.666_665_5e-1);
    let c = 1.0 - 0.5 * z + z * z * ((2.443_315_7e-5 * z - 1.388_731_6e-3) * z + 4.166_664_6e-2);
    // k fits an i32 for every argument that reaches here; the cast saturates otherwise.
    match (k as i32) & 3 {
        0 => (s, c),
        1 => (c, -s),
        2 => (-s, -c),
        _ => (-c, s),
    }
}

/// `x` rounded to the nearest integer (halves away from zero), as an `f32`: `core`'s
/// `f32::round` is not available without `std`.
fn round(x: f32) -> f32 {
    // Beyond 2²³ every f32 is an integer already.
    if x.abs() >= 8_388_608.0 {
        return x;
    }
    let t = (x.abs() + 0.5) as i32 as f32;
    if x < 0.0 {
        -t
    } else {
        t
    }
}

/// `√x` for x ≥ 0: the reciprocal square root from an integer first guess (within 3.5 %)
/// and two Newton steps, times x, and a Newton step on the root. Relative error at most 2.5 × 10⁻⁷ for x from 10⁻³⁰ to
/// 10³⁰ (the tests' range); 0 for x ≤ 0 or NaN; x for +∞.
pub fn sqrt(x: f32) -> f32 {
    if x.is_nan() || x <= 0.0 {
        return 0.0;
    }
    if x.is_infinite() {
        return x;
    }
    let mut y = f32::from_bits(0x5f37_59df_u32.wrapping_sub(x.to_bits() >> 1));
    let half = 0.5 * x;
    // Each step squares the relative error: 3.5 % → 1.8 × 10⁻³ → 5 × 10⁻⁶.
    y *= 1.5 - half * y * y;
    y *= 1.5 - half * y * y;
    // One Newton step on the square root itself squares it again, below f32's rounding.
    let s = x * y;
    s + 0.5 * y * (x - s * s)
}

/// `asin x` for |x| ≤ 0.5, Cephes' minimax polynomial.
fn asin_small(x: f32) -> f32 {
    let z = x * x;
    let p = (((4.216_32e-2 * z + 2.418_131e-2) * z + 4.547_002_6e-2) * z + 7.495_300_3e-2) * z
        + 1.666_675_2e-1;
    x + x * z * p
}

/// `asin x`, rad, x in [−1, 1] (clamped; NaN gives 0). Absolute error at most
/// 2.5 × 10⁻⁷ rad over the whole domain.
///
/// For |x| > 0.5, `asin x = π/2 − 2 asin √((1 − |x|)/2)` keeps the polynomial's argument
/// at most 0.5, where it is accurate.
pub fn asin(x: f32) -> f32 {
    if x.is_nan() {
        return 0.0;
    }
    let a = x.abs().min(1.0);
    let y = if a <= 0.5 {
        asin_small(a)
    } else {
        FRAC_PI_2 - 2.0 * asin_small(sqrt(0.5 * (1.0 - a)))
    };
    if x < 0.0 {
        -y
    } else {
        y
    }
}

/// `acos x`, rad in [0, π], x in [−1, 1] (clamped; NaN gives π/2). Absolute error at most
/// 4 × 10⁻⁷ rad over the whole domain.
///
/// For |x| > 0.5 from `acos x = 2 asin √((1 − x)/2)` (and `π −` that for x < 0), so that
/// near ±1, where `acos` is steep, the error stays absolute rather than growing as
/// `1/√(1 − x²)`.
pub fn acos(x: f32) -> f32 {
    if x.is_nan() {
        return FRAC_PI_2;
    }
    let x = x.clamp(-1.0, 1.0);
    if x > 0.5 {
        2.0 * asin_small(sqrt(0.5 * (1.0 - x)))
    } else if x < -0.5 {
        PI - 2.0 * asin_small(sqrt(0.5 * (1.0 + x)))
    } else {
        FRAC_PI_2 - asin_small(x)
    }
}

/// `atan2(y, x)`, rad in [−π, π], the angle of the point (x, y) from the +x axis. Absolute
/// error at most 3 × 10⁻⁷ rad for every finite (x, y); 0 at the origin and for NaN.
///
/// Cephes' `atanf`: the ratio's magnitude is brought below tan(π/8) with
/// `atan t = π/2 + atan(−1/t)` above tan(3π/8) and `π/4 + atan((t − 1)/(t + 1))` between,
/// then a minimax polynomial; the signs of x and y place the quadrant.
pub fn atan2(y: f32, x: f32) -> f32 {
    if x.is_nan() || y.is_nan() || (x == 0.0 && y == 0.0) {
        return 0.0;
    }
    let (ax, ay) = (x.abs(), y.abs());
    // atan of ay/ax in [0, π/2], without forming a ratio that overflows.
    let (base, t) = if ay > 2.414_213_6 * ax {
        (FRAC_PI_2, -ax / ay)
    } else if ay > 0.414_213_57 * ax {
        (FRAC_PI_4, (ay - ax) / (ay + ax))
    } else {
        (0.0, ay / ax)
    };
    let z = t * t;
    let a = base
        + t
        + t * z * (((8.053_744_5e-2 * z - 1.387_768_6e-1) * z + 1.997_771_1e-1) * z - 3.333_295e-1);
    let a = if x < 0.0 { PI - a } else { a };
    if y < 0.0 {
        -a
    } else {
        a
    }
}

/// `e^x`. Relative error at most 2.5 × 10⁻⁷ for x in [−86, 88.7] (where e^x is a normal
/// `f32`); 0 below −86 (e^−86 = 4.4 × 10⁻³⁸) and for NaN, +∞ above 88.7.
///
/// `x = n ln 2 + r` with n the nearest integer to x/ln 2 and ln 2 in two parts (Cody and
/// Waite), Cephes' minimax polynomial of degree 7 for e^r on |r| ≤ ln 2 / 2, and n added to
/// the result's exponent bits.
pub fn exp(x: f32) -> f32 {
    if x.is_nan() || x < -86.0 {
        return 0.0;
    }
    if x > 88.7 {
        return f32::INFINITY;
    }
    const LN2_HIGH: f32 = 0.693_359_4;
    const LN2_LOW: f32 = -2.121_944_4e-4;
    let n = round(x * core::f32::consts::LOG2_E);
    let r = (x - n * LN2_HIGH) - n * LN2_LOW;
    let z = r * r;
    let p = (((((1.987_569_1e-4 * r + 1.398_2e-3) * r + 8.333_452e-3) * r + 4.166_579_6e-2) * r
        + 1.666_666_5e-1)
        * r
        + 0.5)
        * z
        + r
        + 1.0;
    // n is in [−124, 128] and p in [0.7, 1.42] (exponent −1 or 0): the sum's exponent is a
    // normal one, 127 at most since n = 128 only comes with r < 0 (x ≤ 88.7 < 128 ln 2).
    let n = n as i32;
    f32::from_bits((p.to_bits() as i32).wrapping_add(n << 23) as u32)
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, clippy::indexing_slicing)]
    // The f64 references use std's float functions.
    extern crate std;
    use super::*;

    /// `count` points spread evenly over [lo, hi], both ends included, as f32.
    fn samples(lo: f64, hi: f64, count: u32) -> impl Iterator<Item = f32> {
        (0..=count).map(move |i| (lo + (hi - lo) * f64::from(i) / f64::from(count)) as f32)
    }

    /// Sine and cosine over the whole stated domain, and densely over the first turns
    /// where the sky and the sun use them, within 1.2 × 10⁻⁷ absolute of f64.
    #[test]
    fn sin_cos_within_bound() {
        let mut worst = 0.0f64;
        let d = f64::from(SIN_COS_DOMAIN);
        for x in samples(-7.0, 7.0, 4_000_000).chain(samples(-d, d, 4_000_000)) {
            let (s, c) = sin_cos(x);
            let x64 = f64::from(x);
            worst = worst
                .max((f64::from(s) - x64.sin()).abs())
                .max((f64::from(c) - x64.cos()).abs());
        }
        assert!(worst <= 1.2e-7, "sin/cos: {worst:.2e}");
        assert_eq!(sin_cos(f32::NAN), (0.0, 1.0));
        assert_eq!(sin_cos(f32::INFINITY), (0.0, 1.0));
        assert_eq!(sin_cos(1.0e30), (0.0, 1.0));
    }

    /// The square root over 60 decades, within 2.5 × 10⁻⁷ relative of f64.
    #[test]
    fn sqrt_within_bound() {
        let mut worst = 0.0f64;
        for e in samples(-30.0, 30.0, 4_000_000) {
            let x = 10f32.powf(e);
            let exact = f64::from(x).sqrt();
            worst = worst.max((f64::from(sqrt(x)) - exact).abs() / exact);
        }
        assert!(worst <= 2.5e-7, "sqrt: {worst:.2e}");
        assert_eq!(sqrt(0.0), 0.0);
        assert_eq!(sqrt(-1.0), 0.0);
        assert_eq!(sqrt(f32::NAN), 0.0);
        assert_eq!(sqrt(f32::INFINITY), f32::INFINITY);
    }

    /// Arcsine and arccosine over [−1, 1], the ends included, within 2.5 × 10⁻⁷ and
    /// 4 × 10⁻⁷ rad of f64; arguments beyond ±1 are clamped.
    #[test]
    fn asin_acos_within_bound() {
        let (mut worst_asin, mut worst_acos) = (0.0f64, 0.0f64);
        // Near ±1 the samples thin out in f32; the last 10⁻³ gets its own dense pass.
        let near_one = samples(0.999, 1.0, 1_000_000).flat_map(|x| [x, -x]);
        for x in samples(-1.0, 1.0, 8_000_000).chain(near_one) {
            let x64 = f64::from(x);
            worst_asin = worst_asin.max((f64::from(asin(x)) - x64.asin()).abs());
            worst_acos = worst_acos.max((f64::from(acos(x)) - x64.acos()).abs());
        }
        assert!(worst_asin <= 2.5e-7, "asin: {worst_asin:.2e}");
        assert!(worst_acos <= 4.0e-7, "acos: {worst_acos:.2e}");
        assert_eq!(acos(2.0), 0.0);
        assert!((acos(-2.0) - PI).abs() <= 4.0e-7);
        assert!((asin(-3.0) + FRAC_PI_2).abs() <= 2.5e-7);
        assert_eq!(acos(f32::NAN), FRAC_PI_2);
    }

    /// Arctangent of two arguments on circles of radius 10⁻³, 1 and 10⁵ (every angle,
    /// both signs of each coordinate) and along the axes, within 3 × 10⁻⁷ rad of f64.
    #[test]
    fn atan2_within_bound() {
        let mut worst = 0.0f64;
        for radius in [1.0e-3f64, 1.0, 1.0e5] {
            for t in samples(-std::f64::consts::PI, std::f64::consts::PI, 3_000_000) {
                let (y, x) = (
                    (radius * f64::from(t).sin()) as f32,
                    (radius * f64::from(t).cos()) as f32,
                );
                let exact = f64::from(y).atan2(f64::from(x));
                let got = f64::from(atan2(y, x));
                // ±π are the same angle.
                let diff = (got - exact).abs();
                worst = worst.max(diff.min((diff - 2.0 * std::f64::consts::PI).abs()));
            }
        }
        assert!(worst <= 3.0e-7, "atan2: {worst:.2e}");
        assert_eq!(atan2(0.0, 0.0), 0.0);
        assert!((atan2(1.0, 0.0) - FRAC_PI_2).abs() <= 2.5e-7);
        assert!((atan2(0.0, -1.0) - PI).abs() <= 2.5e-7);
        assert!((atan2(-1.0, 0.0) + FRAC_PI_2).abs() <= 2.5e-7);
        assert_eq!(atan2(f32::NAN, 1.0), 0.0);
    }

    /// The exponential over its whole normal range, within 2.5 × 10⁻⁷ relative of f64;
    /// underflow to 0 and overflow to +∞ past the ends.
    #[test]
    fn exp_within_bound() {
        let mut worst = 0.0f64;
        for x in samples(-86.0, 88.7, 8_000_000).chain(samples(-1.0, 1.0, 2_000_000)) {
            let exact = f64::from(x).exp();
            worst = worst.max((f64::from(exp(x)) - exact).abs() / exact);
        }
        assert!(worst <= 2.5e-7, "exp: {worst:.2e}");
        let top = f64::from(exp(88.7));
        assert!((top - 88.7f32.exp() as f64).abs() <= 2.5e-7 * top);
        assert_eq!(exp(-86.1), 0.0);
        assert_eq!(exp(89.0), f32::INFINITY);
        assert_eq!(exp(f32::NAN), 0.0);
        assert_eq!(exp(0.0), 1.0);
    }
}
