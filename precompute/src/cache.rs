//! The form-factor cache: the patch form factors of a scene, kept on disk so that `solve`,
//! `verify`, `build` and `form-factors` on the same scene content reuse them instead of
//! computing them again (most of those commands' time on a large scene).
//!
//! An entry is named by a SHA-256 key of everything the form factors depend on: every patch
//! (corners, normal, area, centroid, surface index) and every face the occluders are built
//! from, in order, every [`FormFactorOptions`] field the computation reads, the crate version
//! and [`formfactor::ALGORITHM_VERSION`]. Two scene files that mesh to the same patches share
//! an entry; any change to the geometry, the meshing or the settings is another key. Channel
//! levels, reflectances, sensors, zones and luminaires do not enter: they are not read by the
//! patch form factors.
//!
//! The cache is only ever a copy: it is written atomically (`cli/atomic.rs`), may be deleted at
//! any time, and an entry that fails any check (length, SHA-256 checksum, magic, version, key)
//! is reported on standard error and recomputed, never used. An entry holds the `n × n` matrix
//! as `f64`, so results with and without the cache are the same to the bit. Entries larger
//! than [`MAX_ENTRY_BYTES`] are not written.
//!
//! Where it lives: `$EIGENRAD_CACHE_DIR`, else `$XDG_CACHE_HOME/eigenrad`, else
//! `$HOME/.cache/eigenrad` ([`default_dir`]); the `eigenrad` commands' `--no-cache` turns it
//! off. Library calls use no cache unless [`FormFactorOptions::cache`] names a folder.
//!
//! Entry layout (little-endian): magic `EIGENRFF`, entry version (u32), key (32 bytes),
//! patch count n (u64), reciprocity mismatch and share (f64 each), the matrix column by column
//! (n² f64), the row sums (n f64), the length of everything before this field (u64), and the
//! SHA-256 of everything before the checksum (32 bytes).

use std::io::Write as _;
use std::path::{Path, PathBuf};

use faer::Mat;
use sha2::{Digest, Sha256};

use crate::cli::atomic;
use crate::formfactor::{self, FormFactorOptions, FormFactors, Occluders};
use crate::geometry::{Face, Patch, Vec3};

/// Largest entry written, bytes (256 MiB: a scene of up to about 5 800 patches). Larger
/// matrices are recomputed every time rather than fill the disk unasked.
pub const MAX_ENTRY_BYTES: u64 = 256 << 20;

const MAGIC: &[u8; 8] = b"EIGENRFF";
/// Version of the entry layout above; another layout is another key, so old entries are
/// simply never read again.
const ENTRY_VERSION: u32 = 1;
/// Magic, version, key, n, the two mismatches.
const HEADER_BYTES: usize = 8 + 4 + 32 + 8 + 8 + 8;
/// Payload length and checksum.
const TRAILER_BYTES: usize = 8 + 32;

/// The folder the `eigenrad` commands keep form factors in: `$EIGENRAD_CACHE_DIR`, else
/// `$XDG_CACHE_HOME/eigenrad`, else `$HOME/.cache/eigenrad`; `None` when none of them is set.
pub fn default_dir() -> Option<PathBuf> {
    let var = |name| std::env::var_os(name).filter(|v| !v.is_empty());
    var("EIGENRAD_CACHE_DIR")
        .map(PathBuf::from)
        .or_else(|| var("XDG_CACHE_HOME").map(|d| PathBuf::from(d).join("eigenrad")))
        .or_else(|| var("HOME").map(|d| PathBuf::from(d).join(".cache").join("eigenrad")))
}

/// The key of the form factors of `patches` (with occluders from `faces`) under `opts`.
pub fn key(patches: &[Patch], faces: &[Face], opts: &FormFactorOptions) -> [u8; 32] {
    // Every field named, so that a new option cannot be forgotten here.
    let FormFactorOptions {
        gauss_order,
        progress: _,
        cache: _,
        touching_order,
        quadrature_tolerance,
        visibility_depth,
        visibility_cell_share,
        occluded_order,
    } = opts;
    let mut h = Sha256::new();
    h.update(b"eigenrad patch form factors\0");
    h.update(env!("CARGO_PKG_VERSION").as_bytes());
    h.update([0]);
    h.update(formfactor::ALGORITHM_VERSION.to_le_bytes());
    h.update(ENTRY_VERSION.to_le_bytes());
    for x in [*gauss_order, *touching_order, *occluded_order] {
        h.update((x as u64).to_le_bytes());
    }
    h.update(u64::from(*visibility_depth).to_le_bytes());
    h.update(quadrature_tolerance.to_bits().to_le_bytes());
    h.update(visibility_cell_share.to_bits().to_le_bytes());
    let point = |h: &mut Sha256, p: &Vec3| {
        for c in [p.x, p.y, p.z] {
            h.update(c.to_bits().to_le_bytes());
        }
    };
    h.update((patches.len() as u64).to_le_bytes());
    for p in patches {
        h.update((p.polygon.vertices.len() as u64).to_le_bytes());
        for v in &p.polygon.vertices {
            point(&mut h, v);
        }
        point(&mut h, &p.normal);
        point(&mut h, &p.centroid);
        h.update(p.area.to_bits().to_le_bytes());
        h.update((p.surface as u64).to_le_bytes());
    }
    h.update((faces.len() as u64).to_le_bytes());
    for f in faces {
        h.update((f.patches.start as u64).to_le_bytes());
        h.update((f.patches.end as u64).to_le_bytes());
        h.update((f.polygon.vertices.len() as u64).to_le_bytes());
        for v in &f.polygon.vertices {
            point(&mut h, v);
        }
    }
    h.finalize().into()
}

