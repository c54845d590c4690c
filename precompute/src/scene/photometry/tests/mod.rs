//! Tests of the photometric model and readers, on the synthetic files of `testdata/` (see its
//! README): closed forms of flux, the symmetries against equivalent full files, interpolation,
//! malformed files, and Radiance's `ies2rad` where it is installed.

mod eulumdat;
mod ies;
mod malformed;
mod model;
mod radiance;

use std::path::{Path, PathBuf};

use super::Photometry;

/// A file of `testdata/`.
fn data(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("src/scene/photometry/testdata")
        .join(name)
}

/// Reads a file of `testdata/`, which must be valid.
fn load(name: &str) -> Photometry {
    super::read(&data(name)).unwrap_or_else(|e| panic!("{e}"))
}

/// The synthetic files' γ profile, cd: `60 + 30 cos γ`.
fn profile(gamma: f64) -> f64 {
    60.0 + 30.0 * gamma.to_radians().cos()
}

/// The flux of the synthetic symmetric distributions, lm: `2π ∫ (60 + 30 cos γ) sin γ dγ`;
/// their C factors average to 1.
const SYMMETRIC_FLUX: f64 = 2.0 * std::f64::consts::PI * 120.0;

/// How far the flux of the interpolant of `profile` on a γ step of `step` degrees may be from
/// `SYMMETRIC_FLUX`, lm, C factors up to 1.6 included: linear interpolation errs by at most
/// `h²/8 · max|I''|`, with `max|I''| = 30 · 1.6` cd, over a sphere of 4π sr.
fn interpolation_bound(step: f64) -> f64 {
    step.to_radians().powi(2) / 8.0 * 30.0 * 1.6 * 4.0 * std::f64::consts::PI
}
