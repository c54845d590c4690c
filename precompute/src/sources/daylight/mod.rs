//! Daylight through the windows as light sources: the room's direct response to each patch
//! of a discretised sky, to the ground and the obstructions outside, and to the sun
//! (docs/math.md, "Daylight through windows").
//!
//! Everything is photopic and per unit of the quantity that drives it: a sky patch's light is
//! the illuminance (lux) it gives at a uniform luminance of 1 cd/m² over the patch; the
//! exterior's at a luminance of 1 cd/m² of `E_gh / π` times each surface's reflectance; the
//! sun's at a direct normal illuminance of 1 lux. The outputs are laid out as the
//! luminaires' ([`crate::sources::luminaires`]): patches; sensors, zones (area-weighted means
//! over a zone's patches or work-plane receivers), then grid points.
//!
//! # Clear glazing
//!
//! Light keeps its direction. A receiving point `x` (normal `n_x`) gets from sky patch `k`
//!
//! ```text
//! E_k(x) = ∫_window L_k τ(θ_w) V cos θ_x cos θ_w / r² dA
//! ```
//!
//! over the window points `y`: `θ_w` the angle of `y − x` to the window's normal, `V` the
//! room's visibility from `x` to `y`, and the ray continued outside from `y` ending on an
//! obstruction (counted for the exterior with its reflectance), below the horizon (the ground,
//! `site.ground_reflectance`) or in a sky patch (`SkyPatches::index` in the site's frame,
//! turned by `site.north`). The window's patches are integrated by Gauss–Legendre rules
//! (`order` points per side) on cells split while they are large for their distance from
//! `x` (`cell_angle`, `max_depth`), and split again where their points or corners see
//! different sky patches or some points are hidden (the corners catch a patch boundary that
//! runs between the outermost points and the cell's edge), until a cell's apparent size from
//! `x` (its angular diameter times `√cos θ_w`, the square root of its solid angle) is less
//! than `edge_angle` (`edge_depth` at most): the patches' boundaries are resolved to a
//! fraction of `edge_angle`, and cells seen almost edge-on from a point near the window's
//! own plane, which carry little light, are not split for boundaries that crowd there. The ground's edge, the largest jump, is exact: each window patch is first cut
//! along the receiving point's horizontal plane. The sum over the patches of a uniform sky is
//! the smooth form-factor integral, exact to the quadrature's error whatever the patch
//! boundaries do. A receiving patch's value is its mean, by Gauss–Legendre rules
//! (`receiver_order`) on cells of the patch split while they are large for their distance to
//! the nearest window (`receiver_cell_angle`) and the split still moves the integral of the
//! windows' unoccluded light under a uniform sky (exact and cheap: Lambert's contour
//! integral) by more than `receiver_tolerance` of the patch's.
//!
//! The sun is a direction `s`: `E(x) = τ(θ_w) max(0, n_x · s) V(x, s)` where the ray from
//! `x` towards the sun crosses a window, no room surface before it and no obstruction after
//! it. On a patch, the window's projection along `s` onto the patch's plane is cut out of the
//! patch exactly (convex polygon clipping), and so are the shadows inside and outside the room
//! on that lit part: every occluder between the two planes and every obstruction past the
//! window projected along `s`, united and taken out by polygon Booleans (`sunlit`). A
//! quadrature of the lit part, however fine, misses slivers of sun between shadows that none
//! of its points sees.
//!
//! # Diffusing glazing
//!
//! The window's patches emit (as [`ChannelLight::emission`], Lambertian) their transmitted
//! exitance `M(y) = ∫ L τ(θ) cos θ dω` over the exterior hemisphere, averaged over each
//! window patch (sky patches and ground integrated in altitude and azimuth; obstructions by
//! rays); for the sun, `τ(θ_w) cos θ_w` times the window patch's unshaded fraction (the
//! obstructions' shadows on it, exactly as on a receiving patch). Their
//! direct irradiance on receivers is that exitance through the point-to-patch form factor
//! `∫ cos θ_x cos θ_w / (π r²) V dA`, by the same window quadrature, so that
//! [`ChannelLight::external`] of a diffusing window's light is the quadratures' disagreement
//! with the form factors', near 0.
//!
//! The room's own outside walls never shade its windows (only [`Scene::obstructions`] do),
//! and a ray from a window meets an obstruction before the ground: the ground is a plane far
//! below.

