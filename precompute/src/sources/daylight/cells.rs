//! The quadratures daylight shares: receiving patches cut into cells by their distance to the
//! windows, window cells refined where their points see different things, and lit areas
//! refined along shadow edges.

use super::outside::{centre, clip};
use super::Ctx;
use crate::formfactor::{for_each_on_cell, point_to_polygon, split_cell, Shaft};
use crate::geometry::Vec3;
use crate::scene::FieldOfView;

/// Most Gauss–Legendre points per side (a cell's samples live in a fixed buffer).
pub(super) const MAX_ORDER: usize = 8;

/// Signature of a sample that contributes nothing (behind, outside a sensor's view, hidden).
const NOTHING: usize = usize::MAX;

/// The apparent size (rad) of a window cell of radius `r` (m) whose centre lies at `distance`
/// (m) from the viewer in the unit direction `towards`, on a pane facing `normal` (into the
/// room): `2 r √cos θ_w / distance`, the square root of twice the solid angle of a square
/// cell seen at the incidence θ_w. Seen face-on it is the cell's angular diameter; seen
/// edge-on it shrinks with the solid angle, which bounds what a misplaced boundary inside the
/// cell can move. Near the window's own plane every sky patch's boundary crowds into thin
/// strips of the pane seen almost edge-on: their angular diameter would split the strips to
/// `edge_depth` while what they carry vanishes with `cos θ_w`.
fn apparent_size(r: f64, distance: f64, normal: Vec3, towards: Vec3) -> f64 {
    let cos_w = (-normal.dot(towards)).clamp(0.0, 1.0);
    2.0 * r * cos_w.sqrt() / distance
}

/// What a point `x` facing `normal` gets from the window `panes` under a uniform sky of
/// 1 cd/m² (lux), unoccluded and through glass of τ = 1: `Σ π F`, the point-to-polygon form
/// factors exact (Lambert's contour integral). Smooth where the windows' light is, and
/// cheap: what receiving cells are refined against.
pub(super) fn uniform_light<'p>(
    panes: impl Iterator<Item = Pane<'p>>,
    x: Vec3,
    normal: Vec3,
) -> f64 {
    panes
        .map(|p| std::f64::consts::PI * point_to_polygon(x, normal, p.corners, p.normal))
        .sum()
}

/// A receiving point: where it is, where it faces, what it sees.
#[derive(Clone, Copy)]
pub(super) struct Viewer<'a> {
    pub(super) x: Vec3,
    pub(super) normal: Vec3,
    /// What it sees: only directions within it count, each weighted by its sensitivity.
    pub(super) field: FieldOfView<'a>,
    /// Patches whose faces do not block (the receiving patch, the window patch).
    pub(super) ignore: &'a [usize],
}

/// A window patch or face as seen by the quadratures.
#[derive(Clone, Copy)]
pub(super) struct Pane<'a> {
    pub(super) corners: &'a [Vec3],
    /// Unit normal, into the room.
    pub(super) normal: Vec3,
}

/// What one window point contributes: `(bin, factor)` for the point `y`, the unit direction
/// `d` from the receiver through it and the cosine at the window `cos_w`; the geometric
/// kernel `cos θ_x cos θ_w / r²` is applied by the caller. `None`: nothing.
pub(super) type Sample<'s> = dyn Fn(Vec3, Vec3, f64) -> Option<(usize, f64)> + 's;

