//! How far computed form factors are from the identities exact ones satisfy: reciprocity
//! (`A_i F_ij = A_j F_ji`) and closure (every row of a closed cavity sums to 1).

use serde::Serialize;

use super::{closure, FormFactors};
use crate::geometry::{Face, Patch};

/// Health of a scene's form-factor matrix: reciprocity before symmetrising and closure (row
/// sums) after, the figures `eigenrad build` reports.
#[derive(Clone, Debug, Serialize)]
pub struct FormFactorHealth {
    /// Worst reciprocity mismatch before symmetrising, relative to the pair's own exchange
    /// (or to 0.1 % of the smaller patch's output, whichever is larger).
    pub reciprocity_mismatch: f64,
    /// Worst reciprocity mismatch before symmetrising as a share of the smaller patch's
    /// output (`FormFactors::reciprocity_share`).
    pub reciprocity_share: f64,
    /// Smallest row sum of F after symmetrising.
    pub row_sum_min: f64,
    /// Largest row sum of F after symmetrising.
    pub row_sum_max: f64,
    /// Share of the light leaving the patches that leaves the scene: `Σ A_i (1 − Σ_j F_ij) /
    /// Σ A_i` (0 for a closed room; an open window or a missing ceiling raise it).
    pub escaping: f64,
    /// Whether every row sums to 1 within [`CLOSED_TOLERANCE`]: a closed scene. Otherwise the
    /// deficit is light leaving through openings.
    pub closed: bool,
    /// The closed cavities of the geometry (faces that enclose a volume, facing in; module
    /// `closure`) and how their rows sum: exact form factors give exactly 1 there.
    pub cavities: Vec<CavityClosure>,
    /// The pairs of patches whose two directions disagreed most before symmetrising, worst
    /// first.
    pub worst_pairs: Vec<PairDisagreement>,
    /// A warning for each cavity with a row further than [`CAVITY_TOLERANCE`] from 1, naming
    /// the surfaces of its worst rows.
    pub warnings: Vec<String>,
}

/// How the rows of one closed cavity sum.
#[derive(Clone, Debug, Serialize)]
pub struct CavityClosure {
    /// The surfaces whose faces make up the cavity, in scene order.
    pub surfaces: Vec<String>,
    /// Number of patches in the cavity.
    pub patches: usize,
    /// Smallest row sum of F over the cavity's patches (dimensionless).
    pub row_sum_min: f64,
    /// Largest row sum of F over the cavity's patches (dimensionless).
    pub row_sum_max: f64,
    /// The rows furthest from 1, worst first (at most [`WORST_ROWS`]).
    pub worst_rows: Vec<RowMiss>,
}

/// One patch's row sum.
#[derive(Clone, Debug, Serialize)]
pub struct RowMiss {
    /// Patch index in the scene.
    pub patch: usize,
    /// Its surface.
    pub surface: String,
    /// `Σ_j F_ij` (dimensionless).
    pub row_sum: f64,
}

/// A pair whose two directions disagree before symmetrising.
#[derive(Clone, Debug, Serialize)]
pub struct PairDisagreement {
    /// The two patches (scene indices, the smaller first).
    pub patches: [usize; 2],
    /// Their surfaces.
    pub surfaces: [String; 2],
    /// `|A_i F_ij − A_j F_ji| / min(A_i, A_j)` (dimensionless).
    pub share: f64,
}

/// Rows listed per cavity in [`CavityClosure::worst_rows`].
pub const WORST_ROWS: usize = 3;

/// Row-sum deviation in a closed cavity above which `build` and `form-factors` warn
/// (dimensionless). The quadrature keeps rows of closed cavities within a few 10⁻⁵ (10⁻⁵ on the
/// reference solids, whose patches touch along every edge) and occluded rows within a few
/// 10⁻⁴: a row further off than 10⁻³ points at geometry the rules do not resolve.
pub const CAVITY_TOLERANCE: f64 = 1e-3;

/// Row-sum deviation up to which a scene counts as closed. With occlusion the symmetrised
/// form factors are accurate to a few 10⁻⁴ per row (the fixed outer quadrature where a shadow
/// edge crosses a source patch), so a much tighter bound would call closed rooms open; an opening that matters takes far more than
/// 1 % of the view of the patches facing it.
pub const CLOSED_TOLERANCE: f64 = 1e-2;

