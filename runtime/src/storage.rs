//! Typed, bounds-checked views of the little-endian tables inside a basis.
//!
//! Every table's length is validated once when the basis is decoded, so the accessors here
//! never fall outside their slice; they still return neutral values instead of panicking, so
//! that no byte string can reset a controller.

use crate::format::{f16_finite_to_f32, Precision};

/// Reads the `i`-th little-endian `f32` of `bytes`, or 0 past the end.
#[inline]
pub(crate) fn f32_at(bytes: &[u8], i: usize) -> f32 {
    match bytes.get(i * 4..i * 4 + 4) {
        Some(&[a, b, c, d]) => f32::from_le_bytes([a, b, c, d]),
        _ => 0.0,
    }
}

/// Reads the `i`-th little-endian `u16` of `bytes`, or `u16::MAX` past the end.
#[inline]
pub(crate) fn u16_at(bytes: &[u8], i: usize) -> u16 {
    match bytes.get(i * 2..i * 2 + 2) {
        Some(&[a, b]) => u16::from_le_bytes([a, b]),
        _ => u16::MAX,
    }
}

/// Reads the `i`-th little-endian `u32` of `bytes`, or `u32::MAX` past the end.
#[inline]
pub(crate) fn u32_at(bytes: &[u8], i: usize) -> u32 {
    match bytes.get(i * 4..i * 4 + 4) {
        Some(&[a, b, c, d]) => u32::from_le_bytes([a, b, c, d]),
        _ => u32::MAX,
    }
}

/// Row `row` of a little-endian `f32` table with rows of `len` values (empty past the end).
#[inline]
pub(crate) fn f32_row(bytes: &[u8], row: usize, len: usize) -> &[u8] {
    let start = row * len * 4;
    bytes.get(start..start + len * 4).unwrap_or(&[])
}

/// `f32` values of a little-endian table, in order.
#[inline]
pub(crate) fn f32s(bytes: &[u8]) -> impl Iterator<Item = f32> + '_ {
    bytes.chunks_exact(4).map(|c| match *c {
        [a, b, c, d] => f32::from_le_bytes([a, b, c, d]),
        _ => 0.0,
    })
}

/// `Σ_k table[k] · x[k]` over a little-endian `f32` table.
#[inline]
pub(crate) fn dot_f32(bytes: &[u8], x: &[f32]) -> f32 {
    f32s(bytes).zip(x).map(|(a, &b)| a * b).sum()
}

/// Bytes `tables` take in a payload as postcard writes byte strings: each its length as a
/// varint (7 bits a byte) and its bytes.
pub(crate) fn serialized_len(tables: &[&[u8]]) -> usize {
    let varint_len = |mut n: usize| {
        let mut bytes = 1;
        while n >= 0x80 {
            n >>= 7;
            bytes += 1;
        }
        bytes
    };
    tables
        .iter()
        .map(|table| table.len() + varint_len(table.len()))
        .sum()
}

/// A row-major matrix in the basis' storage precision with a scale per column.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Matrix<'a> {
    pub precision: Precision,
    pub cols: usize,
    pub scales: &'a [u8],
    pub data: &'a [u8],
}

