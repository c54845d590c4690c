//! EULUMDAT files (`.ldt`): one field a line, at fixed positions.
//!
//! Lines 1–25: company; type indicator `Ityp`; symmetry indicator `Isym` (0–4); number `Mc`
//! and spacing of the C-planes; number `Ng` and spacing of the γ angles; report number;
//! luminaire name; luminaire number; file name; date/user; luminaire length (or diameter),
//! width (0: round) and height, mm; luminous area length (or diameter), width (0: round), mm,
//! and its heights seen in the C0, C90, C180 and C270 planes, mm; downward flux fraction DFF,
//! %; light output ratio LORL, %; conversion factor for the intensities; tilt during
//! measurement, degrees. Line 26: the number `n` of lamp sets, then six groups of `n` lines
//! (number of lamps, negative for absolute photometry; lamp type; total lamp flux, lm; colour;
//! colour rendering; wattage, W). Then 10 direct ratios, the `Mc` C angles, the `Ng` γ
//! angles, and the intensities in cd/klm, plane after plane, for the planes `Isym` stores:
//! all (0), the first (1), C0…C180 (2), C270…C360 and C0…C90 (3), C0…C90 (4).
//!
//! The intensities are scaled to candela by the first lamp set's total flux / 1000 (the
//! flux of all its lamps: the format calls it "total luminous flux of lamps") and the
//! conversion factor; further lamp sets are alternatives and are not used. A decimal comma
//! ("12,5") is read as a decimal point, as European writers of the format produce it.

use std::path::Path;

use super::text::{decode, lines, File};
use super::{
    Distribution, Format, Identity, Opening, OpeningShape, Photometry, PhotometryError, Symmetry,
};

type Result<T> = std::result::Result<T, PhotometryError>;

/// Reads an EULUMDAT file's bytes; `path` names the file in errors.
pub fn parse(path: &Path, bytes: &[u8]) -> Result<Photometry> {
    let text = decode(bytes);
    let mut lines = Lines {
        file: File::new(path),
        lines: lines(&text).collect(),
        next: 0,
    };
    let header = read_header(&mut lines)?;
    let lamps = read_lamps(&mut lines)?;
    let (symmetry, distribution) = read_distribution(&mut lines, &header, &lamps)?;
    let mut identity = header.identity;
    identity.lamp = Some(lamps.lamp_type.clone()).filter(|t| !t.is_empty());
    identity.keywords.extend(lamps.keywords);
    Ok(Photometry {
        format: Format::Eulumdat,
        identity,
        symmetry,
        opening: header.opening,
        luminaire: Some(header.luminaire),
        lamps: lamps.count,
        absolute: lamps.absolute,
        lamp_flux: Some(lamps.flux),
        luminaire_flux: Some(lamps.flux * header.lorl / 100.0),
        downward_fraction: Some(header.dff / 100.0),
        input_watts: Some(lamps.watts),
        tilt: None,
        distribution,
    })
}

/// The file's lines, read one field at a time.
struct Lines<'a> {
    file: File<'a>,
    lines: Vec<(usize, &'a str)>,
    next: usize,
}

impl<'a> Lines<'a> {
    fn line(&mut self, what: &str) -> Result<(usize, &'a str)> {
        let Some(&line) = self.lines.get(self.next) else {
            let last = self.lines.last().map_or(1, |l| l.0);
            return Err(self
                .file
                .invalid(last, format!("the file ends before the {what}")));
        };
        self.next += 1;
        Ok(line)
    }

    fn text(&mut self, what: &str) -> Result<String> {
        Ok(self.line(what)?.1.trim().to_string())
    }

    fn number(&mut self, what: &str) -> Result<(usize, f64)> {
        let (n, line) = self.line(what)?;
        let text = line.trim();
        // A decimal comma, when it is the only separator.
        let text = if text.contains(',') && !text.contains('.') {
            text.replacen(',', ".", 1)
        } else {
            text.to_string()
        };
        Ok((n, self.file.number(n, &text, || what.to_string())?))
    }

