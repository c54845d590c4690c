//! The direction bins of a directional port (docs/math.md, "Directional ports"): the
//! hemisphere of directions in which light crosses a port patch, cut into `N` bins of equal
//! projected solid angle, and the share of a form factor whose directions fall in each bin.
//!
//! A direction of travel `d` through an opening whose normal points into the receiving room
//! is `n` falls in the central cone when `cos θ = d·n ≥ √(1 − 1/N)` (a cone holding `1/N` of
//! the hemisphere's projected solid angle `π`, since `∫ cos θ dω` over a cone of half angle
//! `θc` is `π sin² θc`), and otherwise in one of `N − 1` equal azimuth sectors of the ring
//! around it, counted from the opening's "up" (the world's `z` projected onto its plane, or
//! its `y` for a horizontal opening), sector 0 centred on it. Every bin thus holds `1/N` of
//! the hemisphere's projected solid angle. One bin is the whole hemisphere: the diffuse port.
//!
//! Both rooms of a port cut a direction of travel the same way: the bins depend on the world
//! direction and the opening's plane only, so bin `β` of the light leaving one room is bin
//! `β` of the light entering the other.

use crate::geometry::{Patch, Vec3};

/// The default number of direction bins of a port: one, the diffuse port.
pub const DEFAULT_DIRECTIONS: usize = 1;

/// The largest number of direction bins a port may have: a cone and 63 sectors, far finer
/// than the patches the bins' shares are sampled over can tell apart.
pub const MAX_DIRECTIONS: usize = 64;

/// The bins of one port patch's hemisphere of directions, seen from the room the light enters.
#[derive(Clone, Copy, Debug)]
pub struct Bins {
    /// `N`, the number of bins.
    count: usize,
    /// Unit normal into the receiving room.
    normal: Vec3,
    /// The opening's "up" in its plane (azimuth 0), unit.
    up: Vec3,
    /// `normal × up`: azimuth 90°, unit.
    side: Vec3,
    /// `cos θc` of the central cone.
    cone: f64,
}

impl Bins {
    /// `count` bins of the light entering a room through an opening whose unit `normal`
    /// points into that room.
    pub fn new(count: usize, normal: Vec3) -> Bins {
        let z = Vec3::new(0.0, 0.0, 1.0);
        let y = Vec3::new(0.0, 1.0, 0.0);
        // "Up" is the same axis for both sides of the opening (it depends on the plane, not
        // on which way the normal points), so both rooms agree on the sectors.
        let reference = if normal.z.abs() > 0.9 { y } else { z };
        let up = (reference - normal * normal.dot(reference)).normalized();
        let side = normal.cross(up);
        Bins {
            count,
            normal,
            up,
            side,
            cone: (1.0 - 1.0 / count as f64).max(0.0).sqrt(),
        }
    }

    /// `N`.
    pub fn count(&self) -> usize {
        self.count
    }

    /// Share of the hemisphere's projected solid angle `π` each bin holds: `1/N`.
    pub fn weight(&self) -> f64 {
        1.0 / self.count as f64
    }

    /// The bin of the direction of travel `d` (any length, pointing into the receiving room).
    pub fn of(&self, d: Vec3) -> usize {
        if self.count == 1 {
            return 0;
        }
        let length = d.length();
        if length == 0.0 || self.normal.dot(d) >= self.cone * length {
            return 0;
        }
        let sectors = (self.count - 1) as f64;
        let azimuth = self.side.dot(d).atan2(self.up.dot(d));
        // Sector 0 centred on "up": shift by half a sector before cutting.
        let turn = (azimuth / std::f64::consts::TAU + 0.5 / sectors).rem_euclid(1.0);
        1 + ((turn * sectors) as usize).min(self.count - 2)
    }
}

