//! What a basis stores for the controller to compute the direct sun at its point receivers
//! itself (docs/format.md, "Direct sun"; `eigenrad_runtime::sky::direct`): the clear
//! windows' faces with their glazing's transmittance, the room's faces and the exterior
//! obstructions' faces that shade some receiver from the sun through a window, and each
//! sensor's weighting. The rule is the one [`super::sun_light`] applies at a point.

use eigenrad_runtime::sky::direct::{GLAZING_STEPS, MAX_POLYGON_VERTICES};
use eigenrad_runtime::sky::sun_grid::direction_of;
use rayon::prelude::*;

use super::nodes::{room_sun, MAX_DECLINATION};
use crate::geometry::Vec3;
use crate::scene::receivers::{receivers, Receiver};
use crate::scene::{Scene, Site};

/// Degrees between the sun directions the occluders are culled with, in declination and in
/// hour angle: an occluder that shades no receiver at any of them is left out. A face
/// shading a receiver only within a sliver of sun directions narrower than this may be
/// missed; the between-nodes check measures what that costs (docs/accuracy.md).
pub const CULLING_STEP_DEG: f64 = 0.5;

/// Part of the distance to a window within which a room face is taken to lie in the
/// window's plane, as the controller's `PLANE_MARGIN`.
const PLANE_MARGIN: f64 = 1.0e-4;

/// The direct sun's tables, as [`eigenrad_runtime::writer::BasisTables`] holds them.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct DirectSunTables {
    /// Window faces, room occluders, exterior occluders.
    pub counts: [u32; 3],
    /// Each polygon's vertex count, windows first.
    pub sizes: Vec<u8>,
    /// Per polygon: unit normal (a window's into the room), then its vertices, m.
    pub polygons: Vec<f64>,
    /// `W × 65`: each window face's transmittance at incidence cosines `k / 64`.
    pub glazing: Vec<f64>,
    /// Rows of each sensor's response, 0 for a cone or hemisphere.
    pub sensor_rows: Vec<u32>,
    /// (polar angle in rad, sensitivity) pairs, sensor by sensor.
    pub sensor_response: Vec<f64>,
}

/// Per receiver, which room faces and which exterior faces cut one of its rays.
type Hits = (Vec<bool>, Vec<bool>);

/// A convex polygon with its unit normal.
struct Polygon {
    corners: Vec<Vec3>,
    normal: Vec3,
}

/// The direct sun's tables of `scene` at `site`: its clear windows' faces, and the room and
/// exterior faces that cut the ray from some sensor or grid point towards some sun
/// direction of the year through a window (sampled every [`CULLING_STEP_DEG`]), or from
/// some of `patch_points` (the sample points of the sun's first reflection,
/// [`super::sun_first`]) towards some of `patch_suns`.
pub fn direct_sun_tables(
    scene: &Scene,
    site: &Site,
    patch_points: &[Vec3],
    patch_suns: &[Vec3],
) -> DirectSunTables {
    let window_surfaces: Vec<usize> = scene.windows.iter().map(|w| w.surface).collect();
    let mut windows = Vec::new();
    let mut glazing = Vec::new();
    for window in scene.windows.iter().filter(|w| !w.glazing.is_diffusing()) {
        let range = scene.surfaces[window.surface].patch_range.clone();
        for face in scene
            .faces
            .iter()
            .filter(|f| range.contains(&f.patches.start))
        {
            windows.push(Polygon {
                corners: face.polygon.vertices.clone(),
                normal: scene.patches[face.patches.start].normal,
            });
            glazing.extend((0..=GLAZING_STEPS).map(|k| {
                let cos = k as f64 / GLAZING_STEPS as f64;
                f64::from(window.glazing.transmittance(cos.acos() as f32))
            }));
        }
    }
    let in_window = |start: usize| {
        window_surfaces
            .iter()
            .any(|&s| scene.surfaces[s].patch_range.contains(&start))
    };
    let room: Vec<Polygon> = scene
        .faces
        .iter()
        .filter(|f| !in_window(f.patches.start))
        .map(|f| Polygon {
            corners: f.polygon.vertices.clone(),
            normal: f.polygon.normal(),
        })
        .collect();
    let exterior: Vec<Polygon> = scene
        .obstructions
        .iter()
        .flat_map(|o| &o.faces)
        .map(|f| Polygon {
            corners: f.polygon.vertices.clone(),
            normal: f.polygon.normal(),
        })
        .collect();
    let points: Vec<Vec3> = receivers(scene)
        .filter_map(|r| match r {
            Receiver::Point { position, .. } => Some(position),
            _ => None,
        })
        .collect();
    let suns = year_of_suns(site);
    let (mut room_used, mut exterior_used) = culled(&points, &suns, &windows, &room, &exterior);
    let (room_patches, exterior_patches) =
        culled(patch_points, patch_suns, &windows, &room, &exterior);
    for (used, more) in [
        (&mut room_used, room_patches),
        (&mut exterior_used, exterior_patches),
    ] {
        used.extend(more);
        used.sort_unstable();
        used.dedup();
    }
    let mut t = DirectSunTables {
        counts: [
            windows.len() as u32,
            room_used.len() as u32,
            exterior_used.len() as u32,
        ],
        glazing,
        ..DirectSunTables::default()
    };
    let kept = windows
        .iter()
        .chain(room_used.iter().map(|&k| &room[k]))
        .chain(exterior_used.iter().map(|&k| &exterior[k]));
    for p in kept {
        // Faces are meshed into far fewer corners than the format's limit.
        let size = p.corners.len().min(usize::from(MAX_POLYGON_VERTICES));
        t.sizes.push(size as u8);
        t.polygons.extend(p.normal.to_array());
        for c in &p.corners[..size] {
            t.polygons.extend(c.to_array());
        }
    }
    for s in &scene.sensors {
        let rows: Vec<(f64, f64)> = s
            .response
            .as_ref()
            .map_or(Vec::new(), |r| r.rows().collect());
        t.sensor_rows.push(rows.len() as u32);
        t.sensor_response
            .extend(rows.iter().flat_map(|&(angle, value)| [angle, value]));
    }
    t
}

