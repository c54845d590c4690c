//! Sun and sky: the models that turn a sky state into luminances, in `f32`, without
//! allocation, for the controller and the host alike.
//!
//! - [`cie`]: the CIE standard general sky (ISO 15469:2004 / CIE S 011/E:2003), its 15
//!   types, and the traditional CIE overcast sky (Moon and Spencer 1942);
//! - [`perez`]: the Perez all-weather sky (Perez, Seals and Michalsky 1993) from direct
//!   normal and diffuse horizontal irradiance or illuminance;
//! - [`efficacy`]: the luminous efficacy of diffuse and direct sunlight (Perez et al. 1990);
//! - [`patches`]: the Tregenza sky of 145 patches and its Reinhart subdivisions;
//! - [`glazing`]: the angular transmittance of clear and diffusing glazing;
//! - [`sun`]: the sun's position from a UTC time and a site, within 0.05° of SPA from 2000
//!   to 2100 in `f32`;
//! - [`sun_grid`]: the sun's directions at a site as a grid in declination and hour angle,
//!   the nodes of a basis' daylight;
//! - [`horizontal_illuminance`]: a sky's luminance integrated over the hemisphere, the rule
//!   that turns a relative sky into an absolute one.
//!
//! **Frame.** Directions are unit vectors `[x, y, z]` with z up (the zenith). The sky models
//! depend on a direction only through its zenith angle and its angle to the sun, so any
//! horizontal orientation serves as long as the sun is given in the same frame.
//! [`direction`] builds one from altitude and azimuth in the site's frame (x east, y north,
//! azimuth clockwise from north seen from above, as on a compass); the host turns it into
//! the room's frame from the room's north angle (`docs/math.md`, "Sun and sky").
//!
//! **Why `f32`.** The controller's FPU (Cortex-M4F) is single precision; `f64` would be
//! software floating point there, slower by an order of magnitude and several KB of code.
//! The models' published coefficients have four or five significant digits and the models
//! themselves fit measured skies to a few per cent, so `f32`'s 7 digits lose nothing; the
//! quadrature's sums run over 512 positive terms (relative rounding below 10⁻⁵). The host
//! uses this same code; the tests check it against independent `f64` computations.
//!
//! **No `f64`.** The sky models, the patch luminances and the sun's position call the
//! sines, cosines, arccosines, exponentials and square roots of the private `approx`
//! module, short polynomials in `f32` arithmetic alone with bounds a few units in the last
//! place (stated and tested there), rather than `libm`'s single-precision sine and cosine,
//! which work in `f64` (software floating point on a Cortex-M4F). The geometry a basis is
//! built from ([`patches::SkyPatches::patch`], [`sun_grid::direction_of`]) keeps `libm`'s,
//! so that what the host writes into a basis does not depend on these approximations.
//!
//! Nothing here but [`sun_grid`] is called by the basis evaluators: a firmware that does not
//! use the sky models links none of them.

pub(crate) mod approx;
pub mod cie;
mod conditions;
pub mod direct;
pub mod efficacy;
pub mod glazing;
pub mod patches;
pub mod perez;
pub mod sun;
pub mod sun_first;
pub mod sun_grid;
pub mod sunlit;

use crate::error::{Error, Result};

/// A sky luminance distribution relative to some reference luminance (the zenith, for CIE
/// skies): what [`horizontal_illuminance`] integrates.
pub trait RelativeSky {
    /// Relative luminance seen in direction `dir` (a unit vector, z up), 0 below the horizon
    /// (`dir[2] < 0`). Never negative, never NaN for a unit vector.
    fn relative_luminance(&self, dir: [f32; 3]) -> f32;
    /// The sun's direction (unit vector, z up, at or above the horizon).
    fn sun(&self) -> [f32; 3];
}

/// Unit vector of altitude `altitude` (rad above the horizon) and azimuth `azimuth` (rad,
/// clockwise from north seen from above) in the site's frame: x east, y north, z up.
///
/// In `f32` alone: sines and cosines within 1.2 × 10⁻⁷ of the exact ones for angles up to
/// 8192 rad in magnitude (beyond that an angle is taken as 0).
pub fn direction(altitude: f32, azimuth: f32) -> [f32; 3] {
    let (s, c) = approx::sin_cos(altitude);
    let (sa, ca) = approx::sin_cos(azimuth);
    [sa * c, ca * c, s]
}

