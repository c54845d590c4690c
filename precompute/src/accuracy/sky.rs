//! How much a basis loses by taking the sky patch by patch: the direct daylight at the
//! outputs through one Reinhart subdivision against the next finer one (docs/math.md,
//! "Choosing the sky's patches"), and the build's choice of subdivision from a tolerance on
//! it (`eigenrad build --sky-tolerance`).

use eigenrad_runtime::sky::cie::CieSky;
use eigenrad_runtime::sky::patches::SkyPatches;
use eigenrad_runtime::sky::{direction, horizontal_illuminance};
use serde::Serialize;

use crate::error::{Error, Result};
use crate::formfactor::Occluders;
use crate::pipeline::SkySelection;
use crate::scene::Scene;
use crate::sources::daylight::{sky_response, DaylightOptions, SkyResponse};

/// The subdivisions `--sky-tolerance` tries, coarsest first; each is measured against twice
/// its own (MF:8, 9217 patches, is the finest reference).
pub const CANDIDATES: [u8; 3] = [1, 2, 4];

/// A reading whose reference value is below this share of the largest reading of the same
/// sky is left out of the relative error: at the far end of a deep room, or under a sensor
/// that faces away from the windows, a tiny reading's relative change says nothing of the
/// light a controller acts on.
pub const READING_FLOOR: f64 = 1e-2;

/// The sun's altitudes (degrees) of the clear skies the error is measured under, each at
/// the four compass points: a low, a middle and a high sun, whichever way the windows face.
const SUN_ALTITUDES_DEG: [f32; 3] = [15.0, 35.0, 55.0];

/// The sky-discretisation error of a basis' daylight: the direct daylight of every reading
/// (each output's direct illuminance, lux, and each diffusing window patch's transmitted
/// exitance) under the sky's patches of MF:`subdivision` against MF:`reference`
/// (`2 × subdivision`), under the reference skies: the traditional CIE overcast sky and
/// the CIE clear sky (standard type 12) with the sun at 15°, 35° and 55° due north, east,
/// south and west. Each sky's luminances are taken at its patches' centres, as the
/// controller takes them; the sun itself is not a patch (it is the sun nodes') and is left
/// out. The difference is relative to the reading under the finer sky; readings below
/// [`READING_FLOOR`] of that sky's largest are left out.
#[derive(Clone, Debug, Serialize, PartialEq)]
pub struct SkyDiscretisation {
    /// The subdivision measured (1: Tregenza's 145 patches).
    pub subdivision: u8,
    /// The finer subdivision it is measured against.
    pub reference: u8,
    /// Sky states measured.
    pub skies: usize,
    /// Readings measured (sky states times readings above the floor).
    pub readings: usize,
    /// Mean relative difference.
    pub mean: f64,
    /// Largest relative difference.
    pub max: f64,
}

/// The sky patches `selection` asks for, with their sky response (as
/// [`sky_response`] gives it) and, when the choice was made from a tolerance, the
/// discretisation error of the one chosen. `Err` when no candidate meets the tolerance,
/// naming the finest one's error.
pub fn choose(
    scene: &Scene,
    occluders: &Occluders,
    selection: SkySelection,
    opts: &DaylightOptions,
) -> Result<(SkyResponse, Option<SkyDiscretisation>)> {
    let response = |n: u8| -> Result<SkyResponse> {
        let patches = SkyPatches::reinhart(n).map_err(|e| Error::Daylight {
            what: "--mf".to_owned(),
            reason: e.to_string(),
        })?;
        Ok(sky_response(scene, occluders, patches, opts))
    };
    let tolerance = match selection {
        SkySelection::Subdivision(n) => return Ok((response(n)?, None)),
        SkySelection::Tolerance(t) => t,
    };
    let mut coarse = response(CANDIDATES[0])?;
    let mut last = None;
    for n in CANDIDATES {
        let fine = response(2 * n)?;
        let error = discretisation(&coarse, &fine)?;
        if error.max <= tolerance {
            return Ok((coarse, Some(error)));
        }
        last = Some(error);
        // Each candidate is twice the one before: its response is this one's reference.
        coarse = fine;
    }
    let error = last.expect("CANDIDATES is not empty");
    Err(Error::Daylight {
        what: format!("--sky-tolerance {tolerance}"),
        reason: format!(
            "the finest sky tried, Reinhart MF:{} ({} patches), is still {:.3} % from MF:{} \
             at the outputs; give a larger tolerance, or --mf to take a subdivision unchecked",
            error.subdivision,
            144 * u32::from(error.subdivision).pow(2) + 1,
            100.0 * error.max,
            error.reference
        ),
    })
}

