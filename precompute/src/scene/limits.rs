//! Refusing scenes too large for the machine before meshing them.
//!
//! The radiosity system is dense: the form factors `G` (n × n f64), the exact solve's LU
//! factors and the eigensolver's workspace are each about n² × 8 bytes. A scene whose
//! estimated patch count needs more than the machine's physical memory for three such
//! matrices is refused with the estimate, in milliseconds, instead of running out of memory
//! while meshing or computing form factors.

use super::context::RawSurface;
use super::error::{Location, SceneError};
use super::mesh::estimate;

/// Dense n × n matrices of f64 that a build holds at once (form factors, LU or eigenvector
/// workspace, and a copy while symmetrising).
pub(crate) const DENSE_MATRICES: f64 = 3.0;

/// Bytes per matrix entry (f64).
const ENTRY_BYTES: f64 = 8.0;

/// Memory assumed when the platform does not tell (bytes).
const ASSUMED_MEMORY: f64 = 8e9;

/// Checks the patch count `surfaces` would mesh to against physical memory.
///
/// `default_edge` is the scene's `max_edge` (m) and `default_at` where it was written; the
/// error names the setting behind the largest share of the patches.
pub(crate) fn check(
    surfaces: &[RawSurface],
    default_edge: f64,
    default_at: &Location,
) -> Result<(), SceneError> {
    let mut total = 0.0;
    let mut largest: Option<(f64, &RawSurface)> = None;
    for s in surfaces {
        let edge = s.max_edge.unwrap_or(default_edge);
        let count: f64 = s.faces.iter().map(|f| estimate(f, edge)).sum();
        total += count;
        if largest.is_none_or(|(c, _)| count > c) {
            largest = Some((count, s));
        }
    }
    let needed = total * total * ENTRY_BYTES * DENSE_MATRICES;
    let available = physical_memory_bytes();
    if needed <= available {
        return Ok(());
    }
    let (at, field) = match largest {
        Some((_, s)) if s.max_edge.is_some() => {
            (s.at.clone(), format!("surface `{}` max_edge", s.name))
        }
        _ => (default_at.clone(), "scene.max_edge".to_string()),
    };
    Err(SceneError::TooManyPatches {
        at,
        field,
        patches: total,
        needed,
        available,
    })
}

/// Physical memory in bytes (Linux `/proc/meminfo`; [`ASSUMED_MEMORY`] elsewhere).
fn physical_memory_bytes() -> f64 {
    std::fs::read_to_string("/proc/meminfo")
        .ok()
        .and_then(|s| {
            s.lines()
                .find(|l| l.starts_with("MemTotal:"))
                .and_then(|l| l.split_whitespace().nth(1))
                .and_then(|kb| kb.parse::<f64>().ok())
        })
        .map_or(ASSUMED_MEMORY, |kb| kb * 1024.0)
}
