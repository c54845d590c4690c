//! The sky and the exterior through the windows: per sky patch and for the exterior, on
//! every receiver (clear glazing) and as the exitance of diffusing windows.

use eigenrad_runtime::sky::patches::SkyPatches;

use super::cells::{uniform_light, Pane, Viewer};
use super::outside::{Outside, Seen};
use super::{facing, Aperture, Ctx, DaylightOptions, SkyResponse, Transmittance};
use crate::formfactor::{for_each_on_cell, Occluders, Shaft};
use crate::geometry::{Patch, Vec3};
use crate::scene::{FieldOfView, Scene};

/// [`super::sky_response`] with the transmittance `tau` in place of the glazings'.
pub(crate) fn response(
    scene: &Scene,
    occluders: &Occluders,
    patches: SkyPatches,
    opts: &DaylightOptions,
    tau: &Transmittance,
) -> SkyResponse {
    response_on(scene, occluders, patches, opts, tau, None)
}

/// [`response`] on the patches `receiving` marks alone (the others read 0) and every
/// output, from the clear windows alone when `receiving` is given ([`super::clear_sky_on`]).
pub(super) fn response_on(
    scene: &Scene,
    occluders: &Occluders,
    patches: SkyPatches,
    opts: &DaylightOptions,
    tau: &Transmittance,
    receiving: Option<&[bool]>,
) -> SkyResponse {
    let Some(site) = scene.site.as_ref() else {
        panic!("daylight from the sky needs the scene's site (north, ground reflectance)");
    };
    let outside = Outside::new(scene, patches, site.north, site.ground_reflectance);
    let ctx = Ctx::new(scene, occluders, outside, opts, tau).receiving(receiving);
    let bins = patches.count() + 1;
    let panes = ctx.diffusing_panes(|a, j| ctx.exitance(a, j, bins));
    let mut emission = vec![vec![0.0; bins]; scene.patches.len()];
    for (j, e) in &panes {
        emission[*j].clone_from(e);
    }
    let on_patch = |p: &Patch, ignore: Option<usize>| {
        let mut acc = ctx.sky_on_patch(p, ignore, bins);
        ctx.lambertian_on_patch(p, ignore, &panes, &mut acc);
        acc
    };
    let on_point = |x: Vec3, normal: Vec3, field: FieldOfView| {
        let mut acc = ctx.sky_at_point(x, normal, field, bins);
        ctx.lambertian_at_point(x, normal, field, &panes, &mut acc);
        acc
    };
    let mut sky = ctx.gather(bins, &emission, &on_patch, &on_point);
    let Some(exterior) = sky.pop() else {
        unreachable!("a sky of {bins} bins");
    };
    SkyResponse {
        patches,
        sky,
        exterior,
    }
}

/// A clear window patch seen from a receiver: the window, its patch, and the occluders that
/// may cut light between them.
struct Target {
    window: usize,
    patch: usize,
    ignore: Vec<usize>,
    shaft: Shaft,
}

