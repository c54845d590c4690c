//! Building rooms into parts (on this machine, rooms in parallel as far as its memory
//! allows), and merging the parts into every controller's basis.

use std::path::{Path, PathBuf};
use std::sync::mpsc;
use std::time::Instant;

use serde::Serialize;

use super::controller::{self, Neighbours};
use super::error::BuildingError;
use super::manifest::{Manifest, PortModel};
use super::part::{self, Part};
use super::port;
use crate::flash::FlashBudget;
use crate::memory;
use crate::pipeline::{self, BuildOptions};
use crate::scene;

/// One room built.
#[derive(Clone, Debug, Serialize)]
pub struct RoomBuilt {
    /// The room.
    pub room: String,
    /// Its patches.
    pub patches: usize,
    /// Its modes per band.
    pub modes: usize,
    /// Bytes of the whole room's basis.
    pub basis_bytes: usize,
    /// Seconds its build took, from loading the scene to its part written.
    pub seconds: f64,
}

/// Builds the rooms `rooms` (indices into the manifest's) and writes each one's part into
/// `parts` as soon as it is built. Rooms are built at the same time, up to the machine's
/// threads, as long as the peak memory of the builds running together
/// ([`pipeline::peak_bytes`]) stays within [`memory::budget_bytes`]; each build still makes its
/// own check against the whole machine's budget. Returns the rooms built, in `rooms`' order;
/// the first room that failed, in that order, is the error (the other rooms' parts are
/// written all the same).
pub fn build_rooms(
    manifest: &Manifest,
    rooms: &[usize],
    options: &BuildOptions,
    parts: &Path,
) -> Result<Vec<RoomBuilt>, BuildingError> {
    let room_error = |r: usize, reason: crate::Error| BuildingError::Room {
        at: manifest.rooms[r].at.clone(),
        room: manifest.rooms[r].name.clone(),
        reason: Box::new(reason),
    };
    // Each room's peak, from its scene meshed (cheap against the build).
    let mut need = Vec::with_capacity(rooms.len());
    for &r in rooms {
        let scene = scene::load(&manifest.rooms[r].scene).map_err(|e| room_error(r, e.into()))?;
        need.push(
            pipeline::peak_bytes(&scene, &options.form_factors)
                .iter()
                .sum::<f64>(),
        );
    }
    let budget = memory::budget_bytes();
    let threads = std::thread::available_parallelism().map_or(1, |n| n.get());
    let mut results: Vec<Option<Result<RoomBuilt, BuildingError>>> = vec![];
    results.resize_with(rooms.len(), || None);
    std::thread::scope(|s| {
        let (done, finished) = mpsc::channel();
        let (mut next, mut running, mut held) = (0, 0, 0.0);
        loop {
            // Start what fits; a room larger than the budget alone starts alone (and its own
            // check refuses it).
            while next < rooms.len()
                && running < threads
                && (running == 0 || held + need[next] <= budget)
            {
                let (k, done) = (next, done.clone());
                held += need[k];
                running += 1;
                next += 1;
                s.spawn(move || {
                    let r = rooms[k];
                    let built = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
                        build_room(manifest, r, options, parts)
                    }))
                    .unwrap_or_else(|_| {
                        Err(room_error(
                            r,
                            crate::Error::Thread("the room's build panicked".into()),
                        ))
                    });
                    // The receiver outlives every sender: this send cannot fail.
                    let _ = done.send((k, built));
                });
            }
            if running == 0 {
                break;
            }
            let Ok((k, built)) = finished.recv() else {
                break;
            };
            running -= 1;
            held -= need[k];
            results[k] = Some(built);
        }
    });
    results
        .into_iter()
        .enumerate()
        .map(|(k, r)| {
            r.unwrap_or_else(|| {
                Err(room_error(
                    rooms[k],
                    crate::Error::Thread("the room's build did not finish".into()),
                ))
            })
        })
        .collect()
}

/// Builds room `r` and writes its part.
fn build_room(
    manifest: &Manifest,
    r: usize,
    options: &BuildOptions,
    parts: &Path,
) -> Result<RoomBuilt, BuildingError> {
    let room = &manifest.rooms[r];
    let start = Instant::now();
    let fail = |reason: crate::Error| BuildingError::Room {
        at: room.at.clone(),
        room: room.name.clone(),
        reason: Box::new(reason),
    };
    // Hashed before the build: a scene edited while it is built is refused at the merge.
    let scene_hash = part::scene_hash(&room.scene).map_err(fail)?;
    let openings: Vec<port::PortAsked> = manifest
        .ports
        .iter()
        .filter(|p| p.model == PortModel::Diffusing)
        .filter_map(|p| {
            Some(port::PortAsked {
                port: p.name.clone(),
                surface: p.opening_in(r)?.to_string(),
                directions: p.directions,
            })
        })
        .collect();
    let exact: Vec<port::exact::ExactOpening> = manifest
        .ports
        .iter()
        .filter(|p| p.model == PortModel::Exact)
        .filter_map(|p| {
            Some(port::exact::ExactOpening {
                port: p.name.clone(),
                surface: p.opening_in(r)?.to_string(),
            })
        })
        .collect();
    // Every patch's exitance for light entering through an exact port serves the modes only.
    let modes = manifest.controllers.iter().any(|c| c.room == r && c.modes);
    // The merge folds a room's first reflection into its modes (its daylight nodes become
    // its neighbours' too, `basis::fold_daylight_reflection`): kept at full rank, the fold
    // loses nothing of the sky's.
    let options = &BuildOptions {
        sky_rank_tolerance: f64::MIN_POSITIVE,
        ..options.clone()
    };
    let (built, ports) = pipeline::build_tables_and(
        &room.scene,
        options,
        Some("responses at the ports"),
        |scene, occluders, system, daylight| {
            Ok((
                port::respond(scene, occluders, system, daylight, &openings)?,
                port::exact::respond(
                    scene,
                    system,
                    daylight,
                    &exact,
                    &options.form_factors,
                    modes,
                )?,
            ))
        },
    )
    .map_err(fail)?;
    let (ports, exact) = ports;
    let part = Part {
        program: part::program_version(),
        room: room.name.clone(),
        scene_hash,
        tables: built.tables,
        ports,
        exact,
    };
    part.write(&part::path(parts, &room.name))?;
    Ok(RoomBuilt {
        room: room.name.clone(),
        patches: built.report.patches,
        modes: built.report.modes,
        basis_bytes: built.bytes.len(),
        seconds: start.elapsed().as_secs_f64(),
    })
}

