//! The basis format's table checks: a tiny basis edited table by table, each edit decoded
//! to its own error (the header's checks and the golden bytes are in `format.rs`).
#![allow(
    clippy::unwrap_used,
    clippy::expect_used,
    clippy::indexing_slicing,
    clippy::panic
)]

mod common;

use eigenrad_runtime::format::{f16_to_f32, f32_to_f16, HEADER_LEN};
use eigenrad_runtime::{Basis, Error, Formulation, Precision, Quantity};

type Edit = Box<dyn Fn(&mut eigenrad_runtime::writer::BasisTables)>;

/// Encodes `tables` after `edit`, then decodes.
fn decode_edited(
    edit: impl FnOnce(&mut eigenrad_runtime::writer::BasisTables),
) -> Result<(), Error> {
    let mut t = common::tiny();
    edit(&mut t);
    let bytes = t.to_bytes().unwrap();
    Basis::from_bytes(&bytes).map(|_| ())
}

#[test]
fn invalid_band_count() {
    // Bands are the payload's first byte.
    let mut bytes = common::tiny().to_bytes().unwrap();
    bytes[HEADER_LEN] = 2;
    common::reseal(&mut bytes);
    assert_eq!(
        Basis::from_bytes(&bytes).unwrap_err(),
        Error::DecodeField {
            field: "bands",
            value: 2
        }
    );
}

#[test]
fn invalid_enumerations() {
    for (offset, field) in [(1, "quantity"), (2, "formulation"), (3, "precision")] {
        let mut bytes = common::tiny().to_bytes().unwrap();
        bytes[HEADER_LEN + offset] = 9;
        common::reseal(&mut bytes);
        assert_eq!(
            Basis::from_bytes(&bytes).unwrap_err(),
            Error::DecodeField { field, value: 9 }
        );
    }
}

#[test]
fn photometric_needs_one_band() {
    let r = decode_edited(|t| {
        *t = common::random(3, Formulation::Split, Precision::F32, 3);
        t.quantity = Quantity::Photometric;
    });
    assert!(matches!(
        r,
        Err(Error::DecodeField {
            field: "quantity",
            ..
        })
    ));
}

#[test]
fn table_length_mismatches() {
    let cases: Vec<(&str, Edit)> = vec![
        ("eigenvalues", Box::new(|t| t.eigenvalues.push(0.1))),
        (
            "patch_centroid",
            Box::new(|t| t.patch_centroid.pop().map(|_| ()).unwrap_or(())),
        ),
        ("patch_surface", Box::new(|t| t.patch_surface.push(0))),
        ("patch_channel", Box::new(|t| t.patch_channel.push(None))),
        (
            "patch_reflectance",
            Box::new(|t| t.patch_reflectance.push(0.5)),
        ),
        ("patch_emission", Box::new(|t| t.patch_emission.push(0.0))),
        ("modes.data", Box::new(|t| t.modes.push(0.0))),
        (
            "black_projection",
            Box::new(|t| t.black_projection.push(0.0)),
        ),
        (
            "channel_response.data",
            Box::new(|t| t.channel_response.push(0.0)),
        ),
        (
            "sensor_geometry",
            Box::new(|t| t.sensor_geometry.push([0.0; 7])),
        ),
        ("zone_area", Box::new(|t| t.zone_area.push(1.0))),
        ("output_modes", Box::new(|t| t.output_modes.push(0.0))),
        ("output_channels", Box::new(|t| t.output_channels.push(0.0))),
        ("output_view.data", Box::new(|t| t.output_view.push(0.0))),
        ("grid_pieces", Box::new(|t| t.grid_pieces.push(1))),
        ("grid_lattice", Box::new(|t| t.grid_lattice.push([1, 1, 1]))),
        ("grid_layout", Box::new(|t| t.grid_layout.push([0.0; 7]))),
        (
            "grid_position",
            Box::new(|t| t.grid_position.push([0.0; 3])),
        ),
        ("grid_modes", Box::new(|t| t.grid_modes.push(0.0))),
        ("grid_channels", Box::new(|t| t.grid_channels.push(0.0))),
        ("grid_view.data", Box::new(|t| t.grid_view.push(0.0))),
        // One more point counted than the tables hold.
        ("grid_position", Box::new(|t| t.grid_lattice[0] = [3, 1, 3])),
        // One more piece counted than the lattice table holds.
        ("grid_lattice", Box::new(|t| t.grid_pieces[0] = 2)),
    ];
    for (field, edit) in cases {
        let r = decode_edited(|t| edit(t));
        assert!(
            matches!(r, Err(Error::DecodeLength { field: f, .. }) if f == field),
            "{field}: got {r:?}"
        );
    }
}

#[test]
fn names_must_match_the_counts() {
    // One surface name too many: the writer counts surfaces from the names, so rewrite the
    // count byte (the payload's seventh byte, varint `surface_count`) back to 2.
    let mut t = common::tiny();
    t.surface_names.push("extra".into());
    let mut bytes = t.to_bytes().unwrap();
    assert_eq!(bytes[HEADER_LEN + 6], 3);
    bytes[HEADER_LEN + 6] = 2;
    common::reseal(&mut bytes);
    assert!(matches!(
        Basis::from_bytes(&bytes),
        Err(Error::DecodeLength { field: "names", .. })
    ));
}

