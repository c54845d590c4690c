//! The sky state of a moment as the daylight tables are weighed by it, and the one loop every
//! such table is summed with: rows of little-endian `f32` values dotted with a vector four
//! rows at a time, so that each of the vector's values is loaded once for four products.
//!
//! The loop serves every product of a sky update: the outputs' rows (`O × D`), the sky's
//! first-reflection coefficients (`r × (S_k + 1)`) and the modes' amplitudes (`p × r`).
//! Each row's sum runs in the order of a plain dot product (`Iterator::sum`, from −0), so
//! that four rows at a time and one at a time agree to the bit.

use crate::storage::{dot_f32, f32_at};

/// A sun node's column among the daylight nodes when it has none (it lights nothing).
pub(super) const NO_COLUMN: u32 = u32::MAX;

/// No sun: four nodes without a column.
pub(super) const NO_SUN: [SunWeight; 4] = [(NO_COLUMN, 0.0); 4];

/// A sun node's weight in the sky state: its column among the daylight nodes (or
/// [`NO_COLUMN`] when it lights nothing) and its bilinear weight times `E_n`, lux.
pub(super) type SunWeight = (u32, f32);

/// What a row of a daylight table (one value per node) is weighed by: the sky's luminances,
/// the exterior's and the sun nodes' weights.
pub(super) struct Weights<'s> {
    /// Each sky patch's luminance, cd/m² (the basis' sky order).
    pub sky: &'s [f32],
    /// `E_gh / π`, cd/m².
    pub exterior: f32,
    /// The four sun nodes around the sun.
    pub sun: &'s [SunWeight; 4],
}

impl Weights<'_> {
    /// The exterior's and the sun's terms added to `sky`, the sky part of row `row`.
    fn finish(&self, row: &[u8], sky: f32) -> f32 {
        let mut sum = sky + f32_at(row, self.sky.len()) * self.exterior;
        for &(column, weight) in self.sun {
            if column != NO_COLUMN {
                sum += f32_at(row, column as usize) * weight;
            }
        }
        sum
    }

    /// Every row of `table` (rows of `columns` values) weighed into `out` (one slot per
    /// row): `Σ_j row_j sky_j` in order, then the exterior's and the sun's terms.
    pub(super) fn table(&self, table: &[u8], columns: usize, out: &mut [f32]) {
        dots(table, columns, self.sky, out);
        for (slot, row) in out.iter_mut().zip(rows(table, columns)) {
            *slot = self.finish(row, *slot);
        }
    }
}

/// The rows of `table`, each of `columns` little-endian `f32` values, then empty rows: a
/// table shorter than its rows (never, in a basis that decoded) reads as zeros.
pub(super) fn rows(table: &[u8], columns: usize) -> impl Iterator<Item = &[u8]> {
    // `chunks_exact` needs a positive size; a table without columns has no bytes.
    let stride = (4 * columns).max(1);
    table
        .chunks_exact(stride)
        .chain(core::iter::repeat(&[][..]))
}

/// `Σ_j row_j x_j` of every row of `table` (rows of `columns` little-endian `f32` values, at
/// least `x.len()` of them) into `out` (one slot per row), each summed in order from −0 as
/// [`dot_f32`] sums it: four rows at a time share each value of `x` they read.
pub(super) fn dots(table: &[u8], columns: usize, x: &[f32], out: &mut [f32]) {
    let mut rows = rows(table, columns);
    let mut next = || rows.next().unwrap_or(&[]);
    let mut groups = out.chunks_exact_mut(4);
    for group in &mut groups {
        let four_rows = [next(), next(), next(), next()];
        match four(four_rows, x) {
            Some(sums) => group.copy_from_slice(&sums),
            None => {
                for (slot, row) in group.iter_mut().zip(four_rows) {
                    *slot = dot_f32(row, x);
                }
            }
        }
    }
    for slot in groups.into_remainder() {
        *slot = dot_f32(next(), x);
    }
}

