//! Any bytes as an OBJ file and its MTL (split at the first 0xFF byte, which UTF-8 text never
//! holds), loaded through a scene that names the OBJ, as `eigenrad build` loads them. The MTL
//! is written under every name the OBJ's `mtllib` lines give. Nothing may panic.
#![no_main]

use std::path::{Path, PathBuf};
use std::sync::OnceLock;

use libfuzzer_sys::fuzz_target;

const SCENE: &str = r#"
[scene]
name = "fuzz"
bands = "rgb"
unit = "m"
max_edge = 0.5

[[obj]]
file = "model.obj"
up = "y"
"#;

/// A folder of this process's own for the files of each input.
fn folder() -> &'static Path {
    static FOLDER: OnceLock<PathBuf> = OnceLock::new();
    FOLDER.get_or_init(|| {
        let folder = std::env::temp_dir().join(format!("eigenrad-fuzz-obj-{}", std::process::id()));
        std::fs::create_dir_all(&folder).expect("a temporary folder for the fuzzed files");
        folder
    })
}

fuzz_target!(|data: &[u8]| {
    let (obj, mtl) = match data.iter().position(|&b| b == 0xFF) {
        Some(at) => (&data[..at], &data[at + 1..]),
        None => (data, &[][..]),
    };
    let folder = folder();
    // Last input's files must not leak into this one.
    for entry in std::fs::read_dir(folder).into_iter().flatten().flatten() {
        let _ = std::fs::remove_file(entry.path());
    }
    std::fs::write(folder.join("model.obj"), obj).expect("the OBJ written");
    for line in String::from_utf8_lossy(obj).lines() {
        let mut words = line.split_whitespace();
        if words.next() != Some("mtllib") {
            continue;
        }
        for name in words {
            // Only plain names inside the folder: the fuzzer must not write elsewhere.
            let plain = !name.contains(['/', '\\']) && name != "." && name != "..";
            if plain && name != "model.obj" && name != "scene.toml" {
                let _ = std::fs::write(folder.join(name), mtl);
            }
        }
    }
    let _ = eigenrad_precompute::scene::parse(SCENE, &folder.join("scene.toml"));
});
