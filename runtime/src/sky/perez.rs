//! The Perez all-weather sky (R. Perez, R. Seals and J. Michalsky, "All-weather model for
//! sky luminance distribution — preliminary configuration and validation", Solar Energy
//! 50(3), 235–245, 1993).
//!
//! The sky's state comes from two irradiances that weather files and rooftop sensors give,
//! the diffuse horizontal `E_ed` and the direct normal `E_es` (W/m²), and the sun's zenith
//! angle Z (rad):
//!
//! ```text
//! ε = ((E_ed + E_es)/E_ed + κ Z³) / (1 + κ Z³),  κ = 1.041   (clearness, 1 overcast … > 6.2 clear)
//! Δ = E_ed m / E_0                                            (brightness)
//! ```
//!
//! with `m` the relative optical air mass (Kasten 1966, [`air_mass`]) and `E_0` the
//! extraterrestrial normal irradiance ([`extraterrestrial_irradiance`]). ε picks one of
//! eight bins; in each, the five coefficients are `x = x1 + x2 Z + Δ (x3 + x4 Z)` from the
//! paper's Table 1 ([`COEFFICIENTS`]), except `c` and `d` in the first bin,
//! `c = exp((Δ (c1 + c2 Z))^c3) − c4` and `d = −exp(Δ (d1 + d2 Z)) + d3 + Δ d4`. The relative
//! luminance of a sky element at zenith angle ζ and angle γ from the sun is
//!
//! ```text
//! l(ζ, γ) = (1 + a exp(b / cos ζ)) (1 + c exp(d γ) + e cos² γ)
//! ```
//!
//! and the absolute luminance `l · E_dh / ∫ l cos ζ dω`, so that the unobstructed sky gives
//! the diffuse horizontal illuminance `E_dh` (lux; [`super::horizontal_illuminance`]).
//!
//! Like Radiance's `gendaylit` (2.x), the coefficients are evaluated with ε limited to
//! [1, 12.01) and Δ to [0.01, 0.6], the range of the measurements the model was fitted to,
//! and Δ at least 0.2 for 1.065 < ε < 2.8. The fitted `b` comes out positive for some clear
//! states of a sun a few degrees up (ε 7.4, Δ 0.2 at 0.9°, say), a gradation that brightens
//! without bound towards the horizon,
//! whose integral does not exist. `gendaylit` refuses such a state; `gendaymtx`, which must
//! give every hour of a year a sky, evaluates it at its patch centres (6° and more above the
//! horizon). A controller must have a sky every hour too: `b` is held at 0 at most, a
//! gradation flat from the zenith to the horizon, which the scale then fits to the diffuse
//! horizontal illuminance.

use super::{approx, check_range, check_sun, efficacy, RelativeSky};
use crate::error::{Error, Result};

// The state itself lives in `conditions.rs`, below both this sky and the efficacies; its
// paths stay here.
pub use super::conditions::{
    air_mass, clearness_bin, extraterrestrial_irradiance, Conditions, CLEARNESS_BINS,
    SOLAR_CONSTANT,
};

