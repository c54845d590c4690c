//! The sun's first reflection at the sun's own direction, computed on the controller from
//! the patches a basis stores as the sun's candidates (docs/format.md, "The sun's first
//! reflection"; docs/math.md, "The sun between the grid's nodes, part by part").
//!
//! Between the sun grid's nodes a reading is not smooth where the sun patch's first
//! reflection changes what it sees (a ceiling photocell's cone cutting the floor's sun
//! patch), nor where the light entering the room jumps (an obstruction's shadow edge
//! sweeping the window). Both are computed here at the sun: each candidate patch's
//! irradiance `E_j`, the mean direct sun over its area (its sunlit part clipped exactly,
//! [`crate::sky::sunlit`]; sampled at points where that does not fit its buffers), its
//! first reflection `M0_j = ρ_j E_j`, and its power `P = Σ_j A_j M0_j`. A basis that stores each
//! reading's response to each candidate (`sun_first_response`, `T_oj`, the reading's whole
//! response to a unit of `M0_j`: its view of the patch and everything the room reflects
//! after it) reads the sun's reflected light as `Σ_j T_oj M0_j`, exact for the `M0` computed
//! here, and interpolates only what is left (a diffusing window's sun, say). Without it, a
//! reading's first reflection is `Σ_j R_oj M0_j` over the stored view rows (`output_view`,
//! `grid_view`), and what the room reflects after it is interpolated per unit of `P`.
//!
//! Every loop runs over the stored tables with checked reads: any bytes give a number, never
//! a panic.

use super::direct::DirectSun;
use crate::basis::Basis;
use crate::storage::{f32_at, u32_at};

/// Most corners of one candidate patch.
pub const MAX_CORNERS: u8 = 16;

/// The candidates of a basis that stores them, with the direct sun's geometry their sample
/// points are lit through.
#[derive(Clone, Copy, Debug)]
pub struct SunFirst<'b, 'a> {
    basis: &'b Basis<'a>,
    direct: DirectSun<'b, 'a>,
}

impl<'b, 'a> SunFirst<'b, 'a> {
    /// The sun's first reflection of `basis` lit through `direct` (its direct sun), `None`
    /// when the basis stores no candidates (each sun node's reflected sun is then
    /// interpolated whole). The tables were checked with the daylight's values
    /// ([`Basis::check_daylight`], which [`DirectSun::new`] runs).
    pub fn new(basis: &'b Basis<'a>, direct: DirectSun<'b, 'a>) -> Option<Self> {
        (!basis.tables.sun_node_power.is_empty()).then_some(SunFirst { basis, direct })
    }

    /// Whether `basis` stores the candidates.
    pub fn stored(basis: &Basis<'_>) -> bool {
        !basis.tables.sun_node_power.is_empty()
    }

    /// Candidate patches stored.
    pub fn patch_count(&self) -> usize {
        self.basis.tables.sun_first_patches.len() / 4
    }

    /// The power of the first reflection at stored sun node `position` (its place among the
    /// stored nodes) as this rule computes it, lm per lux of direct normal illuminance; 0
    /// out of range.
    pub fn node_power(&self, position: usize) -> f32 {
        f32_at(self.basis.tables.sun_node_power, position)
    }

    /// Bytes of the eight tables, their lengths included: what the sun's first reflection
    /// adds to the basis.
    pub fn stored_bytes(&self) -> usize {
        let t = &self.basis.tables;
        crate::storage::serialized_len(&[
            t.sun_first_patches,
            t.sun_first_sizes,
            t.sun_first_points,
            t.sun_node_power,
            t.sun_first_response,
            t.zone_sun_counts,
            t.zone_sun_sizes,
            t.zone_sun_polygons,
        ])
    }

    /// Bytes of the responses alone (`sun_first_response`), its length included.
    pub fn response_bytes(&self) -> usize {
        crate::storage::serialized_len(&[self.basis.tables.sun_first_response])
    }

    /// Polygons the zones' direct sun is computed on, all zones together.
    pub fn zone_polygon_count(&self) -> usize {
        self.basis.tables.zone_sun_sizes.len()
    }

    /// Whether the basis stores every reading's response to each candidate: the sun's
    /// reflected light is then computed whole at the sun, and only what is left of each
    /// node's reading interpolated, without weighing it by the power.
    pub fn responds(&self) -> bool {
        !self.basis.tables.sun_first_response.is_empty()
    }

    /// Readings per candidate in the response table: sensors, zones, grid points.
    fn readings(&self) -> usize {
        let c = &self.basis.counts;
        c.sensor_count + c.zone_count + c.grid_point_count
    }

