//! Gauss–Legendre rules on patches: tensor rules on the unit square mapped bilinearly onto
//! quadrilaterals, and collapsed (Duffy) onto triangles.
//!
//! Every patch gets its rules for all orders up to the largest one needed, precomputed once, so
//! that evaluating a pair of patches never allocates.

use crate::geometry::{Patch, Vec3};

/// One quadrature point on a patch.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Sample {
    /// Position, metres.
    pub(crate) point: Vec3,
    /// Weight as a fraction of the patch area (the weights of a rule sum to 1).
    pub(crate) weight: f64,
}

/// Nodes and weights of the `m`-point Gauss–Legendre rule on [0, 1] (weights sum to 1).
///
/// Newton iteration on the Legendre polynomial P_m from the Tricomi initial guess
/// (Abramowitz & Stegun 25.4.29, Numerical Recipes `gauleg`); accurate to rounding.
pub fn gauss_legendre(m: usize) -> Vec<(f64, f64)> {
    let mut rule = Vec::with_capacity(m);
    for i in 0..m {
        let mut z = (std::f64::consts::PI * (i as f64 + 0.75) / (m as f64 + 0.5)).cos();
        let mut dp = 1.0;
        for _ in 0..100 {
            // Recurrence for P_m(z) and its derivative.
            let (mut p0, mut p1) = (1.0, 0.0);
            for k in 0..m {
                let p2 = p1;
                p1 = p0;
                p0 = ((2 * k + 1) as f64 * z * p1 - k as f64 * p2) / (k + 1) as f64;
            }
            dp = m as f64 * (z * p0 - p1) / (z * z - 1.0);
            let dz = p0 / dp;
            z -= dz;
            if dz.abs() < 1e-16 {
                break;
            }
        }
        let w = 2.0 / ((1.0 - z * z) * dp * dp);
        rule.push((0.5 * (1.0 - z), 0.5 * w));
    }
    rule
}

/// Appends the `m × m` rule on a convex quadrilateral (bilinear map of the unit square).
fn quad_rule(c: [Vec3; 4], gl: &[(f64, f64)], out: &mut Vec<Sample>) {
    for &(u, wu) in gl {
        for &(v, wv) in gl {
            let p = c[0] * ((1.0 - u) * (1.0 - v))
                + c[1] * (u * (1.0 - v))
                + c[2] * (u * v)
                + c[3] * ((1.0 - u) * v);
            let du = (c[1] - c[0]) * (1.0 - v) + (c[2] - c[3]) * v;
            let dv = (c[3] - c[0]) * (1.0 - u) + (c[2] - c[1]) * u;
            out.push(Sample {
                point: p,
                weight: wu * wv * du.cross(dv).length(),
            });
        }
    }
}

/// Appends the `m × m` collapsed rule on a triangle: `x = a + u (b − a) + u v (c − b)`,
/// Jacobian `u |(b − a) × (c − b)|` (Duffy).
fn triangle_rule(a: Vec3, b: Vec3, c: Vec3, gl: &[(f64, f64)], out: &mut Vec<Sample>) {
    let twice_area = (b - a).cross(c - b).length();
    for &(u, wu) in gl {
        for &(v, wv) in gl {
            let p = a + (b - a) * u + (c - b) * (u * v);
            out.push(Sample {
                point: p,
                weight: wu * wv * u * twice_area,
            });
        }
    }
}

/// Calls `f(point, weight)` for the collapsed rule (Gauss–Legendre nodes `gl`) on each triangle
/// of the fan of a convex polygon; weights are areas in m² (they sum to the polygon's area).
/// Used on the part of a source patch in front of a target whose plane cuts it.
pub(crate) fn for_each_on_polygon(
    corners: &[Vec3],
    gl: &[(f64, f64)],
    mut f: impl FnMut(Vec3, f64),
) {
    let Some(&a) = corners.first() else {
        return;
    };
    for k in 1..corners.len().saturating_sub(1) {
        let (b, c) = (corners[k], corners[k + 1]);
        let twice_area = (b - a).cross(c - b).length();
        for &(u, wu) in gl {
            for &(v, wv) in gl {
                f(
                    a + (b - a) * u + (c - b) * (u * v),
                    wu * wv * u * twice_area,
                );
            }
        }
    }
}

/// Calls `f(point, weight)` for the rule of Gauss–Legendre nodes `gl` on a convex cell: the
/// bilinear tensor rule on a quadrilateral, [`for_each_on_polygon`] otherwise; weights are
/// areas in m².
pub(crate) fn for_each_on_cell(corners: &[Vec3], gl: &[(f64, f64)], mut f: impl FnMut(Vec3, f64)) {
    if let &[a, b, c, d] = corners {
        let mut samples = Vec::with_capacity(gl.len() * gl.len());
        quad_rule([a, b, c, d], gl, &mut samples);
        for s in samples {
            f(s.point, s.weight);
        }
    } else {
        for_each_on_polygon(corners, gl, f);
    }
}

