//! The daylight's first reflection (`docs/format.md`, "First reflection"), part of the
//! daylight section since format version 7: its tables' lengths and values, checked where
//! daylight is used (every table empty without a rank is checked at decode, with the
//! daylight section's shape).

use super::daylight::total;
use super::tables::{bad_value, check_len, cols, f32_table, matrix, mul, u32_sum, Allowed};
use crate::error::Result;
use crate::format::{Counts, Payload, Precision};
use crate::storage::u32_at;

/// Bytes of the tables the counts size: the rank, the sky's weights and matrix, the sun
/// nodes' counts (not the lists, which their counts size).
pub(super) fn sized_bytes(raw: &Payload<'_>) -> usize {
    raw.sky_reflection_weights.len()
        + raw.sky_reflection.scales.len()
        + raw.sky_reflection.data.len()
        + raw.sun_reflection_counts.len()
}

/// The tables, where daylight is used: each of the length its rank and counts give it
/// (named), a rank no larger than the matrix it factors
/// (`min(n, S_k + 1)`), the weights and the sky's matrix finite and bounded, each sun node's
/// patches ascending below `n` and their values finite and bounded. Every table empty
/// without a rank.
pub(super) fn check(raw: &Payload<'_>, c: &Counts, precision: Precision) -> Result<()> {
    let Some(rank) = c.reflection_rank else {
        let found = sized_bytes(raw) + raw.sun_reflection_patches.len() + raw.sun_reflection.len();
        return total("reflection", 0, found);
    };
    let sky = cols(c.sky_reflection_cols())?;
    if rank > c.patch_count.min(sky) {
        return Err(bad_value("reflection_rank", 0));
    }
    f32_table(
        "sky_reflection_weights",
        raw.sky_reflection_weights,
        mul(rank, sky)?,
        Allowed::Bounded,
    )?;
    matrix(
        "sky_reflection.data",
        "sky_reflection.scales",
        raw.sky_reflection,
        precision,
        c.patch_count,
        rank,
    )?;
    let listed = u32_sum(
        "sun_reflection_counts",
        raw.sun_reflection_counts,
        c.sun_node_count,
    )?;
    check_len(
        "sun_reflection_patches",
        raw.sun_reflection_patches,
        listed,
        4,
    )?;
    let mut first = 0usize;
    for node in 0..c.sun_node_count {
        let count = u32_at(raw.sun_reflection_counts, node) as usize;
        let mut previous: Option<u32> = None;
        for k in first..first + count {
            let patch = u32_at(raw.sun_reflection_patches, k);
            if patch as usize >= c.patch_count || previous.is_some_and(|p| p >= patch) {
                return Err(bad_value("sun_reflection_patches", k));
            }
            previous = Some(patch);
        }
        first += count;
    }
    f32_table(
        "sun_reflection",
        raw.sun_reflection,
        listed,
        Allowed::Bounded,
    )
}
