//! Refusing scenes too large for the machine before meshing them.
//!
//! A scene whose estimated patch count would make a build hold more than the machine can
//! spare ([`crate::memory::build_bytes`] against [`crate::memory::budget_bytes`], taking
//! every patch as reflecting: reflectance is resolved only while meshing) is refused with
//! the estimate, in milliseconds, instead of running out of memory while meshing or
//! computing form factors.

use super::context::RawSurface;
use super::error::{Location, SceneError};
use super::mesh::estimate;
use crate::memory;

/// Checks the patch count `surfaces` would mesh to, in `bands` bands, against the memory a
/// build may use.
///
/// `default_edge` is the scene's `max_edge` (m) and `default_at` where it was written; the
/// error names the setting behind the largest share of the patches.
pub(crate) fn check(
    surfaces: &[RawSurface],
    bands: usize,
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
    let needed = memory::build_bytes(total, &vec![total; bands]);
    let available = memory::budget_bytes();
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
