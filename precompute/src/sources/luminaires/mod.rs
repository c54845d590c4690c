//! Luminaires with photometry as light sources: the illuminance their intensity
//! distributions put directly on every patch, sensor and work-plane receiver, with the
//! scene's occlusion (docs/math.md, "Light sources: emission and direct irradiance").
//!
//! A luminaire emits nothing on the patches (`emission` is zero): all of its light enters as
//! direct irradiance, so the model takes it as external light and its first reflection
//! `ρ ∘ E_d` is what the basis carries further.
//!
//! # Point illuminance
//!
//! From a source of intensity `I(C, γ)` (cd) at `q`, the illuminance (lux) at a point `x`
//! with unit normal `n` is `E = MF · I(C, γ) · cos θ / d²`, `d = |q − x|` (m), `cos θ = n ·
//! (q − x)/d` (0 when the light arrives from behind), `(C, γ)` the angles of `x − q` in the
//! luminaire's frame ([`crate::scene::Luminaire::angles`]), `MF` the maintenance factor times
//! the tilt table's factor at the luminaire's orientation
//! ([`crate::scene::Luminaire::tilt_factor`]), and zero where a blocker cuts the segment
//! ([`Occluders::visible`], ignoring the receiving patch). A sensor counts only directions within its half-angle of its normal. Each patch,
//! sensor and point first gathers the occluders that may cut a segment between it and the
//! opening's bounding rectangle (shaft culling, as for the form factors); when there are none,
//! no ray is traced, and otherwise rays are tested against those alone.
//!
//! # Near field
//!
//! `I cos θ / d²` holds far from the source. When the luminous opening (length `L` along C0,
//! width `W` along C90, from the photometric file) is larger than `d / ratio`, `d` the
//! distance from the receiving point to the opening's nearest point (ratio 5 by default, the
//! five-times rule of photometry), the opening is split into `k_L × k_W`
//! equal pieces, `k_L = ⌈ratio · L / d⌉` and likewise for the width (at most
//! [`MAX_SPLIT`] each), so that every piece is at most `d / ratio` across; each piece sits at
//! its centre in the opening's plane (through the photometric centre, perpendicular to the
//! nadir) and carries its share of the intensity, the same distribution scaled. A round
//! opening keeps the pieces whose centres lie inside its ellipse, in equal shares. The
//! opening's height is not split: its pieces lie in the plane of its length and width.
//!
//! # Patches and receivers
//!
//! The illuminance of a patch is its mean `(1/A) ∫ E dA`, by Gauss–Legendre rules (`order`
//! points per side, bilinear on quadrilaterals, collapsed on triangles) on cells of the patch:
//! a cell is split in four while its diameter exceeds `cell_angle` times the smallest distance
//! its points can have to the opening (its centroid's distance less its half-diameter and the
//! opening's half-diagonal), at most `max_depth` times. A smooth integrand is then integrated
//! to about `(cell_angle / 2)^(2 order)`, ~1e-7 at the defaults; the tests hold patches next to
//! a point source to 1e-5 of the exact patch average. A patch whose plane has the whole
//! opening behind or in it receives nothing and costs nothing.
//!
//! # Shadows
//!
//! Where the shaft of a cell small for its distance holds blockers, the opening is split
//! finer, into pieces at most `1/shadow_ratio` (1/20) of the distance from the cell's centroid:
//! a penumbra is a staircase of one step a piece, and the five-times rule, made for a smooth
//! field, leaves it coarse (the side of a desk of the open-plan floor 23 % off a four times
//! finer split, at 2.7e-3 with it). A point (a sensor, a grid point) a blocker may shadow is
//! lit by the same finer pieces, one ray each. In a cell, each piece is a point source, and
//! the part of the cell it lights is the cell less the blockers' shadows from it, as convex polygons (`formfactor::shadow`, the form factors'
//! exact visibility): the rule integrates the smooth `I cos θ / d²` on each lit piece, and a
//! shadow edge costs no refinement. The tests hold the flux of a shadow and patch means under
//! a penumbra to 1e-9 of exact for the pieces. Where the polygons do not fit their fixed
//! capacities, the shaft overflowed, the cell straddles the opening's plane, or
//! [`LuminaireOptions::polygon_shadows`] is off, rays decide, from the pieces of the five-times
//! rule: where a shadow edge crosses a cell (some of its points lit, a blocker hiding light
//! from some, and not the same pieces of the opening hidden from all: a cell wholly inside one
//! part of a penumbra is smooth) the cell is split again, down to `edge_depth` (1/256 of the
//! patch's side): the tests hold the flux of a shadow to 2e-3, and patch means under a
//! penumbra to 1e-3 of exact. Rays miss a shadow that falls between a cell's points: some
//! patch means of the open-plan floor were 19 % off by rays against a midpoint rule with the
//! same pieces, 1.9e-3 with the polygons (`eigenrad-bench shadows`, docs/performance.md,
//! "Shadows as polygons").
//!
//! The split pieces of a Lambertian opening converge to its exitance's exact form factor as
//! `1/k²`: 0.7 % off at the five-times rule, 0.05 % at twenty times.