/// The dot products of four rows with `x`, each summed in order from −0 (as
/// `Iterator::sum`), or `None` when a row is shorter than `x` (never, in a basis that
/// decoded).
fn four(rows: [&[u8]; 4], x: &[f32]) -> Option<[f32; 4]> {
    let n = x.len() * 4;
    let [a, b, c, d] = rows.map(|r| r.get(..n).map(|r| r.as_chunks::<4>().0));
    let (a, b, c, d) = (a?, b?, c?, d?);
    let (mut s0, mut s1, mut s2, mut s3) = (-0.0f32, -0.0f32, -0.0f32, -0.0f32);
    for ((((&l, x0), x1), x2), x3) in x.iter().zip(a).zip(b).zip(c).zip(d) {
        s0 += f32::from_le_bytes(*x0) * l;
        s1 += f32::from_le_bytes(*x1) * l;
        s2 += f32::from_le_bytes(*x2) * l;
        s3 += f32::from_le_bytes(*x3) * l;
    }
    Some([s0, s1, s2, s3])
}

#[cfg(test)]
mod tests {
    #![allow(clippy::indexing_slicing)]
    use super::*;
    use crate::storage::f32_row;

    /// A table of `rows` rows of `columns` little-endian `f32` values from a simple
    /// generator: mixed signs, magnitudes and exact zeros, and a row of zeros (the sign of a
    /// zero sum).
    fn table(rows: usize, columns: usize, seed: u32) -> ([u8; 4 * 9 * 12], usize) {
        let mut bytes = [0u8; 4 * 9 * 12];
        let mut x = seed.wrapping_mul(2_654_435_761) | 1;
        for r in 0..rows {
            for c in 0..columns {
                x ^= x << 13;
                x ^= x >> 17;
                x ^= x << 5;
                let v = if r == 2 || x.is_multiple_of(7) {
                    0.0
                } else {
                    (x % 20_001) as f32 / 997.0 - 10.0
                };
                let i = 4 * (r * columns + c);
                bytes[i..i + 4].copy_from_slice(&v.to_le_bytes());
            }
        }
        (bytes, rows * columns * 4)
    }

    /// Four rows at a time give what a plain dot product of each row gives, to the bit, for every row count
    /// (whole groups and remainders) and with a sun node or none.
    #[test]
    fn grouped_rows_match_row_by_row() {
        let sky = [3.5f32, 0.0, 1.0e3, 2.25e-3, 7.0, 11.0, 0.5];
        let columns = sky.len() + 1 + 4;
        for rows in 0..=9 {
            for (seed, sun) in [
                (1u32, NO_SUN),
                (2, [(8, 0.25), (9, 0.75), (NO_COLUMN, 0.0), (11, 1.5e4)]),
            ] {
                let (bytes, len) = table(rows, columns, seed + rows as u32);
                let weights = Weights {
                    sky: &sky,
                    exterior: 1.25e3,
                    sun: &sun,
                };
                let mut grouped = [f32::NAN; 9];
                weights.table(&bytes[..len], columns, &mut grouped[..rows]);
                for (r, g) in grouped[..rows].iter().enumerate() {
                    let row = f32_row(&bytes[..len], r, columns);
                    let one = weights.finish(row, dot_f32(row, &sky));
                    assert_eq!(g.to_bits(), one.to_bits(), "{rows} rows, row {r}");
                }
            }
        }
    }

    /// Dot products over the first `x.len()` values of longer rows (the modes' rows: the
    /// coefficients, then a value per sun node) match `dot_f32` to the bit.
    #[test]
    fn grouped_dots_over_a_prefix_match_dot_f32() {
        let x = [0.5f32, -2.0, 1.0e-3, 6.0];
        let columns = 11;
        for rows in 0..=9 {
            let (bytes, len) = table(rows, columns, 7 + rows as u32);
            let mut grouped = [f32::NAN; 9];
            dots(&bytes[..len], columns, &x, &mut grouped[..rows]);
            for (r, g) in grouped[..rows].iter().enumerate() {
                let one = dot_f32(f32_row(&bytes[..len], r, columns), &x);
                assert_eq!(g.to_bits(), one.to_bits(), "{rows} rows, row {r}");
            }
        }
    }
}
