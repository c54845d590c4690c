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

use std::path::Path;

use super::text::{decode, lines, words, File};
use super::{
    Distribution, Format, Identity, LampGeometry, Lm63Version, Opening, OpeningShape, Photometry,
    PhotometryError, Symmetry, Tilt,
};

type Result<T> = std::result::Result<T, PhotometryError>;

/// Feet to metres.
const FOOT: f64 = 0.3048;

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

enum Tag {
    Known(Lm63Version),
    /// No version line: LM-63-1986.
    None,
    /// An LM-63 version line of a version this reader does not know.
    Unknown,
}

fn version(first_line: &str) -> Tag {
    let tag: String = first_line
        .chars()
        .filter(|c| !c.is_whitespace())
        .collect::<String>()
        .to_ascii_uppercase();
    match tag.as_str() {
        "IESNA91" => Tag::Known(Lm63Version::V1991),
        "IESNA:LM-63-1995" => Tag::Known(Lm63Version::V1995),
        "IESNA:LM-63-2002" => Tag::Known(Lm63Version::V2002),
        "IES:LM-63-2019" | "IESNA:LM-63-2019" => Tag::Known(Lm63Version::V2019),
        t if t.starts_with("IESNA:LM-63") || t.starts_with("IES:LM-63") => Tag::Unknown,
        _ => Tag::None,
    }
}

fn is_tilt_line(line: &str) -> bool {
    let t = line.trim_start().as_bytes();
    t.len() >= 5 && t[..5].eq_ignore_ascii_case(b"TILT=")
}

/// The keywords of the label lines from `start` up to the `TILT=` line, and that line's index.
fn label(lines: &[(usize, &str)], start: usize) -> (Identity, Option<usize>) {
    let mut identity = Identity::default();
    let mut tilt = None;
    for (index, (_, line)) in lines.iter().enumerate().skip(start) {
        if is_tilt_line(line) {
            tilt = Some(index);
            break;
        }
        let line = line.trim();
        let keyword = line
            .strip_prefix('[')
            .and_then(|rest| rest.split_once(']'))
            .map(|(key, value)| (key.trim().to_ascii_uppercase(), value.trim().to_string()));
        match (keyword, identity.keywords.last_mut()) {
            // [MORE] continues the keyword before it.
            (Some((key, value)), Some(last)) if key == "MORE" => {
                last.1.push(' ');
                last.1.push_str(&value);
            }
            (Some(pair), _) => identity.keywords.push(pair),
            // LM-63-1986's free-form label, or a stray line: kept, under no keyword.
            (None, _) if !line.is_empty() => identity.keywords.push((String::new(), line.into())),
            (None, _) => {}
        }
    }
    let find = |key: &str| {
        identity
            .keywords
            .iter()
            .find(|(k, v)| k == key && !v.is_empty())
            .map(|(_, v)| v.clone())
    };
    identity.manufacturer = find("MANUFAC");
    identity.catalogue = find("LUMCAT");
    identity.luminaire = find("LUMINAIRE");
    identity.lamp = find("LAMP");
    identity.test = find("TEST");
    (identity, tilt)
}

/// One value and its line.
#[derive(Clone, Copy)]
struct Value<'a> {
    line: usize,
    text: &'a str,
}

/// What follows the record being read, for telling a short record from a long one.
#[derive(Clone, Copy)]
enum Next {
    /// A record of this many values.
    Size(usize),
    /// A record governed by the same count as this one (tilt angles, then their factors): if
    /// the count is wrong, the next record is as long as this one really is.
    Same,
    /// Nothing: the file's data ends.
    End,
    /// Not known yet.
    Unknown,
}

/// The numeric lines after `TILT=`, read as whole-line records.
struct Records<'a> {
    file: File<'a>,
    /// Lines that hold values, with their values.
    lines: Vec<(usize, Vec<&'a str>)>,
    /// Index of the first line not read yet.
    next: usize,
    /// The line an error names when the file ends before any value.
    before_data: usize,
}

