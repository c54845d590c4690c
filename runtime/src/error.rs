//! The runtime's one error type.

use core::fmt;

/// Result with the runtime's [`Error`].
pub type Result<T> = core::result::Result<T, Error>;

/// Everything that can go wrong when encoding, decoding or evaluating a basis.
///
/// Decoding errors (`Decode*`) come from [`Basis::from_bytes`](crate::Basis::from_bytes) and
/// mean the byte string is not a valid basis. Encoding errors (`Encode*`) come from the
/// host-side writer ([`format::encode`](crate::format::encode) and `writer::BasisTables`) and
/// mean the tables cannot be written in the format. The others come from the evaluators
/// ([`ChannelEvaluator`](crate::ChannelEvaluator), [`Evaluator`](crate::Evaluator)) and
/// mean the request does not fit the basis or the evaluator's capacities;
/// [`Error::UnknownName`] is for callers that look a name up. No byte string and no request
/// makes the runtime panic.
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub enum Error {
    /// The byte string is shorter than the fixed header or than the payload it announces.
    DecodeTruncated {
        /// Bytes needed.
        needed: usize,
        /// Bytes present.
        found: usize,
    },
    /// The first eight bytes are not `EIGENRAD`: this is not a basis.
    DecodeBadMagic,
    /// The basis was written in a format version this runtime does not read.
    DecodeVersion {
        /// Version in the header.
        found: u16,
        /// The version this runtime reads.
        supported: u16,
    },
    /// The CRC-32 of the payload differs from the header's: the bytes were corrupted.
    DecodeChecksum {
        /// Checksum stored in the header.
        expected: u32,
        /// Checksum of the payload as found.
        found: u32,
    },
    /// The payload is not a valid postcard encoding of the basis layout.
    DecodePayload,
    /// A header field, setting or count holds a value outside its range.
    DecodeField {
        /// The field, as named in `docs/format.md`.
        field: &'static str,
        /// The value found.
        value: u32,
    },
    /// A table's byte length does not match the counts in the payload.
    DecodeLength {
        /// The table, as named in `docs/format.md`, or `daylight` for the daylight section's
        /// sized tables together (`Basis::from_bytes` checks their total; the table is named
        /// when daylight is used).
        field: &'static str,
        /// Byte length the dimensions require.
        expected: usize,
        /// Byte length found.
        found: usize,
    },
    /// A stored number is NaN, infinite or outside the range the format allows, or a name
    /// (`field` `names`, checked when it is read) is not UTF-8.
    DecodeValue {
        /// The table, as named in `docs/format.md`.
        field: &'static str,
        /// Element index within that table.
        index: usize,
    },
    /// The buffer given to the encoder is shorter than the encoded basis.
    EncodeBuffer {
        /// Bytes the encoding takes, header included.
        needed: usize,
        /// Bytes the buffer has.
        found: usize,
    },
    /// A number does not fit the field the format gives it: `bands` in a byte, a count or
    /// the payload length in 32 bits.
    EncodeOverflow {
        /// The field, as named in `docs/format.md`.
        field: &'static str,
    },
    /// The payload could not be serialised with postcard.
    EncodePayload,
    /// The basis needs more room than the evaluator's compile-time capacities give.
    Capacity {
        /// Which capacity (`"patches"`, `"modes"`, `"channels"`, `"outputs"`, `"bands"`).
        what: &'static str,
        /// What the basis needs.
        needed: usize,
        /// What the evaluator type provides.
        capacity: usize,
    },
    /// An index (patch, channel, sensor, zone) beyond the basis' count.
    IndexOutOfRange {
        /// Which kind of index.
        what: &'static str,
        /// The index given.
        index: usize,
        /// How many there are.
        count: usize,
    },
    /// A caller's slice has the wrong length.
    LengthMismatch {
        /// Which argument.
        what: &'static str,
        /// Length required.
        expected: usize,
        /// Length given.
        found: usize,
    },
    /// A level or exitance is negative, NaN, infinite, or so large that the result would
    /// overflow `f32`; the evaluator's state is left unchanged.
    InvalidInput {
        /// Which argument.
        what: &'static str,
    },
    /// Irradiance cannot be read back from the exitance of a patch with zero reflectance in
    /// this band (it reflects nothing); use a sensor or a zone there.
    BlackPatch {
        /// The patch.
        patch: usize,
    },
    /// A zone's grid figures were asked for, but the zone has no calculation grid (surface
    /// zones have none) or a reading on it is not finite.
    NoGrid {
        /// The zone.
        zone: usize,
    },
    /// DALI arc power level 255 is "MASK" (no change), not a light level.
    DaliMask,
    /// Daylight was asked of a basis that carries none (its scene had no site or no
    /// glazed window, docs/scene.md "Daylight").
    NoDaylight,
    /// A sun, sky or glazing input (module [`sky`](crate::sky)) is NaN or outside the range
    /// its model is defined on.
    OutOfRange {
        /// Which input, with its unit.
        what: &'static str,
        /// What it must be, in words (`"from 1 to 15"`): the runtime formats no floats.
        range: &'static str,
    },
    /// A name the caller needs is not in the basis. The runtime's lookups
    /// ([`Basis::find_channel`](crate::Basis::find_channel) and the like) return `None`; a
    /// controller that cannot run without the name reports it with this.
    UnknownName {
        /// Which kind of name (`"channel"`, `"sensor"`, `"zone"`).
        what: &'static str,
    },
    /// A [`LevelProblem`](crate::LevelProblem) bound whose lower bound is above its upper
    /// bound.
    InvalidBound {
        /// The bound, in the order added.
        bound: usize,
    },
    /// No channel levels in [0, 1] meet every bound of a
    /// [`LevelProblem`](crate::LevelProblem): the levels written are the closest (least
    /// total violation), and this is the bound they violate the most.
    BoundUnmet {
        /// The bound, in the order added.
        bound: usize,
        /// The upper bound is exceeded (else the lower bound is not reached).
        upper: bool,
        /// By how much, in the reading's unit (lux in a photopic basis).
        by: f32,
    },
    /// The level solver stopped after this many pivots without an optimum (a safeguard
    /// against rounding; see `target.rs`).
    PivotLimit {
        /// Pivots and bound flips made.
        pivots: u32,
    },
}

