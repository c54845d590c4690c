//! Channel levels for a target: the levels in [0, 1] that keep every chosen reading between
//! its bounds at the least total power, found on the controller.
//!
//! A [`LevelProblem`] holds up to [`MAX_CONTROLS`] controlled channels, each with a power
//! weight `wᵢ` (W at level 1, or any unit as long as it is the same for all), and up to
//! [`MAX_BOUNDS`] bounds. Bound `j` is on a reading that depends linearly on the levels:
//!
//! ```text
//! reading_j = ambient_j + Σᵢ gain_ji · levelᵢ,     lower_j ≤ reading_j ≤ upper_j
//! ```
//!
//! with the gains the reading per channel at level 1 (for a basis, the stored exact
//! `output_channels`: [`output_gains`]) and `ambient_j` the light not due to the controlled
//! channels (daylight, a channel the controller does not dim, patch exitance). The caller
//! passes it, or reads it from an evaluator with
//! [`ChannelEvaluator::reading_without`](crate::ChannelEvaluator::reading_without) /
//! [`Evaluator::reading_without`](crate::Evaluator::reading_without). Readings and bounds
//! are in the basis' unit: lux in a photopic basis.
//!
//! [`LevelProblem::solve`] minimises `Σᵢ wᵢ·levelᵢ` over `0 ≤ levelᵢ ≤ 1` and the bounds.
//! When no levels meet every bound it writes the levels that come closest — the least total
//! violation `Σⱼ (shortfall below lower_j + excess above upper_j)`, in lux, and among those
//! the least power — and returns [`Error::BoundUnmet`] naming the bound violated the most
//! and by how much.
//!
//! # The algorithm
//!
//! A dense bounded-variable primal simplex in `f32` with Bland's rule, in two phases.
//! Each bound is a row `Σᵢ gᵢ·xᵢ − t − p + q = lower − ambient`, scaled to entries of at
//! most 1, with `t ∈ [0, upper − lower]` the reading above its lower bound, `p ≥ 0` the
//! excess above the upper bound (fixed at 0 when there is none) and `q ≥ 0` the shortfall
//! below the lower bound. With every level at 0, `p` or `q` (or `t`) of each row is a
//! feasible starting basis. Phase 1 minimises the total violation `Σ (p + q)` in lux. If it
//! is zero (within [`FEASIBILITY`] of each row's scale), every `p` and `q` is fixed at 0;
//! otherwise every non-basic variable with a non-zero phase-1 reduced cost is fixed where it
//! is, which keeps the total violation at its minimum (complementary slackness: those are the
//! variables that cannot move on the optimal face). Phase 2 then minimises the power from
//! that basis. The tableau is kept as `B⁻¹G` (bounds × channels) and `B⁻¹` (bounds ×
//! bounds): the columns of `t`, `p` and `q` are ± the columns of `B⁻¹`. After each phase
//! the basic values are refined twice against the original rows (`β += B⁻¹ (b − A x)`), so
//! rounding does not accumulate in them from one pivot to the next. Tableau entries below
//! 10⁻⁵ are never pivots: in `f32` they are the rounding residue of entries that are 0 (two
//! bounds on one reading make such entries), and dividing by them would wreck `B⁻¹`. The
//! verdict (met, or which bound fails) is taken from the final levels against the original
//! bounds, each within [`FEASIBILITY`] of its row's scale.
//!
//! **Termination.** Bland's rule (enter the lowest-indexed improving variable, and among
//! tied ratios leave the lowest-indexed one) never revisits a basis in exact arithmetic
//! (Bland 1977; a variable at its upper bound is its complement at a lower bound, to which
//! the same argument applies), and there are finitely many bases and bound states, so each
//! phase ends. Rounding in `f32` voids the proof, so every solve also stops after
//! [`MAX_PIVOTS`] pivots and bound flips in all with [`Error::PivotLimit`]. The random tests
//! (`tests/levels.rs`) take at most 75 pivots at the full 16 × 16 size.
//!
//! Only one-band bases: a reading is one number. [`output_gains`] refuses a three-band
//! basis with [`Error::Capacity`] (`"bands"`).

