//! The manifest's `[[port]]`s (docs/building.md, "Ports"): each joins two rooms of the
//! building through one opening, a black quad of both rooms' scenes seen from its two sides,
//! checked against the scene files when the manifest is loaded.

use std::collections::{BTreeMap, BTreeSet};

use serde::Deserialize;
use toml::Spanned;

use super::{Room, SceneNames};
use crate::building::error::BuildingError;
use crate::scene::file::SceneFile;
use crate::scene::Location;

/// `[[port]]`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(super) struct PortDef {
    name: Spanned<String>,
    /// The two rooms it joins.
    rooms: Spanned<Vec<Spanned<String>>>,
    /// The opening's quad in each room's scene, in the order of `rooms` (default: the port's
    /// name in both).
    #[serde(default)]
    openings: Option<Spanned<Vec<Spanned<String>>>>,
    /// Share of the light reaching the opening that passes (1: an open door).
    #[serde(default)]
    transmittance: Option<Spanned<f64>>,
    /// Number of direction bins of the light crossing it (1: diffuse). Read as a number, so
    /// that `2.5` is refused naming the field, as `0` is.
    #[serde(default)]
    directions: Option<Spanned<f64>>,
    /// How the light crossing it is modelled: `"diffuse"` (the default; with `directions`,
    /// in direction bins) or `"exact"`.
    #[serde(default)]
    model: Option<Spanned<String>>,
}

/// How a port's light is modelled (docs/building.md, "Ports").
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PortModel {
    /// A pass-through surface re-emitting what crosses it, diffusely or within direction
    /// bins ([`Port::directions`]; docs/math.md, "Rooms coupled through ports").
    Diffusing,
    /// The opening a real hole: the rooms' patches that see it exchange light through it as
    /// in one scene (docs/math.md, "Rooms seen through an exact port").
    Exact,
}

/// A port: an opening shared by two rooms (an open door, internal glazing) through which
/// light leaving one enters the other, diffusely (docs/building.md, "Ports").
#[derive(Clone, Debug)]
pub struct Port {
    /// `port.name`.
    pub name: String,
    /// Indices of its two rooms in [`Manifest::rooms`](super::Manifest::rooms).
    pub rooms: [usize; 2],
    /// The opening's quad in each room's scene (a black quad in the room's `openings`), in
    /// the order of `rooms`.
    pub openings: [String; 2],
    /// Share of the flux reaching the opening from one side that leaves it on the other, in
    /// (0, 1] (1 for an open door).
    pub transmittance: f64,
    /// Number of direction bins the light crossing it is resolved into, from 1 (diffuse: what
    /// enters a room is re-emitted as Lambertian) to
    /// [`MAX_DIRECTIONS`](crate::building::port::MAX_DIRECTIONS) (docs/math.md, "Directional
    /// ports").
    pub directions: usize,
    /// How the light crossing it is modelled.
    pub model: PortModel,
    /// Where the manifest names it.
    pub at: Location,
}

impl Port {
    /// The opening of this port in room `room`, if the port joins it.
    pub fn opening_in(&self, room: usize) -> Option<&str> {
        self.rooms
            .iter()
            .position(|&r| r == room)
            .map(|side| self.openings[side].as_str())
    }
}

/// A quad of a scene file, as a port's opening needs it.
pub(super) struct Quad {
    /// Its corners, in metres, counter-clockwise seen from the front.
    corners: [[f64; 3]; 4],
    /// Whether it is one of a room's `openings` (its wall meshed around it).
    opening: bool,
    /// Whether its material reflects, transmits and emits nothing: light reaching it leaves
    /// the room.
    black: bool,
}

