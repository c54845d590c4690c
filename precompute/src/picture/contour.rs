//! Isolux lines: marching squares on a lattice of point values, with the crossing on each
//! edge found by linear interpolation between its two points, and the segments joined into
//! polylines.
//!
//! A point counts as above the level when its value is at least the level. Where a cell's
//! four corners alternate (a saddle), the mean of the corners decides which pair is joined,
//! the usual rule (Lorensen and Cline's ambiguity resolved by the cell centre).

use std::collections::BTreeMap;

/// Values at the points `(x0 + i·dx, y0 + j·dy)`, `i < counts[0]`, `j < counts[1]`, `i`
/// fastest; positions in m.
#[derive(Clone, Copy, Debug)]
pub struct Lattice<'a> {
    /// Points along x and y.
    pub counts: [usize; 2],
    /// The first point, m.
    pub origin: [f64; 2],
    /// Distance between neighbouring points along x and y, m.
    pub spacing: [f64; 2],
    /// One value per point; NaN where the lattice has no point.
    pub values: &'a [f64],
}

/// An edge between neighbouring points: along x from `(i, j)` (`false`) or along y
/// (`true`). Ordered, so that joining segments is deterministic.
type Edge = (bool, usize, usize);

impl Lattice<'_> {
    fn value(&self, i: usize, j: usize) -> f64 {
        self.values[j * self.counts[0] + i]
    }

    fn position(&self, i: usize, j: usize) -> [f64; 2] {
        [
            self.origin[0] + i as f64 * self.spacing[0],
            self.origin[1] + j as f64 * self.spacing[1],
        ]
    }

    /// Where `level` crosses `edge`, interpolated from its lower point to its upper one (the
    /// same arithmetic from either cell, so shared ends are the same numbers).
    fn crossing(&self, (along_y, i, j): Edge, level: f64) -> [f64; 2] {
        let (a, b) = if along_y {
            ((i, j), (i, j + 1))
        } else {
            ((i, j), (i + 1, j))
        };
        let (va, vb) = (self.value(a.0, a.1), self.value(b.0, b.1));
        let t = ((level - va) / (vb - va)).clamp(0.0, 1.0);
        let (pa, pb) = (self.position(a.0, a.1), self.position(b.0, b.1));
        [pa[0] + t * (pb[0] - pa[0]), pa[1] + t * (pb[1] - pa[1])]
    }
}

/// The isoline of `level` through the lattice as polylines (m): open ones run from edge to
/// edge of the lattice, closed ones end where they start. Empty when no pair of neighbours
/// straddles the level, or when the lattice has fewer than 2 × 2 points or not one value per
/// point.
pub fn isolines(lattice: &Lattice<'_>, level: f64) -> Vec<Vec<[f64; 2]>> {
    let [nx, ny] = lattice.counts;
    if nx < 2 || ny < 2 || lattice.values.len() != nx * ny || !level.is_finite() {
        return Vec::new();
    }
    let above = |i: usize, j: usize| lattice.value(i, j) >= level;
    let mut segments: Vec<[Edge; 2]> = Vec::new();
    for j in 0..ny - 1 {
        for i in 0..nx - 1 {
            // A cell with a corner missing (NaN: outside the floor, inside an obstacle) has
            // no line: the lines end at the edge of the cells that have all four points.
            if [(i, j), (i + 1, j), (i + 1, j + 1), (i, j + 1)]
                .iter()
                .any(|&(a, b)| lattice.value(a, b).is_nan())
            {
                continue;
            }
            // Corners counter-clockwise from (i, j); edge k joins corner k to corner k + 1.
            let corner = [
                above(i, j),
                above(i + 1, j),
                above(i + 1, j + 1),
                above(i, j + 1),
            ];
            let edges: [Edge; 4] = [
                (false, i, j),
                (true, i + 1, j),
                (false, i, j + 1),
                (true, i, j),
            ];
            let crossed: Vec<usize> = (0..4)
                .filter(|&k| corner[k] != corner[(k + 1) % 4])
                .collect();
            match crossed.len() {
                2 => segments.push([edges[crossed[0]], edges[crossed[1]]]),
                4 => {
                    // A saddle: cut off the two corners on the other side from the centre.
                    let centre = (lattice.value(i, j)
                        + lattice.value(i + 1, j)
                        + lattice.value(i + 1, j + 1)
                        + lattice.value(i, j + 1))
                        / 4.0;
                    let centre_above = centre >= level;
                    for k in 0..4 {
                        if corner[k] != centre_above {
                            // Corner k lies between edge k − 1 and edge k.
                            segments.push([edges[(k + 3) % 4], edges[k]]);
                        }
                    }
                }
                _ => {}
            }
        }
    }
    join(&segments)
        .into_iter()
        .map(|edges| {
            edges
                .into_iter()
                .map(|e| lattice.crossing(e, level))
                .collect()
        })
        .collect()
}

