//! EULUMDAT files: each symmetry indicator against the equivalent LM-63 full file, the scale
//! to candela, the stated flux (LORL, DFF) and the dimensions.

use std::f64::consts::PI;

use super::super::{eulumdat, Format, OpeningShape, Symmetry};
use super::{data, interpolation_bound, load, SYMMETRIC_FLUX};

#[test]
fn each_symmetry_indicator_expands_to_the_equivalent_full_file() {
    // Lamp flux 1000 lm and conversion factor 1: cd/klm are candela, and the files tabulate
    // the same numbers as the LM-63 ones.
    for (isym, symmetry, full) in [
        (0, Symmetry::None, "lm63-2019-none.ies"),
        (1, Symmetry::Rotational, "lm63-2002-rotational.ies"),
        (2, Symmetry::AboutC0C180, "lm63-full-half.ies"),
        (3, Symmetry::AboutC90C270, "lm63-full-c90.ies"),
        (4, Symmetry::Quadrant, "lm63-full-quadrant.ies"),
    ] {
        let p = load(&format!("eulumdat-isym{isym}.ldt"));
        assert_eq!(p.format, Format::Eulumdat);
        assert_eq!(p.symmetry, symmetry, "Isym {isym}");
        assert_eq!(p.distribution, load(full).distribution, "Isym {isym}");
    }
}

#[test]
fn intensities_scale_with_the_lamp_flux_and_conversion_factor() {
    // The same file with 2000 lm lamps and a conversion factor of 1.5: three times the candela.
    let text = std::fs::read_to_string(data("eulumdat-isym2.ldt")).unwrap();
    let mut lines: Vec<&str> = text.lines().collect();
    assert_eq!((lines[23], lines[28]), ("1", "1000"));
    lines[23] = "1.5";
    lines[28] = "2000";
    let scaled = eulumdat::parse("scaled.ldt".as_ref(), lines.join("\r\n").as_bytes()).unwrap();
    let p = load("eulumdat-isym2.ldt");
    for (c, gamma) in [(0.0, 0.0), (75.0, 33.0), (200.0, 140.0)] {
        assert!((scaled.intensity(c, gamma) - 3.0 * p.intensity(c, gamma)).abs() < 1e-9);
    }
    assert_eq!(scaled.lamp_flux, Some(2000.0));
}

#[test]
fn flux_matches_lorl_and_dff() {
    for isym in 0..=4 {
        let p = load(&format!("eulumdat-isym{isym}.ldt"));
        let stated = p.luminaire_flux.unwrap();
        // LORL 75.40 % of 1000 lm is the closed form 2π · 120 lm to the file's two decimals.
        assert!(
            (stated - SYMMETRIC_FLUX).abs() < 0.05,
            "Isym {isym}: {stated}"
        );
        let bound = interpolation_bound(10.0);
        assert!(
            (p.flux() - stated).abs() < bound + 0.05,
            "Isym {isym}: {} vs {stated}",
            p.flux()
        );
        let down = p.distribution.flux_between(0.0, 90.0) / p.flux();
        let dff = p.downward_fraction.unwrap();
        assert_eq!(dff, 0.625);
        assert!(
            (down - dff).abs() < 2.0 * bound / p.flux(),
            "Isym {isym}: {down}"
        );
    }
}

#[test]
fn lambertian_flux_is_pi_i0() {
    // I = (1000/π) cos γ cd/klm on 0°…90° in 5° steps, lamps of 1000 lm, LORL 100 %, DFF 100 %.
    let p = load("lambertian.ldt");
    let i0 = p.intensity(0.0, 0.0);
    assert_eq!(i0, 318.31);
    let h2 = 5f64.to_radians().powi(2);
    let error = 1.0 - p.flux() / (PI * i0);
    assert!(error > 0.0 && error < h2 / 8.0, "relative error {error}");
    assert!((p.flux() / p.luminaire_flux.unwrap() - 1.0).abs() < h2 / 8.0 + 1e-5);
    assert!((p.distribution.flux_between(0.0, 90.0) / p.flux() - 1.0).abs() < 1e-12);
    assert_eq!(p.intensity(0.0, 95.0), 0.0);
}

#[test]
fn identity_lamps_and_dimensions() {
    let p = load("eulumdat-isym4.ldt");
    let id = &p.identity;
    assert_eq!(
        id.manufacturer.as_deref(),
        Some("eigenrad synthetic test data: not a real luminaire")
    );
    assert_eq!(
        id.luminaire.as_deref(),
        Some("synthetic quadrant distribution")
    );
    assert_eq!(id.catalogue.as_deref(), Some("SYN-QUADRANT"));
    assert_eq!(id.test.as_deref(), Some("SYNTH-quadrant"));
    assert_eq!(id.lamp.as_deref(), Some("synthetic lamp"));
    assert_eq!((p.lamps, p.absolute, p.input_watts), (2, false, Some(40.0)));
    let body = p.luminaire.unwrap();
    assert_eq!(body.shape, OpeningShape::Rectangular);
    assert_eq!((body.length, body.width, body.height), (0.62, 0.31, 0.08));
    assert_eq!(p.opening.shape, OpeningShape::Rectangular);
    assert_eq!((p.opening.length, p.opening.width), (0.6, 0.3));
    assert_eq!(p.opening.side_heights, Some([0.0; 4]));
}

#[test]
fn a_decimal_comma_reads_as_a_point() {
    let text = std::fs::read_to_string(data("eulumdat-isym1.ldt")).unwrap();
    let mut lines: Vec<&str> = text.lines().collect();
    assert_eq!(lines[21], "62.5");
    lines[21] = "62,5";
    let p = eulumdat::parse("comma.ldt".as_ref(), lines.join("\n").as_bytes()).unwrap();
    assert_eq!(p.downward_fraction, Some(0.625));
}

#[test]
fn negative_lamp_count_is_absolute_photometry() {
    let text = std::fs::read_to_string(data("eulumdat-isym1.ldt")).unwrap();
    let mut lines: Vec<&str> = text.lines().collect();
    assert_eq!(lines[26], "2");
    lines[26] = "-1";
    let p = eulumdat::parse("absolute.ldt".as_ref(), lines.join("\n").as_bytes()).unwrap();
    assert!(p.absolute);
    assert_eq!(p.lamps, 1);
    assert_eq!(p.distribution, load("eulumdat-isym1.ldt").distribution);
}
