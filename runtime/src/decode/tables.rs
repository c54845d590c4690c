//! The checks every table goes through, whichever section it belongs to: its length
//! against the counts (or empty), its values against their range ([`Allowed`]), its
//! indices, its counts summed, a matrix's data and scales. Each is one function, so that one
//! copy in flash serves every table.

use crate::basis::MIN_REFLECTANCE;
use crate::error::{Error, Result};
use crate::format::{MatrixBytes, Precision, NO_CHANNEL};
use crate::storage::{f32s, u16_at, u32_at};

/// Largest magnitude accepted for any stored number. Keeps every sum the evaluator forms
/// far from `f32` overflow, while leaving room for any physical scene (10⁹ lux is 10⁴ suns).
const VALUE_LIMIT: f32 = 1.0e9;
/// Largest `|μ|` for the split formulation: `c = μ/(1−μ)` stays below 10⁶.
const MAX_MU: f32 = 1.0 - 1.0e-6;
/// Smallest seed eigenvalue `λ`: the evaluator divides by it.
const MIN_LAMBDA: f32 = 1.0e-30;

/// A product of counts, or an error when the counts of a corrupt basis overflow it.
pub(super) fn mul(a: usize, b: usize) -> Result<usize> {
    cols(a.checked_mul(b))
}

/// A column count of [`Counts`], or the same error as [`mul`] on overflow.
///
/// [`Counts`]: crate::format::Counts
pub(super) fn cols(count: Option<usize>) -> Result<usize> {
    count.ok_or(Error::DecodeField {
        field: "dimensions",
        value: u32::MAX,
    })
}

/// Checks that `bytes` holds exactly `count` values of `width` bytes. Not inlined: it runs
/// once per table, and one copy of it takes less flash than one per table.
#[inline(never)]
pub(super) fn check_len(
    field: &'static str,
    bytes: &[u8],
    count: usize,
    width: usize,
) -> Result<()> {
    let expected = mul(count, width)?;
    if bytes.len() == expected {
        Ok(())
    } else {
        Err(Error::DecodeLength {
            field,
            expected,
            found: bytes.len(),
        })
    }
}

