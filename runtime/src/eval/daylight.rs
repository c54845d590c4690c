//! Daylight through the windows of a basis that carries it: the sky's patches, the exterior
//! and the sun, each a node whose exact readings the basis stores (docs/format.md,
//! "Daylight"; docs/math.md, "Daylight in the basis").

use super::reflection::{self, SunLists};
use super::weights::{SunWeight, Weights, NO_COLUMN, NO_SUN};
use super::{fits, grid_figures, luminance, ChannelEvaluator, Figures, MAX_EXITANCE};
use crate::basis::{check_index, Basis};
use crate::error::{Error, Result};
use crate::sky::direct::{DirectSun, DirectSunState};
use crate::sky::sun_first::SunFirst;
use crate::sky::sun_grid::NodeWeight;

/// `(0.0..=MAX_EXITANCE).contains(&x)` on the bits, for the sky's luminances of every
/// update: a non-negative `f32` (NaN and +∞ included) orders as its bits do, and a negative
/// one has the sign bit, so larger bits than any of them, −0 aside (valid, as `0.0 <= -0.0`).
#[inline]
fn valid_bits(x: f32) -> bool {
    x.to_bits() <= MAX_EXITANCE.to_bits() || x == 0.0
}

/// The largest bits of the values of `values` (0 for none).
fn largest_bits(values: &[f32]) -> u32 {
    let (fours, rest) = values.as_chunks::<4>();
    let largest = fours.iter().fold(0u32, |m, &[a, b, c, d]| {
        m.max(a.to_bits())
            .max(b.to_bits())
            .max(c.to_bits())
            .max(d.to_bits())
    });
    rest.iter().fold(largest, |m, x| m.max(x.to_bits()))
}

/// `from` copied into `to` (as long as `from`) four values a load and a store: `memcpy`
/// took 3.4 instructions a value, a loop of one value a step four. The last four values
/// are copied as one, again when the length is a multiple of four: a loop for the rest was
/// turned into a call of `memcpy`, about a hundred instructions for one value.
fn copy(from: &[f32], to: &mut [f32]) {
    if from.len() < 4 {
        for (t, &f) in to.iter_mut().zip(from) {
            *t = f;
        }
        return;
    }
    let (from_fours, _) = from.as_chunks::<4>();
    let (to_fours, _) = to.as_chunks_mut::<4>();
    for (t, &f) in to_fours.iter_mut().zip(from_fours) {
        *t = f;
    }
    let to = to.get_mut(..from.len()).unwrap_or(&mut []);
    if let (Some(t), Some(&f)) = (to.last_chunk_mut::<4>(), from.last_chunk::<4>()) {
        *t = f;
    }
}

/// The sun of a moment, as a [`DaylightEvaluator`] takes it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sun {
    /// Unit vector towards the sun in the site's frame: x east, y north, z up
    /// ([`crate::sky::direction`] builds it from altitude and azimuth). Below the horizon
    /// (`z < 0`) it lights nothing.
    pub direction: [f32; 3],
    /// Direct normal illuminance, lux.
    pub direct_normal: f32,
}