/// Points of a convex patch with their areas (m², summing to its area): a fan of triangles
/// from its centroid, three points in each (the symmetric rule exact for quadratics).
pub fn samples(patch: &Patch) -> Vec<(Vec3, f64)> {
    let c = patch.centroid;
    let v = &patch.polygon.vertices;
    let mut out = Vec::with_capacity(3 * v.len());
    for k in 0..v.len() {
        let (a, b) = (v[k], v[(k + 1) % v.len()]);
        let area = 0.5 * (a - c).cross(b - c).length();
        for (x, y, z) in [
            (2.0 / 3.0, 1.0 / 6.0, 1.0 / 6.0),
            (1.0 / 6.0, 2.0 / 3.0, 1.0 / 6.0),
            (1.0 / 6.0, 1.0 / 6.0, 2.0 / 3.0),
        ] {
            out.push((c * x + a * y + b * z, area / 3.0));
        }
    }
    out
}

/// How the light exchanged between a port patch (its `samples` and unit `normal`, into the
/// room) and a receiver (its `samples` and unit normal, `None` for a point that sees every
/// way) splits over the bins `bins`, by the direction of travel `from → to` of each pair of
/// samples weighted by the point-to-point kernel `cos θ cos θ' / r²` (both cosines clipped
/// at 0; occlusion is not sampled, the exact form factor carries it). The shares sum to 1;
/// where no pair of samples faces the other, the light goes in the bin of the centroids'
/// direction.
pub fn shares(
    bins: &Bins,
    port: (&[(Vec3, f64)], Vec3),
    receiver: (&[(Vec3, f64)], Option<Vec3>),
    leaving: bool,
) -> Vec<f64> {
    let mut mass = vec![0.0; bins.count()];
    accumulate(&mut mass, bins, port, receiver, leaving);
    normalised(mass, bins, port.0, receiver.0, leaving)
}

/// [`shares`] for a receiver of many points each facing its own unit normal (an imported
/// sensor grid's zone): every point's pairs with the port's samples weighted by the same
/// kernel, together.
pub fn shares_at_points(
    bins: &Bins,
    port: (&[(Vec3, f64)], Vec3),
    points: &[(Vec3, Vec3)],
    leaving: bool,
) -> Vec<f64> {
    let mut mass = vec![0.0; bins.count()];
    for &(x, n) in points {
        accumulate(&mut mass, bins, port, (&[(x, 1.0)], Some(n)), leaving);
    }
    let centres: Vec<(Vec3, f64)> = points.iter().map(|&(x, _)| (x, 1.0)).collect();
    normalised(mass, bins, port.0, &centres, leaving)
}

/// Adds the kernel of every pair of port and receiver samples to the bin of its direction.
fn accumulate(
    mass: &mut [f64],
    bins: &Bins,
    port: (&[(Vec3, f64)], Vec3),
    receiver: (&[(Vec3, f64)], Option<Vec3>),
    leaving: bool,
) {
    let (port_points, port_normal) = port;
    let (receiver_points, receiver_normal) = receiver;
    for &(x, wx) in port_points {
        for &(y, wy) in receiver_points {
            let d = y - x;
            let r2 = d.dot(d);
            if r2 == 0.0 {
                continue;
            }
            let at_port = port_normal.dot(d).max(0.0);
            let at_receiver = receiver_normal.map_or(r2.sqrt(), |n| (-n.dot(d)).max(0.0));
            let kernel = wx * wy * at_port * at_receiver / (r2 * r2);
            if kernel > 0.0 {
                // Light leaving the room travels from the receiver onto the port patch.
                mass[bins.of(if leaving { -d } else { d })] += kernel;
            }
        }
    }
}

/// The masses as shares summing to 1; all zero, the bin of the direction between the
/// centroids of the port's and the receiver's samples.
fn normalised(
    mass: Vec<f64>,
    bins: &Bins,
    port_points: &[(Vec3, f64)],
    receiver_points: &[(Vec3, f64)],
    leaving: bool,
) -> Vec<f64> {
    let total: f64 = mass.iter().sum();
    if total > 0.0 {
        mass.iter().map(|m| m / total).collect()
    } else {
        let centre = |p: &[(Vec3, f64)]| {
            let w: f64 = p.iter().map(|q| q.1).sum();
            p.iter().fold(Vec3::ZERO, |s, q| s + q.0 * (q.1 / w))
        };
        let d = centre(receiver_points) - centre(port_points);
        let mut one = vec![0.0; bins.count()];
        one[bins.of(if leaving { -d } else { d })] = 1.0;
        one
    }
}
