//! A room's part: what building one room leaves for the merge. One file per room
//! (`<room>.part`), written atomically, holding the room's basis tables in `f64` (every
//! controller's basis is cut from them), its responses at its ports' openings, the room's name, the content hash of its scene's
//! files and the version of the program that built it, so that parts of different scenes or
//! versions are never mixed.
//!
//! Layout: the magic `EIGENRAD PART\n`, the postcard encoding of [`Part`], and the SHA-256
//! of that encoding (a damaged file is refused, not misread).

use std::path::{Path, PathBuf};

use eigenrad_runtime::writer::BasisTables;
use serde::{Deserialize, Serialize};
use sha2::{Digest, Sha256};

use super::error::BuildingError;
use super::manifest::Room;
use super::port::exact::ExactPorts;
use super::port::RoomPorts;
use crate::atomic;

/// The first bytes of every part file.
const MAGIC: &[u8] = b"EIGENRAD PART\n";

/// The layout of [`Part`]: 2 since the ports' responses hold the daylight's flux onto the
/// port patches, 3 since they are resolved into the ports' direction bins, 4 since it holds
/// the responses at the exact ports, 5 since those hold the rules of the room's pair
/// integrals and every patch's exitance only when a controller of the room keeps the modes,
/// 6 since they hold the seen patches' exitance under each daylight node.
const PART_FORMAT: u32 = 6;

/// The program that builds parts: a part of another version is refused. The basis format's
/// version and the part's layout are part of it, since the tables and the part follow them.
pub fn program_version() -> String {
    format!(
        "eigenrad {} (basis format {}, part format {PART_FORMAT})",
        env!("CARGO_PKG_VERSION"),
        eigenrad_runtime::format::FORMAT_VERSION
    )
}

/// A room built: its tables and what they were built from.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Part {
    /// [`program_version`] of the program that built it.
    pub program: String,
    /// The room's name in the manifest.
    pub room: String,
    /// [`scene_hash`] of the scene it was built from.
    pub scene_hash: [u8; 32],
    /// Every table of the room's basis, in `f64`.
    pub tables: BasisTables,
    /// The room's exact responses at its diffusing ports' openings (empty without).
    pub ports: RoomPorts,
    /// The room's exact responses at the patches that see its exact ports' openings (empty
    /// without).
    pub exact: ExactPorts,
}

/// SHA-256 of the contents of the scene's files (`scene::inputs`: the scene file, its OBJ and
/// MTL files, its photometry), in order, each preceded by its length.
pub fn scene_hash(scene: &Path) -> Result<[u8; 32], crate::Error> {
    let mut hasher = Sha256::new();
    for file in crate::scene::inputs(scene)?.files {
        let bytes = std::fs::read(&file).map_err(|reason| crate::Error::Io {
            path: file.clone(),
            reason,
        })?;
        hasher.update((bytes.len() as u64).to_le_bytes());
        hasher.update(&bytes);
    }
    Ok(hasher.finalize().into())
}

/// The part file of room `room` in `dir`.
pub fn path(dir: &Path, room: &str) -> PathBuf {
    dir.join(format!("{room}.part"))
}

impl Part {
    /// The part's bytes.
    pub fn to_bytes(&self) -> Vec<u8> {
        // Encoding owned vectors and strings into a growing buffer cannot fail.
        let payload = postcard::to_allocvec(self).unwrap_or_default();
        let mut bytes = MAGIC.to_vec();
        bytes.extend_from_slice(&payload);
        bytes.extend_from_slice(&Sha256::digest(&payload));
        bytes
    }

    /// Writes the part atomically to `path`.
    pub fn write(&self, path: &Path) -> Result<(), BuildingError> {
        atomic::write(path, &self.to_bytes())?;
        Ok(())
    }

    /// Reads the part at `path`, refusing one that is damaged or not a part.
    pub fn read(path: &Path) -> Result<Part, BuildingError> {
        let fail = |message: String| BuildingError::Part {
            path: path.to_path_buf(),
            message,
        };
        let bytes = std::fs::read(path).map_err(|e| fail(format!("cannot read the part: {e}")))?;
        let body = bytes.strip_prefix(MAGIC).ok_or_else(|| {
            fail("not a part file of eigenrad (no `EIGENRAD PART` header)".into())
        })?;
        let split = body
            .len()
            .checked_sub(32)
            .ok_or_else(|| fail("the part is truncated".into()))?;
        let (payload, checksum) = body.split_at(split);
        if Sha256::digest(payload).as_slice() != checksum {
            return Err(fail(
                "the part is damaged (its checksum does not match): build its room again".into(),
            ));
        }
        postcard::from_bytes(payload).map_err(|e| {
            fail(format!(
                "the part cannot be decoded ({e}): build its room again"
            ))
        })
    }

    /// Reads the part of `room` from `dir` and checks that it is this program's, this room's
    /// and of the scene as it is now.
    pub fn read_checked(dir: &Path, room: &Room) -> Result<Part, BuildingError> {
        let path = path(dir, &room.name);
        if !path.exists() {
            return Err(BuildingError::MissingPart {
                at: room.at.clone(),
                room: room.name.clone(),
                path,
            });
        }
        let part = Part::read(&path)?;
        let fail = |message: String| BuildingError::Part {
            path: path.clone(),
            message,
        };
        if part.program != program_version() {
            return Err(fail(format!(
                "built by {}, not by this {}: build room {} again with this program",
                part.program,
                program_version(),
                room.name
            )));
        }
        if part.room != room.name {
            return Err(fail(format!(
                "holds room {}, not room {} ({})",
                part.room, room.name, room.at
            )));
        }
        let now = scene_hash(&room.scene).map_err(|reason| BuildingError::Room {
            at: room.at.clone(),
            room: room.name.clone(),
            reason: Box::new(reason),
        })?;
        if part.scene_hash != now {
            return Err(fail(format!(
                "built from another version of {} (its files have changed since): build room {} again",
                room.scene.display(),
                room.name
            )));
        }
        Ok(part)
    }
}
