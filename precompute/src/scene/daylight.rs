//! Daylight in the scene file: the `[site]`, glazed materials (their surfaces are windows) and
//! exterior surfaces (obstructions outside the room that shade the windows). The light
//! transport through the windows is `sources::daylight`'s; here the scene only says where the
//! room is, which surfaces let daylight in and what stands outside.

use std::collections::BTreeMap;

use toml::Spanned;

use eigenrad_runtime::sky::glazing::{Glazing, MAX_PANES};

use super::context::{Ctx, MaterialInfo, RawSurface};
use super::error::{Location, SceneError};
use super::file::{GlazingDef, MaterialDef, SceneFile, SiteDef};
use super::mesh::{check_face, triangulate};
use super::openings::CONTACT_TOLERANCE;
use super::room::Room;
use super::{Obstruction, Site, Window};
use crate::daylight::sun;
use crate::geometry::{Face, Polygon, Vec3};

/// Ground reflectance when `[site]` gives none: the usual value for grass and pavement
/// (CIE 110-1994, the daylight-factor convention).
const GROUND_REFLECTANCE: f64 = 0.2;

/// Panes of a glazed material that does not say.
pub(crate) const PANES: u8 = 2;

/// The latest UTC offset in use anywhere, seconds east (+14:00, Line Islands).
const MOST_EAST: i32 = 14 * 3600;

/// The earliest UTC offset in use anywhere, seconds east (−12:00).
const MOST_WEST: i32 = -12 * 3600;

/// The `[site]`, checked; `None` without one.
pub(crate) fn site(ctx: &Ctx, def: Option<&Spanned<SiteDef>>) -> Result<Option<Site>, SceneError> {
    let Some(def) = def else {
        return Ok(None);
    };
    let s = def.get_ref();
    let range = |v: &Spanned<f64>, field: &str, lo: f64, hi: f64, what: &str| {
        let x = *v.get_ref();
        if x.is_finite() && (lo..=hi).contains(&x) {
            Ok(x)
        } else {
            Err(SceneError::OutOfRange {
                at: ctx.at(v),
                field: format!("site.{field}"),
                message: format!("must be {what} from {lo} to {hi}, found {x}"),
            })
        }
    };
    let latitude = range(&s.latitude, "latitude", -90.0, 90.0, "degrees north")?;
    let longitude = range(&s.longitude, "longitude", -180.0, 180.0, "degrees east")?;
    let elevation = match &s.elevation {
        // The sun's position is computed for the range `daylight::sun::check_site` allows.
        Some(e) => range(e, "elevation", -500.0, 9000.0, "metres above sea level")?,
        None => 0.0,
    };
    let north = match &s.north {
        Some(n) => range(
            n,
            "north",
            -360.0,
            360.0,
            "a compass bearing in degrees clockwise from true north",
        )?,
        None => 0.0,
    };
    let ground_reflectance = match &s.ground_reflectance {
        Some(g) => {
            let field = "site.ground_reflectance";
            ctx.check_reflectance(vec![*g.get_ref()], &ctx.at(g), field)?[0]
        }
        None => GROUND_REFLECTANCE,
    };
    let utc_offset = match &s.utc_offset {
        Some(o) => Some(utc_offset(o.get_ref()).ok_or_else(|| SceneError::Invalid {
            at: ctx.at(o),
            field: "site.utc_offset".into(),
            message: format!(
                "`{}` is not a UTC offset: write \"Z\" (UTC), \"+HH:MM\" or \"-HH:MM\" (e.g. \
                 \"+01:00\"), from -12:00 to +14:00",
                o.get_ref()
            ),
        })?),
        None => None,
    };
    let location = sun::Site {
        latitude,
        longitude,
        elevation,
    };
    Ok(Some(Site {
        location,
        north,
        utc_offset,
        ground_reflectance,
    }))
}

/// A UTC offset in seconds east: `Z`, `+HH:MM` or `-HH:MM` (the minus also as U+2212), from
/// −12:00 to +14:00; `None` for anything else.
pub(crate) fn utc_offset(text: &str) -> Option<i32> {
    if text == "Z" {
        return Some(0);
    }
    let (sign, rest) = if let Some(r) = text.strip_prefix('+') {
        (1, r)
    } else if let Some(r) = text
        .strip_prefix('-')
        .or_else(|| text.strip_prefix('\u{2212}'))
    {
        (-1, r)
    } else {
        return None;
    };
    let (hours, minutes) = rest.split_once(':')?;
    let two_digits = |s: &str| -> Option<i32> {
        (s.len() == 2 && s.bytes().all(|b| b.is_ascii_digit()))
            .then(|| s.parse().ok())
            .flatten()
    };
    let (h, m) = (two_digits(hours)?, two_digits(minutes)?);
    if m >= 60 {
        return None;
    }
    let seconds = sign * (h * 3600 + m * 60);
    (MOST_WEST..=MOST_EAST)
        .contains(&seconds)
        .then_some(seconds)
}

