//! Tilt tables: the four records after `TILT=INCLUDE`, or a file of their own (`TILT=<file>`).

use std::path::Path;

use super::records::{increasing_angles, Next, Records};
use super::Result;
use crate::scene::photometry::text::{decode, lines, File};
use crate::scene::photometry::{LampGeometry, Tilt};

/// A tilt table in a file of its own (`TILT=<name>` on line `tilt_line` of `ies`): `name`
/// relative to the folder of the `.ies` file, holding the table's four records and nothing
/// else. A file that cannot be read is an error at the `TILT=` line; a fault inside it names
/// that file and its line.
pub(super) fn read_tilt_file(ies: &File, tilt_line: usize, name: &str) -> Result<Tilt> {
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
pub(super) fn read_tilt(records: &mut Records, after: Next) -> Result<Tilt> {
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