use crate::basis::{check_index, Basis};
use crate::error::{Error, Result};
use crate::eval::{ChannelEvaluator, Evaluator};
use crate::storage::f32_at;

/// Most controlled channels a [`LevelProblem`] holds.
pub const MAX_CONTROLS: usize = 16;
/// Most bounds a [`LevelProblem`] holds.
pub const MAX_BOUNDS: usize = 16;
/// Most pivots and bound flips one [`LevelProblem::solve`] makes, both phases together.
pub const MAX_PIVOTS: u32 = 1000;
/// Largest magnitude accepted for a gain, an ambient reading or a bound (the reading's
/// unit), and for a power weight.
pub const MAX_VALUE: f32 = 1.0e9;
/// A bound counts as met when its violation is at most this fraction of its row's scale
/// (the largest of its gains and `|lower − ambient|`).
pub const FEASIBILITY: f32 = 2.0e-6;

/// A tableau entry at most this in magnitude is not used as a pivot (rows are scaled to
/// entries of at most 1).
const PIVOT_TOL: f32 = 1.0e-5;
/// A reduced cost at most this in magnitude counts as zero (costs are scaled to at most 1).
const COST_TOL: f32 = 1.0e-6;
/// Columns: the levels, then `t`, `p` and `q` of every bound.
const COLUMNS: usize = MAX_CONTROLS + 3 * MAX_BOUNDS;

/// A reading of a basis a bound applies to.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Output {
    /// Sensor `index` (in the basis' order).
    Sensor(usize),
    /// Zone `index` (area average).
    Zone(usize),
}

impl Output {
    /// Row of `output_channels` (sensors first, then zones), checked against the basis.
    fn row(self, basis: &Basis<'_>) -> Result<usize> {
        let counts = &basis.counts;
        match self {
            Output::Sensor(s) => {
                check_index("sensor", s, counts.sensor_count)?;
                Ok(s)
            }
            Output::Zone(z) => {
                check_index("zone", z, counts.zone_count)?;
                Ok(counts.sensor_count + z)
            }
        }
    }
}

/// Fills `gains[k]` with the reading of `output` (lux in a photopic basis) per unit level of
/// basis channel `channels[k]`: the stored exact response `output_channels`. A three-band
/// basis is refused with [`Error::Capacity`] (`"bands"`, capacity 1).
pub fn output_gains(
    basis: &Basis<'_>,
    output: Output,
    channels: &[usize],
    gains: &mut [f32],
) -> Result<()> {
    if basis.bands() != 1 {
        return Err(Error::Capacity {
            what: "bands",
            needed: basis.bands(),
            capacity: 1,
        });
    }
    if gains.len() != channels.len() {
        return Err(Error::LengthMismatch {
            what: "gains",
            expected: channels.len(),
            found: gains.len(),
        });
    }
    let row = output.row(basis)?;
    let m = basis.counts.channel_count;
    for &c in channels {
        check_index("channel", c, m)?;
    }
    for (slot, &c) in gains.iter_mut().zip(channels) {
        *slot = f32_at(basis.tables.output_channels, row * m + c);
    }
    Ok(())
}

/// The reading of `output` less what `channels` contribute at their current levels: the
/// light the controlled channels do not give. `reading(eval) − Σ level_c · gain_c`.
fn without(
    basis: &Basis<'_>,
    output: Output,
    channels: &[usize],
    reading: f32,
    level: impl Fn(usize) -> Result<f32>,
) -> Result<f32> {
    let mut gains = [0.0f32; MAX_CONTROLS];
    let gains = gains.get_mut(..channels.len()).ok_or(Error::Capacity {
        what: "controlled channels",
        needed: channels.len(),
        capacity: MAX_CONTROLS,
    })?;
    output_gains(basis, output, channels, gains)?;
    let mut own = 0.0f32;
    for (&g, &c) in gains.iter().zip(channels) {
        own += g * level(c)?;
    }
    Ok(reading - own)
}

