//! The two header records: lamps, lumens, candela multiplier, angle counts, photometric type,
//! units and luminous opening; ballast factor, ballast-lamp factor and input watts.

use super::records::{Next, Records, Value};
use super::Result;
use crate::scene::photometry::{Lm63Version, Opening, OpeningShape};

/// Feet to metres.
const FOOT: f64 = 0.3048;

/// What the two header records say.
pub(super) struct Header {
    pub(super) lamps: u32,
    pub(super) lumens_per_lamp: f64,
    pub(super) absolute: bool,
    /// Candela multiplier × ballast factor (× ballast-lamp factor in 1986 and 1991).
    pub(super) scale: f64,
    pub(super) vertical: usize,
    pub(super) horizontal: usize,
    pub(super) opening: Opening,
    pub(super) watts: f64,
    /// The line of the counts, for messages about data that does not match them.
    pub(super) counts_line: usize,
}

pub(super) fn read_header(records: &mut Records, version: Lm63Version) -> Result<Header> {
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