use eigenrad_runtime::sky::patches::SkyPatches;
use rayon::prelude::*;

use super::ChannelLight;
use crate::formfactor::{gauss_legendre, Occluders};
use crate::geometry::{Patch, Vec3};
use crate::scene::receivers::{mean_over_points, receivers, Receiver};
use crate::scene::{FieldOfView, Scene};

mod cells;
mod clear;
pub mod direct;
pub mod nodes;
mod outside;
pub mod reflection;
mod sky;
mod sun;
pub mod sun_first;
mod sunlit;
#[cfg(test)]
mod tests;

use cells::{uniform_light, Pane, Viewer, MAX_ORDER};
pub use clear::{clear_sky_on, clear_sun_on};
use outside::{distance_to_polygon, Outside};

/// How finely daylight through the windows is integrated.
#[derive(Clone, Debug)]
pub struct DaylightOptions {
    /// Gauss–Legendre points per side on every cell of a window seen from a receiving point
    /// (1 to 8). Default 3.
    pub order: usize,
    /// A cell of a window seen from a receiving point is split while its diameter exceeds
    /// this times its distance to the point (dimensionless, about the angle in radians it
    /// subtends). Default 0.25: a smooth integrand is integrated to about
    /// `(cell_angle / 2)^(2 order)`, ~4e-6.
    pub cell_angle: f64,
    /// Gauss–Legendre points per side on every cell of a receiving patch (1 to 8). Default 3.
    pub receiver_order: usize,
    /// A cell of a receiving patch is split while its diameter exceeds this times its
    /// smallest distance to the windows (dimensionless). Default 0.5: a patch's mean under a
    /// window is within 2.5e-4 of a fine midpoint rule, a single sky patch's share within
    /// 5.4e-3 of the total (the tests).
    pub receiver_cell_angle: f64,
    /// A cell of a receiving patch, large for its distance to the windows, is split only
    /// while that moves its rule's integral of the windows' light (unoccluded, a uniform sky
    /// through τ = 1: smooth, exact and cheap) by more than this share of the whole patch's
    /// (dimensionless). Default 1e-5. Next to a window's plane, where the light fades to
    /// nothing at the wall, the distance alone would cut the cells to `max_depth`.
    pub receiver_tolerance: f64,
    /// Most times a cell is split for its distance (its finest cells are `4^-max_depth` of
    /// it). Default 4.
    pub max_depth: u32,
    /// A window cell whose points see different sky patches (or some of which are hidden) is
    /// split until its apparent size from the receiving point is less than this angle, rad:
    /// its angular diameter seen face-on, shrinking as `√cos θ_w` with the solid angle seen
    /// obliquely. Default 0.02 (1.1°, a tenth of a Tregenza patch's 12°).
    pub edge_angle: f64,
    /// Most times a window cell is split along an edge (a sky patch's boundary, a
    /// shadow's). Default 8: 1/256 of its side.
    pub edge_depth: u32,
    /// Diffusing windows: each sky patch is integrated over `sky_cells × sky_cells` cells in
    /// altitude and azimuth, the ground over cells of the same size. Default 2.
    pub sky_cells: usize,
}

impl Default for DaylightOptions {
    fn default() -> Self {
        DaylightOptions {
            order: 3,
            cell_angle: 0.25,
            receiver_order: 3,
            receiver_cell_angle: 0.5,
            receiver_tolerance: 1e-5,
            max_depth: 4,
            edge_angle: 0.02,
            edge_depth: 8,
            sky_cells: 2,
        }
    }
}