impl<const CHANNELS: usize> ChannelEvaluator<'_, 1, CHANNELS> {
    /// The current reading of `output` less the part `channels` give at their current levels
    /// (lux in a photopic basis): the ambient of a [`LevelProblem`] bound whose controlled
    /// channels are `channels`. Channels not listed (a window channel, say) count as
    /// ambient.
    pub fn reading_without(&self, output: Output, channels: &[usize]) -> Result<f32> {
        let basis = self.basis();
        let [reading] = match output {
            Output::Sensor(s) => self.sensor_irradiance(s)?,
            Output::Zone(z) => self.zone_irradiance(z)?,
        };
        without(basis, output, channels, reading, |c| self.channel_level(c))
    }
}

impl<const N: usize, const P: usize, const CHANNELS: usize, const O: usize>
    Evaluator<'_, 1, N, P, CHANNELS, O>
{
    /// The current reading of `output`, patch exitance included, less the part `channels`
    /// give at their current levels (lux in a photopic basis): the ambient of a
    /// [`LevelProblem`] bound whose controlled channels are `channels`.
    pub fn reading_without(&self, output: Output, channels: &[usize]) -> Result<f32> {
        let basis = self.basis();
        let [reading] = match output {
            Output::Sensor(s) => self.sensor_irradiance(s)?,
            Output::Zone(z) => self.zone_irradiance(z)?,
        };
        without(basis, output, channels, reading, |c| self.channel_level(c))
    }
}

/// One bound: `lower ≤ ambient + Σ gains·levels ≤ upper`.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Bound {
    gains: [f32; MAX_CONTROLS],
    ambient: f32,
    lower: f32,
    upper: f32,
}

/// What [`LevelProblem::solve`] reports with the levels when every bound is met.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Solution {
    /// `Σᵢ wᵢ·levelᵢ`, in the unit of the weights (W when they are watts at level 1).
    pub power: f32,
    /// Pivots and bound flips made, both phases (at most [`MAX_PIVOTS`]).
    pub pivots: u32,
}

/// The least-power channel levels problem: controlled channels with power weights, and
/// bounds on readings. See the [module documentation](self).
///
/// Fixed size: `size_of` is about 1.3 KiB (16 bounds of 16 gains), and
/// [`solve`](Self::solve) keeps a tableau of about 3.5 KiB on the stack. Nothing allocates;
/// no input panics.
#[derive(Clone, Debug)]
pub struct LevelProblem {
    weights: heapless::Vec<f32, MAX_CONTROLS>,
    bounds: heapless::Vec<Bound, MAX_BOUNDS>,
}

fn check_value(what: &'static str, v: f32) -> Result<()> {
    if v.is_finite() && v.abs() <= MAX_VALUE {
        Ok(())
    } else {
        Err(Error::InvalidInput { what })
    }
}

impl LevelProblem {
    /// A problem on `weights.len()` controlled channels (at most [`MAX_CONTROLS`]), channel
    /// `i` costing `weights[i]` at level 1 (W, or any unit common to all; finite, at least
    /// 0 and at most [`MAX_VALUE`]). No bounds yet.
    pub fn new(weights: &[f32]) -> Result<Self> {
        let mut w = heapless::Vec::new();
        for &x in weights {
            if !(x.is_finite() && (0.0..=MAX_VALUE).contains(&x)) {
                return Err(Error::InvalidInput { what: "weight" });
            }
            w.push(x).map_err(|_| Error::Capacity {
                what: "controlled channels",
                needed: weights.len(),
                capacity: MAX_CONTROLS,
            })?;
        }
        Ok(LevelProblem {
            weights: w,
            bounds: heapless::Vec::new(),
        })
    }

    /// Controlled channels.
    pub fn channel_count(&self) -> usize {
        self.weights.len()
    }

    /// Bounds added so far.
    pub fn bound_count(&self) -> usize {
        self.bounds.len()
    }

    /// Removes every bound, keeping the channels and weights.
    pub fn clear_bounds(&mut self) {
        self.bounds.clear();
    }

