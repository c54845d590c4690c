//! The building manifest (`building.toml`, docs/building.md): its rooms, each a scene file,
//! and its controllers, each the room it serves, the channels it drives and the sensors, zones
//! and grids it reads. Every item is checked against the rooms' scene files when the manifest
//! is loaded, before anything is built, and an error names the file, line and item.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

use serde::Deserialize;
use toml::Spanned;

use super::error::BuildingError;
use crate::flash::FlashBudget;
use crate::scene::file::SceneFile;
use crate::scene::Location;

/// `[building]`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct HeaderDef {
    name: String,
    /// Flash budget of every controller's basis (`"512KiB"`).
    #[serde(default)]
    flash: Option<Spanned<String>>,
}

/// `[[room]]`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RoomDef {
    name: Spanned<String>,
    /// The room's scene file, relative to the manifest.
    scene: Spanned<String>,
}

/// `[[controller]]`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct ControllerDef {
    name: Spanned<String>,
    room: Spanned<String>,
    #[serde(default)]
    drives: Vec<Spanned<String>>,
    #[serde(default)]
    sensors: Vec<Spanned<String>>,
    #[serde(default)]
    zones: Vec<Spanned<String>>,
    #[serde(default)]
    grids: Vec<Spanned<String>>,
    /// Neighbours' channels the controller is not told, each with the highest level it may
    /// assume.
    #[serde(default)]
    bounds: BTreeMap<String, Spanned<f64>>,
    #[serde(default)]
    modes: bool,
}

/// `[[port]]`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct PortDef {
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
}

/// The whole file.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct ManifestFile {
    building: HeaderDef,
    #[serde(default)]
    room: Vec<Spanned<RoomDef>>,
    #[serde(default)]
    controller: Vec<Spanned<ControllerDef>>,
    #[serde(default)]
    port: Vec<Spanned<PortDef>>,
}

/// A loaded and checked building manifest.
#[derive(Clone, Debug)]
pub struct Manifest {
    /// The manifest file.
    pub path: PathBuf,
    /// `building.name`.
    pub name: String,
    /// Flash budget of every controller's basis (`building.flash`, 512 KiB when not given).
    pub flash: FlashBudget,
    /// The rooms, in the manifest's order.
    pub rooms: Vec<Room>,
    /// The controllers, in the manifest's order.
    pub controllers: Vec<Controller>,
    /// The ports joining rooms, in the manifest's order.
    pub ports: Vec<Port>,
}