/// The room's direct response to the sky, patch by patch, and to the exterior surfaces.
#[derive(Clone, Debug, PartialEq)]
pub struct SkyResponse {
    /// The discretisation (its patches are in the site frame; the scene's `site.north` turns
    /// it).
    pub patches: SkyPatches,
    /// One light per sky patch, in the patches' order: the direct illuminance (lux) from that
    /// patch at a uniform luminance of 1 cd/m² over it, seen through the windows, with their
    /// angular transmittance, the room's occlusion and the exterior obstructions.
    pub sky: Vec<ChannelLight>,
    /// The ground and the obstructions: the illuminance (lux) per 1 cd/m² of `E_gh / π`, each
    /// direction that leaves a window downwards (ground, reflectance
    /// `site.ground_reflectance`) or hits an obstruction (its reflectance) counting with that
    /// reflectance. Multiplied by the global horizontal illuminance over π it is the light of
    /// a Lambertian exterior lit by the unobstructed sky and sun (as Radiance's `gensky`
    /// ground glow): obstructions' shadows on the ground, their own shading and
    /// interreflection outside are left out.
    pub exterior: ChannelLight,
}

/// The room's direct response to every patch of `patches` and to the exterior
/// ([`SkyResponse`]), through the scene's windows with their glazing's angular
/// transmittance. `occluders` are the room's (as the luminaires get them); the obstructions'
/// are built here.
///
/// # Panics
///
/// Without a site (`scene.site`: north and the ground's reflectance are needed), or in a scene
/// of more than one band (daylight is photopic).
pub fn sky_response(
    scene: &Scene,
    occluders: &Occluders,
    patches: SkyPatches,
    opts: &DaylightOptions,
) -> SkyResponse {
    sky::response(scene, occluders, patches, opts, &glazing(scene))
}

/// The direct sun from `direction` (unit vector towards the sun, room frame) at a direct
/// normal illuminance of 1 lux: a sun patch on every receiver it reaches through the windows
/// (glazing transmittance at the window's incidence angle, occlusion inside, obstructions
/// outside); a diffusing window emits what it transmits. A sun below the horizon
/// (`direction.z < 0`) is hidden by the ground: no light. Needs no site.
///
/// # Panics
///
/// In a scene of more than one band, or for a direction that is not a unit vector (to 1e-6).
pub fn sun_light(
    scene: &Scene,
    occluders: &Occluders,
    direction: Vec3,
    opts: &DaylightOptions,
) -> ChannelLight {
    sun::light(scene, occluders, direction, opts, &glazing(scene))
}

/// One moment's sky as the room's light sources see it: every sky patch's luminance, the
/// exterior's and the sun's.
#[derive(Clone, Copy, Debug)]
pub struct SkyMoment<'a> {
    /// The sky's patches (site frame).
    pub patches: SkyPatches,
    /// Each patch's centre luminance, cd/m², in the patches' order.
    pub luminances: &'a [f64],
    /// Global horizontal illuminance of the unobstructed sky and sun, lux: the exterior
    /// glows at `E_gh / π` cd/m².
    pub global_horizontal_lux: f64,
    /// Direct normal illuminance of the sun, lux (0: no sun).
    pub direct_normal_lux: f64,
    /// Unit vector towards the sun, room frame.
    pub toward_sun: Vec3,
}

/// The daylight of one moment through the scene's windows, as one light (emission of
/// diffusing windows, direct illuminance everywhere): each sky patch's response times its
/// centre luminance, the exterior's times `E_gh / π`, the sun's times its direct normal
/// illuminance. `solve --time` and `render --time` light the room with it.
///
/// # Panics
///
/// As [`sky_response`]: without a site, or in a scene of more than one band.
pub fn moment_light(
    scene: &Scene,
    occluders: &Occluders,
    moment: &SkyMoment<'_>,
    opts: &DaylightOptions,
) -> ChannelLight {
    let response = sky_response(scene, occluders, moment.patches, opts);
    let mut light = response
        .exterior
        .scaled(moment.global_horizontal_lux / std::f64::consts::PI);
    for (luminance, response) in moment.luminances.iter().zip(&response.sky) {
        light.add_scaled(response, *luminance);
    }
    if moment.direct_normal_lux > 0.0 {
        let sun = sun_light(scene, occluders, moment.toward_sun, opts);
        light.add_scaled(&sun, moment.direct_normal_lux);
    }
    light
}

