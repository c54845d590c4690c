//! Patch exitance under daylight with its first reflection exact (docs/math.md, "Daylight's
//! first reflection"; docs/format.md, "First reflection"): the sky's part from its stored
//! low-rank factors, the sun's from each node's list of the patches it reaches, and only the
//! light reflected after that through the modes.
//!
//! A sky update forms the `r` coefficients of the sky's first reflection (`r × (S_k + 1)`
//! products) and the `p` mode amplitudes from them and the four sun nodes (`p × (r + 4)`),
//! both eight or six rows at a time ([`super::weights`]), and finds the four nodes' runs of the
//! lists from first entries kept when the evaluator is made ([`SunLists`]); a patch read is its row of the sky's matrix (`r`), the four nodes' entries for it (a
//! bisection each) and its mode row (`p`).

use super::weights::{add_column, dots, SunWeight, Weights, NO_SUN};
use crate::basis::Basis;
use crate::storage::{f32_at, u32_at};

/// First entries an evaluator keeps of the sun nodes' lists: of every `stride`-th node, so
/// that finding a node's place sums at most `stride − 1` counts, where summing from the
/// first node would sum up to all of them (164 for the daylight office) four times a sky
/// update.
const CHECKPOINTS: usize = 16;

/// Where the sun nodes' first reflections lie in the basis' lists (docs/format.md, "First
/// reflection": each node's patches follow the previous node's, `sun_reflection_counts`
/// giving how many): a node's first entry every `stride` nodes, found once when the
/// evaluator is made, and the four nodes of the current sun's runs.
#[derive(Clone, Copy, Debug)]
pub(super) struct SunLists {
    /// The first entry of nodes `0, stride, 2·stride, …`.
    checkpoints: [u32; CHECKPOINTS],
    /// Nodes from one checkpoint to the next (at least 1).
    stride: u32,
    /// The four sun nodes' runs of the lists: first entry and count (none: `(0, 0)`).
    runs: [(u32, u32); 4],
}

impl SunLists {
    /// The checkpoints of `basis`' lists (none without a first reflection), no sun.
    pub(super) fn new(basis: &Basis<'_>) -> Self {
        let counts = basis.tables.sun_reflection_counts;
        let nodes = basis.counts.sun_node_count;
        let stride = nodes.div_ceil(CHECKPOINTS).max(1);
        let mut checkpoints = [0u32; CHECKPOINTS];
        let mut first = 0u32;
        // At most `CHECKPOINTS` chunks of `stride` nodes; the counts' sum fits in `u32`
        // (checked with the daylight section: at most the payload's length over 4).
        for (slot, chunk) in checkpoints.iter_mut().zip(counts.chunks(4 * stride)) {
            *slot = first;
            first = first.saturating_add(sum_u32(chunk));
        }
        SunLists {
            checkpoints,
            stride: u32::try_from(stride).unwrap_or(u32::MAX),
            runs: [(0, 0); 4],
        }
    }

    /// The first entry of stored sun node `node`'s list, and its count.
    fn run(&self, counts: &[u8], node: usize) -> (u32, u32) {
        let stride = self.stride as usize;
        let checkpoint = node / stride;
        let from = checkpoint * stride;
        let before = counts.get(4 * from..4 * node).map_or(0, sum_u32);
        let start = self.checkpoints.get(checkpoint).copied().unwrap_or(0);
        (start.saturating_add(before), u32_at(counts, node))
    }
}

/// The sum of the little-endian `u32` values of `bytes`, saturating.
fn sum_u32(bytes: &[u8]) -> u32 {
    bytes
        .as_chunks::<4>()
        .0
        .iter()
        .fold(0u32, |sum, &c| sum.saturating_add(u32::from_le_bytes(c)))
}

/// Fills `state` (`p` mode amplitudes, then the `r` coefficients of the sky's first
/// reflection) for the moment `drive`, and `lists` with the four sun nodes' runs of the
/// lists. `r` is the basis' rank: `Some` when it stores a first reflection. Nothing to do
/// when `state` is empty (an evaluator without patch exitance).
pub(super) fn update(
    basis: &Basis<'_>,
    rank: usize,
    drive: &Weights<'_>,
    state: &mut [f32],
    lists: &mut SunLists,
) {
    if state.is_empty() {
        return;
    }
    let p = basis.counts.mode_count;
    let (amplitudes, coefficients) = state.split_at_mut(p.min(state.len()));
    let sky = drive.sky.len();
    // The coefficients' rows are the outputs' without the sun: the sky, then the exterior.
    let sky_weights = Weights {
        sun: &NO_SUN,
        ..*drive
    };
    sky_weights.table(basis.tables.sky_reflection_weights, sky + 1, coefficients);
    let first_sun = sky + 1;
    // The four nodes' places among the stored sun nodes; none for a node that lights
    // nothing.
    let sun_nodes = basis.counts.sun_node_count;
    let nodes = drive.sun.map(|(column, weight)| {
        let node = (column as usize)
            .checked_sub(first_sun)
            .filter(|&node| node < sun_nodes);
        (node, weight)
    });
    let modes = basis.tables.daylight_modes;
    let columns = rank + sun_nodes;
    dots(modes, columns, coefficients, amplitudes);
    // Each amplitude adds its nodes' terms in their order (the nodes that light nothing left
    // out first), a node at a time down the amplitudes.
    let mut sun = [(0usize, 0.0f32); 4];
    let mut lit = 0;
    for &(node, weight) in &nodes {
        if let (Some(node), Some(slot)) = (node, sun.get_mut(lit)) {
            *slot = (rank + node, weight);
            lit += 1;
        }
    }
    for &(column, weight) in sun.get(..lit).unwrap_or(&[]) {
        add_column(modes, columns, column, weight, amplitudes);
    }
    let counts = basis.tables.sun_reflection_counts;
    lists.runs = nodes.map(|(node, _)| node.map_or((0, 0), |node| lists.run(counts, node)));
}

/// The first reflection of `patch` (lux) for the coefficients `coefficients` and the four
/// sun nodes `sun` whose runs of the lists are `lists`.
pub(super) fn first_reflection(
    basis: &Basis<'_>,
    patch: usize,
    coefficients: &[f32],
    sun: &[SunWeight; 4],
    lists: &SunLists,
) -> f32 {
    let mut sum = basis.sky_reflection().row_dot(patch, 0, coefficients);
    let patches = basis.tables.sun_reflection_patches;
    for (&(_, weight), &(start, count)) in sun.iter().zip(&lists.runs) {
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
