//! Any bytes as the gbXML model of a scene's `[[import]]` ([`building_model`]).
#![no_main]

use libfuzzer_sys::fuzz_target;

mod building_model;

fuzz_target!(|data: &[u8]| building_model::import("gbxml", "model.xml", data));