    fn non_negative(&mut self, what: &str) -> Result<f64> {
        let (n, x) = self.number(what)?;
        if x < 0.0 {
            return Err(self.file.invalid(n, format!("{what} {x} is negative")));
        }
        Ok(x)
    }

    fn integer(&mut self, what: &str, min: i64, max: i64) -> Result<(usize, i64)> {
        let (n, line) = self.line(what)?;
        let value = self
            .file
            .integer(n, line.trim(), min, max, || what.to_string())?;
        Ok((n, value))
    }

    /// `count` numbers, one a line; `what` names them in the plural.
    fn numbers(&mut self, count: usize, what: &str) -> Result<Vec<(usize, f64)>> {
        let left = self.lines.len() - self.next;
        if left < count {
            let last = self.lines.last().map_or(1, |l| l.0);
            return Err(self.file.count(last, what, count, left));
        }
        (0..count)
            .map(|i| self.number(&format!("{} {}", singular(what), i + 1)))
            .collect()
    }
}

fn singular(what: &str) -> &str {
    what.strip_suffix('s').unwrap_or(what)
}

/// Lines 1 to 25.
struct Header {
    identity: Identity,
    symmetry: (usize, i64),
    planes: (usize, usize),
    gammas: usize,
    luminaire: Opening,
    opening: Opening,
    dff: f64,
    lorl: f64,
    conversion: f64,
}

fn read_header(lines: &mut Lines) -> Result<Header> {
    let company = lines.text("company identification")?;
    lines.integer("type indicator Ityp", 0, 3)?;
    let symmetry = lines.integer("symmetry indicator Isym (0 to 4)", 0, 4)?;
    let (mc_line, mc) = lines.integer("number Mc of C-planes", 1, i64::from(u32::MAX))?;
    // Isym 2 stores half the planes, 3 and 4 a quarter plus a half or one more.
    let divisor = match symmetry.1 {
        2 => 2,
        3 | 4 => 4,
        _ => 1,
    };
    if !(mc as u64).is_multiple_of(divisor) {
        return Err(lines.file.invalid(
            mc_line,
            format!(
                "Isym {} (line {}) needs Mc divisible by {divisor}, found {mc}",
                symmetry.1, symmetry.0
            ),
        ));
    }
    lines.number("distance Dc between C-planes")?;
    let (_, ng) = lines.integer("number Ng of γ angles", 2, i64::from(u32::MAX))?;
    lines.number("distance Dg between γ angles")?;
    let mut keywords = Vec::new();
    for what in [
        "measurement report number",
        "luminaire name",
        "luminaire number",
        "file name",
        "date/user",
    ] {
        keywords.push((what.to_string(), lines.text(what)?));
    }
    let mm = |x: f64| x / 1000.0;
    let body = [
        lines.non_negative("luminaire length")?,
        lines.non_negative("luminaire width")?,
        lines.non_negative("luminaire height")?,
    ];
    let area = [
        lines.non_negative("luminous area length")?,
        lines.non_negative("luminous area width")?,
    ];
    let mut heights = [0.0; 4];
    for (h, plane) in heights.iter_mut().zip(["C0", "C90", "C180", "C270"]) {
        *h = mm(lines.non_negative(&format!("luminous area height in the {plane} plane"))?);
    }
    let (dff_line, dff) = lines.number("downward flux fraction DFF")?;
    if !(0.0..=100.0).contains(&dff) {
        return Err(lines
            .file
            .invalid(dff_line, format!("DFF {dff}% is outside 0…100%")));
    }
    let lorl = lines.non_negative("light output ratio LORL")?;
    let (cf_line, conversion) = lines.number("conversion factor for luminous intensities")?;
    if conversion <= 0.0 {
        return Err(lines.file.invalid(
            cf_line,
            format!("conversion factor for luminous intensities {conversion}: must be positive"),
        ));
    }
    let tilt = lines.text("tilt during measurement")?;
    keywords.push(("tilt during measurement".into(), tilt));
    let text = |k: usize| Some(keywords[k].1.clone()).filter(|v| !v.is_empty());
    let identity = Identity {
        manufacturer: Some(company.clone()).filter(|v| !v.is_empty()),
        catalogue: text(2),
        luminaire: text(1),
        lamp: None,
        test: text(0),
        keywords: std::iter::once(("company".to_string(), company))
            .chain(keywords.iter().cloned())
            .collect(),
    };
    Ok(Header {
        identity,
        symmetry,
        planes: (mc_line, mc as usize),
        gammas: ng as usize,
        luminaire: size(mm(body[0]), mm(body[1]), mm(body[2]), None),
        opening: size(mm(area[0]), mm(area[1]), 0.0, Some(heights)),
        dff,
        lorl,
        conversion,
    })
}

