//! Any bytes as a weather file, EPW or TMY3 by content, read as [`weather::read`] reads a
//! file (UTF-8, else Latin-1). Nothing may panic; a year that reads has whole days of
//! consecutive hours, its irradiances finite and within 0 to 1500 W/m², its illuminances
//! finite and not negative.
#![no_main]

use std::path::Path;

use eigenrad_precompute::weather;
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let text = match std::str::from_utf8(data) {
        Ok(text) => text.to_owned(),
        Err(_) => data.iter().map(|&b| char::from(b)).collect(),
    };
    let Ok(year) = weather::parse(Path::new("fuzz.epw"), &text) else {
        return;
    };
    assert!(!year.records.is_empty() && year.records.len() % 24 == 0);
    assert_eq!(year.records[0].hour, 1);
    for r in &year.records {
        assert!((1..=12).contains(&r.month) && (1..=31).contains(&r.day));
        assert!((1..=24).contains(&r.hour));
        for irradiance in [r.global_horizontal, r.direct_normal, r.diffuse_horizontal] {
            assert!((0.0..=1500.0).contains(&irradiance), "{irradiance} W/m²");
        }
        for lux in [
            r.global_horizontal_lux,
            r.direct_normal_lux,
            r.diffuse_horizontal_lux,
        ] {
            assert!(lux.is_none_or(|e| e.is_finite() && e >= 0.0), "{lux:?} lx");
        }
        let minutes = r.mid_hour_minutes();
        assert!((30.0..=1410.0).contains(&minutes));
    }
    let location = &year.location;
    let d = location.distance_km(-location.latitude, location.longitude + 180.0);
    assert!(d.is_finite() && (0.0..=20_016.0).contains(&d), "{d} km");
});
