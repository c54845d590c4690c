//! Angular transmittance of glazing: the visible transmittance τ(θ) at incidence angle θ
//! from the transmittance at normal incidence τ_n.
//!
//! **Clear glass** (one or more identical uncoated panes): each surface reflects by
//! Fresnel's equations for refractive index n = 1.52 (soda-lime glass), separately for the
//! s and p polarisations; the glass absorbs along the refracted ray by Bouguer's law, an
//! internal transmittance `a(θ) = a_0^(1/cos θ_t)`; reflections between the two surfaces of
//! a pane, and between panes, add incoherently:
//!
//! ```text
//! pane:   T = (1 − r)² a / (1 − r² a²),   R = r + (1 − r)² r a² / (1 − r² a²)
//! panes:  T₁₂ = T₁ T₂ / (1 − R₁ R₂)
//! ```
//!
//! and τ(θ) is the mean of the s and p transmittances. `a_0` is solved for so that
//! τ(0) = τ_n. One pane is the model of Radiance's `glass` material; τ(0) = τ_n and
//! τ(90°) = 0 hold by construction. τ_n can be at most the value of non-absorbing glass
//! (0.9183 for one pane, 0.8491 for two, 0.7894 for three).
//!
//! **Diffusing glazing**: the same angular transmittance as clear glass of the same τ_n
//! and panes, but what it transmits leaves the inner surface as a Lambertian emitter
//! (uniform luminance over the room-side hemisphere) instead of keeping its direction.

use crate::error::{Error, Result};

/// Refractive index of the glass.
pub const REFRACTIVE_INDEX: f32 = 1.52;

/// Most panes a glazing may have.
pub const MAX_PANES: u8 = 3;

/// A glazing's angular model.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Glazing {
    panes: u8,
    normal: f32,
    /// Internal transmittance of one pane at normal incidence, `a_0`.
    internal: f32,
    diffusing: bool,
}

/// s and p reflectance of one air–glass surface at incidence cosine `cos_i`, and the cosine
/// of the refracted ray.
fn fresnel(cos_i: f32) -> (f32, f32, f32) {
    let n = REFRACTIVE_INDEX;
    let sin_i2 = (1.0 - cos_i * cos_i).max(0.0);
    let cos_t = libm::sqrtf((1.0 - sin_i2 / (n * n)).max(0.0));
    let rs = (cos_i - n * cos_t) / (cos_i + n * cos_t);
    let rp = (n * cos_i - cos_t) / (n * cos_i + cos_t);
    (rs * rs, rp * rp, cos_t)
}

/// (T, R) of one pane for surface reflectance `r` and internal transmittance `a`.
fn pane(r: f32, a: f32) -> (f32, f32) {
    let denominator = 1.0 - r * r * a * a;
    if denominator <= 0.0 {
        return (0.0, 1.0);
    }
    let t = (1.0 - r) * (1.0 - r) * a / denominator;
    (t, r + (1.0 - r) * (1.0 - r) * r * a * a / denominator)
}

/// Transmittance of `panes` identical panes for one polarisation.
fn stack(r: f32, a: f32, panes: u8) -> f32 {
    let (t1, r1) = pane(r, a);
    let (mut t, mut rr) = (t1, r1);
    for _ in 1..panes {
        // Adding a pane on the far side: T = T t1/(1 − R r1); R seen from the near side.
        let d = 1.0 - rr * r1;
        if d <= 0.0 {
            return 0.0;
        }
        let new_t = t * t1 / d;
        rr += t * t * r1 / d;
        t = new_t;
    }
    t
}

/// τ at incidence cosine `cos_i` for internal transmittance `a0`.
fn transmittance(cos_i: f32, a0: f32, panes: u8) -> f32 {
    if cos_i <= 0.0 {
        return 0.0;
    }
    let (rs, rp, cos_t) = fresnel(cos_i.min(1.0));
    let a = if cos_t > 0.0 {
        libm::powf(a0, 1.0 / cos_t)
    } else {
        0.0
    };
    0.5 * (stack(rs, a, panes) + stack(rp, a, panes))
}

