//! What a basis stores for the controller to compute the sun's first reflection at the sun's
//! own direction (docs/format.md, "The sun's first reflection"; `eigenrad_runtime::sky::
//! sun_first`): the patches the sun can light directly, each with a few sample points that
//! share its area, and the sun directions their shadows are culled with.

use eigenrad_runtime::sky::sun_first::MAX_SAMPLES;
use eigenrad_runtime::sky::sun_grid::{direction_of, SunGrid};

use super::nodes::room_sun;
use crate::geometry::{Patch, Vec3};
use crate::scene::Site;

/// The candidates' tables, as [`eigenrad_runtime::writer::BasisTables`] holds them, and
/// their sample points for the occluders' culling.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct SunFirstTables {
    /// The candidate patches, ascending.
    pub patches: Vec<u32>,
    /// Each candidate's sample points.
    pub sizes: Vec<u8>,
    /// Per candidate: unit normal, then each sample point's position (m) and weight.
    pub points: Vec<f64>,
    /// Every sample point, candidate by candidate.
    pub sample_points: Vec<Vec3>,
}

/// The candidates among `patches`: those `lit` says the sun lights at some stored node (a
/// non-zero initial exitance there) and that reflect. Each patch's sample points are the
/// centroids of the triangles its centroid fans it into, weighed by their share of its
/// area: the midpoint rule on each triangle (a patch with more corners than
/// [`MAX_SAMPLES`], or degenerate, is sampled at its centroid alone).
pub fn sun_first_tables(patches: &[Patch], lit: impl Fn(usize) -> bool) -> SunFirstTables {
    let mut t = SunFirstTables::default();
    for (i, p) in patches.iter().enumerate().filter(|&(i, _)| lit(i)) {
        let corners = &p.polygon.vertices;
        let n = corners.len();
        let fan: Vec<(Vec3, f64)> = (0..n)
            .map(|k| {
                let (a, b) = (corners[k], corners[(k + 1) % n]);
                let area = 0.5 * (a - p.centroid).cross(b - p.centroid).length();
                ((p.centroid + a + b) * (1.0 / 3.0), area)
            })
            .collect();
        let total: f64 = fan.iter().map(|f| f.1).sum();
        let samples: Vec<(Vec3, f64)> =
            if n > usize::from(MAX_SAMPLES) || total.is_nan() || total <= 0.0 || n < 3 {
                vec![(p.centroid, 1.0)]
            } else {
                fan.iter().map(|&(x, a)| (x, a / total)).collect()
            };
        t.patches.push(i as u32);
        t.sizes.push(samples.len() as u8);
        t.points.extend(p.normal.to_array());
        for (x, w) in samples {
            t.points.extend(x.to_array());
            t.points.push(w);
            t.sample_points.push(x);
        }
    }
    t
}

/// The sun directions (room frame) the candidates' occluders are culled with: every stored
/// node's and the centre of every cell with a stored corner, where the controller reads the
/// sun between nodes.
pub fn culling_suns(site: &Site, grid: &SunGrid, stored: &[u32]) -> Vec<Vec3> {
    let mut suns = Vec::new();
    for &node in stored {
        let node = node as usize;
        let Some((declination, hour)) = grid.angles(node) else {
            continue;
        };
        for (dd, dh) in [
            (0.0, 0.0),
            (0.5, 0.5),
            (-0.5, 0.5),
            (0.5, -0.5),
            (-0.5, -0.5),
        ] {
            let d = direction_of(
                grid.latitude,
                declination + dd * grid.declination_step,
                hour + dh * grid.hour_step,
            );
            suns.extend(room_sun(site, d));
        }
    }
    suns
}
