//! Any bytes as an IES LM-63 file (first byte even) or a EULUMDAT file (odd), with the tilt
//! table inline when the file has one. Nothing may panic; a file that reads has a finite,
//! non-negative flux and intensities.
#![no_main]

use std::path::Path;

use eigenrad_precompute::scene::photometry::{eulumdat, ies};
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let Some((&choice, bytes)) = data.split_first() else {
        return;
    };
    let read = if choice % 2 == 0 {
        ies::parse(Path::new("fuzz.ies"), bytes)
    } else {
        eulumdat::parse(Path::new("fuzz.ldt"), bytes)
    };
    if let Ok(photometry) = read {
        let flux = photometry.flux();
        assert!(flux.is_finite() && flux >= 0.0, "flux {flux} lm");
        for c in [0.0, 45.0, 90.0, 180.0, 270.0, 359.0] {
            for gamma in [0.0, 30.0, 90.0, 135.0, 180.0] {
                let intensity = photometry.intensity(c, gamma);
                assert!(intensity.is_finite() && intensity >= 0.0, "{intensity} cd");
            }
        }
    }
});
