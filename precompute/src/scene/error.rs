//! Scene errors: every one names the file and, where known, the line, field or surface.

use std::fmt;
use std::path::PathBuf;

/// Where in an input file something was found: the file and, when known, the 1-based line.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Location {
    /// The scene file, OBJ file or MTL file.
    pub file: PathBuf,
    /// 1-based line number, when the input format tells us.
    pub line: Option<usize>,
}

impl Location {
    /// A location from a file and a byte offset into its text.
    pub(crate) fn at_offset(file: &std::path::Path, text: &str, offset: usize) -> Self {
        let end = offset.min(text.len());
        let line = text.as_bytes()[..end]
            .iter()
            .filter(|&&b| b == b'\n')
            .count()
            + 1;
        Location {
            file: file.to_path_buf(),
            line: Some(line),
        }
    }

    /// A location naming only a file.
    pub(crate) fn file(file: &std::path::Path) -> Self {
        Location {
            file: file.to_path_buf(),
            line: None,
        }
    }
}

impl fmt::Display for Location {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.line {
            Some(line) => write!(f, "{}:{}", self.file.display(), line),
            None => write!(f, "{}", self.file.display()),
        }
    }
}

/// Why a scene could not be loaded.
///
/// Every variant carries a [`Location`] (file and line) and names the field, surface, channel or
/// sensor at fault, so that the message alone is enough to find and fix the input.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum SceneError {
    /// A file (scene, OBJ or MTL) could not be read.
    // The reason is in the message and deliberately not a `source`: callers printing the
    // error chain would show it twice.
    #[error("{path}: cannot read file: {reason}", path = path.display())]
    Read {
        /// The path that was tried.
        path: PathBuf,
        /// The operating system's reason.
        reason: std::io::Error,
    },
    /// The scene file is not valid TOML or does not match the schema (wrong type, unknown or
    /// missing field).
    #[error("{at}: {message}")]
    Syntax {
        /// File and line of the offending text.
        at: Location,
        /// The parser's message, naming the field.
        message: String,
    },
    /// An OBJ or MTL file could not be parsed.
    #[error("{at}: OBJ/MTL error in `{field}`: {message}")]
    Obj {
        /// The scene entry that names the file.
        at: Location,
        /// The file as written in the scene (`obj.file`).
        field: String,
        /// What went wrong.
        message: String,
    },
    /// A file named by the scene (OBJ or its MTL) does not exist.
    #[error("{at}: {field}: file not found: {path}", path = path.display())]
    MissingFile {
        /// The scene entry that names the file.
        at: Location,
        /// The field that names it.
        field: String,
        /// The resolved path that was looked for.
        path: PathBuf,
    },
    /// A building model (`[[import]]`) is malformed or holds a space that cannot be
    /// imported; the location is the model file's, the element its id.
    #[error("{at}: {element}: {message}")]
    Import {
        /// The model file and, when known, the line of the element.
        at: Location,
        /// The element at fault (space, face, opening, material), by its id in the file.
        element: String,
        /// What is wrong.
        message: String,
    },
    /// A value is outside its allowed range (reflectance, exitance, flux, angle, size...).
    #[error("{at}: {field}: {message}")]
    OutOfRange {
        /// Where the value was written.
        at: Location,
        /// The field, e.g. `materials.wall.reflectance`.
        field: String,
        /// The value and its allowed range.
        message: String,
    },
    /// A list has the wrong length (e.g. per-band values for the wrong number of bands).
    #[error("{at}: {field}: expected {expected} value(s), found {found}")]
    BandCount {
        /// Where the list was written.
        at: Location,
        /// The field.
        field: String,
        /// How many values were expected.
        expected: usize,
        /// How many were found.
        found: usize,
    },
    /// Two things of the same kind share a name.
    #[error("{at}: duplicate {kind} name `{name}`")]
    Duplicate {
        /// Where the second one was defined.
        at: Location,
        /// `surface`, `material`, `channel`, `sensor` or `zone`.
        kind: &'static str,
        /// The name.
        name: String,
    },
    /// A reference to a surface, material or room that does not exist.
    #[error("{at}: {field}: unknown {kind} `{name}`")]
    Unknown {
        /// Where the reference was written.
        at: Location,
        /// The field holding the reference.
        field: String,
        /// `surface`, `material` or `room`.
        kind: &'static str,
        /// The name that was not found.
        name: String,
    },
    /// A face is degenerate (zero area or a zero-length edge), non-planar or not convex.
    #[error("{at}: surface `{surface}`, face {face}: {message}")]
    BadFace {
        /// Where the surface was defined.
        at: Location,
        /// The surface name.
        surface: String,
        /// 1-based index of the face within the surface.
        face: usize,
        /// What is wrong, with the measured figure.
        message: String,
    },
    /// A channel drives no emitting surface.
    #[error("{at}: channel `{channel}`: {message}")]
    EmptyChannel {
        /// Where the channel was defined.
        at: Location,
        /// The channel.
        channel: String,
        /// Why nothing emits.
        message: String,
    },
    /// A surface emits light but no channel drives it, or two channels claim it.
    #[error("{at}: surface `{surface}`: {message}")]
    Emitter {
        /// Where the surface (or the second channel) was defined.
        at: Location,
        /// The surface.
        surface: String,
        /// What is wrong.
        message: String,
    },
    /// A luminaire's photometric file could not be read; the reader's error names that file
    /// and its line.
    #[error("{at}: {field}: {reason}")]
    Photometry {
        /// Where the scene names the file.
        at: Location,
        /// The field naming it (`luminaire `NAME`.file`).
        field: String,
        /// The reader's error.
        reason: Box<crate::scene::photometry::PhotometryError>,
    },
    /// A zone or sensor is not well defined (e.g. zero-length normal, no surfaces).
    #[error("{at}: {field}: {message}")]
    Invalid {
        /// Where it was defined.
        at: Location,
        /// The field at fault.
        field: String,
        /// What is wrong.
        message: String,
    },
    /// A work plane would have more receivers than a build on this machine can hold next to
    /// the scene's patches ([`crate::memory::receiver_bytes`]); refused before meshing it.
    #[error(
        "{at}: {field}: the work plane would have about {receivers:.3e} receivers; their form \
         factors to the scene's patches and the build need about {needed:.3e} bytes, more than \
         the {available:.3e} bytes a build may use on this machine; raise `max_edge`"
    )]
    TooManyReceivers {
        /// Where the work plane's `max_edge` (or the scene's) was written.
        at: Location,
        /// The mesh size setting at fault.
        field: String,
        /// Estimated receiver count.
        receivers: f64,
        /// Estimated memory, bytes.
        needed: f64,
        /// Memory a build may use ([`crate::memory::budget_bytes`]), bytes.
        available: f64,
    },
    /// Meshing would make more patches than a build on this machine can hold
    /// ([`crate::memory::build_bytes`]); refused before meshing.
    #[error(
        "{at}: {field}: meshing would make about {patches:.3e} patches; the form factors and \
         the solve need about {needed:.3e} bytes (the form-factor operator \
         `--operator auto` stores at that size, and the solvers' workspace), more than the {available:.3e} bytes a build may use \
         on this machine; raise `max_edge`"
    )]
    TooManyPatches {
        /// Where the scene's `max_edge` was written.
        at: Location,
        /// The mesh size setting at fault (`scene.max_edge`, or the surface's).
        field: String,
        /// Estimated patch count.
        patches: f64,
        /// Estimated memory, bytes.
        needed: f64,
        /// Memory a build may use ([`crate::memory::budget_bytes`]), bytes.
        available: f64,
    },
}
