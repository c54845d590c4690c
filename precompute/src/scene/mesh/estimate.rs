//! Counting the patches a face will make before meshing it, for the memory check.

use super::cut::cut;
use super::ASPECT_BOUND;
use crate::geometry::{aspect, narrowest, Vec3};

/// Up to how many cells of a grid over its narrowest rectangle [`estimate`] counts a
/// polygon's or sliver's pieces by cutting it (a few milliseconds); beyond, the grid is the
/// estimate.
const EXACT_UP_TO: f64 = 1e5;

/// How many patches [`mesh_face`](super::mesh_face) would make of a face, without making
/// them (f64, so that an absurd count is a number rather than an overflow); exact unless a
/// polygon or sliver would have more than about [`EXACT_UP_TO`] pieces.
pub(crate) fn estimate(corners: &[Vec3], max_edge: f64) -> f64 {
    // As `parts` does, so that a side of exactly k × max_edge counts k.
    let count = |length: f64| (length / max_edge * (1.0 - 1e-12)).ceil().max(1.0);
    let triangle = |a: Vec3, b: Vec3, c: Vec3| {
        let m = count((b - a).length().max((c - b).length()).max((a - c).length()));
        m * m
    };
    match corners {
        [a, b, c, d] => {
            count((*b - *a).length().max((*c - *d).length()))
                * count((*d - *a).length().max((*c - *b).length()))
        }
        [_, _, _] if aspect(corners) <= ASPECT_BOUND => {
            triangle(corners[0], corners[1], corners[2])
        }
        // What [`cut`] makes: counted by cutting, unless a grid over the narrowest rectangle
        // already has more than EXACT_UP_TO cells (the count is then that grid, more or less
        // the pieces cut off along a slanted or curved boundary).
        _ => narrowest(corners).map_or(1.0, |r| {
            let grid = count(r.length) * count(r.width);
            if grid > EXACT_UP_TO {
                return grid;
            }
            let mut out = Vec::new();
            cut(corners.to_vec(), max_edge, 0, &mut out);
            out.len() as f64
        }),
    }
}

#[cfg(test)]
mod tests {
    use super::super::fixtures::{faces, regular};
    use super::super::mesh_face;
    use super::*;

    #[test]
    fn scene_mesh_estimate_is_the_count() {
        for (name, face) in faces() {
            for max_edge in [5.0, 0.4, 0.25, 0.1] {
                let mut out = Vec::new();
                mesh_face(&face, max_edge, &mut out);
                assert_eq!(
                    estimate(&face, max_edge),
                    out.len() as f64,
                    "{name} at {max_edge}"
                );
            }
        }
        // An absurd edge is a number, not a meshing.
        let e = estimate(&regular(7, 100.0), 1e-6);
        assert!(e > 1e15 && e.is_finite(), "{e}");
    }
}
