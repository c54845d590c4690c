//! What the partition makes of a scene before any entry is read (`eigenrad-bench partition`).

use serde::Serialize;

use super::tree::Kind;
use super::{partitioned, Hierarchical, Occlusion, Settings};
use crate::geometry::Patch;

/// How the block partition of a scene divides the `n²` entries of `S`, before any entry is
/// read: what assembly will read whole and why (`eigenrad-bench partition`). Shares count
/// both halves of each off-diagonal block (dimensionless, of `n²`).
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct Census {
    /// Patches.
    pub patches: usize,
    /// Blocks of the partition.
    pub blocks: usize,
    /// Entries in blocks of clusters too close to be admissible: read whole.
    pub near: f64,
    /// Entries of admissible pairs that a blocker may cut (the `tree` module's mixed pairs), split down
    /// to blocks read whole.
    pub mixed_whole: f64,
    /// Entries of the same mixed pairs that the split brought into admissible blocks again
    /// (clear or dark once split).
    pub mixed_compressed: f64,
    /// Entries in clear admissible blocks (to the cross approximation).
    pub far: f64,
    /// Entries in dark blocks (0, unread).
    pub dark: f64,
    /// Entries in shaded blocks ([`Settings::shade_mixed`]).
    pub shaded: f64,
    /// Mixed admissible pairs where the split starts.
    pub mixed_pairs: usize,
    /// Blocks read whole under them.
    pub mixed_blocks_whole: usize,
    /// Wall seconds the tree and the partition took (the sight tests).
    pub seconds: f64,
}

impl Hierarchical {
    /// The [`Census`] of the partition `assemble` would use on `patches`.
    pub(in crate::formfactor) fn census(
        patches: &[Patch],
        settings: &Settings,
        occlusion: Option<&Occlusion>,
    ) -> Census {
        let clock = std::time::Instant::now();
        let (_, spans, _) = partitioned(patches, settings, occlusion);
        let seconds = clock.elapsed().as_secs_f64();
        let n2 = (patches.len() * patches.len()).max(1) as f64;
        let mut census = Census {
            patches: patches.len(),
            blocks: spans.len(),
            seconds,
            ..Census::default()
        };
        let mut tops = std::collections::BTreeSet::new();
        for span in &spans {
            let entries = (span.rows.len() * span.cols.len()) as f64
                * if span.is_diagonal() { 1.0 } else { 2.0 }
                / n2;
            match (span.kind, span.split_from) {
                (Kind::Near, None) => census.near += entries,
                (Kind::Near, Some(top)) => {
                    census.mixed_whole += entries;
                    census.mixed_blocks_whole += 1;
                    tops.insert(top);
                }
                (Kind::Far | Kind::Clear | Kind::Dark | Kind::Shaded, Some(top)) => {
                    census.mixed_compressed += entries;
                    tops.insert(top);
                }
                (Kind::Far | Kind::Clear, None) => census.far += entries,
                (Kind::Dark, None) => census.dark += entries,
                (Kind::Shaded, None) => census.shaded += entries,
            }
        }
        census.mixed_pairs = tops.len();
        census
    }
}
