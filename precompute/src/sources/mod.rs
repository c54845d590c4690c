//! What emits light into the room. Every kind of light source hands the radiosity model the
//! same thing, a [`ChannelLight`] per channel: the exitance its patches emit and the
//! irradiance it puts directly on every patch and output (docs/math.md, "Light sources:
//! emission and direct irradiance").
//!
//! - [`surfaces`]: emitting surfaces of the scene (luminaire faces, windows as Lambertian
//!   panels), grouped by the scene's channels.
//! - [`daylight`]: the sky, the ground and the sun through the scene's windows: their direct
//!   illuminance per sky patch, per unit of the exterior's luminance and per unit of direct
//!   normal illuminance.
//! - [`luminaires`]: luminaires placed with their photometry: no emission, their direct
//!   illuminance on every patch and output.
//!
//! The photometric files themselves (IES LM-63, EULUMDAT) are scene input, read by
//! [`crate::scene::photometry`].
//!
//! A channel may have both kinds; [`ChannelLight::plus`] adds their light.

pub mod daylight;
pub mod luminaires;
pub mod surfaces;

/// The light of one channel at level 1, per band: what the model needs of a light source.
///
/// Units: exitance and irradiance in W/m² per band (radiometric scenes) or lux (photopic).
/// The direct irradiance includes the scene's occlusion and counts all light that arrives
/// straight from the channel's sources, from its own emitting patches too.
#[derive(Clone, Debug, PartialEq)]
pub struct ChannelLight {
    /// Exitance emitted by each patch, `emission[band][patch]`; zero where the channel's
    /// sources are not patches of the scene.
    pub emission: Vec<Vec<f64>>,
    /// Direct irradiance on each patch, `patch_irradiance[band][patch]`.
    pub patch_irradiance: Vec<Vec<f64>>,
    /// Direct irradiance at each output, `output_irradiance[band][output]`: sensors, then
    /// zones (a zone's value is the area-weighted mean over its patches or work-plane
    /// receivers).
    pub output_irradiance: Vec<Vec<f64>>,
}

impl ChannelLight {
    /// Number of bands.
    pub fn bands(&self) -> usize {
        self.emission.len()
    }

    /// The light of two sources of one channel together: emission and direct irradiance
    /// added entry by entry (light is additive).
    ///
    /// # Panics
    ///
    /// When the two are not of the same shape (bands, patches, outputs): they would not be
    /// lights of the same scene.
    pub fn plus(&self, other: &ChannelLight) -> ChannelLight {
        let add = |a: &[Vec<f64>], b: &[Vec<f64>], what: &str| -> Vec<Vec<f64>> {
            let shape = |x: &[Vec<f64>]| x.iter().map(Vec::len).collect::<Vec<_>>();
            assert_eq!(shape(a), shape(b), "{what} of different shapes");
            a.iter()
                .zip(b)
                .map(|(x, y)| x.iter().zip(y).map(|(p, q)| p + q).collect())
                .collect()
        };
        ChannelLight {
            emission: add(&self.emission, &other.emission, "emission"),
            patch_irradiance: add(
                &self.patch_irradiance,
                &other.patch_irradiance,
                "patch irradiance",
            ),
            output_irradiance: add(
                &self.output_irradiance,
                &other.output_irradiance,
                "output irradiance",
            ),
        }
    }
}

impl ChannelLight {
    /// This light times `factor`: a source's response per unit of what drives it, taken at a
    /// given drive (a sky patch's luminance, the sun's direct normal illuminance).
    pub fn scaled(&self, factor: f64) -> ChannelLight {
        let times = |x: &[Vec<f64>]| -> Vec<Vec<f64>> {
            x.iter()
                .map(|v| v.iter().map(|y| y * factor).collect())
                .collect()
        };
        ChannelLight {
            emission: times(&self.emission),
            patch_irradiance: times(&self.patch_irradiance),
            output_irradiance: times(&self.output_irradiance),
        }
    }

    /// Adds `factor` times `other` to this light, entry by entry.
    ///
    /// # Panics
    ///
    /// As [`ChannelLight::plus`], when the two are not of the same shape.
    pub fn add_scaled(&mut self, other: &ChannelLight, factor: f64) {
        let add = |a: &mut [Vec<f64>], b: &[Vec<f64>], what: &str| {
            assert_eq!(a.len(), b.len(), "{what} of different band counts");
            for (x, y) in a.iter_mut().zip(b) {
                assert_eq!(x.len(), y.len(), "{what} of different lengths");
                for (p, q) in x.iter_mut().zip(y) {
                    *p += factor * q;
                }
            }
        };
        add(&mut self.emission, &other.emission, "emission");
        add(
            &mut self.patch_irradiance,
            &other.patch_irradiance,
            "patch irradiance",
        );
        add(
            &mut self.output_irradiance,
            &other.output_irradiance,
            "output irradiance",
        );
    }
}

/// The part of a channel's direct light that its own emitting patches do not account for:
/// light from sources that are not patches of the scene (a luminaire's photometry, the sky).
/// The radiosity model propagates patch emission itself (its first bounce is `R F e`, its
/// reading at an output `Σ_j R_oj e_j`); this remainder enters as first-reflected exitance
/// `ρ ∘ E_ext` and as direct irradiance at the outputs (docs/math.md, "Light sources: emission
/// and direct irradiance").
///
/// Per band; `None` where the remainder is zero, as it is for emitting surfaces.
#[derive(Clone, Debug, PartialEq)]
pub struct ExternalLight {
    /// `E_ext = E_d − F e` on every patch, W/m² or lux.
    pub patches: Vec<Option<Vec<f64>>>,
    /// `E_d,o − Σ_j R_oj e_j` at every output (sensors, then zones), W/m² or lux.
    pub outputs: Vec<Option<Vec<f64>>>,
}

impl ChannelLight {
    /// What remains of this light beyond its patches' emission, through the same exchange
    /// functions a producer uses (so that emitting surfaces leave exactly nothing). `g` is
    /// `G = A F` (m²), `area` the patch areas (m²), `output_rows` the sensor and zone rows.
    pub fn external(
        &self,
        g: &dyn crate::formfactor::FormFactorOperator,
        area: &[f64],
        output_rows: &[Vec<f64>],
    ) -> ExternalLight {
        use crate::formfactor::exchange;
        let remainder = |direct: &[f64], carried: Vec<f64>| {
            let rest: Vec<f64> = direct.iter().zip(&carried).map(|(d, c)| d - c).collect();
            rest.iter().any(|x| *x != 0.0).then_some(rest)
        };
        ExternalLight {
            patches: (0..self.bands())
                .map(|b| {
                    remainder(
                        &self.patch_irradiance[b],
                        exchange::patch_irradiance(g, area, &self.emission[b]),
                    )
                })
                .collect(),
            outputs: (0..self.bands())
                .map(|b| {
                    remainder(
                        &self.output_irradiance[b],
                        exchange::output_irradiance(output_rows, &self.emission[b]),
                    )
                })
                .collect(),
        }
    }
}
