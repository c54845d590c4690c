//! What both readers share: numbered lines, numbers that must be finite, and errors that
//! carry the file and line.

use std::path::Path;

use super::PhotometryError;

/// The file being read, for error messages.
#[derive(Clone, Copy)]
pub(super) struct File<'a> {
    pub path: &'a Path,
}

impl<'a> File<'a> {
    pub fn new(path: &'a Path) -> Self {
        File { path }
    }

    pub fn invalid(&self, line: usize, message: impl Into<String>) -> PhotometryError {
        PhotometryError::Invalid {
            path: self.path.to_path_buf(),
            line,
            message: message.into(),
        }
    }

    pub fn count(
        &self,
        line: usize,
        what: impl Into<String>,
        expected: usize,
        found: usize,
    ) -> PhotometryError {
        PhotometryError::Count {
            path: self.path.to_path_buf(),
            line,
            what: what.into(),
            expected,
            found,
        }
    }

    pub fn unsupported(&self, line: usize, feature: impl Into<String>) -> PhotometryError {
        PhotometryError::Unsupported {
            path: self.path.to_path_buf(),
            line,
            feature: feature.into(),
        }
    }

    /// A finite number. `what` names the field and is only formatted on error.
    pub fn number(
        &self,
        line: usize,
        text: &str,
        what: impl Fn() -> String,
    ) -> Result<f64, PhotometryError> {
        let value: f64 = text.parse().map_err(|_| PhotometryError::NotANumber {
            path: self.path.to_path_buf(),
            line,
            what: what(),
            text: text.to_string(),
        })?;
        if value.is_finite() {
            Ok(value)
        } else {
            // `f64::from_str` reads "inf" and "NaN"; neither is a measurement.
            Err(self.invalid(line, format!("{}: `{text}` is not finite", what())))
        }
    }

    /// A whole number in `min..=max`. Written as a decimal ("3.0") is accepted, as LM-63-1986
    /// allows.
    pub fn integer(
        &self,
        line: usize,
        text: &str,
        min: i64,
        max: i64,
        what: impl Fn() -> String,
    ) -> Result<i64, PhotometryError> {
        let value = self.number(line, text, &what)?;
        if value.fract() != 0.0 || value < min as f64 || value > max as f64 {
            return Err(self.invalid(
                line,
                format!(
                    "{}: {text} is not a whole number from {min} to {max}",
                    what()
                ),
            ));
        }
        Ok(value as i64)
    }
}

/// The text's lines with their 1-based numbers (LF or CR LF line ends).
pub(super) fn lines(text: &str) -> impl Iterator<Item = (usize, &str)> {
    text.lines().enumerate().map(|(i, l)| (i + 1, l))
}

/// The values of an LM-63 line: separated by blanks or commas.
pub(super) fn words(line: &str) -> impl Iterator<Item = &str> {
    line.split(|c: char| c.is_whitespace() || c == ',')
        .filter(|w| !w.is_empty())
}

/// The text of a file, whatever its encoding: EULUMDAT files are often Latin-1 and LM-63 files
/// may carry any bytes in their keywords; only the numbers need to be ASCII.
pub(super) fn decode(bytes: &[u8]) -> String {
    String::from_utf8_lossy(bytes).into_owned()
}
