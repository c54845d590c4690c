//! What the building-model importers' targets share: any bytes as the model file of a scene's
//! `[[import]]` (HBJSON or gbXML, told by the file's extension), read, its spaces laid out as
//! rooms and meshed, or an error. Nothing may panic; a scene that builds has finite, positive
//! patch areas.

/// The scene importing `model`, every kind of face mapped to a material of its own.
fn scene(model: &str) -> String {
    format!(
        r#"[scene]
name = "fuzz"
bands = "photopic"
unit = "m"
max_edge = 2.0

[materials]
wall = {{ reflectance = 0.5 }}
glass = {{ reflectance = 0.08, transmittance = 0.6 }}

[[import]]
file = "{model}"
materials = {{ Wall = "wall", Floor = "wall", RoofCeiling = "wall", Aperture = "glass", Door = "wall" }}
"#
    )
}

/// Writes `data` as the file `model` (its extension names the format) beside a scene that
/// imports it, in a folder of this process's own named after `format`, and parses the scene.
pub fn import(format: &str, model: &str, data: &[u8]) {
    // The import reads the model from a file beside the scene.
    let dir = std::env::temp_dir().join(format!("eigenrad-fuzz-{format}-{}", std::process::id()));
    if std::fs::create_dir_all(&dir).is_err() || std::fs::write(dir.join(model), data).is_err() {
        return;
    }
    if let Ok(scene) = eigenrad_precompute::scene::parse(&scene(model), &dir.join("scene.toml")) {
        for patch in &scene.patches {
            assert!(patch.area.is_finite() && patch.area > 0.0);
        }
    }
}