/// [`SkyDiscretisation`] of `coarse` against `fine` (responses of one scene to two
/// subdivisions of the sky).
pub fn discretisation(coarse: &SkyResponse, fine: &SkyResponse) -> Result<SkyDiscretisation> {
    let mut skies = 0;
    let mut errors = Vec::new();
    for sky in reference_skies()? {
        let coarse = direct_readings(coarse, &sky)?;
        let fine = direct_readings(fine, &sky)?;
        let largest = fine.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        if largest <= 0.0 {
            continue;
        }
        skies += 1;
        errors.extend(
            coarse
                .iter()
                .zip(&fine)
                .filter(|(_, f)| f.abs() >= READING_FLOOR * largest)
                .map(|(c, f)| ((c - f) / f).abs()),
        );
    }
    Ok(SkyDiscretisation {
        subdivision: coarse.patches.subdivision(),
        reference: fine.patches.subdivision(),
        skies,
        readings: errors.len(),
        mean: if errors.is_empty() {
            0.0
        } else {
            errors.iter().sum::<f64>() / errors.len() as f64
        },
        max: errors.iter().copied().fold(0.0, f64::max),
    })
}

/// The reference skies of [`SkyDiscretisation`], in the site's frame.
fn reference_skies() -> Result<Vec<CieSky>> {
    let mut skies = vec![CieSky::traditional_overcast([0.0, 0.0, 1.0])?];
    for altitude in SUN_ALTITUDES_DEG {
        for azimuth in [0.0f32, 90.0, 180.0, 270.0] {
            let sun = direction(altitude.to_radians(), azimuth.to_radians());
            skies.push(CieSky::standard(12, sun)?);
        }
    }
    Ok(skies)
}

/// Every reading's direct daylight under `sky` (relative to its zenith luminance) through
/// `response`: the outputs' direct illuminance, then the windows' transmitted exitance, each
/// patch's luminance taken at its centre and the exterior glowing at `E_gh / π`.
fn direct_readings(response: &SkyResponse, sky: &CieSky) -> Result<Vec<f64>> {
    let patches = response.patches;
    let mut luminance = vec![0.0f32; patches.count()];
    patches.luminances(sky, 1.0, &mut luminance)?;
    let exterior = f64::from(horizontal_illuminance(sky)) / std::f64::consts::PI;
    let readings = |light: &crate::sources::ChannelLight| {
        let mut all = light.output_irradiance.concat();
        all.extend(light.emission.iter().flatten());
        all
    };
    let mut total: Vec<f64> = readings(&response.exterior)
        .into_iter()
        .map(|x| x * exterior)
        .collect();
    for (light, &l) in response.sky.iter().zip(&luminance) {
        for (t, x) in total.iter_mut().zip(readings(light)) {
            *t += f64::from(l) * x;
        }
    }
    Ok(total)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sources::ChannelLight;

    /// An unobstructed horizontal receiver's response to `patches`: each patch gives its
    /// projected solid angle (lux per cd/m²), the exterior nothing.
    fn horizontal_receiver(patches: SkyPatches) -> SkyResponse {
        let light = |e: f64| ChannelLight {
            emission: vec![Vec::new()],
            patch_irradiance: vec![Vec::new()],
            output_irradiance: vec![vec![e]],
        };
        SkyResponse {
            patches,
            sky: (0..patches.count())
                .map(|i| light(f64::from(patches.patch(i).unwrap().projected_solid_angle)))
                .collect(),
            exterior: light(0.0),
        }
    }

    /// The largest relative error of MF:`n`'s horizontal illuminance over the reference
    /// skies, against the skies' own hemisphere quadrature (`horizontal_illuminance`,
    /// within 2e-4 on clear skies): the truth the estimate stands for.
    fn true_error(n: u8) -> f64 {
        let response = horizontal_receiver(SkyPatches::reinhart(n).unwrap());
        reference_skies()
            .unwrap()
            .iter()
            .map(|sky| {
                let e = direct_readings(&response, sky).unwrap()[0];
                let exact = f64::from(horizontal_illuminance(sky));
                ((e - exact) / exact).abs()
            })
            .fold(0.0, f64::max)
    }

    /// On a horizontal receiver under the open sky, the estimate of MF:1 against MF:2 is
    /// within MF:2's own error (plus the quadrature's 2e-4 twice) of MF:1's true error, and
    /// the estimates shrink with the subdivision (docs/math.md's table of the horizontal
    /// illuminance: Tregenza within 0.2 % on overcast skies, 1.6 % on the most peaked).
    #[test]
    fn the_estimate_stands_for_the_true_error_on_a_horizontal_receiver() {
        let [one, two, four] =
            [1, 2, 4].map(|n| horizontal_receiver(SkyPatches::reinhart(n).unwrap()));
        let coarse = discretisation(&one, &two).unwrap();
        let finer = discretisation(&two, &four).unwrap();
        assert_eq!((coarse.subdivision, coarse.reference), (1, 2));
        assert_eq!((coarse.skies, coarse.readings), (13, 13));
        let (t1, t2) = (true_error(1), true_error(2));
        assert!(
            (coarse.max - t1).abs() <= t2 + 4e-4,
            "estimate {} against the true {t1} (MF:2's {t2})",
            coarse.max
        );
        assert!(coarse.max > 1e-4 && coarse.max < 1.6e-2, "{coarse:?}");
        assert!(finer.max < coarse.max, "{finer:?} against {coarse:?}");
        assert_eq!(discretisation(&one, &one).unwrap().max, 0.0);
    }
}
