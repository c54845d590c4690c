//! Rows of form factors from a point (a sensor, a grid point) or from receiving patches that
//! do not block light (a work plane's cells) to every patch of the scene.

use faer::Mat;
use rayon::prelude::*;

use super::kernel::Cone;
use super::pair::{Context, Prepared, Viewer};
use super::{progress_bar, FormFactorOptions, Occluders};
use crate::geometry::{Patch, Vec3};
use crate::scene::FieldOfView;

/// Differential element (a point sensor at `point`, metres, facing the unit `normal`; only
/// directions within its `field` of view count, each by its sensitivity)
/// to every patch: `F_sj` (dimensionless) such that irradiance `E = Σ_j F_sj M_j` (W/m² from
/// exitances in W/m², or lux from lm/m²). With occlusion by `occluders`.
///
/// A sensor with an angular response reads `Σ_k weight_k F_sj(edge_k)` over the rings of
/// [`Response::rings`](crate::scene::response::Response::rings): the exact form factors
/// within cones, weighted.
pub fn point_form_factors(
    point: Vec3,
    normal: Vec3,
    field: FieldOfView,
    patches: &[Patch],
    occluders: &Occluders,
) -> Vec<f64> {
    let opts = FormFactorOptions::default();
    let targets = Prepared::targets(patches);
    let ctx = Context::new(&targets, occluders, &opts, false);
    let normal = normal.normalized();
    let in_cone = |half_angle: Option<f64>| {
        let cone = half_angle.and_then(|a| Cone::new(normal, a));
        let viewer = Viewer {
            point,
            normal,
            cone: cone.as_ref(),
        };
        (0..patches.len())
            .into_par_iter()
            .map(|j| {
                let k = ctx.kernel(viewer, j);
                if k <= 0.0 {
                    return 0.0;
                }
                let tgt = &patches[j];
                let shaft =
                    occluders.shaft(&[point], normal, &tgt.polygon.vertices, tgt.normal, &[j]);
                if !shaft.is_clear() {
                    ctx.visible_kernel(viewer, j, &shaft, &[j])
                } else {
                    k
                }
            })
            .collect::<Vec<f64>>()
    };
    let Some(response) = field.table() else {
        return in_cone(field.half_angle());
    };
    let mut sum = vec![0.0; patches.len()];
    for (edge, weight) in response.rings() {
        for (s, f) in sum.iter_mut().zip(in_cone(Some(edge))) {
            *s += weight * f;
        }
    }
    sum
}

/// Receiving patches that do not block light (e.g. a work plane) to every scene patch, with
/// occlusion by the scene patches: rows = receivers, `F_rj` (dimensionless, fraction of the
/// receiver's hemispherical view, front side only), `n_receivers × n`.
///
/// A receiver floats in the room: it is refined toward the patches it touches, but not toward
/// those it merely comes close to, so that all other pairs of its row share one rule and the
/// row of a receiver in a closed room sums to 1 to rounding.
pub fn receiver_form_factors(
    receivers: &[Patch],
    patches: &[Patch],
    occluders: &Occluders,
    opts: &FormFactorOptions,
) -> Mat<f64> {
    let targets = Prepared::targets(patches);
    let sources = Prepared::new(receivers, opts.gauss_order);
    let ctx = Context::new(&targets, occluders, opts, false);
    let bar = progress_bar(receivers.len(), opts.progress, "receivers", "rows");
    let rows: Vec<Vec<f64>> = (0..receivers.len())
        .into_par_iter()
        .map(|r| {
            let row = (0..patches.len())
                .map(|j| ctx.pair(&sources, r, j, &[j]))
                .collect();
            bar.inc(1);
            row
        })
        .collect();
    bar.finish_and_clear();
    Mat::from_fn(receivers.len(), patches.len(), |r, j| rows[r][j])
}

#[cfg(test)]
mod tests;