use rayon::prelude::*;

use super::ChannelLight;
use crate::formfactor::{
    for_each_on_cell, gauss_legendre, split_cell, visible_sum, Occluders, Shaft,
};
use crate::geometry::{Patch, Vec3};
use crate::scene::photometry::OpeningShape;
use crate::scene::receivers::{mean_over_points, receivers, Receiver};
use crate::scene::{FieldOfView, Luminaire, Scene};

mod flux;
#[cfg(test)]
mod tests;

pub use flux::{LuminaireFlux, FLUX_AGREEMENT};

/// How finely the direct light of a luminaire is integrated.
#[derive(Clone, Debug)]
pub struct LuminaireOptions {
    /// A luminous opening is split until each piece is at most `1/near_field_ratio` of its
    /// distance to the receiving point (dimensionless). Default 5.
    pub near_field_ratio: f64,
    /// A cell of a patch is split while its diameter exceeds this times its smallest distance
    /// to the opening (dimensionless, about the angle in radians it subtends). Default 0.25.
    pub cell_angle: f64,
    /// Gauss–Legendre points per side on each cell. Default 4.
    pub order: usize,
    /// Most times a patch is split for its distance (its finest cells are `4^-max_depth` of
    /// it). Default 5.
    pub max_depth: u32,
    /// Most times a patch is split where a shadow edge crosses it. Default 8: cells of
    /// 1/256 of its side along the edge.
    pub edge_depth: u32,
    /// Shadows on a patch's cells as polygons, exact for the pieces of the opening. Default
    /// true; false, or where the polygons do not fit their fixed capacities, rays refined
    /// along the shadow edges (`edge_depth`).
    pub polygon_shadows: bool,
    /// With the shadows as polygons, a cell with blockers between it and the opening splits
    /// the opening until each piece is at most `1/shadow_ratio` of its distance
    /// (dimensionless). Default 20, four times `near_field_ratio`: a penumbra is a staircase
    /// of one step a piece, which the five-times rule, made for a smooth field, leaves coarse.
    pub shadow_ratio: f64,
}

impl Default for LuminaireOptions {
    fn default() -> Self {
        LuminaireOptions {
            near_field_ratio: 5.0,
            cell_angle: 0.25,
            order: 4,
            max_depth: 5,
            edge_depth: 8,
            polygon_shadows: true,
            shadow_ratio: 20.0,
        }
    }
}

/// Most pieces along each side of a luminous opening: a point closer than `L / (5 · 32)` to
/// an opening of length `L` (under 4 mm for a 60 cm panel) sees pieces larger than a fifth of
/// its distance, which only a point on the luminaire itself is.
pub const MAX_SPLIT: usize = 32;

/// The light of every channel of `scene` from its luminaires, in channel order: zero emission,
/// and as direct irradiance their illuminance (lux) on every patch and output (sensors,
/// zones, then grid points). A channel without luminaires gets zeros. `occluders` are the scene's.
///
/// Luminaires are photometric (cd), so a scene with luminaires has one, photopic, band (the
/// scene refuses others).
pub fn channel_lights(
    scene: &Scene,
    occluders: &Occluders,
    opts: &LuminaireOptions,
) -> Vec<ChannelLight> {
    lights_and_flux(scene, occluders, opts).0
}

