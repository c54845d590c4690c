//! Sensors, zones and grid points as rows over the patches: the irradiance at output `o` is
//! `Σ_j R_oj M_j` (docs/math.md, "Outputs people need").
//!
//! Outputs are in basis order: the sensors, then the zones, then every zone's grid points,
//! zone by zone ([`grid_points`]).

use crate::formfactor::operator::FormFactorOperator;
use rayon::prelude::*;

use crate::formfactor::{self, FormFactorOptions, Occluders};
use crate::scene::receivers::{mean_over_points, receivers, Receiver};
use crate::scene::FieldOfView;
use crate::scene::{Scene, Zone, ZoneKind};

/// Area of a zone, m².
pub fn zone_area(scene: &Scene, zone: &Zone) -> f64 {
    match &zone.kind {
        ZoneKind::Surfaces(patches) => patches.iter().map(|&i| scene.patches[i].area).sum(),
        ZoneKind::WorkPlane { receivers, .. } => receivers.iter().map(|r| r.area).sum(),
        ZoneKind::Points { area, .. } => *area,
    }
}

pub use crate::scene::receivers::{grid_offset, grid_points};

/// One row per sensor (point form factors with occlusion and field of view), then one per
/// zone (area-weighted average of its patches' or receivers' form-factor rows, or the mean of
/// an imported sensor grid's point rows), then one per
/// grid point (a full-hemisphere point receiver facing its grid's normal, like a sensor).
///
/// `g` is `A F` symmetrised, `area` the patch areas (m²).
pub fn output_rows(
    scene: &Scene,
    g: &dyn FormFactorOperator,
    area: &[f64],
    occluders: &Occluders,
    opts: &FormFactorOptions,
) -> Vec<Vec<f64>> {
    let n = scene.patches.len();
    let all: Vec<Receiver> = receivers(scene).collect();
    all.par_iter()
        .map(|receiver| match *receiver {
            Receiver::Point {
                position,
                normal,
                field,
            } => formfactor::point_form_factors(position, normal, field, &scene.patches, occluders),
            Receiver::Surfaces(patches) => {
                // Σ_i A_i F_ij / Σ A_i = Σ_i G_ij / Σ A_i, a row of G at a time.
                let total: f64 = patches.iter().map(|&i| area[i]).sum();
                let mut sum = vec![0.0; n];
                let mut row = vec![0.0; n];
                for &i in patches {
                    g.row(i, &mut row);
                    for (s, x) in sum.iter_mut().zip(&row) {
                        *s += x;
                    }
                }
                sum.iter().map(|s| s / total).collect()
            }
            Receiver::Points(points) => mean_over_points(points, n, |position, normal| {
                formfactor::point_form_factors(
                    position,
                    normal,
                    FieldOfView::HEMISPHERE,
                    &scene.patches,
                    occluders,
                )
            }),
            Receiver::Plane(receivers) => {
                let f =
                    formfactor::receiver_form_factors(receivers, &scene.patches, occluders, opts);
                let total: f64 = receivers.iter().map(|r| r.area).sum();
                (0..n)
                    .map(|j| {
                        receivers
                            .iter()
                            .enumerate()
                            .map(|(r, rec)| rec.area * f[(r, j)])
                            .sum::<f64>()
                            / total
                    })
                    .collect()
            }
        })
        .collect()
}
