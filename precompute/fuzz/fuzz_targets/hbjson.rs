//! Any bytes as the Honeybee model (HBJSON) of a scene's `[[import]]`: read, its spaces laid out as
//! rooms and meshed, or an error. Nothing may panic; a scene that builds has finite, positive
//! patch areas.
#![no_main]

use libfuzzer_sys::fuzz_target;

/// The scene importing the model, every kind of face mapped to a material of its own.
const SCENE: &str = r#"[scene]
name = "fuzz"
bands = "photopic"
unit = "m"
max_edge = 2.0

[materials]
wall = { reflectance = 0.5 }
glass = { reflectance = 0.08, transmittance = 0.6 }

[[import]]
file = "model.hbjson"
materials = { Wall = "wall", Floor = "wall", RoofCeiling = "wall", Aperture = "glass", Door = "wall" }
"#;

fuzz_target!(|data: &[u8]| {
    // The import reads the model from a file beside the scene.
    let dir = std::env::temp_dir().join(format!("eigenrad-fuzz-hbjson-{}", std::process::id()));
    if std::fs::create_dir_all(&dir).is_err() || std::fs::write(dir.join("model.hbjson"), data).is_err() {
        return;
    }
    if let Ok(scene) = eigenrad_precompute::scene::parse(SCENE, &dir.join("scene.toml")) {
        for patch in &scene.patches {
            assert!(patch.area.is_finite() && patch.area > 0.0);
        }
    }
});