impl FormFactorHealth {
    /// The health of `ff`, the form factors between `patches`, which were cut from `faces`;
    /// `surfaces` names the surfaces `Patch::surface` indexes.
    pub fn of<M>(
        ff: &FormFactors<M>,
        patches: &[Patch],
        faces: &[Face],
        surfaces: &[String],
    ) -> FormFactorHealth {
        let area: Vec<f64> = patches.iter().map(|p| p.area).collect();
        let name = |patch: usize| {
            patches
                .get(patch)
                .and_then(|p| surfaces.get(p.surface))
                .cloned()
                .unwrap_or_default()
        };
        let row_sum_min = ff.row_sums.iter().copied().fold(f64::INFINITY, f64::min);
        let row_sum_max = ff
            .row_sums
            .iter()
            .copied()
            .fold(f64::NEG_INFINITY, f64::max);
        let mut health = FormFactorHealth {
            reciprocity_mismatch: ff.reciprocity_mismatch,
            reciprocity_share: ff.reciprocity_share,
            row_sum_min,
            row_sum_max,
            escaping: ff
                .row_sums
                .iter()
                .zip(&area)
                .map(|(s, a)| a * (1.0 - s))
                .sum::<f64>()
                / area.iter().sum::<f64>(),
            closed: (row_sum_min - 1.0).abs() <= CLOSED_TOLERANCE
                && (row_sum_max - 1.0).abs() <= CLOSED_TOLERANCE,
            cavities: Vec::new(),
            worst_pairs: ff
                .worst_pairs
                .iter()
                .map(|&(i, j, share)| PairDisagreement {
                    patches: [i, j],
                    surfaces: [name(i), name(j)],
                    share,
                })
                .collect(),
            warnings: Vec::new(),
        };
        for faces_of_cavity in closure::cavities(faces) {
            let rows: Vec<usize> = faces_of_cavity
                .iter()
                .flat_map(|&f| faces[f].patches.clone())
                .filter(|&i| i < ff.row_sums.len())
                .collect();
            let Some(&first) = rows.first() else {
                continue;
            };
            let mut surface_ids: Vec<usize> = rows.iter().map(|&i| patches[i].surface).collect();
            surface_ids.sort_unstable();
            surface_ids.dedup();
            let mut worst = rows.clone();
            // Worst first; ties by patch index, so the report is deterministic.
            worst.sort_by(|&a, &b| {
                let (da, db) = ((ff.row_sums[a] - 1.0).abs(), (ff.row_sums[b] - 1.0).abs());
                db.total_cmp(&da).then(a.cmp(&b))
            });
            worst.truncate(WORST_ROWS);
            let cavity = CavityClosure {
                surfaces: surface_ids
                    .iter()
                    .map(|&s| surfaces.get(s).cloned().unwrap_or_default())
                    .collect(),
                patches: rows.len(),
                row_sum_min: rows
                    .iter()
                    .map(|&i| ff.row_sums[i])
                    .fold(ff.row_sums[first], f64::min),
                row_sum_max: rows
                    .iter()
                    .map(|&i| ff.row_sums[i])
                    .fold(ff.row_sums[first], f64::max),
                worst_rows: worst
                    .iter()
                    .map(|&i| RowMiss {
                        patch: i,
                        surface: name(i),
                        row_sum: ff.row_sums[i],
                    })
                    .collect(),
            };
            let missing: Vec<&RowMiss> = cavity
                .worst_rows
                .iter()
                .filter(|r| (r.row_sum - 1.0).abs() > CAVITY_TOLERANCE)
                .collect();
            if let Some(w) = missing.first() {
                let mut named: Vec<&str> = Vec::new();
                for r in &missing {
                    if !named.contains(&r.surface.as_str()) {
                        named.push(&r.surface);
                    }
                }
                health.warnings.push(format!(
                    "the closed cavity of {} surfaces ({}) does not close: the row of patch {} ({}) sums to {:.6}, {:.1e} from 1 (more than {CAVITY_TOLERANCE:.0e}); surfaces with rows that far off: {} (a surface inside seen from its back, which has no patches, or a gap or contact finer than the form-factor rules resolve)",
                    cavity.surfaces.len(),
                    summary(&cavity.surfaces),
                    w.patch,
                    w.surface,
                    w.row_sum,
                    (w.row_sum - 1.0).abs(),
                    named.join(", ")
                ));
            }
            health.cavities.push(cavity);
        }
        health
    }
}

