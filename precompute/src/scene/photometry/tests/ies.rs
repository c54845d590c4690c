//! LM-63 files: each version, each horizontal symmetry, tilt tables, the scale factors, and
//! flux against closed forms.

use std::f64::consts::PI;

use super::super::{Format, LampGeometry, Lm63Version, OpeningShape, Symmetry};
use super::{interpolation_bound, load, profile, SYMMETRIC_FLUX};

#[test]
fn each_version_line_is_recognised() {
    for (name, version) in [
        ("lm63-1991-factors.ies", Lm63Version::V1991),
        ("lm63-1995-quadrant.ies", Lm63Version::V1995),
        ("lm63-2002-half.ies", Lm63Version::V2002),
        ("lm63-2019-c90.ies", Lm63Version::V2019),
    ] {
        assert_eq!(load(name).format, Format::Lm63(version), "{name}");
    }
}

#[test]
fn keywords_name_the_luminaire() {
    let p = load("lm63-2002-half.ies");
    let id = &p.identity;
    assert_eq!(id.manufacturer.as_deref(), Some("eigenrad test data"));
    assert_eq!(id.catalogue.as_deref(), Some("SYN-HALF"));
    assert_eq!(id.test.as_deref(), Some("SYNTH-half"));
    assert_eq!(id.lamp.as_deref(), Some("none"));
    // [MORE] continues the keyword before it.
    assert_eq!(
        id.luminaire.as_deref(),
        Some("synthetic half distribution from a closed form; not a real luminaire")
    );
    assert!(id
        .keywords
        .iter()
        .any(|(k, v)| k == "OTHER" && v.starts_with("Synthetic")));
}

#[test]
fn each_horizontal_symmetry_is_read() {
    for (name, symmetry, stored) in [
        ("lm63-2002-rotational.ies", Symmetry::Rotational, 1),
        ("lm63-1995-quadrant.ies", Symmetry::Quadrant, 12),
        ("lm63-2002-half.ies", Symmetry::AboutC0C180, 12),
        ("lm63-2019-c90.ies", Symmetry::AboutC90C270, 12),
        ("lm63-2019-none.ies", Symmetry::None, 12),
    ] {
        let p = load(name);
        assert_eq!(p.symmetry, symmetry, "{name}");
        // Expanded: 0°, 30°, … 330° (one plane for rotational symmetry).
        assert_eq!(p.distribution.c_angles().len(), stored, "{name}");
        assert_eq!(p.distribution.gamma_angles().len(), 19, "{name}");
    }
}

#[test]
fn every_symmetry_expands_to_the_equivalent_full_file() {
    for (reduced, full) in [
        ("lm63-1995-quadrant.ies", "lm63-full-quadrant.ies"),
        ("lm63-2002-half.ies", "lm63-full-half.ies"),
        ("lm63-2019-c90.ies", "lm63-full-c90.ies"),
    ] {
        assert_eq!(
            load(reduced).distribution,
            load(full).distribution,
            "{reduced}"
        );
    }
    // Rotational symmetry keeps one plane; the full file has twelve equal ones.
    let one = load("lm63-2002-rotational.ies");
    let all = load("lm63-full-rotational.ies");
    for c in [0.0, 17.0, 95.0, 200.0, 359.0] {
        for gamma in [0.0, 33.0, 90.0, 151.0, 180.0] {
            assert_eq!(one.intensity(c, gamma), all.intensity(c, gamma));
        }
    }
}

#[test]
fn tabulated_values_come_back_at_their_angles() {
    // Half: 90 · (1 + 0.3 cos C + 0.1 cos 2C) at γ = 0.
    let p = load("lm63-2002-half.ies");
    assert_eq!(p.intensity(0.0, 0.0), 126.0);
    assert_eq!(p.intensity(180.0, 0.0), 72.0);
    // C 240° is the image of 120°: 90 · (1 − 0.15 − 0.05) at γ 0.
    assert!((p.intensity(240.0, 0.0) - 90.0 * 0.8).abs() < 1e-9);
    // C90–C270 symmetry, 90° stored: 117 at C 90°, and the same at its own mirror image.
    let c90 = load("lm63-2019-c90.ies");
    assert_eq!(c90.intensity(90.0, 0.0), 117.0);
    assert_eq!(c90.intensity(30.0, 20.0), c90.intensity(150.0, 20.0));
}

#[test]
fn the_scale_factors_multiply_the_candela() {
    // LM-63-1991: candela multiplier 2 × ballast factor 0.9 × ballast-lamp factor 0.95.
    let p = load("lm63-1991-factors.ies");
    let scale = 2.0 * 0.9 * 0.95;
    for gamma in [0.0, 40.0, 180.0] {
        let expected = (profile(gamma) * 100.0).round() / 100.0 * scale;
        assert!(
            (p.intensity(0.0, gamma) - expected).abs() < 1e-9,
            "γ {gamma}"
        );
    }
    assert_eq!(p.lamps, 2);
    assert!(!p.absolute);
    assert_eq!(p.lamp_flux, Some(800.0));
    // LM-63-2019's second field is the file generation type (1.1 here), not a factor.
    let c90 = load("lm63-2019-c90.ies");
    assert!(c90.absolute);
    assert_eq!(c90.lamp_flux, None);
    assert_eq!(c90.intensity(270.0, 0.0), 63.0);
}

