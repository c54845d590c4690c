//! A building: many rooms, each one scene built as one system, and many controllers, each
//! with a basis holding only what it reads (docs/building.md).
//!
//! | module | what it holds |
//! |---|---|
//! | [`manifest`] | `building.toml`: its rooms, controllers and ports, checked against the rooms' scenes |
//! | [`part`] | a room built: its tables, the hash of its scene's files, the program's version |
//! | [`port`] | rooms sharing light through openings: each room's responses at its ports, and the merge's port system |
//! | [`controller`] | a controller's basis cut from its room's tables, its size by section |
//! | `run` | rooms built into parts (in parallel within the memory budget, or a shard of them) and the merge |
//! | `error` | [`BuildingError`]: every failure naming the manifest's file, line and item |

pub mod controller;
mod error;
pub mod manifest;
pub mod part;
pub mod port;
mod run;

pub use error::BuildingError;
pub use manifest::{Controller, Manifest, Port, PortModel, Room};
pub use part::Part;
pub use run::{basis_path, build_rooms, merge, ControllerBasis, Merged, RoomBuilt};

/// The folder of the parts in a building's output folder.
pub fn parts_dir(out: &std::path::Path) -> std::path::PathBuf {
    out.join("parts")
}
