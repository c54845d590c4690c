//! The sun's directions at a site as a grid in declination and hour angle: the nodes a basis
//! stores the room's response to the sun at, and the bilinear weights that read the sun of
//! any moment from its four nearest nodes (docs/math.md, "Daylight in the basis").
//!
//! Over a year the sun's declination `δ` stays within ±23.44°, and over a day its hour angle
//! `h` sweeps the sky at 15° an hour. A grid in `(δ, h)` follows the sun's daily paths, so
//! that no node is spent on directions the sun never takes at the site, as a grid in
//! altitude and azimuth would be. The direction of `(δ, h)` at latitude `φ`, in the site's
//! frame (x east, y north, z up, as [`super::direction`]) is
//!
//! ```text
//! up    = sin φ sin δ + cos φ cos δ cos h
//! north = cos φ sin δ − sin φ cos δ cos h
//! east  = −cos δ sin h
//! ```
//!
//! (`h` positive in the afternoon, when the sun is west of the meridian), and back:
//! `sin δ = north cos φ + up sin φ`, `h = atan2(−east, up cos φ − north sin φ)`. The frame
//! relation is exact; refraction, which lifts the apparent sun near the horizon, moves it
//! slightly off its true path and is read as a nearby `(δ, h)`: the weights clamp to the
//! grid's edges.

use super::approx;
use crate::error::{Error, Result};

/// A rectangular grid of `rows` declinations by `columns` hour angles, in degrees.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SunGrid {
    /// Latitude of the site, degrees north.
    pub latitude: f32,
    /// Declination of the first row, degrees.
    pub declination_first: f32,
    /// Degrees between rows (> 0).
    pub declination_step: f32,
    /// Rows (≥ 1).
    pub rows: usize,
    /// Hour angle of the first column, degrees (negative before solar noon).
    pub hour_first: f32,
    /// Degrees between columns (> 0).
    pub hour_step: f32,
    /// Columns (≥ 1).
    pub columns: usize,
}

/// One node of a [`SunGrid`] and its weight in a sun read from the grid.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct NodeWeight {
    /// The node's index, `row · columns + column`.
    pub node: usize,
    /// Its bilinear weight (the four of a sun add up to 1).
    pub weight: f32,
}

impl SunGrid {
    /// Number of nodes, `rows · columns`.
    pub fn len(&self) -> usize {
        self.rows.saturating_mul(self.columns)
    }

    /// Whether the grid has no node.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Declination and hour angle (degrees) of node `node`.
    pub fn angles(&self, node: usize) -> Option<(f32, f32)> {
        if node >= self.len() {
            return None;
        }
        let (row, column) = (node / self.columns, node % self.columns);
        Some((
            self.declination_first + self.declination_step * row as f32,
            self.hour_first + self.hour_step * column as f32,
        ))
    }

    /// Direction of node `node` in the site's frame (unit vector, x east, y north, z up);
    /// below the horizon when `z < 0`.
    pub fn direction(&self, node: usize) -> Option<[f32; 3]> {
        let (declination, hour) = self.angles(node)?;
        Some(direction_of(self.latitude, declination, hour))
    }

    /// The sine and cosine of the latitude, which every conversion of a direction needs:
    /// computed once by a caller that converts many ([`SunGrid::weights_at`]).
    pub fn latitude_sin_cos(&self) -> [f32; 2] {
        let (sin, cos) = approx::sin_cos(self.latitude.to_radians());
        [sin, cos]
    }

    /// Declination and hour angle (degrees) of the unit vector `direction` (site frame).
    pub fn declination_hour(&self, direction: [f32; 3]) -> (f32, f32) {
        declination_hour(direction, self.latitude_sin_cos())
    }

    /// The four nodes around the sun in `direction` (unit vector, site frame, to 10⁻³) and
    /// their bilinear weights in declination and hour angle. A sun beyond the grid's edges
    /// is read at the nearest edge; a grid of one row (or column) has equal nodes there.
    pub fn weights(&self, direction: [f32; 3]) -> Result<[NodeWeight; 4]> {
        self.weights_at(direction, self.latitude_sin_cos())
    }

    /// [`SunGrid::weights`] with the latitude's sine and cosine given
    /// ([`SunGrid::latitude_sin_cos`]), computed once by a caller that converts many.
    pub fn weights_at(
        &self,
        direction: [f32; 3],
        latitude_sin_cos: [f32; 2],
    ) -> Result<[NodeWeight; 4]> {
        let mut out = [NodeWeight::default(); 4];
        self.weights_into(direction, latitude_sin_cos, &mut out)?;
        Ok(out)
    }

    /// [`SunGrid::weights_at`] into `out` (left as it is on an error): a sky update writes
    /// the nodes in place rather than copying a returned `Result` of them.
    pub(crate) fn weights_into(
        &self,
        direction: [f32; 3],
        latitude_sin_cos: [f32; 2],
        out: &mut [NodeWeight; 4],
    ) -> Result<()> {
        let [x, y, z] = direction;
        let norm2 = x * x + y * y + z * z;
        if !(norm2.is_finite() && (norm2 - 1.0).abs() <= 2.0e-3) {
            return Err(Error::OutOfRange {
                what: "sun direction length",
                range: "1 (a unit vector, to 10⁻³)",
            });
        }
        let (declination, hour) = declination_hour(direction, latitude_sin_cos);
        let (row, s) = cell(
            declination,
            self.declination_first,
            self.declination_step,
            self.rows,
        );
        let (column, t) = cell(hour, self.hour_first, self.hour_step, self.columns);
        let next_row = (row + 1).min(self.rows.saturating_sub(1));
        let next_column = (column + 1).min(self.columns.saturating_sub(1));
        let at = |r: usize, c: usize, weight: f32| NodeWeight {
            node: r * self.columns + c,
            weight,
        };
        *out = [
            at(row, column, (1.0 - s) * (1.0 - t)),
            at(row, next_column, (1.0 - s) * t),
            at(next_row, column, s * (1.0 - t)),
            at(next_row, next_column, s * t),
        ];
        Ok(())
    }
}