/// Perez, Seals and Michalsky (1993), Table 1: for each clearness bin, `[x1, x2, x3, x4]`
/// of a, b, c, d, e in that order. Checked number for number against Radiance's
/// `gendaylit.c` (`coeff_perez`) and a second public transcription that cites the paper.
pub const COEFFICIENTS: [[[f32; 4]; 5]; 8] = [
    // ε 1.000–1.065 (overcast); c and d by the special forms.
    [
        [1.3525, -0.2576, -0.2690, -1.4366],
        [-0.7670, 0.0007, 1.2734, -0.1233],
        [2.8000, 0.6004, 1.2375, 1.0000],
        [1.8734, 0.6297, 0.9738, 0.2809],
        [0.0356, -0.1246, -0.5718, 0.9938],
    ],
    // ε 1.065–1.230
    [
        [-1.2219, -0.7730, 1.4148, 1.1016],
        [-0.2054, 0.0367, -3.9128, 0.9156],
        [6.9750, 0.1774, 6.4477, -0.1239],
        [-1.5798, -0.5081, -1.7812, 0.1080],
        [0.2624, 0.0672, -0.2190, -0.4285],
    ],
    // ε 1.230–1.500
    [
        [-1.1000, -0.2515, 0.8952, 0.0156],
        [0.2782, -0.1812, -4.5000, 1.1766],
        [24.7219, -13.0812, -37.7000, 34.8438],
        [-5.0000, 1.5218, 3.9229, -2.6204],
        [-0.0156, 0.1597, 0.4199, -0.5562],
    ],
    // ε 1.500–1.950
    [
        [-0.5484, -0.6654, -0.2672, 0.7117],
        [0.7234, -0.6219, -5.6812, 2.6297],
        [33.3389, -18.3000, -62.2500, 52.0781],
        [-3.5000, 0.0016, 1.1477, 0.1062],
        [0.4659, -0.3296, -0.0876, -0.0329],
    ],
    // ε 1.950–2.800
    [
        [-0.6000, -0.3566, -2.5000, 2.3250],
        [0.2937, 0.0496, -5.6812, 1.8415],
        [21.0000, -4.7656, -21.5906, 7.2492],
        [-3.5000, -0.1554, 1.4062, 0.3988],
        [0.0032, 0.0766, -0.0656, -0.1294],
    ],
    // ε 2.800–4.500
    [
        [-1.0156, -0.3670, 1.0078, 1.4051],
        [0.2875, -0.5328, -3.8500, 3.3750],
        [14.0000, -0.9999, -7.1406, 7.5469],
        [-3.4000, -0.1078, -1.0750, 1.5702],
        [-0.0672, 0.4016, 0.3017, -0.4844],
    ],
    // ε 4.500–6.200
    [
        [-1.0000, 0.0211, 0.5025, -0.5119],
        [-0.3000, 0.1922, 0.7023, -1.6317],
        [19.0000, -5.0000, 1.2438, -1.9094],
        [-4.0000, 0.0250, 0.3844, 0.2656],
        [1.0468, -0.3788, -2.4517, 1.4656],
    ],
    // ε ≥ 6.200 (clear)
    [
        [-1.0500, 0.0289, 0.4260, 0.3590],
        [-0.3250, 0.1156, 0.7781, 0.0025],
        [31.0625, -14.5000, -46.1148, 55.3750],
        [-7.2312, 0.4050, 13.3500, 0.6234],
        [1.5000, -0.6426, 1.8564, 0.5636],
    ],
];

impl Conditions {
    /// From illuminances instead (lux): the irradiances that, through the Perez (1990)
    /// efficacies at precipitable water `water` (cm), give these illuminances. Found as
    /// `gendaylit` does: start from the illuminances over 127 500 lx / 1367 W/m² (the
    /// extraterrestrial efficacy), then divide by the efficacies of the ε and Δ found, ten
    /// times or until both irradiances move by less than 10⁻⁴ relative. Returns the
    /// conditions with the irradiances `(diffuse horizontal, direct normal)` in W/m².
    pub fn from_illuminance(
        diffuse_horizontal: f32,
        direct_normal: f32,
        zenith: f32,
        day_of_year: u16,
        water: f32,
    ) -> Result<(Self, f32, f32)> {
        check_range(
            diffuse_horizontal,
            "diffuse horizontal illuminance (lux)",
            1.0e-3,
            2.0e5,
            "from 0.001 to 200000",
        )?;
        check_range(
            direct_normal,
            "direct normal illuminance (lux)",
            0.0,
            2.0e5,
            "from 0 to 200000",
        )?;
        let mut dhi = diffuse_horizontal * SOLAR_CONSTANT / 127_500.0;
        let mut dni = direct_normal * SOLAR_CONSTANT / 127_500.0;
        let mut conditions = Self::from_irradiance(dhi, dni, zenith, day_of_year)?;
        for _ in 0..10 {
            let diffuse = efficacy::diffuse(&conditions, water)?;
            let direct = efficacy::direct(&conditions, water)?;
            let new_dhi = diffuse_horizontal / diffuse;
            let new_dni = if direct < 0.1 {
                0.0
            } else {
                direct_normal / direct
            };
            let moved = (new_dhi - dhi).abs() <= 1.0e-4 * dhi
                && (new_dni - dni).abs() <= 1.0e-4 * dni.max(1.0e-3);
            dhi = new_dhi;
            dni = new_dni;
            conditions = Self::from_irradiance(dhi, dni, zenith, day_of_year)?;
            if moved {
                break;
            }
        }
        Ok((conditions, dhi, dni))
    }