/// [`channel_lights`], and where each luminaire's flux goes (in [`Scene::luminaires`] order).
pub fn lights_and_flux(
    scene: &Scene,
    occluders: &Occluders,
    opts: &LuminaireOptions,
) -> (Vec<ChannelLight>, Vec<LuminaireFlux>) {
    let bands = scene.bands.count();
    assert!(
        scene.luminaires.is_empty() || bands == 1,
        "luminaires in a scene of {bands} bands"
    );
    let (n, m) = (scene.patches.len(), scene.channels.len());
    let gl = gauss_legendre(opts.order.max(1));
    let mut patches = vec![vec![0.0; n]; m];
    // Every receiver in output order: points and work planes lit directly here, surface
    // zones averaged from their patches once every luminaire has lit them.
    let all: Vec<Receiver> = receivers(scene).collect();
    let mut outputs = vec![vec![0.0; all.len()]; m];
    let mut accounts = Vec::with_capacity(scene.luminaires.len());
    for lum in &scene.luminaires {
        let source = Source::new(lum, occluders, opts, &gl);
        let c = lum.channel;
        let on_patches: Vec<f64> = scene
            .patches
            .par_iter()
            .enumerate()
            .map(|(i, p)| source.patch(p, &[i]))
            .collect();
        let received: f64 = scene
            .patches
            .iter()
            .zip(&on_patches)
            .map(|(p, e)| p.area * e)
            .sum();
        accounts.push(LuminaireFlux::new(lum, received));
        for (sum, e) in patches[c].iter_mut().zip(on_patches) {
            *sum += e;
        }
        let direct = direct_at_receivers(&source, &all);
        for (sum, e) in outputs[c].iter_mut().zip(direct) {
            *sum += e;
        }
    }
    let lights = (0..m)
        .map(|c| {
            for (out, receiver) in outputs[c].iter_mut().zip(&all) {
                if let Receiver::Surfaces(members) = *receiver {
                    let area: f64 = members.iter().map(|&i| scene.patches[i].area).sum();
                    let lumens: f64 = members
                        .iter()
                        .map(|&i| scene.patches[i].area * patches[c][i])
                        .sum();
                    *out = lumens / area;
                }
            }
            ChannelLight {
                emission: vec![vec![0.0; n]; bands],
                patch_irradiance: vec![patches[c].clone(); bands],
                output_irradiance: vec![outputs[c].clone(); bands],
            }
        })
        .collect();
    (lights, accounts)
}

/// One luminaire ready to light points: its opening and the rules used on patches.
pub struct Source<'a> {
    lum: &'a Luminaire,
    occluders: &'a Occluders,
    opts: &'a LuminaireOptions,
    gl: &'a [(f64, f64)],
    /// Half the opening's length along C0 and its width along C90, m.
    half: (f64, f64),
    /// Round (an ellipse in its bounding rectangle) rather than rectangular.
    round: bool,
}

impl<'a> Source<'a> {
    /// The luminaire `lum` with the scene's `occluders`; `gl` is the Gauss–Legendre rule of
    /// `opts.order` points on [0, 1].
    pub fn new(
        lum: &'a Luminaire,
        occluders: &'a Occluders,
        opts: &'a LuminaireOptions,
        gl: &'a [(f64, f64)],
    ) -> Self {
        let o = &lum.photometry.opening;
        let (half, round) = match o.shape {
            OpeningShape::Point => ((0.0, 0.0), false),
            OpeningShape::Rectangular
            | OpeningShape::HorizontalCylinderAlongLength
            | OpeningShape::HorizontalCylinderAlongWidth => {
                ((0.5 * o.length, 0.5 * o.width), false)
            }
            OpeningShape::VerticalCylinder | OpeningShape::Ellipsoid => {
                ((0.5 * o.length, 0.5 * o.width), true)
            }
        };
        Source {
            lum,
            occluders,
            opts,
            gl,
            half,
            round,
        }
    }

    /// Half the diagonal of the opening's bounding rectangle, m.
    fn radius(&self) -> f64 {
        self.half.0.hypot(self.half.1)
    }

