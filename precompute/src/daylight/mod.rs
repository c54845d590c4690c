//! Daylight on the host: the sun's position from a date, time and site ([`sun`]), a sky's
//! patch luminances and illuminances for a site, a time and a weather state ([`sky`]), and
//! the conversion from the site's frame to the room's. The sky models themselves are the
//! runtime's ([`eigenrad_runtime::sky`]), so that the host and the controller compute the
//! same skies.
//!
//! **Frames.** The site's frame has x east, y north (true north), z up; azimuths are
//! measured clockwise from north seen from above, as on a compass. The room's frame is the
//! scene's (z up). Its orientation is one angle, `north`: the compass bearing of the scene's
//! +y axis, in degrees clockwise from true north. With `north = 0` the scene's +y points
//! north and +x east; with `north = 90` +y points east and +x south. A direction of
//! altitude h and azimuth A is `(sin(A − north) cos h, cos(A − north) cos h, sin h)` in the
//! room's frame.

pub mod clear_sky;
pub mod sky;
pub mod sun;

/// A site, a time, the sun's position or a sky input that cannot be used: `what` names the
/// input (a command-line flag or a quantity), `reason` says what is wrong. The commands
/// report it as [`crate::Error::Daylight`].
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[error("{what}: {reason}")]
pub struct DaylightError {
    /// The input: `--lat`, `--lon`, `--elevation`, `--time`, a sky flag (`--cie`,
    /// `--dhi-lux`, …) or a quantity (`sun position`, `Perez sky`).
    pub what: String,
    /// What is wrong with it.
    pub reason: String,
}

/// The result of this stage's functions.
pub type Result<T> = std::result::Result<T, DaylightError>;

/// A [`DaylightError`] about `what`.
pub(crate) fn error(what: &str, reason: impl Into<String>) -> DaylightError {
    DaylightError {
        what: what.to_owned(),
        reason: reason.into(),
    }
}

/// Unit vector of altitude `altitude` and azimuth `azimuth` (degrees, azimuth clockwise from
/// true north) in the room's frame, for a room whose +y axis has compass bearing `north`
/// (degrees clockwise from true north).
pub fn room_direction(altitude: f64, azimuth: f64, north: f64) -> [f64; 3] {
    let (h, a) = (altitude.to_radians(), (azimuth - north).to_radians());
    [a.sin() * h.cos(), a.cos() * h.cos(), h.sin()]
}

/// The inverse of [`room_direction`] for a site-frame direction: a direction in the room's
/// frame turned into the site's frame (x east, y north, z up).
pub fn room_to_site(dir: [f64; 3], north: f64) -> [f64; 3] {
    let (s, c) = north.to_radians().sin_cos();
    // Turning by −north about z (clockwise bearings are negative angles about +z).
    [dir[0] * c + dir[1] * s, -dir[0] * s + dir[1] * c, dir[2]]
}

/// A site-frame direction in the room's frame.
pub fn site_to_room(dir: [f64; 3], north: f64) -> [f64; 3] {
    room_to_site(dir, -north)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: [f64; 3], b: [f64; 3]) -> bool {
        a.iter().zip(b).all(|(x, y)| (x - y).abs() < 1e-12)
    }

    /// The convention by hand: north = 90 turns the scene so that its +y points east. The
    /// sun due east on the horizon is then along the scene's +y, due south along +x, due
    /// north along −x.
    #[test]
    fn north_angle_convention() {
        assert!(close(room_direction(0.0, 90.0, 90.0), [0.0, 1.0, 0.0]));
        assert!(close(room_direction(0.0, 180.0, 90.0), [1.0, 0.0, 0.0]));
        assert!(close(room_direction(0.0, 0.0, 90.0), [-1.0, 0.0, 0.0]));
        assert!(close(room_direction(0.0, 0.0, 0.0), [0.0, 1.0, 0.0]));
        assert!(close(room_direction(90.0, 123.0, 45.0), [0.0, 0.0, 1.0]));
        for (h, a, n) in [(20.0, 200.0, 30.0), (60.0, 10.0, -75.0)] {
            let room = room_direction(h, a, n);
            let site = room_direction(h, a, 0.0);
            assert!(close(room_to_site(room, n), site));
            assert!(close(site_to_room(site, n), room));
        }
    }
}