/// Checks that every table of `tables` (name, bytes) is empty: a section the basis does not
/// carry.
pub(super) fn empty(tables: &[(&'static str, &[u8])]) -> Result<()> {
    for &(field, bytes) in tables {
        check_len(field, bytes, 0, 1)?;
    }
    Ok(())
}

/// The error of a value out of its range: `field`'s value number `index`.
pub(super) fn bad_value(field: &'static str, index: usize) -> Error {
    Error::DecodeValue { field, index }
}

/// Checks that `bytes` holds `count` little-endian `u32` and returns their sum, or the
/// overflow error of [`cols`]: the number of items that a table of counts (pieces per zone,
/// response rows per sensor) announces.
pub(super) fn u32_sum(field: &'static str, bytes: &[u8], count: usize) -> Result<usize> {
    check_len(field, bytes, count, 4)?;
    (0..count).try_fold(0usize, |sum, i| {
        cols(sum.checked_add(u32_at(bytes, i) as usize))
    })
}

/// Checks that the little-endian `u32` of `bytes` (whose length [`check_len`] checked) rise
/// strictly and stay below `limit`: a list of indices, each named once.
pub(super) fn ascending_below(field: &'static str, bytes: &[u8], limit: usize) -> Result<()> {
    let mut previous: Option<u32> = None;
    for i in 0..bytes.len() / 4 {
        let index = u32_at(bytes, i);
        if index as usize >= limit || previous.is_some_and(|p| p >= index) {
            return Err(bad_value(field, i));
        }
        previous = Some(index);
    }
    Ok(())
}

/// The values a stored `f32` table may hold. A value rather than a closure, so that one
/// checking loop serves every table (one copy of it in flash).
#[derive(Clone, Copy)]
pub(super) enum Allowed {
    /// Finite, magnitude at most [`VALUE_LIMIT`].
    Bounded,
    /// Bounded and > 0 (areas).
    Positive,
    /// Bounded and ≥ 0 (emission, scales).
    NonNegative,
    /// 0 (black) or in `[MIN_REFLECTANCE, 1)`.
    Reflectance,
    /// A split eigenvalue: `|μ| ≤ MAX_MU`.
    Mu,
    /// A seed eigenvalue: bounded and at least [`MIN_LAMBDA`].
    Lambda,
    /// Bounded and ≥ −1 (a grid's layout: its normal's components and its sizes).
    NotBelowMinusOne,
    /// In `[0, 1]` (a glazing's transmittance).
    Fraction,
}

impl Allowed {
    fn admits(self, v: f32) -> bool {
        let bounded = v.is_finite() && v.abs() <= VALUE_LIMIT;
        match self {
            Allowed::Bounded => bounded,
            Allowed::Positive => bounded && v > 0.0,
            Allowed::NonNegative => bounded && v >= 0.0,
            Allowed::Reflectance => v == 0.0 || (MIN_REFLECTANCE..1.0).contains(&v),
            Allowed::Mu => v.abs() <= MAX_MU,
            Allowed::Lambda => bounded && v >= MIN_LAMBDA,
            Allowed::NotBelowMinusOne => bounded && v >= -1.0,
            Allowed::Fraction => (0.0..=1.0).contains(&v),
        }
    }
}

/// Checks every `f32` of a table against `allowed`.
fn check_f32(field: &'static str, bytes: &[u8], allowed: Allowed) -> Result<()> {
    match f32s(bytes).position(|v| !allowed.admits(v)) {
        Some(index) => Err(bad_value(field, index)),
        None => Ok(()),
    }
}

/// A table of `count` little-endian `f32`, each one `allowed`.
pub(super) fn f32_table(
    field: &'static str,
    bytes: &[u8],
    count: usize,
    allowed: Allowed,
) -> Result<()> {
    check_len(field, bytes, count, 4)?;
    check_f32(field, bytes, allowed)
}

/// A table of `count` little-endian `u16` indices, each below `limit` (or [`NO_CHANNEL`]
/// where `no_channel_allowed`). Not inlined, as [`check_len`].
#[inline(never)]
pub(super) fn u16_table(
    field: &'static str,
    bytes: &[u8],
    count: usize,
    limit: usize,
    no_channel_allowed: bool,
) -> Result<()> {
    check_len(field, bytes, count, 2)?;
    let admits = |v: u16| usize::from(v) < limit || (no_channel_allowed && v == NO_CHANNEL);
    match (0..count).position(|i| !admits(u16_at(bytes, i))) {
        Some(index) => Err(bad_value(field, index)),
        None => Ok(()),
    }
}

/// A `rows × cols` matrix in `precision` (`docs/format.md`, "Matrices"): data and scales of
/// the right lengths, every value finite, every scale finite and non-negative.
pub(super) fn matrix(
    field: &'static str,
    scales_field: &'static str,
    raw: MatrixBytes<'_>,
    precision: Precision,
    rows: usize,
    cols: usize,
) -> Result<()> {
    check_len(field, raw.data, mul(rows, cols)?, precision.bytes())?;
    let scale_count = match precision {
        Precision::F32 => 0,
        Precision::F16 | Precision::I16 => cols,
    };
    check_len(scales_field, raw.scales, scale_count, 4)?;
    check_f32(scales_field, raw.scales, Allowed::NonNegative)?;
    match precision {
        Precision::F32 => check_f32(field, raw.data, Allowed::Bounded),
        // Exponent 31 is infinity or NaN.
        Precision::F16 => match raw
            .data
            .chunks_exact(2)
            .position(|c| matches!(*c, [_, hi] if hi & 0x7C == 0x7C))
        {
            Some(index) => Err(bad_value(field, index)),
            None => Ok(()),
        },
        // Every 16-bit integer is a value.
        Precision::I16 => Ok(()),
    }
}