/// Transmittance of window `w` (index into [`Scene::windows`]) at incidence angle `theta`
/// (rad): the glazing's, or a test's.
pub(crate) type Transmittance<'a> = dyn Fn(usize, f64) -> f64 + Sync + 'a;

/// The scene's glazings as a [`Transmittance`].
fn glazing(scene: &Scene) -> impl Fn(usize, f64) -> f64 + Sync + '_ {
    |w, theta| f64::from(scene.windows[w].glazing.transmittance(theta as f32))
}

/// One window as the quadratures see it.
struct Aperture {
    /// Index into [`Scene::windows`].
    window: usize,
    diffusing: bool,
    /// Its patches (indices into [`Scene::patches`]).
    patches: Vec<usize>,
    /// Its faces: corners, unit normal into the room, and one of its patches (ignoring a
    /// patch ignores its face).
    faces: Vec<(Vec<Vec3>, Vec3, usize)>,
}

/// What every daylight quadrature needs.
pub(super) struct Ctx<'a> {
    scene: &'a Scene,
    occluders: &'a Occluders,
    outside: Outside,
    opts: &'a DaylightOptions,
    /// Gauss–Legendre rules on [0, 1]: on window cells, and on receiving patches' cells.
    gl: Vec<(f64, f64)>,
    gl_receiver: Vec<(f64, f64)>,
    apertures: Vec<Aperture>,
    tau: &'a Transmittance<'a>,
    /// τ of every window tabulated at [`TAU_STEPS`] + 1 equal steps of `cos θ` from 0 to 1,
    /// for the sky's many evaluations.
    tau_table: Vec<Vec<f64>>,
    /// The scene's patches that receive light (`None`: all); with it, the clear windows'
    /// light alone ([`clear_sky_on`]).
    receiving: Option<&'a [bool]>,
}

/// Steps of the transmittance table in `cos θ`. Linear interpolation between them departs
/// from the clear glass model by less than 1e-5 (9.5e-6 at grazing incidence, the tests).
const TAU_STEPS: usize = 4096;

/// A point or patch this close to a plane (m) is in it.
const PLANE_TOLERANCE: f64 = 1e-9;

impl<'a> Ctx<'a> {
    fn new(
        scene: &'a Scene,
        occluders: &'a Occluders,
        outside: Outside,
        opts: &'a DaylightOptions,
        tau: &'a Transmittance<'a>,
    ) -> Self {
        assert!(
            scene.windows.is_empty() || scene.bands.count() == 1,
            "daylight in a scene of {} bands",
            scene.bands.count()
        );
        let apertures = scene
            .windows
            .iter()
            .enumerate()
            .map(|(w, window)| {
                let range = scene.surfaces[window.surface].patch_range.clone();
                let faces = scene
                    .faces
                    .iter()
                    .filter(|f| range.contains(&f.patches.start))
                    .map(|f| {
                        let p = f.patches.start;
                        (f.polygon.vertices.clone(), scene.patches[p].normal, p)
                    })
                    .collect();
                Aperture {
                    window: w,
                    diffusing: window.glazing.is_diffusing(),
                    patches: range.collect(),
                    faces,
                }
            })
            .collect();
        let tau_table = (0..scene.windows.len())
            .map(|w| {
                (0..=TAU_STEPS)
                    .map(|i| tau(w, (i as f64 / TAU_STEPS as f64).acos()))
                    .collect()
            })
            .collect();
        Ctx {
            tau_table,
            scene,
            occluders,
            outside,
            opts,
            gl: gauss_legendre(opts.order.clamp(1, MAX_ORDER)),
            gl_receiver: gauss_legendre(opts.receiver_order.clamp(1, MAX_ORDER)),
            apertures,
            tau,
            receiving: None,
        }
    }