impl<'a> Records<'a> {
    fn new(file: File<'a>, lines: &[(usize, &'a str)], before_data: usize) -> Self {
        let lines = lines
            .iter()
            .map(|(n, l)| (*n, words(l).collect::<Vec<_>>()))
            .filter(|(_, w)| !w.is_empty())
            .collect();
        Records {
            file,
            lines,
            next: 0,
            before_data,
        }
    }

    /// The next record of `n` values, on whole lines.
    fn record(&mut self, n: usize, what: &str, next: Next) -> Result<Vec<Value<'a>>> {
        let start = self.next;
        let (mut found, mut end) = (0, start);
        while found < n {
            let Some((_, values)) = self.lines.get(end) else {
                let line = if end > start {
                    self.lines[end - 1].0
                } else {
                    self.lines.last().map_or(self.before_data, |l| l.0)
                };
                return Err(self.file.count(line, what, n, found));
            };
            found += values.len();
            end += 1;
        }
        if found > n {
            let last = end - 1;
            let before = found - self.lines[last].1.len();
            // The record ends inside a line: either that line holds too many values, or the
            // record ended on the line before and this line starts the next record.
            let fits = match next {
                Next::Same => self.fits(last, n) || self.fits(last, before),
                Next::Size(size) => self.fits(last, size),
                Next::End | Next::Unknown => false,
            };
            if before > 0 && fits {
                return Err(self.file.count(self.lines[last - 1].0, what, n, before));
            }
            return Err(self.file.count(self.lines[last].0, what, n, found));
        }
        self.next = end;
        Ok(self.lines[start..end]
            .iter()
            .flat_map(|(line, values)| {
                values.iter().map(|t| Value {
                    line: *line,
                    text: t,
                })
            })
            .collect())
    }

    /// Whether a record of `size` values fills whole lines from line `from`.
    fn fits(&self, from: usize, size: usize) -> bool {
        let mut sum = 0;
        for (_, values) in &self.lines[from..] {
            sum += values.len();
            if sum >= size {
                return sum == size;
            }
        }
        false
    }

    /// No value may follow the last record.
    fn finish(&self, counts_line: usize) -> Result<()> {
        let Some((line, _)) = self.lines.get(self.next) else {
            return Ok(());
        };
        let extra: usize = self.lines[self.next..].iter().map(|(_, v)| v.len()).sum();
        Err(self.file.invalid(
            *line,
            format!(
                "{extra} values follow the last candela record: the counts on line \
                 {counts_line} do not match the data"
            ),
        ))
    }

    fn number(&self, v: Value, what: &str) -> Result<f64> {
        self.file.number(v.line, v.text, || what.to_string())
    }

    fn integer(&self, v: Value, what: &str, min: i64, max: i64) -> Result<i64> {
        self.file
            .integer(v.line, v.text, min, max, || what.to_string())
    }
}

/// A tilt table in a file of its own (`TILT=<name>` on line `tilt_line` of `ies`): `name`
/// relative to the folder of the `.ies` file, holding the table's four records and nothing
/// else. A file that cannot be read is an error at the `TILT=` line; a fault inside it names
/// that file and its line.
fn read_tilt_file(ies: &File, tilt_line: usize, name: &str) -> Result<Tilt> {
    let path = ies.path.parent().unwrap_or(Path::new("")).join(name);
    let bytes = std::fs::read(&path).map_err(|reason| {
        ies.invalid(
            tilt_line,
            format!(
                "`TILT={name}`: cannot read the tilt table's file {}: {reason}",
                path.display()
            ),
        )
    })?;
    let text = decode(&bytes);
    let lines: Vec<(usize, &str)> = lines(&text).collect();
    let mut records = Records::new(File::new(&path), &lines, 1);
    let tilt = read_tilt(&mut records, Next::End)?;
    if let Some((line, _)) = records.lines.get(records.next) {
        let extra: usize = records.lines[records.next..]
            .iter()
            .map(|(_, v)| v.len())
            .sum();
        return Err(records.file.invalid(
            *line,
            format!(
                "{extra} values follow the tilt table: its number of angles does not match \
                 the data"
            ),
        ));
    }
    Ok(tilt)
}

/// The four records of a tilt table; `after` is what follows its factors.
fn read_tilt(records: &mut Records, after: Next) -> Result<Tilt> {
    let g = records.record(1, "lamp-to-luminaire geometry", Next::Size(1))?[0];
    let geometry = match records.integer(g, "lamp-to-luminaire geometry", 1, 3)? {
        1 => LampGeometry::Vertical,
        2 => LampGeometry::Horizontal0,
        _ => LampGeometry::Horizontal90,
    };
    let c = records.record(1, "number of tilt angles", Next::Unknown)?[0];
    let n = records.integer(c, "number of tilt angles", 1, i64::from(u32::MAX))? as usize;
    let angle_values = records.record(n, "tilt angles", Next::Same)?;
    let factor_values = records.record(n, "tilt multiplying factors", after)?;
    let angles = increasing_angles(records, &angle_values, "tilt angle", -90.0, 180.0)?;
    let mut factors = Vec::with_capacity(n);
    for v in factor_values {
        let f = records.number(v, "tilt multiplying factor")?;
        if f < 0.0 {
            return Err(records
                .file
                .invalid(v.line, format!("tilt multiplying factor {f} is negative")));
        }
        factors.push(f);
    }
    Ok(Tilt {
        geometry,
        angles,
        factors,
    })
}