/// Turns a sky state (the luminance of every sky patch, the global horizontal illuminance,
/// the sun) into the daylight illuminance of every sensor, zone and grid point, exact to
/// `f32` for the sky's patches and at the sun grid's nodes, and into patch exitance: its
/// first reflection from the basis' own tables when it stores them, what the room reflects
/// after that through the modes.
///
/// The basis stores, per daylight node (each sky patch per cd/m², the exterior per cd/m² of
/// `E_gh/π`, each sun node per lux of direct normal illuminance), every output's exact
/// illuminance, every grid point's, and the mode amplitudes of the room's exact exitance.
/// A sky update ([`set_sky`](Self::set_sky)) weighs the nodes: the sky's patches by their
/// luminances, the exterior by `E_gh/π`, the four sun nodes around the sun by their bilinear
/// weights in declination and hour angle ([`crate::sky::sun_grid`]) times `E_n`; it then
/// sums every output's row (`O × D` products) and, when `EXITANCE > 0`, the state patch
/// exitance is read from: with a stored first reflection, its `r` coefficients
/// (`r × (S_k + 1)` products) and the `p` mode amplitudes of what follows it
/// (`p × (r + 4)`); without, the modes' amplitudes of the whole exitance (`p × D`).
/// When the basis stores the direct sun's geometry ([`crate::sky::direct`]), the sun nodes
/// hold only the light the room reflects at sensors and grid points, and the update adds
/// each sensor's direct sun at the sun's own direction (a ray test per window face and
/// occluder), so that a sun patch's edge crossing a sensor is not smeared between nodes.
/// Sensor and zone reads cost nothing more; a grid point sums its row and computes its
/// direct sun when read.
///
/// Capacities: `SKY` at least the basis' sky patches (145 for Tregenza), `OUTPUTS` at least
/// its sensors plus zones, and `EXITANCE` either 0 (no patch exitance: updates skip it) or
/// at least [`Basis::daylight_exitance_state`], its mode count plus the rank of its first
/// reflection. Daylight adds to the electric light of a
/// [`ChannelEvaluator`] or an [`Evaluator`](crate::Evaluator), which it does not hold:
/// [`zone_figures_with`](Self::zone_figures_with) takes the figures of the two together.
#[derive(Clone, Debug)]
pub struct DaylightEvaluator<'a, const SKY: usize, const OUTPUTS: usize, const EXITANCE: usize> {
    basis: Basis<'a>,
    /// Each sky patch's luminance, cd/m² (the basis' sky order).
    sky: heapless::Vec<f32, SKY>,
    /// `E_gh / π`, cd/m²: what the exterior's node is weighed by.
    exterior: f32,
    /// The sine and cosine of the site's latitude, for the sun's place in the grid.
    latitude_sin_cos: [f32; 2],
    /// The four sun nodes around the sun (their columns among the daylight nodes, or none
    /// where the node lights nothing) with their weight times `E_n`, lux.
    sun: [SunWeight; 4],
    /// The direct sun's geometry, when the basis stores it: sensors and grid points then
    /// add the sun they see through the windows themselves.
    direct: Option<DirectSunState>,
    /// The sun in the room's frame and its direct normal illuminance (lux; 0 without sun).
    direct_sun: ([f32; 3], f32),
    /// Whether the basis stores the sun's first reflection ([`crate::sky::sun_first`]):
    /// readings then add it at the sun's direction and read the rest per unit of its power.
    first: bool,
    /// The four sun nodes as the readings weigh them: [`Self::sun`], or with a stored first
    /// reflection each lit node's weight times `P(s) / (P_c Σ_lit w)`, so that the rest its
    /// column holds is interpolated per unit of power.
    reading_sun: [SunWeight; 4],
    /// Every output's daylight illuminance, lux.
    outputs: heapless::Vec<f32, OUTPUTS>,
    /// The daylight's mode amplitudes, then the coefficients of the sky's first reflection
    /// (empty when `EXITANCE` is 0).
    amplitude: heapless::Vec<f32, EXITANCE>,
    /// Where the sun nodes' first reflections lie in the basis' lists.
    sun_lists: SunLists,
}

