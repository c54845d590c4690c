//! What a window looks out on: the obstructions, the ground and the sky patches, for a ray
//! leaving a window point in a direction (room frame), and small polygon helpers.

use eigenrad_runtime::sky::patches::SkyPatches;

use crate::formfactor::Occluders;
use crate::geometry::{Aabb, Patch, Polygon, Vec3};
use crate::scene::Scene;

/// Where a ray that leaves a window ends: a sky patch, or an exterior surface (the ground or
/// an obstruction) of the given reflectance.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) enum Seen {
    /// Sky patch `k`, in the patches' order.
    Sky(usize),
    /// The ground or an obstruction, of this diffuse reflectance.
    Exterior(f64),
}

/// One face of an obstruction, for the nearest hit.
struct Face {
    corners: Vec<Vec3>,
    normal: Vec3,
    offset: f64,
    reflectance: f64,
}

/// The world outside the windows.
pub(super) struct Outside {
    /// The obstructions' faces as blockers, with two sentinel faces (ignored) that make the
    /// hierarchy keep every face ([`Outside::new`]); `None` without obstructions.
    occluders: Option<Occluders>,
    /// Indices of the sentinels in `occluders`.
    sentinels: [usize; 2],
    faces: Vec<Face>,
    /// All obstructions have this reflectance: the nearest hit need not be found.
    common_reflectance: Option<f64>,
    /// Length of an exterior ray, m: past every obstruction from every window point.
    reach: f64,
    /// Diffuse reflectance of the ground.
    pub(super) ground: f64,
    /// Compass bearing of the scene's +y, degrees clockwise from true north.
    pub(super) north: f64,
    /// Sine and cosine of `north`.
    turn: (f64, f64),
    pub(super) patches: SkyPatches,
}

impl Outside {
    /// The scene's obstructions, ground and sky; `north` (degrees) and `ground` (reflectance)
    /// from its site.
    pub(super) fn new(scene: &Scene, patches: SkyPatches, north: f64, ground: f64) -> Self {
        let faces: Vec<Face> = scene
            .obstructions
            .iter()
            .flat_map(|o| {
                o.faces.iter().filter_map(move |f| {
                    let v = &f.polygon.vertices;
                    let normal = f.polygon.normal();
                    (v.len() >= 3 && normal.is_finite() && normal.length() > 0.5).then(|| Face {
                        corners: v.clone(),
                        normal,
                        offset: normal.dot(v[0]),
                        reflectance: o.reflectance,
                    })
                })
            })
            .collect();
        let windows: Vec<Vec3> = scene
            .windows
            .iter()
            .flat_map(|w| scene.surfaces[w.surface].patch_range.clone())
            .flat_map(|i| scene.patches[i].polygon.vertices.iter().copied())
            .collect();
        let corners: Vec<Vec3> = faces.iter().flat_map(|f| f.corners.clone()).collect();
        let mut reach = 1.0;
        for &w in &windows {
            for &c in &corners {
                reach = f64::max(reach, 2.0 * (c - w).length());
            }
        }
        let first = faces.first().map(|f| f.reflectance);
        let common_reflectance = first.filter(|r| faces.iter().all(|f| f.reflectance == *r));
        let (occluders, sentinels) = if faces.is_empty() {
            (None, [0, 0])
        } else {
            // The hierarchy leaves out a polygon with no scene corner behind its plane (it
            // could cut no segment between two scene points). Exterior rays end far outside:
            // two faces of a box around every ray's end put corners on both sides of every
            // obstruction's plane, and are themselves ignored.
            let all: Vec<Vec3> = corners.iter().chain(&windows).copied().collect();
            let b = Aabb::of(&all).expanded(2.0 * reach);
            let (lo, hi) = (b.min, b.max);
            let bottom = Polygon::new(vec![
                Vec3::new(lo.x, lo.y, lo.z),
                Vec3::new(lo.x, hi.y, lo.z),
                Vec3::new(hi.x, hi.y, lo.z),
                Vec3::new(hi.x, lo.y, lo.z),
            ]);
            let top = Polygon::new(vec![
                Vec3::new(lo.x, lo.y, hi.z),
                Vec3::new(hi.x, lo.y, hi.z),
                Vec3::new(hi.x, hi.y, hi.z),
                Vec3::new(lo.x, hi.y, hi.z),
            ]);
            let mut list: Vec<Patch> = faces
                .iter()
                .map(|f| Patch::new(Polygon::new(f.corners.clone()), 0))
                .collect();
            let n = list.len();
            list.push(Patch::new(bottom, 0));
            list.push(Patch::new(top, 0));
            (Some(Occluders::new(&list)), [n, n + 1])
        };
        Outside {
            occluders,
            sentinels,
            faces,
            common_reflectance,
            reach,
            ground,
            north,
            turn: north.to_radians().sin_cos(),
            patches,
        }
    }

    /// The obstructions' faces, corners in order (m).
    pub(super) fn faces(&self) -> impl Iterator<Item = &[Vec3]> {
        self.faces.iter().map(|f| f.corners.as_slice())
    }

    /// Are there obstructions at all?
    pub(super) fn has_obstructions(&self) -> bool {
        self.occluders.is_some()
    }

