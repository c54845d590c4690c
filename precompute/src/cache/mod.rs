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
//! form factors, 2 sensor and zone rows, 3 hierarchical form factors), key (32 bytes), rows
//! and columns (u64 each), the values (f64 each), the length of everything before this field
//! (u64), and the SHA-256 of everything before the checksum (32 bytes). Patch form factors
//! (n × n) hold the reciprocity mismatch and share, the matrix column by column and the row
//! sums (n² + n + 2 values); sensor and zone rows (r × n) hold the rows one after the other;
//! hierarchical form factors (n × the count of values) hold the reciprocity mismatch and
//! share, the row sums, the worst pairs and the operator's numbers (its tree, its blocks'
//! f32 numbers widened to f64 and its compression figures:
//! `formfactor::hierarchical` module `stored`), and are keyed on the compression's settings
//! too ([`hierarchical_key`]).
//!
//! The parts: the keys ([`key`], [`rows_key`]; `keys.rs`), the entry format and its checks
//! (`entry.rs`), and the lookups that read a sound entry or compute the value and store it
//! ([`form_factors`], [`hierarchical_form_factors`], [`output_rows`]; `lookup.rs`).
//!
//! [`FormFactorOptions`]: crate::formfactor::FormFactorOptions
//! [`FormFactorOptions::cache`]: crate::formfactor::FormFactorOptions::cache
//! [`formfactor::ALGORITHM_VERSION`]: crate::formfactor::ALGORITHM_VERSION

mod entry;
#[cfg(test)]
mod fixtures;
mod keys;
mod lookup;

use std::path::{Path, PathBuf};

pub use entry::encode_form_factors;
pub use keys::{hierarchical_key, key, rows_key};
pub use lookup::{form_factors, hierarchical_form_factors, output_rows};

/// Largest entry written, bytes (256 MiB: the patch form factors of up to about 5 800
/// patches). Larger ones are recomputed every time rather than fill the disk unasked.
pub const MAX_ENTRY_BYTES: u64 = 256 << 20;

// The form factors `auto` keeps in f64 fit an entry (`memory::AUTO_HIERARCHICAL_ABOVE`): a second run
// of the same scene reads them back.
const _: () = {
    let n = crate::memory::AUTO_HIERARCHICAL_ABOVE as u64;
    assert!(8 * n * n <= MAX_ENTRY_BYTES);
};

/// The folder the `eigenrad` commands keep form factors in: `$EIGENRAD_CACHE_DIR`, else
/// `$XDG_CACHE_HOME/eigenrad`, else `$HOME/.cache/eigenrad`; `None` when none of them is set.
pub fn default_dir() -> Option<PathBuf> {
    let var = |name| std::env::var_os(name).filter(|v| !v.is_empty());
    var("EIGENRAD_CACHE_DIR")
        .map(PathBuf::from)
        .or_else(|| var("XDG_CACHE_HOME").map(|d| PathBuf::from(d).join("eigenrad")))
        .or_else(|| var("HOME").map(|d| PathBuf::from(d).join(".cache").join("eigenrad")))
}

/// The entry file of `key` in `dir`.
pub fn entry_path(dir: &Path, key: &[u8; 32]) -> PathBuf {
    let hex: String = key.iter().map(|b| format!("{b:02x}")).collect();
    dir.join(format!("ff-{hex}.bin"))
}
