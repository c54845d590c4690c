//! Sensors: where they are, where they face, and that they can see the room.

use toml::Spanned;

use crate::geometry::Vec3;
use crate::scene::context::{unique, Ctx};
use crate::scene::error::SceneError;
use crate::scene::file::{ResponseDef, SensorDef};
use crate::scene::openings::CONTACT_TOLERANCE;
use crate::scene::response::{self, Response};
use crate::scene::room::Room;
use crate::scene::Sensor;

/// Reads and checks the sensors; `blocks` are (name, min, max) in metres.
pub(crate) fn sensors(
    ctx: &Ctx,
    defs: &[Spanned<SensorDef>],
    rooms: &[Room],
    blocks: &[(String, Vec3, Vec3)],
    extent: Option<(Vec3, Vec3)>,
    enclosures: &[(Vec3, Vec3)],
) -> Result<Vec<Sensor>, SceneError> {
    unique(
        "sensor",
        defs.iter().map(|s| (s.get_ref().name.as_str(), ctx.at(s))),
    )?;
    let mut sensors = Vec::with_capacity(defs.len());
    for def in defs {
        let s = def.get_ref();
        let what = format!("sensor `{}`", s.name);
        let position = ctx.point(&s.position, &format!("{what}.position"))?;
        let n = s.normal.get_ref();
        let normal = Vec3::new(n[0], n[1], n[2]);
        if !(normal.is_finite() && normal.length() > 0.0) {
            return Err(SceneError::Invalid {
                at: ctx.at(&s.normal),
                field: format!("{what}.normal"),
                message: format!("must be a finite, non-zero vector, found {n:?}"),
            });
        }
        let half_angle = match &s.half_angle {
            Some(a) if !(*a.get_ref() > 0.0 && *a.get_ref() <= 90.0) => {
                return Err(SceneError::OutOfRange {
                    at: ctx.at(a),
                    field: format!("{what}.half_angle"),
                    message: format!("must be in (0, 90] degrees, found {}", a.get_ref()),
                })
            }
            Some(a) => Some(a.get_ref().to_radians()),
            None => None,
        };
        let (half_angle, response) = match &s.response {
            None => (half_angle, None),
            Some(r) if s.half_angle.is_some() => {
                return Err(SceneError::Invalid {
                    at: ctx.at(r),
                    field: format!("{what}.response"),
                    message: "give either `half_angle` or `response`, not both (a cone is \
                              `response = { preset = \"cone\", half_angle = ... }`)"
                        .into(),
                })
            }
            Some(r) => response(ctx, r, &format!("{what}.response"))?,
        };
        let normal = normal.normalized();
        placement(ctx, s, &what, position, normal, rooms, blocks, extent)?;
        enclosed(ctx, s, &what, position, enclosures)?;
        sensors.push(Sensor {
            name: s.name.clone(),
            position,
            normal,
            half_angle,
            response,
        });
    }

    Ok(sensors)
}

