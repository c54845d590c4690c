//! The sky state of a moment as the daylight tables are weighed by it, and the one loop every
//! such table is summed with: rows of little-endian `f32` values dotted with a vector eight
//! or six rows at a time (then four, two and one), so that each of the vector's values is
//! loaded once for up to eight products; then the terms every row adds (the exterior, the
//! sun nodes) a column at a time.
//!
//! The loop serves every product of a sky update: the outputs' rows (`O × D`), the sky's
//! first-reflection coefficients (`r × (S_k + 1)`) and the modes' amplitudes (`p × r`).
//! Each row's sum runs in the order of a plain dot product (`Iterator::sum`, from −0), so
//! that any number of rows at a time and one at a time agree to the bit.
//!
//! The kernels that sum several rows are functions of their own, never inlined: inlined,
//! the optimiser sees that the rows lie a stride apart in one table and addresses them all
//! from one pointer, an add a row more in the inner loop (38 instructions per eight
//! products on the Cortex-M4F against 29). Taken as separate slices, each row is read
//! through its own post-incremented pointer: a word load (the basis is read in place,
//! unaligned, so not one `VLDR`), a move to the FPU and a multiply-add a product, the
//! vector's load and the loop's count shared by the rows.

#[cfg(test)]
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
    /// The exterior's and the sun's terms added to `sky`, the sky part of row `row`: what
    /// [`table`](Self::table) adds, one term at a time.
    #[cfg(test)]
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
        add_column(table, columns, self.sky.len(), self.exterior, out);
        for (column, weight) in lit(self.sun, 0) {
            add_column(table, columns, column, weight, out);
        }
    }
}

/// Adds `weight` times the value in column `column` of every row of `table` (rows of
/// `columns` values; 0 past a row's end, as `f32_at` reads it) to the row's slot of `out`.
/// A column at a time, down the rows a stride apart, so that a term added to every row
/// costs a load, a multiply-add and the slot's load and store: row by row, each term cost
/// the row's cut and checks (about 37 instructions a row for the modes' one sun term).
/// Each slot still adds its terms in the order of the calls.
pub(super) fn add_column(
    table: &[u8],
    columns: usize,
    column: usize,
    weight: f32,
    out: &mut [f32],
) {
    let whole = rows(table, columns).len();
    let whole = whole.min(out.len());
    let out = out.get_mut(..whole).unwrap_or(&mut []);
    if column >= columns {
        for slot in out {
            *slot += 0.0 * weight;
        }
        return;
    }
    let values = table.as_chunks::<4>().0;
    // The value's index runs down the column: a test a row, where `step_by` took five
    // instructions more.
    let mut at = column;
    for slot in out {
        if let Some(v) = values.get(at) {
            *slot += value(v) * weight;
        }
        at = at.saturating_add(columns);
    }
}

/// The nodes of `sun` that have a column, in their order, each column plus `offset`: the
/// others add nothing, so that the rows' loops need not test them.
pub(super) fn lit(sun: &[SunWeight; 4], offset: usize) -> heapless::Vec<(usize, f32), 4> {
    let mut out = heapless::Vec::new();
    for &(column, weight) in sun.iter().filter(|s| s.0 != NO_COLUMN) {
        // At most four, as many as `sun` holds.
        let _ = out.push((column as usize + offset, weight));
    }
    out
}

/// The rows of `table`, each of `columns` little-endian `f32` values (none for a table
/// without columns).
pub(super) fn rows(table: &[u8], columns: usize) -> core::slice::ChunksExact<'_, u8> {
    // `chunks_exact` needs a positive size; a table without columns has no bytes.
    table.chunks_exact((4 * columns).max(1))
}

