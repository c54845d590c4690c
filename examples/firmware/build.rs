//! Copies the basis chosen at build time (`EIGENRAD_BASIS`, a path) into `OUT_DIR/basis.bin`
//! for `include_bytes!`, and puts `memory.x` where the linker finds it. When the basis carries
//! daylight, sets the `daylight` configuration: the firmware then also steps through two days
//! (`src/daylight.rs`); without it, that code is not linked.

use std::path::PathBuf;
use std::{env, fs};

/// The basis used when `EIGENRAD_BASIS` is not set: the runtime's 2-patch golden file.
const DEFAULT_BASIS: &str = "../../runtime/tests/data/tiny.basis";

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let out = PathBuf::from(env::var("OUT_DIR")?);
    let manifest = PathBuf::from(env::var("CARGO_MANIFEST_DIR")?);

    println!("cargo:rerun-if-env-changed=EIGENRAD_BASIS");
    let basis = match env::var_os("EIGENRAD_BASIS") {
        Some(path) => PathBuf::from(path),
        None => manifest.join(DEFAULT_BASIS),
    };
    let basis = if basis.is_relative() {
        manifest.join(basis)
    } else {
        basis
    };
    println!("cargo:rerun-if-changed={}", basis.display());
    fs::copy(&basis, out.join("basis.bin"))
        .map_err(|e| format!("EIGENRAD_BASIS={}: {e}", basis.display()))?;

    // A basis the runtime refuses builds without daylight: the firmware reports the error.
    println!("cargo:rustc-check-cfg=cfg(daylight)");
    let bytes = fs::read(&basis)?;
    if eigenrad_runtime::Basis::from_bytes(&bytes).is_ok_and(|b| b.has_daylight()) {
        println!("cargo:rustc-cfg=daylight");
    }

    fs::copy(manifest.join("memory.x"), out.join("memory.x"))?;
    println!("cargo:rustc-link-search={}", out.display());
    println!("cargo:rerun-if-changed=memory.x");
    Ok(())
}