/// A sensor's `response` (field `field`): `(half_angle, table)`, the cone's half-angle in
/// radians for the cosine and cone presets, the table for the others.
fn response(
    ctx: &Ctx,
    def: &Spanned<ResponseDef>,
    field: &str,
) -> Result<(Option<f64>, Option<Response>), SceneError> {
    let r = def.get_ref();
    let given = [
        r.preset.is_some(),
        r.file.is_some(),
        r.polar.is_some() || r.sensitivity.is_some(),
    ];
    if given.iter().filter(|&&g| g).count() != 1 {
        return Err(SceneError::Invalid {
            at: ctx.at(def),
            field: field.into(),
            message: "give exactly one of `preset`, `file` or `polar` with `sensitivity`".into(),
        });
    }
    let angle = |a: &Spanned<f64>, name: &str, high: f64, closed: bool| {
        let v = *a.get_ref();
        let inside = v > 0.0 && (v < high || closed && v == high);
        if inside {
            Ok(v.to_radians())
        } else {
            Err(SceneError::OutOfRange {
                at: ctx.at(a),
                field: format!("{field}.{name}"),
                message: format!(
                    "must be in (0, {high}{} degrees, found {v}",
                    if closed { "]" } else { ")" }
                ),
            })
        }
    };
    let unused = |what: Option<&Spanned<f64>>, name: &str, preset: &str| match what {
        Some(a) => Err(SceneError::Invalid {
            at: ctx.at(a),
            field: format!("{field}.{name}"),
            message: format!("the `{preset}` preset takes no `{name}`"),
        }),
        None => Ok(()),
    };
    if let Some(preset) = &r.preset {
        return match preset.get_ref().as_str() {
            "cosine" => {
                unused(r.half_angle.as_ref(), "half_angle", "cosine")?;
                unused(r.cutoff.as_ref(), "cutoff", "cosine")?;
                Ok((None, None))
            }
            "cone" => {
                unused(r.cutoff.as_ref(), "cutoff", "cone")?;
                let Some(a) = &r.half_angle else {
                    return Err(SceneError::Invalid {
                        at: ctx.at(preset),
                        field: format!("{field}.half_angle"),
                        message: "the `cone` preset needs `half_angle`, degrees".into(),
                    });
                };
                Ok((Some(angle(a, "half_angle", 90.0, true)?), None))
            }
            "shielded" => {
                unused(r.half_angle.as_ref(), "half_angle", "shielded")?;
                let cutoff = match &r.cutoff {
                    Some(c) => angle(c, "cutoff", 90.0, false)?,
                    None => DEFAULT_CUTOFF.to_radians(),
                };
                Ok((None, Some(Response::shielded(cutoff))))
            }
            other => Err(SceneError::Invalid {
                at: ctx.at(preset),
                field: format!("{field}.preset"),
                message: format!(
                    "unknown preset `{other}`: expected `cosine`, `cone` or `shielded`"
                ),
            }),
        };
    }
    for (a, name) in [(&r.half_angle, "half_angle"), (&r.cutoff, "cutoff")] {
        if let Some(a) = a {
            return Err(SceneError::Invalid {
                at: ctx.at(a),
                field: format!("{field}.{name}"),
                message: format!("`{name}` belongs to a preset; a table gives its own angles"),
            });
        }
    }
    if let Some(file) = &r.file {
        let path = ctx
            .origin
            .parent()
            .unwrap_or(std::path::Path::new(""))
            .join(file.get_ref());
        if !path.exists() {
            return Err(SceneError::MissingFile {
                at: ctx.at(file),
                field: format!("{field}.file"),
                path,
            });
        }
        return response::read_rsensor(&path)
            .map(|t| (None, Some(t)))
            .map_err(|(path, e)| SceneError::Invalid {
                at: super::super::error::Location {
                    file: path,
                    line: e.line,
                },
                field: format!("{field}.file"),
                message: e.message,
            });
    }
    let (Some(polar), Some(sensitivity)) = (&r.polar, &r.sensitivity) else {
        return Err(SceneError::Invalid {
            at: ctx.at(def),
            field: field.into(),
            message: "an inline table needs both `polar` (degrees) and `sensitivity`".into(),
        });
    };
    if polar.get_ref().len() != sensitivity.get_ref().len() {
        return Err(SceneError::BandCount {
            at: ctx.at(sensitivity),
            field: format!("{field}.sensitivity"),
            expected: polar.get_ref().len(),
            found: sensitivity.get_ref().len(),
        });
    }
    let rows: Vec<(f64, f64)> = polar
        .get_ref()
        .iter()
        .copied()
        .zip(sensitivity.get_ref().iter().copied())
        .collect();
    Response::from_rows(&rows, None)
        .map(|t| (None, Some(t)))
        .map_err(|e| SceneError::Invalid {
            at: ctx.at(polar),
            field: format!("{field}.polar"),
            message: e.to_string(),
        })
}

/// Cut-off of the `shielded` preset when the scene gives none, degrees: the shield hides the
/// detector from light more than this far from its normal.
const DEFAULT_CUTOFF: f64 = 60.0;

/// In a scene without rooms, how far a sensor may lie from the box around the faces, in
/// diagonals of that box.
const FAR_OUTSIDE: f64 = 10.0;

/// Face names of a block by axis and side (min, max).
const BLOCK_FACES: [[&str; 2]; 3] = [
    ["side_xmin", "side_xmax"],
    ["side_ymin", "side_ymax"],
    ["bottom", "top"],
];

/// Checks that a sensor (position `p`, metres) of a scene without rooms whose faces close
/// into cavities (`enclosures`, the box around each, metres) lies within one of them: outside
/// them it would see only the backs of faces and read nothing.
fn enclosed(
    ctx: &Ctx,
    s: &SensorDef,
    what: &str,
    p: Vec3,
    enclosures: &[(Vec3, Vec3)],
) -> Result<(), SceneError> {
    let within = |(lo, hi): &(Vec3, Vec3)| {
        let tol = CONTACT_TOLERANCE * (*hi - *lo).length();
        (0..3).all(|k| p.axis(k) >= lo.axis(k) - tol && p.axis(k) <= hi.axis(k) + tol)
    };
    if enclosures.is_empty() || enclosures.iter().any(within) {
        return Ok(());
    }
    let written = |v: Vec3| (v / ctx.unit).to_array();
    Err(SceneError::OutOfRange {
        at: ctx.at(&s.position),
        field: format!("{what}.position"),
        message: format!(
            "{:?} is outside the scene's closed geometry ({}): a sensor there sees only the \
             backs of faces and would read nothing",
            written(p),
            enclosures
                .iter()
                .map(|(lo, hi)| format!("faces enclosing {:?} to {:?}", written(*lo), written(*hi)))
                .collect::<Vec<_>>()
                .join("; ")
        ),
    })
}

