//! The form-factor cache: the patch form factors of a scene and its sensor and zone rows,
//! kept on disk so that `solve`, `verify`, `build` and `form-factors` on the same scene content
//! reuse them instead of computing them again (most of those commands' time on a large scene).
//!
//! An entry is named by a SHA-256 key of everything it depends on. For the patch form factors
//! ([`key`]): every patch (corners, normal, area, centroid, surface index) and every face the
//! occluders are built from, in order, every [`FormFactorOptions`] field the computation reads,
//! the crate version and [`formfactor::ALGORITHM_VERSION`]. For the sensor and zone rows
//! ([`rows_key`]): that key, every sensor (position, normal, field of view) and every zone
//! (its patches, or its work plane's height and receivers). Two scene files that mesh to the
//! same patches share entries; any change to the geometry, the meshing, the sensors, the zones
//! or the settings is another key. Channel levels, reflectances and luminaires do not enter:
//! the form factors do not read them.
//!
//! The cache is only ever a copy: it is written atomically (`atomic.rs`), may be deleted at
//! any time, and an entry that fails any check (length, SHA-256 checksum, magic, version, kind,
//! key, dimensions) is reported on standard error and recomputed, never used. Entries hold
//! `f64`s, so results with and without the cache are the same to the bit. Entries larger than
//! [`MAX_ENTRY_BYTES`] are not written.
//!
//! Where it lives: `$EIGENRAD_CACHE_DIR`, else `$XDG_CACHE_HOME/eigenrad`, else
//! `$HOME/.cache/eigenrad` ([`default_dir`]); the `eigenrad` commands' `--no-cache` turns it
//! off. Library calls use no cache unless [`FormFactorOptions::cache`] names a folder.
//!
//! Entry layout (little-endian): magic `EIGENRFF`, entry version (u32), kind (u32: 1 patch
//! form factors, 2 sensor and zone rows), key (32 bytes), rows and columns (u64 each), the
//! values (f64 each), the length of everything before this field (u64), and the SHA-256 of
//! everything before the checksum (32 bytes). Patch form factors (n × n) hold the reciprocity
//! mismatch and share, the matrix column by column and the row sums (n² + n + 2 values);
//! sensor and zone rows (r × n) hold the rows one after the other.

use std::io::Write as _;
use std::path::{Path, PathBuf};

use faer::Mat;
use sha2::{Digest, Sha256};

use crate::atomic;
use crate::formfactor::{self, outputs, FormFactorOptions, FormFactors, Occluders, WORST_PAIRS};
use crate::geometry::{Face, Patch, Vec3};
use crate::scene::{Scene, ZoneKind};

/// Largest entry written, bytes (256 MiB: the patch form factors of up to about 5 800
/// patches). Larger ones are recomputed every time rather than fill the disk unasked.
pub const MAX_ENTRY_BYTES: u64 = 256 << 20;

const MAGIC: &[u8; 8] = b"EIGENRFF";
/// Version of the entry layout above; another layout is another key, so old entries are
/// simply never read again.
const ENTRY_VERSION: u32 = 3;
/// Magic, version, kind, key, rows, columns.
const HEADER_BYTES: usize = 8 + 4 + 4 + 32 + 8 + 8;
/// Payload length and checksum.
const TRAILER_BYTES: usize = 8 + 32;

/// What an entry holds, and its shape.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Kind {
    /// [`FormFactors`] of n patches: n × n.
    Patches,
    /// Sensor and zone rows over n patches: r × n.
    Rows,
}

impl Kind {
    fn tag(self) -> u32 {
        match self {
            Kind::Patches => 1,
            Kind::Rows => 2,
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
        }
    }
}

/// The folder the `eigenrad` commands keep form factors in: `$EIGENRAD_CACHE_DIR`, else
/// `$XDG_CACHE_HOME/eigenrad`, else `$HOME/.cache/eigenrad`; `None` when none of them is set.
pub fn default_dir() -> Option<PathBuf> {
    let var = |name| std::env::var_os(name).filter(|v| !v.is_empty());
    var("EIGENRAD_CACHE_DIR")
        .map(PathBuf::from)
        .or_else(|| var("XDG_CACHE_HOME").map(|d| PathBuf::from(d).join("eigenrad")))
        .or_else(|| var("HOME").map(|d| PathBuf::from(d).join(".cache").join("eigenrad")))
}

fn hash_point(h: &mut Sha256, p: &Vec3) {
    for c in [p.x, p.y, p.z] {
        h.update(c.to_bits().to_le_bytes());
    }
}

fn hash_usize(h: &mut Sha256, x: usize) {
    h.update((x as u64).to_le_bytes());
}

