//! The basis format: golden bytes, round trip, and one test per decoder error of the header
//! and the payload (the tables' own checks are in `format_tables.rs`).
#![allow(
    clippy::unwrap_used,
    clippy::expect_used,
    clippy::indexing_slicing,
    clippy::panic
)]

mod common;

use eigenrad_runtime::format::{crc32, FORMAT_VERSION, HEADER_LEN};
use eigenrad_runtime::{Basis, Error, Formulation, Precision, Quantity};

/// The tiny basis of `common::tiny`, encoded. Changing the layout changes these bytes: that
/// is a format change and needs a new `FORMAT_VERSION`.
const TINY_GOLDEN: &str = concat!(
    "454947454e52414409000000570100006705f66e010100000201020101011b05666c6f6f72046c61",
    "6d70046d61696e046465736b05706c616e65040000003f08000000400000803e180000803f000080",
    "3f000000000000803f0000803f00002040040000010004ffff0000080000003f0000000008000000",
    "0000007a4400080000003f000000000401000000040000c84100080000964200007a441c0000803f",
    "0000803fcdcc4c3f00000000000000000000803fdb0f49400400000040080000803e0000003f0800",
    "00c8420000204200100000000000000000cdcccc3dcdcc4c3d04010000000c020000000100000002",
    "0000001ccdcc4c3e0000803f0000803f0000003f00000000000000000000803f180000003f000080",
    "3fcdcc4c3f0000c03f0000803fcdcc4c3f080000803e9a99993e080000dc420000b4420010000000",
    "008fc2f53d000000000ad7a33d000000000000000000000000000000000000000000000000000000",
    "000000",
);

fn hex(bytes: &[u8]) -> String {
    bytes.iter().map(|b| format!("{b:02x}")).collect()
}

#[test]
fn crc32_check_value() {
    // The catalogued check value of CRC-32/ISO-HDLC for the ASCII string "123456789".
    assert_eq!(crc32(b"123456789"), 0xCBF4_3926);
}

#[test]
fn golden_bytes_of_the_tiny_basis() {
    let bytes = common::tiny().to_bytes().unwrap();
    assert_eq!(&bytes[..8], b"EIGENRAD");
    assert_eq!(u16::from_le_bytes([bytes[8], bytes[9]]), FORMAT_VERSION);
    assert_eq!(
        u32::from_le_bytes(bytes[12..16].try_into().unwrap()) as usize,
        bytes.len() - HEADER_LEN
    );
    assert_eq!(hex(&bytes), TINY_GOLDEN, "format layout changed");
    // The same bytes are committed as a file, used by the README example.
    let file = std::fs::read(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/data/tiny.basis"
    ))
    .unwrap();
    assert_eq!(file, bytes);
}

#[test]
fn round_trip_of_the_tiny_basis() {
    let bytes = common::tiny().to_bytes().unwrap();
    let basis = Basis::from_bytes(&bytes).unwrap();
    assert_eq!(basis.bands(), 1);
    assert_eq!(basis.quantity(), Quantity::Photometric);
    assert_eq!(basis.formulation(), Formulation::Split);
    assert_eq!(basis.precision(), Precision::F32);
    assert_eq!(
        (
            basis.patch_count(),
            basis.mode_count(),
            basis.channel_count()
        ),
        (2, 1, 1)
    );
    assert_eq!(
        (
            basis.sensor_count(),
            basis.zone_count(),
            basis.surface_count()
        ),
        (1, 1, 2)
    );
    assert_eq!(basis.byte_len(), bytes.len());
    assert_eq!(basis.surface_name(1).unwrap(), "lamp");
    assert_eq!(basis.channel_name(0).unwrap(), "main");
    assert_eq!(basis.sensor_name(0).unwrap(), "desk");
    assert_eq!(basis.zone_name(0).unwrap(), "plane");
    assert_eq!(basis.find_channel("main"), Some(0));
    assert_eq!(basis.find_channel("desk"), None);
    assert_eq!(basis.find_sensor("desk"), Some(0));
    assert_eq!(basis.find_zone("plane"), Some(0));
    assert_eq!(basis.eigenvalue(0, 0).unwrap(), 0.5);
    let lamp = basis.patch(1).unwrap();
    assert_eq!(lamp.area, 0.25);
    assert_eq!(lamp.centroid, [1.0, 1.0, 2.5]);
    assert_eq!(lamp.channel, Some(0));
    assert_eq!(lamp.surface, 1);
    assert_eq!(lamp.reflectance[0], 0.0);
    assert_eq!(lamp.emission[0], 1000.0);
    assert_eq!(basis.patch(0).unwrap().channel, None);
    let s = basis.sensor(0).unwrap();
    assert_eq!(s.position, [1.0, 1.0, 0.8]);
    assert_eq!(basis.zone_area(0).unwrap(), 2.0);
    assert_eq!(basis.grid_point_count(), 2);
    assert_eq!(
        basis.grid_piece(0, 0).unwrap(),
        eigenrad_runtime::GridPiece {
            points: 2,
            counts: [2, 1],
            spacing: 0.2,
            cell: [1.0, 1.0],
            border: 0.5,
            normal: [0.0, 0.0, 1.0],
        }
    );
    assert_eq!(basis.grid_point(0, 0).unwrap(), [0.5, 1.0, 0.8]);
    assert!(matches!(
        basis.grid_point(0, 2),
        Err(Error::IndexOutOfRange {
            what: "grid point",
            ..
        })
    ));
    assert!(matches!(
        basis.patch(2),
        Err(Error::IndexOutOfRange {
            what: "patch",
            index: 2,
            count: 2
        })
    ));
    assert!(matches!(
        basis.channel_name(1),
        Err(Error::IndexOutOfRange { .. })
    ));
}