/// Segments (pairs of edges) joined at shared edges into chains of edges: open chains first
/// from their ends, then the closed ones (first edge repeated at the end).
fn join(segments: &[[Edge; 2]]) -> Vec<Vec<Edge>> {
    let mut at: BTreeMap<Edge, Vec<usize>> = BTreeMap::new();
    for (s, pair) in segments.iter().enumerate() {
        for e in pair {
            at.entry(*e).or_default().push(s);
        }
    }
    let mut used = vec![false; segments.len()];
    let mut chains = Vec::new();
    // An edge of one segment only is an open end: start there, so open lines come out whole.
    let starts: Vec<(usize, Edge)> = segments
        .iter()
        .enumerate()
        .flat_map(|(s, pair)| pair.iter().map(move |e| (s, *e)))
        .filter(|(_, e)| at[e].len() == 1)
        .chain(segments.iter().enumerate().map(|(s, pair)| (s, pair[0])))
        .collect();
    for (first, start) in starts {
        if used[first] {
            continue;
        }
        let mut chain = vec![start];
        let (mut s, mut from) = (first, start);
        loop {
            used[s] = true;
            let pair = segments[s];
            let to = if pair[0] == from { pair[1] } else { pair[0] };
            chain.push(to);
            match at[&to].iter().find(|&&t| !used[t]) {
                Some(&next) => (s, from) = (next, to),
                None => break,
            }
        }
        chains.push(chain);
    }
    chains
}

#[cfg(test)]
mod tests {
    use super::*;

    fn lattice(
        counts: [usize; 2],
        origin: [f64; 2],
        h: f64,
        f: impl Fn(f64, f64) -> f64,
    ) -> Vec<f64> {
        let mut v = Vec::new();
        for j in 0..counts[1] {
            for i in 0..counts[0] {
                v.push(f(origin[0] + i as f64 * h, origin[1] + j as f64 * h));
            }
        }
        v
    }

    /// A linear field `v = 100 x + 20 y`: linear interpolation is exact, so every vertex lies
    /// on the line `100 x + 20 y = level` to rounding, and the line is one open polyline from
    /// one edge of the lattice to another.
    #[test]
    fn a_linear_field_gives_its_straight_line() {
        let (counts, origin, h) = ([9, 6], [0.25, 0.5], 0.5);
        let values = lattice(counts, origin, h, |x, y| 100.0 * x + 20.0 * y);
        let l = Lattice {
            counts,
            origin,
            spacing: [h, h],
            values: &values,
        };
        for level in [100.0, 237.5, 400.0] {
            let lines = isolines(&l, level);
            assert_eq!(lines.len(), 1, "level {level}: {lines:?}");
            assert!(lines[0].len() >= 2);
            for p in &lines[0] {
                assert!(
                    (100.0 * p[0] + 20.0 * p[1] - level).abs() < 1e-9,
                    "{level}: {p:?}"
                );
            }
            assert_ne!(lines[0].first(), lines[0].last());
        }
        // Outside the field's range: nothing.
        assert!(isolines(&l, 1e4).is_empty());
        assert!(isolines(&l, -1.0).is_empty());
    }

    /// A radial field `r = |p|` about the lattice's centre: the isoline of r = R is one closed
    /// polyline, every vertex within the bound on linear interpolation along an edge of
    /// length h, `|Δr| ≤ h² max|r''| / 8 ≤ h² / (8 (R − h))` (r'' ≤ 1/r along a line), of R.
    #[test]
    fn a_radial_field_gives_a_closed_circle() {
        let (counts, h) = ([41, 41], 0.1);
        let origin = [-2.0, -2.0];
        let values = lattice(counts, origin, h, |x, y| x.hypot(y));
        let l = Lattice {
            counts,
            origin,
            spacing: [h, h],
            values: &values,
        };
        for radius in [0.55, 1.0, 1.73] {
            let lines = isolines(&l, radius);
            assert_eq!(lines.len(), 1, "r = {radius}");
            let line = &lines[0];
            assert_eq!(line.first(), line.last(), "closed");
            let tolerance = h * h / (8.0 * (radius - h));
            for p in line {
                assert!(
                    (p[0].hypot(p[1]) - radius).abs() <= tolerance,
                    "{radius}: {p:?}"
                );
            }
            // All the way round: a circle crosses about 8R/h lattice edges (its perimeter
            // 2πR times the mean of |cos| + |sin|, 4/π, per h); at least half of them.
            assert!(line.len() as f64 >= 4.0 * radius / h);
        }
    }

    /// A saddle `v = x y` on a 2 × 2 cell centred at 0: the centre is 0, so level 0.5 cuts
    /// off the two corners above it (x y = 1) and level −0.5 the two below.
    #[test]
    fn saddles_follow_the_centre() {
        let values = [1.0, -1.0, -1.0, 1.0];
        let l = Lattice {
            counts: [2, 2],
            origin: [-1.0, -1.0],
            spacing: [2.0, 2.0],
            values: &values,
        };
        for level in [0.5, -0.5] {
            let lines = isolines(&l, level);
            assert_eq!(lines.len(), 2, "{level}");
            for line in &lines {
                assert_eq!(line.len(), 2);
                // Each cuts off one corner: both ends are near the same corner.
                let mid = [
                    (line[0][0] + line[1][0]) / 2.0,
                    (line[0][1] + line[1][1]) / 2.0,
                ];
                assert!(mid[0].abs() > 0.4 && mid[1].abs() > 0.4, "{mid:?}");
                let sign = mid[0].signum() * mid[1].signum();
                assert_eq!(sign, level.signum(), "{level}: {line:?}");
            }
        }
    }

    #[test]
    fn too_small_or_mismatched_lattices_give_nothing() {
        let values = [1.0, 2.0, 3.0];
        let l = Lattice {
            counts: [3, 1],
            origin: [0.0, 0.0],
            spacing: [1.0, 1.0],
            values: &values,
        };
        assert!(isolines(&l, 1.5).is_empty());
        let l = Lattice {
            counts: [2, 2],
            origin: [0.0, 0.0],
            spacing: [1.0, 1.0],
            values: &values,
        };
        assert!(isolines(&l, 1.5).is_empty());
    }
}