impl<'a, const SKY: usize, const OUTPUTS: usize, const EXITANCE: usize>
    DaylightEvaluator<'a, SKY, OUTPUTS, EXITANCE>
{
    /// Bytes of state besides the basis view and the vectors' lengths.
    pub const RAM_BYTES: usize = 4 * (SKY + OUTPUTS + EXITANCE)
        + 4 * 3
        + 2 * core::mem::size_of::<[SunWeight; 4]>()
        + core::mem::size_of::<SunLists>()
        + core::mem::size_of::<Option<DirectSunState>>()
        + 4 * 4
        + 4;

    /// An evaluator of `basis`' daylight, dark (no sky, no sun).
    ///
    /// [`Error::NoDaylight`] when the basis carries none; [`Error::Capacity`] when its sky,
    /// its outputs or (with `EXITANCE > 0`) its patch exitance's state do not fit; a decoding error naming the
    /// table when a value of the daylight section is out of range (checked here,
    /// [`Basis::check_daylight`], not by [`Basis::from_bytes`]).
    pub fn new(basis: Basis<'a>) -> Result<Self> {
        let sky_patches = basis.sky_patches().ok_or(Error::NoDaylight)?;
        // Checks the daylight section's values before anything reads them.
        let direct = DirectSun::new(&basis)?.map(|d| d.state());
        fits("sky patches", sky_patches.count(), SKY)?;
        let outputs = basis.sensor_count() + basis.zone_count();
        fits("outputs", outputs, OUTPUTS)?;
        let state = basis.daylight_exitance_state();
        if EXITANCE > 0 {
            fits("modes and first reflection", state, EXITANCE)?;
        }
        let capacity = Error::Capacity {
            what: "outputs",
            needed: outputs,
            capacity: OUTPUTS,
        };
        let mut evaluator = DaylightEvaluator {
            basis,
            sky: heapless::Vec::new(),
            exterior: 0.0,
            latitude_sin_cos: basis
                .sun_grid()
                .map_or([0.0, 1.0], |g| g.latitude_sin_cos()),
            sun: NO_SUN,
            direct,
            direct_sun: ([0.0, 0.0, 1.0], 0.0),
            first: direct.is_some() && SunFirst::stored(&basis),
            reading_sun: NO_SUN,
            outputs: heapless::Vec::new(),
            amplitude: heapless::Vec::new(),
            sun_lists: SunLists::new(&basis),
        };
        evaluator
            .sky
            .resize(sky_patches.count(), 0.0)
            .map_err(|_| capacity)?;
        evaluator
            .outputs
            .resize(outputs, 0.0)
            .map_err(|_| capacity)?;
        if EXITANCE > 0 {
            evaluator
                .amplitude
                .resize(state, 0.0)
                .map_err(|_| capacity)?;
        }
        Ok(evaluator)
    }

    /// The basis being evaluated.
    pub fn basis(&self) -> &Basis<'a> {
        &self.basis
    }

    /// Sets the sky of a moment: `sky_luminance` (cd/m², one per sky patch of the basis, in
    /// its order: [`Basis::sky_patches`]), the global horizontal illuminance `E_gh` (lux)
    /// that lights the ground and the obstructions outside, and the sun, if any. Then sums
    /// every output's daylight (`O × D` products) and, with `EXITANCE > 0`, the state of
    /// patch exitance (see the type's documentation).
    ///
    /// An input that is negative, not finite or above [`MAX_EXITANCE`], a wrong number of
    /// luminances, or a sun direction that is not a unit vector is an error and changes
    /// nothing.
    /// A basis whose tables, each in range, multiply to a reading that is not finite (a
    /// sun node's stored power near 0) gives [`Error::DecodeValue`] naming
    /// `daylight_outputs` and the reading, after the update.
    pub fn set_sky(
        &mut self,
        sky_luminance: &[f32],
        global_horizontal: f32,
        sun: Option<Sun>,
    ) -> Result<()> {
        if sky_luminance.len() != self.sky.len() {
            return Err(Error::LengthMismatch {
                what: "sky_luminance",
                expected: self.sky.len(),
                found: sky_luminance.len(),
            });
        }
        // NaN and the infinities fall outside the (finite) range: one test covers them.
        let valid = |x: f32| (0.0..=MAX_EXITANCE).contains(&x);
        // Every luminance is in range when the largest of their bits is: a non-negative
        // `f32` orders as its bits do. Above it, a −0 (valid) or a value out of range: each
        // is then tested alone. Four values a step without a branch, where a test a value
        // took nine instructions.
        if largest_bits(sky_luminance) > MAX_EXITANCE.to_bits()
            && !sky_luminance.iter().all(|&x| valid_bits(x))
        {
            return Err(Error::InvalidInput {
                what: "sky_luminance",
            });
        }
        if !valid(global_horizontal) {
            return Err(Error::InvalidInput {
                what: "global_horizontal",
            });
        }
        let mut sun_nodes = NO_SUN;
        if let Some(s) = sun {
            if !valid(s.direct_normal) {
                return Err(Error::InvalidInput {
                    what: "direct_normal",
                });
            }
            self.sun_columns(s, &mut sun_nodes)?;
        }
        copy(sky_luminance, &mut self.sky);
        self.exterior = global_horizontal / core::f32::consts::PI;
        self.sun = sun_nodes;
        self.reading_sun = sun_nodes;
        // By reference: the basis view is over a hundred words, too many to copy per update.
        let basis = &self.basis;
        let columns = basis.counts.daylight_node_count;
        let tables = &basis.tables;
        let first = self.first_reflection(basis);
        // With the sun's first reflection the sun columns are weighed after it, per unit of
        // its power: the table's sum takes the sky and the exterior alone.
        let table_sun = if first.is_some() { &NO_SUN } else { &self.sun };
        let weights = Weights {
            sky: &self.sky,
            exterior: self.exterior,
            sun: table_sun,
        };
        weights.table(tables.daylight_outputs, columns, &mut self.outputs);
        let weights = Weights {
            sun: &self.sun,
            ..weights
        };
        match basis.counts.reflection_rank {
            None => weights.table(tables.daylight_modes, columns, &mut self.amplitude),
            Some(rank) => {
                reflection::update(
                    basis,
                    rank,
                    &weights,
                    &mut self.amplitude,
                    &mut self.sun_lists,
                );
            }
        }
        self.direct_sun = ([0.0, 0.0, 1.0], 0.0);
        if let (Some(state), Some(s)) = (self.direct, sun) {
            let direct = DirectSun::with(basis, state);
            let room = direct.room_direction(s.direction);
            self.direct_sun = (room, s.direct_normal);
            for (sensor, reading) in self.outputs.iter_mut().enumerate() {
                if sensor >= basis.counts.sensor_count {
                    break;
                }
                *reading += s.direct_normal * direct.at_sensor(sensor, room);
            }
        }
        if let (Some(first), Some(s)) = (first, sun) {
            let (room, direct_normal) = self.direct_sun;
            let power = first.add_outputs(room, direct_normal, &mut self.outputs);
            self.reading_sun = per_power(&first, self.sky.len() + 1, self.sun, power, s);
            for (o, reading) in self.outputs.iter_mut().enumerate() {
                for &(column, weight) in &self.reading_sun {
                    if column != NO_COLUMN {
                        let at = o.saturating_mul(columns).saturating_add(column as usize);
                        *reading += weight * crate::storage::f32_at(tables.daylight_outputs, at);
                    }
                }
            }
        }
        // Tables in range can still multiply to an overflow (a node's stored power close to
        // 0 divides its rest): such a basis is refused here rather than read as infinite.
        match self.outputs.iter().position(|x| !x.is_finite()) {
            Some(index) => Err(Error::DecodeValue {
                field: "daylight_outputs",
                index,
            }),
            None => Ok(()),
        }
    }

    /// Grid point `g`'s reading, [`Error::DecodeValue`] naming `daylight_grid` when the
    /// basis' tables make it overflow (as [`Self::set_sky`] refuses the outputs').
    fn checked_grid_reading(&self, g: usize) -> Result<f32> {
        let x = self.grid_reading(g);
        if x.is_finite() {
            Ok(x)
        } else {
            Err(Error::DecodeValue {
                field: "daylight_grid",
                index: g,
            })
        }
    }

    /// The sun's first reflection, when the basis stores it.
    fn first_reflection<'b>(&self, basis: &'b Basis<'a>) -> Option<SunFirst<'b, 'a>> {
        match self.direct {
            Some(state) if self.first => SunFirst::new(basis, DirectSun::with(basis, state)),
            _ => None,
        }
    }

    /// The four sun nodes around `sun` into `out` (left as it is on an error) as columns
    /// among the daylight nodes, each with its bilinear weight times the direct normal
    /// illuminance (lux); nodes that light nothing (absent from `sun_nodes`) have no column,
    /// and a sun below the horizon none at all. Written in place: a returned `Result` of the
    /// array was copied through `memcpy`, byte by byte, twice an update.
    fn sun_columns(&self, sun: Sun, out: &mut [SunWeight; 4]) -> Result<()> {
        let grid = self.basis.sun_grid().ok_or(Error::NoDaylight)?;
        let mut weights = [NodeWeight::default(); 4];
        grid.weights_into(sun.direction, self.latitude_sin_cos, &mut weights)?;
        *out = NO_SUN;
        if sun.direction[2] < 0.0 {
            return Ok(());
        }
        let first_sun = self.sky.len() + 1;
        for (slot, w) in out.iter_mut().zip(weights) {
            if w.weight > 0.0 {
                *slot = (
                    self.basis
                        .sun_node_position(w.node)
                        .and_then(|i| u32::try_from(first_sun + i).ok())
                        .unwrap_or(NO_COLUMN),
                    w.weight * sun.direct_normal,
                );
            }
        }
        Ok(())
    }

    /// Daylight illuminance at sensor `sensor`, lux. O(1).
    pub fn sensor_illuminance(&self, sensor: usize) -> Result<f32> {
        check_index("sensor", sensor, self.basis.counts.sensor_count)?;
        Ok(self.outputs.get(sensor).copied().unwrap_or(0.0))
    }

    /// Daylight illuminance averaged over zone `zone`, lux. O(1).
    pub fn zone_illuminance(&self, zone: usize) -> Result<f32> {
        check_index("zone", zone, self.basis.counts.zone_count)?;
        let o = self.basis.counts.sensor_count + zone;
        Ok(self.outputs.get(o).copied().unwrap_or(0.0))
    }

    /// Daylight illuminance of grid point `g` (among all grid points), already checked.
    /// O(D).
    fn grid_reading(&self, g: usize) -> f32 {
        let view = self.basis.daylight_grid();
        let sky = view.row_dot(g, 0, &self.sky);
        let exterior = self.sky.len();
        let mut sum = sky;
        let mut add = |column: usize, weight: f32| {
            view.for_each_compact(g, column, 1, |_, v| sum += v * weight);
        };
        add(exterior, self.exterior);
        for &(column, weight) in &self.reading_sun {
            if column != NO_COLUMN {
                add(column as usize, weight);
            }
        }
        let (sun, direct_normal) = self.direct_sun;
        if direct_normal > 0.0 {
            if let Some(first) = self.first_reflection(&self.basis) {
                let seen = first.at_grid_point(g, sun);
                sum += direct_normal * seen;
            }
        }
        match self.direct {
            Some(state) if direct_normal > 0.0 => {
                sum + direct_normal * DirectSun::with(&self.basis, state).at_grid_point(g, sun)
            }
            _ => sum,
        }
    }

    /// Daylight illuminance at point `point` of zone `zone`'s calculation grid, lux: exact
    /// per node as a sensor's. O(D).
    pub fn grid_point_illuminance(&self, zone: usize, point: usize) -> Result<f32> {
        let g = self.basis.grid_index(zone, point)?;
        self.checked_grid_reading(g)
    }

    /// `E_avg`, `E_min`, `E_max` and `U_o` of zone `zone`'s grid under daylight alone,
    /// streamed without a buffer. O(points · D). [`Error::NoGrid`] for a zone without one.
    pub fn zone_figures(&self, zone: usize) -> Result<Figures> {
        let range = self.basis.grid_range(zone)?;
        let [figures] = grid_figures(zone, range, |g| Ok([self.checked_grid_reading(g)?]))?;
        Ok(figures)
    }

    /// The figures of zone `zone`'s grid under daylight and the electric light of
    /// `electric` together (the same basis), point by point: the minimum of a sum is not the
    /// sum of the minima. O(points · (D + m)).
    pub fn zone_figures_with<const CHANNELS: usize>(
        &self,
        zone: usize,
        electric: &ChannelEvaluator<'_, 1, CHANNELS>,
    ) -> Result<Figures> {
        let range = self.basis.grid_range(zone)?;
        let [figures] = grid_figures(zone, range, |g| {
            let [e] = electric.grid_reading(g);
            Ok([self.checked_grid_reading(g)? + e])
        })?;
        Ok(figures)
    }

    /// Daylight exitance of `patch`, lux (lm/m²): with a stored first reflection, that
    /// reflection exact (to `f32` and the sky's rank) plus what the room reflects after it
    /// through the modes, `Σ_k v_k · a_k`; without, the whole exitance through the modes.
    /// Exact when `p = n`, otherwise the modes' part is its projection on the `p` modes
    /// (docs/math.md, "Daylight's first reflection"). O(r + p). [`Error::Capacity`] when
    /// `EXITANCE` is 0.
    pub fn exitance(&self, patch: usize) -> Result<f32> {
        check_index("patch", patch, self.basis.counts.patch_count)?;
        if EXITANCE == 0 {
            return Err(Error::Capacity {
                what: "modes and first reflection",
                needed: self.basis.daylight_exitance_state(),
                capacity: 0,
            });
        }
        let p = self.basis.counts.mode_count;
        let (amplitudes, coefficients) = self.amplitude.split_at(p.min(self.amplitude.len()));
        let reflected = self.basis.modes().row_dot(patch, 0, amplitudes);
        if self.basis.counts.reflection_rank.is_none() {
            return Ok(reflected);
        }
        let first = reflection::first_reflection(
            &self.basis,
            patch,
            coefficients,
            &self.sun,
            &self.sun_lists,
        );
        Ok(first + reflected)
    }

    /// Daylight luminance of `patch` as a Lambertian surface, `M/π`, cd/m².
    pub fn luminance(&self, patch: usize) -> Result<f32> {
        let [l] = luminance([self.exitance(patch)?]);
        Ok(l)
    }
}