/// What the two header records say.
struct Header {
    lamps: u32,
    lumens_per_lamp: f64,
    absolute: bool,
    /// Candela multiplier × ballast factor (× ballast-lamp factor in 1986 and 1991).
    scale: f64,
    vertical: usize,
    horizontal: usize,
    opening: Opening,
    watts: f64,
    /// The line of the counts, for messages about data that does not match them.
    counts_line: usize,
}

fn read_header(records: &mut Records, version: Lm63Version) -> Result<Header> {
    const FIRST: &str = "values in the record of lamps, lumens, multiplier, angle counts, \
                         photometric type, units and luminous opening";
    let r = records.record(10, FIRST, Next::Size(3))?;
    let lamps = records.integer(r[0], "number of lamps", 1, i64::from(u32::MAX))? as u32;
    let lumens_per_lamp = records.number(r[1], "lumens per lamp")?;
    let absolute = lumens_per_lamp == -1.0;
    if !absolute && lumens_per_lamp <= 0.0 {
        return Err(records.file.invalid(
            r[1].line,
            format!(
                "lumens per lamp {lumens_per_lamp}: must be positive, or −1 for absolute \
                 photometry"
            ),
        ));
    }
    let multiplier = positive(records, r[2], "candela multiplier")?;
    let count = |v, what| records.integer(v, what, 1, i64::from(u32::MAX));
    let vertical = count(r[3], "number of vertical angles")? as usize;
    let horizontal = count(r[4], "number of horizontal angles")? as usize;
    if vertical < 2 {
        return Err(records
            .file
            .invalid(r[3].line, "at least two vertical angles are needed"));
    }
    match records.integer(r[5], "photometric type", 1, 3)? {
        1 => {}
        2 => {
            return Err(records
                .file
                .unsupported(r[5].line, "type B photometry (type 2)"))
        }
        _ => {
            return Err(records
                .file
                .unsupported(r[5].line, "type A photometry (type 3)"))
        }
    }
    let unit = match records.integer(r[6], "units type (1 feet, 2 metres)", 1, 2)? {
        1 => FOOT,
        _ => 1.0,
    };
    let size = |v| {
        records
            .number(v, "luminous opening dimension")
            .map(|x| x * unit)
    };
    let (width, length, height) = (size(r[7])?, size(r[8])?, size(r[9])?);
    let opening = opening(width, length, height).ok_or_else(|| {
        let message = format!(
            "luminous opening width {width} m, length {length} m, height {height} m matches no \
             LM-63 shape"
        );
        records.file.invalid(r[7].line, message)
    })?;
    let b = records.record(
        3,
        "values in the record of ballast factor, ballast-lamp factor and input watts",
        Next::Size(vertical),
    )?;
    let ballast = positive(records, b[0], "ballast factor")?;
    let second = records.number(b[1], "ballast-lamp photometric factor")?;
    let scale = if version <= Lm63Version::V1991 {
        if second <= 0.0 {
            return Err(records.file.invalid(
                b[1].line,
                format!("ballast-lamp photometric factor {second}: must be positive"),
            ));
        }
        multiplier * ballast * second
    } else {
        multiplier * ballast
    };
    Ok(Header {
        lamps,
        lumens_per_lamp,
        absolute,
        scale,
        vertical,
        horizontal,
        opening,
        watts: records.number(b[2], "input watts")?,
        counts_line: r[3].line,
    })
}

fn positive(records: &Records, v: Value, what: &str) -> Result<f64> {
    let x = records.number(v, what)?;
    if x > 0.0 {
        Ok(x)
    } else {
        Err(records
            .file
            .invalid(v.line, format!("{what} {x}: must be positive")))
    }
}

fn read_distribution(records: &mut Records, header: &Header) -> Result<(Symmetry, Distribution)> {
    let (nv, nh) = (header.vertical, header.horizontal);
    let v_values = records.record(nv, "vertical angles", Next::Size(nh))?;
    let h_values = records.record(nh, "horizontal angles", Next::Size(nv))?;
    let gamma = increasing_angles(records, &v_values, "vertical angle", 0.0, 180.0)?;
    let planes = increasing_angles(records, &h_values, "horizontal angle", 0.0, 360.0)?;
    let symmetry = lateral(records, &planes, h_values[nh - 1].line)?;
    let mut candela = Vec::new();
    for (j, &h) in planes.iter().enumerate() {
        let next = if j + 1 < nh {
            Next::Size(nv)
        } else {
            Next::End
        };
        let what = format!("candela values for horizontal angle {h}°");
        let values = records.record(nv, &what, next)?;
        let mut plane = Vec::with_capacity(nv);
        for (v, g) in values.into_iter().zip(&gamma) {
            let x = records.number(v, "candela value")?;
            if x < 0.0 {
                return Err(records.file.invalid(
                    v.line,
                    format!(
                        "candela value {x} at horizontal angle {h}°, vertical angle {g}° is \
                         negative"
                    ),
                ));
            }
            plane.push(x * header.scale);
        }
        candela.push(plane);
    }
    records.finish(header.counts_line)?;
    let distribution = Distribution::new(symmetry, &planes, gamma, candela)
        .map_err(|m| records.file.invalid(h_values[0].line, m))?;
    Ok((symmetry, distribution))
}

