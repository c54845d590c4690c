//! Sampled visibility of a pair of patches ([`Visibility::Sampled`]): the pair's unoccluded
//! form factor times the share of a fixed grid of rays between the two patches that no blocker
//! cuts, each ray weighted by the point-to-point kernel.
//!
//! Both patches carry the midpoint grid of `k × k` cells of their parametrisation
//! (`visibility::Param`), each point weighted by its cell's area. A ray from source point `x`
//! (area `a_x`) to target point `y` (area `a_y`) has the weight
//! `w = a_x a_y cos θ_x cos θ_y / r²`, so that `Σ w / π` is the midpoint rule of the pair's
//! unoccluded exchange; the visible fraction is `Σ_visible w / Σ w`. The grids are fixed
//! (deterministic whatever the thread order), and the estimate is the same in both directions
//! of a pair (the same segments, the same weights), so `G = A F` stays symmetric up to the
//! unoccluded integral's own quadrature error. See `docs/math.md`, "Sampled visibility".

use super::bvh::{Occluders, Shaft};
use super::visibility::Param;
use crate::geometry::Patch;

/// How the visibility of a pair that a blocker may cut is found (`--visibility`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Visibility {
    /// The blockers' shadows are cut out of the target at every quadrature point of the source
    /// (module `shadow`): the visible part is exact.
    #[default]
    Exact,
    /// Pairs that do not touch or come close (closer than their size) take the unoccluded
    /// form factor times a visible fraction from `per_side² × per_side²` rays between fixed
    /// grids of `per_side × per_side` points on each patch ([`Visibility::DEFAULT_PER_SIDE`]
    /// from the command line). Close pairs, and patches other than triangles and
    /// quadrilaterals, keep exact visibility.
    Sampled {
        /// Points per side of each patch's grid (at least 1).
        per_side: u32,
    },
    /// With the hierarchical operator, two well-separated clusters of patches that a blocker
    /// may cut take their unoccluded form factors times each patch's visible share of the
    /// other cluster, from rays between them (`visibility::between_clusters`)
    /// (`hierarchical::Settings::shade_mixed`); the other pairs keep the exact shadows. The
    /// dense operators read every pair exactly.
    Clusters,
}

impl Visibility {
    /// Points per side of the sampled grids when the command line does not say.
    pub const DEFAULT_PER_SIDE: u32 = 3;
}

/// Largest number of points per side (so that a pair casts at most 16⁴ = 65 536 rays).
pub const MAX_PER_SIDE: u32 = 16;

/// Kernel-weighted share in [0, 1] of the rays between the grids of `src` and `tgt` that the
/// blockers of `shaft` let through (module docs); `None` when a patch is not a triangle or a
/// quadrilateral, or no ray joins two points that face each other (the caller keeps the exact
/// visibility).
pub(super) fn visible_fraction(
    occluders: &Occluders,
    shaft: &Shaft,
    src: &Patch,
    tgt: &Patch,
    per_side: u32,
    ignore: &[usize],
) -> Option<f64> {
    let (s, t) = (Param::of(src)?, Param::of(tgt)?);
    let k = per_side.clamp(1, MAX_PER_SIDE);
    let grid = |p: Param| {
        let step = 1.0 / f64::from(k);
        (0..k * k).map(move |c| {
            let (u, v) = (
                (f64::from(c % k) + 0.5) * step,
                (f64::from(c / k) + 0.5) * step,
            );
            (p.point(u, v), p.jacobian(u, v) * step * step)
        })
    };
    let (mut seen, mut total) = (0.0, 0.0);
    for (x, ax) in grid(s) {
        for (y, ay) in grid(t) {
            let d = y - x;
            let (cx, cy) = (src.normal.dot(d), -tgt.normal.dot(d));
            if cx <= 0.0 || cy <= 0.0 {
                continue;
            }
            let r2 = d.dot(d);
            let w = ax * ay * cx * cy / (r2 * r2);
            total += w;
            if occluders.visible_in(shaft, x, y, ignore) {
                seen += w;
            }
        }
    }
    (total > 0.0 && total.is_finite()).then(|| (seen / total).clamp(0.0, 1.0))
}

#[cfg(test)]
mod tests;
