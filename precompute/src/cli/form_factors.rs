//! `eigenrad form-factors`: surface-to-surface form factors, area-weighted over each
//! surface's patches.

use super::figures::fixed;
use std::fmt::Write as _;
use std::path::Path;

use serde::Serialize;

use crate::error::Result;
use crate::formfactor::{FormFactorHealth, FormFactorOptions};
use crate::pipeline;

/// What `eigenrad form-factors` prints: every surface pair and the health of the patch form
/// factors they were summed from.
#[derive(Clone, Debug, Serialize)]
pub struct FormFactorTable {
    /// Every ordered pair of surfaces, in scene order, zeros included.
    pub factors: Vec<SurfaceFactor>,
    /// Reciprocity, row sums, closure of the closed cavities, worst pairs, warnings.
    pub health: FormFactorHealth,
}

/// One line per surface pair (a pair that exchanges nothing says so), then the health: the
/// closure of each closed cavity, the worst pairs and the warnings.
pub fn format_surface_form_factors(table: &FormFactorTable) -> String {
    let mut s = String::new();
    for row in &table.factors {
        if row.value == 0.0 {
            let _ = writeln!(s, "{:>24} -> {:<24} 0 (no exchange)", row.from, row.to);
        } else {
            let _ = writeln!(s, "{:>24} -> {:<24} {:.6}", row.from, row.to, row.value);
        }
    }
    s += &format_health(&table.health);
    s
}

/// The health lines shared by `form-factors` and the build report: row sums, the closure of
/// each closed cavity, the pairs whose two directions disagreed most, and one `warning:` line
/// per cavity that does not close.
pub fn format_health(f: &FormFactorHealth) -> String {
    let mut s = String::new();
    let _ = writeln!(
        s,
        "form factors: before symmetrising, the two directions of a pair differ by at most {:.1e} of a patch's output ({:.1e} relative to the exchange, floored at 0.1 % of the output); row sums {:.5} .. {:.5}; {}",
        f.reciprocity_share,
        f.reciprocity_mismatch,
        f.row_sum_min,
        f.row_sum_max,
        if f.closed {
            "closed scene".to_owned()
        } else {
            format!(
                "open scene: {} % of the light leaving the surfaces escapes through openings",
                fixed(100.0 * f.escaping, 2)
            )
        }
    );
    for c in &f.cavities {
        let worst = c.worst_rows.first().map_or(String::new(), |w| {
            format!(
                "; furthest from 1: patch {} ({}) at {:.6}",
                w.patch, w.surface, w.row_sum
            )
        });
        let _ = writeln!(
            s,
            "  closed cavity of {} surfaces, {} patches: row sums {:.6} .. {:.6} (exactly 1 for exact form factors){worst}",
            c.surfaces.len(),
            c.patches,
            c.row_sum_min,
            c.row_sum_max,
        );
    }
    if !f.worst_pairs.is_empty() {
        let pairs: Vec<String> = f
            .worst_pairs
            .iter()
            .map(|p| {
                format!(
                    "{:.1e} (patches {} {} and {} {})",
                    p.share, p.patches[0], p.surfaces[0], p.patches[1], p.surfaces[1]
                )
            })
            .collect();
        let _ = writeln!(
            s,
            "  pairs whose directions disagree most (share of the smaller patch's output): {}",
            pairs.join(", ")
        );
    }
    for w in &f.warnings {
        let _ = writeln!(s, "warning: {w}");
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

/// `eigenrad form-factors`: surface-to-surface form factors (area-weighted), the non-zero
/// ones (see [`form_factor_table`] for every pair and the health), computed with `opts` (its
/// progress bar and cache).
pub fn surface_form_factors(
    scene_path: &Path,
    opts: &FormFactorOptions,
) -> Result<Vec<SurfaceFactor>> {
    let mut table = form_factor_table(scene_path, opts)?;
    table.factors.retain(|f| f.value != 0.0);
    Ok(table.factors)
}

/// `eigenrad form-factors`: every surface-to-surface form factor (area-weighted; pairs that
/// exchange nothing as 0) and the health of the patch form factors, computed with `opts`.
pub fn form_factor_table(scene_path: &Path, opts: &FormFactorOptions) -> Result<FormFactorTable> {
    let prepared = pipeline::prepare(scene_path, opts)?;
    let scene = &prepared.scene;
    let s = scene.surfaces.len();
    let mut sums = vec![vec![0.0f64; s]; s];
    let mut areas = vec![0.0f64; s];
    let g = prepared.system.operator();
    let mut row = vec![0.0; g.len()];
    for (i, p) in scene.patches.iter().enumerate() {
        areas[p.surface] += p.area;
        g.row(i, &mut row);
        for (q, x) in scene.patches.iter().zip(&row) {
            sums[p.surface][q.surface] += x;
        }
    }
    let mut out = Vec::new();
    for a in 0..s {
        for b in 0..s {
            if areas[a] > 0.0 {
                out.push(SurfaceFactor {
                    from: scene.surfaces[a].name.clone(),
                    to: scene.surfaces[b].name.clone(),
                    value: sums[a][b] / areas[a],
                });
            }
        }
    }
    Ok(FormFactorTable {
        factors: out,
        health: prepared.form_factor_health,
    })
}
