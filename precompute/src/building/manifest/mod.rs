//! The building manifest (`building.toml`, docs/building.md): its rooms, each a scene file,
//! its controllers, each the room it serves, the channels it drives and the sensors, zones
//! and grids it reads, and the ports joining rooms (`ports`). Every item is checked against
//! the rooms' scene files when the manifest is loaded, before anything is built, and an error
//! names the file, line and item.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

use serde::Deserialize;
use toml::Spanned;

use super::error::BuildingError;
use crate::flash::FlashBudget;
use crate::scene::file::SceneFile;
use crate::scene::Location;

mod ports;

use ports::{quads, PortDef, Quad};
pub use ports::{Port, PortModel};

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
        let ports = ports::check(&file.port, &rooms, &names, &at)?;
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