#[test]
fn luminous_openings_in_metres() {
    // 2002, metres: width 0.6, length 1.2, flat.
    let o = load("lm63-2002-half.ies").opening;
    assert_eq!(o.shape, OpeningShape::Rectangular);
    assert_eq!((o.length, o.width, o.height), (1.2, 0.6, 0.0));
    // 1995, feet: a negative width and zero length, a disc 1 ft across.
    let o = load("lm63-1995-quadrant.ies").opening;
    assert_eq!(o.shape, OpeningShape::VerticalCylinder);
    assert!((o.length - 0.3048).abs() < 1e-12 && (o.width - 0.3048).abs() < 1e-12);
    assert_eq!(o.height, 0.0);
    assert_eq!(load("isotropic.ies").opening.shape, OpeningShape::Point);
}

/// `TILT=<file>`: the table of `lm63-2002-tilt.ies` (its lines 12 to 17) moved into a file of
/// its own next to the `.ies` file reads as the included one; a fault in it names that file
/// and its line.
#[test]
fn a_tilt_table_in_its_own_file_reads_as_an_included_one() {
    let dir = std::env::temp_dir().join(format!("eigenrad-tilt-file-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let text = std::fs::read_to_string(super::data("lm63-2002-tilt.ies")).unwrap();
    let lines: Vec<&str> = text.lines().collect();
    let mut ies: Vec<&str> = lines[..10].to_vec();
    ies.push("TILT=lamp.tlt");
    ies.extend_from_slice(&lines[17..]);
    let path = dir.join("lamp.ies");
    std::fs::write(&path, ies.join("\n") + "\n").unwrap();
    let table = lines[11..17].join("\n") + "\n";
    std::fs::write(dir.join("lamp.tlt"), &table).unwrap();
    let p = super::super::read(&path).unwrap_or_else(|e| panic!("{e}"));
    let included = load("lm63-2002-tilt.ies");
    assert_eq!(p.tilt, included.tilt);
    assert_eq!(p.distribution, included.distribution);
    // One factor too many: the table's file and the line of the extra value.
    std::fs::write(dir.join("lamp.tlt"), table.clone() + "0.6\n").unwrap();
    let e = super::super::read(&path).expect_err("a value after the table");
    assert_eq!(e.path(), dir.join("lamp.tlt"), "{e}");
    assert_eq!(e.line(), Some(7), "{e}");
    assert!(e.to_string().contains("follow the tilt table"), "{e}");
    // A factor short.
    std::fs::write(dir.join("lamp.tlt"), table.replace(" 0.7\n", "\n")).unwrap();
    let e = super::super::read(&path).expect_err("a factor short");
    assert_eq!(e.path(), dir.join("lamp.tlt"), "{e}");
    assert!(
        e.to_string()
            .contains("expected 7 tilt multiplying factors, found 6"),
        "{e}"
    );
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn an_included_tilt_table_is_kept() {
    let p = load("lm63-2002-tilt.ies");
    let tilt = p.tilt.expect("TILT=INCLUDE");
    assert_eq!(tilt.geometry, LampGeometry::Vertical);
    assert_eq!(tilt.angles, [0.0, 15.0, 30.0, 45.0, 60.0, 75.0, 90.0]);
    assert_eq!(tilt.factors, [1.0, 0.98, 0.95, 0.9, 0.84, 0.77, 0.7]);
    // The records after the table are read as in a file without one.
    assert_eq!(
        p.distribution,
        load("lm63-2002-rotational.ies").distribution
    );
    assert!(load("lm63-2002-half.ies").tilt.is_none());
}

#[test]
fn isotropic_flux_matches_the_rated_lumens() {
    // 100 cd in every direction: 4π · 100 lm; the file rates its lamp at 1256.64 lm.
    let p = load("isotropic.ies");
    assert!((p.flux() / (4.0 * PI * 100.0) - 1.0).abs() < 1e-12);
    let rated = p.lamp_flux.unwrap();
    assert!(
        (p.flux() / rated - 1.0).abs() < 1e-5,
        "{} vs {rated}",
        p.flux()
    );
}

#[test]
fn flux_of_each_symmetry_matches_the_closed_form() {
    // The C factors integrate to 1 over the circle (exactly, on 30° steps), so every file
    // carries 2π · 120 lm up to the γ interpolation error.
    for name in [
        "lm63-2002-rotational.ies",
        "lm63-1995-quadrant.ies",
        "lm63-2002-half.ies",
        "lm63-2019-c90.ies",
        "lm63-2019-none.ies",
    ] {
        let flux = load(name).flux();
        assert!(
            (flux - SYMMETRIC_FLUX).abs() < interpolation_bound(10.0),
            "{name}: {flux} lm vs {SYMMETRIC_FLUX}"
        );
    }
}
