//! The cached lookups: a value read from its entry when the entry is sound, else computed and
//! stored; cache trouble is a warning, never an error.

use std::io::Write as _;
use std::path::Path;

use super::entry::{
    declared_dims, decode, encode, entry_bytes, from_hierarchical_values, from_patch_values,
    hierarchical_values, patch_values, Kind,
};
use super::{entry_path, hierarchical_key, key, rows_key, MAX_ENTRY_BYTES};
use crate::atomic;
use crate::formfactor::hierarchical::{NonFiniteEntry, Settings};
use crate::formfactor::{self, outputs, FormFactorOptions, FormFactors, Hierarchical, Occluders};
use crate::geometry::{Face, Patch};
use crate::scene::Scene;

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

/// The hierarchical form factors of `patches` ([`formfactor::patch_form_factors_hierarchical`],
/// same arguments), from the cache in `opts.cache` when it holds a sound entry for them, else
/// computed and stored there, as [`form_factors`]. The operator read back is the one stored,
/// to the bit.
pub fn hierarchical_form_factors(
    patches: &[Patch],
    faces: &[Face],
    occluders: &Occluders,
    opts: &FormFactorOptions,
    settings: &Settings,
) -> Result<FormFactors<Hierarchical>, NonFiniteEntry> {
    let compute =
        || formfactor::patch_form_factors_hierarchical(patches, occluders, opts, settings);
    let Some(dir) = &opts.cache else {
        return compute();
    };
    let n = patches.len();
    let key = hierarchical_key(patches, faces, opts, settings);
    let path = entry_path(dir, &key);
    // The count of values depends on the ranks: the entry's header says it, and the length
    // and checksum checks hold it to the bytes.
    let read = read_entry(&path, |bytes| {
        let (rows, values) = declared_dims(bytes).ok_or("too short for a header")?;
        if rows != n as u64 {
            return Err("dimension mismatch".into());
        }
        decode(bytes, Kind::Hierarchical, &key, (rows, values))
            .and_then(|v| from_hierarchical_values(v, n))
    });
    if let Some(ff) = read {
        return Ok(ff);
    }
    let ff = compute()?;
    let values = hierarchical_values(&ff);
    store_entry(
        dir,
        &path,
        Kind::Hierarchical,
        &key,
        (n as u64, values.len() as u64),
        &values,
    );
    Ok(ff)
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
    if let Some(value) = read_entry(&path, |bytes| {
        decode(bytes, kind, key, dims).and_then(&from_values)
    }) {
        return value;
    }
    let value = compute();
    store_entry(dir, &path, kind, key, dims, &to_values(&value));
    value
}

/// The value of the entry at `path` through `read`, or `None` (with a warning when an entry
/// is there but unusable).
fn read_entry<T>(path: &Path, read: impl FnOnce(&[u8]) -> Result<T, String>) -> Option<T> {
    match std::fs::read(path) {
        Ok(bytes) => match read(&bytes) {
            Ok(value) => return Some(value),
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
    None
}

/// Writes `values` as the entry at `path` in `dir`, atomically, unless it would exceed
/// [`MAX_ENTRY_BYTES`]; trouble is a warning.
fn store_entry(
    dir: &Path,
    path: &Path,
    kind: Kind,
    key: &[u8; 32],
    dims: (u64, u64),
    values: &[f64],
) {
    if entry_bytes(kind, dims).is_none_or(|b| b > MAX_ENTRY_BYTES) {
        return;
    }
    let bytes = encode(kind, key, dims, values);
    let stored = std::fs::create_dir_all(dir)
        .map_err(|e| format!("{}: {e}", dir.display()))
        .and_then(|()| atomic::write(path, &bytes).map_err(|e| e.to_string()));
    if let Err(reason) = stored {
        warn(&format!("form factors not cached: {reason}"));
    }
}

/// A warning on standard error; a closed standard error is no reason to fail.
fn warn(text: &str) {
    let _ = writeln!(std::io::stderr(), "warning: {text}");
}

#[cfg(test)]
mod tests {
    use super::super::fixtures::{pair, scratch, square};
    use super::*;

    /// A floor and a ceiling of 8 × 2 unit squares 2 m apart with a plate between them: a
    /// hierarchical operator with near and low-rank blocks and pairs a blocker cuts.
    fn hall() -> Vec<Patch> {
        let mut patches = Vec::new();
        for (z, up) in [(0.0, true), (2.0, false)] {
            for y in 0..2 {
                for x in 0..8 {
                    let mut p = square(x as f64, z, up);
                    for c in &mut p.polygon.vertices {
                        c.y += y as f64;
                    }
                    patches.push(Patch::new(p.polygon, 0));
                }
            }
        }
        patches.push(square(3.0, 1.0, true));
        patches
    }

    /// Reference: the operator computed without a cache. The second lookup reads the entry the
    /// first wrote: the same operator to the bit (every entry, the compression figures, the
    /// health figures). A damaged entry is recomputed and written again.
    #[test]
    fn a_hierarchical_operator_round_trips_through_its_entry() {
        let dir = scratch("hierarchical");
        let patches = hall();
        let n = patches.len();
        let occluders = Occluders::new(&patches);
        let settings = Settings {
            leaf: 4,
            tolerance: 1e-4,
            ..Settings::default()
        };
        let fresh = formfactor::patch_form_factors_hierarchical(
            &patches,
            &occluders,
            &FormFactorOptions::default(),
            &settings,
        )
        .expect("finite");
        assert!(fresh.matrix.compression().low_rank_blocks > 0);
        let opts = FormFactorOptions {
            cache: Some(dir.clone()),
            ..FormFactorOptions::default()
        };
        let path = entry_path(&dir, &hierarchical_key(&patches, &[], &opts, &settings));
        let same = |ff: &FormFactors<Hierarchical>| {
            use crate::formfactor::FormFactorOperator;
            let entries = (0..n).all(|i| {
                (0..n)
                    .all(|j| ff.matrix.entry(i, j).to_bits() == fresh.matrix.entry(i, j).to_bits())
            });
            entries
                && ff.matrix.compression() == fresh.matrix.compression()
                && ff.row_sums == fresh.row_sums
                && ff.worst_pairs == fresh.worst_pairs
                && ff.reciprocity_share.to_bits() == fresh.reciprocity_share.to_bits()
        };
        let lookup = || {
            hierarchical_form_factors(&patches, &[], &occluders, &opts, &settings).expect("finite")
        };
        assert!(same(&lookup()), "first lookup (computed)");
        let stored = std::fs::read(&path).expect("entry written");
        assert!(same(&lookup()), "second lookup (read)");
        // Read, not recomputed: an entry whose last number (the measured row error) was
        // changed, its checksum made good again, gives that number back.
        let key = hierarchical_key(&patches, &[], &opts, &settings);
        let dims = declared_dims(&stored).expect("a header");
        let mut values = decode(&stored, Kind::Hierarchical, &key, dims).expect("sound");
        *values.last_mut().expect("values") = 0.125;
        std::fs::write(&path, encode(Kind::Hierarchical, &key, dims, &values)).unwrap();
        assert_eq!(lookup().matrix.compression().row_error, 0.125);
        std::fs::write(&path, &stored[..stored.len() - 1]).unwrap();
        assert!(same(&lookup()), "after a damaged entry");
        assert_eq!(std::fs::read(&path).unwrap(), stored, "entry not rewritten");
        std::fs::remove_dir_all(&dir).ok();
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
