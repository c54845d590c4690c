//! The entry format: the bytes of an entry (layout in the module docs of `cache`), written
//! and read back with every check, and the values a patch form-factor entry holds.

use faer::Mat;
use sha2::{Digest, Sha256};

use crate::formfactor::{FormFactors, Hierarchical, WORST_PAIRS};

const MAGIC: &[u8; 8] = b"EIGENRFF";
/// Version of the entry layout (the `cache` module's docs); another layout is another key, so old entries are
/// simply never read again.
pub(super) const ENTRY_VERSION: u32 = 4;
/// Magic, version, kind, key, rows, columns.
const HEADER_BYTES: usize = 8 + 4 + 4 + 32 + 8 + 8;
/// Payload length and checksum.
const TRAILER_BYTES: usize = 8 + 32;

/// What an entry holds, and its shape.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Kind {
    /// [`FormFactors`] of n patches: n × n.
    Patches,
    /// Sensor and zone rows over n patches: r × n.
    Rows,
    /// [`FormFactors`] of n patches as a hierarchical operator: n × (the count of its values).
    Hierarchical,
}

impl Kind {
    fn tag(self) -> u32 {
        match self {
            Kind::Patches => 1,
            Kind::Rows => 2,
            Kind::Hierarchical => 3,
        }
    }

    /// Values held for `rows × cols`, `None` past `u64`.
    fn values(self, rows: u64, cols: u64) -> Option<u64> {
        let product = rows.checked_mul(cols)?;
        match self {
            Kind::Patches => product
                .checked_add(rows)?
                .checked_add(2 + 3 * WORST_PAIRS as u64),
            Kind::Rows => Some(product),
            Kind::Hierarchical => Some(cols),
        }
    }
}

/// Bytes of an entry, `None` past `u64`.
pub(super) fn entry_bytes(kind: Kind, (rows, cols): (u64, u64)) -> Option<u64> {
    kind.values(rows, cols)?
        .checked_mul(8)?
        .checked_add((HEADER_BYTES + TRAILER_BYTES) as u64)
}

/// The values of a patch form-factor entry.
pub(super) fn patch_values(ff: &FormFactors) -> Vec<f64> {
    let n = ff.matrix.nrows();
    let mut out = Vec::with_capacity(n * n + n + 2);
    out.push(ff.reciprocity_mismatch);
    out.push(ff.reciprocity_share);
    for j in 0..n {
        out.extend((0..n).map(|i| ff.matrix[(i, j)]));
    }
    out.extend_from_slice(&ff.row_sums);
    // The worst pairs in `WORST_PAIRS` fixed slots, an unused one as (−1, −1, 0).
    for k in 0..WORST_PAIRS {
        let (i, j, share) = ff
            .worst_pairs
            .get(k)
            .map_or((-1.0, -1.0, 0.0), |&(i, j, s)| (i as f64, j as f64, s));
        out.extend([i, j, share]);
    }
    out
}

/// The reciprocity figures, row sums and worst pairs of `ff`, as a hierarchical entry begins.
fn health_values<M>(ff: &FormFactors<M>, out: &mut Vec<f64>) {
    out.push(ff.reciprocity_mismatch);
    out.push(ff.reciprocity_share);
    out.extend_from_slice(&ff.row_sums);
    for k in 0..WORST_PAIRS {
        let (i, j, share) = ff
            .worst_pairs
            .get(k)
            .map_or((-1.0, -1.0, 0.0), |&(i, j, s)| (i as f64, j as f64, s));
        out.extend([i, j, share]);
    }
}

/// The values of a hierarchical form-factor entry: the figures of [`health_values`], then
/// the operator's numbers (`Hierarchical::write_values`).
pub(super) fn hierarchical_values(ff: &FormFactors<Hierarchical>) -> Vec<f64> {
    let mut out = Vec::new();
    health_values(ff, &mut out);
    ff.matrix.write_values(&mut out);
    out
}

