//! `[[luminaire]]` entries: photometry read from their files, placed, oriented and copied into
//! arrays, each element in its channel.

use std::collections::BTreeMap;
use std::path::PathBuf;
use std::sync::Arc;

use toml::Spanned;

use super::context::{unique, Ctx};
use super::error::SceneError;
use super::file::{ChannelDef, LuminaireDef};
use super::openings::CONTACT_TOLERANCE;
use super::room::Room;
use super::Luminaire;
use crate::geometry::Vec3;
use crate::scene::photometry::{self, Photometry, PhotometryError};

/// Checks that every luminaire's photometric centre is in a room (when the scene has rooms)
/// and not inside one of the `blocks` (name, min, max in metres): its light would otherwise
/// leave the scene or fall inside an obstacle, and show only as flux that never arrives.
pub(crate) fn check_placement(
    ctx: &Ctx,
    defs: &[Spanned<LuminaireDef>],
    luminaires: &[Luminaire],
    rooms: &[Room],
    blocks: &[(String, Vec3, Vec3)],
) -> Result<(), SceneError> {
    for l in luminaires {
        // An array's elements are `name[row,column]`.
        let Some(def) = defs.iter().find(|d| {
            let name = &d.get_ref().name;
            l.name == *name || l.name.starts_with(&format!("{name}["))
        }) else {
            continue;
        };
        let p = l.position;
        let written = (p / ctx.unit).to_array();
        let error = |message: String| SceneError::OutOfRange {
            at: ctx.at(&def.get_ref().position),
            field: format!("luminaire `{}`.position", l.name),
            message,
        };
        if !rooms.is_empty() && !rooms.iter().any(|r| r.contains(p)) {
            return Err(error(format!(
                "{written:?} is outside every room ({}): its light would leave the scene",
                rooms
                    .iter()
                    .map(|r| r.describe(ctx.unit))
                    .collect::<Vec<_>>()
                    .join("; ")
            )));
        }
        for (name, lo, hi) in blocks {
            let tol = CONTACT_TOLERANCE * (*hi - *lo).length();
            if (0..3).all(|k| p.axis(k) > lo.axis(k) + tol && p.axis(k) < hi.axis(k) - tol) {
                let room = rooms
                    .iter()
                    .find(|r| r.contains(p))
                    .map_or(String::new(), |r| format!(" in room `{}`", r.name));
                return Err(error(format!(
                    "{written:?} is inside block `{name}`{room} (from {:?} to {:?}): its light \
                     would stay inside the block",
                    (*lo / ctx.unit).to_array(),
                    (*hi / ctx.unit).to_array()
                )));
            }
        }
    }
    Ok(())
}

/// The luminaires of the file, element by element, with the channel each belongs to (an index
/// into `channels`, the `[[channel]]` entries in file order). Only photopic scenes (one band)
/// take luminaires: photometry is in candela and says nothing of the spectrum.
pub(crate) fn place(
    ctx: &Ctx,
    defs: &[Spanned<LuminaireDef>],
    channels: &[Spanned<ChannelDef>],
) -> Result<Vec<Luminaire>, SceneError> {
    let mut read: BTreeMap<PathBuf, Arc<Photometry>> = BTreeMap::new();
    let mut placed = Vec::new();
    let mut names = Vec::new();
    for def in defs {
        let l = def.get_ref();
        let what = format!("luminaire `{}`", l.name);
        if ctx.bands != 1 {
            return Err(SceneError::Invalid {
                at: ctx.at(def),
                field: what,
                message: "luminaires need a photopic scene (`bands = \"photopic\"`): photometry \
                          is in candela and does not give the light's colour"
                    .into(),
            });
        }
        let channel = channels
            .iter()
            .position(|c| &c.get_ref().name == l.channel.get_ref())
            .ok_or_else(|| SceneError::Unknown {
                at: ctx.at(&l.channel),
                field: format!("{what}.channel"),
                kind: "channel",
                name: l.channel.get_ref().clone(),
            })?;
        let file = ctx
            .origin
            .parent()
            .unwrap_or(std::path::Path::new(""))
            .join(l.file.get_ref());
        let photometry = match read.get(&file) {
            Some(p) => p.clone(),
            None => {
                let p = Arc::new(load(ctx, &l.file, &file, &what)?);
                read.insert(file.clone(), p.clone());
                p
            }
        };
        let position = ctx.point(&l.position, &format!("{what}.position"))?;
        let (nadir, c0, c90) = frame_of(ctx, l, &what)?;
        let maintenance_factor = maintenance(ctx, l, &what)?;
        // The array's elements share the entry's orientation, and so its tilt.
        let tilt_factor = photometry.tilt_factor(nadir, c0, c90);
        for (name, offset) in elements(ctx, l, &what)? {
            names.push((name.clone(), ctx.at(def)));
            placed.push(Luminaire {
                name,
                file: file.clone(),
                photometry: photometry.clone(),
                position: position + offset,
                nadir,
                c0,
                c90,
                channel,
                maintenance_factor,
                tilt_factor,
            });
        }
    }
    unique(
        "luminaire",
        names.iter().map(|(n, at)| (n.as_str(), at.clone())),
    )?;
    Ok(placed)
}

