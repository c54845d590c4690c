//! `eigenrad-bench building`: a building's rooms built one after the other and then all at
//! once on this machine (`eigenrad building`'s parallel build), in one run: the wall time of
//! each, their ratio (the parallel speed-up), and each controller's basis size.

use std::path::Path;
use std::time::Instant;

use anyhow::{anyhow, Result};
use eigenrad_precompute::building::{self, Manifest};
use eigenrad_precompute::pipeline::BuildOptions;

/// Prints the rooms' table, the speed-up and the controllers' table.
pub(crate) fn run(manifest: &Path) -> Result<()> {
    let manifest = Manifest::load(manifest)?;
    // Form factors computed afresh in both runs: the cache would make the second one cheaper.
    let options = BuildOptions::default();
    let scratch =
        std::env::temp_dir().join(format!("eigenrad-bench-building-{}", std::process::id()));
    let (apart, together) = (scratch.join("one-by-one"), scratch.join("together"));
    for dir in [&apart, &together] {
        std::fs::create_dir_all(building::parts_dir(dir))?;
    }
    let mut rooms = Vec::new();
    let start = Instant::now();
    for r in 0..manifest.rooms.len() {
        rooms.extend(building::build_rooms(
            &manifest,
            &[r],
            &options,
            &building::parts_dir(&apart),
        )?);
    }
    let one_by_one = start.elapsed().as_secs_f64();
    let all: Vec<usize> = (0..manifest.rooms.len()).collect();
    let start = Instant::now();
    building::build_rooms(&manifest, &all, &options, &building::parts_dir(&together))?;
    let parallel = start.elapsed().as_secs_f64();
    let merged = building::merge(
        &manifest,
        &building::parts_dir(&together),
        &together,
        manifest.flash,
    )?;
    // The two runs must agree, or the figures compare different work.
    building::merge(
        &manifest,
        &building::parts_dir(&apart),
        &apart,
        manifest.flash,
    )?;
    for c in &merged.controllers {
        let other = building::basis_path(&apart, &c.controller);
        if std::fs::read(&other)? != std::fs::read(&c.file)? {
            return Err(anyhow!(
                "{}: the two runs built different bases",
                c.controller
            ));
        }
    }
    println!("| room | patches | modes | whole-room basis bytes | build s (alone) |");
    println!("|---|---|---|---|---|");
    for r in &rooms {
        println!(
            "| {} | {} | {} | {} | {:.2} |",
            r.room, r.patches, r.modes, r.basis_bytes, r.seconds
        );
    }
    let sum: f64 = rooms.iter().map(|r| r.seconds).sum();
    println!();
    println!(
        "rooms one after the other: {one_by_one:.2} s (sum of the rooms {sum:.2} s); all at once: {parallel:.2} s; speed-up {:.2}x on {} threads",
        one_by_one / parallel,
        std::thread::available_parallelism().map_or(1, |n| n.get())
    );
    println!();
    println!(
        "| controller | room | basis bytes | of the flash ({}) | channels | largest section |",
        merged.flash
    );
    println!("|---|---|---|---|---|---|");
    for c in &merged.controllers {
        let (section, bytes) = c.sections.first().copied().unwrap_or(("none", 0));
        println!(
            "| {} | {} | {} | {:.1} % | {} | {section} {bytes} |",
            c.controller,
            c.room,
            c.bytes,
            100.0 * c.bytes as f64 / manifest.flash.bytes as f64,
            c.channels.len()
        );
    }
    let _ = std::fs::remove_dir_all(&scratch);
    Ok(())
}
