//! Why a photometric file could not be read. Every variant past [`PhotometryError::Read`] names
//! the file and the 1-based line at fault, so that the message alone finds the mistake.

use std::path::{Path, PathBuf};

/// A photometric file that could not be read, or whose content is not a valid LM-63 or
/// EULUMDAT file of type C photometry.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum PhotometryError {
    /// The file could not be read.
    // The reason is in the message and deliberately not a `source`: callers printing the
    // error chain would show it twice.
    #[error("{path}: cannot read file: {reason}", path = path.display())]
    Read {
        /// The path that was tried.
        path: PathBuf,
        /// The operating system's reason.
        reason: std::io::Error,
    },
    /// The file's name does not say which format it is in.
    #[error(
        "{path}: unknown photometric format: expected an .ies (IES LM-63) or .ldt (EULUMDAT) file",
        path = path.display()
    )]
    UnknownFormat {
        /// The file.
        path: PathBuf,
    },
    /// A record or a list holds more or fewer values than the file's own counts announce, or
    /// the file ends before them.
    #[error("{path}:{line}: expected {expected} {what}, found {found}", path = path.display())]
    Count {
        /// The file.
        path: PathBuf,
        /// 1-based line of the record at fault (the file's last line when it ends early).
        line: usize,
        /// What was being read ("vertical angles", "candela values for horizontal angle 45").
        what: String,
        /// How many the file's counts announce.
        expected: usize,
        /// How many there are.
        found: usize,
    },
    /// A field that must be a number is not one.
    #[error("{path}:{line}: {what}: `{text}` is not a number", path = path.display())]
    NotANumber {
        /// The file.
        path: PathBuf,
        /// 1-based line.
        line: usize,
        /// The field ("candela multiplier", "C angle 3").
        what: String,
        /// The text found.
        text: String,
    },
    /// A value is out of its range or inconsistent with the rest of the file: negative or
    /// non-finite candela, angles not increasing, a symmetry the angles do not match.
    #[error("{path}:{line}: {message}", path = path.display())]
    Invalid {
        /// The file.
        path: PathBuf,
        /// 1-based line.
        line: usize,
        /// What is wrong, naming the field and its value.
        message: String,
    },
    /// The file uses a feature this reader does not implement (type A or B photometry, a tilt
    /// table in a separate file in LM-63-2019, which no longer allows one).
    #[error("{path}:{line}: {feature} is not supported", path = path.display())]
    Unsupported {
        /// The file.
        path: PathBuf,
        /// 1-based line.
        line: usize,
        /// The feature, as the file spells it.
        feature: String,
    },
}

impl PhotometryError {
    /// The file the error is about.
    pub fn path(&self) -> &Path {
        match self {
            Self::Read { path, .. }
            | Self::UnknownFormat { path }
            | Self::Count { path, .. }
            | Self::NotANumber { path, .. }
            | Self::Invalid { path, .. }
            | Self::Unsupported { path, .. } => path,
        }
    }

    /// The 1-based line at fault, when the error is about the file's content.
    pub fn line(&self) -> Option<usize> {
        match self {
            Self::Read { .. } | Self::UnknownFormat { .. } => None,
            Self::Count { line, .. }
            | Self::NotANumber { line, .. }
            | Self::Invalid { line, .. }
            | Self::Unsupported { line, .. } => Some(*line),
        }
    }
}
