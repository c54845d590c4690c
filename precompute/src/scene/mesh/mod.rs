//! Checking faces and cutting them into patches no longer than a given edge, of bounded
//! aspect ratio where the face allows.
//!
//! Quadrilaterals become a regular grid of convex quads; triangles within [`ASPECT_BOUND`]
//! become m² similar triangles (each edge cut into m equal parts; m = 2 is midpoint
//! subdivision). Thinner triangles (slivers) and polygons of more than four corners are cut
//! by straight lines across their long side ([`cut`](cut())), not fanned from a corner: a
//! fan's triangles all meet at one corner and run across the whole face, and a sliver's
//! similar triangles are as thin as the sliver. Everything depends only on the corners and
//! the edge length, so meshing is deterministic.
//!
//! The aspect ratio is [`geometry::aspect`](crate::geometry::aspect): the long side over the
//! short side of the narrowest rectangle around a patch. Away from a face's boundary the
//! pieces are about `max_edge` on each side (aspect under 2), and every piece at least
//! [`NARROW`] × `max_edge` wide is within [`ASPECT_BOUND`]; the small pieces left along a
//! slanted or curved outline may be thinner. A face narrower than
//! `max_edge` is cut across its length only, into pieces at most `max_edge` long: rounder
//! pieces would multiply the patch count by their aspect without resolving the exitance any
//! finer along the face, and the form-factor quadrature refines thin patches itself. A patch
//! holding a corner sharper than the bound allows is as thin as that corner.

mod check;
mod cut;
mod estimate;
#[cfg(test)]
mod fixtures;
mod regular;
mod surfaces;

pub(crate) use check::{check_face, FaceProblem};
pub(crate) use estimate::estimate;
pub(crate) use surfaces::{mesh_surfaces, Meshed};

use crate::geometry::{aspect, Polygon, Vec3};
use cut::cut;
use regular::{mesh_quad, mesh_triangle};

/// Aspect ratio ([`aspect`]) up to which a triangle is subdivided into similar triangles and
/// a polygon's pieces are cut down to quadrilaterals and triangles: a right isosceles
/// triangle has 2, a 2 × 1 rectangle 2.
pub(crate) const ASPECT_BOUND: f64 = 2.5;

/// Most corners a patch cut from a polygon keeps: a piece of more is halved across its long
/// side. The form-factor quadrature maps quadrilaterals and triangles directly but fans larger
/// polygons from a corner: a closed 32-sided prism's base rows missed 1 by 1.2e-2 with pieces
/// of up to eight corners, and miss it by under 7e-6 in quadrilaterals and triangles
/// (`c79_c109_closed_faceted_prisms_and_pyramids_close`).
pub(crate) const MAX_CORNERS: usize = 4;

/// A piece narrower than this share of `max_edge` is narrow: [`cut`](cut()) makes it no
/// longer than `max_edge` but no rounder (a wider one is cut to within [`ASPECT_BOUND`]).
pub(crate) const NARROW: f64 = 0.25;

/// Cuts a checked convex face into convex patches whose edges are at most `max_edge`
/// (metres), with the face's winding.
///
/// A quad gives a grid of quads, a triangle within [`ASPECT_BOUND`] m² similar triangles;
/// a thinner triangle or a polygon of more than four corners is [`cut`](cut()) across its
/// long side.
pub(crate) fn mesh_face(corners: &[Vec3], max_edge: f64, out: &mut Vec<Polygon>) {
    match corners {
        [a, b, c] if aspect(corners) <= ASPECT_BOUND => mesh_triangle(*a, *b, *c, max_edge, out),
        [a, b, c, d] => mesh_quad(*a, *b, *c, *d, max_edge, out),
        _ => cut(corners.to_vec(), max_edge, 0, out),
    }
}

/// Cuts a face into triangles: a quad along its shorter diagonal, other polygons as a fan.
pub(crate) fn triangulate(corners: &[Vec3]) -> Vec<Vec<Vec3>> {
    if let [a, b, c, d] = corners {
        if (*c - *a).length() <= (*d - *b).length() {
            return vec![vec![*a, *b, *c], vec![*a, *c, *d]];
        }
        return vec![vec![*a, *b, *d], vec![*b, *c, *d]];
    }
    (1..corners.len().saturating_sub(1))
        .map(|i| vec![corners[0], corners[i], corners[i + 1]])
        .collect()
}

/// How many equal parts make pieces of `length` no longer than `max_edge`.
fn parts(length: f64, max_edge: f64) -> usize {
    let k = (length / max_edge * (1.0 - 1e-12)).ceil();
    if k.is_finite() && k >= 1.0 {
        k as usize
    } else {
        1
    }
}
