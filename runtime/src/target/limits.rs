//! The capacities of a [`LevelProblem`](super::LevelProblem) and the tolerance of its
//! verdict.

/// Most controlled channels a [`LevelProblem`](super::LevelProblem) holds.
pub const MAX_CONTROLS: usize = 16;
/// Most bounds a [`LevelProblem`](super::LevelProblem) holds.
pub const MAX_BOUNDS: usize = 16;
/// Most pivots and bound flips one [`LevelProblem::solve`](super::LevelProblem::solve)
/// makes, both phases together.
pub const MAX_PIVOTS: u32 = 1000;
/// Largest magnitude accepted for a gain, an ambient reading or a bound (the reading's
/// unit), and for a power weight.
pub const MAX_VALUE: f32 = 1.0e9;
/// A bound counts as met when its violation is at most this fraction of its row's scale
/// (the largest of its gains and `|lower − ambient|`).
pub const FEASIBILITY: f32 = 2.0e-6;
