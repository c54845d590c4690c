//! Any text as a building manifest beside copies of the example building's scenes (and the
//! photometry they name), read and checked against those scenes as `eigenrad building` does.
//! Nothing may panic; a manifest that reads has rooms, and controllers that read something.
#![no_main]

use std::path::{Path, PathBuf};
use std::sync::OnceLock;

use eigenrad_precompute::building::Manifest;
use libfuzzer_sys::fuzz_target;

/// A folder of this process's own: `building/` holds the example's scenes and each input's
/// manifest, `photometry/` the files the scenes name.
fn folder() -> &'static Path {
    static FOLDER: OnceLock<PathBuf> = OnceLock::new();
    FOLDER.get_or_init(|| {
        let root =
            std::env::temp_dir().join(format!("eigenrad-fuzz-building-{}", std::process::id()));
        let examples = Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../../examples"));
        for (from, to) in [("building", "building"), ("photometry", "photometry")] {
            std::fs::create_dir_all(root.join(to)).expect("a temporary folder");
            for entry in std::fs::read_dir(examples.join(from)).expect("the examples").flatten() {
                if entry.path().is_file() {
                    std::fs::copy(entry.path(), root.join(to).join(entry.file_name()))
                        .expect("an example copied");
                }
            }
        }
        root.join("building")
    })
}

fuzz_target!(|data: &[u8]| {
    let manifest = folder().join("fuzz-building.toml");
    std::fs::write(&manifest, data).expect("the manifest written");
    if let Ok(building) = Manifest::load(&manifest) {
        assert!(!building.rooms.is_empty());
    }
});