/// Angle between two unit vectors, rad, and its cosine, robust to rounding (the cosine
/// clamped to [−1, 1]); the arccosine within 4 × 10⁻⁷ rad ([`approx::acos`]).
pub(crate) fn angle_between(a: [f32; 3], b: [f32; 3]) -> (f32, f32) {
    let cos = (a[0] * b[0] + a[1] * b[1] + a[2] * b[2]).clamp(-1.0, 1.0);
    (approx::acos(cos), cos)
}

/// Checks that `sun` is a unit vector (to 10⁻³) at or above the horizon, as the sky models
/// need; `Err` names `what`.
pub(crate) fn check_sun(sun: [f32; 3]) -> Result<[f32; 3]> {
    let norm2 = sun[0] * sun[0] + sun[1] * sun[1] + sun[2] * sun[2];
    if !(norm2.is_finite() && (norm2 - 1.0).abs() <= 2.0e-3) {
        return Err(Error::OutOfRange {
            what: "sun direction length",
            range: "1 (a unit vector, to 10⁻³)",
        });
    }
    if sun[2].is_nan() || sun[2] < 0.0 {
        return Err(Error::OutOfRange {
            what: "sun direction z (sin of the altitude)",
            range: "from 0 to 1 (the sun at or above the horizon)",
        });
    }
    Ok(sun)
}

/// `x` in [min, max] (NaN is not), else [`Error::OutOfRange`] with `what` and `range`, the
/// same bounds in words (no float formatting on the controller).
pub(crate) fn check_range(
    x: f32,
    what: &'static str,
    min: f32,
    max: f32,
    range: &'static str,
) -> Result<()> {
    if x >= min && x <= max {
        Ok(())
    } else {
        Err(Error::OutOfRange { what, range })
    }
}

/// Gauss–Legendre nodes and weights of order 16 on [−1, 1], the non-negative half (the rule
/// is symmetric): `(x, w)`. Exact for polynomials up to degree 31; the tests check that and
/// the weights' sum.
const GAUSS_16: [(f32, f32); 8] = [
    (9.501_251e-2, 1.894_506e-1),
    (2.816_035_5e-1, 1.826_034_2e-1),
    (4.580_167_8e-1, 1.691_565_2e-1),
    (6.178_762_4e-1, 1.495_959_9e-1),
    (7.554_044e-1, 1.246_289_7e-1),
    (8.656_312e-1, 9.515_851e-2),
    (9.445_75e-1, 6.225_352_4e-2),
    (9.894_009e-1, 2.715_245_9e-2),
];

/// Azimuth steps of [`horizontal_illuminance`] over the half circle on one side of the sun.
pub const QUADRATURE_AZIMUTHS: usize = 32;

/// Zenith-angle nodes of [`horizontal_illuminance`].
pub const QUADRATURE_ZENITHS: usize = 16;