impl Ctx<'_> {
    /// Calls `f(point, weight)` (m, m²) over the convex cell `corners` of a receiving patch,
    /// split in four while its diameter exceeds `receiver_cell_angle` times its distance to
    /// the nearest window (`near`, m, from a point), at most `max_depth` times, and while
    /// splitting moves the rule's integral of `light` (the windows' light at a point, lux per
    /// cd/m², smooth and cheap: [`uniform_light`]) by more than `receiver_tolerance` of the
    /// whole patch's; then by the Gauss–Legendre rule of `receiver_order`.
    pub(super) fn over_cells(
        &self,
        corners: &[Vec3],
        near: &dyn Fn(Vec3) -> f64,
        light: &dyn Fn(Vec3) -> f64,
        f: &mut dyn FnMut(Vec3, f64),
    ) {
        let least = self.opts.receiver_tolerance * self.rule(corners, light).abs();
        self.over_cells_within(corners, near, light, least, 0, f);
    }

    /// [`Ctx::over_cells`] on a cell at `depth`, split while splitting moves the integral of
    /// `light` by more than `least` (lux m² per cd/m²).
    fn over_cells_within(
        &self,
        corners: &[Vec3],
        near: &dyn Fn(Vec3) -> f64,
        light: &dyn Fn(Vec3) -> f64,
        least: f64,
        depth: u32,
        f: &mut dyn FnMut(Vec3, f64),
    ) {
        let (c, r) = centre(corners);
        let gap = (near(c) - r).max(0.0);
        if depth < self.opts.max_depth && 2.0 * r > self.opts.receiver_cell_angle * gap {
            let cells = split_cell(corners);
            // The parent's rule against its children's: the error the split removes, most
            // of the parent's own (the children's is ~2^-(2 order) of it on a smooth integrand).
            let parts: f64 = cells.iter().map(|cell| self.rule(cell, light)).sum();
            if (self.rule(corners, light) - parts).abs() > least {
                for cell in cells {
                    self.over_cells_within(&cell, near, light, least, depth + 1, f);
                }
                return;
            }
        }
        for_each_on_cell(corners, &self.gl_receiver, f);
    }

    /// The receiving cells' rule of `light` on `corners`, lux m² per cd/m².
    fn rule(&self, corners: &[Vec3], light: &dyn Fn(Vec3) -> f64) -> f64 {
        let mut sum = 0.0;
        for_each_on_cell(corners, &self.gl_receiver, |x, w| sum += w * light(x));
        sum
    }

    /// [`Ctx::window_pane`] for window patch `j` seen from a point `x` facing `normal` (within
    /// its `field` of view): the pane, its shaft to the point, and the point as viewer,
    /// with the window patch itself not blocking.
    #[allow(clippy::too_many_arguments)]
    pub(super) fn window_patch_at_point(
        &self,
        j: usize,
        x: Vec3,
        normal: Vec3,
        field: FieldOfView,
        sample: &Sample,
        scale: f64,
        acc: &mut [f64],
    ) {
        let w = &self.scene.patches[j];
        let ignore = [j];
        let pane = Pane {
            corners: &w.polygon.vertices,
            normal: w.normal,
        };
        let shaft = self
            .occluders
            .shaft(pane.corners, pane.normal, &[x], normal, &ignore);
        let v = Viewer {
            x,
            normal,
            field,
            ignore: &ignore,
        };
        self.window_pane(v, &shaft, pane, sample, scale, acc);
    }

    /// [`Ctx::window_cell`] over a whole window pane, cut first along the viewer's horizon
    /// (the horizontal plane through it) so that the ground's edge is exact.
    pub(super) fn window_pane(
        &self,
        v: Viewer,
        shaft: &Shaft,
        pane: Pane,
        sample: &Sample,
        scale: f64,
        acc: &mut [f64],
    ) {
        let up = Vec3::new(0.0, 0.0, 1.0);
        let (mut above, mut below) = (false, false);
        for c in pane.corners {
            above |= c.z > v.x.z;
            below |= c.z < v.x.z;
        }
        if above && below {
            for part in [clip(pane.corners, v.x, up), clip(pane.corners, v.x, -up)] {
                if part.len() >= 3 {
                    self.window_cell(v, shaft, pane, &part, sample, scale, 0, acc);
                }
            }
        } else {
            self.window_cell(v, shaft, pane, pane.corners, sample, scale, 0, acc);
        }
    }

    /// `∫ sample · cos θ_x cos θ_w / r² dA` over a cell of a window pane seen from the viewer,
    /// times `scale`, added into `acc` by bin. The cell is split while it is large for its
    /// distance (`cell_angle`, `max_depth`) and, where its points fall in different bins or
    /// some are hidden, while its apparent size ([`apparent_size`]) exceeds `edge_angle` (at
    /// most `edge_depth` splits).
    #[allow(clippy::too_many_arguments)]
    fn window_cell(
        &self,
        v: Viewer,
        shaft: &Shaft,
        pane: Pane,
        corners: &[Vec3],
        sample: &Sample,
        scale: f64,
        depth: u32,
        acc: &mut [f64],
    ) {
        let (c, r) = centre(corners);
        let distance = (c - v.x).length();
        let gap = (distance - r).max(0.0);
        let split = |acc: &mut [f64]| {
            for cell in split_cell(corners) {
                self.window_cell(v, shaft, pane, &cell, sample, scale, depth + 1, acc);
            }
        };
        // A polygon of more than four corners is cut into its fan's triangles first, so that
        // a cell's samples fit the buffer.
        if corners.len() > 4
            || (depth < self.opts.max_depth && 2.0 * r > self.opts.cell_angle * gap)
        {
            return split(acc);
        }
        let mut samples = [(NOTHING, 0.0); MAX_ORDER * MAX_ORDER * 4];
        let mut count = 0;
        for_each_on_cell(corners, &self.gl, |y, w| {
            let s = self
                .at(v, shaft, pane, y, sample)
                .map(|(bin, value)| (bin, w * value));
            if let Some(slot) = samples.get_mut(count) {
                *slot = s.unwrap_or((NOTHING, 0.0));
                count += 1;
            }
        });
        let taken = &samples[..count];
        if depth < self.opts.edge_depth
            && apparent_size(r, distance, pane.normal, (c - v.x) / distance) > self.opts.edge_angle
        {
            let first = taken.first().map_or(NOTHING, |s| s.0);
            let uniform = taken.iter().all(|s| s.0 == first)
                && (first == NOTHING || self.corners_agree(v, pane, corners, sample, first));
            if !uniform {
                return split(acc);
            }
        }
        for &(bin, value) in taken {
            if let Some(a) = acc.get_mut(bin) {
                *a += scale * value;
            }
        }
    }

    /// Whether the sky (or exterior) bin seen through every corner of a cell is `bin`, the
    /// one all its Gauss points see: a patch boundary between the outermost points and the
    /// cell's edge then splits the cell too. Corners lie on the cell's edges, where the
    /// window meets its frame: only the direction counts there, not the visibility (a ray
    /// grazing the wall's edge), nor a corner behind the viewer or outside its field.
    fn corners_agree(
        &self,
        v: Viewer,
        pane: Pane,
        corners: &[Vec3],
        sample: &Sample,
        bin: usize,
    ) -> bool {
        corners.iter().all(|&y| {
            let d = y - v.x;
            let r = d.length();
            if r == 0.0 {
                return true;
            }
            let d = d / r;
            let cw = -pane.normal.dot(d);
            if !(cw > 0.0 && v.field.admits(v.normal.dot(d))) {
                return true;
            }
            sample(y, d, cw).is_none_or(|(corner, _)| corner == bin)
        })
    }

    /// One window point `y`: `(bin, sample · cos θ_x cos θ_w / r²)`, or `None`.
    fn at(
        &self,
        v: Viewer,
        shaft: &Shaft,
        pane: Pane,
        y: Vec3,
        sample: &Sample,
    ) -> Option<(usize, f64)> {
        let d = y - v.x;
        let r2 = d.dot(d);
        let r = r2.sqrt();
        if r == 0.0 {
            return None;
        }
        let d = d / r;
        // The receiver's one rule: `cos θ`, or a sensor's response in its place.
        let cx = v.field.sensitivity(v.normal.dot(d));
        let cw = -pane.normal.dot(d);
        if !(cw > 0.0 && cx > 0.0) {
            return None;
        }
        let clear = shaft.is_clear() || self.occluders.visible_in(shaft, v.x, y, v.ignore);
        if !clear {
            return None;
        }
        sample(y, d, cw).map(|(bin, f)| (bin, f * cx * cw / r2))
    }
}
