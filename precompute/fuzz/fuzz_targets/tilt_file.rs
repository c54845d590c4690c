//! Any bytes as a tilt table in a file of its own (`TILT=lamp.tlt`), read with the IES file
//! that names it. Nothing may panic; a table that reads gives finite, non-negative factors.
#![no_main]

use std::path::{Path, PathBuf};
use std::sync::OnceLock;

use eigenrad_precompute::geometry::Vec3;
use eigenrad_precompute::scene::photometry;
use libfuzzer_sys::fuzz_target;

/// An isotropic 1000 cd lamp whose tilt table is in `lamp.tlt`.
const IES: &str = "IESNA:LM-63-2002\n[TEST] fuzz\nTILT=lamp.tlt\n\
1 -1 1 3 1 1 2 0.1 0.1 0\n1 1 10\n0 45 90\n0\n1000 1000 1000\n";

fn folder() -> &'static Path {
    static FOLDER: OnceLock<PathBuf> = OnceLock::new();
    FOLDER.get_or_init(|| {
        let folder =
            std::env::temp_dir().join(format!("eigenrad-fuzz-tilt-{}", std::process::id()));
        std::fs::create_dir_all(&folder).expect("a temporary folder for the fuzzed files");
        std::fs::write(folder.join("lamp.ies"), IES).expect("the IES file written");
        folder
    })
}

fuzz_target!(|data: &[u8]| {
    let folder = folder();
    std::fs::write(folder.join("lamp.tlt"), data).expect("the tilt file written");
    if let Ok(lamp) = photometry::read(&folder.join("lamp.ies")) {
        let flux = lamp.flux();
        assert!(flux.is_finite() && flux >= 0.0, "flux {flux} lm");
        // Pointing down, tipped 30° and lying on its side: three angles of the table.
        let (s, c) = (0.5, 0.75f64.sqrt());
        for (nadir, c0) in [
            (Vec3::new(0.0, 0.0, -1.0), Vec3::new(1.0, 0.0, 0.0)),
            (Vec3::new(s, 0.0, -c), Vec3::new(c, 0.0, s)),
            (Vec3::new(1.0, 0.0, 0.0), Vec3::new(0.0, 0.0, 1.0)),
        ] {
            let c90 = nadir.cross(c0);
            let factor = lamp.tilt_factor(nadir, c0, c90);
            assert!(factor.is_finite() && factor >= 0.0, "tilt factor {factor}");
        }
    }
});