    /// Calls `lit(candidate, patch, m0)` for every candidate the sun in the room-frame
    /// direction `sun` lights (`candidate` its place among the candidates), `m0` its first
    /// reflection (lux per lux of direct normal illuminance), and returns their power
    /// `P = Σ_j A_j M0_j` (lm per lux).
    pub fn each_lit(&self, sun: [f32; 3], mut lit: impl FnMut(usize, usize, f32)) -> f32 {
        self.each_lit_dyn(sun, &mut lit)
    }

    /// [`SunFirst::each_lit`] through a reference: one copy of the candidates' loop in flash
    /// whatever the callers.
    #[inline(never)]
    fn each_lit_dyn(&self, sun: [f32; 3], lit: &mut dyn FnMut(usize, usize, f32)) -> f32 {
        let t = &self.basis.tables;
        let bands = self.basis.counts.bands;
        let mut power = 0.0;
        let mut offset = 0usize;
        for (k, &size) in t.sun_first_sizes.iter().enumerate() {
            let here = offset;
            let size = usize::from(size).min(usize::from(MAX_CORNERS));
            offset = offset.saturating_add(3 + 3 * size);
            // A candidate facing away is dark: its corners are not read.
            let at = |i: usize| f32_at(t.sun_first_points, here.saturating_add(i));
            let facing = at(0) * sun[0] + at(1) * sun[1] + at(2) * sun[2];
            // NaN compares false: a NaN direction lights nothing.
            if facing.is_nan() || facing <= 0.0 {
                continue;
            }
            let (irradiance, _) = self.on_polygon(t.sun_first_points, here, size, sun);
            if irradiance > 0.0 {
                let patch = u32_at(t.sun_first_patches, k) as usize;
                // Daylight is photopic: band 0.
                let m0 = f32_at(t.patch_reflectance, patch.saturating_mul(bands)) * irradiance;
                power += f32_at(t.patch_area, patch) * m0;
                lit(k, patch, m0);
            }
        }
        power
    }

    /// The mean direct irradiance (per lux of direct normal illuminance) over the polygon of
    /// `size` corners stored in `table` from `offset` (its unit normal, then its corners) and
    /// its area (m²): clipped exactly, or sampled where the
    /// clipping does not fit its buffers.
    #[inline(never)]
    fn on_polygon(&self, table: &[u8], offset: usize, size: usize, sun: [f32; 3]) -> (f32, f32) {
        let at = |i: usize| f32_at(table, offset.saturating_add(i));
        let normal = [at(0), at(1), at(2)];
        let mut corners = [[0.0f32; 3]; MAX_CORNERS as usize];
        for (i, c) in corners.iter_mut().enumerate().take(size) {
            *c = [at(3 + 3 * i), at(4 + 3 * i), at(5 + 3 * i)];
        }
        let corners = corners.get(..size).unwrap_or(&[]);
        let irradiance = match self.direct.on_patch(corners, normal, sun) {
            Some(e) => e,
            None => self.sampled(corners, normal, sun),
        };
        (irradiance, polygon_area(corners))
    }

    /// The mean direct irradiance of a patch sampled at the centroids of the triangles its
    /// centroid fans it into, each weighed by its area: the rule where the sunlit pieces do
    /// not fit their buffers or a polygon is not convex.
    #[inline(never)]
    fn sampled(&self, corners: &[[f32; 3]], normal: [f32; 3], sun: [f32; 3]) -> f32 {
        let n = corners.len() as f32;
        let centre = corners.iter().fold([0.0f32; 3], |c, x| {
            [c[0] + x[0] / n, c[1] + x[1] / n, c[2] + x[2] / n]
        });
        let (mut sum, mut total) = (0.0, 0.0);
        for (i, &a) in corners.iter().enumerate() {
            let b = corners.get(i + 1).or(corners.first()).copied().unwrap_or(a);
            let (p, q) = (
                [a[0] - centre[0], a[1] - centre[1], a[2] - centre[2]],
                [b[0] - centre[0], b[1] - centre[1], b[2] - centre[2]],
            );
            let cross = [
                p[1] * q[2] - p[2] * q[1],
                p[2] * q[0] - p[0] * q[2],
                p[0] * q[1] - p[1] * q[0],
            ];
            let area =
                0.5 * libm::sqrtf(cross[0] * cross[0] + cross[1] * cross[1] + cross[2] * cross[2]);
            let x = [
                (centre[0] + a[0] + b[0]) / 3.0,
                (centre[1] + a[1] + b[1]) / 3.0,
                (centre[2] + a[2] + b[2]) / 3.0,
            ];
            sum += area * self.direct.at_surface(x, normal, sun);
            total += area;
        }
        if total > 0.0 {
            sum / total
        } else {
            0.0
        }
    }
}

