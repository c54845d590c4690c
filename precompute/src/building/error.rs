//! Why a building could not be built or merged: every error names the manifest's file and
//! line and the room, controller, channel, shard or part at fault.

use std::path::PathBuf;

use crate::scene::Location;

/// Why a building could not be built or merged.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum BuildingError {
    /// The manifest could not be read.
    #[error("{}: cannot read the building manifest: {reason}", path.display())]
    Read {
        /// The manifest.
        path: PathBuf,
        /// The operating system's reason.
        reason: std::io::Error,
    },
    /// The manifest is not valid TOML or does not match its schema (a wrong type, an unknown
    /// or missing field).
    #[error("{at}: {message}")]
    Syntax {
        /// File and line of the offending text.
        at: Location,
        /// The parser's message, naming the field.
        message: String,
    },
    /// An item of the manifest is wrong: an unknown room, channel, sensor or zone, a
    /// controller reading nothing, two things of one name, a bound out of range.
    #[error("{at}: {item}: {message}")]
    Manifest {
        /// File and line of the item.
        at: Location,
        /// The item: `room office`, `controller open_a`, `controller open_a: channel x`.
        item: String,
        /// What is wrong with it.
        message: String,
    },
    /// `--shard I/N` names no shard of this building.
    #[error("{}: --shard {given}: {message}", manifest.display())]
    Shard {
        /// The manifest.
        manifest: PathBuf,
        /// The argument as given.
        given: String,
        /// What is wrong with it.
        message: String,
    },
    /// `--room NAME` names no room of the manifest.
    #[error("{}: --room {given}: no room of that name (the rooms: {rooms})", manifest.display())]
    UnknownRoom {
        /// The manifest.
        manifest: PathBuf,
        /// The name given.
        given: String,
        /// The manifest's rooms, comma-separated.
        rooms: String,
    },
    /// A room's build failed.
    // The reason is in the message and deliberately not a `source`: callers printing the
    // error chain would show it twice.
    #[error("{at}: room {room}: {reason}")]
    Room {
        /// Where the manifest names the room.
        at: Location,
        /// The room.
        room: String,
        /// Why its build failed (boxed: the stages' error is large).
        reason: Box<crate::Error>,
    },
    /// A room's part is missing: the room was not built into this folder.
    #[error("{}: room {room} ({at}) has no part here: build it first (`eigenrad building --room {room}`, or the shard that holds it)", path.display())]
    MissingPart {
        /// Where the manifest names the room.
        at: Location,
        /// The room.
        room: String,
        /// The part file looked for.
        path: PathBuf,
    },
    /// A part file cannot be used: not a part, damaged, of another room, of another version
    /// of its scene, or written by another version of eigenrad.
    #[error("{}: {message}", path.display())]
    Part {
        /// The part file.
        path: PathBuf,
        /// What is wrong with it.
        message: String,
    },
    /// A controller's basis is larger than its flash.
    #[error("{at}: controller {controller}: its basis takes {bytes} bytes, more than the {budget} of flash; by section: {sections}; read fewer grid points, leave out modes or daylight, or give a larger `flash`")]
    Flash {
        /// Where the manifest names the controller.
        at: Location,
        /// The controller.
        controller: String,
        /// The basis' size in bytes.
        bytes: usize,
        /// The flash budget.
        budget: crate::flash::FlashBudget,
        /// What takes the room: the bytes of each section, largest first.
        sections: String,
    },
    /// A file could not be written, or a command would write over one of its inputs.
    #[error(transparent)]
    Output(Box<crate::Error>),
}

impl From<crate::atomic::WriteError> for BuildingError {
    fn from(e: crate::atomic::WriteError) -> Self {
        BuildingError::Output(Box::new(e.into()))
    }
}