    /// Adds the bound `lower ≤ ambient + Σᵢ gains[i]·levelᵢ ≤ upper` and returns its index
    /// (the `bound` of [`Error::BoundUnmet`]). `gains` has one entry per controlled channel;
    /// gains, `ambient` and `lower` are finite and at most [`MAX_VALUE`] in magnitude;
    /// `upper` is too, or `f32::INFINITY` for no upper bound, and `lower ≤ upper`. Use
    /// `lower = 0` (or below the ambient) for an upper bound alone.
    ///
    /// Errors: [`Error::LengthMismatch`], [`Error::InvalidInput`] (`"gain"`, `"ambient"`,
    /// `"lower"`, `"upper"`), [`Error::InvalidBound`] (lower above upper),
    /// [`Error::Capacity`] (`"bounds"`); the problem is unchanged then.
    pub fn add_bound(
        &mut self,
        gains: &[f32],
        ambient: f32,
        lower: f32,
        upper: f32,
    ) -> Result<usize> {
        let m = self.weights.len();
        if gains.len() != m {
            return Err(Error::LengthMismatch {
                what: "gains",
                expected: m,
                found: gains.len(),
            });
        }
        for &g in gains {
            check_value("gain", g)?;
        }
        check_value("ambient", ambient)?;
        check_value("lower", lower)?;
        if !(upper == f32::INFINITY || check_value("upper", upper).is_ok()) {
            return Err(Error::InvalidInput { what: "upper" });
        }
        let index = self.bounds.len();
        if lower > upper {
            return Err(Error::InvalidBound { bound: index });
        }
        let mut bound = Bound {
            gains: [0.0; MAX_CONTROLS],
            ambient,
            lower,
            upper,
        };
        for (slot, &g) in bound.gains.iter_mut().zip(gains) {
            *slot = g;
        }
        self.bounds.push(bound).map_err(|_| Error::Capacity {
            what: "bounds",
            needed: index + 1,
            capacity: MAX_BOUNDS,
        })?;
        Ok(index)
    }

    /// Adds a bound on `output` of `basis`, with the gains of basis channels `channels` (the
    /// controlled channels in order: one per weight) read by [`output_gains`]. Lux in a
    /// photopic basis.
    pub fn add_output_bound(
        &mut self,
        basis: &Basis<'_>,
        channels: &[usize],
        output: Output,
        ambient: f32,
        lower: f32,
        upper: f32,
    ) -> Result<usize> {
        let mut gains = [0.0f32; MAX_CONTROLS];
        let gains = gains.get_mut(..channels.len()).ok_or(Error::Capacity {
            what: "controlled channels",
            needed: channels.len(),
            capacity: MAX_CONTROLS,
        })?;
        output_gains(basis, output, channels, gains)?;
        self.add_bound(gains, ambient, lower, upper)
    }

    /// The reading of bound `bound` at `levels`: `ambient + Σ gains·levels`.
    pub fn reading(&self, bound: usize, levels: &[f32]) -> Result<f32> {
        check_index("bound", bound, self.bounds.len())?;
        if levels.len() != self.weights.len() {
            return Err(Error::LengthMismatch {
                what: "levels",
                expected: self.weights.len(),
                found: levels.len(),
            });
        }
        Ok(self.bounds.get(bound).map_or(0.0, |b| reading(b, levels)))
    }

    /// `Σᵢ wᵢ·levelᵢ` (the weights' unit).
    pub fn power(&self, levels: &[f32]) -> Result<f32> {
        if levels.len() != self.weights.len() {
            return Err(Error::LengthMismatch {
                what: "levels",
                expected: self.weights.len(),
                found: levels.len(),
            });
        }
        Ok(self.weights.iter().zip(levels).map(|(w, l)| w * l).sum())
    }