/// The hierarchical form factors of `n` patches from the values of their entry
/// ([`hierarchical_values`] read back), or what is wrong with them.
pub(super) fn from_hierarchical_values(
    values: Vec<f64>,
    n: usize,
) -> Result<FormFactors<Hierarchical>, String> {
    let operator_at = 2 + n + 3 * WORST_PAIRS;
    if values.len() < operator_at {
        return Err("too few values".into());
    }
    let worst_pairs = worst_pairs(&values[2 + n..operator_at], n)?;
    Ok(FormFactors {
        reciprocity_mismatch: values[0],
        reciprocity_share: values[1],
        matrix: Hierarchical::read_values(&values[operator_at..], n)?,
        row_sums: values[2..2 + n].to_vec(),
        worst_pairs,
    })
}

/// The worst pairs from their [`WORST_PAIRS`] slots of three values, an unused slot's first
/// value negative.
fn worst_pairs(slots: &[f64], n: usize) -> Result<Vec<(usize, usize, f64)>, String> {
    let mut worst_pairs = Vec::new();
    for slot in slots.chunks_exact(3) {
        let index = |x: f64| {
            (x >= 0.0 && x < n as f64 && x.fract() == 0.0)
                .then_some(x as usize)
                .ok_or_else(|| "a worst pair names no patch".to_string())
        };
        if slot[0] >= 0.0 {
            worst_pairs.push((index(slot[0])?, index(slot[1])?, slot[2]));
        }
    }
    Ok(worst_pairs)
}

/// The patch form factors of `n` patches from the values of their entry ([`patch_values`]
/// read back), or what is wrong with them.
pub(super) fn from_patch_values(values: Vec<f64>, n: usize) -> Result<FormFactors, String> {
    if values.len() != n * n + n + 2 + 3 * WORST_PAIRS {
        return Err("wrong number of values".into());
    }
    let matrix = Mat::from_fn(n, n, |i, j| values[2 + j * n + i]);
    let pairs_at = 2 + n * n + n;
    let worst_pairs = worst_pairs(&values[pairs_at..], n)?;
    Ok(FormFactors {
        reciprocity_mismatch: values[0],
        reciprocity_share: values[1],
        matrix,
        row_sums: values[2 + n * n..pairs_at].to_vec(),
        worst_pairs,
    })
}

/// The entry bytes of the patch form factors `ff` under `key` (as the cache writes them).
pub fn encode_form_factors(ff: &FormFactors, key: &[u8; 32]) -> Vec<u8> {
    let n = ff.matrix.nrows() as u64;
    encode(Kind::Patches, key, (n, n), &patch_values(ff))
}

/// The bytes of an entry of `kind` under `key` holding `values` of `rows × cols`.
pub(super) fn encode(
    kind: Kind,
    key: &[u8; 32],
    (rows, cols): (u64, u64),
    values: &[f64],
) -> Vec<u8> {
    let mut out = Vec::with_capacity(HEADER_BYTES + TRAILER_BYTES + 8 * values.len());
    out.extend_from_slice(MAGIC);
    out.extend_from_slice(&ENTRY_VERSION.to_le_bytes());
    out.extend_from_slice(&kind.tag().to_le_bytes());
    out.extend_from_slice(key);
    out.extend_from_slice(&rows.to_le_bytes());
    out.extend_from_slice(&cols.to_le_bytes());
    for v in values {
        out.extend_from_slice(&v.to_le_bytes());
    }
    out.extend_from_slice(&(out.len() as u64).to_le_bytes());
    let sum: [u8; 32] = Sha256::digest(&out).into();
    out.extend_from_slice(&sum);
    out
}

/// The dimensions an entry's header declares (its second one is what a hierarchical entry's
/// reader cannot know beforehand); `None` for bytes too short to hold a header.
pub(super) fn declared_dims(bytes: &[u8]) -> Option<(u64, u64)> {
    let field = |at: usize| -> Option<u64> {
        Some(u64::from_le_bytes(bytes.get(at..at + 8)?.try_into().ok()?))
    };
    Some((field(HEADER_BYTES - 16)?, field(HEADER_BYTES - 8)?))
}