/// `Σ_j row_j x_j` of every row of `table` (rows of `columns` little-endian `f32` values, at
/// least `x.len()` of them) into `out` (one slot per row), each summed in order from −0 as
/// `dot_f32` sums it: eight or six rows at a time share each value of `x` they read. A table
/// shorter than `out` reads as empty rows past its own (never, in a basis that decoded).
pub(super) fn dots(table: &[u8], columns: usize, x: &[f32], out: &mut [f32]) {
    let mut rows = rows(table, columns);
    // Every row holds `x.len()` values (always, in a basis that decoded): the kernels are
    // then given whole rows, each summed over its first `x.len()` values (the kernels' sums
    // stop at the shortest of `x` and the rows), with no cut or test a row.
    if columns < x.len() || rows.len() < out.len() {
        let n = 4 * x.len();
        for slot in out.iter_mut() {
            let row = rows.next().and_then(|row| row.get(..n)).unwrap_or(&[]);
            *slot = one(row.as_chunks::<4>().0, x);
        }
        return;
    }
    // A missing row ends the sums (never: the table holds every row, checked above). A
    // branch a row, where an empty row in its place took a dozen instructions a row.
    let mut next = || rows.next().map(|row| row.as_chunks::<4>().0);
    // Six rows at a time take 21 instructions a column, 3.5 a row, eight 29: a table of a
    // multiple of eight rows is summed eight at a time (fewer calls), any other six at a
    // time (18 rows: three sixes, 63 a column, where two eights and a two took 67).
    let rest = if out.len().is_multiple_of(8) {
        let (eights, rest) = out.as_chunks_mut::<8>();
        for group in eights {
            let (Some(a), Some(b), Some(c), Some(d)) = (next(), next(), next(), next()) else {
                return;
            };
            let (Some(e), Some(f), Some(g), Some(h)) = (next(), next(), next(), next()) else {
                return;
            };
            eight([a, b, c, d], [e, f, g, h], x, group);
        }
        rest
    } else {
        let (sixes, rest) = out.as_chunks_mut::<6>();
        for group in sixes {
            let (Some(a), Some(b), Some(c)) = (next(), next(), next()) else {
                return;
            };
            let (Some(d), Some(e), Some(f)) = (next(), next(), next()) else {
                return;
            };
            six([a, b, c], [d, e, f], x, group);
        }
        rest
    };
    let (fours, rest) = rest.as_chunks_mut::<4>();
    for group in fours {
        let (Some(a), Some(b), Some(c), Some(d)) = (next(), next(), next(), next()) else {
            return;
        };
        four([a, b, c, d], x, group);
    }
    let (twos, rest) = rest.as_chunks_mut::<2>();
    for group in twos {
        let (Some(a), Some(b)) = (next(), next()) else {
            return;
        };
        two(a, b, x, group);
    }
    for slot in rest {
        *slot = next().map_or(0.0, |row| one(row, x));
    }
}

/// As [`eight`], one row.
fn one(row: &[[u8; 4]], x: &[f32]) -> f32 {
    row.iter()
        .zip(x)
        .fold(-0.0f32, |s, (v, &l)| s + value(v) * l)
}

/// The value of a 4-byte chunk.
#[inline]
fn value(bytes: &[u8; 4]) -> f32 {
    f32::from_le_bytes(*bytes)
}

/// The dot products of eight rows with `x` into `out`, over as many values as the shortest
/// of them holds, each summed in order from −0 (as `Iterator::sum`). The sums are locals,
/// not an array: an array was set to −0 and read back through the stack on every call.
#[inline(never)]
fn eight(first: [&[[u8; 4]]; 4], second: [&[[u8; 4]]; 4], x: &[f32], out: &mut [f32; 8]) {
    let ([a, b, c, d], [e, f, g, h]) = (first, second);
    let (mut s0, mut s1, mut s2, mut s3) = (-0.0f32, -0.0f32, -0.0f32, -0.0f32);
    let (mut s4, mut s5, mut s6, mut s7) = (-0.0f32, -0.0f32, -0.0f32, -0.0f32);
    let columns = x
        .iter()
        .zip(a)
        .zip(b)
        .zip(c)
        .zip(d)
        .zip(e)
        .zip(f)
        .zip(g)
        .zip(h);
    for ((((((((&l, va), vb), vc), vd), ve), vf), vg), vh) in columns {
        s0 += value(va) * l;
        s1 += value(vb) * l;
        s2 += value(vc) * l;
        s3 += value(vd) * l;
        s4 += value(ve) * l;
        s5 += value(vf) * l;
        s6 += value(vg) * l;
        s7 += value(vh) * l;
    }
    *out = [s0, s1, s2, s3, s4, s5, s6, s7];
}