/// The sun nodes `sun` (columns from `first_sun` on, each weight its bilinear weight times
/// `E_n`) weighed for a rest per unit of the first reflection's power: a node whose stored
/// power `P_c` is positive takes `w_c P(s) / (P_c Σ_lit w / E_n)`, the bilinear mean of the
/// lit nodes' `Q_c / P_c` times `P(s)` (docs/math.md, "The sun between the grid's nodes, part
/// by part"); a node lighting no candidate keeps its weight, its column the rest itself.
/// With the stored responses what is left of a column after the reflected sun is mostly a
/// work-plane zone's direct sun, which follows the power entering the room as well.
fn per_power(
    first: &SunFirst<'_, '_>,
    first_sun: usize,
    sun: [SunWeight; 4],
    power: f32,
    s: Sun,
) -> [SunWeight; 4] {
    let node_power = |column: u32| {
        if column == NO_COLUMN {
            0.0
        } else {
            first.node_power((column as usize).saturating_sub(first_sun))
        }
    };
    let lit: f32 = sun
        .iter()
        .filter(|&&(column, _)| node_power(column) > 0.0)
        .map(|&(_, weight)| weight)
        .sum();
    sun.map(|(column, weight)| {
        let p = node_power(column);
        if p > 0.0 && lit > 0.0 {
            (column, weight * power * s.direct_normal / (p * lit))
        } else {
            (column, weight)
        }
    })
}