impl<'a> Matrix<'a> {
    /// Stored bytes of `len` values of row `row` from column `col`.
    #[inline]
    fn span(&self, row: usize, col: usize, len: usize) -> &'a [u8] {
        let w = self.precision.bytes();
        let start = (row * self.cols + col) * w;
        self.data.get(start..start + len * w).unwrap_or(&[])
    }

    /// Scales of columns `col..col + len` (empty for `F32`).
    #[inline]
    fn scale_span(&self, col: usize, len: usize) -> &'a [u8] {
        self.scales.get(col * 4..(col + len) * 4).unwrap_or(&[])
    }

    /// Calls `f(k, value(row, col + k))` for `k` in `0..len`, with a loop specialised per
    /// precision (three loops in flash per caller): for long rows, the `p` mode values of a
    /// patch update.
    #[inline]
    pub fn for_each(&self, row: usize, col: usize, len: usize, mut f: impl FnMut(usize, f32)) {
        let data = self.span(row, col, len);
        match self.precision {
            Precision::F32 => {
                for (k, v) in f32s(data).enumerate() {
                    f(k, v);
                }
            }
            Precision::F16 => {
                let scales = f32s(self.scale_span(col, len));
                for (k, (c, s)) in data.chunks_exact(2).zip(scales).enumerate() {
                    if let [a, b] = *c {
                        f(k, f16_finite_to_f32(u16::from_le_bytes([a, b])) * s);
                    }
                }
            }
            Precision::I16 => {
                let scales = f32s(self.scale_span(col, len));
                for (k, (c, s)) in data.chunks_exact(2).zip(scales).enumerate() {
                    if let [a, b] = *c {
                        f(k, f32::from(i16::from_le_bytes([a, b])) * s);
                    }
                }
            }
        }
    }

    /// As [`Matrix::for_each`], with one loop for every precision (a match at each element):
    /// a third of the flash per caller, for short rows (a patch's view of the outputs, its
    /// `m` channel responses) where the match costs little.
    #[inline]
    pub fn for_each_compact(
        &self,
        row: usize,
        col: usize,
        len: usize,
        mut f: impl FnMut(usize, f32),
    ) {
        let data = self.span(row, col, len);
        // F32 has no scales: every value is taken as it is (times 1, exactly).
        let mut scales = f32s(self.scale_span(col, len)).chain(core::iter::repeat(1.0));
        for (k, bytes) in data.chunks_exact(self.precision.bytes()).enumerate() {
            let scale = scales.next().unwrap_or(1.0);
            let v = match (self.precision, bytes) {
                (Precision::F32, &[a, b, c, d]) => f32::from_le_bytes([a, b, c, d]),
                (Precision::F16, &[a, b]) => f16_finite_to_f32(u16::from_le_bytes([a, b])) * scale,
                (Precision::I16, &[a, b]) => f32::from(i16::from_le_bytes([a, b])) * scale,
                _ => 0.0,
            };
            f(k, v);
        }
    }

    /// Row `row`'s sums per band, `Σ_c value(row, c·B + b) · x[c]` for `b < B` over the
    /// first `x.len() · B` columns ([`weighted_sums`]): a patch's exitance from its channel
    /// responses (`x` the levels). [`weighted_rows`](Self::weighted_rows) on the matrix from
    /// that row on, so that a patch read alone and every patch read at once are the same
    /// code and agree to the bit. Sums of nothing past the last row.
    #[inline]
    pub fn weighted_row<const B: usize>(&self, row: usize, x: &[f32]) -> [f32; B] {
        let stride = self.cols * self.precision.bytes();
        let from_row = Matrix {
            data: row
                .checked_mul(stride)
                .and_then(|start| self.data.get(start..))
                .unwrap_or(&[]),
            ..*self
        };
        let mut out = [[0.0f32; B]];
        from_row.weighted_rows(x, &mut out);
        let [sums] = out;
        sums
    }

    /// [`weighted_row`](Self::weighted_row) of every row from the first into `out`, one
    /// entry per row, for rows of at least `x.len() · B` values (the channel responses have
    /// `m·B`, one per channel and band): the rows are walked in order as consecutive slices
    /// of the matrix' bytes, the precision dispatched once for them all and each row read in
    /// a plain loop, so that the whole matrix reads at about the speed of a plain loop over
    /// its bytes. Entries past the matrix' rows are left as they are.
    pub fn weighted_rows<const B: usize>(&self, x: &[f32], out: &mut [[f32; B]]) {
        // `chunks_exact` needs a positive size; a matrix without columns has no bytes.
        let stride = (self.cols * self.precision.bytes()).max(1);
        let rows = self.data.chunks_exact(stride).zip(out);
        let scales = || f32s(self.scale_span(0, x.len() * B));
        match self.precision {
            Precision::F32 => {
                for (row, slot) in rows {
                    *slot = weighted_sums(f32s(row), x);
                }
            }
            Precision::F16 => {
                for (row, slot) in rows {
                    let values = row.chunks_exact(2).zip(scales()).map(|(c, s)| match *c {
                        [lo, hi] => f16_finite_to_f32(u16::from_le_bytes([lo, hi])) * s,
                        _ => 0.0,
                    });
                    *slot = weighted_sums(values, x);
                }
            }
            Precision::I16 => {
                for (row, slot) in rows {
                    let values = row.chunks_exact(2).zip(scales()).map(|(c, s)| match *c {
                        [lo, hi] => f32::from(i16::from_le_bytes([lo, hi])) * s,
                        _ => 0.0,
                    });
                    *slot = weighted_sums(values, x);
                }
            }
        }
    }

    /// `Σ_k value(row, col + k) · x[k]` for `k < x.len()`. Specialised per precision so
    /// that the inner loop is a plain zip the compiler can unroll.
    #[inline]
    pub fn row_dot(&self, row: usize, col: usize, x: &[f32]) -> f32 {
        let data = self.span(row, col, x.len());
        match self.precision {
            Precision::F32 => dot_f32(data, x),
            Precision::F16 => {
                let scales = f32s(self.scale_span(col, x.len()));
                data.chunks_exact(2)
                    .zip(scales)
                    .zip(x)
                    .map(|((c, s), &b)| match *c {
                        [lo, hi] => f16_finite_to_f32(u16::from_le_bytes([lo, hi])) * s * b,
                        _ => 0.0,
                    })
                    .sum()
            }
            Precision::I16 => {
                let scales = f32s(self.scale_span(col, x.len()));
                data.chunks_exact(2)
                    .zip(scales)
                    .zip(x)
                    .map(|((c, s), &b)| match *c {
                        [lo, hi] => f32::from(i16::from_le_bytes([lo, hi])) * s * b,
                        _ => 0.0,
                    })
                    .sum()
            }
        }
    }
}

/// `Σ_c v[c·B + b] · x[c]` for each band `b < B`, over `values` in order (channel-major,
/// band-minor): the one rule for a row's weighted sums, so that a patch read alone and every
/// patch read at once agree to the bit. One band is a plain dot product; several bands add
/// each product to its band's sum in turn, from 0.
#[inline]
fn weighted_sums<const B: usize>(mut values: impl Iterator<Item = f32>, x: &[f32]) -> [f32; B] {
    let mut out = [0.0f32; B];
    if B == 1 {
        if let Some(slot) = out.first_mut() {
            *slot = values.zip(x).map(|(v, &l)| v * l).sum();
        }
        return out;
    }
    for &level in x {
        for slot in out.iter_mut() {
            match values.next() {
                Some(v) => *slot += v * level,
                None => return out,
            }
        }
    }
    out
}
