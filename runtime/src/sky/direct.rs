//! The direct sun at a point receiver (a sensor, a grid point), computed on the controller
//! from the geometry a basis stores (docs/format.md, "Direct sun"; docs/math.md, "The sun
//! between the grid's nodes").
//!
//! The sun patch's edge crossing a point makes its reading jump as the sun moves: read from
//! a grid of sun directions, a bilinear mean misses up to the whole sunlight between nodes
//! however fine the grid. The jump is the direct part alone, which is cheap to compute
//! exactly: the ray from the receiver `x` towards the sun `s` passes a window face (where
//! the glazing transmits `τ(θ_w)`), meets no room occluder before it and no exterior
//! occluder after it, and counts with the receiver's weighting of its direction (`cos θ`,
//! within a cone, or a sensor's response):
//!
//! ```text
//! E_direct(x) = E_n Σ_windows τ(θ_w) w(θ_x) V(x, s)
//! ```
//!
//! the host's rule for a point (`precompute`'s `sun_at_point`). What is left of a node's
//! reading after its direct part, the light the room reflects, is smooth in the sun's
//! direction and is interpolated between the nodes as before.
//!
//! Every loop runs over the stored tables with checked reads: any bytes give a number, never
//! a panic. Everything is `f32`; the arccosine of a sensor's response is
//! `approx::acos`.

use super::approx;
use crate::basis::Basis;
use crate::storage::{f32_at, u32_at};

/// Most vertices of one stored polygon.
pub const MAX_POLYGON_VERTICES: u8 = 64;

/// Steps of a window's transmittance table in the incidence cosine: 65 values at `k / 64`.
pub const GLAZING_STEPS: usize = 64;

/// Part of the distance to a window within which a room occluder is taken to lie in the
/// window's own plane (the wall around it) rather than in front of it, and beyond which an
/// exterior occluder is past the window; also the distance from the receiver within which a
/// surface it lies on does not shade it. A relative `f32` margin of about 800 ulp.
const PLANE_MARGIN: f32 = 1.0e-4;

/// What an evaluator keeps of the direct sun between calls: the counts of the stored polygons
/// and the north angle (20 bytes on every target; the tables stay in the basis).
#[derive(Clone, Copy, Debug)]
pub struct DirectSunState {
    /// Window faces, room occluders, exterior occluders.
    counts: [u32; 3],
    /// Sine and cosine of the site's north angle: the sun's direction in the room's frame.
    north_sin_cos: [f32; 2],
}

/// The direct sun's geometry of a basis: window faces with their glazing, the occluders
/// that may shade them, each sensor's weighting. It borrows the basis view of its evaluator
/// rather than holding a copy of it, so that an evaluator carries one view only.
#[derive(Clone, Copy, Debug)]
pub struct DirectSun<'b, 'a> {
    basis: &'b Basis<'a>,
    state: DirectSunState,
}

/// How a receiver weighs the direction light arrives from, at cosine `c` to its normal.
#[derive(Clone, Copy, Debug)]
enum Weighting {
    /// `c` for `c > 0` and `c ≥ cos α` (α the cone's half-angle; the hemisphere's is −1).
    Cone { cos_half_angle: f32 },
    /// A sensor's response: `rows` pairs (polar angle, sensitivity) from pair `first`.
    Response { first: usize, rows: usize },
}

impl<'b, 'a> DirectSun<'b, 'a> {
    /// The direct sun of `basis`, `Ok(None)` when it stores no such geometry (a basis
    /// without daylight, or whose every sun reading is interpolated). The daylight section's
    /// values, its tables among them, are checked here ([`Basis::check_daylight`]): a table
    /// of the wrong length or with a value out of range is the decoder's error naming it.
    pub fn new(basis: &'b Basis<'a>) -> crate::Result<Option<Self>> {
        basis.check_daylight()?;
        let t = &basis.tables;
        if t.sun_polygon_counts.is_empty() {
            return Ok(None);
        }
        let count = |k: usize| u32_at(t.sun_polygon_counts, k);
        let north = basis.site().map_or(0.0, |s| s.north);
        let (sin, cos) = approx::sin_cos(north.to_radians());
        Ok(Some(DirectSun {
            basis,
            state: DirectSunState {
                counts: [count(0), count(1), count(2)],
                north_sin_cos: [sin, cos],
            },
        }))
    }

    /// The direct sun of `basis` from the `state` that [`DirectSun::new`] made of it.
    pub fn with(basis: &'b Basis<'a>, state: DirectSunState) -> Self {
        DirectSun { basis, state }
    }

    /// What an evaluator keeps of it.
    pub fn state(&self) -> DirectSunState {
        self.state
    }

    /// Window faces, room occluders and exterior occluders stored.
    pub fn polygon_counts(&self) -> [usize; 3] {
        self.state.counts.map(|c| c as usize)
    }