/// The glazing of material `name` (`m`, its `reflectance` already checked), `None` unless
/// it gives a transmittance.
pub(crate) fn glazing(
    ctx: &Ctx,
    name: &str,
    m: &MaterialDef,
    reflectance: &[f64],
) -> Result<Option<Glazing>, SceneError> {
    let field = |f: &str| format!("materials.{name}.{f}");
    let Some(t) = &m.transmittance else {
        let stray = m
            .panes
            .as_ref()
            .map(|p| (ctx.at(p), "panes"))
            .or(m.glazing.as_ref().map(|g| (ctx.at(g), "glazing")));
        return match stray {
            Some((at, which)) => Err(SceneError::Invalid {
                at,
                field: field(which),
                message: format!(
                    "`{which}` describes glazing, but the material gives no `transmittance`; \
                     give its visible transmittance at normal incidence too"
                ),
            }),
            None => Ok(None),
        };
    };
    let at = ctx.at(t);
    let tau = *t.get_ref();
    if ctx.bands != 1 {
        return Err(SceneError::Invalid {
            at,
            field: field("transmittance"),
            message: "glazing is not available in rgb scenes yet: daylight is computed in the \
                      photopic band only; use `bands = \"photopic\"`"
                .into(),
        });
    }
    if !(tau.is_finite() && tau > 0.0 && tau < 1.0) {
        return Err(SceneError::OutOfRange {
            at,
            field: field("transmittance"),
            message: format!(
                "visible transmittance at normal incidence must be in (0, 1), found {tau}"
            ),
        });
    }
    if let Some(e) = &m.emission {
        if ctx
            .per_band(e, &field("emission"))?
            .iter()
            .any(|&x| x != 0.0)
        {
            return Err(SceneError::Invalid {
                at: ctx.at(e),
                field: field("emission"),
                message: "a glazed material (with `transmittance`) cannot emit: daylight \
                          enters through its windows"
                    .into(),
            });
        }
    }
    let rho = reflectance[0];
    if rho + tau > 1.0 {
        return Err(SceneError::OutOfRange {
            at,
            field: field("transmittance"),
            message: format!(
                "reflectance {rho} plus transmittance {tau} exceeds 1: glazing cannot \
                 return more light than it receives"
            ),
        });
    }
    let panes = match &m.panes {
        Some(p) => match u8::try_from(*p.get_ref()) {
            Ok(n) if (1..=MAX_PANES).contains(&n) => n,
            _ => {
                return Err(SceneError::OutOfRange {
                    at: ctx.at(p),
                    field: field("panes"),
                    message: format!("must be 1 to {MAX_PANES}, found {}", p.get_ref()),
                })
            }
        },
        None => PANES,
    };
    let diffusing = matches!(
        m.glazing.as_ref().map(|g| *g.get_ref()),
        Some(GlazingDef::Diffusing)
    );
    let model = if diffusing {
        Glazing::diffusing(tau as f32, panes)
    } else {
        Glazing::clear(tau as f32, panes)
    };
    model.map(Some).map_err(|e| SceneError::OutOfRange {
        at,
        field: field("transmittance"),
        message: format!("{e}; found {tau} for {panes} pane(s)"),
    })
}

/// An exterior surface taken out of the room's surfaces, with its `[surfaces]` settings.
pub(crate) struct Outside {
    pub surface: RawSurface,
    pub flip: bool,
    pub split: bool,
}

/// Takes the exterior surfaces out of `raw` and the per-surface lists that go with it, in
/// order.
pub(crate) fn take_exterior(
    raw: &mut Vec<RawSurface>,
    flip: &mut Vec<bool>,
    split: &mut Vec<bool>,
    is_obj: &mut Vec<bool>,
) -> Vec<Outside> {
    let mut outside = Vec::new();
    let (mut r, mut f, mut s, mut o) = (Vec::new(), Vec::new(), Vec::new(), Vec::new());
    for (((surface, flip), split), obj) in std::mem::take(raw)
        .into_iter()
        .zip(std::mem::take(flip))
        .zip(std::mem::take(split))
        .zip(std::mem::take(is_obj))
    {
        if surface.exterior {
            outside.push(Outside {
                surface,
                flip,
                split,
            });
        } else {
            r.push(surface);
            f.push(flip);
            s.push(split);
            o.push(obj);
        }
    }
    (*raw, *flip, *split, *is_obj) = (r, f, s, o);
    outside
}

