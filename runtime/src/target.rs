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
//!
//! [`Error::BoundUnmet`]: crate::Error::BoundUnmet
//! [`Error::PivotLimit`]: crate::Error::PivotLimit
//! [`Error::Capacity`]: crate::Error::Capacity

// The parts, lowest first, each importing only parts before it: `limits` (capacities and
// the tolerance), `bound` (one bound as a row), `simplex` (the solver on those rows),
// `outputs` (a basis' readings as bounds), `problem` (the bounds a controller adds, solved
// by the simplex).
mod bound;
mod limits;
mod outputs;
mod problem;
mod simplex;

pub use limits::{FEASIBILITY, MAX_BOUNDS, MAX_CONTROLS, MAX_PIVOTS, MAX_VALUE};
pub use outputs::{output_gains, Output};
pub use problem::{LevelProblem, Solution};
