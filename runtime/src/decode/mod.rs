//! Decoding a basis, one function per section of `docs/format.md`: header
//! ([`format::check_header`]), settings and counts ([`dimensions`]), then the room's
//! sections, names to grids ([`room`]), and the daylight's ([`daylight`], with its direct
//! sun in [`direct_sun`]).
//!
//! Each section checks its tables' lengths against the counts and every stored value against
//! its range, so that the evaluator reads the tables without checking them again.
//! [`Basis::from_bytes`], defined here, runs the sections in payload order and returns the
//! first failure. The daylight's values are the exception: `from_bytes` checks that section's
//! shape (which tables, how long), and [`check_daylight`] its values, when daylight is used
//! ([`Basis::check_daylight`]), so that a firmware that reads no daylight links none of it.

// The settings and counts every later length follows from.
mod dimensions;
// The daylight section: its shape at decode, its values where it is used.
mod daylight;
// The direct sun's geometry, part of the daylight section (format version 6).
mod direct_sun;
// The daylight's first reflection, part of the daylight section (format version 7).
mod reflection;
// The sun's first reflection, part of the daylight section (format version 8).
mod sun_first;
// The sections every basis has: names, eigenvalues, patch tables, modes, black patches,
// channel tables, outputs, grids.
mod room;
// The checks of one table (length, values, indices, matrix), shared by every section.
mod tables;

pub(crate) use daylight::check_values as check_daylight;

use crate::basis::Basis;
use crate::error::Result;
use crate::format;

impl<'a> Basis<'a> {
    /// Decodes and validates a basis in place.
    ///
    /// Checks the magic, the format version, the CRC-32 of the payload, every table length
    /// against the counts, and that every stored number is finite and in range, section by
    /// section of `docs/format.md`; of the daylight section, its tables' lengths only (its
    /// values are checked when it is used: [`Basis::check_daylight`]). Vector data stays
    /// where it is (flash): only slice headers are kept. Any byte string gives `Ok` or an
    /// `Err`; none panics.
    pub fn from_bytes(bytes: &'a [u8]) -> Result<Self> {
        let body = format::check_header(bytes)?;
        let raw = format::decode_payload(body)?;
        let dimensions::Settings {
            bands,
            quantity,
            formulation,
            precision,
        } = dimensions::settings(&raw)?;
        let counts = dimensions::counts(&raw, bands)?;
        room::names(&raw, &counts)?;
        room::eigenvalues(&raw, &counts, formulation)?;
        room::patch_tables(&raw, &counts)?;
        room::modes(&raw, &counts, precision)?;
        room::black_patches(&raw, &counts)?;
        room::channel_tables(&raw, &counts, precision)?;
        room::outputs(&raw, &counts, precision)?;
        room::grids(&raw, &counts, precision)?;
        daylight::shape(&raw, &counts, quantity, precision)?;
        Ok(Basis {
            quantity,
            formulation,
            precision,
            counts,
            byte_len: format::HEADER_LEN + body.len(),
            tables: raw,
        })
    }
}
