//! Writes the fuzzer's seed corpus: valid bases of every formulation, precision and band
//! count (`cargo test -p eigenrad-runtime --test seed_corpus -- --ignored` regenerates it).
#![allow(
    clippy::unwrap_used,
    clippy::expect_used,
    clippy::indexing_slicing,
    clippy::panic
)]

mod common;

use eigenrad_runtime::{Formulation, Precision};

#[test]
#[ignore = "writes files: run by hand to regenerate the fuzz seed corpus"]
fn write_seed_corpus() {
    let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/fuzz/corpus/decode_eval");
    std::fs::create_dir_all(dir).unwrap();
    std::fs::write(
        format!("{dir}/tiny.basis"),
        common::tiny().to_bytes().unwrap(),
    )
    .unwrap();
    std::fs::write(
        format!("{dir}/tiny-daylight.basis"),
        common::tiny_daylight().to_bytes().unwrap(),
    )
    .unwrap();
    std::fs::write(
        format!("{dir}/tiny-daylight-sun-first.basis"),
        common::tiny_daylight_sun_first([0.3, 0.2, 0.1])
            .to_bytes()
            .unwrap(),
    )
    .unwrap();
    std::fs::write(
        format!("{dir}/tiny-daylight-reflection.basis"),
        common::tiny_daylight_reflection().to_bytes().unwrap(),
    )
    .unwrap();
    for f in [Formulation::Split, Formulation::Seed] {
        for p in [Precision::F32, Precision::F16, Precision::I16] {
            for bands in [1, 3] {
                let bytes = common::random(21, f, p, bands).to_bytes().unwrap();
                std::fs::write(
                    format!("{dir}/{f:?}-{p:?}-{bands}band.basis").to_lowercase(),
                    bytes,
                )
                .unwrap();
            }
        }
    }
}