/// A luminaire or luminous area: round when its width is zero, a point when it has no size.
fn size(length: f64, width: f64, height: f64, sides: Option<[f64; 4]>) -> Opening {
    let height = sides.map_or(height, |s| s.iter().copied().fold(height, f64::max));
    let (shape, width) = if length == 0.0 && width == 0.0 && height == 0.0 {
        (OpeningShape::Point, 0.0)
    } else if width == 0.0 {
        (OpeningShape::VerticalCylinder, length)
    } else {
        (OpeningShape::Rectangular, width)
    };
    Opening {
        shape,
        length,
        width,
        height,
        side_heights: sides,
    }
}

/// The first lamp set, which the intensities are relative to.
struct Lamps {
    count: u32,
    absolute: bool,
    lamp_type: String,
    flux: f64,
    watts: f64,
    keywords: Vec<(String, String)>,
}

fn read_lamps(lines: &mut Lines) -> Result<Lamps> {
    let (_, sets) = lines.integer("number n of lamp sets", 1, i64::from(u32::MAX))?;
    let sets = sets as usize;
    // Six groups of `sets` lines; the first line of each group is the first set's.
    let (count_line, count) =
        lines.integer("number of lamps", -i64::from(u32::MAX), i64::from(u32::MAX))?;
    if count == 0 {
        return Err(lines
            .file
            .invalid(count_line, "number of lamps of the first lamp set is 0"));
    }
    skip(lines, sets - 1, "numbers of lamps")?;
    let lamp_type = lines.text("lamp type")?;
    skip(lines, sets - 1, "lamp types")?;
    let (flux_line, flux) = lines.number("total luminous flux of the lamps")?;
    if flux <= 0.0 {
        return Err(lines.file.invalid(
            flux_line,
            format!("total luminous flux of the lamps {flux} lm: must be positive"),
        ));
    }
    skip(lines, sets - 1, "lamp fluxes")?;
    let colour = lines.text("colour appearance")?;
    skip(lines, sets - 1, "colour appearances")?;
    let rendering = lines.text("colour rendering")?;
    skip(lines, sets - 1, "colour renderings")?;
    let watts = lines.non_negative("wattage including ballast")?;
    skip(lines, sets - 1, "wattages")?;
    for k in 0..10 {
        lines.number(&format!("direct ratio {}", k + 1))?;
    }
    Ok(Lamps {
        count: count.unsigned_abs() as u32,
        absolute: count < 0,
        lamp_type,
        flux,
        watts,
        keywords: vec![
            ("colour appearance".into(), colour),
            ("colour rendering".into(), rendering),
        ],
    })
}

/// Lines of further lamp sets, which this reader does not use.
fn skip(lines: &mut Lines, count: usize, what: &str) -> Result<()> {
    for _ in 0..count {
        lines.line(what)?;
    }
    Ok(())
}