/// Whether `name` matches the surface reference `pattern` (an exact name, or a prefix
/// followed by `*`), as `context::matching` reads it.
fn matches(pattern: &str, name: &str) -> bool {
    match pattern.strip_suffix('*') {
        Some(prefix) => name.starts_with(prefix),
        None => name == pattern,
    }
}

/// Exterior surfaces are not the room's: a room's `openings`, a channel's or a zone's
/// `surfaces` naming one (and no surface of the room), or a channel's `materials` naming a
/// material only exterior surfaces have, is an error saying so.
pub(crate) fn check_references(
    ctx: &Ctx,
    file: &SceneFile,
    inside: &[RawSurface],
    outside: &[Outside],
) -> Result<(), SceneError> {
    let lists = file
        .room
        .iter()
        .filter_map(|r| {
            let r = r.get_ref();
            r.openings
                .as_ref()
                .map(|l| (format!("room `{}`.openings", r.name), l, "an opening"))
        })
        .chain(file.channel.iter().filter_map(|c| {
            let c = c.get_ref();
            c.surfaces
                .as_ref()
                .map(|l| (format!("channel `{}`.surfaces", c.name), l, "in a channel"))
        }))
        .chain(file.zone.iter().filter_map(|z| {
            let z = z.get_ref();
            z.surfaces
                .as_ref()
                .map(|l| (format!("zone `{}`.surfaces", z.name), l, "in a zone"))
        }));
    for (field, list, role) in lists {
        for pattern in list.get_ref() {
            if inside.iter().any(|s| matches(pattern, &s.name)) {
                continue;
            }
            if let Some(o) = outside.iter().find(|o| matches(pattern, &o.surface.name)) {
                return Err(SceneError::Invalid {
                    at: ctx.at(list),
                    field,
                    message: format!(
                        "`{}` is an exterior surface (`exterior = true`): it stands outside \
                         the room and has no patches, so it cannot be {role}",
                        o.surface.name
                    ),
                });
            }
        }
    }
    for c in &file.channel {
        let Some(list) = &c.get_ref().materials else {
            continue;
        };
        for m in list.get_ref() {
            let on = |s: &RawSurface| &s.material == m;
            if !inside.iter().any(on) {
                if let Some(o) = outside.iter().find(|o| on(&o.surface)) {
                    return Err(SceneError::Invalid {
                        at: ctx.at(list),
                        field: format!("channel `{}`.materials", c.get_ref().name),
                        message: format!(
                            "material `{m}` is only on exterior surfaces (`{}` ...), which \
                             stand outside the room and cannot be in a channel",
                            o.surface.name
                        ),
                    });
                }
            }
        }
    }
    Ok(())
}

/// The exterior surfaces as obstructions: materials resolved (photopic, not emitting, not
/// glazed), faces checked flat within `planarity` and convex, none reaching into a room
/// (`rooms`: name, min, max in metres).
pub(crate) fn obstructions(
    ctx: &Ctx,
    outside: &[Outside],
    materials: &BTreeMap<String, MaterialInfo>,
    rooms: &[Room],
    planarity: f64,
) -> Result<Vec<Obstruction>, SceneError> {
    let mut out = Vec::with_capacity(outside.len());
    for o in outside {
        let s = &o.surface;
        let invalid = |at: &Location, message: String| SceneError::Invalid {
            at: at.clone(),
            field: format!("surface `{}`.exterior", s.name),
            message,
        };
        if ctx.bands != 1 {
            return Err(invalid(
                &s.at,
                "exterior surfaces are not available in rgb scenes yet: they shade daylight, \
                 which is computed in the photopic band only"
                    .into(),
            ));
        }
        let material = s.material_in(materials)?;
        if material.emission.iter().any(|&e| e > 0.0) {
            return Err(invalid(
                &s.material_at,
                format!(
                    "its material `{}` emits; an exterior surface only reflects daylight",
                    s.material
                ),
            ));
        }
        if material.glazing.is_some() {
            return Err(invalid(
                &s.material_at,
                format!(
                    "its material `{}` is glazed (has a transmittance); a window belongs to the \
                     room: leave out `exterior`",
                    s.material
                ),
            ));
        }
        if s.faces.is_empty() {
            return Err(SceneError::BadFace {
                at: s.at.clone(),
                surface: s.name.clone(),
                face: 0,
                message: "surface has no faces".into(),
            });
        }
        let mut faces = Vec::new();
        for (f, face) in s.faces.iter().enumerate() {
            let mut face = face.clone();
            if o.flip {
                face.reverse();
            }
            let pieces = if o.split {
                triangulate(&face)
            } else {
                vec![face]
            };
            for piece in pieces {
                check_face(&piece, planarity).map_err(|p| SceneError::BadFace {
                    at: s.at.clone(),
                    surface: s.name.clone(),
                    face: f + 1,
                    message: p.to_string(),
                })?;
                if let Some(room) = rooms.iter().find(|r| reaches_into_room(&piece, r)) {
                    let room = &room.name;
                    return Err(invalid(
                        &s.at,
                        format!(
                            "face {} reaches into room `{room}`: an exterior surface must stand \
                             outside every room (it may touch a room's faces)",
                            f + 1
                        ),
                    ));
                }
                faces.push(Face {
                    polygon: Polygon::new(piece),
                    patches: 0..0,
                });
            }
        }
        out.push(Obstruction {
            name: s.name.clone(),
            faces,
            reflectance: material.reflectance[0],
        });
    }
    Ok(out)
}