/// Horizontal illuminance of the unobstructed sky relative to its reference luminance: the
/// integral `∫ L_rel(ω) cos Z dω` over the upper hemisphere (sr, times the relative
/// luminance). For a CIE sky that is `E_h / L_z`; a uniform sky of relative luminance 1
/// gives π.
///
/// The rule: Gauss–Legendre of order 16 in the zenith angle Z on [0, π/2] (weight
/// `sin Z cos Z`), times the midpoint rule in azimuth with 32 steps on the half circle
/// [0, π] measured from the sun's vertical plane, doubled (every sky here is symmetric about
/// that plane): 512 luminance evaluations. On smooth skies (the gradation, uniform and
/// overcast skies) the rule is within 3 × 10⁻⁷ of the exact integral, f32 rounding adding up
/// to 2 × 10⁻⁶; the sun's circumsolar peak, `exp(d χ)` with a corner at the sun, limits clear
/// skies to 2 × 10⁻⁴ relative (measured against fine midpoint rules in f64: 4000 × 4000 for
/// types 1, 5, 12, 13 and 15; 800 × 1600 in the tests for all 15 types at sun altitudes 5°
/// to 85° and four Perez states with the sun at 10° to 60°; `docs/math.md`, "Sun and sky").
pub fn horizontal_illuminance<S: RelativeSky + ?Sized>(sky: &S) -> f32 {
    let sun = sky.sun();
    // Azimuths are measured from the sun's azimuth; a sun at the zenith has none, and any
    // reference does.
    let horizontal = libm::sqrtf(sun[0] * sun[0] + sun[1] * sun[1]);
    let (ux, uy) = if horizontal > 1.0e-6 {
        (sun[0] / horizontal, sun[1] / horizontal)
    } else {
        (0.0, 1.0)
    };
    let quarter = core::f32::consts::FRAC_PI_4;
    let step = core::f32::consts::PI / QUADRATURE_AZIMUTHS as f32;
    // The azimuths' sines and cosines are the same on every ring: once.
    let mut azimuths = [(0.0f32, 0.0f32); QUADRATURE_AZIMUTHS];
    for (k, slot) in azimuths.iter_mut().enumerate() {
        *slot = approx::sin_cos((k as f32 + 0.5) * step);
    }
    let mut total = 0.0f32;
    for &(x, w) in GAUSS_16.iter() {
        for sign in [-1.0f32, 1.0] {
            // Z = π/4 (1 + x) maps [−1, 1] onto [0, π/2].
            let zenith = quarter * (1.0 + sign * x);
            let (sz, cz) = approx::sin_cos(zenith);
            let mut ring = 0.0f32;
            for &(sp, cp) in azimuths.iter() {
                // Azimuth φ from the sun's vertical plane: along (ux, uy) and its normal.
                let dir = [sz * (cp * ux - sp * uy), sz * (cp * uy + sp * ux), cz];
                ring += sky.relative_luminance(dir);
            }
            total += w * quarter * sz * cz * ring;
        }
    }
    // Each ring: 2 (both sides) × step × Σ.
    total * 2.0 * step
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, clippy::indexing_slicing)]
    use super::*;

    /// The Gauss–Legendre table integrates x^k exactly for k up to 31: ∫ x^k dx over
    /// [−1, 1] is 2/(k + 1) for even k (odd k vanish by symmetry, which the half table
    /// builds in). Tolerance 2 × 10⁻⁷: the table's f32 rounding.
    #[test]
    fn gauss_table_is_exact_to_degree_31() {
        for k in (0..=30).step_by(2) {
            let sum: f64 = GAUSS_16
                .iter()
                .map(|&(x, w)| 2.0 * f64::from(w) * f64::from(x).powi(k))
                .sum();
            let exact = 2.0 / (f64::from(k) + 1.0);
            assert!(
                (sum - exact).abs() <= 2.0e-7,
                "degree {k}: {sum} against {exact}"
            );
        }
    }

    struct Uniform;
    impl RelativeSky for Uniform {
        fn relative_luminance(&self, dir: [f32; 3]) -> f32 {
            if dir[2] < 0.0 {
                0.0
            } else {
                1.0
            }
        }
        fn sun(&self) -> [f32; 3] {
            direction(0.5, 1.0)
        }
    }

    /// A uniform sky of luminance L gives E_h = π L (the cosine law over the hemisphere).
    #[test]
    fn uniform_sky_gives_pi() {
        let e = horizontal_illuminance(&Uniform);
        assert!((e - core::f32::consts::PI).abs() <= 1.0e-6 * core::f32::consts::PI);
    }

    #[test]
    fn direction_convention() {
        // North on the horizon is +y, east +x, the zenith +z.
        let n = direction(0.0, 0.0);
        let e = direction(0.0, core::f32::consts::FRAC_PI_2);
        let z = direction(core::f32::consts::FRAC_PI_2, 0.3);
        assert!((n[1] - 1.0).abs() < 1e-6 && n[0].abs() < 1e-6);
        assert!((e[0] - 1.0).abs() < 1e-6 && e[1].abs() < 1e-6);
        assert!((z[2] - 1.0).abs() < 1e-6);
    }
}
