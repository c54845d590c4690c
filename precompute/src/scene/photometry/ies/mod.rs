//! IES LM-63 files (`.ies`), versions 1986 to 2019, type C photometry.
//!
//! A file is a version line (none in LM-63-1986), label lines (`[KEYWORD] value`), a `TILT=`
//! line, then records of numbers separated by blanks or commas. Every record is made of whole
//! lines, as LM-63 requires, and that is what lets a count that does not match its data be
//! named at its line: the values are read record by record, and a record that ends inside a
//! line is too long or (when the next record then fits exactly) too short. The records:
//!
//! 1. with `TILT=INCLUDE`: lamp-to-luminaire geometry; number of tilt angles `n`; `n` angles;
//!    `n` multiplying factors. With `TILT=<file>` (LM-63 up to 2002; LM-63-2019 dropped it)
//!    these four records are that file's whole content instead, the file named relative to
//!    the folder of the `.ies` file (an absolute name as it is), and its errors name it;
//! 2. number of lamps, lumens per lamp (−1: absolute photometry), candela multiplier, number
//!    of vertical angles, number of horizontal angles, photometric type (1 = C), units (1 =
//!    feet, 2 = metres), width, length, height of the luminous opening;
//! 3. ballast factor, a field whose meaning changed (ballast-lamp photometric factor in 1986
//!    and 1991, "future use" in 1995 and 2002, file generation type in 2019), input watts;
//! 4. the vertical angles; the horizontal angles; one record of candela values (one per
//!    vertical angle) for each horizontal angle.
//!
//! The candela written are multiplied by the candela multiplier and the ballast factor, and in
//! 1986 and 1991 files by the ballast-lamp photometric factor (later versions do not define
//! that field as a factor; Radiance's `ies2rad` reads it the same way).

mod distribution;
mod header;
mod label;
mod records;
mod tilt;

use std::path::Path;

use super::text::{decode, lines, File};
use super::{Format, Lm63Version, Photometry, PhotometryError};
use distribution::read_distribution;
use header::read_header;
use label::{label, version, Tag};
use records::{Next, Records};
use tilt::{read_tilt, read_tilt_file};

type Result<T> = std::result::Result<T, PhotometryError>;

/// Reads an LM-63 file's bytes; `path` names the file in errors.
pub fn parse(path: &Path, bytes: &[u8]) -> Result<Photometry> {
    let file = File::new(path);
    let text = decode(bytes);
    let lines: Vec<(usize, &str)> = lines(&text).collect();
    let first = lines
        .first()
        .map_or("", |(_, l)| l.trim_start_matches('\u{feff}'));
    let (version, label_start) = match version(first) {
        Tag::Known(v) => (v, 1),
        Tag::None => (Lm63Version::V1986, 0),
        Tag::Unknown => {
            return Err(file.unsupported(1, format!("LM-63 version line `{}`", first.trim())))
        }
    };
    let (identity, tilt_index) = label(&lines, label_start);
    let Some(tilt_index) = tilt_index else {
        let last = lines.last().map_or(1, |(n, _)| *n);
        return Err(file.invalid(last, "no `TILT=` line: this is no LM-63 file"));
    };
    let (tilt_line, tilt_text) = lines[tilt_index];
    let mut records = Records::new(file, &lines[tilt_index + 1..], tilt_line);
    let spec = tilt_text.trim()[5..].trim();
    let tilt = if spec.eq_ignore_ascii_case("NONE") {
        None
    } else if spec.eq_ignore_ascii_case("INCLUDE") {
        Some(read_tilt(&mut records, Next::Size(10))?)
    } else if version >= Lm63Version::V2019 {
        return Err(file.unsupported(
            tilt_line,
            format!(
                "`TILT={spec}` (a tilt table in a separate file, which LM-63-2019 no longer \
                 allows)"
            ),
        ));
    } else if spec.is_empty() {
        return Err(file.invalid(tilt_line, "`TILT=` names no tilt table"));
    } else {
        Some(read_tilt_file(&file, tilt_line, spec)?)
    };
    let header = read_header(&mut records, version)?;
    let (symmetry, distribution) = read_distribution(&mut records, &header)?;
    let lamp_flux = (!header.absolute).then(|| header.lumens_per_lamp * f64::from(header.lamps));
    Ok(Photometry {
        format: Format::Lm63(version),
        identity,
        symmetry,
        opening: header.opening,
        luminaire: None,
        lamps: header.lamps,
        absolute: header.absolute,
        lamp_flux,
        luminaire_flux: None,
        downward_fraction: None,
        input_watts: Some(header.watts),
        tilt,
        distribution,
    })
}