    /// Writes into `levels` (one per controlled channel, each in [0, 1]) the least-power
    /// levels that meet every bound, and returns their power and pivot count.
    ///
    /// When no levels meet every bound, `levels` gets those with the least total violation
    /// (lux; then the least power) and the result is [`Error::BoundUnmet`] with the bound
    /// violated the most. [`Error::LengthMismatch`] leaves `levels` unchanged;
    /// [`Error::PivotLimit`] (not expected: see the module documentation) leaves the levels
    /// of the last basis reached.
    pub fn solve(&self, levels: &mut [f32]) -> Result<Solution> {
        let m = self.weights.len();
        if levels.len() != m {
            return Err(Error::LengthMismatch {
                what: "levels",
                expected: m,
                found: levels.len(),
            });
        }
        let mut t = Tableau::new(self);
        let outcome = t.run(self);
        t.levels(levels);
        let pivots = outcome?;
        // The verdict comes from the levels themselves, against the original data.
        let mut worst: Option<(usize, bool, f32, f32)> = None;
        for (j, b) in self.bounds.iter().enumerate() {
            let r = reading(b, levels);
            let (upper, by) = if r < b.lower {
                (false, b.lower - r)
            } else if r > b.upper {
                (true, r - b.upper)
            } else {
                continue;
            };
            let tol = FEASIBILITY * row_scale(b, m);
            if by > tol && worst.is_none_or(|(.., w, _)| by > w) {
                worst = Some((j, upper, by, tol));
            }
        }
        if let Some((bound, upper, by, _)) = worst {
            return Err(Error::BoundUnmet { bound, upper, by });
        }
        Ok(Solution {
            power: self.power(levels).unwrap_or(0.0),
            pivots,
        })
    }
}

/// `ambient + Σ gains·levels`, in the order of the channels.
fn reading(b: &Bound, levels: &[f32]) -> f32 {
    let mut r = b.ambient;
    for (&g, &l) in b.gains.iter().zip(levels) {
        r += g * l;
    }
    r
}

/// The scale row `b` is divided by: its largest gain or `|lower − ambient|`, at least
/// 10⁻⁶ (a row of zeros stays as it is).
fn row_scale(b: &Bound, m: usize) -> f32 {
    let mut s = (b.lower - b.ambient).abs();
    for &g in b.gains.get(..m).unwrap_or(&[]) {
        s = s.max(g.abs());
    }
    s.max(1.0e-6)
}

/// The state of the bounded-variable simplex. Variable `k`: level `k` for `k < m`; `t`, `p`,
/// `q` of bound `j` at `m + j`, `m + r + j`, `m + 2r + j`.
struct Tableau {
    m: usize,
    r: usize,
    /// `B⁻¹ G'` (rows scaled): one row per bound, one column per level.
    a: [[f32; MAX_CONTROLS]; MAX_BOUNDS],
    /// `B⁻¹`.
    inv: [[f32; MAX_BOUNDS]; MAX_BOUNDS],
    /// Scaled right-hand sides `(lower − ambient)/s`.
    rhs: [f32; MAX_BOUNDS],
    /// Row scales `s`.
    scale: [f32; MAX_BOUNDS],
    /// Value of each row's basic variable.
    beta: [f32; MAX_BOUNDS],
    /// Basic variable of each row.
    head: [usize; MAX_BOUNDS],
    lo: [f32; COLUMNS],
    hi: [f32; COLUMNS],
    /// A non-basic variable is at `hi` (else at `lo`).
    at_upper: [bool; COLUMNS],
    basic: [bool; COLUMNS],
    cost: [f32; COLUMNS],
    pivots: u32,
}

