//! The cached lookups: a value read from its entry when the entry is sound, else computed and
//! stored; cache trouble is a warning, never an error.

use std::io::Write as _;
use std::path::Path;

use super::entry::{decode, encode, entry_bytes, from_patch_values, patch_values, Kind};
use super::{entry_path, key, rows_key, MAX_ENTRY_BYTES};
use crate::atomic;
use crate::formfactor::{self, outputs, FormFactorOptions, FormFactors, Occluders};
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

#[cfg(test)]
mod tests {
    use super::super::fixtures::{pair, scratch};
    use super::*;

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
