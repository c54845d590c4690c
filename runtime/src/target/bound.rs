//! One bound of a level problem: its gains, ambient and bounds, its reading at given levels
//! and the scale its row is divided by; what both the problem and the simplex read.

use super::limits::MAX_CONTROLS;

/// One bound: `lower ≤ ambient + Σ gains·levels ≤ upper`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct Bound {
    pub(super) gains: [f32; MAX_CONTROLS],
    pub(super) ambient: f32,
    pub(super) lower: f32,
    pub(super) upper: f32,
}

/// `ambient + Σ gains·levels`, in the order of the channels.
pub(super) fn reading(b: &Bound, levels: &[f32]) -> f32 {
    let mut r = b.ambient;
    for (&g, &l) in b.gains.iter().zip(levels) {
        r += g * l;
    }
    r
}

/// The scale row `b` is divided by: its largest gain or `|lower − ambient|`, at least
/// 10⁻⁶ (a row of zeros stays as it is).
pub(super) fn row_scale(b: &Bound, m: usize) -> f32 {
    let mut s = (b.lower - b.ambient).abs();
    for &g in b.gains.get(..m).unwrap_or(&[]) {
        s = s.max(g.abs());
    }
    s.max(1.0e-6)
}