/// A port: an opening shared by two rooms (an open door, internal glazing) through which
/// light leaving one enters the other, diffusely (docs/building.md, "Ports").
#[derive(Clone, Debug)]
pub struct Port {
    /// `port.name`.
    pub name: String,
    /// Indices of its two rooms in [`Manifest::rooms`].
    pub rooms: [usize; 2],
    /// The opening's quad in each room's scene (a black quad in the room's `openings`), in
    /// the order of `rooms`.
    pub openings: [String; 2],
    /// Share of the flux reaching the opening from one side that leaves it on the other, in
    /// (0, 1] (1 for an open door).
    pub transmittance: f64,
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

/// A room: one scene, built as one radiosity system.
#[derive(Clone, Debug)]
pub struct Room {
    /// `room.name`: also the name of its part file.
    pub name: String,
    /// The scene file, resolved against the manifest's folder.
    pub scene: PathBuf,
    /// Where the manifest names it.
    pub at: Location,
}

/// A controller: what it drives and reads in its room.
#[derive(Clone, Debug)]
pub struct Controller {
    /// `controller.name`: also the name of its basis file.
    pub name: String,
    /// Index of its room in [`Manifest::rooms`].
    pub room: usize,
    /// The channels it drives.
    pub drives: Vec<String>,
    /// The sensors it reads.
    pub sensors: Vec<String>,
    /// The zones it reads as area averages.
    pub zones: Vec<String>,
    /// The zones whose calculation grids it reads point by point.
    pub grids: Vec<String>,
    /// Neighbours' channels it is not told, each with the highest level (0 to
    /// [`eigenrad_runtime::MAX_LEVEL`]) the controller assumes for it. Every other
    /// neighbour's channel that reaches its outputs is an input it must be told.
    pub bounds: Vec<(String, f64)>,
    /// Whether its basis carries the room's modes (every patch: for exitance set patch by
    /// patch and per-patch readings), not only its outputs.
    pub modes: bool,
    /// Where the manifest names it.
    pub at: Location,
}

/// What a room's scene file names: its channels, sensors, and zones with whether each has a
/// calculation grid.
struct SceneNames {
    channels: BTreeSet<String>,
    sensors: BTreeSet<String>,
    zones: BTreeMap<String, bool>,
    /// Every quad, by name.
    quads: BTreeMap<String, Quad>,
}

/// A quad of a scene file, as a port's opening needs it.
struct Quad {
    /// Its corners, in metres, counter-clockwise seen from the front.
    corners: [[f64; 3]; 4],
    /// Whether it is one of a room's `openings` (its wall meshed around it).
    opening: bool,
    /// Whether its material reflects, transmits and emits nothing: light reaching it leaves
    /// the room.
    black: bool,
}

impl SceneNames {
    fn read(path: &Path) -> Result<SceneNames, crate::scene::SceneError> {
        let text =
            std::fs::read_to_string(path).map_err(|reason| crate::scene::SceneError::Read {
                path: path.to_path_buf(),
                reason,
            })?;
        let file = SceneFile::parse(&text, path)?;
        Ok(SceneNames {
            channels: file
                .channel
                .iter()
                .map(|c| c.get_ref().name.clone())
                .collect(),
            sensors: file
                .sensor
                .iter()
                .map(|s| s.get_ref().name.clone())
                .collect(),
            zones: file
                .zone
                .iter()
                .map(|z| {
                    let z = z.get_ref();
                    (z.name.clone(), z.work_plane.is_some() || z.grid.is_some())
                })
                .collect(),
            quads: quads(&file),
        })
    }
}

/// The quads of a scene file, by name (a quad without four corners is the scene's error, at
/// its build: its corners read NaN here and match no other).
fn quads(file: &SceneFile) -> BTreeMap<String, Quad> {
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

/// Whether `name` can name a file of its own in a folder: letters, digits, `_`, `-` and `.`,
/// not starting with `.`.
fn is_file_name(name: &str) -> bool {
    !name.is_empty()
        && !name.starts_with('.')
        && name
            .chars()
            .all(|c| c.is_ascii_alphanumeric() || matches!(c, '_' | '-' | '.'))
}

impl Manifest {
    /// Reads and checks the manifest at `path` and the names its controllers use against
    /// their rooms' scene files.
    pub fn load(path: &Path) -> Result<Manifest, BuildingError> {
        let text = std::fs::read_to_string(path).map_err(|reason| BuildingError::Read {
            path: path.to_path_buf(),
            reason,
        })?;
        let file: ManifestFile = toml::from_str(&text).map_err(|e| BuildingError::Syntax {
            at: match e.span() {
                Some(span) => Location::at_offset(path, &text, span.start),
                None => Location::file(path),
            },
            message: e.message().trim().to_string(),
        })?;
        let at = |offset: usize| Location::at_offset(path, &text, offset);
        let wrong = |offset: usize, item: String, message: String| BuildingError::Manifest {
            at: at(offset),
            item,
            message,
        };
        let flash = match &file.building.flash {
            None => FlashBudget::DEFAULT,
            Some(f) => f
                .get_ref()
                .parse()
                .map_err(|e: crate::flash::ParseFlashBudgetError| {
                    wrong(f.span().start, "building.flash".into(), e.to_string())
                })?,
        };
        let dir = path.parent().unwrap_or(Path::new(""));
        let mut rooms: Vec<Room> = Vec::new();
        let mut names = Vec::new();
        for def in &file.room {
            let name = def.get_ref().name.get_ref();
            let offset = def.get_ref().name.span().start;
            if !is_file_name(name) {
                return Err(wrong(offset, format!("room {name:?}"), "a room's name names its part file: use letters, digits, `_`, `-` and `.`, not starting with `.`".into()));
            }
            if rooms.iter().any(|r| &r.name == name) {
                return Err(wrong(
                    offset,
                    format!("room {name}"),
                    "a second room of this name".into(),
                ));
            }
            let scene = dir.join(def.get_ref().scene.get_ref());
            let scene_names = SceneNames::read(&scene).map_err(|e| {
                wrong(
                    def.get_ref().scene.span().start,
                    format!("room {name}"),
                    format!("its scene: {e}"),
                )
            })?;
            rooms.push(Room {
                name: name.clone(),
                scene,
                at: at(offset),
            });
            names.push(scene_names);
        }
        if rooms.is_empty() {
            return Err(BuildingError::Manifest {
                at: Location::file(path),
                item: "room".into(),
                message: "the building has no room: add a [[room]] with its scene".into(),
            });
        }
        let mut controllers: Vec<Controller> = Vec::new();
        let mut driven: BTreeMap<(usize, String), String> = BTreeMap::new();
        for def in &file.controller {
            let c = def.get_ref();
            let name = c.name.get_ref().clone();
            let item = format!("controller {name}");
            let offset = c.name.span().start;
            if !is_file_name(&name) {
                return Err(wrong(offset, format!("controller {name:?}"), "a controller's name names its basis file: use letters, digits, `_`, `-` and `.`, not starting with `.`".into()));
            }
            if controllers.iter().any(|k| k.name == name) {
                return Err(wrong(
                    offset,
                    item,
                    "a second controller of this name".into(),
                ));
            }
            let room_name = c.room.get_ref();
            let Some(room) = rooms.iter().position(|r| &r.name == room_name) else {
                let known: Vec<&str> = rooms.iter().map(|r| r.name.as_str()).collect();
                return Err(wrong(
                    c.room.span().start,
                    item,
                    format!(
                        "unknown room `{room_name}` (the rooms: {})",
                        known.join(", ")
                    ),
                ));
            };
            if c.sensors.is_empty() && c.zones.is_empty() && c.grids.is_empty() {
                return Err(wrong(
                    offset,
                    item,
                    "reads nothing: give it `sensors`, `zones` or `grids` to read".into(),
                ));
            }
            let scene = &names[room];
            let scene_file = rooms[room].scene.display();
            let check = |list: &[Spanned<String>], kind: &str, known: &dyn Fn(&str) -> bool| {
                let mut seen = BTreeSet::new();
                for entry in list {
                    let value = entry.get_ref();
                    if !known(value) {
                        return Err(wrong(
                            entry.span().start,
                            format!("{item}: {kind} {value}"),
                            format!("room {room_name} has no {kind} of this name ({scene_file})"),
                        ));
                    }
                    if !seen.insert(value.clone()) {
                        return Err(wrong(
                            entry.span().start,
                            format!("{item}: {kind} {value}"),
                            "named twice".into(),
                        ));
                    }
                }
                Ok(list
                    .iter()
                    .map(|e| e.get_ref().clone())
                    .collect::<Vec<String>>())
            };
            let drives = check(&c.drives, "channel", &|n| scene.channels.contains(n))?;
            let sensors = check(&c.sensors, "sensor", &|n| scene.sensors.contains(n))?;
            let zones = check(&c.zones, "zone", &|n| scene.zones.contains_key(n))?;
            let grids = check(&c.grids, "zone", &|n| scene.zones.contains_key(n))?;
            for g in &c.grids {
                if scene.zones.get(g.get_ref()) == Some(&false) {
                    return Err(wrong(g.span().start, format!("{item}: grid {}", g.get_ref()), format!("zone {} has no calculation grid ({scene_file}: give it a `work_plane` or a `grid`)", g.get_ref())));
                }
            }
            for d in &c.drives {
                let key = (room, d.get_ref().clone());
                if let Some(other) = driven.get(&key) {
                    return Err(wrong(
                        d.span().start,
                        format!("{item}: channel {}", d.get_ref()),
                        format!(
                            "already driven by controller {other}: a channel has one controller"
                        ),
                    ));
                }
                driven.insert(key, name.clone());
            }
            let mut bounds = Vec::new();
            for (channel, level) in &c.bounds {
                let here = level.span().start;
                let bound_item = format!("{item}: bounds.{channel}");
                if !scene.channels.contains(channel) {
                    return Err(wrong(
                        here,
                        bound_item,
                        format!("room {room_name} has no channel of this name ({scene_file})"),
                    ));
                }
                if drives.contains(channel) {
                    return Err(wrong(
                        here,
                        bound_item,
                        "the controller drives this channel: a bound is for a neighbour's".into(),
                    ));
                }
                let value = *level.get_ref();
                if !(0.0..=f64::from(eigenrad_runtime::MAX_LEVEL)).contains(&value) {
                    return Err(wrong(
                        here,
                        bound_item,
                        format!(
                            "{value} is not a channel level from 0 to {}",
                            eigenrad_runtime::MAX_LEVEL
                        ),
                    ));
                }
                bounds.push((channel.clone(), value));
            }
            controllers.push(Controller {
                name,
                room,
                drives,
                sensors,
                zones,
                grids,
                bounds,
                modes: c.modes,
                at: at(offset),
            });
        }
        let mut ports: Vec<Port> = Vec::new();
        for def in &file.port {
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
                            format!(
                                "{value} is not a transmittance in (0, 1] (1 for an open door)"
                            ),
                        ));
                    }
                    value
                }
            };
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
                at: at(offset),
            });
        }
        Ok(Manifest {
            path: path.to_path_buf(),
            name: file.building.name,
            flash,
            rooms,
            controllers,
            ports,
        })
    }

    /// The rooms of shard `text` (`I/N`, 0 ≤ I < N ≤ rooms): every room whose index in the
    /// manifest leaves `I` when divided by `N`.
    pub fn shard(&self, text: &str) -> Result<Vec<usize>, BuildingError> {
        let fail = |message: String| BuildingError::Shard {
            manifest: self.path.clone(),
            given: text.to_string(),
            message,
        };
        let rooms = self.rooms.len();
        let (i, n) = text
            .split_once('/')
            .and_then(|(i, n)| {
                Some((
                    i.trim().parse::<usize>().ok()?,
                    n.trim().parse::<usize>().ok()?,
                ))
            })
            .ok_or_else(|| fail("not a shard I/N (e.g. 0/3: the first of three)".into()))?;
        if n == 0 || n > rooms {
            return Err(fail(format!(
                "{n} shards for {rooms} rooms: give from 1 to {rooms} shards"
            )));
        }
        if i >= n {
            return Err(fail(format!(
                "shard {i} is out of range: the shards of {n} are 0 to {}",
                n - 1
            )));
        }
        Ok((0..rooms).filter(|r| r % n == i).collect())
    }

    /// The room named `name`.
    pub fn room(&self, name: &str) -> Result<usize, BuildingError> {
        self.rooms
            .iter()
            .position(|r| r.name == name)
            .ok_or_else(|| BuildingError::UnknownRoom {
                manifest: self.path.clone(),
                given: name.to_string(),
                rooms: self
                    .rooms
                    .iter()
                    .map(|r| r.name.as_str())
                    .collect::<Vec<_>>()
                    .join(", "),
            })
    }
}
