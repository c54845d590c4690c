//! The sun's first reflection at the sun's own direction, computed on the controller from
//! the patches a basis stores as the sun's candidates (docs/format.md, "The sun's first
//! reflection"; docs/math.md, "The sun between the grid's nodes, part by part").
//!
//! Between the sun grid's nodes a reading is not smooth where the sun patch's first
//! reflection changes what it sees (a ceiling photocell's cone cutting the floor's sun
//! patch), nor where the light entering the room jumps (an obstruction's shadow edge
//! sweeping the window). Both are computed here at the sun: each candidate patch's
//! irradiance `E_j`, the mean of its sample points' direct sun (the rule of
//! [`crate::sky::direct`], weighed by each point's share of the patch's area), its first
//! reflection `M0_j = ρ_j E_j`, and its power `P = Σ_j A_j M0_j`. A reading's first
//! reflection is then `Σ_j R_oj M0_j` over the stored view rows (`output_view`,
//! `grid_view`), and what the room reflects after it is interpolated per unit of `P`.
//!
//! Every loop runs over the stored tables with checked reads: any bytes give a number, never
//! a panic.

use super::direct::DirectSun;
use crate::basis::Basis;
use crate::storage::{f32_at, u32_at};

/// Most sample points of one candidate patch.
pub const MAX_SAMPLES: u8 = 16;

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

    /// Bytes of the four tables, their lengths included: what the sun's first reflection
    /// adds to the basis.
    pub fn stored_bytes(&self) -> usize {
        let t = &self.basis.tables;
        crate::storage::serialized_len(&[
            t.sun_first_patches,
            t.sun_first_sizes,
            t.sun_first_points,
            t.sun_node_power,
        ])
    }

    /// Calls `lit(patch, m0)` for every candidate the sun in the room-frame direction `sun`
    /// lights, `m0` its first reflection (lux per lux of direct normal illuminance), and
    /// returns their power `P = Σ_j A_j M0_j` (lm per lux).
    pub fn each_lit(&self, sun: [f32; 3], mut lit: impl FnMut(usize, f32)) -> f32 {
        let t = &self.basis.tables;
        let bands = self.basis.counts.bands;
        let mut power = 0.0;
        let mut offset = 0usize;
        for (k, &size) in t.sun_first_sizes.iter().enumerate() {
            let here = offset;
            let size = usize::from(size);
            offset = offset.saturating_add(3 + 4 * size);
            let at = |i: usize| f32_at(t.sun_first_points, here.saturating_add(i));
            let normal = [at(0), at(1), at(2)];
            let facing = normal[0] * sun[0] + normal[1] * sun[1] + normal[2] * sun[2];
            // NaN compares false: a NaN direction lights nothing.
            if facing.is_nan() || facing <= 0.0 {
                continue;
            }
            let mut irradiance = 0.0;
            for p in 0..size {
                let point = 3 + 4 * p;
                let x = [at(point), at(point + 1), at(point + 2)];
                let e = self.direct.at_surface(x, normal, sun);
                if e > 0.0 {
                    irradiance += at(point + 3) * e;
                }
            }
            if irradiance > 0.0 {
                let patch = u32_at(t.sun_first_patches, k) as usize;
                // Daylight is photopic: band 0.
                let m0 = f32_at(t.patch_reflectance, patch.saturating_mul(bands)) * irradiance;
                power += f32_at(t.patch_area, patch) * m0;
                lit(patch, m0);
            }
        }
        power
    }
}

impl SunFirst<'_, '_> {
    /// Adds `scale` times each output's first reflection `Σ_j R_oj M0_j` at the sun in the
    /// room-frame direction `sun` (`R_o` its stored view row, `output_view`) to its slot of
    /// `out` (sensors, then zones; lux per lux of direct normal illuminance times `scale`),
    /// and returns the first reflection's power `P` (lm per lux).
    pub fn add_outputs(&self, sun: [f32; 3], scale: f32, out: &mut [f32]) -> f32 {
        let view = self.basis.output_view();
        let count = out.len();
        self.each_lit(sun, |patch, m0| {
            let m0 = scale * m0;
            view.for_each_compact(patch, 0, count, |o, r| {
                if let Some(slot) = out.get_mut(o) {
                    *slot += r * m0;
                }
            });
        })
    }

    /// Grid point `g`'s first reflection `Σ_j R_gj M0_j` at the sun in the room-frame
    /// direction `sun` (`R_g` its stored view row, `grid_view`), lux per lux of direct normal
    /// illuminance; 0 for an index out of range.
    pub fn at_grid_point(&self, g: usize, sun: [f32; 3]) -> f32 {
        let view = self.basis.grid_view();
        let mut seen = 0.0;
        self.each_lit(sun, |patch, m0| {
            view.for_each_compact(g, patch, 1, |_, r| seen += r * m0);
        });
        seen
    }
}