    /// This context lighting only the patches `receiving` marks (`None`: all), from the clear
    /// windows alone when given: the diffusing windows' light is their patches' emission.
    fn receiving(mut self, receiving: Option<&'a [bool]>) -> Self {
        if receiving.is_some() {
            self.apertures.retain(|a| !a.diffusing);
        }
        self.receiving = receiving;
        self
    }

    /// Whether patch `i` of the scene receives light (every receiver that is no patch does).
    fn receives(&self, i: Option<usize>) -> bool {
        match (self.receiving, i) {
            (Some(marks), Some(i)) => marks.get(i).copied().unwrap_or(false),
            _ => true,
        }
    }

    /// τ of window `w` at the incidence cosine `cos`.
    fn transmittance(&self, w: usize, cos: f64) -> f64 {
        (self.tau)(w, cos.clamp(-1.0, 1.0).acos())
    }

    /// [`Ctx::transmittance`] interpolated in its table (within 1e-5 of it).
    fn tabulated(&self, w: usize, cos: f64) -> f64 {
        let Some(table) = self.tau_table.get(w) else {
            return 0.0;
        };
        let at = cos.clamp(0.0, 1.0) * TAU_STEPS as f64;
        let i = (at as usize).min(TAU_STEPS - 1);
        let f = at - i as f64;
        table[i] * (1.0 - f) + table[i + 1] * f
    }

    /// Distance, m, from `x` to the nearest window of the given kind.
    fn near(&self, x: Vec3, diffusing: bool) -> f64 {
        self.apertures
            .iter()
            .filter(|a| a.diffusing == diffusing)
            .flat_map(|a| &a.faces)
            .map(|(c, n, _)| distance_to_polygon(x, c, *n))
            .fold(f64::INFINITY, f64::min)
    }

    /// The diffusing windows' patches with their exitance per bin (lux), from `exitance`.
    fn diffusing_panes(
        &self,
        exitance: impl Fn(&Aperture, usize) -> Vec<f64> + Sync,
    ) -> Vec<(usize, Vec<f64>)> {
        self.apertures
            .iter()
            .filter(|a| a.diffusing)
            .flat_map(|a| a.patches.iter().map(move |&j| (a, j)))
            .collect::<Vec<_>>()
            .par_iter()
            .map(|&(a, j)| (j, exitance(a, j)))
            .collect()
    }

    /// Adds the direct irradiance of the Lambertian `panes` (patch, exitance per bin) on a
    /// receiving patch (its mean) into `acc`; `ignore` is the patch itself when it is one of
    /// the scene's.
    fn lambertian_on_patch(
        &self,
        p: &Patch,
        ignore: Option<usize>,
        panes: &[(usize, Vec<f64>)],
        acc: &mut [f64],
    ) {
        let corners = &p.polygon.vertices;
        for (j, exitance) in panes {
            let w = &self.scene.patches[*j];
            if !facing(p, w) {
                continue;
            }
            let ignore: Vec<usize> = ignore.into_iter().chain([*j]).collect();
            let pane = Pane {
                corners: &w.polygon.vertices,
                normal: w.normal,
            };
            let shaft = self
                .occluders
                .shaft(pane.corners, pane.normal, corners, p.normal, &ignore);
            let mut f = [0.0];
            let near = |x: Vec3| distance_to_polygon(x, pane.corners, pane.normal);
            let light = |x: Vec3| uniform_light([pane].into_iter(), x, p.normal);
            self.over_cells(corners, &near, &light, &mut |x, weight| {
                let v = Viewer {
                    x,
                    normal: p.normal,
                    field: FieldOfView::HEMISPHERE,
                    ignore: &ignore,
                };
                let lambert = |_: Vec3, _: Vec3, _: f64| Some((0, std::f64::consts::FRAC_1_PI));
                self.window_pane(v, &shaft, pane, &lambert, weight, &mut f);
            });
            for (a, e) in acc.iter_mut().zip(exitance) {
                *a += f[0] / p.area * e;
            }
        }
    }