fn read_distribution(
    lines: &mut Lines,
    header: &Header,
    lamps: &Lamps,
) -> Result<(Symmetry, Distribution)> {
    let (mc_line, mc) = header.planes;
    let c = lines.numbers(mc, "C angles")?;
    let g = lines.numbers(header.gammas, "γ angles")?;
    let c_angles = increasing(lines, &c, "C angle", 0.0, 360.0 - 1e-9)?;
    let gamma = increasing(lines, &g, "γ angle", 0.0, 180.0)?;
    let (symmetry, stored) = stored_planes(lines, header.symmetry, &c, &c_angles)?;
    let count = stored.len().saturating_mul(gamma.len());
    let values = lines.numbers(count, "luminous intensities")?;
    let scale = header.conversion * lamps.flux / 1000.0;
    let mut candela = Vec::with_capacity(stored.len());
    for (plane, &at) in values.chunks(gamma.len()).zip(&stored) {
        let mut row = Vec::with_capacity(gamma.len());
        for (&(line, v), g) in plane.iter().zip(&gamma) {
            if v < 0.0 {
                return Err(lines.file.invalid(
                    line,
                    format!("luminous intensity {v} cd/klm at C {at}°, γ {g}° is negative"),
                ));
            }
            row.push(v * scale);
        }
        candela.push(row);
    }
    let rest: Vec<_> = lines.lines[lines.next..]
        .iter()
        .filter(|(_, l)| !l.trim().is_empty())
        .collect();
    if let Some((line, _)) = rest.first() {
        return Err(lines.file.invalid(
            *line,
            format!(
                "{} lines follow the last luminous intensity: Mc, Ng (lines 4 and 6) and \
                 Isym (line 3) do not match the data",
                rest.len()
            ),
        ));
    }
    let first = values.first().map_or(mc_line, |v| v.0);
    let distribution = Distribution::new(symmetry, &stored, gamma, candela)
        .map_err(|m| lines.file.invalid(first, m))?;
    Ok((symmetry, distribution))
}

/// Angles that must be strictly increasing within `min..=max` degrees.
fn increasing(
    lines: &Lines,
    values: &[(usize, f64)],
    what: &str,
    min: f64,
    max: f64,
) -> Result<Vec<f64>> {
    for (i, &(line, a)) in values.iter().enumerate() {
        if !(min..=max).contains(&a) {
            let message = format!("{what} {} is {a}°, outside {min}°…{max:.0}°", i + 1);
            return Err(lines.file.invalid(line, message));
        }
        if i > 0 && a <= values[i - 1].1 {
            let message = format!(
                "{what} {} is {a}°, not above the one before ({}°): angles must increase",
                i + 1,
                values[i - 1].1
            );
            return Err(lines.file.invalid(line, message));
        }
    }
    Ok(values.iter().map(|v| v.1).collect())
}

/// The C angles of the planes `Isym` stores, in file order (`Isym` 3's C270…C360 as −90…0).
fn stored_planes(
    lines: &Lines,
    (isym_line, isym): (usize, i64),
    c: &[(usize, f64)],
    angles: &[f64],
) -> Result<(Symmetry, Vec<f64>)> {
    let mc = angles.len();
    let near = |a: f64, b: f64| (a - b).abs() < 1e-6;
    // Each symmetry stores the planes from index `from`, `count` of them (wrapping past Mc),
    // and needs the given angles at the given indices.
    let (symmetry, from, count, needs): (_, _, _, &[(usize, f64)]) = match isym {
        0 => (Symmetry::None, 0, mc, &[]),
        1 => (Symmetry::Rotational, 0, 1, &[]),
        2 => (
            Symmetry::AboutC0C180,
            0,
            mc / 2 + 1,
            &[(0, 0.0), (mc / 2, 180.0)],
        ),
        3 => (
            Symmetry::AboutC90C270,
            3 * mc / 4,
            mc / 2 + 1,
            &[(3 * mc / 4, 270.0), (mc / 4, 90.0)],
        ),
        _ => (
            Symmetry::Quadrant,
            0,
            mc / 4 + 1,
            &[(0, 0.0), (mc / 4, 90.0)],
        ),
    };
    for &(index, angle) in needs {
        if !near(angles[index], angle) {
            return Err(lines.file.invalid(
                c[index].0,
                format!(
                    "Isym {isym} (line {isym_line}) needs C angle {} to be {angle}°, found {}°",
                    index + 1,
                    angles[index]
                ),
            ));
        }
    }
    let planes = (from..from + count)
        .map(|k| {
            let a = angles[k % mc];
            if k < mc && a > 180.0 && isym == 3 {
                a - 360.0
            } else {
                a
            }
        })
        .collect();
    Ok((symmetry, planes))
}