    /// The pieces of the opening seen from a point `d` metres from its nearest point, each at
    /// most `d / ratio` across: `f(position, share)` for each, shares summing to 1 (module
    /// documentation, "Near field").
    fn for_each_piece(&self, d: f64, ratio: f64, mut f: impl FnMut(Vec3, f64)) {
        let count = |half: f64| -> usize {
            let k = (ratio * 2.0 * half / d).ceil();
            if k.is_finite() {
                (k as usize).clamp(1, MAX_SPLIT)
            } else {
                MAX_SPLIT
            }
        };
        let (kl, kw) = (count(self.half.0), count(self.half.1));
        if kl == 1 && kw == 1 {
            return f(self.lum.position, 1.0);
        }
        let centre = |i: usize, k: usize| -1.0 + (2.0 * i as f64 + 1.0) / k as f64;
        let inside = |u: f64, v: f64| !self.round || u * u + v * v <= 1.0;
        let kept = if self.round {
            (0..kl)
                .flat_map(|i| (0..kw).map(move |j| (i, j)))
                .filter(|&(i, j)| inside(centre(i, kl), centre(j, kw)))
                .count()
        } else {
            kl * kw
        };
        let share = 1.0 / kept as f64;
        for i in 0..kl {
            for j in 0..kw {
                let (u, v) = (centre(i, kl), centre(j, kw));
                if inside(u, v) {
                    let offset = self.lum.c0 * (u * self.half.0) + self.lum.c90 * (v * self.half.1);
                    f(self.lum.position + offset, share);
                }
            }
        }
    }

    /// Illuminance, lux, at `x` (m) facing the unit `normal`; only light within `field`
    /// counts; `ignore` the receiving patch.
    pub fn point(&self, x: Vec3, normal: Vec3, field: FieldOfView, ignore: &[usize]) -> f64 {
        let shaft = self.shaft(&[x], normal, ignore);
        // A point a blocker may shadow sees the opening in the finer pieces of a shadowed
        // cell (module documentation, "Shadows"): each is one ray.
        let ratio = match &shaft {
            Some(s) if !s.is_clear() => self.opts.shadow_ratio,
            _ => self.opts.near_field_ratio,
        };
        self.lit(x, normal, field, ignore, shaft.as_ref(), ratio)
            .lux
    }

