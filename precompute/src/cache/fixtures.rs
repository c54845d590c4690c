//! Patches and scratch folders the cache's tests share.

use std::path::PathBuf;

use crate::geometry::{Patch, Polygon, Vec3};

/// A unit square at height `z` (m) from `x` to `x + 1` along x, facing up or down.
pub(super) fn square(x: f64, z: f64, up: bool) -> Patch {
    let v = |a: f64, b: f64| Vec3::new(a, b, z);
    let mut corners = vec![v(x, 0.0), v(x + 1.0, 0.0), v(x + 1.0, 1.0), v(x, 1.0)];
    if !up {
        corners.reverse();
    }
    Patch::new(Polygon { vertices: corners }, 0)
}

/// Two facing unit squares 1 m apart: a floor and a ceiling.
pub(super) fn pair() -> Vec<Patch> {
    vec![square(0.0, 0.0, true), square(0.0, 1.0, false)]
}

/// A folder under the system's temporary folder for test `name` of this process, removed
/// first if an earlier run left it.
pub(super) fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("eigenrad-cache-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    dir
}
