//! The serialized basis, format version 9: the wire types a writer fills and the reader
//! decodes in place. `docs/format.md` is the normative description; this module is its
//! layout and header, the checks of the payload's sections are in `decode/`.
//!
//! A basis is a 20-byte header followed by a postcard-encoded [`Payload`]:
//!
//! | offset | size | field | meaning |
//! |---|---|---|---|
//! | 0 | 8 | magic | `EIGENRAD` |
//! | 8 | 2 | version | [`FORMAT_VERSION`], little-endian |
//! | 10 | 2 | reserved | 0 |
//! | 12 | 4 | payload length | bytes of payload, little-endian |
//! | 16 | 4 | checksum | CRC-32 (ISO-HDLC) of the payload, little-endian |
//!
//! Bulk tables inside the payload are borrowed byte slices of little-endian numbers, so that a
//! basis kept in flash is read where it lies: decoding copies nothing but a few slice headers.

// The parts: the settings' typed values; the payload's wire type and its reader; the
// dimensions every table's length follows from; binary16 conversions. This file keeps the
// header, which frames the payload, and the public paths of them all.
mod counts;
mod half;
mod payload;
mod settings;

pub(crate) use counts::{daylight_nodes, Counts};
pub(crate) use half::f16_finite_to_f32;
pub use half::{f16_to_f32, f32_to_f16};
pub(crate) use payload::decode_payload;
pub use payload::{MatrixBytes, Payload, NO_CHANNEL};
pub use settings::{Formulation, Precision, Quantity};

use crate::error::{Error, Result};

/// The eight bytes every basis starts with.
pub const MAGIC: [u8; 8] = *b"EIGENRAD";
/// The format version this runtime writes and reads.
pub const FORMAT_VERSION: u16 = 9;
/// Size of the fixed header in bytes.
pub const HEADER_LEN: usize = 20;

/// CRC-32/ISO-HDLC (the zlib/PNG CRC): reflected polynomial `0xEDB88320`, initial value and
/// final XOR `0xFFFF_FFFF`. A nibble table keeps it small for flash and fast enough to check
/// a basis at boot.
pub fn crc32(bytes: &[u8]) -> u32 {
    // Evaluated at compile time: an index out of bounds here fails the build, not the device.
    #[allow(clippy::indexing_slicing)]
    const fn table() -> [u32; 16] {
        let mut t = [0u32; 16];
        let mut i = 0;
        while i < 16 {
            let mut c = i as u32;
            let mut k = 0;
            while k < 4 {
                c = if c & 1 != 0 {
                    (c >> 1) ^ 0xEDB8_8320
                } else {
                    c >> 1
                };
                k += 1;
            }
            t[i] = c;
            i += 1;
        }
        t
    }
    const TABLE: [u32; 16] = table();
    let mut crc = !0u32;
    for &byte in bytes {
        crc ^= u32::from(byte);
        for _ in 0..2 {
            // `crc & 0xF` is below 16, so the lookup cannot fail; `unwrap_or` keeps it total.
            let t = TABLE.get((crc & 0xF) as usize).copied().unwrap_or(0);
            crc = (crc >> 4) ^ t;
        }
    }
    !crc
}

/// Bytes the encoding of `payload` takes, header included.
pub fn encoded_len(payload: &Payload<'_>) -> Result<usize> {
    let body = postcard::serialize_with_flavor(payload, postcard::ser_flavors::Size::default())
        .map_err(|_| Error::EncodePayload)?;
    Ok(HEADER_LEN + body)
}

/// Encodes `payload` with its header into `out`, returning the bytes written.
///
/// `out` must hold [`encoded_len`] bytes ([`Error::EncodeBuffer`] otherwise). Host tools
/// allocate that; the runtime itself never encodes.
pub fn encode<'o>(payload: &Payload<'_>, out: &'o mut [u8]) -> Result<&'o mut [u8]> {
    let total = encoded_len(payload)?;
    let too_small = Error::EncodeBuffer {
        needed: total,
        found: out.len(),
    };
    let out = out.get_mut(..total).ok_or(too_small)?;
    let (header, body) = out.split_at_mut_checked(HEADER_LEN).ok_or(too_small)?;
    let len = postcard::to_slice(payload, body)
        .map_err(|_| Error::EncodePayload)?
        .len();
    let crc = crc32(body.get(..len).unwrap_or(&[]));
    let len32 = u32::try_from(len).map_err(|_| Error::EncodeOverflow {
        field: "payload length",
    })?;
    let fields: [&[u8]; 5] = [
        &MAGIC,
        &FORMAT_VERSION.to_le_bytes(),
        &0u16.to_le_bytes(),
        &len32.to_le_bytes(),
        &crc.to_le_bytes(),
    ];
    for (slot, &b) in header.iter_mut().zip(fields.into_iter().flatten()) {
        *slot = b;
    }
    Ok(out)
}

/// Checks the header and checksum of `bytes` and decodes the payload, borrowing from `bytes`.
///
/// Trailing bytes after the payload (e.g. erased flash padding) are ignored. This checks the
/// header section only; [`Basis::from_bytes`](crate::Basis::from_bytes) checks the rest.
pub fn decode(bytes: &[u8]) -> Result<Payload<'_>> {
    decode_payload(check_header(bytes)?)
}

/// The header section of `docs/format.md`: checks magic, version, reserved, that the
/// payload is present, and the checksum, in that order, and returns the payload's bytes.
pub(crate) fn check_header(bytes: &[u8]) -> Result<&[u8]> {
    let header = bytes.get(..HEADER_LEN).ok_or(Error::DecodeTruncated {
        needed: HEADER_LEN,
        found: bytes.len(),
    })?;
    // Byte by byte: a slice comparison calls `memcmp`.
    if !MAGIC.iter().enumerate().all(|(k, &m)| byte(header, k) == m) {
        return Err(Error::DecodeBadMagic);
    }
    let version = u16::from_le_bytes([byte(header, 8), byte(header, 9)]);
    if version != FORMAT_VERSION {
        return Err(Error::DecodeVersion {
            found: version,
            supported: FORMAT_VERSION,
        });
    }
    let reserved = u16::from_le_bytes([byte(header, 10), byte(header, 11)]);
    if reserved != 0 {
        return Err(Error::DecodeField {
            field: "reserved",
            value: u32::from(reserved),
        });
    }
    let len = u32::from_le_bytes([
        byte(header, 12),
        byte(header, 13),
        byte(header, 14),
        byte(header, 15),
    ]);
    let expected = u32::from_le_bytes([
        byte(header, 16),
        byte(header, 17),
        byte(header, 18),
        byte(header, 19),
    ]);
    let needed = HEADER_LEN.saturating_add(len as usize);
    let body = bytes
        .get(HEADER_LEN..needed)
        .ok_or(Error::DecodeTruncated {
            needed,
            found: bytes.len(),
        })?;
    let found = crc32(body);
    if found != expected {
        return Err(Error::DecodeChecksum { expected, found });
    }
    Ok(body)
}

fn byte(bytes: &[u8], at: usize) -> u8 {
    bytes.get(at).copied().unwrap_or(0)
}