/// The quads of a scene file, by name (a quad without four corners is the scene's error, at
/// its build: its corners read NaN here and match no other).
pub(super) fn quads(file: &SceneFile) -> BTreeMap<String, Quad> {
    let metres = file.scene.unit.get_ref().metres();
    let openings: BTreeSet<&String> = file
        .room
        .iter()
        .filter_map(|r| r.get_ref().openings.as_ref())
        .flat_map(|o| o.get_ref())
        .collect();
    file.quad
        .iter()
        .map(|q| {
            let q = q.get_ref();
            let corners = q.corners.get_ref();
            let corners: [[f64; 3]; 4] = std::array::from_fn(|k| {
                let c = corners.get(k).map_or([f64::NAN; 3], |c| c.0);
                c.map(|x| x * metres)
            });
            let black = file.materials.get(q.material.get_ref()).is_some_and(|m| {
                let m = m.get_ref();
                let zero = |v: &crate::scene::file::PerBand| match v {
                    crate::scene::file::PerBand::One(x) => *x == 0.0,
                    crate::scene::file::PerBand::Many(x) => x.iter().all(|x| *x == 0.0),
                };
                zero(m.reflectance.get_ref())
                    && m.emission.as_ref().is_none_or(|e| zero(e.get_ref()))
                    && m.transmittance.is_none()
            });
            (
                q.name.clone(),
                Quad {
                    corners,
                    opening: openings.contains(&q.name) && !q.exterior,
                    black,
                },
            )
        })
        .collect()
}

/// Farthest two openings' corners may lie apart and still be one port's, in metres: a
/// micrometre, far below any drawing's precision and far above rounding.
const PORT_CORNER_TOLERANCE: f64 = 1e-6;

/// Whether two quads are one opening seen from its two sides: the same four corners, in
/// opposite turns (so facing opposite ways).
fn same_opening_facing_back(a: &[[f64; 3]; 4], b: &[[f64; 3]; 4]) -> bool {
    let near =
        |p: &[f64; 3], q: &[f64; 3]| (0..3).all(|k| (p[k] - q[k]).abs() <= PORT_CORNER_TOLERANCE);
    // b runs a's corners backwards from some corner.
    (0..4).any(|start| (0..4).all(|k| near(&a[k], &b[(start + 4 - k) % 4])))
}