    /// The occluders that may cut light from the opening to a receiver (its `corners`, one for
    /// a point, and front `normal`): shaft culling, as the form factors use it, between the
    /// receiver and the opening's bounding rectangle, on the side of the opening's plane that
    /// the receiver is on. `None` when the receiver reaches both sides of that plane: its rays
    /// then go through the whole hierarchy.
    fn shaft(&self, corners: &[Vec3], normal: Vec3, ignore: &[usize]) -> Option<Shaft> {
        let p = self.lum.position;
        let heights = corners.iter().map(|&x| self.lum.nadir.dot(x - p));
        let (low, high) = heights.fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), h| {
            (lo.min(h), hi.max(h))
        });
        let facing = if low >= -PLANE_TOLERANCE && high > PLANE_TOLERANCE {
            self.lum.nadir
        } else if high <= PLANE_TOLERANCE && low < -PLANE_TOLERANCE {
            -self.lum.nadir
        } else {
            return None;
        };
        let (a, b) = (self.lum.c0 * self.half.0, self.lum.c90 * self.half.1);
        let opening = [p + a + b, p - a + b, p - a - b, p + a - b];
        Some(
            self.occluders
                .shaft(&opening, facing, corners, normal, ignore),
        )
    }

    /// Distance, m, from `x` to the nearest point of the opening's bounding rectangle.
    fn distance(&self, x: Vec3) -> f64 {
        let v = x - self.lum.position;
        let u = v.dot(self.lum.c0).abs() - self.half.0;
        let w = v.dot(self.lum.c90).abs() - self.half.1;
        let h = v.dot(self.lum.nadir);
        (u.max(0.0).powi(2) + w.max(0.0).powi(2) + h * h).sqrt()
    }

    /// What [`Source::point`] receives at `x` from the opening split by `ratio`
    /// ([`Source::for_each_piece`]), with which pieces a blocker hides; `shaft` holds the
    /// occluders that may cut light reaching `x` ([`Source::shaft`]).
    fn lit(
        &self,
        x: Vec3,
        normal: Vec3,
        field: FieldOfView,
        ignore: &[usize],
        shaft: Option<&Shaft>,
        ratio: f64,
    ) -> Received {
        let d = self.distance(x);
        if d == 0.0 {
            return Received::default();
        }
        let (mut e, mut hidden) = (0.0, false);
        let (mut signature, mut piece) = (SIGNATURE_SEED, 0u64);
        self.for_each_piece(d, ratio, |q, share| {
            piece += 1;
            let v = q - x;
            let r2 = v.dot(v);
            // The receiver's one rule: `cos θ`, or a sensor's response in its place. NaN (a
            // piece at the point itself) counts as behind.
            let sensitivity = field.sensitivity(normal.dot(v) / r2.sqrt());
            if sensitivity <= 0.0 {
                return;
            }
            let intensity = self.lum.intensity(-v) * share;
            if intensity > 0.0 {
                let visible = match shaft {
                    Some(s) if s.is_clear() => true,
                    Some(s) => self.occluders.visible_in(s, q, x, ignore),
                    None => self.occluders.visible(q, x, ignore),
                };
                if visible {
                    e += intensity * sensitivity / r2;
                } else {
                    hidden = true;
                    signature = mix(signature, piece);
                }
            }
        });
        Received {
            lux: e,
            hidden,
            signature: mix(signature, piece),
        }
    }

    /// Mean illuminance, lux, over `patch` (its front side); `ignore` is the patch itself when
    /// it is one of the scene's.
    pub fn patch(&self, patch: &Patch, ignore: &[usize]) -> f64 {
        let corners = &patch.polygon.vertices;
        if patch.area <= 0.0 || corners.is_empty() || self.behind(patch) {
            return 0.0;
        }
        let shaft = self.shaft(corners, patch.normal, ignore);
        self.cell(corners, patch.normal, ignore, shaft.as_ref(), 0) / patch.area
    }

    /// Is the whole opening behind the patch's plane or in it?
    fn behind(&self, patch: &Patch) -> bool {
        let on = patch.polygon.vertices[0];
        let (a, b) = (self.lum.c0 * self.half.0, self.lum.c90 * self.half.1);
        let p = self.lum.position;
        [p + a + b, p + a - b, p - a + b, p - a - b]
            .iter()
            .all(|&q| patch.normal.dot(q - on) <= PLANE_TOLERANCE)
    }

    /// `∫ E dA` over a convex cell, lm: split while it is large for its distance, then the
    /// Gauss–Legendre rule; a cell where some points see the light and a blocker hides it
    /// from others holds a shadow edge, and is split again down to `edge_depth`.
    /// `shaft` is the patch's ([`Source::shaft`]), valid for every cell inside it.
    fn cell(
        &self,
        corners: &[Vec3],
        normal: Vec3,
        ignore: &[usize],
        shaft: Option<&Shaft>,
        depth: u32,
    ) -> f64 {
        let split = |corners: &[Vec3]| -> f64 {
            split_cell(corners)
                .iter()
                .map(|c| self.cell(c, normal, ignore, shaft, depth + 1))
                .sum()
        };
        let centroid = corners.iter().fold(Vec3::ZERO, |s, &c| s + c) / corners.len() as f64;
        let half_diameter = corners
            .iter()
            .map(|&c| (c - centroid).length())
            .fold(0.0, f64::max);
        let nearest =
            ((self.lum.position - centroid).length() - half_diameter - self.radius()).max(0.0);
        let large = 2.0 * half_diameter > self.opts.cell_angle * nearest;
        if depth < self.opts.max_depth && large {
            return split(corners);
        }
        // Blockers between the cell and the opening, and the cell small for its distance:
        // the shadows as polygons, when they fit the fixed capacities.
        let polygons = self.opts.polygon_shadows && !large;
        if let Some(shaft) = shaft.filter(|s| polygons && !s.is_clear()) {
            if let Some(lumens) = self.shadowed_cell(corners, normal, shaft, centroid) {
                return lumens;
            }
        }
        let (mut lumens, mut seen, mut hidden) = (0.0, false, false);
        let (mut first, mut uniform) = (None, true);
        for_each_on_cell(corners, self.gl, |x, w| {
            let ratio = self.opts.near_field_ratio;
            let r = self.lit(x, normal, FieldOfView::HEMISPHERE, ignore, shaft, ratio);
            lumens += w * r.lux;
            seen |= r.lux > 0.0;
            hidden |= r.hidden;
            uniform &= *first.get_or_insert(r.signature) == r.signature;
        });
        // Every point hiding the same pieces (a cell wholly in one part of a penumbra): the
        // integrand is smooth over the cell, and there is no edge to split along.
        if seen && hidden && !uniform && depth < self.opts.edge_depth {
            return split(corners);
        }
        lumens
    }
}