    /// The five coefficients a, b, c, d, e of this state (with the limits of the module
    /// documentation).
    pub fn coefficients(&self) -> [f32; 5] {
        let clearness = self.clearness.clamp(1.0, 12.0);
        let mut delta = self.brightness.clamp(0.01, 0.6);
        if clearness > 1.065 && clearness < 2.8 {
            delta = delta.max(0.2);
        }
        let z = self.zenith;
        let bin = clearness_bin(clearness);
        // `bin` is at most 7 by construction; the fallback row is never taken.
        let rows = COEFFICIENTS.get(bin).unwrap_or(&COEFFICIENTS[7]);
        let linear = |x: &[f32; 4]| x[0] + x[1] * z + delta * (x[2] + x[3] * z);
        let [ra, rb, rc, rd, re] = rows;
        let (c, d) = if bin == 0 {
            (
                approx::exp(libm::powf(delta * (rc[0] + rc[1] * z), rc[2])) - rc[3],
                -approx::exp(delta * (rd[0] + rd[1] * z)) + rd[2] + delta * rd[3],
            )
        } else {
            (linear(rc), linear(rd))
        };
        [linear(ra), linear(rb).min(0.0), c, d, linear(re)]
    }
}

/// A Perez sky for one state and sun position: relative luminance `l(ζ, γ)`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PerezSky {
    coefficients: [f32; 5],
    sun: [f32; 3],
}

impl PerezSky {
    /// The sky of `conditions` with the sun in direction `sun` (unit vector, z up, at or
    /// above the horizon; its zenith angle should be `conditions.zenith`). `Err` when a
    /// coefficient is not finite (`b` is held at 0 at most: the module documentation).
    pub fn new(conditions: &Conditions, sun: [f32; 3]) -> Result<Self> {
        let sun = check_sun(sun)?;
        let coefficients = conditions.coefficients();
        if !coefficients.iter().all(|x| x.is_finite()) {
            return Err(Error::OutOfRange {
                what: "Perez coefficients (from the clearness and brightness)",
                range: "finite",
            });
        }
        Ok(Self { coefficients, sun })
    }

    /// The coefficients a, b, c, d, e.
    pub fn coefficients(&self) -> [f32; 5] {
        self.coefficients
    }

    /// The factor that turns [`RelativeSky::relative_luminance`] into luminance (cd/m²) for
    /// a sky of diffuse horizontal illuminance `diffuse_horizontal` (lux, or W/m² for
    /// radiance in W/(m² sr)): `E_dh / ∫ l cos ζ dω`.
    pub fn luminance_scale(&self, diffuse_horizontal: f32) -> Result<f32> {
        check_range(
            diffuse_horizontal,
            "diffuse horizontal illuminance (lux)",
            0.0,
            f32::MAX,
            "finite and at least 0",
        )?;
        let integral = super::horizontal_illuminance(self);
        if !(integral > 0.0 && integral.is_finite()) {
            return Err(Error::OutOfRange {
                what: "Perez sky integral ∫ l cos ζ dω (sr)",
                range: "above 0",
            });
        }
        Ok(diffuse_horizontal / integral)
    }
}