impl fmt::Display for Error {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            Error::DecodeTruncated { needed, found } => {
                write!(f, "basis truncated: {needed} bytes needed, {found} present")
            }
            Error::DecodeBadMagic => f.write_str("not an eigenrad basis (bad magic bytes)"),
            Error::DecodeVersion { found, supported } => write!(
                f,
                "basis format version {found} is not supported: this runtime reads version \
                 {supported}; rebuild the basis with `eigenrad build`"
            ),
            Error::DecodeChecksum { expected, found } => write!(
                f,
                "basis checksum mismatch: header says {expected:#010x}, payload has {found:#010x}"
            ),
            Error::DecodePayload => f.write_str("basis payload is not a valid postcard encoding"),
            Error::DecodeField { field, value } => {
                write!(f, "basis field `{field}` has invalid value {value}")
            }
            Error::DecodeLength {
                field,
                expected,
                found,
            } => write!(
                f,
                "basis table `{field}` is {found} bytes, its counts need {expected}"
            ),
            Error::DecodeValue { field, index } => write!(
                f,
                "basis table `{field}` element {index} is not finite, out of range or (a name) not UTF-8"
            ),
            Error::EncodeBuffer { needed, found } => write!(
                f,
                "encoding the basis takes {needed} bytes, the buffer has {found}"
            ),
            Error::EncodeOverflow { field } => {
                write!(f, "basis field `{field}` is too large for the format")
            }
            Error::EncodePayload => f.write_str("basis payload could not be serialised"),
            Error::Capacity {
                what,
                needed,
                capacity,
            } => write!(
                f,
                "basis needs {needed} {what} but the evaluator has room for {capacity}"
            ),
            Error::IndexOutOfRange { what, index, count } => {
                write!(f, "{what} index {index} out of range (there are {count})")
            }
            Error::LengthMismatch {
                what,
                expected,
                found,
            } => {
                write!(f, "`{what}` has length {found}, expected {expected}")
            }
            Error::InvalidInput { what } => write!(
                f,
                "`{what}` must be finite, non-negative and small enough not to overflow"
            ),
            Error::BlackPatch { patch } => write!(
                f,
                "patch {patch} has zero reflectance: its irradiance is not defined by its exitance"
            ),
            Error::NoGrid { zone } => {
                write!(
                    f,
                    "zone {zone} has no calculation grid with finite readings"
                )
            }
            Error::NoDaylight => f.write_str(
                "the basis carries no daylight: build it from a scene with a [site] and glazed windows",
            ),
            Error::DaliMask => f.write_str("DALI arc power level 255 (MASK) is not a light level"),
            Error::OutOfRange { what, range } => write!(f, "{what} must be {range}"),
            Error::UnknownName { what } => write!(f, "the basis has no {what} of that name"),
            Error::InvalidBound { bound } => {
                write!(f, "bound {bound}: its lower bound is above its upper bound")
            }
            Error::BoundUnmet { bound, upper, by } => {
                write!(
                f,
                "no channel levels in [0, 1] meet bound {bound}: the closest levels {} by {by:e} \
                 (lux in a photopic basis)",
                if upper { "exceed its upper bound" } else { "fall short of its lower bound" }
            )
            }
            Error::PivotLimit { pivots } => write!(
                f,
                "the level solver stopped after {pivots} pivots without reaching an optimum"
            ),
        }
    }
}

impl core::error::Error for Error {}
