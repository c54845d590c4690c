//! The daylight a basis carries: one light per node, each per unit of what drives it
//! (docs/math.md, "Daylight in the basis"). The nodes are every patch of the sky (per cd/m²),
//! the exterior (per cd/m² of `E_gh/π`) and the sun at the nodes of a grid in declination and
//! hour angle that light the room (per lux of direct normal illuminance). Daylight is linear
//! in them: the runtime weighs the nodes by a sky state's luminances, illuminance and sun.

use eigenrad_runtime::sky::patches::SkyPatches;
use eigenrad_runtime::sky::sun_grid::SunGrid;
use rayon::prelude::*;

use super::{sky_response, sun_light, DaylightOptions, SkyResponse};
use crate::formfactor::Occluders;
use crate::geometry::Vec3;
use crate::scene::{Scene, Site};
use crate::sources::ChannelLight;

/// The sun's largest declination, degrees: the obliquity of the ecliptic (23.44° in this
/// century, falling by 0.013° a century).
pub const MAX_DECLINATION: f64 = 23.44;

/// The sun grid's default spacing, degrees of declination and of hour angle: 5.86° (nine
/// declinations from −23.44° to 23.44°, about three weeks of the sun's travel near the
/// equinoxes) by 7.5° (half an hour). On the example daylight office the zones read the sun
/// between nodes within 2.8 % of their sunlight on average over the sun's positions, 14 %
/// at the 95th percentile, for 101 KB of flash; halving both steps halves the errors and
/// costs about three times the bytes (docs/accuracy.md, "Daylight in the basis").
pub const DEFAULT_SUN_STEP: [f64; 2] = [2.0 * MAX_DECLINATION / 8.0, 7.5];

/// The room's direct light from every daylight node, in the basis' order.
#[derive(Clone, Debug)]
pub struct DaylightNodes {
    /// The sky's patches (site frame).
    pub patches: SkyPatches,
    /// The sun grid of the site.
    pub sun_grid: SunGrid,
    /// The grid's nodes that light the room (`row · columns + column`), ascending.
    pub sun_nodes: Vec<u32>,
    /// One light per node: the sky's patches (per cd/m²), the exterior (per cd/m² of
    /// `E_gh/π`), the sun at each of `sun_nodes` (per lux of direct normal illuminance).
    pub lights: Vec<ChannelLight>,
}

impl DaylightNodes {
    /// `D`: the number of nodes.
    pub fn len(&self) -> usize {
        self.lights.len()
    }

    /// Whether there is no node (never, for nodes of a scene with a site).
    pub fn is_empty(&self) -> bool {
        self.lights.is_empty()
    }
}

/// The sun grid of a site with about `step` degrees between declinations and between hour
/// angles (`[declination, hour angle]`), each step shortened to divide its span evenly: the
/// declinations from −[`MAX_DECLINATION`] to +[`MAX_DECLINATION`], the hour angles over the
/// whole day (−180° to 180°). Steps must be positive (the build's options check them).
pub fn sun_grid(site: &Site, step: [f64; 2]) -> SunGrid {
    let span = 2.0 * MAX_DECLINATION;
    let intervals = |span: f64, step: f64| ((span / step).ceil() as usize).max(1);
    let (rows, columns) = (intervals(span, step[0]), intervals(360.0, step[1]));
    SunGrid {
        latitude: site.location.latitude as f32,
        declination_first: -MAX_DECLINATION as f32,
        declination_step: (span / rows as f64) as f32,
        rows: rows + 1,
        hour_first: -180.0,
        hour_step: (360.0 / columns as f64) as f32,
        columns: columns + 1,
    }
}

/// The sun of node direction `site_direction` (site frame) in the room's frame, normalised
/// in `f64`; `None` below the horizon.
pub fn room_sun(site: &Site, site_direction: [f32; 3]) -> Option<Vec3> {
    let d = site_direction.map(f64::from);
    let norm = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
    let [x, y, z] = crate::daylight::site_to_room(d.map(|x| x / norm), site.north);
    (z > 0.0).then(|| Vec3::new(x, y, z))
}

/// Every daylight node of `scene` (which has a site), its sky in `patches`, its sun grid
/// stepped by `sun_step` ([`sun_grid`]).
///
/// # Panics
///
/// Without a site, or in a scene of more than one band (as [`sky_response`]).
pub fn nodes(
    scene: &Scene,
    occluders: &Occluders,
    patches: SkyPatches,
    sun_step: [f64; 2],
    opts: &DaylightOptions,
) -> DaylightNodes {
    let sky = sky_response(scene, occluders, patches, opts);
    nodes_with_sky(scene, occluders, sky, sun_step, opts)
}

/// Every daylight node of `scene` (which has a site), its sky's response `sky` already
/// computed (as [`sky_response`] gives it), its sun grid stepped by `sun_step`.
///
/// # Panics
///
/// As [`nodes`].
pub fn nodes_with_sky(
    scene: &Scene,
    occluders: &Occluders,
    sky: SkyResponse,
    sun_step: [f64; 2],
    opts: &DaylightOptions,
) -> DaylightNodes {
    let site = scene
        .site
        .as_ref()
        .expect("daylight nodes need the scene's site");
    let patches = sky.patches;
    let grid = sun_grid(site, sun_step);
    let suns: Vec<(u32, ChannelLight)> = (0..grid.len())
        .into_par_iter()
        .filter_map(|node| {
            let sun = room_sun(site, grid.direction(node)?)?;
            let light = sun_light(scene, occluders, sun, opts);
            lights_something(&light).then_some((node as u32, light))
        })
        .collect();
    let mut lights = sky.sky;
    lights.push(sky.exterior);
    let sun_nodes = suns.iter().map(|(node, _)| *node).collect();
    lights.extend(suns.into_iter().map(|(_, light)| light));
    DaylightNodes {
        patches,
        sun_grid: grid,
        sun_nodes,
        lights,
    }
}

/// Whether a light reaches anything: a patch, an output, or emission.
fn lights_something(light: &ChannelLight) -> bool {
    let any = |x: &[Vec<f64>]| x.iter().flatten().any(|&v| v != 0.0);
    any(&light.emission) || any(&light.patch_irradiance) || any(&light.output_irradiance)
}
