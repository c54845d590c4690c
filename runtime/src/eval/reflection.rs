//! Patch exitance under daylight with its first reflection exact (docs/math.md, "Daylight's
//! first reflection"; docs/format.md, "First reflection"): the sky's part from its stored
//! low-rank factors, the sun's from each node's list of the patches it reaches, and only the
//! light reflected after that through the modes.
//!
//! A sky update forms the `r` coefficients of the sky's first reflection (`r × (S_k + 1)`
//! products) and the `p` mode amplitudes from them and the four sun nodes (`p × (r + 4)`);
//! a patch read is its row of the sky's matrix (`r`), the four nodes' entries for it (a
//! bisection each) and its mode row (`p`).

use crate::basis::Basis;
use crate::storage::{dot_f32, f32_at, f32_row, u32_at};

/// A sun node's weight in the sky state: its column among the daylight nodes (or `u32::MAX`
/// when it lights nothing) and its bilinear weight times `E_n`, lux.
pub(super) type SunWeight = (u32, f32);

/// Where a sun node's first reflection lies in the lists: its first entry and its count.
pub(super) type SunList = (u32, u32);

/// The sky's and the sun's state of a moment, as the update reads it.
pub(super) struct Drive<'s> {
    /// Each sky patch's luminance, cd/m².
    pub sky: &'s [f32],
    /// `E_gh / π`, cd/m².
    pub exterior: f32,
    /// The four sun nodes around the sun.
    pub sun: &'s [SunWeight; 4],
}

/// Fills `state` (`p` mode amplitudes, then the `r` coefficients of the sky's first
/// reflection) for the moment `drive`, and `lists` with the four sun nodes' runs of the
/// lists. `r` is the basis' rank: `Some` when it stores a first reflection. Nothing to do
/// when `state` is empty (an evaluator without patch exitance).
pub(super) fn update(
    basis: &Basis<'_>,
    rank: usize,
    drive: &Drive<'_>,
    state: &mut [f32],
    lists: &mut [SunList; 4],
) {
    if state.is_empty() {
        return;
    }
    let p = basis.counts.mode_count;
    let (amplitudes, coefficients) = state.split_at_mut(p.min(state.len()));
    let sky = drive.sky.len();
    let weights = basis.tables.sky_reflection_weights;
    for (j, z) in coefficients.iter_mut().enumerate() {
        let row = f32_row(weights, j, sky + 1);
        *z = dot_f32(row, drive.sky) + f32_at(row, sky) * drive.exterior;
    }
    let first_sun = sky + 1;
    // A node's place among the stored sun nodes; none for a node that lights nothing.
    let sun_nodes = basis.counts.sun_node_count;
    let sun_column = |column: u32| {
        (column as usize)
            .checked_sub(first_sun)
            .filter(|&node| node < sun_nodes)
    };
    let modes = basis.tables.daylight_modes;
    let columns = rank + sun_nodes;
    for (k, a) in amplitudes.iter_mut().enumerate() {
        let row = f32_row(modes, k, columns);
        let mut sum = dot_f32(row, coefficients);
        for &(column, weight) in drive.sun {
            if let Some(node) = sun_column(column) {
                sum += f32_at(row, rank + node) * weight;
            }
        }
        *a = sum;
    }
    let counts = basis.tables.sun_reflection_counts;
    for (list, &(column, _)) in lists.iter_mut().zip(drive.sun) {
        *list = match sun_column(column) {
            Some(node) => {
                // At most the payload's length over 4: a sum that fits in `u32`.
                let start = (0..node).fold(0usize, |sum, i| {
                    sum.saturating_add(u32_at(counts, i) as usize)
                });
                (
                    u32::try_from(start).unwrap_or(u32::MAX),
                    u32_at(counts, node),
                )
            }
            None => (0, 0),
        };
    }
}

/// The first reflection of `patch` (lux) for the coefficients `coefficients` and the four
/// sun nodes `sun` whose runs of the lists are `lists`.
pub(super) fn first_reflection(
    basis: &Basis<'_>,
    patch: usize,
    coefficients: &[f32],
    sun: &[SunWeight; 4],
    lists: &[SunList; 4],
) -> f32 {
    let mut sum = basis.sky_reflection().row_dot(patch, 0, coefficients);
    let patches = basis.tables.sun_reflection_patches;
    for (&(_, weight), &(start, count)) in sun.iter().zip(lists) {
        let (start, count) = (start as usize, count as usize);
        let (mut lo, mut hi) = (start, start.saturating_add(count));
        while lo < hi {
            let mid = lo + (hi - lo) / 2;
            let listed = u32_at(patches, mid) as usize;
            if listed == patch {
                sum += f32_at(basis.tables.sun_reflection, mid) * weight;
                break;
            }
            if listed < patch {
                lo = mid + 1;
            } else {
                hi = mid;
            }
        }
    }
    sum
}