    /// [`Ctx::lambertian_on_patch`] at a point facing `normal`, within its `field`
    /// of view.
    fn lambertian_at_point(
        &self,
        x: Vec3,
        normal: Vec3,
        field: FieldOfView,
        panes: &[(usize, Vec<f64>)],
        acc: &mut [f64],
    ) {
        for (j, exitance) in panes {
            let lambert = |_: Vec3, _: Vec3, _: f64| Some((0, std::f64::consts::FRAC_1_PI));
            let mut f = [0.0];
            self.window_patch_at_point(*j, x, normal, field, &lambert, 1.0, &mut f);
            for (a, e) in acc.iter_mut().zip(exitance) {
                *a += f[0] * e;
            }
        }
    }

    /// One light per bin from what every receiver gets: `on_patch(patch, ignore)` (the mean
    /// irradiance per bin on a scene patch or a work-plane receiver), `on_point(x, normal,
    /// field)` (at a sensor or grid point), and the `emission` of every patch per bin.
    fn gather(
        &self,
        bins: usize,
        emission: &[Vec<f64>],
        on_patch: &(dyn Fn(&Patch, Option<usize>) -> Vec<f64> + Sync),
        on_point: &(dyn Fn(Vec3, Vec3, FieldOfView) -> Vec<f64> + Sync),
    ) -> Vec<ChannelLight> {
        let scene = self.scene;
        let patches: Vec<Vec<f64>> = scene
            .patches
            .par_iter()
            .enumerate()
            .map(|(i, p)| {
                if self.receives(Some(i)) {
                    on_patch(p, Some(i))
                } else {
                    vec![0.0; bins]
                }
            })
            .collect();
        let mean = |members: Vec<(f64, Vec<f64>)>, area: f64| {
            let mut mean = vec![0.0; bins];
            for (a, e) in members {
                for (m, v) in mean.iter_mut().zip(e) {
                    *m += a * v / area;
                }
            }
            mean
        };
        let all: Vec<Receiver> = receivers(scene).collect();
        let outputs: Vec<Vec<f64>> = all
            .par_iter()
            .map(|receiver| match *receiver {
                Receiver::Point {
                    position,
                    normal,
                    field,
                } => on_point(position, normal, field),
                Receiver::Surfaces(list) => mean(
                    list.iter()
                        .map(|&i| (scene.patches[i].area, patches[i].clone()))
                        .collect(),
                    list.iter().map(|&i| scene.patches[i].area).sum(),
                ),
                Receiver::Points(points) => mean_over_points(points, bins, |position, normal| {
                    on_point(position, normal, FieldOfView::HEMISPHERE)
                }),
                // Receivers do not block light: nothing to ignore.
                Receiver::Plane(receivers) => mean(
                    receivers
                        .par_iter()
                        .map(|r| (r.area, on_patch(r, None)))
                        .collect(),
                    receivers.iter().map(|r| r.area).sum(),
                ),
            })
            .collect();
        (0..bins)
            .map(|b| ChannelLight {
                emission: vec![emission.iter().map(|e| e[b]).collect()],
                patch_irradiance: vec![patches.iter().map(|e| e[b]).collect()],
                output_irradiance: vec![outputs.iter().map(|e| e[b]).collect()],
            })
            .collect()
    }
}

/// Can light pass from the window patch `w` to the receiving patch `p`: some corner of each
/// strictly in front of the other's plane?
fn facing(p: &Patch, w: &Patch) -> bool {
    let front = |of: &Patch, corners: &[Vec3]| {
        let o = of.polygon.vertices[0];
        corners
            .iter()
            .any(|&c| of.normal.dot(c - o) > PLANE_TOLERANCE)
    };
    !p.polygon.vertices.is_empty()
        && !w.polygon.vertices.is_empty()
        && p.area > 0.0
        && front(p, &w.polygon.vertices)
        && front(w, &p.polygon.vertices)
}