/// The entry file of `key` in `dir`.
pub fn entry_path(dir: &Path, key: &[u8; 32]) -> PathBuf {
    let hex: String = key.iter().map(|b| format!("{b:02x}")).collect();
    dir.join(format!("ff-{hex}.bin"))
}

/// The patch form factors of `patches`, from the cache in `opts.cache` when it holds a sound
/// entry for them, else computed ([`formfactor::patch_form_factors_with`]) and stored there.
/// Without `opts.cache`, simply computed. Cache trouble (an unreadable folder, a corrupt
/// entry, a full disk) is a warning on standard error, never an error: the cache is a copy.
pub fn form_factors(
    patches: &[Patch],
    faces: &[Face],
    occluders: &Occluders,
    opts: &FormFactorOptions,
) -> FormFactors {
    let Some(dir) = &opts.cache else {
        return formfactor::patch_form_factors_with(patches, occluders, opts);
    };
    let key = key(patches, faces, opts);
    let path = entry_path(dir, &key);
    match std::fs::read(&path) {
        Ok(bytes) => match decode(&bytes, &key, patches.len()) {
            Ok(ff) => return ff,
            Err(reason) => warn(&format!(
                "form-factor cache entry {} is unusable ({reason}); computing the form factors again",
                path.display()
            )),
        },
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => {}
        Err(e) => warn(&format!(
            "cannot read form-factor cache entry {} ({e}); computing the form factors again",
            path.display()
        )),
    }
    let ff = formfactor::patch_form_factors_with(patches, occluders, opts);
    if entry_bytes(patches.len()).is_some_and(|b| b <= MAX_ENTRY_BYTES) {
        let stored = std::fs::create_dir_all(dir)
            .map_err(|e| format!("{}: {e}", dir.display()))
            .and_then(|()| atomic::write(&path, &encode(&ff, &key)).map_err(|e| e.to_string()));
        if let Err(reason) = stored {
            warn(&format!("form factors not cached: {reason}"));
        }
    }
    ff
}

/// A warning on standard error; a closed standard error is no reason to fail.
fn warn(text: &str) {
    let _ = writeln!(std::io::stderr(), "warning: {text}");
}

/// Bytes of the entry of an n-patch scene, `None` past `u64`.
fn entry_bytes(n: usize) -> Option<u64> {
    let n = n as u64;
    n.checked_mul(n)?
        .checked_add(n)?
        .checked_mul(8)?
        .checked_add((HEADER_BYTES + TRAILER_BYTES) as u64)
}

/// The entry bytes of `ff` under `key`.
pub fn encode(ff: &FormFactors, key: &[u8; 32]) -> Vec<u8> {
    let n = ff.matrix.nrows();
    let mut out = Vec::with_capacity(HEADER_BYTES + TRAILER_BYTES + 8 * (n * n + n));
    out.extend_from_slice(MAGIC);
    out.extend_from_slice(&ENTRY_VERSION.to_le_bytes());
    out.extend_from_slice(key);
    out.extend_from_slice(&(n as u64).to_le_bytes());
    out.extend_from_slice(&ff.reciprocity_mismatch.to_le_bytes());
    out.extend_from_slice(&ff.reciprocity_share.to_le_bytes());
    for j in 0..n {
        for i in 0..n {
            out.extend_from_slice(&ff.matrix[(i, j)].to_le_bytes());
        }
    }
    for s in &ff.row_sums {
        out.extend_from_slice(&s.to_le_bytes());
    }
    out.extend_from_slice(&(out.len() as u64).to_le_bytes());
    let sum: [u8; 32] = Sha256::digest(&out).into();
    out.extend_from_slice(&sum);
    out
}