impl Source<'_> {
    /// `∫ E dA` over a convex cell, lm, with exact shadows: each piece of the opening (cut by
    /// `shadow_ratio` for the distance of the cell's `centroid` to it) is a point source, the
    /// part of the cell it lights is the cell less the shadows the shaft's occluders cast from
    /// it (`formfactor::shadow`, convex pieces), and the Gauss–Legendre rule integrates the
    /// smooth `I cos θ / r²` over each lit piece. `None` when the shaft overflowed or the lit
    /// part is too fragmented for the fixed capacities: the caller then traces rays.
    fn shadowed_cell(
        &self,
        corners: &[Vec3],
        normal: Vec3,
        shaft: &Shaft,
        centroid: Vec3,
    ) -> Option<f64> {
        let &origin = corners.first()?;
        let d = self.distance(centroid);
        let mut lumens = 0.0;
        let mut complete = true;
        self.for_each_piece(d, self.opts.shadow_ratio, |q, share| {
            // A piece behind the cell's plane, or in it, lights none of it.
            if !complete || normal.dot(q - origin) <= 0.0 {
                return;
            }
            let Some(outlines) = self.occluders.shaft_outlines(shaft) else {
                complete = false;
                return;
            };
            let lit = visible_sum(q, corners, normal, outlines, |piece| {
                let mut sum = 0.0;
                for_each_on_cell(piece, self.gl, |x, w| {
                    let v = q - x;
                    let r2 = v.dot(v);
                    let sensitivity =
                        FieldOfView::HEMISPHERE.sensitivity(normal.dot(v) / r2.sqrt());
                    if sensitivity > 0.0 {
                        sum += w * self.lum.intensity(-v) * share * sensitivity / r2;
                    }
                });
                sum
            });
            match lit {
                Some(l) => lumens += l,
                None => complete = false,
            }
        });
        complete.then_some(lumens)
    }
}

/// An opening this close to a patch's plane (m) is in it: a recessed luminaire in its ceiling.
const PLANE_TOLERANCE: f64 = 1e-9;

/// What one point receives from a luminaire.
#[derive(Clone, Copy, Debug)]
struct Received {
    /// Illuminance, lux.
    lux: f64,
    /// A blocker hides light that would otherwise arrive.
    hidden: bool,
    /// Which pieces of the opening are hidden, and how many pieces there are, as a hash: two
    /// points with the same signature see the same pieces.
    signature: u64,
}

impl Default for Received {
    fn default() -> Self {
        Received {
            lux: 0.0,
            hidden: false,
            signature: SIGNATURE_SEED,
        }
    }
}

/// FNV-1a's offset basis and prime: the signature of a [`Received`].
const SIGNATURE_SEED: u64 = 0xcbf2_9ce4_8422_2325;

/// The direct illuminance `source` puts at every receiver of `all`, lux: at a sensor's point
/// within its field of view, the mean over a work plane's cells and over an imported grid's
/// points; 0 for a surface zone, whose mean the caller takes from its patches' light.
/// Receivers do not block light: nothing to ignore. Summed in order once computed: a
/// parallel sum's order, and its last bits, would follow the threads' work stealing, and
/// the same scene must give the same bytes.
pub(crate) fn direct_at_receivers(source: &Source, all: &[Receiver]) -> Vec<f64> {
    all.par_iter()
        .map(|receiver| match *receiver {
            Receiver::Point {
                position,
                normal,
                field,
            } => source.point(position, normal, field, &[]),
            Receiver::Plane(receivers) => {
                let lit: Vec<f64> = receivers
                    .par_iter()
                    .map(|r| r.area * source.patch(r, &[]))
                    .collect();
                let lumens: f64 = lit.iter().sum();
                lumens / receivers.iter().map(|r| r.area).sum::<f64>()
            }
            Receiver::Points(points) => mean_over_points(points, 1, |position, normal| {
                vec![source.point(position, normal, FieldOfView::HEMISPHERE, &[])]
            })[0],
            Receiver::Surfaces(_) => 0.0,
        })
        .collect()
}

fn mix(hash: u64, value: u64) -> u64 {
    (hash ^ value).wrapping_mul(0x0000_0100_0000_01b3)
}
