//! Any byte string: decode it, and if it decodes, drive every evaluator entry point with
//! inputs taken from the tail of the data. Nothing may panic; every Ok reading is finite.
#![no_main]

use eigenrad_runtime::{Basis, ChannelEvaluator, DaylightEvaluator, Evaluator, Sun};
use libfuzzer_sys::fuzz_target;

fn run<const B: usize>(basis: Basis<'_>, knobs: &[u8]) {
    let Ok(mut e) = Evaluator::<B, 256, 32, 8, 8>::new(basis) else { return };
    let knob = |i: usize| knobs.get(i % knobs.len().max(1)).copied().unwrap_or(128);
    let m = basis.channel_count();
    let levels: Vec<f32> = (0..m).map(|c| f32::from(knob(c)) / 64.0).collect();
    let _ = e.set_channel_levels(&levels);
    for c in 0..m {
        let _ = e.set_channel_arc_power(c, knob(c + 3));
        let _ = e.set_channel_level(c, f32::from(knob(c + 5)) * 4.0);
    }
    for i in 0..basis.patch_count().min(64) {
        let _ = e.set_patch_exitance(i, [f32::from(knob(i + 7)) * 1.0e6; B]);
    }
    let check = |r: eigenrad_runtime::Result<[f32; B]>| {
        if let Ok(v) = r {
            assert!(v.iter().all(|x| x.is_finite()));
        }
    };
    for i in 0..basis.patch_count() {
        check(e.exitance(i));
        check(e.irradiance(i));
    }
    for s in 0..basis.sensor_count() {
        check(e.sensor_irradiance(s));
    }
    let figures = |r: eigenrad_runtime::Result<[eigenrad_runtime::Figures; B]>| {
        if let Ok(f) = r {
            for x in f {
                assert!([x.average, x.minimum, x.maximum, x.uniformity]
                    .iter()
                    .all(|v| v.is_finite()));
            }
        }
    };
    for z in 0..basis.zone_count() {
        check(e.zone_irradiance(z));
        let points = basis.grid_points(z).unwrap_or(0);
        for point in 0..=points.min(64) {
            check(e.grid_point_irradiance(z, point));
            let _ = basis.grid_point(z, point);
        }
        figures(e.zone_figures(z));
    }
    e.clear_patch_exitance();
    // The channel evaluator, driven with the same levels.
    if let Ok(mut c) = ChannelEvaluator::<B, 8>::new(basis) {
        let _ = c.set_channel_levels(&levels);
        for ch in 0..m {
            let _ = c.set_channel_arc_power(ch, knob(ch + 3));
        }
        for i in 0..basis.patch_count() {
            check(c.exitance(i));
            check(c.irradiance(i));
        }
        for s in 0..basis.sensor_count() {
            check(c.sensor_irradiance(s));
        }
        for z in 0..basis.zone_count() {
            check(c.zone_irradiance(z));
            let points = basis.grid_points(z).unwrap_or(0);
            for point in 0..=points.min(64) {
                check(c.grid_point_irradiance(z, point));
            }
            figures(c.zone_figures(z));
        }
    }
    // Daylight (a basis that carries it, Tregenza's sky), driven by the same knobs.
    if let Ok(mut d) = DaylightEvaluator::<145, 8, 32>::new(basis) {
        let sky: Vec<f32> = (0..145).map(|i| f32::from(knob(i + 11)) * 40.0).collect();
        let raw = [
            f32::from(knob(1)) - 128.0,
            f32::from(knob(2)) - 128.0,
            f32::from(knob(4)) - 100.0,
        ];
        let norm = (raw[0] * raw[0] + raw[1] * raw[1] + raw[2] * raw[2]).sqrt().max(1.0);
        let sun = Sun {
            direction: raw.map(|x| x / norm),
            direct_normal: f32::from(knob(6)) * 400.0,
        };
        let _ = d.set_sky(&sky, f32::from(knob(8)) * 500.0, Some(sun));
        let finite = |r: eigenrad_runtime::Result<f32>| {
            if let Ok(v) = r {
                assert!(v.is_finite());
            }
        };
        for s in 0..basis.sensor_count() {
            finite(d.sensor_illuminance(s));
        }
        for z in 0..basis.zone_count() {
            finite(d.zone_illuminance(z));
            let points = basis.grid_points(z).unwrap_or(0);
            for point in 0..=points.min(64) {
                finite(d.grid_point_illuminance(z, point));
            }
            if let Ok(f) = d.zone_figures(z) {
                assert!([f.average, f.minimum, f.maximum, f.uniformity]
                    .iter()
                    .all(|v| v.is_finite()));
            }
        }
        for i in 0..basis.patch_count().min(256) {
            finite(d.exitance(i));
        }
    }
    let _ = basis.find_channel("main");
    for i in 0..basis.channel_count() {
        let _ = basis.channel_name(i);
    }
}

fuzz_target!(|data: &[u8]| {
    if let Ok(basis) = Basis::from_bytes(data) {
        let knobs = data.get(basis.byte_len()..).unwrap_or(&[]);
        match basis.bands() {
            1 => run::<1>(basis, knobs),
            _ => run::<3>(basis, knobs),
        }
    }
});