    /// Bytes of the six direct-sun tables, their lengths included (one byte each while under
    /// 128 bytes, as postcard writes them): what the direct sun adds to the basis.
    pub fn stored_bytes(&self) -> usize {
        let t = &self.basis.tables;
        crate::storage::serialized_len(&[
            t.sun_polygon_counts,
            t.sun_polygon_sizes,
            t.sun_polygons,
            t.sun_glazing,
            t.sensor_response_rows,
            t.sensor_response,
        ])
    }

    /// The sun's unit direction `site` (x east, y north, z up) in the room's frame: turned
    /// by the site's north angle.
    pub fn room_direction(&self, site: [f32; 3]) -> [f32; 3] {
        let [s, c] = self.state.north_sin_cos;
        [
            site[0] * c - site[1] * s,
            site[0] * s + site[1] * c,
            site[2],
        ]
    }

    /// Direct illuminance at sensor `sensor` per lux of direct normal illuminance from the
    /// sun in the room-frame direction `sun`; 0 for an index out of range.
    pub fn at_sensor(&self, sensor: usize, sun: [f32; 3]) -> f32 {
        let Ok(info) = self.basis.sensor(sensor) else {
            return 0.0;
        };
        let rows_table = self.basis.tables.sensor_response_rows;
        let rows = |i: usize| u32_at(rows_table, i) as usize;
        let weighting = match rows(sensor) {
            0 => Weighting::Cone {
                cos_half_angle: approx::sin_cos(info.half_angle).1,
            },
            rows_here => Weighting::Response {
                first: (0..sensor).map(rows).fold(0usize, usize::saturating_add),
                rows: rows_here,
            },
        };
        self.at(info.position, info.normal, weighting, sun)
    }

    /// Direct illuminance at grid point `g` (among all grid points) per lux of direct
    /// normal illuminance from the sun in the room-frame direction `sun`; 0 for an index out
    /// of range.
    pub fn at_grid_point(&self, g: usize, sun: [f32; 3]) -> f32 {
        let Some((position, normal)) = self.basis.grid_point_placement(g) else {
            return 0.0;
        };
        self.at_surface(position, normal, sun)
    }

    /// Direct irradiance at a point `x` of a surface facing `normal` (a patch's sample
    /// point, [`crate::sky::sun_first`]) per lux of direct normal illuminance from the sun
    /// in the room-frame direction `sun`: the rule of a grid point.
    pub fn at_surface(&self, x: [f32; 3], normal: [f32; 3], sun: [f32; 3]) -> f32 {
        let hemisphere = Weighting::Cone {
            cos_half_angle: -1.0,
        };
        self.at(x, normal, hemisphere, sun)
    }

    /// The rule of the module documentation at `x` facing `normal`.
    fn at(&self, x: [f32; 3], normal: [f32; 3], weighting: Weighting, s: [f32; 3]) -> f32 {
        let weight = self.weight(weighting, dot(normal, s));
        // NaN compares false: a NaN weight or direction lights nothing.
        if weight.is_nan() || weight <= 0.0 || s[2].is_nan() || s[2] < 0.0 {
            return 0.0;
        }
        let [windows, room, exterior] = self.polygon_counts();
        let sizes = self.basis.tables.sun_polygon_sizes;
        let size = |k: usize| usize::from(sizes.get(k).copied().unwrap_or(0));
        // The polygons are walked in the stored order: each takes its normal and vertices.
        let after_windows = (0..windows).fold(0usize, |o, w| o.saturating_add(3 + 3 * size(w)));
        let mut total = 0.0;
        let mut offset = 0usize;
        for w in 0..windows {
            let here = offset;
            offset = offset.saturating_add(3 + 3 * size(w));
            let cos_window = -dot(self.vector(here), s);
            if cos_window.is_nan() || cos_window <= 0.0 {
                continue;
            }
            let Some(distance) = self.crossing(here, size(w), x, s) else {
                continue;
            };
            if distance <= 0.0
                || self.shaded(after_windows, windows, room, exterior, x, s, distance)
            {
                continue;
            }
            total += self.transmittance(w, cos_window) * weight;
        }
        total
    }

    /// Whether an occluder cuts the ray from `x` along `s`: a room occluder before the
    /// window (at `distance`), an exterior one past it. `after_windows` is the offset of the
    /// first occluder.
    #[allow(clippy::too_many_arguments)]
    fn shaded(
        &self,
        after_windows: usize,
        windows: usize,
        room: usize,
        exterior: usize,
        x: [f32; 3],
        s: [f32; 3],
        distance: f32,
    ) -> bool {
        let sizes = self.basis.tables.sun_polygon_sizes;
        let mut offset = after_windows;
        for k in 0..room.saturating_add(exterior) {
            let size = usize::from(sizes.get(windows + k).copied().unwrap_or(0));
            let here = offset;
            offset = offset.saturating_add(3 + 3 * size);
            let Some(t) = self.crossing(here, size, x, s) else {
                continue;
            };
            let cut = if k < room {
                t > PLANE_MARGIN * distance && t < distance * (1.0 - PLANE_MARGIN)
            } else {
                t > distance * (1.0 + PLANE_MARGIN)
            };
            if cut {
                return true;
            }
        }
        false
    }