impl Tableau {
    fn new(problem: &LevelProblem) -> Self {
        let m = problem.weights.len();
        let r = problem.bounds.len();
        let mut t = Tableau {
            m,
            r,
            a: [[0.0; MAX_CONTROLS]; MAX_BOUNDS],
            inv: [[0.0; MAX_BOUNDS]; MAX_BOUNDS],
            rhs: [0.0; MAX_BOUNDS],
            scale: [1.0; MAX_BOUNDS],
            beta: [0.0; MAX_BOUNDS],
            head: [0; MAX_BOUNDS],
            lo: [0.0; COLUMNS],
            hi: [0.0; COLUMNS],
            at_upper: [false; COLUMNS],
            basic: [false; COLUMNS],
            cost: [0.0; COLUMNS],
            pivots: 0,
        };
        for k in 0..m {
            t.set_hi(k, 1.0);
        }
        for (j, b) in problem.bounds.iter().enumerate() {
            let s = row_scale(b, m);
            let rhs = (b.lower - b.ambient) / s;
            let range = if b.upper == f32::INFINITY {
                f32::INFINITY
            } else {
                (b.upper - b.lower) / s
            };
            let (tj, pj, qj) = (m + j, m + r + j, m + 2 * r + j);
            t.set_hi(tj, range);
            // No upper bound: nothing can exceed it.
            t.set_hi(
                pj,
                if range == f32::INFINITY {
                    0.0
                } else {
                    f32::INFINITY
                },
            );
            t.set_hi(qj, f32::INFINITY);
            // Row j: Σ g'x − t − p + q = rhs, every level at 0 and t at 0 or its range.
            let (head, sign, value) = if rhs >= 0.0 {
                (qj, 1.0, rhs)
            } else if -rhs <= range {
                (tj, -1.0, -rhs)
            } else {
                if let Some(u) = t.at_upper.get_mut(tj) {
                    *u = true;
                }
                (pj, -1.0, -rhs - range)
            };
            if let (Some(arow), Some(irow)) = (t.a.get_mut(j), t.inv.get_mut(j)) {
                for (slot, &g) in arow.iter_mut().zip(&b.gains).take(m) {
                    *slot = sign * g / s;
                }
                if let Some(d) = irow.get_mut(j) {
                    *d = sign;
                }
            }
            set(&mut t.rhs, j, rhs);
            set(&mut t.scale, j, s);
            set(&mut t.beta, j, value);
            if let Some(h) = t.head.get_mut(j) {
                *h = head;
            }
            if let Some(bflag) = t.basic.get_mut(head) {
                *bflag = true;
            }
        }
        t
    }

    fn set_hi(&mut self, k: usize, v: f32) {
        set(&mut self.hi, k, v);
    }

    fn n(&self) -> usize {
        self.m + 3 * self.r
    }

    /// Entry of variable `k`'s column in row `i` of the current tableau.
    fn entry(&self, i: usize, k: usize) -> f32 {
        let (m, r) = (self.m, self.r);
        if k < m {
            return get2(&self.a, i, k);
        }
        let f = (k - m) / r.max(1);
        let j = (k - m) % r.max(1);
        let v = get2(&self.inv, i, j);
        // t and p enter their row with −1, q with +1.
        if f == 2 {
            v
        } else {
            -v
        }
    }

    /// Value of a non-basic variable.
    fn bound_value(&self, k: usize) -> f32 {
        if get(&self.at_upper, k) {
            get(&self.hi, k)
        } else {
            get(&self.lo, k)
        }
    }

    /// Every variable's value.
    fn values(&self) -> [f32; COLUMNS] {
        let mut v = [0.0f32; COLUMNS];
        for (k, slot) in v.iter_mut().enumerate().take(self.n()) {
            *slot = self.bound_value(k);
        }
        for i in 0..self.r {
            set(&mut v, get(&self.head, i), get(&self.beta, i));
        }
        v
    }

    /// Refines the basic values against the original rows, twice: `β += B⁻¹ (rhs − A x)`.
    /// Rounding then does not accumulate in them from one pivot to the next.
    fn refresh(&mut self, problem: &LevelProblem) {
        let (m, r) = (self.m, self.r);
        for _ in 0..2 {
            let x = self.values();
            let mut residual = [0.0f32; MAX_BOUNDS];
            for (j, b) in problem.bounds.iter().enumerate().take(r) {
                let s = get(&self.scale, j);
                let mut v = get(&self.rhs, j);
                for c in 0..m {
                    v -= b.gains.get(c).copied().unwrap_or(0.0) / s * get(&x, c);
                }
                v += get(&x, m + j) + get(&x, m + r + j) - get(&x, m + 2 * r + j);
                set(&mut residual, j, v);
            }
            for i in 0..r {
                let mut v = get(&self.beta, i);
                for j in 0..r {
                    v += get2(&self.inv, i, j) * get(&residual, j);
                }
                set(&mut self.beta, i, v);
            }
        }
    }

