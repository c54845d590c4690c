//! The receivers of a scene, the one enumeration every light path walks: the sensors, then
//! the zones, then every calculation-grid point, in the order of a basis' outputs. The form
//! factors, the luminaires' direct light and the daylight each say what one receiver gets;
//! the order, and what a sensor sees, are decided here.

use super::response::Response;
use rayon::prelude::*;

use super::{Scene, ZoneKind};
use crate::geometry::{Patch, Vec3};

/// The directions a point receiver takes light from and how much each counts: the front
/// hemisphere of its normal, a cone of half-angle `α` around it, or a photosensor's angular
/// response ([`Response`]). [`FieldOfView::sensitivity`] is the one rule every light path
/// asks.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FieldOfView<'r> {
    /// `α`, radians; `None`: the whole front hemisphere.
    half_angle: Option<f64>,
    /// `cos α`, computed once: the quadratures test it at every sample.
    cos_half_angle: Option<f64>,
    /// A sensor's relative sensitivity over polar angle, in place of the cosine.
    response: Option<&'r Response>,
}

impl<'r> FieldOfView<'r> {
    /// The whole front hemisphere (grid points, an unshielded sensor).
    pub const HEMISPHERE: FieldOfView<'static> = FieldOfView {
        half_angle: None,
        cos_half_angle: None,
        response: None,
    };

    /// A cone of `half_angle` radians around the normal; `None` is the hemisphere.
    pub fn cone(half_angle: Option<f64>) -> FieldOfView<'static> {
        FieldOfView {
            half_angle,
            cos_half_angle: half_angle.map(f64::cos),
            response: None,
        }
    }

    /// A photosensor reading `∫ L S(θ) dω` with the relative sensitivity `response`.
    pub fn response(response: &'r Response) -> FieldOfView<'r> {
        FieldOfView {
            half_angle: None,
            cos_half_angle: None,
            response: Some(response),
        }
    }

    /// The cone's half-angle, radians, as the scene gives it; `None` for the hemisphere and
    /// for a response.
    pub fn half_angle(&self) -> Option<f64> {
        self.half_angle
    }

    /// `cos α`: a direction at a smaller cosine to the normal is outside; `None` for the
    /// hemisphere.
    pub fn cos_half_angle(&self) -> Option<f64> {
        self.cos_half_angle
    }

    /// The sensor's response, when it has one.
    pub fn table(&self) -> Option<&'r Response> {
        self.response
    }

    /// How much light arriving at cosine `cos` to the normal counts, the factor that stands
    /// where illuminance has `cos θ` (dimensionless): `cos θ` in front of the receiver and
    /// inside its cone, the response `S(θ)` of a sensor that has one, zero elsewhere. NaN
    /// counts nothing: the result is never NaN.
    pub fn sensitivity(&self, cos: f64) -> f64 {
        match self.response {
            Some(r) => r.at_cos(cos),
            None if self.admits(cos) => cos,
            None => 0.0,
        }
    }

    /// Whether light arriving at cosine `cos` to the normal counts at all. NaN never counts.
    pub fn admits(&self, cos: f64) -> bool {
        match self.response {
            Some(r) => r.at_cos(cos) > 0.0,
            None => cos > 0.0 && !self.cos_half_angle.is_some_and(|c| cos < c),
        }
    }
}

/// One receiver: what an output reads.
#[derive(Clone, Copy, Debug)]
pub enum Receiver<'s> {
    /// A point facing a unit normal: a sensor, or a grid point (hemisphere).
    Point {
        /// Position, m.
        position: Vec3,
        /// Unit normal of its face.
        normal: Vec3,
        /// What it sees.
        field: FieldOfView<'s>,
    },
    /// A surface zone: the area-weighted mean over these patches (indices into
    /// [`Scene::patches`]).
    Surfaces(&'s [usize]),
    /// A work plane: the area-weighted mean over its receiving patches, which block no light.
    Plane(&'s [Patch]),
    /// An imported sensor grid's zone: the mean over these points (position in m, unit
    /// normal), each a point receiver over the front hemisphere of its normal, as its grid
    /// points are read ([`grid_points`]).
    Points(&'s [(Vec3, Vec3)]),
}

/// Every receiver of `scene` in output order: the sensors, the zones, then every zone's grid
/// points.
pub fn receivers(scene: &Scene) -> impl Iterator<Item = Receiver<'_>> + '_ {
    let sensors = scene.sensors.iter().map(|s| Receiver::Point {
        position: s.position,
        normal: s.normal,
        field: match &s.response {
            Some(r) => FieldOfView::response(r),
            None => FieldOfView::cone(s.half_angle),
        },
    });
    let zones = scene.zones.iter().map(|z| match &z.kind {
        ZoneKind::Surfaces(list) => Receiver::Surfaces(list),
        ZoneKind::WorkPlane { receivers, .. } => Receiver::Plane(receivers),
        ZoneKind::Points { points, .. } => Receiver::Points(points),
    });
    let points = grid_points(scene).map(|(_, position, normal)| Receiver::Point {
        position,
        normal,
        field: FieldOfView::HEMISPHERE,
    });
    sensors.chain(zones).chain(points)
}

/// The mean over `points` (position, normal) of `read(position, normal)` (`len` values
/// each), what a [`Receiver::Points`] reads; zeros without points. The points are read in
/// parallel and summed in order, so that the same scene gives the same bytes.
pub fn mean_over_points(
    points: &[(Vec3, Vec3)],
    len: usize,
    read: impl Fn(Vec3, Vec3) -> Vec<f64> + Sync,
) -> Vec<f64> {
    let values: Vec<Vec<f64>> = points.par_iter().map(|&(x, n)| read(x, n)).collect();
    let mut mean = vec![0.0; len];
    for v in &values {
        for (m, x) in mean.iter_mut().zip(v) {
            *m += x;
        }
    }
    if !values.is_empty() {
        let count = values.len() as f64;
        mean.iter_mut().for_each(|m| *m /= count);
    }
    mean
}

/// Every zone's grid points in output order: (zone index, position in m, unit normal).
pub fn grid_points(scene: &Scene) -> impl Iterator<Item = (usize, Vec3, Vec3)> + '_ {
    scene.zones.iter().enumerate().flat_map(|(z, zone)| {
        zone.grid
            .iter()
            .flat_map(move |g| g.points().map(move |(p, normal)| (z, p, normal)))
    })
}

/// Number of sensors plus zones: the index of the first grid point among the outputs.
pub fn grid_offset(scene: &Scene) -> usize {
    scene.sensors.len() + scene.zones.len()
}

/// Number of outputs: sensors, zones and grid points.
pub fn output_count(scene: &Scene) -> usize {
    grid_offset(scene) + grid_points(scene).count()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A cone admits what is inside it and in front, the hemisphere everything in front;
    /// nothing behind or NaN.
    #[test]
    fn field_of_view_admits_its_cone() {
        let cone = FieldOfView::cone(Some(60f64.to_radians()));
        assert!(cone.admits(1.0));
        assert!(cone.admits(0.51));
        assert!(!cone.admits(0.49));
        assert!(!cone.admits(-0.5));
        assert!(!cone.admits(f64::NAN));
        let all = FieldOfView::HEMISPHERE;
        assert!(all.admits(1e-9));
        assert!(!all.admits(0.0));
        assert!(!all.admits(f64::NAN));
        assert_eq!(all.cos_half_angle(), None);
        assert!((cone.cos_half_angle().unwrap_or(0.0) - 0.5).abs() < 1e-15);
    }
}
