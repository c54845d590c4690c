//! The state of a Perez sky (R. Perez, P. Ineichen, R. Seals, J. Michalsky and R. Stewart,
//! Solar Energy 44(5), 1990, eq. 1 and Table 1): clearness ε, brightness Δ and the sun's
//! zenith angle, from the two irradiances of a weather file.
//!
//! Both the Perez sky ([`perez`](super::perez)) and the luminous efficacies
//! ([`efficacy`](super::efficacy)) are functions of this state, and the state from
//! illuminances goes through the efficacies: so the state sits below both, and its public
//! paths are those `perez` re-exports (`sky::perez::Conditions` and the rest). The state
//! from illuminances ([`Conditions::from_illuminance`]) and the sky's coefficients
//! ([`Conditions::coefficients`]) are in `perez.rs`, with the sky they serve.

use super::{approx, check_range};
use crate::error::Result;

/// Upper bounds of the first seven clearness bins; the eighth is ε ≥ 6.2 (Perez et al. 1990,
/// Table 1; the same bins in 1993).
pub const CLEARNESS_BINS: [f32; 7] = [1.065, 1.230, 1.500, 1.950, 2.800, 4.500, 6.200];

/// The solar constant, W/m², of Perez's model and Radiance (`gendaylit`'s `solar_constant_e`).
pub const SOLAR_CONSTANT: f32 = 1367.0;

/// κ of the clearness, for Z in rad (Perez et al. 1990, eq. 1).
const KAPPA: f32 = 1.041;

/// The clearness bin of ε, 0 to 7 (bin 0 also for ε below 1).
pub fn clearness_bin(clearness: f32) -> usize {
    CLEARNESS_BINS
        .iter()
        .position(|&upper| clearness < upper)
        .unwrap_or(CLEARNESS_BINS.len())
}

/// Relative optical air mass at zenith angle `zenith` (rad, up to π/2): Kasten (1966),
/// `m = 1 / (cos Z + 0.15 (93.885 − Z°)^−1.253)`, as Perez and `gendaylit` use it.
pub fn air_mass(zenith: f32) -> f32 {
    let degrees = zenith.to_degrees().clamp(0.0, 90.0);
    let cos_zenith = approx::sin_cos(degrees.to_radians()).1;
    1.0 / (cos_zenith + 0.15 * libm::powf(93.885 - degrees, -1.253))
}

/// Extraterrestrial normal irradiance (W/m²) on day `day_of_year` (1 = 1 January):
/// [`SOLAR_CONSTANT`] times the eccentricity correction of Spencer (1971),
/// `1.00011 + 0.034221 cos Γ + 0.00128 sin Γ + 0.000719 cos 2Γ + 0.000077 sin 2Γ`,
/// `Γ = 2π (day − 1)/365`.
pub fn extraterrestrial_irradiance(day_of_year: u16) -> f32 {
    let g = 2.0 * core::f32::consts::PI * (f32::from(day_of_year.clamp(1, 366)) - 1.0) / 365.0;
    let (sin_g, cos_g) = approx::sin_cos(g);
    let (sin_2g, cos_2g) = approx::sin_cos(2.0 * g);
    let e0 = 1.00011 + 0.034221 * cos_g + 0.00128 * sin_g + 0.000719 * cos_2g + 0.000077 * sin_2g;
    SOLAR_CONSTANT * e0
}

/// The state of a Perez sky: clearness ε, brightness Δ and the sun's zenith angle.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Conditions {
    /// Sky clearness ε (1 overcast; above 6.2 clear).
    pub clearness: f32,
    /// Sky brightness Δ.
    pub brightness: f32,
    /// Sun zenith angle, rad.
    pub zenith: f32,
}

impl Conditions {
    /// ε and Δ from the diffuse horizontal and direct normal irradiance (W/m²), the sun's
    /// zenith angle (rad, 0 to π/2) and the day of the year (1 to 366). The diffuse
    /// irradiance must be positive (the clearness divides by it), the direct one
    /// non-negative.
    pub fn from_irradiance(
        diffuse_horizontal: f32,
        direct_normal: f32,
        zenith: f32,
        day_of_year: u16,
    ) -> Result<Self> {
        check_range(
            diffuse_horizontal,
            "diffuse horizontal irradiance (W/m²)",
            1.0e-6,
            2000.0,
            "above 0 and at most 2000",
        )?;
        check_range(
            direct_normal,
            "direct normal irradiance (W/m²)",
            0.0,
            2000.0,
            "from 0 to 2000",
        )?;
        check_range(
            zenith,
            "sun zenith angle (rad)",
            0.0,
            core::f32::consts::FRAC_PI_2,
            "from 0 to π/2",
        )?;
        let z3 = KAPPA * zenith * zenith * zenith;
        let clearness =
            ((diffuse_horizontal + direct_normal) / diffuse_horizontal + z3) / (1.0 + z3);
        let brightness =
            diffuse_horizontal * air_mass(zenith) / extraterrestrial_irradiance(day_of_year);
        Ok(Self {
            clearness,
            brightness,
            zenith,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Bins at their edges: each upper bound belongs to the next bin (Perez et al. 1990,
    /// Table 1: "1.065 ≤ ε < 1.230" and so on).
    #[test]
    fn clearness_bins_at_their_edges() {
        let edges = [1.065f32, 1.230, 1.500, 1.950, 2.800, 4.500, 6.200];
        for (i, &edge) in edges.iter().enumerate() {
            assert_eq!(clearness_bin(edge), i + 1, "ε = {edge}");
            assert_eq!(clearness_bin(edge - 1.0e-4), i, "just below {edge}");
        }
        assert_eq!(clearness_bin(1.0), 0);
        assert_eq!(clearness_bin(0.9), 0);
        assert_eq!(clearness_bin(40.0), 7);
    }
}