    /// Both phases; the number of pivots and flips.
    fn run(&mut self, problem: &LevelProblem) -> Result<u32> {
        let (m, r) = (self.m, self.r);
        // Phase 1: least total violation in lux, each row's p and q counted at its scale.
        let smax = self.scale.iter().take(r).fold(0.0f32, |a, &s| a.max(s));
        for j in 0..r {
            let c = get(&self.scale, j) / smax.max(f32::MIN_POSITIVE);
            set(&mut self.cost, m + r + j, c);
            set(&mut self.cost, m + 2 * r + j, c);
        }
        self.optimise()?;
        self.refresh(problem);
        let x = self.values();
        let feasible = (0..r).all(|j| get(&x, m + r + j) + get(&x, m + 2 * r + j) <= FEASIBILITY);
        if feasible {
            for k in m + r..m + 3 * r {
                set(&mut self.hi, k, 0.0);
                set(&mut self.at_upper, k, false);
            }
        } else {
            // Fix what cannot move without raising the violation.
            let d = self.reduced_costs();
            for k in 0..self.n() {
                if !get(&self.basic, k) && get(&d, k).abs() > COST_TOL {
                    let v = self.bound_value(k);
                    set(&mut self.lo, k, v);
                    set(&mut self.hi, k, v);
                }
            }
        }
        // Phase 2: least power.
        self.cost = [0.0; COLUMNS];
        let wmax = problem.weights.iter().fold(0.0f32, |a, &w| a.max(w));
        if wmax > 0.0 {
            for (c, &w) in problem.weights.iter().enumerate() {
                set(&mut self.cost, c, w / wmax);
            }
        }
        self.optimise()?;
        self.refresh(problem);
        Ok(self.pivots)
    }

    /// `d_k = c_k − c_Bᵀ B⁻¹ A_k` for every variable.
    fn reduced_costs(&self) -> [f32; COLUMNS] {
        let (m, r) = (self.m, self.r);
        let mut pi = [0.0f32; MAX_BOUNDS];
        for j in 0..r {
            let mut v = 0.0;
            for i in 0..r {
                v += get(&self.cost, get(&self.head, i)) * get2(&self.inv, i, j);
            }
            set(&mut pi, j, v);
        }
        let mut d = [0.0f32; COLUMNS];
        for c in 0..m {
            let mut v = get(&self.cost, c);
            for i in 0..r {
                v -= get(&self.cost, get(&self.head, i)) * get2(&self.a, i, c);
            }
            set(&mut d, c, v);
        }
        for j in 0..r {
            let p = get(&pi, j);
            set(&mut d, m + j, get(&self.cost, m + j) + p);
            set(&mut d, m + r + j, get(&self.cost, m + r + j) + p);
            set(&mut d, m + 2 * r + j, get(&self.cost, m + 2 * r + j) - p);
        }
        d
    }

    /// Bland's-rule simplex on the current costs, until no variable improves.
    fn optimise(&mut self) -> Result<()> {
        while self.step()? {}
        Ok(())
    }