/// The values of an entry, or what is wrong with it; `dims` are the ones expected.
pub(super) fn decode(
    bytes: &[u8],
    kind: Kind,
    key: &[u8; 32],
    dims: (u64, u64),
) -> Result<Vec<f64>, String> {
    let expected = entry_bytes(kind, dims).ok_or("too large")?;
    if bytes.len() as u64 != expected {
        return Err(format!(
            "{} bytes where {expected} are expected: truncated or not an entry",
            bytes.len()
        ));
    }
    let (body, sum) = bytes.split_at(bytes.len() - 32);
    if Sha256::digest(body).as_slice() != sum {
        return Err("checksum mismatch".into());
    }
    let mut r = Reader { bytes: body, at: 0 };
    if r.take(8)? != MAGIC {
        return Err("not a form-factor cache entry".into());
    }
    let version = u32::from_le_bytes(r.array()?);
    if version != ENTRY_VERSION {
        return Err(format!("entry version {version}, expected {ENTRY_VERSION}"));
    }
    if u32::from_le_bytes(r.array()?) != kind.tag() {
        return Err("another kind of entry".into());
    }
    if r.take(32)? != key {
        return Err("key mismatch".into());
    }
    if (r.u64()?, r.u64()?) != dims {
        return Err("dimension mismatch".into());
    }
    let count = (body.len() - HEADER_BYTES - 8) / 8;
    let values = (0..count).map(|_| r.f64()).collect::<Result<Vec<_>, _>>()?;
    if r.u64()? != (body.len() - 8) as u64 {
        return Err("length field mismatch".into());
    }
    Ok(values)
}

/// Little-endian fields in order; running out is an error, never a panic.
struct Reader<'a> {
    bytes: &'a [u8],
    at: usize,
}

impl<'a> Reader<'a> {
    fn take(&mut self, len: usize) -> Result<&'a [u8], String> {
        let end = self.at.checked_add(len).ok_or("entry too short")?;
        let slice = self.bytes.get(self.at..end).ok_or("entry too short")?;
        self.at = end;
        Ok(slice)
    }

    fn array<const N: usize>(&mut self) -> Result<[u8; N], String> {
        let mut out = [0u8; N];
        out.copy_from_slice(self.take(N)?);
        Ok(out)
    }

    fn u64(&mut self) -> Result<u64, String> {
        Ok(u64::from_le_bytes(self.array()?))
    }

    fn f64(&mut self) -> Result<f64, String> {
        Ok(f64::from_le_bytes(self.array()?))
    }
}

#[cfg(test)]
mod tests {
    use super::super::fixtures::pair;
    use super::super::key;
    use super::*;
    use crate::formfactor::{self, FormFactorOptions};

    #[test]
    fn an_entry_reads_back_to_the_bit() {
        let patches = pair();
        let ff = formfactor::patch_form_factors(&patches, &FormFactorOptions::default());
        let key = key(&patches, &[], &FormFactorOptions::default());
        let back = from_patch_values(
            decode(&encode_form_factors(&ff, &key), Kind::Patches, &key, (2, 2)).unwrap(),
            2,
        )
        .unwrap();
        for i in 0..2 {
            for j in 0..2 {
                assert_eq!(back.matrix[(i, j)].to_bits(), ff.matrix[(i, j)].to_bits());
            }
        }
        assert_eq!(back.row_sums, ff.row_sums);
        assert_eq!(back.reciprocity_mismatch, ff.reciprocity_mismatch);
        assert_eq!(back.reciprocity_share, ff.reciprocity_share);
    }

    #[test]
    fn every_damaged_entry_is_refused() {
        let patches = pair();
        let ff = formfactor::patch_form_factors(&patches, &FormFactorOptions::default());
        let key = key(&patches, &[], &FormFactorOptions::default());
        let good = encode_form_factors(&ff, &key);
        let d = (2, 2);
        // Each byte flipped in turn, and every truncation: all refused.
        for at in 0..good.len() {
            let mut bad = good.clone();
            bad[at] ^= 0x20;
            assert!(
                decode(&bad, Kind::Patches, &key, d).is_err(),
                "flipped byte {at} accepted"
            );
        }
        for len in 0..good.len() {
            assert!(
                decode(&good[..len], Kind::Patches, &key, d).is_err(),
                "{len} bytes accepted"
            );
        }
        let mut other = key;
        other[0] ^= 1;
        assert!(decode(&good, Kind::Patches, &other, d)
            .unwrap_err()
            .contains("key"));
        assert!(decode(&good, Kind::Patches, &key, (3, 3)).is_err());
        assert!(decode(&good, Kind::Rows, &key, d).is_err());
    }
}