impl Glazing {
    /// Clear glazing of `panes` panes (1 to [`MAX_PANES`]) with visible transmittance `normal`
    /// at normal incidence (above 0, at most that of non-absorbing glass with as many
    /// panes).
    pub fn clear(normal: f32, panes: u8) -> Result<Self> {
        if !(1..=MAX_PANES).contains(&panes) {
            return Err(Error::OutOfRange {
                what: "glazing panes",
                range: "from 1 to 3",
            });
        }
        let most = transmittance(1.0, 1.0, panes);
        if !(normal > 0.0 && normal <= most) {
            return Err(Error::OutOfRange {
                what: "glazing normal transmittance τ_n",
                range: "above 0 and at most that of non-absorbing glass (0.9183 for one pane, 0.8491 for two, 0.7894 for three)",
            });
        }
        // τ(0) grows with a0: bisection on (0, 1], 40 halvings (below f32's resolution).
        let (mut low, mut high) = (0.0f32, 1.0f32);
        for _ in 0..40 {
            let mid = 0.5 * (low + high);
            if transmittance(1.0, mid, panes) < normal {
                low = mid;
            } else {
                high = mid;
            }
        }
        Ok(Self {
            panes,
            normal,
            internal: 0.5 * (low + high),
            diffusing: false,
        })
    }

    /// Diffusing glazing: as [`Self::clear`], transmitting into a Lambertian distribution.
    pub fn diffusing(normal: f32, panes: u8) -> Result<Self> {
        Ok(Self {
            diffusing: true,
            ..Self::clear(normal, panes)?
        })
    }

    /// Whether transmitted light leaves as a Lambertian emitter (diffusing glazing).
    pub fn is_diffusing(&self) -> bool {
        self.diffusing
    }

    /// Panes.
    pub fn panes(&self) -> u8 {
        self.panes
    }

    /// Transmittance at normal incidence, τ_n.
    pub fn normal_transmittance(&self) -> f32 {
        self.normal
    }

    /// Internal transmittance of one pane at normal incidence (the absorption solved for).
    pub fn internal_transmittance(&self) -> f32 {
        self.internal
    }

