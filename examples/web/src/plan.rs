//! The plan's colours and isolux lines, from the very source files `eigenrad render` draws
//! with: the value-to-colour map, its round scale and isolux levels
//! (`precompute/src/picture/colour.rs`) and marching squares (`contour.rs`), compiled into
//! this crate by path. One definition: a change to the map changes the page and the pictures
//! alike.

#[allow(dead_code)]
#[path = "../../../precompute/src/picture/colour.rs"]
pub mod colour;
#[allow(dead_code)]
#[path = "../../../precompute/src/picture/contour.rs"]
pub mod contour;

use colour::Scale;
use contour::{isolines, Lattice};

/// A plan of one grid's values: the scale, one colour per point, the isolux lines.
pub struct Plan {
    pub scale: Scale,
    /// 8-bit sRGB per point, in the grid's order.
    pub colours: Vec<[u8; 3]>,
    /// Each isolux level with its polylines `(x, y)`, m.
    pub isolux: Vec<(f64, Vec<Vec<[f64; 2]>>)>,
}

/// The plan of `values` at `points` (`(x, y)`, m) on a lattice of `counts` points `cell`
/// apart, as `eigenrad render --plan` builds it (`precompute/src/picture/plan.rs`): the scale
/// spans the values, the lines are at its round values inside them. Without a full lattice
/// (`counts[0] · counts[1]` points) the plan has no lines.
pub fn plan(values: &[f64], points: &[[f64; 2]], counts: [usize; 2], cell: [f64; 2]) -> Plan {
    let (lo, hi) = values
        .iter()
        .filter(|v| v.is_finite())
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &v| {
            (a.min(v), b.max(v))
        });
    let (lo, hi) = if lo <= hi { (lo, hi) } else { (0.0, 0.0) };
    let scale = Scale::around(lo, hi, "lux");
    let colours = values.iter().map(|&v| scale.colour(Some(v))).collect();
    let isolux = match points.first() {
        Some(&origin) if counts[0] * counts[1] == values.len() => {
            let lattice = Lattice {
                counts,
                origin,
                spacing: cell,
                values,
            };
            scale
                .isolux_levels(lo, hi)
                .into_iter()
                .map(|t| (t, isolines(&lattice, t)))
                .filter(|(_, lines)| !lines.is_empty())
                .collect()
        }
        _ => Vec::new(),
    };
    Plan {
        scale,
        colours,
        isolux,
    }
}