#[test]
fn every_precision_and_formulation_round_trips() {
    for formulation in [Formulation::Split, Formulation::Seed] {
        for precision in [Precision::F32, Precision::F16, Precision::I16] {
            for bands in [1, 3] {
                let bytes = common::random(7, formulation, precision, bands)
                    .to_bytes()
                    .unwrap();
                let basis = Basis::from_bytes(&bytes).unwrap();
                assert_eq!(
                    (basis.formulation(), basis.precision(), basis.bands()),
                    (formulation, precision, bands)
                );
            }
        }
    }
}

#[test]
fn trailing_padding_is_ignored() {
    let mut bytes = common::tiny().to_bytes().unwrap();
    bytes.extend_from_slice(&[0xFF; 64]); // erased flash after the basis
    assert!(Basis::from_bytes(&bytes).is_ok());
}

#[test]
fn truncated_input() {
    let bytes = common::tiny().to_bytes().unwrap();
    assert_eq!(
        Basis::from_bytes(&bytes[..10]).unwrap_err(),
        Error::DecodeTruncated {
            needed: 20,
            found: 10
        }
    );
    let cut = &bytes[..bytes.len() - 1];
    assert!(
        matches!(Basis::from_bytes(cut), Err(Error::DecodeTruncated { found, .. }) if found == cut.len())
    );
    assert!(matches!(
        Basis::from_bytes(&[]),
        Err(Error::DecodeTruncated { .. })
    ));
}

#[test]
fn bad_magic() {
    let mut bytes = common::tiny().to_bytes().unwrap();
    bytes[0] = b'X';
    assert_eq!(
        Basis::from_bytes(&bytes).unwrap_err(),
        Error::DecodeBadMagic
    );
}

#[test]
fn newer_version() {
    let mut bytes = common::tiny().to_bytes().unwrap();
    bytes[8..10].copy_from_slice(&(FORMAT_VERSION + 1).to_le_bytes());
    assert_eq!(
        Basis::from_bytes(&bytes).unwrap_err(),
        Error::DecodeVersion {
            found: FORMAT_VERSION + 1,
            supported: FORMAT_VERSION
        }
    );
}

/// Bases of the older formats, kept byte for byte as each version wrote the tiny basis
/// (`runtime/tests/data/tiny-v1.basis`, `-v2` before the grid tables of version 3, `-v3`
/// before the grid pieces of version 4, `-v5` before the direct sun's tables of version 6,
/// `-v6` before the first reflection of version 7, `-v7` before the sun's first reflection of
/// version 8, `-v8` before the readings' responses to it of version 9), are refused with both
/// versions named.
#[test]
fn older_versions_are_refused_naming_both_versions() {
    let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data");
    for version in 1..FORMAT_VERSION {
        let old = std::fs::read(format!("{dir}/tiny-v{version}.basis")).unwrap();
        assert_eq!(&old[..8], b"EIGENRAD");
        assert_eq!(u16::from_le_bytes([old[8], old[9]]), version);
        let err = Basis::from_bytes(&old).unwrap_err();
        assert_eq!(
            err,
            Error::DecodeVersion {
                found: version,
                supported: FORMAT_VERSION
            }
        );
        let message = err.to_string();
        let (found, supported) = (
            format!("version {version}"),
            format!("version {FORMAT_VERSION}"),
        );
        for part in [found.as_str(), supported.as_str(), "eigenrad build"] {
            assert!(message.contains(part), "`{part}` missing: {message}");
        }
    }
}

#[test]
fn reserved_header_bits() {
    let mut bytes = common::tiny().to_bytes().unwrap();
    bytes[10] = 1;
    assert!(matches!(
        Basis::from_bytes(&bytes),
        Err(Error::DecodeField {
            field: "reserved",
            value: 1
        })
    ));
}

#[test]
fn corrupted_payload_fails_the_checksum() {
    let mut bytes = common::tiny().to_bytes().unwrap();
    let last = bytes.len() - 1;
    bytes[last] ^= 0x40;
    assert!(matches!(
        Basis::from_bytes(&bytes),
        Err(Error::DecodeChecksum { .. })
    ));
}

#[test]
fn garbage_payload_with_a_valid_checksum() {
    let mut bytes = common::tiny().to_bytes().unwrap();
    for b in &mut bytes[HEADER_LEN..] {
        *b = 0xFF;
    }
    common::reseal(&mut bytes);
    assert_eq!(Basis::from_bytes(&bytes).unwrap_err(), Error::DecodePayload);
}
