//! The direct sun through the windows: the sun patch on every receiver (clear glazing), the
//! exitance of diffusing windows.

use eigenrad_runtime::sky::patches::SkyPatches;

use super::outside::{area, clip, ray_polygon, Outside};
use super::sunlit::{along_sun, area_outside, shadow};
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
    /// cut out of the patch, less the shadows on that part of the room's occluders and the
    /// obstructions outside, exactly ([`super::sunlit`]).
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
                let mut beam: Vec<Vec3> = front
                    .iter()
                    .map(|&y| along_sun(y, o, p.normal, s))
                    .collect();
                if doubled_vector_area(&beam).dot(p.normal) < 0.0 {
                    beam.reverse();
                }
                let mut part = corners.clone();
                for k in 0..beam.len() {
                    let (a, b) = (beam[k], beam[(k + 1) % beam.len()]);
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
                let seen = if s.z < 0.0 {
                    // The ground hides the sun.
                    0.0
                } else {
                    let ignore: Vec<usize> = ignore.into_iter().chain([*pw]).collect();
                    let w0 = window[0];
                    // The room's occluders between the patch's plane and the window's, the
                    // obstructions past the window's.
                    let in_room = [(o, p.normal), (w0, *nw)];
                    let outdoors = [(o, p.normal), past_the_pane(w0, *nw)];
                    let room = self
                        .occluders
                        .shaft_outlines_all(window, *nw, &part, p.normal, &ignore)
                        .into_iter()
                        .filter_map(|c| shadow(c, &in_room, o, p.normal, s));
                    let exterior = self
                        .outside
                        .faces()
                        .filter_map(|c| shadow(c, &outdoors, o, p.normal, s));
                    let dark: Vec<Vec<Vec3>> = room.chain(exterior).collect();
                    if dark.is_empty() {
                        whole
                    } else {
                        area_outside(&part, p.normal, &dark)
                    }
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
            let corners = &w.polygon.vertices;
            let outdoors = [past_the_pane(corners[0], w.normal)];
            let dark: Vec<Vec<Vec3>> = self
                .outside
                .faces()
                .filter_map(|c| shadow(c, &outdoors, corners[0], w.normal, s))
                .collect();
            area_outside(corners, w.normal, &dark) / w.area
        } else {
            1.0
        };
        self.transmittance(a.window, cw) * cw * unshaded
    }
}

/// The side of a pane's plane (a corner `corner`, `normal` into the room) past it, as a plane
/// [`shadow`] keeps: strictly, so that a face in the pane's own plane (which a ray leaving the
/// pane does not cross) casts nothing.
fn past_the_pane(corner: Vec3, normal: Vec3) -> (Vec3, Vec3) {
    (corner - normal * 1e-9, -normal)
}