/// An entry read back, or what is wrong with it. `n` is the scene's patch count.
fn decode(bytes: &[u8], key: &[u8; 32], n: usize) -> Result<FormFactors, String> {
    let expected = entry_bytes(n).ok_or("too many patches")?;
    if bytes.len() as u64 != expected {
        return Err(format!(
            "{} bytes where {n} patches need {expected}: truncated or not an entry",
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
    if r.take(32)? != key {
        return Err("key mismatch".into());
    }
    if r.u64()? != n as u64 {
        return Err("patch count mismatch".into());
    }
    let reciprocity_mismatch = r.f64()?;
    let reciprocity_share = r.f64()?;
    let mut matrix = Mat::<f64>::zeros(n, n);
    for j in 0..n {
        for i in 0..n {
            matrix[(i, j)] = r.f64()?;
        }
    }
    let row_sums = (0..n).map(|_| r.f64()).collect::<Result<Vec<_>, _>>()?;
    let length = r.u64()?;
    if length != (body.len() - 8) as u64 {
        return Err("length field mismatch".into());
    }
    Ok(FormFactors {
        matrix,
        reciprocity_mismatch,
        reciprocity_share,
        row_sums,
    })
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
    use super::*;
    use crate::geometry::Polygon;

    fn square(x: f64, z: f64, up: bool) -> Patch {
        let v = |a: f64, b: f64| Vec3::new(a, b, z);
        let mut corners = vec![v(x, 0.0), v(x + 1.0, 0.0), v(x + 1.0, 1.0), v(x, 1.0)];
        if !up {
            corners.reverse();
        }
        Patch::new(Polygon { vertices: corners }, 0)
    }

    /// Two facing unit squares 1 m apart: a floor and a ceiling.
    fn pair() -> Vec<Patch> {
        vec![square(0.0, 0.0, true), square(0.0, 1.0, false)]
    }

    fn scratch(name: &str) -> PathBuf {
        let dir =
            std::env::temp_dir().join(format!("eigenrad-cache-{name}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        dir
    }

    #[test]
    fn an_entry_reads_back_to_the_bit() {
        let patches = pair();
        let ff = formfactor::patch_form_factors(&patches, &FormFactorOptions::default());
        let key = key(&patches, &[], &FormFactorOptions::default());
        let back = decode(&encode(&ff, &key), &key, 2).unwrap();
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
    fn the_key_changes_with_the_geometry_and_the_settings_but_not_with_progress() {
        let patches = pair();
        let base = FormFactorOptions::default();
        let k = key(&patches, &[], &base);
        let mut moved = pair();
        moved[1] = square(0.0, 1.5, false);
        assert_ne!(k, key(&moved, &[], &base));
        let finer = FormFactorOptions {
            gauss_order: 6,
            ..FormFactorOptions::default()
        };
        assert_ne!(k, key(&patches, &[], &finer));
        let tolerance = FormFactorOptions {
            quadrature_tolerance: 1e-7,
            ..FormFactorOptions::default()
        };
        assert_ne!(k, key(&patches, &[], &tolerance));
        let shown = FormFactorOptions {
            progress: true,
            cache: Some(PathBuf::from("/elsewhere")),
            ..FormFactorOptions::default()
        };
        assert_eq!(k, key(&patches, &[], &shown));
    }

    #[test]
    fn every_damaged_entry_is_refused() {
        let patches = pair();
        let ff = formfactor::patch_form_factors(&patches, &FormFactorOptions::default());
        let key = key(&patches, &[], &FormFactorOptions::default());
        let good = encode(&ff, &key);
        // Each byte flipped in turn, and every truncation: all refused.
        for at in 0..good.len() {
            let mut bad = good.clone();
            bad[at] ^= 0x20;
            assert!(decode(&bad, &key, 2).is_err(), "flipped byte {at} accepted");
        }
        for len in 0..good.len() {
            assert!(
                decode(&good[..len], &key, 2).is_err(),
                "{len} bytes accepted"
            );
        }
        let mut other = key;
        other[0] ^= 1;
        assert!(decode(&good, &other, 2).unwrap_err().contains("key"));
        assert!(decode(&good, &key, 3).is_err());
    }

    #[test]
    fn a_corrupt_entry_on_disk_is_recomputed_and_replaced() {
        let dir = scratch("corrupt");
        let patches = pair();
        let opts = FormFactorOptions {
            cache: Some(dir.clone()),
            ..FormFactorOptions::default()
        };
        let fresh = form_factors(&patches, &[], &Occluders::new(&patches), &opts);
        let path = entry_path(&dir, &key(&patches, &[], &opts));
        let stored = std::fs::read(&path).unwrap();
        // Half an entry, as a killed writer could not leave but a full disk or a copy might.
        std::fs::write(&path, &stored[..stored.len() / 2]).unwrap();
        let again = form_factors(&patches, &[], &Occluders::new(&patches), &opts);
        assert_eq!(
            again.matrix[(0, 1)].to_bits(),
            fresh.matrix[(0, 1)].to_bits()
        );
        assert_eq!(std::fs::read(&path).unwrap(), stored, "entry not rewritten");
        std::fs::remove_dir_all(&dir).ok();
    }
}