/// Whether a convex polygon (m) reaches into `room`: into its box for a box room; for a room
/// given by its plan, one of its corners or its centroid strictly inside the room.
fn reaches_into_room(polygon: &[Vec3], room: &Room) -> bool {
    if room.is_box {
        return reaches_into(polygon, room.lo, room.hi);
    }
    let centroid = Polygon::new(polygon.to_vec()).centroid();
    room.strictly_contains(centroid) || polygon.iter().any(|&p| room.strictly_contains(p))
}

/// Whether a convex polygon (m) has a point inside the box `lo`..`hi` by more than
/// [`CONTACT_TOLERANCE`] of its diagonal: the polygon clipped to the shrunk box
/// (Sutherland–Hodgman, one axis-aligned plane at a time) is not empty.
fn reaches_into(polygon: &[Vec3], lo: Vec3, hi: Vec3) -> bool {
    let tol = CONTACT_TOLERANCE * (hi - lo).length();
    let mut clipped = polygon.to_vec();
    for axis in 0..3 {
        for (bound, sign) in [(lo.axis(axis) + tol, 1.0), (hi.axis(axis) - tol, -1.0)] {
            let inside = |p: Vec3| sign * (p.axis(axis) - bound);
            let mut next = Vec::with_capacity(clipped.len() + 1);
            for (i, &a) in clipped.iter().enumerate() {
                let b = clipped[(i + 1) % clipped.len()];
                let (da, db) = (inside(a), inside(b));
                if da >= 0.0 {
                    next.push(a);
                }
                if (da >= 0.0) != (db >= 0.0) {
                    next.push(a + (b - a) * (da / (da - db)));
                }
            }
            clipped = next;
            if clipped.is_empty() {
                return false;
            }
        }
    }
    true
}

/// The windows: every surface of the room (`raw`, after the openings are cut) whose material
/// is glazed, in surface order. A window driven
/// by a channel (`channel_of_surface`) is an error naming both; so is one lying in a room's
/// face (`rooms`) that is neither among the room's `openings` nor that face itself
/// (`in_place`): the face would hide it.
pub(crate) fn windows(
    ctx: &Ctx,
    file: &SceneFile,
    raw: &[RawSurface],
    materials: &BTreeMap<String, MaterialInfo>,
    channel_of_surface: &[Option<usize>],
    rooms: &[Room],
    in_place: &[bool],
) -> Result<Vec<Window>, SceneError> {
    let mut windows = Vec::new();
    for (i, s) in raw.iter().enumerate() {
        let Some(glazing) = materials.get(&s.material).and_then(|m| m.glazing) else {
            continue;
        };
        if let Some(def) = channel_of_surface[i].and_then(|k| file.channel.get(k)) {
            return Err(SceneError::Emitter {
                at: ctx.at(def),
                surface: s.name.clone(),
                message: format!(
                    "is a window (its material `{}` has a transmittance) and is in channel \
                     `{}`: daylight enters through it, it cannot also emit; take it out of the \
                     channel",
                    s.material,
                    def.get_ref().name
                ),
            });
        }
        if !in_place[i] {
            if let Some(face) = room_face_holding(&s.faces, rooms) {
                return Err(SceneError::Invalid {
                    at: s.at.clone(),
                    field: format!("window `{}`", s.name),
                    message: format!(
                        "lies in the face `{face}` but is not in the room's `openings`: the \
                         face behind it would hide it from the room; list it in `openings`"
                    ),
                });
            }
        }
        windows.push(Window {
            surface: i,
            glazing,
        });
    }
    Ok(windows)
}

/// The room face (`<room>.<face>`) holding every corner of `faces` (within
/// [`CONTACT_TOLERANCE`] of the room's diagonal), if any.
fn room_face_holding(faces: &[Vec<Vec3>], rooms: &[Room]) -> Option<String> {
    let corners: Vec<Vec3> = faces.iter().flatten().copied().collect();
    rooms.iter().find_map(|r| {
        r.face_holding(&corners)
            .map(|f| format!("{}.{}", r.name, f.suffix))
    })
}
