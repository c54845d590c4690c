//! `eigenrad building` and `eigenrad merge`: a building's rooms built into parts (all of
//! them, one room, or one shard of them), and every controller's basis written from the parts.
//!
//! A command of its own rather than `eigenrad build`: a building takes a manifest, not a
//! scene, writes a folder, not one basis, and its settings come from the manifest; sniffing
//! a TOML file to choose between the two would turn a typo in a scene into a manifest error.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use clap::Args;

use super::groups::JsonFlag;
use crate::building::{self, Manifest, Merged, RoomBuilt};
use crate::cli::guard;
use crate::error::Error;
use crate::flash::FlashBudget;
use crate::pipeline::BuildOptions;
use crate::{cache, scene};

/// The arguments of `eigenrad building`.
#[derive(Args)]
pub(super) struct BuildingArgs {
    /// Building manifest (TOML, docs/building.md).
    manifest: PathBuf,
    /// Output folder: the rooms' parts go into `OUT/parts/`; with neither --room nor
    /// --shard, every controller's basis into `OUT/<controller>.basis`, with the index
    /// `OUT/building.json`.
    #[arg(long)]
    out: PathBuf,
    /// Build this room's part only.
    #[arg(long, conflicts_with = "shard")]
    room: Option<String>,
    /// Build shard I of N (I from 0): the rooms whose place in the manifest, counted from
    /// 0, leaves I when divided by N. `eigenrad merge` then writes the bases.
    #[arg(long, value_name = "I/N")]
    shard: Option<String>,
    /// Flash budget of each controller's basis (512KiB, 1MiB, bytes); default the
    /// manifest's `flash`, else 512 KiB.
    #[arg(long)]
    flash: Option<FlashBudget>,
    /// Compute the form factors without reading or writing the form-factor cache.
    #[arg(long)]
    no_cache: bool,
    #[command(flatten)]
    json: JsonFlag,
}

/// The arguments of `eigenrad merge`.
#[derive(Args)]
pub(super) struct MergeArgs {
    /// Building manifest (TOML, docs/building.md).
    manifest: PathBuf,
    /// The building's output folder: the parts are read from `OUT/parts/`, and every
    /// controller's basis written into `OUT/<controller>.basis` with the index
    /// `OUT/building.json`.
    #[arg(long)]
    out: PathBuf,
    /// Flash budget of each controller's basis; default the manifest's `flash`, else 512 KiB.
    #[arg(long)]
    flash: Option<FlashBudget>,
    #[command(flatten)]
    json: JsonFlag,
}

/// What `eigenrad building` did: the rooms built and, for the whole building, the bases.
#[derive(serde::Serialize)]
struct BuildingReport {
    rooms: Vec<RoomBuilt>,
    merged: Option<Merged>,
}

/// The files the building's commands read: the manifest and every room's scene inputs.
fn inputs(manifest: &Manifest) -> anyhow::Result<Vec<PathBuf>> {
    let mut files = vec![manifest.path.clone()];
    for room in &manifest.rooms {
        files.extend(scene::inputs(&room.scene)?.files);
    }
    Ok(files)
}

/// Before any work: the folders can be made, and nothing written replaces an input.
fn check_outputs(manifest: &Manifest, out: &Path, merging: bool) -> anyhow::Result<()> {
    let parts = building::parts_dir(out);
    std::fs::create_dir_all(&parts).map_err(|reason| Error::Io {
        path: parts.clone(),
        reason,
    })?;
    let mut outputs: Vec<PathBuf> = manifest
        .rooms
        .iter()
        .map(|r| building::part::path(&parts, &r.name))
        .collect();
    if merging {
        outputs.extend(
            manifest
                .controllers
                .iter()
                .map(|c| building::basis_path(out, &c.name)),
        );
        outputs.push(out.join("building.json"));
    }
    guard::check_outputs(&outputs, &inputs(manifest)?)?;
    Ok(())
}

impl BuildingArgs {
    pub(super) fn run(self) -> anyhow::Result<()> {
        let manifest = Manifest::load(&self.manifest)?;
        let rooms = match (&self.room, &self.shard) {
            (Some(room), _) => vec![manifest.room(room)?],
            (None, Some(shard)) => manifest.shard(shard)?,
            (None, None) => (0..manifest.rooms.len()).collect(),
        };
        let whole = self.room.is_none() && self.shard.is_none();
        check_outputs(&manifest, &self.out, whole)?;
        let mut options = BuildOptions::default();
        if !self.no_cache {
            options.form_factors.cache = cache::default_dir();
        }
        let parts = building::parts_dir(&self.out);
        let built = building::build_rooms(&manifest, &rooms, &options, &parts)?;
        let merged = if whole {
            let flash = self.flash.unwrap_or(manifest.flash);
            Some(building::merge(&manifest, &parts, &self.out, flash)?)
        } else {
            None
        };
        let report = BuildingReport {
            rooms: built,
            merged,
        };
        self.json.print(&report, |r| {
            let mut text = format_rooms(&r.rooms);
            if let Some(m) = &r.merged {
                text.push_str(&format_merged(m));
            }
            text
        })
    }
}

impl MergeArgs {
    pub(super) fn run(self) -> anyhow::Result<()> {
        let manifest = Manifest::load(&self.manifest)?;
        check_outputs(&manifest, &self.out, true)?;
        let flash = self.flash.unwrap_or(manifest.flash);
        let merged = building::merge(&manifest, &building::parts_dir(&self.out), &self.out, flash)?;
        self.json.print(&merged, format_merged)
    }
}

/// One line per room built.
fn format_rooms(rooms: &[RoomBuilt]) -> String {
    let mut text = String::new();
    for r in rooms {
        let _ = writeln!(
            text,
            "room {}: {} patches, {} modes, whole-room basis {} bytes, built in {:.1} s",
            r.room, r.patches, r.modes, r.basis_bytes, r.seconds
        );
    }
    text
}

/// One line per controller's basis, with its neighbours' channels.
fn format_merged(m: &Merged) -> String {
    let mut text = String::new();
    for c in &m.controllers {
        let _ = write!(
            text,
            "controller {} (room {}): {} bytes of {} flash, {} channels",
            c.controller,
            c.room,
            c.bytes,
            m.flash,
            c.channels.len()
        );
        if !c.neighbours.inputs.is_empty() {
            let _ = write!(text, "; told: {}", c.neighbours.inputs.join(", "));
        }
        if !c.neighbours.bounds.is_empty() {
            let bounds: Vec<String> = c
                .neighbours
                .bounds
                .iter()
                .map(|(n, l)| format!("{n} ≤ {l}"))
                .collect();
            let _ = write!(text, "; bounded: {}", bounds.join(", "));
        }
        let _ = writeln!(text, " -> {}", c.file.display());
    }
    text
}