/// Reads a photometric file; a missing file is named as such, any other error keeps the
/// reader's own file and line.
fn load(
    ctx: &Ctx,
    written: &Spanned<String>,
    file: &std::path::Path,
    what: &str,
) -> Result<Photometry, SceneError> {
    photometry::read(file).map_err(|reason| match reason {
        PhotometryError::Read { reason: e, .. } if e.kind() == std::io::ErrorKind::NotFound => {
            SceneError::MissingFile {
                at: ctx.at(written),
                field: format!("{what}.file"),
                path: file.to_path_buf(),
            }
        }
        reason => SceneError::Photometry {
            at: ctx.at(written),
            field: format!("{what}.file"),
            // Boxed: the reader's error is large, and every scene result carries the variant.
            reason: Box::new(reason),
        },
    })
}

/// The luminaire's frame `(nadir, c0, c90)` from its `aim` and `spin` (degrees).
fn frame_of(ctx: &Ctx, l: &LuminaireDef, what: &str) -> Result<(Vec3, Vec3, Vec3), SceneError> {
    let aim = match &l.aim {
        Some(a) => {
            let v = Vec3::new(a.get_ref()[0], a.get_ref()[1], a.get_ref()[2]);
            if !(v.is_finite() && v.length() > 0.0) {
                return Err(SceneError::Invalid {
                    at: ctx.at(a),
                    field: format!("{what}.aim"),
                    message: format!(
                        "must be a finite, non-zero vector, found {:?}",
                        a.get_ref().0
                    ),
                });
            }
            v
        }
        None => Vec3::new(0.0, 0.0, -1.0),
    };
    let spin = match &l.spin {
        Some(s) if !s.get_ref().is_finite() => {
            return Err(SceneError::OutOfRange {
                at: ctx.at(s),
                field: format!("{what}.spin"),
                message: format!("must be a finite angle in degrees, found {}", s.get_ref()),
            })
        }
        Some(s) => s.get_ref().to_radians(),
        None => 0.0,
    };
    Ok(frame(aim, spin))
}

/// The frame of a luminaire aimed along `aim` (any non-zero length) and spun by `spin`
/// (radians): the luminaire hanging straight down with C0 along +x (C90 along +y) is turned by
/// the smallest rotation taking −z to `aim` (about the horizontal axis `−z × aim`; for `aim`
/// straight up, half a turn about x), then its C0 is turned by `spin` about the axis opposite
/// to the nadir (counter-clockwise seen from behind the luminaire).
pub(crate) fn frame(aim: Vec3, spin: f64) -> (Vec3, Vec3, Vec3) {
    let nadir = aim.normalized();
    let down = Vec3::new(0.0, 0.0, -1.0);
    let x = Vec3::new(1.0, 0.0, 0.0);
    let cos = down.dot(nadir);
    let c0_unspun = if cos < -1.0 + 1e-12 {
        // Straight up: any half turn about a horizontal axis would do; x keeps C0 along +x.
        x
    } else {
        // Rodrigues with k = down × nadir (|k| = sin): v cos + k × v + k (k · v)/(1 + cos).
        let k = down.cross(nadir);
        x * cos + k.cross(x) + k * (k.dot(x) / (1.0 + cos))
    };
    let up = -nadir;
    // Remove what rounding left along the nadir before spinning.
    let c0_unspun = (c0_unspun - nadir * c0_unspun.dot(nadir)).normalized();
    let c0 = c0_unspun * spin.cos() + up.cross(c0_unspun) * spin.sin();
    let c90 = up.cross(c0);
    (nadir, c0, c90)
}