impl RelativeSky for PerezSky {
    /// `l(ζ, γ)`, clamped at 0 (the model can dip below in places); 0 below the horizon.
    fn relative_luminance(&self, dir: [f32; 3]) -> f32 {
        let cos_zenith = dir[2];
        if cos_zenith.is_nan() || cos_zenith < 0.0 {
            return 0.0;
        }
        let [a, b, c, d, e] = self.coefficients;
        let gradation = if cos_zenith > 0.0 {
            1.0 + a * approx::exp(b / cos_zenith)
        } else {
            1.0
        };
        let (gamma, cos_gamma) = super::angle_between(dir, self.sun);
        let indicatrix = 1.0 + c * approx::exp(d * gamma) + e * cos_gamma * cos_gamma;
        (gradation * indicatrix).max(0.0)
    }

    fn sun(&self) -> [f32; 3] {
        self.sun
    }
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, clippy::indexing_slicing)]
    // The f64 references use std's float functions.
    extern crate std;
    use super::super::{direction, horizontal_illuminance};
    use super::*;

    /// The coefficients at bin edges against the published Table 1 evaluated by hand (f64,
    /// in the test): at ε just above 6.2 (bin 8), Z = 0.5 rad, Δ = 0.3, a = −1.05 + 0.0289 Z +
    /// Δ (0.426 + 0.359 Z) and so on; at ε just below 1.065 (bin 1, the special c and d).
    #[test]
    fn coefficients_against_the_published_table() {
        let (z, delta) = (0.5f64, 0.3f64);
        let lin = |x: [f64; 4]| x[0] + x[1] * z + delta * (x[2] + x[3] * z);
        let clear = Conditions {
            clearness: 6.2,
            brightness: delta as f32,
            zenith: z as f32,
        }
        .coefficients();
        let expect = [
            lin([-1.05, 0.0289, 0.426, 0.359]),
            lin([-0.325, 0.1156, 0.7781, 0.0025]),
            lin([31.0625, -14.5, -46.1148, 55.375]),
            lin([-7.2312, 0.405, 13.35, 0.6234]),
            lin([1.5, -0.6426, 1.8564, 0.5636]),
        ];
        for (k, (&got, want)) in clear.iter().zip(expect).enumerate() {
            assert!(
                (f64::from(got) - want).abs() <= 2.0e-5 * want.abs().max(1.0),
                "bin 8, coefficient {k}: {got} against {want}"
            );
        }
        let overcast = Conditions {
            clearness: 1.0649,
            brightness: delta as f32,
            zenith: z as f32,
        }
        .coefficients();
        let expect = [
            lin([1.3525, -0.2576, -0.269, -1.4366]),
            lin([-0.767, 0.0007, 1.2734, -0.1233]),
            (delta * (2.8 + 0.6004 * z)).powf(1.2375).exp() - 1.0,
            -(delta * (1.8734 + 0.6297 * z)).exp() + 0.9738 + delta * 0.2809,
            lin([0.0356, -0.1246, -0.5718, 0.9938]),
        ];
        for (k, (&got, want)) in overcast.iter().zip(expect).enumerate() {
            assert!(
                (f64::from(got) - want).abs() <= 2.0e-5 * want.abs().max(1.0),
                "bin 1, coefficient {k}: {got} against {want}"
            );
        }
    }

    /// Against Radiance's `gendaylit` (Radiance 6.0a as shipped in the `pyradiance` 1.3.1
    /// wheel), which prints ε, Δ (4 decimals), the sun direction and a..e (6 decimals), and
    /// whose diffuse and solar normalisations with `-O 2` (lumens) over those with `-O 1`
    /// (solar watts) are the diffuse and direct efficacies (4 significant digits each). The
    /// five states, each `gendaylit M D H -a 48.2 -o -16.4 -m -15 -W DNI DHI` (Vienna) but the
    /// fourth (`-a 39.74 -o 105.18 -m 105`, Golden): clear, intermediate, overcast-bin and
    /// no-sun (DNI 0, ε = 1: the special c and d). Tolerances: the printed digits (ε, Δ
    /// 6 × 10⁻⁵; coefficients 2 × 10⁻⁴ relative to max(1, |x|), f32 and the rounding of
    /// Z; efficacies 10⁻³ relative, the 4-digit quotients rounding by up to 8 × 10⁻⁴).
    #[test]
    fn against_gendaylit() {
        for (cos_z, day, dni, dhi, eps, delta, coefficients, (diffuse, direct)) in GENDAYLIT {
            let zenith = libm::acosf(cos_z);
            let c = Conditions::from_irradiance(dhi, dni, zenith, day).unwrap();
            assert!(
                (c.clearness - eps).abs() <= 6.0e-5,
                "ε {} against {eps}",
                c.clearness
            );
            assert!(
                (c.brightness - delta).abs() <= 6.0e-5,
                "Δ {} against {delta}",
                c.brightness
            );
            let ours = c.coefficients();
            for (k, (&got, &want)) in ours.iter().zip(coefficients.iter()).enumerate() {
                assert!(
                    (got - want).abs() <= 2.0e-4 * want.abs().max(1.0),
                    "ε {eps}, coefficient {k}: {got} against {want}"
                );
            }
            let k_diffuse = efficacy::diffuse(&c, efficacy::DEFAULT_WATER).unwrap();
            assert!(
                (k_diffuse - diffuse).abs() <= 1.0e-3 * diffuse,
                "ε {eps}: diffuse efficacy {k_diffuse} against {diffuse} lm/W"
            );
            let k_direct = efficacy::direct(&c, efficacy::DEFAULT_WATER).unwrap();
            if dni > 0.0 {
                assert!(
                    (k_direct - direct).abs() <= 1.0e-3 * direct,
                    "ε {eps}: direct efficacy {k_direct} against {direct} lm/W"
                );
            }
        }
    }

    /// (cos Z, day of year, DNI W/m², DHI W/m², ε, Δ, a..e, (diffuse, direct) efficacy lm/W)
    /// as printed by `gendaylit`; see [`against_gendaylit`].
    // The digits as `gendaylit` prints them, some beyond f32's.
    #[allow(clippy::type_complexity, clippy::excessive_precision)]
    const GENDAYLIT: [(f32, u16, f32, f32, f32, f32, [f32; 5], (f32, f32)); 5] = [
        // 6 21 12 -W 700 120
        (
            0.908048,
            172,
            700.0,
            120.0,
            6.3811,
            0.0998,
            [-0.979484, -0.197241, 22.580903, -5.696337, 1.431942],
            (6673.0 / 51.25, 1.065e9 / 1.030e7),
        ),
        // 12 21 10 -W 40 90
        (
            0.243628,
            355,
            40.0,
            90.0,
            1.1300,
            0.2571,
            [-1.507000, -0.850894, 8.825420, -2.674018, 0.149187],
            (3183.0 / 27.67, 4.656e7 / 5.885e5),
        ),
        // 3 21 9 -W 300 200
        (
            0.462325,
            80,
            300.0,
            200.0,
            1.6386,
            0.3126,
            [-1.114779, -0.834425, 11.676818, -3.103259, 0.067977],
            (5763.0 / 46.74, 3.986e8 / 4.414e6),
        ),
        // 9 1 16 -a 39.74 -o 105.18 -m 105 -W 450 150
        (
            0.470014,
            244,
            450.0,
            150.0,
            2.2949,
            0.2369,
            [-0.982233, -0.526690, 12.588681, -3.232781, 0.037351],
            (5649.0 / 41.51, 6.036e8 / 6.621e6),
        ),
        // 11 5 11 -W 0 60
        (
            0.417868,
            309,
            0.0,
            60.0,
            1.0000,
            0.1027,
            [0.863222, -0.649906, 0.323380, -0.302083, -0.048834],
            (1459.0 / 12.00, 0.0),
        ),
    ];

    /// The Perez sky, scaled, gives back the diffuse horizontal illuminance it was scaled
    /// to, within the quadrature's stated 2 × 10⁻⁴, checked against an independent fine
    /// midpoint rule (800 × 1600 steps, f64) of the same luminance for clear, intermediate
    /// and overcast states.
    #[test]
    fn scaled_sky_integrates_to_the_diffuse_illuminance() {
        for (dhi, dni, alt) in [
            (120.0f32, 700.0f32, 60.0f32),
            (200.0, 300.0, 30.0),
            (80.0, 0.0, 20.0),
            (60.0, 850.0, 10.0),
        ] {
            let zenith = (90.0 - alt).to_radians();
            let c = Conditions::from_irradiance(dhi, dni, zenith, 172).unwrap();
            let sky = PerezSky::new(&c, direction(alt.to_radians(), 3.0)).unwrap();
            let e_dh = 15_000.0f32;
            let scale = sky.luminance_scale(e_dh).unwrap();
            let (nz, nphi) = (800u32, 1600u32);
            let (hz, hp) = (
                std::f64::consts::FRAC_PI_2 / f64::from(nz),
                2.0 * std::f64::consts::PI / f64::from(nphi),
            );
            let mut e = 0.0f64;
            for i in 0..nz {
                let z = (f64::from(i) + 0.5) * hz;
                let mut ring = 0.0f64;
                for j in 0..nphi {
                    let a = (f64::from(j) + 0.5) * hp;
                    let d = direction((std::f64::consts::FRAC_PI_2 - z) as f32, a as f32);
                    ring += f64::from(sky.relative_luminance(d));
                }
                e += ring * hp * z.cos() * z.sin() * hz;
            }
            e *= f64::from(scale);
            let rel = (e - f64::from(e_dh)).abs() / f64::from(e_dh);
            assert!(
                rel <= 2.0e-4,
                "ε {} sun {alt}°: {e} lx against {e_dh} ({rel:.1e})",
                c.clearness
            );
            let _ = horizontal_illuminance(&sky);
        }
    }

    #[test]
    fn bad_inputs_are_refused() {
        assert!(Conditions::from_irradiance(0.0, 100.0, 0.5, 100).is_err());
        assert!(Conditions::from_irradiance(-5.0, 100.0, 0.5, 100).is_err());
        assert!(Conditions::from_irradiance(100.0, -1.0, 0.5, 100).is_err());
        assert!(Conditions::from_irradiance(100.0, f32::NAN, 0.5, 100).is_err());
        assert!(Conditions::from_irradiance(100.0, 100.0, 1.7, 100).is_err());
        assert!(Conditions::from_illuminance(-1.0, 100.0, 0.5, 100, 2.0).is_err());
    }

    /// A clear state of a low sun (ε 7.4, Δ 0.20, the sun 0.9° up: what Greensboro's
    /// TMY3 illuminances at 19:30 EST on 14 July turn into through the efficacies at 4.2 cm
    /// of precipitable water) whose fitted `b` is positive: held at 0, the sky exists and
    /// has a finite scale.
    #[test]
    fn a_positive_b_is_held_at_zero() {
        let zenith = 89.102f32.to_radians();
        let c = Conditions::from_irradiance(9.7, 307.0, zenith, 195).unwrap();
        let bin = clearness_bin(c.clearness.clamp(1.0, 12.0));
        let row = &COEFFICIENTS[bin][1];
        let delta = c.brightness.clamp(0.01, 0.6);
        let delta = if c.clearness > 1.065 && c.clearness < 2.8 {
            delta.max(0.2)
        } else {
            delta
        };
        let fitted = row[0] + row[1] * zenith + delta * (row[2] + row[3] * zenith);
        assert!(
            fitted > 0.0,
            "the case should have a positive fitted b: {fitted}"
        );
        assert_eq!(c.coefficients()[1], 0.0);
        let sun = [0.0, (zenith).sin(), (zenith).cos()];
        let sky = PerezSky::new(&c, sun).unwrap();
        let scale = sky.luminance_scale(1000.0).unwrap();
        assert!(scale.is_finite() && scale > 0.0);
    }
}
