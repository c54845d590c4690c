//! Emitting surfaces as light sources: a channel's surfaces emit their exitance at level 1
//! (`e`, from the scene's materials and flux), and their direct irradiance is what that
//! exitance sends through the form factors, `F e` on the patches and `Σ_j R_oj e_j` at the
//! outputs, occlusion included (the form factors and output rows carry it).

use super::ChannelLight;
use crate::formfactor::exchange;
use crate::formfactor::FormFactorOperator;
use crate::scene::Scene;

/// The light of every channel of `scene` from its emitting surfaces, in channel order.
///
/// `g` is `G = A F` (m², symmetrised), `area` the patch areas (m²) and `output_rows` the
/// sensor and zone rows of [`crate::formfactor::outputs::output_rows`].
pub fn channel_lights(
    scene: &Scene,
    g: &dyn FormFactorOperator,
    area: &[f64],
    output_rows: &[Vec<f64>],
) -> Vec<ChannelLight> {
    let bands = scene.bands.count();
    (0..scene.channels.len())
        .map(|c| {
            let emission: Vec<Vec<f64>> = (0..bands)
                .map(|b| {
                    scene
                        .emission
                        .iter()
                        .zip(&scene.channel_of_patch)
                        .map(|(e, owner)| if *owner == Some(c) { e[b] } else { 0.0 })
                        .collect()
                })
                .collect();
            ChannelLight {
                patch_irradiance: emission
                    .iter()
                    .map(|e| exchange::patch_irradiance(g, area, e))
                    .collect(),
                output_irradiance: emission
                    .iter()
                    .map(|e| exchange::output_irradiance(output_rows, e))
                    .collect(),
                emission,
            }
        })
        .collect()
}