/// As [`eight`], six rows.
#[inline(never)]
fn six(first: [&[[u8; 4]]; 3], second: [&[[u8; 4]]; 3], x: &[f32], out: &mut [f32; 6]) {
    let ([a, b, c], [d, e, f]) = (first, second);
    let (mut s0, mut s1, mut s2) = (-0.0f32, -0.0f32, -0.0f32);
    let (mut s3, mut s4, mut s5) = (-0.0f32, -0.0f32, -0.0f32);
    let columns = x.iter().zip(a).zip(b).zip(c).zip(d).zip(e).zip(f);
    for ((((((&l, va), vb), vc), vd), ve), vf) in columns {
        s0 += value(va) * l;
        s1 += value(vb) * l;
        s2 += value(vc) * l;
        s3 += value(vd) * l;
        s4 += value(ve) * l;
        s5 += value(vf) * l;
    }
    *out = [s0, s1, s2, s3, s4, s5];
}

/// As [`eight`], four rows.
#[inline(never)]
fn four([a, b, c, d]: [&[[u8; 4]]; 4], x: &[f32], out: &mut [f32; 4]) {
    let (mut s0, mut s1, mut s2, mut s3) = (-0.0f32, -0.0f32, -0.0f32, -0.0f32);
    for ((((&l, va), vb), vc), vd) in x.iter().zip(a).zip(b).zip(c).zip(d) {
        s0 += value(va) * l;
        s1 += value(vb) * l;
        s2 += value(vc) * l;
        s3 += value(vd) * l;
    }
    *out = [s0, s1, s2, s3];
}

/// As [`eight`], two rows.
#[inline(never)]
fn two(a: &[[u8; 4]], b: &[[u8; 4]], x: &[f32], out: &mut [f32; 2]) {
    let (mut s0, mut s1) = (-0.0f32, -0.0f32);
    for ((&l, va), vb) in x.iter().zip(a).zip(b) {
        s0 += value(va) * l;
        s1 += value(vb) * l;
    }
    *out = [s0, s1];
}

#[cfg(test)]
mod tests {
    #![allow(clippy::indexing_slicing)]
    use super::*;
    use crate::storage::f32_row;

    /// The most rows a test table has: three groups of six, then four and one (a multiple
    /// of eight, 8 or 16, is summed eight at a time; the others six at a time).
    const ROWS: usize = 23;

    /// A table of `rows` rows of `columns` little-endian `f32` values from a simple
    /// generator: mixed signs, magnitudes and exact zeros, and a row of zeros (the sign of a
    /// zero sum).
    fn table(rows: usize, columns: usize, seed: u32) -> ([u8; 4 * ROWS * 12], usize) {
        let mut bytes = [0u8; 4 * ROWS * 12];
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

    /// Eight, six, four and two rows at a time give what a plain dot product of each row
    /// and its terms one after the other give, to the bit, for every row count (whole
    /// groups and every remainder) and with a sun node or none.
    #[test]
    fn grouped_rows_match_row_by_row() {
        let sky = [3.5f32, 0.0, 1.0e3, 2.25e-3, 7.0, 11.0, 0.5];
        let columns = sky.len() + 1 + 4;
        for rows in 0..=ROWS {
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
                let mut grouped = [f32::NAN; ROWS];
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
        for rows in 0..=ROWS {
            let (bytes, len) = table(rows, columns, 7 + rows as u32);
            let mut grouped = [f32::NAN; ROWS];
            dots(&bytes[..len], columns, &x, &mut grouped[..rows]);
            for (r, g) in grouped[..rows].iter().enumerate() {
                let one = dot_f32(f32_row(&bytes[..len], r, columns), &x);
                assert_eq!(g.to_bits(), one.to_bits(), "{rows} rows, row {r}");
            }
        }
    }
}
