//! `eigenrad form-factors`: surface-to-surface form factors, area-weighted over each
//! surface's patches.

use std::fmt::Write as _;
use std::path::Path;

use serde::Serialize;

use crate::error::Result;
use crate::formfactor::FormFactorOptions;
use crate::pipeline;

/// One line per non-zero surface-to-surface form factor.
pub fn format_surface_form_factors(table: &[SurfaceFactor]) -> String {
    let mut s = String::new();
    for row in table {
        let _ = writeln!(s, "{:>24} -> {:<24} {:.6}", row.from, row.to, row.value);
    }
    s
}

/// One surface-to-surface form factor.
#[derive(Clone, Debug, Serialize)]
pub struct SurfaceFactor {
    /// Emitting surface.
    pub from: String,
    /// Receiving surface.
    pub to: String,
    /// `F_ST = Σ_{i∈S} Σ_{j∈T} A_i F_ij / A_S`.
    pub value: f64,
}

/// `eigenrad form-factors`: surface-to-surface form factors (area-weighted), non-zero ones,
/// computed with `opts` (its progress bar and cache).
pub fn surface_form_factors(
    scene_path: &Path,
    opts: &FormFactorOptions,
) -> Result<Vec<SurfaceFactor>> {
    let prepared = pipeline::prepare(scene_path, opts)?;
    let scene = &prepared.scene;
    let s = scene.surfaces.len();
    let mut sums = vec![vec![0.0f64; s]; s];
    let mut areas = vec![0.0f64; s];
    for (i, p) in scene.patches.iter().enumerate() {
        areas[p.surface] += p.area;
        for (j, q) in scene.patches.iter().enumerate() {
            sums[p.surface][q.surface] += prepared.g[(i, j)];
        }
    }
    let mut out = Vec::new();
    for a in 0..s {
        for b in 0..s {
            if sums[a][b] != 0.0 && areas[a] > 0.0 {
                out.push(SurfaceFactor {
                    from: scene.surfaces[a].name.clone(),
                    to: scene.surfaces[b].name.clone(),
                    value: sums[a][b] / areas[a],
                });
            }
        }
    }
    Ok(out)
}