impl Ctx<'_> {
    /// What a point of clear window `w` contributes: its bin (the sky patch the ray ends in,
    /// or the exterior, the last bin) and `τ` times 1 (sky) or the exterior's reflectance.
    fn clear_sample(&self, w: usize) -> impl Fn(Vec3, Vec3, f64) -> Option<(usize, f64)> + '_ {
        let exterior = self.outside.patches.count();
        move |y, d, cos_w| {
            let t = self.tabulated(w, cos_w);
            Some(match self.outside.seen(y, d) {
                Seen::Sky(k) => (k, t),
                Seen::Exterior(r) => (exterior, t * r),
            })
        }
    }

    /// Mean illuminance per bin on a receiving patch from the clear windows; `ignore` is
    /// the patch itself when it is one of the scene's.
    pub(super) fn sky_on_patch(&self, p: &Patch, ignore: Option<usize>, bins: usize) -> Vec<f64> {
        let mut acc = vec![0.0; bins];
        let corners = &p.polygon.vertices;
        let mut targets = Vec::new();
        for a in self.apertures.iter().filter(|a| !a.diffusing) {
            for &j in &a.patches {
                let w = &self.scene.patches[j];
                if !facing(p, w) {
                    continue;
                }
                let ignore: Vec<usize> = ignore.into_iter().chain([j]).collect();
                let shaft =
                    self.occluders
                        .shaft(&w.polygon.vertices, w.normal, corners, p.normal, &ignore);
                targets.push(Target {
                    window: a.window,
                    patch: j,
                    ignore,
                    shaft,
                });
            }
        }
        if targets.is_empty() {
            return acc;
        }
        let samples: Vec<_> = targets
            .iter()
            .map(|t| self.clear_sample(t.window))
            .collect();
        let near = |x: Vec3| self.near(x, false);
        let panes = || {
            targets.iter().map(|t| {
                let w = &self.scene.patches[t.patch];
                Pane {
                    corners: &w.polygon.vertices,
                    normal: w.normal,
                }
            })
        };
        let light = |x: Vec3| uniform_light(panes(), x, p.normal);
        self.over_cells(corners, &near, &light, &mut |x, weight| {
            for (t, sample) in targets.iter().zip(&samples) {
                let w = &self.scene.patches[t.patch];
                let pane = Pane {
                    corners: &w.polygon.vertices,
                    normal: w.normal,
                };
                let v = Viewer {
                    x,
                    normal: p.normal,
                    field: FieldOfView::HEMISPHERE,
                    ignore: &t.ignore,
                };
                self.window_pane(v, &t.shaft, pane, sample, weight / p.area, &mut acc);
            }
        });
        acc
    }

    /// Illuminance per bin at a point facing `normal` (within its `field` of view)
    /// from the clear windows.
    pub(super) fn sky_at_point(
        &self,
        x: Vec3,
        normal: Vec3,
        field: FieldOfView,
        bins: usize,
    ) -> Vec<f64> {
        let mut acc = vec![0.0; bins];
        for a in self.apertures.iter().filter(|a| !a.diffusing) {
            let sample = self.clear_sample(a.window);
            for &j in &a.patches {
                self.window_patch_at_point(j, x, normal, field, &sample, 1.0, &mut acc);
            }
        }
        acc
    }

    /// Transmitted exitance per bin (lux per cd/m²) of patch `j` of the diffusing window
    /// `a`, averaged over the patch: `∫ L τ(θ) cos θ dω` over the exterior hemisphere.
    fn exitance(&self, a: &Aperture, j: usize, bins: usize) -> Vec<f64> {
        let mut acc = vec![0.0; bins];
        let w = &self.scene.patches[j];
        if w.area <= 0.0 {
            return acc;
        }
        for_each_on_cell(&w.polygon.vertices, &self.gl, |y, weight| {
            self.hemisphere(y, w.normal, a.window, weight / w.area, &mut acc);
        });
        acc
    }

    /// Adds `scale · ∫ L τ(θ) cos θ dω` at window point `y` (normal `normal` into the room)
    /// into `acc` by bin: each sky patch over `sky_cells²` cells in altitude and azimuth,
    /// Gauss–Legendre in each, `dω = cos h dh dA`; the ground likewise, in rows of the
    /// patches' height.
    fn hemisphere(&self, y: Vec3, normal: Vec3, w: usize, scale: f64, acc: &mut [f64]) {
        let o = &self.outside;
        let exterior = o.patches.count();
        let m = self.opts.sky_cells.max(1);
        let mut cell = |h0: f64, h1: f64, a0: f64, a1: f64, bin: usize, ground: bool| {
            let (dh, da) = (h1 - h0, a1 - a0);
            for &(u, wu) in &self.gl {
                let h = h0 + u * dh;
                for &(v, wv) in &self.gl {
                    let az = a0 + v * da;
                    let site = [az.sin() * h.cos(), az.cos() * h.cos(), h.sin()];
                    let [x, yy, z] = crate::daylight::site_to_room(site, o.north);
                    let d = Vec3::new(x, yy, z);
                    let cos = -normal.dot(d);
                    if cos <= 0.0 {
                        continue;
                    }
                    let value = scale * wu * wv * dh * da * h.cos() * cos * self.tabulated(w, cos);
                    match (o.obstruction(y, d), ground) {
                        (Some(r), _) => acc[exterior] += value * r,
                        (None, true) => acc[exterior] += value * o.ground,
                        (None, false) => acc[bin] += value,
                    }
                }
            }
        };
        let mut rows = 0.0f64;
        for k in 0..exterior {
            let Some(p) = o.patches.patch(k) else {
                continue;
            };
            let (h0, h1) = (f64::from(p.altitude[0]), f64::from(p.altitude[1]));
            let width = f64::from(p.azimuth_width);
            let a0 = f64::from(p.azimuth) - 0.5 * width;
            rows = rows.max(h1 - h0);
            for i in 0..m {
                for l in 0..m {
                    let (fi, fl, mf) = (i as f64, l as f64, m as f64);
                    cell(
                        h0 + fi * (h1 - h0) / mf,
                        h0 + (fi + 1.0) * (h1 - h0) / mf,
                        a0 + fl * width / mf,
                        a0 + (fl + 1.0) * width / mf,
                        k,
                        false,
                    );
                }
            }
        }
        // The ground: cells as large as the sky's lowest ones.
        let step = rows / m as f64;
        let count_h = (std::f64::consts::FRAC_PI_2 / step).ceil().max(1.0) as usize;
        let count_a = (std::f64::consts::TAU / step).ceil().max(1.0) as usize;
        let (dh, da) = (
            std::f64::consts::FRAC_PI_2 / count_h as f64,
            std::f64::consts::TAU / count_a as f64,
        );
        for i in 0..count_h {
            for l in 0..count_a {
                let h0 = -std::f64::consts::FRAC_PI_2 + i as f64 * dh;
                let a0 = l as f64 * da;
                cell(h0, h0 + dh, a0, a0 + da, exterior, true);
            }
        }
    }
}