/// Declination and hour angle (degrees) of the unit vector `direction` (site frame) at the
/// latitude of sine and cosine `[sin φ, cos φ]`.
fn declination_hour(direction: [f32; 3], [sin_phi, cos_phi]: [f32; 2]) -> (f32, f32) {
    let [east, north, up] = direction;
    let sin_declination = (north * cos_phi + up * sin_phi).clamp(-1.0, 1.0);
    let declination = approx::asin(sin_declination);
    let hour = approx::atan2(-east, up * cos_phi - north * sin_phi);
    (declination.to_degrees(), hour.to_degrees())
}

/// The direction of declination `declination` and hour angle `hour` (degrees) at latitude
/// `latitude` (degrees): unit vector, site frame.
pub fn direction_of(latitude: f32, declination: f32, hour: f32) -> [f32; 3] {
    let (phi, delta, h) = (
        latitude.to_radians(),
        declination.to_radians(),
        hour.to_radians(),
    );
    let (sin_phi, cos_phi) = (libm::sinf(phi), libm::cosf(phi));
    let (sin_delta, cos_delta) = (libm::sinf(delta), libm::cosf(delta));
    let (sin_h, cos_h) = (libm::sinf(h), libm::cosf(h));
    [
        -cos_delta * sin_h,
        cos_phi * sin_delta - sin_phi * cos_delta * cos_h,
        sin_phi * sin_delta + cos_phi * cos_delta * cos_h,
    ]
}

/// The cell of a lattice of `count` values from `first` by `step` that holds `value`: its
/// lower index and the fraction (0 to 1) towards the next, clamped to the lattice.
fn cell(value: f32, first: f32, step: f32, count: usize) -> (usize, f32) {
    if count < 2 || step.is_nan() || step <= 0.0 || value.is_nan() {
        return (0, 0.0);
    }
    let at = ((value - first) / step).clamp(0.0, (count - 1) as f32);
    // `at` is within [0, count − 1]: the cast cannot overflow.
    let low = (at as usize).min(count - 2);
    (low, (at - low as f32).clamp(0.0, 1.0))
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, clippy::indexing_slicing)]
    use super::*;

    fn vienna() -> SunGrid {
        SunGrid {
            latitude: 48.21,
            declination_first: -23.44,
            declination_step: 5.86,
            rows: 9,
            hour_first: -180.0,
            hour_step: 7.5,
            columns: 49,
        }
    }

    /// Solar noon at the equinox stands due south at 90° − φ; six hours later the sun sets
    /// due west (a textbook case: at δ = 0 the sun rises and sets at hour angle ∓90°).
    #[test]
    fn noon_and_sunset_at_the_equinox() {
        let g = vienna();
        let [e, n, u] = direction_of(48.21, 0.0, 0.0);
        let altitude = libm::asinf(u).to_degrees();
        assert!(e.abs() < 1e-6 && n < 0.0);
        assert!((altitude - (90.0 - 48.21)).abs() < 1e-4, "{altitude}");
        let [e, n, u] = direction_of(48.21, 0.0, 90.0);
        assert!((e + 1.0).abs() < 1e-6 && n.abs() < 1e-6 && u.abs() < 1e-6);
        // And back.
        let (d, h) = g.declination_hour(direction_of(48.21, 12.3, -47.0));
        assert!(
            (d - 12.3).abs() < 1e-3 && (h + 47.0).abs() < 1e-3,
            "{d} {h}"
        );
    }

    /// At a node the weights pick that node alone; halfway between four nodes each has a
    /// quarter; the weights always add up to 1.
    #[test]
    fn weights_at_nodes_and_between() {
        let g = vienna();
        let node = 4 * 49 + 30;
        let w = g.weights(g.direction(node).unwrap()).unwrap();
        let at_node: f32 = w.iter().filter(|x| x.node == node).map(|x| x.weight).sum();
        assert!((at_node - 1.0).abs() < 1e-3, "{w:?}");
        let (d, h) = g.angles(node).unwrap();
        let mid = direction_of(48.21, d + 0.5 * 5.86, h + 0.5 * 7.5);
        let w = g.weights(mid).unwrap();
        let nodes: [usize; 4] = [node, node + 1, node + 49, node + 50];
        for (x, expected) in w.iter().zip(nodes) {
            assert_eq!(x.node, expected);
            assert!((x.weight - 0.25).abs() < 1e-3, "{w:?}");
        }
        let total: f32 = w.iter().map(|x| x.weight).sum();
        assert!((total - 1.0).abs() < 1e-6);
    }

    /// Beyond the declinations of the grid the sun is read on its edge row, and a direction
    /// that is not a unit vector is an error.
    #[test]
    fn clamped_and_refused() {
        let g = vienna();
        let w = g.weights(direction_of(48.21, 30.0, 0.0)).unwrap();
        assert!(w.iter().all(|x| x.node / 49 == 8 || x.weight == 0.0));
        assert!(g.weights([0.0, 0.0, 2.0]).is_err());
        assert!(g.weights([f32::NAN, 0.0, 1.0]).is_err());
    }
}