/// The light-loss factor, 1 unless written; it must be in (0, 1].
fn maintenance(ctx: &Ctx, l: &LuminaireDef, what: &str) -> Result<f64, SceneError> {
    match &l.maintenance_factor {
        Some(m) if !(*m.get_ref() > 0.0 && *m.get_ref() <= 1.0) => Err(SceneError::OutOfRange {
            at: ctx.at(m),
            field: format!("{what}.maintenance_factor"),
            message: format!("must be in (0, 1], found {}", m.get_ref()),
        }),
        Some(m) => Ok(*m.get_ref()),
        None => Ok(1.0),
    }
}

/// Each element's name and offset from `position` (m): the entry alone, or its array's
/// `rows × columns` copies, columns along +x and rows along +y of the scene.
fn elements(ctx: &Ctx, l: &LuminaireDef, what: &str) -> Result<Vec<(String, Vec3)>, SceneError> {
    let Some(array) = &l.array else {
        return Ok(vec![(l.name.clone(), Vec3::ZERO)]);
    };
    let a = array.get_ref();
    let field = format!("{what}.array");
    let bad = |message: String| SceneError::OutOfRange {
        at: ctx.at(array),
        field: field.clone(),
        message,
    };
    if a.rows == 0 || a.columns == 0 {
        return Err(bad(format!(
            "rows and columns must be at least 1, found {} × {}",
            a.rows, a.columns
        )));
    }
    if a.rows.saturating_mul(a.columns) > MAX_ARRAY {
        return Err(bad(format!(
            "{} × {} luminaires: at most {MAX_ARRAY} per entry",
            a.rows, a.columns
        )));
    }
    let &[dx, dy] = a.spacing.as_slice() else {
        return Err(bad(format!(
            "spacing must be two lengths [dx, dy], found {} numbers",
            a.spacing.len()
        )));
    };
    if !(dx.is_finite() && dy.is_finite() && dx > 0.0 && dy > 0.0) {
        return Err(bad(format!(
            "spacing must be two positive finite lengths, found [{dx}, {dy}]"
        )));
    }
    let mut out = Vec::with_capacity(a.rows * a.columns);
    for r in 0..a.rows {
        for c in 0..a.columns {
            let offset = Vec3::new(c as f64 * dx, r as f64 * dy, 0.0) * ctx.unit;
            out.push((format!("{}[{},{}]", l.name, r + 1, c + 1), offset));
        }
    }
    Ok(out)
}

/// Most elements of one array: far more than any room holds, few enough that a typo in
/// `rows` cannot ask for millions of luminaires.
const MAX_ARRAY: usize = 10_000;

#[cfg(test)]
mod tests {
    use super::frame;
    use crate::geometry::Vec3;

    fn close(a: Vec3, b: Vec3) -> bool {
        (a - b).length() < 1e-12
    }

    #[test]
    fn frame_down_up_and_sideways() {
        let (x, y, z) = (
            Vec3::new(1.0, 0.0, 0.0),
            Vec3::new(0.0, 1.0, 0.0),
            Vec3::new(0.0, 0.0, 1.0),
        );
        let (n, c0, c90) = frame(-z, 0.0);
        assert!(close(n, -z) && close(c0, x) && close(c90, y));
        // Spin 90°: C0 turns counter-clockwise seen from above, onto +y.
        let (_, c0, c90) = frame(-z * 2.0, 90f64.to_radians());
        assert!(close(c0, y) && close(c90, -x), "{c0:?} {c90:?}");
        // Straight up: turned over about x.
        let (n, c0, c90) = frame(z, 0.0);
        assert!(close(n, z) && close(c0, x) && close(c90, -y));
        // Aimed at +x: tilted about y; C0 points up, C90 stays +y.
        let (n, c0, c90) = frame(x, 0.0);
        assert!(
            close(n, x) && close(c0, z) && close(c90, y),
            "{c0:?} {c90:?}"
        );
        // Tilted 45° towards +x: C90 stays along the tilt axis.
        let (n, c0, c90) = frame(Vec3::new(1.0, 0.0, -1.0), 0.0);
        let s = 0.5f64.sqrt();
        assert!(close(n, Vec3::new(s, 0.0, -s)) && close(c0, Vec3::new(s, 0.0, s)));
        assert!(close(c90, y));
        // Always orthonormal and right-handed seen from behind.
        for aim in [Vec3::new(0.3, -0.7, 0.2), Vec3::new(-1.0, 2.0, -0.1)] {
            let (n, c0, c90) = frame(aim, 0.7);
            assert!(n.dot(c0).abs() < 1e-12 && n.dot(c90).abs() < 1e-12);
            assert!((c0.length() - 1.0).abs() < 1e-12 && close((-n).cross(c0), c90));
        }
    }
}