/// Angles that must be finite, strictly increasing and within `min..=max` degrees.
fn increasing_angles(
    records: &Records,
    values: &[Value],
    what: &str,
    min: f64,
    max: f64,
) -> Result<Vec<f64>> {
    let mut angles: Vec<f64> = Vec::with_capacity(values.len());
    for (i, &v) in values.iter().enumerate() {
        let a = records.number(v, what)?;
        if !(min..=max).contains(&a) {
            return Err(records.file.invalid(
                v.line,
                format!("{what} {} is {a}°, outside {min}°…{max}°", i + 1),
            ));
        }
        if let Some(&before) = angles.last() {
            if a <= before {
                return Err(records.file.invalid(
                    v.line,
                    format!(
                        "{what} {} is {a}°, not above the one before ({before}°): angles must \
                         increase",
                        i + 1
                    ),
                ));
            }
        }
        angles.push(a);
    }
    Ok(angles)
}

/// The symmetry LM-63's first and last horizontal angles declare.
fn lateral(records: &Records, planes: &[f64], line: usize) -> Result<Symmetry> {
    let near = |a: f64, b: f64| (a - b).abs() < 1e-6;
    let (first, last) = (planes[0], planes[planes.len() - 1]);
    Ok(match planes.len() {
        1 => Symmetry::Rotational,
        _ if near(first, 0.0) && near(last, 90.0) => Symmetry::Quadrant,
        _ if near(first, 0.0) && near(last, 180.0) => Symmetry::AboutC0C180,
        _ if near(first, 90.0) && near(last, 270.0) => Symmetry::AboutC90C270,
        _ if near(first, 0.0) && last > 180.0 => Symmetry::None,
        _ => {
            return Err(records.file.invalid(
                line,
                format!(
                    "horizontal angles {first}°…{last}° match no LM-63 symmetry \
                     (0 alone, 0…90, 0…180, 90…270 or 0…360)"
                ),
            ))
        }
    })
}

/// The luminous opening LM-63's signed dimensions (metres) encode; `None` for a combination
/// of signs no version defines. A negative dimension is a diameter: the opening is round in
/// that direction. LM-63-1995 and earlier write a circle as a negative width and a zero
/// length, and a horizontal cylinder as a negative height with the other round dimension
/// zero; LM-63-1986 an ellipse as one negative horizontal dimension.
fn opening(width: f64, length: f64, height: f64) -> Option<Opening> {
    let (mut w, mut l, h) = (width.abs(), length.abs(), height.abs());
    let round_h = height < 0.0;
    let round_w = width < 0.0;
    // LM-63-1995's circle: the negative width is the diameter, the length zero.
    let round_l = length < 0.0 || (round_w && length == 0.0);
    if round_w && length == 0.0 {
        l = w;
    }
    let shape = match (round_w, round_l, round_h) {
        (false, false, false) if w == 0.0 && l == 0.0 && h == 0.0 => OpeningShape::Point,
        (false, false, false) => OpeningShape::Rectangular,
        (true, _, false) | (_, true, false) => OpeningShape::VerticalCylinder,
        (true, true, true) => OpeningShape::Ellipsoid,
        (true, false, true) => OpeningShape::HorizontalCylinderAlongLength,
        (false, true, true) => OpeningShape::HorizontalCylinderAlongWidth,
        // LM-63-1995's horizontal cylinders: the negative height is the diameter, the
        // horizontal dimension across the axis zero.
        (false, false, true) if w == 0.0 && l > 0.0 => {
            w = h;
            OpeningShape::HorizontalCylinderAlongLength
        }
        (false, false, true) if l == 0.0 && w > 0.0 => {
            l = h;
            OpeningShape::HorizontalCylinderAlongWidth
        }
        (false, false, true) => return None,
    };
    Some(Opening {
        shape,
        length: l,
        width: w,
        height: h,
        side_heights: None,
    })
}
