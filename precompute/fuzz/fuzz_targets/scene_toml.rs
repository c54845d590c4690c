//! Any text as a scene file placed in `examples/office/`, so that the files it names resolve
//! against the shipped examples (photometry, OBJ): read, validated and meshed, or an error.
//! Nothing may panic; a scene that builds has finite, positive patch areas.
#![no_main]

use std::path::Path;

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    // `scene::load` reads the file as UTF-8 text and refuses anything else before parsing.
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    let origin = Path::new(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../examples/office/scene.toml"
    ));
    if let Ok(scene) = eigenrad_precompute::scene::parse(text, origin) {
        for patch in &scene.patches {
            assert!(patch.area.is_finite() && patch.area > 0.0);
        }
    }
});