    /// One pivot or bound flip; `false` when no variable improves the objective.
    fn step(&mut self) -> Result<bool> {
        let (r, n) = (self.r, self.n());
        {
            let d = self.reduced_costs();
            let entering = (0..n).find(|&k| {
                let dk = get(&d, k);
                !get(&self.basic, k)
                    && get(&self.hi, k) > get(&self.lo, k)
                    && if get(&self.at_upper, k) {
                        dk > COST_TOL
                    } else {
                        dk < -COST_TOL
                    }
            });
            let Some(k) = entering else {
                return Ok(false);
            };
            if self.pivots >= MAX_PIVOTS {
                return Err(Error::PivotLimit {
                    pivots: self.pivots,
                });
            }
            self.pivots += 1;
            let dir = if get(&self.at_upper, k) { -1.0 } else { 1.0 };
            let mut col = [0.0f32; MAX_BOUNDS];
            for i in 0..r {
                set(&mut col, i, self.entry(i, k));
            }
            // Ratio test: the entering variable's own range, then each basic variable.
            let mut theta = get(&self.hi, k) - get(&self.lo, k);
            let mut leave: Option<(usize, bool)> = None;
            for i in 0..r {
                let alpha = get(&col, i) * dir;
                let b = get(&self.head, i);
                let beta = get(&self.beta, i);
                let (limit, to_upper) = if alpha > PIVOT_TOL {
                    ((beta - get(&self.lo, b)) / alpha, false)
                } else if alpha < -PIVOT_TOL && get(&self.hi, b) < f32::INFINITY {
                    ((get(&self.hi, b) - beta) / -alpha, true)
                } else {
                    continue;
                };
                let limit = limit.max(0.0);
                let better = match leave {
                    _ if limit < theta => true,
                    Some((l, _)) => limit == theta && b < get(&self.head, l),
                    None => false,
                };
                if better {
                    theta = limit;
                    leave = Some((i, to_upper));
                }
            }
            if theta == f32::INFINITY {
                // An improving ray: impossible with levels in [0, 1] and costs ≥ 0.
                return Err(Error::PivotLimit {
                    pivots: self.pivots,
                });
            }
            for i in 0..r {
                let v = get(&self.beta, i) - get(&col, i) * dir * theta;
                set(&mut self.beta, i, v);
            }
            let Some((row, to_upper)) = leave else {
                let flipped = !get(&self.at_upper, k);
                set(&mut self.at_upper, k, flipped);
                return Ok(true);
            };
            let entering_value = self.bound_value(k) + dir * theta;
            let out = get(&self.head, row);
            set(&mut self.basic, out, false);
            set(&mut self.at_upper, out, to_upper);
            set(&mut self.basic, k, true);
            set(&mut self.at_upper, k, false);
            if let Some(h) = self.head.get_mut(row) {
                *h = k;
            }
            set(&mut self.beta, row, entering_value);
            self.pivot(row, &col);
        }
        Ok(true)
    }

    /// Gauss–Jordan step on `row`, whose entry in the entering column `col` is the pivot.
    fn pivot(&mut self, row: usize, col: &[f32; MAX_BOUNDS]) {
        let (m, r) = (self.m, self.r);
        let p = get(col, row);
        if p == 0.0 {
            return;
        }
        let (mut prow_a, mut prow_inv) = (
            self.a.get(row).copied().unwrap_or([0.0; MAX_CONTROLS]),
            self.inv.get(row).copied().unwrap_or([0.0; MAX_BOUNDS]),
        );
        for v in prow_a.iter_mut().take(m) {
            *v /= p;
        }
        for v in prow_inv.iter_mut().take(r) {
            *v /= p;
        }
        for i in 0..r {
            let (Some(arow), Some(irow)) = (self.a.get_mut(i), self.inv.get_mut(i)) else {
                continue;
            };
            if i == row {
                *arow = prow_a;
                *irow = prow_inv;
                continue;
            }
            let f = get(col, i);
            if f == 0.0 {
                continue;
            }
            for (v, &pv) in arow.iter_mut().zip(&prow_a).take(m) {
                *v -= f * pv;
            }
            for (v, &pv) in irow.iter_mut().zip(&prow_inv).take(r) {
                *v -= f * pv;
            }
        }
    }

    /// The levels, clamped to [0, 1] against rounding.
    fn levels(&self, out: &mut [f32]) {
        let x = self.values();
        for (c, slot) in out.iter_mut().enumerate().take(self.m) {
            *slot = get(&x, c).clamp(0.0, 1.0);
        }
    }
}

fn get<T: Copy + Default>(v: &[T], i: usize) -> T {
    v.get(i).copied().unwrap_or_default()
}

fn get2<const C: usize>(v: &[[f32; C]], i: usize, j: usize) -> f32 {
    v.get(i).and_then(|row| row.get(j)).copied().unwrap_or(0.0)
}

fn set<T>(v: &mut [T], i: usize, x: T) {
    if let Some(slot) = v.get_mut(i) {
        *slot = x;
    }
}