fn hash_patches(h: &mut Sha256, patches: &[Patch]) {
    hash_usize(h, patches.len());
    for p in patches {
        hash_usize(h, p.polygon.vertices.len());
        for v in &p.polygon.vertices {
            hash_point(h, v);
        }
        hash_point(h, &p.normal);
        hash_point(h, &p.centroid);
        h.update(p.area.to_bits().to_le_bytes());
        hash_usize(h, p.surface);
    }
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
        operator: _,
    } = opts;
    let mut h = Sha256::new();
    h.update(b"eigenrad patch form factors\0");
    h.update(env!("CARGO_PKG_VERSION").as_bytes());
    h.update([0]);
    h.update(formfactor::ALGORITHM_VERSION.to_le_bytes());
    h.update(ENTRY_VERSION.to_le_bytes());
    for x in [*gauss_order, *touching_order, *occluded_order] {
        hash_usize(&mut h, x);
    }
    h.update(u64::from(*visibility_depth).to_le_bytes());
    h.update(quadrature_tolerance.to_bits().to_le_bytes());
    h.update(visibility_cell_share.to_bits().to_le_bytes());
    hash_patches(&mut h, patches);
    hash_usize(&mut h, faces.len());
    for f in faces {
        hash_usize(&mut h, f.patches.start);
        hash_usize(&mut h, f.patches.end);
        hash_usize(&mut h, f.polygon.vertices.len());
        for v in &f.polygon.vertices {
            hash_point(&mut h, v);
        }
    }
    h.finalize().into()
}