/// A name that is not UTF-8 decodes (the name table's framing is checked, its text is not),
/// and is refused when it is read, naming the table and the name's index; finding the
/// other names by name still works, and no `&str` finds the bad one.
#[test]
fn a_name_that_is_not_utf8_is_refused_when_read() {
    let mut t = common::tiny();
    t.channel_names = vec!["m\u{e9}in".into()];
    let mut bytes = t.to_bytes().unwrap();
    // "méin" in UTF-8 is 6d c3 a9 69 6e; c3 followed by 'X' is no UTF-8.
    let at = bytes
        .windows(5)
        .position(|w| w == [0x6d, 0xc3, 0xa9, 0x69, 0x6e])
        .unwrap();
    bytes[at + 2] = b'X';
    common::reseal(&mut bytes);
    let basis = Basis::from_bytes(&bytes).unwrap();
    let surfaces = basis.surface_count();
    assert_eq!(
        basis.channel_name(0),
        Err(Error::DecodeValue {
            field: "names",
            index: surfaces
        })
    );
    assert_eq!(basis.surface_name(0), Ok("floor"));
    assert_eq!(basis.sensor_name(0), Ok("desk"));
    assert_eq!(basis.find_sensor("desk"), Some(0));
    assert_eq!(basis.find_zone("plane"), Some(0));
    assert_eq!(basis.find_channel("m\u{e9}in"), None);
    assert_eq!(basis.find_channel("main"), None);
}

#[test]
fn values_out_of_range() {
    let cases: Vec<(&str, Edit)> = vec![
        ("eigenvalues", Box::new(|t| t.eigenvalues[0] = 1.0)),
        ("eigenvalues", Box::new(|t| t.eigenvalues[0] = f64::NAN)),
        ("patch_area", Box::new(|t| t.patch_area[0] = 0.0)),
        ("patch_area", Box::new(|t| t.patch_area[0] = f64::INFINITY)),
        (
            "patch_centroid",
            Box::new(|t| t.patch_centroid[0][2] = f64::NAN),
        ),
        (
            "patch_reflectance",
            Box::new(|t| t.patch_reflectance[0] = 1.0),
        ),
        (
            "patch_reflectance",
            Box::new(|t| t.patch_reflectance[0] = -0.1),
        ),
        (
            "patch_reflectance",
            Box::new(|t| t.patch_reflectance[0] = 1e-9),
        ),
        ("patch_emission", Box::new(|t| t.patch_emission[1] = -1.0)),
        ("patch_emission", Box::new(|t| t.patch_emission[0] = 5.0)), // emits but in no channel
        ("patch_surface", Box::new(|t| t.patch_surface[0] = 7)),
        ("patch_channel", Box::new(|t| t.patch_channel[0] = Some(3))),
        ("modes.data", Box::new(|t| t.modes[0] = f64::NAN)),
        (
            "black_projection",
            Box::new(|t| t.black_projection[0] = f64::INFINITY),
        ),
        (
            "channel_response.data",
            Box::new(|t| t.channel_response[0] = f64::NAN),
        ),
        (
            "channel_response.data",
            Box::new(|t| t.channel_response[1] = 1e30),
        ),
        (
            "sensor_geometry",
            Box::new(|t| t.sensor_geometry[0][0] = f64::NAN),
        ),
        ("zone_area", Box::new(|t| t.zone_area[0] = -2.0)),
        ("output_modes", Box::new(|t| t.output_modes[0] = f64::NAN)),
        (
            "output_channels",
            Box::new(|t| t.output_channels[1] = f64::INFINITY),
        ),
        (
            "output_view.data",
            Box::new(|t| t.output_view[3] = f64::NAN),
        ),
        // A piece that keeps no point, or more points than it has cells.
        ("grid_lattice", Box::new(|t| t.grid_lattice[0] = [2, 1, 0])),
        ("grid_lattice", Box::new(|t| t.grid_lattice[0] = [2, 1, 3])),
        ("grid_layout", Box::new(|t| t.grid_layout[0][0] = -0.2)),
        ("grid_layout", Box::new(|t| t.grid_layout[0][6] = 0.5)),
        (
            "grid_position",
            Box::new(|t| t.grid_position[1][2] = f64::NAN),
        ),
        ("grid_modes", Box::new(|t| t.grid_modes[0] = f64::INFINITY)),
        ("grid_channels", Box::new(|t| t.grid_channels[1] = 2.0e9)),
        ("grid_view.data", Box::new(|t| t.grid_view[1] = f64::NAN)),
    ];
    for (field, edit) in cases {
        let r = decode_edited(|t| edit(t));
        assert!(
            matches!(r, Err(Error::DecodeValue { field: f, .. }) if f == field),
            "{field}: got {r:?}"
        );
    }
}