/// The four cells of a convex cell split at its edge midpoints: a quadrilateral into four
/// quadrilaterals through its bilinear centre, a triangle into four triangles, other polygons
/// into the triangles of their fan (then split).
pub(crate) fn split_cell(corners: &[Vec3]) -> Vec<Vec<Vec3>> {
    let mid = |p: Vec3, q: Vec3| (p + q) * 0.5;
    match *corners {
        [a, b, c, d] => {
            let (ab, bc, cd, da) = (mid(a, b), mid(b, c), mid(c, d), mid(d, a));
            let centre = (a + b + c + d) * 0.25;
            vec![
                vec![a, ab, centre, da],
                vec![ab, b, bc, centre],
                vec![centre, bc, c, cd],
                vec![da, centre, cd, d],
            ]
        }
        [a, b, c] => {
            let (ab, bc, ca) = (mid(a, b), mid(b, c), mid(c, a));
            vec![
                vec![a, ab, ca],
                vec![ab, b, bc],
                vec![ca, bc, c],
                vec![ab, bc, ca],
            ]
        }
        _ => (1..corners.len().saturating_sub(1))
            .flat_map(|k| split_cell(&[corners[0], corners[k], corners[k + 1]]))
            .collect(),
    }
}

/// Appends the rule of order `m` (points per side) on `patch`, weights normalised to sum to 1.
/// Quadrilaterals are mapped bilinearly; other polygons are cut into a fan of triangles.
fn patch_rule(patch: &Patch, gl: &[(f64, f64)], out: &mut Vec<Sample>) {
    let start = out.len();
    let v = &patch.polygon.vertices;
    match v.len() {
        0..=2 => {}
        // The collapsed rule of order 1 is not exact for linear functions: use the centroid.
        3 if gl.len() == 1 => out.push(Sample {
            point: patch.centroid,
            weight: 1.0,
        }),
        4 => quad_rule([v[0], v[1], v[2], v[3]], gl, out),
        _ => {
            for k in 1..v.len() - 1 {
                triangle_rule(v[0], v[k], v[k + 1], gl, out);
            }
        }
    }
    let total: f64 = out[start..].iter().map(|s| s.weight).sum();
    if total > 0.0 {
        for s in &mut out[start..] {
            s.weight /= total;
        }
    } else {
        // Degenerate patch: one point at the centroid keeps the callers simple.
        out.truncate(start);
        out.push(Sample {
            point: patch.centroid,
            weight: 1.0,
        });
    }
}

/// Quadrature rules of orders `1..=max_order` for every patch of a scene, in one flat table.
#[derive(Clone, Debug)]
pub(crate) struct SampleTable {
    samples: Vec<Sample>,
    /// `ranges[patch * max_order + order − 1]` = (start, end) in `samples`.
    ranges: Vec<(usize, usize)>,
    max_order: usize,
}

impl SampleTable {
    /// Rules of every order from 1 to `max_order` (at least 1) for every patch.
    pub(crate) fn new(patches: &[Patch], max_order: usize) -> Self {
        let max_order = max_order.max(1);
        let rules: Vec<Vec<(f64, f64)>> = (1..=max_order).map(gauss_legendre).collect();
        let mut samples = Vec::new();
        let mut ranges = Vec::with_capacity(patches.len() * max_order);
        for patch in patches {
            for gl in &rules {
                let start = samples.len();
                patch_rule(patch, gl, &mut samples);
                ranges.push((start, samples.len()));
            }
        }
        SampleTable {
            samples,
            ranges,
            max_order,
        }
    }

    /// The rule of order `order` (clamped to `1..=max_order`) on patch `patch`.
    pub(crate) fn rule(&self, patch: usize, order: usize) -> &[Sample] {
        let order = order.clamp(1, self.max_order);
        match self.ranges.get(patch * self.max_order + order - 1) {
            Some(&(start, end)) => &self.samples[start..end],
            None => &[],
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::Polygon;

    #[test]
    fn gauss_legendre_integrates_polynomials_exactly() {
        // Order m is exact for degree 2m − 1: ∫_0^1 x^k dx = 1 / (k + 1), to rounding.
        for m in 1..=8 {
            let rule = gauss_legendre(m);
            for k in 0..2 * m {
                let q: f64 = rule.iter().map(|&(x, w)| w * x.powi(k as i32)).sum();
                assert!(
                    (q - 1.0 / (k as f64 + 1.0)).abs() < 1e-14,
                    "m {m} k {k}: {q}"
                );
            }
        }
    }

    #[test]
    fn triangle_rule_integrates_linear_functions() {
        let tri = Patch::new(
            Polygon::new(vec![
                Vec3::new(0.0, 0.0, 0.0),
                Vec3::new(2.0, 0.0, 0.0),
                Vec3::new(0.0, 1.0, 0.0),
            ]),
            0,
        );
        let table = SampleTable::new(&[tri], 3);
        for m in 1..=3 {
            let mean_x: f64 = table.rule(0, m).iter().map(|s| s.weight * s.point.x).sum();
            assert!((mean_x - 2.0 / 3.0).abs() < 1e-14);
        }
    }
}