/// The key of the output rows of `scene` under `opts`: the patch form factors' key, every
/// sensor, every zone and every zone's calculation-grid points.
pub fn rows_key(scene: &Scene, opts: &FormFactorOptions) -> [u8; 32] {
    let mut h = Sha256::new();
    h.update(b"eigenrad sensor and zone rows\0");
    h.update(key(&scene.patches, &scene.faces, opts));
    hash_usize(&mut h, scene.sensors.len());
    for s in &scene.sensors {
        hash_point(&mut h, &s.position);
        hash_point(&mut h, &s.normal);
        match s.half_angle {
            None => h.update([0]),
            Some(a) => {
                h.update([1]);
                h.update(a.to_bits().to_le_bytes());
            }
        }
    }
    hash_usize(&mut h, scene.zones.len());
    for z in &scene.zones {
        match &z.kind {
            ZoneKind::Surfaces(patches) => {
                h.update([0]);
                hash_usize(&mut h, patches.len());
                for &p in patches {
                    hash_usize(&mut h, p);
                }
            }
            ZoneKind::WorkPlane { height, receivers } => {
                h.update([1]);
                h.update(height.to_bits().to_le_bytes());
                hash_patches(&mut h, receivers);
            }
        }
    }
    hash_usize(&mut h, outputs::grid_points(scene).count());
    for (zone, position, normal) in outputs::grid_points(scene) {
        hash_usize(&mut h, zone);
        hash_point(&mut h, &position);
        hash_point(&mut h, &normal);
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
    let compute = || formfactor::patch_form_factors_with(patches, occluders, opts);
    let Some(dir) = &opts.cache else {
        return compute();
    };
    let n = patches.len() as u64;
    let key = key(patches, faces, opts);
    cached(
        dir,
        Kind::Patches,
        &key,
        (n, n),
        compute,
        patch_values,
        |v| from_patch_values(v, patches.len()),
    )
}

/// The output rows of `scene` (sensors, zones, grid points: [`outputs::output_rows`], same
/// arguments), from the cache in `opts.cache` or computed and stored there, as [`form_factors`].
pub fn output_rows(
    scene: &Scene,
    g: &dyn crate::formfactor::FormFactorOperator,
    area: &[f64],
    occluders: &Occluders,
    opts: &FormFactorOptions,
) -> Vec<Vec<f64>> {
    let compute = || outputs::output_rows(scene, g, area, occluders, opts);
    let Some(dir) = &opts.cache else {
        return compute();
    };
    let n = scene.patches.len();
    let rows = (outputs::grid_offset(scene) + outputs::grid_points(scene).count()) as u64;
    let key = rows_key(scene, opts);
    cached(
        dir,
        Kind::Rows,
        &key,
        (rows, n as u64),
        compute,
        |r: &Vec<Vec<f64>>| r.iter().flatten().copied().collect(),
        |v| {
            Ok(if n == 0 {
                vec![Vec::new(); rows as usize]
            } else {
                v.chunks(n).map(<[f64]>::to_vec).collect()
            })
        },
    )
}

/// The value of `key` from `dir` when its entry is sound, else `compute()`d and stored.
fn cached<T>(
    dir: &Path,
    kind: Kind,
    key: &[u8; 32],
    dims: (u64, u64),
    compute: impl FnOnce() -> T,
    to_values: impl Fn(&T) -> Vec<f64>,
    from_values: impl Fn(Vec<f64>) -> Result<T, String>,
) -> T {
    let path = entry_path(dir, key);
    match std::fs::read(&path) {
        Ok(bytes) => match decode(&bytes, kind, key, dims).and_then(&from_values) {
            Ok(value) => return value,
            Err(reason) => warn(&format!(
                "form-factor cache entry {} is unusable ({reason}); computing it again",
                path.display()
            )),
        },
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => {}
        Err(e) => warn(&format!(
            "cannot read form-factor cache entry {} ({e}); computing it again",
            path.display()
        )),
    }
    let value = compute();
    if entry_bytes(kind, dims).is_some_and(|b| b <= MAX_ENTRY_BYTES) {
        let bytes = encode(kind, key, dims, &to_values(&value));
        let stored = std::fs::create_dir_all(dir)
            .map_err(|e| format!("{}: {e}", dir.display()))
            .and_then(|()| atomic::write(&path, &bytes).map_err(|e| e.to_string()));
        if let Err(reason) = stored {
            warn(&format!("form factors not cached: {reason}"));
        }
    }
    value
}

/// A warning on standard error; a closed standard error is no reason to fail.
fn warn(text: &str) {
    let _ = writeln!(std::io::stderr(), "warning: {text}");
}

/// Bytes of an entry, `None` past `u64`.
fn entry_bytes(kind: Kind, (rows, cols): (u64, u64)) -> Option<u64> {
    kind.values(rows, cols)?
        .checked_mul(8)?
        .checked_add((HEADER_BYTES + TRAILER_BYTES) as u64)
}

/// The values of a patch form-factor entry.
fn patch_values(ff: &FormFactors) -> Vec<f64> {
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

fn from_patch_values(values: Vec<f64>, n: usize) -> Result<FormFactors, String> {
    if values.len() != n * n + n + 2 + 3 * WORST_PAIRS {
        return Err("wrong number of values".into());
    }
    let matrix = Mat::from_fn(n, n, |i, j| values[2 + j * n + i]);
    let pairs_at = 2 + n * n + n;
    let mut worst_pairs = Vec::new();
    for slot in values[pairs_at..].chunks_exact(3) {
        let index = |x: f64| {
            (x >= 0.0 && x < n as f64 && x.fract() == 0.0)
                .then_some(x as usize)
                .ok_or_else(|| "a worst pair names no patch".to_string())
        };
        if slot[0] >= 0.0 {
            worst_pairs.push((index(slot[0])?, index(slot[1])?, slot[2]));
        }
    }
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

fn encode(kind: Kind, key: &[u8; 32], (rows, cols): (u64, u64), values: &[f64]) -> Vec<u8> {
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

/// The values of an entry, or what is wrong with it; `dims` are the ones expected.
fn decode(bytes: &[u8], kind: Kind, key: &[u8; 32], dims: (u64, u64)) -> Result<Vec<f64>, String> {
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
    fn the_rows_key_follows_the_sensors_and_zones_and_the_patch_key_does_not() {
        let dir = scratch("rows-key");
        std::fs::create_dir_all(&dir).unwrap();
        let text = |x: f64, margin: f64| {
            format!(
                "[scene]\nname = \"box\"\nbands = \"photopic\"\nunit = \"m\"\nmax_edge = 1\n\n\
                 [materials]\nwall = {{ reflectance = 0.5 }}\n\n\
                 [[room]]\nname = \"room\"\nmin = [0, 0, 0]\nmax = [2, 2, 2]\nmaterial = \"wall\"\n\n\
                 [[sensor]]\nname = \"s\"\nposition = [{x}, 1, 0.5]\nnormal = [0, 0, 1]\n\n\
                 [[zone]]\nname = \"wp\"\nwork_plane = {{ height = 0.8, margin = {margin} }}\n"
            )
        };
        let load = |name: &str, body: String| {
            let path = dir.join(name);
            std::fs::write(&path, body).unwrap();
            crate::scene::load(&path).unwrap()
        };
        let opts = FormFactorOptions::default();
        let base = load("a.toml", text(1.0, 0.2));
        let moved = load("b.toml", text(1.5, 0.2));
        let narrower = load("c.toml", text(1.0, 0.3));
        let same = load("d.toml", text(1.0, 0.2));
        let patches = |s: &Scene| key(&s.patches, &s.faces, &opts);
        assert_eq!(patches(&base), patches(&moved));
        assert_eq!(patches(&base), patches(&narrower));
        assert_ne!(rows_key(&base, &opts), rows_key(&moved, &opts));
        assert_ne!(rows_key(&base, &opts), rows_key(&narrower, &opts));
        assert_eq!(rows_key(&base, &opts), rows_key(&same, &opts));
        std::fs::remove_dir_all(&dir).ok();
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