    /// Does an obstruction cut the ray from the window point `y` in the unit direction `d`
    /// (room frame)? `Some(reflectance)` of the nearest one hit.
    pub(super) fn obstruction(&self, y: Vec3, d: Vec3) -> Option<f64> {
        let occluders = self.occluders.as_ref()?;
        if occluders.visible(y, y + d * self.reach, &self.sentinels) {
            return None;
        }
        if let Some(r) = self.common_reflectance {
            return Some(r);
        }
        let mut nearest = (f64::INFINITY, None);
        for f in &self.faces {
            let denom = f.normal.dot(d);
            if denom == 0.0 {
                continue;
            }
            let t = (f.offset - f.normal.dot(y)) / denom;
            if t > 1e-9 * self.reach && t < nearest.0 && inside(&f.corners, f.normal, y + d * t) {
                nearest = (t, Some(f.reflectance));
            }
        }
        // The hierarchy saw a hit: the scan finds it too, barring a graze on an edge, which
        // counts as black.
        nearest.1.or(Some(0.0))
    }

    /// Does the sun in direction `s` reach window point `y`: above the horizon (below it
    /// the ground hides it) and no obstruction in the way?
    pub(super) fn sun_reaches(&self, y: Vec3, s: Vec3) -> bool {
        s.z >= 0.0 && self.obstruction(y, s).is_none()
    }

    /// What the ray from window point `y` in unit direction `d` (room frame, leaving the room)
    /// ends on: an obstruction first, else the ground below the horizon, else a sky patch.
    pub(super) fn seen(&self, y: Vec3, d: Vec3) -> Seen {
        if let Some(r) = self.obstruction(y, d) {
            return Seen::Exterior(r);
        }
        if d.z < 0.0 {
            return Seen::Exterior(self.ground);
        }
        // `crate::daylight::room_to_site`, its sine and cosine computed once.
        let (sin, cos) = self.turn;
        let site = [d.x * cos + d.y * sin, -d.x * sin + d.y * cos, d.z];
        match self
            .patches
            .index([site[0] as f32, site[1] as f32, site[2] as f32])
        {
            Some(k) => Seen::Sky(k),
            // Rounding just below the horizon.
            None => Seen::Exterior(self.ground),
        }
    }
}

/// Is `p` (in the polygon's plane) inside or on the convex polygon `corners` (counter-clockwise
/// about `normal`)?
fn inside(corners: &[Vec3], normal: Vec3, p: Vec3) -> bool {
    let n = corners.len();
    (0..n).all(|k| {
        let (a, b) = (corners[k], corners[(k + 1) % n]);
        normal.cross(b - a).dot(p - a) >= 0.0
    })
}

/// Where the ray from `x` in direction `d` meets the convex polygon `corners` (unit `normal`),
/// if it does at a positive distance: the point, m.
pub(super) fn ray_polygon(x: Vec3, d: Vec3, corners: &[Vec3], normal: Vec3) -> Option<Vec3> {
    let first = *corners.first()?;
    let denom = normal.dot(d);
    if denom == 0.0 {
        return None;
    }
    let t = normal.dot(first - x) / denom;
    if t.is_nan() || t <= 0.0 {
        return None;
    }
    let p = x + d * t;
    inside(corners, normal, p).then_some(p)
}

/// Distance, m, from `x` to the convex polygon `corners` (unit `normal`).
pub(super) fn distance_to_polygon(x: Vec3, corners: &[Vec3], normal: Vec3) -> f64 {
    let Some(&first) = corners.first() else {
        return f64::INFINITY;
    };
    let h = normal.dot(x - first);
    let foot = x - normal * h;
    if inside(corners, normal, foot) {
        return h.abs();
    }
    let n = corners.len();
    (0..n)
        .map(|k| {
            let (a, b) = (corners[k], corners[(k + 1) % n]);
            let e = b - a;
            let t = ((x - a).dot(e) / e.dot(e).max(1e-300)).clamp(0.0, 1.0);
            (x - (a + e * t)).length()
        })
        .fold(f64::INFINITY, f64::min)
}

/// The part of the convex polygon `corners` where `normal · (p − origin) ≥ 0`
/// (Sutherland–Hodgman against one plane).
pub(super) fn clip(corners: &[Vec3], origin: Vec3, normal: Vec3) -> Vec<Vec3> {
    let n = corners.len();
    let mut out = Vec::with_capacity(n + 1);
    for k in 0..n {
        let (a, b) = (corners[k], corners[(k + 1) % n]);
        let (da, db) = (normal.dot(a - origin), normal.dot(b - origin));
        if da >= 0.0 {
            out.push(a);
        }
        if (da > 0.0 && db < 0.0) || (da < 0.0 && db > 0.0) {
            out.push(a + (b - a) * (da / (da - db)));
        }
    }
    out
}

/// Area, m², of a planar polygon.
pub(super) fn area(corners: &[Vec3]) -> f64 {
    if corners.len() < 3 {
        return 0.0;
    }
    0.5 * crate::geometry::doubled_vector_area(corners).length()
}

/// Centroid and largest distance from it to a corner (m) of a cell.
pub(super) fn centre(corners: &[Vec3]) -> (Vec3, f64) {
    let c = corners.iter().fold(Vec3::ZERO, |s, &p| s + p) / corners.len().max(1) as f64;
    let r = corners
        .iter()
        .map(|&p| (p - c).length())
        .fold(0.0, f64::max);
    (c, r)
}