impl SunFirst<'_, '_> {
    /// Zone `zone`'s direct sun per lux of direct normal illuminance from the sun in the
    /// room-frame direction `sun`: the area-weighted mean over the polygons the basis stores
    /// for it (a work plane's receivers), each clipped as a candidate is; 0 for a zone without
    /// them or out of range.
    #[inline(never)]
    pub fn zone_direct(&self, zone: usize, sun: [f32; 3]) -> f32 {
        let t = &self.basis.tables;
        if t.zone_sun_counts.is_empty() {
            return 0.0;
        }
        let count = |z: usize| u32_at(t.zone_sun_counts, z) as usize;
        let first = (0..zone).map(count).fold(0usize, usize::saturating_add);
        let size = |k: usize| usize::from(t.zone_sun_sizes.get(k).copied().unwrap_or(0));
        let mut offset = (0..first).fold(0usize, |o, k| o.saturating_add(3 + 3 * size(k)));
        let (mut sum, mut total) = (0.0, 0.0);
        for k in first..first.saturating_add(count(zone)) {
            let here = offset;
            let size = size(k).min(usize::from(MAX_CORNERS));
            offset = offset.saturating_add(3 + 3 * size);
            let (irradiance, area) = self.on_polygon(t.zone_sun_polygons, here, size, sun);
            sum += area * irradiance;
            total += area;
        }
        if total > 0.0 {
            sum / total
        } else {
            0.0
        }
    }

    /// Adds `scale` times each output's reflected sun at the sun in the room-frame direction
    /// `sun` to its slot of `out` (sensors, then zones; lux per lux of direct normal
    /// illuminance times `scale`), and returns the first reflection's power `P` (lm per lux):
    /// `Σ_j T_oj M0_j` with the stored responses, else the first reflection alone,
    /// `Σ_j R_oj M0_j` (`R_o` its stored view row, `output_view`); and each zone's direct
    /// sun on its stored polygons ([`SunFirst::zone_direct`]).
    pub fn add_outputs(&self, sun: [f32; 3], scale: f32, out: &mut [f32]) -> f32 {
        let count = out.len();
        let sensors = self.basis.counts.sensor_count;
        for (z, slot) in out.iter_mut().skip(sensors).enumerate() {
            *slot += scale * self.zone_direct(z, sun);
        }
        if self.responds() {
            let (response, width) = (self.basis.tables.sun_first_response, self.readings());
            return self.each_lit(sun, |k, _, m0| {
                let row = k.saturating_mul(width);
                for (o, slot) in out.iter_mut().enumerate().take(width) {
                    *slot += scale * m0 * f32_at(response, row.saturating_add(o));
                }
            });
        }
        let view = self.basis.output_view();
        self.each_lit(sun, |_, patch, m0| {
            let m0 = scale * m0;
            view.for_each_compact(patch, 0, count, |o, r| {
                if let Some(slot) = out.get_mut(o) {
                    *slot += r * m0;
                }
            });
        })
    }

    /// Grid point `g`'s reflected sun at the sun in the room-frame direction `sun`, lux per
    /// lux of direct normal illuminance: `Σ_j T_gj M0_j` with the stored responses, else its
    /// first reflection `Σ_j R_gj M0_j` (`R_g` its stored view row, `grid_view`); 0 for an
    /// index out of range.
    pub fn at_grid_point(&self, g: usize, sun: [f32; 3]) -> f32 {
        let mut seen = 0.0;
        if self.responds() {
            let (response, width) = (self.basis.tables.sun_first_response, self.readings());
            let c = &self.basis.counts;
            if g >= c.grid_point_count {
                return 0.0;
            }
            let column = c.sensor_count + c.zone_count + g;
            self.each_lit(sun, |k, _, m0| {
                let at = k.saturating_mul(width).saturating_add(column);
                seen += m0 * f32_at(response, at);
            });
            return seen;
        }
        let view = self.basis.grid_view();
        self.each_lit(sun, |_, patch, m0| {
            view.for_each_compact(g, patch, 1, |_, r| seen += r * m0);
        });
        seen
    }
}

/// Area of the planar polygon of `corners`, m²: half the length of the sum of the crosses of
/// its fan from the first corner.
fn polygon_area(corners: &[[f32; 3]]) -> f32 {
    let Some(&o) = corners.first() else {
        return 0.0;
    };
    let mut twice = [0.0f32; 3];
    for (i, a) in corners.iter().enumerate().skip(1) {
        let Some(b) = corners.get(i + 1) else { break };
        let (p, q) = (
            [a[0] - o[0], a[1] - o[1], a[2] - o[2]],
            [b[0] - o[0], b[1] - o[1], b[2] - o[2]],
        );
        twice[0] += p[1] * q[2] - p[2] * q[1];
        twice[1] += p[2] * q[0] - p[0] * q[2];
        twice[2] += p[0] * q[1] - p[1] * q[0];
    }
    0.5 * libm::sqrtf(twice[0] * twice[0] + twice[1] * twice[1] + twice[2] * twice[2])
}
