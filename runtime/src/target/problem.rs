//! The problem a controller states: controlled channels with power weights, bounds on
//! readings; and its solution, the levels and the verdict on every bound.

use super::bound::{reading, row_scale, Bound};
use super::limits::{FEASIBILITY, MAX_BOUNDS, MAX_CONTROLS, MAX_VALUE};
use super::outputs::{output_gains, Output};
use super::simplex::Tableau;
use crate::basis::{check_index, Basis};
use crate::error::{Error, Result};

/// What [`LevelProblem::solve`] reports with the levels when every bound is met.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Solution {
    /// `Σᵢ wᵢ·levelᵢ`, in the unit of the weights (W when they are watts at level 1).
    pub power: f32,
    /// Pivots and bound flips made, both phases (at most [`MAX_PIVOTS`](super::MAX_PIVOTS)).
    pub pivots: u32,
}

/// The least-power channel levels problem: controlled channels with power weights, and
/// bounds on readings. See the [module documentation](super).
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
        let mut t = Tableau::new(&self.weights, &self.bounds);
        let outcome = t.run(&self.weights, &self.bounds);
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
