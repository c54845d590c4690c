//! Any bytes as a controller file (`eigenrad simulate --controller`), checked against the
//! runtime's tiny test basis (channel `main`, sensor `desk`, zone `plane`). Nothing may panic;
//! a controller that reads names the basis' sensor, at least one of its zones with a target
//! from 0 to 100 000 lux, every channel with a power from 0 to 100 kW and a dimming range
//! within [0, 1].
#![no_main]

use std::path::Path;

use eigenrad_precompute::simulate;
use eigenrad_runtime::Basis;
use libfuzzer_sys::fuzz_target;

static TINY: &[u8] = include_bytes!("../../../runtime/tests/data/tiny.basis");

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    let basis = Basis::from_bytes(TINY).expect("the tiny basis decodes");
    let Ok(c) = simulate::parse_controller(Path::new("fuzz.toml"), text, &basis) else {
        return;
    };
    assert_eq!(c.sensor.1, 0);
    assert!(!c.targets.is_empty());
    for t in &c.targets {
        assert!(t.illuminance > 0.0 && t.illuminance <= 1.0e5);
    }
    assert_eq!(c.channels.len(), basis.channel_count());
    for ch in &c.channels {
        assert!((0.0..=1.0e5).contains(&ch.full_w));
        assert!((0.0..=1.0).contains(&ch.minimum_level));
        assert!((0.0..=1.0).contains(&ch.power_at_minimum));
        for level in [0.0, ch.minimum_level, 0.5, 1.0] {
            let p = ch.power(level);
            assert!(p.is_finite() && p >= 0.0, "{p} W");
        }
    }
    assert!(c.floor_area_m2 > 0.0 && c.floor_area_m2.is_finite());
});
