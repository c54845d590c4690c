//! The direct sun through the windows: the sun patch on every receiver (clear glazing), the
//! exitance of diffusing windows.

use eigenrad_runtime::sky::patches::SkyPatches;

use super::outside::{area, clip, ray_polygon, Outside};
use super::{Aperture, ChannelLight, Ctx, DaylightOptions, Transmittance};
use crate::formfactor::Occluders;
use crate::geometry::{doubled_vector_area, Patch, Vec3};
use crate::scene::{FieldOfView, Scene};

/// [`super::sun_light`] with the transmittance `tau` in place of the glazings'.
pub(crate) fn light(
    scene: &Scene,
    occluders: &Occluders,
    s: Vec3,
    opts: &DaylightOptions,
    tau: &Transmittance,
) -> ChannelLight {
    light_on(scene, occluders, s, opts, tau, None)
}

/// [`light`] on the patches `receiving` marks alone (the others read 0) and every output,
/// from the clear windows alone when `receiving` is given ([`super::clear_sun_on`]).
pub(super) fn light_on(
    scene: &Scene,
    occluders: &Occluders,
    s: Vec3,
    opts: &DaylightOptions,
    tau: &Transmittance,
    receiving: Option<&[bool]>,
) -> ChannelLight {
    assert!(
        s.is_finite() && (s.length() - 1.0).abs() <= 1e-6,
        "the sun's direction must be a unit vector, found {:?}",
        s.to_array()
    );
    let (north, ground) = scene
        .site
        .as_ref()
        .map_or((0.0, 0.0), |site| (site.north, site.ground_reflectance));
    let outside = Outside::new(scene, SkyPatches::TREGENZA, north, ground);
    let ctx = Ctx::new(scene, occluders, outside, opts, tau).receiving(receiving);
    let panes = ctx.diffusing_panes(|a, j| vec![ctx.sun_exitance(a, j, s)]);
    let mut emission = vec![vec![0.0]; scene.patches.len()];
    for (j, e) in &panes {
        emission[*j].clone_from(e);
    }
    let on_patch = |p: &Patch, ignore: Option<usize>| {
        let mut acc = vec![ctx.sun_on_patch(p, ignore, s)];
        ctx.lambertian_on_patch(p, ignore, &panes, &mut acc);
        acc
    };
    let on_point = |x: Vec3, normal: Vec3, field: FieldOfView| {
        let mut acc = vec![ctx.sun_at_point(x, normal, field, s)];
        ctx.lambertian_at_point(x, normal, field, &panes, &mut acc);
        acc
    };
    let mut lights = ctx.gather(1, &emission, &on_patch, &on_point);
    let Some(light) = lights.pop() else {
        unreachable!("one bin");
    };
    light
}

impl Ctx<'_> {
    /// Mean illuminance (lux per lux of direct normal illuminance) on a receiving patch from
    /// the sun in direction `s` through the clear windows: the window's projection along `s`
    /// cut out of the patch, and the shadows on that part integrated.
    fn sun_on_patch(&self, p: &Patch, ignore: Option<usize>, s: Vec3) -> f64 {
        let corners = &p.polygon.vertices;
        let cx = p.normal.dot(s);
        if cx.is_nan() || cx <= 0.0 || p.area <= 0.0 || corners.is_empty() {
            return 0.0;
        }
        let o = corners[0];
        let mut lit = 0.0;
        for a in self.apertures.iter().filter(|a| !a.diffusing) {
            for (window, nw, pw) in &a.faces {
                let cw = -nw.dot(s);
                let t = if cw > 0.0 {
                    self.transmittance(a.window, cw)
                } else {
                    0.0
                };
                if t.is_nan() || t <= 0.0 {
                    continue;
                }
                // The part of the window in front of the patch's plane, projected onto it
                // along the sun's direction, counter-clockwise about its normal.
                let front = clip(window, o, p.normal);
                if front.len() < 3 {
                    continue;
                }
                let mut shadow: Vec<Vec3> = front
                    .iter()
                    .map(|&y| y - s * (p.normal.dot(y - o) / cx))
                    .collect();
                if doubled_vector_area(&shadow).dot(p.normal) < 0.0 {
                    shadow.reverse();
                }
                let mut part = corners.clone();
                for k in 0..shadow.len() {
                    let (a, b) = (shadow[k], shadow[(k + 1) % shadow.len()]);
                    let inward = p.normal.cross(b - a);
                    if inward.length() > 0.0 {
                        part = clip(&part, a, inward);
                    }
                    if part.len() < 3 {
                        break;
                    }
                }
                let whole = area(&part);
                if whole.is_nan() || whole <= 0.0 {
                    continue;
                }
                let ignore: Vec<usize> = ignore.into_iter().chain([*pw]).collect();
                let shaft = self.occluders.shaft(window, *nw, &part, p.normal, &ignore);
                let seen = if shaft.is_clear() && !self.outside.has_obstructions() && s.z >= 0.0 {
                    whole
                } else {
                    let lit = |x: Vec3| {
                        let y = x + s * (nw.dot(window[0] - x) / nw.dot(s));
                        (shaft.is_clear() || self.occluders.visible_in(&shaft, x, y, &ignore))
                            && self.outside.sun_reaches(y, s)
                    };
                    self.lit_area(&part, &lit, 0)
                };
                lit += t * seen;
            }
        }
        cx * lit / p.area
    }

    /// Illuminance (lux per lux of direct normal illuminance) at a point facing `normal`
    /// (within its `field` of view) from the sun in direction `s` through the clear
    /// windows.
    fn sun_at_point(&self, x: Vec3, normal: Vec3, field: FieldOfView, s: Vec3) -> f64 {
        // The receiver's one rule: `cos θ`, or a sensor's response in its place.
        let cx = field.sensitivity(normal.dot(s));
        if cx <= 0.0 {
            return 0.0;
        }
        let mut e = 0.0;
        for a in self.apertures.iter().filter(|a| !a.diffusing) {
            for (window, nw, pw) in &a.faces {
                let cw = -nw.dot(s);
                if cw.is_nan() || cw <= 0.0 {
                    continue;
                }
                let Some(y) = ray_polygon(x, s, window, *nw) else {
                    continue;
                };
                if self.occluders.visible(x, y, &[*pw]) && self.outside.sun_reaches(y, s) {
                    e += self.transmittance(a.window, cw) * cx;
                }
            }
        }
        e
    }

    /// Exitance (lux per lux of direct normal illuminance) of patch `j` of the diffusing
    /// window `a` in the sun `s`: `τ(θ_w) cos θ_w` times its unshaded fraction.
    fn sun_exitance(&self, a: &Aperture, j: usize, s: Vec3) -> f64 {
        let w = &self.scene.patches[j];
        let cw = -w.normal.dot(s);
        if cw.is_nan() || cw <= 0.0 || w.area <= 0.0 {
            return 0.0;
        }
        let unshaded = if self.outside.has_obstructions() {
            let open = |y: Vec3| self.outside.sun_reaches(y, s);
            self.lit_area(&w.polygon.vertices, &open, 0) / w.area
        } else {
            1.0
        };
        self.transmittance(a.window, cw) * cw * unshaded
    }
}