#[test]
fn seed_eigenvalues_must_be_positive() {
    let r = decode_edited(|t| {
        t.formulation = Formulation::Seed;
        t.eigenvalues[0] = -1.0;
    });
    assert!(matches!(
        r,
        Err(Error::DecodeValue {
            field: "eigenvalues",
            index: 0
        })
    ));
}

#[test]
fn black_patch_list_must_match_reflectance() {
    // Patch 0 made black too: the writer lists it, but its projection rows are missing.
    let r = decode_edited(|t| t.patch_reflectance[0] = 0.0);
    assert!(matches!(
        r,
        Err(Error::DecodeLength {
            field: "black_projection",
            ..
        })
    ));
    // The lamp made reflecting: it is no longer listed, and the projection row is extra.
    let r = decode_edited(|t| t.patch_reflectance[1] = 0.5);
    assert!(matches!(
        r,
        Err(Error::DecodeLength {
            field: "black_projection",
            ..
        })
    ));
}

#[test]
fn quantised_scales_must_be_valid() {
    type Matrix = fn(&mut eigenrad_runtime::writer::BasisTables) -> &mut Vec<f64>;
    let matrices: [(&str, Matrix); 3] = [
        ("modes.scales", |t| &mut t.modes),
        ("channel_response.scales", |t| &mut t.channel_response),
        ("output_view.scales", |t| &mut t.output_view),
    ];
    for precision in [Precision::F16, Precision::I16] {
        for (field, table) in matrices {
            let mut t = common::random(5, Formulation::Split, precision, 1);
            table(&mut t)[0] = 1e30; // the column's scale overflows f32: the reader refuses it
            let bytes = t.to_bytes().unwrap();
            let r = Basis::from_bytes(&bytes);
            assert!(
                matches!(r, Err(Error::DecodeValue { field: f, .. }) if f == field),
                "{precision:?} {field}: got {r:?}"
            );
        }
    }
}

#[test]
fn seed_bases_carry_channel_responses_too() {
    // Version 1 left the first-bounce table empty in the seed formulation; the exact
    // responses are there in both.
    let r = decode_edited(|t| {
        t.formulation = Formulation::Seed;
        t.channel_response.clear();
    });
    assert!(matches!(
        r,
        Err(Error::DecodeLength {
            field: "channel_response.data",
            ..
        })
    ));
}

#[test]
fn f16_conversion_is_exact_where_it_can_be() {
    for v in [
        0.0f32,
        1.0,
        -2.5,
        0.333_251_95,
        65504.0,
        6.103_515_6e-5,
        5.960_464_5e-8,
        -1025.0,
    ] {
        assert_eq!(f16_to_f32(f32_to_f16(v)), v, "{v}");
    }
    // Round to nearest: relative error at most 2^-11 in the normal range.
    let mut x = 1.0e-4f32;
    while x < 6.0e4 {
        let r = f16_to_f32(f32_to_f16(x));
        assert!(((r - x) / x).abs() <= 1.0 / 2048.0, "{x} -> {r}");
        x *= 1.37;
    }
    assert!(f16_to_f32(f32_to_f16(1.0e6)).is_infinite());
    assert!(f16_to_f32(f32_to_f16(f32::NAN)).is_nan());
}

/// Every one of the 65536 binary16 bit patterns reads as the value IEEE 754 defines for it,
/// computed here from the fields in `f64`: (−1)^s × 2^(e−15) × (1 + m/1024) for a normal
/// half, (−1)^s × 2^−24 × m for a subnormal one, infinity or NaN for e = 31.
#[test]
fn every_f16_bit_pattern_reads_as_its_ieee_value() {
    for bits in 0..=u16::MAX {
        let sign = if bits & 0x8000 != 0 { -1.0f64 } else { 1.0 };
        let e = i32::from((bits >> 10) & 0x1F);
        let m = f64::from(bits & 0x3FF);
        let got = f16_to_f32(bits);
        match e {
            31 if m == 0.0 => assert_eq!(f64::from(got), sign * f64::INFINITY, "{bits:#06x}"),
            31 => assert!(got.is_nan(), "{bits:#06x}"),
            0 => assert_eq!(f64::from(got), sign * m * 2f64.powi(-24), "{bits:#06x}"),
            _ => assert_eq!(
                f64::from(got),
                sign * 2f64.powi(e - 15) * (1.0 + m / 1024.0),
                "{bits:#06x}"
            ),
        }
        // The sign of zero is kept too.
        assert_eq!(got.is_sign_negative(), bits & 0x8000 != 0, "{bits:#06x}");
    }
}

#[test]
fn no_byte_string_panics() {
    // Every prefix and every single-byte corruption of a valid basis decodes to Ok or Err.
    let bytes = common::random(11, Formulation::Split, Precision::F16, 3)
        .to_bytes()
        .unwrap();
    for len in 0..bytes.len() {
        let _ = Basis::from_bytes(&bytes[..len]);
    }
    for i in 0..bytes.len() {
        let mut b = bytes.clone();
        b[i] ^= 0xA5;
        let _ = Basis::from_bytes(&b);
        common::reseal(&mut b);
        let _ = Basis::from_bytes(&b);
    }
}