/// The first few names of a list, and how many more.
fn summary(names: &[String]) -> String {
    const SHOWN: usize = 4;
    let head = names
        .iter()
        .take(SHOWN)
        .cloned()
        .collect::<Vec<_>>()
        .join(", ");
    if names.len() > SHOWN {
        format!("{head} and {} more", names.len() - SHOWN)
    } else {
        head
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::{Polygon, Vec3};
    use faer::Mat;

    /// The unit cube's faces facing in, one patch each (patch k on surface k), less the faces
    /// listed in `without`.
    fn cube(without: &[usize]) -> (Vec<Patch>, Vec<Face>) {
        let v = Vec3::new;
        // Counter-clockwise seen from inside.
        let all = [
            vec![v(0., 0., 0.), v(1., 0., 0.), v(1., 1., 0.), v(0., 1., 0.)],
            vec![v(0., 0., 1.), v(0., 1., 1.), v(1., 1., 1.), v(1., 0., 1.)],
            vec![v(0., 0., 0.), v(0., 0., 1.), v(1., 0., 1.), v(1., 0., 0.)],
            vec![v(0., 1., 0.), v(1., 1., 0.), v(1., 1., 1.), v(0., 1., 1.)],
            vec![v(0., 0., 0.), v(0., 1., 0.), v(0., 1., 1.), v(0., 0., 1.)],
            vec![v(1., 0., 0.), v(1., 0., 1.), v(1., 1., 1.), v(1., 1., 0.)],
        ];
        let mut patches = Vec::new();
        let mut faces = Vec::new();
        for (k, c) in all.into_iter().enumerate() {
            if without.contains(&k) {
                continue;
            }
            let n = patches.len();
            patches.push(Patch::new(Polygon::new(c.clone()), k));
            faces.push(Face {
                polygon: Polygon::new(c),
                patches: n..n + 1,
            });
        }
        (patches, faces)
    }

    fn with_rows(row_sums: Vec<f64>) -> FormFactors {
        let n = row_sums.len();
        FormFactors {
            matrix: Mat::zeros(n, n),
            reciprocity_mismatch: 0.0,
            reciprocity_share: 0.0,
            row_sums,
            worst_pairs: vec![(0, 5, 2e-3)],
        }
    }

    fn names() -> Vec<String> {
        ["floor", "ceiling", "south", "north", "west", "east"]
            .map(String::from)
            .to_vec()
    }

    #[test]
    fn a_cavity_row_off_by_more_than_the_threshold_is_named_in_a_warning() {
        // Hand-made row sums: every row exact except the east wall's, 2e-3 short.
        let (patches, faces) = cube(&[]);
        let ff = with_rows(vec![1.0, 1.0, 1.0, 1.0, 1.0, 0.998]);
        let h = FormFactorHealth::of(&ff, &patches, &faces, &names());
        assert_eq!(h.cavities.len(), 1);
        let c = &h.cavities[0];
        assert_eq!((c.patches, c.surfaces.len()), (6, 6));
        assert_eq!((c.row_sum_min, c.row_sum_max), (0.998, 1.0));
        assert_eq!(c.worst_rows[0].surface, "east");
        assert_eq!(h.warnings.len(), 1);
        assert!(h.warnings[0].contains("east"), "{}", h.warnings[0]);
        assert!(!h.warnings[0].contains("surfaces with rows that far off: floor"));
        assert_eq!(
            h.worst_pairs[0].surfaces,
            ["floor".to_owned(), "east".to_owned()]
        );
        // Within the threshold: reported, not warned about.
        let ff = with_rows(vec![1.0, 1.0, 1.0, 1.0, 1.0, 1.0 - 0.5 * CAVITY_TOLERANCE]);
        let h = FormFactorHealth::of(&ff, &patches, &faces, &names());
        assert_eq!(h.cavities.len(), 1);
        assert!(h.warnings.is_empty());
    }

    #[test]
    fn an_open_box_has_no_cavity_and_no_warning() {
        // Without its ceiling the rows legitimately fall short: light leaves.
        let (patches, faces) = cube(&[1]);
        let ff = with_rows(vec![0.8; 5]);
        let h = FormFactorHealth::of(&ff, &patches, &faces, &names());
        assert!(h.cavities.is_empty());
        assert!(h.warnings.is_empty());
        assert!(!h.closed);
    }
}