/// Checks that a sensor (position in metres, unit normal) can see the room: it is inside a
/// room (when the scene has rooms) or, in a scene without rooms (OBJ geometry, quads), within
/// [`FAR_OUTSIDE`] diagonals of the box around its faces (`extent`); not inside a block, and not lying on a room or block
/// face while facing into it.
#[allow(clippy::too_many_arguments)]
fn placement(
    ctx: &Ctx,
    s: &SensorDef,
    what: &str,
    p: Vec3,
    n: Vec3,
    rooms: &[Room],
    blocks: &[(String, Vec3, Vec3)],
    extent: Option<(Vec3, Vec3)>,
) -> Result<(), SceneError> {
    let written = |v: Vec3| (v / ctx.unit).to_array();
    let position_error = |message: String| SceneError::OutOfRange {
        at: ctx.at(&s.position),
        field: format!("{what}.position"),
        message,
    };
    let facing_error = |face: String| SceneError::Invalid {
        at: ctx.at(&s.normal),
        field: format!("{what}.normal"),
        message: format!(
            "the sensor at {:?} lies on `{face}` and faces into it (normal {:?}): it would see \
             nothing; turn its normal away from that face or move it off the face",
            written(p),
            n.to_array()
        ),
    };
    if let (true, Some((lo, hi))) = (rooms.is_empty(), extent) {
        // Distance from the box around the faces; a sensor may look at a panel from a few of
        // its sizes away, but not from many: that is a unit or `translate` slip.
        let outside = Vec3::new(
            (lo.x - p.x).max(p.x - hi.x).max(0.0),
            (lo.y - p.y).max(p.y - hi.y).max(0.0),
            (lo.z - p.z).max(p.z - hi.z).max(0.0),
        )
        .length();
        let diagonal = (hi - lo).length();
        if outside > FAR_OUTSIDE * diagonal {
            return Err(position_error(format!(
                "{:?} is {:.3e} m from the scene, whose faces span {:?} to {:?}: more than \
                 {FAR_OUTSIDE} times the scene's size (a unit or `translate` mistake?)",
                written(p),
                outside,
                written(lo),
                written(hi)
            )));
        }
    }
    if !rooms.is_empty() {
        // Inside the room's own shape (its plan), not only its bounding box.
        let Some(room) = rooms.iter().find(|r| r.contains(p)) else {
            return Err(position_error(format!(
                "{:?} is outside every room ({}); a sensor there would see nothing of the scene",
                written(p),
                rooms
                    .iter()
                    .map(|r| r.describe(ctx.unit))
                    .collect::<Vec<_>>()
                    .join("; ")
            )));
        };
        // Room faces look into the room: a sensor on one facing against its normal sees
        // nothing.
        if let Some(face) = room
            .faces
            .iter()
            .find(|f| room.on_face(f, p) && n.dot(room.inward(f)) < 0.0)
        {
            return Err(facing_error(format!("{}.{}", room.name, face.suffix)));
        }
    }
    for (name, lo, hi) in blocks {
        let tol = CONTACT_TOLERANCE * (*hi - *lo).length();
        let strictly = (0..3).all(|k| p.axis(k) > lo.axis(k) + tol && p.axis(k) < hi.axis(k) - tol);
        if strictly {
            return Err(position_error(format!(
                "{:?} is inside block `{name}` (from {:?} to {:?}): a sensor there would see \
                 nothing",
                written(p),
                written(*lo),
                written(*hi)
            )));
        }
        for k in 0..3 {
            let on_face_extent = (0..3)
                .filter(|&j| j != k)
                .all(|j| p.axis(j) >= lo.axis(j) - tol && p.axis(j) <= hi.axis(j) + tol);
            // Block faces look out of the block: −axis at the min side, +axis at the max side.
            for (side, plane, outward) in [(0, lo.axis(k), -1.0), (1, hi.axis(k), 1.0)] {
                if on_face_extent && (p.axis(k) - plane).abs() <= tol && n.axis(k) * outward < 0.0 {
                    return Err(facing_error(format!("{name}.{}", BLOCK_FACES[k][side])));
                }
            }
        }
    }
    Ok(())
}