#[cfg(test)]
mod tests {
    #![allow(clippy::indexing_slicing)]
    use super::*;

    /// The largest bits of a set pass the range's bound only when every value of the set is
    /// in range, and do for every set of non-negative values in range (every pair of the
    /// values listed, with a valid third); `copy` copies every length whole, nothing past
    /// it.
    #[test]
    fn largest_bits_pass_valid_sets_only_and_copy_copies() {
        let max = MAX_EXITANCE;
        let values = [
            0.0,
            -0.0,
            f32::from_bits(1),
            -1.0,
            1.0,
            1.0e3,
            max,
            f32::from_bits(max.to_bits() + 1),
            f32::INFINITY,
            f32::NAN,
        ];
        for a in values {
            for b in values {
                let set = [a, 2.5, b, 0.5, 1.0e4];
                let positive = set.iter().all(|x| x.to_bits() >> 31 == 0);
                let valid = set.iter().all(|&x| valid_bits(x));
                let passes = largest_bits(&set) <= max.to_bits();
                assert_eq!(passes, valid && positive, "{a:e} {b:e}");
            }
        }
        let from: [f32; 11] = core::array::from_fn(|i| i as f32 + 0.5);
        for n in 0..=from.len() {
            let mut to = [f32::NAN; 11];
            copy(&from[..n], &mut to[..n]);
            assert_eq!(to[..n], from[..n], "{n} values");
            assert!(to[n..].iter().all(|x| x.is_nan()), "{n} values");
        }
    }

    /// The test on the bits agrees with the range's on zeros of either sign, the bounds and
    /// their neighbours, subnormals, the infinities and NaNs of either sign.
    #[test]
    fn luminance_test_on_bits_matches_the_range() {
        let max = MAX_EXITANCE;
        let above = f32::from_bits(max.to_bits() + 1);
        let below = f32::from_bits(max.to_bits() - 1);
        let values = [
            0.0,
            -0.0,
            f32::from_bits(1),
            -f32::from_bits(1),
            f32::MIN_POSITIVE,
            1.0,
            -1.0,
            below,
            max,
            above,
            -max,
            f32::MAX,
            f32::INFINITY,
            f32::NEG_INFINITY,
            f32::NAN,
            -f32::NAN,
        ];
        for x in values {
            let range = (0.0..=max).contains(&x);
            assert_eq!(valid_bits(x), range, "{x:e} ({:#010x})", x.to_bits());
        }
    }
}