/// Unit sun directions (room frame) above the horizon over the year at `site`, every
/// [`CULLING_STEP_DEG`] of declination and hour angle.
fn year_of_suns(site: &Site) -> Vec<Vec3> {
    let rows = (2.0 * MAX_DECLINATION / CULLING_STEP_DEG).ceil() as usize;
    let columns = (360.0 / CULLING_STEP_DEG).ceil() as usize;
    let latitude = site.location.latitude as f32;
    (0..=rows)
        .flat_map(|r| (0..columns).map(move |c| (r, c)))
        .filter_map(|(r, c)| {
            let declination = -MAX_DECLINATION + 2.0 * MAX_DECLINATION * r as f64 / rows as f64;
            let hour = -180.0 + CULLING_STEP_DEG * c as f64;
            room_sun(
                site,
                direction_of(latitude, declination as f32, hour as f32),
            )
        })
        .collect()
}

/// The room and exterior faces (indices, ascending) that cut some ray from `points` towards
/// `suns` through a window: a room face before the window, an exterior one past it.
fn culled(
    points: &[Vec3],
    suns: &[Vec3],
    windows: &[Polygon],
    room: &[Polygon],
    exterior: &[Polygon],
) -> (Vec<usize>, Vec<usize>) {
    let hits: Vec<Hits> = points
        .par_iter()
        .map(|&x| {
            let mut room_hit = vec![false; room.len()];
            let mut exterior_hit = vec![false; exterior.len()];
            for &s in suns {
                for w in windows {
                    if w.normal.dot(s) >= 0.0 {
                        continue;
                    }
                    let Some(distance) = crossing(w, x, s).filter(|&t| t > 0.0) else {
                        continue;
                    };
                    for (hit, f) in room_hit.iter_mut().zip(room) {
                        *hit = *hit
                            || crossing(f, x, s).is_some_and(|t| {
                                t > PLANE_MARGIN * distance && t < distance * (1.0 - PLANE_MARGIN)
                            });
                    }
                    for (hit, f) in exterior_hit.iter_mut().zip(exterior) {
                        *hit = *hit
                            || crossing(f, x, s)
                                .is_some_and(|t| t > distance * (1.0 + PLANE_MARGIN));
                    }
                }
            }
            (room_hit, exterior_hit)
        })
        .collect();
    let used = |pick: &dyn Fn(&Hits) -> &Vec<bool>, len: usize| {
        (0..len)
            .filter(|&k| hits.iter().any(|h| pick(h)[k]))
            .collect::<Vec<usize>>()
    };
    (used(&|h| &h.0, room.len()), used(&|h| &h.1, exterior.len()))
}

/// Where the line `x + t s` crosses the convex polygon `p` inside it: `Some(t)` (m, of either
/// sign), `None` when it misses or runs parallel to its plane.
fn crossing(p: &Polygon, x: Vec3, s: Vec3) -> Option<f64> {
    let first = *p.corners.first()?;
    let along = p.normal.dot(s);
    if along == 0.0 {
        return None;
    }
    let t = p.normal.dot(first - x) / along;
    let y = x + s * t;
    let n = p.corners.len();
    let sign = |k: usize| {
        let (a, b) = (p.corners[k], p.corners[(k + 1) % n]);
        p.normal.cross(b - a).dot(y - a)
    };
    let inside = (0..n).all(|k| sign(k) >= 0.0) || (0..n).all(|k| sign(k) <= 0.0);
    (inside && t.is_finite()).then_some(t)
}