/// The manifest's ports `defs`, each checked against the building's `rooms` and the names of
/// their scenes (`names`, in the rooms' order); `at` locates a byte offset of the manifest.
pub(super) fn check(
    defs: &[Spanned<PortDef>],
    rooms: &[Room],
    names: &[SceneNames],
    at: &dyn Fn(usize) -> Location,
) -> Result<Vec<Port>, BuildingError> {
    let wrong = |offset: usize, item: String, message: String| BuildingError::Manifest {
        at: at(offset),
        item,
        message,
    };
    let mut ports: Vec<Port> = Vec::new();
    for def in defs {
        let p = def.get_ref();
        let name = p.name.get_ref().clone();
        let item = format!("port {name}");
        let offset = p.name.span().start;
        if name.is_empty() || ports.iter().any(|q| q.name == name) {
            return Err(wrong(
                offset,
                item,
                "a port needs a name of its own (empty, or a second port of this name)".into(),
            ));
        }
        let given = p.rooms.get_ref();
        if given.len() != 2 {
            return Err(wrong(
                p.rooms.span().start,
                item,
                format!(
                    "a port joins two rooms, not {}: `rooms = [\"a\", \"b\"]`",
                    given.len()
                ),
            ));
        }
        let mut joined = [0; 2];
        for (side, room_name) in given.iter().enumerate() {
            joined[side] = rooms
                .iter()
                .position(|r| r.name == *room_name.get_ref())
                .ok_or_else(|| {
                    let known: Vec<&str> = rooms.iter().map(|r| r.name.as_str()).collect();
                    wrong(
                        room_name.span().start,
                        format!("{item}: room {}", room_name.get_ref()),
                        format!(
                            "not a room of this building: every room a port joins is built as a [[room]] (the rooms: {})",
                            known.join(", ")
                        ),
                    )
                })?;
        }
        if joined[0] == joined[1] {
            return Err(wrong(
                p.rooms.span().start,
                item,
                "joins a room to itself: a port joins two rooms".into(),
            ));
        }
        let openings: [Spanned<String>; 2] = match &p.openings {
            None => [p.name.clone(), p.name.clone()],
            Some(list) => match list.get_ref().as_slice() {
                [a, b] => [a.clone(), b.clone()],
                other => {
                    return Err(wrong(
                        list.span().start,
                        item,
                        format!(
                            "one opening per room, in the order of `rooms`: 2, not {}",
                            other.len()
                        ),
                    ))
                }
            },
        };
        let mut quads = Vec::new();
        for side in 0..2 {
            let (room, opening) = (&rooms[joined[side]], &openings[side]);
            let scene_file = room.scene.display();
            let here = opening.span().start;
            let opening_item = format!(
                "{item}: opening {} in room {}",
                opening.get_ref(),
                room.name
            );
            let Some(quad) = names[joined[side]].quads.get(opening.get_ref()) else {
                return Err(wrong(
                    here,
                    opening_item,
                    format!(
                        "room {} has no [[quad]] of this name ({scene_file})",
                        room.name
                    ),
                ));
            };
            if !quad.opening {
                return Err(wrong(here, opening_item, format!("not one of the room's `openings` ({scene_file}): list it in its [[room]]'s `openings` so that the wall is meshed around it")));
            }
            if !quad.black {
                return Err(wrong(here, opening_item, format!("its material reflects, emits or transmits ({scene_file}): a port's opening is black (`reflectance = 0`), since the light reaching it leaves the room through it")));
            }
            quads.push(quad);
        }
        if !same_opening_facing_back(&quads[0].corners, &quads[1].corners) {
            return Err(wrong(
                offset,
                item,
                format!(
                    "its openings differ: {} in room {} has corners {:?} m and {} in room {} has {:?} m; a port's opening is one quad, its corners the same in both rooms within {PORT_CORNER_TOLERANCE} m and in opposite turns (each facing into its room)",
                    openings[0].get_ref(),
                    rooms[joined[0]].name,
                    quads[0].corners,
                    openings[1].get_ref(),
                    rooms[joined[1]].name,
                    quads[1].corners
                ),
            ));
        }
        let transmittance = match &p.transmittance {
            None => 1.0,
            Some(t) => {
                let value = *t.get_ref();
                if !(value > 0.0 && value <= 1.0) {
                    return Err(wrong(
                        t.span().start,
                        format!("{item}: transmittance"),
                        format!("{value} is not a transmittance in (0, 1] (1 for an open door)"),
                    ));
                }
                value
            }
        };
        let directions = match &p.directions {
            None => crate::building::port::DEFAULT_DIRECTIONS,
            Some(d) => {
                let value = *d.get_ref();
                let max = crate::building::port::MAX_DIRECTIONS;
                if value.fract() == 0.0 && (1.0..=max as f64).contains(&value) {
                    value as usize
                } else {
                    return Err(wrong(
                        d.span().start,
                        format!("{item}: directions"),
                        format!(
                            "{value} is not a number of direction bins from 1 (diffuse) to {max}"
                        ),
                    ));
                }
            }
        };
        let model = match &p.model {
            None => PortModel::Diffusing,
            Some(m) => match m.get_ref().as_str() {
                "diffuse" => PortModel::Diffusing,
                "exact" if p.directions.is_none() => PortModel::Exact,
                "exact" => {
                    return Err(wrong(
                        m.span().start,
                        format!("{item}: model"),
                        "an exact port has no direction bins: the light crossing it keeps every direction (leave out `directions`)".into(),
                    ))
                }
                other => {
                    return Err(wrong(
                        m.span().start,
                        format!("{item}: model"),
                        format!("{other:?} is not a port model: \"diffuse\" (the default) or \"exact\""),
                    ))
                }
            },
        };
        if let Some(other) = ports.iter().find(|q| q.model != model) {
            return Err(wrong(
                offset,
                item,
                format!(
                    "its model differs from port {}'s: a building's ports are all exact or all diffusing",
                    other.name
                ),
            ));
        }
        for other in &ports {
            for side in 0..2 {
                let (room, opening) = (joined[side], openings[side].get_ref());
                if other.opening_in(room) == Some(opening) {
                    return Err(wrong(
                        openings[side].span().start,
                        format!("{item}: opening {opening} in room {}", rooms[room].name),
                        format!("already the opening of port {}", other.name),
                    ));
                }
            }
        }
        ports.push(Port {
            name,
            rooms: joined,
            openings: openings.map(|o| o.get_ref().clone()),
            transmittance,
            directions,
            model,
            at: at(offset),
        });
    }
    Ok(ports)
}
