//! The candela table: vertical and horizontal angles, the symmetry they declare and one
//! record of candela values per horizontal angle.

use super::header::Header;
use super::records::{increasing_angles, Next, Records};
use super::Result;
use crate::scene::photometry::{Distribution, Symmetry};

pub(super) fn read_distribution(
    records: &mut Records,
    header: &Header,
) -> Result<(Symmetry, Distribution)> {
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