    /// Transmittance at incidence angle `theta` (rad from the glazing's normal): τ_n at 0,
    /// 0 at π/2 and beyond (and for NaN).
    pub fn transmittance(&self, theta: f32) -> f32 {
        if !(0.0..core::f32::consts::FRAC_PI_2).contains(&theta) {
            return 0.0;
        }
        if theta == 0.0 {
            return self.normal;
        }
        transmittance(libm::cosf(theta), self.internal, self.panes)
    }
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, clippy::indexing_slicing)]
    // The f64 references use std's float functions.
    extern crate std;
    use super::*;

    /// An independent single-pane model in f64: Fresnel's sine and tangent forms
    /// (`r_s = sin²(θ − θ_t)/sin²(θ + θ_t)`, `r_p = tan²(θ − θ_t)/tan²(θ + θ_t)`), absorption
    /// `a_0^(1/cos θ_t)`, and the pane's interreflections as the explicit series
    /// `(1 − r)² a Σ (r a)^(2k)` summed to 200 terms.
    fn reference(theta: f64, a0: f64) -> f64 {
        let n = f64::from(REFRACTIVE_INDEX);
        if theta == 0.0 {
            let r = ((n - 1.0) / (n + 1.0)).powi(2);
            return (0..200)
                .map(|k| (1.0 - r).powi(2) * a0 * (r * a0).powi(2 * k))
                .sum();
        }
        let t = (theta.sin() / n).asin();
        let rs = ((theta - t).sin() / (theta + t).sin()).powi(2);
        let rp = ((theta - t).tan() / (theta + t).tan()).powi(2);
        let a = a0.powf(1.0 / t.cos());
        let series = |r: f64| -> f64 {
            (0..200)
                .map(|k| (1.0 - r).powi(2) * a * (r * a).powi(2 * k))
                .sum()
        };
        0.5 * (series(rs) + series(rp))
    }

    /// τ(0) = τ_n, τ(60°) against the independent model, τ(90°) = 0. Tolerance 10⁻⁵
    /// absolute (f32; the bisection resolves a_0 to 10⁻⁷).
    #[test]
    fn single_pane_against_fresnel() {
        for tau_n in [0.9f32, 0.85, 0.6] {
            let g = Glazing::clear(tau_n, 1).unwrap();
            let a0 = f64::from(g.internal_transmittance());
            assert!((reference(0.0, a0) - f64::from(tau_n)).abs() <= 1.0e-5);
            assert_eq!(g.transmittance(0.0), tau_n);
            for deg in [30.0f64, 60.0, 80.0] {
                let ours = f64::from(g.transmittance((deg as f32).to_radians()));
                let want = reference(deg.to_radians(), a0);
                assert!(
                    (ours - want).abs() <= 1.0e-5,
                    "τ_n {tau_n} at {deg}°: {ours} against {want}"
                );
            }
            assert_eq!(g.transmittance(core::f32::consts::FRAC_PI_2), 0.0);
            assert!(g.transmittance(1.5706) < 0.01);
        }
    }

    /// Non-absorbing glass: one surface at normal incidence reflects ((n − 1)/(n + 1))² =
    /// 0.042580; a pane transmits (1 − r)/(1 + r) = 0.91832 (closed form of the series).
    #[test]
    fn clearest_glass_closed_form() {
        let r = ((1.52f64 - 1.0) / 2.52).powi(2);
        let most = (1.0 - r) / (1.0 + r);
        let clearest = transmittance(1.0, 1.0, 1);
        assert!((f64::from(clearest) - most).abs() <= 1.0e-6);
        let g = Glazing::clear(clearest, 1).unwrap();
        assert!((f64::from(g.internal_transmittance()) - 1.0).abs() <= 1.0e-5);
        assert!(Glazing::clear(0.95, 1).is_err());
        assert!(Glazing::clear(0.8, 2).is_ok());
        assert!(Glazing::clear(0.86, 2).is_err());
        assert!(Glazing::clear(0.5, 0).is_err());
        assert!(Glazing::clear(f32::NAN, 1).is_err());
        assert!(Glazing::clear(0.0, 1).is_err());
    }

    /// Two panes without absorption against the closed form of two identical
    /// non-absorbing slabs per polarisation, T₂ = T₁/(2 − T₁) (T₁₂ = T²/(1 − R²), R = 1 − T),
    /// at 45°.
    #[test]
    fn double_pane_closed_form() {
        let theta = 45f64.to_radians();
        let n = f64::from(REFRACTIVE_INDEX);
        let t = (theta.sin() / n).asin();
        let rs = ((theta - t).sin() / (theta + t).sin()).powi(2);
        let rp = ((theta - t).tan() / (theta + t).tan()).powi(2);
        let slab = |r: f64| (1.0 - r) / (1.0 + r);
        let two = |r: f64| {
            let t1 = slab(r);
            t1 / (2.0 - t1)
        };
        let want = 0.5 * (two(rs) + two(rp));
        let g = Glazing::clear(transmittance(1.0, 1.0, 2), 2).unwrap();
        let ours = f64::from(g.transmittance(theta as f32));
        assert!((ours - want).abs() <= 1.0e-5, "{ours} against {want}");
    }

    /// The absorption solved for against Radiance's published conversion from normal
    /// transmittance T_n to the `glass` material's transmissivity (Radiance reference manual,
    /// "Glass"): `t_n = (sqrt(0.8402528435 + 0.0072522239 T_n²) − 0.9166530661) /
    /// 0.0036261119 / T_n`, the same single pane with n = 1.52. Tolerance 10⁻⁵ (f32).
    #[test]
    fn internal_transmittance_is_radiance_glass_transmissivity() {
        for tau_n in [0.88f64, 0.8, 0.6, 0.3] {
            let radiance = ((0.8402528435 + 0.0072522239 * tau_n * tau_n).sqrt() - 0.9166530661)
                / 0.0036261119
                / tau_n;
            let g = Glazing::clear(tau_n as f32, 1).unwrap();
            let ours = f64::from(g.internal_transmittance());
            assert!(
                (ours - radiance).abs() <= 1.0e-5,
                "τ_n {tau_n}: {ours} against {radiance}"
            );
        }
    }

    #[test]
    fn diffusing_keeps_the_angular_law() {
        let c = Glazing::clear(0.7, 2).unwrap();
        let d = Glazing::diffusing(0.7, 2).unwrap();
        assert!(d.is_diffusing() && !c.is_diffusing());
        assert_eq!(c.transmittance(1.0), d.transmittance(1.0));
        assert_eq!(d.transmittance(f32::NAN), 0.0);
    }
}