    /// Where the line `x + t s` crosses the polygon of `size` vertices stored at `offset`:
    /// `Some(t)` (m, of either sign) when it passes inside it, `None` when it misses or runs
    /// parallel to its plane. Inside by the crossing number in the plane of the two axes
    /// the normal leans on least.
    fn crossing(&self, offset: usize, size: usize, x: [f32; 3], s: [f32; 3]) -> Option<f32> {
        let n = self.vector(offset);
        let along = dot(n, s);
        if along == 0.0 || size < 3 {
            return None;
        }
        let first = self.vector(offset + 3);
        let t = dot(n, sub(first, x)) / along;
        let p = [x[0] + t * s[0], x[1] + t * s[1], x[2] + t * s[2]];
        let a = [n[0].abs(), n[1].abs(), n[2].abs()];
        let (u, v) = if a[0] >= a[1] && a[0] >= a[2] {
            (1, 2)
        } else if a[1] >= a[2] {
            (0, 2)
        } else {
            (0, 1)
        };
        let at = |k: usize, axis: usize| {
            f32_at(self.basis.tables.sun_polygons, offset + 3 + 3 * k + axis)
        };
        let (pu, pv) = (component(p, u), component(p, v));
        let mut inside = false;
        let mut j = size - 1;
        for i in 0..size {
            let (iu, iv, ju, jv) = (at(i, u), at(i, v), at(j, u), at(j, v));
            if (iv > pv) != (jv > pv) && pu < iu + (pv - iv) * (ju - iu) / (jv - iv) {
                inside = !inside;
            }
            j = i;
        }
        (inside && t.is_finite()).then_some(t)
    }

    /// Where each stored polygon starts in the polygon table and its vertex count: the
    /// window faces, then the room occluders, then the exterior ones.
    pub(super) fn polygons(&self) -> impl Iterator<Item = (usize, usize)> + '_ {
        let total = self
            .state
            .counts
            .iter()
            .fold(0usize, |a, &c| a.saturating_add(c as usize));
        let sizes = self.basis.tables.sun_polygon_sizes;
        sizes.iter().take(total).scan(0usize, |offset, &size| {
            let (here, size) = (*offset, usize::from(size));
            *offset = offset.saturating_add(3 + 3 * size);
            Some((here, size))
        })
    }

    /// The three `f32` of the polygon table from `offset`.
    pub(super) fn vector(&self, offset: usize) -> [f32; 3] {
        let at = |k: usize| f32_at(self.basis.tables.sun_polygons, offset + k);
        [at(0), at(1), at(2)]
    }

    /// Window face `w`'s transmittance at incidence cosine `cos`, linear in its table.
    pub(super) fn transmittance(&self, w: usize, cos: f32) -> f32 {
        let at = cos.clamp(0.0, 1.0) * GLAZING_STEPS as f32;
        // `at` is in [0, 64]: the cast truncates towards zero.
        let i = (at as usize).min(GLAZING_STEPS - 1);
        let f = at - i as f32;
        let row = w * (GLAZING_STEPS + 1);
        let table = self.basis.tables.sun_glazing;
        f32_at(table, row + i) * (1.0 - f) + f32_at(table, row + i + 1) * f
    }

    /// How a receiver of `weighting` counts light arriving at cosine `c` to its normal.
    fn weight(&self, weighting: Weighting, c: f32) -> f32 {
        if c.is_nan() || c <= 0.0 {
            return 0.0;
        }
        match weighting {
            Weighting::Cone { cos_half_angle } if c >= cos_half_angle => c,
            Weighting::Cone { .. } => 0.0,
            Weighting::Response { first, rows } => {
                let table = self.basis.tables.sensor_response;
                let pair = |k: usize| {
                    let at = 2 * (first + k);
                    (f32_at(table, at), f32_at(table, at + 1))
                };
                // The host's rule (`Response::at_angle`): linear in the polar angle between
                // rows, zero before the first and past the last.
                let theta = approx::acos(c.min(1.0));
                let mut previous: Option<(f32, f32)> = None;
                for k in 0..rows {
                    let (p, value) = pair(k);
                    if p > theta {
                        return match previous {
                            Some((p0, s0)) => s0 + (value - s0) * (theta - p0) / (p - p0),
                            None => 0.0,
                        };
                    }
                    previous = Some((p, value));
                }
                match previous {
                    Some((p, value)) if p == theta => value,
                    _ => 0.0,
                }
            }
        }
    }
}

fn dot(a: [f32; 3], b: [f32; 3]) -> f32 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn sub(a: [f32; 3], b: [f32; 3]) -> [f32; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

/// Component `axis` (0, 1 or 2) of `p`, without an indexing that could panic.
fn component(p: [f32; 3], axis: usize) -> f32 {
    match axis {
        0 => p[0],
        1 => p[1],
        _ => p[2],
    }
}