/// One controller's basis, as the merge wrote it.
#[derive(Clone, Debug, Serialize)]
pub struct ControllerBasis {
    /// The controller.
    pub controller: String,
    /// Its room.
    pub room: String,
    /// The basis file.
    pub file: PathBuf,
    /// Its size in bytes.
    pub bytes: usize,
    /// Bytes by section, largest first.
    pub sections: Vec<(&'static str, usize)>,
    /// The channels its basis holds, in the basis' order.
    pub channels: Vec<String>,
    /// The channels it drives.
    pub drives: Vec<String>,
    /// How its neighbours' channels stand to it.
    pub neighbours: Neighbours,
    /// Whether its basis carries the room's modes.
    pub modes: bool,
}

/// What the merge wrote: every controller's basis, and the index (`building.json`).
#[derive(Clone, Debug, Serialize)]
pub struct Merged {
    /// The building.
    pub building: String,
    /// The flash budget every basis was checked against.
    pub flash: String,
    /// The bases, in the manifest's order of controllers.
    pub controllers: Vec<ControllerBasis>,
}

/// The basis file of `controller` in `dir`.
pub fn basis_path(dir: &Path, controller: &str) -> PathBuf {
    dir.join(format!("{controller}.basis"))
}

/// Reads every room's part from `parts`, cuts every controller's basis, checks each against
/// `flash`, and only then writes them into `out` (each atomically) with the index
/// `building.json` last. Any missing, damaged or mismatched part, and any basis over its
/// flash, is an error before anything is written.
pub fn merge(
    manifest: &Manifest,
    parts: &Path,
    out: &Path,
    flash: FlashBudget,
) -> Result<Merged, BuildingError> {
    let rooms: Vec<Part> = manifest
        .rooms
        .iter()
        .map(|room| Part::read_checked(parts, room))
        .collect::<Result<_, _>>()?;
    let coupled = port::couple(manifest, &rooms, parts)?;
    let mut bases = Vec::new();
    let mut merged = Merged {
        building: manifest.name.clone(),
        flash: flash.to_string(),
        controllers: Vec::new(),
    };
    for c in &manifest.controllers {
        let write_error = |e: eigenrad_runtime::Error| BuildingError::Manifest {
            at: c.at.clone(),
            item: format!("controller {}", c.name),
            message: format!("its basis cannot be written: {e}"),
        };
        // A controller's basis reads its sun between nodes from the readings alone: it may
        // leave out the patches the sun's first reflection is computed on.
        let mut room = coupled.tables[c.room].clone();
        crate::basis::fold_sun_first(&mut room).map_err(write_error)?;
        let room = &room;
        let (selection, neighbours) = controller::select(room, c);
        let tables = controller::cut(room, &selection);
        let bytes = tables.to_bytes().map_err(write_error)?;
        let sections = controller::section_bytes(&tables).map_err(write_error)?;
        if !flash.fits(bytes.len() as u64) {
            return Err(BuildingError::Flash {
                at: c.at.clone(),
                controller: c.name.clone(),
                bytes: bytes.len(),
                budget: flash,
                sections: sections
                    .iter()
                    .map(|(name, b)| format!("{name} {b}"))
                    .collect::<Vec<_>>()
                    .join(", "),
            });
        }
        merged.controllers.push(ControllerBasis {
            controller: c.name.clone(),
            room: manifest.rooms[c.room].name.clone(),
            file: basis_path(out, &c.name),
            bytes: bytes.len(),
            sections,
            channels: tables.channel_names.clone(),
            drives: c.drives.clone(),
            neighbours,
            modes: c.modes,
        });
        bases.push(bytes);
    }
    for (basis, bytes) in merged.controllers.iter().zip(&bases) {
        crate::atomic::write(&basis.file, bytes)?;
    }
    let index = crate::cli::json(&merged).map_err(|e| BuildingError::Output(Box::new(e)))?;
    crate::atomic::write(&out.join("building.json"), index.as_bytes())?;
    Ok(merged)
}
